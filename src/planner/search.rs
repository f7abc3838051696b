//! The query: validate, connect, search (Dijkstra or A*), and write the route.

use super::heap::ItemState;
use super::{Link, Meter, PlanError, Planner, Query, QueryField, RouteSummary, Search, FROM_START};
use crate::geometry::{DubinsPath, Primitive, Vec2};

/// How the best route found so far reaches the goal.
#[derive(Clone, Copy, Debug)]
pub(super) enum Arrival {
    /// Straight from the start, by this path.
    Direct(DubinsPath),
    /// Through the network, leaving it at goal link `k`.
    FromVertex { link: usize },
    /// At the target vertex (landmark mode: the goal is a vertex).
    AtVertex,
}

/// Where a vertex search starts and what it looks for.
#[derive(Clone, Copy, Debug)]
pub(super) enum Ends {
    /// From the start links to the goal links (roadmap mode).
    Links,
    /// From one vertex (cost 0) to another (landmark mode).
    Vertices {
        /// The start vertex.
        from: u32,
        /// The goal vertex.
        to: u32,
    },
}

/// A* heuristic scale: the chord to the goal shrunk by 1e-4 so that f32 rounding of stored edge
/// costs (relative error ~1e-7) cannot make it exceed a true remaining cost.
const HEURISTIC_SCALE: f32 = 1.0 - 1e-4;

impl<'n, const V: usize, const E: usize, const P: usize, const R: usize> Planner<'n, V, E, P, R> {
    /// Plans from `query.start` to `query.goal` through the network, counting work against
    /// `budget` (compare [`Planner::worst_case_work`]). On success the route replaces the
    /// previous one; on any error the previous route is left as it was.
    pub fn plan(&mut self, query: &Query, budget: u64) -> Result<RouteSummary, PlanError> {
        let mut meter = Meter::new(budget);
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
        if self.network.terrain().is_some() {
            return self.plan_terrain(query, &mut meter);
        }
        if self.network.landmark().is_some() {
            return self.plan_landmark(query, &mut meter);
        }
        self.check_free(query.start.position, QueryField::Start, &mut meter)?;
        self.check_free(query.goal.position, QueryField::Goal, &mut meter)?;

        self.connect_start(&query.start, &mut meter)?;
        self.connect_goal(&query.goal, &mut meter)?;
        let direct = if query.start.position.distance(query.goal.position)
            <= self.config().connect_radius_m
        {
            self.best_clear_path_to_goal(&query.start, &query.goal, &mut meter)?
        } else {
            None
        };
        if self.start_links.is_empty() && direct.is_none() {
            return Err(PlanError::StartUnconnected);
        }
        if self.goal_links.is_empty() && direct.is_none() {
            return Err(PlanError::GoalUnconnected);
        }
        let arrival = self.search(query, Ends::Links, direct, &mut meter)?;
        self.write_route(arrival, &mut meter)
    }

    /// Dijkstra (or A*) from the start links (or a start vertex); returns how the cheapest
    /// route arrives. Edges are relaxed only when [`Planner::is_edge_usable`].
    pub(super) fn search(
        &mut self,
        query: &Query,
        ends: Ends,
        direct: Option<DubinsPath>,
        meter: &mut Meter,
    ) -> Result<Arrival, PlanError> {
        let n = self.network.vertex_count() as usize;
        self.heap.clear(n);
        meter.work.vertex_scans += n as u64;
        let goal = query.goal.position;
        let heuristic = |p: Vec2| match query.search {
            Search::Dijkstra => 0.0,
            Search::AStar => p.distance(goal) * HEURISTIC_SCALE,
        };
        let mut best = direct.map(|p| (p.length(), Arrival::Direct(p)));

        if let Ends::Vertices { from, .. } = ends {
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
            Ends::Vertices { .. } => 0,
        };
        for (k, link) in self.start_links.iter().take(links).enumerate() {
            let v = link.vertex as usize;
            let cost = link.path.length();
            let (Some(d), Some(via)) = (self.dist.get_mut(v), self.via.get_mut(v)) else {
                return Err(PlanError::Internal);
            };
            if self.heap.state(link.vertex) == ItemState::Unseen || cost < *d {
                *d = cost;
                *via = FROM_START + k as u32;
                let h = self
                    .network
                    .vertex(link.vertex)
                    .map_or(0.0, |p| heuristic(p.position));
                meter.work.heap_steps += self.heap.push_or_decrease(link.vertex, cost + h) as u64;
            }
        }
        meter.check()?;

        while let Some((u, key, levels)) = self.heap.pop() {
            meter.work.heap_steps += levels as u64;
            if best.is_some_and(|(b, _)| key >= b) {
                break; // every remaining route costs at least `key`
            }
            let du = self
                .dist
                .get(u as usize)
                .copied()
                .ok_or(PlanError::Internal)?;
            if let Ends::Vertices { to, .. } = ends {
                if u == to {
                    // Popped with its final cost: no cheaper route remains.
                    best = Some((du, Arrival::AtVertex));
                    break;
                }
            }
            for (k, link) in self.goal_links.iter().enumerate() {
                meter.work.relaxations += 1;
                if link.vertex == u {
                    let total = du + link.path.length();
                    if best.is_none_or(|(b, _)| total < b) {
                        best = Some((total, Arrival::FromVertex { link: k }));
                    }
                }
            }
            for e in self.network.out_edges(u) {
                meter.work.relaxations += 1;
                if !self.is_edge_usable(e) {
                    continue;
                }
                let Some((cost, t)) = self.network.edge_cost_target(e) else {
                    return Err(PlanError::Internal);
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
                    let h = self
                        .network
                        .vertex(t)
                        .map_or(0.0, |p| heuristic(p.position));
                    meter.work.heap_steps += self.heap.push_or_decrease(t, candidate + h) as u64;
                }
            }
            meter.check()?;
        }
        best.map(|(_, a)| a).ok_or(PlanError::NoRoute)
    }

