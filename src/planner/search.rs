//! The query: validate, connect, search (Dijkstra or A*), and write the route.

use super::heap::ItemState;
use super::state::{LinkSide, ModeState};
use super::{
    Link, Meter, Phase, PlanError, PlanStep, Planner, Query, QueryField, RouteSummary, Search,
    SummarySlot, Work, FROM_START,
};
use crate::geometry::{DubinsPath, Primitive, Vec2};

/// How the best route found so far reaches the goal.
#[derive(Clone, Copy, Debug)]
pub(super) enum Arrival {
    /// Straight from the start, by this path.
    Direct(DubinsPath),
    /// Through the network: from search state `state` by goal link `link`.
    FromState {
        /// The last search state (a vertex, or a terrain edge state).
        state: u32,
        /// The goal link.
        link: usize,
    },
    /// At the target vertex (landmark mode: the goal is a vertex).
    AtVertex,
}

/// What a search's states are: the one choice that differs between the modes' searches.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum StateSpace {
    /// The network's vertices (roadmap and landmark modes): a state is "at vertex `v`".
    Vertices,
    /// The straights of the route (terrain mode): a state is "arrived at the end of a directed
    /// edge or start link", under the paper's turn rule with the straight before it, so that
    /// each turn can be checked when it is taken (`planner/terrain`).
    EdgeStates,
}

/// Where a vertex search starts and what it looks for. An explicit `u8` tag whose first
/// variant is 0: an idle query ([`Flight::IDLE`](super::slice::Flight::IDLE)) is all-zero bytes.
#[derive(Clone, Copy, Debug)]
#[repr(u8)]
pub(super) enum Ends {
    /// From the start links to the goal links (roadmap mode).
    Links = 0,
    /// Landmark mode: from a vertex (cost 0) or the online start links, to a vertex or the
    /// online goal links (`planner/landmark_connect.rs`).
    Landmark {
        /// Where the search starts.
        from: LandmarkEnd,
        /// What it looks for.
        to: LandmarkEnd,
    } = 1,
}

/// One end of a landmark search.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(u8)]
pub(super) enum LandmarkEnd {
    /// A network vertex: the stored start, an overflight, or the stored goal.
    Vertex(u32) = 0,
    /// The query's pose, joined to the network by online links.
    Online = 1,
}

impl Ends {
    /// The vertex the search stops at, if it stops at one.
    fn target(self) -> Option<u32> {
        match self {
            Ends::Landmark {
                to: LandmarkEnd::Vertex(to),
                ..
            } => Some(to),
            Ends::Links
            | Ends::Landmark {
                to: LandmarkEnd::Online,
                ..
            } => None,
        }
    }
}

/// A* heuristic scale: the chord to the goal shrunk by 1e-4 so that f32 rounding of stored edge
/// costs (relative error ~1e-7) cannot make it exceed a true remaining cost.
const HEURISTIC_SCALE: f32 = 1.0 - 1e-4;

impl<'n, const V: usize, const E: usize, const P: usize, const R: usize> Planner<'n, V, E, P, R> {
    /// Plans from `query.start` to `query.goal` through the network, counting work against
    /// `budget` (compare [`Planner::worst_case_work`]). On success the route replaces the
    /// previous one; on any error the previous route is left as it was. The same as
    /// [`Planner::start_plan`] followed by [`Planner::step`] until it is done (this is how it
    /// runs), in one call.
    pub fn plan(&mut self, query: &Query, budget: u64) -> Result<RouteSummary, PlanError> {
        // Opaque, so that a program calling both `plan` and `plan_observed` gets one copy of
        // the query code rather than a second one specialised for this observer.
        self.plan_observed(query, budget, core::hint::black_box(&mut |_, _| {}))
    }

