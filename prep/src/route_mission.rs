//! Routes as autopilot missions: QGroundControl `.plan` files and the MAVLink `QGC WPL 110` text
//! format (`.waypoints`), from the detailed route file's JSON and the scenario.
//!
//! The plan file follows QGroundControl's "Plan File Format" page
//! (<https://docs.qgroundcontrol.com/master/en/qgc-dev-guide/file_formats/plan.html>): `mission`
//! (version 2) with one `SimpleItem` per waypoint, `geoFence` (version 2) with the scenario's
//! no-fly zones as exclusion polygons (clockwise, `[lat, lon]`) and the route's pop-ups as
//! exclusion circles, `rallyPoints` (version 2) with the goal. The text format is MAVLink's
//! "Mission Plain-Text File Format" (<https://mavlink.io/en/file_formats/>): a `QGC WPL 110`
//! line, then one tab-separated line per item (index, current, frame, command, param1–4,
//! latitude, longitude, altitude, autocontinue), item 0 the home position.
//!
//! The waypoints are those of [`crate::mission_waypoints::choose_waypoints`], every one a
//! `MAV_CMD_NAV_WAYPOINT` (16) with param1 (hold) 0, param2 its acceptance radius, param3 (pass
//! radius) 0 and param4 (yaw) 0. There is no takeoff item: the route starts in the air at the
//! scenario's start pose, so the mission starts there too (prepend a takeoff in the ground
//! station when launching from the ground).

use crate::frame::LocalFrame;
use crate::mission_waypoints::{choose_waypoints, LegPrimitives, WaypointPlan};
use crate::render::{route_from_json, Route};
use crate::scenario::{Mode, Scenario};
use serde_json::{json, Value};

/// `MAV_CMD_NAV_WAYPOINT`.
pub const NAV_WAYPOINT: u16 = 16;
/// `MAV_FRAME_GLOBAL`: altitude above mean sea level.
pub const FRAME_GLOBAL: u8 = 0;
/// `MAV_FRAME_GLOBAL_RELATIVE_ALT`: altitude above the home position.
pub const FRAME_GLOBAL_RELATIVE_ALT: u8 = 3;
/// `MAV_TYPE_FIXED_WING`.
const VEHICLE_FIXED_WING: u8 = 1;
/// The altitude above home when neither `--altitude` nor the scenario gives one, metres.
pub const DEFAULT_ALTITUDE_M: f64 = 100.0;
/// Vertices of a pop-up's circle in KML (the plan file has true circles).
const POPUP_VERTICES: usize = 64;

/// The flight stack a mission is written for (`plan --autopilot`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Autopilot {
    /// PX4 (`MAV_AUTOPILOT_PX4`, 12).
    #[default]
    Px4,
    /// ArduPilot (`MAV_AUTOPILOT_ARDUPILOTMEGA`, 3).
    ArduPilot,
}

impl Autopilot {
    /// Its `MAV_AUTOPILOT` value, the plan file's `firmwareType`.
    pub fn firmware_type(self) -> u8 {
        match self {
            Autopilot::Px4 => 12,
            Autopilot::ArduPilot => 3,
        }
    }

    /// Its name on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Autopilot::Px4 => "px4",
            Autopilot::ArduPilot => "ardupilot",
        }
    }
}

/// How a mission is written: for which autopilot, at which altitude.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct MissionOutput {
    /// The flight stack.
    pub autopilot: Autopilot,
    /// `--altitude`: metres above home (on a terrain network, above mean sea level).
    pub altitude_m: Option<f64>,
}

impl MissionOutput {
    /// A mission for `autopilot` at `altitude_m` (`None`: the default altitude).
    pub fn new(autopilot: Autopilot, altitude_m: Option<f64>) -> Self {
        MissionOutput {
            autopilot,
            altitude_m,
        }
    }
}

/// The mission's altitude and MAVLink frame: on a terrain network the network's altitude (or
/// `--altitude`) above mean sea level in `MAV_FRAME_GLOBAL`, since the route was checked against
/// the terrain at that altitude and the home's ground elevation is not known here; otherwise
/// `--altitude` (default 100 m) above home in `MAV_FRAME_GLOBAL_RELATIVE_ALT`.
pub fn mission_altitude(route_json: &Value, s: &Scenario, out: &MissionOutput) -> (f64, u8) {
    let terrain = route_json
        .get("altitude_m")
        .and_then(Value::as_f64)
        .or_else(|| s.terrain.as_ref().map(|t| t.altitude_m));
    match (s.planner.mode, terrain) {
        (Mode::Terrain, Some(a)) => (out.altitude_m.unwrap_or(a), FRAME_GLOBAL),
        _ => (
            out.altitude_m.unwrap_or(DEFAULT_ALTITUDE_M),
            FRAME_GLOBAL_RELATIVE_ALT,
        ),
    }
}

