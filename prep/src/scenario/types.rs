//! The typed scenario: what [`super::parse`] returns.

use super::error::ScenarioError;
use crate::frame::LocalFrame;
use std::path::PathBuf;

/// A parsed and checked scenario.
#[derive(Clone, Debug, PartialEq)]
pub struct Scenario {
    /// The collection's `name` (the file stem when absent).
    pub name: String,
    /// The file it was read from.
    pub path: PathBuf,
    /// The collection's `description` (empty when absent).
    pub description: String,
    /// The aircraft.
    pub vehicle: Vehicle,
    /// The planner's mode and parameters.
    pub planner: PlannerParams,
    /// The environmental conditions the landmark rosettes are given for (landmark mode), in file
    /// order; [`Landmark::quality`] follows this order.
    pub weather: Vec<String>,
    /// The terrain model (terrain mode; always present there).
    pub terrain: Option<Terrain>,
    /// No-fly areas, in file order.
    pub no_fly: Vec<NoFly>,
    /// Landmarks, in file order.
    pub landmarks: Vec<Landmark>,
    /// The start, if the file has one.
    pub start: Option<Endpoint>,
    /// The goal, if the file has one.
    pub goal: Option<Endpoint>,
    /// Intermediate waypoints, in file order.
    pub waypoints: Vec<Endpoint>,
    /// Known threats (circles to avoid or to weigh), in file order.
    pub threats: Vec<Circle>,
    /// Pop-up threats, in file order.
    pub popups: Vec<Popup>,
    /// What [`ParseOptions`](super::ParseOptions) allowed through and repaired (empty with the default options).
    pub warnings: Vec<ScenarioError>,
}

impl Scenario {
    /// Every position in the scenario, `(lon, lat)` degrees: no-fly vertices, landmarks, start,
    /// goal, waypoints, threat and pop-up centres.
    pub fn positions(&self) -> impl Iterator<Item = (f64, f64)> + '_ {
        self.no_fly
            .iter()
            .flat_map(|z| z.ring.iter().copied())
            .chain(self.landmarks.iter().map(|l| (l.lon, l.lat)))
            .chain(self.start.iter().map(|e| (e.lon, e.lat)))
            .chain(self.goal.iter().map(|e| (e.lon, e.lat)))
            .chain(self.waypoints.iter().map(|e| (e.lon, e.lat)))
            .chain(self.threats.iter().map(|c| (c.lon, c.lat)))
            .chain(self.popups.iter().map(|p| (p.lon, p.lat)))
    }

    /// The local frame centred on the bounding box of [`Scenario::positions`] (a parsed scenario
    /// always has at least one feature).
    pub fn local_frame(&self) -> LocalFrame {
        LocalFrame::centred_on(self.positions())
    }

    /// The altitude band and vertical limits of a three-dimensional roadmap scenario (one with
    /// `planner.altitude_min_m` and `planner.altitude_max_m`); `None` for a planar one.
    pub fn vertical(&self) -> Option<Vertical> {
        Some(Vertical {
            altitude_min_m: self.planner.altitude_min_m?,
            altitude_max_m: self.planner.altitude_max_m?,
            climb_rate_mps: self
                .vehicle
                .climb_rate_mps
                .unwrap_or(DEFAULT_CLIMB_RATE_MPS),
            vertical_accel_mps2: self
                .vehicle
                .vertical_accel_mps2
                .unwrap_or(DEFAULT_VERTICAL_ACCEL_MPS2),
        })
    }
}

/// The aircraft's performance figures.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Vehicle {
    /// Cruise speed, m/s.
    pub v_nominal_mps: f64,
    /// Slowest speed, m/s (> 0, ≤ nominal).
    pub v_min_mps: f64,
    /// Fastest speed, m/s (≥ nominal).
    pub v_max_mps: f64,
    /// Largest lateral acceleration, m/s² (> 0).
    pub a_lat_max_mps2: f64,
    /// Largest deceleration, as a non-positive acceleration, m/s².
    pub a_long_min_mps2: f64,
    /// Largest acceleration, m/s² (≥ 0).
    pub a_long_max_mps2: f64,
    /// Wingspan, m (> 0).
    pub wingspan_m: f64,
    /// Three-dimensional roadmap: largest climb or sink rate `v_c`, m/s (> 0); `None`: the
    /// default [`DEFAULT_CLIMB_RATE_MPS`].
    pub climb_rate_mps: Option<f64>,
    /// Three-dimensional roadmap: largest vertical acceleration `a_z`, m/s² (> 0); `None`: the
    /// default [`DEFAULT_VERTICAL_ACCEL_MPS2`].
    pub vertical_accel_mps2: Option<f64>,
}

