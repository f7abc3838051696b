//! `skyroute plan` never ignores its scenario: a network is bound to the scenario it was built
//! from, the scenario's pop-ups are applied, anything off the network's map is refused by name,
//! connections widen (or say why they fail), and exit codes and outputs are honest.

mod common;

use common::{code, niendorf, ok, scenario, skyroute, stderr, stdout, TempDir};
use serde_json::{json, Value};
use std::path::Path;
use std::sync::OnceLock;

/// The niendorf-urban network, built once for the tests of this file.
fn niendorf_network() -> &'static Path {
    static NET: OnceLock<(TempDir, String)> = OnceLock::new();
    let (_, path) = NET.get_or_init(|| {
        let dir = TempDir::new("plan-checks-net");
        let net = dir.file("niendorf.bin");
        ok(skyroute(&["build", &niendorf(), "-o", &net]), "build");
        (dir, net)
    });
    Path::new(path)
}

fn read_json(path: &str) -> Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

fn write_json(path: &str, v: &Value) {
    std::fs::write(path, serde_json::to_string_pretty(v).unwrap()).unwrap();
}

/// A square no-fly zone or pop-up ring of half-side `d` degrees around `(lon, lat)`.
/// medeiros-jacksboro's scenario with its DEM copied into `dir` (so a test may change either):
/// the DEM's path and the scenario pointing at it.
fn jacksboro_in(dir: &TempDir) -> (String, Value) {
    let dem = dir.file("dem.asc");
    std::fs::copy(scenario("jacksboro-dem.asc"), &dem).unwrap();
    let mut s = read_json(&scenario("medeiros-jacksboro.geojson"));
    s["terrain"]["dem"] = json!(dem);
    (dem, s)
}

/// medeiros-jacksboro flown at `altitude_m`, written to `dir` and built: (scenario, network).
fn jacksboro_built_at(dir: &TempDir, altitude_m: f64) -> (String, String) {
    let (_, mut s) = jacksboro_in(dir);
    s["terrain"]["altitude_m"] = json!(altitude_m);
    let sc = dir.file("jb.geojson");
    write_json(&sc, &s);
    let net = dir.file("jb.bin");
    ok(
        skyroute(&["build", &sc, "-o", &net]),
        &format!("build terrain at {altitude_m} m"),
    );
    (sc, net)
}

fn square(lon: f64, lat: f64, d: f64) -> Value {
    json!([[
        [lon - d, lat - d],
        [lon + d, lat - d],
        [lon + d, lat + d],
        [lon - d, lat + d],
        [lon - d, lat - d]
    ]])
}

/// Plans and expects a failure with `exit` whose message has every one of `parts`; checks that
/// the output was not written.
fn refused(args: &[&str], out: &str, exit: i32, parts: &[&str]) -> String {
    let o = skyroute(args);
    let e = stderr(&o);
    assert_eq!(code(&o), exit, "{args:?}: {e}{}", stdout(&o));
    for part in parts {
        assert!(e.contains(part), "{args:?}: {e:?} lacks {part:?}");
    }
    assert!(!Path::new(out).exists(), "{args:?} wrote {out}");
    e
}

#[test]
fn a_zone_added_after_the_build_is_refused_by_name() {
    let dir = TempDir::new("added-zone");
    let mut s = read_json(&niendorf());
    // Between W3 and W4, across the leg the planned route flies.
    let (lon, lat) = (
        (11.63885173 + 11.61329868) / 2.0,
        (48.105141 + 48.08286679) / 2.0,
    );
    s["features"].as_array_mut().unwrap().push(json!({
        "type": "Feature",
        "properties": {"kind": "no_fly", "name": "NEW"},
        "geometry": {"type": "Polygon", "coordinates": square(lon, lat, 0.0015)}
    }));
    let changed = dir.file("added.geojson");
    write_json(&changed, &s);
    let net = niendorf_network().display().to_string();
    let out = dir.file("route.json");
    refused(
        &["plan", &net, "--scenario", &changed, "-o", &out],
        &out,
        1,
        &["added.geojson", "no-fly zone \"NEW\"", "skyroute build"],
    );
    // The same for render, whose closest-approach figures would otherwise miss the zone.
    let svg = dir.file("x.svg");
    refused(
        &["render", &net, "--scenario", &changed, "-o", &svg],
        &svg,
        1,
        &["no-fly zone \"NEW\""],
    );
}

