//! The terrain search (Dijkstra over its turn rule's states) against a second algorithm: on
//! small random terrain networks, a depth-first enumeration of whole walks — start turn and
//! straight, node turns, final straight — with branch and bound, costing each walk in f64 with
//! its own fillet formula (`r·tan(θ/2)` from the turn angle, not the planner's half-angle
//! identity) and each turn rule's feasibility written out on the walk: under the paper's rule
//! (equations 1–2) the cuts at the two ends of every straight sum to at most its length (the
//! start straight's whole length for the first turn, the goal straight's for the last); under
//! the equal split every cut is within half of each node-to-node straight (the whole start
//! straight, half the goal straight); every edge usable at the altitude, every turn arc and
//! connection over free cells. The cheapest walk must cost what the planner's route measures,
//! the planner must find a route exactly when a walk exists, and its route must be one
//! continuous curve (a straight shorter than its two cuts would leave a gap).

use host_tests::{cases, Rng};
use skyroute::geometry::grid::{arc_cells, primitive_cells, CellGrid};
use skyroute::network::elevation::ElevationCoding;
use skyroute::network::write::{encode, EdgeSpec, NetworkSpec, TerrainSpec};
use skyroute::planner::{Goal, PlanError, PlannerConfig, Query, Search, TurnRule};
use skyroute::{Arc, DubinsPath, Planner, Pose, Primitive, Turn, Vec2};

const CELL: f32 = 50.0;
const N: u32 = 60;
const RADIUS: f32 = 250.0;
const WIDEN: f32 = 20.0;
const FREE: u8 = 10;
const HIGH: u8 = 200;
/// Flight altitude 150 m, safety height 0: codes ≥ 150 (coding base 0, step 1) are blocked.
const ALTITUDE: f32 = 150.0;

struct Case {
    bytes: Vec<u8>,
    nodes: Vec<Vec2>,
    codes: Vec<u8>,
    grid: CellGrid,
}

fn case(rng: &mut Rng) -> Case {
    let grid = CellGrid::new(Vec2::new(0.0, 0.0), CELL, N, N);
    let mut codes = vec![FREE; (N * N) as usize];
    // Random rectangular hills.
    for _ in 0..6 {
        let (c0, r0) = (
            rng.below(N as u64 - 8) as u32 + 4,
            rng.below(N as u64 - 8) as u32 + 4,
        );
        let (w, h) = (rng.below(8) as u32 + 2, rng.below(8) as u32 + 2);
        for r in r0..(r0 + h).min(N) {
            for c in c0..(c0 + w).min(N) {
                codes[(r * N + c) as usize] = HIGH;
            }
        }
    }
    let blocked_near = |p: Vec2| {
        let mut hit = false;
        primitive_cells(
            &grid,
            &Primitive::Line(skyroute::Segment::new(p, p)),
            WIDEN,
            |c, r| {
                hit = codes[(r * N + c) as usize] >= 150;
                !hit
            },
        )
        .unwrap();
        hit
    };
    let mut nodes = Vec::new();
    while nodes.len() < 7 {
        let p = Vec2::new(
            rng.range(300.0, 2700.0) as f32,
            rng.range(300.0, 2700.0) as f32,
        );
        if !blocked_near(p) && nodes.iter().all(|q: &Vec2| q.distance(p) > 150.0) {
            nodes.push(p);
        }
    }
    // Every ordered pair is an edge; those over blocked cells are pruned by their stored code.
    let mut edges = Vec::new();
    for i in 0..nodes.len() {
        for j in 0..nodes.len() {
            if i != j && rng.unit() < 0.8 {
                edges.push(EdgeSpec::line(
                    i as u32,
                    j as u32,
                    nodes[i].distance(nodes[j]),
                ));
            }
        }
    }
    let spec = NetworkSpec {
        origin_lat_deg: 36.5,
        origin_lon_deg: -84.2,
        turn_radius_m: RADIUS,
        clearance_m: WIDEN,
        vertices: nodes
            .iter()
            .map(|&p| Pose {
                position: p,
                heading: 0.0,
            })
            .collect(),
        edges,
        obstacles: Vec::new(),
        // Pop-up index cells of 100 m: a diagonal edge meets far fewer of them than its
        // bounding box overlaps, so the pop-up test below checks the exact listing.
        grid_cell_m: 100.0,
        landmark: None,
        voronoi: None,
        terrain: Some(TerrainSpec {
            grid,
            coding: ElevationCoding {
                base_m: 0.0,
                step_m: 1.0,
            },
            codes: codes.clone(),
            widen_m: WIDEN,
            altitude_m: ALTITUDE,
            safety_height_m: 0.0,
        }),
        provenance: Vec::new(),
    };
    Case {
        bytes: encode(&spec).unwrap(),
        nodes,
        codes,
        grid,
    }
}

