//! Planning on a three-dimensional roadmap (`planner/vertical.rs`): a low wall across a
//! lattice that a planar roadmap must go round and a three-dimensional one flies over. Every
//! route is checked by an independent f64 sampling in 3-D: each point of each path (the
//! path's own points), at the altitude of the f64 profile from the definitions
//! (`host_tests::reference::vertical_altitude`), must be above the wall's height plus the
//! clearance wherever it is within the clearance of its footprint (`reference::dist_polygon`).

use host_tests::reference::{dist_polygon, vertical_altitude, P};
use host_tests::world::lattice_spec;
use skyroute::geometry::predicates::conflicts_with_polygon;
use skyroute::geometry::vertical::{pieces_within, VerticalLimits, VerticalProfile};
use skyroute::network::write::VerticalSpec;
use skyroute::network::write::{encode, encode_three_dimensional, NetworkSpec, ObstacleSpec};
use skyroute::planner::{Goal, PlanError, Planner, Query, QueryField, Search};
use skyroute::{Pose, Vec2};

pub(crate) type Small<'n> = Planner<'n, 512, 8192, 4, 128>;

pub(crate) const CLEARANCE: f32 = 5.0;
const WALL_HEIGHT: f32 = 35.0;

/// The wall: 20 m thick across x = 290…310, from y = −100 to 480 (a gap above it, under the
/// lattice's top row at 600 m).
fn wall() -> Vec<Vec2> {
    vec![
        Vec2::new(290.0, -100.0),
        Vec2::new(310.0, -100.0),
        Vec2::new(310.0, 480.0),
        Vec2::new(290.0, 480.0),
    ]
}

/// Vertex altitudes by lattice position: 30, 40 or 50 m in a diagonal pattern.
fn altitude_at(p: Vec2) -> f32 {
    let (i, j) = ((p.x / 100.0).round() as i32, (p.y / 100.0).round() as i32);
    30.0 + 10.0 * ((i + j).rem_euclid(3)) as f32
}

pub(crate) fn limits() -> VerticalLimits {
    VerticalLimits::niendorf(25.0)
}

/// A 7 × 7 lattice 100 m apart (turn radius 30 m) with the wall, keeping the edges that clear
/// it: in 3-D (flyable climbs, the wall checked below its height plus the clearance) or in the
/// plane (the wall of unbounded height).
pub(crate) fn network(three_d: bool) -> Vec<u8> {
    let mut spec: NetworkSpec = lattice_spec(7, 100.0, 0.0, 30.0);
    spec.clearance_m = CLEARANCE;
    spec.obstacles = vec![ObstacleSpec::Polygon(wall())];
    let altitudes: Vec<f32> = spec
        .vertices
        .iter()
        .map(|v| altitude_at(v.position))
        .collect();
    let wall = wall();
    let poly = wall.as_slice();
    spec.edges.retain(|e| {
        let (a, b) = (
            spec.vertices[e.source as usize],
            spec.vertices[e.target as usize],
        );
        let Some(path) = skyroute::DubinsPath::with_word(&a, &b, 30.0, e.word) else {
            return false;
        };
        let (za, zb) = (altitudes[e.source as usize], altitudes[e.target as usize]);
        let pieces = match (
            three_d,
            VerticalProfile::new(za, zb, path.length(), &limits()),
        ) {
            (false, _) => path.primitives(),
            (true, None) => return false,
            (true, Some(profile)) => match profile.span_below(WALL_HEIGHT + CLEARANCE) {
                Some((s0, s1)) => pieces_within(&path, s0, s1),
                None => [None; 3],
            },
        };
        !pieces
            .iter()
            .flatten()
            .any(|p| conflicts_with_polygon(p, poly, CLEARANCE))
    });
    if !three_d {
        return encode(&spec).expect("planar network");
    }
    let vertical = VerticalSpec {
        limits: limits(),
        altitudes,
        heights: vec![WALL_HEIGHT],
    };
    encode_three_dimensional(&spec, &vertical, None).expect("3-D network")
}

