//! The onboard planner: fixed memory, pop-up pruning, endpoint connection, bounded search.
//!
//! `Planner<'n, V, E, P, R>` holds all mutable state in arrays sized by its const generics:
//! `V` search states, `E` edges, `P` pop-ups (at most 16) and `R` route primitives. A search
//! state is a vertex of a roadmap, or — in terrain mode, whose search runs over the route's
//! straights — a directed edge or one of the [`MAX_LINKS`] start links, so a terrain planner
//! needs `V ≥ |E| + MAX_LINKS`; under the paper's [`TurnRule`] a state is a (straight before,
//! edge) pair, and a query with `Ks` start links needs `|E| + T + 2·Ks + 1 + Σₖ outdeg(vₖ)`
//! (`T = Σ_v indeg(v)·outdeg(v)`, `vₖ` the start links' nodes; `planner/terrain`). Its size is
//! about `20·V + 2·E + 140·P + 56·R + 4.5 KiB` bytes (`core::mem::size_of` gives the exact
//! figure); place it in a `static` so the linker rejects a build whose RAM does not suffice.
//! A new planner is all-zero, so such a `static` lands in `.bss` and costs no flash.

pub mod alternatives;
mod connect;
pub mod decision;
mod error;
mod exit;
pub mod heap;
mod landmark;
mod landmark_connect;
mod popup;
pub mod risk;
mod search;
mod slice;
mod smooth;
mod state;
mod terrain;
mod threats;
mod vertical;
mod voronoi;
mod window;
pub mod work;

pub use error::{PlanError, PopupError, QueryField};
pub use exit::{
    Exit, Violation, EXIT_MARGIN_M, EXIT_TURN_STEPS, MAX_EXIT_INTERVALS, MAX_EXIT_REGIONS,
};
pub use landmark::POPUP_CHORDS_PER_PIECE;
use popup::ActivePopup;
pub use popup::{Popup, PopupSummary, MAX_POPUP_VERTICES};
pub use slice::PlanStep;
pub use smooth::SmoothSummary;
pub use state::{ArcCheckStats, MAX_ROSETTE_DIRECTIONS, MAX_ROSETTE_OVERRIDES};
pub use voronoi::{
    segment_exposure, threat_rebuild_work_bound, HalfEdge, SearchGraph, Threat, ThreatError,
    ThreatOrigin, ThreatSummary, VoronoiStorage, CHORDS_PER_CUBIC, CHORD_TOLERANCE_M,
    EXPOSURE_POINTS, MAX_ROUTE_PIECES, MAX_THREATS, VORONOI_GRAPH_EDGES, VORONOI_GRAPH_VERTICES,
    VORONOI_LINKS,
};
pub use work::{
    cells_bound, exit_work_bound, landmark_plan_work_bound, landmark_popup_work_bound,
    plan_work_bound, popup_work_bound, roadmap_step_unit_bound, terrain_plan_work_bound,
    voronoi_plan_work_bound, TerrainBoundInputs, VoronoiBoundInputs, Work, WorkBoundInputs,
};

use crate::geometry::{DubinsPath, Pose, Primitive, Vec2};
use crate::network::{LoadError, Mode, Network};
use heap::IndexedHeap;
use heapless::Vec;
use state::{LandmarkState, ModeState, RoadmapState, TerrainState};

/// The most start (and the most goal) links a query keeps.
pub const MAX_LINKS: usize = 16;

/// The most vertices a query tries to connect the start (and the goal) to, nearest first, to
/// find its links: enough to get past nearby vertices whose heading or surroundings admit no
/// collision-free connection.
pub const MAX_CANDIDATES: usize = 32;

/// The most headings a goal without one is tried at
/// ([`PlannerConfig::free_goal_headings`] is clamped to it).
pub const MAX_GOAL_HEADINGS: u16 = 360;

/// How a query connects to the network.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct PlannerConfig {
    /// Links from the start wanted (at most [`MAX_LINKS`]): the nearest vertices a
    /// collision-free Dubins path reaches, among the [`MAX_CANDIDATES`] nearest.
    pub start_candidates: u8,
    /// Links to the goal wanted (at most [`MAX_LINKS`]), chosen as for the start.
    pub goal_candidates: u8,
    /// Only vertices within this distance are candidates, metres.
    pub connect_radius_m: f32,
    /// Headings tried for a goal without one, evenly spaced (36: every 10°).
    pub free_goal_headings: u16,
    /// Terrain mode: how consecutive turns share the straight between them.
    pub turn_rule: TurnRule,
}

