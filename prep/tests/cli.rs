//! The `skyroute` binary end to end: build → plan → export → render on niendorf-urban, `--help`
//! on every command, and the one-line errors for a truncated network and a self-intersecting
//! no-fly polygon.

mod common;

use common::{niendorf, ok, one_line_error, skyroute, stdout, TempDir};
use serde_json::Value;
use std::path::Path;

#[test]
fn build_plan_export_render_end_to_end() {
    let dir = TempDir::new("e2e");
    let (net, route, json) = (
        dir.file("n.bin"),
        dir.file("route.json"),
        dir.file("n.json"),
    );
    let (svg, png, png2) = (dir.file("n.svg"), dir.file("n.png"), dir.file("also.png"));
    let scenario = niendorf();

    let o = ok(skyroute(&["build", &scenario, "-o", &net]), "build");
    assert!(stdout(&o).contains(" edges"), "{}", stdout(&o));
    ok(
        skyroute(&["plan", &net, "--scenario", &scenario, "-o", &route]),
        "plan",
    );
    let o = ok(skyroute(&["info", &net]), "info");
    for part in [
        "roadmap network, format v4",
        "1445 vertices, 18342 edges, 60 obstacles",
        "V >= 1445 (search states), E >= 18342",
        "provenance: 63 digests",
        // The bound of a planner with the RAM line's capacities (P = 4 pop-ups).
        "worst-case work with P = 4 and R = 128: a query 2083910,",
    ] {
        assert!(
            stdout(&o).contains(part),
            "info lacks {part:?}: {}",
            stdout(&o)
        );
    }
    let o = ok(skyroute(&["export", &net, "-o", &json]), "export");
    assert!(stdout(&o).contains("exported"), "{}", stdout(&o));

    // The export: the documented members, and as many vertices/edges as the image holds.
    let v: Value = serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let bytes = std::fs::read(&net).unwrap();
    let n = skyroute::Network::from_bytes(&bytes).unwrap();
    assert_eq!(
        v["vertices"].as_array().unwrap().len(),
        n.vertex_count() as usize
    );
    assert_eq!(
        v["edges"].as_array().unwrap().len(),
        n.edge_count() as usize
    );
    assert_eq!(v["obstacles"].as_array().unwrap().len(), 60);
    assert_eq!(v["clearance_m"].as_f64(), Some(7.0));
    for k in ["origin_lat_deg", "origin_lon_deg", "method"] {
        assert!(!v["frame"][k].is_null(), "frame.{k}");
    }
    let v0 = &v["vertices"][0];
    for k in [
        "id",
        "x",
        "y",
        "heading_rad",
        "heading_compass_deg",
        "lon",
        "lat",
    ] {
        assert!(!v0[k].is_null(), "vertices[0].{k}");
    }
    let e0 = &v["edges"][0];
    for k in ["id", "from", "to", "cost", "word", "primitives"] {
        assert!(!e0[k].is_null(), "edges[0].{k}");
    }
    assert_eq!(v["obstacles"][0]["kind"], "polygon");

    // Render: SVG with a PNG beside it, and a PNG chosen by the output's name.
    let o = ok(
        skyroute(&[
            "render",
            &net,
            "--route",
            &route,
            "--scenario",
            &scenario,
            "--popup",
            "11.63,48.095,60",
            "-o",
            &svg,
            "--png",
            &png2,
        ]),
        "render svg",
    );
    assert!(stdout(&o).contains("rendered"), "{}", stdout(&o));
    let text = std::fs::read_to_string(&svg).unwrap();
    assert!(text.starts_with("<svg"), "{}", &text[..100.min(text.len())]);
    for label in [
        "P (start)",
        "W1",
        "W2",
        "W3",
        "W4",
        "Q (goal)",
        "--popup #1",
        "route:",
    ] {
        assert!(text.contains(label), "the SVG lacks {label:?}");
    }
    ok(
        skyroute(&[
            "render",
            &net,
            "--route",
            &route,
            "--scenario",
            &scenario,
            "-o",
            &png,
        ]),
        "render png",
    );
    for p in [&png, &png2] {
        let b = std::fs::read(p).unwrap();
        assert_eq!(&b[..8], b"\x89PNG\r\n\x1a\n", "{p} is not a PNG");
        assert!(b.len() > 10_000, "{p}: {} bytes", b.len());
    }
    // Network only, no route or scenario.
    ok(
        skyroute(&["render", &net, "--no-edges", "-o", &dir.file("plain.svg")]),
        "render plain",
    );
}

