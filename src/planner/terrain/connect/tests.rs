//! Terrain mode's connections, each against its definition: start links turn left or right
//! onto a straight to each of the nearest nodes (or leave a node the start is on without a
//! loop), in order of distance, until enough are clear; goal paths end at the goal on its
//! heading; the direct path is the shorter clear one. Clear is judged by the sampled f64
//! reference of `terrain::tests`.

extern crate std;
use super::super::tests::{
    at, codes_with_block, network, reference_clear, Small, COLS, FREE, NODES, ROWS,
};
use crate::geometry::{DubinsPath, Pose, Turn, Vec2};
use crate::planner::{Goal, Link, Meter, PlannerConfig};
use core::f32::consts::PI;
use std::vec;
use std::vec::Vec;

const R: f32 = 30.0;

fn node(v: u32) -> Vec2 {
    let (x, y) = NODES[v as usize];
    at(x, y)
}

fn free_network() -> Vec<u8> {
    network(vec![FREE; (COLS * ROWS) as usize], R)
}

/// Whether the reference finds every primitive of `path` clear; panics where it cannot tell.
fn clear(path: &DubinsPath, codes: &[u8]) -> bool {
    path.primitives().iter().flatten().all(|p| {
        reference_clear(p, codes).unwrap_or_else(|| panic!("{p:?} is too near a blocked cell"))
    })
}

/// Each link's vertex and path, in order.
fn vertices_and_paths(links: &[Link]) -> Vec<(u32, DubinsPath)> {
    links.iter().map(|l| (l.vertex, l.path)).collect()
}

fn angle_gap(a: f32, b: f32) -> f32 {
    let d = (a - b).rem_euclid(2.0 * PI);
    d.min(2.0 * PI - d)
}

/// From `at(100, 150)` heading north, high cells `[160, 220] × [160, 190]` block the
/// straight that the right turn flies to `at(340, 150)` (it descends from y = 180) but not the
/// left turn's loop below the start and its straight rising to the goal from below.
fn right_turn_blocked() -> (Vec<u8>, Pose, Vec2) {
    let start = at(100.0, 150.0);
    (
        codes_with_block(160.0, 160.0, 220.0, 190.0),
        Pose::new(start.x, start.y, 0.5 * PI),
        at(340.0, 150.0),
    )
}

/// Start links from `at(100, 150)` heading north: to each node nearest first, a left and a right
/// turn-then-straight where one exists (n0, 50 m west, lies inside the left turn's circle) and
/// is clear, two Dubins solves per node; with the right turns' straight blocked, the kept links
/// are exactly the clear ones. With two wanted, the first two.
#[test]
fn start_links_turn_onto_a_straight_to_each_nearest_node_where_clear() {
    let (codes, start, _) = right_turn_blocked();
    let mut by_distance: Vec<u32> = (0..3).collect();
    by_distance.sort_by(|&a, &b| {
        start
            .position
            .distance(node(a))
            .total_cmp(&start.position.distance(node(b)))
    });
    for blocked in [false, true] {
        let codes = match blocked {
            true => codes.clone(),
            false => vec![FREE; (COLS * ROWS) as usize],
        };
        let image = network(codes.clone(), R);
        let mut planner = Small::new();
        planner.load(&image).unwrap();
        let mut meter = Meter::new(u64::MAX);
        planner.connect_terrain_start(&start, &mut meter).unwrap();
        let mut expected = Vec::new();
        for &v in &by_distance {
            for turn in [Turn::Left, Turn::Right] {
                let Some(path) = DubinsPath::turn_then_straight(&start, R, node(v), turn) else {
                    continue;
                };
                if clear(&path, &codes) {
                    expected.push((v, path));
                }
            }
        }
        let found = vertices_and_paths(&planner.start_links);
        assert_eq!(found, expected, "blocked: {blocked}");
        assert!(
            blocked == (expected.len() < 5),
            "the wall blocks some: {expected:?}"
        );
        for link in &planner.start_links {
            assert_eq!(link.cost, link.path.length());
            assert!(!link.pending);
            assert!(link.path.end().position.distance(node(link.vertex)) < 1e-2);
        }
        assert_eq!(meter.work.dubins_solves, 6);
    }

    let image = free_network();
    let mut planner = Small::new();
    planner.load(&image).unwrap();
    planner.set_config(PlannerConfig {
        start_candidates: 2,
        ..PlannerConfig::DEFAULT
    });
    let mut meter = Meter::new(u64::MAX);
    planner.connect_terrain_start(&start, &mut meter).unwrap();
    // n0 first: its left turn has no path, its right turn is the first link; n1's left the
    // second, after three solves.
    assert_eq!(by_distance[..2], [0, 1]);
    let found = vertices_and_paths(&planner.start_links);
    let right = DubinsPath::turn_then_straight(&start, R, node(0), Turn::Right).unwrap();
    let left = DubinsPath::turn_then_straight(&start, R, node(1), Turn::Left).unwrap();
    assert!(DubinsPath::turn_then_straight(&start, R, node(0), Turn::Left).is_none());
    assert_eq!(found, [(0, right), (1, left)]);
    assert_eq!(meter.work.dubins_solves, 3);
}

