//! `skyroute plan --popup-appears NAME`: the decision among the named pop-ups' bypass
//! alternatives, and the route that flies the choice.
//!
//! Only the named pop-ups are considered (each may appear with its scenario `probability`
//! P_A, the weight of its radar in the risk); the scenario's other pop-ups are left out. The
//! alternatives of each are planned and scored ([`super::alternatives`]), the decision picks
//! one per pop-up ([`decide`]: least total risk Σ R_K with the mean time and fuel factors within
//! the limits), and the route flown is the mission planned with every disc of the chosen
//! alternatives (each pop-up's disc and the blocking discs that shaped its alternative): with
//! one pop-up that is its chosen alternative; with several it keeps clear of every pop-up and
//! takes each bypass's side, and its own figures are reported beside the decision's.

use super::alternatives::{Planning, PopupAlternatives, ScoredRoute, Study};
use super::risk_params;
use super::stored::study;
use crate::mission::{MissionOptions, Shortcuts};
use crate::output::refuse_overwriting_inputs;
use crate::plan_checks::{check_query, gather_popups, PopupInput};
use crate::plan_cli::{load_scenario, popups_json, CliResult, NoRoute, PlanRequest};
use crate::provenance::check_binding;
use crate::route_output::RouteFormat;
use crate::scenario::{self, Scenario};
use serde_json::{json, Value};
use skyroute::planner::decision::{
    decide, Alternative, Decision, DecisionError, DecisionLimits, Limit,
};
use skyroute::planner::risk::{route_figures, AlternativeRisk, RiskParams};
use std::time::Instant;

pub use super::{FUEL_LIMIT, LIMITS, TIME_LIMIT};

/// The indices of the scenario pop-ups named by `--popup-appears`, in the order given; an
/// unknown or repeated name is refused by name.
pub fn popups_named(s: &Scenario, names: &[String]) -> Result<Vec<usize>, String> {
    let mut out: Vec<usize> = Vec::new();
    for n in names {
        let Some(i) = s.popups.iter().position(|p| &p.name == n) else {
            let known: Vec<&str> = s.popups.iter().map(|p| p.name.as_str()).collect();
            return Err(format!(
                "--popup-appears {n}: {} has no popup feature named {n:?} (its pop-ups: {})",
                s.path.display(),
                if known.is_empty() {
                    "none".to_string()
                } else {
                    known.join(", ")
                }
            ));
        };
        if out.contains(&i) {
            return Err(format!("--popup-appears {n}: given twice"));
        }
        out.push(i);
    }
    Ok(out)
}

/// The decision's figures of a pop-up's alternatives.
pub fn decision_inputs(study: &Study, p: &PopupAlternatives) -> Vec<Alternative> {
    p.alternatives
        .iter()
        .map(|a| {
            skyroute::planner::risk::alternative(
                &a.figures,
                study.nominal.figures.steps,
                p.probability as f32,
            )
        })
        .collect()
}

/// Why no decision: a [`NoRoute`] (exit code 3) when the limits cannot be met, naming the
/// tightest; otherwise a plain error.
pub fn decision_error(e: DecisionError, limits: &DecisionLimits) -> Box<dyn std::error::Error> {
    match e {
        DecisionError::Infeasible { limit, least, max } => {
            let (what, option, other) = match limit {
                Limit::Time => ("time", "--time-limit", "fuel"),
                Limit::Fuel => ("fuel", "--fuel-limit", "time"),
            };
            let meets = if least.is_finite() {
                format!(
                    "the least mean {what} factor of a choice within the {other} limit is \
                     {least:.3}"
                )
            } else {
                format!("no choice meets the {other} limit either")
            };
            Box::new(NoRoute(format!(
                "no choice of alternatives meets both limits (time {:.3}, fuel {:.3}); the \
                 tightest is the {what} limit: {meets}, above {option} {max:.3}",
                limits.time_max, limits.fuel_max
            )))
        }
        other => format!("the decision refused its input: {other:?}").into(),
    }
}

/// The figures of the route flown, with every decided pop-up's radar weighted by its P_A.
pub struct Flown {
    /// The route.
    pub route: ScoredRoute,
    /// P_S,PU of the route against each decided pop-up's radar, in the decision's order.
    pub survival_popups: Vec<f32>,
    /// Its R_K against the known radars and the pop-ups.
    pub risk: f32,
    /// Its time factor.
    pub time: f32,
}

/// Plans the route flying `choice` (one alternative index per pop-up of `study`) and scores it.
pub fn fly(planning: &Planning, study: &Study, choice: &[usize]) -> Result<Flown, String> {
    let mut discs = Vec::new();
    for (p, &k) in study.popups.iter().zip(choice) {
        if let Some(a) = p.alternatives.get(k) {
            discs.extend(a.discs.iter().cloned());
        }
    }
    let route = planning
        .score(&study.params, &study.radars, discs, None)
        .map_err(|e| format!("the route flying the chosen alternatives: {e}"))?;
    let survival_popups: Vec<f32> = study
        .popups
        .iter()
        .map(|p| route_figures(&study.params, &route.route, &[], Some(p.centre)).survival_popup)
        .collect();
    let survival = study.popups.iter().zip(&survival_popups).fold(
        route.figures.survival_known,
        |s, (p, &pu)| {
            let pa = p.probability as f32;
            s * ((1.0 - pa) + pa * pu)
        },
    );
    let time =
        skyroute::planner::risk::time_factor(study.nominal.figures.steps, route.figures.steps);
    Ok(Flown {
        route,
        survival_popups,
        risk: (1.0 - survival).clamp(0.0, 1.0),
        time,
    })
}