#[test]
fn a_network_of_a_thinned_scenario_does_not_plan_the_full_one() {
    let dir = TempDir::new("thinned");
    let mut s = read_json(&niendorf());
    let mut zones = 0;
    s["features"].as_array_mut().unwrap().retain(|f| {
        if f["properties"]["kind"] != "no_fly" {
            return true;
        }
        zones += 1;
        zones <= 10
    });
    let thin = dir.file("thin.geojson");
    write_json(&thin, &s);
    let thin_net = dir.file("thin.bin");
    ok(skyroute(&["build", &thin, "-o", &thin_net]), "build thin");
    let out = dir.file("route.json");
    refused(
        &["plan", &thin_net, "--scenario", &niendorf(), "-o", &out],
        &out,
        1,
        &["no-fly zone \"B11\"", "and 44 more", "added or changed"],
    );
    // And the other way round: zones of the build that the scenario lost.
    let net = niendorf_network().display().to_string();
    refused(
        &["plan", &net, "--scenario", &thin, "-o", &out],
        &out,
        1,
        &["50 no-fly zones of the build are not in the scenario"],
    );
}

#[test]
fn single_values_that_changed_are_named_and_reformatting_changes_nothing() {
    let dir = TempDir::new("changed-values");
    let net = niendorf_network().display().to_string();
    let out = dir.file("route.json");
    let base = read_json(&niendorf());
    for (field, change) in [
        (
            "planner.clearance_m",
            json!({"planner": {"clearance_m": 3.5}}),
        ),
        ("vehicle", json!({"vehicle": {"a_lat_max_mps2": 12.0}})),
        ("planner.mode", json!({"planner": {"mode": "terrain"}})),
    ] {
        let mut s = base.clone();
        for (section, values) in change.as_object().unwrap() {
            for (k, v) in values.as_object().unwrap() {
                s[section][k] = v.clone();
            }
        }
        if field == "planner.mode" {
            s["terrain"] = json!({"dem": scenario("jacksboro-dem.asc"),
                                  "altitude_m": 750, "safety_height_m": 100});
        }
        let path = dir.file("changed.geojson");
        write_json(&path, &s);
        refused(
            &["plan", &net, "--scenario", &path, "-o", &out],
            &out,
            1,
            &[field],
        );
    }
    // Whitespace and key order are not part of any digest.
    let same = dir.file("same.geojson");
    std::fs::write(&same, serde_json::to_string(&base).unwrap()).unwrap();
    ok(
        skyroute(&["plan", &net, "--scenario", &same, "-o", &out]),
        "plan reformatted",
    );
}

#[test]
fn a_changed_dem_is_refused_and_a_terrain_scenario_with_zones_is_not_built() {
    let dir = TempDir::new("dem");
    let (dem, mut s) = jacksboro_in(&dir);
    let sc = dir.file("terrain.geojson");
    write_json(&sc, &s);
    let net = dir.file("terrain.bin");
    ok(skyroute(&["build", &sc, "-o", &net]), "build terrain");
    let out = dir.file("route.json");
    ok(
        skyroute(&["plan", &net, "--scenario", &sc, "-o", &out]),
        "plan terrain",
    );
    std::fs::remove_file(&out).unwrap();
    // Either turn rule by name; anything else is refused before planning.
    ok(
        skyroute(&[
            "plan",
            &net,
            "--scenario",
            &sc,
            "--turn-rule",
            "shared-equally",
            "-o",
            &out,
        ]),
        "plan terrain with the equal split",
    );
    std::fs::remove_file(&out).unwrap();
    refused(
        &[
            "plan",
            &net,
            "--scenario",
            &sc,
            "--turn-rule",
            "half",
            "-o",
            &out,
        ],
        &out,
        2,
        &["expected paper or shared-equally"],
    );
    // One elevation raised by a metre, far down the file.
    let text = std::fs::read_to_string(&dem).unwrap();
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    let row = lines.len() - 10;
    let mut cells: Vec<String> = lines[row].split_whitespace().map(str::to_string).collect();
    let v: f64 = cells[5].parse().unwrap();
    cells[5] = format!("{}", v + 1.0);
    lines[row] = cells.join(" ");
    std::fs::write(&dem, lines.join("\n") + "\n").unwrap();
    refused(
        &["plan", &net, "--scenario", &sc, "-o", &out],
        &out,
        1,
        &["terrain (DEM \"dem.asc\"", "differs from the build's"],
    );

    // A terrain network would fly straight through a no-fly zone, so the build refuses it.
    s["features"].as_array_mut().unwrap().push(json!({
        "type": "Feature",
        "properties": {"kind": "no_fly", "name": "Tower"},
        "geometry": {"type": "Polygon", "coordinates": square(-98.2, 33.2, 0.01)}
    }));
    write_json(&sc, &s);
    let net2 = dir.file("terrain2.bin");
    refused(
        &["build", &sc, "-o", &net2],
        &net2,
        1,
        &[
            "no-fly zone \"Tower\"",
            "terrain networks hold no no-fly zones",
        ],
    );
}

