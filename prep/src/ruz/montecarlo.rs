//! The Monte Carlo study: missions in which the pop-ups appear by their probabilities, flown
//! with the decision of Ruz et al. and with a baseline that decides on time and fuel alone.
//!
//! Both methods choose one alternative per pop-up before the aircraft reaches it. The decision
//! chooses up front with every pop-up weighted by its P_A ([`decide`]); then, in the
//! chronological order of the pop-ups along the nominal route, each pop-up appears (with
//! probability P_A) or not as the aircraft passes it, its choice is fixed and its P_A becomes 1
//! or 0, and the decision is taken again over the pop-ups still ahead. The baseline takes for
//! each pop-up the alternative of least time factor among those within the fuel limit (the
//! least fuel factor if none is). A mission's **realised risk** is the kill probability of the
//! route flying its choice given which pop-ups appeared: `1 − P_S,known · Π_{appeared} P_S,PU`
//! of that route (each combination of alternatives is planned once, before the missions).
//! A limit is violated when the chosen alternatives' summed time or fuel factor exceeds the
//! decision's budget for it ([`decision_budget`]: the mean limit times the pop-ups, with the
//! decision's rounding tolerance), so a choice the decision accepts never counts as one.

use super::alternatives::{sample_points, Planning, Study};
use super::cli::{decision_inputs, fly};
use rand_core::{RngCore, SeedableRng};
use rand_pcg::Pcg64Mcg;
use rayon::prelude::*;
use skyroute::planner::decision::{decide, decision_budget, Alternative, DecisionLimits};
use skyroute::planner::risk::AlternativeRisk;

/// Missions per random stream (and per parallel task).
pub const CHUNK: u64 = 1 << 20;

/// The route flying one combination of alternatives.
#[derive(Clone, Debug)]
pub struct Combination {
    /// P_S,known of the route.
    pub survival_known: f64,
    /// P_S,PU of the route against each pop-up's radar.
    pub survival_popups: Vec<f64>,
    /// Its time factor against the nominal route.
    pub time: f64,
}

/// Everything a mission needs: the pop-ups in chronological order with their decision
/// figures, and every combination's route.
pub struct Setup {
    /// Chronological order: indices into the study's pop-ups.
    pub order: Vec<usize>,
    /// The pop-ups' P_A, in the study's order.
    pub probability: Vec<f64>,
    /// Each pop-up's alternatives' survival figures, in the study's order.
    pub survival: Vec<Vec<AlternativeRisk>>,
    /// Each pop-up's alternatives' decision figures for its P_A.
    pub inputs: Vec<Vec<Alternative>>,
    /// The combinations, indexed by `Σ_u choice_u · 3^u` (mixed radix of the counts).
    pub combinations: Vec<Option<Combination>>,
}

/// The index of a combination of alternatives.
pub fn combination_index(setup: &Setup, choice: &[usize]) -> usize {
    let mut index = 0;
    let mut radix = 1;
    for (alts, &k) in setup.inputs.iter().zip(choice) {
        index += k * radix;
        radix *= alts.len();
    }
    index
}

/// Plans every combination of alternatives and orders the pop-ups along the nominal route.
pub fn setup(planning: &Planning, study: &Study) -> Result<Setup, String> {
    let nominal = sample_points(&study.nominal.route);
    let mut order: Vec<(usize, usize)> = study
        .popups
        .iter()
        .enumerate()
        .map(|(u, p)| {
            let d2 = |q: &(f64, f64)| {
                (q.0 - p.centre.x as f64).powi(2) + (q.1 - p.centre.y as f64).powi(2)
            };
            let at = (0..nominal.len())
                .min_by(|&a, &b| d2(&nominal[a]).total_cmp(&d2(&nominal[b])))
                .unwrap_or(0);
            (at, u)
        })
        .collect();
    order.sort();
    let inputs: Vec<Vec<Alternative>> = study
        .popups
        .iter()
        .map(|p| decision_inputs(study, p))
        .collect();
    let total: usize = inputs.iter().map(Vec::len).product();
    let mut combinations = Vec::with_capacity(total);
    for index in 0..total {
        let mut choice = Vec::new();
        let mut rest = index;
        for alts in &inputs {
            choice.push(rest % alts.len());
            rest /= alts.len();
        }
        combinations.push(fly(planning, study, &choice).ok().map(|f| Combination {
            survival_known: f.route.figures.survival_known as f64,
            survival_popups: f.survival_popups.iter().map(|&s| s as f64).collect(),
            time: f.time as f64,
        }));
    }
    Ok(Setup {
        order: order.into_iter().map(|(_, u)| u).collect(),
        probability: study.popups.iter().map(|p| p.probability).collect(),
        survival: study
            .popups
            .iter()
            .map(|p| {
                p.alternatives
                    .iter()
                    .map(|a| AlternativeRisk {
                        survival_known: a.figures.survival_known,
                        survival_popup: a.figures.survival_popup,
                    })
                    .collect()
            })
            .collect(),
        inputs,
        combinations,
    })
}

