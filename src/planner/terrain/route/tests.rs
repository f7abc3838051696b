//! The terrain route's walk back, counted: one vertex scan per state it steps through, and
//! under the paper's rule the table reads that decode each pair state (module doc of
//! `planner/terrain/states`): a bisection over the `S` straights' offsets, at most
//! `⌈log₂ S⌉` reads a state.

extern crate std;
use super::super::tests::{at, codes_with_block, network, query, Small};
use crate::planner::{Meter, PlannerConfig, TurnRule};

/// The route around a wall through the network's three nodes (the start and the goal each
/// joined to their nearest node only; the paper's rule, the default) walked back again from
/// the search's arrival, with 1 000 scans already counted: the walk adds one scan per step,
/// and at least one and at most `⌈log₂ S⌉` reads per state it decodes.
#[test]
fn the_walk_back_counts_a_scan_per_step_and_the_reads_of_each_decoding() {
    let image = network(codes_with_block(190.0, 100.0, 210.0, 200.0), 30.0);
    let mut p = Small::new();
    p.load(&image).unwrap();
    p.set_config(PlannerConfig {
        start_candidates: 1,
        goal_candidates: 1,
        ..p.config()
    });
    assert_eq!(p.config().turn_rule, TurnRule::Paper);
    let summary = p
        .plan(&query(at(20.0, 150.0), at(380.0, 150.0)), u64::MAX)
        .unwrap();
    assert!(summary.network_edges >= 2, "{summary:?}");
    let arrival = p.flight.best.first().map(|&(_, a)| a).unwrap();
    let mut meter = Meter::new(u64::MAX);
    meter.work.vertex_scans = 1000;
    let mut legs = 0u64;
    let edges = p
        .walk_terrain_route(&arrival, &mut meter, &mut |_| legs += 1)
        .unwrap();
    assert_eq!(edges, summary.network_edges);
    // The walk steps through the route's edges and its start link, one scan each.
    let steps = u64::from(edges) + 1;
    let reads = meter.work.vertex_scans - 1000 - steps;
    // The straights: the network's edges and the query's start links.
    let straights = u64::from(p.network().edge_count()) + p.start_links.len() as u64;
    let per_state = u64::from(64 - (straights - 1).leading_zeros());
    assert!(
        reads >= 1 && reads <= (u64::from(edges) + 1) * per_state,
        "{reads} reads for {edges} edges over {straights} straights"
    );
    // The legs: the one into the goal, one per edge, the start link.
    assert_eq!(legs, u64::from(edges) + 2);
}
