//! The three-dimensional roadmap's keys (Niendorf et al.): the altitude band
//! (`planner.altitude_min_m`, `planner.altitude_max_m`), the vertical limits
//! (`vehicle.climb_rate_mps`, `vehicle.vertical_accel_mps2`), the no-fly zones' and pop-ups'
//! `height_m` and the endpoints' `altitude_m`. A scenario with the band is three-dimensional; in any other,
//! each of these keys is refused by name ([`ErrorKind::Planar`]).

use super::error::{compact, ErrorKind};
use super::parser::{At, Parser, R, TOP};
use super::types::{Mode, PlannerParams, Vehicle, MAX_ALTITUDE_M};
use serde_json::{Map, Value};

impl Parser<'_> {
    /// An optional top-level member `prefix` + `key` that, when present, is a positive number.
    pub(super) fn opt_positive(
        &self,
        o: &Map<String, Value>,
        key: &str,
        prefix: &str,
    ) -> R<Option<f64>> {
        self.opt_number(&TOP, o, key, prefix)?
            .map(|x| self.positive(&TOP, &format!("{prefix}{key}"), x))
            .transpose()
    }

    /// An optional altitude `prefix` + `key`: finite, at most [`MAX_ALTITUDE_M`] in magnitude.
    pub(super) fn opt_altitude(
        &self,
        at: &At,
        o: &Map<String, Value>,
        key: &str,
        prefix: &str,
    ) -> R<Option<f64>> {
        self.opt_number(at, o, key, prefix)?
            .map(|z| {
                self.range(
                    at,
                    &format!("{prefix}{key}"),
                    z,
                    z.abs() <= MAX_ALTITUDE_M,
                    "an altitude within ±100000 m",
                )
            })
            .transpose()
    }

    /// The altitude band's rules, once `vehicle` and `planner` are read: both bounds or
    /// neither, the lower not above the upper, only in roadmap mode. Then the vehicle's
    /// vertical limits (`vehicle_obj` is the member as written), which `vehicle` is given: in a
    /// three-dimensional scenario each a positive number or absent (the default); in a planar
    /// one refused when present, even as null (it would be ignored).
    pub(super) fn vertical(
        &self,
        vehicle: &mut Vehicle,
        vehicle_obj: &Value,
        planner: &PlannerParams,
    ) -> R<()> {
        let invalid =
            |field: &str, why: String| Err(self.err(&TOP, field, ErrorKind::Invalid(why)));
        let both = "a three-dimensional roadmap needs both bounds of its altitude band";
        let three_dimensional = match (planner.altitude_min_m, planner.altitude_max_m) {
            (Some(_), None) => {
                return invalid(
                    "planner.altitude_max_m",
                    format!("missing: planner.altitude_min_m is given, and {both}"),
                )
            }
            (None, Some(_)) => {
                return invalid(
                    "planner.altitude_min_m",
                    format!("missing: planner.altitude_max_m is given, and {both}"),
                )
            }
            (Some(lo), Some(hi)) if lo > hi => {
                return invalid(
                    "planner.altitude_min_m",
                    format!(
                        "{} is above planner.altitude_max_m {}",
                        compact(lo),
                        compact(hi)
                    ),
                )
            }
            (Some(_), Some(_)) if planner.mode != Mode::Roadmap => {
                return invalid(
                    "planner.altitude_min_m",
                    format!(
                        "only a roadmap can be three-dimensional, and planner.mode is {:?}",
                        planner.mode.as_str()
                    ),
                )
            }
            (Some(_), Some(_)) => true,
            (None, None) => false,
        };
        let Some(o) = vehicle_obj.as_object() else {
            return Ok(());
        };
        let p = "vehicle.";
        if three_dimensional {
            vehicle.climb_rate_mps = self.opt_positive(o, "climb_rate_mps", p)?;
            vehicle.vertical_accel_mps2 = self.opt_positive(o, "vertical_accel_mps2", p)?;
            return Ok(());
        }
        for key in ["climb_rate_mps", "vertical_accel_mps2"] {
            if o.contains_key(key) {
                return Err(self.err(&TOP, format!("{p}{key}"), ErrorKind::Planar));
            }
        }
        Ok(())
    }

    /// A no-fly or pop-up feature's `properties.height_m`: in a three-dimensional scenario a
    /// positive number or absent (unbounded); `None` in a planar one (whose key check refused
    /// it).
    pub(super) fn zone_height(
        &self,
        at: &At,
        props: &Map<String, Value>,
        three_dimensional: bool,
    ) -> R<Option<f64>> {
        if !three_dimensional {
            return Ok(None);
        }
        self.opt_number(at, props, "height_m", "properties.")?
            .map(|h| self.positive(at, "properties.height_m", h))
            .transpose()
    }

    /// A start, goal or waypoint's `properties.altitude_m`: required in a three-dimensional
    /// scenario; `None` in a planar one (whose key check refused it).
    pub(super) fn endpoint_altitude(
        &self,
        at: &At,
        props: &Map<String, Value>,
        three_dimensional: bool,
    ) -> R<Option<f64>> {
        if !three_dimensional {
            return Ok(None);
        }
        match self.opt_altitude(at, props, "altitude_m", "properties.")? {
            Some(z) => Ok(Some(z)),
            None => Err(self.err(
                at,
                "properties.altitude_m",
                ErrorKind::Invalid(
                    "missing: a three-dimensional scenario needs the altitude of every start, \
                     goal and waypoint"
                        .into(),
                ),
            )),
        }
    }
}
