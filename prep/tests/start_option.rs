//! `skyroute plan --start LON,LAT,HEADING_DEG`: re-planning from where the aircraft is. The
//! first leg starts at the given pose (checked against a closed form: a straight leg to a
//! free-heading waypoint), the new start is checked like the scenario's (inside a building:
//! the leg leaves it by an exit, named), and a landmark network, whose start is built in,
//! refuses the option.

mod common;

use common::{code, niendorf, ok, one_line_error, scenario, skyroute, stdout, TempDir};
use skyroute::geometry::Vec2;

/// W1 of niendorf-urban, a waypoint without heading.
const W1: (f64, f64) = (11.64785599, 48.09486928);

#[test]
fn a_start_300_m_north_of_a_free_heading_waypoint_flies_300_m_straight_to_it() {
    let dir = TempDir::new("start-option");
    let net = dir.file("niendorf.bin");
    ok(skyroute(&["build", &niendorf(), "-o", &net]), "build");
    let bytes = std::fs::read(&net).unwrap();
    let frame = skyroute::Network::from_bytes(&bytes).unwrap().local_frame();
    // 300 m up the frame's y axis from W1, heading back down it: the shortest path to a
    // waypoint that takes any heading is the 300 m straight.
    let w1 = frame.position(W1.0, W1.1).unwrap();
    let start = Vec2::new(w1.x, w1.y + 300.0);
    let (lon, lat) = frame.lon_lat(start).unwrap();
    let heading = frame
        .compass_deg(&skyroute::geometry::Pose::new(
            start.x,
            start.y,
            -core::f32::consts::FRAC_PI_2,
        ))
        .unwrap();
    let arg = format!("{lon},{lat},{heading}");
    let route = dir.file("route.json");
    let o = ok(
        skyroute(&[
            "plan",
            &net,
            "--scenario",
            &niendorf(),
            "--start",
            &arg,
            "-o",
            &route,
        ]),
        "plan --start",
    );
    let out = stdout(&o);
    let first = out
        .lines()
        .find(|l| l.trim_start().starts_with("P -> W1:"))
        .unwrap();
    let metres: f64 = first
        .split(':')
        .nth(1)
        .unwrap()
        .trim()
        .split(' ')
        .next()
        .unwrap()
        .parse()
        .unwrap();
    assert!((metres - 300.0).abs() < 0.2, "{first}");

    // A start inside a building is checked like the scenario's: on a roadmap the leg first
    // leaves the building by the shortest exit, and the note names it.
    let inside = "11.6212378,48.0844964,90"; // the centroid of building B1
    let o = ok(
        skyroute(&[
            "plan",
            &net,
            "--scenario",
            &niendorf(),
            "--start",
            inside,
            "-o",
            &dir.file("r2.json"),
        ]),
        "plan --start inside B1",
    );
    let note = stdout(&o);
    assert!(
        note.contains("no-fly zone \"B1\"") && note.contains("exit"),
        "{note}"
    );
}

#[test]
fn a_landmark_network_refuses_a_start_and_a_bad_start_is_a_usage_error() {
    let dir = TempDir::new("start-option-landmark");
    let net = dir.file("babel.bin");
    let sc = scenario("babel-II-N.geojson");
    ok(skyroute(&["build", &sc, "-o", &net]), "build");
    let out = dir.file("route.json");
    let o = skyroute(&[
        "plan",
        &net,
        "--scenario",
        &sc,
        "--start",
        "11.6,48.0,10",
        "-o",
        &out,
    ]);
    assert_eq!(code(&o), 1);
    assert!(
        one_line_error(&o).contains("is a landmark network"),
        "{}",
        one_line_error(&o)
    );
    assert!(!std::path::Path::new(&out).exists());
    let o = skyroute(&[
        "plan",
        &net,
        "--scenario",
        &sc,
        "--start",
        "11.6,48.0,nan",
        "-o",
        &out,
    ]);
    assert_eq!(code(&o), 2);
}
