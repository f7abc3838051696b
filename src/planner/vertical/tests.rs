//! The three-dimensional roadmap's onboard checks, each against values worked out from the
//! definitions: the altitudes a link or leg flies between, the junction bookkeeping of
//! post-processing, a path's climb and its clearance below each obstacle's height (against a
//! sampled f64 reference), the work it counts, and the route's altitudes after a plan.
//!
//! The worlds lie at negative coordinates, so that a bound that multiplies or divides a
//! coordinate instead of adding the clearance to it errs (at positive ones some such errors
//! are safe).

extern crate std;
use crate::geometry::vertical::VerticalLimits;
use crate::geometry::{DubinsPath, DubinsWord, Pose, Vec2};
use crate::network::write::{
    encode, encode_three_dimensional, EdgeSpec, NetworkSpec, ObstacleSpec, VerticalSpec,
};
use crate::planner::popup::Popup;
use crate::planner::search::Arrival;
use crate::planner::state::{LinkEnd, ModeState};
use crate::planner::{Goal, Link, Meter, PlanError, Planner, Query, Search, FROM_START};
use crate::test_rng::Rng;
use std::format;
use std::vec;
use std::vec::Vec;

type Small<'n> = Planner<'n, 64, 512, 4, 32>;

/// Niendorf et al.'s aircraft at 25 m/s: gradient g = 0.4, curvature k = 0.032 per metre.
const LIMITS: VerticalLimits = VerticalLimits::niendorf(25.0);
const CLEARANCE: f32 = 5.0;
const RADIUS: f32 = 30.0;
const ORIGIN: Vec2 = Vec2::new(-3000.0, -2000.0);

/// A point `(dx, dy)` metres from [`ORIGIN`].
fn at(dx: f32, dy: f32) -> Vec2 {
    ORIGIN + Vec2::new(dx, dy)
}

/// Vertices heading east at `v0 = at(0, 0)`, `v1 = at(100, 100)`, `v2 = at(200, 0)`, at 30,
/// 40 and 50 m, with edges v0 → v1 (edge 0) and v1 → v2 (edge 1).
const VERTICES: [(f32, f32, f32); 3] = [(0.0, 0.0, 30.0), (100.0, 100.0, 40.0), (200.0, 0.0, 50.0)];

/// The roadmap of [`VERTICES`] with `obstacles` (each with its height), and the vertical
/// section that makes it three-dimensional.
fn spec(obstacles: &[(ObstacleSpec, f32)]) -> (NetworkSpec, VerticalSpec) {
    let vertices: Vec<Pose> = VERTICES
        .iter()
        .map(|&(x, y, _)| {
            let p = at(x, y);
            Pose::new(p.x, p.y, 0.0)
        })
        .collect();
    let edges = [(0u32, 1u32), (1, 2)]
        .iter()
        .map(|&(a, b)| {
            let path = DubinsPath::shortest(&vertices[a as usize], &vertices[b as usize], RADIUS)
                .expect("a Dubins path between distinct poses");
            EdgeSpec::dubins(a, b, &path)
        })
        .collect();
    let network = NetworkSpec {
        origin_lat_deg: 48.0,
        origin_lon_deg: 11.6,
        turn_radius_m: RADIUS,
        clearance_m: CLEARANCE,
        vertices,
        edges,
        obstacles: obstacles.iter().map(|(o, _)| o.clone()).collect(),
        grid_cell_m: 2.0 * RADIUS,
        terrain: None,
        landmark: None,
        voronoi: None,
        provenance: Vec::new(),
    };
    let vertical = VerticalSpec {
        limits: LIMITS,
        altitudes: VERTICES.iter().map(|&(_, _, z)| z).collect(),
        heights: obstacles.iter().map(|&(_, h)| h).collect(),
    };
    (network, vertical)
}

fn three_d(obstacles: &[(ObstacleSpec, f32)]) -> Vec<u8> {
    let (network, vertical) = spec(obstacles);
    encode_three_dimensional(&network, &vertical, None).expect("a valid 3-D network")
}

fn planar() -> Vec<u8> {
    encode(&spec(&[]).0).expect("a valid planar network")
}