/// The brute force's own view of feasibility: primitive over free cells (inside the grid).
fn clear(case: &Case, prim: &Primitive) -> bool {
    let (lo, hi) = prim.bounding_box();
    let w = Vec2::new(WIDEN, WIDEN);
    if !case.grid.covers(lo - w, hi + w) {
        return false;
    }
    let mut ok = true;
    primitive_cells(&case.grid, prim, WIDEN, |c, r| {
        ok = case.codes[(r * N + c) as usize] < 150;
        ok
    })
    .unwrap();
    ok
}

fn path_clear(case: &Case, path: &DubinsPath) -> bool {
    path.primitives()
        .into_iter()
        .flatten()
        .all(|p| clear(case, &p))
}

/// A turn at `v` from direction `a` to direction `b` (unit, f64): (cut, angle, left).
fn fillet(a: (f64, f64), b: (f64, f64), r: f64) -> (f64, f64, bool) {
    let cross = a.0 * b.1 - a.1 * b.0;
    let dot = a.0 * b.0 + a.1 * b.1;
    let angle = cross.abs().atan2(dot);
    ((angle / 2.0).tan() * r, angle, cross >= 0.0)
}

/// Whether the fillet's arc is over free cells (built from f32 like the route would be).
fn fillet_clear(case: &Case, v: Vec2, a: (f64, f64), cut: f64, angle: f64, left: bool) -> bool {
    if angle * RADIUS as f64 <= 1e-6 {
        return true;
    }
    let entry = Vec2::new(
        (v.x as f64 - a.0 * cut) as f32,
        (v.y as f64 - a.1 * cut) as f32,
    );
    let pose = Pose {
        position: entry,
        heading: a.1.atan2(a.0) as f32,
    };
    let turn = if left { Turn::Left } else { Turn::Right };
    let arc = Arc::from_pose(&pose, turn, RADIUS, angle as f32);
    let (lo, hi) = Primitive::Arc(arc).bounding_box();
    let w = Vec2::new(WIDEN, WIDEN);
    if !case.grid.covers(lo - w, hi + w) {
        return false;
    }
    let mut ok = true;
    arc_cells(&case.grid, &arc, WIDEN, |c, r| {
        ok = case.codes[(r * N + c) as usize] < 150;
        ok
    })
    .unwrap();
    ok
}

struct Search2<'a> {
    case: &'a Case,
    rule: TurnRule,
    edge_ok: Vec<Vec<bool>>,
    goal: Vec2,
    goal_ok: Vec<bool>,
    best: f64,
    walks: u64,
}

fn dir(a: Vec2, b: Vec2) -> ((f64, f64), f64) {
    let (dx, dy) = (b.x as f64 - a.x as f64, b.y as f64 - a.y as f64);
    let l = dx.hypot(dy);
    ((dx / l, dy / l), l)
}

impl Search2<'_> {
    /// At node `v`, arrived along `a` with `share` of the straight usable by the turn at `v`,
    /// `cost` so far (the straight counted to `v`), from node `from`; `depth` edges so far.
    /// Any walk on flies at least `cost − share` (up to the turn's entry).
    fn walk(
        &mut self,
        v: usize,
        a: (f64, f64),
        share: f64,
        cost: f64,
        from: Option<usize>,
        depth: u32,
    ) {
        self.walks += 1;
        if cost - share >= self.best || depth > 14 {
            return;
        }
        let p = self.case.nodes[v];
        if self.goal_ok[v] {
            let (b, l) = dir(p, self.goal);
            let (cut, angle, left) = fillet(a, b, RADIUS as f64);
            let goal_room = match self.rule {
                TurnRule::Paper => l,
                TurnRule::SharedEqually => 0.5 * l,
            };
            if cut <= share && cut <= goal_room && fillet_clear(self.case, p, a, cut, angle, left) {
                let total = cost + l - 2.0 * cut + RADIUS as f64 * angle;
                self.best = self.best.min(total);
            }
        }
        for w in 0..self.case.nodes.len() {
            if w == v || Some(w) == from || !self.edge_ok[v][w] {
                continue;
            }
            let (b, l) = dir(p, self.case.nodes[w]);
            let (cut, angle, left) = fillet(a, b, RADIUS as f64);
            // The room the next straight leaves: the paper's `ℓ − c` (eq. 1–2), or half.
            let (cap, room) = match self.rule {
                TurnRule::Paper => (l, l - cut),
                TurnRule::SharedEqually => (0.5 * l, 0.5 * l),
            };
            if cut > share || cut > cap || !fillet_clear(self.case, p, a, cut, angle, left) {
                continue;
            }
            let next = cost + l - 2.0 * cut + RADIUS as f64 * angle;
            self.walk(w, b, room, next, Some(v), depth + 1);
        }
    }
}

