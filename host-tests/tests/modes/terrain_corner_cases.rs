//! Review of terrain mode: small synthetic terrain networks that exercise the corner cases of
//! the turn-feasible search (degenerate fillets, zero-length edges, goal on a node), the
//! planner's documented work bound, and the handling of sections the terrain search ignores.
//! Every route a query returns is checked independently: continuous in position and heading,
//! from the start pose to the goal, and with every sample of its centre line over a cell that
//! is free at the altitude in force.

use host_tests::world::query_to;
use skyroute::geometry::grid::CellGrid;
use skyroute::network::elevation::ElevationCoding;
use skyroute::network::write::{encode, EdgeSpec, NetworkSpec, ObstacleSpec, TerrainSpec};
use skyroute::network::LoadError;
use skyroute::planner::{PlanError, PlannerConfig, Popup, TurnRule, MAX_LINKS};
use skyroute::{Planner, Pose, Primitive, Vec2};

/// Codes of free and high cells; with base 0, step 1, altitude 150 and safety height 0 every
/// code ≥ 150 is blocked.
const FREE: u8 = 10;
const HIGH: u8 = 200;
const ALTITUDE: f32 = 150.0;
const BLOCKING: u8 = 150;

type SmallPlanner<'n> = Planner<'n, 4096, 4096, 4, 256>;
type RingPlanner<'n> = Planner<'n, 32768, 8192, 16, 512>;

struct Terrain {
    grid: CellGrid,
    codes: Vec<u8>,
}

impl Terrain {
    fn new(origin: Vec2, cell: f32, cols: u32, rows: u32) -> Self {
        Terrain {
            grid: CellGrid::new(origin, cell, cols, rows),
            codes: vec![FREE; (cols * rows) as usize],
        }
    }

    /// Marks every cell whose square lies within `[x0, x1] × [y0, y1]` as high.
    fn block(&mut self, x0: f32, y0: f32, x1: f32, y1: f32) {
        for r in 0..self.grid.rows {
            for c in 0..self.grid.cols {
                let (lo, hi) = self.grid.cell_rect(c, r);
                if lo.x >= x0 && hi.x <= x1 && lo.y >= y0 && hi.y <= y1 {
                    self.codes[(r * self.grid.cols + c) as usize] = HIGH;
                }
            }
        }
    }

    fn code_at(&self, p: Vec2) -> u8 {
        match self.grid.cell_of(p) {
            Some((c, r)) => self.codes[(r * self.grid.cols + c) as usize],
            None => 255,
        }
    }
}

/// A terrain network over `t` (widen 0) with straight edges `(from, to, stored length)`.
fn network(
    t: &Terrain,
    nodes: &[Vec2],
    edges: &[(u32, u32, f32)],
    radius: f32,
    obstacles: Vec<ObstacleSpec>,
) -> Result<Vec<u8>, skyroute::network::write::WriteError> {
    let spec = NetworkSpec {
        origin_lat_deg: 36.5,
        origin_lon_deg: -84.2,
        turn_radius_m: radius,
        clearance_m: 0.0,
        vertices: nodes
            .iter()
            .map(|&p| Pose {
                position: p,
                heading: 0.0,
            })
            .collect(),
        edges: edges
            .iter()
            .map(|&(a, b, l)| EdgeSpec::line(a, b, l))
            .collect(),
        obstacles,
        grid_cell_m: 1000.0,
        terrain: Some(TerrainSpec {
            grid: t.grid,
            coding: ElevationCoding {
                base_m: 0.0,
                step_m: 1.0,
            },
            codes: t.codes.clone(),
            widen_m: 0.0,
            altitude_m: ALTITUDE,
            safety_height_m: 0.0,
        }),
        landmark: None,
        voronoi: None,
        provenance: Vec::new(),
    };
    encode(&spec)
}

fn chord(nodes: &[Vec2], a: u32, b: u32) -> (u32, u32, f32) {
    (a, b, nodes[a as usize].distance(nodes[b as usize]))
}

