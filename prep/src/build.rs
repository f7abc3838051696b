//! From a scenario to a network image: project to the local frame, build the mode's network,
//! encode it.

use crate::frame::LocalFrame;
use crate::roadmap::{build_roadmap, CollisionCheck, Roadmap, RoadmapInput, RoadmapParams};
use crate::scenario::{Mode, Scenario};
use skyroute::network::write::{encode, NetworkSpec, ObstacleSpec};
use skyroute::{Pose, Vec2};
use std::fmt;

/// Overrides of the scenario's parameters, for experiments and for networks that must fit a
/// smaller target.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct BuildOptions {
    /// Replaces `planner.sample_spacing_m`.
    pub sample_spacing_m: Option<f32>,
    /// Replaces `planner.neighbour_radius_m`.
    pub neighbour_radius_m: Option<f32>,
    /// Use the paper's discretised collision check (`planner.arc_step_m`) instead of the exact one.
    pub discretised: bool,
    /// Side of a grid-index cell; default: twice the turn radius.
    pub grid_cell_m: Option<f32>,
}

/// Why a network could not be built.
#[derive(Debug)]
pub enum BuildError {
    /// The scenario lacks what the mode needs: (scenario file, field).
    Missing(String, &'static str),
    /// The scenario's mode is not built yet.
    UnsupportedMode(String, Mode),
    /// The encoder refused the network.
    Encode(String, skyroute::network::write::WriteError),
}

impl fmt::Display for BuildError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            BuildError::Missing(file, field) => {
                write!(f, "{file}: {field}: required for this mode")
            }
            BuildError::UnsupportedMode(file, mode) => write!(
                f,
                "{file}: planner.mode: {mode:?} networks are not built yet"
            ),
            BuildError::Encode(file, e) => write!(f, "{file}: {e}"),
        }
    }
}

impl std::error::Error for BuildError {}

/// A built network and what it took.
#[derive(Clone, Debug)]
pub struct Built {
    /// The encoded network.
    pub bytes: Vec<u8>,
    /// The frame it is expressed in.
    pub frame: LocalFrame,
    /// The roadmap's statistics.
    pub roadmap: Roadmap,
    /// The obstacles in the local frame.
    pub obstacles: Vec<ObstacleSpec>,
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

/// Builds the scenario's network.
pub fn build(
    s: &Scenario,
    options: &BuildOptions,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<Built, BuildError> {
    let file = s.path.display().to_string();
    if s.planner.mode != Mode::Roadmap {
        return Err(BuildError::UnsupportedMode(file, s.planner.mode));
    }
    let p = &s.planner;
    let need = |v: Option<f64>, field: &'static str| {
        v.ok_or_else(|| BuildError::Missing(file.clone(), field))
    };
    let turn_radius = s.vehicle.turn_radius_m() as f32;
    let params = RoadmapParams {
        turn_radius_m: turn_radius,
        sample_spacing_m: options.sample_spacing_m.map_or_else(
            || need(p.sample_spacing_m, "planner.sample_spacing_m").map(|v| v as f32),
            Ok,
        )?,
        neighbour_radius_m: options.neighbour_radius_m.map_or_else(
            || need(p.neighbour_radius_m, "planner.neighbour_radius_m").map(|v| v as f32),
            Ok,
        )?,
        k_nearest_fallback: p.k_nearest_fallback.unwrap_or(8) as usize,
        allow_ccc: p.allow_ccc.unwrap_or(true),
        clearance_m: p.clearance_m.unwrap_or(0.0) as f32,
        seed: p.seed.unwrap_or(1),
        check: if options.discretised {
            CollisionCheck::Discretised {
                arc_step_m: need(p.arc_step_m, "planner.arc_step_m")? as f32,
            }
        } else {
            CollisionCheck::Exact
        },
    };
    let frame = s.local_frame();
    let obstacles = local_obstacles(s, &frame);
    let (lo, hi) = skyroute::geometry::points_bounding_box(
        s.positions().map(|(lon, lat)| local(&frame, lon, lat)),
    );
    let input = RoadmapInput {
        area_min: lo,
        area_max: hi,
        obstacles: obstacles.clone(),
        fixed_vertices: Vec::new(),
    };
    let roadmap = build_roadmap(&input, &params, progress);
    let (origin_lat, origin_lon) = frame.origin();
    let spec = NetworkSpec {
        origin_lat_deg: origin_lat,
        origin_lon_deg: origin_lon,
        turn_radius_m: turn_radius,
        clearance_m: params.clearance_m,
        vertices: roadmap.vertices.clone(),
        edges: roadmap.edges.clone(),
        obstacles: obstacles.clone(),
        grid_cell_m: options.grid_cell_m.unwrap_or(2.0 * turn_radius),
    };
    let bytes = encode(&spec).map_err(|e| BuildError::Encode(file, e))?;
    Ok(Built {
        bytes,
        frame,
        roadmap,
        obstacles,
    })
}
