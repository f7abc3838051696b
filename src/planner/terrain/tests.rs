//! Terrain mode's altitude setting, bound inputs, query preparation and grid checks, each
//! against values worked out from the definitions: the bound's degree sums counted from the
//! edge list, and every band check against a sampled f64 reference of which blocked cells lie
//! within the widening of the primitive.
//!
//! The grid lies at negative coordinates, so that a bound that multiplies or divides a
//! coordinate instead of adding the widening to it errs.

extern crate std;
use super::fillet::Fillet;
use super::states::Arrived;
use crate::geometry::grid::{arc_cells, primitive_cells, CellGrid};
use crate::geometry::{Arc, Pose, Primitive, Segment, Vec2};
use crate::network::elevation::ElevationCoding;
use crate::network::write::{encode, EdgeSpec, NetworkSpec, TerrainSpec};
use crate::planner::state::ArcCheckStats;
use crate::planner::work::cells_bound;
use crate::planner::{Goal, Meter, PlanError, Planner, Popup, Query, QueryField, Search};
use crate::test_rng::Rng;
use core::f32::consts::{PI, TAU};
use std::vec;
use std::vec::Vec;

pub(super) type Small<'n> = Planner<'n, 256, 256, 4, 64>;

pub(super) const ORIGIN: Vec2 = Vec2::new(-3000.0, -2000.0);
/// 40 × 30 cells of 10 m.
pub(super) const CELL: f32 = 10.0;
pub(super) const COLS: u32 = 40;
pub(super) const ROWS: u32 = 30;
pub(super) const WIDEN: f32 = 7.0;
/// With elevation code c bounding c metres, at 100 m with no safety height code 100 blocks.
pub(super) const ALTITUDE: f32 = 100.0;
pub(super) const BLOCKING: u8 = 100;
/// Free cells are one code below the blocking one, so that a comparison off by one errs.
pub(super) const FREE: u8 = BLOCKING - 1;

/// A point `(dx, dy)` metres from [`ORIGIN`].
pub(super) fn at(dx: f32, dy: f32) -> Vec2 {
    ORIGIN + Vec2::new(dx, dy)
}

pub(super) fn grid() -> CellGrid {
    CellGrid::new(ORIGIN, CELL, COLS, ROWS)
}

/// Codes with the cells whose squares lie within `[x0, x1] × [y0, y1]` (from [`ORIGIN`])
/// blocked.
pub(super) fn codes_with_block(x0: f32, y0: f32, x1: f32, y1: f32) -> Vec<u8> {
    let g = grid();
    let mut codes = vec![FREE; (COLS * ROWS) as usize];
    for r in 0..ROWS {
        for c in 0..COLS {
            let (lo, hi) = g.cell_rect(c, r);
            if lo.x >= at(x0, 0.0).x
                && hi.x <= at(x1, 0.0).x
                && lo.y >= at(0.0, y0).y
                && hi.y <= at(0.0, y1).y
            {
                codes[(r * COLS + c) as usize] = BLOCKING;
            }
        }
    }
    codes
}

/// Nodes `n0 = at(50, 150)`, `n1 = at(200, 250)`, `n2 = at(350, 150)`, joined both ways
/// (edges n0 → n1, n1 → n0, n1 → n2, n2 → n1).
pub(super) const NODES: [(f32, f32); 3] = [(50.0, 150.0), (200.0, 250.0), (350.0, 150.0)];
pub(super) const EDGES: [(u32, u32); 4] = [(0, 1), (1, 0), (1, 2), (2, 1)];

/// The terrain network of [`NODES`] and [`EDGES`] over `codes`, with turn radius `radius`.
pub(super) fn network(codes: Vec<u8>, radius: f32) -> Vec<u8> {
    let nodes: Vec<Vec2> = NODES.iter().map(|&(x, y)| at(x, y)).collect();
    let spec = NetworkSpec {
        origin_lat_deg: 36.5,
        origin_lon_deg: -84.2,
        turn_radius_m: radius,
        clearance_m: 0.0,
        vertices: nodes.iter().map(|&p| Pose::new(p.x, p.y, 0.0)).collect(),
        edges: EDGES
            .iter()
            .map(|&(a, b)| EdgeSpec::line(a, b, nodes[a as usize].distance(nodes[b as usize])))
            .collect(),
        obstacles: Vec::new(),
        grid_cell_m: 100.0,
        terrain: Some(TerrainSpec {
            grid: grid(),
            coding: ElevationCoding {
                base_m: 0.0,
                step_m: 1.0,
            },
            codes,
            widen_m: WIDEN,
            altitude_m: ALTITUDE,
            safety_height_m: 0.0,
        }),
        landmark: None,
        voronoi: None,
        provenance: Vec::new(),
    };
    encode(&spec).expect("a valid terrain network")
}

