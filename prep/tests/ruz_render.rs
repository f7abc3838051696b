//! `render` of a route that flies a decision among pop-up bypass alternatives (`plan
//! --popup-appears` on ruz-popups): the nominal route, every alternative and the chosen ones
//! drawn, the legend listing each alternative's risk, time and fuel with the choice marked, and
//! the pop-up discs labelled with their appearance probability.

mod common;

use common::{ok, scenario, skyroute, TempDir};
use serde_json::Value;

#[test]
fn a_decided_route_renders_its_alternatives_and_their_legend() {
    let dir = TempDir::new("ruz-render");
    let (net, route, svg) = (dir.file("n.bin"), dir.file("r.json"), dir.file("d.svg"));
    let ruz = scenario("ruz-popups.geojson");
    ok(skyroute(&["build", &ruz, "-o", &net]), "build");
    let mut plan = vec!["plan", &net, "--scenario", &ruz];
    for u in ["U1", "U2", "U3"] {
        plan.extend(["--popup-appears", u]);
    }
    plan.extend(["-o", &route]);
    ok(skyroute(&plan), "plan --popup-appears");
    ok(
        skyroute(&[
            "render",
            &net,
            "--route",
            &route,
            "--scenario",
            &ruz,
            "--no-edges",
            "-o",
            &svg,
        ]),
        "render",
    );
    let r: Value = serde_json::from_str(&std::fs::read_to_string(&route).unwrap()).unwrap();
    let text = std::fs::read_to_string(&svg).unwrap();
    let popups = r["decision"]["popups"].as_array().unwrap();
    let total: usize = popups
        .iter()
        .map(|p| p["alternatives"].as_array().unwrap().len())
        .sum();
    assert_eq!(total, 9);
    assert_eq!(
        text.matches(r#"class="alternative"#).count(),
        total,
        "every alternative drawn once"
    );
    assert_eq!(
        text.matches(r#"class="alternative chosen""#).count(),
        3,
        "one chosen per pop-up"
    );
    assert_eq!(text.matches(r#"class="nominal""#).count(), 1);
    for (name, p) in [("U1", "0.5"), ("U2", "0.2"), ("U3", "0.8")] {
        assert!(
            text.contains(&format!("{name}, P_A {p} (3000 m)")),
            "{name}'s disc label"
        );
        assert!(
            text.contains(&format!("{name} (P_A {p})")),
            "{name}'s legend"
        );
    }
    // Each alternative's legend line: its length, risk, time and fuel factors; the chosen ones
    // marked.
    for p in popups {
        let chosen = p["chosen"].as_u64().unwrap() as usize;
        for (k, a) in p["alternatives"].as_array().unwrap().iter().enumerate() {
            let line = format!(
                "{}: {:.2} km, {:.4}, {:.3}, {:.3}{}",
                k + 1,
                a["length_m"].as_f64().unwrap() / 1000.0,
                a["risk"].as_f64().unwrap(),
                a["time_factor"].as_f64().unwrap(),
                a["fuel_factor"].as_f64().unwrap(),
                if k == chosen { "  chosen" } else { "" }
            );
            assert!(
                text.contains(&line),
                "legend line {line:?} of {}",
                p["name"]
            );
        }
    }
    assert_eq!(text.matches("  chosen<").count(), 3);
    assert!(text.contains("choice: Σ R_K "), "the decision's total");
}
