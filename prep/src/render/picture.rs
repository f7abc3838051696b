//! What a picture shows: the network, a route read from a route file, the scenario's endpoints
//! and pop-ups, all in the network's local frame.

use crate::frame::LocalFrame;
use crate::scenario::{self, Scenario};
use skyroute::geometry::spline::Piece;
use skyroute::{Network, Primitive, Vec2};

/// A leg of a route file written by `skyroute plan`.
#[derive(Clone, Debug, PartialEq)]
pub struct RouteLeg {
    /// Name of the endpoint it leaves.
    pub from: String,
    /// Name of the endpoint it reaches.
    pub to: String,
    /// Length, metres.
    pub length_m: f64,
    /// Its lines and arcs in the local frame (for a Voronoi route, the chords of its pieces).
    pub primitives: Vec<Primitive>,
    /// A Voronoi route's smoothed pieces (lines and cubics); empty for other routes.
    pub pieces: Vec<Piece>,
    /// A Voronoi route's coarse polyline (start, graph vertices, goal); empty for other routes.
    pub coarse: Vec<Vec2>,
    /// A three-dimensional roadmap route: for each primitive, its path's altitude profile and
    /// the distance along the path at which it starts; empty for other routes.
    pub vertical: Vec<(skyroute::geometry::vertical::VerticalProfile, f32)>,
}

/// A route file written by `skyroute plan`.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Route {
    /// The scenario it was planned for.
    pub scenario: String,
    /// Origin of its local frame, `(lat, lon)` degrees.
    pub origin_deg: (f64, f64),
    /// Its legs, in order.
    pub legs: Vec<RouteLeg>,
    /// The pop-ups it was planned round (its `popups` member; empty when the file has none).
    pub popups: Vec<PopupMark>,
    /// The threats in force when it was planned (its `threats` member; empty when none).
    pub threats: Vec<ThreatMark>,
    /// The weight k of length against exposure it was planned with (`threat_weight`).
    pub threat_weight: Option<f64>,
    /// Its exposure, the dense integral along the flown route (`exposure_flown`).
    pub exposure_flown: Option<f64>,
    /// Whether it was planned round the scenario's `popup` features (`scenario_popups_applied`;
    /// `None` when the file does not say).
    pub scenario_popups_applied: Option<bool>,
    /// The decision among pop-up bypass alternatives it flies (`plan --popup-appears`: its
    /// `decision` member), if any.
    pub decision: Option<DecisionMark>,
    /// The altitude it is flown at, metres (`altitude_m`: routes on a terrain network).
    pub altitude_m: Option<f64>,
}

/// One bypass alternative of a pop-up, as a route file's `decision` records it.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct AlternativeMark {
    /// Its lines and arcs in the local frame, start to goal.
    pub primitives: Vec<Primitive>,
    /// Length, metres.
    pub length_m: f64,
    /// R_K for the pop-up's appearance probability.
    pub risk: f64,
    /// Time factor f_t.
    pub time: f64,
    /// Fuel factor F_c.
    pub fuel: f64,
}

/// A pop-up of a decision: its alternatives and the one chosen.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct DecisionPopup {
    /// Its name in the scenario.
    pub name: String,
    /// P_A, its appearance probability.
    pub probability: f64,
    /// Index of the chosen alternative.
    pub chosen: usize,
    /// Its alternatives, in order.
    pub alternatives: Vec<AlternativeMark>,
}

/// A route file's `decision`: the nominal route, every pop-up's alternatives, the choice and
/// its figures against the limits.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct DecisionMark {
    /// The nominal route (no pop-ups).
    pub nominal: Vec<Primitive>,
    /// The pop-ups decided, in order.
    pub popups: Vec<DecisionPopup>,
    /// T_max and F_cmax.
    pub limits: (f64, f64),
    /// Σ R_K of the choice.
    pub total_risk: f64,
    /// Its mean time factor.
    pub mean_time: f64,
    /// Its mean fuel factor.
    pub mean_fuel: f64,
}

impl Route {
    /// The total length of its legs, metres.
    pub fn length_m(&self) -> f64 {
        self.legs.iter().map(|l| l.length_m).sum()
    }
}

/// A radar threat to draw, in the local frame: a site with its exposure's reference distance.
#[derive(Clone, Debug, PartialEq)]
pub struct ThreatMark {
    /// Site, metres.
    pub centre: (f64, f64),
    /// Reference distance r (the exposure density is (r/d)⁴ at distance d), metres.
    pub radius: f64,
    /// Whether it popped up in flight (`plan --threat`) rather than being one of the network's.
    pub popped: bool,
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

/// A landmark to draw, in the local frame.
#[derive(Clone, Debug, PartialEq)]
pub struct LandmarkMark {
    /// Label: its name in the scenario, or `L` and its number in the network.
    pub name: String,
    /// Position, metres.
    pub position: (f64, f64),
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
    /// The routes, in the network's frame: one is drawn a colour per leg, several a colour per
    /// route with a legend entry each.
    pub routes: Vec<Route>,
    /// Radar threats (a Voronoi network's sites, and pop-up ones from the routes); with a
    /// Voronoi network they also give the exposure heat map.
    pub threats: Vec<ThreatMark>,
    /// Start, waypoints and goal.
    pub endpoints: Vec<EndpointMark>,
    /// Pop-up threats.
    pub popups: Vec<PopupMark>,
    /// Landmarks (a landmark network's).
    pub landmarks: Vec<LandmarkMark>,
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