/// Three nodes at a right-angled corner, (0, 0) → (3000, 0) → (3000, 3000), joined both ways
/// (edges 0 and 1 along the first leg, 2 and 3 along the second).
fn corner() -> ([Vec2; 3], [(u32, u32, f32); 4]) {
    let nodes = [
        Vec2::new(0.0, 0.0),
        Vec2::new(3000.0, 0.0),
        Vec2::new(3000.0, 3000.0),
    ];
    let edges = [
        chord(&nodes, 0, 1),
        chord(&nodes, 1, 0),
        chord(&nodes, 1, 2),
        chord(&nodes, 2, 1),
    ];
    (nodes, edges)
}

fn angle_diff(a: f32, b: f32) -> f32 {
    let d = (a - b).rem_euclid(std::f32::consts::TAU);
    d.min(std::f32::consts::TAU - d)
}

/// Problems with `route` flown from `start` to `goal` over `t`: jumps in position or heading
/// between consecutive primitives, wrong ends, and samples over blocked cells.
fn route_problems(route: &[Primitive], start: Pose, goal: Vec2, t: &Terrain) -> Vec<String> {
    let mut problems = Vec::new();
    let Some(first) = route.first() else {
        if start.position.distance(goal) > 0.1 {
            problems.push("empty route".into());
        }
        return problems;
    };
    if first.start().distance(start.position) > 0.1 {
        problems.push(format!("route starts at {:?}", first.start()));
    }
    if angle_diff(first.pose_at(0.0).heading, start.heading) > 1e-2 {
        problems.push(format!(
            "route starts heading {} instead of {}",
            first.pose_at(0.0).heading,
            start.heading
        ));
    }
    let last = route.last().unwrap();
    if last.end().distance(goal) > 0.1 {
        problems.push(format!("route ends at {:?}, goal {goal:?}", last.end()));
    }
    for (i, w) in route.windows(2).enumerate() {
        let (a, b) = (&w[0], &w[1]);
        let gap = a.end().distance(b.start());
        if gap > 0.1 {
            problems.push(format!(
                "jump of {gap} m between primitives {i} and {}",
                i + 1
            ));
        }
        let (ha, hb) = (a.pose_at(a.length()).heading, b.pose_at(0.0).heading);
        if a.length() > 1e-3 && b.length() > 1e-3 && angle_diff(ha, hb) > 1e-2 {
            problems.push(format!(
                "heading jumps from {ha} to {hb} between primitives {i} and {}",
                i + 1
            ));
        }
    }
    for (i, p) in route.iter().enumerate() {
        let n = (p.length() / 1.0).ceil().max(1.0) as u32;
        for k in 0..=n {
            let q = p.pose_at(p.length() * k as f32 / n as f32).position;
            if t.code_at(q) >= BLOCKING {
                problems.push(format!(
                    "primitive {i} ({p:?}) flies over a blocked cell at {q:?}"
                ));
                break;
            }
        }
    }
    problems
}

/// The smallest whole distance in `lo..hi` metres for which the unit direction the planner
/// computes along an axis-aligned edge, `d · (1/ℓ)`, comes out just below 1 in `f32`.
fn length_with_short_direction(lo: u32, hi: u32) -> f32 {
    (lo..hi)
        .map(|x| x as f32)
        .find(|&x| x * (1.0 / x) < 1.0)
        .expect("some length rounds below 1")
}

/// A corridor along the x axis where the start heads east, away from a goal in the west, and
/// every turn back near the start is blocked: high strips at `y ∈ [150, 250]` and
/// `y ∈ [−250, −150]` up to `x = strip_end`. Nodes are added by the caller.
fn corridor(strip_end: f32) -> Terrain {
    let mut t = Terrain::new(Vec2::new(-1000.0, -1000.0), 50.0, 60, 40);
    t.block(-1000.0, 150.0, strip_end, 250.0);
    t.block(-1000.0, -250.0, strip_end, -150.0);
    t
}