    /// [`Planner::plan`], telling `observe` as each [`Phase`] of a roadmap or terrain query
    /// begins, with the work counted so far, and [`Phase::Done`] (also after an error) at the
    /// end. Landmark and Voronoi queries report only [`Phase::Done`]. The observer sees the
    /// query; it does not change it.
    pub fn plan_observed(
        &mut self,
        query: &Query,
        budget: u64,
        observe: &mut dyn FnMut(Phase, &Work),
    ) -> Result<RouteSummary, PlanError> {
        if let Err(e) = self.start_plan(query, budget) {
            observe(Phase::Done, &Work::default());
            return Err(e);
        }
        // One step with an unlimited slice runs the query to its end; the loop only guards
        // against a step that stops early all the same.
        loop {
            if let PlanStep::Done(result) = self.step_observed(u64::MAX, observe) {
                return result;
            }
        }
    }

    /// Checks the query's numbers: finite, and within the range the geometry handles.
    pub(super) fn check_query(query: &Query) -> Result<(), PlanError> {
        if !query.start.is_finite() {
            return Err(PlanError::NonFinite {
                field: QueryField::Start,
            });
        }
        if !query.goal.position.is_finite() || query.goal.heading.is_some_and(|h| !h.is_finite()) {
            return Err(PlanError::NonFinite {
                field: QueryField::Goal,
            });
        }
        if !query.start.position.is_in_range() {
            return Err(PlanError::OutOfRange {
                field: QueryField::Start,
            });
        }
        if !query.goal.position.is_in_range() {
            return Err(PlanError::OutOfRange {
                field: QueryField::Goal,
            });
        }
        Ok(())
    }

    /// The state space of the loaded mode's search.
    pub(super) fn state_space(&self) -> StateSpace {
        match self.state {
            ModeState::Roadmap(_) | ModeState::Landmark(_) | ModeState::Voronoi(_) => {
                StateSpace::Vertices
            }
            ModeState::Terrain(_) => StateSpace::EdgeStates,
        }
    }

    /// Begins the one search of every mode: Dijkstra (or A*, over vertices) from the start
    /// links (or a start vertex) over the states of the mode's [`StateSpace`]. Resets the heap
    /// and queues the start; [`Planner::search_expand`] then expands one state at a time.
    pub(super) fn search_begin(
        &mut self,
        query: &Query,
        ends: Ends,
        meter: &mut Meter,
    ) -> Result<(), PlanError> {
        let space = self.state_space();
        let states = match space {
            StateSpace::Vertices => self.search_vertex_count() as usize,
            StateSpace::EdgeStates => self.prepare_edge_states(meter)?,
        };
        if states > V {
            return Err(PlanError::Internal); // load() rules this out
        }
        self.heap.clear(states);
        meter.work.vertex_scans += states as u64;
        match space {
            StateSpace::Vertices => self.seed_vertices(query, ends, meter)?,
            StateSpace::EdgeStates => self.seed_edge_states(meter)?,
        }
        meter.check()
    }

    /// One step of the search [`Planner::search_begin`] began: pops the cheapest state and
    /// expands it. `best` is the cheapest route found so far (at first the direct start–goal
    /// path, if any, with its cost); a pending goal link it resolves reads the query's goal
    /// window first, if unread ([`Planner::resolve_goal_link`]). Returns whether the search is over: the heap is
    /// empty, every remaining route costs at least `best`'s, or the search's target vertex
    /// ([`Ends::target`]) is reached. Edges are relaxed only when
    /// [`Planner::is_edge_usable`]; the expansion of a state is the space's
    /// ([`Planner::expand_vertex`], [`Planner::expand_edge_state`]).
    #[inline(always)] // its one caller's loop is the search's loop
    pub(super) fn search_expand(
        &mut self,
        query: &Query,
        ends: Ends,
        best: &mut Option<(f32, Arrival)>,
        meter: &mut Meter,
    ) -> Result<bool, PlanError> {
        let Some((s, key, levels)) = self.heap.pop() else {
            return Ok(true);
        };
        meter.work.heap_steps += levels as u64;
        if best.is_some_and(|(b, _)| key >= b) {
            return Ok(true); // every remaining route costs at least `key`
        }
        let reached = match self.state_space() {
            StateSpace::Vertices => self.expand_vertex(query, ends, s, best, meter)?,
            StateSpace::EdgeStates => self.expand_edge_state(s, key, best, meter)?,
        };
        if reached {
            return Ok(true);
        }
        meter.check()?;
        Ok(false)
    }

