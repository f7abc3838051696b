//! Bad input to the `skyroute` binary, each case a row of the "Bad input" table in
//! `docs/RELIABILITY.md` that no other test file covers: damaged networks, files of another
//! format where a scenario or a DEM is expected, endpoints inside pop-ups, outputs whose name
//! does not match their format or whose folder is missing, the Monte Carlo study's inputs, the
//! sizes that once hung, plan options that do not apply, an empty scenario. Each refusal is one
//! line naming the file (or the option) with its exit code, and writes nothing.

mod common;

use common::{code, niendorf, ok, one_line_error, scenario, skyroute, stderr, stdout, TempDir};
use serde_json::{json, Value};
use std::path::Path;
use std::sync::OnceLock;
use std::time::{Duration, Instant};

/// The niendorf-urban network, built once for the tests of this file.
fn niendorf_network() -> &'static str {
    static NET: OnceLock<(TempDir, String)> = OnceLock::new();
    let (_, path) = NET.get_or_init(|| {
        let dir = TempDir::new("bad-input-net");
        let net = dir.file("niendorf.bin");
        ok(skyroute(&["build", &niendorf(), "-o", &net]), "build");
        (dir, net)
    });
    path
}

/// Runs `args`; expects exit code `exit`, one line of error containing every one of `parts`,
/// and `out` not written.
fn refused(args: &[&str], out: &str, exit: i32, parts: &[&str]) -> String {
    let o = skyroute(args);
    assert_eq!(code(&o), exit, "{args:?}: {}", stderr(&o));
    let line = one_line_error(&o);
    for part in parts {
        assert!(line.contains(part), "{args:?}: {line:?} lacks {part:?}");
    }
    assert!(!Path::new(out).exists(), "{args:?} wrote {out}");
    line
}

fn read_json(path: &str) -> Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// The feature of `kind` (start or goal) of a scenario.
fn endpoint(s: &Value, kind: &str) -> [f64; 2] {
    let f = s["features"]
        .as_array()
        .unwrap()
        .iter()
        .find(|f| f["properties"]["kind"] == kind)
        .unwrap();
    let c = &f["geometry"]["coordinates"];
    [c[0].as_f64().unwrap(), c[1].as_f64().unwrap()]
}

#[test]
fn damaged_networks_are_refused_naming_the_file_and_the_damage() {
    let dir = TempDir::new("bad-networks");
    let good = std::fs::read(niendorf_network()).unwrap();
    let mut flipped = good.clone();
    flipped[good.len() / 2] ^= 0x10;
    let mut version = good.clone();
    version[4] = 7;
    let mut trailing = good.clone();
    trailing.extend_from_slice(b"abc");
    let out = dir.file("r.json");
    for (name, bytes, parts) in [
        (
            "flipped.bin",
            flipped,
            &["body CRC-32", "does not match the header's"][..],
        ),
        (
            "v7.bin",
            version,
            &["network format version 7, this build reads"],
        ),
        (
            "trailing.bin",
            trailing,
            &["3 unexpected bytes after the network body"],
        ),
        ("empty.bin", Vec::new(), &["network truncated", "0 present"]),
    ] {
        let net = dir.file(name);
        std::fs::write(&net, bytes).unwrap();
        refused(&["info", &net], &out, 1, &[&net, parts[0]]);
        let line = refused(
            &["plan", &net, "--scenario", &niendorf(), "-o", &out],
            &out,
            1,
            parts,
        );
        assert!(line.contains(&net), "{line}");
    }
    // A scenario given as the network.
    refused(
        &["info", &niendorf()],
        &out,
        1,
        &[&niendorf(), "not a skyroute network"],
    );
}

#[test]
fn a_scenario_in_another_format_is_named_as_what_it_is() {
    let dir = TempDir::new("foreign-scenario");
    let files = [
        (
            "area.kml",
            b"<?xml version=\"1.0\"?><kml xmlns=\"http://www.opengis.net/kml/2.2\"></kml>".to_vec(),
            "this is a KML document",
        ),
        (
            "dem.tif",
            [&b"II*\0"[..], &[0u8; 60]].concat(),
            "this is a TIFF image",
        ),
        (
            "dem.asc",
            b"ncols 3\nnrows 1\nxllcorner 10\nyllcorner 48\ncellsize 0.01\n1 2 3\n".to_vec(),
            "this is an ESRI ASCII grid",
        ),
        (
            "copy.bin",
            std::fs::read(niendorf_network()).unwrap(),
            "this is a skyroute network image",
        ),
    ];
    let (out, route, svg) = (dir.file("n.bin"), dir.file("r.json"), dir.file("x.svg"));
    for (name, bytes, what) in files {
        let path = dir.file(name);
        std::fs::write(&path, bytes).unwrap();
        let parts = [path.as_str(), what, "not a scenario"];
        refused(&["build", &path, "-o", &out], &out, 1, &parts);
        refused(
            &[
                "plan",
                niendorf_network(),
                "--scenario",
                &path,
                "-o",
                &route,
            ],
            &route,
            1,
            &parts,
        );
        refused(
            &[
                "render",
                niendorf_network(),
                "--scenario",
                &path,
                "-o",
                &svg,
            ],
            &svg,
            1,
            &parts,
        );
    }
}