/// Smallest distance from the route file's polyline to `(x, y)`, metres (local frame).
fn route_distance_to(route: &Value, x: f64, y: f64) -> f64 {
    let mut best = f64::INFINITY;
    for leg in route["legs"].as_array().unwrap() {
        for p in leg["primitives"].as_array().unwrap() {
            let prim = skyroute_prep::render::primitive_from_json(p).unwrap();
            let n = (prim.length() / 1.0).ceil().max(1.0) as usize;
            for k in 0..=n {
                let q = prim.pose_at(prim.length() * k as f32 / n as f32).position;
                best = best.min((q.x as f64 - x).hypot(q.y as f64 - y));
            }
        }
    }
    best
}

#[test]
fn scenario_popups_are_applied_and_recorded() {
    let dir = TempDir::new("scenario-popups");
    let net = niendorf_network().display().to_string();
    let (nominal, avoided) = (dir.file("nominal.json"), dir.file("avoided.json"));
    ok(
        skyroute(&["plan", &net, "--scenario", &niendorf(), "-o", &nominal]),
        "plan nominal",
    );
    // A pop-up on the middle of the nominal route's W3 -> W4 leg.
    let route = read_json(&nominal);
    let leg = route["legs"]
        .as_array()
        .unwrap()
        .iter()
        .find(|l| l["from"] == "W3")
        .unwrap();
    let prims = leg["primitives"].as_array().unwrap();
    let mid = skyroute_prep::render::primitive_from_json(&prims[prims.len() / 2]).unwrap();
    let c = mid.pose_at(mid.length() / 2.0).position;
    let (x, y) = (c.x as f64, c.y as f64);
    let frame = skyroute_prep::frame::LocalFrame::new(
        route["frame"]["origin_lat_deg"].as_f64().unwrap(),
        route["frame"]["origin_lon_deg"].as_f64().unwrap(),
    );
    let (lon, lat) = frame.to_geo(x, y);
    let radius = 60.0;
    let mut s = read_json(&niendorf());
    s["features"].as_array_mut().unwrap().push(json!({
        "type": "Feature",
        "properties": {"kind": "popup", "name": "U9", "radius_m": radius, "probability": 0.7},
        "geometry": {"type": "Point", "coordinates": [lon, lat]}
    }));
    let with_popup = dir.file("with-popup.geojson");
    write_json(&with_popup, &s);
    let o = ok(
        skyroute(&["plan", &net, "--scenario", &with_popup, "-o", &avoided]),
        "plan with the pop-up",
    );
    assert!(stdout(&o).contains("pop-up \"U9\""), "{}", stdout(&o));
    let r = read_json(&avoided);
    let clearance = 7.0;
    let d = route_distance_to(&r, x, y);
    assert!(
        d >= radius + clearance - 0.5,
        "the route passes {d:.1} m from U9"
    );
    assert_eq!(r["popups"][0]["name"], "pop-up \"U9\"");
    assert_eq!(r["popups"][0]["source"], "scenario");
    assert_eq!(r["popups"][0]["probability"], 0.7);
    assert_eq!(r["scenario_popups_applied"], true);
    // Left out on request, the route flies through it again, and the file says so.
    ok(
        skyroute(&[
            "plan",
            &net,
            "--scenario",
            &with_popup,
            "--no-scenario-popups",
            "-o",
            &nominal,
        ]),
        "plan without scenario pop-ups",
    );
    let r = read_json(&nominal);
    assert!(route_distance_to(&r, x, y) < 1.0);
    assert_eq!(r["scenario_popups_applied"], false);
    assert_eq!(r["popups"].as_array().unwrap().len(), 0);
}

