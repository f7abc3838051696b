//! Counted work is never under-counted: lower bounds of the work a query or a pop-up must
//! count, recomputed independently of the planner, are never above what it reports (and the
//! reported work never above the documented worst case).
//!
//! * A Dijkstra query with one start and one goal link pops every vertex closer than its
//!   route's cost (recomputed by an f64 Dijkstra) and relaxes each one's out-edges and goal
//!   link: `relaxations ≥ Σ (out-degree + 1)` over those vertices.
//! * A pop-up visits exactly the grid cells its box, widened by the clearance, overlaps
//!   (computed here in f64 from the header's grid), every entry of those cells, and at least
//!   one predicate per distinct edge listed there.
//! * Finding the start's and the goal's nearest vertices scans every vertex once each, exactly.

use host_tests::world::{free_pose, work_at_phases, world};
use host_tests::{cases, Rng};
use skyroute::planner::{Goal, Phase, PlannerConfig, Popup, Query, Search};
use skyroute::{Network, Planner, Vec2};
use std::cmp::Reverse;
use std::collections::{BTreeSet, BinaryHeap, HashMap};

type Wp<'n> = Planner<'n, 4096, 65536, 4, 1024>;

fn load(bytes: &[u8]) -> Box<Wp<'_>> {
    let mut p: Box<Wp<'_>> = Box::new(Planner::new());
    p.load(bytes).expect("test network loads");
    p
}

/// Dijkstra distances in f64 from `source` over every edge (costs as stored).
fn distances_from(net: &Network<'_>, source: u32) -> Vec<f64> {
    let mut dist = vec![f64::INFINITY; net.vertex_count() as usize];
    let mut heap = BinaryHeap::new();
    dist[source as usize] = 0.0;
    heap.push(Reverse((0u64, source))); // non-negative f64 bits order like the values
    while let Some(Reverse((bits, u))) = heap.pop() {
        let d = f64::from_bits(bits);
        if d > dist[u as usize] {
            continue;
        }
        for e in net.out_edges(u) {
            let (cost, t) = net.edge_cost_target(e).unwrap();
            let candidate = d + cost as f64;
            if candidate < dist[t as usize] {
                dist[t as usize] = candidate;
                heap.push(Reverse((candidate.to_bits(), t)));
            }
        }
    }
    dist
}

/// With one start link and one goal link, Dijkstra pops every vertex `v` whose distance
/// (start link, then the cheapest edges) is below the route's cost — it stops only when the
/// heap's smallest key reaches the best route found — and a popped vertex counts one
/// relaxation per out-edge and one for the goal link. The distances are recomputed here with
/// an f64 Dijkstra over the stored edge costs; vertices within 10⁻⁴ of the route's cost are
/// left out (rounding may go either way).
#[test]
fn dijkstra_relaxations_cover_every_vertex_it_must_pop() {
    let (mut checked, mut tightest) = (0, f64::INFINITY);
    for seed in 0..2u64 {
        let w = world(60 + seed, 1200.0, 60.0, 40.0, 4);
        let mut p = load(&w.bytes);
        p.set_config(PlannerConfig {
            start_candidates: 1,
            goal_candidates: 1,
            ..PlannerConfig::DEFAULT
        });
        let net = *p.network();
        // Stored vertices by their exact pose bits.
        let mut by_pose: HashMap<(u32, u32, u32), u32> = HashMap::new();
        for v in 0..net.vertex_count() {
            let pose = net.vertex(v).unwrap();
            let key = (
                pose.position.x.to_bits(),
                pose.position.y.to_bits(),
                pose.heading.to_bits(),
            );
            by_pose.insert(key, v);
        }
        let bound = p.worst_case_work();
        let mut rng = Rng(700 + seed);
        for _ in 0..cases(100, 500) {
            let start = free_pose(&mut rng, &w, 10.0);
            let goal = free_pose(&mut rng, &w, 10.0);
            let q = Query {
                start,
                goal: Goal {
                    position: goal.position,
                    heading: Some(goal.heading),
                },
                search: Search::Dijkstra,
            };
            let Ok(s) = p.plan(&q, u64::MAX) else {
                continue;
            };
            assert!(s.work.total() <= bound, "{:?} above {bound}", s.work);
            let paths = p.route_paths();
            if s.network_edges == 0 || paths.len() != s.network_edges as usize + 2 {
                continue; // the direct start-goal path
            }
            // The start link ends at the one vertex the search started from.
            let first = paths[1].start;
            let key = (
                first.position.x.to_bits(),
                first.position.y.to_bits(),
                first.heading.to_bits(),
            );
            let s0 = *by_pose
                .get(&key)
                .expect("the first edge starts at a vertex");
            let dist = distances_from(&net, s0);
            let start_link = paths[0].length() as f64;
            let last = paths[paths.len() - 1].start;
            let key = (
                last.position.x.to_bits(),
                last.position.y.to_bits(),
                last.heading.to_bits(),
            );
            let v_last = *by_pose.get(&key).expect("the goal link starts at a vertex");
            let cost = start_link + dist[v_last as usize] + paths[paths.len() - 1].length() as f64;
            let must_pop: Vec<u32> = (0..net.vertex_count())
                .filter(|&v| start_link + dist[v as usize] < cost * (1.0 - 1e-4))
                .collect();
            let lower: u64 = must_pop
                .iter()
                .map(|&v| {
                    let r = net.out_edges(v);
                    (r.end - r.start) as u64 + 1
                })
                .sum();
            assert!(
                s.work.relaxations >= lower,
                "{} relaxations counted, but the {} vertices Dijkstra must pop have {lower} \
                 out-edges and goal links",
                s.work.relaxations,
                must_pop.len()
            );
            tightest = tightest.min(s.work.relaxations as f64 / lower as f64);
            checked += 1;
        }
    }
    println!("{checked} routes checked; smallest relaxations / lower bound: {tightest:.3}");
    assert!(checked >= 20, "only {checked} routes");
}