#[test]
fn dijkstra_under_each_turn_rule_matches_an_exhaustive_walk_search() {
    let mut rng = Rng(11);
    let (mut routed, mut none) = (0, 0);
    let (mut paper_only, mut paper_shorter) = (0, 0);
    let mut walks = 0;
    for k in 0..150 {
        let c = case(&mut rng);
        let net = skyroute::Network::from_bytes(&c.bytes).unwrap();
        let blocking = net.elevation_coding().unwrap().blocking_code(ALTITUDE, 0.0);
        let n = c.nodes.len();
        let mut edge_ok = vec![vec![false; n]; n];
        for e in 0..net.edge_count() {
            let edge = net.edge(e).unwrap();
            edge_ok[edge.source as usize][edge.target as usize] =
                net.edge_highest_code(e).unwrap() < blocking;
        }
        // Start and goal over free cells.
        let free_point = |rng: &mut Rng| loop {
            let p = Vec2::new(
                rng.range(200.0, 2800.0) as f32,
                rng.range(200.0, 2800.0) as f32,
            );
            let (col, row) = c.grid.cell_of(p).unwrap();
            if c.codes[(row * N + col) as usize] < 150 {
                return p;
            }
        };
        let start = Pose {
            position: free_point(&mut rng),
            heading: rng.range(0.0, std::f64::consts::TAU) as f32,
        };
        let goal = free_point(&mut rng);
        // Goal links: straight from a node, its band clear.
        let goal_ok: Vec<bool> = c
            .nodes
            .iter()
            .map(|&p| {
                p.distance(goal) > 0.0
                    && clear(&c, &Primitive::Line(skyroute::Segment::new(p, goal)))
            })
            .collect();
        let mut bests = [f64::INFINITY; 2];
        for (which, rule) in [TurnRule::Paper, TurnRule::SharedEqually]
            .into_iter()
            .enumerate()
        {
            let (best, n_walks) = brute_force(&c, rule, &edge_ok, &goal_ok, &start, goal);
            walks += n_walks;
            bests[which] = best;
            check_planner(&c, rule, &start, goal, best, k, &mut routed, &mut none);
        }
        // The paper's rule is the weaker condition: never costlier, and sometimes cheaper or
        // the only one to route.
        assert!(bests[0] <= bests[1] + 1e-9, "case {k}: {bests:?}");
        if bests[0].is_finite() && !bests[1].is_finite() {
            paper_only += 1;
        } else if bests[0] < bests[1] - 1e-6 {
            paper_shorter += 1;
        }
    }
    eprintln!(
        "{routed} routed, {none} without a route, {walks} walks enumerated; the paper's rule \
         alone routes {paper_only} cases and is shorter in {paper_shorter}"
    );
    assert!(routed >= 40 && none >= 2);
    assert!(paper_only + paper_shorter >= 1);
}

/// The cheapest walk under `rule` (infinite if none) and the walks enumerated.
fn brute_force(
    c: &Case,
    rule: TurnRule,
    edge_ok: &[Vec<bool>],
    goal_ok: &[bool],
    start: &Pose,
    goal: Vec2,
) -> (f64, u64) {
    let mut s = Search2 {
        case: c,
        rule,
        edge_ok: edge_ok.to_vec(),
        goal,
        goal_ok: goal_ok.to_vec(),
        best: f64::INFINITY,
        walks: 0,
    };
    // The direct path, then every start link.
    for turn in [Turn::Left, Turn::Right] {
        if let Some(p) = DubinsPath::turn_then_straight(start, RADIUS, goal, turn) {
            if path_clear(c, &p) {
                s.best = s.best.min(p.length() as f64);
            }
        }
    }
    for v in 0..c.nodes.len() {
        for turn in [Turn::Left, Turn::Right] {
            let Some(p) = DubinsPath::turn_then_straight(start, RADIUS, c.nodes[v], turn) else {
                continue;
            };
            if !path_clear(c, &p) {
                continue;
            }
            let h = p.end().heading as f64;
            s.walk(
                v,
                (h.cos(), h.sin()),
                p.lengths[1] as f64,
                p.length() as f64,
                None,
                0,
            );
        }
    }
    (s.best, s.walks)
}