#[test]
fn help_works_on_every_command() {
    for args in [
        &["--help"][..],
        &["help"],
        &["build", "--help"],
        &["plan", "--help"],
        &["export", "--help"],
        &["render", "--help"],
        &["info", "--help"],
        &["init", "--help"],
        &["help", "render"],
    ] {
        let o = ok(skyroute(args), &args.join(" "));
        assert!(stdout(&o).contains("Usage:"), "{args:?}: {}", stdout(&o));
    }
    let o = skyroute(&["--help"]);
    for c in ["build", "plan", "export", "render"] {
        assert!(stdout(&o).contains(c), "--help does not list {c}");
    }
    let o = skyroute(&["render", "--help"]);
    for flag in [
        "--route",
        "--scenario",
        "--popup",
        "--output",
        "--png",
        ".png",
    ] {
        assert!(
            stdout(&o).contains(flag),
            "render --help does not mention {flag}"
        );
    }
}

#[test]
fn truncated_network_gives_one_line_naming_the_file() {
    let dir = TempDir::new("truncated");
    let (net, cut) = (dir.file("n.bin"), dir.file("cut.bin"));
    let scenario = niendorf();
    ok(skyroute(&["build", &scenario, "-o", &net]), "build");
    let bytes = std::fs::read(&net).unwrap();
    std::fs::write(&cut, &bytes[..bytes.len() / 3]).unwrap();
    // (`plan` picks its format by the extension: a route file ends in .json.)
    let (out, svg, route) = (dir.file("x.json"), dir.file("x.svg"), dir.file("r.json"));
    for (args, written) in [
        (vec!["export", &cut, "-o", &out], &out),
        (vec!["render", &cut, "-o", &svg], &svg),
        (
            vec!["plan", &cut, "--scenario", &scenario, "-o", &route],
            &route,
        ),
    ] {
        let line = one_line_error(&skyroute(&args));
        assert!(line.contains(&cut), "{args:?}: {line}");
        assert!(line.contains("truncated"), "{args:?}: {line}");
        assert!(!Path::new(written).exists(), "{args:?} wrote {written}");
    }
    // Not a network at all, and a missing file.
    std::fs::write(&cut, b"hello").unwrap();
    let line = one_line_error(&skyroute(&["export", &cut, "-o", &out]));
    assert!(line.contains(&cut), "{line}");
    let missing = dir.file("missing.bin");
    let line = one_line_error(&skyroute(&["export", &missing, "-o", &out]));
    assert!(line.contains(&missing), "{line}");
}

