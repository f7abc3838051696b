//! Terrain mode (Medeiros & da Silva): a turn-feasible Dijkstra over (previous node, node)
//! states of the visibility graph, with every turn arc checked against the elevation grid while
//! the search runs.
//!
//! # The route model: 1-trajectories
//! A route is the polyline start → v₁ → … → vₙ → goal whose corners are rounded by arcs of the
//! turn radius `r`. The turn at node `v` between the unit directions `u_in` and `u_out`, by the
//! angle `θ ∈ [0, π)`, is the *1-trajectory* line – arc – line: the arc is tangent to both
//! lines at the distance `c = r·tan(θ/2)` from `v` (computed as `r·|u_in × u_out| / (1 + u_in·u_out)`,
//! the half-angle identity `tan(θ/2) = sin θ / (1 + cos θ)`), and replaces a corner of length `2c`
//! by an arc of length `r·θ`. It fits between its neighbours (the paper's equations 1 and 2)
//! when `c` is at most the share of each adjacent straight that this turn may use. Each straight
//! between two nodes is shared equally by the turns at its two ends (`c ≤ ℓ/2`), which makes
//! the condition local to one transition, as a Dijkstra over (previous node, node) states
//! needs. The start's straight (after its initial turn, see below) has a turn only at its far
//! end, which may use all of it. The goal's straight is shared equally too, although it has
//! no turn at the goal, so that every step of the search adds a non-negative cost:
//! `ℓ_out − 2c + r·θ ≥ ℓ_out − 2c ≥ 0`, which Dijkstra's stopping rule needs.
//!
//! # States and costs
//! A state is a directed edge `(u → v)` of the network (index `e < |E|`), or start link `k`
//! (index `|E| + k`): "arrived at `v` along this straight". Its cost is the length flown from
//! the start to `v` counting the last straight to `v` whole; a transition to `(v → w)` adds
//! `ℓ(v, w) − 2c + r·θ`. A transition is kept only if the edge is enabled (no pop-up, its
//! highest elevation code below the altitude's blocking code), `w ≠ u`, `c` fits both
//! straights, and the arc — within the widening (half the wingspan plus the clearance) — meets
//! no blocked cell: [`arc_cells`] visits every cell within that distance of the arc, provably
//! (see `geometry::grid`), in O(cells touched), whatever the number of blocked cells. The
//! straights themselves lie on edges whose whole band was checked ([`Network`] validates each
//! edge's highest code at load).
//!
//! # Start and goal
//! The start pose connects to a node by turning left or right on radius `r` until it heads at
//! the node, then flying straight ([`DubinsPath::turn_then_straight`]). A goal without a
//! heading is reached by a straight from the last node; one with a heading by a straight and a
//! final arc (the reverse of a turn-then-straight from the goal flown backwards). The direct
//! start–goal path is tried as well. Every connection primitive is checked against the grid
//! ([`primitive_cells`]) and the pop-ups.
//!
//! [`Network`]: crate::network::Network

use super::heap::ItemState;
use super::search::{Arrival, Ends};
use super::state::{ArcCheckStats, ModeState};
use super::work::{cells_bound, TerrainBoundInputs};
use super::{
    Goal, Link, Meter, Phase, PlanError, Planner, Query, QueryField, RouteSummary, Work, MAX_LINKS,
};
use super::{MAX_CANDIDATES, MAX_POPUP_VERTICES};
use crate::geometry::grid::{arc_cells, primitive_cells, CellGrid};
use crate::geometry::{Arc, DubinsPath, DubinsWord, Pose, Primitive, Turn, Vec2};
use core::f32::consts::{PI, TAU};

/// `via` of a start-link state: no previous state.
const NO_PREVIOUS: u32 = u32::MAX;

/// A start or goal within this many metres of a node is on it: the start leaves the node along
/// its own heading (a link of length 0, whose first turn may cut at most this far), and a
/// free-heading goal is reached by arriving at the node (no turn).
const ON_NODE_M: f32 = 1e-3;

/// Whether `p` is on node position `node` ([`ON_NODE_M`], plus the f32 rounding of their
/// coordinates).
fn on_node(p: Vec2, node: Vec2) -> bool {
    p.distance(node) <= ON_NODE_M + 1e-6 * (libm::fabsf(node.x) + libm::fabsf(node.y))
}

