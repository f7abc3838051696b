//! Unit tests of the scenario parser.

use super::geometry::first_self_intersection;
use super::*;
use std::path::PathBuf;

fn shared(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../shared/scenarios")
        .join(name)
}

const FILES: [&str; 7] = [
    "babel-I.geojson",
    "babel-II-N.geojson",
    "babel-II-S.geojson",
    "babel-III.geojson",
    "medeiros-jacksboro.geojson",
    "niendorf-urban.geojson",
    "ruz-popups.geojson",
];

#[test]
fn shared_scenarios_parse() {
    let mut strict_failures = Vec::new();
    for f in FILES {
        let path = shared(f);
        match load(&path) {
            Ok(s) => {
                assert!(s.warnings.is_empty());
                assert!(s.start.is_some() && s.goal.is_some(), "{f}");
            }
            Err(e) => strict_failures.push(e),
        }
        // With the hull repair every file loads.
        let s = load_with(
            &path,
            &ParseOptions {
                hull_self_intersecting_no_fly: true,
            },
        )
        .unwrap_or_else(|e| panic!("{e}"));
        assert!(s.start.is_some() && s.goal.is_some(), "{f}");
        for z in &s.no_fly {
            assert!(z.ring.len() >= 3 && first_self_intersection(&z.ring).is_none());
        }
    }
    // The shared data has one defect, which the strict loader reports: babel-I's Z2 is a
    // bow-tie (its edge 0 crosses its edge 2).
    let msgs: Vec<String> = strict_failures.iter().map(|e| e.to_string()).collect();
    assert_eq!(msgs.len(), 1, "{msgs:#?}");
    assert!(msgs[0].ends_with(
        "babel-I.geojson: feature 1 (Z2): geometry.coordinates: polygon ring is \
             self-intersecting: edges 0 and 2 meet (0-based; edge i joins vertices i and i+1)"
    ));
}

#[test]
fn shared_scenario_contents() {
    let repair = ParseOptions {
        hull_self_intersecting_no_fly: true,
    };
    let s = load_with(&shared("babel-I.geojson"), &repair).unwrap();
    assert_eq!(s.name, "babel-I");
    assert_eq!(s.planner.mode, Mode::Landmark);
    assert_eq!(s.planner.directions, Some(12));
    assert_eq!(s.planner.line_elements_per_pair, Some(500));
    assert_eq!(s.planner.sample_spacing_m, None);
    assert_eq!(s.weather, ["nominal", "degraded"]);
    assert_eq!((s.no_fly.len(), s.landmarks.len()), (3, 10));
    assert_eq!(s.landmarks[0].quality[1].0, "degraded");
    assert_eq!(s.landmarks[0].quality[1].1, [0.5; 12]);
    let start = s.start.as_ref().unwrap();
    assert_eq!(
        (start.name.as_str(), start.heading_deg, start.dist_m),
        ("P", Some(90.0), Some(7000.0))
    );
    assert_eq!(s.no_fly[0].ring.len(), 5);
    assert_eq!(s.warnings.len(), 1);
    assert_eq!(s.vehicle.turn_radius_m(), 45.0);

    let s = load(&shared("niendorf-urban.geojson")).unwrap();
    assert_eq!(s.planner.mode, Mode::Roadmap);
    assert_eq!((s.no_fly.len(), s.waypoints.len()), (60, 4));
    assert_eq!(
        s.waypoints
            .iter()
            .map(|w| w.name.as_str())
            .collect::<Vec<_>>(),
        ["W1", "W2", "W3", "W4"]
    );
    assert!(s.waypoints.iter().all(|w| w.heading_deg.is_none()));
    assert_eq!(s.planner.allow_ccc, Some(true));
    assert_eq!(s.planner.k_nearest_fallback, Some(8));
    assert!((s.vehicle.turn_radius_m() - 63.71).abs() < 0.01);

    let s = load(&shared("medeiros-jacksboro.geojson")).unwrap();
    assert_eq!(s.planner.mode, Mode::Terrain);
    let t = s.terrain.as_ref().unwrap();
    assert_eq!(t.dem, shared("jacksboro-dem.asc"));
    assert!(t.dem.is_file());
    assert_eq!((t.altitude_m, t.safety_height_m), (750.0, 100.0));
    assert_eq!(s.goal.as_ref().unwrap().heading_deg, None);

    let s = load(&shared("ruz-popups.geojson")).unwrap();
    assert_eq!((s.threats.len(), s.popups.len()), (12, 3));
    assert_eq!(
        s.popups.iter().map(|p| p.probability).collect::<Vec<_>>(),
        [0.5, 0.2, 0.8]
    );
    assert_eq!(s.planner.threat_weight, Some(0.5));

    let s = load(&shared("babel-III.geojson")).unwrap();
    assert_eq!((s.no_fly.len(), s.landmarks.len()), (18, 50));
    let frame = s.local_frame();
    let (lat0, lon0) = frame.origin();
    assert!((lat0 - 48.23).abs() < 0.01 && (lon0 - 12.28).abs() < 0.01);
}

