//! The pop-up decision (`skyroute::planner::decision`, Ruz et al. eqs 33–36) against a brute
//! force over every combination: the same least risk on random instances, infeasible exactly
//! when no combination meets both limits (with the tightest limit named as the brute force
//! finds it), the work within its bound and equal to the node count of the documented pruning
//! rule (a recursion written here), ties settled by the first choice in lexicographic order,
//! bad input refused by name.

use host_tests::rng::Rng;
use skyroute::planner::decision::{
    decide, decision_budget, decision_work_bound, Alternative, DecisionError, DecisionLimits,
    Limit, MAX_ALTERNATIVES, MAX_DECISION_POPUPS, MAX_FACTOR,
};

/// Every combination: `(risk, mean time, mean fuel, choice)`, in lexicographic order.
fn combinations(alts: &[Vec<Alternative>]) -> Vec<(f64, f64, f64, Vec<u8>)> {
    let mut out = vec![(0.0, 0.0, 0.0, Vec::new())];
    for a in alts {
        let mut next = Vec::new();
        for (r, t, f, c) in &out {
            for (k, x) in a.iter().enumerate() {
                let mut c2 = c.clone();
                c2.push(k as u8);
                next.push((r + x.risk as f64, t + x.time as f64, f + x.fuel as f64, c2));
            }
        }
        out = next;
    }
    let n = alts.len().max(1) as f64;
    out.into_iter()
        .map(|(r, t, f, c)| (r, t / n, f / n, c))
        .collect()
}

fn random_instance(rng: &mut Rng) -> (Vec<Vec<Alternative>>, DecisionLimits) {
    let n = rng.below(MAX_DECISION_POPUPS as u64 + 1) as usize;
    // Coarse values make ties and limits met exactly common: risks in tenths from 0 to 1,
    // factors and limits from −0.3 to 1. A negative factor (an alternative faster than the
    // nominal route has a negative time factor) and a negative limit test the tightest limit's
    // relative relaxation across signs.
    let q = |rng: &mut Rng| (rng.below(11) as f32) / 10.0;
    let signed = |rng: &mut Rng| (rng.below(14) as f32 - 3.0) / 10.0;
    let alts = (0..n)
        .map(|_| {
            (0..1 + rng.below(MAX_ALTERNATIVES as u64) as usize)
                .map(|_| Alternative {
                    risk: q(rng),
                    time: signed(rng),
                    fuel: signed(rng),
                })
                .collect()
        })
        .collect();
    let limits = DecisionLimits {
        time_max: signed(rng),
        fuel_max: signed(rng),
    };
    (alts, limits)
}

