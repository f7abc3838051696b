//! The pop-up alternatives section (Ruz et al.) and the onboard switch: random tables read back
//! as written; each out-of-domain record refused by name; `decide_stored` against a brute force
//! over every combination, its figures from the closed forms R_K = 1 − P_S,known·((1 − P_A) +
//! P_A·P_S,PU) and f_t = 1 − τ/T; `fly_alternatives` adds exactly the chosen discs, the next
//! route keeps clear of them (f64 distances), and a switch that does not fit adds nothing.

use host_tests::damage::fix_crc;
use host_tests::reference::route_distance;
use host_tests::rng::Rng;
use host_tests::world::world;
use skyroute::network::format::{
    AlternativesRecord, DiscRecord, PopupRecord, FLAG_POPUP_ALTERNATIVES, MAX_BLOCKING_DISCS,
    MAX_STORED_ALTERNATIVES, MAX_STORED_POPUPS,
};
use skyroute::network::write::{
    encode_with_alternatives, AlternativeSpec, AlternativesSpec, NetworkSpec, PopupSpec, WriteError,
};
use skyroute::network::{Parameter, Section};
use skyroute::planner::alternatives::{decide_stored, Announced, SwitchError};
use skyroute::planner::decision::{DecisionError, DecisionLimits};
use skyroute::planner::{PlanStep, PopupError};
use skyroute::{Goal, LoadError, Network, Planner, Popup, Pose, Query, Search, Vec2};

/// A random table over a `size` × `size` world: 1 to 8 pop-ups of 1 to 4 alternatives of 0 to
/// 8 blocking discs, every figure in its domain.
fn random_table(rng: &mut Rng, size: f32) -> AlternativesSpec {
    let disc = |rng: &mut Rng| {
        (
            Vec2::new(rng.range_f32(0.0, size), rng.range_f32(0.0, size)),
            rng.range_f32(1.0, 0.05 * size),
        )
    };
    let popups = (0..1 + rng.below(MAX_STORED_POPUPS as u64))
        .map(|_| {
            let (centre, radius) = disc(rng);
            PopupSpec {
                centre,
                radius,
                probability: rng.unit_f32(),
                alternatives: (0..1 + rng.below(MAX_STORED_ALTERNATIVES as u64))
                    .map(|_| AlternativeSpec {
                        steps: 1 + rng.below(2000) as u32,
                        survival_known: rng.unit_f32(),
                        survival_popup: rng.unit_f32(),
                        fuel: rng.unit_f32(),
                        length_m: rng.range_f32(1.0, 1e5),
                        discs: (0..rng.below(MAX_BLOCKING_DISCS as u64 + 1))
                            .map(|_| disc(rng))
                            .collect(),
                    })
                    .collect(),
            }
        })
        .collect();
    AlternativesSpec {
        nominal_steps: 1 + rng.below(2000) as u32,
        time_limit: rng.unit_f32(),
        fuel_limit: rng.unit_f32(),
        popups,
    }
}

fn base() -> NetworkSpec {
    world(11, 1200.0, 80.0, 40.0, 2).spec
}

#[test]
fn random_tables_read_back_as_written() {
    let spec = base();
    let plain = skyroute::network::write::encode(&spec).unwrap();
    let net = Network::from_bytes(&plain).unwrap();
    assert_eq!(net.alternatives_summary(), None);
    assert_eq!(net.stored_popup(0), None);
    let mut rng = Rng(5);
    for case in 0..host_tests::cases(20, 200) {
        let table = random_table(&mut rng, 1200.0);
        let bytes = encode_with_alternatives(&spec, &table).unwrap();
        let net = Network::from_bytes(&bytes).unwrap();
        assert_eq!(net.header().flags, FLAG_POPUP_ALTERNATIVES);
        let s = net.alternatives_summary().unwrap();
        assert_eq!(s.popups as usize, table.popups.len(), "case {case}");
        assert_eq!(s.nominal_steps, table.nominal_steps);
        assert_eq!(s.time_limit.to_bits(), table.time_limit.to_bits());
        assert_eq!(s.fuel_limit.to_bits(), table.fuel_limit.to_bits());
        assert_eq!(net.stored_popup(s.popups), None);
        for (u, p) in (0u32..).zip(&table.popups) {
            let got = net.stored_popup(u).unwrap();
            assert_eq!((got.centre, got.radius), (p.centre, p.radius));
            assert_eq!(got.probability.to_bits(), p.probability.to_bits());
            assert_eq!(got.alternatives as usize, p.alternatives.len());
            assert_eq!(net.stored_alternative(u, got.alternatives), None);
            for (k, a) in (0u32..).zip(&p.alternatives) {
                let g = net.stored_alternative(u, k).unwrap();
                assert_eq!(g.steps, a.steps, "case {case} pop-up {u} alternative {k}");
                assert_eq!(g.survival_known.to_bits(), a.survival_known.to_bits());
                assert_eq!(g.survival_popup.to_bits(), a.survival_popup.to_bits());
                assert_eq!(g.fuel.to_bits(), a.fuel.to_bits());
                assert_eq!(g.length_m.to_bits(), a.length_m.to_bits());
                let discs: Vec<(Vec2, f32)> = (0..=g.discs)
                    .filter_map(|j| net.blocking_disc(&g, j))
                    .collect();
                assert_eq!(discs, a.discs, "case {case} pop-up {u} alternative {k}");
            }
        }
    }
}

