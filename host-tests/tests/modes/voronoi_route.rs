//! Voronoi mode's route as written out (`planner/voronoi/route.rs`): the line chords for
//! autopilots that fly lines only, against the smoothed pieces in f64, and the start and goal
//! joined to the graph or, with no graph vertex in reach, to each other.

use crate::voronoi_plan::{curvature64, p64, planner, query, voronoi, VPlanner};
use host_tests::reference::{dist_point_segment, dist_polygon, dist_segment_segment, inside, P};
use skyroute::geometry::spline::Piece;
use skyroute::planner::{VoronoiStorage, CHORD_TOLERANCE_M};
use skyroute::{Goal, PlanError, Planner, Primitive, Query, Vec2};

/// The route of line chords (`Planner::route`, for autopilots that fly lines only) runs
/// unbroken from the start to the goal, and follows the smoothed pieces within the reported
/// chord deviation, itself within [`CHORD_TOLERANCE_M`]: every sampled point of a piece lies
/// that near a chord, and every chord's ends and middle that near the pieces (f64 distances to
/// the pieces sampled 400 times each).
#[test]
fn the_route_of_chords_follows_the_pieces_within_the_chord_tolerance() {
    for name in ["ruz-popups", "voronoi-dense"] {
        let (s, b) = voronoi(name);
        for k in [0.1f32, 0.5, 1.0] {
            let mut p = planner(&b.bytes);
            p.set_threat_weight(k).unwrap();
            let q = query(&s, &b);
            let summary = p.plan(&q, p.worst_case_work()).unwrap();
            let chords: Vec<(P, P)> = p
                .route()
                .iter()
                .map(|primitive| match primitive {
                    Primitive::Line(l) => (p64(l.start), p64(l.end)),
                    other => panic!("{name} k={k}: a Voronoi route holds {other:?}"),
                })
                .collect();
            assert_eq!(summary.primitives as usize, chords.len(), "{name} k={k}");
            assert_eq!(chords[0].0, p64(q.start.position), "{name} k={k}");
            assert!(
                chords.windows(2).all(|w| w[0].1 == w[1].0),
                "{name} k={k}: a gap"
            );
            let end = chords.last().unwrap().1;
            assert!(host_tests::reference::dist(end, p64(q.goal.position)) < 0.05);
            let (_, v, _) = curvature64(p.route_pieces().last().unwrap(), 1.0);
            let turn = (summary.arrival_heading as f64 - v.1.atan2(v.0) + std::f64::consts::PI)
                .rem_euclid(std::f64::consts::TAU)
                - std::f64::consts::PI;
            assert!(
                turn.abs() < 1e-2,
                "{name} k={k}: arrival heading off by {turn} rad"
            );
            let deviation = p.chord_deviation().unwrap() as f64;
            assert!(
                deviation <= CHORD_TOLERANCE_M as f64,
                "{name} k={k}: {deviation}"
            );
            let samples: Vec<P> = p
                .route_pieces()
                .iter()
                .flat_map(|piece| (0..=400).map(|j| curvature64(piece, j as f64 / 400.0).0))
                .collect();
            let to_chords = |x: P| {
                chords
                    .iter()
                    .map(|c| dist_point_segment(x, c.0, c.1))
                    .fold(f64::INFINITY, f64::min)
            };
            let to_pieces = |x: P| {
                samples
                    .windows(2)
                    .map(|w| dist_point_segment(x, w[0], w[1]))
                    .fold(f64::INFINITY, f64::min)
            };
            for x in &samples {
                let d = to_chords(*x);
                assert!(
                    d <= deviation + 1e-3,
                    "{name} k={k}: {x:?} is {d} m from the chords"
                );
            }
            for c in &chords {
                let middle = ((c.0 .0 + c.1 .0) / 2.0, (c.0 .1 + c.1 .1) / 2.0);
                for x in [c.0, middle, c.1] {
                    let d = to_pieces(x);
                    assert!(
                        d <= deviation + 1e-2,
                        "{name} k={k}: chord point {x:?} {d} m off"
                    );
                }
            }
        }
    }
}

