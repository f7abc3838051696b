//! Scenario coordinates in the network's local frame: points, headings, poses and obstacles as
//! the core's f32 types.

use crate::frame::LocalFrame;
use crate::scenario::Scenario;
use skyroute::network::write::ObstacleSpec;
use skyroute::planner::{Threat, ThreatOrigin};
use skyroute::{Pose, Vec2};

/// The scenario's threats in the local frame, as the core's soft threats (each `radius_m` the
/// exposure's reference distance), in file order.
pub fn local_threats(s: &Scenario, frame: &LocalFrame) -> Vec<Threat> {
    s.threats
        .iter()
        .enumerate()
        .map(|(i, t)| Threat {
            position: local(frame, t.lon, t.lat),
            radius: t.radius_m as f32,
            origin: ThreatOrigin::Network(i as u32),
        })
        .collect()
}

/// The scenario's obstacles in the local frame: no-fly polygons and threat discs, in the
/// order the core numbers them (see [`local_obstacles_named`]).
pub fn local_obstacles(s: &Scenario, frame: &LocalFrame) -> Vec<ObstacleSpec> {
    local_obstacles_named(s, frame)
        .into_iter()
        .map(|(o, _)| o)
        .collect()
}

/// The scenario's obstacles in the local frame, each with the name of the scenario feature it
/// comes from (as `no-fly zone "B12"` or `threat "T3"`): the no-fly zones in file order, then
/// the threat discs. A zone without holes is one polygon; a zone with holes is the simple
/// polygons of [`crate::zone_pieces::simple_pieces`], computed in the local frame, each named
/// after the zone.
pub fn local_obstacles_named(s: &Scenario, frame: &LocalFrame) -> Vec<(ObstacleSpec, String)> {
    local_obstacles_sourced(s, frame)
        .into_iter()
        .map(|(o, name, _)| (o, name))
        .collect()
}

/// The height of each of [`local_obstacles`], in its order: a zone's pieces have the zone's
/// `height_m` (`None`: unbounded), a threat disc is unbounded.
pub fn local_obstacle_heights(s: &Scenario, frame: &LocalFrame) -> Vec<Option<f64>> {
    local_obstacles_sourced(s, frame)
        .into_iter()
        .map(|(_, _, h)| h)
        .collect()
}

/// [`local_obstacles_named`], each with its height too.
fn local_obstacles_sourced(
    s: &Scenario,
    frame: &LocalFrame,
) -> Vec<(ObstacleSpec, String, Option<f64>)> {
    let to_local = |ring: &[(f64, f64)]| -> Vec<(f64, f64)> {
        ring.iter()
            .map(|&(lon, lat)| frame.to_local(lon, lat))
            .collect()
    };
    let mut out = Vec::new();
    for z in &s.no_fly {
        let name = format!("no-fly zone {:?}", z.name);
        let holes: Vec<Vec<(f64, f64)>> = z.holes.iter().map(|h| to_local(h)).collect();
        for piece in crate::zone_pieces::simple_pieces(&to_local(&z.ring), &holes) {
            let ring = piece
                .iter()
                .map(|&(x, y)| Vec2::new(x as f32, y as f32))
                .collect();
            out.push((ObstacleSpec::Polygon(ring), name.clone(), z.height_m));
        }
    }
    out.extend(s.threats.iter().map(|t| {
        let disc = ObstacleSpec::Circle {
            centre: local(frame, t.lon, t.lat),
            radius: t.radius_m as f32,
        };
        (disc, format!("threat {:?}", t.name), None)
    }));
    out
}

/// The name of the scenario's no-fly zone or threat disc that contains the local point `p`
/// (as `no-fly zone "B12"` or `threat "T3"`), if any.
pub fn obstacle_containing(s: &Scenario, frame: &LocalFrame, p: Vec2) -> Option<String> {
    local_obstacles_named(s, frame)
        .into_iter()
        .find(|(o, _)| match o {
            ObstacleSpec::Polygon(ring) => {
                skyroute::geometry::predicates::point_in_polygon(p, ring.as_slice())
            }
            ObstacleSpec::Circle { centre, radius } => p.distance(*centre) <= *radius,
        })
        .map(|(_, name)| name)
}

/// A lon/lat point in the local frame, as the core's f32 vector.
pub fn local(frame: &LocalFrame, lon: f64, lat: f64) -> Vec2 {
    let (x, y) = frame.to_local(lon, lat);
    Vec2::new(x as f32, y as f32)
}

/// A compass heading at `(lon, lat)` as the core's local heading (radians counter-clockwise
/// from the frame's `x` axis), corrected for the projection's meridian convergence.
pub fn local_heading(frame: &LocalFrame, lon: f64, lat: f64, compass_deg: f64) -> f32 {
    skyroute::geometry::heading_from_compass_deg(
        frame.heading_to_local(lon, lat, compass_deg) as f32
    )
}

/// A scenario endpoint as a pose (heading 0 where the endpoint has none).
pub fn local_pose(frame: &LocalFrame, lon: f64, lat: f64, compass_deg: Option<f64>) -> Pose {
    Pose {
        position: local(frame, lon, lat),
        heading: compass_deg.map_or(0.0, |c| local_heading(frame, lon, lat, c)),
    }
}

/// A circular pop-up in the local frame, with a name for errors.
#[derive(Clone, Debug, PartialEq)]
pub struct LocalPopup {
    /// Name for messages.
    pub name: String,
    /// Centre.
    pub centre: Vec2,
    /// Radius, metres.
    pub radius: f32,
    /// Its top, metres (three-dimensional roadmaps); `None`: no altitude clears it.
    pub height: Option<f32>,
}

impl LocalPopup {
    /// Adds the pop-up to `planner`, with its height if it has one.
    pub fn add_to<const V: usize, const E: usize, const P: usize, const R: usize>(
        &self,
        planner: &mut skyroute::Planner<'_, V, E, P, R>,
    ) -> Result<skyroute::planner::PopupSummary, skyroute::planner::PopupError> {
        let disc = skyroute::Popup::Circle {
            centre: self.centre,
            radius: self.radius,
        };
        planner.add_popup_with_height(disc, self.height.unwrap_or(f32::INFINITY))
    }
}
