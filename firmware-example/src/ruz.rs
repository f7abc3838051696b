//! The pop-up switch of Ruz et al. on the flight computer: the network image stores each
//! potential pop-up's bypass alternatives (figures and discs, from the ground tool); pop-ups
//! are announced in flight with their appearance probabilities; the aircraft decides one
//! alternative per pop-up and re-plans round the chosen ones.
//!
//! 1. the nominal route: the scenario's start → goal planned as the ground tool plans a
//!    mission's leg ([`plan_leg`]: A*, connection widened when an end does not connect, then
//!    the shortcut and heading-smoothing passes);
//! 2. for every announcement of the fixture: `decide_stored` recomputes each announced pop-up's
//!    alternatives' R_K, f_t, F_c from the stored figures and decides (timed); on a choice,
//!    `fly_alternatives` adds the chosen alternatives' discs as pop-ups (timed), the leg is
//!    planned again (timed) and the discs removed;
//! 3. the verdict: every decision (choice, total risk, mean factors and work, or the
//!    infeasibility with its tightest limit) and every route (length, primitives, counted work)
//!    equals the host's bit for bit, and the decision's work is within `decision_work_bound`.
//!
//! Then the worst case of the decision alone: a synthetic instance of the most pop-ups and
//! alternatives whose search cuts nothing, timed against `decision_work_bound`.

use crate::clock::{self, Clock};
use crate::log_stack;
use skyroute::planner::alternatives::{decide_stored, Announced, SwitchError};
use skyroute::planner::decision::{
    decide, decision_work_bound, Alternative, Decision, DecisionError, DecisionLimits,
    MAX_ALTERNATIVES, MAX_DECISION_POPUPS,
};
use skyroute::planner::{PlanError, PlannerConfig};
use skyroute::{Planner, Query};

/// What the host decided: the choice and its figures.
#[derive(Clone, Copy, Debug, defmt::Format)]
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

/// A route the host planned: the discs flown round, its length, primitives and counted work
/// (plan, shortcut and smoothing).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Flown {
    /// Pop-up discs active.
    pub discs: u8,
    /// Length, metres.
    pub length: f32,
    /// Lines and arcs.
    pub primitives: u32,
    /// Work counted.
    pub work: u64,
}

/// One announcement: the pop-ups and their appearance probabilities, the limits, and the
/// host's answers.
pub struct Announcement {
    /// What happened, for the log.
    pub what: &'static str,
    /// The announced pop-ups (indices into the image's stored ones) with P_A.
    pub announced: &'static [Announced],
    /// T_max and F_cmax.
    pub limits: DecisionLimits,
    /// The host's decision.
    pub expected: Result<Expected, DecisionError>,
    /// The route flying the host's choice (none when infeasible).
    pub flown: Option<Flown>,
}

/// Everything the `ruz` binary's `query.rs` holds.
pub struct RuzFixture {
    /// The stored pop-ups' names.
    pub names: &'static [&'static str],
    /// The scenario's start → goal.
    pub query: Query,
    /// The connection settings when an end does not connect with the default's.
    pub wide_config: PlannerConfig,
    /// Candidate headings of the heading-smoothing pass.
    pub smoothing_headings: u16,
    /// Work budget of each pass.
    pub budget: u64,
    /// The nominal route as the host planned it.
    pub nominal: Flown,
    /// The announcements, in order.
    pub announcements: &'static [Announcement],
    /// The decision's worst-case instance.
    pub worst: &'static [&'static [Alternative]],
    /// Its limits.
    pub worst_limits: DecisionLimits,
    /// The host's decision of it.
    pub worst_expected: Result<Expected, DecisionError>,
}

/// `decision_work_bound` of the first [`MAX_DECISION_POPUPS`] alternative counts of `counts`.
fn bound_of(counts: impl Iterator<Item = usize>) -> u64 {
    let mut c = [0usize; MAX_DECISION_POPUPS];
    let mut n = 0;
    for (slot, k) in c.iter_mut().zip(counts) {
        *slot = k;
        n += 1;
    }
    decision_work_bound(c.get(..n).unwrap_or(&[]))
}