/// The direction a goal link leaves its node in: its own, or — for a free-heading goal on the
/// node (a straight of length 0) — the direction the route arrives in, so that arriving at the
/// node is arriving at the goal, with no turn.
fn goal_direction(at: &Arrived, link: &DubinsPath) -> Vec2 {
    let on_node = link.lengths[0] == 0.0 && link.lengths[2] == 0.0 && link.lengths[1] <= ON_NODE_M;
    if on_node {
        at.direction
    } else {
        Vec2::from_angle(link.start.heading)
    }
}

/// The rounding of one corner.
#[derive(Clone, Copy, Debug)]
struct Fillet {
    /// Distance from the node to each tangent point, `r·tan(θ/2)`.
    cut: f32,
    /// Turn angle `θ`, radians in `[0, π]`.
    angle: f32,
    /// Turn direction.
    turn: Turn,
}

impl Fillet {
    /// The fillet of radius `r` between unit directions `u_in` and `u_out`.
    fn new(u_in: Vec2, u_out: Vec2, r: f32) -> Self {
        let cross = u_in.cross(u_out);
        let dot = u_in.dot(u_out);
        let angle = libm::atan2f(libm::fabsf(cross), dot);
        // A (near) reversal has no room to turn: `1 + dot` near 0 would give a cut of 0 for
        // directions a rounding short of unit length, so turns within 10⁻³ rad of π are refused.
        let cut = if angle < PI - 1e-3 && 1.0 + dot > 1e-6 {
            r * libm::fabsf(cross) / (1.0 + dot)
        } else {
            f32::INFINITY
        };
        let turn = if cross >= 0.0 {
            Turn::Left
        } else {
            Turn::Right
        };
        Fillet { cut, angle, turn }
    }

    /// What the fillet changes in the length flown: `r·θ − 2c` (never positive).
    fn saving(&self, r: f32) -> f32 {
        r * self.angle - 2.0 * self.cut
    }

    /// The arc at node `v` entered along `u_in`, or `None` for a straight pass.
    fn arc(&self, v: Vec2, u_in: Vec2, r: f32) -> Option<Arc> {
        if !(self.angle * r > 0.0) || !self.cut.is_finite() {
            return None;
        }
        let entry = v - u_in * self.cut;
        let pose = Pose {
            position: entry,
            heading: u_in.angle(),
        };
        Some(Arc::from_pose(&pose, self.turn, r, self.angle))
    }
}

/// A state's node, the unit direction it arrived along, the share of that straight a turn at
/// the node may use, and the node it came from (`None` for a start link).
#[derive(Clone, Copy, Debug)]
struct Arrived {
    node: u32,
    position: Vec2,
    direction: Vec2,
    share: f32,
    from: Option<u32>,
}

impl<'n, const V: usize, const E: usize, const P: usize, const R: usize> Planner<'n, V, E, P, R> {
    /// Terrain mode: sets the flight altitude and the safety height kept above the terrain.
    /// Cells whose stored elevation bound is at least `altitude_m − safety_height_m` become
    /// blocked, and so does every edge whose band reaches such a cell. Work: O(1) — the stored
    /// elevation codes are compared with the new blocking code as the search reads them
    /// (`network::elevation`). Non-finite values are refused (the setting is kept).
    pub fn set_altitude(&mut self, altitude_m: f32, safety_height_m: f32) -> Result<(), PlanError> {
        let ModeState::Terrain(t) = &mut self.state else {
            return Err(PlanError::NotTerrainNetwork);
        };
        if !(altitude_m.is_finite() && safety_height_m.is_finite() && safety_height_m >= 0.0) {
            return Err(PlanError::InvalidAltitude);
        }
        t.altitude = Some((altitude_m, safety_height_m));
        t.blocking = t.blocking_code(&self.network);
        Ok(())
    }

    /// Terrain mode: the altitude and safety height in force (those the network was built for
    /// until [`Planner::set_altitude`]); `None` for other networks.
    pub fn altitude(&self) -> Option<(f32, f32)> {
        match &self.state {
            ModeState::Terrain(t) => t.altitude(&self.network),
            _ => None,
        }
    }

    /// Terrain mode: cells (and edges) with an elevation code at or above this are blocked
    /// (0 for other networks).
    pub fn blocking_code(&self) -> u8 {
        match &self.state {
            ModeState::Terrain(t) => t.blocking,
            _ => 0,
        }
    }

