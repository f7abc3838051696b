//! The corner hull test of Voronoi mode's smoothing (`triangle_is_clear`) on a small Voronoi
//! network built here: which zones refuse a hull triangle, and the work it counts.

use crate::geometry::spline::table::build_corner_table;
use crate::geometry::voronoi::{Bounds, Delaunay, VoronoiGraph};
use crate::geometry::{Pose, Vec2};
use crate::network::write::{encode, EdgeSpec, NetworkSpec, ObstacleSpec, VoronoiSpec};
use crate::planner::{
    Meter, Planner, Popup, VoronoiStorage, MAX_THREATS, VORONOI_GRAPH_EDGES, VORONOI_GRAPH_VERTICES,
};
use std::boxed::Box;
use std::vec::Vec;

type TestPlanner<'n> = Planner<'n, 1024, 1024, 4, 256>;

/// The axis-aligned square of side `2·half` around `centre`, counter-clockwise.
fn square(centre: Vec2, half: f32) -> Vec<Vec2> {
    [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
        .iter()
        .map(|(x, y)| centre + Vec2::new(x * half, y * half))
        .collect()
}

/// A Voronoi network of three threat sites in a 10 km box around the origin, with the two
/// no-fly squares `obstacles`: its vertices and edges are the sites' diagram, as the loader
/// checks.
fn network(obstacles: &[Vec<Vec2>]) -> Vec<u8> {
    let sites = [
        Vec2::new(-3000.0, -2000.0),
        Vec2::new(3000.0, -2500.0),
        Vec2::new(0.0, 3500.0),
    ];
    let bounds = Bounds {
        min: Vec2::new(-5000.0, -5000.0),
        max: Vec2::new(5000.0, 5000.0),
    };
    let mut diagram: Box<Delaunay<MAX_THREATS, { 2 * MAX_THREATS }>> = Box::default();
    for s in sites {
        diagram.insert(s).unwrap();
    }
    let mut graph: Box<VoronoiGraph<VORONOI_GRAPH_VERTICES, VORONOI_GRAPH_EDGES>> =
        Box::new(VoronoiGraph::new());
    diagram.graph(&bounds, &mut graph).unwrap();
    let vertices = graph.vertices();
    let mut edges = Vec::new();
    for e in graph.edges() {
        let (a, b) = (u32::from(e.a), u32::from(e.b));
        let length = vertices[a as usize].distance(vertices[b as usize]);
        edges.push(EdgeSpec::line(a, b, length));
        edges.push(EdgeSpec::line(b, a, length));
    }
    let spec = NetworkSpec {
        origin_lat_deg: 45.0,
        origin_lon_deg: 7.0,
        turn_radius_m: 200.0,
        clearance_m: 5.0,
        vertices: vertices.iter().map(|p| Pose::new(p.x, p.y, 0.0)).collect(),
        edges,
        obstacles: obstacles
            .iter()
            .cloned()
            .map(ObstacleSpec::Polygon)
            .collect(),
        grid_cell_m: 1000.0,
        terrain: None,
        landmark: None,
        voronoi: Some(VoronoiSpec {
            threats: sites.iter().map(|s| (*s, 2000.0)).collect(),
            threat_weight: 0.5,
            kappa_max: 1.0 / 200.0,
            bounds: (bounds.min, bounds.max),
            corner_table: build_corner_table().to_vec(),
        }),
        provenance: Vec::new(),
    };
    encode(&spec).unwrap()
}

/// A planner of `image` (its storage leaked: a test's lifetime).
fn planner(image: &[u8]) -> Box<TestPlanner<'_>> {
    let storage = Box::leak(Box::new(VoronoiStorage::new()));
    let mut p: Box<TestPlanner> = Box::default();
    p.load_voronoi(image, storage).unwrap();
    p
}

/// The hull triangle the tests use: (0, 0), (1 000, 0), (0, 1 000); its long side runs from
/// (1 000, 0) to (0, 1 000).
const TRIANGLE: [Vec2; 3] = [
    Vec2::new(0.0, 0.0),
    Vec2::new(1000.0, 0.0),
    Vec2::new(0.0, 1000.0),
];

/// Two no-fly squares 3 km from the triangle, on either side.
fn far_squares() -> [Vec<Vec2>; 2] {
    [
        square(Vec2::new(-3000.0, -3000.0), 100.0),
        square(Vec2::new(3000.0, 3000.0), 100.0),
    ]
}

/// Zones far from the triangle leave it clear. A no-fly square wholly inside it (no point near
/// a side) refuses it by its first vertex, and a pop-up disc wholly inside by its centre.
/// A pop-up square across the long side, its centre outside the triangle and none of the
/// triangle's corners inside it, refuses it by that side alone.
#[test]
fn a_zone_inside_the_hull_or_across_one_side_refuses_it() {
    let far = far_squares();
    let image = network(&far);
    let mut p = planner(&image);
    let mut meter = Meter::new(u64::MAX);
    assert!(p.triangle_is_clear(TRIANGLE, &mut meter));
    let inside = network(&[far[0].clone(), square(Vec2::new(250.0, 250.0), 50.0)]);
    let q = planner(&inside);
    assert!(!q.triangle_is_clear(TRIANGLE, &mut meter));
    p.add_popup(Popup::Circle {
        centre: Vec2::new(200.0, 200.0),
        radius: 20.0,
    })
    .unwrap();
    assert!(!p.triangle_is_clear(TRIANGLE, &mut meter));
    let mut p = planner(&image);
    // Across the long side (x + y = 1 000): its corner (470, 470) lies inside the triangle,
    // its centre (520, 520) outside.
    p.add_popup(Popup::Polygon(
        square(Vec2::new(520.0, 520.0), 50.0).into_iter().collect(),
    ))
    .unwrap();
    assert!(!p.triangle_is_clear(TRIANGLE, &mut meter));
}

/// A clear hull test counts the collision tests of its three sides (each a straight path, as
/// `path_is_clear` counts it alone), then one containment test per no-fly zone and one per
/// pop-up: here 2 zones and 3 pop-ups, all far away. A side of zero length (two corners at
/// one point) is not tested.
#[test]
fn a_hull_test_counts_its_sides_then_one_test_per_zone_and_popup() {
    let far = far_squares();
    let image = network(&far);
    let mut p = planner(&image);
    for x in [-4000.0, -3500.0, -2500.0] {
        p.add_popup(Popup::Circle {
            centre: Vec2::new(x, 4000.0),
            radius: 50.0,
        })
        .unwrap();
    }
    let radius = p.voronoi_turn_radius();
    let side = |a: Vec2, b: Vec2| {
        let mut meter = Meter::new(u64::MAX);
        assert!(p.path_is_clear(&super::straight(a, b, radius), &mut meter));
        meter.work.collision_tests
    };
    let [a, b, c] = TRIANGLE;
    let sides = side(a, b) + side(b, c) + side(c, a);
    assert!(sides >= 3 * 5, "{sides} tests for the sides");
    let mut meter = Meter::new(u64::MAX);
    assert!(p.triangle_is_clear(TRIANGLE, &mut meter));
    assert_eq!(meter.work.collision_tests, sides + 2 + 3);
    let degenerate = side(b, c) + side(c, b);
    let mut meter = Meter::new(u64::MAX);
    assert!(p.triangle_is_clear([b, b, c], &mut meter));
    assert_eq!(meter.work.collision_tests, degenerate + 2 + 3);
}