/// The cells a box `[lo, hi]` overlaps on the network's grid, counted in f64; `None` when a
/// side lies within 10⁻³ of a cell boundary (f32 rounding may go either way there).
fn cells_overlapping_f64(net: &Network<'_>, lo: Vec2, hi: Vec2, widen: f64) -> Option<u64> {
    let h = net.header();
    let cell = h.grid_cell_m as f64;
    let span = |a: f32, b: f32, origin: f32, n: u32| -> Option<u64> {
        let fa = (a as f64 - widen - origin as f64) / cell;
        let fb = (b as f64 + widen - origin as f64) / cell;
        for f in [fa, fb] {
            if (f - f.round()).abs() < 1e-3 {
                return None;
            }
        }
        let (first, last) = (fa.floor().max(0.0), fb.floor().min(n as f64 - 1.0));
        Some(if last < first {
            0
        } else {
            (last - first) as u64 + 1
        })
    };
    Some(
        span(lo.x, hi.x, h.grid_origin_x, h.grid_nx)?
            * span(lo.y, hi.y, h.grid_origin_y, h.grid_ny)?,
    )
}

#[test]
fn popups_count_every_cell_entry_and_edge_of_their_widened_box() {
    let w = world(62, 1200.0, 60.0, 40.0, 4);
    let mut p = load(&w.bytes);
    let net = *p.network();
    let clearance = net.clearance() as f64;
    assert!(clearance > 0.0);
    let bound = p.worst_case_popup_work();
    let mut rng = Rng(71);
    let mut checked = 0;
    for case in 0..cases(200, 2000) {
        let c = Vec2::new(rng.range_f32(-100.0, 1300.0), rng.range_f32(-100.0, 1300.0));
        let size = rng.range_f32(1.0, 120.0);
        let popup = if case % 2 == 0 {
            Popup::Circle {
                centre: c,
                radius: size,
            }
        } else {
            let pts = [
                Vec2::new(c.x - size, c.y - 0.4 * size),
                Vec2::new(c.x + 0.7 * size, c.y - size),
                Vec2::new(c.x + 0.2 * size, c.y + size),
            ];
            Popup::Polygon(heapless::Vec::from_slice(&pts).unwrap())
        };
        let (lo, hi) = popup.bounding_box();
        let Some(cells) = cells_overlapping_f64(&net, lo, hi, clearance) else {
            continue;
        };
        // The entries and distinct edges of those cells, read from the index.
        let (mut entries, mut edges) = (0u64, BTreeSet::new());
        if let Some(r) = net.cells_overlapping(
            lo - Vec2::new(net.clearance(), net.clearance()),
            hi + Vec2::new(net.clearance(), net.clearance()),
        ) {
            assert_eq!(
                (r.x1 - r.x0 + 1) as u64 * (r.y1 - r.y0 + 1) as u64,
                cells,
                "cells_overlapping agrees with the f64 count"
            );
            for y in r.y0..=r.y1 {
                for x in r.x0..=r.x1 {
                    for e in net.cell_edges(x, y) {
                        entries += 1;
                        edges.insert(e);
                    }
                }
            }
        } else {
            assert_eq!(cells, 0);
        }
        let s = p.add_popup(popup.clone()).unwrap();
        assert_eq!(s.cells_visited as u64, cells, "case {case}: {popup:?}");
        assert_eq!(s.entries_visited as u64, entries, "case {case}: {popup:?}");
        assert!(
            s.predicate_tests as u64 >= edges.len() as u64,
            "case {case}: {} predicate tests for {} distinct edges",
            s.predicate_tests,
            edges.len()
        );
        assert!(s.edges_blocked as usize <= edges.len());
        let counted = s.cells_visited as u64 + s.entries_visited as u64 + s.predicate_tests as u64;
        assert!(counted <= bound, "case {case}: {counted} above {bound}");
        p.remove_popup(s.id).unwrap();
        checked += 1;
    }
    assert!(
        checked >= cases(200, 2000) * 9 / 10,
        "only {checked} checked"
    );
}

/// The start's nearest vertices are found once [`Phase::ConnectStart`] begins, the goal's once
/// [`Phase::ConnectGoal`] begins: each scan counts one vertex scan per vertex of the network,
/// and nothing else before the direct path counts one.
#[test]
fn the_nearest_vertex_scans_count_every_vertex_once_per_end() {
    let w = world(61, 1200.0, 60.0, 40.0, 4);
    let mut p = load(&w.bytes);
    let vertices = p.network().vertex_count() as u64;
    let mut rng = Rng(0x5CA7);
    for _ in 0..cases(10, 50) {
        let start = free_pose(&mut rng, &w, 10.0);
        let goal = free_pose(&mut rng, &w, 10.0).position;
        let q = host_tests::world::query_to(start, goal);
        let phases = [
            Phase::CheckFree,
            Phase::ConnectStart,
            Phase::ConnectGoal,
            Phase::ConnectDirect,
        ];
        let [free, start_links, goal_links, direct] =
            work_at_phases(&mut p, &q, phases, |work| work.vertex_scans);
        assert_eq!(
            (
                start_links - free,
                goal_links - start_links,
                direct - goal_links
            ),
            (0, vertices, vertices),
            "{q:?}"
        );
    }
}