#[test]
fn an_endpoint_inside_a_popup_is_refused_by_both_names() {
    let dir = TempDir::new("popup-ends");
    let out = dir.file("r.json");
    let mut s = read_json(&niendorf());
    let [glon, glat] = endpoint(&s, "goal");
    s["features"].as_array_mut().unwrap().push(json!({
        "type": "Feature",
        "properties": {"kind": "popup", "name": "OverGoal", "radius_m": 60.0, "probability": 1.0},
        "geometry": {"type": "Point", "coordinates": [glon, glat]}
    }));
    let sc = dir.file("over-goal.geojson");
    std::fs::write(&sc, serde_json::to_string(&s).unwrap()).unwrap();
    // Exit 3: no route exists; the goal is named, not the waypoint before it.
    refused(
        &["plan", niendorf_network(), "--scenario", &sc, "-o", &out],
        &out,
        3,
        &[
            &sc,
            "goal \"Q\" lies inside pop-up \"OverGoal\" (radius 60 m, its centre 0 m away)",
        ],
    );
    // A roadmap start inside a pop-up is left by an exit first (`prep/tests/drift_exit.rs`).
    let [slon, slat] = endpoint(&s, "start");
    let popup = format!("{},{},40", slon + 0.0002, slat);
    let o = skyroute(&[
        "plan",
        niendorf_network(),
        "--scenario",
        &niendorf(),
        "--popup",
        &popup,
        "-o",
        &out,
    ]);
    assert_eq!(code(&o), 0, "{}", stderr(&o));
    assert!(stdout(&o).contains("P lies inside or within the clearance of --popup #1"));
}

#[test]
fn outputs_named_for_another_format_are_refused() {
    let dir = TempDir::new("out-ext");
    let net = niendorf_network();
    let (jpg, svg, png) = (dir.file("x.jpg"), dir.file("x.svg"), dir.file("x.png"));
    refused(
        &["render", net, "-o", &jpg],
        &jpg,
        1,
        &[&jpg, "render writes SVG or PNG"],
    );
    refused(
        &["render", net, "-o", &svg, "--png", &jpg],
        &svg,
        1,
        &[&jpg, "--png writes PNG"],
    );
    refused(
        &["render", net, "-o", &png, "--png", &png],
        &png,
        1,
        &[&png, "given as both -o and --png"],
    );
    let txt = dir.file("e.txt");
    refused(
        &["export", net, "-o", &txt],
        &txt,
        1,
        &[&txt, "export writes JSON"],
    );
    refused(
        &["montecarlo", net, "--scenario", &niendorf(), "-o", &txt],
        &txt,
        1,
        &[&txt, "montecarlo writes JSON"],
    );
}

#[test]
fn an_output_in_a_missing_folder_is_refused_before_the_work() {
    let dir = TempDir::new("no-folder");
    let net = niendorf_network();
    let missing = dir.file("missing");
    let inside = |name: &str| format!("{missing}/{name}");
    let sc = niendorf();
    let cases: [Vec<String>; 6] = [
        vec!["build".into(), sc.clone(), "-o".into(), inside("n.bin")],
        vec![
            "plan".into(),
            net.into(),
            "--scenario".into(),
            sc.clone(),
            "-o".into(),
            inside("r.json"),
        ],
        vec!["export".into(), net.into(), "-o".into(), inside("e.json")],
        vec!["render".into(), net.into(), "-o".into(), inside("x.svg")],
        vec![
            "montecarlo".into(),
            net.into(),
            "--scenario".into(),
            sc.clone(),
            "-o".into(),
            inside("mc.json"),
        ],
        vec![
            "montecarlo".into(),
            net.into(),
            "--scenario".into(),
            sc.clone(),
            "-o".into(),
            dir.file("mc.json"),
            "--histograms".into(),
            inside("h"),
        ],
    ];
    for args in cases {
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let t0 = Instant::now();
        let line = refused(
            &args,
            &missing,
            1,
            &[&format!("the folder {missing} does not exist")],
        );
        assert!(t0.elapsed() < Duration::from_secs(5), "{args:?}: {line}");
    }
}

