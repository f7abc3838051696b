//! The top-level members: `vehicle`, `planner`, `weather`, `terrain`.

use super::error::{compact, ErrorKind};
use super::json::describe;
use super::parser::{Parser, R, TOP};
use super::types::*;
use serde_json::Value;
use std::path::Path;

const VEHICLE_KEYS: &[&str] = &[
    "v_nominal_mps",
    "v_min_mps",
    "v_max_mps",
    "a_lat_max_mps2",
    "a_long_min_mps2",
    "a_long_max_mps2",
    "wingspan_m",
    "climb_rate_mps",
    "vertical_accel_mps2",
];
const PLANNER_KEYS: &[&str] = &[
    "mode",
    "clearance_m",
    "sample_spacing_m",
    "neighbour_radius_m",
    "k_nearest_fallback",
    "allow_ccc",
    "arc_step_m",
    "directions",
    "line_elements_per_pair",
    "threat_weight",
    "seed",
    "altitude_min_m",
    "altitude_max_m",
];
const TERRAIN_KEYS: &[&str] = &["dem", "altitude_m", "safety_height_m"];

impl Parser<'_> {
    pub(super) fn vehicle(&self, v: &Value) -> R<Vehicle> {
        let o = self.object(&TOP, v, "vehicle")?;
        self.no_unknown_members(o, VEHICLE_KEYS, "vehicle.")?;
        let p = "vehicle.";
        let n = |k: &str| self.req_number(&TOP, o, k, p);
        let veh = Vehicle {
            v_nominal_mps: n("v_nominal_mps")?,
            v_min_mps: n("v_min_mps")?,
            v_max_mps: n("v_max_mps")?,
            a_lat_max_mps2: n("a_lat_max_mps2")?,
            a_long_min_mps2: n("a_long_min_mps2")?,
            a_long_max_mps2: n("a_long_max_mps2")?,
            wingspan_m: n("wingspan_m")?,
            // Read once the planner says whether the scenario is three-dimensional
            // (`Parser::vertical`).
            climb_rate_mps: None,
            vertical_accel_mps2: None,
        };
        let bad = |field: &str, m: String| Err(self.err(&TOP, field, ErrorKind::VehicleLimits(m)));
        if veh.v_min_mps <= 0.0 {
            return bad(
                "vehicle.v_min_mps",
                format!(
                    "{} is not positive: a fixed-wing aircraft cannot hover",
                    compact(veh.v_min_mps)
                ),
            );
        }
        if veh.v_min_mps > veh.v_nominal_mps {
            return bad(
                "vehicle.v_min_mps",
                format!(
                    "{} exceeds v_nominal_mps {} (need v_min ≤ v_nominal ≤ v_max)",
                    compact(veh.v_min_mps),
                    compact(veh.v_nominal_mps)
                ),
            );
        }
        if veh.v_max_mps < veh.v_nominal_mps {
            return bad(
                "vehicle.v_max_mps",
                format!(
                    "{} is below v_nominal_mps {} (need v_min ≤ v_nominal ≤ v_max)",
                    compact(veh.v_max_mps),
                    compact(veh.v_nominal_mps)
                ),
            );
        }
        if veh.a_lat_max_mps2 <= 0.0 {
            return bad(
                "vehicle.a_lat_max_mps2",
                format!(
                    "{} is not positive: the aircraft could not turn",
                    compact(veh.a_lat_max_mps2)
                ),
            );
        }
        if veh.a_long_min_mps2 > 0.0 {
            return bad(
                "vehicle.a_long_min_mps2",
                format!(
                    "{} is positive: the deceleration limit must be ≤ 0",
                    compact(veh.a_long_min_mps2)
                ),
            );
        }
        if veh.a_long_max_mps2 < 0.0 {
            return bad(
                "vehicle.a_long_max_mps2",
                format!(
                    "{} is negative: the acceleration limit must be ≥ 0",
                    compact(veh.a_long_max_mps2)
                ),
            );
        }
        if veh.wingspan_m <= 0.0 {
            return bad(
                "vehicle.wingspan_m",
                format!("{} is not positive", compact(veh.wingspan_m)),
            );
        }
        Ok(veh)
    }

    pub(super) fn planner(&self, v: &Value) -> R<PlannerParams> {
        let o = self.object(&TOP, v, "planner")?;
        let mode_v = self.req(&TOP, o, "mode", "planner.mode")?;
        let mode = match self.string(&TOP, mode_v, "planner.mode")? {
            "roadmap" => Mode::Roadmap,
            "landmark" => Mode::Landmark,
            "terrain" => Mode::Terrain,
            "voronoi" => Mode::Voronoi,
            other => {
                return Err(self.err(&TOP, "planner.mode", ErrorKind::UnknownMode(other.into())))
            }
        };
        self.no_unknown_members(o, PLANNER_KEYS, "planner.")?;
        let p = "planner.";
        let num = |k: &str| self.opt_number(&TOP, o, k, p);
        let pos = |k: &str| -> R<Option<f64>> {
            num(k)?
                .map(|x| self.positive(&TOP, &format!("{p}{k}"), x))
                .transpose()
        };
        let nonneg = |k: &str| -> R<Option<f64>> {
            num(k)?
                .map(|x| self.non_negative(&TOP, &format!("{p}{k}"), x))
                .transpose()
        };
        let int = |k: &str, min: u64, max: u64| -> R<Option<u64>> {
            let field = format!("{p}{k}");
            match Self::opt(o, k) {
                None => Ok(None),
                Some(v) => {
                    let n = self.integer(&TOP, v, &field, max)?;
                    if n < min {
                        Err(self.err(
                            &TOP,
                            field,
                            ErrorKind::OutOfRange {
                                value: n as f64,
                                expected: "at least 1",
                            },
                        ))
                    } else {
                        Ok(Some(n))
                    }
                }
            }
        };
        let allow_ccc = match Self::opt(o, "allow_ccc") {
            None => None,
            Some(Value::Bool(b)) => Some(*b),
            Some(v) => {
                return Err(self.err(
                    &TOP,
                    "planner.allow_ccc",
                    ErrorKind::WrongType {
                        expected: "a boolean",
                        found: describe(v),
                    },
                ))
            }
        };
        let u32max = u32::MAX as u64;
        Ok(PlannerParams {
            mode,
            clearance_m: nonneg("clearance_m")?,
            sample_spacing_m: pos("sample_spacing_m")?,
            neighbour_radius_m: pos("neighbour_radius_m")?,
            k_nearest_fallback: int("k_nearest_fallback", 0, u32max)?.map(|n| n as u32),
            allow_ccc,
            arc_step_m: pos("arc_step_m")?,
            directions: int("directions", 1, u32max)?.map(|n| n as u32),
            line_elements_per_pair: int("line_elements_per_pair", 1, u32max)?.map(|n| n as u32),
            threat_weight: match nonneg("threat_weight")? {
                Some(k) if k > 1.0 => {
                    return Err(self.err(
                        &TOP,
                        "planner.threat_weight",
                        ErrorKind::Invalid(format!(
                            "{} is above 1: the weight k of length against exposure is in \
                             [0, 1]",
                            compact(k)
                        )),
                    ))
                }
                k => k,
            },
            seed: int("seed", 0, u64::MAX)?,
            altitude_min_m: self.opt_altitude(&TOP, o, "altitude_min_m", p)?,
            altitude_max_m: self.opt_altitude(&TOP, o, "altitude_max_m", p)?,
        })
    }

    pub(super) fn weather(&self, v: &Value) -> R<Vec<String>> {
        let a = v.as_array().ok_or_else(|| {
            self.err(
                &TOP,
                "weather",
                ErrorKind::WrongType {
                    expected: "an array of strings",
                    found: describe(v),
                },
            )
        })?;
        let mut out: Vec<String> = Vec::with_capacity(a.len());
        for (i, w) in a.iter().enumerate() {
            let field = format!("weather[{i}]");
            let w = self.string(&TOP, w, &field)?;
            if w.is_empty() {
                return Err(self.err(&TOP, field, ErrorKind::Invalid("empty name".into())));
            }
            if out.iter().any(|o| o == w) {
                return Err(self.err(&TOP, field, ErrorKind::DuplicateWeather(w.into())));
            }
            out.push(w.into());
        }
        Ok(out)
    }

    pub(super) fn terrain(&self, v: &Value) -> R<Terrain> {
        let o = self.object(&TOP, v, "terrain")?;
        self.no_unknown_members(o, TERRAIN_KEYS, "terrain.")?;
        let dem_v = self.req(&TOP, o, "dem", "terrain.dem")?;
        let dem = self.string(&TOP, dem_v, "terrain.dem")?;
        if dem.is_empty() {
            return Err(self.err(&TOP, "terrain.dem", ErrorKind::Invalid("empty path".into())));
        }
        let base = self.file.parent().unwrap_or(Path::new(""));
        let altitude_m = self.req_number(&TOP, o, "altitude_m", "terrain.")?;
        let h = self.req_number(&TOP, o, "safety_height_m", "terrain.")?;
        let safety_height_m = self.non_negative(&TOP, "terrain.safety_height_m", h)?;
        Ok(Terrain {
            dem: base.join(dem),
            altitude_m,
            safety_height_m,
        })
    }

    // --- geometry ----------------------------------------------------------------------------
}
