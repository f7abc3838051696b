//! What `skyroute plan` checks before it plans, beyond the network's own validation: that the
//! scenario is the one the network was built from ([`crate::provenance`]), that the mode's
//! query is all the scenario asks for, and that every endpoint and pop-up lies on the network's
//! map. It also gathers the pop-ups to apply: the scenario's `popup` features and `--popup`.

use crate::frame::LocalFrame;
use crate::mission::LocalPopup;
use crate::scenario::{Mode, Scenario};
use skyroute::{Network, Vec2};

/// Where a pop-up came from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PopupSource {
    /// A `popup` feature of the scenario.
    Scenario,
    /// A `--popup` option.
    CommandLine,
}

/// A circular pop-up to apply, as given.
#[derive(Clone, Debug, PartialEq)]
pub struct PopupInput {
    /// How messages name it: the feature's name, or `--popup #k`.
    pub name: String,
    /// Where it came from.
    pub source: PopupSource,
    /// Centre longitude, degrees.
    pub lon: f64,
    /// Centre latitude, degrees.
    pub lat: f64,
    /// Radius, metres.
    pub radius_m: f64,
    /// Its top, metres (three-dimensional roadmaps); `None`: no altitude clears it.
    pub height_m: Option<f64>,
    /// The scenario's appearance probability, if it gives one.
    pub probability: Option<f64>,
}

impl PopupInput {
    /// The pop-up in the network's frame.
    pub fn local(&self, frame: &LocalFrame) -> LocalPopup {
        LocalPopup {
            name: self.name.clone(),
            centre: crate::local::local(frame, self.lon, self.lat),
            radius: self.radius_m as f32,
            height: self.height_m.map(|h| h as f32),
        }
    }
}

/// The pop-ups a plan applies: the scenario's `popup` features (unless `with_scenario` is
/// false), then the command line's, numbered from 1 as `--popup #k`.
pub fn gather_popups(
    s: &Scenario,
    command_line: &[crate::cli_values::PopupArg],
    with_scenario: bool,
) -> Vec<PopupInput> {
    let from_scenario = s
        .popups
        .iter()
        .filter(|_| with_scenario)
        .map(|p| PopupInput {
            name: format!("pop-up {:?}", p.name),
            source: PopupSource::Scenario,
            lon: p.lon,
            lat: p.lat,
            radius_m: p.radius_m,
            height_m: p.height_m,
            probability: Some(p.probability),
        });
    let given = command_line.iter().enumerate().map(|(i, p)| PopupInput {
        name: format!("--popup #{}", i + 1),
        source: PopupSource::CommandLine,
        lon: p.lon,
        lat: p.lat,
        radius_m: p.radius_m,
        height_m: p.height_m,
        probability: None,
    });
    from_scenario.chain(given).collect()
}

/// The network's extent in the frame, and as a lon/lat box for messages.
struct Extent {
    lo: Vec2,
    hi: Vec2,
    text: String,
}

impl Extent {
    /// The network's map: its pop-up grid index, and for a terrain network also its elevation
    /// grid (where few cells are blocked, as high above the terrain, the nodes and so the index
    /// cover much less than the DEM, and the start and goal connect through the elevations).
    fn of(net: &Network, frame: &LocalFrame) -> Self {
        let (mut lo, mut hi) = net.extent();
        if let Some(g) = net.terrain_grid() {
            let far = g.origin + Vec2::new(g.cols as f32 * g.cell, g.rows as f32 * g.cell);
            lo = Vec2::new(lo.x.min(g.origin.x), lo.y.min(g.origin.y));
            hi = Vec2::new(hi.x.max(far.x), hi.y.max(far.y));
        }
        let corners = [(lo.x, lo.y), (hi.x, lo.y), (lo.x, hi.y), (hi.x, hi.y)]
            .map(|(x, y)| frame.to_geo(x as f64, y as f64));
        let lons = corners.map(|c| c.0);
        let lats = corners.map(|c| c.1);
        let min = |v: [f64; 4]| v.into_iter().fold(f64::INFINITY, f64::min);
        let max = |v: [f64; 4]| v.into_iter().fold(f64::NEG_INFINITY, f64::max);
        let text = format!(
            "lon {:.4}..{:.4}, lat {:.4}..{:.4}",
            min(lons),
            max(lons),
            min(lats),
            max(lats)
        );
        Extent { lo, hi, text }
    }

    /// How far `(lon, lat)` lies outside the extent, metres (0 inside; infinite where the
    /// projection gives no finite point).
    fn distance_outside(&self, frame: &LocalFrame, lon: f64, lat: f64) -> f64 {
        let (x, y) = frame.to_local(lon, lat);
        if !(x.is_finite() && y.is_finite()) {
            return f64::INFINITY;
        }
        let dx = (self.lo.x as f64 - x).max(x - self.hi.x as f64).max(0.0);
        let dy = (self.lo.y as f64 - y).max(y - self.hi.y as f64).max(0.0);
        dx.hypot(dy)
    }
}