    /// Walks back from the goal link: calls `visit` with each path of the route, goal end first.
    /// Returns the number of network edges on the route.
    fn walk_back(
        &self,
        link: &Link,
        meter: &mut Meter,
        mut visit: impl FnMut(&DubinsPath),
    ) -> Result<u32, PlanError> {
        visit(&link.path);
        let mut v = link.vertex;
        // Predecessors form a tree over at most |V| vertices: more steps mean a broken invariant.
        for edges in 0..=self.network.vertex_count() {
            meter.work.vertex_scans += 1;
            let via = self
                .via
                .get(v as usize)
                .copied()
                .ok_or(PlanError::Internal)?;
            if via >= FROM_START {
                let start = self
                    .start_links
                    .get((via - FROM_START) as usize)
                    .ok_or(PlanError::Internal)?;
                visit(&start.path);
                return Ok(edges);
            }
            let path = self.network.edge_path(via).ok_or(PlanError::Internal)?;
            visit(&path);
            v = path_source(&self.network, via)?;
        }
        Err(PlanError::Internal)
    }

    /// Replaces the route with the one `arrival` describes, if it fits in `R` paths and `R`
    /// primitives.
    fn write_route(
        &mut self,
        arrival: Arrival,
        meter: &mut Meter,
    ) -> Result<RouteSummary, PlanError> {
        let count = |p: &DubinsPath| p.primitives().iter().flatten().count() as u32;
        let (needed, paths, network_edges) = match arrival {
            Arrival::AtVertex => return Err(PlanError::Internal),
            Arrival::Direct(p) => (count(&p), 1, 0),
            Arrival::FromVertex { link } => {
                let link = *self.goal_links.get(link).ok_or(PlanError::Internal)?;
                let (mut needed, mut paths) = (0, 0);
                let edges = self.walk_back(&link, meter, |p| {
                    needed += count(p);
                    paths += 1;
                })?;
                (needed, paths, edges)
            }
        };
        if needed as usize > R || paths as usize > R {
            return Err(PlanError::RouteTooLong {
                primitives: needed.max(paths),
                capacity: R as u32,
            });
        }
        // Charge the second walk (identical to the first) before it starts, so that the budget
        // is settled before the old route is touched.
        if let Arrival::FromVertex { .. } = arrival {
            meter.work.vertex_scans += network_edges as u64 + 1;
        }
        meter.check()?;
        // The walk below repeats the one that just succeeded: the new route replaces the old one.
        let mut chain = core::mem::take(&mut self.paths);
        chain.clear();
        let walked = match arrival {
            Arrival::AtVertex => Err(PlanError::Internal),
            Arrival::Direct(p) => chain.push(p).map(|_| 0).map_err(|_| PlanError::Internal),
            Arrival::FromVertex { link } => match self.goal_links.get(link).copied() {
                Some(link) => {
                    let mut replay = Meter::new(u64::MAX);
                    self.walk_back(&link, &mut replay, |p| {
                        let _ = chain.push(*p);
                    })
                }
                None => Err(PlanError::Internal),
            },
        };
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
        };
        self.summary = Some(summary);
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

    fn clear_route(&mut self) {
        self.paths.clear();
        self.route.clear();
        self.summary = None;
    }
}

fn path_source(network: &crate::network::Network<'_>, edge: u32) -> Result<u32, PlanError> {
    network.edge_source(edge).ok_or(PlanError::Internal)
}