#[test]
fn anything_off_the_map_is_refused_by_name() {
    let dir = TempDir::new("off-map");
    let net = niendorf_network().display().to_string();
    let out = dir.file("route.json");
    // Latitude and longitude swapped.
    let e = refused(
        &[
            "plan",
            &net,
            "--scenario",
            &niendorf(),
            "--popup",
            "48.09,11.62,100",
            "-o",
            &out,
        ],
        &out,
        1,
        &["--popup #1", "outside the network's extent", "swapped"],
    );
    assert_eq!(e.lines().count(), 1, "{e}");
    // A goal 20 km east of the map.
    let mut s = read_json(&niendorf());
    for f in s["features"].as_array_mut().unwrap() {
        if f["properties"]["kind"] == "goal" {
            f["geometry"]["coordinates"][0] = json!(11.92);
        }
    }
    let far = dir.file("far.geojson");
    write_json(&far, &s);
    refused(
        &["plan", &net, "--scenario", &far, "-o", &out],
        &out,
        1,
        &["goal \"Q\"", "outside the network's extent"],
    );
}

/// A terrain network's map is its elevation grid: flown at 1 000 m over Jacksboro, few cells
/// are blocked, so the nodes (and the pop-up index built round them) cover a corner of the DEM
/// that leaves Q 2.7 km outside, yet the goal lies on the DEM and the core connects to it.
#[test]
fn a_terrain_goal_on_the_dem_but_far_from_every_node_is_planned() {
    let dir = TempDir::new("terrain-high");
    let (sc, net) = jacksboro_built_at(&dir, 1000.0);
    let out = dir.file("route.json");
    ok(
        skyroute(&["plan", &net, "--scenario", &sc, "-o", &out]),
        "plan terrain at 1000 m",
    );
    let route = read_json(&out);
    let length = route["length_m"].as_f64().unwrap();
    // P and Q are about 21 km apart (great circle): nearly straight at this altitude.
    assert!((20_000.0..30_000.0).contains(&length), "{length}");
    std::fs::remove_file(&out).unwrap();
    // A goal off the DEM is still refused by name.
    let mut s = read_json(&sc);
    for f in s["features"].as_array_mut().unwrap() {
        if f["properties"]["kind"] == "goal" {
            f["geometry"]["coordinates"][0] = json!(-83.0);
        }
    }
    let far = dir.file("far.geojson");
    write_json(&far, &s);
    refused(
        &["plan", &net, "--scenario", &far, "-o", &out],
        &out,
        1,
        &["goal \"Q\"", "outside the network's extent"],
    );
}

/// The default terrain network joins every visible pair of nodes; `--max-edge` keeps a subset
/// of its edges on the same nodes, so the exact search plans P → Q no shorter on it. Each plan
/// reports its turn-arc checks against the elevation grid, within the stated bound.
#[test]
fn a_terrain_network_of_every_pair_plans_no_longer_than_one_with_a_longest_edge() {
    let dir = TempDir::new("terrain-max-edge");
    let (_, s) = jacksboro_in(&dir);
    let sc = dir.file("jb.geojson");
    write_json(&sc, &s);
    let mut planned = Vec::new();
    for (name, extra) in [
        ("every.bin", vec![]),
        ("10km.bin", vec!["--max-edge", "10000"]),
    ] {
        let net = dir.file(name);
        let mut args = vec!["build", sc.as_str(), "-o", net.as_str()];
        args.extend(extra);
        let built = stdout(&ok(skyroute(&args), "build terrain"));
        let out = dir.file("route.json");
        let o = ok(
            skyroute(&[
                "plan",
                &net,
                "--scenario",
                &sc,
                "--turn-rule",
                "shared-equally",
                "-o",
                &out,
            ]),
            "plan terrain",
        );
        let text = stdout(&o);
        let line = text
            .lines()
            .find(|l| l.contains("turn arcs checked against the elevation grid"))
            .unwrap_or_else(|| panic!("no turn-arc line in {text}"));
        let numbers: Vec<f64> = line
            .split(|c: char| !(c.is_ascii_digit() || c == '.'))
            .filter_map(|w| w.parse().ok())
            .collect();
        let [arcs, cells, mean, most, bound] = numbers[..] else {
            panic!("{line}")
        };
        assert!(arcs > 0.0 && cells >= arcs, "{line}");
        assert!((mean - cells / arcs).abs() < 0.06, "{line}");
        assert!(most >= mean && most <= bound, "{line}");
        let route = read_json(&out);
        planned.push((
            route["legs"][0]["planned_length_m"].as_f64().unwrap(),
            built,
        ));
    }
    let (every, limited) = (&planned[0], &planned[1]);
    assert!(every.0 <= limited.0 + 0.01, "{every:?} against {limited:?}");
    assert!(every.1.contains("1760 nodes") && limited.1.contains("1760 nodes"));
    // "terrain graph N nodes, E edges": the default tries the pairs beyond 10 km too.
    let edges = |summary: &str| -> u64 {
        let after = summary.split(" nodes, ").nth(1).expect("a node count");
        after.split(' ').next().unwrap().parse().unwrap()
    };
    assert!(
        edges(&every.1) > edges(&limited.1),
        "{every:?} against {limited:?}"
    );
}