pub(crate) fn query(start: Vec2, goal: Vec2) -> Query {
    Query {
        start: Pose::new(start.x, start.y, 0.0),
        goal: Goal {
            position: goal,
            heading: Some(0.0),
        },
        search: Search::Dijkstra,
    }
}

/// A random query with its start and goal in `[x0, x1] × [y0, y1]`, random headings (the goal's
/// given), and the start's and goal's altitudes, 20–60 m each.
pub(crate) fn random_query(
    rng: &mut host_tests::Rng,
    (x0, x1): (f32, f32),
    (y0, y1): (f32, f32),
) -> (Query, (f32, f32)) {
    let mut end = || {
        let p = Vec2::new(rng.range_f32(x0, x1), rng.range_f32(y0, y1));
        (p, rng.range_f32(-3.1, 3.1), rng.range_f32(20.0, 60.0))
    };
    let ((s, sh, sz), (g, gh, gz)) = (end(), end());
    let q = Query {
        start: Pose::new(s.x, s.y, sh),
        goal: Goal {
            position: g,
            heading: Some(gh),
        },
        search: Search::Dijkstra,
    };
    (q, (sz, gz))
}

/// Samples the planner's route every 0.25 m in 3-D; returns the least margin above the
/// wall's height plus the clearance among points within the clearance of its footprint
/// (+∞ when no point comes near it) and asserts each path's profile joins the altitudes.
fn least_margin_over_wall(planner: &Small, start_z: f32, goal_z: f32) -> f64 {
    least_margin_after(planner, start_z, goal_z, 0)
}

/// [`least_margin_over_wall`] from path `first` on (1: after an exit, which may fly within
/// the clearance of the region it leaves).
fn least_margin_after(planner: &Small, start_z: f32, goal_z: f32, first: usize) -> f64 {
    let paths = planner.route_paths();
    let altitudes = planner.route_altitudes();
    assert_eq!(altitudes.len(), paths.len(), "one altitude per path");
    assert_eq!(*altitudes.last().unwrap(), goal_z);
    let wall: Vec<P> = wall().iter().map(|p| (p.x as f64, p.y as f64)).collect();
    let mut least = f64::INFINITY;
    for (k, path) in paths.iter().enumerate() {
        let profile = planner
            .route_profile(k)
            .expect("every path has a flyable profile");
        let from = if k == 0 { start_z } else { altitudes[k - 1] };
        assert_eq!((profile.from, profile.to), (from, altitudes[k]), "path {k}");
        let n = (4.0 * path.length() as f64).ceil().max(1.0) as usize;
        for i in 0..=n {
            let s = path.length() as f64 * i as f64 / n as f64;
            let at = path.sample(s as f32).position;
            let z = vertical_altitude(&profile, &limits(), s);
            if k >= first && dist_polygon((at.x as f64, at.y as f64), &wall) < CLEARANCE as f64 {
                least = least.min(z - (WALL_HEIGHT + CLEARANCE) as f64);
            }
        }
    }
    least
}

#[test]
fn a_three_dimensional_route_flies_over_a_low_wall_that_a_planar_one_goes_round() {
    let (planar, solid) = (network(false), network(true));
    let (start, goal) = (Vec2::new(0.0, 100.0), Vec2::new(600.0, 100.0));

    let mut flat = Small::new();
    flat.load(&planar).unwrap();
    let round = flat
        .plan(&query(start, goal), u64::MAX)
        .expect("planar route");

    let mut planner = Small::new();
    planner.load(&solid).unwrap();
    assert_eq!(
        planner.plan(&query(start, goal), u64::MAX),
        Err(PlanError::AltitudesNeeded)
    );
    planner.set_query_altitudes(30.0, 30.0).unwrap();
    let over = planner
        .plan(&query(start, goal), u64::MAX)
        .expect("3-D route");
    assert!(
        over.length < round.length - 200.0,
        "over the wall {} m, round it {} m",
        over.length,
        round.length
    );
    assert!(over.work.total() <= planner.worst_case_work());
    let margin = least_margin_over_wall(&planner, 30.0, 30.0);
    assert!(margin.is_finite(), "the route passes over the wall");
    assert!(
        margin >= -1e-3,
        "{margin} m below the wall's height plus clearance"
    );
    // Post-processing keeps it flyable and clear, with one altitude per path.
    let best = planner.shortcut_best(u64::MAX).unwrap();
    assert!(best.length_after <= best.length_before);
    planner.smooth_headings(9, u64::MAX).unwrap();
    assert!(least_margin_over_wall(&planner, 30.0, 30.0) >= -1e-3);
    planner.shortcut(u64::MAX).unwrap();
    assert!(least_margin_over_wall(&planner, 30.0, 30.0) >= -1e-3);
}