/// A roadmap (not terrain) network of one vertex.
fn roadmap() -> Vec<u8> {
    let spec = NetworkSpec {
        origin_lat_deg: 36.5,
        origin_lon_deg: -84.2,
        turn_radius_m: 30.0,
        clearance_m: 0.0,
        vertices: vec![Pose::new(0.0, 0.0, 0.0)],
        edges: Vec::new(),
        obstacles: Vec::new(),
        grid_cell_m: 100.0,
        terrain: None,
        landmark: None,
        voronoi: None,
        provenance: Vec::new(),
    };
    encode(&spec).expect("a valid roadmap")
}

/// The altitude is set only to finite values with a safety height of at least 0; each setting
/// blocks from the smallest code reaching the altitude less the safety height.
#[test]
fn an_altitude_is_set_only_when_finite_with_a_non_negative_safety_height() {
    let image = network(vec![FREE; (COLS * ROWS) as usize], 30.0);
    let mut planner = Small::new();
    planner.load(&image).unwrap();
    assert_eq!(planner.altitude(), Some((ALTITUDE, 0.0)), "as built");
    assert_eq!(planner.blocking_code(), BLOCKING);
    assert_eq!(planner.set_altitude(120.0, 15.0), Ok(()));
    assert_eq!(planner.altitude(), Some((120.0, 15.0)));
    assert_eq!(planner.blocking_code(), 105);
    for (altitude, safety) in [
        (f32::NAN, 0.0),
        (120.0, f32::NAN),
        (f32::INFINITY, 0.0),
        (120.0, f32::INFINITY),
        (120.0, -1.0),
        (f32::NAN, -1.0),
    ] {
        assert_eq!(
            planner.set_altitude(altitude, safety),
            Err(PlanError::InvalidAltitude),
            "{altitude} m with {safety} m"
        );
        assert_eq!(planner.altitude(), Some((120.0, 15.0)), "kept");
        assert_eq!(planner.blocking_code(), 105);
    }
    assert_eq!(planner.set_altitude(80.0, 0.0), Ok(()));
    assert_eq!(planner.blocking_code(), 80);

    let other = roadmap();
    planner.load(&other).unwrap();
    assert_eq!(
        planner.set_altitude(120.0, 0.0),
        Err(PlanError::NotTerrainNetwork)
    );
    assert_eq!(planner.altitude(), None);
    assert_eq!(planner.blocking_code(), 0);
    assert_eq!(planner.arc_check_stats(), ArcCheckStats::default());
}

/// The bound's inputs: the degree sums counted here from the edge list, and the cells of a
/// half turn and of the longer of the grid's diagonal and a full turn, in cells, widened by
/// `widen / cell`. With radius 30 m the diagonal (50 cells) is the longer; with 100 m the full
/// turn (62.8 cells).
#[test]
fn the_bound_inputs_count_transitions_and_cells_from_the_definitions() {
    let out = |v: u32| EDGES.iter().filter(|&&(a, _)| a == v).count() as u64;
    let transitions: u64 = EDGES.iter().map(|&(_, b)| out(b)).sum();
    let pairs: u64 = EDGES
        .iter()
        .map(|&(_, b)| {
            EDGES
                .iter()
                .filter(|&&(a, _)| a == b)
                .map(|&(_, c)| out(c))
                .sum::<u64>()
        })
        .sum();
    assert_eq!((transitions, pairs), (6, 8), "worked by hand");
    let diagonal = ((COLS * COLS + ROWS * ROWS) as f32).sqrt();
    assert_eq!(diagonal, 50.0);
    for radius in [30.0f32, 100.0] {
        let image = network(vec![FREE; (COLS * ROWS) as usize], radius);
        let mut planner = Small::new();
        planner.load(&image).unwrap();
        let inputs = planner.terrain_bound_inputs();
        assert_eq!((inputs.vertices, inputs.edges), (3, 4));
        assert_eq!(inputs.transitions, transitions);
        assert_eq!(inputs.pair_relaxations, pairs);
        assert_eq!(inputs.max_out_degree, 2);
        let widen = 0.7;
        let half_turn = PI * radius / CELL;
        let full_turn = TAU * radius / CELL;
        assert_eq!(
            inputs.cells_per_turn,
            cells_bound(half_turn, widen),
            "r {radius}"
        );
        assert_eq!(
            inputs.cells_per_connection,
            cells_bound(diagonal.max(full_turn), widen),
            "r {radius}"
        );
        assert!(inputs.cells_per_turn > 0);
    }
    let cells = |radius: f32| {
        let image = network(vec![FREE; (COLS * ROWS) as usize], radius);
        let mut planner = Small::new();
        planner.load(&image).unwrap();
        planner.terrain_bound_inputs().cells_per_connection
    };
    assert!(cells(100.0) > cells(30.0), "the full turn counts at 100 m");
}