/// Terrain mode: how the turns at the two ends of a straight of length `ℓ` share it, with the
/// cuts `c = r·tan(θ/2)` of their 1-trajectories (`planner/terrain`'s module doc).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[repr(u8)]
pub enum TurnRule {
    /// The paper's equations 1–2 (Medeiros & da Silva): `cᵢ₋₁ + cᵢ ≤ ℓ`. Exact, over
    /// (straight before, edge) states: a query with `Ks` start links needs
    /// `V ≥ |E| + T + 2·Ks + 1 + Σₖ outdeg(vₖ)` (`T = Σ_v indeg(v)·outdeg(v)`), and is refused
    /// with [`PlanError::TooManySearchStates`] otherwise.
    Paper = 0,
    /// Each straight split equally: `cᵢ₋₁ ≤ ℓ/2` and `cᵢ ≤ ℓ/2`. Stricter (it loses routes the
    /// paper's rule finds), over the directed edges alone (`V ≥ |E| + MAX_LINKS`).
    SharedEqually = 1,
}

impl PlannerConfig {
    /// 8 start and 8 goal candidates within 1 km, 36 free goal headings, the paper's turn
    /// rule (a planner too small for its states plans with [`TurnRule::SharedEqually`] set).
    pub const DEFAULT: PlannerConfig = PlannerConfig {
        start_candidates: 8,
        goal_candidates: 8,
        connect_radius_m: 1000.0,
        free_goal_headings: 36,
        turn_rule: TurnRule::Paper,
    };

    fn start_links(&self) -> usize {
        (self.start_candidates as usize).min(MAX_LINKS)
    }

    fn goal_links(&self) -> usize {
        (self.goal_candidates as usize).min(MAX_LINKS)
    }

    fn headings(&self, goal: &Goal) -> u16 {
        match goal.heading {
            Some(_) => 1,
            None => self.free_goal_headings.clamp(1, MAX_GOAL_HEADINGS),
        }
    }
}

impl Default for PlannerConfig {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// The goal: a position and, optionally, the heading to arrive with.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Goal {
    /// Where to arrive.
    pub position: Vec2,
    /// Heading to arrive with (radians counter-clockwise from east); `None`: any, tried at
    /// [`PlannerConfig::free_goal_headings`] evenly spaced headings.
    pub heading: Option<f32>,
}

/// The search algorithm.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Search {
    /// Dijkstra's algorithm.
    Dijkstra,
    /// A* with the straight-line distance to the goal as heuristic (admissible and consistent,
    /// since no Dubins path is shorter than the chord it spans).
    AStar,
}

/// A phase of a roadmap or terrain query, reported as it begins to the observer of
/// [`Planner::plan_observed`] (for example to time each phase with a board's clock).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Phase {
    /// The start and goal checked against the obstacles and pop-ups (and the terrain).
    CheckFree,
    /// The start connected to its nearest vertices.
    ConnectStart,
    /// The goal connected to its nearest vertices, over the goal headings.
    ConnectGoal,
    /// The direct path from the start to the goal.
    ConnectDirect,
    /// The search over the network.
    Search,
    /// The route written out.
    Route,
    /// The query has ended, with a route or an error.
    Done,
}

/// One planning request.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Query {
    /// The aircraft's current pose.
    pub start: Pose,
    /// Where to go.
    pub goal: Goal,
    /// Which search to run.
    pub search: Search,
}

/// What a successful query produced (the primitives are in [`Planner::route`]).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct RouteSummary {
    /// Length of the route, metres (the sum of its primitives' lengths).
    pub length: f32,
    /// Number of primitives.
    pub primitives: u32,
    /// Network edges the route uses.
    pub network_edges: u32,
    /// The heading the route arrives with.
    pub arrival_heading: f32,
    /// Work the query counted.
    pub work: Work,
    /// Roadmap mode: the exit the route begins with when the start lay inside or within the
    /// clearance of an obstacle or pop-up (`planner/exit.rs`); `None` otherwise.
    pub exit: Option<Exit>,
}