fn km(m: f64) -> String {
    if m.is_finite() {
        format!("{:.1} km", m / 1000.0)
    } else {
        "immeasurably far".to_string()
    }
}

/// Refuses, by name, a start, waypoint or goal outside the network's extent, and a pop-up
/// whose disc does not reach it (such a pop-up can change nothing, so it is most likely a
/// mistake: the message says when swapping its longitude and latitude would put it on the
/// map), and a pop-up with a height on a network without altitudes. In landmark mode, also a
/// scenario with waypoints (a landmark network plans its stored start to its stored goal, so it
/// could not visit them).
pub fn check_query(
    s: &Scenario,
    net: &Network,
    frame: &LocalFrame,
    popups: &[PopupInput],
) -> Result<(), String> {
    if s.planner.mode == Mode::Landmark {
        if let Some(w) = s.waypoints.first() {
            return Err(format!(
                "waypoint {:?}: landmark networks plan from their start to their goal and \
                 cannot visit waypoints ({} in the scenario)",
                w.name,
                s.waypoints.len()
            ));
        }
    }
    let extent = Extent::of(net, frame);
    let ends = s
        .start
        .iter()
        .map(|e| ("start", e))
        .chain(s.waypoints.iter().map(|e| ("waypoint", e)))
        .chain(s.goal.iter().map(|e| ("goal", e)));
    for (role, e) in ends {
        let out = extent.distance_outside(frame, e.lon, e.lat);
        if out > 0.0 {
            return Err(format!(
                "{role} {:?} (lon {}, lat {}) lies {} outside the network's extent ({})",
                e.name,
                e.lon,
                e.lat,
                km(out),
                extent.text
            ));
        }
    }
    for p in popups {
        if let Some(h) = p.height_m.filter(|_| !net.is_three_dimensional()) {
            return Err(format!(
                "{} has a height ({h} m) but the network has no altitudes (not a 3-D \
                 roadmap): without the height it is a wall",
                p.name
            ));
        }
        let out = extent.distance_outside(frame, p.lon, p.lat);
        if out > p.radius_m {
            let swapped = p.lat.abs() <= 180.0
                && p.lon.abs() <= 90.0
                && extent.distance_outside(frame, p.lat, p.lon) <= p.radius_m;
            return Err(format!(
                "{} (lon {}, lat {}, radius {} m) lies {} outside the network's extent ({}){}",
                p.name,
                p.lon,
                p.lat,
                p.radius_m,
                km(out - p.radius_m),
                extent.text,
                if swapped {
                    "; with longitude and latitude swapped it would lie on the map: pop-ups \
                     are given as LON,LAT,RADIUS_M"
                } else {
                    ""
                }
            ));
        }
    }
    Ok(())
}

/// Refuses, by name, a waypoint or goal inside the disc of one of `popups` (below its top,
/// on a three-dimensional roadmap), and a start too except on a roadmap network (whose
/// planner leaves the pop-up by an exit first, `src/planner/exit.rs`): no route can pass or
/// end there, and the message names the endpoint and the pop-up as the scenario and the
/// command line do (the core's refusal would name the pop-up by its slot, and a goal it
/// cannot be reached in is reported at the waypoint before it).
pub fn check_ends_clear_of_popups(
    s: &Scenario,
    frame: &LocalFrame,
    popups: &[PopupInput],
) -> Result<(), String> {
    let exits = s.planner.mode == crate::scenario::Mode::Roadmap;
    let ends = s
        .start
        .iter()
        .filter(|_| !exits)
        .map(|e| ("start", e))
        .chain(s.waypoints.iter().map(|e| ("waypoint", e)))
        .chain(s.goal.iter().map(|e| ("goal", e)));
    for (role, e) in ends {
        let (x, y) = frame.to_local(e.lon, e.lat);
        for p in popups {
            let (cx, cy) = frame.to_local(p.lon, p.lat);
            let d = (x - cx).hypot(y - cy);
            let above = e.altitude_m.zip(p.height_m).is_some_and(|(z, h)| z >= h);
            if d < p.radius_m && !above {
                return Err(format!(
                    "{role} {:?} lies inside {} (radius {} m, its centre {:.0} m away): no \
                     route can {} there",
                    e.name,
                    p.name,
                    p.radius_m,
                    d,
                    match role {
                        "start" => "begin",
                        "goal" => "end",
                        _ => "pass",
                    }
                ));
            }
        }
    }
    Ok(())
}
