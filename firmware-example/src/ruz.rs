//! The pop-up decision of Ruz et al. on the flight computer: pop-ups are announced with their
//! appearance probabilities, the aircraft picks one bypass alternative per pop-up.
//!
//! For every announcement of the fixture:
//!
//! 1. the alternatives' figures for the decision are recomputed from the stored ones (steps,
//!    P_S,known, P_S,PU, F_c of each alternative, the nominal route's steps) and the announced
//!    probabilities with `skyroute::planner::risk::alternative` (R_K, f_t, F_c; timed);
//! 2. `decide` picks the least total risk within the mean time and fuel limits (timed);
//! 3. the verdict: every recomputed figure, the choice, the total risk, the mean factors and
//!    the work (or the infeasibility with its tightest limit) equal the host's bit for bit, and
//!    the work is within `decision_work_bound`.
//!
//! Then the worst case: a synthetic instance of the most pop-ups and alternatives whose search
//! cuts nothing, timed against `decision_work_bound`.
//!
//! The alternatives are constants of the fixture (`query.rs`), not read from a network image.

use crate::clock::{self, Clock};
use crate::log_stack;
use skyroute::planner::decision::{
    decide, decision_work_bound, Alternative, Decision, DecisionError, DecisionLimits,
    MAX_ALTERNATIVES, MAX_DECISION_POPUPS,
};
use skyroute::planner::risk::{alternative, RouteFigures};

/// What the host decided: the choice and its figures.
#[derive(Clone, Copy, Debug)]
pub struct Expected {
    /// The alternative chosen for each pop-up.
    pub choice: &'static [u8],
    /// Σ R_K of the choice.
    pub risk: f32,
    /// Its mean time factor.
    pub mean_time: f32,
    /// Its mean fuel factor.
    pub mean_fuel: f32,
    /// Search nodes visited.
    pub work: u64,
}

/// One announcement: the appearance probabilities and limits, and the host's figures.
pub struct Announcement {
    /// What happened, for the log.
    pub what: &'static str,
    /// P_A of each pop-up, in the order of the stored alternatives.
    pub appearance: &'static [f32],
    /// T_max and F_cmax.
    pub limits: DecisionLimits,
    /// The host's recomputed figures of every alternative.
    pub inputs: &'static [&'static [Alternative]],
    /// The host's decision.
    pub expected: Result<Expected, DecisionError>,
}

/// Everything the `ruz` binary's `query.rs` holds.
pub struct RuzFixture {
    /// The pop-ups' names.
    pub names: &'static [&'static str],
    /// M of the nominal route.
    pub nominal_steps: u32,
    /// Each pop-up's alternatives' stored figures.
    pub alternatives: &'static [&'static [RouteFigures]],
    /// The announcements, in order.
    pub announcements: &'static [Announcement],
    /// The worst-case instance.
    pub worst: &'static [&'static [Alternative]],
    /// Its limits.
    pub worst_limits: DecisionLimits,
    /// The host's decision of it.
    pub worst_expected: Result<Expected, DecisionError>,
}

/// The decision's inputs, in fixed memory: up to [`MAX_DECISION_POPUPS`] ×
/// [`MAX_ALTERNATIVES`] alternatives.
struct Inputs {
    alts: [[Alternative; MAX_ALTERNATIVES]; MAX_DECISION_POPUPS],
    counts: [usize; MAX_DECISION_POPUPS],
    popups: usize,
}

impl Inputs {
    /// Copies `rows` (at most the capacities; the rest is left out).
    fn from_rows(rows: &[&[Alternative]]) -> Self {
        let mut s = Inputs {
            alts: [[Alternative::default(); MAX_ALTERNATIVES]; MAX_DECISION_POPUPS],
            counts: [0; MAX_DECISION_POPUPS],
            popups: rows.len().min(MAX_DECISION_POPUPS),
        };
        for ((dst, count), row) in s.alts.iter_mut().zip(&mut s.counts).zip(rows) {
            for (d, a) in dst.iter_mut().zip(row.iter()) {
                *d = *a;
            }
            *count = row.len().min(MAX_ALTERNATIVES);
        }
        s
    }

    /// The rows as `decide` takes them.
    fn rows(&self) -> [&[Alternative]; MAX_DECISION_POPUPS] {
        let mut out: [&[Alternative]; MAX_DECISION_POPUPS] = [&[]; MAX_DECISION_POPUPS];
        for ((o, row), &n) in out.iter_mut().zip(&self.alts).zip(&self.counts) {
            *o = row.get(..n).unwrap_or(&[]);
        }
        out
    }

    /// The decision's work bound for these counts.
    fn bound(&self) -> u64 {
        decision_work_bound(self.counts.get(..self.popups).unwrap_or(&[]))
    }
}

/// Recomputes every alternative's R_K, f_t and F_c for `appearance` from the stored figures.
fn recompute(fixture: &RuzFixture, appearance: &[f32]) -> Inputs {
    let mut s = Inputs::from_rows(&[]);
    s.popups = fixture.alternatives.len().min(MAX_DECISION_POPUPS);
    for (u, figures) in fixture.alternatives.iter().enumerate().take(s.popups) {
        let p = appearance.get(u).copied().unwrap_or(1.0);
        let (Some(dst), Some(count)) = (s.alts.get_mut(u), s.counts.get_mut(u)) else {
            break;
        };
        for (d, f) in dst.iter_mut().zip(figures.iter()) {
            *d = alternative(f, fixture.nominal_steps, p);
        }
        *count = figures.len().min(MAX_ALTERNATIVES);
    }
    s
}