/// One alternative of one pop-up, in the domain.
fn one() -> AlternativesSpec {
    AlternativesSpec {
        nominal_steps: 100,
        time_limit: 0.35,
        fuel_limit: 0.4,
        popups: vec![PopupSpec {
            centre: Vec2::new(600.0, 600.0),
            radius: 50.0,
            probability: 0.5,
            alternatives: vec![AlternativeSpec {
                steps: 110,
                survival_known: 0.9,
                survival_popup: 0.8,
                fuel: 0.1,
                length_m: 5500.0,
                discs: vec![(Vec2::new(500.0, 500.0), 30.0)],
            }],
        }],
    }
}

fn refused(table: &AlternativesSpec) -> LoadError {
    match encode_with_alternatives(&base(), table) {
        Err(WriteError::Invalid(e)) => e,
        other => panic!("{table:?} was not refused by the loader: {other:?}"),
    }
}

#[test]
fn each_out_of_domain_record_is_refused_by_name() {
    let bad_parameter = LoadError::InvalidParameter {
        parameter: Parameter::PopupAlternatives,
    };
    let bad = |section, index| LoadError::BadPopupAlternatives { section, index };
    type Edit = fn(&mut AlternativesSpec);
    let cases: Vec<(&str, Edit, LoadError)> = vec![
        ("no pop-ups", |t| t.popups.clear(), bad_parameter),
        (
            "nine pop-ups",
            |t| t.popups = vec![t.popups[0].clone(); 9],
            bad_parameter,
        ),
        ("no nominal steps", |t| t.nominal_steps = 0, bad_parameter),
        ("NaN time limit", |t| t.time_limit = f32::NAN, bad_parameter),
        ("huge fuel limit", |t| t.fuel_limit = 1e7, bad_parameter),
        (
            "probability 1.5",
            |t| t.popups[0].probability = 1.5,
            bad(Section::StoredPopups, 0),
        ),
        (
            "pop-up radius 0",
            |t| t.popups[0].radius = 0.0,
            bad(Section::StoredPopups, 0),
        ),
        (
            "pop-up centre NaN",
            |t| t.popups[0].centre.x = f32::NAN,
            bad(Section::StoredPopups, 0),
        ),
        (
            "no alternatives",
            |t| t.popups[0].alternatives.clear(),
            bad(Section::StoredPopups, 0),
        ),
        (
            "five alternatives",
            |t| t.popups[0].alternatives = vec![t.popups[0].alternatives[0].clone(); 5],
            bad(Section::StoredPopups, 0),
        ),
        (
            "no steps",
            |t| t.popups[0].alternatives[0].steps = 0,
            bad(Section::StoredAlternatives, 0),
        ),
        (
            "survival above 1",
            |t| t.popups[0].alternatives[0].survival_known = 1.01,
            bad(Section::StoredAlternatives, 0),
        ),
        (
            "NaN pop-up survival",
            |t| t.popups[0].alternatives[0].survival_popup = f32::NAN,
            bad(Section::StoredAlternatives, 0),
        ),
        (
            "negative fuel",
            |t| t.popups[0].alternatives[0].fuel = -0.1,
            bad(Section::StoredAlternatives, 0),
        ),
        (
            "zero length",
            |t| t.popups[0].alternatives[0].length_m = 0.0,
            bad(Section::StoredAlternatives, 0),
        ),
        (
            "nine blocking discs",
            |t| {
                let d = t.popups[0].alternatives[0].discs[0];
                t.popups[0].alternatives[0].discs = vec![d; 9];
            },
            bad(Section::StoredAlternatives, 0),
        ),
        (
            "disc radius negative",
            |t| t.popups[0].alternatives[0].discs[0].1 = -1.0,
            bad(Section::BlockingDiscs, 0),
        ),
        (
            "disc beyond the coordinate limit",
            |t| t.popups[0].alternatives[0].discs[0].0.x = 2e7,
            bad(Section::BlockingDiscs, 0),
        ),
    ];
    for (what, edit, want) in cases {
        let mut t = one();
        edit(&mut t);
        assert_eq!(refused(&t), want, "{what}");
    }
}

