//! The core under bad input and tight budgets: post-processing never reports success over its
//! budget, overlapping polygon point ranges and edge geometry that misses its target are
//! rejected by the loader, a pop-up circle containing the start is not ignored, a plan never
//! returns a non-finite route, capacities of 0 and 1 never panic, and random sequences of calls
//! with extreme values never panic and keep their work within the budget.
//!
//! Each test pins a behaviour the core must keep (its comment names the failure it rules out);
//! the others are edge cases not covered elsewhere (marked `EDGE CASE`).

use host_tests::world::lattice_spec;
use host_tests::{cases, Rng};

use skyroute::network::format::{EdgeRecord, Header, ObstacleRecord, U32Record, VertexRecord};
use skyroute::network::write::{encode, EdgeSpec, NetworkSpec, ObstacleSpec};
use skyroute::network::{image_checksum, LoadError};
use skyroute::planner::{Goal, PlanError, PlannerConfig, Popup, Query, Search, TurnRule};
use skyroute::{DubinsPath, Network, Planner, Pose, Vec2};
use std::f32::consts::{FRAC_PI_2, PI};

type Big<'n> = Planner<'n, 1024, 16384, 16, 1024>;

fn boxed<'n, const V: usize, const E: usize, const P: usize, const R: usize>(
    bytes: &'n [u8],
) -> Box<Planner<'n, V, E, P, R>> {
    let mut p: Box<Planner<'n, V, E, P, R>> = Box::new(Planner::new());
    p.load(bytes).expect("test network loads");
    p
}

fn put_u32(b: &mut [u8], at: usize, v: u32) {
    b[at..at + 4].copy_from_slice(&v.to_le_bytes());
}

fn obstacle_bytes(kind: u8, first: u32, count: u32, circle: [f32; 3], bbox: [f32; 4]) -> Vec<u8> {
    let mut out = vec![kind];
    out.extend_from_slice(&first.to_le_bytes());
    out.extend_from_slice(&count.to_le_bytes());
    for x in circle.iter().chain(bbox.iter()) {
        out.extend_from_slice(&x.to_le_bytes());
    }
    assert_eq!(out.len(), ObstacleRecord::SIZE);
    out
}

/// Replaces the obstacle and point sections of an image that has no obstacles, fixing the
/// header's counts, body length and CRC. (The grid index does not depend on obstacles.)
fn splice_obstacles(image: &[u8], obstacles: &[Vec<u8>], points: &[Vec2]) -> Vec<u8> {
    let net = Network::from_bytes(image).unwrap();
    assert_eq!(net.obstacle_count(), 0);
    let (v, e) = (net.vertex_count() as usize, net.edge_count() as usize);
    let at =
        Header::SIZE + v * VertexRecord::SIZE + (v + 1) * U32Record::SIZE + e * EdgeRecord::SIZE;
    let mut out = image[..at].to_vec();
    for o in obstacles {
        out.extend_from_slice(o);
    }
    for p in points {
        out.extend_from_slice(&p.x.to_le_bytes());
        out.extend_from_slice(&p.y.to_le_bytes());
    }
    out.extend_from_slice(&image[at..]);
    put_u32(&mut out, 40, obstacles.len() as u32);
    put_u32(&mut out, 44, points.len() as u32);
    let body_len = (out.len() - Header::SIZE) as u32;
    put_u32(&mut out, Header::SIZE - 8, body_len);
    let crc = image_checksum(&out);
    put_u32(&mut out, Header::CHECKED_SIZE, crc);
    out
}

/// [`try_plan_route`], which must find a route.
fn plan_route<const V: usize, const E: usize, const P: usize, const R: usize>(
    p: &mut Planner<'_, V, E, P, R>,
) -> skyroute::RouteSummary {
    try_plan_route(p).expect("lattice route")
}

