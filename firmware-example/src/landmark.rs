//! Landmark mode (Babel) on the flight computer: plan from the network's stored start to its
//! stored goal in the fixture's weather, then lose a landmark in flight and plan again.
//!
//! 1. `set_weather` with the fixture's weather; the query is the stored start vertex's pose →
//!    the stored goal vertex's position with a free heading, Dijkstra, budget
//!    `Planner::worst_case_work()`; one [`RouteTask`] cycle plans it (timed with SysTick) and
//!    the route's overflights are logged (landmark, compass direction, the leg's cost from
//!    `route_edges` + `edge_link`);
//! 2. `update_rosette(lost_landmark, &[0.0; D])` — the fixture's landmark (the first one the
//!    route overflies) is lost — through [`RouteTask::planner`] between cycles, as a navigation
//!    monitor would, then one more cycle re-plans;
//! 3. a start that is no network vertex (halfway along the re-plan's first edge), with
//!    the range left set by `set_start_range`: the core joins it to the overflights online
//!    and plans again, the landmark still lost;
//! 4. the verdict: the three answers equal the host's exactly ([`LandmarkFixture`]: length,
//!    edges, pieces, work; or a plan fails on both), and the later routes avoid the lost
//!    landmark.

use crate::autopilot::RouteTask;
use crate::clock::{self, Clock};
use crate::{log_stack, PERIOD_MS};
use skyroute::planner::{RouteSummary, MAX_ROSETTE_DIRECTIONS};
use skyroute::{Goal, Network, PlanError, Planner, Pose, Query, Search};

/// What the landmark binary's `query.rs` holds for this mission: the weather, the landmark to
/// lose, and both answers of the host.
pub struct LandmarkFixture {
    /// The weather in force (`Planner::set_weather`).
    pub weather: u32,
    /// Route length the host computed, stored start → stored goal, metres.
    pub expected_length: f32,
    /// Hermite pieces of that route.
    pub expected_primitives: u32,
    /// Network edges of that route.
    pub expected_network_edges: u32,
    /// Work the host counted.
    pub expected_work: u64,
    /// The network's worst-case work (the host's `Planner::worst_case_work`), compared with the
    /// target's own, which is the budget.
    pub budget: u64,
    /// The landmark lost in flight (all-zero rosette): the first one the route overflies.
    pub lost_landmark: u32,
    /// The host's re-plan after losing it: `Some((length m, network edges, work))`, or `None`
    /// when its `plan` failed.
    pub expected_replan: Option<(f32, u32, u64)>,
    /// A start that is no network vertex, `(x, y, heading)`.
    pub online_start: (f32, f32, f32),
    /// The range left there, metres.
    pub online_range: f32,
    /// The host's plan from it, the landmark still lost (as `expected_replan`).
    pub expected_online: Option<(f32, u32, u64)>,
}

/// The task type: the planner, SysTick as delay and clock.
type Task<'p, 'n, const V: usize, const E: usize, const P: usize, const R: usize> =
    RouteTask<'p, 'n, Clock, Clock, V, E, P, R>;

