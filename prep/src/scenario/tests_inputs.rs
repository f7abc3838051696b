//! Unit tests of the parser against bad inputs:
//! a start without a heading, unknown property keys, duplicate keys, a byte-order mark, huge
//! numbers in messages, non-finite vehicle and planner numbers.

use super::*;

const FILE: &str = "scenarios/x.geojson";

const VEHICLE: &str = r#""vehicle": {"v_nominal_mps": 30, "v_min_mps": 25, "v_max_mps": 35,
        "a_lat_max_mps2": 20, "a_long_min_mps2": -3, "a_long_max_mps2": 3, "wingspan_m": 4}"#;

fn doc(mode: &str, features: &str) -> String {
    format!(
        r#"{{"type": "FeatureCollection", "name": "x", {VEHICLE},
            "planner": {{"mode": "{mode}"}}, "features": [{features}]}}"#
    )
}

fn point(kind: &str, name: &str, extra: &str) -> String {
    format!(
        r#"{{"type": "Feature", "properties": {{"kind": "{kind}", "name": "{name}"{extra}}},
               "geometry": {{"type": "Point", "coordinates": [10.0, 48.0]}}}}"#
    )
}

/// Parses `text`, expects an error, and returns its message.
fn message(text: &str) -> String {
    parse(text, Path::new(FILE))
        .expect_err("should not parse")
        .to_string()
}