/// Finding: `Fillet::new` (src/planner/terrain/fillet.rs) takes `cut = r·|u_in × u_out| / (1 + u_in·u_out)`
/// and only treats `dot == −1` as infeasible. For exactly opposite directions whose computed
/// dot product rounds to just above −1 (a direction `d·(1/ℓ)` one ulp short of unit length, the
/// normal case for nodes on a grid line), the cross product is 0, so the cut is 0: a U-turn of
/// angle π accepted as if it needed no room. The route then flies a half circle off the node
/// and its next straight 2r to the side of the checked edge, over blocked terrain, and jumps
/// back to the next node.
#[test]
fn u_turn_at_collinear_nodes_is_not_accepted_with_a_zero_cut() {
    let x = length_with_short_direction(650, 900);
    let t = corridor(x - 150.0);
    // Q west of the start, P ahead of it; the only way back west from P is a U-turn.
    let nodes = [Vec2::new(0.0, 0.0), Vec2::new(x, 0.0)];
    let edges = [chord(&nodes, 1, 0), chord(&nodes, 0, 1)];
    let bytes = network(&t, &nodes, &edges, 100.0, Vec::new()).unwrap();
    let mut p: Box<SmallPlanner<'_>> = Box::new(Planner::new());
    p.load(&bytes).unwrap();
    let start = Pose::new(100.0, 0.0, 0.0);
    let goal = Vec2::new(-400.0, 0.0);
    match p.plan(&query_to(start, goal), u64::MAX) {
        Err(_) => {} // correct: no turn-feasible route exists
        Ok(_) => {
            let problems = route_problems(p.route(), start, goal, &t);
            assert!(
                problems.is_empty(),
                "U-turn at P (edge length {x}) accepted: {problems:#?}\nroute {:#?}",
                p.route()
            );
        }
    }
}

/// Finding: an edge between two nodes at the same position (chord 0) with a small stored length
/// passes the loader (`validate_line_edge` accepts |chord − length| ≤ 1 cm), and the search
/// then takes its direction `(to − from)·(1/ℓ)` = (0, 0). `Fillet::new` gives angle
/// `atan2(0, 0) = 0` and cut 0 both into and out of that edge, so the route reverses at the
/// duplicate node with no turn at all; the flown leg after it even heads along the zero
/// vector's angle (east) instead of along the next edge.
#[test]
fn zero_length_edge_does_not_allow_an_instant_reversal() {
    let t = corridor(550.0);
    // Q, P and P' (a duplicate of P).
    let nodes = [
        Vec2::new(0.0, 0.0),
        Vec2::new(700.0, 0.0),
        Vec2::new(700.0, 0.0),
    ];
    let edges = [(1, 2, 0.005), chord(&nodes, 2, 0), chord(&nodes, 0, 1)];
    let bytes = match network(&t, &nodes, &edges, 100.0, Vec::new()) {
        Ok(b) => b,
        Err(_) => return, // rejected at load: fine
    };
    let mut p: Box<SmallPlanner<'_>> = Box::new(Planner::new());
    p.load(&bytes).unwrap();
    let start = Pose::new(100.0, 0.0, 0.0);
    let goal = Vec2::new(-400.0, 0.0);
    match p.plan(&query_to(start, goal), u64::MAX) {
        Err(_) => {}
        Ok(_) => {
            let problems = route_problems(p.route(), start, goal, &t);
            assert!(
                problems.is_empty(),
                "reversal at a duplicate node: {problems:#?}\nroute {:#?}",
                p.route()
            );
        }
    }
}

