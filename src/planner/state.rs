//! Each mode's mutable planner state, one variant per mode, set by [`Planner::load`].
//!
//! The state every mode shares (edge masks, pop-ups, distances, heap, links, route) lives in
//! [`Planner`] itself; what only one mode has lives here, so that a planner holds exactly its
//! network's mode's state and every operation that differs by mode matches on it once.
//!
//! [`Planner`]: super::Planner
//! [`Planner::load`]: super::Planner::load

use super::MAX_LINKS;
use crate::geometry::hermite::HermiteSegment;
use crate::network::Network;
use heapless::Vec;

/// The most overflight directions a rosette override holds (the network may have more; then
/// [`Planner::update_rosette`](super::Planner::update_rosette) refuses).
pub const MAX_ROSETTE_DIRECTIONS: usize = 24;

/// The most landmarks whose rosettes may be overridden at once.
pub const MAX_ROSETTE_OVERRIDES: usize = 8;

/// Cells visited and the most for one check, over the turn-arc checks of the last query.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ArcCheckStats {
    /// Turn arcs checked.
    pub arcs: u64,
    /// Cells visited by those checks.
    pub cells: u64,
    /// The most cells one check visited.
    pub most_cells: u64,
}

/// Terrain mode's state: the altitude in force and what the last query's turn checks cost.
#[derive(Clone, Copy, Debug)]
pub(super) struct TerrainState {
    /// The altitude and safety height set in flight (`None`: the network's).
    pub(super) altitude: Option<(f32, f32)>,
    /// Cells and edges with an elevation code at or above this are blocked at that altitude.
    pub(super) blocking: u8,
    /// The turn-arc checks of the last query.
    pub(super) arc_stats: ArcCheckStats,
}

impl TerrainState {
    /// The state after loading `network`: its own altitude and safety height.
    pub(super) fn for_network(network: &Network) -> Self {
        let mut s = TerrainState {
            altitude: None,
            blocking: 0,
            arc_stats: ArcCheckStats::default(),
        };
        s.blocking = s.blocking_code(network);
        s
    }

    /// The altitude and safety height in force (the network's until one is set).
    pub(super) fn altitude(&self, network: &Network) -> Option<(f32, f32)> {
        let t = network.terrain()?;
        Some(self.altitude.unwrap_or((t.altitude_m, t.safety_height_m)))
    }

    /// The blocking code of the altitude in force (0, blocking everything, without terrain).
    pub(super) fn blocking_code(&self, network: &Network) -> u8 {
        match (network.elevation_coding(), self.altitude(network)) {
            (Some(coding), Some((a, s))) => coding.blocking_code(a, s),
            _ => 0,
        }
    }
}

/// A landmark query's online link: one direct Hermite piece between the query's start or goal
/// and `vertex`, `length` metres long (`planner/landmark_connect.rs`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct OnlineLink {
    /// The network vertex the piece joins.
    pub(super) vertex: u32,
    /// The piece's length, metres: what the link costs the search.
    pub(super) length: f32,
}

/// Which end of a landmark query an online link joins.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum LinkSide {
    /// From the query's start to a vertex.
    Start,
    /// From a vertex to the query's goal.
    Goal,
}

/// Landmark mode's state: the weather, the in-flight rosettes, the range left at an online
/// start, and the last route.
#[derive(Clone, Debug)]
pub(super) struct LandmarkState<const R: usize> {
    /// The weather in force (an index into the network's weathers).
    pub(super) weather: u32,
    /// In-flight rosettes replacing the stored ones, per landmark.
    pub(super) rosettes: Vec<(u32, [f32; MAX_ROSETTE_DIRECTIONS]), MAX_ROSETTE_OVERRIDES>,
    /// The range left to a start that is not a network vertex, metres (`None`: the network's
    /// start range).
    pub(super) start_range_m: Option<f32>,
    /// The query's links from such a start.
    pub(super) start_links: Vec<OnlineLink, MAX_LINKS>,
    /// The query's links to a goal that is not the network's.
    pub(super) goal_links: Vec<OnlineLink, MAX_LINKS>,
    /// The last route's network edges, start to goal.
    pub(super) route_edges: Vec<u32, R>,
    /// The last route's piece from a start that is not a network vertex to its first edge.
    pub(super) start_piece: Option<HermiteSegment>,
    /// The last route's piece from its last edge to a goal that is not the network's.
    pub(super) goal_piece: Option<HermiteSegment>,
}

impl<const R: usize> LandmarkState<R> {
    /// Weather 0, no overrides, the network's start range, no route.
    pub(super) const fn new() -> Self {
        LandmarkState {
            weather: 0,
            rosettes: Vec::new(),
            start_range_m: None,
            start_links: Vec::new(),
            goal_links: Vec::new(),
            route_edges: Vec::new(),
            start_piece: None,
            goal_piece: None,
        }
    }
}

/// Which end of a roadmap query a link joins.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum LinkEnd {
    /// From the start to a vertex.
    Start,
    /// From a vertex to the goal.
    Goal,
}

/// Roadmap mode's state: what a three-dimensional roadmap's queries need beyond the planar
/// ones (`planner/vertical.rs`). A planar roadmap leaves it empty.
#[derive(Clone, Debug)]
pub(super) struct RoadmapState<const R: usize> {
    /// The start's and the goal's altitudes for the queries that follow, metres (`None`: not
    /// set; a three-dimensional roadmap refuses to plan without them).
    pub(super) altitudes: Option<(f32, f32)>,
    /// The last route's altitude at the end of each of its paths, metres (three-dimensional
    /// roadmaps; empty otherwise).
    pub(super) route_altitudes: Vec<f32, R>,
}

impl<const R: usize> RoadmapState<R> {
    /// No altitudes set, no route.
    pub(super) const fn new() -> Self {
        RoadmapState {
            altitudes: None,
            route_altitudes: Vec::new(),
        }
    }
}

/// The state of the loaded network's mode.
// Fixed memory: the planner reserves room for the largest variant once (no allocator to box
// it), which is still less than keeping every mode's state side by side.
#[allow(clippy::large_enum_variant)]
#[derive(Debug)]
pub(super) enum ModeState<'n, const R: usize> {
    /// Roadmap mode (also the state of a planner with no network).
    Roadmap(RoadmapState<R>),
    /// Terrain mode.
    Terrain(TerrainState),
    /// Landmark mode.
    Landmark(LandmarkState<R>),
    /// Voronoi mode: its state, in storage the caller provided to
    /// [`Planner::load_voronoi`](super::Planner::load_voronoi).
    Voronoi(&'n mut super::threats::VoronoiStorage),
}