    /// The vertices a search over vertices walks: the network's, or in Voronoi mode the
    /// onboard graph's (rebuilt when a threat pops up). The five accessors below are the one
    /// place the vertex search tells the two graphs apart.
    pub(super) fn search_vertex_count(&self) -> u32 {
        match &self.state {
            ModeState::Roadmap(_) | ModeState::Terrain(_) | ModeState::Landmark(_) => {
                self.network.vertex_count()
            }
            ModeState::Voronoi(state) => state.graph().vertex_count(),
        }
    }

    /// Where search vertex `v` lies.
    pub(super) fn search_vertex_position(&self, v: u32) -> Option<Vec2> {
        match &self.state {
            ModeState::Roadmap(_) | ModeState::Terrain(_) | ModeState::Landmark(_) => {
                self.network.vertex(v).map(|p| p.position)
            }
            ModeState::Voronoi(state) => state.graph().vertex(v),
        }
    }

    /// The edges (Voronoi mode: half-edges) leaving search vertex `u`.
    fn search_out_edges(&self, u: u32) -> core::ops::Range<u32> {
        match &self.state {
            ModeState::Roadmap(_) | ModeState::Terrain(_) | ModeState::Landmark(_) => {
                self.network.out_edges(u)
            }
            ModeState::Voronoi(state) => state.graph().out_edges(u),
        }
    }

    /// Edge `e`'s cost and target.
    fn search_edge_cost_target(&self, e: u32) -> Option<(f32, u32)> {
        match &self.state {
            ModeState::Roadmap(_) | ModeState::Terrain(_) | ModeState::Landmark(_) => {
                self.network.edge_cost_target(e)
            }
            ModeState::Voronoi(state) => {
                let h = state.graph().half_edge(e)?;
                Some((state.graph().edge_cost(h.edge as u32)?, h.target as u32))
            }
        }
    }

    /// Edge `e`'s source.
    pub(super) fn search_edge_source(&self, e: u32) -> Option<u32> {
        match &self.state {
            ModeState::Roadmap(_) | ModeState::Terrain(_) | ModeState::Landmark(_) => {
                self.network.edge_source(e)
            }
            ModeState::Voronoi(state) => state.graph().half_edge(e).map(|h| h.source as u32),
        }
    }

    /// The A* heuristic at `p` (0 for Dijkstra).
    #[inline(always)]
    fn heuristic(query: &Query, p: Vec2) -> f32 {
        match query.search {
            Search::Dijkstra => 0.0,
            Search::AStar => p.distance(query.goal.position) * HEURISTIC_SCALE,
        }
    }

    /// Queues the start of a search over vertices: the start vertex at cost 0, or the start
    /// links' vertices at the links' lengths.
    fn seed_vertices(
        &mut self,
        query: &Query,
        ends: Ends,
        meter: &mut Meter,
    ) -> Result<(), PlanError> {
        if let Ends::Landmark {
            from: LandmarkEnd::Vertex(from),
            ..
        } = ends
        {
            let (Some(d), Some(via)) = (
                self.dist.get_mut(from as usize),
                self.via.get_mut(from as usize),
            ) else {
                return Err(PlanError::Internal);
            };
            *d = 0.0;
            *via = FROM_START;
            meter.work.heap_steps += self.heap.push_or_decrease(from, 0.0) as u64;
        }
        let links = match ends {
            Ends::Links => self.start_links.len(),
            Ends::Landmark {
                from: LandmarkEnd::Online,
                ..
            } => self.online_links(LinkSide::Start).len(),
            Ends::Landmark {
                from: LandmarkEnd::Vertex(_),
                ..
            } => 0,
        };
        for k in 0..links {
            let link = match ends {
                Ends::Links => self.start_links.get(k).map(|l| (l.vertex, l.cost)),
                Ends::Landmark { .. } => self
                    .online_links(LinkSide::Start)
                    .get(k)
                    .map(|l| (l.vertex, l.length)),
            };
            let (vertex, cost) = link.ok_or(PlanError::Internal)?;
            self.seed_link(query, k, vertex, cost, meter)?;
        }
        Ok(())
    }

