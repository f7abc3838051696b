//! Terrain mode (Medeiros & da Silva): a turn-feasible Dijkstra over straights of the
//! visibility graph, with every turn arc checked against the elevation grid while the search
//! runs.
//!
//! # The route model: 1-trajectories
//! A route is the polyline start → v₁ → … → vₙ → goal whose corners are rounded by arcs of the
//! turn radius `r`. The turn at node `v` between the unit directions `u_in` and `u_out`, by the
//! angle `θ ∈ [0, π)`, is the *1-trajectory* line – arc – line: the arc is tangent to both
//! lines at the distance `c = r·tan(θ/2)` from `v` (computed as `r·|u_in × u_out| / (1 + u_in·u_out)`,
//! the half-angle identity `tan(θ/2) = sin θ / (1 + cos θ)`), and replaces a corner of length `2c`
//! by an arc of length `r·θ` ([`Fillet`]). The turns fit between their neighbours when, on every
//! straight of length `ℓᵢ` between the turns at its two ends, the cuts `cᵢ₋₁` (at its start)
//! and `cᵢ` (at its end) leave room for both. Which room is the query's
//! [`TurnRule`](crate::planner::TurnRule):
//!
//! * [`Paper`](crate::planner::TurnRule::Paper), the paper's equations 1–2: `cᵢ₋₁ + cᵢ ≤ ℓᵢ`;
//!   consecutive turns share each straight as they need.
//! * [`SharedEqually`](crate::planner::TurnRule::SharedEqually): `cᵢ₋₁ ≤ ℓᵢ/2` and
//!   `cᵢ ≤ ℓᵢ/2`; each straight is split equally between its two turns. Stricter (it refuses
//!   some feasible routes), but its states are the directed edges alone.
//!
//! A start link's straight (after its initial turn, see below) has a turn only at its far end,
//! which may use all of it (`c₁ ≤ ℓ`) under both rules; the goal link's straight has no turn
//! at the goal (`cₙ ≤ ℓ` under the paper's rule, `cₙ ≤ ℓ/2` under the equal split).
//!
//! # States ([`states`])
//! A state is "arrived at the end `v` of straight `i`, with `sᵢ` of its start given to the turn
//! at its start `u`": under the equal split `sᵢ = ℓᵢ/2` whatever the turn at `u` was, so the
//! state is the directed edge `(u → v)` alone (index `e < |E|`, then start link `k` at
//! `|E| + k`, with `s = 0`). Under the paper's rule `sᵢ = cᵢ₋₁`, the cut the turn at `u`
//! really used, which depends on the straight before: the state is the pair (straight before,
//! edge `u → v`) — a *transition* of the graph — plus the start links. The pair fixes `cᵢ₋₁`,
//! so whether a next turn fits (`cᵢ ≤ ℓᵢ − cᵢ₋₁`), what it costs and whether its arc is clear
//! depend on the state alone: one label per state is exact, and Dijkstra over these states
//! finds the shortest route of 1-trajectories that satisfies equations 1–2 at every straight
//! (on the graph's node sequences without an immediate reversal `w = u`). One label per
//! directed edge would not be: a costlier arrival with a smaller cut can enable a turn the
//! cheaper one cannot.
//!
//! Memory: the paper's rule needs `S = (|E| + Ks + 1) + Ks + T + Σₖ outdeg(vₖ)` search states,
//! `T = Σ_v indeg(v)·outdeg(v)` (the first `|E| + Ks + 1` entries of the planner's `via` hold
//! the table of each straight's first pair state; no other memory). On the Jacksboro networks:
//! the 4 084-edge network of the STM32F405 firmware has `T` = 38 424, where its `V` holds 4 416
//! states, so it plans with the equal split; the default 32 222-edge network needs `S` = 947 143
//! (`skyroute info`), about 19 MB of planner on the host, beyond the 1 MiB board. A planner
//! whose `V` is too small for a query under the paper's rule refuses it with
//! [`PlanError::TooManySearchStates`](crate::planner::PlanError::TooManySearchStates).
//!
//! # Costs, and why every step is non-negative
//! A state's key is the length flown from the start to the point at `kᵢ` along its straight
//! from `u`: under the equal split its end (`kᵢ = ℓᵢ`, the straight counted whole to `v`),
//! under the paper's rule the end of the turn at `u` (`kᵢ = cᵢ₋₁`). A transition to the edge
//! `(v → w)` of length `ℓₒ`, with the turn of cut `c` and angle `θ` at `v`, adds
//!
//! `(ℓᵢ − kᵢ) + kₒ + r·θ − 2c`,
//!
//! never negative when the turn fits, as Dijkstra's stopping rule needs (no route through a
//! state is shorter than its key): under the equal split it is `ℓₒ − 2c + r·θ ≥ ℓₒ − 2c ≥ 0`
//! (`c ≤ ℓₒ/2`); under the paper's rule `(ℓᵢ − cᵢ₋₁ − c) + r·θ ≥ 0` (`c ≤ ℓᵢ − cᵢ₋₁`, eq. 1–2),
//! the straight flown between the two turns and the arc. A goal link of length `L` (its
//! straight and final arc) adds `(ℓᵢ − kᵢ) + L + r·θ − 2c ≥ 0` likewise. The equal split's
//! accounting would not do for the paper's rule: `ℓₒ − 2c + r·θ` is negative once
//! `c > ℓₒ/2`. The paper's accounting would do for the equal split, but its keys are lower
//! (a weaker stopping bound): on the full Jacksboro network's P → Q it counted 702 820 units
//! of work where the equal split's keys count 388 396.
//!
//! A transition is kept only if the edge is enabled (no pop-up, its highest elevation code
//! below the altitude's blocking code), `w ≠ u`, the turn fits, and the arc — within the
//! widening (half the wingspan plus the clearance) — meets no blocked cell: [`arc_cells`]
//! visits every cell within that distance of the arc, provably (see `geometry::grid`), in
//! O(cells touched), whatever the number of blocked cells. The straights themselves lie on
//! edges whose whole band was checked ([`Network`] validates each edge's highest code at load).
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
//! [`DubinsPath::turn_then_straight`]: crate::geometry::DubinsPath::turn_then_straight