/// The decision's work bound for the stored alternatives of `announced`.
fn stored_bound<const V: usize, const E: usize, const P: usize, const R: usize>(
    planner: &Planner<'_, V, E, P, R>,
    announced: &[Announced],
) -> u64 {
    let net = planner.network();
    bound_of(announced.iter().map(|a| {
        net.stored_popup(a.popup as u32)
            .map_or(0, |p| p.alternatives as usize)
    }))
}

/// Plans `fixture.query` as the ground tool plans a mission's leg: A* with the default
/// connection, again with [`RuzFixture::wide_config`] when an end does not connect, then the
/// shortcut and heading-smoothing passes (Niendorf et al. §V). Returns the route's figures and
/// the SysTick ticks it took.
pub fn plan_leg<const V: usize, const E: usize, const P: usize, const R: usize>(
    planner: &mut Planner<'_, V, E, P, R>,
    clock: Clock,
    fixture: &RuzFixture,
    discs: u8,
) -> Result<(Flown, u64), PlanError> {
    let t = clock.now();
    let planned = match planner.plan(&fixture.query, fixture.budget) {
        Err(PlanError::StartUnconnected | PlanError::GoalUnconnected) => {
            planner.set_config(fixture.wide_config);
            let second = planner.plan(&fixture.query, fixture.budget);
            planner.set_config(PlannerConfig::DEFAULT);
            second
        }
        other => other,
    }?;
    let shortcut = planner.shortcut(fixture.budget)?;
    let smooth = planner.smooth_headings(fixture.smoothing_headings, fixture.budget)?;
    let ticks = clock.now() - t;
    let s = planner.route_summary().ok_or(PlanError::Internal)?;
    let flown = Flown {
        discs,
        length: s.length,
        primitives: s.primitives,
        work: planned.work.total() + shortcut.work.total() + smooth.work.total(),
    };
    Ok((flown, ticks))
}

