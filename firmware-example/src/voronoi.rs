//! Voronoi mode (Judd & McLain) on the flight computer: plan through radar threats, a radar
//! pops up in flight, plan again from where the aircraft is.
//!
//! 1. [`boot`], then `load_voronoi` into the caller's `VoronoiStorage` (the image validated,
//!    the diagram of its threat sites built onboard and checked against the stored graph;
//!    timed);
//! 2. one [`RouteTask`] cycle plans the fixture's start → goal (Dijkstra over the onboard
//!    graph, then the smoothing), budget `Planner::worst_case_work()`;
//! 3. `add_threat` with the fixture's radar through [`RouteTask::planner`] between cycles, as a
//!    threat warning receiver would (the site inserted into the diagram, the graph rebuilt;
//!    timed);
//! 4. one more cycle re-plans from [`VoronoiFixture::replan_start`], a pose along the first
//!    route;
//! 5. the verdict: every answer equals the host's exactly (length, pieces, chords, network
//!    edges, work; the `add_threat` summary), and each counted work is within its bound.

use crate::autopilot::RouteTask;
use crate::clock::{self, Clock};
use crate::{boot, log_stack, PERIOD_MS};
use skyroute::planner::{
    threat_rebuild_work_bound, RouteSummary, ThreatSummary, VoronoiStorage, VORONOI_GRAPH_VERTICES,
};
use skyroute::{Goal, PlanError, Planner, Pose, Query, Search, Vec2};

/// What one plan answered on the host: the figures the firmware compares.
#[derive(Clone, Copy)]
pub struct Answer {
    /// Route length, metres.
    pub length: f32,
    /// Smoothed pieces (`Planner::route_pieces`).
    pub pieces: u32,
    /// Line chords (`Planner::route`).
    pub chords: u32,
    /// Graph edges and links of the coarse route.
    pub network_edges: u32,
    /// Counted work.
    pub work: u64,
}

/// What the Voronoi binary's `query.rs` holds: the query, the radar that pops up, the re-plan's
/// start and every answer of the host.
pub struct VoronoiFixture {
    /// The aircraft's pose when it first plans.
    pub start: Pose,
    /// Where to go (the same goal for the re-plan).
    pub goal: Goal,
    /// The host's `Planner::worst_case_work()`: the budget of every plan.
    pub budget: u64,
    /// The first plan.
    pub first: Answer,
    /// The radar that pops up: site x, y and reference distance, metres.
    pub threat: (f32, f32, f32),
    /// The host's `add_threat` summary.
    pub expected_threat: ThreatSummary,
    /// `threat_rebuild_work_bound` of the network's sites, as the host computed it.
    pub load_diagram_bound: u64,
    /// `threat_rebuild_work_bound` of the threats after `add_threat`, as the host computed it.
    pub threat_bound: u64,
    /// The pose the re-plan starts from.
    pub replan_start: Pose,
    /// The re-plan.
    pub replan: Answer,
}

/// The task type: the planner, SysTick as delay and clock.
type Task<'p, 'n, const V: usize, const E: usize, const P: usize, const R: usize> =
    RouteTask<'p, 'n, Clock, Clock, V, E, P, R>;

/// Boots, loads `network` into `planner` with `storage`, plans, adds the fixture's radar and
/// re-plans; true only if every answer equals the host's.
pub fn run<const V: usize, const E: usize, const P: usize, const R: usize>(
    planner: &mut Planner<'static, V, E, P, R>,
    storage: &'static mut VoronoiStorage,
    network: &'static [u8],
    fixture: &VoronoiFixture,
) -> bool {
    let Some(clock) = boot::<V, E, P, R>() else {
        return false;
    };
    defmt::info!(
        "voronoi storage: {=usize} B; the planner needs V >= {=usize}",
        core::mem::size_of::<VoronoiStorage>(),
        VORONOI_GRAPH_VERTICES
    );
    let (loaded, load_ticks) = crate::with_stack_peak("load_voronoi", || {
        let t = clock.now();
        let loaded = planner.load_voronoi(network, storage);
        (loaded, clock.now() - t)
    });
    if let Err(e) = loaded {
        defmt::error!("load_voronoi failed: {}", e);
        return false;
    }
    let sites = planner.threats().len() as u64;
    let net = planner.network();
    let graph = planner.threat_graph().map_or((0, 0), |g| {
        (g.vertices().len() as u32, g.edges().len() as u32)
    });
    defmt::info!(
        "network: {=u32} vertices, {=u32} edges, {=usize} B in flash, {=u64} threat sites, onboard graph {=u32} vertices {=u32} edges, k = {=f32}",
        net.vertex_count(),
        net.edge_count(),
        net.byte_len(),
        sites,
        graph.0,
        graph.1,
        planner.threat_weight().unwrap_or(f32::NAN)
    );
    defmt::info!(
        "load_voronoi (validation, diagram of {=u64} sites, graph) took {=u64} ticks = {=u64} us; diagram bound {=u64} work (host {=u64})",
        sites,
        load_ticks,
        Clock::ticks_to_us(load_ticks),
        threat_rebuild_work_bound(sites),
        fixture.load_diagram_bound
    );
    let budget = planner.worst_case_work();
    defmt::info!(
        "worst-case work bound {=u64} (host {=u64}): the budget",
        budget,
        fixture.budget
    );
    let mut verdict = budget == fixture.budget;
    if !verdict {
        defmt::error!("the host computed a different bound: fixture out of date?");
    }

    let mut task: Task<'_, '_, V, E, P, R> =
        RouteTask::new(planner, clock, clock, PERIOD_MS, budget);
    let query = Query {
        start: fixture.start,
        goal: fixture.goal,
        search: Search::Dijkstra,
    };
    defmt::info!("query: {}", query);
    let (first, ticks) = task.plan_once(query);
    verdict &= check("plan", &mut task, first, ticks, &fixture.first, budget);

    verdict &= pop_up(&mut task, clock, fixture);

    let requery = Query {
        start: fixture.replan_start,
        ..query
    };
    defmt::info!("re-plan query: {}", requery);
    let (second, ticks) = task.plan_once(requery);
    verdict &= check("re-plan", &mut task, second, ticks, &fixture.replan, budget);

    log_stack();
    if verdict {
        defmt::info!(
            "PASS: route {=f32} m and, after the pop-up radar, {=f32} m: equal to the host's",
            fixture.first.length,
            fixture.replan.length
        );
    }
    verdict
}

