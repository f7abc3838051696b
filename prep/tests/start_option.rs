//! `skyroute plan --start LON,LAT,HEADING_DEG`: re-planning from where the aircraft is. The
//! first leg starts at the given pose (checked against a closed form: a straight leg to a
//! free-heading waypoint), the new start is checked like the scenario's (inside a building:
//! the leg leaves it by an exit, named); on a landmark network the start is joined online
//! with the range left (`--flown-m`, `--last-overflight`), and `--goal` likewise.

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

/// A pose on babel-I-detour's stored route, about 3.6 km east of its start (lon, lat, compass
/// heading).
const ON_THE_ROUTE: &str = "11.6528,48.1071,100";

/// babel-I-detour's network, built in `dir`.
fn babel_i_detour(dir: &TempDir) -> String {
    let net = dir.file("babel.bin");
    let sc = scenario("babel-I-detour.geojson");
    ok(skyroute(&["build", &sc, "-o", &net]), "build");
    net
}

/// `skyroute plan NET --scenario babel-I-detour -o OUT EXTRA...`.
fn plan_babel_i_detour(net: &str, out: &str, extra: &[&str]) -> std::process::Output {
    let sc = scenario("babel-I-detour.geojson");
    let mut args = vec!["plan", net, "--scenario", sc.as_str(), "-o", out];
    args.extend_from_slice(extra);
    skyroute(&args)
}

#[test]
fn a_landmark_start_is_joined_online_with_the_range_left() {
    let dir = TempDir::new("start-option-landmark");
    let (net, out) = (babel_i_detour(&dir), dir.file("route.json"));
    let plan = |extra: &[&str]| plan_babel_i_detour(&net, &out, extra);
    ok(
        plan(&["--start", ON_THE_ROUTE, "--flown-m", "1500"]),
        "plan --start",
    );
    let route: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
    // The scenario start's dist_m is 7000 m: 5500 m are left.
    let online = &route["online_start"];
    assert_eq!(online["range_left_m"].as_f64(), Some(5500.0), "{online}");
    let first = &route["pieces"][0];
    assert!(first["edge"].is_null(), "{first}");
    assert!(first["length"].as_f64().unwrap() <= 5500.0);
    let bytes = std::fs::read(&net).unwrap();
    let frame = skyroute::Network::from_bytes(&bytes).unwrap().local_frame();
    let at = frame.position(11.6528, 48.1071).unwrap();
    let from = &first["from"]["position"];
    let gap =
        (from[0].as_f64().unwrap() - at.x as f64).hypot(from[1].as_f64().unwrap() - at.y as f64);
    assert!(gap < 0.01, "the first piece starts {gap} m from --start");
    assert_eq!(route["legs"][0]["from"], "start");
    assert_eq!(route["legs"][1]["from"], route["legs"][0]["to"]);
    std::fs::remove_file(&out).unwrap();

    // Flown beyond the range the start fix allows: no route can exist (exit 3).
    let o = plan(&["--start", ON_THE_ROUTE, "--flown-m", "9000"]);
    assert_eq!(code(&o), 3);
    assert!(
        one_line_error(&o).contains("9000 m flown"),
        "{}",
        one_line_error(&o)
    );
    // A start inside no-fly zone Z1: no piece leaves it (exit 3).
    let o = plan(&["--start", "11.72,48.137,90"]);
    assert_eq!(code(&o), 3);
    assert!(
        one_line_error(&o).contains("--start: no overflight"),
        "{}",
        one_line_error(&o)
    );
    // Bad input (exit 1): an unknown landmark, --flown-m without --start.
    let o = plan(&["--start", ON_THE_ROUTE, "--last-overflight", "Nope,90"]);
    assert_eq!(code(&o), 1);
    assert!(one_line_error(&o).contains("\"Nope\" is not a landmark"));
    let o = plan(&["--flown-m", "10"]);
    assert_eq!(code(&o), 1);
    assert!(one_line_error(&o).contains("needs --start"));
    // Malformed values are usage errors (exit 2).
    for bad in [
        &["--start", "11.6,48.0,nan"][..],
        &["--start", ON_THE_ROUTE, "--flown-m", "-1"],
        &["--start", ON_THE_ROUTE, "--last-overflight", "L1"],
    ] {
        assert_eq!(code(&plan(bad)), 2, "{bad:?}");
    }
    assert!(!std::path::Path::new(&out).exists());
}

#[test]
fn flown_m_on_a_roadmap_network_is_refused_by_name() {
    let dir = TempDir::new("start-option-flown-roadmap");
    let net = dir.file("niendorf.bin");
    ok(skyroute(&["build", &niendorf(), "-o", &net]), "build");
    let out = dir.file("route.json");
    let o = skyroute(&[
        "plan",
        &net,
        "--scenario",
        &niendorf(),
        "--start",
        "11.6478,48.0919,0",
        "--flown-m",
        "10",
        "-o",
        &out,
    ]);
    assert_eq!(code(&o), 1);
    assert!(
        one_line_error(&o).contains("--flown-m applies to landmark networks"),
        "{}",
        one_line_error(&o)
    );
}

#[test]
fn a_landmark_goal_is_joined_online_from_the_overflights() {
    let dir = TempDir::new("goal-option-landmark");
    let (net, out) = (babel_i_detour(&dir), dir.file("route.json"));
    let plan = |extra: &[&str]| plan_babel_i_detour(&net, &out, extra);
    let bytes = std::fs::read(&net).unwrap();
    let frame = skyroute::Network::from_bytes(&bytes).unwrap().local_frame();
    let goal = frame.position(12.05, 48.11).unwrap();
    for extra in [
        &["--goal", "12.05,48.11"][..],
        &["--goal", "12.05,48.11,90"],
    ] {
        ok(plan(extra), "plan --goal");
        let route: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
        let pieces = route["pieces"].as_array().unwrap();
        let last = pieces.last().unwrap();
        assert!(last["edge"].is_null(), "{last}");
        let to = &last["to"]["position"];
        let gap = (to[0].as_f64().unwrap() - goal.x as f64)
            .hypot(to[1].as_f64().unwrap() - goal.y as f64);
        assert!(gap < 0.01, "the last piece ends {gap} m from --goal");
        let legs = route["legs"].as_array().unwrap();
        assert_eq!(legs.last().unwrap()["to"], "goal");
        if extra[1].ends_with(",90") {
            // Compass 90° is east, the local frame's x axis up to the meridian convergence.
            let v = &last["to"]["velocity"];
            let (vx, vy) = (v[0].as_f64().unwrap(), v[1].as_f64().unwrap());
            assert!(vy.atan2(vx).abs() < 0.05, "arrives heading {vx}, {vy}");
        }
        std::fs::remove_file(&out).unwrap();
    }
    // A goal inside no-fly zone Z2: no piece reaches it (exit 3); a malformed one (exit 2).
    let o = plan(&["--goal", "12.04,48.08,90"]);
    assert_eq!(code(&o), 3);
    assert!(
        one_line_error(&o).contains("--goal: no overflight"),
        "{}",
        one_line_error(&o)
    );
    assert_eq!(code(&plan(&["--goal", "12.05"])), 2);
    assert!(!std::path::Path::new(&out).exists());
}