/// A start on a node leaves it along its heading without a loop: a link of length 0 to that
/// node first, then turns to the others; with no link wanted, none.
#[test]
fn a_start_on_a_node_leaves_it_without_a_loop() {
    let image = free_network();
    let mut planner = Small::new();
    planner.load(&image).unwrap();
    let start = Pose::new(node(0).x, node(0).y, 0.3);
    let mut meter = Meter::new(u64::MAX);
    planner.connect_terrain_start(&start, &mut meter).unwrap();
    let first = planner.start_links[0];
    assert_eq!(first.vertex, 0);
    assert_eq!(first.path.lengths, [0.0; 3]);
    assert_eq!(first.path.start, start);
    assert_eq!(first.cost, 0.0);
    assert_eq!(
        planner.start_links.len(),
        5,
        "the node, then two turns to each other node"
    );
    for link in &planner.start_links[1..] {
        assert_ne!(link.vertex, 0);
        assert!(link.path.end().position.distance(node(link.vertex)) < 1e-2);
    }
    assert_eq!(meter.work.dubins_solves, 4);

    planner.set_config(PlannerConfig {
        start_candidates: 0,
        ..PlannerConfig::DEFAULT
    });
    planner
        .connect_terrain_start(&start, &mut Meter::new(u64::MAX))
        .unwrap();
    assert!(planner.start_links.is_empty());
}

/// A goal without a heading is reached by the straight from the node; one with a heading by a
/// straight and a final left or right arc, each ending at the goal on its heading.
#[test]
fn goal_paths_end_at_the_goal_on_its_heading() {
    let image = free_network();
    let mut planner = Small::new();
    planner.load(&image).unwrap();
    let from = node(2);
    let goal = at(380.0, 260.0);
    let free = planner.goal_paths(
        from,
        &Goal {
            position: goal,
            heading: None,
        },
    );
    let straight = free[0].unwrap();
    assert!(free[1].is_none());
    assert_eq!(straight.start.position, from);
    assert!(angle_gap(straight.start.heading, libm::atan2f(110.0, 30.0)) < 1e-5);
    assert_eq!(straight.lengths[0], 0.0);
    assert_eq!(straight.lengths[2], 0.0);
    assert!((straight.lengths[1] - from.distance(goal)).abs() < 1e-3);
    for heading in [0.0, 1.0, -2.5, 3.0] {
        let paths = planner.goal_paths(
            from,
            &Goal {
                position: goal,
                heading: Some(heading),
            },
        );
        for path in paths {
            let path = path.expect("both turns reach a goal 114 m away");
            assert_eq!(path.start.position, from);
            assert_eq!(path.lengths[0], 0.0);
            let end = path.end();
            assert!(end.position.distance(goal) < 1e-2, "{heading}: {path:?}");
            assert!(
                angle_gap(end.heading, heading) < 1e-4,
                "{heading}: {path:?}"
            );
        }
    }
}

