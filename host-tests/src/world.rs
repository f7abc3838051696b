//! Small synthetic roadmap worlds: a square area with random rectangles and circles, built
//! with the ground tool's real roadmap builder and encoded.

use crate::Rng;
use skyroute::network::write::{encode, EdgeSpec, NetworkSpec, ObstacleSpec};
use skyroute::planner::{Goal, Phase, Query, Search, Work, MAX_CANDIDATES};
use skyroute::{DubinsPath, Pose, Vec2};
use skyroute::{Network, Planner};
use skyroute_prep::roadmap::{build_roadmap, CollisionCheck, RoadmapInput, RoadmapParams};
use std::f32::consts::{FRAC_PI_2, PI};

/// An axis-aligned rectangle as a polygon.
pub fn rect(x0: f32, y0: f32, x1: f32, y1: f32) -> Vec<Vec2> {
    vec![
        Vec2::new(x0, y0),
        Vec2::new(x1, y0),
        Vec2::new(x1, y1),
        Vec2::new(x0, y1),
    ]
}

/// A test world: a square area with rectangular and circular obstacles.
pub struct World {
    /// The area's lower-left corner.
    pub origin: Vec2,
    /// The area's side, metres.
    pub size: f32,
    pub obstacles: Vec<ObstacleSpec>,
    pub spec: NetworkSpec,
    pub bytes: Vec<u8>,
}

/// Builds a roadmap over the `size` × `size` area from (0, 0) with `n_obstacles` random
/// obstacles.
pub fn world(seed: u64, size: f32, spacing: f32, radius: f32, n_obstacles: usize) -> World {
    world_at(
        seed,
        Vec2::new(0.0, 0.0),
        size,
        spacing,
        radius,
        n_obstacles,
    )
}

/// [`world`] over the area whose lower-left corner is `origin` (with a negative origin, a
/// world whose coordinates are all negative).
pub fn world_at(
    seed: u64,
    origin: Vec2,
    size: f32,
    spacing: f32,
    radius: f32,
    n_obstacles: usize,
) -> World {
    let mut rng = Rng(seed);
    let mut obstacles = Vec::new();
    for i in 0..n_obstacles {
        let (x, y) = (
            origin.x + rng.range_f32(0.1 * size, 0.9 * size),
            origin.y + rng.range_f32(0.1 * size, 0.9 * size),
        );
        let s = rng.range_f32(0.02 * size, 0.06 * size);
        if i % 3 == 2 {
            obstacles.push(ObstacleSpec::Circle {
                centre: Vec2::new(x, y),
                radius: s,
            });
        } else {
            obstacles.push(ObstacleSpec::Polygon(rect(
                x - s,
                y - s * 0.7,
                x + s,
                y + s * 0.7,
            )));
        }
    }
    let input = RoadmapInput {
        area_min: origin,
        area_max: origin + Vec2::new(size, size),
        obstacles: obstacles.clone(),
        fixed_vertices: Vec::new(),
    };
    let params = RoadmapParams {
        turn_radius_m: radius,
        sample_spacing_m: spacing,
        neighbour_radius_m: 3.0 * radius,
        k_nearest_fallback: 4,
        allow_ccc: true,
        clearance_m: 5.0,
        seed,
        check: CollisionCheck::Exact,
    };
    let roadmap = build_roadmap(&input, &params, &|_, _| {});
    let spec = NetworkSpec {
        origin_lat_deg: 48.0,
        origin_lon_deg: 11.6,
        turn_radius_m: radius,
        clearance_m: params.clearance_m,
        vertices: roadmap.vertices,
        edges: roadmap.edges,
        obstacles: obstacles.clone(),
        grid_cell_m: 2.0 * radius,
        landmark: None,
        voronoi: None,
        terrain: None,
        provenance: Vec::new(),
    };
    let bytes = encode(&spec).expect("test network encodes");
    World {
        origin,
        size,
        obstacles,
        spec,
        bytes,
    }
}

