//! `skyroute build/plan/info` in Voronoi mode, end to end through the binary: a roadmap
//! scenario taken as a Voronoi one with `--mode voronoi`, the same `--mode` needed to plan with
//! it, `--threat-weight` and `--threat`, the route file's pieces and exposure figures, the
//! GeoJSON route, and refusals that name what is wrong.

mod common;

use common::{code, ok, scenario, skyroute, stderr, stdout, TempDir};
use serde_json::Value;

fn route(path: &str) -> Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

#[test]
fn ruz_popups_builds_and_plans_as_a_voronoi_network() {
    let dir = TempDir::new("voronoi-cli");
    let (net, r5, r1, rt, geo) = (
        dir.file("v.bin"),
        dir.file("k05.json"),
        dir.file("k1.json"),
        dir.file("threat.json"),
        dir.file("k05.geojson"),
    );
    let ruz = scenario("ruz-popups.geojson");
    let built = ok(
        skyroute(&["build", &ruz, "--mode", "voronoi", "-o", &net]),
        "build --mode voronoi",
    );
    assert!(stdout(&built).contains("Voronoi graph of 12 threats"));
    let info = ok(skyroute(&["info", &net]), "info");
    assert!(stdout(&info).contains("voronoi network"));
    assert!(stdout(&info).contains("12 threat sites"));

    // Without --mode the scenario is a roadmap scenario: refused, naming the mode.
    let refused = skyroute(&["plan", &net, "--scenario", &ruz, "-o", &r5]);
    assert_eq!(code(&refused), 1);
    assert!(
        stderr(&refused).contains("planner.mode"),
        "{}",
        stderr(&refused)
    );

    let plan = |k: &str, out: &str, extra: &[&str]| {
        let mut args = vec![
            "plan",
            &net,
            "--scenario",
            &ruz,
            "--mode",
            "voronoi",
            "--threat-weight",
            k,
            "-o",
            out,
        ];
        args.extend_from_slice(extra);
        ok(skyroute(&args), "plan --mode voronoi")
    };
    plan("0.5", &r5, &[]);
    plan("1", &r1, &[]);
    let (a, b) = (route(&r5), route(&r1));
    assert_eq!(a["mode"], "voronoi");
    assert_eq!(a["threat_weight"].as_f64(), Some(0.5));
    let leg = &a["legs"][0];
    assert!(leg["pieces"]
        .as_array()
        .unwrap()
        .iter()
        .any(|p| p["type"] == "cubic"));
    assert!(!leg["primitives"].as_array().unwrap().is_empty());
    assert!(leg["chord_deviation_m"].as_f64().unwrap() <= 2.0 + 1e-6);
    // A lower weight never flies more exposed or shorter (the coarse optimum's trade-off).
    let (ea, eb) = (
        a["exposure_coarse_three_point"].as_f64().unwrap(),
        b["exposure_coarse_three_point"].as_f64().unwrap(),
    );
    assert!(
        ea <= eb * (1.0 + 1e-4),
        "k 0.5 exposure {ea} above k 1's {eb}"
    );

    // A radar pops up in flight near the k = 0.5 route's middle: it is in the route file.
    let coarse = leg["coarse"].as_array().unwrap();
    let mid = &coarse[coarse.len() / 2];
    // Pulled a tenth towards the origin: the route may run along the box's border.
    let (x, y) = (
        0.9 * mid[0].as_f64().unwrap(),
        0.9 * mid[1].as_f64().unwrap(),
    );
    let (lat0, lon0) = (
        a["frame"]["origin_lat_deg"].as_f64().unwrap(),
        a["frame"]["origin_lon_deg"].as_f64().unwrap(),
    );
    let lon = lon0 + x / (111_320.0 * lat0.to_radians().cos());
    let lat = lat0 + y / 111_132.0;
    let at = format!("{lon},{lat},3000");
    plan("0.5", &rt, &["--threat", &at]);
    let t = route(&rt);
    let threats = t["threats"].as_array().unwrap();
    assert_eq!(threats.len(), 13);
    assert!(threats.iter().any(|t| t["origin"] == "in flight 0"));

    // The GeoJSON route of a Voronoi plan.
    plan("0.5", &geo, &[]);
    let g = route(&geo);
    assert_eq!(g["type"], "FeatureCollection");
}

#[test]
fn voronoi_options_are_refused_where_they_do_not_apply() {
    let dir = TempDir::new("voronoi-cli-refusals");
    let (net, out) = (dir.file("t.bin"), dir.file("r.json"));
    let urban = scenario("niendorf-urban.geojson");
    ok(skyroute(&["build", &urban, "-o", &net]), "build");
    let o = skyroute(&[
        "plan",
        &net,
        "--scenario",
        &urban,
        "--threat",
        "11.6,48.1,100",
        "-o",
        &out,
    ]);
    assert_eq!(code(&o), 1);
    assert!(stderr(&o).contains("voronoi"), "{}", stderr(&o));
    let o = skyroute(&[
        "plan",
        &net,
        "--scenario",
        &urban,
        "--threat-weight",
        "2",
        "-o",
        &out,
    ]);
    assert_eq!(code(&o), 2, "a weight outside [0, 1] is a usage error");
    let o = skyroute(&["build", &urban, "--mode", "radar", "-o", &net]);
    assert_eq!(code(&o), 2);
}