/// The baseline's choice: per pop-up the least time factor within the fuel limit.
pub fn baseline(setup: &Setup, limits: &DecisionLimits) -> Vec<usize> {
    setup
        .inputs
        .iter()
        .map(|alts| {
            let within: Vec<usize> = (0..alts.len())
                .filter(|&k| alts[k].fuel <= limits.fuel_max)
                .collect();
            let pool: Vec<usize> = if within.is_empty() {
                (0..alts.len()).collect()
            } else {
                within
            };
            pool.into_iter()
                .min_by(|&a, &b| alts[a].time.total_cmp(&alts[b].time))
                .unwrap_or(0)
        })
        .collect()
}

/// The decision's choice for a mission in which `appeared[u]` tells, for the pop-ups already
/// passed (the first `passed` of the chronological order), whether they appeared. Returns the
/// choice, or `None` when no choice meets the limits, and the decision's work.
fn decide_with(
    setup: &Setup,
    fixed: &[Option<usize>],
    appeared: &[Option<bool>],
    limits: &DecisionLimits,
) -> (Option<Vec<usize>>, u64) {
    let lists: Vec<Vec<Alternative>> = (0..setup.inputs.len())
        .map(|u| {
            let pa = match appeared[u] {
                Some(true) => 1.0,
                Some(false) => 0.0,
                None => setup.probability[u] as f32,
            };
            let all = setup.inputs[u]
                .iter()
                .zip(&setup.survival[u])
                .map(|(a, s)| Alternative {
                    risk: s.risk(pa),
                    ..*a
                });
            match fixed[u] {
                Some(k) => all.skip(k).take(1).collect(),
                None => all.collect(),
            }
        })
        .collect();
    let slices: Vec<&[Alternative]> = lists.iter().map(Vec::as_slice).collect();
    match decide(&slices, limits) {
        Ok(d) => {
            let choice = d
                .choice
                .iter()
                .enumerate()
                .map(|(u, &k)| fixed[u].unwrap_or(k as usize))
                .collect();
            (Some(choice), d.work)
        }
        Err(_) => (None, 0),
    }
}

/// One mission's outcome for one method.
#[derive(Clone, Copy, Debug, Default)]
pub struct Outcome {
    /// The realised risk (NaN when the combination has no route).
    pub risk: f64,
    /// Whether a limit was violated (or the decision found no choice).
    pub violated: bool,
}

/// The outcome of flying `choice` when `appeared` pop-ups appeared.
pub fn outcome(
    setup: &Setup,
    choice: &[usize],
    appeared: &[bool],
    limits: &DecisionLimits,
) -> Outcome {
    let (t, f) = choice
        .iter()
        .zip(&setup.inputs)
        .fold((0.0f32, 0.0f32), |(t, f), (&k, alts)| {
            (t + alts[k].time, f + alts[k].fuel)
        });
    let n = choice.len();
    let violated =
        t > decision_budget(n, limits.time_max) || f > decision_budget(n, limits.fuel_max);
    let risk = match &setup.combinations[combination_index(setup, choice)] {
        Some(c) => {
            let s = c
                .survival_popups
                .iter()
                .zip(appeared)
                .filter(|(_, &a)| a)
                .fold(c.survival_known, |s, (&pu, _)| s * pu);
            1.0 - s
        }
        None => f64::NAN,
    };
    Outcome { risk, violated }
}

/// One mission: draws the appearances in chronological order, runs both methods. Returns
/// (decision, baseline, the decision's work).
pub fn mission(
    setup: &Setup,
    base: &[usize],
    limits: &DecisionLimits,
    rng: &mut Pcg64Mcg,
) -> (Outcome, Outcome, u64) {
    let n = setup.inputs.len();
    let mut fixed: Vec<Option<usize>> = vec![None; n];
    let mut known: Vec<Option<bool>> = vec![None; n];
    let (mut current, mut work) = decide_with(setup, &fixed, &known, limits);
    let mut failed = current.is_none();
    for &u in &setup.order {
        let k = current.as_ref().map_or(base[u], |c| c[u]);
        fixed[u] = Some(k);
        let draw = (rng.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64);
        known[u] = Some(draw < setup.probability[u]);
        let (next, w) = decide_with(setup, &fixed, &known, limits);
        work += w;
        failed |= next.is_none();
        if next.is_some() {
            current = next;
        }
    }
    let appeared: Vec<bool> = known.iter().map(|a| a.unwrap_or(false)).collect();
    let chosen: Vec<usize> = fixed.iter().map(|k| k.unwrap_or(0)).collect();
    let mut ours = outcome(setup, &chosen, &appeared, limits);
    ours.violated |= failed;
    (ours, outcome(setup, base, &appeared, limits), work)
}