/// A connection between the start or goal and a network vertex.
#[derive(Clone, Copy, Debug)]
struct Link {
    vertex: u32,
    path: DubinsPath,
    /// What the link costs the search: its length, or in Voronoi mode its length and
    /// exposure; for a pending link, a lower bound of its length.
    cost: f32,
    /// A roadmap goal link whose vertex is known to reach the goal by a collision-free path
    /// (`path`), but whose shortest such path is found only when the search needs it: when
    /// it pops the vertex and the lower bound `cost` could still improve the route.
    pending: bool,
}

/// The planner. See the module documentation for its memory.
pub struct Planner<'n, const V: usize, const E: usize, const P: usize, const R: usize> {
    network: Network<'n>,
    /// The settings given to [`Planner::set_config`], once `config_set`; until then
    /// [`PlannerConfig::DEFAULT`] is in force. (A flag rather than an `Option`, whose `None`
    /// would take the turn rule's spare value: all-zero bytes keep a new planner all-zero, so
    /// that a `static` one lands in `.bss` instead of also costing its size in flash for
    /// `.data`; the all-zero config has [`TurnRule::Paper`], discriminant 0.)
    config: PlannerConfig,
    /// Whether `config` was set.
    config_set: bool,
    /// Bit `p` set: pop-up slot `p` blocks the edge.
    blocked_by: [u16; E],
    /// Active pop-ups (ids distinct, below `P`).
    popups: Vec<ActivePopup, P>,
    /// Best known cost to each vertex (valid once the vertex has been queued).
    dist: [f32; V],
    /// How each vertex was reached: an edge index, or `FROM_START + link`.
    via: [u32; V],
    heap: IndexedHeap<V>,
    start_links: Vec<Link, MAX_LINKS>,
    goal_links: Vec<Link, MAX_LINKS>,
    /// The route as a chain of Dubins paths, start to goal.
    paths: Vec<DubinsPath, R>,
    /// The same route as lines and arcs.
    route: Vec<Primitive, R>,
    summary: SummarySlot,
    /// What only the loaded network's mode keeps (altitude, weather, rosettes, ...).
    state: ModeState<'n, R>,
    /// The query in progress ([`Planner::start_plan`], [`Planner::step`]), if any.
    flight: slice::Flight<'n>,
}

/// The last route's summary, if any: an enum with an explicit `u8` tag whose empty variant is
/// 0. (An `Option<RouteSummary>` would take a spare value of the exit's violation tag for
/// `None`, 3; all-zero bytes keep a new planner all-zero, so that a `static` one lands in
/// `.bss` instead of also costing its size in flash for `.data`.)
#[repr(u8)]
#[derive(Clone, Copy, Debug)]
enum SummarySlot {
    /// No route yet, or the last one was cleared.
    Empty = 0,
    /// The summary of the route in [`Planner::route`].
    Full(RouteSummary) = 1,
}

impl SummarySlot {
    fn get(&self) -> Option<&RouteSummary> {
        match self {
            Self::Full(summary) => Some(summary),
            Self::Empty => None,
        }
    }

    fn get_mut(&mut self) -> Option<&mut RouteSummary> {
        match self {
            Self::Full(summary) => Some(summary),
            Self::Empty => None,
        }
    }
}

/// The state [`Planner::load`] gives the loaded network's mode: only the terrain state is
/// built before it is installed; the larger ones are built in place.
enum FreshState {
    Roadmap,
    Terrain(TerrainState),
    Landmark,
}

/// `via` values at or above this mark a vertex reached straight from start link `via − FROM_START`.
const FROM_START: u32 = u32::MAX - MAX_LINKS as u32;

impl<'n, const V: usize, const E: usize, const P: usize, const R: usize> Default
    for Planner<'n, V, E, P, R>
{
    fn default() -> Self {
        Self::new()
    }
}

impl<'n, const V: usize, const E: usize, const P: usize, const R: usize> Planner<'n, V, E, P, R> {
    /// Evaluated at compile time where the planner is built: at most 16 pop-ups (the width of
    /// the per-edge blocking mask).
    const CAPACITY_OK: () = assert!(P <= 16, "a planner supports at most 16 pop-ups");