/// A route file's route, its frame and the mission waypoints along it.
pub struct MissionRoute {
    /// The route.
    pub route: Route,
    /// Its local frame.
    pub frame: LocalFrame,
    /// The waypoints.
    pub plan: WaypointPlan,
}

/// The route of a detailed route file's JSON and its waypoints for `s`'s clearance.
pub fn mission_route(route_json: &Value, s: &Scenario) -> Result<MissionRoute, String> {
    let route = route_from_json(route_json)?;
    let frame = LocalFrame::new(route.origin_deg.0, route.origin_deg.1);
    let legs: Vec<LegPrimitives> = route
        .legs
        .iter()
        .map(|l| LegPrimitives {
            from: &l.from,
            to: &l.to,
            primitives: &l.primitives,
        })
        .collect();
    let plan = choose_waypoints(&legs, s.planner.clearance_m);
    if plan.waypoints.is_empty() {
        return Err("legs: no primitives, so no waypoints".to_string());
    }
    Ok(MissionRoute { route, frame, plan })
}

/// `[lat, lon]` of a local point.
fn lat_lon(frame: &LocalFrame, p: (f64, f64)) -> (f64, f64) {
    let (lon, lat) = frame.to_geo(p.0, p.1);
    (lat, lon)
}

/// One mission item: command, frame, the seven params (x, y, z = lat, lon, alt).
struct Item {
    command: u16,
    frame: u8,
    params: [f64; 7],
}

fn items(m: &MissionRoute, altitude: f64, frame: u8) -> Vec<Item> {
    m.plan
        .waypoints
        .iter()
        .map(|w| {
            let (lat, lon) = lat_lon(&m.frame, w.position);
            Item {
                command: NAV_WAYPOINT,
                frame,
                params: [0.0, w.acceptance_m, 0.0, 0.0, lat, lon, altitude],
            }
        })
        .collect()
}

/// A circle's ring of `n` vertices (not closed), `(lat, lon)`, counter-clockwise in the local
/// frame.
pub fn circle_lat_lon(frame: &LocalFrame, centre: (f64, f64), r: f64, n: usize) -> Vec<(f64, f64)> {
    (0..n)
        .map(|k| {
            let a = std::f64::consts::TAU * k as f64 / n as f64;
            lat_lon(frame, (centre.0 + r * a.cos(), centre.1 + r * a.sin()))
        })
        .collect()
}

/// The pop-up circles of a route as KML rings (see [`circle_lat_lon`]).
pub fn popup_rings(m: &MissionRoute) -> Vec<(String, Vec<(f64, f64)>)> {
    m.route
        .popups
        .iter()
        .map(|p| {
            (
                p.name.clone(),
                circle_lat_lon(&m.frame, p.centre, p.radius, POPUP_VERTICES),
            )
        })
        .collect()
}

/// Twice the signed area of a ring of `(lat, lon)` in the plane (lon, lat): positive when
/// counter-clockwise on a map.
fn signed_area2(ring: &[(f64, f64)]) -> f64 {
    (0..ring.len())
        .map(|i| {
            let (a, b) = (ring[i], ring[(i + 1) % ring.len()]);
            a.1 * b.0 - b.1 * a.0
        })
        .sum()
}

/// The rings `(lon, lat)` that fence no-fly zone `z`: its ring, or for a zone with holes (which
/// a geofence polygon cannot have) the simple pieces the core checks, computed in `frame`.
fn fence_rings(z: &crate::scenario::NoFly, frame: &LocalFrame) -> Vec<Vec<(f64, f64)>> {
    if z.holes.is_empty() {
        return vec![z.ring.clone()];
    }
    let to_local = |r: &[(f64, f64)]| -> Vec<(f64, f64)> {
        r.iter()
            .map(|&(lon, lat)| frame.to_local(lon, lat))
            .collect()
    };
    let holes: Vec<Vec<(f64, f64)>> = z.holes.iter().map(|h| to_local(h)).collect();
    crate::zone_pieces::simple_pieces(&to_local(&z.ring), &holes)
        .into_iter()
        .map(|piece| piece.iter().map(|&(x, y)| frame.to_geo(x, y)).collect())
        .collect()
}

