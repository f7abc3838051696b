//! Voronoi pictures and the ground roadmap planner under the exposure cost, end to end: a
//! Voronoi network rendered with two routes (SVG and PNG), and `plan --threat-weight` on a
//! roadmap network lowering the exposure below the shortest route's.

mod common;

use common::{ok, scenario, skyroute, stdout, TempDir};
use serde_json::Value;

fn json(path: &str) -> Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

#[test]
fn voronoi_network_with_two_routes_renders_threats_heat_map_and_legends() {
    let dir = TempDir::new("voronoi-render");
    let ruz = scenario("ruz-popups.geojson");
    let net = dir.file("v.bin");
    ok(
        skyroute(&["build", &ruz, "--mode", "voronoi", "-o", &net]),
        "build",
    );
    let mut routes = Vec::new();
    for (k, extra) in [("0.1", None), ("1", Some("12.05,48.2,2500"))] {
        let out = dir.file(&format!("r{k}.json"));
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
            &out,
        ];
        if let Some(t) = extra {
            args.extend(["--threat", t]);
        }
        ok(skyroute(&args), "plan");
        routes.push(out);
    }
    let (svg, png) = (dir.file("v.svg"), dir.file("v.png"));
    let o = ok(
        skyroute(&[
            "render",
            &net,
            "--route",
            &routes[0],
            "--route",
            &routes[1],
            "--scenario",
            &ruz,
            "--mode",
            "voronoi",
            "-o",
            &svg,
            "--png",
            &png,
            "--width",
            "600",
        ]),
        "render",
    );
    assert!(stdout(&o).contains("rendered"), "{}", stdout(&o));
    let text = std::fs::read_to_string(&svg).unwrap();
    // The 12 network threats and the pop-up one, each with its dashed circle.
    assert_eq!(text.matches(r#"<circle class="threat""#).count(), 13);
    assert!(text.contains("radar threat popped up in flight"));
    assert!(text.contains("exposure per metre flown"));
    let legends: Vec<&str> = text
        .lines()
        .filter(|l| l.contains(r#"class="route-legend""#))
        .collect();
    assert_eq!(legends.len(), 2, "{legends:?}");
    for (l, k) in legends.iter().zip(["k = 0.10", "k = 1.00"]) {
        assert!(
            l.contains(k) && l.contains("length") && l.contains("exposure"),
            "{l}"
        );
    }
    // Both routes' coarse polylines, dashed.
    assert_eq!(text.matches(r#"class="coarse""#).count(), 2);
    let bytes = std::fs::read(&png).unwrap();
    assert_eq!(&bytes[1..4], b"PNG");
}

#[test]
fn ground_roadmap_planner_lowers_exposure_below_the_shortest_route() {
    let dir = TempDir::new("roadmap-exposure");
    let ruz = scenario("ruz-popups.geojson");
    let net = dir.file("r.bin");
    ok(skyroute(&["build", &ruz, "-o", &net]), "build");
    let mut figures = Vec::new();
    for k in ["1", "0.1"] {
        let out = dir.file(&format!("r{k}.json"));
        let o = ok(
            skyroute(&[
                "plan",
                &net,
                "--scenario",
                &ruz,
                "--threat-weight",
                k,
                "-o",
                &out,
            ]),
            "plan",
        );
        assert!(stdout(&o).contains("on the ground"), "{}", stdout(&o));
        let r = json(&out);
        assert_eq!(r["mode"], "roadmap");
        figures.push((
            r["length_m"].as_f64().unwrap(),
            r["exposure_flown"].as_f64().unwrap(),
        ));
    }
    let ((l1, e1), (l01, e01)) = (figures[0], figures[1]);
    assert!(e01 < 0.5 * e1, "exposure k = 0.1: {e01}, k = 1: {e1}");
    assert!(l01 > l1, "length k = 0.1: {l01}, k = 1: {l1}");
    // --threat stays a Voronoi option.
    let o = skyroute(&[
        "plan",
        &net,
        "--scenario",
        &ruz,
        "--threat",
        "12.0,48.2,1000",
        "-o",
        &dir.file("x.json"),
    ]);
    assert_eq!(o.status.code(), Some(1));
}