/// An axis-aligned box `(x0, y0)`–`(x1, y1)` metres from [`ORIGIN`].
fn boxed(x0: f32, y0: f32, x1: f32, y1: f32) -> ObstacleSpec {
    ObstacleSpec::Polygon(vec![at(x0, y0), at(x1, y0), at(x1, y1), at(x0, y1)])
}

/// A path from `start` with the given word and lengths on [`RADIUS`].
fn path(start: Pose, word: DubinsWord, lengths: [f32; 3]) -> DubinsPath {
    DubinsPath {
        start,
        radius: RADIUS,
        word,
        lengths,
    }
}

/// The straight `length` metres east from `at(0, 0)`.
fn east(length: f32) -> DubinsPath {
    let p = at(0.0, 0.0);
    path(
        Pose::new(p.x, p.y, 0.0),
        DubinsWord::Lsl,
        [0.0, length, 0.0],
    )
}

fn set_route_altitudes(planner: &mut Small, altitudes: &[f32]) {
    let ModeState::Roadmap(state) = &mut planner.state else {
        panic!("a roadmap planner");
    };
    state.route_altitudes = heapless::Vec::from_slice(altitudes).unwrap();
}

/// The rest-to-rest altitude `s` metres along a path of `length` metres from `z0` to `z1`, in
/// f64 from the definitions (`geometry/vertical.rs`): accelerate at k = a_z/v² until the
/// gradient reaches g = v_c/v (or half the move is done), coast, brake; a climb as early as
/// it can, a descent as late. `None` when the move needs more than `length`.
fn reference_altitude(z0: f32, z1: f32, length: f64, s: f64) -> Option<f64> {
    let g = LIMITS.climb_rate as f64 / LIMITS.airspeed as f64;
    let k = LIMITS.vertical_accel as f64 / (LIMITS.airspeed as f64).powi(2);
    let d = (z1 as f64 - z0 as f64).abs();
    let (ease, ramp) = match d >= g * g / k {
        true => (g / k, d / g + g / k),
        false => ((d / k).sqrt(), 2.0 * (d / k).sqrt()),
    };
    if ramp > length {
        return None;
    }
    let s = s.clamp(0.0, length);
    let u = match z1 >= z0 {
        true => s,
        false => s - (length - ramp),
    }
    .clamp(0.0, ramp);
    let moved = if u <= ease {
        0.5 * k * u * u
    } else if u >= ramp - ease {
        d - 0.5 * k * (ramp - u).powi(2)
    } else {
        0.5 * k * ease * ease + k * ease * (u - ease)
    };
    Some(match z1 >= z0 {
        true => z0 as f64 + moved,
        false => z0 as f64 - moved,
    })
}

#[test]
fn only_a_three_dimensional_network_without_query_altitudes_is_refused() {
    let (solid, flat) = (three_d(&[]), planar());
    let mut planner = Small::new();
    planner.load(&flat).unwrap();
    assert_eq!(planner.check_query_altitudes(), Ok(()));
    planner.load(&solid).unwrap();
    assert_eq!(
        planner.check_query_altitudes(),
        Err(PlanError::AltitudesNeeded)
    );
    planner.set_query_altitudes(20.0, 60.0).unwrap();
    assert_eq!(planner.check_query_altitudes(), Ok(()));
}

/// An end is above a height when its altitude is at least the height plus the margin: the
/// start at 50 m is above 45 + 5 (equal) but not 45 + 10 (whose difference, 35, it is above).
#[test]
fn an_end_is_above_a_height_from_the_height_plus_the_margin_up() {
    let (solid, flat) = (three_d(&[]), planar());
    let mut planner = Small::new();
    planner.load(&solid).unwrap();
    assert!(
        !planner.end_is_above(LinkEnd::Start, 0.0, 0.0),
        "no altitudes"
    );
    planner.set_query_altitudes(50.0, 20.0).unwrap();
    assert!(planner.end_is_above(LinkEnd::Start, 45.0, 5.0));
    assert!(!planner.end_is_above(LinkEnd::Start, 45.0, 10.0));
    assert!(!planner.end_is_above(LinkEnd::Start, 45.0, 5.001));
    assert!(planner.end_is_above(LinkEnd::Goal, 15.0, 5.0));
    assert!(!planner.end_is_above(LinkEnd::Goal, 16.0, 5.0));
    assert!(!planner.end_is_above(LinkEnd::Start, f32::INFINITY, 5.0));
    planner.load(&flat).unwrap();
    assert!(!planner.end_is_above(LinkEnd::Start, 0.0, 0.0), "planar");
}

