//! Reading route files written by `skyroute plan`.

use super::picture::{
    AlternativeMark, DecisionMark, DecisionPopup, PopupMark, Route, RouteLeg, ThreatMark,
};
use serde_json::Value;
use skyroute::geometry::spline::Piece;
use skyroute::geometry::vertical::{VerticalLimits, VerticalProfile};
use skyroute::{Arc, Primitive, Segment, Vec2};
use std::path::Path;

fn num(v: &Value, field: &str) -> Result<f64, String> {
    v.get(field)
        .and_then(Value::as_f64)
        .ok_or_else(|| format!("{field}: missing or not a number"))
}

fn point(v: &Value, field: &str) -> Result<Vec2, String> {
    match v.get(field).and_then(Value::as_array).map(|a| a.as_slice()) {
        Some([x, y]) => match (x.as_f64(), y.as_f64()) {
            (Some(x), Some(y)) => Ok(Vec2::new(x as f32, y as f32)),
            _ => Err(format!("{field}: expected [x, y] numbers")),
        },
        _ => Err(format!("{field}: expected [x, y]")),
    }
}

/// A primitive from the JSON written by [`crate::route_json::primitive_json`].
pub fn primitive_from_json(v: &Value) -> Result<Primitive, String> {
    match v.get("type").and_then(Value::as_str) {
        Some("line") => Ok(Primitive::Line(Segment::new(
            point(v, "start")?,
            point(v, "end")?,
        ))),
        Some("arc") => {
            let radius = num(v, "radius")?;
            if !radius.is_finite() || radius <= 0.0 {
                return Err(format!("radius: {radius} is not positive"));
            }
            Ok(Primitive::Arc(Arc {
                centre: point(v, "centre")?,
                radius: radius as f32,
                start_angle: num(v, "start_angle")? as f32,
                sweep: num(v, "sweep")? as f32,
            }))
        }
        Some(t) => Err(format!("type: unknown primitive type {t:?}")),
        None => Err("type: missing".to_string()),
    }
}

/// A piece from the JSON written by [`crate::voronoi_mission::piece_json`].
pub fn piece_from_json(v: &Value) -> Result<Piece, String> {
    match v.get("type").and_then(Value::as_str) {
        Some("line") => Ok(Piece::Line {
            a: point(v, "start")?,
            b: point(v, "end")?,
        }),
        Some("cubic") => {
            let pts = v
                .get("control_points")
                .and_then(Value::as_array)
                .ok_or("control_points: missing or not an array")?;
            if pts.len() != 4 {
                return Err(format!(
                    "control_points: expected 4 points, got {}",
                    pts.len()
                ));
            }
            let mut p = [Vec2::new(0.0, 0.0); 4];
            for (k, q) in pts.iter().enumerate() {
                p[k] = xy(q).ok_or_else(|| format!("control_points[{k}]: expected [x, y]"))?;
            }
            Ok(Piece::Cubic { p })
        }
        Some(t) => Err(format!("type: unknown piece type {t:?}")),
        None => Err("type: missing".to_string()),
    }
}

/// An `[x, y]` pair of numbers.
fn xy(v: &Value) -> Option<Vec2> {
    match v.as_array().map(|a| a.as_slice()) {
        Some([x, y]) => Some(Vec2::new(x.as_f64()? as f32, y.as_f64()? as f32)),
        _ => None,
    }
}

/// A Voronoi leg's `pieces` and `coarse` (both empty when the leg has none).
fn leg_curves(leg: &Value, i: usize) -> Result<(Vec<Piece>, Vec<Vec2>), String> {
    let pieces = leg
        .get("pieces")
        .and_then(Value::as_array)
        .into_iter()
        .flatten()
        .enumerate()
        .map(|(k, p)| piece_from_json(p).map_err(|e| format!("legs[{i}].pieces[{k}].{e}")))
        .collect::<Result<Vec<_>, _>>()?;
    let coarse = leg
        .get("coarse")
        .and_then(Value::as_array)
        .into_iter()
        .flatten()
        .enumerate()
        .map(|(k, p)| xy(p).ok_or_else(|| format!("legs[{i}].coarse[{k}]: expected [x, y]")))
        .collect::<Result<Vec<_>, _>>()?;
    Ok((pieces, coarse))
}

