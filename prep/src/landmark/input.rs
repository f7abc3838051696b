//! The builder's input: the scenario's landmarks, endpoints, obstacles and vehicle in the
//! local frame.

use super::params::{LandmarkError, LandmarkParams};
use crate::frame::LocalFrame;
use crate::local::{local, local_heading, local_obstacles, local_pose};
use crate::scenario::{Landmark, Scenario, ROSETTE_HEADINGS};
use skyroute::geometry::hermite::FlyLimits;
use skyroute::network::write::ObstacleSpec;
use skyroute::{Pose, Vec2};

/// A landmark's quality rosette for one weather.
#[derive(Clone, Debug, PartialEq)]
pub struct Rosette {
    /// The weather's name.
    pub weather: String,
    /// Quality in [0, 1] per overflight direction (index = direction).
    pub quality: Vec<f32>,
}

/// A landmark in the local frame.
#[derive(Clone, Debug, PartialEq)]
pub struct LandmarkSite {
    /// Its name.
    pub name: String,
    /// Position, metres.
    pub position: Vec2,
    /// Largest useful distance, metres.
    pub d_max_m: f32,
    /// One rosette per weather, in the scenario's weather order.
    pub rosettes: Vec<Rosette>,
}

impl LandmarkSite {
    /// The best-weather range of direction `k`: `d_max · max_ω q(k, ω)`, metres (0 for an
    /// unknown direction or no weather).
    pub fn range_m(&self, k: usize) -> f32 {
        self.rosettes
            .iter()
            .filter_map(|r| r.quality.get(k))
            .fold(0.0f32, |m, &q| m.max(q))
            * self.d_max_m
    }

    /// The largest best-weather range over all directions, metres.
    pub fn max_range_m(&self) -> f32 {
        let n = self.rosettes.first().map_or(0, |r| r.quality.len());
        (0..n).map(|k| self.range_m(k)).fold(0.0, f32::max)
    }
}

/// A start or goal in the local frame.
#[derive(Clone, Debug, PartialEq)]
pub struct EndpointSite {
    /// Its name.
    pub name: String,
    /// The pose (heading 0 when the scenario gives none).
    pub pose: Pose,
    /// Local headings the endpoint may be flown with (radians): the scenario's heading, or
    /// without one, the compass headings of the overflight directions.
    pub headings: Vec<f32>,
    /// Start: the largest path length to the first landmark (`dist_m`), metres. Goal: `None`.
    pub dist_m: Option<f32>,
}

/// Everything the builder needs, in the local frame.
#[derive(Clone, Debug, PartialEq)]
pub struct LandmarkInput {
    /// The scenario file (for messages).
    pub file: String,
    /// The local frame (`None` for inputs made by hand).
    pub frame: Option<LocalFrame>,
    /// Landmarks, in scenario order.
    pub landmarks: Vec<LandmarkSite>,
    /// Weather names, in scenario order.
    pub weather: Vec<String>,
    /// Static obstacles (no-fly polygons and threat discs).
    pub obstacles: Vec<ObstacleSpec>,
    /// The vehicle's limits.
    pub limits: FlyLimits,
    /// Nominal speed, m/s.
    pub v_nominal: f32,
    /// Per landmark, per direction `k`: the local velocity (nominal speed) of compass heading
    /// `360·k/directions` degrees, converted at the landmark by the frame (meridian
    /// convergence); for an even count, direction `k + directions/2` is exactly `−v_k`.
    pub direction_velocities: Vec<Vec<Vec2>>,
    /// The start, if any.
    pub start: Option<EndpointSite>,
    /// The goal, if any.
    pub goal: Option<EndpointSite>,
}

/// The quality of rosette `q` (given at 0°, 30°, … 330°) at compass heading `deg`, linearly
/// interpolated around the circle.
pub fn rosette_quality(q: &[f64; ROSETTE_HEADINGS], deg: f64) -> f64 {
    let step = 360.0 / ROSETTE_HEADINGS as f64;
    let x = deg.rem_euclid(360.0) / step;
    let i = (x.floor() as usize) % ROSETTE_HEADINGS;
    let f = x - x.floor();
    q[i] * (1.0 - f) + q[(i + 1) % ROSETTE_HEADINGS] * f
}

