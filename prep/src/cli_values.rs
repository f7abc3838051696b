//! The values of the command line's options, checked as clap parses them: each returns the
//! value or a message saying what was expected.

use crate::roadmap::Sagitta;
use crate::route_mission::Autopilot;
use crate::scenario::Mode;
use skyroute::planner::decision::DecisionLimits;

/// A `--popup` of `skyroute plan` and `render`: a disc, and on a three-dimensional roadmap
/// optionally its top.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PopupArg {
    /// Centre longitude, degrees.
    pub lon: f64,
    /// Centre latitude, degrees.
    pub lat: f64,
    /// Radius, metres.
    pub radius_m: f64,
    /// Its top, metres in the scenario's datum; `None`: no altitude clears it.
    pub height_m: Option<f64>,
}

/// `LON,LAT,RADIUS_M[,HEIGHT_M]` of `--popup`: a position in range, a positive finite
/// radius and, optionally, a positive height up to 100 km.
pub fn parse_tall_popup(s: &str) -> Result<PopupArg, String> {
    let v: Vec<f64> = s
        .split(',')
        .map(|x| x.trim().parse::<f64>().map_err(|e| format!("{x:?}: {e}")))
        .collect::<Result<_, _>>()?;
    let (disc, height_m) = match v[..] {
        [lon, lat, r] => ([lon, lat, r], None),
        [lon, lat, r, h] if h > 0.0 && h <= crate::scenario::MAX_ALTITUDE_M => {
            ([lon, lat, r], Some(h))
        }
        _ => ([f64::NAN; 3], None),
    };
    match disc {
        [lon, lat, r] if lon.abs() <= 180.0 && lat.abs() <= 90.0 && r > 0.0 && r.is_finite() => {
            Ok(PopupArg {
                lon,
                lat,
                radius_m: r,
                height_m,
            })
        }
        _ => Err(format!(
            "expected LON,LAT,RADIUS_M[,HEIGHT_M] with |lon| <= 180, |lat| <= 90, radius > 0 \
             and 0 < height <= 100000, got {s:?}"
        )),
    }
}

/// `LON,LAT,RADIUS_M` of `--threat`: a position in range and a positive finite radius.
pub fn parse_threat(s: &str) -> Result<(f64, f64, f64), String> {
    let v: Vec<f64> = s
        .split(',')
        .map(|x| x.trim().parse::<f64>().map_err(|e| format!("{x:?}: {e}")))
        .collect::<Result<_, _>>()?;
    match v[..] {
        [lon, lat, r] if lon.abs() <= 180.0 && lat.abs() <= 90.0 && r > 0.0 && r.is_finite() => {
            Ok((lon, lat, r))
        }
        _ => Err(format!(
            "expected LON,LAT,RADIUS_M with |lon| <= 180, |lat| <= 90, radius > 0, got {s:?}"
        )),
    }
}

/// `LON,LAT,HEADING_DEG` of `--start`: a position in range and a finite compass heading.
pub fn parse_start(s: &str) -> Result<(f64, f64, f64), String> {
    let v: Vec<f64> = s
        .split(',')
        .map(|x| x.trim().parse::<f64>().map_err(|e| format!("{x:?}: {e}")))
        .collect::<Result<_, _>>()?;
    match v[..] {
        [lon, lat, h] if lon.abs() <= 180.0 && lat.abs() <= 90.0 && h.is_finite() => Ok((lon, lat, h)),
        _ => Err(format!(
            "expected LON,LAT,HEADING_DEG with |lon| <= 180, |lat| <= 90, a finite heading, got {s:?}"
        )),
    }
}

/// `LON,LAT[,HEADING_DEG]` of `--goal`: a position and, optionally, a finite compass heading.
pub fn parse_goal(s: &str) -> Result<(f64, f64, Option<f64>), String> {
    let v: Vec<f64> = s
        .split(',')
        .map(|x| x.trim().parse::<f64>().map_err(|e| format!("{x:?}: {e}")))
        .collect::<Result<_, _>>()?;
    let on_earth = |lon: f64, lat: f64| lon.abs() <= 180.0 && lat.abs() <= 90.0;
    match v[..] {
        [lon, lat] if on_earth(lon, lat) => Ok((lon, lat, None)),
        [lon, lat, h] if on_earth(lon, lat) && h.is_finite() => Ok((lon, lat, Some(h))),
        _ => Err(format!(
            "expected LON,LAT or LON,LAT,HEADING_DEG with |lon| <= 180, |lat| <= 90, a finite \
             heading, got {s:?}"
        )),
    }
}

/// `NAME,HEADING_DEG` of `--last-overflight`: a landmark's name and a finite compass
/// heading (the name is everything before the last comma).
pub fn parse_last_overflight(s: &str) -> Result<(String, f64), String> {
    let parsed = s.rsplit_once(',').and_then(|(name, h)| {
        let h = h.trim().parse::<f64>().ok().filter(|h| h.is_finite())?;
        (!name.trim().is_empty()).then(|| (name.trim().to_string(), h))
    });
    parsed.ok_or_else(|| format!("expected NAME,HEADING_DEG with a finite heading, got {s:?}"))
}

/// A planner mode by name: roadmap, landmark, terrain or voronoi.
pub fn parse_mode(s: &str) -> Result<Mode, String> {
    match s.trim() {
        "roadmap" => Ok(Mode::Roadmap),
        "landmark" => Ok(Mode::Landmark),
        "terrain" => Ok(Mode::Terrain),
        "voronoi" => Ok(Mode::Voronoi),
        _ => Err(format!(
            "expected roadmap, landmark, terrain or voronoi, got {s:?}"
        )),
    }
}

