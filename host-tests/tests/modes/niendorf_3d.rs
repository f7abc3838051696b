//! The three-dimensional urban mission (`scenarios/niendorf-urban-3d`: niendorf-urban's
//! buildings with heights, samples in an altitude band), checked from the outside.
//!
//! The network is built and the mission planned by the ground tool's library, exactly as
//! `skyroute build` and `skyroute plan` do, and written to the route file's JSON. Everything
//! after that works from the JSON (read back by the route reader) and the scenario's own
//! GeoJSON: each primitive is sampled every ≤ 0.5 m, its altitude computed in f64 from the
//! definitions (`host_tests::reference::vertical_altitude`), and each point's distance to each
//! building footprint (projected with the route's frame) by the f64 point–polygon distance.

use std::path::PathBuf;

use serde_json::Value;
use skyroute_prep::build::{build, BuildOptions};
use skyroute_prep::frame::LocalFrame;
use skyroute_prep::mission::{plan_mission, Mission};
use skyroute_prep::render::route_from_json;
use skyroute_prep::route_json::mission_json;
use skyroute_prep::scenario;

use host_tests::reference::{dist_polygon, vertical_altitude, P};
use host_tests::scenarios;

const NAME: &str = "niendorf-urban-3d";
/// Clearance may be missed by this much (f32 storage and sampling), metres.
const TOL: f64 = 1e-2;

/// Each building's footprint (lon/lat ring, unclosed) and height (`+∞` when it has none).
fn buildings(text: &str) -> Vec<(String, Vec<P>, f64)> {
    let v: Value = serde_json::from_str(text).unwrap();
    let mut out = Vec::new();
    for f in v["features"].as_array().unwrap() {
        let props = &f["properties"];
        if props["kind"] != "no_fly" {
            continue;
        }
        let ring = f["geometry"]["coordinates"][0].as_array().unwrap();
        let mut ring: Vec<P> = ring
            .iter()
            .map(|p| (p[0].as_f64().unwrap(), p[1].as_f64().unwrap()))
            .collect();
        ring.pop();
        let height = props["height_m"].as_f64().unwrap_or(f64::INFINITY);
        out.push((props["name"].as_str().unwrap().to_string(), ring, height));
    }
    out
}

/// What the samples of a mission's route found: the least margin above height + clearance
/// among points within the clearance of a footprint, and the buildings flown over (points
/// inside a footprint).
struct Finding {
    least_margin: f64,
    overflown: Vec<String>,
}

fn check(m: &Mission, frame: &LocalFrame, text: &str, clearance: f64) -> Finding {
    let json = mission_json(m, frame, NAME);
    let route = route_from_json(&json).expect("the route reads back");
    let limits = &json["vertical"];
    assert!(
        limits.is_object(),
        "a three-dimensional route file names its limits"
    );
    let limits = skyroute::geometry::vertical::VerticalLimits {
        airspeed: limits["airspeed_mps"].as_f64().unwrap() as f32,
        climb_rate: limits["climb_rate_mps"].as_f64().unwrap() as f32,
        vertical_accel: limits["vertical_accel_mps2"].as_f64().unwrap() as f32,
    };
    let footprints: Vec<(String, Vec<P>, f64)> = buildings(text)
        .into_iter()
        .map(|(name, ring, h)| {
            let ring = ring
                .iter()
                .map(|&(lon, lat)| frame.to_local(lon, lat))
                .collect();
            (name, ring, h)
        })
        .collect();
    let mut finding = Finding {
        least_margin: f64::INFINITY,
        overflown: Vec::new(),
    };
    for leg in &route.legs {
        assert_eq!(
            leg.vertical.len(),
            leg.primitives.len(),
            "one profile per primitive"
        );
        for (p, (profile, offset)) in leg.primitives.iter().zip(&leg.vertical) {
            let n = (2.0 * p.length() as f64).ceil().max(1.0) as usize;
            for i in 0..=n {
                let s = p.length() as f64 * i as f64 / n as f64;
                let at = p.pose_at(s as f32).position;
                let z = vertical_altitude(profile, &limits, *offset as f64 + s);
                for (name, ring, height) in &footprints {
                    let d = dist_polygon((at.x as f64, at.y as f64), ring);
                    if d < clearance {
                        finding.least_margin = finding.least_margin.min(z - (height + clearance));
                    }
                    if d == 0.0 && !finding.overflown.contains(name) {
                        finding.overflown.push(name.clone());
                    }
                }
            }
        }
    }
    finding
}

/// The mission on the 3-D network keeps above every building's height plus the clearance
/// wherever it comes within the clearance of its footprint, flies over low buildings, and is
/// shorter than the same mission on the same scenario with every building of unbounded height.
#[test]
fn the_three_dimensional_urban_mission_flies_over_low_buildings_and_is_shorter_for_it() {
    let path = scenarios::scenario_path(NAME);
    let text = std::fs::read_to_string(&path).unwrap();
    let s = scenarios::scenario(NAME);
    let clearance = s
        .planner
        .clearance_m
        .expect("the scenario gives its clearance");
    let built = scenarios::built(NAME);
    let mission = plan_mission(&built.bytes, s, &built.frame, &[]).expect("the mission plans");
    let found = check(&mission, &built.frame, &text, clearance);
    assert!(
        found.least_margin >= -TOL,
        "{} m below a building's height plus the clearance",
        found.least_margin
    );
    assert!(
        !found.overflown.is_empty(),
        "the route flies over no building (the test would prove nothing)"
    );

    // The twin: the same scenario, every building a wall of unbounded height.
    let mut v: Value = serde_json::from_str(&text).unwrap();
    for f in v["features"].as_array_mut().unwrap() {
        f["properties"].as_object_mut().unwrap().remove("height_m");
    }
    let dir = std::env::temp_dir().join(format!("skyroute-3d-walls-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let walls_path: PathBuf = dir.join("walls.geojson");
    std::fs::write(&walls_path, serde_json::to_string(&v).unwrap()).unwrap();
    let walls = scenario::load(&walls_path).expect("the twin loads");
    let walls_built = build(&walls, &BuildOptions::default(), &|_, _| {}).expect("twin builds");
    let walled = plan_mission(&walls_built.bytes, &walls, &walls_built.frame, &[])
        .expect("the twin's mission plans");
    let _ = std::fs::remove_dir_all(&dir);
    let twin = check(&walled, &walls_built.frame, &text, clearance);
    assert!(twin.overflown.is_empty(), "walls are never flown over");
    println!(
        "3-D urban mission: {:.1} m over {} buildings ({:?}), least margin {:.2} m; with walls \
         {:.1} m",
        mission.length,
        found.overflown.len(),
        found.overflown,
        found.least_margin,
        walled.length
    );
    assert!(
        mission.length < walled.length,
        "{} m over low buildings, {} m with walls",
        mission.length,
        walled.length
    );
}