pub(super) fn query(start: Vec2, goal: Vec2) -> Query {
    Query {
        start: Pose::new(start.x, start.y, 0.0),
        goal: Goal {
            position: goal,
            heading: None,
        },
        search: Search::Dijkstra,
    }
}

/// Over free terrain the direct path wins: the straight 240 m east from the start to the goal.
#[test]
fn over_free_terrain_the_direct_straight_is_the_route() {
    let image = network(vec![FREE; (COLS * ROWS) as usize], 30.0);
    let mut planner = Small::new();
    planner.load(&image).unwrap();
    let summary = planner
        .plan(&query(at(60.0, 150.0), at(300.0, 150.0)), u64::MAX)
        .unwrap();
    assert!((summary.length - 240.0).abs() < 1e-3, "{summary:?}");
    // The turn before the straight rounds to an arc of about 10⁻⁷ rad, or to none.
    let route = planner.route();
    let flown: f32 = route.iter().map(|p| p.length()).sum();
    assert!((flown - 240.0).abs() < 1e-3, "{route:?}");
    assert!(route[0].start().distance(at(60.0, 150.0)) < 1e-3);
    assert!(route[route.len() - 1].end().distance(at(300.0, 150.0)) < 1e-3);
}

/// A wall of blocked cells across the direct line: the route goes through the network, over
/// free cells only, and is longer than the direct line; start and goal over the wall, at the
/// blocking code exactly, are refused by name.
#[test]
fn a_wall_across_the_direct_line_sends_the_route_through_the_network() {
    let codes = codes_with_block(190.0, 100.0, 210.0, 200.0);
    let code_at = |p: Vec2| {
        let (c, r) = grid().cell_of(p).unwrap();
        codes[(r * COLS + c) as usize]
    };
    let image = network(codes.clone(), 30.0);
    let mut planner = Small::new();
    planner.load(&image).unwrap();
    let (start, goal) = (at(20.0, 150.0), at(380.0, 150.0));
    let summary = planner.plan(&query(start, goal), u64::MAX).unwrap();
    assert!(summary.length > 360.0 + 1.0, "{summary:?}");
    let route = planner.route();
    assert!(route.first().unwrap().start().distance(start) < 1e-3);
    assert!(route.last().unwrap().end().distance(goal) < 1e-3);
    for prim in route {
        let n = (prim.length() / 0.5).ceil() as usize;
        for i in 0..=n {
            let p = prim.pose_at(prim.length() * i as f32 / n as f32).position;
            assert_eq!(code_at(p), FREE, "{p:?} on {prim:?}");
        }
    }
    let on_wall = at(200.0, 150.0);
    assert_eq!(code_at(on_wall), BLOCKING);
    assert_eq!(
        planner.plan(&query(on_wall, goal), u64::MAX),
        Err(PlanError::OverBlockedTerrain {
            field: QueryField::Start
        })
    );
    assert_eq!(
        planner.plan(&query(start, on_wall), u64::MAX),
        Err(PlanError::OverBlockedTerrain {
            field: QueryField::Goal
        })
    );
}

/// A point is over free terrain below the blocking code, and not at it or outside the grid;
/// each check counts one cell.
#[test]
fn a_point_is_over_free_terrain_only_below_the_blocking_code() {
    let codes = codes_with_block(190.0, 100.0, 210.0, 200.0);
    let image = network(codes, 30.0);
    let mut planner = Small::new();
    planner.load(&image).unwrap();
    for (p, free) in [
        (at(100.0, 50.0), true),
        (at(200.0, 150.0), false),
        (at(-5.0, 50.0), false),
        (at(100.0, 305.0), false),
    ] {
        let mut meter = Meter::new(u64::MAX);
        let result = planner.check_over_terrain(p, QueryField::Goal, &mut meter);
        let expected = match free {
            true => Ok(()),
            false => Err(PlanError::OverBlockedTerrain {
                field: QueryField::Goal,
            }),
        };
        assert_eq!(result, expected, "{p:?}");
        assert_eq!(meter.work.cells_visited, 1);
        assert_eq!(meter.work.total(), 1);
    }
}