    /// Queues `vertex` at `cost`, reached from start link `k`, unless it is queued cheaper.
    fn seed_link(
        &mut self,
        query: &Query,
        k: usize,
        vertex: u32,
        cost: f32,
        meter: &mut Meter,
    ) -> Result<(), PlanError> {
        let v = vertex as usize;
        let (Some(d), Some(via)) = (self.dist.get_mut(v), self.via.get_mut(v)) else {
            return Err(PlanError::Internal);
        };
        if self.heap.state(vertex) == ItemState::Unseen || cost < *d {
            *d = cost;
            *via = FROM_START + k as u32;
            let h = self
                .search_vertex_position(vertex)
                .map_or(0.0, |p| Self::heuristic(query, p));
            meter.work.heap_steps += self.heap.push_or_decrease(vertex, cost + h) as u64;
        }
        Ok(())
    }

    /// Expands vertex `u`: offers the goal links that leave it to `best` (resolving a pending
    /// one first unless its lower bound shows it cannot improve `best`), relaxes its usable
    /// edges. Returns whether `u` is the search's target vertex ([`Ends::target`]; popped with
    /// its final cost: no cheaper route remains, and `best` is set to it).
    fn expand_vertex(
        &mut self,
        query: &Query,
        ends: Ends,
        u: u32,
        best: &mut Option<(f32, Arrival)>,
        meter: &mut Meter,
    ) -> Result<bool, PlanError> {
        let du = self
            .dist
            .get(u as usize)
            .copied()
            .ok_or(PlanError::Internal)?;
        if let Some(to) = ends.target() {
            if u == to {
                *best = Some((du, Arrival::AtVertex));
                return Ok(true);
            }
        }
        if let Ends::Landmark {
            to: LandmarkEnd::Online,
            ..
        } = ends
        {
            self.offer_online_goal_links(u, du, best, meter);
        }
        meter.work.relaxations += self.goal_links.len() as u64;
        for k in 0..self.goal_links.len() {
            let Some(&link) = self.goal_links.get(k) else {
                return Err(PlanError::Internal);
            };
            if link.vertex == u {
                if link.pending && best.is_some_and(|(b, _)| du + link.cost >= b) {
                    continue; // its shortest clear path is no shorter than `cost`
                }
                let link = self.resolve_goal_link(k, &query.goal, meter)?;
                let total = du + link.cost;
                if best.is_none_or(|(b, _)| total < b) {
                    *best = Some((total, Arrival::FromState { state: u, link: k }));
                }
            }
        }
        let edges = self.search_out_edges(u);
        meter.work.relaxations += edges.end.saturating_sub(edges.start) as u64;
        // An edge's cost and target if the search may use it (`Some(None)`: it may not;
        // `None`: unreadable). The roadmap's without matching the mode for every edge.
        match self.state {
            ModeState::Roadmap(_) => self.relax_edges(query, du, edges, meter, |me, e| {
                if me.is_edge_enabled(e) {
                    me.network.edge_cost_target(e).map(Some)
                } else {
                    Some(None)
                }
            })?,
            ModeState::Terrain(_) | ModeState::Landmark(_) | ModeState::Voronoi(_) => self
                .relax_edges(query, du, edges, meter, |me, e| {
                    if me.is_edge_usable_from(u, e) {
                        me.search_edge_cost_target(e).map(Some)
                    } else {
                        Some(None)
                    }
                })?,
        }
        Ok(false)
    }

