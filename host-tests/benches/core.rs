//! Host timings of the onboard core: Dubins paths, the exact predicates, pop-up pruning and a
//! planning query on the `niendorf-urban` roadmap; the terrain query P → Q on the
//! `medeiros-jacksboro` network, the network load (validation), and an arc check against the
//! elevation grid; the landmark query on `babel-II-N`, with an in-flight rosette update, from an
//! online start, and its load; the Voronoi query P → Q on `ruz-popups` (as the `voronoi` firmware plans it), its load,
//! a radar popping up (`add_threat`) and the re-plan. Run: `cargo bench -p host-tests --bench core`.

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use skyroute::geometry::predicates::{
    arc_segment_distance, conflicts_with_polygon, segment_segment_distance,
};
use skyroute::geometry::spline::Piece;
use skyroute::planner::{Goal, Popup, Query, Search, VoronoiStorage};
use skyroute::{Arc, DubinsPath, Planner, Pose, Primitive, Segment, Vec2};
use std::f32::consts::PI;
use std::path::Path;

use host_tests::Rng;

fn geometry(c: &mut Criterion) {
    let mut rng = Rng(0x1234_5678);
    let poses: Vec<(Pose, Pose)> = (0..1024)
        .map(|_| {
            let a = Pose::new(
                rng.range_f32(-500.0, 500.0),
                rng.range_f32(-500.0, 500.0),
                rng.range_f32(-PI, PI),
            );
            let b = Pose::new(
                rng.range_f32(-500.0, 500.0),
                rng.range_f32(-500.0, 500.0),
                rng.range_f32(-PI, PI),
            );
            (a, b)
        })
        .collect();
    let mut i = 0;
    c.bench_function("dubins_shortest_six_words", |b| {
        b.iter(|| {
            i = (i + 1) % poses.len();
            black_box(DubinsPath::shortest(&poses[i].0, &poses[i].1, 64.0))
        })
    });
    let segs: Vec<Segment> = (0..1024)
        .map(|_| {
            Segment::new(
                Vec2::new(rng.range_f32(-100.0, 100.0), rng.range_f32(-100.0, 100.0)),
                Vec2::new(rng.range_f32(-100.0, 100.0), rng.range_f32(-100.0, 100.0)),
            )
        })
        .collect();
    let arcs: Vec<Arc> = (0..1024)
        .map(|_| Arc {
            centre: Vec2::new(rng.range_f32(-100.0, 100.0), rng.range_f32(-100.0, 100.0)),
            radius: rng.range_f32(10.0, 80.0),
            start_angle: rng.range_f32(-PI, PI),
            sweep: rng.range_f32(-6.0, 6.0),
        })
        .collect();
    let mut j = 0;
    c.bench_function("segment_segment_distance", |b| {
        b.iter(|| {
            j = (j + 1) % 1023;
            black_box(segment_segment_distance(&segs[j], &segs[j + 1]))
        })
    });
    c.bench_function("arc_segment_distance", |b| {
        b.iter(|| {
            j = (j + 1) % 1023;
            black_box(arc_segment_distance(&arcs[j], &segs[j]))
        })
    });
    let square = [
        Vec2::new(-20.0, -20.0),
        Vec2::new(20.0, -20.0),
        Vec2::new(20.0, 20.0),
        Vec2::new(-20.0, 20.0),
    ];
    c.bench_function("arc_vs_square_polygon_clearance", |b| {
        b.iter(|| {
            j = (j + 1) % 1023;
            black_box(conflicts_with_polygon(
                &Primitive::Arc(arcs[j]),
                &square[..],
                7.0,
            ))
        })
    });
}