/// With the direct segment blocked (a pop-up on its middle), the route goes through the graph;
/// with the start and the goal walled in by four pop-ups that no graph vertex lies within (no
/// vertex in reach of either), the route is the direct segment.
#[test]
fn a_blocked_direct_segment_routes_through_the_graph_and_a_walled_in_pair_flies_direct() {
    let (s, b) = voronoi("ruz-popups");
    let q = query(&s, &b);
    let (a, g) = (q.start.position, q.goal.position);
    let mut p = planner(&b.bytes);
    let radius = 0.2 * a.distance(g);
    p.add_popup(skyroute::Popup::Circle {
        centre: (a + g) * 0.5,
        radius,
    })
    .unwrap();
    let through_graph = p.plan(&q, p.worst_case_work()).unwrap();
    assert!(through_graph.network_edges > 0);

    // A goal 300 m ahead of the start, and a square wall 200 m thick around both, 1.5 km
    // inside.
    let mut p = planner(&b.bytes);
    let goal = ahead_of_start(&q, 300.0);
    let centre = (a + goal) * 0.5;
    let (inner, outer) = (1500.0f32, 1700.0f32);
    let rect = |lo: Vec2, hi: Vec2| {
        skyroute::Popup::Polygon(
            [lo, Vec2::new(hi.x, lo.y), hi, Vec2::new(lo.x, hi.y)]
                .into_iter()
                .map(|v| centre + v)
                .collect(),
        )
    };
    for wall in [
        rect(Vec2::new(-outer, -outer), Vec2::new(outer, -inner)),
        rect(Vec2::new(-outer, inner), Vec2::new(outer, outer)),
        rect(Vec2::new(-outer, -outer), Vec2::new(-inner, outer)),
        rect(Vec2::new(inner, -outer), Vec2::new(outer, outer)),
    ] {
        p.add_popup(wall).unwrap();
    }
    let graph = p.threat_graph().unwrap();
    assert!(
        graph
            .vertices()
            .iter()
            .all(|v| (v.x - centre.x).abs().max((v.y - centre.y).abs()) > outer),
        "a graph vertex lies within the wall"
    );
    let walled = Query {
        goal: Goal {
            position: goal,
            heading: None,
        },
        ..q
    };
    let direct = p.plan(&walled, p.worst_case_work()).unwrap();
    assert_eq!(direct.network_edges, 0);
    let last = p.route().last().unwrap();
    let end = last.pose_at(last.length()).position;
    assert!(
        end.distance(goal) < 0.05,
        "ends {} m from the goal",
        end.distance(goal)
    );
}

/// The point `metres` ahead of the query's start along its heading.
fn ahead_of_start(q: &Query, metres: f32) -> Vec2 {
    let heading = q.start.heading;
    q.start.position + Vec2::new(heading.cos(), heading.sin()) * metres
}

/// A pop-up disc on the middle of a corner piece, wholly inside that corner's hull triangle and
/// farther than the clearance from its sides and from every coarse leg: the coarse route is
/// unchanged, so the corner's hull test alone can see it. The plan is refused as `Smoothing`
/// at that corner (the coarse vertex nearest the disc), with the previous route kept.
#[test]
fn a_popup_inside_a_corner_hull_refuses_that_corner_and_keeps_the_route() {
    let (q, mut p, clearance, legs) = dense_route();
    let radius = 1.0;
    // The corner whose middle lies deepest inside its hull triangle (p0, p1, p3).
    let (centre, depth) = p
        .route_pieces()
        .iter()
        .filter_map(|piece| match piece {
            Piece::Cubic { p: c } => {
                let m = curvature64(piece, 0.5).0;
                let (a, t, e) = (p64(c[0]), p64(c[1]), p64(c[3]));
                let sides = [(a, t), (t, e), (e, a)];
                let depth = sides
                    .iter()
                    .chain(legs.iter())
                    .map(|(u, v)| dist_point_segment(m, *u, *v))
                    .fold(f64::INFINITY, f64::min);
                Some((m, depth))
            }
            Piece::Line { .. } => None,
        })
        .max_by(|x, y| x.1.total_cmp(&y.1))
        .expect("a corner piece");
    assert!(
        depth > radius + clearance + 1.0,
        "the deepest corner middle is only {depth} m inside"
    );
    let disc = skyroute::Popup::Circle {
        centre: Vec2::new(centre.0 as f32, centre.1 as f32),
        radius: radius as f32,
    };
    // Corner `i + 1` is the coarse route's vertex `i` (`PlanError::Smoothing`): the start of
    // leg `i + 1`.
    let (nearest, _) = legs
        .iter()
        .skip(1)
        .map(|l| host_tests::reference::dist(l.0, centre))
        .enumerate()
        .min_by(|x, y| x.1.total_cmp(&y.1))
        .unwrap();
    let distance = |at: P| host_tests::reference::dist(at, centre) - radius;
    let refused = replan_with_popup(&mut p, &q, disc, &distance, clearance);
    assert_eq!(refused, Some(nearest as u32 + 1), "the refused corner");
}

