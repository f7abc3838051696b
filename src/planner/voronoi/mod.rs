//! Voronoi mode (Judd & McLain): radar threats as soft points, their Voronoi diagram built and
//! rebuilt onboard in fixed memory, edges costed by length and exposure, the one search, and
//! the coarse route smoothed into curvature-bounded cubic pieces.
//!
//! - `planner::threats` (beside this module, so that the mode's state can name it): the
//!   threats, their diagram, the search graph over it (half-edges grouped by source), which
//!   edges are clear and what each costs, in the caller's [`VoronoiStorage`];
//! - `exposure`: the exposure of a segment (the paper's three-point rule) and the edge cost;
//! - `route`: the query (links, search, walk-back, smoothing, route output).

mod exposure;
mod route;

pub use route::{CHORDS_PER_CUBIC, CHORD_TOLERANCE_M, VORONOI_LINKS};

pub use super::threats::{
    HalfEdge, SearchGraph, Threat, ThreatError, ThreatOrigin, ThreatSummary, VoronoiStorage,
    MAX_ROUTE_PIECES, MAX_THREATS, VORONOI_GRAPH_EDGES, VORONOI_GRAPH_VERTICES,
};
pub use exposure::{segment_exposure, EXPOSURE_POINTS};

use super::Planner;
use crate::geometry::voronoi::{
    delaunay_work_bound, graph_edge_bound, graph_vertex_bound, graph_work_bound,
};
use crate::geometry::Vec2;
use crate::network::LoadError;

/// The most work one rebuild counts for `n` sites ([`ThreatSummary::work`]): the diagram's
/// insertions ([`delaunay_work_bound`]), the graph built from it ([`graph_work_bound`]) and
/// the grouping of its half-edges by source, `2E + V` for the graph's most edges and vertices
/// ([`graph_edge_bound`], [`graph_vertex_bound`]). Saturating.
pub fn threat_rebuild_work_bound(n: u64) -> u64 {
    let sites = usize::try_from(n).unwrap_or(usize::MAX);
    let grouping = (graph_edge_bound(sites) as u64)
        .saturating_mul(2)
        .saturating_add(graph_vertex_bound(sites) as u64);
    delaunay_work_bound(n)
        .saturating_add(graph_work_bound(sites))
        .saturating_add(grouping)
}

impl<'n, const V: usize, const E: usize, const P: usize, const R: usize> Planner<'n, V, E, P, R> {
    /// Validates `bytes` — a Voronoi network — for this planner's capacities and makes it the
    /// network, with its mode's state in `storage`: the diagram of its threat sites, built
    /// here and checked against the graph the image stores
    /// ([`LoadError::VoronoiMismatch`]), and the search graph over it. The planner needs
    /// `V ≥` [`VORONOI_GRAPH_VERTICES`], the most vertices the graph can have after threats pop
    /// up ([`LoadError::TooManySearchStates`]). On error the planner keeps its previous network
    /// and state (`storage` is left unspecified). [`Planner::load`] refuses Voronoi networks:
    /// they need this storage. Work: one pass over the image, and the diagram of its sites
    /// ([`threat_rebuild_work_bound`]).
    pub fn load_voronoi(
        &mut self,
        bytes: &'n [u8],
        storage: &'n mut VoronoiStorage,
    ) -> Result<(), LoadError> {
        self.cancel_plan();
        let network = crate::network::Network::from_bytes_with_capacity(bytes, V, E)?;
        match network.mode() {
            crate::network::Mode::Voronoi => {}
            other @ (crate::network::Mode::Roadmap
            | crate::network::Mode::Terrain
            | crate::network::Mode::Landmark
            | crate::network::Mode::Unknown(_)) => {
                return Err(LoadError::NotVoronoi { mode: other.code() })
            }
        }
        if V < VORONOI_GRAPH_VERTICES {
            return Err(LoadError::TooManySearchStates {
                needed: VORONOI_GRAPH_VERTICES,
                capacity: V,
            });
        }
        storage.init(&network)?;
        self.install(network, super::state::ModeState::Voronoi(storage));
        Ok(())
    }