#[test]
fn self_intersecting_polygon_names_file_feature_and_field() {
    let dir = TempDir::new("bowtie");
    let scenario = dir.file("bowtie.geojson");
    // A bow tie: edges 0 and 2 cross.
    std::fs::write(
        &scenario,
        r#"{
  "type": "FeatureCollection",
  "name": "bowtie",
  "vehicle": {"v_nominal_mps": 25.0, "v_min_mps": 20.0, "v_max_mps": 30.0, "a_lat_max_mps2": 9.81,
              "a_long_min_mps2": -3.0, "a_long_max_mps2": 3.0, "wingspan_m": 3.0},
  "planner": {"mode": "roadmap", "sample_spacing_m": 50.0, "neighbour_radius_m": 190.0, "clearance_m": 5.0},
  "features": [
    {"type": "Feature", "properties": {"kind": "start", "name": "S", "heading_deg": 90},
     "geometry": {"type": "Point", "coordinates": [11.600, 48.100]}},
    {"type": "Feature", "properties": {"kind": "no_fly", "name": "Bowtie"},
     "geometry": {"type": "Polygon", "coordinates": [[[11.61, 48.10], [11.62, 48.11], [11.62, 48.10], [11.61, 48.11], [11.61, 48.10]]]}},
    {"type": "Feature", "properties": {"kind": "goal", "name": "G"},
     "geometry": {"type": "Point", "coordinates": [11.630, 48.100]}}
  ]
}"#,
    )
    .unwrap();
    let out = dir.file("n.bin");
    let line = one_line_error(&skyroute(&["build", &scenario, "-o", &out]));
    for part in [
        scenario.as_str(),
        "feature 1 (Bowtie)",
        "geometry.coordinates",
        "self-intersecting",
    ] {
        assert!(line.contains(part), "{line:?} lacks {part:?}");
    }
    assert!(!Path::new(&out).exists());

    // The same through render --scenario (a network to draw on is needed first).
    let net = dir.file("good.bin");
    ok(skyroute(&["build", &niendorf(), "-o", &net]), "build");
    let svg = dir.file("x.svg");
    let line = one_line_error(&skyroute(&[
        "render",
        &net,
        "--scenario",
        &scenario,
        "-o",
        &svg,
    ]));
    for part in [
        scenario.as_str(),
        "feature 1 (Bowtie)",
        "geometry.coordinates",
    ] {
        assert!(line.contains(part), "{line:?} lacks {part:?}");
    }
    assert!(!Path::new(&svg).exists());
}

/// Bad scenario inputs through `skyroute build`: each is refused with exit code 1 and one
/// line naming the file, the feature and the field, before anything is built; a byte-order mark
/// is accepted.
#[test]
fn bad_scenario_inputs_are_refused_by_name() {
    let dir = TempDir::new("badinput");
    // Compact, with the keys in order: the start's properties are one known string.
    let json: Value = serde_json::from_str(&std::fs::read_to_string(niendorf()).unwrap()).unwrap();
    let text = serde_json::to_string(&json).unwrap();
    let start = r#""heading_deg":216.5,"kind":"start","name":"P""#;
    assert_eq!(text.matches(start).count(), 1);
    let out = dir.file("n.bin");
    for (name, changed, parts) in [
        (
            "no-heading.geojson",
            text.replace(start, r#""kind":"start","name":"P""#),
            &["feature ", "(P): properties.heading_deg: missing: the start needs a heading"][..],
        ),
        (
            "misspelt.geojson",
            text.replace(start, r#""heading":216.5,"kind":"start","name":"P""#),
            &["(P): properties.heading: unknown key; expected one of kind, name, heading_deg, dist_m"],
        ),
        (
            "twice.geojson",
            text.replace(start, &format!(r#"{start},"heading_deg":10"#)),
            &["invalid JSON: duplicate key \"heading_deg\" in features[", "].properties"],
        ),
    ] {
        let path = dir.file(name);
        std::fs::write(&path, changed).unwrap();
        let o = skyroute(&["build", &path, "-o", &out]);
        assert_eq!(common::code(&o), 1);
        let line = one_line_error(&o);
        assert!(line.contains(&path), "{line}");
        for p in parts {
            assert!(line.contains(p), "{line:?} lacks {p:?}");
        }
        assert!(!Path::new(&out).exists());
    }
    // A UTF-8 byte-order mark before the same scenario.
    let bom = dir.file("bom.geojson");
    std::fs::write(&bom, format!("\u{feff}{text}")).unwrap();
    ok(skyroute(&["build", &bom, "-o", &out]), "build with a BOM");
}