#[test]
fn ruz_popups_plans_and_a_fixed_radius_says_why_it_cannot() {
    let dir = TempDir::new("ruz");
    let (net, out) = (dir.file("ruz.bin"), dir.file("route.json"));
    let sc = scenario("ruz-popups.geojson");
    ok(skyroute(&["build", &sc, "-o", &net]), "build ruz-popups");
    let o = ok(
        skyroute(&["plan", &net, "--scenario", &sc, "-o", &out]),
        "plan ruz-popups",
    );
    assert!(
        stdout(&o).contains("connected beyond the network's radius"),
        "{}",
        stdout(&o)
    );
    let r = read_json(&out);
    let names: Vec<&str> = r["popups"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| p["name"].as_str().unwrap())
        .collect();
    assert_eq!(names, ["pop-up \"U1\"", "pop-up \"U2\"", "pop-up \"U3\""]);
    for p in r["popups"].as_array().unwrap() {
        let c = p["centre"].as_array().unwrap();
        let (x, y) = (c[0].as_f64().unwrap(), c[1].as_f64().unwrap());
        let d = route_distance_to(&r, x, y);
        let needed = p["radius_m"].as_f64().unwrap() + 50.0;
        assert!(d >= needed - 0.5, "{}: {d:.0} m", p["name"]);
    }
    std::fs::remove_file(&out).unwrap();
    refused(
        &[
            "plan",
            &net,
            "--scenario",
            &sc,
            "--connect-radius",
            "1000",
            "-o",
            &out,
        ],
        &out,
        3,
        &[
            "no route from P to Q",
            "within --connect-radius 1000 m",
            "the nearest is 1422 m away",
        ],
    );
}

#[test]
fn exit_codes_and_outputs_are_honest() {
    let dir = TempDir::new("exit-codes");
    let net = niendorf_network().display().to_string();
    // Usage: clap's exit code 2.
    let o = skyroute(&["plan", &net, "--no-such-flag"]);
    assert_eq!(code(&o), 2, "{}", stderr(&o));
    let o = skyroute(&["plan", "--help"]);
    for part in ["Exit codes:", "3  no route exists", "--connect-radius"] {
        assert!(stdout(&o).contains(part), "plan --help lacks {part:?}");
    }
    // An output naming an input is refused, and the input is left as it was.
    let before = std::fs::read(&net).unwrap();
    let o = skyroute(&["plan", &net, "--scenario", &niendorf(), "-o", &net]);
    assert_eq!(code(&o), 1);
    assert!(
        stderr(&o).contains("would overwrite the input"),
        "{}",
        stderr(&o)
    );
    assert_eq!(std::fs::read(&net).unwrap(), before);
    let o = skyroute(&["export", &net, "-o", &net]);
    assert_eq!(code(&o), 1);
    assert_eq!(std::fs::read(&net).unwrap(), before);
    // A failed plan leaves an existing output untouched and no temporary file behind.
    let out = dir.file("route.json");
    std::fs::write(&out, b"old route").unwrap();
    let o = skyroute(&[
        "plan",
        &net,
        "--scenario",
        &niendorf(),
        "--popup",
        "48.09,11.62,100",
        "-o",
        &out,
    ]);
    assert_eq!(code(&o), 1);
    assert_eq!(std::fs::read(&out).unwrap(), b"old route");
    let files: Vec<_> = std::fs::read_dir(&dir.0)
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(files.len(), 1, "{files:?}");
}