// --- error classes: each message names the file, the feature and the field --------------

pub(super) const FILE: &str = "scenarios/x.geojson";

pub(super) fn doc(features: &str) -> String {
    doc_with(
        r#""vehicle": {"v_nominal_mps": 30, "v_min_mps": 25, "v_max_mps": 35,
                "a_lat_max_mps2": 20, "a_long_min_mps2": -3, "a_long_max_mps2": 3,
                "wingspan_m": 4},
               "planner": {"mode": "landmark", "directions": 12, "seed": 1},
               "weather": ["nominal", "degraded"]"#,
        features,
    )
}

pub(super) fn doc_with(top: &str, features: &str) -> String {
    format!(r#"{{"type": "FeatureCollection", "name": "x", {top}, "features": [{features}]}}"#)
}

const ZONE: &str = r#"{"type": "Feature", "properties": {"kind": "no_fly", "name": "Z1"},
        "geometry": {"type": "Polygon", "coordinates": [[[11.0, 48.0], [11.1, 48.0],
        [11.1, 48.1], [11.0, 48.1], [11.0, 48.0]]]}}"#;

pub(super) fn point(kind: &str, name: &str, lon: f64, lat: f64, extra: &str) -> String {
    format!(
        r#"{{"type": "Feature", "properties": {{"kind": "{kind}", "name": "{name}"{extra}}},
               "geometry": {{"type": "Point", "coordinates": [{lon}, {lat}]}}}}"#
    )
}

pub(super) fn polygon(name: &str, ring: &str) -> String {
    format!(
        r#"{{"type": "Feature", "properties": {{"kind": "no_fly", "name": "{name}"}},
               "geometry": {{"type": "Polygon", "coordinates": [{ring}]}}}}"#
    )
}