/// voronoi-dense's query planned once: the query, the planner (its network leaked: a test's
/// lifetime), the clearance and the coarse route's legs.
pub(crate) fn dense_route() -> (Query, Box<VPlanner<'static>>, f64, Vec<(P, P)>) {
    let (s, b) = voronoi("voronoi-dense");
    let q = query(&s, &b);
    let bytes: &'static [u8] = Box::leak(b.bytes.into_boxed_slice());
    let mut p = planner(bytes);
    p.plan(&q, p.worst_case_work()).unwrap();
    let clearance = p.network().clearance() as f64;
    let legs = coarse_legs(&p);
    (q, p, clearance, legs)
}

/// The coarse route's legs (start, graph vertices, goal).
pub(crate) fn coarse_legs(p: &VPlanner) -> Vec<(P, P)> {
    p.route_paths()
        .iter()
        .map(|l| (p64(l.start.position), p64(l.end().position)))
        .collect()
}

/// Adds `popup` and plans again: refused at a corner with the route kept (returns the corner),
/// or flown at least the clearance from the pop-up by `distance` (negative inside it), sampling
/// every piece in f64.
pub(crate) fn replan_with_popup(
    p: &mut VPlanner,
    q: &Query,
    popup: skyroute::Popup,
    distance: &dyn Fn(P) -> f64,
    clearance: f64,
) -> Option<u32> {
    let before = (p.route().to_vec(), p.route_pieces().to_vec());
    p.add_popup(popup).unwrap();
    match p.plan(q, p.worst_case_work()) {
        Err(PlanError::Smoothing { corner }) => {
            assert_eq!((p.route().to_vec(), p.route_pieces().to_vec()), before);
            Some(corner)
        }
        Ok(_) => {
            for piece in p.route_pieces() {
                for j in 0..=400 {
                    let d = distance(curvature64(piece, j as f64 / 400.0).0);
                    assert!(d >= clearance - 0.5, "passes {d} m from the pop-up");
                }
            }
            None
        }
        Err(e) => panic!("{e}"),
    }
}

/// A thin pop-up needle through the middle of a corner piece, out across the hull triangle's
/// chord (from the piece's first to its last point) to a centre behind it, so that the
/// triangle's chord side meets it but holds neither its centre nor any zone's; it lies farther
/// than the clearance from every coarse leg. The plan is refused (`Smoothing`) with the route
/// kept, or flies clear of the needle.
#[test]
fn a_popup_across_a_corner_hulls_chord_is_flown_clear_of_or_the_corner_refused() {
    let (q, mut p, clearance, legs) = dense_route();
    let half_width = 1.0;
    // Per corner: the needle from 2 m past the piece's middle `m` to as far behind the chord's
    // middle as `m` is in front of it plus 20 m (its centre 9 m behind the chord), and its
    // margin beyond the clearance from the coarse legs.
    let (tip, base, margin) = p
        .route_pieces()
        .iter()
        .filter_map(|piece| match piece {
            Piece::Cubic { p: c } => {
                let m = curvature64(piece, 0.5).0;
                let chord = (
                    (c[0].x + c[3].x) as f64 / 2.0,
                    (c[0].y + c[3].y) as f64 / 2.0,
                );
                let h = host_tests::reference::dist(chord, m);
                let u = ((m.0 - chord.0) / h, (m.1 - chord.1) / h);
                let tip = (m.0 + 2.0 * u.0, m.1 + 2.0 * u.1);
                let base = (chord.0 - (h + 20.0) * u.0, chord.1 - (h + 20.0) * u.1);
                let to_legs = legs
                    .iter()
                    .map(|(a, b)| dist_segment_segment(tip, base, *a, *b))
                    .fold(f64::INFINITY, f64::min);
                Some((tip, base, to_legs - half_width - clearance))
            }
            Piece::Line { .. } => None,
        })
        .max_by(|x, y| x.2.total_cmp(&y.2))
        .expect("a corner piece");
    assert!(
        margin > 1.0,
        "the best corner's needle is {margin} m from the legs' clearance"
    );
    let length = host_tests::reference::dist(tip, base);
    let n = (
        -(tip.1 - base.1) / length * half_width,
        (tip.0 - base.0) / length * half_width,
    );
    let needle: Vec<P> = vec![
        (base.0 - n.0, base.1 - n.1),
        (tip.0 - n.0, tip.1 - n.1),
        (tip.0 + n.0, tip.1 + n.1),
        (base.0 + n.0, base.1 + n.1),
    ];
    let popup = skyroute::Popup::Polygon(
        needle
            .iter()
            .map(|v| Vec2::new(v.0 as f32, v.1 as f32))
            .collect(),
    );
    let distance = |at: P| {
        let d = dist_polygon(at, &needle);
        if inside(at, &needle) {
            -d
        } else {
            d
        }
    };
    replan_with_popup(&mut p, &q, popup, &distance, clearance);
}

