//! The roadmap search's work counted exactly, from the [`Phase::Search`] mark to the route's
//! (or, when no route is found, to the end), and the route writer's, by an independent
//! Dijkstra and A* over the same network, links and pop-up.
//!
//! The search clears the heap (one vertex scan per vertex), queues each start link's vertex at
//! the link's length unless it is queued cheaper, then pops the cheapest vertex (each pop and
//! each push or decrease counting the levels the heap reports) until the heap is empty or the
//! popped key reaches the best route so far (at first the direct path, if clear). A popped
//! vertex examines every goal link (one relaxation each) and offers those leaving it; a pending
//! link (free arrival headings, a clear probe) is resolved only if its lower bound could still
//! improve the route, reading the goal's obstacle window the first time (one test per
//! obstacle) and then counting as [`super::connect_work::clear_over_headings`] does. Then every
//! out-edge counts one relaxation, and an edge no pop-up blocks lowers its target's distance
//! if it is unseen or still queued at a larger one. A* adds the chord to the goal, shrunk by
//! 1e-4, to every key. Writing a route through the network then walks its states back twice
//! (to count its paths, then to copy them): a vertex scan per network edge and one for the
//! start, each time; the direct path is written without a walk.
//!
//! The heap is the core's [`IndexedHeap`], checked against its own reference in the crate's
//! tests: this test counts what the search asks of it, in the order the search must ask.

use super::connect_work::{
    clear_over_headings, goal_links, planner_with_popup, start_links, GoalLink, TestPlanner, RADIUS,
};
use host_tests::world::{free_pose, world};
use host_tests::{cases, Rng};
use skyroute::planner::heap::{IndexedHeap, ItemState};
use skyroute::planner::{Phase, Query, Search, Work};
use skyroute::{PlanError, Pose, RouteSummary};

/// The search's work planning `query` on `p`, given its start links (vertex, length), its goal
/// links, the direct path's length if it is clear, and the number of static obstacles (a goal
/// window's read); with the best route's cost and, if it runs through the network, its
/// network edges (`None`: the direct path).
fn search_work(
    p: &TestPlanner<'_>,
    query: &Query,
    starts: &[(u32, f32)],
    goals: &[GoalLink],
    direct: Option<f32>,
    obstacles: u64,
) -> (Work, Option<(f32, Option<u32>)>) {
    let net = p.network();
    let n = net.vertex_count() as usize;
    let goal = query.goal.position;
    let heuristic = |v: u32| match query.search {
        Search::Dijkstra => 0.0,
        Search::AStar => net.vertex(v).unwrap().position.distance(goal) * (1.0 - 1e-4),
    };
    let mut work = Work::default();
    let mut heap: Box<IndexedHeap<4096>> = Box::new(IndexedHeap::new());
    heap.clear(n);
    work.vertex_scans += n as u64;
    let mut dist = vec![f32::INFINITY; n];
    let mut hops = vec![0u32; n];
    for &(v, cost) in starts {
        if heap.state(v) == ItemState::Unseen || cost < dist[v as usize] {
            dist[v as usize] = cost;
            hops[v as usize] = 0;
            work.heap_steps += heap.push_or_decrease(v, cost + heuristic(v)) as u64;
        }
    }
    let mut best = direct.map(|d| (d, None));
    let mut window_read = false;
    while let Some((u, key, levels)) = heap.pop() {
        work.heap_steps += levels as u64;
        if best.is_some_and(|(b, _)| key >= b) {
            break;
        }
        let du = dist[u as usize];
        work.relaxations += goals.len() as u64;
        for link in goals.iter().filter(|l| l.vertex == u) {
            let cost = match link.resolution {
                None => link.cost,
                Some(_) if best.is_some_and(|(b, _)| du + link.cost >= b) => continue,
                Some(((tests, solves), exact)) => {
                    if !window_read {
                        work.collision_tests += obstacles;
                        window_read = true;
                    }
                    work.collision_tests += tests;
                    work.dubins_solves += solves;
                    exact
                }
            };
            if best.is_none_or(|(b, _)| du + cost < b) {
                best = Some((du + cost, Some(hops[u as usize])));
            }
        }
        let edges = net.out_edges(u);
        work.relaxations += edges.len() as u64;
        for e in edges.filter(|&e| p.is_edge_enabled(e)) {
            let (cost, t) = net.edge_cost_target(e).unwrap();
            let candidate = du + cost;
            let state = heap.state(t);
            if state == ItemState::Unseen
                || (state == ItemState::Queued && candidate < dist[t as usize])
            {
                dist[t as usize] = candidate;
                hops[t as usize] = hops[u as usize] + 1;
                work.heap_steps += heap.push_or_decrease(t, candidate + heuristic(t)) as u64;
            }
        }
    }
    (work, best)
}

/// What planning a query counted, phase by phase, and its result.
struct Measured {
    /// From the direct path's mark to the search's.
    direct: Work,
    /// From the search's mark to the route's (to the end's when there is no route).
    search: Work,
    /// From the route's mark to the end's, if there is a route.
    route: Option<Work>,
    result: Result<RouteSummary, PlanError>,
}