impl LandmarkInput {
    /// Converts a scenario (any mode; its landmarks, weather, obstacles, vehicle, start and goal)
    /// to the local frame.
    pub fn from_scenario(s: &Scenario, params: &LandmarkParams) -> Result<Self, LandmarkError> {
        let file = s.path.display().to_string();
        let invalid =
            |field: &str, why: String| LandmarkError::Invalid(file.clone(), field.into(), why);
        if s.landmarks.is_empty() {
            return Err(LandmarkError::Missing(file, "features: a landmark"));
        }
        if s.weather.is_empty() {
            return Err(LandmarkError::Missing(
                file,
                "weather: at least one weather",
            ));
        }
        if params.directions == 0 {
            return Err(invalid("planner.directions", "must be at least 1".into()));
        }
        if params.line_elements_per_pair == 0 {
            return Err(invalid(
                "planner.line_elements_per_pair",
                "must be at least 1".into(),
            ));
        }
        if !(params.clearance_m >= 0.0 && params.clearance_m.is_finite()) {
            return Err(invalid(
                "planner.clearance_m",
                format!(
                    "{} is not a finite non-negative distance",
                    params.clearance_m
                ),
            ));
        }
        if !(params.neighbour_radius_m > 0.0 && params.neighbour_radius_m.is_finite()) {
            return Err(invalid(
                "neighbour_radius_m",
                format!(
                    "{} is not a finite positive distance",
                    params.neighbour_radius_m
                ),
            ));
        }
        let v = &s.vehicle;
        let limits = FlyLimits {
            v_min: v.v_min_mps as f32,
            v_max: v.v_max_mps as f32,
            a_long_min: v.a_long_min_mps2 as f32,
            a_long_max: v.a_long_max_mps2 as f32,
            a_lat_max: v.a_lat_max_mps2 as f32,
        };
        if !limits.is_valid() {
            return Err(invalid(
                "vehicle",
                format!("limits are not usable: {limits:?}"),
            ));
        }
        let v_nominal = v.v_nominal_mps as f32;
        if !(v_nominal >= limits.v_min && v_nominal <= limits.v_max) {
            return Err(invalid(
                "vehicle.v_nominal_mps",
                format!("{v_nominal} is outside [v_min, v_max]"),
            ));
        }
        let frame = s.local_frame();
        let n = params.directions;
        let compass = |k: usize| 360.0 * k as f64 / n as f64;
        let mut landmarks = Vec::with_capacity(s.landmarks.len());
        let mut direction_velocities = Vec::with_capacity(s.landmarks.len());
        for l in &s.landmarks {
            landmarks.push(site(l, &s.weather, &frame, n, compass));
            direction_velocities.push(direction_velocities_at(&frame, l, n, v_nominal));
        }
        let endpoint = |e: &crate::scenario::Endpoint,
                        is_start: bool|
         -> Result<EndpointSite, LandmarkError> {
            let dist_m = if is_start {
                Some(e.dist_m.ok_or_else(|| {
                    LandmarkError::Missing(file.clone(), "start: properties.dist_m")
                })? as f32)
            } else {
                None
            };
            Ok(EndpointSite {
                name: e.name.clone(),
                pose: local_pose(&frame, e.lon, e.lat, e.heading_deg),
                headings: match e.heading_deg {
                    Some(h) => vec![local_heading(&frame, e.lon, e.lat, h)],
                    None => (0..n)
                        .map(|k| local_heading(&frame, e.lon, e.lat, compass(k)))
                        .collect(),
                },
                dist_m,
            })
        };
        let start = s.start.as_ref().map(|e| endpoint(e, true)).transpose()?;
        let goal = s.goal.as_ref().map(|e| endpoint(e, false)).transpose()?;
        Ok(Self {
            file,
            landmarks,
            weather: s.weather.clone(),
            obstacles: local_obstacles(s, &frame),
            limits,
            v_nominal,
            direction_velocities,
            start,
            goal,
            frame: Some(frame),
        })
    }
}

fn site(
    l: &Landmark,
    weather: &[String],
    frame: &LocalFrame,
    n: usize,
    compass: impl Fn(usize) -> f64,
) -> LandmarkSite {
    let rosettes = weather
        .iter()
        .map(|w| {
            let q = l
                .quality
                .iter()
                .find(|(name, _)| name == w)
                .map(|(_, q)| *q)
                .unwrap_or([0.0; ROSETTE_HEADINGS]);
            Rosette {
                weather: w.clone(),
                quality: (0..n)
                    .map(|k| rosette_quality(&q, compass(k)) as f32)
                    .collect(),
            }
        })
        .collect();
    LandmarkSite {
        name: l.name.clone(),
        position: local(frame, l.lon, l.lat),
        d_max_m: l.d_max_m as f32,
        rosettes,
    }
}

/// The local velocities of the `n` overflight directions at landmark `l`; for an even `n`,
/// direction `k + n/2` is exactly `−v_k`.
fn direction_velocities_at(frame: &LocalFrame, l: &Landmark, n: usize, v: f32) -> Vec<Vec2> {
    let mut out: Vec<Vec2> = Vec::with_capacity(n);
    for k in 0..n {
        if n.is_multiple_of(2) && k >= n / 2 {
            let o = out[k - n / 2];
            out.push(Vec2::new(-o.x, -o.y));
        } else {
            let deg = 360.0 * k as f64 / n as f64;
            let h = local_heading(frame, l.lon, l.lat, deg);
            out.push(Vec2::from_angle(h) * v);
        }
    }
    out
}