#[test]
fn the_decision_is_the_brute_force_optimum() {
    let mut rng = Rng(33);
    let (mut feasible, mut infeasible) = (0, 0);
    for case in 0..host_tests::cases(3000, 30000) {
        let (alts, limits) = random_instance(&mut rng);
        let slices: Vec<&[Alternative]> = alts.iter().map(|a| a.as_slice()).collect();
        let all = combinations(&alts);
        let tol = 1e-5;
        // No pop-ups: the empty choice, whatever the limits (a mean over none constrains nothing).
        let meets = |t: f64, f: f64| {
            alts.is_empty()
                || (t <= limits.time_max as f64 + tol && f <= limits.fuel_max as f64 + tol)
        };
        let best = all
            .iter()
            .filter(|(_, t, f, _)| meets(*t, *f))
            .map(|(r, ..)| *r)
            .fold(f64::INFINITY, f64::min);
        let counts: Vec<usize> = alts.iter().map(Vec::len).collect();
        match decide(&slices, &limits) {
            Ok(d) => {
                feasible += 1;
                assert!(
                    (d.risk as f64 - best).abs() <= 1e-5,
                    "case {case}: risk {} but the brute force finds {best}",
                    d.risk
                );
                let (r, t, f, _) = all.iter().find(|(.., c)| c[..] == d.choice[..]).unwrap();
                assert!(
                    (r - d.risk as f64).abs() <= 1e-5 && meets(*t, *f),
                    "case {case}"
                );
                assert!(
                    (d.mean_time as f64 - t).abs() <= 1e-5
                        && (d.mean_fuel as f64 - f).abs() <= 1e-5,
                    "case {case}: means {} and {}, the choice's {t} and {f}",
                    d.mean_time,
                    d.mean_fuel
                );
                assert!(d.work <= decision_work_bound(&counts), "case {case}");
            }
            Err(DecisionError::Infeasible { limit, least, max }) => {
                infeasible += 1;
                assert!(
                    best.is_infinite(),
                    "case {case}: infeasible, but {best} meets both"
                );
                // The least mean of each factor among choices meeting the other limit.
                let least_time = all
                    .iter()
                    .filter(|(_, _, f, _)| *f <= limits.fuel_max as f64 + tol)
                    .map(|(_, t, ..)| *t)
                    .fold(f64::INFINITY, f64::min);
                let least_fuel = all
                    .iter()
                    .filter(|(_, t, _, _)| *t <= limits.time_max as f64 + tol)
                    .map(|(_, _, f, _)| *f)
                    .fold(f64::INFINITY, f64::min);
                let want = match limit {
                    Limit::Time => (least_time, limits.time_max),
                    Limit::Fuel => (least_fuel, limits.fuel_max),
                };
                assert_eq!(max, want.1, "case {case}");
                assert!(
                    (least as f64 - want.0).abs() <= 1e-5
                        || (least.is_infinite() && want.0.is_infinite()),
                    "case {case}: {limit:?} least {least}, brute force {}",
                    want.0
                );
                let over =
                    |l: f64, m: f32| (l - m as f64) / (m.abs().max(f32::MIN_POSITIVE)) as f64;
                let (ot, of) = (
                    over(least_time, limits.time_max),
                    over(least_fuel, limits.fuel_max),
                );
                // The limit named is one whose relaxation alone helps, whenever one does; of
                // two such, the one needing the larger relative relaxation.
                match limit {
                    Limit::Time if ot.is_finite() && of.is_finite() => {
                        assert!(ot >= of - 1e-4, "case {case}")
                    }
                    Limit::Fuel if ot.is_finite() && of.is_finite() => {
                        assert!(of >= ot - 1e-4, "case {case}")
                    }
                    Limit::Time => assert!(ot.is_finite() || of.is_infinite(), "case {case}"),
                    Limit::Fuel => assert!(of.is_finite(), "case {case}"),
                }
            }
            Err(e) => panic!("case {case}: {e:?}"),
        }
    }
    println!("{feasible} feasible, {infeasible} infeasible instances");
    assert!(feasible > 0 && infeasible > 0);
}

#[test]
fn the_papers_instance_decides_within_its_limits() {
    // 3 pop-ups × 3 alternatives, limits 0.35 (time) and 0.40 (fuel), as in Ruz et al.
    let a = |risk, time, fuel| Alternative { risk, time, fuel };
    let alts = [
        vec![
            a(0.30, 0.10, 0.20),
            a(0.10, 0.40, 0.35),
            a(0.05, 0.60, 0.50),
        ],
        vec![
            a(0.25, 0.15, 0.10),
            a(0.12, 0.30, 0.45),
            a(0.02, 0.55, 0.60),
        ],
        vec![
            a(0.40, 0.05, 0.05),
            a(0.20, 0.35, 0.30),
            a(0.08, 0.50, 0.55),
        ],
    ];
    let slices: Vec<&[Alternative]> = alts.iter().map(|v| v.as_slice()).collect();
    let limits = DecisionLimits {
        time_max: 0.35,
        fuel_max: 0.40,
    };
    let d = decide(&slices, &limits).unwrap();
    assert!(d.mean_time <= 0.35 + 1e-6 && d.mean_fuel <= 0.40 + 1e-6);
    let best = combinations(&alts)
        .into_iter()
        .filter(|(_, t, f, _)| *t <= 0.35 + 1e-6 && *f <= 0.40 + 1e-6)
        .map(|(r, ..)| r)
        .fold(f64::INFINITY, f64::min);
    assert!((d.risk as f64 - best).abs() < 1e-6);
}

