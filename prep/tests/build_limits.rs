//! `skyroute build` refuses bad parameters before it allocates: each case here once panicked,
//! aborted on a huge allocation or was silently accepted. Now the message names the file and
//! the field (or the option), the exit code is 1 (2 for a malformed option value, clap's), no
//! output is written, and each refusal takes a fraction of a second.

mod common;

use common::{code, niendorf, one_line_error, scenario, skyroute, stderr, TempDir};
use serde_json::Value;
use skyroute::network::write::{encode, NetworkSpec, WriteError, MAX_GRID_CELLS};
use skyroute::{Pose, Vec2};
use std::path::Path;
use std::time::{Duration, Instant};

/// The niendorf-urban scenario changed by `change`, written to `dir/name`.
fn niendorf_with(dir: &TempDir, name: &str, change: impl FnOnce(&mut Value)) -> String {
    let mut s: Value = serde_json::from_str(&std::fs::read_to_string(niendorf()).unwrap()).unwrap();
    change(&mut s);
    let path = dir.file(name);
    std::fs::write(&path, serde_json::to_string(&s).unwrap()).unwrap();
    path
}

/// Moves the feature of `kind` (start or goal) to `(lon, lat)`.
fn move_endpoint(s: &mut Value, kind: &str, lon: f64, lat: f64) {
    for f in s["features"].as_array_mut().unwrap() {
        if f["properties"]["kind"] == kind {
            f["geometry"]["coordinates"] = serde_json::json!([lon, lat]);
        }
    }
}

/// Builds with `args` after `build SCENARIO -o OUT`; expects exit `exit` within 5 seconds, a
/// message containing every one of `parts`, and no output.
fn refused(scenario: &str, args: &[&str], exit: i32, parts: &[&str]) -> String {
    let dir = TempDir::new(&format!(
        "limits-{}",
        parts[0].replace(['/', ' ', '.'], "_")
    ));
    let out = dir.file("out.bin");
    let mut all = vec!["build", scenario, "-o", &out];
    all.extend_from_slice(args);
    let t0 = Instant::now();
    let o = skyroute(&all);
    let took = t0.elapsed();
    let e = stderr(&o);
    assert_eq!(code(&o), exit, "{all:?}: {e}");
    for part in parts {
        assert!(e.contains(part), "{all:?}: {e:?} lacks {part:?}");
    }
    assert!(!Path::new(&out).exists(), "{all:?} wrote {out}");
    assert!(took < Duration::from_secs(5), "{all:?} took {took:?}");
    e
}

#[test]
fn a_crawling_vehicle_is_refused_for_its_grid_index() {
    // 1 mm/s: a turn radius of 0.1 µm made the default grid cell 0.2 µm, and the writer's
    // unchecked grid product wrapped: an index out of bounds after 18 s and 3 GB in a release
    // build, a multiplication overflow in a test build.
    let dir = TempDir::new("slow-vehicle");
    let s = niendorf_with(&dir, "slow.geojson", |s| {
        s["vehicle"]["v_nominal_mps"] = 1e-3.into();
        s["vehicle"]["v_min_mps"] = 1e-3.into();
    });
    let e = refused(
        &s,
        &[],
        1,
        &["slow.geojson", "vehicle.v_nominal_mps", "4194304"],
    );
    assert!(e.contains("--grid-cell"), "{e}");
    one_line_error(&skyroute(&["build", &s, "-o", &dir.file("o.bin")]));
}

#[test]
fn a_tiny_grid_cell_is_refused_by_option() {
    // Both aborted on allocations of tens of gigabytes (67 to 83 GB).
    refused(
        &niendorf(),
        &["--grid-cell", "0.001"],
        1,
        &["niendorf-urban.geojson", "--grid-cell", "4194304"],
    );
    let jacksboro = scenario("medeiros-jacksboro.geojson");
    refused(
        &jacksboro,
        &["--grid-cell", "1"],
        1,
        &["medeiros-jacksboro.geojson", "--grid-cell"],
    );
}

#[test]
fn a_zero_or_vanishing_sample_spacing_is_refused() {
    // Both panicked in prep/src/roadmap.rs (index out of bounds).
    refused(
        &niendorf(),
        &["--sample-spacing", "0"],
        2,
        &["--sample-spacing"],
    );
    let dir = TempDir::new("spacing");
    let s = niendorf_with(&dir, "tiny.geojson", |s| {
        s["planner"]["sample_spacing_m"] = 1e-300.into()
    });
    refused(
        &s,
        &[],
        1,
        &[
            "tiny.geojson",
            "planner.sample_spacing_m",
            "1e-300",
            "at least 1 m",
        ],
    );
}

#[test]
fn a_spacing_that_would_need_terabytes_is_refused() {
    // 0.01 m over niendorf's 2.6 km aborted on a terabyte allocation.
    let dir = TempDir::new("spacing-cm");
    let s = niendorf_with(&dir, "cm.geojson", |s| {
        s["planner"]["sample_spacing_m"] = 0.01.into()
    });
    refused(
        &s,
        &[],
        1,
        &["cm.geojson", "planner.sample_spacing_m", "at least 1 m"],
    );
    // Above the minimum, the candidate count is limited too.
    refused(
        &niendorf(),
        &["--sample-spacing", "1.5"],
        1,
        &["--sample-spacing", "1048576"],
    );
    // And the neighbour pairs: 4 m ran out of memory (1.4 GB after 60 s, still growing).
    refused(
        &niendorf(),
        &["--sample-spacing", "4"],
        1,
        &[
            "--sample-spacing and planner.neighbour_radius_m",
            "33554432",
        ],
    );
    // A radius beyond the area connects every pair, which are few with a 200 m spacing: built.
    let dir = TempDir::new("wide-radius");
    let out = dir.file("wide.bin");
    common::ok(
        skyroute(&[
            "build",
            &niendorf(),
            "-o",
            &out,
            "--neighbour-radius",
            "100000",
            "--sample-spacing",
            "200",
        ]),
        "build with a 100 km neighbour radius",
    );
}