#[test]
fn flags_and_counts_that_disagree_are_refused() {
    let spec = base();
    let good = encode_with_alternatives(&spec, &one()).unwrap();
    // The section closes the body (the world has no provenance records).
    let section = AlternativesRecord::SIZE + PopupRecord::SIZE + 24 + DiscRecord::SIZE;
    let start = good.len() - section;
    let flags_at = 7;
    // An undefined flag bit (bit 1 is the vertical section's).
    let mut b = good.clone();
    b[flags_at] |= 4;
    fix_crc(&mut b);
    assert_eq!(
        Network::from_bytes(&b).unwrap_err(),
        LoadError::InvalidParameter {
            parameter: Parameter::Flags
        }
    );
    // The flag without its section: the record is read past the end.
    let mut b = skyroute::network::write::encode(&spec).unwrap();
    b[flags_at] = FLAG_POPUP_ALTERNATIVES;
    fix_crc(&mut b);
    assert!(matches!(
        Network::from_bytes(&b),
        Err(LoadError::Truncated { .. })
    ));
    // The pop-up claims two alternatives where the record counts one.
    let mut b = good.clone();
    let count_at = start + AlternativesRecord::SIZE + 16;
    b[count_at] = 2;
    fix_crc(&mut b);
    assert_eq!(
        Network::from_bytes(&b).unwrap_err(),
        LoadError::BadPopupAlternatives {
            section: Section::PopupAlternatives,
            index: 0
        }
    );
}

/// The figures of alternative `a` for appearance probability `p`, by the closed forms: R_K,
/// f_t against `nominal` steps, F_c.
fn closed_form(a: &AlternativeSpec, nominal: u32, p: f32) -> (f64, f64, f64) {
    let (pk, pu, p) = (a.survival_known as f64, a.survival_popup as f64, p as f64);
    let risk = 1.0 - pk * ((1.0 - p) + p * pu);
    let time = 1.0 - nominal as f64 / a.steps as f64;
    (risk, time, a.fuel as f64)
}

/// The least total risk over every choice within the limits (means over the announced), or
/// `None`; choices within `margin` of a limit make the instance ambiguous (`Err`).
fn brute_force(
    table: &AlternativesSpec,
    announced: &[Announced],
    limits: &DecisionLimits,
) -> Result<Option<f64>, ()> {
    let mut sums = vec![(0.0f64, 0.0f64, 0.0f64)];
    for a in announced {
        let p = &table.popups[a.popup as usize];
        sums = sums
            .iter()
            .flat_map(|s| {
                p.alternatives.iter().map(move |x| {
                    let f = closed_form(x, table.nominal_steps, a.appearance);
                    (s.0 + f.0, s.1 + f.1, s.2 + f.2)
                })
            })
            .collect();
    }
    let n = announced.len().max(1) as f64;
    let margin = 1e-5;
    let mut best: Option<f64> = None;
    for (r, t, f) in sums {
        let (t, f) = (t / n, f / n);
        let near = (t - limits.time_max as f64).abs() < margin
            || (f - limits.fuel_max as f64).abs() < margin;
        if near && !announced.is_empty() {
            return Err(());
        }
        if t <= limits.time_max as f64 && f <= limits.fuel_max as f64 {
            best = Some(best.map_or(r, |b: f64| b.min(r)));
        }
    }
    Ok(if announced.is_empty() {
        Some(0.0)
    } else {
        best
    })
}

