//! A* with an inertia term (Ruz et al. eqs 19–21) on a regular grid in the local frame.
//!
//! The grid covers the start and the goal with a margin. A cell is free when its centre keeps
//! the clearance from every disc and no-fly zone; a move joins the centres of two free cells
//! (8 neighbours, or 16 with the knight's moves) and is allowed when the whole straight piece
//! keeps the clearance (the keep-out areas are inflated by it, `super::check`). The search
//! state is (cell, direction of the move into it), and a move costs (metres)
//!
//! `g = ℓ + λ·|Δψ| + μ₂·v·D`
//!
//! with ℓ its length, λ the inertia (metres per radian of direction change between the move
//! and the one before it, eq. 20: a turn costs as much as λ·angle metres of flight), and D the
//! risk model's kill probability of the piece (eq. 22 for one piece: `p_k·(ℓ/v)/Δt·(1 −
//! Π_j (1 − P_t,j))`, P_t at its middle on its heading) weighed by μ₂ (seconds per unit,
//! as the MILP's) at the nominal speed v. The heuristic is the straight-line distance to the
//! goal's cell (eq. 21), a lower bound of every term's sum, so A* is exact. The start and the
//! goal are joined to the nearest free cells by straight pieces.

use super::check::segment_intrusion;
use super::{Problem, Pt, StaticRoute};
use skyroute::planner::risk::detection_at;
use skyroute::Pose;
use std::cmp::Reverse;
use std::collections::BinaryHeap;

/// The 16 moves: the 8 neighbours first, then the knight's moves.
pub const MOVES: [(i32, i32); 16] = [
    (1, 0),
    (1, 1),
    (0, 1),
    (-1, 1),
    (-1, 0),
    (-1, -1),
    (0, -1),
    (1, -1),
    (2, 1),
    (1, 2),
    (-1, 2),
    (-2, 1),
    (-2, -1),
    (-1, -2),
    (1, -2),
    (2, -1),
];

/// A*'s settings.
#[derive(Clone, Debug, PartialEq)]
pub struct AstarOptions {
    /// The side of a cell, metres.
    pub cell_m: f64,
    /// 8 or 16 moves per cell.
    pub connectivity: usize,
    /// λ, metres per radian of direction change.
    pub inertia: f64,
    /// μ₂, seconds per unit of kill probability (0: no detection cost).
    pub risk_weight: f64,
    /// How far the grid reaches beyond the start's and goal's box, metres.
    pub margin_m: f64,
}

impl Default for AstarOptions {
    fn default() -> Self {
        Self {
            cell_m: 250.0,
            connectivity: 16,
            inertia: 500.0,
            risk_weight: 10_000.0,
            margin_m: 15_000.0,
        }
    }
}

/// The grid: cells `(col, row)` of side `cell` from `origin` (the lower left corner).
#[derive(Clone, Debug)]
pub struct Grid {
    /// Lower left corner, local metres.
    pub origin: Pt,
    /// Side of a cell, metres.
    pub cell: f64,
    /// Columns.
    pub cols: usize,
    /// Rows.
    pub rows: usize,
    free: Vec<bool>,
}

impl Grid {
    /// The grid of `problem` with `o`'s cell and margin (free cells as the module says).
    pub fn new(problem: &Problem, o: &AstarOptions) -> Grid {
        let (a, b) = (problem.start, problem.goal);
        let origin = Pt::new(a.x.min(b.x) - o.margin_m, a.y.min(b.y) - o.margin_m);
        let cols = (((a.x - b.x).abs() + 2.0 * o.margin_m) / o.cell_m).ceil() as usize + 1;
        let rows = (((a.y - b.y).abs() + 2.0 * o.margin_m) / o.cell_m).ceil() as usize + 1;
        let mut g = Grid {
            origin,
            cell: o.cell_m,
            cols,
            rows,
            free: Vec::new(),
        };
        g.free = (0..cols * rows)
            .map(|i| {
                let c = g.centre(i);
                segment_intrusion(problem, problem.clearance, c, c).is_none_or(|w| w.0 <= 0.0)
            })
            .collect();
        g
    }