/// A route's lines and arcs in the local frame, as the route file's legs hold them.
fn primitives_json(route: &[skyroute::Primitive]) -> Vec<Value> {
    route
        .iter()
        .map(crate::route_json::primitive_json)
        .collect()
}

/// The route file's record of the alternatives (each with its lines and arcs), the choice and
/// the route flown.
fn decision_json(
    study: &Study,
    inputs: &[Vec<Alternative>],
    d: &Decision,
    limits: &DecisionLimits,
    flown: &Flown,
) -> Value {
    let popups: Vec<Value> = study
        .popups
        .iter()
        .zip(inputs)
        .zip(&d.choice)
        .map(|((p, alts), &k)| {
            let alternatives: Vec<Value> = p
                .alternatives
                .iter()
                .zip(alts)
                .map(|(a, f)| {
                    json!({
                        "length_m": a.length_m,
                        "steps": a.figures.steps,
                        "survival_known": a.figures.survival_known,
                        "survival_popup": a.figures.survival_popup,
                        "risk": f.risk,
                        "time_factor": f.time,
                        "fuel_factor": f.fuel,
                        "primitives": primitives_json(&a.route),
                        "discs": a.discs.iter().map(|c| json!({
                            "name": c.name, "centre": [c.centre.x, c.centre.y], "radius_m": c.radius,
                        })).collect::<Vec<_>>(),
                    })
                })
                .collect();
            json!({
                "name": p.name,
                "probability": p.probability,
                "nominal_distance_m": p.nominal_distance_m,
                "touches_nominal": p.touches_nominal,
                "chosen": k,
                "alternatives": alternatives,
            })
        })
        .collect();
    json!({
        "method": "Ruz et al.: least total risk with mean time and fuel factors within the limits",
        "limits": {"time": limits.time_max, "fuel": limits.fuel_max},
        "nominal": {"length_m": study.nominal.length_m, "steps": study.nominal.figures.steps,
                    "survival_known": study.nominal.figures.survival_known,
                    "fuel_factor": study.nominal.figures.fuel,
                    "primitives": primitives_json(&study.nominal.route)},
        "popups": popups,
        "total_risk": d.risk,
        "mean_time_factor": d.mean_time,
        "mean_fuel_factor": d.mean_fuel,
        "work": d.work,
        "flown": {"risk": flown.risk, "time_factor": flown.time,
                  "fuel_factor": flown.route.figures.fuel,
                  "survival_known": flown.route.figures.survival_known,
                  "survival_popups": flown.survival_popups,
                  "length_m": flown.route.length_m},
    })
}

/// Prints each pop-up's alternatives, the one chosen and why.
fn report(study: &Study, inputs: &[Vec<Alternative>], d: &Decision, limits: &DecisionLimits) {
    for ((p, alts), &k) in study.popups.iter().zip(inputs).zip(&d.choice) {
        println!(
            "  pop-up {:?} (P_A {}, nominal route {:.0} m from its centre{}):",
            p.name,
            p.probability,
            p.nominal_distance_m,
            if p.touches_nominal {
                ", its disc touches it"
            } else {
                ""
            }
        );
        for (i, (a, f)) in p.alternatives.iter().zip(alts).enumerate() {
            println!(
                "    {} alternative {}: {:.1} km, risk {:.4}, time factor {:.3}, fuel factor {:.3}",
                if i == k as usize { "*" } else { " " },
                i + 1,
                a.length_m / 1000.0,
                f.risk,
                f.time,
                f.fuel
            );
        }
        let chosen = alts.get(k as usize).copied().unwrap_or_default();
        let least = alts.iter().map(|a| a.risk).fold(f32::INFINITY, f32::min);
        let why = if chosen.risk <= least {
            "its least risk".to_string()
        } else {
            format!(
                "the least risk ({least:.4}) would break a limit of the means, so the next \
                 best within both limits"
            )
        };
        println!("    chose alternative {}: {why}", k + 1);
    }
    println!(
        "  decision: total risk {:.4}, mean time factor {:.3} (limit {:.3}), mean fuel factor \
         {:.3} (limit {:.3}), {} search nodes",
        d.risk, d.mean_time, limits.time_max, d.mean_fuel, limits.fuel_max, d.work
    );
}

