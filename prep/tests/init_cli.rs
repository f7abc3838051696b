//! `skyroute init`: every mode's template builds and plans as written; an existing file is
//! kept unless `--force`; terrain without `--dem` is refused by name.

mod common;

use common::{code, ok, one_line_error, scenario, skyroute, TempDir};

#[test]
fn every_template_builds_and_plans_as_written() {
    let dir = TempDir::new("init");
    let dem = scenario("jacksboro-dem.asc");
    for mode in ["roadmap", "landmark", "voronoi", "terrain"] {
        let (sc, net, route) = (
            dir.file(&format!("{mode}.geojson")),
            dir.file(&format!("{mode}.bin")),
            dir.file(&format!("{mode}.geojson.route.json")),
        );
        let mut args = vec!["init", &sc, "--mode", mode];
        if mode == "terrain" {
            args.extend(["--dem", &dem]);
        }
        ok(skyroute(&args), "init");
        let text = std::fs::read_to_string(&sc).unwrap();
        let v: serde_json::Value = serde_json::from_str(&text).unwrap();
        assert_eq!(v["planner"]["mode"], mode);
        assert!(v["comments"].as_array().is_some_and(|c| c.len() >= 3));
        ok(skyroute(&["build", &sc, "-o", &net]), "build");
        let mut plan = vec!["plan", &net, "--scenario", &sc, "-o", &route];
        if mode == "landmark" {
            plan.extend(["--weather", "nominal"]);
        }
        ok(skyroute(&plan), "plan");
    }
}

#[test]
fn an_existing_file_is_kept_unless_forced() {
    let dir = TempDir::new("init-force");
    let sc = dir.file("s.geojson");
    std::fs::write(&sc, "mine").unwrap();
    let o = skyroute(&["init", &sc]);
    assert_eq!(code(&o), 1);
    let e = one_line_error(&o);
    assert!(e.contains("s.geojson: exists; pass --force"), "{e}");
    assert_eq!(std::fs::read_to_string(&sc).unwrap(), "mine");
    ok(skyroute(&["init", &sc, "--force"]), "init --force");
    assert!(std::fs::read_to_string(&sc)
        .unwrap()
        .contains("FeatureCollection"));
}

#[test]
fn terrain_needs_a_dem_and_a_bad_dem_is_named() {
    let dir = TempDir::new("init-terrain");
    let sc = dir.file("t.geojson");
    let e = one_line_error(&skyroute(&["init", &sc, "--mode", "terrain"]));
    assert!(e.contains("--mode terrain needs --dem"), "{e}");
    let bad = dir.file("bad.asc");
    std::fs::write(&bad, "ncols 2\n").unwrap();
    let e = one_line_error(&skyroute(&[
        "init", &sc, "--mode", "terrain", "--dem", &bad,
    ]));
    assert!(e.contains("bad.asc: line 2: nrows: missing"), "{e}");
    assert!(!std::path::Path::new(&sc).exists());
}
