//! Roadmap and terrain mode on the flight computer: a pop-up, then periodic re-planning.
//!
//! 1. on a three-dimensional roadmap, `set_query_altitudes` with the fixture's; then
//!    `add_popup_with_height` with the fixture's disc and top (a wall in the plane; timed with
//!    SysTick); the work bound after it must be the host's budget (a warning otherwise: the
//!    fixture is out of date);
//! 2. [`CYCLES`] cycles of the [`RouteTask`] every [`PERIOD_MS`](crate::PERIOD_MS): the
//!    fixture's query, Dijkstra, budget [`RouteFixture::budget`]; each `plan` call is timed;
//! 3. one more `plan` of the same query with [`Planner::plan_observed`], timing each [`Phase`]
//!    (connect the start, connect the goal, search, write the route) with SysTick;
//! 4. the verdict: every cycle's route length is within [`TOLERANCE`] (relative) of the host's
//!    and its primitives are all in the route; on a three-dimensional roadmap, the sum of the
//!    route's altitudes at its primitives' middles is within [`TOLERANCE`] of the host's too.

use crate::autopilot::{Cycle, Next, RouteTask};
use crate::clock::{self, Clock};
use crate::{log_stack, PERIOD_MS};
use skyroute::network::Mode;
use skyroute::planner::Work;
use skyroute::{Goal, Phase, Planner, Popup, Pose, Query, Search, Vec2};

/// What a roadmap or terrain binary's `query.rs` holds for this mission: the query, the pop-up,
/// and the host's answer.
pub struct RouteFixture {
    /// The aircraft's pose when it plans.
    pub start: Pose,
    /// Where to go.
    pub goal: Goal,
    /// The pop-up disc: centre x, centre y, radius (metres).
    pub popup: (f32, f32, f32),
    /// The pop-up's top, metres (`f32::INFINITY`: a wall).
    pub popup_height: f32,
    /// Three-dimensional roadmap: the start's and goal's altitudes (`None` in the plane).
    pub altitudes: Option<(f32, f32)>,
    /// The host's sum over the route's primitives of the altitude at each one's middle (0 in
    /// the plane).
    pub expected_altitude_sum: f32,
    /// Route length the host computed, metres.
    pub expected_length: f32,
    /// Route primitives the host computed.
    pub expected_primitives: u32,
    /// Work the host counted.
    pub expected_work: u64,
    /// Work budget of each plan: the network's worst case (the host's `Planner::worst_case_work`).
    pub budget: u64,
    /// The start as the autopilot gives it: longitude, latitude, compass heading (degrees).
    pub start_geo: (f64, f64, f64),
    /// `start_geo` in the network's frame as the host converts it.
    pub start_from_geo: Pose,
}

/// Plan cycles to run.
pub const CYCLES: u32 = 3;
/// Largest accepted relative difference between the target's and the host's route length.
pub const TOLERANCE: f32 = 1e-4;