/// The plan file's `geoFence`: the no-fly zones as clockwise exclusion polygons (a zone with
/// holes as several), the pop-ups as exclusion circles.
fn geofence(s: &Scenario, m: &MissionRoute) -> Value {
    let polygons: Vec<Value> = s
        .no_fly
        .iter()
        .flat_map(|z| fence_rings(z, &m.frame))
        .map(|fence| {
            let mut ring: Vec<(f64, f64)> = fence.iter().map(|&(lon, lat)| (lat, lon)).collect();
            if signed_area2(&ring) > 0.0 {
                ring.reverse();
            }
            let points: Vec<[f64; 2]> = ring.iter().map(|&(lat, lon)| [lat, lon]).collect();
            json!({"inclusion": false, "polygon": points, "version": 1})
        })
        .collect();
    let circles: Vec<Value> = m
        .route
        .popups
        .iter()
        .map(|p| {
            let (lat, lon) = lat_lon(&m.frame, p.centre);
            json!({
                "circle": {"center": [lat, lon], "radius": p.radius},
                "inclusion": false,
                "version": 1,
            })
        })
        .collect();
    json!({"circles": circles, "polygons": polygons, "version": 2})
}

/// The QGroundControl plan file of a detailed route file's JSON.
pub fn qgc_plan(route_json: &Value, s: &Scenario, out: &MissionOutput) -> Result<Value, String> {
    let m = mission_route(route_json, s)?;
    let (altitude, frame) = mission_altitude(route_json, s, out);
    let items: Vec<Value> = items(&m, altitude, frame)
        .iter()
        .enumerate()
        .map(|(i, it)| {
            json!({
                "autoContinue": true,
                "command": it.command,
                "doJumpId": i + 1,
                "frame": it.frame,
                "params": it.params,
                "type": "SimpleItem",
            })
        })
        .collect();
    let home = lat_lon(&m.frame, m.plan.waypoints[0].position);
    let goal = lat_lon(
        &m.frame,
        m.plan.waypoints[m.plan.waypoints.len() - 1].position,
    );
    let speed = s.vehicle.v_nominal_mps;
    Ok(json!({
        "fileType": "Plan",
        "version": 1,
        "groundStation": "QGroundControl",
        "mission": {
            "version": 2,
            "firmwareType": out.autopilot.firmware_type(),
            "vehicleType": VEHICLE_FIXED_WING,
            // QGroundControl's altitude modes: 1 relative to home, 2 above mean sea level.
            "globalPlanAltitudeMode": if frame == FRAME_GLOBAL { 2 } else { 1 },
            "cruiseSpeed": speed,
            "hoverSpeed": speed,
            "plannedHomePosition": [home.0, home.1, 0.0],
            "items": items,
        },
        "geoFence": geofence(s, &m),
        "rallyPoints": {"points": [[goal.0, goal.1, altitude]], "version": 2},
    }))
}

/// A number for the text format: integers without a fraction, others with enough digits to
/// round-trip.
fn wpl_number(v: f64) -> String {
    if v.fract() == 0.0 && v.abs() < 1e15 {
        format!("{v:.0}")
    } else {
        format!("{v}")
    }
}

/// The `QGC WPL 110` text of a detailed route file's JSON: item 0 the home position (the
/// route's start, altitude 0 in `MAV_FRAME_GLOBAL`), then one item per waypoint.
pub fn wpl_text(route_json: &Value, s: &Scenario, out: &MissionOutput) -> Result<String, String> {
    let m = mission_route(route_json, s)?;
    let (altitude, frame) = mission_altitude(route_json, s, out);
    let home = lat_lon(&m.frame, m.plan.waypoints[0].position);
    let mut text = String::from("QGC WPL 110\n");
    let home_item = Item {
        command: NAV_WAYPOINT,
        frame: FRAME_GLOBAL,
        params: [0.0, 0.0, 0.0, 0.0, home.0, home.1, 0.0],
    };
    for (i, it) in std::iter::once(home_item)
        .chain(items(&m, altitude, frame))
        .enumerate()
    {
        let params: Vec<String> = it.params.iter().map(|&v| wpl_number(v)).collect();
        text.push_str(&format!(
            "{i}\t{}\t{}\t{}\t{}\t1\n",
            u8::from(i == 0),
            it.frame,
            it.command,
            params.join("\t")
        ));
    }
    Ok(text)
}

/// One line saying how the mission follows the route, for `skyroute plan`'s output.
pub fn mission_summary(m: &MissionRoute) -> String {
    let acc = m.plan.waypoints.iter().map(|w| w.acceptance_m);
    let (lo, hi) = acc.fold((f64::INFINITY, 0.0f64), |(a, b), x| (a.min(x), b.max(x)));
    format!(
        "mission: {} waypoints; the polyline stays within {:.2} m of the route and the \
         acceptance radii ({lo:.0}-{hi:.0} m) cut corners by at most {:.2} m (tolerance {:.2} m \
         = min(clearance / 2, 10 m))",
        m.plan.waypoints.len(),
        m.plan.polyline_error_m,
        m.plan.corner_cut_m,
        m.plan.tolerance_m
    )
}