/// Plans across the lattice of `lattice_spec(5, 100.0, 300.0, 30.0)`, corner to corner.
fn try_plan_route<const V: usize, const E: usize, const P: usize, const R: usize>(
    p: &mut Planner<'_, V, E, P, R>,
) -> Result<skyroute::RouteSummary, PlanError> {
    try_plan_lattice(p, Pose::new(700.0, 700.0, FRAC_PI_2))
}

/// Plans on the lattice of `lattice_spec(5, 100.0, 300.0, 30.0)` from its corner (300, 300),
/// heading east, to `goal`.
fn try_plan_lattice<const V: usize, const E: usize, const P: usize, const R: usize>(
    p: &mut Planner<'_, V, E, P, R>,
    goal: Pose,
) -> Result<skyroute::RouteSummary, PlanError> {
    // A short connect radius: no direct start–goal path, the route runs through the network.
    p.set_config(PlannerConfig {
        connect_radius_m: 150.0,
        ..PlannerConfig::DEFAULT
    });
    let q = Query {
        start: Pose::new(300.0, 300.0, 0.0),
        goal: Goal {
            position: goal.position,
            heading: Some(goal.heading),
        },
        search: Search::Dijkstra,
    };
    p.plan(&q, u64::MAX)
}

// ---------------------------------------------------------------------------------------------
// Rules out: `smooth_headings` returning Ok with work over its budget. src/planner/smooth.rs
// checks the meter before every candidate, whichever way the previous one ended (a first solve
// not clear, not shorter, a second not clear), and `finish` checks the last one's work.
// ---------------------------------------------------------------------------------------------
#[test]
fn smooth_headings_never_reports_success_over_budget() {
    let spec = lattice_spec(5, 100.0, 300.0, 30.0);
    let bytes = encode(&spec).unwrap();
    let mut p: Box<Big<'_>> = boxed(&bytes);
    let s = plan_route(&mut p);
    assert!(
        p.route_paths().len() >= 3,
        "need a route with junctions: {s:?}"
    );
    // Pop-ups arrive on the route's junctions (after the route was planned): every candidate
    // heading there now fails its clearance check, so each candidate `continue`s.
    let junctions: Vec<Vec2> = p.route_paths()[1..]
        .iter()
        .map(|path| path.start.position)
        .collect();
    assert!(junctions.len() <= 16);
    for centre in junctions {
        p.add_popup(Popup::Circle {
            centre,
            radius: 2.0,
        })
        .unwrap();
    }
    for (candidates, budget) in [(1000u16, 100u64), (64, 10), (1, 0)] {
        match p.smooth_headings(candidates, budget) {
            Ok(summary) => assert!(
                summary.work.total() <= budget,
                "smooth_headings({candidates}, {budget}) returned Ok with work {} > budget",
                summary.work.total()
            ),
            Err(PlanError::BudgetExhausted { .. }) => {}
            Err(e) => panic!("unexpected {e:?}"),
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Rules out: polygon obstacles whose point ranges overlap (FORMAT.md: Q is "polygon points over
// all obstacles"). `plan_work_bound` charges `obstacle_points` once in total while
// `path_is_clear` charges each polygon `point_count + 1` collision tests per primitive, so such
// an image would make `plan` count more than `worst_case_work()`, and a query given exactly
// that budget would fail with BudgetExhausted. src/network/validate.rs validate_obstacles,
// src/planner/work.rs plan_work_bound.
// ---------------------------------------------------------------------------------------------
#[test]
fn overlapping_polygon_point_ranges_are_rejected() {
    let spec = lattice_spec(5, 100.0, 300.0, 30.0);
    let image = encode(&spec).unwrap();
    // A thin, simple L-shaped polygon along the south and east sides of the area, with many
    // collinear points on its south side: its bounding box covers the whole area, so every
    // primitive is tested exactly against it, but nothing in the interior conflicts.
    let mut pts = Vec::new();
    for k in 0..=100 {
        pts.push(Vec2::new(-100.0 + 12.0 * k as f32, -100.0)); // (-100,-100) .. (1100,-100)
    }
    pts.push(Vec2::new(1100.0, 1100.0));
    pts.push(Vec2::new(1090.0, 1100.0));
    pts.push(Vec2::new(1090.0, -90.0));
    pts.push(Vec2::new(-100.0, -90.0));
    let n = pts.len() as u32;
    let bbox = [-100.0, -100.0, 1100.0, 1100.0];
    // 100 obstacle records, all naming the same points.
    let obstacles: Vec<Vec<u8>> = (0..100)
        .map(|_| obstacle_bytes(0, 0, n, [0.0; 3], bbox))
        .collect();
    let bytes = splice_obstacles(&image, &obstacles, &pts);
    // Rejected: polygons must own back-to-back point ranges covering every point once, which
    // is what the work bound charges.
    assert_eq!(
        Network::from_bytes(&bytes).unwrap_err(),
        skyroute::LoadError::BadOffsets {
            section: skyroute::network::Section::Obstacles,
            index: 1
        }
    );
}

// ---------------------------------------------------------------------------------------------
// Rules out (fail-open, numeric range): a circle pop-up ignored because a distance overflows.
// Squared in f32, distances above ~1.8e19 m are +inf; a pop-up whose centre is that far but
// whose radius reaches the network (here a disc containing the whole area) must be refused by
// `Popup::validate` or must block the edges and contain the start, never be routed through.
// src/planner/popup.rs validate/contains/conflicts, src/geometry/mod.rs Vec2::norm.
// ---------------------------------------------------------------------------------------------
#[test]
fn huge_circle_popup_that_contains_the_start_is_not_ignored() {
    let spec = lattice_spec(5, 100.0, 300.0, 30.0);
    let bytes = encode(&spec).unwrap();
    let mut p: Box<Big<'_>> = boxed(&bytes);
    let r = 1.0e20f32;
    // Disc centred (r, 500) of radius r: every point with x > 0 and |y − 500| ≪ sqrt(r·x) is
    // inside; the whole lattice (x, y in [300, 700]) is, by ~x metres.
    let popup = Popup::Circle {
        centre: Vec2::new(r, 500.0),
        radius: r,
    };
    match p.add_popup(popup) {
        // Refused since the fix: beyond MAX_COORDINATE_M.
        Err(e) => assert_eq!(e, skyroute::PopupError::OutOfRange),
        Ok(s) => {
            let q = Query {
                start: Pose::new(300.0, 300.0, 0.0),
                goal: Goal {
                    position: Vec2::new(700.0, 700.0),
                    heading: None,
                },
                search: Search::Dijkstra,
            };
            let res = p.plan(&q, u64::MAX);
            assert!(
                matches!(res, Err(PlanError::InsidePopup { .. })),
                "start lies inside the pop-up, yet plan gave {res:?} (edges blocked: {})",
                s.edges_blocked
            );
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Rules out (NaN/inf propagation): with `connect_radius_m = +inf` (or any radius ≥ ~1.8e19) a
// far start reaches `DubinsPath::with_word`, whose squared centre distance overflows f32
// (d*d → inf); the planner must refuse the query rather than return a route whose length is
// infinite or whose primitives have non-finite coordinates.
// src/geometry/dubins.rs csc_angles (l_sq = d*d − …), src/planner/connect.rs nearest_vertices.
// ---------------------------------------------------------------------------------------------
#[test]
fn plan_never_returns_a_non_finite_route() {
    let spec = lattice_spec(5, 100.0, 300.0, 30.0);
    let bytes = encode(&spec).unwrap();
    let mut p: Box<Big<'_>> = boxed(&bytes);
    p.set_config(PlannerConfig {
        connect_radius_m: f32::INFINITY,
        ..PlannerConfig::DEFAULT
    });
    let q = Query {
        start: Pose::new(1.0e30, 500.0, PI),
        goal: Goal {
            position: Vec2::new(500.0, 500.0),
            heading: Some(0.0),
        },
        search: Search::Dijkstra,
    };
    if let Ok(s) = p.plan(&q, u64::MAX) {
        assert!(
            s.length.is_finite(),
            "route length {}: {:?}",
            s.length,
            p.route()
        );
        for prim in p.route() {
            assert!(
                prim.start().is_finite() && prim.end().is_finite() && prim.length().is_finite(),
                "non-finite primitive in an accepted route: {prim:?}"
            );
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Rules out (validation gap): an edge whose path does not end at its target's pose. FORMAT.md
// says an edge's path "starts at the source vertex's pose; flying it ends at the target's
// pose", and the grid-coverage check (4r around each vertex) and pop-up pruning rely on it; an
// edge flying 5 km away from its target would make routes discontinuous and a pop-up on its far
// part (outside the grid) block nothing. src/network/validate.rs validate_edges.
// ---------------------------------------------------------------------------------------------
#[test]
fn loader_rejects_edge_geometry_that_misses_its_target() {
    let spec = lattice_spec(3, 100.0, 300.0, 30.0);
    let mut bytes = encode(&spec).unwrap();
    let net = Network::from_bytes(&bytes).unwrap();
    let v = net.vertex_count() as usize;
    let edge0 = Header::SIZE + v * VertexRecord::SIZE + (v + 1) * U32Record::SIZE;
    // Edge 0 becomes LSL with lengths [0, 5000, 0]: a 5 km straight from its source.
    bytes[edge0 + 12] = 0;
    for (k, x) in [0.0f32, 5000.0, 0.0].iter().enumerate() {
        let at = edge0 + 13 + 4 * k;
        bytes[at..at + 4].copy_from_slice(&x.to_le_bytes());
    }
    let crc = image_checksum(&bytes);
    put_u32(&mut bytes, Header::CHECKED_SIZE, crc);
    match Network::from_bytes(&bytes) {
        Err(_) => {}
        Ok(net) => {
            let e = net.edge(0).unwrap();
            let end = net.edge_path(0).unwrap().end();
            let target = net.vertex(e.target).unwrap();
            panic!(
                "accepted an edge whose path ends at {:?}, {} m from its target {:?}",
                end.position,
                end.position.distance(target.position),
                target.position
            );
        }
    }
}

// ---------------------------------------------------------------------------------------------
// EDGE CASE: a network with exactly as many vertices as the planner holds. The search's states
// fill its heap and tables to the last slot; the route is the one a larger planner finds.
// ---------------------------------------------------------------------------------------------
#[test]
fn a_network_filling_the_vertex_capacity_exactly_plans_as_a_larger_planner() {
    let spec = lattice_spec(5, 100.0, 300.0, 30.0);
    assert_eq!(spec.vertices.len(), 100);
    let bytes = encode(&spec).unwrap();
    let mut big: Box<Big<'_>> = boxed(&bytes);
    let want = plan_route(&mut big);
    let mut exact: Box<Planner<'_, 100, 16384, 16, 1024>> = boxed(&bytes);
    assert_eq!(plan_route(&mut exact), want);
    assert_eq!(exact.route(), big.route());
}

// ---------------------------------------------------------------------------------------------
// EDGE CASE: a route whose paths fit the route capacity but whose primitives do not is refused
// as too long, and the previous route is kept.
// ---------------------------------------------------------------------------------------------
#[test]
fn a_route_with_more_primitives_than_the_capacity_is_refused() {
    let bytes = encode(&lattice_spec(5, 100.0, 300.0, 30.0)).unwrap();
    let mut big: Box<Big<'_>> = boxed(&bytes);
    let want = plan_route(&mut big);
    let (paths, primitives) = (big.route_paths().len(), want.primitives as usize);
    assert!(
        paths <= 8 && primitives > 8,
        "{paths} paths, {primitives} primitives"
    );
    let mut small: Box<Planner<'_, 1024, 16384, 16, 8>> = boxed(&bytes);
    assert!(matches!(
        try_plan_route(&mut small),
        Err(PlanError::RouteTooLong { capacity: 8, .. })
    ));
    assert!(small.route().is_empty());
}

#[test]
fn a_route_of_as_many_paths_and_primitives_as_the_capacity_is_accepted() {
    // Along the lattice's first row, heading east: straight paths of one primitive each.
    let bytes = encode(&lattice_spec(5, 100.0, 300.0, 30.0)).unwrap();
    let east = Pose::new(700.0, 300.0, 0.0);
    let mut big: Box<Big<'_>> = boxed(&bytes);
    let want = try_plan_lattice(&mut big, east).expect("the row's route");
    let paths = big.route_paths().len();
    assert_eq!(
        (paths, want.primitives),
        (4, 4),
        "the row's route: {:?}",
        big.route_paths()
    );
    let mut exact: Box<Planner<'_, 1024, 16384, 16, 4>> = boxed(&bytes);
    let got = try_plan_lattice(&mut exact, east).expect("a route that fits exactly");
    assert_eq!((got.length, got.primitives), (want.length, want.primitives));
    assert_eq!(exact.route_paths(), big.route_paths());
    let mut short: Box<Planner<'_, 1024, 16384, 16, 3>> = boxed(&bytes);
    assert!(matches!(
        try_plan_lattice(&mut short, east),
        Err(PlanError::RouteTooLong { capacity: 3, .. })
    ));
}

#[test]
fn a_route_of_more_paths_than_the_capacity_is_refused_even_with_fewer_primitives() {
    // The goal is vertex (500, 300, 0)'s own pose: its goal link is a path of length 0, no
    // primitive. With a connect radius of 60 m the start (250, 300) links only to the
    // vertices at (300, 300) and the goal only to those at (500, 300), so the route is four
    // paths: the start link, two edges, and that empty link, three primitives in all.
    let bytes = encode(&lattice_spec(3, 100.0, 300.0, 30.0)).unwrap();
    let query = Query {
        start: Pose::new(250.0, 300.0, 0.0),
        goal: Goal {
            position: Vec2::new(500.0, 300.0),
            heading: Some(0.0),
        },
        search: Search::Dijkstra,
    };
    let config = PlannerConfig {
        connect_radius_m: 60.0,
        ..PlannerConfig::DEFAULT
    };
    let mut four: Box<Planner<'_, 1024, 16384, 16, 4>> = boxed(&bytes);
    four.set_config(config);
    let summary = four.plan(&query, u64::MAX).expect("four paths fit four");
    let primitives = |p: &DubinsPath| p.primitives().iter().flatten().count();
    let counts: Vec<usize> = four.route_paths().iter().map(primitives).collect();
    assert_eq!((counts, summary.primitives), (vec![1, 1, 1, 0], 3));
    let mut three: Box<Planner<'_, 1024, 16384, 16, 3>> = boxed(&bytes);
    three.set_config(config);
    assert_eq!(
        three.plan(&query, u64::MAX),
        Err(PlanError::RouteTooLong {
            primitives: 4,
            capacity: 3
        })
    );
    assert!(three.route_paths().is_empty());
}

// ---------------------------------------------------------------------------------------------
// EDGE CASE (passes): the degenerate capacities. `Planner<0,0,0,0>` and `<1,1,1,1>` must load a
// network that fits, refuse one that does not, and never panic on plan / pop-ups / smoothing.
// ---------------------------------------------------------------------------------------------
#[test]
fn zero_and_one_capacities_never_panic() {
    let empty = NetworkSpec {
        origin_lat_deg: 0.0,
        origin_lon_deg: 0.0,
        turn_radius_m: 30.0,
        clearance_m: 5.0,
        vertices: Vec::new(),
        edges: Vec::new(),
        obstacles: vec![ObstacleSpec::Circle {
            centre: Vec2::new(50.0, 50.0),
            radius: 10.0,
        }],
        grid_cell_m: 60.0,
        landmark: None,
        voronoi: None,
        terrain: None,
        provenance: Vec::new(),
    };
    let empty = encode(&empty).unwrap();
    // A self-loop: the image keeps a word, and LRL between a pose and itself is a loop of
    // (nearly) zero length at the vertex.
    let at = Pose::new(0.0, 0.0, 0.0);
    let loop_path = DubinsPath::with_word(&at, &at, 30.0, skyroute::DubinsWord::Lrl).unwrap();
    let one = NetworkSpec {
        vertices: vec![at],
        edges: vec![EdgeSpec {
            source: 0,
            target: 0,
            cost: loop_path.length(),
            word: loop_path.word,
            lengths: loop_path.lengths,
        }],
        obstacles: Vec::new(),
        ..lattice_spec(1, 100.0, 0.0, 30.0)
    };
    let one = encode(&one).unwrap();
    let queries = [
        Query {
            start: Pose::new(-200.0, 0.0, 0.0),
            goal: Goal {
                position: Vec2::new(200.0, 0.0),
                heading: None,
            },
            search: Search::AStar,
        },
        Query {
            start: Pose::new(0.0, 0.0, 0.0),
            goal: Goal {
                position: Vec2::new(0.0, 0.0),
                heading: Some(0.0),
            },
            search: Search::Dijkstra,
        },
    ];
    let mut p0: Planner<'_, 0, 0, 0, 0> = Planner::new();
    assert!(matches!(
        p0.load(&one),
        Err(LoadError::TooManyVertices { .. })
    ));
    p0.load(&empty).unwrap();
    assert!(p0
        .add_popup(Popup::Circle {
            centre: Vec2::new(0.0, 0.0),
            radius: 1.0
        })
        .is_err());
    assert!(p0.remove_popup(0).is_err());
    assert!(p0.remove_popup(255).is_err());
    for q in &queries {
        let _ = p0.plan(q, u64::MAX);
        let _ = p0.plan(q, 0);
    }
    let _ = p0.shortcut(u64::MAX);
    let _ = p0.smooth_headings(u16::MAX, 1000);
    assert!(p0.route().is_empty());

    let mut p1: Planner<'_, 1, 1, 1, 1> = Planner::new();
    p1.load(&one).unwrap();
    for cfg in [
        PlannerConfig::DEFAULT,
        PlannerConfig {
            start_candidates: 0,
            goal_candidates: 255,
            connect_radius_m: f32::NAN,
            free_goal_headings: 0,
            turn_rule: TurnRule::Paper,
        },
        PlannerConfig {
            start_candidates: 255,
            goal_candidates: 0,
            connect_radius_m: -1.0,
            free_goal_headings: u16::MAX,
            turn_rule: TurnRule::SharedEqually,
        },
    ] {
        p1.set_config(cfg);
        for q in &queries {
            let _ = p1.plan(q, u64::MAX);
            let _ = p1.shortcut(u64::MAX);
            let _ = p1.smooth_headings(3, u64::MAX);
        }
    }
    let id = p1
        .add_popup(Popup::Circle {
            centre: Vec2::new(0.0, 0.0),
            radius: 1.0,
        })
        .unwrap()
        .id;
    assert_eq!(id, 0);
    assert!(p1
        .add_popup(Popup::Circle {
            centre: Vec2::new(9.0, 9.0),
            radius: 1.0
        })
        .is_err());
    assert!(!p1.is_edge_enabled(0));
    p1.remove_popup(id).unwrap();
    assert!(p1.is_edge_enabled(0));
}

// ---------------------------------------------------------------------------------------------
// EDGE CASE (passes): random sequences of calls with extreme values (NaN, ±inf, ±f32::MAX,
// subnormals, huge headings, odd configs, degenerate pop-ups) never panic (debug assertions on)
// and every Ok result keeps its counted work within the budget it was given.
// ---------------------------------------------------------------------------------------------
/// Extreme values drawn from the shared SplitMix64.
trait Extreme {
    fn f(&mut self) -> f32;
    fn v(&mut self) -> Vec2;
}

impl Extreme for Rng {
    fn f(&mut self) -> f32 {
        const SPECIAL: [f32; 14] = [
            f32::NAN,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::MAX,
            f32::MIN,
            f32::MIN_POSITIVE,
            1.0e-40,
            0.0,
            -0.0,
            1.0e20,
            -1.0e20,
            1.0e30,
            8192.5,
            -1.0e7,
        ];
        match self.below(4) {
            0 => SPECIAL[self.below(SPECIAL.len() as u64) as usize],
            _ => (self.below(2_000_000) as f32) / 1000.0 - 500.0,
        }
    }
    fn v(&mut self) -> Vec2 {
        Vec2::new(self.f(), self.f())
    }
}

#[test]
fn random_extreme_call_sequences_never_panic() {
    let mut spec = lattice_spec(4, 100.0, 300.0, 30.0);
    spec.obstacles = vec![
        ObstacleSpec::Circle {
            centre: Vec2::new(450.0, 450.0),
            radius: 12.0,
        },
        ObstacleSpec::Polygon(vec![
            Vec2::new(340.0, 520.0),
            Vec2::new(370.0, 520.0),
            Vec2::new(370.0, 560.0),
            Vec2::new(340.0, 560.0),
        ]),
    ];
    let bytes = encode(&spec).unwrap();
    let mut p: Box<Planner<'_, 64, 4096, 3, 24>> = boxed(&bytes);
    let seeds: u64 = std::env::var("FUZZ_SEEDS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(cases(1, 3) as u64);
    for seed in 0..seeds {
        let mut rng = Rng(42 + seed);
        for _ in 0..6000 {
            match rng.below(9) {
                0 => p.set_config(PlannerConfig {
                    start_candidates: rng.below(256) as u8,
                    goal_candidates: rng.below(256) as u8,
                    connect_radius_m: rng.f().abs() * if rng.below(5) == 0 { -1.0 } else { 1.0 },
                    free_goal_headings: rng.below(400) as u16,
                    turn_rule: if rng.below(2) == 0 {
                        TurnRule::Paper
                    } else {
                        TurnRule::SharedEqually
                    },
                }),
                1 | 2 => {
                    let popup = if rng.below(2) == 0 {
                        Popup::Circle {
                            centre: rng.v(),
                            radius: rng.f(),
                        }
                    } else {
                        let mut pts = heapless::Vec::new();
                        for _ in 0..rng.below(18) {
                            let _ = pts.push(rng.v());
                        }
                        Popup::Polygon(pts)
                    };
                    let _ = p.add_popup(popup);
                }
                3 => {
                    let _ = p.remove_popup(rng.below(20) as u8);
                }
                4 => {
                    let b = rng.below(2000);
                    if let Ok(s) = p.shortcut(b) {
                        assert!(s.work.total() <= b);
                    }
                }
                5 => {
                    let b = rng.below(5000);
                    if let Ok(s) = p.smooth_headings(rng.below(40) as u16, b) {
                        assert!(s.work.total() <= b);
                    }
                }
                _ => {
                    let near = rng.below(3) != 0;
                    let pick = |rng: &mut Rng| {
                        if near {
                            Vec2::new(250.0 + rng.below(500) as f32, 250.0 + rng.below(500) as f32)
                        } else {
                            rng.v()
                        }
                    };
                    let start = Pose {
                        position: pick(&mut rng),
                        heading: rng.f(),
                    };
                    let goal = Goal {
                        position: pick(&mut rng),
                        heading: if rng.below(2) == 0 {
                            None
                        } else {
                            Some(rng.f())
                        },
                    };
                    let q = Query {
                        start,
                        goal,
                        search: if rng.below(2) == 0 {
                            Search::Dijkstra
                        } else {
                            Search::AStar
                        },
                    };
                    let before = format!("{:?}{:?}", p.route(), p.route_paths());
                    let budget = if rng.below(3) == 0 {
                        rng.below(20_000)
                    } else {
                        u64::MAX
                    };
                    match p.plan(&q, budget) {
                        Ok(s) => assert!(s.work.total() <= budget),
                        Err(e) => assert_eq!(
                            format!("{:?}{:?}", p.route(), p.route_paths()),
                            before,
                            "{e:?} changed the route"
                        ),
                    }
                }
            }
        }
    }
}
