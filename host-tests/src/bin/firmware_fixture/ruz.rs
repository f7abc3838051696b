//! The onboard switch of Ruz et al. (`--ruz --scenario FILE` on a roadmap network built from
//! `ruz-popups`, whose image stores every pop-up's bypass alternatives): the host does exactly
//! what the `ruz` firmware will, with the same core calls on the same image: load, plan the
//! scenario's start → goal (the nominal route), then for each announcement decide among the
//! stored alternatives ([`decide_stored`]), fly the choice ([`Planner::fly_alternatives`]: the
//! chosen alternatives' discs as pop-ups), plan again, and remove the discs. `query.rs`
//! records the capacities, the query, every answer and route, and a worst-case instance of the
//! decision; the firmware compares them bit for bit.
//!
//! The announcements: every pop-up with its stored probability under the paper's limits; the
//! second pop-up appears (P = 1) and the first does not (P = 0); the same with a time limit
//! halfway between the least mean time factor any choice reaches and the unconstrained
//! choice's (so it binds, when they differ); a time limit below that least mean (infeasible,
//! the time limit named); the last pop-up alone, certain. Then a synthetic instance of
//! [`MAX_DECISION_POPUPS`] × [`MAX_ALTERNATIVES`] whose risks fall along the search's order, so
//! that no choice is ever cut: the decision visits exactly [`decision_work_bound`] nodes, its
//! worst case.

use super::{capacity, config_rs, lit, write_fixture, Args, HOST_E, HOST_V, R_CAP};
use skyroute::network::Network;
use skyroute::planner::alternatives::{decide_stored, Announced, SwitchError};
use skyroute::planner::decision::{
    decide, decision_work_bound, Alternative, Decision, DecisionError, DecisionLimits, Limit,
    MAX_ALTERNATIVES, MAX_DECISION_POPUPS,
};
use skyroute::planner::{PlanError, PlannerConfig};
use skyroute::{Goal, Planner, Pose, Query, Search};
use skyroute_prep::mission::SMOOTHING_HEADINGS;
use skyroute_prep::ruz::cli::LIMITS;
use std::fmt::Write as _;
use std::path::Path;

/// Pop-up slots of the `ruz` firmware's planner: every chosen alternative's discs (three
/// pop-ups of at most three discs each on ruz-popups).
pub(super) const RUZ_P_CAP: usize = 16;

/// The connection settings when an end does not connect with the default's: its candidates,
/// however far (on a coarse roadmap the scenario's start and goal lie more than the default
/// 1 km from every vertex).
const WIDE_CONFIG: PlannerConfig = PlannerConfig {
    connect_radius_m: f32::INFINITY,
    ..PlannerConfig::DEFAULT
};

type RuzPlanner<'n> = Planner<'n, HOST_V, HOST_E, RUZ_P_CAP, R_CAP>;

/// A route the host planned: its length, primitives and counted work, and the discs flown
/// round.
#[derive(Clone, Copy, Debug)]
struct Flown {
    discs: usize,
    length: f32,
    primitives: u32,
    work: u64,
}

/// One announcement: what the firmware is told, and what the host decided and flew.
struct Announcement {
    what: String,
    announced: Vec<Announced>,
    limits: DecisionLimits,
    answer: Result<Decision, DecisionError>,
    flown: Option<Flown>,
}