fn niendorf(c: &mut Criterion) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenarios/niendorf-urban.geojson");
    let scenario = skyroute_prep::scenario::load(&path).expect("scenario");
    let built =
        skyroute_prep::build::build(&scenario, &Default::default(), &|_, _| {}).expect("network");
    let bytes: &'static [u8] = Box::leak(built.bytes.into_boxed_slice());
    let mut planner: Box<Planner<'static, 8192, 262144, 8, 1024>> = Box::new(Planner::new());
    planner.load(bytes).expect("loads");
    let frame = &built.frame;
    let start = scenario.start.as_ref().expect("start");
    let goal = scenario.goal.as_ref().expect("goal");
    let query = Query {
        start: skyroute_prep::build::local_pose(frame, start.lon, start.lat, start.heading_deg),
        goal: Goal {
            position: skyroute_prep::build::local(frame, goal.lon, goal.lat),
            heading: goal
                .heading_deg
                .map(|c| skyroute::geometry::heading_from_compass_deg(c as f32)),
        },
        search: Search::Dijkstra,
    };
    let at = |name: &str| {
        let e = scenario
            .waypoints
            .iter()
            .find(|w| w.name == name)
            .expect("waypoint");
        skyroute_prep::build::local(frame, e.lon, e.lat)
    };
    // W3 → W4 crosses the map (about 3.1 km): the longest leg of the mission.
    let across = Query {
        start: Pose {
            position: at("W3"),
            heading: 0.0,
        },
        goal: Goal {
            position: at("W4"),
            heading: None,
        },
        search: Search::Dijkstra,
    };
    eprintln!(
        "niendorf-urban network: {} vertices, {} edges, {} bytes",
        planner.network().vertex_count(),
        planner.network().edge_count(),
        bytes.len()
    );
    let queries = [
        ("plan_niendorf_start_to_goal_dijkstra", query),
        ("plan_niendorf_w3_to_w4_free_heading_dijkstra", across),
        (
            "plan_niendorf_w3_to_w4_free_heading_astar",
            Query {
                search: Search::AStar,
                ..across
            },
        ),
    ];
    for (name, q) in queries {
        let s = planner.plan(&q, u64::MAX).expect("route");
        eprintln!(
            "{name}: length {:.1} m, work {} (bound {})",
            s.length,
            s.work.total(),
            planner.worst_case_work()
        );
        c.bench_function(name, |b| b.iter(|| black_box(planner.plan(&q, u64::MAX))));
    }
    let centre = Vec2::new(0.0, 0.0);
    c.bench_function("add_and_remove_popup_r150_niendorf", |b| {
        b.iter(|| {
            let s = planner
                .add_popup(Popup::Circle {
                    centre,
                    radius: 150.0,
                })
                .expect("popup");
            planner.remove_popup(s.id).expect("remove");
            black_box(s)
        })
    });
}

fn jacksboro(c: &mut Criterion) {
    let path =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenarios/medeiros-jacksboro.geojson");
    let scenario = skyroute_prep::scenario::load(&path).expect("scenario");
    let built =
        skyroute_prep::build::build(&scenario, &Default::default(), &|_, _| {}).expect("network");
    let bytes: &'static [u8] = Box::leak(built.bytes.into_boxed_slice());
    // Search states: the network's directed edges and the start links (the equal split of
    // each straight between its turns; the paper's rule needs one state per transition).
    let mut planner: Box<Planner<'static, 65536, 65536, 8, 1024>> = Box::new(Planner::new());
    planner.load(bytes).expect("loads");
    planner.set_config(skyroute::PlannerConfig {
        turn_rule: skyroute::TurnRule::SharedEqually,
        ..skyroute_prep::mission::TERRAIN_CONFIG
    });
    let frame = &built.frame;
    let start = scenario.start.as_ref().expect("start");
    let goal = scenario.goal.as_ref().expect("goal");
    let query = Query {
        start: skyroute_prep::build::local_pose(frame, start.lon, start.lat, start.heading_deg),
        goal: Goal {
            position: skyroute_prep::build::local(frame, goal.lon, goal.lat),
            heading: None,
        },
        search: Search::Dijkstra,
    };
    let s = planner.plan(&query, u64::MAX).expect("route");
    eprintln!(
        "medeiros-jacksboro network: {} vertices, {} edges, {} bytes; P → Q {:.1} m, work {} \
         (bound {}), {:?}",
        planner.network().vertex_count(),
        planner.network().edge_count(),
        bytes.len(),
        s.length,
        s.work.total(),
        planner.worst_case_work(),
        planner.arc_check_stats()
    );
    c.bench_function("plan_jacksboro_p_to_q_750m", |b| {
        b.iter(|| black_box(planner.plan(&query, u64::MAX)))
    });
    planner.set_altitude(850.0, 100.0).expect("altitude");
    c.bench_function("plan_jacksboro_p_to_q_850m_set_in_flight", |b| {
        b.iter(|| black_box(planner.plan(&query, u64::MAX)))
    });
    c.bench_function("load_jacksboro_network", |b| {
        b.iter(|| black_box(skyroute::Network::from_bytes(black_box(bytes)).is_ok()))
    });
    // One turn arc of 60° at the turn radius against the grid, as the search checks it.
    let grid = planner.network().terrain_grid().expect("grid");
    let widen = planner.network().terrain().expect("terrain").widen_m;
    let arc = Arc {
        centre: query.start.position + Vec2::new(0.0, 300.0),
        radius: 300.0,
        start_angle: -PI / 2.0,
        sweep: PI / 3.0,
    };
    c.bench_function("arc_cells_60deg_r300_band_101m", |b| {
        b.iter(|| skyroute::geometry::grid::arc_cells(&grid, black_box(&arc), widen, |_, _| true))
    });
}

