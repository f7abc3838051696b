//! Voronoi mode's query: price the graph's edges, join the start and the goal each to their
//! [`VORONOI_LINKS`] nearest graph vertices, run the one search, walk back the coarse route and
//! smooth it into curvature-bounded pieces (`geometry::spline`), written as pieces and as line
//! chords.

use super::exposure::segment_cost;
use crate::geometry::predicates::point_in_polygon;
use crate::geometry::spline::{fit, FitError, FitInput, Piece, Vertex};
use crate::geometry::{DubinsPath, DubinsWord, Pose, Primitive, Segment, Vec2};
use crate::network::Obstacle;
use crate::planner::search::Arrival;
use crate::planner::state::ModeState;
use crate::planner::threats::MAX_ROUTE_PIECES;
use crate::planner::{
    Link, Meter, PlanError, Planner, Query, QueryField, RouteSummary, SummarySlot,
};
use crate::planner::{MAX_CANDIDATES, MAX_LINKS};
use heapless::Vec;

#[cfg(all(test, feature = "std"))]
mod tests;

/// The graph vertices the start and the goal are each joined to (the paper's three nearest;
/// nearer candidates whose segment is not clear are skipped, up to [`MAX_CANDIDATES`]).
pub const VORONOI_LINKS: usize = 3;

/// How far the line chords of a cubic piece in [`Planner::route`] (for autopilots that fly
/// lines only) may lie from it, metres: each cubic gets the fewest equal-parameter chords whose
/// bound max|B″|·Δt²/8 ([`Piece::chord_deviation`]) is within it, at most
/// [`CHORDS_PER_CUBIC`]; the route's largest bound is [`Planner::chord_deviation`].
pub const CHORD_TOLERANCE_M: f32 = 2.0;

/// The most line chords one cubic piece gets in [`Planner::route`].
pub const CHORDS_PER_CUBIC: u32 = 64;

/// The chords a piece gets: 1 for a line; for a cubic the fewest within
/// [`CHORD_TOLERANCE_M`], at most [`CHORDS_PER_CUBIC`].
fn chord_count(piece: &Piece) -> u32 {
    match piece {
        Piece::Line { .. } => 1,
        Piece::Cubic { .. } => piece
            .chords_for_deviation(CHORD_TOLERANCE_M)
            .unwrap_or(CHORDS_PER_CUBIC)
            .clamp(1, CHORDS_PER_CUBIC),
    }
}

/// The most corners a coarse route has: its graph vertices.
const MAX_COARSE: usize = super::VORONOI_GRAPH_VERTICES;

/// A straight path from `a` to `b` as a Dubins path of one straight piece.
fn straight(a: Vec2, b: Vec2, radius: f32) -> DubinsPath {
    let d = b - a;
    DubinsPath {
        start: Pose {
            position: a,
            heading: libm::atan2f(d.y, d.x),
        },
        radius,
        word: DubinsWord::Lsl,
        lengths: [0.0, d.norm(), 0.0],
    }
}

impl<'n, const V: usize, const E: usize, const P: usize, const R: usize> Planner<'n, V, E, P, R> {
    /// Voronoi mode's [`Planner::plan`] up to its search, after the query's numbers were
    /// checked: checks the start and goal, prices the graph's edges and joins the start and
    /// goal to it. Returns the direct segment with its cost, if clear; the search and
    /// [`Planner::write_voronoi_route`] follow.
    #[inline(never)] // once per query; inlined, its frame would add to the step's (slice.rs)
    pub(in crate::planner) fn voronoi_prepare(
        &mut self,
        query: &Query,
        meter: &mut Meter,
    ) -> Result<Option<(f32, DubinsPath)>, PlanError> {
        self.check_free(query.start.position, QueryField::Start, meter)?;
        self.check_free(query.goal.position, QueryField::Goal, meter)?;
        self.price_voronoi_edges(meter)?;
        let direct = self.connect_voronoi(query, meter)?;
        if self.start_links.is_empty() && direct.is_none() {
            return Err(PlanError::StartUnconnected);
        }
        if self.goal_links.is_empty() && direct.is_none() {
            return Err(PlanError::GoalUnconnected);
        }
        Ok(direct)
    }