    /// Relaxes `edges` out of a vertex popped at cost `du`: `usable` gives an edge's cost and
    /// target if the search may use it (see [`Planner::expand_vertex`]).
    #[inline(always)]
    fn relax_edges(
        &mut self,
        query: &Query,
        du: f32,
        edges: core::ops::Range<u32>,
        meter: &mut Meter,
        usable: impl Fn(&Self, u32) -> Option<Option<(f32, u32)>>,
    ) -> Result<(), PlanError> {
        for e in edges {
            let Some((cost, t)) = usable(self, e).ok_or(PlanError::Internal)? else {
                continue;
            };
            let candidate = du + cost;
            let state = self.heap.state(t);
            let (Some(dt), Some(via)) =
                (self.dist.get_mut(t as usize), self.via.get_mut(t as usize))
            else {
                return Err(PlanError::Internal);
            };
            if state == ItemState::Unseen || (state == ItemState::Queued && candidate < *dt) {
                *dt = candidate;
                *via = e;
                let h = match query.search {
                    Search::Dijkstra => 0.0, // without reading the vertex
                    Search::AStar => self
                        .search_vertex_position(t)
                        .map_or(0.0, |p| Self::heuristic(query, p)),
                };
                meter.work.heap_steps += self.heap.push_or_decrease(t, candidate + h) as u64;
            }
        }
        Ok(())
    }

    /// The one walk-back of every search: follows search states back along their
    /// predecessors from `from`. `step` is given each state (one vertex scan each) and returns
    /// the state before it, or `None` at a start. The predecessors form a tree over at most
    /// `limit + 1` states, so more steps mean a broken invariant ([`PlanError::Internal`]).
    /// Returns the number of steps taken before the start: the route's network edges.
    pub(super) fn walk_states(
        &self,
        from: u32,
        limit: u32,
        meter: &mut Meter,
        mut step: impl FnMut(u32) -> Result<Option<u32>, PlanError>,
    ) -> Result<u32, PlanError> {
        let mut s = from;
        for taken in 0..=limit {
            meter.work.vertex_scans += 1;
            match step(s)? {
                Some(previous) => s = previous,
                None => return Ok(taken),
            }
        }
        Err(PlanError::Internal)
    }

    /// [`Planner::walk_states`] over vertices (roadmap and landmark searches): calls `visit`
    /// with each network edge, goal end first, from vertex `to`. Returns the number of edges
    /// and the start link the walk ends at.
    pub(super) fn walk_vertices(
        &self,
        to: u32,
        meter: &mut Meter,
        mut visit: impl FnMut(u32) -> Result<(), PlanError>,
    ) -> Result<(u32, Option<usize>), PlanError> {
        let mut start = None;
        let edges = self.walk_states(to, self.search_vertex_count(), meter, |v| {
            let via = self
                .via
                .get(v as usize)
                .copied()
                .ok_or(PlanError::Internal)?;
            if via >= FROM_START {
                start = Some((via - FROM_START) as usize);
                return Ok(None);
            }
            visit(via)?;
            Ok(Some(
                self.search_edge_source(via).ok_or(PlanError::Internal)?,
            ))
        })?;
        Ok((edges, start))
    }

    /// Walks back from the goal link: calls `visit` with each path of the route, goal end first.
    /// Returns the number of network edges on the route.
    fn walk_back(
        &self,
        link: &Link,
        meter: &mut Meter,
        visit: &mut dyn FnMut(&DubinsPath),
    ) -> Result<u32, PlanError> {
        visit(&link.path);
        let (edges, start) = self.walk_vertices(link.vertex, meter, |e| {
            visit(&self.network.edge_path(e).ok_or(PlanError::Internal)?);
            Ok(())
        })?;
        let start = start
            .and_then(|k| self.start_links.get(k))
            .ok_or(PlanError::Internal)?;
        visit(&start.path);
        Ok(edges)
    }