#[test]
fn endpoints_above_a_wall_are_free_and_inside_it_are_refused() {
    let solid = network(true);
    let mut planner = Small::new();
    planner.load(&solid).unwrap();
    let on_wall = Vec2::new(300.0, 200.0);
    // A goal over the wall's footprint, above its height: planned, and arrived at that
    // altitude.
    planner.set_query_altitudes(30.0, 50.0).unwrap();
    planner
        .plan(&query(Vec2::new(0.0, 100.0), on_wall), u64::MAX)
        .expect("a goal above the wall");
    assert_eq!(planner.route_altitudes().last(), Some(&50.0));
    assert!(least_margin_over_wall(&planner, 30.0, 50.0) >= -1e-3);
    // Below its height: inside it.
    planner.set_query_altitudes(30.0, 20.0).unwrap();
    assert_eq!(
        planner.plan(&query(Vec2::new(0.0, 100.0), on_wall), u64::MAX),
        Err(PlanError::InsideObstacle {
            field: QueryField::Goal,
            obstacle: 0
        })
    );
}

#[test]
fn altitudes_are_refused_on_a_planar_network_or_when_not_finite() {
    let (planar, solid) = (network(false), network(true));
    let mut flat = Small::new();
    flat.load(&planar).unwrap();
    assert_eq!(
        flat.set_query_altitudes(30.0, 30.0),
        Err(PlanError::NotThreeDimensional)
    );
    assert_eq!(flat.query_altitudes(), None);
    assert!(flat.route_altitudes().is_empty());
    let mut planner = Small::new();
    planner.load(&solid).unwrap();
    planner.set_query_altitudes(30.0, 40.0).unwrap();
    for (a, b) in [
        (f32::NAN, 30.0),
        (30.0, f32::INFINITY),
        (1.0001e5, 30.0),
        (30.0, -1.0001e5),
    ] {
        assert_eq!(
            planner.set_query_altitudes(a, b),
            Err(PlanError::InvalidAltitude)
        );
    }
    assert_eq!(
        planner.query_altitudes(),
        Some((30.0, 40.0)),
        "the setting is kept"
    );
}

/// Random starts and goals on both sides of the wall and over it, at random altitudes: every
/// route the planner finds, and every route post-processing makes of it, keeps above the
/// wall's height plus the clearance wherever it comes within the clearance of the footprint.
/// The links and shortcuts the planner builds in flight are what cross the wall here.
#[test]
fn random_queries_over_the_wall_keep_above_it() {
    let solid = network(true);
    let mut planner = Small::new();
    planner.load(&solid).unwrap();
    let mut rng = host_tests::Rng(0x3D_0001);
    let (mut routed, mut over, mut exits) = (0, 0, 0);
    for case in 0..host_tests::cases(150, 1_500) {
        let (q, (sz, gz)) = random_query(&mut rng, (150.0, 450.0), (0.0, 500.0));
        planner.set_query_altitudes(sz, gz).unwrap();
        let Ok(summary) = planner.plan(&q, u64::MAX) else {
            continue;
        };
        routed += 1;
        assert!(
            summary.work.total() <= planner.worst_case_work(),
            "case {case}"
        );
        // A start within the wall's clearance below its height plus the clearance leaves by
        // an exit, flown level, which may be that near it (`planner/exit.rs`).
        let first = summary.exit.is_some() as usize;
        exits += first as u32;
        let margin = least_margin_after(&planner, sz, gz, first);
        assert!(margin >= -1e-3, "case {case}: {margin} m below ({q:?})");
        over += margin.is_finite() as u32;
        planner.shortcut_best(u64::MAX).unwrap();
        planner.smooth_headings(9, u64::MAX).unwrap();
        let margin = least_margin_after(&planner, sz, gz, first);
        assert!(
            margin >= -1e-3,
            "case {case} smoothed: {margin} m below ({q:?})"
        );
    }
    assert!(
        routed >= 30 && over >= 10,
        "{routed} routed, {over} over the wall"
    );
    eprintln!("{routed} routed, {over} over the wall, {exits} after an exit");
}