#[test]
fn a_link_flies_from_the_start_to_its_vertex_or_from_its_vertex_to_the_goal() {
    let (solid, flat) = (three_d(&[]), planar());
    let mut planner = Small::new();
    planner.load(&solid).unwrap();
    assert_eq!(
        planner.link_altitudes(LinkEnd::Start, 1),
        None,
        "no altitudes"
    );
    planner.set_query_altitudes(20.0, 60.0).unwrap();
    assert_eq!(
        planner.link_altitudes(LinkEnd::Start, 1),
        Some((20.0, 40.0))
    );
    assert_eq!(planner.link_altitudes(LinkEnd::Goal, 2), Some((50.0, 60.0)));
    let (from, to) = planner.link_altitudes(LinkEnd::Start, 3).unwrap();
    assert_eq!(from, 20.0);
    assert!(to.is_nan(), "a vertex past the network has no altitude");
    planner.load(&flat).unwrap();
    assert_eq!(planner.link_altitudes(LinkEnd::Goal, 1), None, "planar");
}

/// Junction 0 is the start; junction k the end of path k − 1; past the route, NaN.
#[test]
fn a_legs_altitudes_are_its_junctions_from_the_start_and_the_route() {
    let (solid, flat) = (three_d(&[]), planar());
    let mut planner = Small::new();
    planner.load(&solid).unwrap();
    planner.set_query_altitudes(20.0, 60.0).unwrap();
    set_route_altitudes(&mut planner, &[31.0, 42.0, 60.0]);
    assert_eq!(planner.junction_altitude(0), 20.0);
    assert_eq!(planner.junction_altitude(1), 31.0);
    assert_eq!(planner.junction_altitude(2), 42.0);
    assert_eq!(planner.junction_altitude(3), 60.0);
    assert!(planner.junction_altitude(4).is_nan());
    assert_eq!(planner.leg_altitudes(0, 2), Some((20.0, 42.0)));
    assert_eq!(planner.leg_altitudes(1, 3), Some((31.0, 60.0)));
    let (from, to) = planner.leg_altitudes(2, 5).unwrap();
    assert_eq!(from, 42.0);
    assert!(to.is_nan());
    planner.load(&flat).unwrap();
    assert_eq!(planner.leg_altitudes(0, 1), None, "planar");
}

/// Dropping junction k removes the end of path k − 1; junction 0 (the start) and junctions
/// past the route leave the altitudes as they are. Keeping a chain keeps its junctions after
/// the first; a route without altitudes keeps none.
#[test]
fn dropped_and_kept_junctions_edit_the_route_altitudes() {
    let solid = three_d(&[]);
    let mut planner = Small::new();
    planner.load(&solid).unwrap();
    planner.set_query_altitudes(20.0, 60.0).unwrap();
    let cases: [(usize, &[f32]); 5] = [
        (0, &[31.0, 42.0, 60.0]),
        (1, &[42.0, 60.0]),
        (2, &[31.0, 60.0]),
        (3, &[31.0, 42.0]),
        (4, &[31.0, 42.0, 60.0]),
    ];
    for (k, expected) in cases {
        set_route_altitudes(&mut planner, &[31.0, 42.0, 60.0]);
        planner.forget_junction_altitude(k);
        assert_eq!(planner.route_altitudes(), expected, "junction {k} dropped");
    }
    set_route_altitudes(&mut planner, &[31.0, 42.0, 55.0, 60.0]);
    planner.keep_junction_altitudes(&[0, 2, 4]);
    assert_eq!(planner.route_altitudes(), &[42.0, 60.0]);
    set_route_altitudes(&mut planner, &[31.0, 42.0, 55.0, 60.0]);
    planner.keep_junction_altitudes(&[0, 1, 3, 4]);
    assert_eq!(planner.route_altitudes(), &[31.0, 55.0, 60.0]);
    set_route_altitudes(&mut planner, &[]);
    planner.keep_junction_altitudes(&[0, 2]);
    assert!(
        planner.route_altitudes().is_empty(),
        "no altitudes, none kept"
    );
    set_route_altitudes(&mut planner, &[31.0, 60.0]);
    planner.forget_route_altitudes();
    assert!(planner.route_altitudes().is_empty());
}

