//! The onboard decision of Ruz et al. (`--ruz --scenario FILE` on a roadmap network built from
//! `ruz-popups`): the host computes every pop-up's bypass alternatives with the ground tool's
//! code ([`skyroute_prep::ruz::alternatives::study`]), keeps the figures the decision needs
//! (each alternative's [`RouteFigures`]: steps, the two survival figures and the fuel factor,
//! and the nominal route's steps), and decides with [`decide`] for a sequence of
//! announcements, exactly as the `ruz` firmware will: R_K recomputed for the announced
//! appearance probabilities with [`skyroute::planner::risk::alternative`], then `decide`.
//! `query.rs` records the figures, the announcements, every recomputed alternative and every
//! answer; the firmware compares them bit for bit.
//!
//! The announcements: every pop-up with its scenario probability under the paper's limits;
//! the second pop-up appears (P = 1) and the first does not (P = 0); a time limit that binds
//! (the least-risk choice breaks it); a time limit no choice meets (the tightest named). Then a
//! synthetic instance of [`MAX_DECISION_POPUPS`] × [`MAX_ALTERNATIVES`] whose risks fall along
//! the search's order, so that no choice is ever cut: the decision visits exactly
//! [`decision_work_bound`] nodes, its worst case.
//!
//! The alternatives are `const` data in the firmware, not stored in the network image.

use super::{lit, write_fixture, Args};
use skyroute::network::Network;
use skyroute::planner::decision::{
    decide, decision_work_bound, Alternative, Decision, DecisionError, DecisionLimits, Limit,
    MAX_ALTERNATIVES, MAX_DECISION_POPUPS,
};
use skyroute::planner::risk::{alternative, RouteFigures};
use skyroute_prep::mission::MissionOptions;
use skyroute_prep::ruz::alternatives::{study, Planning};
use skyroute_prep::ruz::cli::LIMITS;
use std::fmt::Write as _;

/// One announcement: what the firmware is told, and what the host decided.
struct Announcement {
    what: String,
    appearance: Vec<f32>,
    limits: DecisionLimits,
    inputs: Vec<Vec<Alternative>>,
    answer: Result<Decision, DecisionError>,
}

/// The pop-ups' names, their scenario probabilities, the nominal route's steps and every
/// alternative's figures.
struct Figures {
    names: Vec<String>,
    probabilities: Vec<f32>,
    nominal_steps: u32,
    alternatives: Vec<Vec<RouteFigures>>,
}

/// Decides for `appearance` under `limits` as the firmware does.
fn announce(f: &Figures, what: &str, appearance: Vec<f32>, limits: DecisionLimits) -> Announcement {
    let inputs: Vec<Vec<Alternative>> = f
        .alternatives
        .iter()
        .zip(&appearance)
        .map(|(alts, &p)| {
            alts.iter()
                .map(|a| alternative(a, f.nominal_steps, p))
                .collect()
        })
        .collect();
    let slices: Vec<&[Alternative]> = inputs.iter().map(Vec::as_slice).collect();
    let answer = decide(&slices, &limits);
    Announcement {
        what: what.to_string(),
        appearance,
        limits,
        inputs,
        answer,
    }
}

/// The announcements of the module documentation.
fn announcements(f: &Figures) -> Vec<Announcement> {
    let n = f.probabilities.len();
    let mut out = vec![announce(
        f,
        "every pop-up announced with its probability, the paper's limits",
        f.probabilities.clone(),
        LIMITS,
    )];
    if n >= 2 {
        let mut p = f.probabilities.clone();
        p[1] = 1.0;
        p[0] = 0.0;
        let what = format!(
            "{} appears (P = 1), {} does not (P = 0): re-decide",
            f.names[1], f.names[0]
        );
        out.push(announce(f, &what, p, LIMITS));
    }
    let binding = DecisionLimits {
        time_max: 0.003,
        fuel_max: LIMITS.fuel_max,
    };
    out.push(announce(
        f,
        "the same, a time limit that binds (0.003)",
        out.last()
            .map_or(f.probabilities.clone(), |a| a.appearance.clone()),
        binding,
    ));
    let tight = DecisionLimits {
        time_max: 0.001,
        fuel_max: LIMITS.fuel_max,
    };
    out.push(announce(
        f,
        "the same, a time limit no choice meets (0.001)",
        out.last()
            .map_or(f.probabilities.clone(), |a| a.appearance.clone()),
        tight,
    ));
    out
}