fn babel(c: &mut Criterion) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenarios/babel-II-N.geojson");
    let scenario = skyroute_prep::scenario::load(&path).expect("scenario");
    let t = std::time::Instant::now();
    let built =
        skyroute_prep::build::build(&scenario, &Default::default(), &|_, _| {}).expect("network");
    eprintln!("babel-II-N build: {:.2} s", t.elapsed().as_secs_f64());
    let bytes: &'static [u8] = Box::leak(built.bytes.into_boxed_slice());
    let mut planner: Box<Planner<'static, 256, 8192, 8, 256>> = Box::new(Planner::new());
    planner.load(bytes).expect("loads");
    let net = *planner.network();
    let l = *net.landmark().expect("landmark network");
    let query = Query {
        start: net.vertex(l.start_vertex).expect("start"),
        goal: Goal {
            position: net.vertex(l.goal_vertex).expect("goal").position,
            heading: None,
        },
        search: Search::Dijkstra,
    };
    let s = planner.plan(&query, u64::MAX).expect("route");
    eprintln!(
        "babel-II-N network: {} vertices, {} edges, {} bytes; P → Q {:.1} m, work {} (bound {})",
        net.vertex_count(),
        net.edge_count(),
        bytes.len(),
        s.length,
        s.work.total(),
        planner.worst_case_work()
    );
    c.bench_function("plan_babel_ii_n_p_to_q", |b| {
        b.iter(|| black_box(planner.plan(&query, u64::MAX)))
    });
    // A landmark found lost in flight: its rosette zeroed, then the re-plan.
    let lost = planner.route_edges()[1];
    let lost = net.edge_link(lost).expect("edge").source / l.directions;
    c.bench_function("update_rosette_and_replan_babel_ii_n", |b| {
        b.iter(|| {
            planner.update_rosette(lost, &[0.0; 12]).expect("update");
            let r = black_box(planner.plan(&query, u64::MAX));
            planner.clear_rosette(lost);
            r
        })
    });
    // From a pose that is no network vertex, halfway along the route's first edge, joined
    // online (direct Hermite pieces to the overflights within the start's range).
    let first = planner.route_edges()[0];
    let piece = net
        .chain_piece(first, net.chain_piece_count(first) / 2)
        .expect("piece");
    let (at, v) = (
        piece.position(piece.t_max() * 0.5).expect("position"),
        piece.velocity(piece.t_max() * 0.5).expect("velocity"),
    );
    let online = Query {
        start: Pose::new(at.x, at.y, v.y.atan2(v.x)),
        ..query
    };
    let s = planner.plan(&online, u64::MAX).expect("online route");
    eprintln!(
        "babel-II-N online start: {:.1} m, work {} (bound {})",
        s.length,
        s.work.total(),
        planner.worst_case_work()
    );
    c.bench_function("plan_babel_ii_n_online_start", |b| {
        b.iter(|| black_box(planner.plan(&online, u64::MAX)))
    });
    c.bench_function("load_babel_ii_n_network", |b| {
        b.iter(|| black_box(skyroute::Network::from_bytes(black_box(bytes)).is_ok()))
    });
}

/// The Voronoi firmware's planner type (`firmware-example/fixture-voronoi/query.rs`).
type VoronoiPlanner<'n> = Planner<'n, 320, 768, 4, 256>;

/// The pose `distance` metres along `pieces` on a line piece (the end of a cubic piece
/// otherwise), as `firmware_fixture` picks the Voronoi re-plan's start.
fn pose_along(pieces: &[Piece], distance: f32) -> Pose {
    let mut flown = 0.0;
    for p in pieces {
        let length = p.length();
        if flown + length >= distance {
            let t = match p {
                Piece::Line { .. } => ((distance - flown) / length).clamp(0.0, 1.0),
                Piece::Cubic { .. } => 1.0,
            };
            let d = p.tangent(t).expect("tangent");
            let q = p.point(t);
            return Pose::new(q.x, q.y, d.y.atan2(d.x));
        }
        flown += length;
    }
    panic!("the route is shorter than {distance} m")
}

