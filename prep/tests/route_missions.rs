//! `skyroute plan -o X.plan / X.waypoints / X.kml`: the missions are checked by a real consumer
//! (pymavlink loads the WPL file, the plan's items convert to the same MAVLink mission:
//! `scripts/check_mission.py`), every waypoint lies on the route and every polyline segment
//! within the tolerance of it, and the KML's coordinates are the route's.

mod common;

use common::{ok, scenario, skyroute, stdout, TempDir};
use serde_json::Value;
use skyroute_prep::frame::LocalFrame;
use std::path::Path;
use std::process::Command;

/// The distance from local `p` to a primitive of the route file (`line` or `arc`), metres,
/// computed here from the JSON independently of the tool's own geometry.
fn distance_to(p: (f64, f64), prim: &Value) -> f64 {
    let pt = |v: &Value| (v[0].as_f64().unwrap(), v[1].as_f64().unwrap());
    let d = |a: (f64, f64), b: (f64, f64)| (a.0 - b.0).hypot(a.1 - b.1);
    match prim["type"].as_str().unwrap() {
        "line" => {
            let (a, b) = (pt(&prim["start"]), pt(&prim["end"]));
            let (dx, dy) = (b.0 - a.0, b.1 - a.1);
            let len2 = dx * dx + dy * dy;
            let t = if len2 > 0.0 {
                (((p.0 - a.0) * dx + (p.1 - a.1) * dy) / len2).clamp(0.0, 1.0)
            } else {
                0.0
            };
            d(p, (a.0 + t * dx, a.1 + t * dy))
        }
        _ => {
            let c = pt(&prim["centre"]);
            let r = prim["radius"].as_f64().unwrap();
            let (s0, sw) = (
                prim["start_angle"].as_f64().unwrap(),
                prim["sweep"].as_f64().unwrap(),
            );
            // Sample the arc densely (0.05 m): an independent, if approximate, nearest point.
            let n = ((r * sw.abs()) / 0.05).ceil().max(1.0) as usize;
            (0..=n)
                .map(|k| {
                    let a = s0 + sw * k as f64 / n as f64;
                    d(p, (c.0 + r * a.cos(), c.1 + r * a.sin()))
                })
                .fold(f64::INFINITY, f64::min)
        }
    }
}

/// The distance from `p` to the whole route.
fn distance_to_route(p: (f64, f64), route: &Value) -> f64 {
    route["legs"]
        .as_array()
        .unwrap()
        .iter()
        .flat_map(|l| l["primitives"].as_array().unwrap().iter())
        .map(|q| distance_to(p, q))
        .fold(f64::INFINITY, f64::min)
}

fn frame_of(route: &Value) -> LocalFrame {
    LocalFrame::new(
        route["frame"]["origin_lat_deg"].as_f64().unwrap(),
        route["frame"]["origin_lon_deg"].as_f64().unwrap(),
    )
}

fn read_json(path: &str) -> Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// Runs `scripts/check_mission.py` on a WPL and a plan file; `None` when pymavlink (or Python)
/// is missing in the fast tier.
fn pymavlink_check(wpl: &str, plan: &str) -> Option<String> {
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scripts/check_mission.py");
    let full = std::env::var("SKYROUTE_TIER").as_deref() == Ok("full");
    let o = match Command::new("python3")
        .arg(&script)
        .args([wpl, plan])
        .output()
    {
        Ok(o) => o,
        Err(e) if full => panic!("python3 is needed in the full tier: {e}"),
        Err(e) => {
            eprintln!("SKIPPED in the fast tier: the pymavlink check (no python3: {e})");
            return None;
        }
    };
    let text = String::from_utf8_lossy(&o.stdout).into_owned();
    match o.status.code() {
        Some(0) => Some(text),
        Some(2) if !full => {
            eprintln!(
                "SKIPPED in the fast tier: the pymavlink check ({})",
                text.trim()
            );
            None
        }
        _ => panic!(
            "check_mission.py {wpl} {plan}: {text}{}",
            String::from_utf8_lossy(&o.stderr)
        ),
    }
}