/// Codes with about one cell in 40 blocked at random.
fn scattered_codes(rng: &mut Rng) -> Vec<u8> {
    (0..COLS * ROWS)
        .map(|_| match rng.unit() < 0.025 {
            true => BLOCKING,
            false => FREE,
        })
        .collect()
}

/// What a sampled f64 reference says of `prim` over `codes`: `Some(true)` when its band (the
/// points within [`WIDEN`] of it) lies inside the grid and every blocked cell is more than
/// [`WIDEN`] + 0.1 m from it, `Some(false)` when the band leaves the grid by more than 0.1 m
/// or a blocked cell is within [`WIDEN`] − 0.1 m, `None` in between (the checks' rounding
/// margins decide those). Points every 0.02 m along the primitive.
pub(super) fn reference_clear(prim: &Primitive, codes: &[u8]) -> Option<bool> {
    let g = grid();
    let (sw, _) = g.cell_rect(0, 0);
    let (_, ne) = g.cell_rect(COLS - 1, ROWS - 1);
    let length = prim.length() as f64;
    let n = (length / 0.02).ceil().max(1.0) as usize;
    let points: Vec<(f64, f64)> = (0..=n)
        .map(|i| {
            let p = prim.pose_at((length * i as f64 / n as f64) as f32).position;
            (p.x as f64, p.y as f64)
        })
        .collect();
    let w = WIDEN as f64;
    // How far the band stays inside the grid (negative: it leaves it).
    let inside = points
        .iter()
        .map(|&(x, y)| {
            (x - sw.x as f64)
                .min(ne.x as f64 - x)
                .min(y - sw.y as f64)
                .min(ne.y as f64 - y)
                - w
        })
        .fold(f64::INFINITY, f64::min);
    if inside < -0.1 {
        return Some(false);
    }
    let mut nearest_blocked = f64::INFINITY;
    for r in 0..ROWS {
        for c in 0..COLS {
            if codes[(r * COLS + c) as usize] < BLOCKING {
                continue;
            }
            let (lo, hi) = g.cell_rect(c, r);
            for &(x, y) in &points {
                let dx = (lo.x as f64 - x).max(x - hi.x as f64).max(0.0);
                let dy = (lo.y as f64 - y).max(y - hi.y as f64).max(0.0);
                nearest_blocked = nearest_blocked.min(dx.hypot(dy));
            }
        }
    }
    if nearest_blocked < w - 0.1 {
        Some(false)
    } else if nearest_blocked > w + 0.1 && inside > 0.1 {
        Some(true)
    } else {
        None
    }
}

/// A sampled primitive over the grid: a line of 10–150 m or an arc of radius 20–80 m turning
/// 0.2–3 rad either way, from anywhere within 30 m of the grid (so some bands leave it).
fn sampled_primitive(rng: &mut Rng) -> Primitive {
    let p = at(rng.range(-30.0, 430.0), rng.range(-30.0, 330.0));
    let heading = rng.range(-PI, PI);
    match rng.unit() < 0.5 {
        true => {
            let length = rng.range(10.0, 150.0);
            let d = Vec2::new(libm::cosf(heading), libm::sinf(heading));
            Primitive::Line(Segment::new(p, p + d * length))
        }
        false => {
            let sign = if rng.unit() < 0.5 { 1.0 } else { -1.0 };
            Primitive::Arc(Arc {
                centre: p,
                radius: rng.range(20.0, 80.0),
                start_angle: heading,
                sweep: sign * rng.range(0.2, 3.0),
            })
        }
    }
}

