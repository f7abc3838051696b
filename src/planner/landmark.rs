//! Landmark mode onboard (Babel 2014): navigability pruning by weather and in-flight rosette
//! updates, evaluated lazily in the search; queries from the stored start, an overflight or
//! any other pose to the stored goal or any other point (either end joined online:
//! `planner/landmark_connect.rs`); routes as network edges whose Hermite pieces the
//! autopilot samples.
//!
//! An edge leaving overflight `(L, α)` is navigable in weather `ω` iff its cost (its length)
//! is at most `d_max(L)·q(α, ω)`; a start edge iff it is at most the start's range. The test
//! reads the stored quality (or the landmark's override) when the search relaxes the edge, so
//! [`Planner::set_weather`] and [`Planner::update_rosette`] are O(1): re-pruning a landmark's
//! edges costs nothing until a search reads them.

use super::popup::{Popup, PopupSummary};
use super::search::{Ends, LandmarkEnd};
use super::state::{
    LandmarkState, LinkSide, ModeState, MAX_ROSETTE_DIRECTIONS, MAX_ROSETTE_OVERRIDES,
};
use super::{Meter, PlanError, Planner, Query, RouteSummary, SummarySlot};
use crate::geometry::{wrap_to_pi, Vec2};
use crate::network::format::LandmarkRecord;
use heapless::Vec;

/// Chords per Hermite piece in pop-up tests
/// ([`HermiteSegment::conflicts_with_circle`](crate::geometry::hermite::HermiteSegment::conflicts_with_circle)):
/// each chord is tested at the clearance plus its deviation bound, so more chords prune less
/// but cost more.
pub const POPUP_CHORDS_PER_PIECE: usize = 16;

/// How close a query's start or goal must be to a vertex, metres.
const MATCH_DISTANCE_M: f32 = 1.0;
/// How close a query's start heading must be to an overflight's, radians.
const MATCH_HEADING_RAD: f32 = 1e-3;

#[cfg(all(test, feature = "std"))]
mod index_tests;
#[cfg(all(test, feature = "std"))]
pub(super) mod tests;

impl<'n, const V: usize, const E: usize, const P: usize, const R: usize> Planner<'n, V, E, P, R> {
    fn landmark_record(&self) -> Result<LandmarkRecord, PlanError> {
        self.network
            .landmark()
            .copied()
            .ok_or(PlanError::NotLandmarkNetwork)
    }

    /// The landmark state, or [`PlanError::NotLandmarkNetwork`].
    fn landmark_state(&mut self) -> Result<&mut LandmarkState<R>, PlanError> {
        match &mut self.state {
            ModeState::Landmark(l) => Ok(l),
            _ => Err(PlanError::NotLandmarkNetwork),
        }
    }

    /// Landmark mode: sets the weather in force (an index into the network's weathers; 0 after
    /// [`Planner::load`]). O(1).
    pub fn set_weather(&mut self, weather: u32) -> Result<(), PlanError> {
        self.cancel_plan();
        let l = self.landmark_record()?;
        if weather >= l.weather_count {
            return Err(PlanError::UnknownWeather {
                weather,
                count: l.weather_count,
            });
        }
        self.landmark_state()?.weather = weather;
        Ok(())
    }

    /// Landmark mode: the weather in force (0 for other networks).
    pub fn weather(&self) -> u32 {
        match &self.state {
            ModeState::Landmark(l) => l.weather,
            _ => 0,
        }
    }

    /// Landmark mode: replaces landmark `landmark`'s rosette, in every weather, by `qualities`
    /// (one per direction, in `[0, 1]`): a landmark found degraded (lower qualities) or lost
    /// (all 0). Its outgoing edges are re-pruned as the next search reads them: O(1) here, and
    /// O([`MAX_ROSETTE_OVERRIDES`]) per edge read.
    pub fn update_rosette(&mut self, landmark: u32, qualities: &[f32]) -> Result<(), PlanError> {
        self.cancel_plan();
        let l = self.landmark_record()?;
        if landmark >= l.landmark_count {
            return Err(PlanError::UnknownLandmark {
                landmark,
                count: l.landmark_count,
            });
        }
        let d = l.directions as usize;
        if qualities.len() != d
            || d > MAX_ROSETTE_DIRECTIONS
            || !qualities.iter().all(|q| (0.0..=1.0).contains(q))
        {
            return Err(PlanError::InvalidRosette {
                given: qualities.len() as u32,
                directions: l.directions,
            });
        }
        let mut row = [0.0f32; MAX_ROSETTE_DIRECTIONS];
        for (r, q) in row.iter_mut().zip(qualities) {
            *r = *q;
        }
        let rosettes = &mut self.landmark_state()?.rosettes;
        if let Some(entry) = rosettes.iter_mut().find(|(at, _)| *at == landmark) {
            entry.1 = row;
            return Ok(());
        }
        rosettes
            .push((landmark, row))
            .map_err(|_| PlanError::RosetteTableFull {
                capacity: MAX_ROSETTE_OVERRIDES as u32,
            })
    }