    /// Terrain mode: the turn-arc checks of the last query.
    pub fn arc_check_stats(&self) -> ArcCheckStats {
        match &self.state {
            ModeState::Terrain(t) => t.arc_stats,
            _ => ArcCheckStats::default(),
        }
    }

    /// Terrain mode: the inputs of [`terrain_plan_work_bound`](super::work::terrain_plan_work_bound) for the loaded network and the
    /// configuration. Work: O(|V| + |E|) (degrees are counted from the CSR offsets and targets).
    pub fn terrain_bound_inputs(&self) -> TerrainBoundInputs {
        let net = &self.network;
        let (v, e) = (net.vertex_count(), net.edge_count());
        let mut transitions = 0u64;
        let mut max_out = 0u64;
        // indeg(v)·outdeg(v) summed = Σ over edges of outdeg(target).
        for i in 0..e {
            if let Some((_, target)) = net.edge_cost_target(i) {
                transitions += net.out_edges(target).len() as u64;
            }
        }
        for i in 0..v {
            max_out = max_out.max(net.out_edges(i).len() as u64);
        }
        let (turn_cells, connection_cells) = match (net.terrain(), net.terrain_grid()) {
            (Some(t), Some(g)) => {
                let cell = g.cell;
                let r = net.turn_radius();
                let widen = t.widen_m / cell;
                let diagonal = libm::sqrtf(
                    (g.cols as f32) * (g.cols as f32) + (g.rows as f32) * (g.rows as f32),
                );
                // Every traversed primitive lies inside the grid (checked first), so a straight
                // is at most its diagonal, whatever the connect radius.
                let line = diagonal;
                let full_turn = TAU * r / cell;
                (
                    cells_bound(PI * r / cell, widen),
                    cells_bound(line.max(full_turn), widen),
                )
            }
            _ => (0, 0),
        };
        TerrainBoundInputs {
            vertices: v as u64,
            edges: e as u64,
            transitions,
            max_out_degree: max_out,
            popups: P as u64,
            popup_vertices: MAX_POPUP_VERTICES as u64,
            candidates: MAX_CANDIDATES as u64,
            start_links: self.config().start_links() as u64,
            goal_links: self.config().goal_links() as u64,
            cells_per_turn: turn_cells,
            cells_per_connection: connection_cells,
        }
    }

    /// Terrain mode's [`Planner::plan`], after the query's numbers were checked.
    pub(super) fn plan_terrain(
        &mut self,
        query: &Query,
        meter: &mut Meter,
        observe: &mut dyn FnMut(Phase, &Work),
    ) -> Result<RouteSummary, PlanError> {
        if let ModeState::Terrain(t) = &mut self.state {
            t.arc_stats = ArcCheckStats::default();
        }
        observe(Phase::CheckFree, &meter.work);
        self.check_over_terrain(query.start.position, QueryField::Start, meter)?;
        self.check_over_terrain(query.goal.position, QueryField::Goal, meter)?;
        self.check_free(query.start.position, QueryField::Start, meter)?;
        self.check_free(query.goal.position, QueryField::Goal, meter)?;
        observe(Phase::ConnectStart, &meter.work);
        self.connect_terrain_start(&query.start, meter)?;
        observe(Phase::ConnectGoal, &meter.work);
        self.connect_terrain_goal(&query.goal, meter)?;
        observe(Phase::ConnectDirect, &meter.work);
        // Always tried: its check is bounded by the grid, not by the connect radius.
        let direct = self.direct_terrain_path(&query.start, &query.goal, meter)?;
        if self.start_links.is_empty() && direct.is_none() {
            return Err(PlanError::StartUnconnected);
        }
        if self.goal_links.is_empty() && direct.is_none() {
            return Err(PlanError::GoalUnconnected);
        }
        let direct = direct.map(|p| (p.length(), p));
        observe(Phase::Search, &meter.work);
        let arrival = self.search(query, Ends::Links, direct, meter)?;
        observe(Phase::Route, &meter.work);
        self.write_terrain_route(arrival, meter)
    }