fn voronoi(c: &mut Criterion) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenarios/ruz-popups.geojson");
    let mut scenario = skyroute_prep::scenario::load(&path).expect("scenario");
    scenario.planner.mode = skyroute_prep::scenario::Mode::Voronoi;
    let built =
        skyroute_prep::build::build(&scenario, &Default::default(), &|_, _| {}).expect("network");
    let bytes: &'static [u8] = Box::leak(built.bytes.into_boxed_slice());
    let frame = &built.frame;
    let (start, goal) = (
        scenario.start.as_ref().expect("start"),
        scenario.goal.as_ref().expect("goal"),
    );
    let query = Query {
        start: skyroute_prep::build::local_pose(frame, start.lon, start.lat, start.heading_deg),
        goal: Goal {
            position: skyroute_prep::build::local(frame, goal.lon, goal.lat),
            heading: goal
                .heading_deg
                .map(|h| skyroute_prep::build::local_heading(frame, goal.lon, goal.lat, h)),
        },
        search: Search::Dijkstra,
    };
    let storage: &'static mut VoronoiStorage = Box::leak(Box::new(VoronoiStorage::new()));
    let mut planner: Box<VoronoiPlanner<'static>> = Box::new(Planner::new());
    planner.load_voronoi(bytes, storage).expect("loads");
    let budget = planner.worst_case_work();
    let s = planner.plan(&query, budget).expect("route");
    let pieces = planner.route_pieces().to_vec();
    // The firmware fixture's radar: 3 km, on the middle of the longest straight.
    let (a, b) = pieces
        .iter()
        .filter_map(|p| match p {
            Piece::Line { a, b } => Some((*a, *b)),
            Piece::Cubic { .. } => None,
        })
        .max_by(|x, y| x.0.distance(x.1).total_cmp(&y.0.distance(y.1)))
        .expect("a straight");
    let site = (a + b) * 0.5;
    let requery = Query {
        start: pose_along(&pieces, 5000.0),
        ..query
    };
    eprintln!(
        "ruz-popups Voronoi network: {} bytes; P → Q {} m, {} pieces, work {} (bound {budget})",
        bytes.len(),
        s.length,
        pieces.len(),
        s.work.total()
    );
    c.bench_function("plan_voronoi_ruz_p_to_q", |b| {
        b.iter(|| black_box(planner.plan(&query, budget)))
    });
    // Only the timed call is counted (a fresh planner per iteration, untimed).
    c.bench_function("load_voronoi_ruz", |b| {
        b.iter_custom(|iters| {
            let mut storage = Box::new(VoronoiStorage::new());
            let mut total = std::time::Duration::ZERO;
            for _ in 0..iters {
                let mut p: Box<VoronoiPlanner<'_>> = Box::new(Planner::new());
                let t = std::time::Instant::now();
                black_box(p.load_voronoi(bytes, &mut storage)).expect("loads");
                total += t.elapsed();
            }
            total
        })
    });
    // Only the timed call is counted: each iteration loads afresh (untimed) so that the radar
    // is inserted into the network's diagram every time.
    c.bench_function("add_threat_ruz_r3000_on_route", |b| {
        b.iter_custom(|iters| {
            let mut storage = Box::new(VoronoiStorage::new());
            let mut total = std::time::Duration::ZERO;
            for _ in 0..iters {
                let mut p: Box<VoronoiPlanner<'_>> = Box::new(Planner::new());
                p.load_voronoi(bytes, &mut storage).expect("loads");
                let t = std::time::Instant::now();
                black_box(p.add_threat(site, 3000.0)).expect("threat");
                total += t.elapsed();
            }
            total
        })
    });
    let added = planner.add_threat(site, 3000.0).expect("threat");
    let r = planner.plan(&requery, budget).expect("re-plan");
    eprintln!(
        "add_threat ({}, {}) r 3000 m: {added:?}; re-plan from {:?}: {} m, {} pieces, work {}",
        site.x,
        site.y,
        requery.start,
        r.length,
        planner.route_pieces().len(),
        r.work.total()
    );
    c.bench_function("replan_voronoi_ruz_after_threat", |b| {
        b.iter(|| black_box(planner.plan(&requery, budget)))
    });
}

criterion_group!(benches, geometry, niendorf, jacksboro, babel, voronoi);
criterion_main!(benches);