/// What the study measured for one method.
#[derive(Clone, Debug, Default)]
pub struct Tally {
    /// Missions.
    pub missions: u64,
    /// Sum of the realised risks.
    pub risk_sum: f64,
    /// Missions that violated a limit.
    pub violations: u64,
    /// Missions whose combination had no route.
    pub no_route: u64,
    /// Histogram of the realised risk: `bins` counts over [0, `top`).
    pub histogram: Vec<u64>,
}

impl Tally {
    fn new(bins: usize) -> Self {
        Tally {
            histogram: vec![0; bins],
            ..Tally::default()
        }
    }

    fn add(&mut self, o: &Outcome, top: f64) {
        self.missions += 1;
        self.violations += o.violated as u64;
        if o.risk.is_nan() {
            self.no_route += 1;
            return;
        }
        self.risk_sum += o.risk;
        let bins = self.histogram.len();
        let b = ((o.risk / top) * bins as f64).clamp(0.0, bins as f64 - 1.0) as usize;
        self.histogram[b] += 1;
    }

    fn merge(&mut self, o: &Tally) {
        self.missions += o.missions;
        self.risk_sum += o.risk_sum;
        self.violations += o.violations;
        self.no_route += o.no_route;
        for (a, b) in self.histogram.iter_mut().zip(&o.histogram) {
            *a += b;
        }
    }

    /// The mean realised risk over the missions with a route.
    pub fn mean(&self) -> f64 {
        self.risk_sum / (self.missions - self.no_route).max(1) as f64
    }
}

/// The study's result: per method its tally, and the decision's total work.
pub struct Results {
    /// The decision of Ruz et al.
    pub decision: Tally,
    /// The time-and-fuel baseline.
    pub baseline: Tally,
    /// Search nodes over every decision taken.
    pub work: u64,
    /// Decisions taken.
    pub decisions: u64,
}

/// Runs `missions` missions from `seed` (one PCG stream per [`CHUNK`] missions, in parallel),
/// histograms of `bins` bins over [0, `top`).
pub fn run(
    setup: &Setup,
    limits: &DecisionLimits,
    missions: u64,
    seed: u64,
    bins: usize,
    top: f64,
) -> Results {
    let base = baseline(setup, limits);
    let chunks = missions.div_ceil(CHUNK);
    let per_decision = 1 + setup.order.len() as u64;
    let parts: Vec<(Tally, Tally, u64)> = (0..chunks)
        .into_par_iter()
        .map(|c| {
            let mut rng = Pcg64Mcg::seed_from_u64(seed ^ c.wrapping_mul(0x9E37_79B9_7F4A_7C15));
            let (mut ours, mut theirs, mut work) = (Tally::new(bins), Tally::new(bins), 0u64);
            let n = CHUNK.min(missions - c * CHUNK);
            for _ in 0..n {
                let (a, b, w) = mission(setup, &base, limits, &mut rng);
                ours.add(&a, top);
                theirs.add(&b, top);
                work += w;
            }
            (ours, theirs, work)
        })
        .collect();
    let mut out = Results {
        decision: Tally::new(bins),
        baseline: Tally::new(bins),
        work: 0,
        decisions: missions * per_decision,
    };
    for (a, b, w) in &parts {
        out.decision.merge(a);
        out.baseline.merge(b);
        out.work += w;
    }
    out
}

/// The exact expectation of the realised risk of both methods: the 2ⁿ appearance patterns
/// weighted by their probabilities, each decided as a mission would be.
pub fn expected(setup: &Setup, limits: &DecisionLimits) -> (f64, f64) {
    let n = setup.inputs.len();
    let base = baseline(setup, limits);
    let (mut ours, mut theirs) = (0.0, 0.0);
    for pattern in 0..(1u32 << n) {
        let appeared: Vec<bool> = (0..n).map(|u| pattern >> u & 1 == 1).collect();
        let weight: f64 = (0..n)
            .map(|u| {
                let p = setup.probability[u];
                if appeared[u] {
                    p
                } else {
                    1.0 - p
                }
            })
            .product();
        let mut fixed: Vec<Option<usize>> = vec![None; n];
        let mut known: Vec<Option<bool>> = vec![None; n];
        let (mut current, _) = decide_with(setup, &fixed, &known, limits);
        for &u in &setup.order {
            fixed[u] = Some(current.as_ref().map_or(base[u], |c| c[u]));
            known[u] = Some(appeared[u]);
            if let (Some(next), _) = decide_with(setup, &fixed, &known, limits) {
                current = Some(next);
            }
        }
        let chosen: Vec<usize> = fixed.iter().map(|k| k.unwrap_or(0)).collect();
        ours += weight * outcome(setup, &chosen, &appeared, limits).risk;
        theirs += weight * outcome(setup, &base, &appeared, limits).risk;
    }
    (ours, theirs)
}