/// Whether a route equals the host's bit for bit; logs it.
fn same_route(what: &str, got: &Flown, ticks: u64, want: &Flown) -> bool {
    defmt::info!(
        "{=str}: {=u8} discs, route {=f32} m, {=u32} primitives, work {=u64}; {=u64} ticks = {=u64} us",
        what,
        got.discs,
        got.length,
        got.primitives,
        got.work,
        ticks,
        Clock::ticks_to_us(ticks)
    );
    let ok = got.discs == want.discs
        && got.length.to_bits() == want.length.to_bits()
        && got.primitives == want.primitives
        && got.work == want.work;
    if !ok {
        defmt::error!(
            "{=str}: the host flew {=u8} discs, {=f32} m, {=u32} primitives, work {=u64}",
            what,
            want.discs,
            want.length,
            want.primitives,
            want.work
        );
    }
    ok
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

/// Logs a decision against the host's and returns the verdict: the same answer bit for bit,
/// and the work within `bound`.
fn check_decision(
    what: &str,
    got: &Result<Decision, DecisionError>,
    ticks: u64,
    bound: u64,
    expected: &Result<Expected, DecisionError>,
) -> bool {
    match got {
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
    let ok = same(got, expected);
    if !ok {
        defmt::error!("{=str}: the host decided {}", what, expected);
    }
    ok && got.as_ref().map_or(true, |d| d.work <= bound)
}

/// Decides one announcement from the stored alternatives, flies the choice, re-plans and
/// removes the discs; true only if everything equals the host's.
fn announce<const V: usize, const E: usize, const P: usize, const R: usize>(
    planner: &mut Planner<'_, V, E, P, R>,
    clock: Clock,
    fixture: &RuzFixture,
    a: &Announcement,
) -> bool {
    defmt::info!("announced: {=str}", a.what);
    for x in a.announced {
        let name = fixture.names.get(x.popup as usize).copied().unwrap_or("?");
        defmt::info!("  {=str}: P_A {=f32}", name, x.appearance);
    }
    let net = *planner.network();
    let (got, ticks) = crate::with_stack_peak("decide_stored", || {
        let t = clock.now();
        let got = decide_stored(&net, a.announced, &a.limits);
        (got, clock.now() - t)
    });
    let got = match got {
        Ok(d) => Ok(d),
        Err(SwitchError::Decision(e)) => Err(e),
        Err(e) => {
            defmt::error!("  decide_stored refused the announcement: {}", e);
            return false;
        }
    };
    let bound = stored_bound(planner, a.announced);
    let mut ok = check_decision("  decision", &got, ticks, bound, &a.expected);
    let (Ok(d), Some(want)) = (&got, &a.flown) else {
        return ok && got.is_err() && a.flown.is_none();
    };
    let (ids, ticks) = crate::with_stack_peak("fly_alternatives", || {
        let t = clock.now();
        let ids = planner.fly_alternatives(a.announced, &d.choice);
        (ids, clock.now() - t)
    });
    let ids = match ids {
        Ok(ids) => ids,
        Err(e) => {
            defmt::error!("  fly_alternatives failed: {}", e);
            return false;
        }
    };
    defmt::info!(
        "  fly_alternatives: {=usize} discs added as pop-ups in {=u64} ticks = {=u64} us",
        ids.len(),
        ticks,
        Clock::ticks_to_us(ticks)
    );
    let discs = ids.len() as u8;
    match crate::with_stack_peak("plan_leg", || plan_leg(planner, clock, fixture, discs)) {
        Ok((flown, ticks)) => ok &= same_route("  re-planned", &flown, ticks, want),
        Err(e) => {
            defmt::error!("  re-plan failed: {}", e);
            ok = false;
        }
    }
    for id in ids {
        ok &= planner.remove_popup(id).is_ok();
    }
    ok
}

/// Plans the nominal route, runs every announcement and the decision's worst case; true only
/// if all equal the host's.
pub fn run<const V: usize, const E: usize, const P: usize, const R: usize>(
    planner: &mut Planner<'_, V, E, P, R>,
    clock: Clock,
    fixture: &RuzFixture,
) -> bool {
    let stored = planner.network().alternatives_summary();
    let Some(stored) = stored else {
        defmt::error!("the network stores no pop-up alternatives");
        return false;
    };
    defmt::info!(
        "ruz switch: {=u32} stored pop-ups, nominal route {=u32} steps, limits {=f32} (time) {=f32} (fuel); at most {=usize} pop-ups of {=usize} alternatives",
        stored.popups,
        stored.nominal_steps,
        stored.time_limit,
        stored.fuel_limit,
        MAX_DECISION_POPUPS,
        MAX_ALTERNATIVES
    );
    let mut verdict =
        match crate::with_stack_peak("plan_leg", || plan_leg(planner, clock, fixture, 0)) {
            Ok((flown, ticks)) => same_route("nominal route", &flown, ticks, &fixture.nominal),
            Err(e) => {
                defmt::error!("the nominal route: {}", e);
                false
            }
        };
    for a in fixture.announcements {
        verdict &= announce(planner, clock, fixture, a);
    }
    let worst = fixture.worst;
    defmt::info!(
        "worst case: {=usize} pop-ups x {=usize} alternatives that no cut prunes",
        worst.len(),
        worst.first().map_or(0, |r| r.len())
    );
    let (got, ticks) = crate::with_stack_peak("decide", || {
        let t = clock.now();
        let got = decide(worst, &fixture.worst_limits);
        (got, clock.now() - t)
    });
    let bound = bound_of(worst.iter().map(|r| r.len()));
    verdict &= check_decision("  decision", &got, ticks, bound, &fixture.worst_expected);
    defmt::info!("SysTick at {=u32} Hz", clock::CORE_HZ);
    log_stack();
    if verdict {
        defmt::info!(
            "PASS: the nominal route, {=usize} announcements and the worst case as on the host",
            fixture.announcements.len()
        );
    }
    verdict
}