#[test]
fn an_area_beyond_the_limit_is_refused() {
    let dir = TempDir::new("area");
    // A goal 60° of latitude south of the start: terabyte allocations (under a 4 GB limit it
    // ran out of memory after minutes).
    let far = niendorf_with(&dir, "far.geojson", |s| {
        move_endpoint(s, "goal", 11.648, -11.91)
    });
    refused(
        &far,
        &[],
        1,
        &["far.geojson", "geometry.coordinates", "1000 km"],
    );
    // From pole to pole: "capacity overflow" (an allocation failure under a 4 GB limit).
    let poles = niendorf_with(&dir, "poles.geojson", |s| {
        move_endpoint(s, "start", 0.0, -90.0);
        move_endpoint(s, "goal", 0.0, 90.0);
    });
    refused(
        &poles,
        &[],
        1,
        &["poles.geojson", "geometry.coordinates", "1000 km"],
    );
}

#[test]
fn non_finite_and_negative_overrides_are_refused_by_name() {
    let options = [
        "--sample-spacing",
        "--neighbour-radius",
        "--grid-cell",
        "--node-spacing",
        "--max-edge",
        "--node-margin",
        "--altitude-levels",
    ];
    for option in options {
        let mut bad = vec!["NaN", "inf", "-inf"];
        if option != "--altitude-levels" {
            bad.push("-5"); // altitudes below sea level are altitudes
        }
        for value in bad {
            let e = refused(&niendorf(), &[option, value], 2, &[option]);
            assert!(e.contains("invalid value"), "{option} {value}: {e}");
        }
    }
    refused(
        &niendorf(),
        &["--altitude-levels", "700,nan"],
        2,
        &["--altitude-levels"],
    );
    refused(&niendorf(), &["--max-edge", "0"], 2, &["--max-edge"]);
}

#[test]
fn a_network_without_vertices_is_refused() {
    // A clearance of 100 km puts every sample within it of a building: the build wrote a
    // network of 0 vertices.
    let dir = TempDir::new("no-vertices");
    let s = niendorf_with(&dir, "wide.geojson", |s| {
        s["planner"]["clearance_m"] = 1e5.into()
    });
    refused(
        &s,
        &[],
        1,
        &["wide.geojson", "no vertices", "planner.clearance_m"],
    );
}

#[test]
fn build_help_states_the_limits() {
    let o = skyroute(&["build", "--help"]);
    let help = common::stdout(&o);
    let spaced = |n: u64| {
        let d = n.to_string();
        let mut out = String::new();
        for (i, c) in d.chars().enumerate() {
            if i > 0 && (d.len() - i).is_multiple_of(3) {
                out.push(' ');
            }
            out.push(c);
        }
        out
    };
    let area_km = format!(
        "{} km",
        skyroute_prep::build_limits::MAX_AREA_SIDE_M / 1000.0
    );
    let spacing = format!("{} m", skyroute_prep::roadmap::MIN_SAMPLE_SPACING_M);
    for part in [
        spaced(MAX_GRID_CELLS),
        spaced(skyroute_prep::roadmap::MAX_SAMPLE_CANDIDATES as u64),
        spaced(skyroute_prep::roadmap::MAX_NEIGHBOUR_PAIRS as u64),
        area_km,
        spacing,
    ] {
        assert!(help.contains(&part), "build --help lacks {part:?}:\n{help}");
    }
}

#[test]
fn the_writer_refuses_an_oversized_grid_index() {
    let pose = |x: f32| Pose {
        position: Vec2::new(x, 0.0),
        heading: 0.0,
    };
    let mut spec = NetworkSpec {
        origin_lat_deg: 48.0,
        origin_lon_deg: 11.0,
        turn_radius_m: 50.0,
        clearance_m: 0.0,
        vertices: vec![pose(0.0), pose(1000.0)],
        edges: Vec::new(),
        obstacles: Vec::new(),
        grid_cell_m: 1e-4,
        terrain: None,
        landmark: None,
        voronoi: None,
        provenance: Vec::new(),
    };
    match encode(&spec) {
        Err(WriteError::GridTooLarge(cell, nx, ny)) => {
            assert_eq!(cell, 1e-4);
            assert!(nx * ny > MAX_GRID_CELLS as f64, "{nx} x {ny}");
        }
        other => panic!("expected GridTooLarge, got {other:?}"),
    }
    for cell in [0.0, -1.0, f32::NAN, f32::INFINITY] {
        spec.grid_cell_m = cell;
        assert!(
            matches!(encode(&spec), Err(WriteError::BadGridCell(_))),
            "grid cell {cell}"
        );
    }
    spec.grid_cell_m = 100.0;
    assert!(encode(&spec).is_ok());
}