/// `add_threat` with the fixture's radar (timed); true only if its summary equals the host's
/// and its work is within `threat_rebuild_work_bound`.
fn pop_up<const V: usize, const E: usize, const P: usize, const R: usize>(
    task: &mut Task<'_, '_, V, E, P, R>,
    clock: Clock,
    fixture: &VoronoiFixture,
) -> bool {
    let (x, y, radius) = fixture.threat;
    let (added, ticks) = crate::with_stack_peak("add_threat", || {
        let t = clock.now();
        let added = task.planner().add_threat(Vec2::new(x, y), radius);
        (added, clock.now() - t)
    });
    let s = match added {
        Ok(s) => s,
        Err(e) => {
            defmt::error!("add_threat failed: {}", e);
            return false;
        }
    };
    let bound = threat_rebuild_work_bound(s.threats as u64);
    defmt::info!(
        "add_threat ({=f32}, {=f32}) r={=f32} m: {} in {=u64} ticks = {=u64} us, work {=u64} of bound {=u64}",
        x,
        y,
        radius,
        s,
        ticks,
        Clock::ticks_to_us(ticks),
        s.work,
        bound
    );
    let same = s == fixture.expected_threat && bound == fixture.threat_bound;
    if !same {
        defmt::error!(
            "add_threat: {} (bound {=u64}); host: {} (bound {=u64})",
            s,
            bound,
            fixture.expected_threat,
            fixture.threat_bound
        );
    }
    same && s.work <= bound
}

/// One plan's verdict: logs it, true only if it equals `expected` and its work is within
/// `budget`.
fn check<const V: usize, const E: usize, const P: usize, const R: usize>(
    what: &str,
    task: &mut Task<'_, '_, V, E, P, R>,
    outcome: Result<RouteSummary, PlanError>,
    ticks: u64,
    expected: &Answer,
    budget: u64,
) -> bool {
    let s = match outcome {
        Ok(s) => s,
        Err(e) => {
            defmt::error!("{=str} failed after {=u64} ticks: {}", what, ticks, e);
            return false;
        }
    };
    let planner = task.planner();
    let pieces = planner.route_pieces().len() as u32;
    let chords = planner.route().len() as u32;
    defmt::info!(
        "{=str}: route {=f32} m, {=u32} pieces, {=u32} chords, {=u32} network edges, arrival heading {=f32} rad, chords within {=f32} m",
        what,
        s.length,
        pieces,
        chords,
        s.network_edges,
        s.arrival_heading,
        planner.chord_deviation().unwrap_or(f32::NAN)
    );
    defmt::info!(
        "{=str}: work {=u64} of bound {=u64}: {}",
        what,
        s.work.total(),
        budget,
        s.work
    );
    defmt::info!(
        "{=str}: took {=u64} SysTick ticks = {=u64} us at {=u32} Hz",
        what,
        ticks,
        Clock::ticks_to_us(ticks),
        clock::CORE_HZ
    );
    for (i, p) in planner.route_pieces().iter().enumerate() {
        defmt::debug!("  piece {=usize}: {}", i, p);
    }
    let same = s.length == expected.length
        && pieces == expected.pieces
        && chords == expected.chords
        && s.network_edges == expected.network_edges
        && s.work.total() == expected.work;
    if !same {
        defmt::error!(
            "{=str}: {=f32} m, {=u32} pieces, {=u32} chords, {=u32} edges, work {=u64}; host: {=f32} m, {=u32} pieces, {=u32} chords, {=u32} edges, work {=u64}",
            what,
            s.length,
            pieces,
            chords,
            s.network_edges,
            s.work.total(),
            expected.length,
            expected.pieces,
            expected.chords,
            expected.network_edges,
            expected.work
        );
    }
    same && s.work.total() <= budget
}