/// Sampled lines and arcs over scattered blocked cells: each is over free terrain exactly
/// where the reference finds its band inside the grid and clear of every blocked cell; a
/// clear one counts the cells the traversal visits.
#[test]
fn a_primitive_is_over_free_terrain_exactly_where_a_sampled_reference_finds_it() {
    let mut rng = Rng(0x7e44_a1b2_2026_1206);
    let (mut clear, mut blocked, mut outside) = (0, 0, 0);
    for round in 0..6 {
        let codes = scattered_codes(&mut rng);
        let image = network(codes.clone(), 30.0);
        let mut planner = Small::new();
        planner.load(&image).unwrap();
        for case in 0..60 {
            let prim = sampled_primitive(&mut rng);
            let Some(expected) = reference_clear(&prim, &codes) else {
                continue;
            };
            let mut meter = Meter::new(u64::MAX);
            let found = planner.primitive_over_free_terrain(&prim, &mut meter);
            assert_eq!(found, expected, "round {round} case {case}: {prim:?}");
            let mut arc_meter = Meter::new(u64::MAX);
            if let Primitive::Arc(arc) = prim {
                let on_arc = planner.arc_over_free_terrain(&grid(), WIDEN, &arc, &mut arc_meter);
                assert_eq!(on_arc, expected, "round {round} case {case}: {arc:?}");
            }
            let (lo, hi) = prim.bounding_box();
            let w = Vec2::new(WIDEN, WIDEN);
            match (expected, grid().covers(lo - w, hi + w)) {
                (true, _) => {
                    clear += 1;
                    let cells = primitive_cells(&grid(), &prim, WIDEN, |_, _| true).unwrap();
                    assert_eq!(meter.work.cells_visited, cells, "{prim:?}");
                    assert_eq!(meter.work.total(), cells);
                    if let Primitive::Arc(_) = prim {
                        assert_eq!(arc_meter.work.cells_visited, cells, "{prim:?}");
                    }
                }
                (false, true) => blocked += 1,
                (false, false) => outside += 1,
            }
        }
    }
    assert!(
        clear >= 40 && blocked >= 40 && outside >= 20,
        "{clear} clear, {blocked} blocked, {outside} outside"
    );
}

/// Arrived at n1 = `at(200, 250)` heading along `direction`, on edge 0.
fn arrived_at_n1(direction: Vec2) -> Arrived {
    Arrived {
        straight: 0,
        node: 1,
        position: at(200.0, 250.0),
        direction,
        length: 180.0,
        start_share: 0.0,
        key_point: 0.0,
        from: Some(0),
    }
}

fn stats(planner: &Small) -> ArcCheckStats {
    planner.arc_check_stats()
}

/// Two turns at n1 over free terrain (a left quarter turn and a right turn of 0.5 rad): each
/// is clear, adds its arc's cells (as the traversal counts them) to the meter, whatever it held
/// before, and to the statistics; a straight pass has no arc and counts nothing. Over a block
/// of high cells under the arc the turn is refused and still counted.
#[test]
fn a_turn_arc_over_terrain_is_checked_and_counted_in_the_statistics() {
    let image = network(vec![FREE; (COLS * ROWS) as usize], 30.0);
    let mut planner = Small::new();
    planner.load(&image).unwrap();
    let east = Vec2::new(1.0, 0.0);
    let turns = [
        Vec2::new(0.0, 1.0),
        Vec2::new(libm::cosf(-0.5), libm::sinf(-0.5)),
    ];
    let mut meter = Meter::new(u64::MAX);
    meter.work.cells_visited = 1000;
    let mut expected = ArcCheckStats::default();
    let mut visited = 1000;
    for u_out in turns {
        let at = arrived_at_n1(east);
        let fillet = Fillet::new(east, u_out, 30.0);
        let arc = fillet.arc(at.position, at.direction, 30.0).unwrap();
        let cells = arc_cells(&grid(), &arc, WIDEN, |_, _| true).unwrap();
        assert!(planner.fillet_is_clear(&at, &fillet, &mut meter));
        visited += cells;
        expected.arcs += 1;
        expected.cells += cells;
        expected.most_cells = expected.most_cells.max(cells);
        assert_eq!(meter.work.cells_visited, visited);
        assert_eq!(stats(&planner), expected);
    }
    assert_ne!(
        expected.cells,
        2 * expected.most_cells,
        "the two arcs differ"
    );
    let straight = Fillet::new(east, east, 30.0);
    assert!(planner.fillet_is_clear(&arrived_at_n1(east), &straight, &mut meter));
    assert_eq!(stats(&planner), expected, "a straight pass has no arc");
    assert_eq!(meter.work.cells_visited, visited);
    assert_eq!(meter.work.collision_tests, 0);

    // High cells under the quarter turn's arc (centre n1 + (−30, 30)).
    let walled = network(codes_with_block(170.0, 250.0, 200.0, 280.0), 30.0);
    planner.load(&walled).unwrap();
    let fillet = Fillet::new(east, turns[0], 30.0);
    let mut meter = Meter::new(u64::MAX);
    assert!(!planner.fillet_is_clear(&arrived_at_n1(east), &fillet, &mut meter));
    assert_eq!(stats(&planner).arcs, 1);
    assert_eq!(meter.work.collision_tests, 0, "no pop-up to test");
}