/// Niendorf et al.'s climb rate `v_c`, m/s: a three-dimensional scenario's default.
pub const DEFAULT_CLIMB_RATE_MPS: f64 = 10.0;

/// Niendorf et al.'s vertical acceleration `a_z`, m/s²: a three-dimensional scenario's default.
pub const DEFAULT_VERTICAL_ACCEL_MPS2: f64 = 20.0;

/// The largest altitude magnitude a scenario may give, metres (the network format's limit on a
/// vertex altitude, `skyroute::network::format::MAX_ALTITUDE_M`).
pub const MAX_ALTITUDE_M: f64 = skyroute::network::format::MAX_ALTITUDE_M as f64;

/// What makes a roadmap scenario three-dimensional (Niendorf et al.): the altitude band its
/// samples are drawn from and the aircraft's vertical limits, defaults applied.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Vertical {
    /// Lowest sample altitude, m.
    pub altitude_min_m: f64,
    /// Highest sample altitude, m (≥ `altitude_min_m`).
    pub altitude_max_m: f64,
    /// Largest climb or sink rate `v_c`, m/s.
    pub climb_rate_mps: f64,
    /// Largest vertical acceleration `a_z`, m/s².
    pub vertical_accel_mps2: f64,
}

impl Vehicle {
    /// The smallest turn radius at nominal speed, `v_nominal² / a_lat_max`, metres.
    pub fn turn_radius_m(&self) -> f64 {
        self.v_nominal_mps * self.v_nominal_mps / self.a_lat_max_mps2
    }
}

/// The planner's mode.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Mode {
    /// Sampled Dubins roadmap (Niendorf et al.), `"roadmap"`.
    Roadmap,
    /// Landmark-based navigation network (Babel), `"landmark"`.
    Landmark,
    /// Terrain grid (Medeiros & da Silva), `"terrain"`.
    Terrain,
    /// Voronoi graph of radar threats with exposure cost (Judd & McLain), `"voronoi"`.
    Voronoi,
}

impl Mode {
    /// The name used in the file.
    pub fn as_str(self) -> &'static str {
        match self {
            Mode::Roadmap => "roadmap",
            Mode::Landmark => "landmark",
            Mode::Terrain => "terrain",
            Mode::Voronoi => "voronoi",
        }
    }
}

/// The `planner` member. Every parameter but `mode` is optional: a mode may omit what it does not
/// use. Present values are checked for range (lengths positive, clearance and weight
/// non-negative, counts at least 1).
#[derive(Clone, Debug, PartialEq)]
pub struct PlannerParams {
    /// The mode.
    pub mode: Mode,
    /// Clearance to keep from obstacles, m (≥ 0).
    pub clearance_m: Option<f64>,
    /// Spacing of roadmap samples, m (> 0).
    pub sample_spacing_m: Option<f64>,
    /// Radius within which samples are connected, m (> 0).
    pub neighbour_radius_m: Option<f64>,
    /// Neighbours to try when none lies within the radius.
    pub k_nearest_fallback: Option<u32>,
    /// Whether CCC Dubins words are allowed.
    pub allow_ccc: Option<bool>,
    /// Step of the discretised collision check along arcs, m (> 0).
    pub arc_step_m: Option<f64>,
    /// Number of overflight headings per landmark (≥ 1).
    pub directions: Option<u32>,
    /// Line elements per landmark pair (≥ 1).
    pub line_elements_per_pair: Option<u32>,
    /// Weight of threat exposure against length (≥ 0).
    pub threat_weight: Option<f64>,
    /// Random seed.
    pub seed: Option<u64>,
    /// Three-dimensional roadmap: lowest sample altitude, m (finite, |value| ≤
    /// [`MAX_ALTITUDE_M`]); present exactly when `altitude_max_m` is.
    pub altitude_min_m: Option<f64>,
    /// Three-dimensional roadmap: highest sample altitude, m (≥ `altitude_min_m`, |value| ≤
    /// [`MAX_ALTITUDE_M`]); present exactly when `altitude_min_m` is.
    pub altitude_max_m: Option<f64>,
}