/// Plans `scenario_file` on `net` to `.json`, `.waypoints`, `.plan` and `.kml` under `dir`.
fn plan_all(dir: &TempDir, net: &str, scenario_file: &str, extra: &[&str]) -> [String; 4] {
    let outs = ["route.json", "route.waypoints", "route.plan", "route.kml"].map(|f| dir.file(f));
    for out in &outs {
        let mut args = vec!["plan", net, "--scenario", scenario_file, "-o", out];
        args.extend_from_slice(extra);
        let o = ok(skyroute(&args), "plan");
        if !out.ends_with(".json") && !out.ends_with(".kml") {
            assert!(stdout(&o).contains("mission: "), "{}", stdout(&o));
        }
    }
    outs
}

/// Checks a plan file's waypoints against the route: each on it, each segment's midpoint within
/// half the tolerance (the polyline's sagitta budget). Returns (items, largest waypoint offset,
/// largest midpoint offset).
fn check_waypoints_on_route(route: &Value, plan: &Value, tolerance: f64) -> (usize, f64, f64) {
    let frame = frame_of(route);
    let items = plan["mission"]["items"].as_array().unwrap();
    let local: Vec<(f64, f64)> = items
        .iter()
        .map(|it| {
            assert_eq!(it["command"], 16);
            let p = it["params"].as_array().unwrap();
            frame.to_local(p[5].as_f64().unwrap(), p[4].as_f64().unwrap())
        })
        .collect();
    let on = local
        .iter()
        .map(|&p| distance_to_route(p, route))
        .fold(0.0, f64::max);
    let mid = local
        .windows(2)
        .map(|w| distance_to_route(((w[0].0 + w[1].0) / 2.0, (w[0].1 + w[1].1) / 2.0), route))
        .fold(0.0, f64::max);
    assert!(on < 0.05, "a waypoint lies {on} m off the route");
    assert!(
        mid <= tolerance / 2.0 + 0.05,
        "a segment's midpoint is {mid} m off"
    );
    (items.len(), on, mid)
}

/// The KML parsed back: each leg's LineString points lie on the route, and the polygons and
/// points are the zones, pop-ups and endpoints.
fn check_kml(kml: &str, route: &Value, zones: usize, popups: usize) {
    let text = std::fs::read_to_string(kml).unwrap();
    let doc = roxmltree::Document::parse(&text).expect("the KML is well-formed XML");
    let ns = "http://www.opengis.net/kml/2.2";
    assert_eq!(doc.root_element().tag_name().namespace(), Some(ns));
    let frame = frame_of(route);
    let coords = |n: roxmltree::Node| -> Vec<(f64, f64, f64)> {
        let c = n
            .descendants()
            .find(|d| d.has_tag_name((ns, "coordinates")))
            .and_then(|d| d.text())
            .unwrap();
        c.split_whitespace()
            .map(|t| {
                let v: Vec<f64> = t.split(',').map(|x| x.parse().unwrap()).collect();
                (v[0], v[1], v[2])
            })
            .collect()
    };
    let lines: Vec<_> = doc
        .descendants()
        .filter(|n| n.has_tag_name((ns, "LineString")))
        .collect();
    assert_eq!(lines.len(), route["legs"].as_array().unwrap().len());
    let mut worst: f64 = 0.0;
    for l in &lines {
        for (lon, lat, alt) in coords(*l) {
            worst = worst.max(distance_to_route(frame.to_local(lon, lat), route));
            assert_eq!(alt, 100.0);
        }
    }
    assert!(worst < 0.05, "a KML point lies {worst} m off the route");
    let polygons = doc
        .descendants()
        .filter(|n| n.has_tag_name((ns, "Polygon")))
        .count();
    assert_eq!(polygons, zones + popups);
    let names: Vec<&str> = doc
        .descendants()
        .filter(|n| n.has_tag_name((ns, "Point")))
        .filter_map(|p| {
            p.parent()?
                .children()
                .find(|c| c.has_tag_name((ns, "name")))?
                .text()
        })
        .collect();
    let legs = route["legs"].as_array().unwrap();
    assert_eq!(names.first().copied(), legs[0]["from"].as_str());
    assert_eq!(names.last().copied(), legs[legs.len() - 1]["to"].as_str());
    eprintln!(
        "KML: {} legs, {} polygons, points {names:?}; largest offset {worst:.4} m",
        lines.len(),
        polygons
    );
}