/// Over free terrain, a pop-up far from the arc costs one test and leaves it clear; one on the
/// arc's midpoint (n1 + (−8.8, 8.8) on the quarter turn) blocks it, after a test of each.
#[test]
fn a_turn_arc_must_also_clear_the_popups() {
    let image = network(vec![FREE; (COLS * ROWS) as usize], 30.0);
    let mut planner = Small::new();
    planner.load(&image).unwrap();
    let east = Vec2::new(1.0, 0.0);
    let fillet = Fillet::new(east, Vec2::new(0.0, 1.0), 30.0);
    let far = Popup::Circle {
        centre: at(50.0, 50.0),
        radius: 10.0,
    };
    planner.add_popup(far).unwrap();
    let mut meter = Meter::new(u64::MAX);
    assert!(planner.fillet_is_clear(&arrived_at_n1(east), &fillet, &mut meter));
    assert_eq!(meter.work.collision_tests, 1);
    let middle =
        at(200.0, 250.0) + Vec2::new(-30.0, 30.0) + Vec2::new(30.0, -30.0) * (0.5f32).sqrt();
    let on_arc = Popup::Circle {
        centre: middle,
        radius: 3.0,
    };
    planner.add_popup(on_arc).unwrap();
    let mut meter = Meter::new(u64::MAX);
    assert!(!planner.fillet_is_clear(&arrived_at_n1(east), &fillet, &mut meter));
    assert_eq!(meter.work.collision_tests, 2, "{:?}", meter.work);
}

/// The loaded elevation table: every cell's code as written, `ELEVATION_BLOCKED` past the last
/// column or row (either alone) and on a roadmap; each edge's highest code, as the writer
/// stores it, at least the highest code of the cells within [`WIDEN`] − 0.1 m of its segment
/// and at most that of those within [`WIDEN`] + 0.1 m (f64), and `None` on a roadmap.
#[test]
fn the_elevation_table_and_each_edges_highest_code_read_back() {
    use crate::network::elevation::ELEVATION_BLOCKED;
    use crate::network::write::tests::segment_box_distance;
    let mut rng = Rng(0xe1e7_a7e5_2026_1206);
    let codes: Vec<u8> = (0..COLS * ROWS)
        .map(|_| (rng.unit() * 250.0) as u8)
        .collect();
    let bytes = network(codes.clone(), 30.0);
    let net = crate::network::Network::from_bytes(&bytes).unwrap();
    for r in 0..ROWS {
        for c in 0..COLS {
            assert_eq!(net.elevation_code(c, r), codes[(r * COLS + c) as usize]);
        }
    }
    for (c, r) in [(COLS, 0), (0, ROWS), (COLS, ROWS - 1), (u32::MAX, 0)] {
        assert_eq!(net.elevation_code(c, r), ELEVATION_BLOCKED, "({c}, {r})");
    }
    let g = grid();
    let f = |p: Vec2| [p.x as f64, p.y as f64];
    for e in 0..net.edge_count() {
        let edge = net.edge(e).unwrap();
        let (a, b) = (
            net.vertex(edge.source).unwrap(),
            net.vertex(edge.target).unwrap(),
        );
        let (mut least, mut most) = (0u8, 0u8);
        for r in 0..ROWS {
            for c in 0..COLS {
                let (lo, hi) = g.cell_rect(c, r);
                let d = segment_box_distance(f(a.position), f(b.position), f(lo), f(hi));
                let code = codes[(r * COLS + c) as usize];
                if d < WIDEN as f64 - 0.1 {
                    least = least.max(code);
                }
                if d < WIDEN as f64 + 0.1 {
                    most = most.max(code);
                }
            }
        }
        let got = net.edge_highest_code(e).unwrap();
        assert!(
            least <= got && got <= most,
            "edge {e}: {got} in [{least}, {most}]"
        );
        assert!(least > 200, "edge {e}: the band holds a high code");
    }
    let road = roadmap();
    let road = crate::network::Network::from_bytes(&road).unwrap();
    assert_eq!(road.elevation_code(0, 0), ELEVATION_BLOCKED);
    assert_eq!(road.edge_highest_code(0), None);
}