pub(super) fn start() -> String {
    point("start", "P", 10.0, 48.0, r#", "heading_deg": 90"#)
}

/// Parses `text`, expects an error, and checks its message holds every part.
pub(super) fn fails(text: &str, parts: &[&str]) -> ScenarioError {
    let e = parse(text, Path::new(FILE)).expect_err("should not parse");
    let m = e.to_string();
    assert!(m.starts_with(&format!("{FILE}: ")), "{m}");
    for p in parts {
        assert!(m.contains(p), "{m:?} lacks {p:?}");
    }
    e
}

#[test]
fn the_fixture_itself_parses() {
    let s = parse(&doc(&format!("{ZONE}, {}", start())), Path::new(FILE)).unwrap();
    assert_eq!(s.no_fly[0].ring.len(), 4);
    assert_eq!(s.start.unwrap().heading_deg, Some(90.0));
}

#[test]
fn invalid_json_names_line_and_column() {
    let e = fails(
        "{\n  \"type\": \"FeatureCollection\",\n  ]",
        &["line 3 column 3", "invalid JSON"],
    );
    assert!(matches!(
        e.kind,
        ErrorKind::Json {
            line: 3,
            column: 3,
            ..
        }
    ));
    // No duplicated position in the message.
    assert!(!e.to_string().contains(" at line "), "{e}");
}

#[test]
fn missing_member() {
    let f = r#"{"type": "Feature", "properties": {"kind": "threat", "name": "T1"},
                    "geometry": {"type": "Point", "coordinates": [10.5, 48.5]}}"#;
    fails(
        &doc(f),
        &["feature 0 (T1)", "properties.radius_m", "missing"],
    );
    let text = doc(&start()).replace(r#""wingspan_m": 4"#, r#""wingspan": 4"#);
    fails(&text, &["vehicle.wingspan"]);
    let text = doc_with(r#""planner": {"mode": "roadmap"}"#, &start());
    fails(&text, &[": vehicle: missing"]);
    let f = r#"{"type": "Feature", "properties": {"kind": "goal"},
                    "geometry": {"type": "Point", "coordinates": [10.5, 48.5]}}"#;
    fails(&doc(f), &["feature 0: properties.name: missing"]);
}

#[test]
fn ill_typed_member() {
    let f = point("threat", "T1", 10.5, 48.5, r#", "radius_m": "3 km""#);
    fails(
        &doc(&f),
        &[
            "feature 0 (T1)",
            "properties.radius_m",
            "expected a number",
            "\"3 km\"",
        ],
    );
    let f = r#"{"type": "Feature", "properties": {"kind": "goal", "name": "Q"},
                    "geometry": {"type": "Point", "coordinates": "here"}}"#;
    fails(
        &doc(f),
        &[
            "feature 0 (Q)",
            "geometry.coordinates",
            "expected a position",
        ],
    );
    let text = doc(&start()).replace(r#""seed": 1"#, r#""seed": 1.5"#);
    fails(&text, &["planner.seed", "integer"]);
}

#[test]
fn unknown_kind() {
    let f = point("tower", "T9", 10.5, 48.5, "");
    let e = fails(
        &doc(&format!("{}, {f}", start())),
        &[
            "feature 1 (T9)",
            "properties.kind",
            "unknown kind \"tower\"",
        ],
    );
    assert_eq!(e.kind, ErrorKind::UnknownKind("tower".into()));
}

#[test]
fn unknown_planner_mode() {
    let text = doc(&start()).replace(r#""mode": "landmark""#, r#""mode": "rrt""#);
    let e = fails(&text, &["planner.mode", "unknown planner mode \"rrt\""]);
    assert_eq!(e.kind, ErrorKind::UnknownMode("rrt".into()));
}

#[test]
fn polygon_not_closed() {
    let z = polygon(
        "B7",
        "[[11.0, 48.0], [11.1, 48.0], [11.1, 48.1], [11.0, 48.1]]",
    );
    let e = fails(
        &doc(&format!("{}, {z}", start())),
        &["feature 1 (B7)", "geometry.coordinates", "not closed"],
    );
    assert_eq!(e.kind, ErrorKind::RingNotClosed);
    assert_eq!(
        e.to_string(),
        "scenarios/x.geojson: feature 1 (B7): geometry.coordinates: polygon ring is not \
             closed (its last position must repeat its first)"
    );
}

#[test]
fn polygon_with_fewer_than_three_distinct_points() {
    let z = polygon(
        "B2",
        "[[11.0, 48.0], [11.1, 48.0], [11.1, 48.0], [11.0, 48.0], [11.0, 48.0]]",
    );
    let e = fails(
        &doc(&format!("{}, {z}", start())),
        &[
            "feature 1 (B2)",
            "geometry.coordinates",
            "2 distinct points",
        ],
    );
    assert_eq!(e.kind, ErrorKind::TooFewPoints(2));
}

#[test]
fn polygon_self_intersecting() {
    // A bow-tie: edges 0 and 2 cross.
    let z = polygon(
        "B3",
        "[[11.0, 48.0], [11.1, 48.1], [11.1, 48.0], [11.0, 48.1], [11.0, 48.0]]",
    );
    let e = fails(
        &doc(&format!("{}, {z}", start())),
        &[
            "feature 1 (B3)",
            "geometry.coordinates",
            "self-intersecting",
            "edges 0 and 2",
        ],
    );
    assert!(matches!(
        e.kind,
        ErrorKind::SelfIntersecting {
            edge_a: 0,
            edge_b: 2,
            overlap: false
        }
    ));
    // Touching at a vertex counts: the ring passes through (11.05, 48.05) twice.
    let z = polygon(
            "B4",
            "[[11.0, 48.0], [11.05, 48.05], [11.1, 48.0], [11.1, 48.1], [11.05, 48.05], [11.0, 48.1], [11.0, 48.0]]",
        );
    fails(
        &doc(&format!("{}, {z}", start())),
        &["feature 1 (B4)", "self-intersecting"],
    );
    // A spike folding back onto the previous edge.
    let z = polygon(
        "B5",
        "[[11.0, 48.0], [11.2, 48.0], [11.1, 48.0], [11.1, 48.1], [11.0, 48.0]]",
    );
    let e = fails(
        &doc(&format!("{}, {z}", start())),
        &["feature 1 (B5)", "fold back"],
    );
    assert!(matches!(
        e.kind,
        ErrorKind::SelfIntersecting {
            edge_a: 0,
            edge_b: 1,
            overlap: true
        }
    ));
    // Three collinear points enclose nothing.
    let z = polygon(
        "B6",
        "[[11.0, 48.0], [11.1, 48.0], [11.2, 48.0], [11.0, 48.0]]",
    );
    fails(
        &doc(&format!("{}, {z}", start())),
        &["feature 1 (B6)", "self-intersecting"],
    );
    // Decided exactly: a notch whose tip comes within 1e-300 degrees of the opposite edge is
    // simple; touching it, or crossing it by 1e-300, is not.
    for (tip, simple) in [("1e-300", true), ("0.0", false), ("-1e-300", false)] {
        let z = polygon(
            "B8",
            &format!("[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.5, {tip}], [0.0, 1.0], [0.0, 0.0]]"),
        );
        let r = parse(&doc(&format!("{}, {z}", start())), Path::new(FILE));
        assert_eq!(r.is_ok(), simple, "tip {tip}: {r:?}");
    }
    // The repair option turns the error into a warning and a convex hull.
    let z = polygon(
        "B3",
        "[[11.0, 48.0], [11.1, 48.1], [11.1, 48.0], [11.0, 48.1], [11.0, 48.0]]",
    );
    let s = parse_with(
        &doc(&format!("{}, {z}", start())),
        Path::new(FILE),
        &ParseOptions {
            hull_self_intersecting_no_fly: true,
        },
    )
    .unwrap();
    assert_eq!(
        s.no_fly[0].ring,
        [(11.0, 48.0), (11.1, 48.0), (11.1, 48.1), (11.0, 48.1)]
    );
    let w = s.warnings[0].to_string();
    assert!(
        w.contains("feature 1 (B3): geometry.coordinates: ") && w.contains("convex hull"),
        "{w}"
    );
}

#[test]
fn heading_not_a_number() {
    let f = point("start", "P", 10.0, 48.0, r#", "heading_deg": "north""#);
    let e = fails(
        &doc(&f),
        &[
            "feature 0 (P)",
            "properties.heading_deg",
            "expected a number",
            "\"north\"",
        ],
    );
    assert!(matches!(e.kind, ErrorKind::WrongType { .. }));
}

#[test]
fn heading_not_finite() {
    for token in ["NaN", "Infinity", "-Infinity", "1e999"] {
        let f = point(
            "goal",
            "Q",
            10.0,
            48.0,
            &format!(r#", "heading_deg": {token}"#),
        );
        let e = fails(
            &doc(&format!("{}, {f}", start())),
            &[
                "feature 1 (Q)",
                "properties.heading_deg",
                "not a finite number",
            ],
        );
        assert_eq!(e.kind, ErrorKind::NotFinite(token.into()));
    }
    // Such a token inside a string is left alone, and when the text has a real syntax error
    // as well, the first error is reported where it was found (here: at the NaN, the first
    // thing serde_json rejects).
    let f = point("goal", "NaN Infinity", 10.0, 48.0, "");
    parse(&doc(&f), Path::new(FILE)).unwrap();
    let text = doc(&point("goal", "Q", 10.0, 48.0, r#", "heading_deg": NaN"#)) + ",";
    let e = fails(&text, &["invalid JSON"]);
    let nan_at = text.find("NaN").unwrap();
    let line = text[..nan_at].matches('\n').count() + 1;
    let column = nan_at - text[..nan_at].rfind('\n').map_or(0, |i| i + 1) + 1;
    assert!(
        matches!(e.kind, ErrorKind::Json { line: l, column: c, .. } if (l, c) == (line, column)),
        "{e}"
    );
    let text = doc(&point("goal", "Q", 10.0, 48.0, r#", "heading_deg": 1"#)) + ",";
    fails(&text, &["invalid JSON", "trailing"]);
}

#[test]
fn quality_wrong_length() {
    let q = r#", "d_max_m": 7000, "quality": {"nominal": [1,1,1,1,1,1,1,1,1,1,1], "degraded": [0.5,0.5,0.5,0.5,0.5,0.5,0.5,0.5,0.5,0.5,0.5,0.5]}"#;
    let f = point("landmark", "L1", 10.5, 48.5, q);
    let e = fails(
        &doc(&f),
        &["feature 0 (L1)", "properties.quality.nominal", "found 11"],
    );
    assert_eq!(e.kind, ErrorKind::QualityLength(11));
    // The message states the rosette length that `ROSETTE_HEADINGS` defines.
    let message = e.kind.to_string();
    assert!(
        message.contains(&format!("has {ROSETTE_HEADINGS} values")),
        "{message}"
    );
}

#[test]
fn quality_out_of_range() {
    let q = r#", "d_max_m": 7000, "quality": {"nominal": [1,1,1,1,1,1,1,1,1,1,1,1], "degraded": [0.5,0.5,0.5,1.5,0.5,0.5,0.5,0.5,0.5,0.5,0.5,0.5]}"#;
    let f = point("landmark", "L2", 10.5, 48.5, q);
    let e = fails(
        &doc(&f),
        &[
            "feature 0 (L2)",
            "properties.quality.degraded[3]",
            "outside [0, 1]",
        ],
    );
    assert_eq!(e.kind, ErrorKind::QualityOutOfRange(1.5));
}

#[test]
fn quality_missing_weather() {
    let q = r#", "d_max_m": 7000, "quality": {"nominal": [1,1,1,1,1,1,1,1,1,1,1,1]}"#;
    let f = point("landmark", "L3", 10.5, 48.5, q);
    let e = fails(
        &doc(&f),
        &[
            "feature 0 (L3)",
            "properties.quality",
            "no rosette for weather \"degraded\"",
        ],
    );
    assert_eq!(e.kind, ErrorKind::MissingWeather("degraded".into()));
    // And one the top level does not list.
    let q = r#", "d_max_m": 7000, "quality": {"nominal": [1,1,1,1,1,1,1,1,1,1,1,1], "degraded": [1,1,1,1,1,1,1,1,1,1,1,1], "fog": [1,1,1,1,1,1,1,1,1,1,1,1]}"#;
    let f = point("landmark", "L4", 10.5, 48.5, q);
    fails(
        &doc(&f),
        &["feature 0 (L4)", "properties.quality.fog", "does not list"],
    );
}

#[test]
fn vehicle_limits_contradict() {
    let base = doc(&start());
    let cases = [
        (
            r#""v_min_mps": 25"#,
            r#""v_min_mps": 31"#,
            "vehicle.v_min_mps",
            "exceeds v_nominal_mps",
        ),
        (
            r#""v_max_mps": 35"#,
            r#""v_max_mps": 29"#,
            "vehicle.v_max_mps",
            "below v_nominal_mps",
        ),
        (
            r#""v_min_mps": 25"#,
            r#""v_min_mps": 0"#,
            "vehicle.v_min_mps",
            "not positive",
        ),
        (
            r#""a_lat_max_mps2": 20"#,
            r#""a_lat_max_mps2": 0"#,
            "vehicle.a_lat_max_mps2",
            "not positive",
        ),
        (
            r#""a_long_min_mps2": -3"#,
            r#""a_long_min_mps2": 1"#,
            "vehicle.a_long_min_mps2",
            "must be ≤ 0",
        ),
        (
            r#""a_long_max_mps2": 3"#,
            r#""a_long_max_mps2": -1"#,
            "vehicle.a_long_max_mps2",
            "must be ≥ 0",
        ),
        (
            r#""wingspan_m": 4"#,
            r#""wingspan_m": -4"#,
            "vehicle.wingspan_m",
            "not positive",
        ),
    ];
    for (from, to, field, words) in cases {
        assert!(base.contains(from));
        let e = fails(
            &base.replace(from, to),
            &[&format!("{FILE}: {field}: "), words],
        );
        assert!(matches!(e.kind, ErrorKind::VehicleLimits(_)));
        assert_eq!(e.feature, None);
    }
}

#[test]
fn coordinates_out_of_range() {
    let f = point("waypoint", "W1", 190.0, 48.0, "");
    let e = fails(
        &doc(&format!("{}, {f}", start())),
        &[
            "feature 1 (W1)",
            "geometry.coordinates[0]",
            "190",
            "longitude",
        ],
    );
    assert!(matches!(e.kind, ErrorKind::OutOfRange { .. }));
    let f = point("waypoint", "W2", 10.0, -91.0, "");
    fails(
        &doc(&format!("{}, {f}", start())),
        &["feature 1 (W2)", "geometry.coordinates[1]", "latitude"],
    );
    let z = polygon(
        "B1",
        "[[11.0, 48.0], [11.1, 48.0], [11.1, 98.1], [11.0, 48.0]]",
    );
    fails(
        &doc(&format!("{}, {z}", start())),
        &[
            "feature 1 (B1)",
            "geometry.coordinates[0][2][1]",
            "latitude",
        ],
    );
}

#[test]
fn endpoint_inside_no_fly() {
    let w = point("waypoint", "W3", 11.05, 48.05, "");
    let e = fails(
        &doc(&format!("{ZONE}, {}, {w}", start())),
        &[
            "feature 2 (W3)",
            "geometry.coordinates",
            "waypoint lies inside no-fly feature 0 (Z1)",
        ],
    );
    assert!(matches!(
        e.kind,
        ErrorKind::InsideNoFly {
            kind: "waypoint",
            ..
        }
    ));
    // On the edge counts as inside; the goal names both features too.
    let g = point("goal", "Q", 11.1, 48.05, "");
    fails(
        &doc(&format!("{ZONE}, {}, {g}", start())),
        &["feature 2 (Q)", "goal lies inside no-fly feature 0 (Z1)"],
    );
    let p = point("start", "P", 11.02, 48.09, r#", "heading_deg": 0"#);
    fails(
        &doc(&format!("{ZONE}, {p}")),
        &["feature 1 (P)", "start lies inside no-fly feature 0 (Z1)"],
    );
    // Just outside (1e-7 degrees, about 1 cm) is fine.
    let g = point("goal", "Q", 11.1000001, 48.05, "");
    parse(&doc(&format!("{ZONE}, {}, {g}", start())), Path::new(FILE)).unwrap();
}

#[test]
fn duplicate_start() {
    let p2 = point("start", "P2", 10.1, 48.0, r#", "heading_deg": 0"#);
    fails(
        &doc(&format!("{}, {p2}", start())),
        &[
            "feature 1 (P2)",
            "properties.kind",
            "a second start (the first is feature 0 (P))",
        ],
    );
}

#[test]
fn missing_start_and_goal_are_allowed() {
    let s = parse(&doc(ZONE), Path::new(FILE)).unwrap();
    assert!(s.start.is_none() && s.goal.is_none());
}

#[test]
fn terrain_mode_needs_terrain_and_resolves_the_dem() {
    let veh = r#""vehicle": {"v_nominal_mps": 30, "v_min_mps": 25, "v_max_mps": 35,
                "a_lat_max_mps2": 20, "a_long_min_mps2": -3, "a_long_max_mps2": 3,
                "wingspan_m": 4}"#;
    let text = doc_with(
        &format!(r#"{veh}, "planner": {{"mode": "terrain"}}"#),
        &start(),
    );
    fails(&text, &["terrain: missing"]);
    let text = doc_with(
        &format!(
            r#"{veh}, "planner": {{"mode": "terrain"}},
                   "terrain": {{"dem": "d.asc", "altitude_m": 750, "safety_height_m": 100}}"#
        ),
        &start(),
    );
    let s = parse(&text, Path::new(FILE)).unwrap();
    assert_eq!(s.terrain.unwrap().dem, Path::new("scenarios/d.asc"));
}