    /// Voronoi mode: a radar that pops up in flight. Inserts it into the diagram and rebuilds
    /// the search graph; the next [`Planner::plan`] (from the current pose) avoids it by its
    /// exposure. On error nothing changes. Work: [`threat_rebuild_work_bound`] of the threats
    /// in force.
    pub fn add_threat(
        &mut self,
        position: Vec2,
        radius: f32,
    ) -> Result<ThreatSummary, ThreatError> {
        self.cancel_plan();
        let super::state::ModeState::Voronoi(state) = &mut self.state else {
            return Err(ThreatError::NotVoronoi);
        };
        if !position.is_finite() || !radius.is_finite() {
            return Err(ThreatError::NonFinite);
        }
        if radius <= 0.0 || radius > crate::geometry::MAX_COORDINATE_M {
            return Err(ThreatError::OutOfRange);
        }
        state.add(position, radius)
    }

    /// Voronoi mode: removes threat `id` (added in flight) and rebuilds the diagram from the
    /// threats that remain. On error nothing changes. Work: as [`Planner::add_threat`].
    pub fn remove_threat(&mut self, id: u8) -> Result<ThreatSummary, ThreatError> {
        self.cancel_plan();
        let super::state::ModeState::Voronoi(state) = &mut self.state else {
            return Err(ThreatError::NotVoronoi);
        };
        state.remove(id)
    }

    /// Voronoi mode: replaces the weight k of length against exposure (the network's until
    /// set) for the next queries.
    pub fn set_threat_weight(&mut self, k: f32) -> Result<(), ThreatError> {
        self.cancel_plan();
        let super::state::ModeState::Voronoi(state) = &mut self.state else {
            return Err(ThreatError::NotVoronoi);
        };
        if !k.is_finite() {
            return Err(ThreatError::NonFinite);
        }
        if !(0.0..=1.0).contains(&k) {
            return Err(ThreatError::OutOfRange);
        }
        state.weight = k;
        Ok(())
    }

    /// Voronoi mode: the inputs of [`voronoi_plan_work_bound`](super::voronoi_plan_work_bound)
    /// for the threats in force (the graph's bounds for [`MAX_THREATS`] threats, so that the
    /// bound holds after any pop-up threat too).
    pub(super) fn voronoi_bound_inputs(&self) -> super::VoronoiBoundInputs {
        let h = self.network.header();
        super::VoronoiBoundInputs {
            graph_vertices: VORONOI_GRAPH_VERTICES as u64,
            graph_edges: VORONOI_GRAPH_EDGES as u64,
            threats: MAX_THREATS as u64,
            obstacles: h.obstacle_count as u64,
            obstacle_points: h.obstacle_point_count as u64,
            popups: P as u64,
            popup_vertices: super::MAX_POPUP_VERTICES as u64,
            candidates: super::MAX_CANDIDATES as u64,
            fit_steps: crate::geometry::spline::fit_work_bound(VORONOI_GRAPH_VERTICES),
            fit_clears: crate::geometry::spline::fit_clear_bound(VORONOI_GRAPH_VERTICES),
        }
    }

    /// Voronoi mode: the weight k in force (`None` in other modes).
    pub fn threat_weight(&self) -> Option<f32> {
        match &self.state {
            super::state::ModeState::Voronoi(state) => Some(state.weight),
            _ => None,
        }
    }

    /// Voronoi mode: the threats in force, the network's first (empty in other modes).
    pub fn threats(&self) -> &[Threat] {
        match &self.state {
            super::state::ModeState::Voronoi(state) => state.threats(),
            _ => &[],
        }
    }

    /// Voronoi mode: the search graph over the threats in force (its vertices and undirected
    /// edges), for display and checks.
    pub fn threat_graph(&self) -> Option<&SearchGraph> {
        match &self.state {
            super::state::ModeState::Voronoi(state) => Some(state.graph()),
            _ => None,
        }
    }

    /// Voronoi mode: the last route as the smoothed pieces the autopilot samples (lines and
    /// cubic Bézier pieces, continuous in position, heading and curvature); empty in other
    /// modes. [`Planner::route`] holds the same route as line chords.
    pub fn route_pieces(&self) -> &[crate::geometry::spline::Piece] {
        match &self.state {
            super::state::ModeState::Voronoi(state) => &state.pieces,
            _ => &[],
        }
    }
}