/// Converts the start from latitude and longitude, adds the fixture's pop-up, then plans
/// [`CYCLES`] times with the [`RouteTask`]; true only if the conversion and every route's length
/// match the host's.
pub fn run<const V: usize, const E: usize, const P: usize, const R: usize>(
    planner: &mut Planner<'_, V, E, P, R>,
    clock: Clock,
    fixture: &RouteFixture,
) -> bool {
    if !convert_start(planner, clock, fixture) {
        return false;
    }
    if let Some((from, to)) = fixture.altitudes {
        if let Err(e) = planner.set_query_altitudes(from, to) {
            defmt::error!("set_query_altitudes failed: {}", e);
            return false;
        }
        defmt::info!("three-dimensional: from {=f32} m to {=f32} m", from, to);
    }
    let (x, y, radius) = fixture.popup;
    let (popup, popup_ticks) = crate::with_stack_peak("add_popup", || {
        let t = clock.now();
        let disc = Popup::Circle {
            centre: Vec2::new(x, y),
            radius,
        };
        let popup = planner.add_popup_with_height(disc, fixture.popup_height);
        (popup, clock.now() - t)
    });
    match popup {
        Ok(s) => defmt::info!(
            "pop-up ({=f32}, {=f32}) r={=f32} m up to {=f32} m: {} in {=u64} ticks, bound {=u64} work",
            x,
            y,
            radius,
            fixture.popup_height,
            s,
            popup_ticks,
            planner.worst_case_popup_work()
        ),
        Err(e) => {
            defmt::error!("add_popup failed: {}", e);
            return false;
        }
    }

    let bound = planner.worst_case_work();
    defmt::info!(
        "worst-case work bound {=u64}, budget {=u64}",
        bound,
        fixture.budget
    );
    if bound != fixture.budget {
        defmt::warn!("the host computed a different bound: fixture out of date?");
    }

    let query = Query {
        start: fixture.start,
        goal: fixture.goal,
        search: Search::Dijkstra,
    };
    let mut verdict = false;
    let mut task = RouteTask::new(planner, clock, clock, PERIOD_MS, fixture.budget);
    let cycles = task.run(
        // Query source: an autopilot reads its navigation filter and mission here.
        |_| query,
        // Route sink: an autopilot hands the primitives to path following here.
        |cycle: &Cycle<'_>| {
            let summary = match cycle.outcome {
                Ok(s) => s,
                Err(e) => {
                    defmt::error!("cycle {=u32}: plan failed: {}", cycle.index, e);
                    verdict = false;
                    return Next::Stop;
                }
            };
            if cycle.index == 0 {
                defmt::info!("query: {}", cycle.query);
            }
            defmt::info!(
                "cycle {=u32}: route {=f32} m, {=u32} primitives (host {=u32}), {=u32} network edges, arrival heading {=f32} rad",
                cycle.index,
                summary.length,
                summary.primitives,
                fixture.expected_primitives,
                summary.network_edges,
                summary.arrival_heading
            );
            defmt::info!(
                "cycle {=u32}: work {=u64} (host {=u64}) of bound {=u64}: {}",
                cycle.index,
                summary.work.total(),
                fixture.expected_work,
                bound,
                summary.work
            );
            defmt::info!(
                "cycle {=u32}: plan took {=u64} SysTick ticks = {=u64} us at {=u32} Hz",
                cycle.index,
                cycle.plan_ticks,
                Clock::ticks_to_us(cycle.plan_ticks),
                clock::CORE_HZ
            );
            if cycle.index == 0 {
                for (i, p) in cycle.route.iter().enumerate() {
                    defmt::debug!("  primitive {=usize}: {}", i, p);
                }
            }
            let expected = fixture.expected_length;
            let error = (summary.length - expected).abs() / expected;
            verdict = error < TOLERANCE && summary.primitives == cycle.route.len() as u32;
            if !verdict {
                defmt::error!(
                    "route length {=f32} m, host expected {=f32} m (relative error {=f32})",
                    summary.length,
                    expected,
                    error
                );
                return Next::Stop;
            }
            if cycle.index + 1 < CYCLES {
                Next::Continue
            } else {
                Next::Stop
            }
        },
    );
    verdict &= altitudes_match(task.planner(), fixture);
    verdict &= log_phases(task.planner(), clock, &query, fixture.budget);
    match task.planner().network().mode() {
        Mode::Terrain => defmt::info!(
            "turn arcs checked in the last query: {}",
            task.planner().arc_check_stats()
        ),
        Mode::Roadmap | Mode::Landmark | Mode::Voronoi | Mode::Unknown(_) => {}
    }
    log_stack();
    if verdict {
        defmt::info!(
            "PASS: {=u32} cycles, route length {=f32} m matches the host's {=f32} m",
            cycles,
            task.planner()
                .route_summary()
                .map_or(f32::NAN, |s| s.length),
            fixture.expected_length
        );
    }
    verdict
}