/// Plans `query` with `p`, reading the work at each phase mark.
fn measured(p: &mut TestPlanner<'_>, query: &Query) -> Measured {
    let mut marks = Vec::new();
    let result = p.plan_observed(query, u64::MAX, &mut |phase, work| {
        marks.push((phase, *work))
    });
    let at = |phase: Phase| marks.iter().find(|m| m.0 == phase).map(|m| m.1);
    let (Some(direct), Some(search), Some(done)) =
        (at(Phase::ConnectDirect), at(Phase::Search), at(Phase::Done))
    else {
        panic!("{query:?}: phases {marks:?}, {result:?}");
    };
    let minus = |a: Work, b: Work| Work {
        vertex_scans: a.vertex_scans - b.vertex_scans,
        dubins_solves: a.dubins_solves - b.dubins_solves,
        collision_tests: a.collision_tests - b.collision_tests,
        heap_steps: a.heap_steps - b.heap_steps,
        relaxations: a.relaxations - b.relaxations,
        cells_visited: a.cells_visited - b.cells_visited,
        threat_steps: a.threat_steps - b.threat_steps,
    };
    let route = at(Phase::Route);
    Measured {
        direct: minus(search, direct),
        search: minus(route.unwrap_or(done), search),
        route: route.map(|r| minus(done, r)),
        result,
    }
}

#[test]
fn the_search_and_the_route_walks_count_their_work_exactly() {
    let mut rng = Rng(0x5EA4);
    let (mut checked, mut resolved, mut astar, mut direct_clear, mut via_network) = (0, 0, 0, 0, 0);
    for seed in 0..cases(3, 12) as u64 {
        let w = world(190 + seed, 1200.0, 60.0, 40.0, 12);
        let (mut p, mut checks, centre) = planner_with_popup(&w, &mut rng, 80.0);
        let net = *p.network();
        for i in 0..cases(20, 60) {
            let start: Pose = free_pose(&mut rng, &w, 10.0);
            // Every third goal near the start, so that the direct path takes part.
            let near = |g: &Pose| i % 3 != 0 || g.position.distance(start.position) < 300.0;
            let Some(goal_pose) = (0..400).map(|_| free_pose(&mut rng, &w, 10.0)).find(near) else {
                continue;
            };
            let goal = goal_pose.position;
            let heading = (i % 2 == 1).then_some(goal_pose.heading);
            let clear_of_popup =
                |q: skyroute::Vec2| q.distance(centre) > 80.0 + net.clearance() + 1.0;
            if !clear_of_popup(start.position) || !clear_of_popup(goal) {
                continue;
            }
            let (Some((_, starts)), Some((_, goals))) = (
                start_links(&p, &mut checks, start),
                goal_links(&p, &mut checks, goal, heading),
            ) else {
                continue;
            };
            let direct = if start.position.distance(goal) <= RADIUS {
                match clear_over_headings(&mut checks, &start, goal, heading) {
                    Some(counted) => Some(counted),
                    None => continue,
                }
            } else {
                None
            };
            let direct_length = direct.and_then(|(_, length)| length);
            if direct_length.is_none() && (starts.is_empty() || goals.is_empty()) {
                continue; // refused before the search
            }
            let mut query = host_tests::world::query_to(start, goal);
            query.goal.heading = heading;
            if i % 4 >= 2 {
                query.search = Search::AStar;
                astar += 1;
            }
            let obstacles = w.obstacles.len() as u64;
            let (expected, best) =
                search_work(&p, &query, &starts, &goals, direct_length, obstacles);
            let m = measured(&mut p, &query);
            let direct_counts = direct.map_or((0, 0), |(counts, _)| counts);
            assert_eq!(
                ((m.direct.collision_tests, m.direct.dubins_solves), m.search),
                (direct_counts, expected),
                "{query:?}"
            );
            // The route is the model's best, to rounding; writing it walks its states back
            // twice (once to count its paths, once to copy them), a vertex scan per network
            // edge and one for the start; the direct path is written without a walk.
            match (&m.result, best) {
                (Ok(summary), Some((cost, edges))) => {
                    let l = summary.length;
                    assert!((l - cost).abs() <= 1e-4 * cost, "{l} against {cost}");
                    assert_eq!(summary.network_edges, edges.unwrap_or(0), "{query:?}");
                    let walks = Work {
                        vertex_scans: edges.map_or(0, |e| 2 * (e as u64 + 1)),
                        ..Work::default()
                    };
                    assert_eq!(m.route, Some(walks), "{query:?}");
                    via_network += edges.is_some() as usize;
                }
                (Err(PlanError::NoRoute), None) => assert_eq!(m.route, None),
                (result, best) => panic!("{query:?}: {result:?}, the model's best {best:?}"),
            }
            checked += 1;
            resolved += (expected.dubins_solves > 0) as u32;
            direct_clear += direct_length.is_some() as u32;
        }
    }
    assert!(
        checked >= cases(3, 12) * 12
            && resolved >= 5
            && astar >= 5
            && direct_clear >= 3
            && via_network >= cases(3, 12) * 8,
        "{checked} queries, {resolved} resolving a goal link, {astar} A*, {direct_clear} direct, \
         {via_network} through the network"
    );
}