/// The work counts what the documented work model says a plan does at least: every graph edge
/// priced against every threat at three points (`threat_steps`), and every graph vertex scanned
/// once for the start's candidates and once for the goal's (`vertex_scans`).
#[test]
fn the_work_counts_each_priced_edge_and_each_vertex_scan() {
    for name in ["ruz-popups", "voronoi-dense"] {
        let (s, b) = voronoi(name);
        let mut p = planner(&b.bytes);
        let work = p.plan(&query(&s, &b), p.worst_case_work()).unwrap().work;
        let g = p.threat_graph().unwrap();
        let threats = p.threats().len() as u64;
        let (vertices, edges) = (g.vertex_count() as u64, g.edges().len() as u64);
        assert!(
            work.threat_steps >= 3 * threats * edges,
            "{name}: {} threat steps for {edges} edges and {threats} threats",
            work.threat_steps
        );
        assert!(
            work.vertex_scans >= 2 * vertices,
            "{name}: {} vertex scans for {vertices} vertices",
            work.vertex_scans
        );
    }
}

/// A planner holding fewer primitives than a route's chords (but more than its coarse legs)
/// refuses it with both counts and keeps the route it had; one holding exactly a route's
/// chords flies it.
#[test]
fn a_route_of_more_chords_than_the_planner_holds_is_refused_and_the_route_kept() {
    const R: usize = 32;
    let (s, b) = voronoi("voronoi-dense");
    let q = query(&s, &b);
    let mut large = planner(&b.bytes);
    let full = large.plan(&q, large.worst_case_work()).unwrap();
    let legs = large.route_paths().len();
    assert!(
        legs <= R && full.primitives as usize > R,
        "{legs} legs, {full:?}"
    );
    let storage = Box::leak(Box::new(VoronoiStorage::new()));
    let mut p: Box<Planner<'_, 1024, 1024, 4, R>> = Box::new(Planner::new());
    p.load_voronoi(&b.bytes, storage).unwrap();
    let short = Query {
        goal: Goal {
            position: ahead_of_start(&q, 300.0),
            heading: None,
        },
        ..q
    };
    p.plan(&short, p.worst_case_work()).unwrap();
    let kept = (p.route().to_vec(), p.route_pieces().to_vec());
    assert_eq!(
        p.plan(&q, p.worst_case_work()),
        Err(PlanError::RouteTooLong {
            primitives: full.primitives,
            capacity: R as u32,
        })
    );
    assert_eq!((p.route().to_vec(), p.route_pieces().to_vec()), kept);
    // The short route is three chords on one leg: a planner holding exactly three flies it.
    const SHORT: usize = 3;
    assert_eq!((kept.0.len(), p.route_paths().len()), (SHORT, 1));
    let storage = Box::leak(Box::new(VoronoiStorage::new()));
    let mut exact: Box<Planner<'_, 1024, 1024, 4, SHORT>> = Box::new(Planner::new());
    exact.load_voronoi(&b.bytes, storage).unwrap();
    exact.plan(&short, exact.worst_case_work()).unwrap();
    assert_eq!(exact.route(), &kept.0[..]);
}
