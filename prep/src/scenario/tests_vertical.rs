//! The three-dimensional roadmap's keys: what a three-dimensional scenario accepts and
//! requires, and each refusal, naming the file, the feature and the field; in a planar
//! scenario every one of the keys is refused as planar.

use super::error::ErrorKind;
use super::parse;
use super::tests::{doc_with, fails, FILE};
use super::{Scenario, DEFAULT_CLIMB_RATE_MPS, DEFAULT_VERTICAL_ACCEL_MPS2};
use std::path::Path;

const VEHICLE: &str = r#""v_nominal_mps": 25, "v_min_mps": 20, "v_max_mps": 55,
    "a_lat_max_mps2": 9.81, "a_long_min_mps2": -3, "a_long_max_mps2": 3, "wingspan_m": 3.2"#;

/// A scenario with the given extra `vehicle` and `planner` members (each starting with `, `),
/// in `mode`, and the given features.
fn text(mode: &str, vehicle: &str, planner: &str, features: &str) -> String {
    doc_with(
        &format!(
            r#""vehicle": {{{VEHICLE}{vehicle}}},
               "planner": {{"mode": "{mode}", "sample_spacing_m": 50{planner}}}"#
        ),
        features,
    )
}

/// The band of a three-dimensional roadmap, as `planner` members.
const BAND: &str = r#", "altitude_min_m": 40, "altitude_max_m": 120"#;

/// A building "B1" with the given extra properties.
fn building(extra: &str) -> String {
    format!(
        r#"{{"type": "Feature", "properties": {{"kind": "no_fly", "name": "B1"{extra}}},
             "geometry": {{"type": "Polygon", "coordinates": [[[11.0, 48.0], [11.001, 48.0],
             [11.001, 48.001], [11.0, 48.001], [11.0, 48.0]]]}}}}"#
    )
}

/// An endpoint of `kind` named `name` with the given extra properties.
fn endpoint(kind: &str, name: &str, extra: &str) -> String {
    format!(
        r#"{{"type": "Feature", "properties": {{"kind": "{kind}", "name": "{name}"{extra}}},
             "geometry": {{"type": "Point", "coordinates": [11.01, 48.01]}}}}"#
    )
}

