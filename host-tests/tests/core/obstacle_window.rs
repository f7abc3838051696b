//! The obstacle window of an endpoint (`planner/window.rs`) keeps the 32 obstacles nearest to
//! it whatever order the network lists them in: the same queries, on one network whose
//! obstacles are listed in several orders, give the same routes and count the same work.
//!
//! The counted collision tests tell which obstacles a window kept: a connection the window
//! covers is checked against its 32 kept obstacles, one it does not cover against all of them.
//! Every obstacle here lies far from every path, so no check stops early and the count does
//! not depend on the order in which the kept obstacles are tried.

use host_tests::world::lattice_spec;
use host_tests::Rng;
use skyroute::network::write::{encode, ObstacleSpec};
use skyroute::planner::{Goal, PlanError, PlannerConfig, Query, RouteSummary, Search};
use skyroute::{Planner, Pose, Vec2};
use std::f32::consts::{PI, TAU};

type WindowPlanner<'n> = Planner<'n, 256, 4096, 4, 256>;

/// Centre of the 4 × 4 lattice (positions 0 … 450 m).
const CENTRE: f32 = 225.0;

/// A circle of radius 10 m at `distance` from the lattice's centre, at angle `angle`.
fn circle_at(distance: f32, angle: f32) -> ObstacleSpec {
    ObstacleSpec::Circle {
        centre: Vec2::new(
            CENTRE + distance * angle.cos(),
            CENTRE + distance * angle.sin(),
        ),
        radius: 10.0,
    }
}

/// Every query's result on the network with `obstacles` in this order.
fn plan_all(
    obstacles: Vec<ObstacleSpec>,
    queries: &[Query],
) -> Vec<Result<RouteSummary, PlanError>> {
    let spec = skyroute::network::write::NetworkSpec {
        obstacles,
        grid_cell_m: 500.0,
        ..lattice_spec(4, 150.0, 0.0, 30.0)
    };
    let bytes = encode(&spec).expect("the lattice encodes");
    let mut p: Box<WindowPlanner<'_>> = Box::new(Planner::new());
    p.load(&bytes).expect("the lattice loads");
    // Connections reach the nearest few lattice points only: most routes use the network.
    p.set_config(PlannerConfig {
        connect_radius_m: 200.0,
        ..PlannerConfig::DEFAULT
    });
    queries.iter().map(|q| p.plan(q, u64::MAX)).collect()
}

#[test]
fn an_endpoint_window_keeps_the_nearest_obstacles_in_any_listing_order() {
    // Eight near obstacles, 180–250 m beyond the lattice's corners and sides (farther than
    // any connection bulges: 2 turn radii), and 32 far ones 5–6 km away: the window keeps
    // the 8 near and the 24 nearest far ones, and its reach (the 25th far one) covers every
    // connection. A window that kept the wrong 32 would leave a near one out, cover nothing
    // and check every connection against all 40.
    let near: Vec<ObstacleSpec> = (0..8)
        .map(|k| circle_at(500.0 + 10.0 * k as f32, k as f32 * TAU / 8.0 + 0.3))
        .collect();
    let far: Vec<ObstacleSpec> = (0..32)
        .map(|k| circle_at(5000.0 + 31.0 * k as f32, k as f32 * 0.7))
        .collect();
    let mut rng = Rng(77);
    let queries: Vec<Query> = (0..12)
        .map(|i| {
            let at =
                |rng: &mut Rng| Vec2::new(rng.range_f32(20.0, 430.0), rng.range_f32(20.0, 430.0));
            let start = Pose {
                position: at(&mut rng),
                heading: rng.range_f32(-PI, PI),
            };
            let goal = Goal {
                position: at(&mut rng),
                heading: (i % 2 == 0).then(|| rng.range_f32(-PI, PI)),
            };
            Query {
                start,
                goal,
                search: Search::Dijkstra,
            }
        })
        .collect();

    let near_last: Vec<ObstacleSpec> = far.iter().chain(&near).cloned().collect();
    let reference = plan_all(near_last, &queries);
    let routed = reference.iter().filter(|r| r.is_ok()).count();
    assert!(
        routed >= 10,
        "only {routed} of 12 queries routed: {reference:?}"
    );

    let near_first: Vec<ObstacleSpec> = near.iter().chain(&far).cloned().collect();
    let mut shuffled: Vec<ObstacleSpec> = near_first.clone();
    for i in (1..shuffled.len()).rev() {
        shuffled.swap(i, rng.below(i as u64 + 1) as usize);
    }
    for (name, order) in [("near first", near_first.clone()), ("shuffled", shuffled)] {
        let got = plan_all(order, &queries);
        for (i, (g, r)) in got.iter().zip(&reference).enumerate() {
            assert_eq!(
                g, r,
                "{name}, query {i}: the same route and work in any order"
            );
        }
    }

    // Forty more obstacles 8–9 km away, beyond the window's 32: only the passes that read
    // every obstacle test them (each endpoint's free-space check, the start window, the goal
    // window for the goal's connections and, once more, for the goal links the search makes
    // exact: five in all); the connections, all within the windows' reach, do not.
    let beyond = (0..40).map(|k| circle_at(8000.0 + 25.0 * k as f32, k as f32 * 0.9));
    let more: Vec<ObstacleSpec> = near_first.iter().cloned().chain(beyond).collect();
    let got = plan_all(more, &queries);
    for (i, (g, r)) in got.iter().zip(&reference).enumerate() {
        let (Ok(g), Ok(r)) = (g, r) else {
            assert_eq!(g, r, "query {i}");
            continue;
        };
        assert_eq!(
            (g.length, g.primitives),
            (r.length, r.primitives),
            "query {i}"
        );
        let added = g.work.collision_tests - r.work.collision_tests;
        println!(
            "query {i}: {} collision tests, {added} more with 40 more obstacles",
            r.work.collision_tests
        );
        assert!(added <= 5 * 40, "query {i}: {added} more collision tests");
    }
}