    /// Rejects a start or goal over a blocked (or unknown) cell.
    fn check_over_terrain(
        &self,
        p: Vec2,
        field: QueryField,
        meter: &mut Meter,
    ) -> Result<(), PlanError> {
        meter.work.cells_visited += 1;
        let grid = self.network.terrain_grid().ok_or(PlanError::Internal)?;
        let code = match grid.cell_of(p) {
            Some((c, r)) => self.network.elevation_code(c, r),
            None => crate::network::elevation::ELEVATION_BLOCKED,
        };
        if code >= self.blocking_code() {
            return Err(PlanError::OverBlockedTerrain { field });
        }
        Ok(())
    }

    /// Whether `prim`'s band (the widening about it) lies inside the grid and meets no blocked
    /// cell; counts the cells visited.
    pub(super) fn primitive_over_free_terrain(&self, prim: &Primitive, meter: &mut Meter) -> bool {
        let (Some(grid), Some(t)) = (self.network.terrain_grid(), self.network.terrain()) else {
            return false;
        };
        let (lo, hi) = prim.bounding_box();
        let w = Vec2::new(t.widen_m, t.widen_m);
        if !grid.covers(lo - w, hi + w) {
            return false;
        }
        let blocking = self.blocking_code();
        let mut clear = true;
        let visited = primitive_cells(&grid, prim, t.widen_m, |c, r| {
            clear = self.network.elevation_code(c, r) < blocking;
            clear
        });
        match visited {
            Ok(n) => {
                meter.work.cells_visited += n;
                clear
            }
            Err(_) => false,
        }
    }

    /// Whether every primitive of `path` is over free terrain and clear of the pop-ups.
    fn terrain_path_is_clear(&self, path: &DubinsPath, meter: &mut Meter) -> bool {
        self.path_is_clear(path, meter)
    }

    /// Start links: a left and a right turn-then-straight to each of the nearest nodes, until
    /// [`PlannerConfig::start_candidates`](super::PlannerConfig) links are found.
    fn connect_terrain_start(&mut self, start: &Pose, meter: &mut Meter) -> Result<(), PlanError> {
        self.start_links.clear();
        let candidates = self.nearest_vertices(start.position, meter)?;
        let wanted = self.config().start_links();
        let r = self.network.turn_radius();
        for &(_, v) in &candidates {
            let target = self.network.vertex(v).ok_or(PlanError::Internal)?.position;
            if on_node(start.position, target) && self.start_links.len() < wanted {
                // On the node: leave it along the start heading, without a loop.
                let path = DubinsPath {
                    start: *start,
                    radius: r,
                    word: DubinsWord::Lsl,
                    lengths: [0.0; 3],
                };
                let _ = self.start_links.push(Link {
                    vertex: v,
                    path,
                    cost: 0.0,
                    pending: false,
                });
                continue;
            }
            for turn in [Turn::Left, Turn::Right] {
                if self.start_links.len() >= wanted {
                    return Ok(());
                }
                meter.work.dubins_solves += 1;
                let Some(path) = DubinsPath::turn_then_straight(start, r, target, turn) else {
                    continue;
                };
                if self.terrain_path_is_clear(&path, meter) {
                    let _ = self.start_links.push(Link {
                        vertex: v,
                        path,
                        cost: path.length(),
                        pending: false,
                    });
                }
                meter.check()?;
            }
        }
        Ok(())
    }

    /// The paths from node position `from` to the goal: a straight for a free heading; for a
    /// fixed one, a straight and a final left or right arc.
    fn goal_paths(&self, from: Vec2, goal: &Goal) -> [Option<DubinsPath>; 2] {
        let r = self.network.turn_radius();
        match goal.heading {
            None => {
                let d = goal.position - from;
                let straight = DubinsPath {
                    start: Pose {
                        position: from,
                        heading: d.angle(),
                    },
                    radius: r,
                    word: DubinsWord::Lsl,
                    lengths: [0.0, d.norm(), 0.0],
                };
                [Some(straight), None]
            }
            Some(h) => {
                // Flown backwards from the goal: turn, then straight to the node.
                let back = Pose {
                    position: goal.position,
                    heading: h + PI,
                };
                [Turn::Left, Turn::Right].map(|turn| {
                    let rev = DubinsPath::turn_then_straight(&back, r, from, turn)?;
                    let heading = rev.end().heading + PI;
                    // Reversed, a left turn is flown clockwise: the last arc turns the other way.
                    let word = match turn {
                        Turn::Left => DubinsWord::Lsr,
                        Turn::Right => DubinsWord::Rsl,
                    };
                    Some(DubinsPath {
                        start: Pose {
                            position: from,
                            heading,
                        },
                        radius: r,
                        word,
                        lengths: [0.0, rev.lengths[1], rev.lengths[0]],
                    })
                })
            }
        }
    }