/// A start "P" heading east at `extra`.
fn start(extra: &str) -> String {
    endpoint("start", "P", &format!(r#", "heading_deg": 90{extra}"#))
}

fn parsed(text: &str) -> Scenario {
    parse(text, Path::new(FILE)).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn a_three_dimensional_scenario_parses_with_defaults() {
    let features = format!(
        "{}, {}, {}, {}, {}",
        building(r#", "height_m": 25.5"#),
        endpoint("no_fly", "B2", "").replace(
            r#""type": "Point", "coordinates": [11.01, 48.01]"#,
            r#""type": "Polygon", "coordinates": [[[11.02, 48.02], [11.03, 48.02],
               [11.03, 48.03], [11.02, 48.02]]]"#
        ),
        start(r#", "altitude_m": 60"#),
        endpoint("waypoint", "W1", r#", "altitude_m": -10.5"#),
        endpoint("goal", "Q", r#", "altitude_m": 1e5"#),
    );
    let s = parsed(&text("roadmap", "", BAND, &features));
    let v = s.vertical().unwrap();
    assert_eq!((v.altitude_min_m, v.altitude_max_m), (40.0, 120.0));
    assert_eq!(v.climb_rate_mps, DEFAULT_CLIMB_RATE_MPS);
    assert_eq!(v.vertical_accel_mps2, DEFAULT_VERTICAL_ACCEL_MPS2);
    assert_eq!(s.no_fly[0].height_m, Some(25.5));
    assert_eq!(s.no_fly[1].height_m, None, "absent: unbounded");
    assert_eq!(s.start.unwrap().altitude_m, Some(60.0));
    assert_eq!(s.waypoints[0].altitude_m, Some(-10.5));
    assert_eq!(s.goal.unwrap().altitude_m, Some(1e5));
    // Given limits, and a band of one altitude.
    let vehicle = r#", "climb_rate_mps": 5, "vertical_accel_mps2": 8"#;
    let planner = r#", "altitude_min_m": 80, "altitude_max_m": 80"#;
    let s = parsed(&text(
        "roadmap",
        vehicle,
        planner,
        &start(r#", "altitude_m": 80"#),
    ));
    let v = s.vertical().unwrap();
    assert_eq!((v.climb_rate_mps, v.vertical_accel_mps2), (5.0, 8.0));
    assert_eq!((v.altitude_min_m, v.altitude_max_m), (80.0, 80.0));
    // Planar: no vertical, no heights or altitudes.
    let s = parsed(&text(
        "roadmap",
        "",
        "",
        &format!("{}, {}", building(""), start("")),
    ));
    assert!(s.vertical().is_none());
    assert_eq!(
        (s.no_fly[0].height_m, s.start.unwrap().altitude_m),
        (None, None)
    );
}

#[test]
fn every_vertical_key_is_refused_in_a_planar_scenario() {
    let planar = "the scenario is planar: this key is read only in a three-dimensional roadmap \
                  scenario, one with planner.altitude_min_m and planner.altitude_max_m";
    let e = fails(
        &text("roadmap", "", "", &building(r#", "height_m": 30"#)),
        &["feature 0 (B1): properties.height_m: ", planar],
    );
    assert_eq!(e.kind, ErrorKind::Planar);
    for kind in ["start", "goal", "waypoint"] {
        let f = endpoint(kind, "E", r#", "heading_deg": 90, "altitude_m": 60"#);
        fails(
            &text("roadmap", "", "", &f),
            &["feature 0 (E): properties.altitude_m: ", planar],
        );
    }
    // Even null is refused: it is written there.
    fails(
        &text("roadmap", "", "", &start(r#", "altitude_m": null"#)),
        &["feature 0 (P): properties.altitude_m: the scenario is planar"],
    );
    for key in ["climb_rate_mps", "vertical_accel_mps2"] {
        // Refused as planar before its value is looked at.
        let vehicle = format!(r#", "{key}": -1"#);
        let e = fails(
            &text("roadmap", &vehicle, "", &start("")),
            &[&format!("{FILE}: vehicle.{key}: {planar}")],
        );
        assert_eq!(e.feature, None);
    }
    // The other modes are planar too.
    fails(
        &text("landmark", "", "", &start(r#", "altitude_m": 60"#)),
        &["properties.altitude_m: the scenario is planar"],
    );
    // A planar scenario's unknown-key message lists the keys a planar scenario takes.
    fails(
        &text("roadmap", "", "", &start(r#", "altitude": 60"#)),
        &["properties.altitude: unknown key; expected one of kind, name, heading_deg, dist_m"],
    );
    let m = fails(
        &text(
            "roadmap",
            "",
            BAND,
            &start(r#", "altitude_m": 1, "altitude": 60"#),
        ),
        &["properties.altitude: unknown key"],
    )
    .to_string();
    assert!(
        m.ends_with("expected one of kind, name, heading_deg, dist_m, altitude_m"),
        "{m}"
    );
}

#[test]
fn the_altitude_band_needs_both_bounds_in_order_in_a_roadmap() {
    let s = start(r#", "altitude_m": 60"#);
    fails(
        &text("roadmap", "", r#", "altitude_min_m": 40"#, &s),
        &[
            &format!("{FILE}: planner.altitude_max_m: missing: planner.altitude_min_m is given"),
            "needs both bounds",
        ],
    );
    fails(
        &text("roadmap", "", r#", "altitude_max_m": 40"#, &s),
        &["planner.altitude_min_m: missing: planner.altitude_max_m is given"],
    );
    fails(
        &text(
            "roadmap",
            "",
            r#", "altitude_min_m": 120, "altitude_max_m": 40"#,
            &s,
        ),
        &["planner.altitude_min_m: 120 is above planner.altitude_max_m 40"],
    );
    fails(
        &text(
            "roadmap",
            "",
            r#", "altitude_min_m": -1e6, "altitude_max_m": 40"#,
            &s,
        ),
        &["planner.altitude_min_m: -1000000 is out of range: expected an altitude within ±100000 m"],
    );
    fails(
        &text(
            "roadmap",
            "",
            r#", "altitude_min_m": 0, "altitude_max_m": 100001"#,
            &s,
        ),
        &["planner.altitude_max_m: 100001 is out of range"],
    );
    fails(
        &text(
            "roadmap",
            "",
            r#", "altitude_min_m": NaN, "altitude_max_m": 40"#,
            &s,
        ),
        &["planner.altitude_min_m: NaN is not a finite number"],
    );
    fails(
        &text(
            "roadmap",
            "",
            r#", "altitude_min_m": "low", "altitude_max_m": 40"#,
            &s,
        ),
        &["planner.altitude_min_m: expected a number"],
    );
    fails(
        &text("voronoi", "", BAND, &s),
        &["planner.altitude_min_m: only a roadmap can be three-dimensional, and planner.mode is \"voronoi\""],
    );
    fails(
        &text("roadmap", "", r#", "altitude_minimum_m": 40"#, &s),
        &["planner.altitude_minimum_m: unknown member"],
    );
}

#[test]
fn the_vertical_limits_are_positive_numbers() {
    let s = start(r#", "altitude_m": 60"#);
    for key in ["climb_rate_mps", "vertical_accel_mps2"] {
        for (value, says) in [
            ("0", "0 is out of range: expected a positive number"),
            ("-2", "-2 is out of range: expected a positive number"),
            ("Infinity", "Infinity is not a finite number"),
            ("\"fast\"", "expected a number, found the string \"fast\""),
        ] {
            let vehicle = format!(r#", "{key}": {value}"#);
            fails(
                &text("roadmap", &vehicle, BAND, &s),
                &[&format!("{FILE}: vehicle.{key}: {says}")],
            );
        }
    }
}

#[test]
fn heights_and_altitudes_are_checked_by_feature() {
    let p = start(r#", "altitude_m": 60"#);
    for (value, says) in [
        ("0", "0 is out of range: expected a positive number"),
        ("-5", "-5 is out of range: expected a positive number"),
        ("1e999", "1e999 is not a finite number"),
        ("\"tall\"", "expected a number"),
    ] {
        let b = building(&format!(r#", "height_m": {value}"#));
        fails(
            &text("roadmap", "", BAND, &format!("{p}, {b}")),
            &[&format!(
                "{FILE}: feature 1 (B1): properties.height_m: {says}"
            )],
        );
    }
    // Every start, goal and waypoint needs its altitude.
    for (i, kind) in ["goal", "waypoint"].iter().enumerate() {
        let f = format!("{p}, {}", endpoint(kind, "E", ""));
        let e = fails(
            &text("roadmap", "", BAND, &f),
            &[
                "feature 1 (E): properties.altitude_m: missing: a three-dimensional scenario needs \
                 the altitude of every start, goal and waypoint",
            ],
        );
        assert_eq!(e.feature.as_ref().unwrap().index, 1, "{i}");
    }
    fails(
        &text("roadmap", "", BAND, &start("")),
        &["feature 0 (P): properties.altitude_m: missing"],
    );
    fails(
        &text("roadmap", "", BAND, &start(r#", "altitude_m": null"#)),
        &["feature 0 (P): properties.altitude_m: missing"],
    );
    for (value, says) in [
        (
            "100000.5",
            "100000.5 is out of range: expected an altitude within ±100000 m",
        ),
        ("-1e7", "-10000000 is out of range"),
        ("NaN", "NaN is not a finite number"),
        ("[60]", "expected a number"),
    ] {
        let w = endpoint("waypoint", "W2", &format!(r#", "altitude_m": {value}"#));
        fails(
            &text("roadmap", "", BAND, &format!("{p}, {w}")),
            &[&format!("feature 1 (W2): properties.altitude_m: {says}")],
        );
    }
}

/// A pop-up "U1" of 60 m with the given extra properties.
fn popup(extra: &str) -> String {
    endpoint(
        "popup",
        "U1",
        &format!(r#", "radius_m": 60, "probability": 0.5{extra}"#),
    )
}

#[test]
fn a_popup_height_is_read_in_three_dimensions_only() {
    let p = start(r#", "altitude_m": 60"#);
    let s = parsed(&text(
        "roadmap",
        "",
        BAND,
        &format!("{p}, {}", popup(r#", "height_m": 30"#)),
    ));
    assert_eq!(s.popups[0].height_m, Some(30.0));
    let s = parsed(&text("roadmap", "", BAND, &format!("{p}, {}", popup(""))));
    assert_eq!(s.popups[0].height_m, None, "absent: unbounded");
    fails(
        &text(
            "roadmap",
            "",
            BAND,
            &format!("{p}, {}", popup(r#", "height_m": 0"#)),
        ),
        &["feature 1 (U1): properties.height_m: 0 is out of range: expected a positive number"],
    );
    let e = fails(
        &text("roadmap", "", "", &popup(r#", "height_m": 30"#)),
        &["feature 0 (U1): properties.height_m: the scenario is planar"],
    );
    assert_eq!(e.kind, ErrorKind::Planar);
}