/// Goal links from each node nearest the goal first, until enough: the node's goal paths that
/// exist and are clear (one for a free heading, up to two for a fixed one), each solve
/// counted; with three wanted, the first three.
#[test]
fn goal_links_join_the_nearest_nodes_until_enough() {
    let image = free_network();
    let codes = vec![FREE; (COLS * ROWS) as usize];
    let mut planner = Small::new();
    planner.load(&image).unwrap();
    let position = at(300.0, 220.0);
    let mut by_distance: Vec<u32> = (0..3).collect();
    by_distance.sort_by(|&a, &b| {
        position
            .distance(node(a))
            .total_cmp(&position.distance(node(b)))
    });
    for heading in [None, Some(0.5)] {
        let goal = Goal { position, heading };
        // Every path tried, in order, with whether it is kept.
        let mut tried = Vec::new();
        for &v in &by_distance {
            for path in planner.goal_paths(node(v), &goal).into_iter().flatten() {
                tried.push((v, path, clear(&path, &codes)));
            }
        }
        let expected: Vec<(u32, DubinsPath)> =
            tried.iter().filter(|t| t.2).map(|t| (t.0, t.1)).collect();
        assert!(
            expected.len() >= 3 && tried.len() >= 3,
            "{heading:?}: {tried:?}"
        );
        let mut meter = Meter::new(u64::MAX);
        planner.connect_terrain_goal(&goal, &mut meter).unwrap();
        let found = vertices_and_paths(&planner.goal_links);
        assert_eq!(found, expected, "{heading:?}");
        assert_eq!(meter.work.dubins_solves, tried.len() as u64);
        for link in &planner.goal_links {
            assert!(link.path.end().position.distance(position) < 1e-2);
            assert_eq!(link.cost, link.path.length());
        }

        planner.set_config(PlannerConfig {
            goal_candidates: 3,
            ..PlannerConfig::DEFAULT
        });
        let mut meter = Meter::new(u64::MAX);
        planner.connect_terrain_goal(&goal, &mut meter).unwrap();
        let found = vertices_and_paths(&planner.goal_links);
        assert_eq!(found, expected[..3]);
        let third = 1 + tried
            .iter()
            .enumerate()
            .filter(|(_, t)| t.2)
            .nth(2)
            .unwrap()
            .0;
        assert_eq!(meter.work.dubins_solves, third as u64);
        planner.set_config(PlannerConfig::DEFAULT);
    }
}

/// The direct path for a free goal heading is the shorter clear turn-then-straight (two
/// solves): over free terrain the right turn; with its straight blocked, the left one's loop;
/// with a fixed heading, the shortest Dubins path (one solve).
#[test]
fn the_direct_path_is_the_shorter_clear_one() {
    let (codes, start, goal) = right_turn_blocked();
    let free = Goal {
        position: goal,
        heading: None,
    };
    let turns = [Turn::Left, Turn::Right]
        .map(|t| DubinsPath::turn_then_straight(&start, R, goal, t).unwrap());
    assert!(turns[1].length() < turns[0].length());
    assert!(!clear(&turns[1], &codes) && clear(&turns[0], &codes));
    for (blocked, expected) in [(false, turns[1]), (true, turns[0])] {
        let image = match blocked {
            true => network(codes.clone(), R),
            false => free_network(),
        };
        let mut planner = Small::new();
        planner.load(&image).unwrap();
        let mut meter = Meter::new(u64::MAX);
        let direct = planner
            .direct_terrain_path(&start, &free, &mut meter)
            .unwrap();
        assert_eq!(direct, Some(expected), "blocked: {blocked}");
        assert_eq!(meter.work.dubins_solves, 2);
    }
    let image = free_network();
    let mut planner = Small::new();
    planner.load(&image).unwrap();
    let fixed = Goal {
        position: goal,
        heading: Some(-1.0),
    };
    let end = Pose::new(goal.x, goal.y, -1.0);
    let mut meter = Meter::new(u64::MAX);
    let direct = planner
        .direct_terrain_path(&start, &fixed, &mut meter)
        .unwrap();
    assert_eq!(direct, DubinsPath::shortest(&start, &end, R));
    assert_eq!(meter.work.dubins_solves, 1);
}