    fn voronoi_turn_radius(&self) -> f32 {
        self.network.turn_radius()
    }

    /// The threats in force, the weight and whether a segment is clear: what pricing needs.
    fn segment_price(&self, a: Vec2, b: Vec2, meter: &mut Meter) -> Option<(f32, bool)> {
        let ModeState::Voronoi(state) = &self.state else {
            return None;
        };
        let (cost, terms) = segment_cost(a, b, state.threats(), state.weight);
        meter.work.threat_steps += terms;
        let clear = self.path_is_clear(&straight(a, b, self.voronoi_turn_radius()), meter);
        Some((cost, clear))
    }

    /// Sets every graph edge's cost and whether it is clear of no-fly zones and pop-ups.
    /// Work: per edge, 3·(threats) exposure terms and the obstacle and pop-up tests.
    fn price_voronoi_edges(&mut self, meter: &mut Meter) -> Result<(), PlanError> {
        let edges = match &self.state {
            ModeState::Voronoi(state) => state.graph().edges().len(),
            _ => return Err(PlanError::Internal),
        };
        for e in 0..edges {
            let ends = match &self.state {
                ModeState::Voronoi(state) => state.graph().edge_ends(e as u32),
                _ => None,
            };
            let (a, b) = ends.ok_or(PlanError::Internal)?;
            let (cost, clear) = self.segment_price(a, b, meter).ok_or(PlanError::Internal)?;
            if let ModeState::Voronoi(state) = &mut self.state {
                state.graph_mut().set_edge(e, cost, clear);
            }
            meter.check()?;
        }
        Ok(())
    }

    /// Joins the start and the goal to their nearest graph vertices by clear straight
    /// segments, and returns the direct segment if it is clear (with its cost).
    fn connect_voronoi(
        &mut self,
        query: &Query,
        meter: &mut Meter,
    ) -> Result<Option<(f32, DubinsPath)>, PlanError> {
        self.start_links.clear();
        self.goal_links.clear();
        let radius = self.voronoi_turn_radius();
        for (p, from_start) in [(query.start.position, true), (query.goal.position, false)] {
            // By reference: a heapless `IntoIter` drops its rest through a range index.
            let candidates = self.nearest_graph_vertices(p, meter)?;
            for &v in candidates.iter() {
                let links = if from_start {
                    &self.start_links
                } else {
                    &self.goal_links
                };
                if links.len() >= VORONOI_LINKS.min(MAX_LINKS) {
                    break;
                }
                let q = self.search_vertex_position(v).ok_or(PlanError::Internal)?;
                let (a, b) = if from_start { (p, q) } else { (q, p) };
                if a.distance(b) <= 0.0 {
                    continue;
                }
                let (cost, clear) = self.segment_price(a, b, meter).ok_or(PlanError::Internal)?;
                if clear {
                    let link = Link {
                        vertex: v,
                        path: straight(a, b, radius),
                        cost,
                        pending: false,
                    };
                    let _ = if from_start {
                        self.start_links.push(link)
                    } else {
                        self.goal_links.push(link)
                    };
                }
                meter.check()?;
            }
        }
        let (a, b) = (query.start.position, query.goal.position);
        if a.distance(b) <= 0.0 {
            return Ok(None);
        }
        let (cost, clear) = self.segment_price(a, b, meter).ok_or(PlanError::Internal)?;
        Ok(clear.then(|| (cost, straight(a, b, radius))))
    }

    /// The [`MAX_CANDIDATES`] graph vertices nearest to `p`, nearest first. Work: one vertex
    /// scan per graph vertex.
    fn nearest_graph_vertices(
        &self,
        p: Vec2,
        meter: &mut Meter,
    ) -> Result<Vec<u32, MAX_CANDIDATES>, PlanError> {
        let mut best: Vec<(f32, u32), MAX_CANDIDATES> = Vec::new();
        for v in 0..self.search_vertex_count() {
            meter.work.vertex_scans += 1;
            let d = self
                .search_vertex_position(v)
                .ok_or(PlanError::Internal)?
                .distance(p);
            let at = best
                .iter()
                .position(|(bd, _)| d < *bd)
                .unwrap_or(best.len());
            if at < MAX_CANDIDATES {
                if best.is_full() {
                    best.pop();
                }
                let _ = best.insert(at, (d, v));
            }
        }
        // Pushed one by one: `collect` into a heapless vector `expect`s that it fits.
        let mut nearest = Vec::new();
        for &(_, v) in best.iter() {
            let _ = nearest.push(v);
        }
        Ok(nearest)
    }