/// From 20 to 40 m the move takes d/g + g/k = 50 + 12.5 = 62.5 m: a 60 m path cannot fly it,
/// a 63 m one can.
#[test]
fn a_path_is_clear_climbing_only_if_its_length_holds_the_move() {
    let solid = three_d(&[]);
    let mut planner = Small::new();
    planner.load(&solid).unwrap();
    let mut meter = Meter::new(u64::MAX);
    assert!(!planner.path_is_clear_climbing(&east(60.0), (20.0, 40.0), &mut meter));
    assert!(planner.path_is_clear_climbing(&east(63.0), (20.0, 40.0), &mut meter));
    assert!(planner.path_is_clear_climbing(&east(63.0), (40.0, 20.0), &mut meter));
    assert!(!planner.path_is_clear_climbing(&east(63.0), (f32::NAN, 20.0), &mut meter));
}

/// A box 3 m high under a level path blocks it up to 3 + 5 = 8 m (the height plus the
/// clearance): at 6 m it is blocked, at 10 m clear; a pop-up of the same height likewise;
/// an obstacle of unbounded height blocks it at any altitude.
#[test]
fn an_obstacle_or_popup_blocks_up_to_its_height_plus_the_clearance() {
    let under = boxed(40.0, -10.0, 60.0, 10.0);
    let low = three_d(&[(under.clone(), 3.0)]);
    let wall = three_d(&[(under, f32::INFINITY)]);
    let open = three_d(&[]);
    let level = |z: f32| (z, z);
    let mut planner = Small::new();
    let mut meter = Meter::new(u64::MAX);
    planner.load(&low).unwrap();
    assert!(!planner.path_is_clear_climbing(&east(100.0), level(6.0), &mut meter));
    assert!(planner.path_is_clear_climbing(&east(100.0), level(10.0), &mut meter));
    planner.load(&wall).unwrap();
    assert!(!planner.path_is_clear_climbing(&east(100.0), level(900.0), &mut meter));
    planner.load(&open).unwrap();
    let popup = Popup::Circle {
        centre: at(50.0, 0.0),
        radius: 10.0,
    };
    planner.add_popup_with_height(popup, 3.0).unwrap();
    assert!(!planner.path_is_clear_climbing(&east(100.0), level(6.0), &mut meter));
    assert!(planner.path_is_clear_climbing(&east(100.0), level(10.0), &mut meter));
}

/// An obstacle of a sampled case: a box (corners) or a disc, in absolute coordinates.
#[derive(Clone, Copy, Debug)]
enum Shape {
    Box(Vec2, Vec2),
    Disc(Vec2, f32),
}

impl Shape {
    fn distance(&self, p: Vec2) -> f64 {
        let (px, py) = (p.x as f64, p.y as f64);
        match *self {
            Shape::Box(lo, hi) => {
                let dx = (lo.x as f64 - px).max(px - hi.x as f64).max(0.0);
                let dy = (lo.y as f64 - py).max(py - hi.y as f64).max(0.0);
                dx.hypot(dy)
            }
            Shape::Disc(c, r) => ((px - c.x as f64).hypot(py - c.y as f64) - r as f64).max(0.0),
        }
    }

    fn spec(&self) -> ObstacleSpec {
        match *self {
            Shape::Box(lo, hi) => {
                ObstacleSpec::Polygon(vec![lo, Vec2::new(hi.x, lo.y), hi, Vec2::new(lo.x, hi.y)])
            }
            Shape::Disc(centre, radius) => ObstacleSpec::Circle { centre, radius },
        }
    }
}

/// The least, over points every 0.2 m along `path` flown from `z0` to `z1`, of how far the
/// point is outside the obstacle's clearance zone: the larger of its distance from the
/// footprint beyond the clearance and its altitude above `height` plus the clearance. Below
/// 0, the path conflicts; `None` when the climb is not flyable.
fn reference_margin(
    path: &DubinsPath,
    (z0, z1): (f32, f32),
    shape: &Shape,
    height: f32,
) -> Option<f64> {
    let length = path.length() as f64;
    let n = (length / 0.2).ceil().max(1.0) as usize;
    let mut least = f64::INFINITY;
    for i in 0..=n {
        let s = length * i as f64 / n as f64;
        let z = reference_altitude(z0, z1, length, s)?;
        let beside = shape.distance(path.sample(s as f32).position) - CLEARANCE as f64;
        let above = z - (height as f64 + CLEARANCE as f64);
        least = least.min(beside.max(above));
    }
    Some(least)
}