/// The route file's `threats` (absent: none). A threat whose `origin` starts with `in flight`
/// popped up in flight.
fn threats_from_json(v: &Value) -> Result<Vec<ThreatMark>, String> {
    let mut out = Vec::new();
    for (i, t) in v
        .get("threats")
        .and_then(Value::as_array)
        .into_iter()
        .flatten()
        .enumerate()
    {
        let centre = point(t, "centre").map_err(|e| format!("threats[{i}].{e}"))?;
        out.push(ThreatMark {
            centre: (centre.x as f64, centre.y as f64),
            radius: num(t, "radius_m").map_err(|e| format!("threats[{i}].{e}"))?,
            popped: t
                .get("origin")
                .and_then(Value::as_str)
                .is_some_and(|o| o.starts_with("in flight")),
        });
    }
    Ok(out)
}

/// The lines and arcs of `v`'s `primitives` member.
fn primitives_of(v: &Value) -> Result<Vec<Primitive>, String> {
    v.get("primitives")
        .and_then(Value::as_array)
        .ok_or("primitives: missing or not an array")?
        .iter()
        .enumerate()
        .map(|(k, p)| primitive_from_json(p).map_err(|e| format!("primitives[{k}].{e}")))
        .collect()
}

/// A pop-up of the route file's `decision` (`what` names it in errors).
fn decision_popup(p: &Value, what: &str) -> Result<DecisionPopup, String> {
    let alternatives = p
        .get("alternatives")
        .and_then(Value::as_array)
        .ok_or_else(|| format!("{what}.alternatives: missing or not an array"))?
        .iter()
        .enumerate()
        .map(|(k, a)| {
            let at = |e: String| format!("{what}.alternatives[{k}].{e}");
            Ok(AlternativeMark {
                primitives: primitives_of(a).map_err(at)?,
                length_m: num(a, "length_m").map_err(at)?,
                risk: num(a, "risk").map_err(at)?,
                time: num(a, "time_factor").map_err(at)?,
                fuel: num(a, "fuel_factor").map_err(at)?,
            })
        })
        .collect::<Result<Vec<_>, String>>()?;
    let chosen = p
        .get("chosen")
        .and_then(Value::as_u64)
        .filter(|&c| (c as usize) < alternatives.len())
        .ok_or_else(|| format!("{what}.chosen: missing or not an alternative's index"))?;
    Ok(DecisionPopup {
        name: p
            .get("name")
            .and_then(Value::as_str)
            .unwrap_or("?")
            .to_string(),
        probability: num(p, "probability").map_err(|e| format!("{what}.{e}"))?,
        chosen: chosen as usize,
        alternatives,
    })
}

/// The route file's `decision` (`plan --popup-appears`), or `None` when it has none.
fn decision_from_json(v: &Value) -> Result<Option<DecisionMark>, String> {
    let Some(d) = v.get("decision") else {
        return Ok(None);
    };
    let at = |e: String| format!("decision.{e}");
    let nominal = d.get("nominal").ok_or("decision.nominal: missing")?;
    let limits = d.get("limits").ok_or("decision.limits: missing")?;
    let popups = d
        .get("popups")
        .and_then(Value::as_array)
        .ok_or("decision.popups: missing or not an array")?
        .iter()
        .enumerate()
        .map(|(i, p)| decision_popup(p, &format!("decision.popups[{i}]")))
        .collect::<Result<Vec<_>, _>>()?;
    Ok(Some(DecisionMark {
        nominal: primitives_of(nominal).map_err(|e| format!("decision.nominal.{e}"))?,
        popups,
        limits: (
            num(limits, "time").map_err(|e| format!("decision.limits.{e}"))?,
            num(limits, "fuel").map_err(|e| format!("decision.limits.{e}"))?,
        ),
        total_risk: num(d, "total_risk").map_err(at)?,
        mean_time: num(d, "mean_time_factor").map_err(at)?,
        mean_fuel: num(d, "mean_fuel_factor").map_err(at)?,
    }))
}

/// A route from the JSON text of a route file.
pub fn parse_route(text: &str) -> Result<Route, String> {
    let v: Value = serde_json::from_str(text).map_err(|e| format!("invalid JSON: {e}"))?;
    route_from_json(&v)
}

