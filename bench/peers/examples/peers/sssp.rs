//! Single-source shortest paths over a whole network: the core's heap (f32) and petgraph's
//! `dijkstra` (f64 weights), on the same sources.

use crate::{network, read, write, write_json, Args};
use petgraph::graph::{DiGraph, NodeIndex};
use serde_json::json;
use skyroute::planner::heap::IndexedHeap;
use skyroute_peers::rng::Rng;
use skyroute_peers::{dijkstra, stats};
use std::time::Instant;

/// Capacity of the heap: the host planner's `V`.
const HEAP_CAPACITY: usize = 131072;

/// Relative tolerance between an f32 and an f64 distance.
const REL_TOL: f64 = 1e-5;

/// `sssp NET.bin SOURCES SEED DIST.bin OUT.json [REPS]`: draws `SOURCES` distinct source
/// vertices with `SEED`, computes all distances from each with [`dijkstra::distances`] and with
/// `petgraph::algo::dijkstra` (graph built once from the network's edges, outside the clock),
/// times each (median over `REPS` runs per source, default 5), compares them (relative
/// difference at most 1e-5, the same vertices unreachable), and writes ours as little-endian
/// f32, `SOURCES × vertices` (infinity where unreachable), for the SciPy side.
pub fn sssp(args: &Args) -> Result<(), String> {
    let bytes = read(args.get(0, "network")?)?;
    let net = network(&bytes)?;
    let count: usize = args.parse(1, "sources")?;
    let mut rng = Rng::new(args.parse(2, "seed")?);
    let reps: usize = args.parse_or(5, "reps", 5)?.max(1);
    let n = net.vertex_count() as usize;
    let mut sources: Vec<u32> = Vec::new();
    while sources.len() < count.min(n) {
        let s = rng.below(n as u64) as u32;
        if !sources.contains(&s) {
            sources.push(s);
        }
    }
    let t_build = Instant::now();
    let mut g: DiGraph<(), f64> = DiGraph::with_capacity(n, net.edge_count() as usize);
    for _ in 0..n {
        g.add_node(());
    }
    for e in 0..net.edge_count() {
        let (Some(src), Some((cost, t))) = (net.edge_source(e), net.edge_cost_target(e)) else {
            return Err(format!("edge {e} unreadable"));
        };
        g.add_edge(
            NodeIndex::new(src as usize),
            NodeIndex::new(t as usize),
            cost as f64,
        );
    }
    let petgraph_build_s = t_build.elapsed().as_secs_f64();
    let mut heap: Box<IndexedHeap<HEAP_CAPACITY>> = Box::new(IndexedHeap::new());
    let mut dist = vec![0.0f32; n];
    let (mut ours_s, mut pg_s) = (Vec::new(), Vec::new());
    let (mut worst_rel, mut mismatches, mut reachable) = (0.0f64, 0usize, 0usize);
    let mut out = Vec::with_capacity(sources.len() * n * 4);
    for &s in &sources {
        let (mut t_ours, mut t_pg) = (Vec::new(), Vec::new());
        let mut theirs = Default::default();
        for _ in 0..reps {
            let t0 = Instant::now();
            dijkstra::distances(&net, &mut heap, s, &mut dist).ok_or("heap too small")?;
            t_ours.push(t0.elapsed().as_secs_f64());
            let t1 = Instant::now();
            theirs =
                petgraph::algo::dijkstra(&g, NodeIndex::new(s as usize), None, |e| *e.weight());
            t_pg.push(t1.elapsed().as_secs_f64());
        }
        ours_s.push(stats::median(&t_ours));
        pg_s.push(stats::median(&t_pg));
        for (v, &d) in dist.iter().enumerate() {
            let other = theirs.get(&NodeIndex::new(v)).copied();
            match other {
                Some(o) if d.is_finite() => {
                    reachable += 1;
                    // The source itself: both 0, so 0 / 1e-9.
                    let rel = (d as f64 - o).abs() / o.max(1e-9);
                    worst_rel = worst_rel.max(rel);
                    if rel > REL_TOL {
                        mismatches += 1;
                    }
                }
                None if !d.is_finite() => {}
                _ => mismatches += 1,
            }
            out.extend_from_slice(&d.to_le_bytes());
        }
    }
    write(args.get(3, "distances output")?, &out)?;
    let summary = |xs: &[f64]| json!({"median": stats::median(xs), "p90": stats::quantile(xs, 0.9), "max": stats::max(xs)});
    write_json(
        args.get(4, "json output")?,
        &json!({
            "vertices": n,
            "edges": net.edge_count(),
            "sources": sources,
            "reps": reps,
            "ours_s": summary(&ours_s),
            "petgraph_s": summary(&pg_s),
            "petgraph_graph_build_s": petgraph_build_s,
            "reachable_pairs": reachable,
            "petgraph_max_rel_diff": worst_rel,
            "petgraph_mismatches": mismatches,
        }),
    )
}
