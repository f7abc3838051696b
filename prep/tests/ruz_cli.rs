//! Pop-ups under uncertainty (Ruz et al.) end to end on ruz-popups: `plan --popup-appears`
//! records the alternatives and the choice and flies it, unknown names and unmeetable limits
//! are refused by name; every alternative stays out of its pop-up's disc (f64 distances of
//! densely sampled lines and arcs); the decision on the real alternatives equals a brute force.

mod common;

use common::{code, ok, scenario, skyroute, stderr, stdout, TempDir};
use serde_json::Value;
use skyroute::planner::decision::{decide, Alternative, DecisionLimits};
use skyroute::Primitive;
use skyroute_prep::ruz::alternatives::{plan_study, Planning};
use skyroute_prep::ruz::cli::{decision_inputs, LIMITS};
use skyroute_prep::ruz::stored::study;

/// The least f64 distance from `c` to the primitive, sampled every metre.
fn distance(p: &Primitive, c: (f64, f64)) -> f64 {
    let n = (p.length() as f64).ceil().max(1.0) as usize;
    (0..=n)
        .map(|i| {
            let (x, y) = match p {
                Primitive::Line(l) => {
                    let t = i as f64 / n as f64;
                    (
                        l.start.x as f64 + t * (l.end.x - l.start.x) as f64,
                        l.start.y as f64 + t * (l.end.y - l.start.y) as f64,
                    )
                }
                Primitive::Arc(a) => {
                    let ang = a.start_angle as f64 + a.sweep as f64 * i as f64 / n as f64;
                    (
                        a.centre.x as f64 + a.radius as f64 * ang.cos(),
                        a.centre.y as f64 + a.radius as f64 * ang.sin(),
                    )
                }
            };
            (x - c.0).hypot(y - c.1)
        })
        .fold(f64::INFINITY, f64::min)
}

#[test]
fn ruz_popups_decides_flies_and_refuses_by_name() {
    let dir = TempDir::new("ruz-cli");
    let (net, out) = (dir.file("n.bin"), dir.file("r.json"));
    let ruz = scenario("ruz-popups.geojson");
    ok(skyroute(&["build", &ruz, "-o", &net]), "build");
    let plan = ok(
        skyroute(&[
            "plan",
            &net,
            "--scenario",
            &ruz,
            "--popup-appears",
            "U2",
            "--popup-appears",
            "U3",
            "--time-limit",
            "0.35",
            "--fuel-limit",
            "0.40",
            "-o",
            &out,
        ]),
        "plan --popup-appears",
    );
    let text = stdout(&plan);
    assert!(text.contains("chose alternative"), "{text}");
    assert!(text.contains("as stored in the network image"), "{text}");
    let info = stdout(&ok(skyroute(&["info", &net]), "info"));
    assert!(
        info.contains("pop-up alternatives (Ruz et al.): 3 pop-ups"),
        "{info}"
    );
    let r: Value = serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
    let d = &r["decision"];
    assert_eq!(d["popups"].as_array().unwrap().len(), 2);
    for p in d["popups"].as_array().unwrap() {
        assert_eq!(p["alternatives"].as_array().unwrap().len(), 3, "{p}");
        assert!(p["chosen"].as_u64().unwrap() < 3);
    }
    assert!(d["mean_time_factor"].as_f64().unwrap() <= 0.35);
    assert_eq!(r["popups_appeared"], serde_json::json!(["U2", "U3"]));
    assert!(r["legs"].as_array().is_some_and(|l| !l.is_empty()));

    let unknown = skyroute(&[
        "plan",
        &net,
        "--scenario",
        &ruz,
        "--popup-appears",
        "U9",
        "-o",
        &out,
    ]);
    assert_eq!(code(&unknown), 1);
    assert!(
        stderr(&unknown).contains("no popup feature named \"U9\""),
        "{}",
        stderr(&unknown)
    );
    let tight = skyroute(&[
        "plan",
        &net,
        "--scenario",
        &ruz,
        "--popup-appears",
        "U2",
        "--time-limit",
        "0.0",
        "--fuel-limit",
        "0.0",
        "-o",
        &out,
    ]);
    assert_eq!(code(&tight), 3, "{}", stderr(&tight));
    assert!(
        stderr(&tight).contains("the tightest is the"),
        "{}",
        stderr(&tight)
    );
}

#[test]
fn alternatives_stay_out_of_their_discs_and_the_decision_is_the_brute_force_optimum() {
    with_ruz_popups("ruz-alternatives", |planning, _| {
        check_discs_and_decision(planning)
    });
}

/// Builds ruz-popups with `skyroute build` and runs `f` on the image and its planning inputs.
fn with_ruz_popups(tag: &str, f: impl FnOnce(&Planning, &skyroute::Network)) {
    let dir = TempDir::new(tag);
    let net = dir.file("n.bin");
    let ruz = scenario("ruz-popups.geojson");
    ok(skyroute(&["build", &ruz, "-o", &net]), "build");
    let bytes = std::fs::read(&net).unwrap();
    let s = skyroute_prep::scenario::load(std::path::Path::new(&ruz)).unwrap();
    let network = skyroute::Network::from_bytes(&bytes).unwrap();
    let frame = skyroute_prep::export::network_frame(&network);
    let planning = Planning {
        bytes: &bytes,
        scenario: &s,
        frame: &frame,
        options: skyroute_prep::ruz::alternatives_options(),
    };
    f(&planning, &network);
}