    /// Goal links from the nearest nodes, until
    /// [`PlannerConfig::goal_candidates`](super::PlannerConfig) are found.
    fn connect_terrain_goal(&mut self, goal: &Goal, meter: &mut Meter) -> Result<(), PlanError> {
        self.goal_links.clear();
        let candidates = self.nearest_vertices(goal.position, meter)?;
        let wanted = self.config().goal_links();
        for &(_, v) in &candidates {
            let from = self.network.vertex(v).ok_or(PlanError::Internal)?.position;
            for path in self.goal_paths(from, goal).into_iter().flatten() {
                if self.goal_links.len() >= wanted {
                    return Ok(());
                }
                meter.work.dubins_solves += 1;
                if self.terrain_path_is_clear(&path, meter) {
                    let _ = self.goal_links.push(Link {
                        vertex: v,
                        path,
                        cost: path.length(),
                        pending: false,
                    });
                }
                meter.check()?;
            }
        }
        Ok(())
    }

    /// The shortest clear path straight from the start to the goal, if any: a turn and a
    /// straight for a free goal heading, a Dubins path for a fixed one.
    fn direct_terrain_path(
        &self,
        start: &Pose,
        goal: &Goal,
        meter: &mut Meter,
    ) -> Result<Option<DubinsPath>, PlanError> {
        let r = self.network.turn_radius();
        let candidates: [Option<DubinsPath>; 2] = match goal.heading {
            None => [Turn::Left, Turn::Right]
                .map(|t| DubinsPath::turn_then_straight(start, r, goal.position, t)),
            Some(h) => {
                let end = Pose {
                    position: goal.position,
                    heading: h,
                };
                [DubinsPath::shortest(start, &end, r), None]
            }
        };
        let mut best: Option<DubinsPath> = None;
        for path in candidates.into_iter().flatten() {
            meter.work.dubins_solves += 1;
            if best.is_none_or(|b| path.length() < b.length())
                && self.terrain_path_is_clear(&path, meter)
            {
                best = Some(path);
            }
            meter.check()?;
        }
        Ok(best)
    }

    /// Where search state `s` stands.
    fn arrived(&self, s: u32) -> Result<Arrived, PlanError> {
        let edges = self.network.edge_count();
        if s < edges {
            let e = self.network.edge(s).ok_or(PlanError::Internal)?;
            let from = self.network.vertex(e.source).ok_or(PlanError::Internal)?;
            let to = self.network.vertex(e.target).ok_or(PlanError::Internal)?;
            let length = e.lengths[1];
            if !(length > 0.0) {
                return Err(PlanError::Internal);
            }
            Ok(Arrived {
                node: e.target,
                position: to.position,
                direction: (to.position - from.position) * (1.0 / length),
                share: 0.5 * length,
                from: Some(e.source),
            })
        } else {
            let link = self
                .start_links
                .get((s - edges) as usize)
                .ok_or(PlanError::Internal)?;
            let position = self
                .network
                .vertex(link.vertex)
                .ok_or(PlanError::Internal)?
                .position;
            Ok(Arrived {
                node: link.vertex,
                position,
                direction: Vec2::from_angle(link.path.end().heading),
                share: link.path.lengths[1],
                from: None,
            })
        }
    }

    /// Whether the turn arc of `fillet` at the state's node is over free terrain; records the
    /// cells visited.
    fn fillet_is_clear(&mut self, at: &Arrived, fillet: &Fillet, meter: &mut Meter) -> bool {
        let r = self.network.turn_radius();
        let Some(arc) = fillet.arc(at.position, at.direction, r) else {
            return true;
        };
        let (Some(grid), Some(t)) = (self.network.terrain_grid(), self.network.terrain()) else {
            return false;
        };
        let before = meter.work.cells_visited;
        let clear = self.arc_over_free_terrain(&grid, t.widen_m, &arc, meter);
        let cells = meter.work.cells_visited - before;
        if let ModeState::Terrain(t) = &mut self.state {
            t.arc_stats.arcs += 1;
            t.arc_stats.cells += cells;
            t.arc_stats.most_cells = t.arc_stats.most_cells.max(cells);
        }
        clear && {
            // The arc must also keep clear of the pop-ups.
            let prim = Primitive::Arc(arc);
            self.popups().all(|(_, p)| {
                let (conflict, tests) = p.conflicts(&prim, self.network.clearance());
                meter.work.collision_tests += tests as u64;
                !conflict
            })
        }
    }

