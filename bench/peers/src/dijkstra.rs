//! Single-source shortest paths over a whole network with the core's pieces.
//!
//! The planner's search (`src/planner/search.rs`) runs from start links to goal links, stops
//! at the goal and keeps its distances private, so it cannot answer "every distance from one
//! vertex". This is its vertex loop on its own: the core's [`IndexedHeap`] (decrease-key,
//! f32 keys), the network's [`Network::out_edges`] and [`Network::edge_cost_target`], the
//! same relaxation rule (a vertex is updated while unseen or queued with a larger distance),
//! without the pop-up mask, the A* heuristic, the goal links and the work meter. It reads the
//! edges as a plain directed graph: in terrain mode the planner searches over edge states
//! with a turn check at every node, which this does not do.

use skyroute::planner::heap::{IndexedHeap, ItemState};
use skyroute::Network;

/// Fills `dist` (at least `net.vertex_count()` long) with the distance from `source` to every
/// vertex along the network's directed edges (`f32::INFINITY` where none leads), using `heap`
/// (`N ≥ net.vertex_count()`). Returns the number of vertices settled, or `None` when the heap
/// or `dist` is too small or `source` is not a vertex.
pub fn distances<const N: usize>(
    net: &Network,
    heap: &mut IndexedHeap<N>,
    source: u32,
    dist: &mut [f32],
) -> Option<usize> {
    let n = net.vertex_count() as usize;
    if n > N || dist.len() < n || source as usize >= n {
        return None;
    }
    heap.clear(n);
    dist[..n].fill(f32::INFINITY);
    dist[source as usize] = 0.0;
    heap.push_or_decrease(source, 0.0);
    let mut settled = 0;
    while let Some((u, _key, _levels)) = heap.pop() {
        settled += 1;
        let du = dist[u as usize];
        for e in net.out_edges(u) {
            let (cost, t) = net.edge_cost_target(e)?;
            let candidate = du + cost;
            let state = heap.state(t);
            let dt = dist.get_mut(t as usize)?;
            if state == ItemState::Unseen || (state == ItemState::Queued && candidate < *dt) {
                *dt = candidate;
                heap.push_or_decrease(t, candidate);
            }
        }
    }
    Some(settled)
}
