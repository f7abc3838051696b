//! Mission planning: a waypoint whose heading points at a wall closer than a turn is reported,
//! by name, as an inevitable-collision state; the same waypoint with room to turn is flown.

use serde_json::json;
use skyroute_prep::build::{build, BuildOptions};
use skyroute_prep::mission::{plan_mission, MissionError};
use skyroute_prep::scenario;

const LAT0: f64 = 48.0;
const LON0: f64 = 11.0;

/// Metres east/north of (LAT0, LON0) as [lon, lat] (small offsets: a local linearisation).
fn ll(x: f64, y: f64) -> [f64; 2] {
    let m_per_deg_lat = 111_132.0;
    let m_per_deg_lon = 111_320.0 * LAT0.to_radians().cos();
    [LON0 + x / m_per_deg_lon, LAT0 + y / m_per_deg_lat]
}

fn rect(name: &str, x0: f64, y0: f64, x1: f64, y1: f64) -> serde_json::Value {
    json!({"type": "Feature", "properties": {"kind": "no_fly", "name": name},
           "geometry": {"type": "Polygon", "coordinates": [[ll(x0, y0), ll(x1, y0), ll(x1, y1), ll(x0, y1), ll(x0, y0)]]}})
}

fn point(kind: &str, name: &str, x: f64, y: f64, heading: Option<f64>) -> serde_json::Value {
    let mut props = json!({"kind": kind, "name": name});
    if let Some(h) = heading {
        props["heading_deg"] = json!(h);
    }
    json!({"type": "Feature", "properties": props, "geometry": {"type": "Point", "coordinates": ll(x, y)}})
}

/// A wall 800 m wide, `gap` m north of a waypoint that must be flown northwards: closer than a
/// turn radius, no turn clears it.
fn wall_scenario(gap: f64) -> String {
    let features = vec![
        rect("wall", 600.0, 1200.0 + gap, 1400.0, 1260.0 + gap),
        point("start", "S", 1000.0, 300.0, Some(0.0)),
        point("waypoint", "FACING WALL", 1000.0, 1200.0, Some(0.0)),
        point("goal", "G", 1700.0, 300.0, Some(180.0)),
        // Two tiny no-fly squares at the corners make the sampled area 2 x 2 km.
        rect("corner sw", 0.0, 0.0, 2.0, 2.0),
        rect("corner ne", 1998.0, 1998.0, 2000.0, 2000.0),
    ];
    json!({
        "type": "FeatureCollection",
        "name": "wall",
        "vehicle": {"v_nominal_mps": 25.0, "v_min_mps": 20.0, "v_max_mps": 40.0, "a_lat_max_mps2": 9.81,
                    "a_long_min_mps2": -3.0, "a_long_max_mps2": 3.0, "wingspan_m": 3.0},
        "planner": {"mode": "roadmap", "sample_spacing_m": 40.0, "neighbour_radius_m": 191.1,
                    "k_nearest_fallback": 8, "allow_ccc": true, "clearance_m": 5.0, "arc_step_m": 20.0, "seed": 3},
        "features": features,
    })
    .to_string()
}

fn plan(gap: f64) -> Result<f64, MissionError> {
    let dir = std::env::temp_dir().join(format!("skyroute-wall-{}-{gap}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("wall.geojson");
    std::fs::write(&path, wall_scenario(gap)).unwrap();
    let s = scenario::load(&path).unwrap();
    let built = build(&s, &BuildOptions::default(), &|_, _| {}).unwrap();
    let frame =
        skyroute_prep::export::network_frame(&skyroute::Network::from_bytes(&built.bytes).unwrap());
    let result = plan_mission(&built.bytes, &s, &frame, &[]).map(|m| m.length);
    let _ = std::fs::remove_dir_all(&dir);
    result
}

#[test]
fn a_waypoint_facing_a_wall_closer_than_a_turn_is_an_inevitable_collision_state() {
    // Turn radius 25²/9.81 = 63.7 m, clearance 5 m: 40 m is too close to turn away.
    match plan(40.0) {
        Err(MissionError::InevitableCollision(name)) => assert_eq!(name, "FACING WALL"),
        other => panic!("expected an inevitable-collision state, got {other:?}"),
    }
}

#[test]
fn the_same_waypoint_with_room_to_turn_is_flown() {
    let length = plan(200.0).expect("route with room to turn");
    assert!(length > 1500.0);
}