    fn arc_over_free_terrain(
        &self,
        grid: &CellGrid,
        widen: f32,
        arc: &Arc,
        meter: &mut Meter,
    ) -> bool {
        let (lo, hi) = Primitive::Arc(*arc).bounding_box();
        let w = Vec2::new(widen, widen);
        if !grid.covers(lo - w, hi + w) {
            return false;
        }
        let blocking = self.blocking_code();
        let mut clear = true;
        match arc_cells(grid, arc, widen, |c, r| {
            clear = self.network.elevation_code(c, r) < blocking;
            clear
        }) {
            Ok(n) => {
                meter.work.cells_visited += n;
                clear
            }
            Err(_) => false,
        }
    }

    /// Queues the start links' states (`|E| + k`) at the links' lengths.
    #[inline(never)]
    pub(super) fn seed_edge_states(&mut self, meter: &mut Meter) -> Result<(), PlanError> {
        let edges = self.network.edge_count();
        for k in 0..self.start_links.len() {
            let s = edges + k as u32;
            let Some(cost) = self.start_links.get(k).map(|link| link.path.length()) else {
                return Err(PlanError::Internal);
            };
            let (Some(d), Some(via)) =
                (self.dist.get_mut(s as usize), self.via.get_mut(s as usize))
            else {
                return Err(PlanError::Internal);
            };
            *d = cost;
            *via = NO_PREVIOUS;
            meter.work.heap_steps += self.heap.push_or_decrease(s, cost) as u64;
        }
        Ok(())
    }

    /// Expands state `s` (popped at cost `ds`): offers the goal links leaving its node, turn
    /// checked, to `best`, and relaxes the transitions to the node's usable out-edges whose
    /// turn fits and is clear (the turn is checked only for a transition that would improve
    /// its target). Returns `false`: an edge-state search has no target state.
    #[inline(never)]
    pub(super) fn expand_edge_state(
        &mut self,
        s: u32,
        ds: f32,
        best: &mut Option<(f32, Arrival)>,
        meter: &mut Meter,
    ) -> Result<bool, PlanError> {
        let r = self.network.turn_radius();
        let at = self.arrived(s)?;
        meter.work.vertex_scans += 1;
        for k in 0..self.goal_links.len() {
            meter.work.relaxations += 1;
            let link = self.goal_links[k];
            if link.vertex != at.node {
                continue;
            }
            let out = goal_direction(&at, &link.path);
            let fillet = Fillet::new(at.direction, out, r);
            let on_goal = out == at.direction;
            if fillet.cut > at.share.max(ON_NODE_M)
                || (!on_goal && fillet.cut > 0.5 * link.path.lengths[1])
            {
                continue;
            }
            let total = ds + link.path.length() + fillet.saving(r);
            if best.is_none_or(|(b, _)| total < b) && self.fillet_is_clear(&at, &fillet, meter) {
                *best = Some((total, Arrival::FromState { state: s, link: k }));
            }
        }
        let node = self
            .network
            .vertex(at.node)
            .ok_or(PlanError::Internal)?
            .position;
        for e in self.network.out_edges(at.node) {
            meter.work.relaxations += 1;
            if !self.is_edge_usable_from(at.node, e) {
                continue;
            }
            // The line from this node to the edge's target, as `Network::edge` measures it.
            let (_, target) = self
                .network
                .edge_cost_target(e)
                .ok_or(PlanError::Internal)?;
            if Some(target) == at.from {
                continue;
            }
            let to = self
                .network
                .vertex(target)
                .ok_or(PlanError::Internal)?
                .position;
            let length = node.distance(to);
            if !(length > 0.0) {
                continue;
            }
            let out = (to - at.position) * (1.0 / length);
            let fillet = Fillet::new(at.direction, out, r);
            // A start link of length 0 (a start on the node) allows only a turn of no cut.
            if fillet.cut > at.share.max(ON_NODE_M) || fillet.cut > 0.5 * length {
                continue;
            }
            let candidate = ds + length + fillet.saving(r);
            let state = self.heap.state(e);
            let improves = state == ItemState::Unseen
                || (state == ItemState::Queued
                    && self.dist.get(e as usize).is_some_and(|d| candidate < *d));
            if !improves || !self.fillet_is_clear(&at, &fillet, meter) {
                continue;
            }
            let (Some(de), Some(via)) =
                (self.dist.get_mut(e as usize), self.via.get_mut(e as usize))
            else {
                return Err(PlanError::Internal);
            };
            *de = candidate;
            *via = s;
            meter.work.heap_steps += self.heap.push_or_decrease(e, candidate) as u64;
        }
        Ok(false)
    }