#[test]
fn bad_input_is_refused_by_name() {
    let a = Alternative {
        risk: 0.1,
        time: 0.1,
        fuel: 0.1,
    };
    let ok = DecisionLimits {
        time_max: 0.5,
        fuel_max: 0.5,
    };
    let nine: Vec<&[Alternative]> = (0..9).map(|_| std::slice::from_ref(&a)).collect();
    assert_eq!(
        decide(&nine, &ok),
        Err(DecisionError::TooManyPopups { count: 9 })
    );
    let empty: [&[Alternative]; 2] = [std::slice::from_ref(&a), &[]];
    assert_eq!(
        decide(&empty, &ok),
        Err(DecisionError::BadAlternativeCount { popup: 1, count: 0 })
    );
    let five = [a; 5];
    assert_eq!(
        decide(&[&five[..]], &ok),
        Err(DecisionError::BadAlternativeCount { popup: 0, count: 5 })
    );
    for bad in [
        Alternative {
            risk: f32::NAN,
            ..a
        },
        Alternative { risk: 1.5, ..a },
        Alternative {
            time: f32::INFINITY,
            ..a
        },
        Alternative {
            fuel: f32::NAN,
            ..a
        },
    ] {
        assert_eq!(
            decide(&[std::slice::from_ref(&bad)], &ok),
            Err(DecisionError::BadNumber { popup: 0 })
        );
    }
    let nan = DecisionLimits {
        time_max: f32::NAN,
        fuel_max: 0.5,
    };
    assert_eq!(
        decide(&[std::slice::from_ref(&a)], &nan),
        Err(DecisionError::BadNumber { popup: usize::MAX })
    );
    let none = decide(&[], &ok).unwrap();
    assert!(none.choice.is_empty() && none.risk == 0.0);
    assert_eq!((none.mean_time, none.mean_fuel), (0.0, 0.0));
    // Beyond MAX_FACTOR in magnitude, finite or not, a limit or a factor is refused.
    let over = MAX_FACTOR * 2.0;
    for (time_max, fuel_max) in [(over, 0.5), (0.5, -over)] {
        let limits = DecisionLimits { time_max, fuel_max };
        assert_eq!(
            decide(&[std::slice::from_ref(&a)], &limits),
            Err(DecisionError::BadNumber { popup: usize::MAX }),
            "{limits:?}"
        );
    }
    for bad in [
        Alternative { time: over, ..a },
        Alternative { fuel: -over, ..a },
    ] {
        let pair = [a, bad];
        assert_eq!(
            decide(&[std::slice::from_ref(&a), &pair], &ok),
            Err(DecisionError::BadNumber { popup: 1 }),
            "{bad:?}"
        );
    }
    let edge = Alternative {
        time: MAX_FACTOR,
        fuel: -MAX_FACTOR,
        ..a
    };
    let limits = DecisionLimits {
        time_max: MAX_FACTOR,
        fuel_max: MAX_FACTOR,
    };
    assert!(decide(&[std::slice::from_ref(&edge)], &limits).is_ok());
}

#[test]
fn an_unmeetable_limit_is_named_even_when_the_other_is_loose() {
    // No choice has a mean time factor within 0.001; every choice meets the fuel limit. Only
    // relaxing the time limit helps, to the least mean time 0.002.
    let a = |time| Alternative {
        risk: 0.1,
        time,
        fuel: 0.004,
    };
    let alts = [vec![a(0.0), a(0.01)], vec![a(0.004), a(0.02)]];
    let slices: Vec<&[Alternative]> = alts.iter().map(|v| v.as_slice()).collect();
    let limits = DecisionLimits {
        time_max: 0.001,
        fuel_max: 0.40,
    };
    match decide(&slices, &limits) {
        Err(DecisionError::Infeasible {
            limit: Limit::Time,
            least,
            max,
        }) => assert!(
            (least - 0.002).abs() < 1e-7 && max == 0.001,
            "{least} {max}"
        ),
        other => panic!("{other:?}"),
    }
}

