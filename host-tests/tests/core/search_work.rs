//! The roadmap search's work counted exactly, from the [`Phase::Search`] mark to the route's
//! (or, when no route is found, to the end), by an independent Dijkstra and A* over the same
//! network, links and pop-up.
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
//! 1e-4, to every key.
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
use skyroute::Pose;

/// The search's work planning `query` on `p`, given its start links (vertex, length), its goal
/// links, the direct path's length if it is clear, and the number of static obstacles (a goal
/// window's read); with the best route's cost, if any.
fn search_work(
    p: &TestPlanner<'_>,
    query: &Query,
    starts: &[(u32, f32)],
    goals: &[GoalLink],
    direct: Option<f32>,
    obstacles: u64,
) -> (Work, Option<f32>) {
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
    for &(v, cost) in starts {
        if heap.state(v) == ItemState::Unseen || cost < dist[v as usize] {
            dist[v as usize] = cost;
            work.heap_steps += heap.push_or_decrease(v, cost + heuristic(v)) as u64;
        }
    }
    let mut best = direct;
    let mut window_read = false;
    while let Some((u, key, levels)) = heap.pop() {
        work.heap_steps += levels as u64;
        if best.is_some_and(|b| key >= b) {
            break;
        }
        let du = dist[u as usize];
        work.relaxations += goals.len() as u64;
        for link in goals.iter().filter(|l| l.vertex == u) {
            let cost = match link.resolution {
                None => link.cost,
                Some(_) if best.is_some_and(|b| du + link.cost >= b) => continue,
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
            if best.is_none_or(|b| du + cost < b) {
                best = Some(du + cost);
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
                work.heap_steps += heap.push_or_decrease(t, candidate + heuristic(t)) as u64;
            }
        }
    }
    (work, best)
}

/// The work counted from `from` to the route's mark (the end's, if there is none), planning
/// `query` with `p`, and the route's length if one was found.
fn measured_search(p: &mut TestPlanner<'_>, query: &Query) -> (Work, Work, Option<f32>) {
    let mut marks = Vec::new();
    let result = p.plan_observed(query, u64::MAX, &mut |phase, work| {
        marks.push((phase, *work))
    });
    let at = |phase: Phase| marks.iter().find(|m| m.0 == phase).map(|m| m.1);
    let (Some(direct), Some(search)) = (at(Phase::ConnectDirect), at(Phase::Search)) else {
        panic!("{query:?}: phases {marks:?}, {result:?}");
    };
    let end = at(Phase::Route).or(at(Phase::Done)).unwrap();
    let minus = |a: Work, b: Work| Work {
        vertex_scans: a.vertex_scans - b.vertex_scans,
        dubins_solves: a.dubins_solves - b.dubins_solves,
        collision_tests: a.collision_tests - b.collision_tests,
        heap_steps: a.heap_steps - b.heap_steps,
        relaxations: a.relaxations - b.relaxations,
        cells_visited: a.cells_visited - b.cells_visited,
        threat_steps: a.threat_steps - b.threat_steps,
    };
    (
        minus(search, direct),
        minus(end, search),
        result.ok().map(|r| r.length),
    )
}

#[test]
fn the_search_counts_its_heap_levels_relaxations_and_goal_link_resolutions() {
    let mut rng = Rng(0x5EA4);
    let (mut checked, mut resolved, mut astar, mut direct_clear) = (0, 0, 0, 0);
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
            let (direct_work, measured, length) = measured_search(&mut p, &query);
            let direct_counts = direct.map_or((0, 0), |(counts, _)| counts);
            assert_eq!(
                (
                    (direct_work.collision_tests, direct_work.dubins_solves),
                    measured
                ),
                (direct_counts, expected),
                "{query:?}"
            );
            // The route found is the model's best, to rounding.
            match (length, best) {
                (Some(l), Some(b)) => assert!((l - b).abs() <= 1e-4 * b, "{l} against {b}"),
                (l, b) => assert_eq!(l.is_some(), b.is_some(), "{query:?}: {l:?}, {b:?}"),
            }
            checked += 1;
            resolved += (expected.dubins_solves > 0) as u32;
            direct_clear += direct_length.is_some() as u32;
        }
    }
    assert!(
        checked >= cases(3, 12) * 12 && resolved >= 5 && astar >= 5 && direct_clear >= 3,
        "{checked} queries, {resolved} resolving a goal link, {astar} A*, {direct_clear} direct"
    );
}