    /// Replaces the route with the one `arrival` describes, after `exit` when the start had
    /// to leave a keep-out region, if it fits in `R` paths and `R` primitives.
    #[inline(never)] // once per query; inlined, its frame would add to the step's (slice.rs)
    pub(super) fn write_route(
        &mut self,
        arrival: Arrival,
        exit: Option<&DubinsPath>,
        meter: &mut Meter,
    ) -> Result<RouteSummary, PlanError> {
        let (link, direct) = match arrival {
            Arrival::AtVertex => return Err(PlanError::Internal),
            Arrival::Direct(p) => (None, Some(p)),
            Arrival::FromState { link, .. } => (
                Some(*self.goal_links.get(link).ok_or(PlanError::Internal)?),
                None,
            ),
        };
        self.write_path_route(meter, link.is_some(), |me, meter, visit| {
            let edges = match (link, direct) {
                (Some(link), _) => me.walk_back(&link, meter, visit),
                (None, Some(path)) => {
                    visit(&path);
                    Ok(0)
                }
                (None, None) => Err(PlanError::Internal),
            }?;
            if let Some(path) = exit {
                visit(path); // the walk is goal end first: the exit is the route's first path
            }
            Ok(edges)
        })
    }

    /// The one route writer of the modes whose routes are chains of Dubins paths (roadmap and
    /// terrain): replaces the route by the paths `walk` visits (goal end first) if they fit in
    /// `R` paths and `R` primitives, and otherwise leaves the route as it was. `walk` returns
    /// the number of network edges on the route; it runs twice, once to count and, after the
    /// budget is settled (the second walk charged when `charge_replay`), once to fill.
    pub(super) fn write_path_route(
        &mut self,
        meter: &mut Meter,
        charge_replay: bool,
        walk: impl Fn(&Self, &mut Meter, &mut dyn FnMut(&DubinsPath)) -> Result<u32, PlanError>,
    ) -> Result<RouteSummary, PlanError> {
        let count = |p: &DubinsPath| p.primitives().iter().flatten().count() as u32;
        let (mut needed, mut paths) = (0u32, 0u32);
        let network_edges = walk(self, meter, &mut |p| {
            needed += count(p);
            paths += 1;
        })?;
        if needed as usize > R || paths as usize > R {
            return Err(PlanError::RouteTooLong {
                primitives: needed.max(paths),
                capacity: R as u32,
            });
        }
        // Charge the second walk (identical to the first) before it starts, so that the budget
        // is settled before the old route is touched.
        if charge_replay {
            meter.work.vertex_scans += network_edges as u64 + 1;
        }
        meter.check()?;
        // The walk below repeats the one that just succeeded: the new route replaces the old one.
        let mut chain = core::mem::take(&mut self.paths);
        chain.clear();
        let mut replay = Meter::new(u64::MAX);
        let walked = walk(self, &mut replay, &mut |p| {
            let _ = chain.push(*p);
        });
        chain.reverse();
        self.paths = chain;
        if walked.is_err() {
            // Unreachable: the same walk succeeded above. Fail closed rather than half-written.
            self.clear_route();
            return Err(PlanError::Internal);
        }
        Ok(self.finish_route(network_edges, meter))
    }

    /// Rebuilds the primitives from the new chain of paths and records the route's summary.
    pub(super) fn finish_route(&mut self, network_edges: u32, meter: &Meter) -> RouteSummary {
        self.flatten_route();
        let summary = RouteSummary {
            length: self.route.iter().map(Primitive::length).sum(),
            primitives: self.route.len() as u32,
            network_edges,
            arrival_heading: self.paths.last().map_or(0.0, |p| p.end().heading),
            work: meter.work,
            exit: None,
        };
        self.summary = SummarySlot::Full(summary);
        summary
    }

    /// Rebuilds the primitives from the route's paths (which fit: each path has ≤ 3 primitives
    /// and callers only shorten the chain or keep its primitive count within `R`).
    pub(super) fn flatten_route(&mut self) {
        self.route.clear();
        for path in &self.paths {
            for prim in path.primitives().into_iter().flatten() {
                let _ = self.route.push(prim);
            }
        }
    }

    pub(super) fn clear_route(&mut self) {
        self.paths.clear();
        self.route.clear();
        self.forget_route_altitudes();
        self.summary = SummarySlot::Empty;
    }
}