/// The nodes the branch and bound visits, by the rule the module documents, written as a
/// recursion: each alternative tried after a prefix is one node; it is cut when its risk plus
/// the least risk of every later pop-up is not below the best complete choice so far, or when
/// its time (fuel) plus the least time (fuel) of every later pop-up exceeds `n·T_max`
/// (`n·F_max`). Exact for figures in eighths (every sum below is exact in f64 and f32).
fn reference_nodes(alts: &[Vec<Alternative>], limits: &DecisionLimits) -> u64 {
    let n = alts.len();
    // least[d]: the least risk, time and fuel summed over pop-ups d.. (0 past the end).
    let mut least = vec![(0.0f64, 0.0f64, 0.0f64); n + 1];
    for d in (0..n).rev() {
        let min = |f: fn(&Alternative) -> f32| {
            alts[d]
                .iter()
                .map(|a| f(a) as f64)
                .fold(f64::INFINITY, f64::min)
        };
        least[d] = (
            least[d + 1].0 + min(|a| a.risk),
            least[d + 1].1 + min(|a| a.time),
            least[d + 1].2 + min(|a| a.fuel),
        );
    }
    let budget = (
        n as f64 * limits.time_max as f64,
        n as f64 * limits.fuel_max as f64,
    );
    struct Walk<'a> {
        alts: &'a [Vec<Alternative>],
        least: Vec<(f64, f64, f64)>,
        budget: (f64, f64),
        best: Option<f64>,
        nodes: u64,
    }
    fn visit(w: &mut Walk, d: usize, (risk, time, fuel): (f64, f64, f64)) {
        if d == w.alts.len() {
            if w.best.is_none_or(|b| risk < b) {
                w.best = Some(risk);
            }
            return;
        }
        for a in &w.alts[d] {
            w.nodes += 1;
            let sums = (
                risk + a.risk as f64,
                time + a.time as f64,
                fuel + a.fuel as f64,
            );
            let after = w.least[d + 1];
            let cut = w.best.is_some_and(|b| sums.0 + after.0 >= b)
                || sums.1 + after.1 > w.budget.0
                || sums.2 + after.2 > w.budget.1;
            if !cut {
                visit(w, d + 1, sums);
            }
        }
    }
    let mut walk = Walk {
        alts,
        least,
        budget,
        best: None,
        nodes: 0,
    };
    visit(&mut walk, 0, (0.0, 0.0, 0.0));
    walk.nodes
}

/// Decides `alts` with limits that every choice of time and fuel 0 meets.
fn decide_loose(alts: &[Vec<Alternative>]) -> skyroute::planner::decision::Decision {
    let slices: Vec<&[Alternative]> = alts.iter().map(|a| a.as_slice()).collect();
    let limits = DecisionLimits {
        time_max: 0.0,
        fuel_max: 0.0,
    };
    decide(&slices, &limits).unwrap()
}