/// The corner network over terrain blocked inside the corner (so no direct start–goal
/// connection crosses it): the terrain, the nodes and the image.
fn blocked_corner() -> (Terrain, [Vec2; 3], Vec<u8>) {
    let mut t = Terrain::new(Vec2::new(-1500.0, -1500.0), 100.0, 60, 60);
    t.block(500.0, 500.0, 2500.0, 2500.0);
    let (nodes, edges) = corner();
    let bytes = network(&t, &nodes, &edges, 100.0, Vec::new()).unwrap();
    (t, nodes, bytes)
}

/// A start 500 m before the corner's first node, heading along its first leg.
const CORNER_START: Pose = Pose {
    position: Vec2::new(-500.0, 0.0),
    heading: 0.0,
};

/// A goal exactly on a node: its free-heading goal link is a straight of length 0, whose own
/// heading (`atan2(0, 0)`) means nothing; arriving at the node is arriving at the goal, from
/// any direction, with no turn. Here the goal node is reached heading north and is the only
/// goal candidate within the connect radius; the route start → A → B → goal is planned and
/// flyable (and so is the same goal 1 m off the node).
#[test]
fn goal_exactly_on_a_node_is_reached_from_any_direction() {
    let (t, nodes, bytes) = blocked_corner();
    let mut p: Box<SmallPlanner<'_>> = Box::new(Planner::new());
    p.load(&bytes).unwrap();
    let start = CORNER_START;
    let goal = nodes[2];
    // The same goal 1 m short of the node is planned.
    let near = Vec2::new(3000.0, 3001.0);
    let r = p.plan(&query_to(start, near), u64::MAX);
    assert!(r.is_ok(), "goal next to the node: {r:?}");
    assert!(route_problems(p.route(), start, near, &t).is_empty());
    let r = p.plan(&query_to(start, goal), u64::MAX);
    assert!(r.is_ok(), "goal exactly on node 2: {r:?}");
    let problems = route_problems(p.route(), start, goal, &t);
    assert!(problems.is_empty(), "{problems:#?}");
}

/// A goal with a heading is reached along its last link's final arc: the route ends at the
/// goal's position, flying its heading, from start → A → B and on to a goal 500 m east and
/// 300 m north of B, heading east (so the link from B ends with a right turn).
#[test]
fn a_goal_with_a_heading_is_reached_on_it() {
    let (t, _, bytes) = blocked_corner();
    let mut p: Box<SmallPlanner<'_>> = Box::new(Planner::new());
    p.load(&bytes).unwrap();
    let start = CORNER_START;
    let goal = Vec2::new(3500.0, 3300.0);
    let mut query = query_to(start, goal);
    query.goal.heading = Some(0.0);
    let r = p.plan(&query, u64::MAX);
    assert!(r.is_ok(), "{r:?}");
    let problems = route_problems(p.route(), start, goal, &t);
    assert!(problems.is_empty(), "{problems:#?}");
    let last = p.route().last().unwrap();
    let arrival = last.pose_at(last.length()).heading;
    assert!(angle_diff(arrival, 0.0) < 1e-2, "arrives heading {arrival}");
}

