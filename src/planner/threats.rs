//! Voronoi mode's state, which `planner::voronoi` plans with: the threats in force, their
//! diagram (exact, incremental, in fixed memory), and the search graph over it — the
//! diagram's edges clipped to the network's box, as half-edges grouped by source so that the
//! one vertex search walks them like a network's edges — with each edge's cost and whether
//! it is clear.

use crate::geometry::spline::Piece;
use crate::geometry::voronoi::VoronoiError;
use crate::geometry::voronoi::{
    graph_edge_bound, graph_vertex_bound, Bounds, Delaunay, GraphEdge, VoronoiGraph,
};
use crate::geometry::Vec2;
use crate::network::{LoadError, Network};
use heapless::Vec;

// For the documentation's links only.
#[cfg(doc)]
use crate::planner::Planner;

/// Where a threat in the planner's list came from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum ThreatOrigin {
    /// Site `i` of the network.
    Network(u32),
    /// Added in flight with [`Planner::add_threat`], under this id.
    Popped(u8),
}

/// A threat the planner avoids: a radar site and its exposure's reference distance.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Threat {
    /// Where the radar is.
    pub position: Vec2,
    /// Flying at this distance from the site costs as much exposure per metre as length.
    pub radius: f32,
    /// Where it came from.
    pub origin: ThreatOrigin,
}

/// What [`Planner::add_threat`] and [`Planner::remove_threat`] did.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ThreatSummary {
    /// The threat's id (for [`Planner::remove_threat`]).
    pub id: u8,
    /// Threats now in force.
    pub threats: u32,
    /// Vertices and undirected edges of the rebuilt search graph.
    pub graph: (u32, u32),
    /// The rebuild's counted work: the diagram's insertions (its comparisons, predicates and
    /// triangle visits), the graph built from it ([`VoronoiGraph::work`]) and the grouping of
    /// its half-edges; at most [`threat_rebuild_work_bound`](crate::planner::threat_rebuild_work_bound).
    pub work: u64,
}

/// Why [`Planner::add_threat`], [`Planner::remove_threat`] or
/// [`Planner::set_threat_weight`] refused.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum ThreatError {
    /// The loaded network is not a Voronoi network.
    NotVoronoi,
    /// A position, radius or weight is not finite.
    NonFinite,
    /// The radius is not positive, or the weight is outside [0, 1].
    OutOfRange,
    /// The position lies outside the network's box.
    OutsideBox,
    /// [`MAX_THREATS`] threats are in force already.
    Full,
    /// Another threat lies at this position (the same point on the diagram's 1/16 m grid).
    Duplicate {
        /// The threat already there (an index into [`Planner::threats`]).
        existing: u32,
    },
    /// No threat added in flight has this id.
    UnknownId {
        /// The id given.
        id: u8,
    },
    /// The rebuilt graph would not fit the planner's storage (never for at most
    /// [`MAX_THREATS`] sites: the storage is sized by the diagram's bounds).
    GraphFull,
}

impl From<VoronoiError> for ThreatError {
    fn from(e: VoronoiError) -> Self {
        match e {
            VoronoiError::DuplicateSite { existing, .. } => ThreatError::Duplicate { existing },
            VoronoiError::TooManySites { .. } => ThreatError::Full,
            _ => ThreatError::GraphFull,
        }
    }
}

impl core::fmt::Display for ThreatError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            ThreatError::NotVoronoi => write!(f, "the network is not a Voronoi network"),
            ThreatError::NonFinite => write!(f, "a position, radius or weight is not finite"),
            ThreatError::OutOfRange => {
                write!(
                    f,
                    "the radius is not positive, or the weight outside [0, 1]"
                )
            }
            ThreatError::OutsideBox => write!(f, "the threat lies outside the network's box"),
            ThreatError::Full => write!(f, "{MAX_THREATS} threats are in force already"),
            ThreatError::Duplicate { existing } => {
                write!(f, "threat {existing} lies at the same position")
            }
            ThreatError::UnknownId { id } => write!(f, "no threat added in flight has id {id}"),
            ThreatError::GraphFull => write!(f, "the rebuilt graph does not fit its storage"),
        }
    }
}

#[cfg(feature = "std")]
impl std::error::Error for ThreatError {}

/// The most threats a Voronoi planner holds: the network's sites and those added in flight.
pub const MAX_THREATS: usize = 32;

/// Triangle slots of the diagram (finite and ghost triangles of `n` sites: at most `2n`).
const TRIANGLES: usize = 2 * MAX_THREATS;

