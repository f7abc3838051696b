//! The collision tests of the start links, counted exactly. After the start's obstacle window
//! (one box distance per obstacle), each candidate tried costs, for each primitive of its
//! Dubins path in order, a box test per obstacle, and for each obstacle whose box the
//! primitive's box, widened by the clearance, overlaps, its exact tests (n + 1 for a polygon
//! of n vertices, 1 for a disc), until one conflicts; then each pop-up's tests, as the pop-up
//! counts them ([`Popup::conflicts`]). The boxes and the overlap are recomputed here in f64 from the
//! stored boxes; whether a primitive conflicts is the ground tool's predicate (it decides only
//! where the count stops). Candidates are tried nearest first until 8 links are made, each
//! with one Dubins solve.

use host_tests::world::{free_pose, world};
use host_tests::{cases, Rng};
use skyroute::network::write::ObstacleSpec;
use skyroute::planner::{Phase, PlannerConfig, Popup, MAX_CANDIDATES};
use skyroute::{DubinsPath, Planner, Pose, Vec2};

type TestPlanner<'n> = Planner<'n, 4096, 65536, 4, 1024>;

/// Whether boxes `a` (widened by `c`) and `b` overlap, in f64, and whether a side lies within
/// 1 mm of deciding the other way (where f32 rounding could).
fn overlap(a: (Vec2, Vec2), b: (Vec2, Vec2), c: f64) -> (bool, bool) {
    let f = |v: f32| v as f64;
    // `apart` in the core's order: each side's gap, positive when apart.
    let gaps = [
        f(a.0.x) - c - f(b.1.x),
        f(b.0.x) - (f(a.1.x) + c),
        f(a.0.y) - c - f(b.1.y),
        f(b.0.y) - (f(a.1.y) + c),
    ];
    let apart = gaps.iter().any(|&g| g > 0.0);
    let near = gaps.iter().any(|&g| g.abs() < 1e-3);
    (!apart, near)
}

/// The exact tests an obstacle costs one primitive.
fn exact_tests(o: &ObstacleSpec) -> u64 {
    match o {
        ObstacleSpec::Polygon(pts) => pts.len() as u64 + 1,
        ObstacleSpec::Circle { .. } => 1,
    }
}

#[test]
fn each_start_link_counts_its_box_and_exact_tests_per_primitive() {
    let mut rng = Rng(0x11AC);
    let (mut checked, mut exact_counted, mut blocked) = (0, 0u64, 0);
    for seed in 0..cases(3, 12) as u64 {
        let w = world(90 + seed, 1200.0, 60.0, 40.0, 12);
        let mut p: Box<TestPlanner<'_>> = Box::new(Planner::new());
        p.load(&w.bytes).unwrap();
        p.set_config(PlannerConfig {
            connect_radius_m: 400.0,
            ..PlannerConfig::DEFAULT
        });
        let centre = free_pose(&mut rng, &w, 80.0).position;
        let popup = Popup::Circle {
            centre,
            radius: 60.0,
        };
        p.add_popup(popup.clone()).unwrap();
        let net = *p.network();
        let c = net.clearance();
        let boxes: Vec<(Vec2, Vec2)> = (0..net.obstacle_count())
            .map(|i| net.obstacle(i).unwrap().1)
            .collect();
        'query: for _ in 0..cases(20, 60) {
            let start: Pose = free_pose(&mut rng, &w, 10.0);
            let goal = free_pose(&mut rng, &w, 10.0).position;
            let clear_of_popup = |q: Vec2| q.distance(centre) > 60.0 + c + 1.0;
            if !clear_of_popup(start.position) || !clear_of_popup(goal) {
                continue;
            }
            // The candidates: the 32 nearest within the connect radius, ties in index order.
            let mut near: Vec<(f32, u32)> = (0..net.vertex_count())
                .map(|v| (net.vertex(v).unwrap().position.distance(start.position), v))
                .filter(|&(d, _)| d <= 400.0)
                .collect();
            near.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
            near.truncate(MAX_CANDIDATES);
            let mut expected = w.obstacles.len() as u64; // the start's window
            let (mut links, mut tried) = (0, 0);
            for &(_, v) in &near {
                if links == 8 {
                    break;
                }
                tried += 1;
                let Some(path) = DubinsPath::shortest(&start, &net.vertex(v).unwrap(), 40.0) else {
                    continue;
                };
                let mut clear = true;
                'path: for prim in path.primitives().into_iter().flatten() {
                    let bbox = prim.bounding_box();
                    for (o, &obox) in w.obstacles.iter().zip(&boxes) {
                        expected += 1;
                        let (overlaps, ambiguous) = overlap(bbox, obox, c as f64);
                        if ambiguous {
                            continue 'query;
                        }
                        if overlaps {
                            expected += exact_tests(o);
                            exact_counted += 1;
                            if skyroute_prep::roadmap::primitive_conflicts(&prim, o, c) {
                                clear = false;
                                blocked += 1;
                                break 'path;
                            }
                        }
                    }
                    let (conflict, tests) = popup.conflicts(&prim, c);
                    expected += tests as u64;
                    if conflict {
                        clear = false;
                        blocked += 1;
                        break 'path;
                    }
                }
                links += clear as u32;
            }
            let mut marks = Vec::new();
            let _ = p.plan_observed(
                &host_tests::world::query_to(start, goal),
                u64::MAX,
                &mut |phase, work| marks.push((phase, (work.collision_tests, work.dubins_solves))),
            );
            let at = |phase| marks.iter().find(|m| m.0 == phase).map(|m| m.1);
            let (Some(from), Some(to)) = (at(Phase::ConnectStart), at(Phase::ConnectGoal)) else {
                panic!("{start:?}: phases {marks:?}");
            };
            assert_eq!(
                (to.0 - from.0, to.1 - from.1),
                (expected, tried),
                "{start:?}"
            );
            checked += 1;
        }
    }
    assert!(
        checked >= cases(3, 12) * 15 && exact_counted >= 50 && blocked >= 5,
        "{checked} queries, {exact_counted} exact checks, {blocked} blocked links"
    );
}