    /// The centre of cell index `i` (`row·cols + col`).
    pub fn centre(&self, i: usize) -> Pt {
        let (c, r) = (i % self.cols, i / self.cols);
        Pt::new(
            self.origin.x + (c as f64 + 0.5) * self.cell,
            self.origin.y + (r as f64 + 0.5) * self.cell,
        )
    }

    /// Whether cell `i` is free.
    pub fn is_free(&self, i: usize) -> bool {
        self.free.get(i).copied().unwrap_or(false)
    }

    /// The cell reached from `i` by `MOVES[m]`, if on the grid.
    pub fn step(&self, i: usize, m: usize) -> Option<usize> {
        let (dc, dr) = MOVES[m];
        let c = (i % self.cols) as i64 + dc as i64;
        let r = (i / self.cols) as i64 + dr as i64;
        (c >= 0 && r >= 0 && (c as usize) < self.cols && (r as usize) < self.rows)
            .then(|| r as usize * self.cols + c as usize)
    }

    /// Whether the move `MOVES[m]` from `i` is allowed: both cells free and the straight piece
    /// keeping the clearance.
    pub fn allowed(&self, problem: &Problem, i: usize, m: usize) -> Option<usize> {
        let j = self.step(i, m)?;
        (self.is_free(i) && self.is_free(j) && clear(problem, self.centre(i), self.centre(j)))
            .then_some(j)
    }

    /// The free cell nearest `p` that `p` reaches by a straight piece keeping the clearance.
    pub fn nearest_free(&self, problem: &Problem, p: Pt) -> Option<usize> {
        (0..self.free.len())
            .filter(|&i| self.is_free(i))
            .map(|i| (self.centre(i).dist(p), i))
            .filter(|&(d, i)| d <= 2.0 * self.cell && clear(problem, p, self.centre(i)))
            .min_by(|a, b| a.0.total_cmp(&b.0))
            .map(|x| x.1)
    }
}

/// Whether the piece `a`–`b` keeps the clearance from every keep-out area.
fn clear(problem: &Problem, a: Pt, b: Pt) -> bool {
    segment_intrusion(problem, problem.clearance, a, b).is_none_or(|w| w.0 <= 0.0)
}

/// An A* route and its search.
#[derive(Clone, Debug, PartialEq)]
pub struct AstarRoute {
    /// The route start → cell centres → goal, timed at the nominal speed.
    pub route: StaticRoute,
    /// The cells visited.
    pub cells: Vec<usize>,
    /// The search's cost of the cell path (eq. 19), metres.
    pub cost: f64,
    /// States expanded.
    pub expanded: usize,
    /// Direction changes along the cell path.
    pub direction_changes: usize,
    /// The sum of |Δψ| along the cell path, radians.
    pub total_turn: f64,
}

/// The angle between moves `a` and `b`, radians in [0, π].
pub fn turn_angle(a: usize, b: usize) -> f64 {
    let ang = |m: usize| (MOVES[m].1 as f64).atan2(MOVES[m].0 as f64);
    let d = (ang(b) - ang(a)).rem_euclid(std::f64::consts::TAU);
    d.min(std::f64::consts::TAU - d)
}

/// The detection cost μ₂·v·D of the straight piece `a`–`b` (module documentation), metres.
fn detection_cost(problem: &Problem, o: &AstarOptions, a: Pt, b: Pt) -> f64 {
    if o.risk_weight <= 0.0 || problem.radars.is_empty() {
        return 0.0;
    }
    let d = b.minus(a);
    let pose = Pose {
        position: a.plus(d.scale(0.5)).vec2(),
        heading: d.y.atan2(d.x) as f32,
    };
    let unseen: f64 = problem
        .radars
        .iter()
        .map(|r| 1.0 - detection_at(&problem.params, &pose, r.vec2()) as f64)
        .product();
    let p = &problem.params;
    let kill = p.kill_per_step as f64 * (d.norm() / problem.v_nominal) / p.dt_s as f64;
    o.risk_weight * problem.v_nominal * kill * (1.0 - unseen)
}