/// Plans from the stored start to the stored goal, loses
/// [`LandmarkFixture::lost_landmark`], plans again; true only if both answers equal the host's.
pub fn run<const V: usize, const E: usize, const P: usize, const R: usize>(
    planner: &mut Planner<'_, V, E, P, R>,
    clock: Clock,
    fixture: &LandmarkFixture,
) -> bool {
    let net = *planner.network();
    let Some(l) = net.landmark().copied() else {
        defmt::error!("the fixture's network is not a landmark network");
        return false;
    };
    defmt::info!(
        "landmark network: {=u32} landmarks x {=u32} directions, {=u32} weathers, {=u32} line elements, start vertex {=u32} (range {=f32} m), goal vertex {=u32}",
        l.landmark_count,
        l.directions,
        l.weather_count,
        l.element_count,
        l.start_vertex,
        l.start_range_m,
        l.goal_vertex
    );
    let (Some(start), Some(goal)) = (net.vertex(l.start_vertex), net.vertex(l.goal_vertex)) else {
        defmt::error!("the network has no stored start or goal");
        return false;
    };

    let t = clock.now();
    let weather = planner.set_weather(fixture.weather);
    let weather_ticks = clock.now() - t;
    if let Err(e) = weather {
        defmt::error!("set_weather({=u32}) failed: {}", fixture.weather, e);
        return false;
    }
    defmt::info!(
        "set_weather({=u32}) took {=u64} ticks",
        fixture.weather,
        weather_ticks
    );

    let query = Query {
        start,
        goal: Goal {
            position: goal.position,
            heading: None,
        },
        search: Search::Dijkstra,
    };
    defmt::info!("query: {}", query);
    let budget = planner.worst_case_work();
    defmt::info!(
        "worst-case work bound {=u64} (host {=u64}): the budget",
        budget,
        fixture.budget
    );
    if budget != fixture.budget {
        defmt::warn!("the host computed a different bound: fixture out of date?");
    }

    let mut task: Task<'_, '_, V, E, P, R> =
        RouteTask::new(planner, clock, clock, PERIOD_MS, budget);

    // 1. The planned route.
    let (first, plan_ticks) = task.plan_once(query);
    let route = task.planner().route_edges();
    let mut verdict = check_plan(&net, first, plan_ticks, route, fixture);
    let lost_landmark = fixture.lost_landmark;
    let overflown = route.iter().any(|&e| {
        net.edge_link(e).is_some_and(|r| {
            r.target < l.landmark_count * l.directions
                && r.target.checked_div(l.directions) == Some(lost_landmark)
        })
    });
    if !overflown {
        defmt::warn!(
            "landmark {=u32} (the fixture's) is not on the route",
            lost_landmark
        );
    }

    // 2. A landmark lost in flight: all its qualities 0, in every weather.
    let zeros = [0.0f32; MAX_ROSETTE_DIRECTIONS];
    let Some(lost) = zeros.get(..l.directions as usize) else {
        defmt::error!(
            "{=u32} directions: more than a rosette override holds ({=usize})",
            l.directions,
            MAX_ROSETTE_DIRECTIONS
        );
        return false;
    };
    let (updated, update_ticks) = crate::with_stack_peak("update_rosette", || {
        let t = clock.now();
        let updated = task.planner().update_rosette(lost_landmark, lost);
        (updated, clock.now() - t)
    });
    if let Err(e) = updated {
        defmt::error!("update_rosette({=u32}) failed: {}", lost_landmark, e);
        return false;
    }
    defmt::info!(
        "landmark {=u32} lost: update_rosette took {=u64} ticks = {=u64} us",
        lost_landmark,
        update_ticks,
        Clock::ticks_to_us(update_ticks)
    );

    // 3. The re-plan.
    let (second, replan_ticks) = task.plan_once(query);
    let route = task.planner().route_edges();
    verdict &= check_replan(
        &net,
        "re-plan",
        (second, replan_ticks),
        route,
        fixture.expected_replan,
        lost_landmark,
    );

    // 4. From where the aircraft is, joined online.
    if let Err(e) = task.planner().set_start_range(fixture.online_range) {
        defmt::error!(
            "set_start_range({=f32}) failed: {}",
            fixture.online_range,
            e
        );
        return false;
    }
    let (x, y, heading) = fixture.online_start;
    let online_query = Query {
        start: Pose::new(x, y, heading),
        ..query
    };
    let (third, online_ticks) = task.plan_once(online_query);
    let route = task.planner().route_edges();
    verdict &= check_replan(
        &net,
        "online start",
        (third, online_ticks),
        route,
        fixture.expected_online,
        lost_landmark,
    );

    log_stack();
    if verdict {
        defmt::info!(
            "PASS: route {=f32} m and, landmark {=u32} lost, {=f32} m, and {=f32} m from the online start: equal to the host's",
            fixture.expected_length,
            lost_landmark,
            fixture.expected_replan.map_or(f32::NAN, |r| r.0),
            fixture.expected_online.map_or(f32::NAN, |r| r.0)
        );
    }
    verdict
}

/// The first plan's verdict: logs the route (`edges`, `ticks`), true only if its length, edges,
/// pieces and work equal the host's.
fn check_plan(
    net: &Network<'_>,
    outcome: Result<RouteSummary, PlanError>,
    ticks: u64,
    edges: &[u32],
    fixture: &LandmarkFixture,
) -> bool {
    let s = match outcome {
        Ok(s) => s,
        Err(e) => {
            defmt::error!("plan failed after {=u64} ticks: {}", ticks, e);
            return false;
        }
    };
    log_route(net, "plan", &s, ticks, edges);
    let same = s.length == fixture.expected_length
        && s.network_edges == fixture.expected_network_edges
        && s.primitives == fixture.expected_primitives
        && s.work.total() == fixture.expected_work;
    if !same {
        defmt::error!(
            "route {=f32} m, {=u32} edges, {=u32} pieces, work {=u64}; host: {=f32} m, {=u32} edges, {=u32} pieces, work {=u64}",
            s.length,
            s.network_edges,
            s.primitives,
            s.work.total(),
            fixture.expected_length,
            fixture.expected_network_edges,
            fixture.expected_primitives,
            fixture.expected_work
        );
    }
    same
}