/// Plans case `k` under `rule` and checks the answer against the brute force's `best`.
#[allow(clippy::too_many_arguments)]
fn check_planner(
    c: &Case,
    rule: TurnRule,
    start: &Pose,
    goal: Vec2,
    best: f64,
    k: usize,
    routed: &mut u32,
    none: &mut u32,
) {
    let mut planner: Box<Planner<'_, 1024, 128, 2, 64>> = Box::new(Planner::new());
    planner.load(&c.bytes).unwrap();
    planner.set_config(PlannerConfig {
        start_candidates: 16,
        goal_candidates: 16,
        connect_radius_m: f32::INFINITY,
        free_goal_headings: 36,
        turn_rule: rule,
    });
    let q = Query {
        start: *start,
        goal: Goal {
            position: goal,
            heading: None,
        },
        search: Search::Dijkstra,
    };
    match planner.plan(&q, u64::MAX) {
        Ok(summary) => {
            *routed += 1;
            assert!(
                best.is_finite(),
                "case {k} {rule:?}: the planner routes ({}) where no walk exists",
                summary.length
            );
            let tol = 1e-4 * best + 0.05;
            assert!(
                (summary.length as f64 - best).abs() <= tol,
                "case {k} {rule:?}: planner {} vs exhaustive {}",
                summary.length,
                best
            );
            // One curve: where two cuts overran their straight, the arcs would not meet.
            for w in planner.route().windows(2) {
                let (a, b) = (w[0].pose_at(w[0].length()), w[1].pose_at(0.0));
                assert!(
                    a.position.distance(b.position) < 0.05,
                    "case {k} {rule:?}: gap {a:?} {b:?}"
                );
            }
            assert!(summary.work.total() <= planner.worst_case_work());
        }
        Err(e) => {
            *none += 1;
            assert!(
                !best.is_finite(),
                "case {k} {rule:?}: planner {e:?} but a walk of {best} exists"
            );
            assert!(matches!(
                e,
                PlanError::NoRoute | PlanError::StartUnconnected | PlanError::GoalUnconnected
            ));
        }
    }
}

/// Pop-ups on terrain networks disable exactly the line edges that come within the clearance
/// of the disc, compared with an f64 scan of every edge (segment–point distance). Half the
/// pop-ups are large and anywhere; half are small (1–20 m) and placed beside a random edge
/// within 15 m of its clearance boundary, so that the pop-up's box meets only one or two index
/// cells of 100 m: the grid index lists each edge only in the cells its segment meets, and a
/// cell missing there leaves an edge enabled that the scan blocks.
#[test]
fn popups_disable_exactly_the_terrain_edges_they_reach() {
    let mut rng = Rng(5);
    let (mut blocked_total, mut near_blocked) = (0, 0);
    for _ in 0..cases(40, 400) {
        let c = case(&mut rng);
        let net = skyroute::Network::from_bytes(&c.bytes).unwrap();
        let mut planner: Box<Planner<'_, 128, 128, 2, 64>> = Box::new(Planner::new());
        planner.load(&c.bytes).unwrap();
        for k in 0..10 {
            let (centre, radius) = if k % 2 == 0 {
                let centre = Vec2::new(
                    rng.range(500.0, 2500.0) as f32,
                    rng.range(500.0, 2500.0) as f32,
                );
                (centre, rng.range(5.0, 400.0) as f32)
            } else {
                let edge = net.edge(rng.below(net.edge_count() as u64) as u32).unwrap();
                let a = net.vertex(edge.source).unwrap().position;
                let b = net.vertex(edge.target).unwrap().position;
                let on = a + (b - a) * rng.unit() as f32;
                let radius = rng.range(1.0, 20.0);
                let (ux, uy) = rng.unit_vector();
                let d = radius + WIDEN as f64 + rng.range(-15.0, 15.0);
                let centre = on + Vec2::new((ux * d) as f32, (uy * d) as f32);
                (centre, radius as f32)
            };
            let summary = planner
                .add_popup(skyroute::Popup::Circle { centre, radius })
                .unwrap();
            for e in 0..net.edge_count() {
                let edge = net.edge(e).unwrap();
                let (a, b) = (
                    net.vertex(edge.source).unwrap().position,
                    net.vertex(edge.target).unwrap().position,
                );
                // f64 distance from the centre to the segment.
                let (ax, ay, bx, by) = (a.x as f64, a.y as f64, b.x as f64, b.y as f64);
                let (px, py) = (centre.x as f64, centre.y as f64);
                let (dx, dy) = (bx - ax, by - ay);
                let t = (((px - ax) * dx + (py - ay) * dy) / (dx * dx + dy * dy)).clamp(0.0, 1.0);
                let d = (ax + t * dx - px).hypot(ay + t * dy - py);
                let limit = (radius + WIDEN) as f64;
                if (d - limit).abs() < 1e-2 {
                    continue; // within rounding of the boundary: either answer is right
                }
                assert_eq!(
                    !planner.is_edge_enabled(e),
                    d < limit,
                    "edge {e}: distance {d}, radius + clearance {limit}, pop-up {k}"
                );
                blocked_total += (d < limit) as u32;
                near_blocked += (d < limit && k % 2 == 1) as u32;
            }
            planner.remove_popup(summary.id).unwrap();
        }
    }
    eprintln!(
        "{blocked_total} edges disabled by pop-ups, all as the scan says; {near_blocked} of them \
         by the small pop-ups beside an edge"
    );
    assert!(blocked_total > 20 && near_blocked > 20);
}