#[test]
fn niendorf_missions_follow_the_route_and_pymavlink_reads_them() {
    let dir = TempDir::new("missions-niendorf");
    let (net, s) = (dir.file("n.bin"), scenario("niendorf-urban.geojson"));
    ok(skyroute(&["build", &s, "-o", &net]), "build");
    let [json, wpl, plan, kml] = plan_all(&dir, &net, &s, &[]);
    let route = read_json(&json);
    let p = read_json(&plan);
    assert_eq!(p["fileType"], "Plan");
    assert_eq!(p["mission"]["firmwareType"], 12, "PX4 by default");
    assert_eq!(p["mission"]["vehicleType"], 1);
    assert_eq!(p["mission"]["cruiseSpeed"], 25.0);
    assert_eq!(p["geoFence"]["polygons"].as_array().unwrap().len(), 60);
    assert!(p["geoFence"]["polygons"]
        .as_array()
        .unwrap()
        .iter()
        .all(|z| z["inclusion"] == false));
    // niendorf-urban's clearance is 7 m: a tolerance of 3.5 m.
    let (n, on, mid) = check_waypoints_on_route(&route, &p, 3.5);
    eprintln!("niendorf: {n} waypoints, on the route within {on:.4} m, midpoints {mid:.3} m");
    if let Some(line) = pymavlink_check(&wpl, &plan) {
        eprintln!("pymavlink: {}", line.trim());
        assert!(line.contains(&format!("home + {n}")), "{line}");
    }
    let zones = 60;
    check_kml(
        &kml,
        &route,
        zones,
        route["popups"].as_array().unwrap().len(),
    );

    let ardu = dir.file("ardu.plan");
    let args = ["plan", &net, "--scenario", &s, "--autopilot", "ardupilot"];
    ok(
        skyroute(&[&args[..], &["--altitude", "120", "-o", &ardu]].concat()),
        "plan",
    );
    let a = read_json(&ardu);
    assert_eq!(a["mission"]["firmwareType"], 3);
    assert_eq!(a["mission"]["items"][0]["params"][6], 120.0);
}

#[test]
fn ruz_popups_voronoi_missions_follow_the_route_and_pymavlink_reads_them() {
    let dir = TempDir::new("missions-ruz");
    let (net, s) = (dir.file("r.bin"), scenario("ruz-popups.geojson"));
    ok(
        skyroute(&["build", &s, "--mode", "voronoi", "-o", &net]),
        "build",
    );
    let [json, wpl, plan, kml] = plan_all(&dir, &net, &s, &["--mode", "voronoi"]);
    let route = read_json(&json);
    let p = read_json(&plan);
    assert_eq!(p["mission"]["cruiseSpeed"], 50.0);
    let popups = route["popups"].as_array().unwrap().len();
    assert_eq!(p["geoFence"]["circles"].as_array().unwrap().len(), popups);
    // ruz-popups' clearance is 50 m: a tolerance of 10 m.
    let (n, on, mid) = check_waypoints_on_route(&route, &p, 10.0);
    eprintln!("ruz-popups: {n} waypoints, on the route within {on:.4} m, midpoints {mid:.3} m");
    if let Some(line) = pymavlink_check(&wpl, &plan) {
        eprintln!("pymavlink: {}", line.trim());
        assert!(line.contains(&format!("home + {n}")), "{line}");
    }
    let zones = p["geoFence"]["polygons"].as_array().unwrap().len();
    check_kml(&kml, &route, zones, popups);
}