mod connect;
mod fillet;
mod route;
pub(super) mod states;
#[cfg(all(test, feature = "std"))]
mod tests;

use super::state::{ArcCheckStats, ModeState};
use super::work::{cells_bound, TerrainBoundInputs};
use super::{Meter, Phase, PlanError, Planner, Query, QueryField, Work};
use super::{MAX_CANDIDATES, MAX_POPUP_VERTICES};
use crate::geometry::grid::{arc_cells, primitive_cells, CellGrid};
use crate::geometry::DubinsPath;
use crate::geometry::{Arc, Primitive, Vec2};
use core::f32::consts::{PI, TAU};
use fillet::Fillet;
use states::Arrived;

impl<'n, const V: usize, const E: usize, const P: usize, const R: usize> Planner<'n, V, E, P, R> {
    /// Terrain mode: sets the flight altitude and the safety height kept above the terrain.
    /// Cells whose stored elevation bound is at least `altitude_m − safety_height_m` become
    /// blocked, and so does every edge whose band reaches such a cell. Work: O(1) — the stored
    /// elevation codes are compared with the new blocking code as the search reads them
    /// (`network::elevation`). Non-finite values are refused (the setting is kept).
    pub fn set_altitude(&mut self, altitude_m: f32, safety_height_m: f32) -> Result<(), PlanError> {
        self.cancel_plan();
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
    /// configuration. Work: O(|V| + |E| + T) (degrees are counted from the CSR offsets and
    /// targets; T the transitions).
    pub fn terrain_bound_inputs(&self) -> TerrainBoundInputs {
        let net = &self.network;
        let (v, e) = (net.vertex_count(), net.edge_count());
        let mut transitions = 0u64;
        let mut pair_relaxations = 0u64;
        let mut max_out = 0u64;
        // indeg(v)·outdeg(v) summed = Σ over edges of outdeg(target); each transition (i, o)
        // expands outdeg(target of o).
        for i in 0..e {
            if let Some((_, target)) = net.edge_cost_target(i) {
                let outs = net.out_edges(target);
                transitions += outs.len() as u64;
                for o in outs {
                    if let Some((_, next)) = net.edge_cost_target(o) {
                        pair_relaxations += net.out_edges(next).len() as u64;
                    }
                }
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
            pair_relaxations,
            turn_rule: self.config().turn_rule,
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

    /// Terrain mode's [`Planner::plan`] up to its search, after the query's numbers were
    /// checked: checks the start and goal, connects them to the network and tries the direct
    /// path. Returns the direct path with its cost, if any; the search and
    /// [`Planner::write_terrain_route`] follow.
    #[inline(never)] // once per query; inlined, its frame would add to the step's (slice.rs)
    pub(super) fn terrain_prepare(
        &mut self,
        query: &Query,
        meter: &mut Meter,
        observe: &mut dyn FnMut(Phase, &Work),
    ) -> Result<Option<(f32, DubinsPath)>, PlanError> {
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
        Ok(direct.map(|p| (p.length(), p)))
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
}