/// The most vertices of the search graph for [`MAX_THREATS`] sites (the diagram's bound): a
/// Voronoi planner needs a search-state capacity `V` at least this.
pub const VORONOI_GRAPH_VERTICES: usize = graph_vertex_bound(MAX_THREATS);

/// The most undirected edges of the search graph for [`MAX_THREATS`] sites.
pub const VORONOI_GRAPH_EDGES: usize = graph_edge_bound(MAX_THREATS);

/// Half-edges: each undirected edge in both directions.
const HALF_EDGES: usize = 2 * VORONOI_GRAPH_EDGES;

/// The most pieces a smoothed route holds: a corner piece and a straight piece per corner,
/// so routes of up to about 30 corners (a route through 32 threats' diagram turns at far
/// fewer); a longer one is refused as [`PlanError::RouteTooLong`](crate::planner::PlanError).
pub const MAX_ROUTE_PIECES: usize = 64;

/// One direction of a graph edge.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct HalfEdge {
    /// The vertex it leaves.
    pub source: u16,
    /// The vertex it reaches.
    pub target: u16,
    /// The undirected edge it belongs to.
    pub edge: u16,
}

/// The search graph over the threats in force.
#[derive(Clone, Debug)]
pub struct SearchGraph {
    diagram: VoronoiGraph<VORONOI_GRAPH_VERTICES, VORONOI_GRAPH_EDGES>,
    /// Slots `offsets[v] .. offsets[v + 1]` of `half_edges` leave vertex `v`.
    offsets: [u16; VORONOI_GRAPH_VERTICES + 1],
    /// Half-edge ids grouped by source: id `2e` runs along edge `e` from `a` to `b`, `2e + 1`
    /// back.
    half_edges: [u16; HALF_EDGES],
    /// Each undirected edge's cost k·L + (1 − k)·exposure, set before each search.
    cost: [f32; VORONOI_GRAPH_EDGES],
    /// Bit `e`: undirected edge `e` is clear of no-fly zones and pop-ups, set before each
    /// search.
    clear: [u32; VORONOI_GRAPH_EDGES.div_ceil(32)],
}

impl SearchGraph {
    const fn new() -> Self {
        SearchGraph {
            diagram: VoronoiGraph::new(),
            offsets: [0; VORONOI_GRAPH_VERTICES + 1],
            half_edges: [0; HALF_EDGES],
            cost: [0.0; VORONOI_GRAPH_EDGES],
            clear: [0; VORONOI_GRAPH_EDGES.div_ceil(32)],
        }
    }

    /// The graph's vertices: Voronoi vertices, clip points on the box and its corners.
    pub fn vertices(&self) -> &[Vec2] {
        self.diagram.vertices()
    }

    /// The graph's undirected edges.
    pub fn edges(&self) -> &[GraphEdge] {
        self.diagram.edges()
    }

    /// Number of vertices.
    pub fn vertex_count(&self) -> u32 {
        self.diagram.vertices().len() as u32
    }

    /// Vertex `v`'s position.
    pub fn vertex(&self, v: u32) -> Option<Vec2> {
        self.diagram.vertices().get(v as usize).copied()
    }

    /// The half-edges leaving vertex `v`.
    pub fn out_edges(&self, v: u32) -> core::ops::Range<u32> {
        match (
            self.offsets.get(v as usize),
            self.offsets.get(v as usize + 1),
        ) {
            (Some(a), Some(b)) if (v as usize) < self.diagram.vertices().len() => {
                *a as u32..*b as u32
            }
            _ => 0..0,
        }
    }

    /// The half-edge in slot `k` of the grouping (slots `out_edges(v)` leave `v`).
    pub fn half_edge(&self, k: u32) -> Option<HalfEdge> {
        let last = self.offsets.get(self.diagram.vertices().len()).copied()?;
        if k >= last as u32 {
            return None;
        }
        let h = *self.half_edges.get(k as usize)?;
        let e = self.diagram.edges().get(h as usize / 2)?;
        let (source, target) = if h % 2 == 0 { (e.a, e.b) } else { (e.b, e.a) };
        Some(HalfEdge {
            source,
            target,
            edge: h / 2,
        })
    }

    /// The cost of undirected edge `e` as of the last search.
    pub fn edge_cost(&self, e: u32) -> Option<f32> {
        self.cost.get(e as usize).copied()
    }

    /// Whether undirected edge `e` was clear at the last search.
    pub fn is_clear(&self, e: u32) -> bool {
        self.clear
            .get(e as usize / 32)
            .is_some_and(|w| w & (1 << (e % 32)) != 0)
    }