#[test]
fn the_work_is_the_documented_node_count_and_ties_keep_the_first_choice() {
    let mut rng = Rng(35);
    let eighth = |rng: &mut Rng| rng.below(9) as f32 / 8.0;
    let mut cut_short = 0;
    for case in 0..host_tests::cases(2000, 20000) {
        let n = rng.below(MAX_DECISION_POPUPS as u64 + 1) as usize;
        let alts: Vec<Vec<Alternative>> = (0..n)
            .map(|_| {
                (0..1 + rng.below(MAX_ALTERNATIVES as u64) as usize)
                    .map(|_| Alternative {
                        risk: eighth(&mut rng),
                        time: eighth(&mut rng),
                        fuel: eighth(&mut rng),
                    })
                    .collect()
            })
            .collect();
        let limits = DecisionLimits {
            time_max: eighth(&mut rng),
            fuel_max: eighth(&mut rng),
        };
        let slices: Vec<&[Alternative]> = alts.iter().map(|a| a.as_slice()).collect();
        let Ok(d) = decide(&slices, &limits) else {
            continue;
        };
        // The first optimum in lexicographic order of the alternatives, by brute force.
        let first = combinations(&alts)
            .into_iter()
            .filter(|(_, t, f, _)| *t <= limits.time_max as f64 && *f <= limits.fuel_max as f64)
            .fold(
                None,
                |best: Option<(f64, Vec<u8>)>, (r, _, _, c)| match best {
                    Some((b, _)) if b <= r => best,
                    _ => Some((r, c)),
                },
            )
            .unwrap();
        assert_eq!(d.choice[..], first.1[..], "case {case}");
        let nodes = reference_nodes(&alts, &limits);
        assert_eq!(d.work, nodes, "case {case}");
        let counts: Vec<usize> = alts.iter().map(Vec::len).collect();
        if nodes < decision_work_bound(&counts) {
            cut_short += 1;
        }
    }
    assert!(cut_short > 100, "only {cut_short} instances were cut short");

    // Each choice better than every one before it (risk: the choice's mixed-radix rank from
    // the end, in units of 2⁻¹⁶): nothing is cut, every prefix is a node, the bound is met.
    let counts = [4usize, 3, 4, 2, 4, 4, 3, 4];
    let weight = |i: usize| counts[i + 1..].iter().product::<usize>() as f32;
    let descending: Vec<Vec<Alternative>> = (0..counts.len())
        .map(|i| {
            (0..counts[i])
                .map(|k| Alternative {
                    risk: (counts[i] - 1 - k) as f32 * weight(i) / 65536.0,
                    ..Alternative::default()
                })
                .collect()
        })
        .collect();
    let d = decide_loose(&descending);
    assert_eq!(d.work, decision_work_bound(&counts));
    assert!(
        d.choice
            .iter()
            .zip(counts)
            .all(|(&k, a)| k as usize == a - 1)
            && d.risk == 0.0
    );

    // Equal risks: the first choice is complete at once and ties with every other, so each
    // later alternative is one node, cut: Σ a_i nodes, and the choice is all first alternatives.
    let equal: Vec<Vec<Alternative>> = counts
        .iter()
        .map(|&a| {
            let alt = Alternative {
                risk: 0.25,
                ..Alternative::default()
            };
            vec![alt; a]
        })
        .collect();
    let d = decide_loose(&equal);
    assert_eq!(d.work, counts.iter().sum::<usize>() as u64);
    assert!(d.choice.iter().all(|&k| k == 0) && d.risk == 2.0);
}

#[test]
fn a_choice_at_the_budget_meets_the_limit_and_one_ulp_above_does_not() {
    // Three pop-ups of one alternative each: the sum of their factors against
    // decision_budget(3, max), exactly at it and at the next f32 above.
    for max in [0.35f32, 0.0, -0.2] {
        let budget = decision_budget(3, max);
        for (sum, meets) in [(budget, true), (budget.next_up(), false)] {
            let third = Alternative {
                risk: 0.1,
                time: 0.0,
                fuel: 0.0,
            };
            // Two thirds of 0 and the whole sum on the last: the sum is exact.
            for limit in [Limit::Time, Limit::Fuel] {
                let last = match limit {
                    Limit::Time => Alternative { time: sum, ..third },
                    Limit::Fuel => Alternative { fuel: sum, ..third },
                };
                let limits = match limit {
                    Limit::Time => DecisionLimits {
                        time_max: max,
                        fuel_max: 1.0,
                    },
                    Limit::Fuel => DecisionLimits {
                        time_max: 1.0,
                        fuel_max: max,
                    },
                };
                let alts = [[third], [third], [last]];
                let slices: Vec<&[Alternative]> = alts.iter().map(|a| a.as_slice()).collect();
                let got = decide(&slices, &limits);
                assert_eq!(
                    got.is_ok(),
                    meets,
                    "{limit:?} max {max}, sum {sum}: {got:?}"
                );
            }
        }
    }
    assert_eq!(decision_budget(3, 0.5), 1.5 + 1.5 * 1e-6 + 1e-6);
    assert_eq!(decision_budget(3, -0.5), -1.5 + 1.5 * 1e-6 + 1e-6);
}
