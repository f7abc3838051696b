//! The obstacle window of an endpoint (`planner/window.rs`) keeps the 32 obstacles nearest to
//! it whatever order the network lists them in: the same queries, on one network whose
//! obstacles are listed in several orders, give the same routes and count the same work.
//!
//! The counted collision tests tell which obstacles a window kept: a connection the window
//! covers is checked against its 32 kept obstacles, one it does not cover against all of them.
//! Every obstacle here lies far from every path, so no check stops early and the count does
//! not depend on the order in which the kept obstacles are tried.

use host_tests::reference::route_distance;
use host_tests::world::lattice_spec;
use host_tests::Rng;
use skyroute::geometry::point_box_distance;
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

/// The 4 × 4 lattice with its south-west corner at (`origin`, `origin`) and `obstacles`.
fn lattice_image(obstacles: Vec<ObstacleSpec>, origin: f32) -> Vec<u8> {
    let spec = skyroute::network::write::NetworkSpec {
        obstacles,
        grid_cell_m: 500.0,
        ..lattice_spec(4, 150.0, origin, 30.0)
    };
    encode(&spec).expect("the lattice encodes")
}

/// A planner on a lattice image, connecting endpoints within 200 m: to the nearest few
/// lattice points only, so most routes use the network.
fn lattice_planner(bytes: &[u8]) -> Box<WindowPlanner<'_>> {
    let mut p: Box<WindowPlanner<'_>> = Box::new(Planner::new());
    p.load(bytes).expect("the lattice loads");
    p.set_config(PlannerConfig {
        connect_radius_m: 200.0,
        ..PlannerConfig::DEFAULT
    });
    p
}

/// Every query's result on the network with `obstacles` in this order.
fn plan_all(
    obstacles: Vec<ObstacleSpec>,
    queries: &[Query],
) -> Vec<Result<RouteSummary, PlanError>> {
    let bytes = lattice_image(obstacles, 0.0);
    let mut p = lattice_planner(&bytes);
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
        .chain((0..4).map(|k| {
            // From one corner of the lattice to the opposite one: the corner lies 290 m from
            // the centre, so its connections reach past 500 m, as far as the near obstacles.
            let corner = |k: usize| {
                let (x, y) = [(20.0, 20.0), (430.0, 20.0), (430.0, 430.0), (20.0, 430.0)][k % 4];
                Vec2::new(x, y)
            };
            let (from, to) = (corner(k), corner(k + 2));
            Query {
                start: Pose {
                    position: from,
                    heading: (to - from).y.atan2((to - from).x) + PI,
                },
                goal: Goal {
                    position: to,
                    heading: None,
                },
                search: Search::Dijkstra,
            }
        }))
        .collect();

    let near_last: Vec<ObstacleSpec> = far.iter().chain(&near).cloned().collect();
    let reference = plan_all(near_last, &queries);
    let routed = reference.iter().filter(|r| r.is_ok()).count();
    assert!(
        routed >= 14,
        "only {routed} of 16 queries routed: {reference:?}"
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
    // every obstacle test them, one collision test each: four on every query (each endpoint's
    // free-space check, the start window, the goal window for the goal's connections) and a
    // fifth when the goal window is read again for the goal links the search makes exact. The
    // connections, all within the windows' reach, do not.
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
        assert!(
            added == 4 * 40 || added == 5 * 40,
            "query {i}: {added} more collision tests"
        );
    }
}

/// The distance the window ranks obstacles by, from a point to a bounding box, against the
/// nearest point of the box found by clamping the point into it, in f64: points inside, on
/// the edges, beside each side and corner, at coordinates near zero and of either sign (where
/// a difference replaced by a quotient, or a sum of squares by a product, goes wrong), and
/// up to 100 km away.
#[test]
fn the_point_to_box_distance_matches_the_clamped_nearest_point() {
    let mut rng = Rng(2026);
    let mut worst = 0.0f64;
    for i in 0..20_000 {
        let scale = [0.5f32, 10.0, 1_000.0, 100_000.0][i % 4];
        let coord = |rng: &mut Rng| rng.range_f32(-scale, scale);
        let (a, b) = (
            Vec2::new(coord(&mut rng), coord(&mut rng)),
            Vec2::new(coord(&mut rng), coord(&mut rng)),
        );
        let (lo, hi) = (
            Vec2::new(a.x.min(b.x), a.y.min(b.y)),
            Vec2::new(a.x.max(b.x), a.y.max(b.y)),
        );
        // Three points in eight on the line of the box's west, east or south side.
        let p = match i % 8 {
            0 => Vec2::new(lo.x, coord(&mut rng)),
            1 => Vec2::new(hi.x, coord(&mut rng)),
            2 => Vec2::new(coord(&mut rng), lo.y),
            _ => Vec2::new(coord(&mut rng), coord(&mut rng)),
        };
        let clamp = |v: f32, l: f32, h: f32| f64::from(v).clamp(f64::from(l), f64::from(h));
        let (nx, ny) = (clamp(p.x, lo.x, hi.x), clamp(p.y, lo.y, hi.y));
        let want = (f64::from(p.x) - nx).hypot(f64::from(p.y) - ny);
        let got = f64::from(point_box_distance(p, lo, hi));
        let error = (got - want).abs();
        // f32 differences of coordinates up to `scale`: a few ulps of the scale.
        assert!(
            error <= 4.0 * f64::from(f32::EPSILON) * f64::from(scale),
            "p {p:?}, box {lo:?}–{hi:?}: {got} against {want}"
        );
        worst = worst.max(error / f64::from(scale));
        let inside = p.x >= lo.x && p.x <= hi.x && p.y >= lo.y && p.y <= hi.y;
        assert_eq!(got == 0.0, inside, "p {p:?}, box {lo:?}–{hi:?}: {got}");
    }
    println!("largest error: {worst:e} of the coordinates' scale");
}