    /// The ends of undirected edge `e`.
    pub fn edge_ends(&self, e: u32) -> Option<(Vec2, Vec2)> {
        let g = self.diagram.edges().get(e as usize)?;
        Some((self.vertex(g.a as u32)?, self.vertex(g.b as u32)?))
    }

    /// Sets edge `e`'s cost and whether it is clear.
    pub(super) fn set_edge(&mut self, e: usize, cost: f32, clear: bool) {
        if let (Some(c), Some(w)) = (self.cost.get_mut(e), self.clear.get_mut(e / 32)) {
            *c = cost;
            let bit = 1u32 << (e % 32);
            *w = if clear { *w | bit } else { *w & !bit };
        }
    }

    /// Groups the half-edges by source (a counting sort): `offsets[v]` is the number of
    /// half-edges leaving vertices before `v`. Returns its steps: each edge twice (counted,
    /// then placed) and each vertex once (the running sum), `2E + V`.
    fn index_half_edges(&mut self) -> u64 {
        let n = self.diagram.vertices().len();
        self.offsets = [0; VORONOI_GRAPH_VERTICES + 1];
        for g in self.diagram.edges() {
            for v in [g.a, g.b] {
                if let Some(o) = self.offsets.get_mut(v as usize + 1) {
                    *o += 1;
                }
            }
        }
        for v in 0..n {
            let before = self.offsets.get(v).copied().unwrap_or(0);
            if let Some(o) = self.offsets.get_mut(v + 1) {
                *o += before;
            }
        }
        let mut next = self.offsets;
        for (e, g) in self.diagram.edges().iter().enumerate() {
            for (h, source) in [(2 * e, g.a), (2 * e + 1, g.b)] {
                let Some(slot) = next.get_mut(source as usize) else {
                    continue;
                };
                if let Some(id) = self.half_edges.get_mut(*slot as usize) {
                    *id = h as u16;
                }
                *slot += 1;
            }
        }
        let edges = self.diagram.edges().len() as u64;
        2 * edges + n as u64
    }
}

/// Voronoi mode's planner state, in storage the caller provides to
/// [`Planner::load_voronoi`](crate::planner::Planner::load_voronoi) (about 15 KB for
/// [`MAX_THREATS`] threats: `core::mem::size_of::<VoronoiStorage>()`), so that only a planner
/// of Voronoi networks pays for it. `new` is `const` and all zero bytes: a `static` costs
/// RAM (`.bss`), not flash.
#[derive(Clone, Debug)]
pub struct VoronoiStorage {
    diagram: Delaunay<MAX_THREATS, TRIANGLES>,
    threats: Vec<Threat, MAX_THREATS>,
    graph: SearchGraph,
    bounds: Bounds,
    /// The weight k of length against exposure in force.
    pub(in crate::planner) weight: f32,
    /// The network's curvature limit.
    pub(in crate::planner) kappa_max: f32,
    /// The last route's smoothed pieces.
    pub(in crate::planner) pieces: Vec<Piece, MAX_ROUTE_PIECES>,
    /// The largest distance of a route chord from its piece, metres (the chord bound).
    pub(in crate::planner) chord_deviation: f32,
}

impl Default for VoronoiStorage {
    fn default() -> Self {
        Self::new()
    }
}

impl VoronoiStorage {
    /// Empty storage.
    pub const fn new() -> Self {
        VoronoiStorage {
            diagram: Delaunay::new(),
            threats: Vec::new(),
            graph: SearchGraph::new(),
            bounds: Bounds {
                min: Vec2::new(0.0, 0.0),
                max: Vec2::new(0.0, 0.0),
            },
            weight: 0.0,
            kappa_max: 0.0,
            pieces: Vec::new(),
            chord_deviation: 0.0,
        }
    }

    /// Fills the storage, in place, with the state of a loaded Voronoi network: its sites'
    /// diagram and graph, which must be the graph the image stores (same vertex and edge
    /// counts, every stored vertex at the built vertex of the same index within the position
    /// tolerance).
    pub(in crate::planner) fn init(&mut self, network: &Network<'_>) -> Result<(), LoadError> {
        let (Some(v), Some(bounds)) = (network.voronoi().copied(), network.voronoi_bounds()) else {
            return Err(LoadError::UnknownMode {
                mode: network.mode().code(),
            });
        };
        self.diagram.clear();
        self.threats.clear();
        self.pieces.clear();
        self.bounds = bounds;
        self.weight = v.threat_weight;
        self.kappa_max = v.kappa_max;
        self.chord_deviation = 0.0;
        let refused = LoadError::ThreatSitesRefused {
            threats: v.threat_count,
            refused: 0,
        };
        for t in 0..v.threat_count {
            let (position, radius) = network.threat(t).ok_or(refused)?;
            let threat = Threat {
                position,
                radius,
                origin: ThreatOrigin::Network(t),
            };
            if self.threats.push(threat).is_err() || self.diagram.insert(position).is_err() {
                return Err(LoadError::ThreatSitesRefused {
                    threats: v.threat_count,
                    refused: t,
                });
            }
        }
        self.rebuild_graph().map_err(|_| refused)?;
        self.check_against(network)
    }

