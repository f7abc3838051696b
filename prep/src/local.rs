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

/// The scenario's obstacles in the local frame: no-fly polygons and threat discs.
pub fn local_obstacles(s: &Scenario, frame: &LocalFrame) -> Vec<ObstacleSpec> {
    let mut out: Vec<ObstacleSpec> = s
        .no_fly
        .iter()
        .map(|z| {
            ObstacleSpec::Polygon(
                z.ring
                    .iter()
                    .map(|&(lon, lat)| local(frame, lon, lat))
                    .collect(),
            )
        })
        .collect();
    out.extend(s.threats.iter().map(|t| ObstacleSpec::Circle {
        centre: local(frame, t.lon, t.lat),
        radius: t.radius_m as f32,
    }));
    out
}

/// The name of the scenario's no-fly zone or threat disc that contains the local point `p`
/// (as `no-fly zone "B12"` or `threat "T3"`), if any.
pub fn obstacle_containing(s: &Scenario, frame: &LocalFrame, p: Vec2) -> Option<String> {
    let names = s
        .no_fly
        .iter()
        .map(|z| format!("no-fly zone {:?}", z.name))
        .chain(s.threats.iter().map(|t| format!("threat {:?}", t.name)));
    local_obstacles(s, frame)
        .iter()
        .zip(names)
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