/// A straight connection of 100 m that ends 4 m from an obstacle (clearance 5 m) which is
/// the nearest one its endpoint's window leaves out, 32 smaller ones lying nearer on the other
/// side: the window's reach (the left-out obstacle's distance) is below the connection's
/// extent plus the clearance, so the connection must be checked against every obstacle and
/// refused. Once at the start (the connection runs from the window's centre) and once at the
/// goal (it runs to the centre, from 100 m away), on a lattice at the origin and one 5 km
/// away. Each query is routed, along the lattice line the refused connection would join, and
/// its first or last path keeps the clearance from the left-out circle (sampled in f64).
#[test]
fn a_connection_within_the_clearance_of_the_nearest_obstacle_left_out_is_refused() {
    let circle = |x: f32, y: f32, radius: f32| ObstacleSpec::Circle {
        centre: Vec2::new(x, y),
        radius,
    };
    // 32 circles of 1 m, 19 to 81 m from `at`, spread over 126° about the direction `towards`.
    let decoys = |at: Vec2, towards: f32| -> Vec<ObstacleSpec> {
        (0..32)
            .map(|k| {
                let angle = towards - 1.1 + 2.2 * k as f32 / 31.0;
                let d = 20.0 + 2.0 * k as f32;
                circle(at.x + d * angle.cos(), at.y + d * angle.sin(), 1.0)
            })
            .collect()
    };
    // (name, start, goal, the left-out circle, the window's centre, the decoys' direction
    // from it (away from the connection), whether the first or the last path is the
    // connection the circle would come near).
    let start = Vec2::new(50.0, 150.0);
    let goal = Vec2::new(400.0, 300.0);
    let cases = [
        // From the start east to the vertex (150, 150): the circle's box is 104 m east of
        // the start, 4 m beyond the vertex.
        (
            "start",
            start,
            Vec2::new(400.0, 150.0),
            (156.0, 150.0, 2.0),
            start,
            PI,
            true,
        ),
        // From the vertex (300, 300) east to the goal: the circle lies 4.5 m beside the line,
        // 94 m from the goal, nearer the vertex.
        (
            "goal",
            Vec2::new(100.0, 300.0),
            goal,
            (305.0, 305.5, 1.0),
            goal,
            0.0,
            false,
        ),
    ];
    // The lattice at the origin, and 5 km from it on both axes, where the window's margin
    // against rounding (1 m plus 10⁻³ of the extent and of the centre's coordinates) is 11 m.
    for shift in [0.0f32, 5_000.0] {
        let o = Vec2::new(shift, shift);
        for (name, from, to, (cx, cy, r), centre, towards, first) in cases {
            let (from, to, centre) = (from + o, to + o, centre + o);
            let (cx, cy) = (cx + shift, cy + shift);
            let mut obstacles = decoys(centre, towards);
            obstacles.push(circle(cx, cy, r));
            let bytes = lattice_image(obstacles, shift);
            let mut p = lattice_planner(&bytes);
            let q = Query {
                start: Pose {
                    position: from,
                    heading: 0.0,
                },
                goal: Goal {
                    position: to,
                    heading: Some(0.0),
                },
                search: Search::Dijkstra,
            };
            p.plan(&q, u64::MAX)
                .unwrap_or_else(|e| panic!("{name}: {e:?}"));
            let paths = p.route_paths();
            let link = if first { paths.first() } else { paths.last() };
            let link: Vec<_> = link
                .expect("a route")
                .primitives()
                .into_iter()
                .flatten()
                .collect();
            let gap = route_distance(&link, Vec2::new(cx, cy)) - f64::from(r);
            assert!(
                gap >= 5.0 - 0.01,
                "{name} at {shift} m: the connection comes {gap:.2} m from the left-out circle"
            );
        }
    }
}