/// Sampled paths (two arcs and a straight, some of them zero, turning either way) flown
/// between two altitudes, each beside one box or disc whose height is near the altitude the
/// path flies it at: the path is clear exactly when the f64 reference finds no point within
/// the clearance of the footprint and below the height plus the clearance (cases within
/// 0.4 m of the boundary are left out, since the predicates' own margins decide them).
#[test]
fn a_climbing_path_is_clear_exactly_where_a_sampled_reference_finds_it_clear() {
    let mut rng = Rng(0x5eed_2026_1206);
    let words = [
        DubinsWord::Lsl,
        DubinsWord::Rsr,
        DubinsWord::Lsr,
        DubinsWord::Rsl,
    ];
    let (mut clear, mut blocked, mut unflyable) = (0, 0, 0);
    for case in 0..400 {
        let mut piece = |lo: f32, hi: f32| match rng.unit() < 0.25 {
            true => 0.0,
            false => rng.range(lo, hi),
        };
        let lengths = [piece(10.0, 80.0), piece(20.0, 150.0), piece(10.0, 80.0)];
        let start = at(rng.range(-150.0, 150.0), rng.range(-150.0, 150.0));
        let heading = rng.range(-3.1, 3.1);
        let word = words[(rng.unit() * 4.0) as usize % 4];
        let flown = path(Pose::new(start.x, start.y, heading), word, lengths);
        let length = flown.length();
        if length < 40.0 {
            continue;
        }
        let altitudes = (rng.range(20.0, 60.0), rng.range(20.0, 60.0));
        // The obstacle beside a point of the path, its height near the altitude there.
        let s = rng.range(0.0, length);
        let near = flown.sample(s);
        let normal = Vec2::new(-libm::sinf(near.heading), libm::cosf(near.heading));
        let centre = near.position + normal * rng.range(-25.0, 25.0);
        let shape = match rng.unit() < 0.5 {
            true => {
                let half = Vec2::new(rng.range(2.0, 10.0), rng.range(2.0, 10.0));
                Shape::Box(centre - half, centre + half)
            }
            false => Shape::Disc(centre, rng.range(2.0, 10.0)),
        };
        let z_there = reference_altitude(altitudes.0, altitudes.1, length as f64, s as f64);
        let height = match (rng.unit() < 0.1, z_there) {
            (true, _) | (_, None) => f32::INFINITY,
            (false, Some(z)) => (z as f32 - CLEARANCE + rng.range(-8.0, 8.0)).max(1.0),
        };
        let expected = reference_margin(&flown, altitudes, &shape, height);
        if expected.is_some_and(|m| m.abs() < 0.4) {
            continue;
        }
        let image = three_d(&[(shape.spec(), height)]);
        let mut planner = Small::new();
        planner.load(&image).unwrap();
        let mut meter = Meter::new(u64::MAX);
        let found = planner.path_is_clear_climbing(&flown, altitudes, &mut meter);
        let context = format!("case {case}: {flown:?} from {altitudes:?} beside {shape:?} of height {height}: reference {expected:?}");
        match expected {
            None => unflyable += 1,
            Some(m) if m > 0.0 => clear += 1,
            Some(_) => blocked += 1,
        }
        assert_eq!(found, expected.is_some_and(|m| m > 0.0), "{context}");
    }
    assert!(
        clear >= 60 && blocked >= 60 && unflyable >= 10,
        "{clear} clear, {blocked} blocked, {unflyable} unflyable"
    );
}