/// Finding: `terrain_plan_work_bound` (src/planner/work.rs) charges each turn-arc check
/// `cells_per_turn` cells, but `fillet_is_clear` also tests the arc against every active
/// pop-up (up to `P·(MAX_POPUP_VERTICES + 1)` collision tests per arc), which the bound leaves
/// out. With 16 polygon pop-ups (away from everything), a ring network whose every turn gets
/// checked runs out of a budget of `worst_case_work()` before the search ends (it would end
/// with `NoRoute`: the goal's only node is not connected to the ring).
#[test]
fn turn_arc_popup_tests_are_within_the_work_bound() {
    std::thread::Builder::new()
        .stack_size(64 << 20)
        .spawn(|| {
            let mut t = Terrain::new(Vec2::new(0.0, 0.0), 500.0, 20, 20);
            // A wall between the start and the goal, off the ring.
            t.block(1500.0, 0.0, 2000.0, 2000.0);
            let (centre, radius, n) = (Vec2::new(5000.0, 5000.0), 3000.0f32, 3000u32);
            let mut nodes: Vec<Vec2> = (0..n)
                .map(|k| {
                    let a = std::f32::consts::TAU * k as f32 / n as f32;
                    centre + Vec2::from_angle(a) * radius
                })
                .collect();
            let mut edges = Vec::new();
            for k in 0..n {
                edges.push(chord(&nodes, k, (k + 1) % n));
                edges.push(chord(&nodes, (k + 1) % n, k));
            }
            // An isolated node next to the goal.
            nodes.push(Vec2::new(1200.0, 1000.0));
            let bytes = network(&t, &nodes, &edges, 100.0, Vec::new()).unwrap();
            let mut p: Box<RingPlanner<'_>> = Box::new(Planner::new());
            p.load(&bytes).unwrap();
            p.set_config(PlannerConfig {
                goal_candidates: 1,
                ..PlannerConfig::DEFAULT
            });
            for i in 0..16 {
                let c = Vec2::new(9700.0 - 120.0 * i as f32, 9700.0);
                let mut poly = heapless::Vec::new();
                for k in 0..16 {
                    let a = std::f32::consts::TAU * k as f32 / 16.0;
                    poly.push(c + Vec2::from_angle(a) * 50.0).unwrap();
                }
                p.add_popup(Popup::Polygon(poly)).unwrap();
            }
            let start = Pose::new(8000.0, 4990.0, std::f32::consts::FRAC_PI_2);
            let goal = Vec2::new(1000.0, 1000.0);
            let q = query_to(start, goal);
            for turn_rule in [TurnRule::Paper, TurnRule::SharedEqually] {
                p.set_config(PlannerConfig {
                    goal_candidates: 1,
                    turn_rule,
                    ..PlannerConfig::DEFAULT
                });
                assert_eq!(p.plan(&q, u64::MAX), Err(PlanError::NoRoute));
                let stats = p.arc_check_stats();
                let bound = p.worst_case_work();
                let r = p.plan(&q, bound);
                assert_eq!(
                    r,
                    Err(PlanError::NoRoute),
                    "{turn_rule:?}: budget worst_case_work() = {bound}; {} turn arcs checked, \
                     each against 16 pop-ups of 16 vertices",
                    stats.arcs
                );
            }
            // A planner whose `V` holds the edges but not the transitions plans with the equal
            // split and refuses the paper's rule by name (needs |E| + T + 2·Ks + 1 + Σ outdeg).
            let mut small: Box<Planner<'_, 8192, 8192, 16, 512>> = Box::new(Planner::new());
            small.load(&bytes).unwrap();
            for (turn_rule, expected) in [
                (TurnRule::SharedEqually, Err(PlanError::NoRoute)),
                (
                    TurnRule::Paper,
                    Err(PlanError::TooManySearchStates {
                        needed: 6000 + 12000 + 2 * 8 + 1 + 8 * 2,
                        capacity: 8192,
                    }),
                ),
            ] {
                small.set_config(PlannerConfig {
                    goal_candidates: 1,
                    turn_rule,
                    ..PlannerConfig::DEFAULT
                });
                assert_eq!(small.plan(&q, u64::MAX), expected, "{turn_rule:?}");
            }
        })
        .unwrap()
        .join()
        .unwrap();
}