/// A query whose budget is one short of its work is refused, and the previous route and its
/// altitudes stay as they were.
#[test]
fn a_budget_one_short_keeps_the_previous_route_and_its_altitudes() {
    let solid = network(true);
    let mut planner = Small::new();
    planner.load(&solid).unwrap();
    planner.set_query_altitudes(30.0, 40.0).unwrap();
    let first = query(Vec2::new(0.0, 100.0), Vec2::new(600.0, 200.0));
    planner.plan(&first, u64::MAX).unwrap();
    let (paths, altitudes) = (
        planner.route_paths().to_vec(),
        planner.route_altitudes().to_vec(),
    );
    let second = query(Vec2::new(0.0, 500.0), Vec2::new(600.0, 100.0));
    planner.set_query_altitudes(50.0, 30.0).unwrap();
    let needed = {
        let mut probe = Small::new();
        probe.load(&solid).unwrap();
        probe.set_query_altitudes(50.0, 30.0).unwrap();
        probe.plan(&second, u64::MAX).unwrap().work.total()
    };
    assert!(matches!(
        planner.plan(&second, needed - 1),
        Err(PlanError::BudgetExhausted { .. })
    ));
    assert_eq!(planner.route_paths(), paths.as_slice());
    assert_eq!(planner.route_altitudes(), altitudes.as_slice());
    assert_eq!(planner.plan(&second, needed).unwrap().work.total(), needed);
    assert_eq!(planner.route_altitudes().last(), Some(&30.0));
}

/// `route_altitude_at` walks the route's primitives in the order of `route()` and gives each
/// point the altitude of its path's profile (checked against the f64 profile); past the route,
/// and on a planar network, there is none.
#[test]
fn route_altitudes_by_primitive_follow_each_paths_profile() {
    let solid = network(true);
    let mut planner = Small::new();
    planner.load(&solid).unwrap();
    planner.set_query_altitudes(30.0, 50.0).unwrap();
    let q = query(Vec2::new(0.0, 100.0), Vec2::new(600.0, 200.0));
    planner.plan(&q, u64::MAX).unwrap();
    let route = planner.route().to_vec();
    let mut k = 0;
    for (p, path) in planner.route_paths().iter().enumerate() {
        let profile = planner.route_profile(p).unwrap();
        let mut offset = 0.0;
        for (prim, length) in path.primitives().iter().zip(path.lengths) {
            let Some(prim) = prim else {
                offset += length;
                continue;
            };
            assert_eq!(route[k], *prim, "primitive {k}");
            for f in [0.0, 0.3, 0.7, 1.0] {
                let s = f * length;
                let z = planner.route_altitude_at(k, s).unwrap() as f64;
                let expected = vertical_altitude(&profile, &limits(), (offset + s) as f64);
                assert!(
                    (z - expected).abs() < 1e-3,
                    "primitive {k} at {s}: {z} {expected}"
                );
            }
            k += 1;
            offset += length;
        }
    }
    assert_eq!(k, route.len());
    assert_eq!(planner.route_altitude_at(k, 0.0), None);
    assert_eq!(planner.route_altitude_at(0, f32::NAN), Some(30.0));
    assert_eq!(planner.route_altitude_at(k - 1, f32::INFINITY), Some(50.0));
    let planar = network(false);
    let mut flat = Small::new();
    flat.load(&planar).unwrap();
    flat.plan(&q, u64::MAX).unwrap();
    assert_eq!(flat.route_altitude_at(0, 0.0), None);
}