/// A route from the parsed JSON of a route file.
pub fn route_from_json(v: &Value) -> Result<Route, String> {
    if v.get("type").and_then(Value::as_str) == Some("FeatureCollection") {
        return Err(
            "a GeoJSON FeatureCollection (a scenario or a .geojson route), not a route \
                    file: give the .json route file `skyroute plan -o ROUTE.json` writes"
                .into(),
        );
    }
    let frame = v.get("frame").ok_or("frame: missing")?;
    let origin_deg = (
        num(frame, "origin_lat_deg").map_err(|e| format!("frame.{e}"))?,
        num(frame, "origin_lon_deg").map_err(|e| format!("frame.{e}"))?,
    );
    let legs = v
        .get("legs")
        .and_then(Value::as_array)
        .ok_or("legs: missing or not an array")?;
    let limits = match v.get("vertical") {
        Some(l) => Some(vertical_limits_from_json(l).map_err(|e| format!("vertical.{e}"))?),
        None => None,
    };
    let mut out = Vec::new();
    for (i, leg) in legs.iter().enumerate() {
        let name = |k: &str| {
            leg.get(k)
                .and_then(Value::as_str)
                .unwrap_or("?")
                .to_string()
        };
        let prims = leg
            .get("primitives")
            .and_then(Value::as_array)
            .ok_or_else(|| format!("legs[{i}].primitives: missing or not an array"))?;
        let primitives = prims
            .iter()
            .enumerate()
            .map(|(k, p)| {
                primitive_from_json(p).map_err(|e| format!("legs[{i}].primitives[{k}].{e}"))
            })
            .collect::<Result<Vec<_>, _>>()?;
        let length_m = leg
            .get("length_m")
            .and_then(Value::as_f64)
            .unwrap_or_else(|| primitives.iter().map(|p| p.length() as f64).sum());
        let (pieces, coarse) = leg_curves(leg, i)?;
        let vertical = match &limits {
            Some(limits) => prims
                .iter()
                .enumerate()
                .map(|(k, p)| {
                    altitude_from_json(p, limits)
                        .map_err(|e| format!("legs[{i}].primitives[{k}].altitude.{e}"))
                })
                .collect::<Result<Vec<_>, _>>()?,
            None => Vec::new(),
        };
        out.push(RouteLeg {
            from: name("from"),
            to: name("to"),
            length_m,
            primitives,
            pieces,
            coarse,
            vertical,
        });
    }
    let mut popups = Vec::new();
    for (i, p) in v
        .get("popups")
        .and_then(Value::as_array)
        .into_iter()
        .flatten()
        .enumerate()
    {
        let centre = point(p, "centre").map_err(|e| format!("popups[{i}].{e}"))?;
        popups.push(PopupMark {
            name: p
                .get("name")
                .and_then(Value::as_str)
                .unwrap_or("?")
                .to_string(),
            centre: (centre.x as f64, centre.y as f64),
            radius: num(p, "radius_m").map_err(|e| format!("popups[{i}].{e}"))?,
        });
    }
    Ok(Route {
        popups,
        scenario: v
            .get("scenario")
            .and_then(Value::as_str)
            .unwrap_or("")
            .to_string(),
        origin_deg,
        legs: out,
        threats: threats_from_json(v)?,
        threat_weight: v.get("threat_weight").and_then(Value::as_f64),
        exposure_flown: v.get("exposure_flown").and_then(Value::as_f64),
        scenario_popups_applied: v.get("scenario_popups_applied").and_then(Value::as_bool),
        decision: decision_from_json(v)?,
        altitude_m: v.get("altitude_m").and_then(Value::as_f64),
    })
}

/// A three-dimensional route's vertical limits (`vertical`: airspeed, climb rate, vertical
/// acceleration).
fn vertical_limits_from_json(v: &Value) -> Result<VerticalLimits, String> {
    let limits = VerticalLimits {
        airspeed: num(v, "airspeed_mps")? as f32,
        climb_rate: num(v, "climb_rate_mps")? as f32,
        vertical_accel: num(v, "vertical_accel_mps2")? as f32,
    };
    match limits.is_valid() {
        true => Ok(limits),
        false => Err("airspeed_mps, climb_rate_mps, vertical_accel_mps2: not all positive".into()),
    }
}

/// A three-dimensional route's primitive: its path's profile, rebuilt from its `altitude`
/// member, and the distance along the path at which it starts.
fn altitude_from_json(
    p: &Value,
    limits: &VerticalLimits,
) -> Result<(VerticalProfile, f32), String> {
    let a = p
        .get("altitude")
        .ok_or("missing (the route is three-dimensional)")?;
    let (from, to, length) = (num(a, "from_m")?, num(a, "to_m")?, num(a, "path_length_m")?);
    let offset = num(a, "offset_m")? as f32;
    let profile = VerticalProfile::new(from as f32, to as f32, length as f32, limits).ok_or(
        "from_m, to_m, path_length_m: not a climb the vertical limits allow over that length",
    )?;
    Ok((profile, offset))
}

/// Reads a route file; errors name it.
pub fn read_route(path: &Path) -> Result<Route, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
    parse_route(&text).map_err(|e| format!("{}: {e}", path.display()))
}