    /// Landmark mode: drops landmark `landmark`'s override (its stored rosettes apply again).
    /// Returns whether it had one.
    pub fn clear_rosette(&mut self, landmark: u32) -> bool {
        self.cancel_plan();
        let Ok(l) = self.landmark_state() else {
            return false;
        };
        match l.rosettes.iter().position(|(at, _)| *at == landmark) {
            Some(i) => {
                l.rosettes.swap_remove(i);
                true
            }
            None => false,
        }
    }

    /// Landmark mode: the quality in force for landmark `landmark` crossed in `direction`
    /// (its override, or the stored rosette of the weather in force); `None` for a landmark or
    /// direction the network does not have, and on any other network.
    pub fn quality(&self, landmark: u32, direction: u32) -> Option<f32> {
        let (ModeState::Landmark(state), Some(l)) = (&self.state, self.network.landmark()) else {
            return None;
        };
        self.quality_in(state, l, landmark, direction)
    }

    /// [`Planner::quality`] with the state and the landmark record at hand.
    #[inline(always)]
    fn quality_in(
        &self,
        state: &LandmarkState<R>,
        l: &LandmarkRecord,
        landmark: u32,
        direction: u32,
    ) -> Option<f32> {
        if let Some((_, row)) = state.rosettes.iter().find(|(at, _)| *at == landmark) {
            // The row is padded to MAX_ROSETTE_DIRECTIONS: past the network's, no direction.
            return (direction < l.directions)
                .then(|| row.get(direction as usize).copied())
                .flatten();
        }
        self.network
            .rosette_quality_of(l, landmark, state.weather, direction)
    }

    /// Landmark mode: whether edge `e` is navigable in the weather and rosettes in force: an
    /// edge from overflight `(L, α)` iff its cost ≤ `d_max(L)·q(α)`; a start edge iff its cost
    /// ≤ the start's range; other edges (and non-landmark networks) always. O(1).
    pub fn is_navigable(&self, e: u32) -> bool {
        match &self.state {
            ModeState::Landmark(state) => self
                .network
                .edge_source(e)
                .is_some_and(|source| self.navigable_from(state, source, e)),
            ModeState::Roadmap(_) | ModeState::Terrain(_) | ModeState::Voronoi(_) => true,
        }
    }

    /// [`Planner::is_navigable`] with the landmark state and edge `e`'s source at hand: the
    /// landmark record is read once for the edge's site and quality.
    #[inline(always)]
    pub(super) fn navigable_from(&self, state: &LandmarkState<R>, source: u32, e: u32) -> bool {
        let Some(l) = self.network.landmark() else {
            return true;
        };
        let Some(r) = self.network.edge_record(e) else {
            return false;
        };
        if source == l.start_vertex {
            return r.cost <= l.start_range_m;
        }
        // Checked: a network with no directions has no overflight to be navigable from.
        let (Some(landmark), Some(direction)) = (
            source.checked_div(l.directions),
            source.checked_rem(l.directions),
        ) else {
            return false;
        };
        if landmark >= l.landmark_count {
            return true; // the goal's (if any)
        }
        match (
            self.network.landmark_site_of(l, landmark),
            self.quality_in(state, l, landmark, direction),
        ) {
            (Some((_, d_max)), Some(q)) => r.cost <= d_max * q,
            _ => false,
        }
    }

    /// Landmark mode: the last route's network edges, start to goal. Piece `k` of edge `e` is
    /// [`Network::chain_piece`](crate::network::Network::chain_piece)`(e, k)`, for
    /// `k < chain_piece_count(e)`; consecutive pieces and edges meet in line elements, so the
    /// route is C² (nominal speed, zero acceleration at every joint).
    pub fn route_edges(&self) -> &[u32] {
        match &self.state {
            ModeState::Landmark(l) => &l.route_edges,
            _ => &[],
        }
    }