#[test]
fn montecarlo_never_overwrites_its_inputs_and_needs_a_mission() {
    let dir = TempDir::new("mc-inputs");
    // Inputs named .json, so that only the overwrite check can refuse them.
    let (net, sc) = (dir.file("net.json"), dir.file("scenario.json"));
    std::fs::copy(niendorf_network(), &net).unwrap();
    std::fs::copy(niendorf(), &sc).unwrap();
    let before = std::fs::read(&net).unwrap();
    for target in [&net, &sc] {
        let o = skyroute(&["montecarlo", &net, "--scenario", &sc, "-o", target]);
        assert_eq!(code(&o), 1, "{}", stderr(&o));
        let line = one_line_error(&o);
        assert!(line.contains("would overwrite the input"), "{line}");
    }
    assert_eq!(std::fs::read(&net).unwrap(), before);
    let out = dir.file("mc.json");
    refused(
        &[
            "montecarlo",
            &net,
            "--scenario",
            &sc,
            "--missions",
            "0",
            "-o",
            &out,
        ],
        &out,
        1,
        &["--missions 0: the study needs at least one mission"],
    );
}

/// The Jacksboro terrain scenario, written to `dir` with its DEM replaced by `dem_text` (or
/// bytes).
fn terrain_with_dem(dir: &TempDir, name: &str, dem: &[u8]) -> String {
    let mut s = read_json(&scenario("medeiros-jacksboro.geojson"));
    let dem_name = format!("{name}.dem");
    std::fs::write(dir.file(&dem_name), dem).unwrap();
    s["terrain"]["dem"] = json!(dem_name);
    let path = dir.file(&format!("{name}.geojson"));
    std::fs::write(&path, serde_json::to_string(&s).unwrap()).unwrap();
    path
}

#[test]
fn bad_dems_are_refused_naming_the_dem_and_what_is_wrong() {
    let dir = TempDir::new("bad-dems");
    let real = std::fs::read_to_string(scenario("jacksboro-dem.asc")).unwrap();
    let lines: Vec<&str> = real.lines().collect();
    let header = &lines[..6];
    let cols = lines[6].split_whitespace().count();
    let rows = lines.len() - 6;
    let with_row = |i: usize, row: String| {
        let mut l: Vec<String> = lines.iter().map(|s| s.to_string()).collect();
        l[i] = row;
        l.join("\n") + "\n"
    };
    let short_row: Vec<&str> = lines[10].split_whitespace().collect();
    let mut nan_row = short_row.clone();
    nan_row[3] = "nan";
    let nodata = format!(
        "{}\n{}",
        header.join("\n"),
        vec![vec!["-9999"; cols].join(" "); rows].join("\n")
    );
    let cases: [(&str, Vec<u8>, &[&str]); 4] = [
        (
            "short-row",
            with_row(10, short_row[..cols - 1].join(" ")).into_bytes(),
            &["line 11: row 5 (from the north)", "expected ncols = 403"],
        ),
        (
            "nan",
            with_row(10, nan_row.join(" ")).into_bytes(),
            &[
                "line 11: row 5 (from the north) column 4",
                "\"nan\" is not a finite number",
            ],
        ),
        (
            "nodata",
            nodata.into_bytes(),
            &["every cell is NODATA: the DEM has no elevation"],
        ),
        (
            "kml",
            b"<?xml version=\"1.0\"?><kml></kml>\n".to_vec(),
            &["line 1: <?xml", "unknown header key"],
        ),
    ];
    let out = dir.file("t.bin");
    for (name, dem, parts) in cases {
        let sc = terrain_with_dem(&dir, name, &dem);
        let line = refused(&["build", &sc, "-o", &out], &out, 1, parts);
        let dem = format!("{name}.dem");
        assert!(line.contains(&dem), "{line} lacks {dem}");
    }
}