/// Plans start → goal by A* (module documentation); `None` when no path exists.
pub fn plan(problem: &Problem, o: &AstarOptions) -> Option<AstarRoute> {
    let grid = Grid::new(problem, o);
    plan_on(problem, &grid, o)
}

/// A* on a given grid.
pub fn plan_on(problem: &Problem, grid: &Grid, o: &AstarOptions) -> Option<AstarRoute> {
    let moves = o.connectivity.clamp(8, 16);
    let first = grid.nearest_free(problem, problem.start)?;
    let last = grid.nearest_free(problem, problem.goal)?;
    let target = grid.centre(last);
    let dirs = moves + 1; // the last: no move yet
    let n = grid.cols * grid.rows * dirs;
    let (mut g, mut parent) = (vec![f64::INFINITY; n], vec![usize::MAX; n]);
    let mut move_cost = vec![f64::NAN; grid.cols * grid.rows * moves];
    let mut heap = BinaryHeap::new();
    let s0 = first * dirs + moves;
    g[s0] = 0.0;
    heap.push((Reverse(Key(grid.centre(first).dist(target))), s0));
    let mut expanded = 0;
    let mut done = None;
    while let Some((Reverse(Key(f)), s)) = heap.pop() {
        let (cell, dir) = (s / dirs, s % dirs);
        if f > g[s] + grid.centre(cell).dist(target) + 1e-9 {
            continue;
        }
        expanded += 1;
        if cell == last {
            done = Some(s);
            break;
        }
        for m in 0..moves {
            let slot = cell * moves + m;
            if move_cost[slot].is_nan() {
                move_cost[slot] = grid.allowed(problem, cell, m).map_or(f64::INFINITY, |j| {
                    let (a, b) = (grid.centre(cell), grid.centre(j));
                    a.dist(b) + detection_cost(problem, o, a, b)
                });
            }
            let Some(j) = grid.step(cell, m).filter(|_| move_cost[slot].is_finite()) else {
                continue;
            };
            // eq. 20: the inertia term charges the change of direction.
            let turn = if dir == moves {
                0.0
            } else {
                turn_angle(dir, m)
            };
            let cost = g[s] + move_cost[slot] + o.inertia * turn;
            let t = j * dirs + m;
            if cost < g[t] {
                g[t] = cost;
                parent[t] = s;
                heap.push((Reverse(Key(cost + grid.centre(j).dist(target))), t));
            }
        }
    }
    let end = done?;
    let mut states = vec![end];
    while let Some(&p) = states
        .last()
        .map(|&s| &parent[s])
        .filter(|&&p| p != usize::MAX)
    {
        states.push(p);
    }
    states.reverse();
    Some(route_of(problem, grid, &states, dirs, g[end], expanded))
}

/// The route of a state path.
fn route_of(
    problem: &Problem,
    grid: &Grid,
    states: &[usize],
    dirs: usize,
    cost: f64,
    expanded: usize,
) -> AstarRoute {
    let cells: Vec<usize> = states.iter().map(|s| s / dirs).collect();
    let moves: Vec<usize> = states.iter().skip(1).map(|s| s % dirs).collect();
    let direction_changes = moves.windows(2).filter(|w| w[0] != w[1]).count();
    let total_turn = moves.windows(2).map(|w| turn_angle(w[0], w[1])).sum();
    let mut points = vec![problem.start];
    points.extend(cells.iter().map(|&c| grid.centre(c)));
    points.push(problem.goal);
    points.dedup_by(|a, b| a.dist(*b) < 1e-9);
    let mut times = vec![0.0];
    for w in points.windows(2) {
        let t = times.last().copied().unwrap_or(0.0) + w[0].dist(w[1]) / problem.v_nominal;
        times.push(t);
    }
    AstarRoute {
        route: StaticRoute { points, times },
        cells,
        cost,
        expanded,
        direction_changes,
        total_turn,
    }
}

/// A heap key ordered by `total_cmp`.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Key(f64);

impl Eq for Key {}

impl PartialOrd for Key {
    fn partial_cmp(&self, other: &Self) -> Option<std::cmp::Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for Key {
    fn cmp(&self, other: &Self) -> std::cmp::Ordering {
        self.0.total_cmp(&other.0)
    }
}