/// The synthetic worst case: [`MAX_DECISION_POPUPS`] pop-ups of [`MAX_ALTERNATIVES`]
/// alternatives, risk `(a − 1 − k)·a^(n−1−u)·2⁻¹⁷` for alternative k of pop-up u (a = 4,
/// n = 8; every sum exact in f32), time and fuel 0. The total risk of a choice falls strictly
/// along the search's lexicographic order, so every complete choice improves on the best so far
/// and no prefix is cut: the work is the bound.
fn worst_case() -> Vec<Vec<Alternative>> {
    let (n, a) = (MAX_DECISION_POPUPS, MAX_ALTERNATIVES);
    (0..n)
        .map(|u| {
            (0..a)
                .map(|k| Alternative {
                    risk: ((a - 1 - k) * a.pow((n - 1 - u) as u32)) as f32 / (1u32 << 17) as f32,
                    time: 0.0,
                    fuel: 0.0,
                })
                .collect()
        })
        .collect()
}

/// Plans the alternatives of every pop-up of the scenario with the ground tool's code.
fn figures(args: &Args, bytes: &[u8], network: &Network<'_>) -> Result<Figures, String> {
    let path = args
        .scenario
        .as_ref()
        .ok_or("--ruz needs --scenario FILE")?;
    let s = skyroute_prep::scenario::load(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let frame = skyroute_prep::export::network_frame(network);
    let planning = Planning {
        bytes,
        scenario: &s,
        frame: &frame,
        options: MissionOptions::default(),
    };
    let params = skyroute_prep::ruz::risk_params(&s);
    let which: Vec<usize> = (0..s.popups.len()).collect();
    let st = study(&planning, &params, &which).map_err(|e| format!("{}: {e}", path.display()))?;
    Ok(Figures {
        names: st.popups.iter().map(|p| p.name.clone()).collect(),
        probabilities: st.popups.iter().map(|p| p.probability as f32).collect(),
        nominal_steps: st.nominal.figures.steps,
        alternatives: st
            .popups
            .iter()
            .map(|p| p.alternatives.iter().map(|a| a.figures).collect())
            .collect(),
    })
}

/// The fixture of the `ruz` firmware: plans the alternatives, decides every announcement and the
/// worst case, reports them and writes `OUT_DIR/query.rs`.
pub(super) fn run_ruz(
    args: &Args,
    bytes: &[u8],
    source: &str,
    network: &Network<'_>,
) -> Result<(), String> {
    let f = figures(args, bytes, network).map_err(|e| format!("{source}: {e}"))?;
    if f.alternatives.is_empty() || f.alternatives.len() > MAX_DECISION_POPUPS {
        return Err(format!("{source}: {} pop-ups", f.alternatives.len()));
    }
    let list = announcements(&f);
    let worst = worst_case();
    let slices: Vec<&[Alternative]> = worst.iter().map(Vec::as_slice).collect();
    let worst_answer = decide(&slices, &LIMITS);
    eprintln!(
        "firmware_fixture: {source}: ruz decision, pop-ups {}, nominal route {} steps",
        f.names.join(", "),
        f.nominal_steps
    );
    for a in &list {
        eprintln!(
            "firmware_fixture: {}: P_A {:?}, limits {:?}: {:?}",
            a.what, a.appearance, a.limits, a.answer
        );
    }
    let counts: Vec<usize> = worst.iter().map(Vec::len).collect();
    eprintln!(
        "firmware_fixture: worst case {}x{}: work {:?} of bound {}",
        MAX_DECISION_POPUPS,
        MAX_ALTERNATIVES,
        worst_answer.as_ref().map(|d| d.work),
        decision_work_bound(&counts)
    );
    let q = query_rs(source, &f, &list, &worst, &worst_answer);
    write_fixture(&args.out_dir, None, &q)
}

/// An f32 literal, infinities included.
fn flit(x: f32) -> String {
    if x == f32::INFINITY {
        "f32::INFINITY".into()
    } else if x == f32::NEG_INFINITY {
        "f32::NEG_INFINITY".into()
    } else {
        lit(x)
    }
}

/// `&[&[Alternative]]` as a Rust expression.
fn alternatives_rs(alts: &[Vec<Alternative>]) -> String {
    let mut s = String::from("&[\n");
    for a in alts {
        s.push_str("        &[\n");
        for x in a {
            let _ = writeln!(
                s,
                "            D::Alternative {{ risk: {}, time: {}, fuel: {} }},",
                flit(x.risk),
                flit(x.time),
                flit(x.fuel)
            );
        }
        s.push_str("        ],\n");
    }
    s.push_str("    ]");
    s
}

/// A host answer as a `Result<R::Expected, D::DecisionError>` expression.
fn answer_rs(answer: &Result<Decision, DecisionError>) -> String {
    match answer {
        Ok(d) => format!(
            "Ok(R::Expected {{ choice: &{:?}, risk: {}, mean_time: {}, mean_fuel: {}, work: {} }})",
            d.choice.as_slice(),
            flit(d.risk),
            flit(d.mean_time),
            flit(d.mean_fuel),
            d.work
        ),
        Err(DecisionError::Infeasible { limit, least, max }) => format!(
            "Err(D::DecisionError::Infeasible {{ limit: D::Limit::{}, least: {}, max: {} }})",
            match limit {
                Limit::Time => "Time",
                Limit::Fuel => "Fuel",
            },
            flit(*least),
            flit(*max)
        ),
        Err(e) => format!("compile_error!(\"the host's decision failed: {e:?}\")"),
    }
}

/// `query.rs`: the figures, the announcements with the host's answers, the worst case.
fn query_rs(
    source: &str,
    f: &Figures,
    list: &[Announcement],
    worst: &[Vec<Alternative>],
    worst_answer: &Result<Decision, DecisionError>,
) -> String {
    let mut q = String::new();
    let w = &mut q;
    let _ = writeln!(
        w,
        "// Generated by host-tests/src/bin/firmware_fixture/ from {source} (the Ruz decision). \
         Do not edit.\n"
    );
    let _ = writeln!(w, "use skyroute::planner::decision as D;");
    let _ = writeln!(w, "use skyroute::planner::risk::RouteFigures;");
    let _ = writeln!(w, "use skyroute_firmware_example::ruz as R;\n");
    let _ = writeln!(w, "/// The pop-ups, in the decision's order.");
    let _ = writeln!(w, "pub const NAMES: &[&str] = &{:?};", f.names);
    let _ = writeln!(
        w,
        "/// M of the nominal route (the time factors' τ = M·Δt)."
    );
    let _ = writeln!(w, "pub const NOMINAL_STEPS: u32 = {};", f.nominal_steps);
    let _ = writeln!(
        w,
        "/// Each pop-up's alternatives as the ground tool scored them: steps, P_S,known, P_S,PU, F_c."
    );
    let _ = writeln!(w, "pub const ALTERNATIVES: &[&[RouteFigures]] = &[");
    for alts in &f.alternatives {
        let _ = writeln!(w, "    &[");
        for a in alts {
            let _ = writeln!(
                w,
                "        RouteFigures {{ steps: {}, survival_known: {}, survival_popup: {}, fuel: {} }},",
                a.steps,
                flit(a.survival_known),
                flit(a.survival_popup),
                flit(a.fuel)
            );
        }
        let _ = writeln!(w, "    ],");
    }
    let _ = writeln!(w, "];");
    let _ = writeln!(
        w,
        "/// The announcements, each with the alternatives' figures and the decision the host computed."
    );
    let _ = writeln!(w, "pub const ANNOUNCEMENTS: &[R::Announcement] = &[");
    for a in list {
        let _ = writeln!(w, "    R::Announcement {{");
        let _ = writeln!(w, "        what: {:?},", a.what);
        let p: Vec<String> = a.appearance.iter().map(|&x| flit(x)).collect();
        let _ = writeln!(w, "        appearance: &[{}],", p.join(", "));
        let _ = writeln!(
            w,
            "        limits: D::DecisionLimits {{ time_max: {}, fuel_max: {} }},",
            flit(a.limits.time_max),
            flit(a.limits.fuel_max)
        );
        let _ = writeln!(w, "        inputs: {},", alternatives_rs(&a.inputs));
        let _ = writeln!(w, "        expected: {},", answer_rs(&a.answer));
        let _ = writeln!(w, "    }},");
    }
    let _ = writeln!(w, "];");
    let _ = writeln!(
        w,
        "/// The worst case: {MAX_DECISION_POPUPS} pop-ups of {MAX_ALTERNATIVES} alternatives that no cut prunes."
    );
    let _ = writeln!(
        w,
        "pub const WORST: &[&[D::Alternative]] = {};",
        alternatives_rs(worst)
    );
    let _ = writeln!(w, "/// The paper's limits, for the worst case.");
    let _ = writeln!(
        w,
        "pub const WORST_LIMITS: D::DecisionLimits = D::DecisionLimits {{ time_max: {}, fuel_max: {} }};",
        flit(LIMITS.time_max),
        flit(LIMITS.fuel_max)
    );
    let _ = writeln!(w, "/// The host's decision of the worst case.");
    let _ = writeln!(
        w,
        "pub const WORST_EXPECTED: Result<R::Expected, D::DecisionError> = {};",
        answer_rs(worst_answer)
    );
    q
}