    /// The stored graph must be the one built here: the same numbers of vertices and of
    /// edges (stored in both directions), and every stored vertex at the built vertex of the
    /// same index.
    fn check_against(&self, network: &Network<'_>) -> Result<(), LoadError> {
        let built = (self.graph.vertex_count(), self.graph.edges().len() as u32);
        let stored = (network.vertex_count(), network.edge_count() / 2);
        let mismatch = LoadError::VoronoiMismatch { stored, built };
        if stored != built || !network.edge_count().is_multiple_of(2) {
            return Err(mismatch);
        }
        for v in 0..built.0 {
            let (Some(s), Some(b)) = (network.vertex(v), self.graph.vertex(v)) else {
                return Err(mismatch);
            };
            if s.position.distance(b) > crate::network::position_tolerance(b) {
                return Err(mismatch);
            }
        }
        Ok(())
    }

    /// Rebuilds the search graph from the diagram (costs and clearance are set per search).
    /// Returns its work: the graph's ([`VoronoiGraph::work`]) and the half-edges' grouping.
    fn rebuild_graph(&mut self) -> Result<u64, ThreatError> {
        self.diagram.graph(&self.bounds, &mut self.graph.diagram)?;
        let grouping = self.graph.index_half_edges();
        Ok(self.graph.diagram.work().saturating_add(grouping))
    }

    /// The threats in force.
    pub(in crate::planner) fn threats(&self) -> &[Threat] {
        &self.threats
    }

    /// The search graph.
    pub(in crate::planner) fn graph(&self) -> &SearchGraph {
        &self.graph
    }

    /// The search graph, to set costs before a search.
    pub(in crate::planner) fn graph_mut(&mut self) -> &mut SearchGraph {
        &mut self.graph
    }

    fn summary(&self, id: u8, work: u64) -> ThreatSummary {
        ThreatSummary {
            id,
            threats: self.threats.len() as u32,
            graph: (self.graph.vertex_count(), self.graph.edges().len() as u32),
            work,
        }
    }

    /// Adds a threat popped up in flight (checked finite and positive by the caller).
    pub(in crate::planner) fn add(
        &mut self,
        position: Vec2,
        radius: f32,
    ) -> Result<ThreatSummary, ThreatError> {
        let b = self.bounds;
        if position.x < b.min.x
            || position.x > b.max.x
            || position.y < b.min.y
            || position.y > b.max.y
        {
            return Err(ThreatError::OutsideBox);
        }
        if self.threats.is_full() {
            return Err(ThreatError::Full);
        }
        let id = (0..=u8::MAX)
            .find(|id| {
                !self
                    .threats
                    .iter()
                    .any(|t| t.origin == ThreatOrigin::Popped(*id))
            })
            .ok_or(ThreatError::Full)?;
        // A refused insertion leaves the diagram as it was (it checks before it changes).
        let work_before = self.diagram.work();
        self.diagram.insert(position)?;
        let _ = self.threats.push(Threat {
            position,
            radius,
            origin: ThreatOrigin::Popped(id),
        });
        // The graph's storage holds the bounds of MAX_THREATS sites: it fits.
        let graph = self.rebuild_graph()?;
        let insertion = self.diagram.work().saturating_sub(work_before);
        Ok(self.summary(id, insertion.saturating_add(graph)))
    }

    /// Removes threat `id` added in flight, rebuilding the diagram from the others.
    pub(in crate::planner) fn remove(&mut self, id: u8) -> Result<ThreatSummary, ThreatError> {
        let at = self
            .threats
            .iter()
            .position(|t| t.origin == ThreatOrigin::Popped(id))
            .ok_or(ThreatError::UnknownId { id })?;
        let mut kept: Vec<Vec2, MAX_THREATS> = Vec::new();
        for (i, t) in self.threats.iter().enumerate() {
            if i != at {
                let _ = kept.push(t.position);
            }
        }
        // The remaining sites were accepted before, in this order: the rebuild succeeds.
        self.diagram.rebuild(&kept)?;
        let _ = self.threats.remove(at);
        let graph = self.rebuild_graph()?;
        Ok(self.summary(id, self.diagram.work().saturating_add(graph)))
    }
}
