//! `skyroute montecarlo`: the Monte Carlo study of [`super::montecarlo`] on a roadmap or
//! terrain network, its histograms and its JSON record.

use super::alternatives::Planning;
use super::histogram::{histogram_svg, Histogram};
use super::montecarlo::{expected, run, setup, Tally};
use super::risk_params;
use super::stored::study;

use crate::output::{refuse_overwriting_inputs, write_atomically};
use crate::plan_cli::{load_scenario, CliResult};
use crate::provenance::check_binding;
use crate::scenario;
use serde_json::json;
use skyroute::planner::decision::DecisionLimits;
use std::path::Path;
use std::time::Instant;

/// Bins of each histogram.
pub const BINS: usize = 200;

/// What `skyroute montecarlo` was asked.
pub struct MonteCarloRequest<'a> {
    /// The network image.
    pub network: &'a Path,
    /// The scenario it was built from.
    pub scenario: &'a Path,
    /// Missions to fly.
    pub missions: u64,
    /// The random seed.
    pub seed: u64,
    /// The decision's limits.
    pub limits: DecisionLimits,
    /// Where to write the results (JSON).
    pub output: &'a Path,
    /// Where to write the histograms: `PREFIX-decision.{svg,png}` and
    /// `PREFIX-baseline.{svg,png}`.
    pub histograms: Option<&'a Path>,
}

fn tally_json(t: &Tally, top: f64) -> serde_json::Value {
    json!({
        "missions": t.missions,
        "mean_risk": t.mean(),
        "limit_violations": t.violations,
        "no_route": t.no_route,
        "histogram": {"top": top, "counts": t.histogram},
    })
}

/// `skyroute montecarlo`.
pub fn montecarlo_command(req: &MonteCarloRequest) -> CliResult {
    if req.missions == 0 {
        return Err("--missions 0: the study needs at least one mission".into());
    }
    if !req
        .output
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("json"))
    {
        return Err(format!(
            "{}: montecarlo writes JSON; name the output .json",
            req.output.display()
        )
        .into());
    }
    let inputs = [req.network, req.scenario];
    refuse_overwriting_inputs(req.output, &inputs)?;
    if let Some(prefix) = req.histograms {
        let first = format!("{}-decision.svg", prefix.display());
        refuse_overwriting_inputs(Path::new(&first), &inputs)?;
    }
    let bytes =
        std::fs::read(req.network).map_err(|e| format!("{}: {e}", req.network.display()))?;
    let net = skyroute::Network::from_bytes(&bytes)
        .map_err(|e| format!("{}: {e}", req.network.display()))?;
    let s = load_scenario(req.scenario, false, None)?;
    let on = || format!("{} on {}", req.scenario.display(), req.network.display());
    check_binding(&s, &net).map_err(|e| format!("{}: {e}", on()))?;
    match s.planner.mode {
        scenario::Mode::Roadmap | scenario::Mode::Terrain => {}
        scenario::Mode::Landmark | scenario::Mode::Voronoi => {
            return Err(format!("{}: montecarlo needs a roadmap or terrain network", on()).into())
        }
    }
    if s.popups.is_empty() {
        return Err(format!("{}: the scenario has no popup features", on()).into());
    }
    let frame = crate::export::network_frame(&net);
    let planning = Planning {
        bytes: &bytes,
        scenario: &s,
        frame: &frame,
        options: super::alternatives_options(),
    };
    let t0 = Instant::now();
    let all: Vec<usize> = (0..s.popups.len()).collect();
    let st = study(&planning, &risk_params(&s), &all).map_err(|e| format!("{}: {e}", on()))?;
    let su = setup(&planning, &st)?;
    let prepared = t0.elapsed().as_secs_f64();
    let worst = su
        .combinations
        .iter()
        .flatten()
        .map(|c| 1.0 - c.survival_popups.iter().product::<f64>() * c.survival_known)
        .fold(0.0, f64::max);
    let top = ((worst * 20.0).ceil() / 20.0).max(0.05);
    let t1 = Instant::now();
    let r = run(&su, &req.limits, req.missions, req.seed, BINS, top);
    let flown = t1.elapsed().as_secs_f64();
    let (exp_ours, exp_base) = expected(&su, &req.limits);
    println!(
        "{} alternatives and {} combined routes planned in {prepared:.1} s; {} missions in \
         {flown:.1} s ({:.2} s per 10^6; {} decisions, {:.0} ns and {:.1} search nodes each)",
        st.popups
            .iter()
            .map(|p| p.alternatives.len())
            .sum::<usize>(),
        su.combinations.len(),
        req.missions,
        flown * 1e6 / req.missions.max(1) as f64,
        r.decisions,
        flown * 1e9 / r.decisions.max(1) as f64,
        r.work as f64 / r.decisions.max(1) as f64
    );
    for (name, t, e) in [
        ("decision (risk, time, fuel)", &r.decision, exp_ours),
        ("baseline (time, fuel)", &r.baseline, exp_base),
    ] {
        println!(
            "  {name}: mean realised risk {:.5} (exact expectation {e:.5}), {} limit \
             violations, {} missions without a route",
            t.mean(),
            t.violations,
            t.no_route
        );
    }
    if let Some(prefix) = req.histograms {
        for (suffix, title, t, colour) in [
            (
                "decision",
                "Decision on risk, time and fuel (Ruz et al.)",
                &r.decision,
                "#3060c0",
            ),
            (
                "baseline",
                "Baseline: decision on time and fuel alone",
                &r.baseline,
                "#c05030",
            ),
        ] {
            let title = format!("{title}: {} missions", t.missions);
            let svg = histogram_svg(&Histogram {
                title: &title,
                counts: &t.histogram,
                top,
                mean: t.mean(),
                colour,
            });
            // The SVG keeps its text where the PNG has no system font to draw it with.
            let path = format!("{}-{suffix}", prefix.display());
            write_atomically(Path::new(&format!("{path}.svg")), svg.as_bytes())?;
            if cfg!(feature = "png") {
                write_atomically(
                    Path::new(&format!("{path}.png")),
                    &crate::render::svg_to_png(&svg)?,
                )?;
                println!("  histogram -> {path}.svg, {path}.png");
            } else {
                println!("  histogram -> {path}.svg (no PNG: the tool was built without `png`)");
            }
        }
    }
    let record = json!({
        "scenario": s.name,
        "missions": req.missions,
        "seed": req.seed,
        "limits": {"time": req.limits.time_max, "fuel": req.limits.fuel_max},
        "chronological_order": su.order.iter().map(|&u| &st.popups[u].name).collect::<Vec<_>>(),
        "decision": tally_json(&r.decision, top),
        "baseline": tally_json(&r.baseline, top),
        "expected": {"decision": exp_ours, "baseline": exp_base},
        "decisions": r.decisions,
        "decision_work": r.work,
        "seconds": {"prepare": prepared, "missions": flown},
        "alternatives": st.popups.iter().zip(&su.inputs).map(|(p, a)| json!({
            "name": p.name, "probability": p.probability,
            "risk": a.iter().map(|x| x.risk).collect::<Vec<_>>(),
            "time_factor": a.iter().map(|x| x.time).collect::<Vec<_>>(),
            "fuel_factor": a.iter().map(|x| x.fuel).collect::<Vec<_>>(),
            "length_m": p.alternatives.iter().map(|x| x.length_m).collect::<Vec<_>>(),
        })).collect::<Vec<_>>(),
    });
    write_atomically(
        req.output,
        serde_json::to_string_pretty(&record)?.as_bytes(),
    )?;
    Ok(())
}