/// Work: one collision test per obstacle for each piece (its box tested first, here far
/// apart), one per pop-up the piece flies wholly above, and a polygon pop-up's edges plus its
/// containment test otherwise. Three pieces, two obstacles, a disc pop-up below the flight
/// and a 4-vertex wall: 3 × (2 + 1 + 5) = 24.
#[test]
fn each_piece_counts_a_test_per_obstacle_and_per_popup_element() {
    let image = three_d(&[
        (boxed(390.0, 390.0, 410.0, 410.0), 100.0),
        (boxed(-410.0, -410.0, -390.0, -390.0), f32::INFINITY),
    ]);
    let mut planner = Small::new();
    planner.load(&image).unwrap();
    let low_disc = Popup::Circle {
        centre: at(300.0, -300.0),
        radius: 20.0,
    };
    planner.add_popup_with_height(low_disc, 10.0).unwrap();
    let wall = Popup::Polygon(
        heapless::Vec::from_slice(&[
            at(-310.0, 290.0),
            at(-290.0, 290.0),
            at(-290.0, 310.0),
            at(-310.0, 310.0),
        ])
        .unwrap(),
    );
    planner.add_popup(wall).unwrap();
    let start = at(0.0, 0.0);
    let flown = path(
        Pose::new(start.x, start.y, 0.0),
        DubinsWord::Lsl,
        [40.0, 60.0, 40.0],
    );
    let mut meter = Meter::new(u64::MAX);
    assert!(planner.path_is_clear_climbing(&flown, (50.0, 50.0), &mut meter));
    assert_eq!(meter.work.collision_tests, 24);
    assert_eq!(meter.work.total(), 24);
}

/// The planner of [`walled`], planned from `at(-150, 0)` to `at(350, 0)` (both heading east)
/// with query altitudes 20 and 60 m.
fn planned<'n>(planner: &mut Small<'n>, image: &'n [u8]) {
    planner.load(image).unwrap();
    planner.set_query_altitudes(20.0, 60.0).unwrap();
    let (start, goal) = (at(-150.0, 0.0), at(350.0, 0.0));
    let query = Query {
        start: Pose::new(start.x, start.y, 0.0),
        goal: Goal {
            position: goal,
            heading: Some(0.0),
        },
        search: Search::Dijkstra,
    };
    planner
        .plan(&query, u64::MAX)
        .expect("a route round the wall");
}

/// [`three_d`] with two walls of unbounded height: one across the straight line from the
/// start to the goal, one across the start's straight line to v1; so the route goes through
/// the network and along an edge of it.
fn walled() -> Vec<u8> {
    three_d(&[
        (boxed(80.0, -20.0, 120.0, 20.0), f32::INFINITY),
        (boxed(-60.0, 10.0, -40.0, 60.0), f32::INFINITY),
    ])
}

/// The altitude of the vertex at `p`.
fn vertex_altitude_at(p: Vec2) -> Option<f32> {
    VERTICES
        .iter()
        .find(|&&(x, y, _)| at(x, y).distance(p) < 1e-3)
        .map(|&(_, _, z)| z)
}

/// The arrival the last plan wrote its route by: the goal link whose path is the route's last.
fn arrival(planner: &Small) -> Arrival {
    let last = *planner.route_paths().last().unwrap();
    let link = planner
        .goal_links
        .iter()
        .position(|l| l.path == last)
        .expect("the route ends on a goal link");
    Arrival::FromState {
        state: planner.goal_links[link].vertex,
        link,
    }
}

/// A route's altitudes are those of the vertices its paths end at, then the goal's; the
/// altitude along primitive k is the f64 profile of its path at the primitive's offset into
/// the path plus `s` (clamped to the primitive).
#[test]
fn a_routes_altitudes_are_its_vertices_then_the_goal_along_each_paths_profile() {
    let image = walled();
    let mut planner = Small::new();
    planned(&mut planner, &image);
    let paths = planner.route_paths();
    assert!(paths.len() >= 3, "through the network: {paths:?}");
    let altitudes = planner.route_altitudes();
    assert_eq!(altitudes.len(), paths.len());
    for (k, path) in paths[..paths.len() - 1].iter().enumerate() {
        let z = vertex_altitude_at(path.end().position).expect("a path ends at a vertex");
        assert_eq!(altitudes[k], z, "path {k}");
    }
    assert_eq!(*altitudes.last().unwrap(), 60.0);
    let mut k = 0;
    for (p, path) in paths.iter().enumerate() {
        let from = if p == 0 { 20.0 } else { altitudes[p - 1] };
        let mut offset = 0.0;
        for (prim, length) in path.primitives().iter().zip(path.lengths) {
            if prim.is_some() {
                for s in [-1.0, 0.0, 0.3 * length, length, length + 5.0] {
                    let along = offset + s.clamp(0.0, length) as f64;
                    let expected =
                        reference_altitude(from, altitudes[p], path.length() as f64, along)
                            .unwrap();
                    let found = planner.route_altitude_at(k, s).unwrap();
                    assert!(
                        (found as f64 - expected).abs() < 1e-3,
                        "primitive {k} (path {p}) at {s}: {found} m, expected {expected}"
                    );
                }
                k += 1;
            }
            offset += length as f64;
        }
    }
    assert_eq!(planner.route_altitude_at(k, 0.0), None, "past the route");
}