/// Whether two decision answers are the same bit for bit.
fn same(got: &Result<Decision, DecisionError>, want: &Result<Expected, DecisionError>) -> bool {
    match (got, want) {
        (Ok(d), Ok(e)) => {
            d.choice.as_slice() == e.choice
                && d.risk.to_bits() == e.risk.to_bits()
                && d.mean_time.to_bits() == e.mean_time.to_bits()
                && d.mean_fuel.to_bits() == e.mean_fuel.to_bits()
                && d.work == e.work
        }
        (Err(a), Err(b)) => match (a, b) {
            (
                DecisionError::Infeasible { limit, least, max },
                DecisionError::Infeasible {
                    limit: l,
                    least: le,
                    max: m,
                },
            ) => limit == l && least.to_bits() == le.to_bits() && max.to_bits() == m.to_bits(),
            _ => a == b,
        },
        _ => false,
    }
}

/// Whether the recomputed inputs equal the host's bit for bit.
fn same_inputs(got: &Inputs, want: &[&[Alternative]]) -> bool {
    let rows = got.rows();
    got.popups == want.len()
        && rows.iter().zip(want).all(|(g, w)| {
            g.len() == w.len()
                && g.iter().zip(w.iter()).all(|(a, b)| {
                    a.risk.to_bits() == b.risk.to_bits()
                        && a.time.to_bits() == b.time.to_bits()
                        && a.fuel.to_bits() == b.fuel.to_bits()
                })
        })
}

/// Decides `inputs` under `limits` (timed), logs it against the host's, returns the verdict.
fn decide_and_check(
    clock: Clock,
    what: &str,
    inputs: &Inputs,
    limits: &DecisionLimits,
    expected: &Result<Expected, DecisionError>,
) -> bool {
    let rows = inputs.rows();
    let rows = rows.get(..inputs.popups).unwrap_or(&[]);
    let (got, ticks) = crate::with_stack_peak("decide", || {
        let t = clock.now();
        let got = decide(rows, limits);
        (got, clock.now() - t)
    });
    let bound = inputs.bound();
    match &got {
        Ok(d) => defmt::info!(
            "{=str}: choice {=[u8]}, risk {=f32}, mean time {=f32}, mean fuel {=f32}; work {=u64} of bound {=u64}; {=u64} ticks = {=u64} us",
            what,
            d.choice.as_slice(),
            d.risk,
            d.mean_time,
            d.mean_fuel,
            d.work,
            bound,
            ticks,
            Clock::ticks_to_us(ticks)
        ),
        Err(e) => defmt::info!(
            "{=str}: {}; bound {=u64} per search (3 searches); {=u64} ticks = {=u64} us",
            what,
            e,
            bound,
            ticks,
            Clock::ticks_to_us(ticks)
        ),
    }
    let ok = same(&got, expected);
    if !ok {
        defmt::error!(
            "{=str}: the host decided {}",
            what,
            defmt::Debug2Format(expected)
        );
    }
    ok && got.as_ref().map_or(true, |d| d.work <= bound)
}

/// Runs every announcement and the worst case; true only if all equal the host's.
pub fn run(clock: Clock, fixture: &RuzFixture) -> bool {
    defmt::info!(
        "ruz decision: {=usize} pop-ups, nominal route {=u32} steps; at most {=usize} pop-ups of {=usize} alternatives",
        fixture.alternatives.len(),
        fixture.nominal_steps,
        MAX_DECISION_POPUPS,
        MAX_ALTERNATIVES
    );
    let mut verdict = fixture.alternatives.len() <= MAX_DECISION_POPUPS;
    for a in fixture.announcements {
        defmt::info!("announced: {=str}", a.what);
        for (name, p) in fixture.names.iter().zip(a.appearance) {
            defmt::info!("  {=str}: P_A {=f32}", name, p);
        }
        let t = clock.now();
        let inputs = recompute(fixture, a.appearance);
        let ticks = clock.now() - t;
        let ok = same_inputs(&inputs, a.inputs);
        defmt::info!(
            "  R_K, f_t, F_c of every alternative recomputed in {=u64} ticks = {=u64} us: {=str}",
            ticks,
            Clock::ticks_to_us(ticks),
            if ok {
                "equal to the host's"
            } else {
                "DIFFERENT from the host's"
            }
        );
        verdict &= ok;
        verdict &= decide_and_check(clock, "  decision", &inputs, &a.limits, &a.expected);
    }
    let worst = Inputs::from_rows(fixture.worst);
    defmt::info!(
        "worst case: {=usize} pop-ups x {=usize} alternatives that no cut prunes",
        worst.popups,
        fixture.worst.first().map_or(0, |r| r.len())
    );
    verdict &= decide_and_check(
        clock,
        "  decision",
        &worst,
        &fixture.worst_limits,
        &fixture.worst_expected,
    );
    defmt::info!("SysTick at {=u32} Hz", clock::CORE_HZ);
    log_stack();
    if verdict {
        defmt::info!(
            "PASS: {=usize} announcements and the worst case decided as on the host",
            fixture.announcements.len()
        );
    }
    verdict
}