/// An autopilot by name: px4 or ardupilot.
pub fn parse_autopilot(s: &str) -> Result<Autopilot, String> {
    match s.trim() {
        "px4" => Ok(Autopilot::Px4),
        "ardupilot" => Ok(Autopilot::ArduPilot),
        _ => Err(format!("expected px4 or ardupilot, got {s:?}")),
    }
}

/// An altitude, metres: any finite number.
pub fn parse_altitude(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(a) if a.is_finite() => Ok(a),
        _ => Err(format!("expected a finite number of metres, got {s:?}")),
    }
}

/// A weight in [0, 1].
pub fn parse_weight(s: &str) -> Result<f32, String> {
    match s.trim().parse::<f32>() {
        Ok(k) if (0.0..=1.0).contains(&k) => Ok(k),
        _ => Err(format!("expected a weight in [0, 1], got {s:?}")),
    }
}

/// The discretised check's reading by name: added or paper.
pub fn parse_sagitta(s: &str) -> Result<Sagitta, String> {
    match s {
        "added" => Ok(Sagitta::Added),
        "paper" => Ok(Sagitta::InClearance),
        _ => Err(format!("expected added or paper, got {s:?}")),
    }
}

/// The landmark range rule by name: ground (chains out of range dropped when built) or
/// onboard (every chain stored, navigability pruned onboard: Babel's reading).
pub fn parse_landmark_ranges(s: &str) -> Result<crate::landmark::RangeRule, String> {
    match s {
        "ground" => Ok(crate::landmark::RangeRule::PathLength),
        "onboard" => Ok(crate::landmark::RangeRule::Onboard),
        _ => Err(format!("expected ground or onboard, got {s:?}")),
    }
}

/// The terrain turn rule by name: paper or shared-equally.
pub fn parse_turn_rule(s: &str) -> Result<skyroute::TurnRule, String> {
    match s.trim() {
        "paper" => Ok(skyroute::TurnRule::Paper),
        "shared-equally" => Ok(skyroute::TurnRule::SharedEqually),
        _ => Err(format!("expected paper or shared-equally, got {s:?}")),
    }
}

/// The decision's time and fuel limits.
pub fn limits(time_max: f32, fuel_max: f32) -> DecisionLimits {
    DecisionLimits { time_max, fuel_max }
}

/// A limit: a finite number, 0 or more.
pub fn parse_limit(s: &str) -> Result<f32, String> {
    match s.trim().parse::<f32>() {
        Ok(x) if x.is_finite() && x >= 0.0 => Ok(x),
        _ => Err(format!("expected a non-negative number, got {s:?}")),
    }
}

/// A radius, metres: finite and positive (f32).
pub fn parse_radius(s: &str) -> Result<f32, String> {
    match s.trim().parse::<f32>() {
        Ok(r) if r.is_finite() && r > 0.0 => Ok(r),
        _ => Err(format!("expected a positive number of metres, got {s:?}")),
    }
}

/// A length, metres: finite and positive.
pub fn parse_positive(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(x) if x.is_finite() && x > 0.0 => Ok(x),
        _ => Err(format!("expected a positive number of metres, got {s:?}")),
    }
}

/// A length, metres: finite, 0 or more.
pub fn parse_non_negative(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(x) if x.is_finite() && x >= 0.0 => Ok(x),
        _ => Err(format!("expected a number of metres, 0 or more, got {s:?}")),
    }
}

/// A finite number of metres.
pub fn parse_finite(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(x) if x.is_finite() => Ok(x),
        _ => Err(format!("expected a finite number of metres, got {s:?}")),
    }
}

/// `MIN_X,MIN_Y,MAX_X,MAX_Y` of `--area`, metres, with each minimum below its maximum.
pub fn parse_area(s: &str) -> Result<(f64, f64, f64, f64), String> {
    let v: Vec<f64> = s
        .split(',')
        .map(|x| x.trim().parse::<f64>().map_err(|e| format!("{x:?}: {e}")))
        .collect::<Result<_, _>>()?;
    match v[..] {
        [x0, y0, x1, y1] if v.iter().all(|x| x.is_finite()) && x0 < x1 && y0 < y1 => {
            Ok((x0, y0, x1, y1))
        }
        _ => Err(format!(
            "expected MIN_X,MIN_Y,MAX_X,MAX_Y with MIN < MAX, got {s:?}"
        )),
    }
}

/// A shortcut pass by name: best or greedy.
pub fn parse_shortcuts(s: &str) -> Result<crate::mission::Shortcuts, String> {
    match s.trim() {
        "best" => Ok(crate::mission::Shortcuts::Best),
        "greedy" => Ok(crate::mission::Shortcuts::Greedy),
        _ => Err(format!("expected best or greedy, got {s:?}")),
    }
}

/// A free-heading rule by name: cheapest or paper.
pub fn parse_free_headings(s: &str) -> Result<crate::mission::FreeHeadingRule, String> {
    match s.trim() {
        "cheapest" => Ok(crate::mission::FreeHeadingRule::Cheapest),
        "paper" => Ok(crate::mission::FreeHeadingRule::MostClearOutEdges),
        _ => Err(format!("expected cheapest or paper, got {s:?}")),
    }
}