#[test]
fn start_without_heading_is_refused() {
    // Before: parsed, and the mission flew the start northwards (`unwrap_or(0.0)`).
    let goal = point("goal", "G", "");
    for mode in ["roadmap", "landmark"] {
        let m = message(&doc(mode, &format!("{goal}, {}", point("start", "S", ""))));
        assert_eq!(
            m,
            format!(
                "{FILE}: feature 1 (S): properties.heading_deg: missing: the start needs a \
                 heading"
            )
        );
    }
    // A heading given as null counts as absent, and is refused the same way.
    let m = message(&doc(
        "roadmap",
        &point("start", "S", r#", "heading_deg": null"#),
    ));
    assert!(m.ends_with("properties.heading_deg: missing: the start needs a heading"));
    // The goal and waypoints may leave their heading free.
    let s = parse(
        &doc(
            "roadmap",
            &format!(
                "{}, {}, {goal}",
                point("start", "S", r#", "heading_deg": 90"#),
                point("waypoint", "W", "")
            ),
        ),
        Path::new(FILE),
    )
    .unwrap();
    assert_eq!(s.start.unwrap().heading_deg, Some(90.0));
    assert_eq!(s.goal.unwrap().heading_deg, None);
}

#[test]
fn unknown_property_keys_are_refused_per_kind() {
    // Before: `heigth` and the misspelt `heading` were ignored (and the start flew north).
    let m = message(&doc(
        "roadmap",
        &point("threat", "B3", r#", "radius_m": 100, "heigth": 30"#),
    ));
    assert_eq!(
        m,
        format!(
            "{FILE}: feature 0 (B3): properties.heigth: unknown key; expected one of kind, name, \
             radius_m"
        )
    );
    let m = message(&doc("roadmap", &point("start", "S", r#", "heading": 90"#)));
    assert!(
        m.ends_with(
            "feature 0 (S): properties.heading: unknown key; expected one of kind, name, \
             heading_deg, dist_m"
        ),
        "{m}"
    );
    // `dist_m` is the start's only (the landmark mode's first leg).
    let m = message(&doc("roadmap", &point("goal", "G", r#", "dist_m": 5"#)));
    assert!(
        m.ends_with("properties.dist_m: unknown key; expected one of kind, name, heading_deg"),
        "{m}"
    );
    let m = message(&doc(
        "roadmap",
        &point(
            "popup",
            "U",
            r#", "radius_m": 9, "probability": 0.5, "p": 1"#,
        ),
    ));
    assert!(
        m.ends_with("expected one of kind, name, radius_m, probability"),
        "{m}"
    );
}

#[test]
fn duplicate_keys_are_refused_by_name() {
    // Before: serde_json kept the last value (the start flew 180°).
    let start = point("start", "S", r#", "heading_deg": 90, "heading_deg": 180"#);
    let text = doc("roadmap", &start);
    let m = message(&text);
    assert!(
        m.contains("invalid JSON: duplicate key \"heading_deg\" in features[0].properties"),
        "{m}"
    );
    // Top level, and in a nested member.
    let ok_start = point("start", "S", r#", "heading_deg": 90"#);
    let text =
        doc("roadmap", &ok_start).replacen(r#""name": "x","#, r#""name": "x", "name": "y","#, 1);
    assert!(message(&text).contains("duplicate key \"name\" in the top level"));
    let text = doc("roadmap", &ok_start).replacen(
        r#""wingspan_m": 4"#,
        r#""wingspan_m": 4, "wingspan_m": 5"#,
        1,
    );
    assert!(message(&text).contains("duplicate key \"wingspan_m\" in vehicle"));
    // The same key in two different objects is fine.
    let goal = point("goal", "G", r#", "heading_deg": 90"#);
    parse(
        &doc("roadmap", &format!("{ok_start}, {goal}")),
        Path::new(FILE),
    )
    .unwrap();
    // Also when a non-finite token had to be marked first: the duplicate is still found.
    let start = point("start", "S", r#", "heading_deg": NaN, "heading_deg": 1"#);
    let m = message(&doc("roadmap", &start));
    assert!(m.contains("duplicate key \"heading_deg\""), "{m}");
}

#[test]
fn a_byte_order_mark_is_accepted() {
    // Before: `line 1 column 1: invalid JSON: expected value`.
    let text = doc("roadmap", &point("start", "S", r#", "heading_deg": 90"#));
    let s = parse(&format!("\u{feff}{text}"), Path::new(FILE)).unwrap();
    assert_eq!(s.start.unwrap().name, "S");
    // Only one, at the start: a second one is not JSON.
    let m = message(&format!("\u{feff}\u{feff}{text}"));
    assert!(m.contains("invalid JSON"), "{m}");
}

#[test]
fn huge_numbers_are_printed_compactly() {
    // Before: the longitude was printed with 309 digits.
    let f = point("start", "S", r#", "heading_deg": 90"#).replace("[10.0, 48.0]", "[1e308, 48.0]");
    let m = message(&doc("roadmap", &f));
    assert!(
        m.ends_with(
            "feature 0 (S): geometry.coordinates[0]: 1e308 is out of range: expected a \
             longitude in [-180, 180]"
        ),
        "{m}"
    );
    let text = doc("roadmap", &point("start", "S", r#", "heading_deg": 90"#));
    let m = message(&text.replace(r#""v_max_mps": 35"#, r#""v_max_mps": -2.5e300"#));
    assert!(
        m.ends_with("vehicle.v_max_mps: -2.5e300 is below v_nominal_mps 30 (need v_min ≤ v_nominal ≤ v_max)"),
        "{m}"
    );
    // Ordinary numbers keep their plain form.
    let m = message(&text.replace(r#""v_max_mps": 35"#, r#""v_max_mps": 29.5"#));
    assert!(m.contains("29.5 is below v_nominal_mps 30"), "{m}");
}

#[test]
fn non_finite_vehicle_and_planner_numbers_are_named() {
    let text = doc("roadmap", &point("start", "S", r#", "heading_deg": 90"#));
    let m = message(&text.replace(r#""v_max_mps": 35"#, r#""v_max_mps": NaN"#));
    assert!(
        m.ends_with("vehicle.v_max_mps: NaN is not a finite number"),
        "{m}"
    );
    let m = message(&text.replace(
        r#""mode": "roadmap""#,
        r#""mode": "roadmap", "sample_spacing_m": Infinity"#,
    ));
    assert!(
        m.ends_with("planner.sample_spacing_m: Infinity is not a finite number"),
        "{m}"
    );
    let m = message(&text.replace(
        r#""mode": "roadmap""#,
        r#""mode": "roadmap", "clearance_m": -1e999"#,
    ));
    assert!(
        m.ends_with("planner.clearance_m: -1e999 is not a finite number"),
        "{m}"
    );
}

#[test]
fn more_waypoints_than_the_limit_are_refused_at_the_first_extra_one() {
    let start = point("start", "S", r#", "heading_deg": 90"#);
    let waypoints = |n: usize| -> String {
        (0..n)
            .map(|i| point("waypoint", &format!("W{i}"), ""))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let at_limit = doc(
        "roadmap",
        &format!("{start}, {}", waypoints(limits::MAX_WAYPOINTS)),
    );
    let s = parse(&at_limit, Path::new(FILE)).expect("the limit itself is accepted");
    assert_eq!(s.waypoints.len(), limits::MAX_WAYPOINTS);
    let over = doc(
        "roadmap",
        &format!("{start}, {}", waypoints(limits::MAX_WAYPOINTS + 1)),
    );
    assert_eq!(
        message(&over),
        format!(
            "{FILE}: feature 501 (W500): properties.kind: more than 500 waypoints, the scenario \
             format's limit"
        )
    );
}

#[test]
fn a_ring_longer_than_the_limit_is_refused_before_it_is_checked() {
    let n = limits::MAX_RING_VERTICES + 1;
    let ring: Vec<String> = (0..=n)
        .map(|i| {
            let t = std::f64::consts::TAU * (i % n) as f64 / n as f64;
            format!("[{}, {}]", 10.0 + 0.1 * t.cos(), 48.0 + 0.1 * t.sin())
        })
        .collect();
    let zone = format!(
        r#"{{"type": "Feature", "properties": {{"kind": "no_fly", "name": "Z"}},
            "geometry": {{"type": "Polygon", "coordinates": [[{}]]}}}}"#,
        ring.join(", ")
    );
    let m = message(&doc("roadmap", &zone));
    assert_eq!(
        m,
        format!(
            "{FILE}: feature 0 (Z): geometry.coordinates: more than 100000 ring vertices, the \
             scenario format's limit"
        )
    );
}

#[cfg(unix)]
#[test]
fn an_endless_file_is_refused_after_the_byte_limit() {
    let e = load(Path::new("/dev/zero")).expect_err("refused");
    assert_eq!(
        e.to_string(),
        "/dev/zero: more than 16777216 bytes, the scenario format's limit"
    );
}

#[test]
fn a_file_that_is_not_utf8_names_the_first_bad_byte() {
    let path = std::env::temp_dir().join(format!("skyroute-latin1-{}.geojson", std::process::id()));
    std::fs::write(&path, b"{\"name\": \"M\xfcnchen\"}").unwrap();
    let e = load(&path).expect_err("refused");
    std::fs::remove_file(&path).ok();
    assert!(
        e.to_string()
            .ends_with("cannot read: not UTF-8 text (byte 11)"),
        "{e}"
    );
}

#[test]
fn a_multipolygon_no_fly_zone_becomes_one_zone_per_member() {
    let square = |x: f64| {
        format!(
            "[[[{x}, 48.0], [{}, 48.0], [{}, 48.1], [{x}, 48.1], [{x}, 48.0]]]",
            x + 0.1,
            x + 0.1
        )
    };
    let zone = format!(
        r#"{{"type": "Feature", "properties": {{"kind": "no_fly", "name": "Z"}},
            "geometry": {{"type": "MultiPolygon", "coordinates": [{}, {}]}}}}"#,
        square(10.0),
        square(10.5)
    );
    let s = parse(&doc("roadmap", &zone), Path::new(FILE)).expect("parses");
    let names: Vec<&str> = s.no_fly.iter().map(|z| z.name.as_str()).collect();
    assert_eq!(names, ["Z[0]", "Z[1]"]);
    assert_eq!(s.no_fly[1].ring[0], (10.5, 48.0));
    // A member whose hole crosses its exterior is refused at its own index.
    let holed = format!(
        r#"{{"type": "Feature", "properties": {{"kind": "no_fly", "name": "H"}},
            "geometry": {{"type": "MultiPolygon", "coordinates": [{}, [{}, {}]]}}}}"#,
        square(10.0),
        &square(10.5)[1..square(10.5).len() - 1],
        &square(10.52)[1..square(10.52).len() - 1]
    );
    let m = message(&doc("roadmap", &holed));
    assert!(
        m.contains("feature 0 (H): geometry.coordinates[1][1]: this hole is not strictly inside"),
        "{m}"
    );
    // A start inside the second member is refused naming the feature.
    let start =
        point("start", "S", r#", "heading_deg": 90"#).replace("[10.0, 48.0]", "[10.55, 48.05]");
    let m = message(&doc("roadmap", &format!("{zone}, {start}")));
    assert!(m.contains("inside no-fly feature 0 (Z)"), "{m}");
    // Other geometries are refused by name.
    let line = zone.replace("MultiPolygon", "LineString");
    let m = message(&doc("roadmap", &line));
    assert!(m.contains("geometry.type"), "{m}");
    assert!(m.contains("Polygon or MultiPolygon"), "{m}");
}
