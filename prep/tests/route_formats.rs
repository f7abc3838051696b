//! `skyroute plan -o FILE` picks the route format by the extension: the detailed `.json` route
//! file, or RFC 7946 GeoJSON (`.geojson`) that GDAL opens; an unknown extension is refused
//! (the mission and KML formats: `route_missions.rs`).

mod common;

use common::{code, niendorf, ok, skyroute, stderr, TempDir};
use serde_json::Value;
use std::path::Path;
use std::process::Command;

/// Great-circle distance on the mean-radius sphere, metres: an independent length check (the
/// planner measures in its transverse Mercator frame; the two agree to far better than 0.5 %
/// over a few kilometres).
fn haversine_m(a: [f64; 2], b: [f64; 2]) -> f64 {
    let (p1, p2) = (a[1].to_radians(), b[1].to_radians());
    let (dp, dl) = (p2 - p1, (b[0] - a[0]).to_radians());
    let h = (dp / 2.0).sin().powi(2) + p1.cos() * p2.cos() * (dl / 2.0).sin().powi(2);
    2.0 * 6_371_008.8 * h.sqrt().asin()
}

fn point(v: &Value) -> [f64; 2] {
    [v[0].as_f64().unwrap(), v[1].as_f64().unwrap()]
}

#[test]
fn geojson_routes_are_rfc7946_and_match_the_detailed_route() {
    let dir = TempDir::new("route-formats");
    let (net, json_path, geo_path) = (
        dir.file("n.bin"),
        dir.file("route.json"),
        dir.file("route.geojson"),
    );
    ok(skyroute(&["build", &niendorf(), "-o", &net]), "build");
    let scenario = niendorf();
    for out in [&json_path, &geo_path] {
        let args = [
            "plan",
            &net,
            "--scenario",
            &scenario,
            "--popup",
            "11.6275,48.0960,150",
            "-o",
            out,
        ];
        ok(skyroute(&args), "plan");
    }
    let detailed: Value =
        serde_json::from_str(&std::fs::read_to_string(&json_path).unwrap()).unwrap();
    let geo: Value = serde_json::from_str(&std::fs::read_to_string(&geo_path).unwrap()).unwrap();
    assert_eq!(geo["type"], "FeatureCollection");
    let features = geo["features"].as_array().unwrap();
    let legs: Vec<&Value> = features
        .iter()
        .filter(|f| f["properties"]["kind"] == "leg")
        .collect();
    assert_eq!(legs.len(), detailed["legs"].as_array().unwrap().len());
    assert_eq!(features.len(), legs.len() + 1, "the legs and one pop-up");

    // The first point is the scenario's start, with its heading (true north, degrees).
    let first = point(&legs[0]["geometry"]["coordinates"][0]);
    assert!((first[0] - 11.64794475).abs() < 1e-7 && (first[1] - 48.0918477).abs() < 1e-7);
    let heading = legs[0]["properties"]["start_heading_deg"].as_f64().unwrap();
    assert!((heading - 216.5).abs() < 0.01, "{heading}");
    let mut total = 0.0;
    for (i, leg) in legs.iter().enumerate() {
        let coords = leg["geometry"]["coordinates"].as_array().unwrap();
        assert_eq!(leg["geometry"]["type"], "LineString");
        let sampled: f64 = coords
            .windows(2)
            .map(|w| haversine_m(point(&w[0]), point(&w[1])))
            .sum();
        let length = leg["properties"]["length_m"].as_f64().unwrap();
        assert!(
            (sampled - length).abs() <= 0.005 * length,
            "leg {i}: {sampled} m sampled, {length} m stated"
        );
        total += length;
        if let Some(next) = legs.get(i + 1) {
            let (end, start) = (
                point(coords.last().unwrap()),
                point(&next["geometry"]["coordinates"][0]),
            );
            assert!(
                haversine_m(end, start) < 0.01,
                "legs {i} and {} meet",
                i + 1
            );
        }
    }
    let length = detailed["length_m"].as_f64().unwrap();
    assert!(
        (total - length).abs() < 0.01 * length.max(1.0),
        "{total} vs {length}"
    );

    // The pop-up: a closed counter-clockwise ring 150 m round its centre.
    let popup = features
        .iter()
        .find(|f| f["properties"]["kind"] == "popup")
        .unwrap();
    let ring = popup["geometry"]["coordinates"][0].as_array().unwrap();
    assert_eq!(ring.first(), ring.last());
    let area2: f64 = ring
        .windows(2)
        .map(|w| {
            let (a, b) = (point(&w[0]), point(&w[1]));
            a[0] * b[1] - b[0] * a[1]
        })
        .sum();
    assert!(
        area2 > 0.0,
        "exterior ring counter-clockwise (RFC 7946 §3.1.6)"
    );
    for v in ring {
        let d = haversine_m(point(v), [11.6275, 48.0960]);
        assert!((d - 150.0).abs() < 0.5, "{d}");
    }
    assert!(geo["skyroute"]["frame"]["proj"]
        .as_str()
        .unwrap()
        .starts_with("+proj=tmerc"));

    // GDAL opens it (Debian's gdal-bin, installed by scripts/test.sh).
    match Command::new("ogrinfo")
        .args(["-ro", "-al", "-so", &geo_path])
        .output()
    {
        Ok(o) => {
            let text = String::from_utf8_lossy(&o.stdout);
            assert!(o.status.success(), "{text}");
            let count = format!("Feature Count: {}", features.len());
            assert!(text.contains(&count), "{text}");
        }
        Err(e) if std::env::var("SKYROUTE_TIER").as_deref() == Ok("full") => {
            panic!("ogrinfo (gdal-bin) is needed in the full tier: {e}")
        }
        Err(e) => eprintln!("SKIPPED in the fast tier: the GDAL check (no ogrinfo: {e})"),
    }
}

#[test]
fn an_unknown_route_extension_is_refused_before_planning() {
    let dir = TempDir::new("route-ext");
    let out = dir.file("route.kmz");
    let o = skyroute(&["plan", "missing.bin", "--scenario", &niendorf(), "-o", &out]);
    assert_eq!(code(&o), 1);
    let e = stderr(&o);
    assert!(e.contains("route.kmz") && e.contains(".geojson"), "{e}");
    assert!(!Path::new(&out).exists());
}