/// A plan after the landmark was lost (`what`): true if it equals the host's `expected`
/// (length, edges, work) and its route (`edges`) avoids `lost_landmark`, or if it failed as
/// the host's did.
fn check_replan(
    net: &Network<'_>,
    what: &str,
    (outcome, ticks): (Result<RouteSummary, PlanError>, u64),
    edges: &[u32],
    expected: Option<(f32, u32, u64)>,
    lost_landmark: u32,
) -> bool {
    let Some(l) = net.landmark() else {
        return false;
    };
    match (outcome, expected) {
        (Ok(s), Some((length, route_edges, work))) => {
            log_route(net, what, &s, ticks, edges);
            let avoids = edges.iter().all(|&e| {
                net.edge_link(e).is_some_and(|r| {
                    r.source >= l.landmark_count * l.directions
                        || r.source.checked_div(l.directions) != Some(lost_landmark)
                })
            });
            if !avoids {
                defmt::error!(
                    "the new route still overflies landmark {=u32}",
                    lost_landmark
                );
            }
            let same =
                s.length == length && s.network_edges == route_edges && s.work.total() == work;
            if !same {
                defmt::error!(
                    "{=str}: {=f32} m, {=u32} edges, work {=u64}; host: {=f32} m, {=u32} edges, work {=u64}",
                    what,
                    s.length,
                    s.network_edges,
                    s.work.total(),
                    length,
                    route_edges,
                    work
                );
            }
            avoids && same
        }
        (Err(e), None) => {
            defmt::info!(
                "{=str}: no route ({}) in {=u64} ticks, as on the host; the previous route is kept",
                what,
                e,
                ticks
            );
            true
        }
        (Ok(s), None) => {
            defmt::error!(
                "{=str} found {=f32} m; the host found no route",
                what,
                s.length
            );
            false
        }
        (Err(e), Some((length, _, _))) => {
            defmt::error!(
                "{=str} failed ({}); the host found {=f32} m",
                what,
                e,
                length
            );
            false
        }
    }
}

/// Logs a route: summary, ticks, and each edge (the start leg, then one line per overflight:
/// landmark, compass direction, the next leg's cost and pieces).
fn log_route(net: &Network<'_>, what: &str, s: &RouteSummary, ticks: u64, edges: &[u32]) {
    defmt::info!(
        "{=str}: route {=f32} m, {=u32} network edges, {=u32} Hermite pieces, work {=u64}: {}",
        what,
        s.length,
        s.network_edges,
        s.primitives,
        s.work.total(),
        s.work
    );
    defmt::info!(
        "{=str}: took {=u64} SysTick ticks = {=u64} us at {=u32} Hz",
        what,
        ticks,
        Clock::ticks_to_us(ticks),
        clock::CORE_HZ
    );
    let Some(l) = net.landmark() else {
        return;
    };
    let overflights = l.landmark_count * l.directions;
    for &e in edges {
        let Some(r) = net.edge_link(e) else {
            continue;
        };
        let pieces = net.chain_piece_count(e);
        if r.source == l.start_vertex {
            defmt::info!(
                "  start -> leg {=f32} m ({=u32} pieces, edge {=u32})",
                r.cost,
                pieces,
                e
            );
        } else if r.source < overflights {
            let landmark = r.source.checked_div(l.directions).unwrap_or(0);
            let direction = r.source.checked_rem(l.directions).unwrap_or(0);
            defmt::info!(
                "  overflight L{=u32} direction {=u32} (compass {=u32} deg) -> leg {=f32} m ({=u32} pieces, edge {=u32}){=str}",
                landmark,
                direction,
                (360 * direction).checked_div(l.directions).unwrap_or(0),
                r.cost,
                pieces,
                e,
                if r.target == l.goal_vertex { " -> goal" } else { "" }
            );
        } else {
            defmt::info!(
                "  vertex {=u32} -> leg {=f32} m (edge {=u32})",
                r.source,
                r.cost,
                e
            );
        }
    }
}