/// Whether the route's altitudes match the host's: the sum over its primitives of the altitude
/// at each one's middle ([`Planner::route_altitude_at`]) within [`TOLERANCE`] (relative) of the
/// fixture's. True in the plane, where there are none and the host's sum is 0.
fn altitudes_match<const V: usize, const E: usize, const P: usize, const R: usize>(
    planner: &Planner<'_, V, E, P, R>,
    fixture: &RouteFixture,
) -> bool {
    let route = planner.route();
    let sum: f32 = (0..route.len())
        .filter_map(|k| {
            let half = 0.5 * route.get(k)?.length();
            planner.route_altitude_at(k, half)
        })
        .sum();
    let expected = fixture.expected_altitude_sum;
    let error = (sum - expected).abs() / expected.abs().max(1.0);
    if fixture.altitudes.is_some() {
        defmt::info!(
            "route altitudes: sum at the primitives' middles {=f32} m (host {=f32} m)",
            sum,
            expected
        );
    }
    if error >= TOLERANCE {
        defmt::error!(
            "route altitudes sum {=f32} m, host {=f32} m (relative error {=f32})",
            sum,
            expected,
            error
        );
    }
    error < TOLERANCE
}

/// Plans `query` once more, timing each [`Phase`] with `clock` (the observer reads SysTick at
/// every phase boundary, a few dozen ticks each), and logs each phase's ticks and counted work.
/// False if the plan fails.
fn log_phases<const V: usize, const E: usize, const P: usize, const R: usize>(
    planner: &mut Planner<'_, V, E, P, R>,
    clock: Clock,
    query: &Query,
    budget: u64,
) -> bool {
    let mut open: Option<(Phase, u64, u64)> = None;
    let (outcome, ticks) = crate::with_stack_peak("plan", || {
        let t0 = clock.now();
        let outcome = planner.plan_observed(query, budget, &mut |phase: Phase, work: &Work| {
            let now = clock.now();
            if let Some((begun, t, w)) = open.take() {
                defmt::info!(
                    "phase {}: {=u64} ticks, work {=u64}",
                    begun,
                    now - t,
                    work.total() - w
                );
            }
            if phase != Phase::Done {
                open = Some((phase, clock.now(), work.total()));
            }
        });
        (outcome, clock.now() - t0)
    });
    match outcome {
        Ok(s) => {
            defmt::info!(
                "phases: plan took {=u64} ticks with the observer, route {=f32} m",
                ticks,
                s.length
            );
            true
        }
        Err(e) => {
            defmt::error!("observed plan failed: {}", e);
            false
        }
    }
}

/// Converts the fixture's start from longitude, latitude and compass heading to the network's
/// frame, as an autopilot passes its position ([`skyroute::LocalFrame::pose`], `f64` maths in
/// software on the M4F), timed; true only if the pose is the host's bit for bit.
fn convert_start<const V: usize, const E: usize, const P: usize, const R: usize>(
    planner: &Planner<'_, V, E, P, R>,
    clock: Clock,
    fixture: &RouteFixture,
) -> bool {
    let (lon, lat, compass) = fixture.start_geo;
    let t = clock.now();
    let converted = planner.network().local_frame().pose(lon, lat, compass);
    let ticks = clock.now() - t;
    let want = fixture.start_from_geo;
    match converted {
        Ok(p) if same_bits(&p, &want) => {
            defmt::info!(
                "start from lon {=f64} lat {=f64} compass {=f64}: {} in {=u64} ticks, the host's bit for bit",
                lon,
                lat,
                compass,
                p,
                ticks
            );
            true
        }
        Ok(p) => {
            defmt::error!("start from lat/lon: {}, host {}", p, want);
            false
        }
        Err(e) => {
            defmt::error!("start from lat/lon refused: {}", e);
            false
        }
    }
}

/// Whether two poses have the same bits.
fn same_bits(a: &Pose, b: &Pose) -> bool {
    a.position.x.to_bits() == b.position.x.to_bits()
        && a.position.y.to_bits() == b.position.y.to_bits()
        && a.heading.to_bits() == b.heading.to_bits()
}