/// The charge walks back from the goal link's vertex to the start link, one vertex scan per
/// vertex on the route (its paths less one: the start link and the edges end at one each),
/// and is refused one scan short; the filling it pays for gives the route's altitudes again,
/// and refuses (clearing them) a route whose path count does not match, here with an exit the
/// route does not have.
#[test]
fn the_route_altitudes_walk_is_charged_one_scan_per_vertex_and_replayed_exactly() {
    let image = walled();
    let mut planner = Small::new();
    planned(&mut planner, &image);
    let kept: Vec<f32> = planner.route_altitudes().to_vec();
    let arrival = arrival(&planner);
    let vertices = planner.route_paths().len() as u64 - 1;
    let mut meter = Meter::new(vertices);
    assert_eq!(planner.charge_route_altitudes(&arrival, &mut meter), Ok(()));
    assert_eq!(meter.work.vertex_scans, vertices);
    assert_eq!(meter.work.total(), vertices);
    let mut short = Meter::new(vertices - 1);
    assert!(matches!(
        planner.charge_route_altitudes(&arrival, &mut short),
        Err(PlanError::BudgetExhausted { .. })
    ));
    let direct = Arrival::Direct(planner.route_paths()[0]);
    let mut none = Meter::new(0);
    assert_eq!(planner.charge_route_altitudes(&direct, &mut none), Ok(()));

    set_route_altitudes(&mut planner, &[1.0]);
    assert_eq!(planner.fill_route_altitudes(&arrival, false), Ok(()));
    assert_eq!(planner.route_altitudes(), kept.as_slice());
    assert_eq!(
        planner.fill_route_altitudes(&arrival, true),
        Err(PlanError::Internal)
    );
    assert!(planner.route_altitudes().is_empty());
}

/// With room for two altitudes, a route of two paths whose walk gives three (goal, one
/// vertex, the start link's vertex; or goal, start link's vertex, the exit's start) is
/// refused as inconsistent, not cut to fit.
#[test]
fn route_altitudes_beyond_the_capacity_are_refused_not_cut() {
    let image = three_d(&[]);
    let mut planner: Planner<'_, 64, 512, 4, 2> = Planner::new();
    planner.load(&image).unwrap();
    planner.set_query_altitudes(20.0, 60.0).unwrap();
    let some_path = planner.network.edge_path(0).unwrap();
    let link = |vertex| Link {
        vertex,
        path: some_path,
        cost: 0.0,
        pending: false,
    };
    for _ in 0..2 {
        planner.paths.push(some_path).unwrap();
    }
    planner.goal_links.push(link(1)).unwrap();
    let arrival = Arrival::FromState { state: 1, link: 0 };

    // Goal, then v1 (edge 0's end), then the start link's v0: three.
    planner.start_links.push(link(0)).unwrap();
    planner.via[1] = 0;
    planner.via[0] = FROM_START;
    assert_eq!(
        planner.fill_route_altitudes(&arrival, false),
        Err(PlanError::Internal)
    );
    assert!(planner.route_altitudes().is_empty());

    // Goal, then the start link's v1, then the exit's start: three.
    planner.start_links[0] = link(1);
    planner.via[1] = FROM_START;
    assert_eq!(
        planner.fill_route_altitudes(&arrival, true),
        Err(PlanError::Internal)
    );
    assert!(planner.route_altitudes().is_empty());
    // Without the exit, two: goal and v1.
    assert_eq!(planner.fill_route_altitudes(&arrival, false), Ok(()));
    assert_eq!(planner.route_altitudes(), &[40.0, 60.0]);
}