/// Finding: a terrain network may carry static obstacles (the loader does not refuse them).
/// Connections test them (`path_is_clear`), but `terrain_plan_work_bound` has no term for them,
/// so many far-away obstacles make a query count more than `worst_case_work()`.
#[test]
fn terrain_network_obstacles_are_refused_or_within_the_work_bound() {
    let t = corridor(-900.0);
    let nodes = [Vec2::new(0.0, 0.0), Vec2::new(700.0, 0.0)];
    let edges = [chord(&nodes, 0, 1), chord(&nodes, 1, 0)];
    let obstacles = (0..40_000)
        .map(|i| ObstacleSpec::Circle {
            centre: Vec2::new(-900.0 + 0.04 * i as f32, -900.0),
            radius: 1.0,
        })
        .collect();
    let Ok(bytes) = network(&t, &nodes, &edges, 100.0, obstacles) else {
        return; // refused: fine
    };
    let mut p: Box<SmallPlanner<'_>> = Box::new(Planner::new());
    if p.load(&bytes).is_err() {
        return;
    }
    let start = Pose::new(-300.0, 0.0, 0.0);
    let goal = Vec2::new(1200.0, 0.0);
    let summary = p.plan(&query_to(start, goal), u64::MAX).unwrap();
    let bound = p.worst_case_work();
    assert!(
        summary.work.total() <= bound,
        "counted {} > worst_case_work() {bound}: {:?}",
        summary.work.total(),
        summary.work
    );
}

/// Finding: static obstacles in a terrain network are ignored by the search: network edges are
/// not checked against them at load, and `fillet_is_clear` tests turn arcs against pop-ups
/// only. A disc on the only edge is flown straight through.
#[test]
fn terrain_network_obstacles_are_refused_or_avoided() {
    let t = corridor(-900.0);
    let nodes = [Vec2::new(0.0, 0.0), Vec2::new(900.0, 0.0)];
    let edges = [chord(&nodes, 0, 1), chord(&nodes, 1, 0)];
    let disc = (Vec2::new(450.0, 0.0), 30.0f32);
    let obstacles = vec![ObstacleSpec::Circle {
        centre: disc.0,
        radius: disc.1,
    }];
    let Ok(bytes) = network(&t, &nodes, &edges, 100.0, obstacles) else {
        return;
    };
    let mut p: Box<SmallPlanner<'_>> = Box::new(Planner::new());
    if p.load(&bytes).is_err() {
        return;
    }
    p.set_config(PlannerConfig {
        connect_radius_m: 300.0,
        ..PlannerConfig::DEFAULT
    });
    let start = Pose::new(-200.0, 0.0, 0.0);
    let goal = Vec2::new(1100.0, 0.0);
    if p.plan(&query_to(start, goal), u64::MAX).is_err() {
        return;
    }
    for prim in p.route() {
        let n = prim.length().ceil().max(1.0) as u32;
        for k in 0..=n {
            let q = prim.pose_at(prim.length() * k as f32 / n as f32).position;
            assert!(
                q.distance(disc.0) > disc.1,
                "route passes {q:?}, inside the static obstacle at {:?}",
                disc.0
            );
        }
    }
}

/// A start exactly on a node: `DubinsPath::turn_then_straight` to the start's own position is
/// degenerate (its turn circle passes through the target, so rounding gives no path or a full
/// loop), so the planner links such a start to its node by a path of length 0 that leaves
/// along the start heading. Here the only node within the connect radius is the one the
/// aircraft sits on, heading along its edge (at three offsets, for the f32 rounding of the
/// heading): the route follows the edges, with no loop, about as long as the polyline.
#[test]
fn start_exactly_on_a_node_needs_no_loop() {
    for offset in [
        Vec2::new(0.0, 0.0),
        Vec2::new(13.7, 21.9),
        Vec2::new(-7.31, 4.45),
    ] {
        let mut t = Terrain::new(Vec2::new(-1000.0, -1000.0), 50.0, 90, 60);
        // Blocks every direct way from A to the goal under the corner B.
        t.block(
            800.0 + offset.x,
            -600.0 + offset.y,
            2200.0 + offset.x,
            500.0 + offset.y,
        );
        let nodes = [
            offset,
            offset + Vec2::new(1500.0, 1500.0),
            offset + Vec2::new(3000.0, 0.0),
        ];
        let edges = [
            chord(&nodes, 0, 1),
            chord(&nodes, 1, 0),
            chord(&nodes, 1, 2),
            chord(&nodes, 2, 1),
        ];
        let bytes = network(&t, &nodes, &edges, 100.0, Vec::new()).unwrap();
        let mut p: Box<SmallPlanner<'_>> = Box::new(Planner::new());
        p.load(&bytes).unwrap();
        let d = nodes[1] - nodes[0];
        let start = Pose {
            position: nodes[0],
            heading: d.angle(),
        };
        let goal = offset + Vec2::new(3300.0, -300.0);
        let r = p.plan(&query_to(start, goal), u64::MAX);
        assert!(r.is_ok(), "start on node 0 at {offset:?}: {r:?}");
        let problems = route_problems(p.route(), start, goal, &t);
        assert!(problems.is_empty(), "{problems:#?}");
        let polyline =
            nodes[0].distance(nodes[1]) + nodes[1].distance(nodes[2]) + nodes[2].distance(goal);
        let length = r.unwrap().length;
        assert!(
            length <= polyline,
            "start on node 0 at {offset:?}: route {length} m, the polyline is {polyline} m \
             (a loop at the start?)"
        );
    }
}