/// The `terrain` member.
#[derive(Clone, Debug, PartialEq)]
pub struct Terrain {
    /// The elevation model, resolved against the scenario file's directory.
    pub dem: PathBuf,
    /// Flight altitude, m.
    pub altitude_m: f64,
    /// Height to keep above the terrain, m (≥ 0).
    pub safety_height_m: f64,
}

/// A no-fly polygon.
#[derive(Clone, Debug, PartialEq)]
pub struct NoFly {
    /// Its name.
    pub name: String,
    /// The ring, `(lon, lat)` degrees, in file order, without the closing duplicate (and without
    /// consecutive duplicates). Simple: at least 3 vertices, no self-intersection.
    pub ring: Vec<(f64, f64)>,
    /// Its holes, rings as [`NoFly::ring`], in file order: areas inside the ring that are not
    /// part of the zone. Each lies strictly inside the ring and apart from the others.
    pub holes: Vec<Vec<(f64, f64)>>,
    /// Height of the building or zone, m (finite, > 0); `None`: unbounded (no altitude clears
    /// it). Only a three-dimensional scenario gives one.
    pub height_m: Option<f64>,
}

/// A polygon as the scenario parser reads it: its exterior ring and its holes.
#[derive(Clone, Debug, PartialEq)]
pub struct ZoneRings {
    /// The exterior ring (see [`NoFly::ring`]).
    pub exterior: Vec<(f64, f64)>,
    /// The holes (see [`NoFly::holes`]).
    pub holes: Vec<Vec<(f64, f64)>>,
}

/// Number of overflight headings in a landmark rosette: 0°, 30°, … 330°.
pub const ROSETTE_HEADINGS: usize = 12;

/// A landmark.
#[derive(Clone, Debug, PartialEq)]
pub struct Landmark {
    /// Its name.
    pub name: String,
    /// Longitude, degrees.
    pub lon: f64,
    /// Latitude, degrees.
    pub lat: f64,
    /// Largest useful distance, m (> 0).
    pub d_max_m: f64,
    /// For each weather of [`Scenario::weather`], in that order: the quality in [0, 1] for the
    /// overflight headings 0°, 30°, … 330°.
    pub quality: Vec<(String, [f64; ROSETTE_HEADINGS])>,
}

/// A start, goal or waypoint.
#[derive(Clone, Debug, PartialEq)]
pub struct Endpoint {
    /// Its name.
    pub name: String,
    /// Longitude, degrees.
    pub lon: f64,
    /// Latitude, degrees.
    pub lat: f64,
    /// Compass heading (degrees clockwise from true north, finite), `None`: any heading (a
    /// parsed start always has one).
    pub heading_deg: Option<f64>,
    /// The start only (landmark mode): the largest distance to the first landmark, m (> 0).
    pub dist_m: Option<f64>,
    /// Altitude, m (finite, |value| ≤ [`MAX_ALTITUDE_M`]): present exactly in a
    /// three-dimensional scenario.
    pub altitude_m: Option<f64>,
}

/// A known threat.
#[derive(Clone, Debug, PartialEq)]
pub struct Circle {
    /// Its name.
    pub name: String,
    /// Longitude of the centre, degrees.
    pub lon: f64,
    /// Latitude of the centre, degrees.
    pub lat: f64,
    /// Radius, m (> 0).
    pub radius_m: f64,
}

/// A pop-up threat.
#[derive(Clone, Debug, PartialEq)]
pub struct Popup {
    /// Its name.
    pub name: String,
    /// Longitude of the centre, degrees.
    pub lon: f64,
    /// Latitude of the centre, degrees.
    pub lat: f64,
    /// Radius, m (> 0).
    pub radius_m: f64,
    /// Probability that it appears, in [0, 1].
    pub probability: f64,
    /// Its top, metres, in a three-dimensional scenario (`properties.height_m`); `None`: no
    /// altitude clears it.
    pub height_m: Option<f64>,
}