/// Plans the alternatives of the pop-ups `which`, decides, plans the route flying the choice,
/// prints why, and returns the route file's JSON (the mission's, with a `decision` member).
pub fn plan_decided(
    planning: &Planning,
    which: &[usize],
    limits: &DecisionLimits,
) -> Result<(Value, Flown), Box<dyn std::error::Error>> {
    let params: RiskParams = risk_params(planning.scenario);
    let stored = skyroute::Network::from_bytes(planning.bytes)
        .is_ok_and(|n| n.alternatives_summary().is_some());
    println!(
        "  alternatives: {}",
        if stored {
            "as stored in the network image by `skyroute build` (the aircraft decides among the same)"
        } else {
            "planned now (the network image stores none)"
        }
    );
    let study = study(planning, &params, which)?;
    let inputs: Vec<Vec<Alternative>> = study
        .popups
        .iter()
        .map(|p| decision_inputs(&study, p))
        .collect();
    let slices: Vec<&[Alternative]> = inputs.iter().map(Vec::as_slice).collect();
    let d = decide(&slices, limits).map_err(|e| decision_error(e, limits))?;
    report(&study, &inputs, &d, limits);
    let choice: Vec<usize> = d.choice.iter().map(|&k| k as usize).collect();
    let flown = fly(planning, &study, &choice)?;
    println!(
        "  route flown (every chosen alternative's discs): {:.1} km, risk {:.4}, time factor \
         {:.3}, fuel factor {:.3}",
        flown.route.length_m / 1000.0,
        flown.risk,
        flown.time,
        flown.route.figures.fuel
    );
    let mut json = crate::route_json::mission_json(
        &flown.route.mission,
        planning.frame,
        &planning.scenario.name,
    );
    json["decision"] = decision_json(&study, &inputs, &d, limits, &flown);
    json["decision"]["alternatives_stored_in_network"] = json!(stored);
    Ok((json, flown))
}

/// The risk of an alternative for another appearance probability, from its two stored
/// survival figures.
pub fn risk_for(a: &ScoredRoute, appearance: f32) -> f32 {
    AlternativeRisk {
        survival_known: a.figures.survival_known,
        survival_popup: a.figures.survival_popup,
    }
    .risk(appearance)
}

/// `skyroute plan --popup-appears`: the decision among the named pop-ups' alternatives
/// ([`crate::ruz::cli`]), on roadmap and terrain networks.
pub fn plan_decided_command(req: &PlanRequest) -> CliResult {
    let t0 = Instant::now();
    if req.start.is_some() {
        return Err(
            "--start with --popup-appears: the bypass alternatives are computed for the \
                    scenario's nominal route, from its start"
                .into(),
        );
    }
    refuse_overwriting_inputs(req.output, &[req.network, req.scenario])?;
    let format = RouteFormat::of(req.output)?;
    let bytes =
        std::fs::read(req.network).map_err(|e| format!("{}: {e}", req.network.display()))?;
    let net = &skyroute::Network::from_bytes(&bytes)
        .map_err(|e| format!("{}: {e}", req.network.display()))?;
    let s = &load_scenario(req.scenario, req.hull_repair, req.mode)?;
    check_binding(s, net).map_err(|e| {
        format!(
            "{} on {}: {e}",
            req.scenario.display(),
            req.network.display()
        )
    })?;
    let frame = &crate::export::network_frame(net);
    let bytes = &bytes;
    let on = || format!("{} on {}", req.scenario.display(), req.network.display());
    match s.planner.mode {
        scenario::Mode::Roadmap | scenario::Mode::Terrain => {}
        scenario::Mode::Landmark | scenario::Mode::Voronoi => {
            return Err(format!(
                "--popup-appears applies to roadmap and terrain networks; {} is a {} network",
                req.network.display(),
                net.mode().name()
            )
            .into())
        }
    }
    let which = popups_named(s, req.popup_appears)?;
    let all = gather_popups(s, &[], true);
    let popups: Vec<PopupInput> = which.iter().filter_map(|&i| all.get(i).cloned()).collect();
    check_query(s, net, frame, &popups).map_err(|e| format!("{}: {e}", on()))?;
    let planning = Planning {
        bytes,
        scenario: s,
        frame,
        options: MissionOptions {
            connect_radius_m: req.connect_radius_m,
            turn_rule: req.turn_rule,
            free_headings: req.free_headings,
            shortcuts: req.shortcuts.unwrap_or(Shortcuts::Greedy),
        },
    };
    let (mut json, flown) = plan_decided(&planning, &which, &req.limits).map_err(
        |e| -> Box<dyn std::error::Error> {
            match e.downcast::<NoRoute>() {
                Ok(n) => Box::new(NoRoute(format!("{}: {n}", on()))),
                Err(e) => format!("{}: {e}", on()).into(),
            }
        },
    )?;
    json["popups"] = popups_json(&popups, frame);
    json["scenario_popups_applied"] = serde_json::json!(false);
    json["popups_appeared"] = serde_json::json!(req.popup_appears);
    println!(
        "planned {} deciding among the alternatives of {}: {:.1} m, {:.2} s -> {}",
        s.name,
        req.popup_appears.join(", "),
        flown.route.length_m,
        t0.elapsed().as_secs_f64(),
        req.output.display()
    );
    crate::plan_cli::write_route(req, format, &json, s)
}