    /// A planner with an empty network. `const`, so it can initialise a `static`.
    pub const fn new() -> Self {
        #[allow(clippy::let_unit_value)]
        let () = Self::CAPACITY_OK;
        Self {
            network: Network::empty(),
            config: PlannerConfig {
                start_candidates: 0,
                goal_candidates: 0,
                connect_radius_m: 0.0,
                free_goal_headings: 0,
                turn_rule: TurnRule::Paper,
            },
            config_set: false,
            blocked_by: [0; E],
            popups: Vec::new(),
            dist: [0.0; V],
            via: [0; V],
            heap: IndexedHeap::new(),
            start_links: Vec::new(),
            goal_links: Vec::new(),
            paths: Vec::new(),
            route: Vec::new(),
            summary: SummarySlot::Empty,
            state: ModeState::Roadmap(RoadmapState::new()),
            flight: slice::Flight::IDLE,
        }
    }

    /// Validates `bytes` for this planner's capacities and makes it the network, clearing
    /// pop-ups and the route. On error the planner keeps its previous network and state.
    pub fn load(&mut self, bytes: &'n [u8]) -> Result<(), LoadError> {
        self.cancel_plan();
        let network = Network::from_bytes_with_capacity(bytes, V, E)?;
        // The terrain state is small; the others are built in place by `install` (a large
        // state built here first would be copied, and its copy would add to the caller's
        // stack frame).
        let fresh = match network.mode() {
            Mode::Roadmap => FreshState::Roadmap,
            Mode::Landmark => FreshState::Landmark,
            Mode::Terrain => {
                // The terrain search runs over directed edges and start links.
                let needed = network.edge_count() as usize + MAX_LINKS;
                if needed > V {
                    return Err(LoadError::TooManySearchStates {
                        needed,
                        capacity: V,
                    });
                }
                FreshState::Terrain(TerrainState::for_network(&network))
            }
            // Its state lives in storage the caller provides.
            Mode::Voronoi => return Err(LoadError::NeedsVoronoiStorage),
            Mode::Unknown(mode) => return Err(LoadError::UnknownMode { mode }),
        };
        self.network = network;
        self.state = match fresh {
            FreshState::Roadmap => ModeState::Roadmap(RoadmapState::new()),
            FreshState::Terrain(t) => ModeState::Terrain(t),
            FreshState::Landmark => ModeState::Landmark(LandmarkState::new()),
        };
        self.reset_for_network();
        Ok(())
    }

    /// Makes `network` the network with its mode's `state`, clearing pop-ups and the route.
    fn install(&mut self, network: Network<'n>, state: ModeState<'n, R>) {
        self.network = network;
        self.state = state;
        self.reset_for_network();
    }

    /// Clears the pop-ups, the edge masks and the route after a network is installed.
    fn reset_for_network(&mut self) {
        self.blocked_by = [0; E];
        self.popups.clear();
        self.paths.clear();
        self.route.clear();
        self.summary = SummarySlot::Empty;
    }