    /// Landmark mode's [`Planner::plan`] up to its search, after the query's numbers were
    /// checked: matches the start to the stored start or an overflight and the goal to the
    /// stored goal, and joins either end that matches none to the network online
    /// (`planner/landmark_connect.rs`). Returns the search's ends; the search and
    /// [`Planner::write_landmark_route`] follow.
    #[inline(never)] // once per query; inlined, its frame would add to the step's (slice.rs)
    pub(super) fn landmark_prepare(
        &mut self,
        query: &Query,
        meter: &mut Meter,
    ) -> Result<Ends, PlanError> {
        let l = self.landmark_record()?;
        self.start_links.clear();
        self.goal_links.clear();
        let state = self.landmark_state()?;
        state.start_links.clear();
        state.goal_links.clear();
        meter.work.vertex_scans += 1;
        let to = match self.network.vertex(l.goal_vertex) {
            Some(g) if g.position.distance(query.goal.position) <= MATCH_DISTANCE_M => {
                LandmarkEnd::Vertex(l.goal_vertex)
            }
            _ => LandmarkEnd::Online,
        };
        let from = match self.match_start(&l, query, meter) {
            Some(v) => LandmarkEnd::Vertex(v),
            None => LandmarkEnd::Online,
        };
        // The other end's vertex, when it is one the piece may join directly: the stored goal
        // for a start link, the stored start for a goal link.
        match (from, to) {
            (LandmarkEnd::Online, LandmarkEnd::Vertex(goal)) => {
                self.connect_online(&l, query, LinkSide::Start, Some(goal), meter)?
            }
            (LandmarkEnd::Vertex(start), LandmarkEnd::Online) => {
                let stored = (start == l.start_vertex).then_some(start);
                self.connect_online(&l, query, LinkSide::Goal, stored, meter)?
            }
            (LandmarkEnd::Online, LandmarkEnd::Online) => {
                self.connect_online(&l, query, LinkSide::Start, None, meter)?;
                self.connect_online(&l, query, LinkSide::Goal, None, meter)?
            }
            (LandmarkEnd::Vertex(_), LandmarkEnd::Vertex(_)) => {}
        }
        meter.check()?;
        Ok(Ends::Landmark { from, to })
    }

    /// The stored start if the query starts there, else the overflight it starts at, if any.
    fn match_start(&self, l: &LandmarkRecord, query: &Query, meter: &mut Meter) -> Option<u32> {
        let at = |v: u32| {
            self.network.vertex(v).is_some_and(|p| {
                p.position.distance(query.start.position) <= MATCH_DISTANCE_M
                    && libm::fabsf(wrap_to_pi(p.heading - query.start.heading)) <= MATCH_HEADING_RAD
            })
        };
        meter.work.vertex_scans += 1;
        if l.start_vertex != LandmarkRecord::ABSENT && at(l.start_vertex) {
            return Some(l.start_vertex);
        }
        let overflights = l.landmark_count.saturating_mul(l.directions);
        (0..overflights).find(|&v| {
            meter.work.vertex_scans += 1;
            at(v)
        })
    }