/// A terrain planner needs one search state per directed edge and one per start link
/// (`|E| + MAX_LINKS`): with exactly that many it loads and plans the corner route; with one
/// fewer it is refused, naming both counts, and keeps the network it had.
#[test]
fn a_planner_with_exactly_the_terrain_states_loads_and_one_fewer_is_refused() {
    let mut t = Terrain::new(Vec2::new(-1500.0, -1500.0), 100.0, 60, 60);
    t.block(500.0, 500.0, 2500.0, 2500.0);
    let (nodes, edges) = corner();
    let bytes = network(&t, &nodes, &edges, 100.0, Vec::new()).unwrap();
    const NEEDED: usize = 4 + MAX_LINKS;
    let start = Pose::new(-500.0, 0.0, 0.0);
    let goal = Vec2::new(3000.0, 3001.0);

    let mut exact: Box<Planner<'_, NEEDED, 64, 4, 64>> = Box::new(Planner::new());
    exact.load(&bytes).unwrap();
    let r = exact.plan(&query_to(start, goal), u64::MAX);
    assert!(r.is_ok(), "{NEEDED} states: {r:?}");
    assert!(route_problems(exact.route(), start, goal, &t).is_empty());

    let mut short: Box<Planner<'_, { NEEDED - 1 }, 64, 4, 64>> = Box::new(Planner::new());
    assert_eq!(
        short.load(&bytes),
        Err(LoadError::TooManySearchStates {
            needed: NEEDED,
            capacity: NEEDED - 1
        })
    );
    assert_eq!(
        short.network().vertex_count(),
        0,
        "the empty network is kept"
    );
}

/// An edge is usable while the highest code under its band is below the blocking code: one
/// cell under it at exactly [`BLOCKING`] makes it (and its reverse) unusable, one code lower
/// leaves it usable; the other edges are unaffected.
#[test]
fn an_edge_over_one_cell_at_the_blocking_code_is_unusable_and_one_code_lower_is_not() {
    let (nodes, edges) = corner();
    for (code, usable) in [(BLOCKING, false), (BLOCKING - 1, true)] {
        let mut t = Terrain::new(Vec2::new(-1500.0, -1500.0), 100.0, 60, 60);
        for y in [-50.0, 50.0] {
            let (c, r) = t.grid.cell_of(Vec2::new(1550.0, y)).unwrap();
            t.codes[(r * t.grid.cols + c) as usize] = code;
        }
        let bytes = network(&t, &nodes, &edges, 100.0, Vec::new()).unwrap();
        let mut p: Box<SmallPlanner<'_>> = Box::new(Planner::new());
        p.load(&bytes).unwrap();
        p.set_altitude(ALTITUDE, 0.0).unwrap();
        let got: Vec<bool> = (0..4).map(|e| p.is_edge_usable(e)).collect();
        assert_eq!(got, [usable, usable, true, true], "code {code}");
    }
}