#[test]
fn landmark_networks_export_their_chains_and_prove_an_impossible_weather() {
    let dir = TempDir::new("landmark");
    let mut s = read_json(&scenario("landmark-figure4.geojson"));
    // A third weather in which every landmark is barely visible (q = 0.1 everywhere).
    s["weather"].as_array_mut().unwrap().push(json!("fog"));
    for f in s["features"].as_array_mut().unwrap() {
        if f["properties"]["kind"] == "landmark" {
            f["properties"]["quality"]["fog"] = json!(vec![0.1; 12]);
        }
    }
    let sc = dir.file("figure4-fog.geojson");
    write_json(&sc, &s);
    let (net, json_out, out) = (dir.file("f4.bin"), dir.file("f4.json"), dir.file("r.json"));
    ok(skyroute(&["build", &sc, "-o", &net]), "build figure 4");

    let o = ok(skyroute(&["export", &net, "-o", &json_out]), "export");
    let v = read_json(&json_out);
    let bytes = std::fs::read(&net).unwrap();
    let n = skyroute::Network::from_bytes(&bytes).unwrap();
    let edges = v["edges"].as_array().unwrap();
    assert_eq!(edges.len(), n.edge_count() as usize);
    assert!(stdout(&o).contains(&format!("{} edges", n.edge_count())));
    for e in edges {
        assert_eq!(e["word"], "hermite_chain");
        let pieces = e["pieces"].as_array().unwrap();
        assert!(!pieces.is_empty(), "{e}");
        let sum: f64 = pieces.iter().map(|p| p["length"].as_f64().unwrap()).sum();
        let length = e["length"].as_f64().unwrap();
        assert!(
            (sum - length).abs() <= 1e-3 * length + 0.1,
            "{sum} vs {length}"
        );
    }

    ok(
        skyroute(&[
            "plan",
            &net,
            "--scenario",
            &sc,
            "--weather",
            "haze",
            "-o",
            &out,
        ]),
        "plan in haze",
    );
    std::fs::remove_file(&out).unwrap();
    let e = refused(
        &[
            "plan",
            &net,
            "--scenario",
            &sc,
            "--weather",
            "fog",
            "-o",
            &out,
        ],
        &out,
        3,
        &[
            "in weather fog",
            "no route can exist",
            "straight legs within range",
        ],
    );
    assert_eq!(e.lines().count(), 1, "{e}");
    // A weather the scenario does not have: bad input, named with the ones it has.
    refused(
        &[
            "plan",
            &net,
            "--scenario",
            &sc,
            "--weather",
            "hurricane",
            "-o",
            &out,
        ],
        &out,
        1,
        &[
            "weather \"hurricane\" is not one of the scenario's",
            "\"haze\"",
        ],
    );
}

#[test]
fn the_best_chain_of_shortcuts_is_the_default_and_the_greedy_pass_an_option() {
    let dir = TempDir::new("terrain-shortcuts");
    // At 850 m the greedy pass keeps most of the searched route's detours (docs/PAPERS.md).
    let (sc, net) = jacksboro_built_at(&dir, 850.0);
    let out = dir.file("route.json");
    let mut routes = Vec::new();
    for extra in [
        &[][..],
        &["--shortcuts", "greedy"],
        &["--shortcuts", "best"],
    ] {
        let mut args = vec![
            "plan",
            net.as_str(),
            "--scenario",
            sc.as_str(),
            "-o",
            out.as_str(),
        ];
        args.extend(extra);
        ok(skyroute(&args), "plan terrain");
        let route = read_json(&out);
        routes.push((
            route["length_m"].as_f64().unwrap(),
            route["legs"][0]["planned_length_m"].as_f64().unwrap(),
        ));
    }
    let (default, greedy, best) = (routes[0], routes[1], routes[2]);
    assert_eq!(default, best, "best is the default");
    assert_eq!(default.1, greedy.1, "the same searched route");
    assert!(
        default.0 < 0.8 * greedy.0,
        "best chain {default:?}, greedy {greedy:?}"
    );
    std::fs::remove_file(&out).unwrap();
    refused(
        &[
            "plan",
            &net,
            "--scenario",
            &sc,
            "--shortcuts",
            "sideways",
            "-o",
            &out,
        ],
        &out,
        2,
        &["--shortcuts", "expected best or greedy"],
    );
}