fn check_discs_and_decision(planning: &Planning) {
    let params = skyroute_prep::ruz::risk_params(planning.scenario);
    let st = study(planning, &params, &[0, 1, 2]).unwrap();
    for p in &st.popups {
        assert_eq!(p.alternatives.len(), 3, "pop-up {}", p.name);
        let c = (p.centre.x as f64, p.centre.y as f64);
        for (k, a) in p.alternatives.iter().enumerate() {
            let least = a
                .route
                .iter()
                .map(|q| distance(q, c))
                .fold(f64::INFINITY, f64::min);
            assert!(
                least >= p.radius_m as f64,
                "pop-up {} alternative {}: {least} m from the centre",
                p.name,
                k + 1
            );
        }
    }
    let inputs: Vec<Vec<Alternative>> = st.popups.iter().map(|p| decision_inputs(&st, p)).collect();
    for limits in [
        LIMITS,
        DecisionLimits {
            time_max: 0.008,
            fuel_max: 0.006,
        },
    ] {
        let slices: Vec<&[Alternative]> = inputs.iter().map(Vec::as_slice).collect();
        let got = decide(&slices, &limits);
        let mut best: Option<(f64, [usize; 3])> = None;
        for i in 0..27 {
            let c = [i % 3, i / 3 % 3, i / 9];
            let a: Vec<Alternative> = (0..3).map(|u| inputs[u][c[u]]).collect();
            let (r, t, f) = a.iter().fold((0.0f64, 0.0f64, 0.0f64), |s, x| {
                (
                    s.0 + x.risk as f64,
                    s.1 + x.time as f64,
                    s.2 + x.fuel as f64,
                )
            });
            let feasible = t / 3.0 <= limits.time_max as f64 * (1.0 + 1e-6) + 1e-6
                && f / 3.0 <= limits.fuel_max as f64 * (1.0 + 1e-6) + 1e-6;
            if feasible && best.is_none_or(|b| r < b.0 - 1e-7) {
                best = Some((r, c));
            }
        }
        match (got, best) {
            (Ok(d), Some((r, _))) => assert!(
                (d.risk as f64 - r).abs() < 1e-5,
                "limits {limits:?}: {} against the brute force's {r}",
                d.risk
            ),
            (Err(_), None) => {}
            (g, b) => panic!("limits {limits:?}: decision {g:?}, brute force {b:?}"),
        }
    }
}

#[test]
fn the_stored_alternatives_are_those_planned_from_the_scenario() {
    with_ruz_popups("ruz-stored", check_stored);
}

fn check_stored(planning: &Planning, network: &skyroute::Network) {
    let params = skyroute_prep::ruz::risk_params(planning.scenario);
    let fresh = plan_study(planning, &params, &[0, 1, 2]).unwrap();
    let stored = network.alternatives_summary().unwrap();
    assert_eq!(stored.popups, 3);
    assert_eq!(stored.nominal_steps, fresh.nominal.figures.steps);
    assert_eq!(
        (stored.time_limit, stored.fuel_limit),
        (LIMITS.time_max, LIMITS.fuel_max)
    );
    for (u, p) in (0u32..).zip(&fresh.popups) {
        let sp = network.stored_popup(u).unwrap();
        assert_eq!((sp.centre, sp.radius), (p.centre, p.radius_m), "{}", p.name);
        assert_eq!(sp.probability, p.probability as f32);
        assert_eq!(sp.alternatives as usize, p.alternatives.len(), "{}", p.name);
        for (k, a) in (0u32..).zip(&p.alternatives) {
            let g = network.stored_alternative(u, k).unwrap();
            let what = format!("{} alternative {}", p.name, k + 1);
            assert_eq!(g.steps, a.figures.steps, "{what}");
            assert_eq!(
                g.survival_known.to_bits(),
                a.figures.survival_known.to_bits(),
                "{what}"
            );
            assert_eq!(
                g.survival_popup.to_bits(),
                a.figures.survival_popup.to_bits(),
                "{what}"
            );
            assert_eq!(g.fuel.to_bits(), a.figures.fuel.to_bits(), "{what}");
            assert_eq!(g.length_m, a.length_m as f32, "{what}");
            let discs: Vec<(skyroute::Vec2, f32)> = (0..g.discs)
                .filter_map(|j| network.blocking_disc(&g, j))
                .collect();
            let planned: Vec<(skyroute::Vec2, f32)> = a
                .discs
                .iter()
                .skip(1)
                .map(|d| (d.centre, d.radius))
                .collect();
            assert_eq!(discs, planned, "{what}");
        }
    }
    // The study read back from the image flies the same routes.
    let read = study(planning, &params, &[0, 1, 2]).unwrap();
    for (p, q) in read.popups.iter().zip(&fresh.popups) {
        for (a, b) in p.alternatives.iter().zip(&q.alternatives) {
            assert_eq!(a.length_m, b.length_m, "{}", p.name);
        }
    }
}
