//! What a picture shows: the network, a route read from a route file, the scenario's endpoints
//! and pop-ups, all in the network's local frame.

use crate::frame::LocalFrame;
use crate::scenario::{self, Scenario};
use skyroute::{Network, Primitive};

/// A leg of a route file written by `skyroute plan`.
#[derive(Clone, Debug, PartialEq)]
pub struct RouteLeg {
    /// Name of the endpoint it leaves.
    pub from: String,
    /// Name of the endpoint it reaches.
    pub to: String,
    /// Length, metres.
    pub length_m: f64,
    /// Its lines and arcs in the local frame.
    pub primitives: Vec<Primitive>,
}

/// A route file written by `skyroute plan`.
#[derive(Clone, Debug, PartialEq)]
pub struct Route {
    /// The scenario it was planned for.
    pub scenario: String,
    /// Origin of its local frame, `(lat, lon)` degrees.
    pub origin_deg: (f64, f64),
    /// Its legs, in order.
    pub legs: Vec<RouteLeg>,
    /// The pop-ups it was planned round (its `popups` member; empty when the file has none).
    pub popups: Vec<PopupMark>,
}

/// A circular pop-up threat to draw, in the local frame.
#[derive(Clone, Debug, PartialEq)]
pub struct PopupMark {
    /// Label.
    pub name: String,
    /// Centre, metres.
    pub centre: (f64, f64),
    /// Radius, metres.
    pub radius: f64,
}

/// A start, waypoint or goal to draw, in the local frame.
#[derive(Clone, Debug, PartialEq)]
pub struct EndpointMark {
    /// Label.
    pub name: String,
    /// `start`, `waypoint` or `goal`.
    pub kind: &'static str,
    /// Position, metres.
    pub position: (f64, f64),
    /// Heading in the local frame (radians counter-clockwise from `x`) when the scenario fixes it.
    pub heading: Option<f64>,
}

/// Everything a picture shows.
#[derive(Clone, Debug, Default)]
pub struct Picture<'a> {
    /// Title (scenario or file name).
    pub title: String,
    /// The network.
    pub network: Option<Network<'a>>,
    /// Draw the network's edges.
    pub edges: bool,
    /// The route, in the network's frame.
    pub route: Option<Route>,
    /// Start, waypoints and goal.
    pub endpoints: Vec<EndpointMark>,
    /// Pop-up threats.
    pub popups: Vec<PopupMark>,
    /// Width of the map in pixels (the legend panel comes on top).
    pub map_width_px: f64,
    /// Draw only this part of the frame, `(min_x, min_y, max_x, max_y)` metres; everything
    /// drawn when `None`.
    pub area: Option<(f64, f64, f64, f64)>,
}

/// The endpoints and pop-ups of a scenario in `frame`.
pub fn scenario_marks(s: &Scenario, frame: &LocalFrame) -> (Vec<EndpointMark>, Vec<PopupMark>) {
    let mark = |e: &scenario::Endpoint, kind: &'static str| {
        let (x, y) = frame.to_local(e.lon, e.lat);
        EndpointMark {
            name: e.name.clone(),
            kind,
            position: (x, y),
            heading: e
                .heading_deg
                .map(|c| crate::local::local_heading(frame, e.lon, e.lat, c) as f64),
        }
    };
    let mut ends: Vec<EndpointMark> = s.start.iter().map(|e| mark(e, "start")).collect();
    ends.extend(s.waypoints.iter().map(|e| mark(e, "waypoint")));
    ends.extend(s.goal.iter().map(|e| mark(e, "goal")));
    let pops = s
        .popups
        .iter()
        .map(|p| PopupMark {
            name: p.name.clone(),
            centre: frame.to_local(p.lon, p.lat),
            radius: p.radius_m,
        })
        .collect();
    (ends, pops)
}