#[test]
fn render_sizes_are_bounded_and_a_tiny_area_renders_promptly() {
    let dir = TempDir::new("render-sizes");
    let net = niendorf_network();
    let png = dir.file("x.png");
    for width in ["nan", "0", "1e9"] {
        refused(
            &["render", net, "-o", &png, "--width", width],
            &png,
            1,
            &["--width", "expected 200 to 20000 pixels"],
        );
    }
    // A 1 mm square of the map: once a PNG render that never finished.
    let t0 = Instant::now();
    ok(
        skyroute(&["render", net, "-o", &png, "--area", "0,0,0.001,0.001"]),
        "render a 1 mm area",
    );
    assert!(t0.elapsed() < Duration::from_secs(10), "{:?}", t0.elapsed());
}

#[test]
fn a_twenty_thousand_vertex_no_fly_ring_builds_promptly() {
    // The ring check was O(n²): such a ring never finished `build`.
    let dir = TempDir::new("ring20k");
    let mut s = read_json(&niendorf());
    let [lon, lat] = endpoint(&s, "start");
    let n = 20_000;
    let mut ring: Vec<[f64; 2]> = (0..n)
        .map(|i| {
            let a = std::f64::consts::TAU * i as f64 / n as f64;
            [lon + 0.003 + 0.001 * a.cos(), lat + 0.001 * a.sin()]
        })
        .collect();
    ring.push(ring[0]);
    s["features"].as_array_mut().unwrap().push(json!({
        "type": "Feature",
        "properties": {"kind": "no_fly", "name": "Ring"},
        "geometry": {"type": "Polygon", "coordinates": [ring]}
    }));
    let sc = dir.file("ring.geojson");
    std::fs::write(&sc, serde_json::to_string(&s).unwrap()).unwrap();
    let t0 = Instant::now();
    ok(
        skyroute(&["build", &sc, "-o", &dir.file("ring.bin")]),
        "build with a 20 000-vertex ring",
    );
    assert!(t0.elapsed() < Duration::from_secs(10), "{:?}", t0.elapsed());
}

#[test]
fn plan_options_that_do_not_apply_are_refused_by_name() {
    let dir = TempDir::new("plan-options");
    let (net, sc, out) = (niendorf_network(), niendorf(), dir.file("r.json"));
    let plan = |extra: &[&str]| {
        let mut a = vec!["plan", net, "--scenario", &sc, "-o", &out];
        a.extend_from_slice(extra);
        a.iter().map(|s| s.to_string()).collect::<Vec<_>>()
    };
    for (extra, part) in [
        (
            &["--threat", "11.63,48.09,100"][..],
            "--threat applies to voronoi networks",
        ),
        (
            &["--popup-appears", "Nope"],
            "has no popup feature named \"Nope\" (its pop-ups: none)",
        ),
    ] {
        let args = plan(extra);
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        refused(&args, &out, 1, &[part]);
    }
    refused(
        &plan(&["--weather", "sunny"])
            .iter()
            .map(String::as_str)
            .collect::<Vec<_>>(),
        &out,
        1,
        &[
            "--weather sunny: ",
            "is not a landmark network, so it has no weather",
        ],
    );
}

#[test]
fn a_scenario_without_features_or_with_a_negative_clearance_is_refused() {
    let dir = TempDir::new("empty-scenario");
    let out = dir.file("n.bin");
    let mut s = read_json(&niendorf());
    s["features"] = json!([]);
    let empty = dir.file("empty.geojson");
    std::fs::write(&empty, serde_json::to_string(&s).unwrap()).unwrap();
    refused(
        &["build", &empty, "-o", &out],
        &out,
        1,
        &[
            &empty,
            "features: empty: a scenario needs at least one feature",
        ],
    );
    let mut s = read_json(&niendorf());
    s["planner"]["clearance_m"] = json!(-5.0);
    let negative = dir.file("negative.geojson");
    std::fs::write(&negative, serde_json::to_string(&s).unwrap()).unwrap();
    refused(
        &["build", &negative, "-o", &out],
        &out,
        1,
        &[
            &negative,
            "planner.clearance_m: -5 is out of range: expected a non-negative number",
        ],
    );
}