    /// Writes the route the search found, ending at vertex `last` (then by online goal link
    /// `goal_link`, if any): the online start's piece when the search began from online
    /// links (`from`), the network edges, the online goal's piece.
    #[inline(never)] // once per query; inlined, its frame would add to the step's (slice.rs)
    pub(super) fn write_landmark_route(
        &mut self,
        query: &Query,
        (from, last, goal_link): (LandmarkEnd, u32, Option<usize>),
        meter: &mut Meter,
    ) -> Result<RouteSummary, PlanError> {
        let (mut length, mut pieces) = (0.0f32, 0u32);
        let net = self.network;
        let (edges, start) = self.walk_vertices(last, meter, |e| {
            length += net.edge_cost_target(e).map_or(0.0, |c| c.0);
            pieces = pieces.saturating_add(net.chain_piece_count(e));
            Ok(())
        })?;
        if edges as usize > R {
            return Err(PlanError::RouteTooLong {
                primitives: edges,
                capacity: R as u32,
            });
        }
        meter.work.vertex_scans += edges as u64 + 1;
        let start_piece = match (from, start) {
            (LandmarkEnd::Vertex(_), _) => None,
            (LandmarkEnd::Online, Some(k)) => {
                Some(self.rebuild_online_piece(query, LinkSide::Start, k, meter)?)
            }
            (LandmarkEnd::Online, None) => return Err(PlanError::Internal),
        };
        let goal_piece = match goal_link {
            Some(k) => Some(self.rebuild_online_piece(query, LinkSide::Goal, k, meter)?),
            None => None,
        };
        for piece in start_piece.iter().chain(goal_piece.iter()) {
            length += piece.length();
            pieces = pieces.saturating_add(1);
        }
        meter.check()?;
        let mut route = core::mem::take(&mut self.landmark_state()?.route_edges);
        route.clear();
        let mut replay = Meter::new(u64::MAX);
        let walked = self.walk_vertices(last, &mut replay, |e| {
            let _ = route.push(e);
            Ok(())
        });
        route.reverse();
        let complete = walked.is_ok() && route.len() == edges as usize;
        let state = self.landmark_state()?;
        state.route_edges = if complete { route } else { Vec::new() };
        state.start_piece = start_piece.filter(|_| complete);
        state.goal_piece = goal_piece.filter(|_| complete);
        self.paths.clear();
        self.route.clear();
        if !complete {
            self.summary = SummarySlot::Empty;
            return Err(PlanError::Internal);
        }
        let arrival_heading = match goal_piece {
            Some(piece) => {
                let v = piece.end().velocity;
                libm::atan2f(v.y, v.x)
            }
            None => self.network.vertex(last).map_or(0.0, |p| p.heading),
        };
        let summary = RouteSummary {
            length,
            primitives: pieces,
            network_edges: edges,
            arrival_heading,
            work: meter.work,
            exit: None,
        };
        self.summary = SummarySlot::Full(summary);
        Ok(summary)
    }

    /// Landmark mode: whether any piece of chain edge `e` may come within `clearance` of
    /// `popup` (conservative: [`POPUP_CHORDS_PER_PIECE`] chords per piece at the clearance
    /// plus their deviation bounds). A piece whose reach — the box around its chord's midpoint
    /// of half-side half its length bound, the edge's length less the other pieces' chords —
    /// misses the pop-up's box widened by the clearance is skipped without being rebuilt. A
    /// piece that cannot be read or rebuilt counts as a conflict (fail safe).
    pub(super) fn chain_conflicts(
        &self,
        e: u32,
        popup: &Popup,
        clearance: f32,
        summary: &mut PopupSummary,
    ) -> bool {
        let net = &self.network;
        let (Some(length), range) = (net.edge_length(e), net.chain_elements(e)) else {
            return true;
        };
        let mut chords = 0.0f32;
        let mut previous: Option<Vec2> = None;
        for k in range.clone() {
            let Some(el) = net.chain_element(k) else {
                return true;
            };
            if let Some(p) = previous {
                chords += p.distance(el.position);
            }
            previous = Some(el.position);
        }
        let (lo, hi) = popup.bounding_box();
        let w = Vec2::new(clearance, clearance);
        let (lo, hi) = (lo - w, hi + w);
        for k in 0..net.chain_piece_count(e) {
            let i = range.start + k;
            let (Some(a), Some(b)) = (net.chain_element(i), net.chain_element(i + 1)) else {
                return true;
            };
            let chord = a.position.distance(b.position);
            // Every other piece is at least its chord long; rounding keeps it an upper bound.
            let bound = (length - (chords - chord) * (1.0 - 1e-5)).max(chord);
            let (rlo, rhi) = net.edge_reach(a.position, b.position, bound);
            if rhi.x < lo.x || rhi.y < lo.y || rlo.x > hi.x || rlo.y > hi.y {
                continue;
            }
            summary.pieces_rebuilt = summary.pieces_rebuilt.saturating_add(1);
            let Some(seg) = net.chain_piece(e, k) else {
                return true;
            };
            let (hit, tests) = popup.conflicts_with_piece(&seg, clearance, POPUP_CHORDS_PER_PIECE);
            summary.predicate_tests = summary.predicate_tests.saturating_add(tests);
            if hit {
                return true;
            }
        }
        false
    }
}