/// A random pose in the world, outside every obstacle by `margin`.
pub fn free_pose(rng: &mut Rng, w: &World, margin: f32) -> Pose {
    loop {
        let p = w.origin + Vec2::new(rng.range_f32(0.0, w.size), rng.range_f32(0.0, w.size));
        let clear = w.obstacles.iter().all(|o| match o {
            ObstacleSpec::Polygon(poly) => {
                !skyroute::geometry::predicates::point_in_polygon(p, poly.as_slice())
                    && (0..poly.len()).all(|i| {
                        let e = skyroute::Segment::new(poly[i], poly[(i + 1) % poly.len()]);
                        skyroute::geometry::predicates::point_segment_distance(p, &e) > margin
                    })
            }
            ObstacleSpec::Circle { centre, radius } => p.distance(*centre) > radius + margin,
        });
        if clear {
            return Pose {
                position: p,
                heading: rng.range_f32(-std::f32::consts::PI, std::f32::consts::PI),
            };
        }
    }
}

/// A lattice roadmap: `n × n` positions `spacing` apart from `origin`, four headings each,
/// an edge (the shortest Dubins path) from every vertex to every vertex at a neighbouring
/// position (8-neighbourhood).
pub fn lattice_spec(n: usize, spacing: f32, origin: f32, radius: f32) -> NetworkSpec {
    let headings = [0.0, FRAC_PI_2, PI, -FRAC_PI_2];
    let mut vertices = Vec::new();
    for j in 0..n {
        for i in 0..n {
            for h in headings {
                vertices.push(Pose::new(
                    origin + i as f32 * spacing,
                    origin + j as f32 * spacing,
                    h,
                ));
            }
        }
    }
    let mut edges = Vec::new();
    for (a, pa) in vertices.iter().enumerate() {
        for (b, pb) in vertices.iter().enumerate() {
            let d = pa.position.distance(pb.position);
            if d > 0.0 && d <= 1.5 * spacing {
                let path = DubinsPath::shortest(pa, pb, radius).unwrap();
                edges.push(EdgeSpec::dubins(a as u32, b as u32, &path));
            }
        }
    }
    NetworkSpec {
        origin_lat_deg: 48.0,
        origin_lon_deg: 11.6,
        turn_radius_m: radius,
        clearance_m: 5.0,
        vertices,
        edges,
        obstacles: Vec::new(),
        grid_cell_m: 2.0 * radius,
        landmark: None,
        voronoi: None,
        terrain: None,
        provenance: Vec::new(),
    }
}

/// A Dijkstra query from `start` to `goal`, any arrival heading.
pub fn query_to(start: Pose, goal: Vec2) -> Query {
    Query {
        start,
        goal: Goal {
            position: goal,
            heading: None,
        },
        search: Search::Dijkstra,
    }
}

/// The vertices a query end at `at` tries, by brute force: the [`MAX_CANDIDATES`] nearest
/// within `radius`, equally near ones in index order.
pub fn nearest_vertices(net: &Network<'_>, at: Vec2, radius: f32) -> Vec<u32> {
    let mut near: Vec<(f32, u32)> = (0..net.vertex_count())
        .map(|v| (net.vertex(v).unwrap().position.distance(at), v))
        .filter(|&(d, _)| d <= radius)
        .collect();
    near.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
    near.into_iter()
        .take(MAX_CANDIDATES)
        .map(|(_, v)| v)
        .collect()
}

/// `read` of the work counted when each of `phases` began, planning `q` with `p` (roadmap or
/// terrain, which report their phases); panics naming the query if a phase is not reached.
pub fn work_at_phases<
    T: Copy + std::fmt::Debug,
    const N: usize,
    const V: usize,
    const E: usize,
    const P: usize,
    const R: usize,
>(
    p: &mut Planner<'_, V, E, P, R>,
    q: &Query,
    phases: [Phase; N],
    read: impl Fn(&Work) -> T,
) -> [T; N] {
    let mut marks = Vec::new();
    let _ = p.plan_observed(q, u64::MAX, &mut |phase, work| {
        marks.push((phase, read(work)))
    });
    phases.map(|phase| match marks.iter().find(|m| m.0 == phase) {
        Some(&(_, value)) => value,
        None => panic!("{q:?}: phases {marks:?}"),
    })
}