#[test]
fn popups_of_no_area_or_off_the_globe_are_refused() {
    let dir = TempDir::new("popup-radius");
    let (net, sc, out) = (niendorf_network(), niendorf(), dir.file("r.json"));
    // clap's usage errors: exit code 2, the value and the rule.
    for popup in [
        "11.63,48.09,0",
        "11.63,48.09,-5",
        "nan,48.09,50",
        "11.63,91,50",
        "11.63,48.09,50,0",
        "11.63,48.09,50,nan",
        "11.63,48.09,50,1e6",
        "11.63,48.09,50,30,1",
    ] {
        let o = skyroute(&["plan", net, "--scenario", &sc, "--popup", popup, "-o", &out]);
        assert_eq!(code(&o), 2, "{popup}: {}", stderr(&o));
        for part in [
            format!("invalid value '{popup}' for '--popup <POPUP>'"),
            "radius > 0".to_string(),
        ] {
            assert!(stderr(&o).contains(&part), "{popup}: {}", stderr(&o));
        }
        assert!(!Path::new(&out).exists());
    }
    let mut s = read_json(&sc);
    let [lon, lat] = endpoint(&s, "goal");
    s["features"].as_array_mut().unwrap().push(json!({
        "type": "Feature",
        "properties": {"kind": "popup", "name": "Zero", "radius_m": 0.0, "probability": 1.0},
        "geometry": {"type": "Point", "coordinates": [lon + 0.001, lat]}
    }));
    let zero = dir.file("zero.geojson");
    std::fs::write(&zero, serde_json::to_string(&s).unwrap()).unwrap();
    refused(
        &["plan", net, "--scenario", &zero, "-o", &out],
        &out,
        1,
        &[
            &zero,
            "(Zero): properties.radius_m: 0 is out of range: expected a positive number",
        ],
    );
}

#[test]
fn render_refuses_a_geojson_file_as_a_route_by_what_it_is() {
    let dir = TempDir::new("route-geojson");
    let svg = dir.file("x.svg");
    refused(
        &[
            "render",
            niendorf_network(),
            "--route",
            &niendorf(),
            "-o",
            &svg,
        ],
        &svg,
        1,
        &[
            &niendorf(),
            "a GeoJSON FeatureCollection",
            "not a route file",
        ],
    );
}

/// Every build option that one mode only uses is refused, by name, on a scenario of another
/// mode, even at its default value; nothing is written.
#[test]
fn a_mode_only_build_option_on_another_mode_is_refused() {
    let dir = TempDir::new("mode-options");
    let out = dir.file("n.bin");
    let roadmap = niendorf();
    let terrain = scenario("medeiros-jacksboro.geojson");
    let landmark = scenario("babel-II-N.geojson");
    let cases: [(&str, &[&str], &str, &str); 9] = [
        (
            &roadmap,
            &["--landmark-ranges", "ground"],
            "--landmark-ranges",
            "landmark",
        ),
        (&roadmap, &["--max-edge", "5000"], "--max-edge", "terrain"),
        (
            &roadmap,
            &["--node-spacing", "0"],
            "--node-spacing",
            "terrain",
        ),
        (
            &roadmap,
            &["--node-margin", "1"],
            "--node-margin",
            "terrain",
        ),
        (
            &landmark,
            &["--altitude-levels", "700"],
            "--altitude-levels",
            "terrain",
        ),
        (
            &terrain,
            &["--sample-spacing", "50"],
            "--sample-spacing",
            "roadmap",
        ),
        (
            &terrain,
            &["--neighbour-radius", "192"],
            "--neighbour-radius",
            "roadmap",
        ),
        (
            &terrain,
            &["--discretised=added"],
            "--discretised",
            "roadmap",
        ),
        (&landmark, &["--discretised"], "--discretised", "roadmap"),
    ];
    for (sc, option, name, applies_to) in cases {
        let mode = if sc == roadmap {
            "roadmap"
        } else if sc == terrain {
            "terrain"
        } else {
            "landmark"
        };
        let mut args = vec!["build", sc];
        args.extend(option);
        args.extend(["-o", &out]);
        let applies = format!("{name} applies to {applies_to} networks");
        let is = format!("this is a {mode} scenario");
        refused(&args, &out, 1, &[&applies, &is]);
    }
}

#[test]
fn a_landmark_only_build_option_on_another_mode_is_refused() {
    let dir = TempDir::new("landmark-ranges");
    let out = dir.file("n.bin");
    refused(
        &[
            "build",
            &niendorf(),
            "--landmark-ranges",
            "onboard",
            "-o",
            &out,
        ],
        &out,
        1,
        &[
            "niendorf-urban.geojson",
            "--landmark-ranges applies to landmark networks",
            "roadmap",
        ],
    );
    // A bad value is a usage error (exit code 2), naming the values it takes.
    let o = skyroute(&[
        "build",
        &niendorf(),
        "--landmark-ranges",
        "everything",
        "-o",
        &out,
    ]);
    assert_eq!(code(&o), 2);
    assert!(
        stderr(&o).contains("expected ground or onboard"),
        "{}",
        stderr(&o)
    );
}