    /// Walks the route of `arrival` back from the goal, calling `visit` with each path (goal
    /// end first): the leg after each node starts at its turn's entry point with the turn arc,
    /// then the straight to the next turn's entry (then, to a goal with a heading, the final
    /// arc). Returns the number of network edges on the route.
    fn walk_terrain_route(
        &self,
        arrival: &Arrival,
        meter: &mut Meter,
        visit: &mut dyn FnMut(&DubinsPath),
    ) -> Result<u32, PlanError> {
        let (state, link) = match *arrival {
            Arrival::Direct(p) => {
                visit(&p);
                return Ok(0);
            }
            Arrival::FromState { state, link } => (state, link),
            Arrival::AtVertex => return Err(PlanError::Internal),
        };
        let r = self.network.turn_radius();
        let link = *self.goal_links.get(link).ok_or(PlanError::Internal)?;
        let edges = self.network.edge_count();
        // The leg leaving the state's node: turn, straight of `straight`, and a last arc.
        let leg = |at: &Arrived, fillet: &Fillet, straight: f32, last: Option<(Turn, f32)>| {
            let first = fillet.turn;
            let (third, third_len) = last.unwrap_or((first, 0.0));
            let word = match (first, third) {
                (Turn::Left, Turn::Left) => DubinsWord::Lsl,
                (Turn::Right, Turn::Right) => DubinsWord::Rsr,
                (Turn::Left, Turn::Right) => DubinsWord::Lsr,
                (Turn::Right, Turn::Left) => DubinsWord::Rsl,
            };
            DubinsPath {
                start: Pose {
                    position: at.position - at.direction * fillet.cut,
                    heading: at.direction.angle(),
                },
                radius: r,
                word,
                lengths: [r * fillet.angle, straight.max(0.0), third_len],
            }
        };

        let mut at = self.arrived(state)?;
        let goal_out = goal_direction(&at, &link.path);
        let fillet = Fillet::new(at.direction, goal_out, r);
        let last = (link.path.lengths[2] > 0.0)
            .then(|| (link.path.word.letters().2, link.path.lengths[2]));
        visit(&leg(&at, &fillet, link.path.lengths[1] - fillet.cut, last));
        let mut next_cut = fillet.cut;
        // States form a tree over at most |E| + Ks states.
        self.walk_states(state, edges + MAX_LINKS as u32, meter, |s| {
            if s >= edges {
                // A start link: its straight ends where the first turn begins.
                let start = self
                    .start_links
                    .get((s - edges) as usize)
                    .ok_or(PlanError::Internal)?;
                let mut path = start.path;
                path.lengths[1] = (path.lengths[1] - next_cut).max(0.0);
                visit(&path);
                return Ok(None);
            }
            let previous = *self.via.get(s as usize).ok_or(PlanError::Internal)?;
            if previous == NO_PREVIOUS {
                return Err(PlanError::Internal);
            }
            let before = self.arrived(previous)?;
            let fillet = Fillet::new(before.direction, at.direction, r);
            let length = 2.0 * at.share;
            visit(&leg(&before, &fillet, length - fillet.cut - next_cut, None));
            next_cut = fillet.cut;
            at = before;
            Ok(Some(previous))
        })
    }

    /// Replaces the route with the one `arrival` describes, if it fits in `R` paths and `R`
    /// primitives; otherwise leaves it untouched.
    fn write_terrain_route(
        &mut self,
        arrival: Arrival,
        meter: &mut Meter,
    ) -> Result<RouteSummary, PlanError> {
        self.write_path_route(meter, true, |me, meter, visit| {
            me.walk_terrain_route(&arrival, meter, visit)
        })
    }
}