    /// Whether the triangle `a, b, c` (a corner piece's hull) lies clear of every no-fly zone
    /// and pop-up by the clearance: its sides are clear and no zone lies inside it (a zone
    /// with no point on or near a side is inside the triangle or wholly outside it, and one of
    /// its vertices tells which).
    fn triangle_is_clear(&self, t: [Vec2; 3], meter: &mut Meter) -> bool {
        let radius = self.voronoi_turn_radius();
        for (a, b) in [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])] {
            if a.distance(b) > 0.0 && !self.path_is_clear(&straight(a, b, radius), meter) {
                return false;
            }
        }
        let tri: &[Vec2] = &t;
        for i in 0..self.network.obstacle_count() {
            meter.work.collision_tests += 1;
            let inside = match self.network.obstacle(i) {
                Some((Obstacle::Polygon(poly), _)) => {
                    use crate::geometry::predicates::PolygonView;
                    poly.vertex(0).is_some_and(|p| point_in_polygon(p, tri))
                }
                Some((Obstacle::Circle { centre, .. }, _)) => point_in_polygon(centre, tri),
                None => true,
            };
            if inside {
                return false;
            }
        }
        for (_, popup) in self.popups() {
            meter.work.collision_tests += 1;
            let (lo, hi) = popup.bounding_box();
            if point_in_polygon((lo + hi) * 0.5, tri) {
                return false;
            }
        }
        true
    }

    /// Walks back the coarse route, smooths it and writes it as pieces and chords; on any
    /// error the previous route is left as it was.
    #[inline(never)] // once per query; inlined, its frame would add to the step's (slice.rs)
    pub(in crate::planner) fn write_voronoi_route(
        &mut self,
        query: &Query,
        arrival: Arrival,
        meter: &mut Meter,
    ) -> Result<RouteSummary, PlanError> {
        let mut corners: Vec<u32, MAX_COARSE> = Vec::new();
        let network_edges = match arrival {
            Arrival::Direct(_) => 0,
            Arrival::FromState { state, .. } => {
                let _ = corners.push(state);
                let (edges, _) = self.walk_vertices(state, meter, |h| {
                    let source = self.search_edge_source(h).ok_or(PlanError::Internal)?;
                    corners.push(source).map_err(|_| PlanError::Internal)
                })?;
                corners.reverse();
                edges
            }
            Arrival::AtVertex => return Err(PlanError::Internal),
        };
        let mut waypoints: Vec<Vec2, MAX_COARSE> = Vec::new();
        for v in &corners {
            let p = self.search_vertex_position(*v).ok_or(PlanError::Internal)?;
            waypoints.push(p).map_err(|_| PlanError::Internal)?;
        }
        let kappa_max = match &self.state {
            ModeState::Voronoi(state) => state.kappa_max,
            _ => return Err(PlanError::Internal),
        };
        let table = self.network.corner_table().ok_or(PlanError::Internal)?;
        let input = FitInput {
            start: query.start,
            waypoints: &waypoints,
            goal: query.goal.position,
            goal_heading: query.goal.heading,
            kappa_max,
        };
        let mut pieces: Vec<Piece, MAX_ROUTE_PIECES> = Vec::new();
        let radius = self.voronoi_turn_radius();
        let mut fit_meter = Meter::new(u64::MAX);
        let fitted = fit(
            &input,
            &table,
            &mut |points: &[Vec2]| match *points {
                [a, b] => {
                    a.distance(b) <= 0.0
                        || self.path_is_clear(&straight(a, b, radius), &mut fit_meter)
                }
                [a, b, c] => self.triangle_is_clear([a, b, c], &mut fit_meter),
                _ => false,
            },
            &mut pieces,
        );
        meter.work += fit_meter.work;
        let summary = match fitted {
            Ok(s) => s,
            Err(FitError::RouteTooLong { .. }) => {
                return Err(PlanError::RouteTooLong {
                    primitives: MAX_ROUTE_PIECES as u32 + 1,
                    capacity: MAX_ROUTE_PIECES as u32,
                })
            }
            Err(FitError::CornerBlocked { corner }) => {
                return Err(PlanError::Smoothing {
                    corner: corner_number(corner, waypoints.len()),
                })
            }
            Err(FitError::SegmentBlocked { from, .. }) => {
                return Err(PlanError::Smoothing {
                    corner: corner_number(from, waypoints.len()),
                })
            }
            Err(FitError::LeadOutInfeasible) => {
                return Err(PlanError::Smoothing {
                    corner: corner_number(Vertex::Goal, waypoints.len()),
                })
            }
            Err(_) => return Err(PlanError::Smoothing { corner: 0 }),
        };
        meter.work.threat_steps += summary.work;
        meter.check()?;
        self.commit_voronoi_route(&pieces, &waypoints, query, network_edges, meter)
    }

    /// Replaces the route by `pieces` (and their chords), and the route's paths by the coarse
    /// legs, if they fit in `R`.
    fn commit_voronoi_route(
        &mut self,
        pieces: &[Piece],
        waypoints: &[Vec2],
        query: &Query,
        network_edges: u32,
        meter: &Meter,
    ) -> Result<RouteSummary, PlanError> {
        let chords: usize = pieces.iter().map(|p| chord_count(p) as usize).sum();
        if chords > R || waypoints.len() + 1 > R {
            return Err(PlanError::RouteTooLong {
                primitives: chords.max(waypoints.len() + 1) as u32,
                capacity: R as u32,
            });
        }
        let radius = self.voronoi_turn_radius();
        self.paths.clear();
        let mut at = query.start.position;
        for p in waypoints
            .iter()
            .chain(core::iter::once(&query.goal.position))
        {
            let _ = self.paths.push(straight(at, *p, radius));
            at = *p;
        }
        self.route.clear();
        let mut deviation = 0.0f32;
        for piece in pieces {
            let n = chord_count(piece);
            if let Piece::Cubic { .. } = piece {
                deviation = deviation.max(piece.chord_deviation(n));
            }
            let mut at = piece.start();
            for b in piece.chord_points(n).skip(1) {
                let _ = self.route.push(Primitive::Line(Segment::new(at, b)));
                at = b;
            }
        }
        let length = pieces.iter().map(Piece::length).sum();
        let arrival_heading = pieces.last().map_or(query.start.heading, |p| {
            let d = p.point(1.0) - p.point(0.999);
            libm::atan2f(d.y, d.x)
        });
        if let ModeState::Voronoi(state) = &mut self.state {
            state.pieces.clear();
            for p in pieces {
                let _ = state.pieces.push(*p);
            }
            state.chord_deviation = deviation;
        }
        let summary = RouteSummary {
            length,
            primitives: self.route.len() as u32,
            network_edges,
            arrival_heading,
            work: meter.work,
            exit: None,
        };
        self.summary = SummarySlot::Full(summary);
        Ok(summary)
    }

    /// Voronoi mode: how far the chords of [`Planner::route`] may lie from the last route's
    /// pieces, metres (`None` in other modes).
    pub fn chord_deviation(&self) -> Option<f32> {
        match &self.state {
            ModeState::Voronoi(state) => Some(state.chord_deviation),
            _ => None,
        }
    }
}

/// A fit vertex as [`PlanError::Smoothing`] numbers corners: 0 the start and its lead-in,
/// `i + 1` the coarse route's vertex `i`, `n + 1` the goal and its lead-out.
fn corner_number(v: Vertex, waypoints: usize) -> u32 {
    match v {
        Vertex::Start | Vertex::LeadIn(_) => 0,
        Vertex::Waypoint(i) => i as u32 + 1,
        Vertex::LeadOut(_) | Vertex::Goal => waypoints as u32 + 1,
    }
}