/// The scenario's start pose and goal in the network's frame, and the pop-ups' names.
fn query_of(
    scenario: Option<&Path>,
    network: &Network<'_>,
) -> Result<(Query, Vec<String>), String> {
    let path = scenario.ok_or("--ruz needs --scenario FILE")?;
    let s = skyroute_prep::scenario::load(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let frame = skyroute_prep::export::network_frame(network);
    let st = s.start.as_ref().ok_or("the scenario has no start")?;
    let g = s.goal.as_ref().ok_or("the scenario has no goal")?;
    let start: Pose = skyroute_prep::local::local_pose(&frame, st.lon, st.lat, st.heading_deg);
    let goal = Goal {
        position: skyroute_prep::local::local(&frame, g.lon, g.lat),
        heading: g
            .heading_deg
            .map(|h| skyroute_prep::local::local_heading(&frame, g.lon, g.lat, h)),
    };
    let query = Query {
        start,
        goal,
        search: Search::AStar,
    };
    Ok((query, s.popups.iter().map(|p| p.name.clone()).collect()))
}

/// Plans `query` with the planner's discs as the firmware does, and as the ground tool plans a
/// mission's leg: with the default connection, again with the nearest vertices however far
/// when an end does not connect, then the shortcut and heading-smoothing passes.
fn plan(
    planner: &mut RuzPlanner<'_>,
    query: &Query,
    budget: u64,
    discs: usize,
) -> Result<Flown, String> {
    let failed = |e: PlanError| format!("plan with {discs} discs: {e}");
    let planned = match planner.plan(query, budget) {
        Err(PlanError::StartUnconnected | PlanError::GoalUnconnected) => {
            planner.set_config(WIDE_CONFIG);
            let second = planner.plan(query, budget);
            planner.set_config(PlannerConfig::DEFAULT);
            second
        }
        other => other,
    }
    .map_err(failed)?;
    let shortcut = planner.shortcut(budget).map_err(failed)?;
    let smooth = planner
        .smooth_headings(SMOOTHING_HEADINGS, budget)
        .map_err(failed)?;
    let s = planner.route_summary().ok_or("no route after smoothing")?;
    Ok(Flown {
        discs,
        length: s.length,
        primitives: s.primitives,
        work: planned.work.total() + shortcut.work.total() + smooth.work.total(),
    })
}

/// Decides `announced` under `limits` and, when there is a choice, flies it and removes its
/// discs again.
fn announce(
    planner: &mut RuzPlanner<'_>,
    query: &Query,
    budget: u64,
    what: String,
    announced: Vec<Announced>,
    limits: DecisionLimits,
) -> Result<Announcement, String> {
    let net = *planner.network();
    let answer = match decide_stored(&net, &announced, &limits) {
        Ok(d) => Ok(d),
        Err(SwitchError::Decision(e)) => Err(e),
        Err(e) => return Err(format!("{what}: {e:?}")),
    };
    let flown = match &answer {
        Ok(d) => {
            let ids = planner
                .fly_alternatives(&announced, &d.choice)
                .map_err(|e| format!("{what}: fly_alternatives: {e:?}"))?;
            let flown = plan(planner, query, budget, ids.len())?;
            for id in ids {
                planner
                    .remove_popup(id)
                    .map_err(|e| format!("{what}: {e}"))?;
            }
            Some(flown)
        }
        Err(_) => None,
    };
    Ok(Announcement {
        what,
        announced,
        limits,
        answer,
        flown,
    })
}

/// The least mean time factor any choice of `announced` reaches.
fn least_mean_time(net: &Network<'_>, announced: &[Announced]) -> f32 {
    // The mean is least when each pop-up takes its least time factor.
    let n = announced.len().max(1) as f32;
    let nominal = net.alternatives_summary().map_or(0, |s| s.nominal_steps);
    announced
        .iter()
        .map(|a| {
            (0..MAX_ALTERNATIVES as u32)
                .filter_map(|k| net.stored_alternative(a.popup as u32, k))
                .map(|s| skyroute::planner::risk::time_factor(nominal, s.steps))
                .fold(f32::INFINITY, f32::min)
        })
        .sum::<f32>()
        / n
}

/// The announcements of the module documentation.
fn announcements(
    planner: &mut RuzPlanner<'_>,
    query: &Query,
    budget: u64,
    names: &[String],
) -> Result<Vec<Announcement>, String> {
    let net = *planner.network();
    let stored = net
        .alternatives_summary()
        .ok_or("the network stores no pop-up alternatives")?;
    let n = stored.popups as u8;
    let prior = |u: u8| net.stored_popup(u as u32).map_or(1.0, |p| p.probability);
    let all: Vec<Announced> = (0..n)
        .map(|u| Announced {
            popup: u,
            appearance: prior(u),
        })
        .collect();
    let name = |u: usize| names.get(u).cloned().unwrap_or_else(|| format!("#{u}"));
    let mut out = vec![announce(
        planner,
        query,
        budget,
        "every pop-up announced with its probability, the paper's limits".into(),
        all.clone(),
        LIMITS,
    )?];
    let mut second = all.clone();
    if n >= 2 {
        second[1].appearance = 1.0;
        second[0].appearance = 0.0;
        let what = format!(
            "{} appears (P = 1), {} does not (P = 0): re-decide",
            name(1),
            name(0)
        );
        out.push(announce(
            planner,
            query,
            budget,
            what,
            second.clone(),
            LIMITS,
        )?);
    }
    let least = least_mean_time(&net, &second);
    let free = out
        .last()
        .and_then(|a| a.answer.as_ref().ok())
        .map_or(least, |d| d.mean_time);
    let binding = DecisionLimits {
        time_max: 0.5 * (least + free),
        fuel_max: LIMITS.fuel_max,
    };
    let what = format!(
        "the same, a time limit of {:.5} halfway between the least mean time factor ({least:.5}) and the free choice's ({free:.5})",
        binding.time_max
    );
    out.push(announce(
        planner,
        query,
        budget,
        what,
        second.clone(),
        binding,
    )?);
    let below = DecisionLimits {
        time_max: least - 0.001,
        fuel_max: LIMITS.fuel_max,
    };
    let what = format!(
        "the same, a time limit of {:.5} that no choice meets",
        below.time_max
    );
    out.push(announce(planner, query, budget, what, second, below)?);
    let last = n.saturating_sub(1);
    let what = format!("{} alone, certain (P = 1)", name(last as usize));
    let alone = vec![Announced {
        popup: last,
        appearance: 1.0,
    }];
    out.push(announce(planner, query, budget, what, alone, LIMITS)?);
    Ok(out)
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

/// What the host computed for the firmware.
struct Answers {
    names: Vec<String>,
    query: Query,
    budget: u64,
    nominal: Flown,
    list: Vec<Announcement>,
}

/// Loads the image into the host planner and answers every announcement (module
/// documentation).
fn answers(scenario: Option<&Path>, bytes: &[u8]) -> Result<Answers, String> {
    let network = Network::from_bytes(bytes).map_err(|e| e.to_string())?;
    let (query, names) = query_of(scenario, &network)?;
    let mut planner: Box<RuzPlanner<'_>> = Box::new(Planner::new());
    planner.load(bytes).map_err(|e| format!("load: {e}"))?;
    planner.set_config(PlannerConfig::DEFAULT);
    let budget = planner.worst_case_work();
    let nominal = plan(&mut planner, &query, budget, 0)?;
    let list = announcements(&mut planner, &query, budget, &names)?;
    Ok(Answers {
        names,
        query,
        budget,
        nominal,
        list,
    })
}

/// The fixture of the `ruz` firmware: answers every announcement and the worst case, reports
/// them and writes `OUT_DIR/{network.bin,query.rs}`.
pub(super) fn run_ruz(
    args: &Args,
    bytes: &[u8],
    source: &str,
    network: &Network<'_>,
) -> Result<(), String> {
    let a = std::thread::Builder::new()
        .stack_size(256 << 20)
        .spawn({
            let bytes = bytes.to_vec();
            let scenario = args.scenario.clone();
            move || answers(scenario.as_deref(), &bytes)
        })
        .map_err(|e| format!("spawning the planning thread: {e}"))?
        .join()
        .map_err(|_| "the planning thread panicked".to_string())?
        .map_err(|e| format!("{source}: {e}"))?;
    let worst = worst_case();
    let slices: Vec<&[Alternative]> = worst.iter().map(Vec::as_slice).collect();
    let worst_answer = decide(&slices, &LIMITS);
    let caps = (
        capacity(network.vertex_count(), 64),
        capacity(network.edge_count(), 256),
    );
    Network::from_bytes_with_capacity(bytes, caps.0, caps.1).map_err(|e| {
        format!(
            "{source}: does not load with V={} E={}: {e}",
            caps.0, caps.1
        )
    })?;
    eprintln!(
        "firmware_fixture: {source}: ruz switch, pop-ups {}; nominal route {} m, {} primitives, work {} of {}",
        a.names.join(", "),
        a.nominal.length,
        a.nominal.primitives,
        a.nominal.work,
        a.budget
    );
    for x in &a.list {
        eprintln!(
            "firmware_fixture: {}: {:?}, limits {:?}: {:?}; flown {:?}",
            x.what, x.announced, x.limits, x.answer, x.flown
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
    let q = query_rs(source, caps, &a, &worst, &worst_answer);
    write_fixture(&args.out_dir, Some(bytes), &q)
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

/// A [`Flown`] as an `R::Flown` expression.
fn flown_rs(f: &Flown) -> String {
    format!(
        "R::Flown {{ discs: {}, length: {}, primitives: {}, work: {} }}",
        f.discs,
        flit(f.length),
        f.primitives,
        f.work
    )
}

/// `query.rs`: the capacities, the query, the host's answers and routes, the worst case.
fn query_rs(
    source: &str,
    (v_cap, e_cap): (usize, usize),
    a: &Answers,
    worst: &[Vec<Alternative>],
    worst_answer: &Result<Decision, DecisionError>,
) -> String {
    let mut q = String::new();
    let w = &mut q;
    let _ = writeln!(
        w,
        "// Generated by host-tests/src/bin/firmware_fixture/ from {source} (the Ruz switch). \
         Do not edit.\n"
    );
    let _ = writeln!(w, "use skyroute::planner::alternatives::Announced;");
    let _ = writeln!(w, "use skyroute::planner::decision as D;");
    let _ = writeln!(w, "use skyroute_firmware_example::ruz as R;\n");
    let _ = writeln!(w, "/// Search-state capacity of the planner.");
    let _ = writeln!(w, "pub const V_CAP: usize = {v_cap};");
    let _ = writeln!(w, "/// Edge capacity of the planner.");
    let _ = writeln!(w, "pub const E_CAP: usize = {e_cap};");
    let _ = writeln!(w, "/// Pop-up slots: every chosen alternative's discs.");
    let _ = writeln!(w, "pub const P_CAP: usize = {RUZ_P_CAP};");
    let _ = writeln!(w, "/// Route primitives the planner holds.");
    let _ = writeln!(w, "pub const R_CAP: usize = {R_CAP};");
    let _ = writeln!(
        w,
        "/// The connection settings when an end does not connect with the default's."
    );
    let _ = writeln!(w, "{}", config_rs("WIDE_CONFIG", &WIDE_CONFIG));
    let _ = writeln!(w, "/// Candidate headings of the heading-smoothing pass.");
    let _ = writeln!(
        w,
        "pub const SMOOTHING_HEADINGS: u16 = {SMOOTHING_HEADINGS};"
    );
    let _ = writeln!(w, "/// The stored pop-ups' names, in the image's order.");
    let _ = writeln!(w, "pub const NAMES: &[&str] = &{:?};", a.names);
    let (s, g) = (a.query.start, a.query.goal);
    let heading = g
        .heading
        .map_or("None".to_string(), |h| format!("Some({})", lit(h)));
    let _ = writeln!(w, "/// The scenario's start → goal.");
    let _ = writeln!(
        w,
        "pub const QUERY: skyroute::Query = skyroute::Query {{\n    start: skyroute::Pose::new({}, {}, {}),\n    \
         goal: skyroute::Goal {{ position: skyroute::Vec2::new({}, {}), heading: {heading} }},\n    \
         search: skyroute::Search::AStar,\n}};",
        lit(s.position.x),
        lit(s.position.y),
        lit(s.heading),
        lit(g.position.x),
        lit(g.position.y)
    );
    let _ = writeln!(w, "/// Work budget of each plan: the network's worst case.");
    let _ = writeln!(w, "pub const BUDGET: u64 = {};", a.budget);
    let _ = writeln!(
        w,
        "/// The nominal route (no pop-up) as the host planned it."
    );
    let _ = writeln!(w, "pub const NOMINAL: R::Flown = {};", flown_rs(&a.nominal));
    let _ = writeln!(
        w,
        "/// The announcements, each with the host's decision and the route flying it."
    );
    let _ = writeln!(w, "pub const ANNOUNCEMENTS: &[R::Announcement] = &[");
    for x in &a.list {
        let _ = writeln!(w, "    R::Announcement {{");
        let _ = writeln!(w, "        what: {:?},", x.what);
        let announced: Vec<String> = x
            .announced
            .iter()
            .map(|a| {
                format!(
                    "Announced {{ popup: {}, appearance: {} }}",
                    a.popup,
                    flit(a.appearance)
                )
            })
            .collect();
        let _ = writeln!(w, "        announced: &[{}],", announced.join(", "));
        let _ = writeln!(
            w,
            "        limits: D::DecisionLimits {{ time_max: {}, fuel_max: {} }},",
            flit(x.limits.time_max),
            flit(x.limits.fuel_max)
        );
        let _ = writeln!(w, "        expected: {},", answer_rs(&x.answer));
        let flown = x
            .flown
            .as_ref()
            .map_or("None".to_string(), |f| format!("Some({})", flown_rs(f)));
        let _ = writeln!(w, "        flown: {flown},");
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