#[test]
fn decide_stored_is_the_brute_force_optimum() {
    let spec = base();
    let mut rng = Rng(17);
    let (mut checked, mut infeasible) = (0, 0);
    for case in 0..host_tests::cases(300, 3000) {
        let table = random_table(&mut rng, 1200.0);
        let bytes = encode_with_alternatives(&spec, &table).unwrap();
        let net = Network::from_bytes(&bytes).unwrap();
        // A random subset of the pop-ups in a random order, random P_A.
        let mut order: Vec<u8> = (0..table.popups.len() as u8).collect();
        for i in (1..order.len()).rev() {
            order.swap(i, rng.below(i as u64 + 1) as usize);
        }
        order.truncate(rng.below(order.len() as u64 + 1) as usize);
        let announced: Vec<Announced> = order
            .iter()
            .map(|&popup| Announced {
                popup,
                appearance: rng.unit_f32(),
            })
            .collect();
        let limits = DecisionLimits {
            time_max: rng.range_f32(-0.5, 1.0),
            fuel_max: rng.range_f32(0.0, 1.0),
        };
        let Ok(want) = brute_force(&table, &announced, &limits) else {
            continue;
        };
        checked += 1;
        match (decide_stored(&net, &announced, &limits), want) {
            (Ok(d), Some(r)) => {
                assert!(
                    (d.risk as f64 - r).abs() < 1e-4,
                    "case {case}: risk {} against the brute force's {r}",
                    d.risk
                );
                assert_eq!(d.choice.len(), announced.len());
            }
            (Err(SwitchError::Decision(DecisionError::Infeasible { .. })), None) => infeasible += 1,
            (got, want) => panic!("case {case}: {got:?}, brute force {want:?}"),
        }
    }
    assert!(
        checked > 100 && infeasible > 5,
        "{checked} checked, {infeasible} infeasible"
    );
}

#[test]
fn bad_announcements_and_choices_are_refused_by_name() {
    let spec = base();
    let plain = skyroute::network::write::encode(&spec).unwrap();
    let limits = DecisionLimits {
        time_max: 0.35,
        fuel_max: 0.4,
    };
    let a = |popup| Announced {
        popup,
        appearance: 0.5,
    };
    let net = Network::from_bytes(&plain).unwrap();
    assert_eq!(
        decide_stored(&net, &[a(0)], &limits),
        Err(SwitchError::NoAlternatives)
    );
    let bytes = encode_with_alternatives(&spec, &one()).unwrap();
    let net = Network::from_bytes(&bytes).unwrap();
    assert_eq!(
        decide_stored(&net, &[a(1)], &limits),
        Err(SwitchError::UnknownPopup { popup: 1 })
    );
    assert_eq!(
        decide_stored(&net, &[a(0), a(0)], &limits),
        Err(SwitchError::UnknownPopup { popup: 0 })
    );
    assert_eq!(
        decide_stored(&net, &[a(0); 9], &limits),
        Err(SwitchError::TooManyPopups { count: 9 })
    );
    let mut p: Box<Planner<'_, 4096, 16384, 4, 128>> = Box::new(Planner::new());
    p.load(&bytes).unwrap();
    assert_eq!(
        p.fly_alternatives(&[a(0)], &[1]),
        Err(SwitchError::BadChoice)
    );
    assert_eq!(
        p.fly_alternatives(&[a(0)], &[]),
        Err(SwitchError::BadChoice)
    );
    assert_eq!(p.popups().count(), 0);
}