    /// The loaded network.
    pub fn network(&self) -> &Network<'n> {
        &self.network
    }

    /// The connection settings.
    pub fn config(&self) -> PlannerConfig {
        if self.config_set {
            self.config
        } else {
            PlannerConfig::DEFAULT
        }
    }

    /// Replaces the connection settings (counts above [`MAX_LINKS`] are used as `MAX_LINKS`).
    pub fn set_config(&mut self, config: PlannerConfig) {
        self.cancel_plan();
        self.config = config;
        self.config_set = true;
    }

    /// The last route found, as lines and arcs from the start pose to the goal.
    pub fn route(&self) -> &[Primitive] {
        &self.route
    }

    /// The last route as the chain of Dubins paths it flies (start link, network edges, goal
    /// link), each starting where the previous ends.
    pub fn route_paths(&self) -> &[DubinsPath] {
        &self.paths
    }

    /// The summary of the last route found.
    pub fn route_summary(&self) -> Option<&RouteSummary> {
        self.summary.get()
    }

    /// Whether the search may use edge `e`: no pop-up blocks it and, in terrain mode, its band
    /// is clear of the terrain at the altitude in force; in landmark mode, it is navigable in
    /// the weather and rosettes in force ([`Planner::is_navigable`]). Work: O(1), and in
    /// landmark mode a binary search for the edge's source.
    pub fn is_edge_usable(&self, e: u32) -> bool {
        match &self.state {
            ModeState::Landmark(_) => self
                .network
                .edge_source(e)
                .is_some_and(|source| self.is_edge_usable_from(source, e)),
            // Only the landmark rule reads the source.
            ModeState::Roadmap(_) | ModeState::Terrain(_) | ModeState::Voronoi(_) => {
                self.is_edge_usable_from(u32::MAX, e)
            }
        }
    }

    /// [`Planner::is_edge_usable`] for an edge whose source the caller knows (the search,
    /// expanding that vertex; only landmark mode reads it). O(1).
    #[inline(always)]
    pub(crate) fn is_edge_usable_from(&self, source: u32, e: u32) -> bool {
        match &self.state {
            ModeState::Roadmap(_) => self.is_edge_enabled(e),
            ModeState::Terrain(t) => {
                self.is_edge_enabled(e)
                    && self
                        .network
                        .edge_highest_code(e)
                        .is_some_and(|c| c < t.blocking)
            }
            ModeState::Landmark(state) => {
                self.is_edge_enabled(e) && self.navigable_from(state, source, e)
            }
            // The search's edges are the onboard graph's half-edges, priced and checked
            // against zones and pop-ups before each search.
            ModeState::Voronoi(state) => state
                .graph()
                .half_edge(e)
                .is_some_and(|h| state.graph().is_clear(h.edge as u32)),
        }
    }

    /// Whether edge `e` may be used (no active pop-up blocks it).
    pub fn is_edge_enabled(&self, e: u32) -> bool {
        self.blocked_by.get(e as usize).is_some_and(|m| *m == 0)
    }

    /// Number of edges no pop-up blocks. Work: |E|.
    pub fn enabled_edge_count(&self) -> u32 {
        let n = self.network.edge_count() as usize;
        self.blocked_by.iter().take(n).filter(|m| **m == 0).count() as u32
    }

    /// The inputs of the work bounds for this network and configuration.
    pub fn work_bound_inputs(&self, goal_has_heading: bool) -> WorkBoundInputs {
        let header = self.network.header();
        WorkBoundInputs {
            vertices: header.vertex_count as u64,
            edges: header.edge_count as u64,
            obstacles: header.obstacle_count as u64,
            obstacle_points: header.obstacle_point_count as u64,
            popups: P as u64,
            popup_vertices: MAX_POPUP_VERTICES as u64,
            candidates: MAX_CANDIDATES as u64,
            start_links: self.config().start_links() as u64,
            goal_links: self.config().goal_links() as u64,
            goal_headings: if goal_has_heading {
                1
            } else {
                self.config().free_goal_headings.clamp(1, MAX_GOAL_HEADINGS) as u64
            },
            three_dimensional: self.network.is_three_dimensional(),
        }
    }

    /// The most work any query on the loaded network can count (with a free goal heading, the
    /// larger case): [`plan_work_bound`].
    pub fn worst_case_work(&self) -> u64 {
        match self.state {
            ModeState::Roadmap(_) => plan_work_bound(&self.work_bound_inputs(false)),
            ModeState::Terrain(_) => terrain_plan_work_bound(&self.terrain_bound_inputs()),
            ModeState::Landmark(_) => landmark_plan_work_bound(&self.work_bound_inputs(true)),
            ModeState::Voronoi(_) => voronoi_plan_work_bound(&self.voronoi_bound_inputs()),
        }
    }

    /// The most work [`Planner::add_popup`] can count on the loaded network.
    pub fn worst_case_popup_work(&self) -> u64 {
        let h = self.network.header();
        let cells = h.grid_nx as u64 * h.grid_ny as u64;
        // Every grid entry takes at least one byte of the cell lists.
        let entries = h.grid_list_bytes as u64;
        match self.state {
            ModeState::Roadmap(_) | ModeState::Terrain(_) | ModeState::Voronoi(_) => {
                popup_work_bound(cells, entries, MAX_POPUP_VERTICES as u64)
            }
            ModeState::Landmark(_) => landmark_popup_work_bound(
                cells,
                entries,
                self.network.max_chain_pieces() as u64,
                MAX_POPUP_VERTICES as u64,
            ),
        }
    }
}

/// Counts work against a budget.
struct Meter {
    work: Work,
    budget: u64,
}

impl Meter {
    const fn new(budget: u64) -> Self {
        Self {
            work: Work::ZERO,
            budget,
        }
    }

    /// Fails once the total exceeds the budget.
    fn check(&self) -> Result<(), PlanError> {
        let used = self.work.total();
        if used > self.budget {
            Err(PlanError::BudgetExhausted {
                used,
                budget: self.budget,
            })
        } else {
            Ok(())
        }
    }
}