#[test]
fn fly_alternatives_adds_the_chosen_discs_and_the_route_keeps_clear() {
    let w = world(23, 2000.0, 70.0, 40.0, 0);
    // Two pop-ups across the middle; the second alternative of each blocks one side.
    let popup = |x: f32, y: f32| PopupSpec {
        centre: Vec2::new(x, y),
        radius: 120.0,
        probability: 0.5,
        alternatives: vec![
            AlternativeSpec {
                steps: 100,
                survival_known: 0.9,
                survival_popup: 0.9,
                fuel: 0.1,
                length_m: 2000.0,
                discs: vec![],
            },
            AlternativeSpec {
                steps: 105,
                survival_known: 0.9,
                survival_popup: 0.95,
                fuel: 0.1,
                length_m: 2100.0,
                discs: vec![
                    (Vec2::new(x, y + 250.0), 100.0),
                    (Vec2::new(x, y + 420.0), 80.0),
                ],
            },
        ],
    };
    let table = AlternativesSpec {
        nominal_steps: 100,
        time_limit: 0.35,
        fuel_limit: 0.4,
        popups: vec![popup(700.0, 1000.0), popup(1300.0, 1000.0)],
    };
    let bytes = encode_with_alternatives(&w.spec, &table).unwrap();
    let mut p: Box<Planner<'_, 4096, 16384, 16, 256>> = Box::new(Planner::new());
    p.load(&bytes).unwrap();
    let announced = [
        Announced {
            popup: 1,
            appearance: 1.0,
        },
        Announced {
            popup: 0,
            appearance: 0.2,
        },
    ];
    let ids = p.fly_alternatives(&announced, &[1, 0]).unwrap();
    // Pop-up 1's disc and its two blocking discs, then pop-up 0's disc.
    let want = [
        (Vec2::new(1300.0, 1000.0), 120.0),
        (Vec2::new(1300.0, 1250.0), 100.0),
        (Vec2::new(1300.0, 1420.0), 80.0),
        (Vec2::new(700.0, 1000.0), 120.0),
    ];
    let got: Vec<(Vec2, f32)> = ids
        .iter()
        .map(|&id| {
            let (_, popup) = p.popups().find(|(i, _)| *i == id).unwrap();
            match popup {
                Popup::Circle { centre, radius } => (*centre, *radius),
                Popup::Polygon(_) => panic!("a polygon"),
            }
        })
        .collect();
    assert_eq!(got, want);
    let query = Query {
        start: Pose::new(100.0, 1000.0, 0.0),
        goal: Goal {
            position: Vec2::new(1900.0, 1000.0),
            heading: Some(0.0),
        },
        search: Search::Dijkstra,
    };
    p.plan(&query, u64::MAX).unwrap();
    // A switch in flight cancels a query in progress (its network state changes under it).
    p.start_plan(&query, u64::MAX).unwrap();
    assert!(matches!(p.step(1), PlanStep::InProgress { .. }));
    let more = p.fly_alternatives(&announced[1..], &[1]).unwrap();
    assert!(!p.is_planning());
    assert_eq!(p.step(u64::MAX), PlanStep::Idle);
    for id in more {
        p.remove_popup(id).unwrap();
    }
    p.plan(&query, u64::MAX).unwrap();
    let clearance = w.spec.clearance_m as f64;
    for (centre, radius) in want {
        let d = route_distance(p.route(), centre);
        assert!(
            d >= radius as f64 + clearance - 0.05,
            "the route passes {d} m from the disc at {centre:?} of radius {radius}"
        );
    }
    for id in ids {
        p.remove_popup(id).unwrap();
    }
    assert_eq!(p.popups().count(), 0);
}

#[test]
fn a_switch_that_does_not_fit_adds_nothing() {
    let w = world(29, 1500.0, 80.0, 40.0, 0);
    let mut table = one();
    table.popups[0].centre = Vec2::new(750.0, 750.0);
    let d = (Vec2::new(600.0, 900.0), 40.0);
    table.popups[0].alternatives[0].discs = vec![d; 4];
    let bytes = encode_with_alternatives(&w.spec, &table).unwrap();
    // Four slots: one taken, the switch needs five.
    let mut p: Box<Planner<'_, 4096, 16384, 4, 128>> = Box::new(Planner::new());
    p.load(&bytes).unwrap();
    let mine = p
        .add_popup(Popup::Circle {
            centre: Vec2::new(200.0, 200.0),
            radius: 30.0,
        })
        .unwrap();
    let blocked_before: Vec<bool> = (0..p.network().edge_count())
        .map(|e| p.is_edge_enabled(e))
        .collect();
    let announced = [Announced {
        popup: 0,
        appearance: 0.5,
    }];
    assert_eq!(
        p.fly_alternatives(&announced, &[0]),
        Err(SwitchError::Popup(PopupError::NoFreeSlot { capacity: 4 }))
    );
    let ids: Vec<u8> = p.popups().map(|(id, _)| id).collect();
    assert_eq!(ids, vec![mine.id]);
    let blocked_after: Vec<bool> = (0..p.network().edge_count())
        .map(|e| p.is_edge_enabled(e))
        .collect();
    assert_eq!(blocked_before, blocked_after);
}
