//! Counted work and its documented worst case.
//!
//! The library reads no clock. Instead every onboard operation counts elementary steps, each of
//! bounded cost, and stops when a caller's budget runs out. The units:
//!
//! | counter | one unit is |
//! |---|---|
//! | `vertex_scans` | reading one vertex's pose (candidate search, heap reset, route walk) |
//! | `dubins_solves` | solving one Dubins path (six words) |
//! | `collision_tests` | one obstacle bounding-box test, or one exact predicate against one polygon edge, containment test or circle |
//! | `heap_steps` | one level of a heap sift (push, decrease-key or pop) |
//! | `relaxations` | examining one out-edge or one goal link of a popped vertex |
//!
//! [`plan_work_bound`] gives the most any query can count on a network, as a function of its
//! counts; `host-tests` checks on random queries that the count never exceeds it.

use super::heap::heap_levels;

/// Work counted by one operation.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Work {
    /// Vertex poses read.
    pub vertex_scans: u64,
    /// Dubins paths solved.
    pub dubins_solves: u64,
    /// Bounding-box tests and exact predicate evaluations.
    pub collision_tests: u64,
    /// Heap sift levels.
    pub heap_steps: u64,
    /// Out-edges and goal links examined.
    pub relaxations: u64,
}

impl Work {
    /// The sum of all counters: what a budget is compared with.
    pub fn total(&self) -> u64 {
        self.vertex_scans
            + self.dubins_solves
            + self.collision_tests
            + self.heap_steps
            + self.relaxations
    }
}

impl core::ops::AddAssign for Work {
    fn add_assign(&mut self, w: Work) {
        self.vertex_scans += w.vertex_scans;
        self.dubins_solves += w.dubins_solves;
        self.collision_tests += w.collision_tests;
        self.heap_steps += w.heap_steps;
        self.relaxations += w.relaxations;
    }
}

/// The counts that bound a query's work.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct WorkBoundInputs {
    /// Vertices in the network, |V|.
    pub vertices: u64,
    /// Edges in the network, |E|.
    pub edges: u64,
    /// Static obstacles, O.
    pub obstacles: u64,
    /// Polygon points over all obstacles.
    pub obstacle_points: u64,
    /// Most pop-ups active at once, P.
    pub popups: u64,
    /// Most vertices (polygon) a pop-up has.
    pub popup_vertices: u64,
    /// Vertices tried per endpoint, C ([`MAX_CANDIDATES`](super::MAX_CANDIDATES)).
    pub candidates: u64,
    /// Start links kept, Ks.
    pub start_links: u64,
    /// Goal links kept, Kg.
    pub goal_links: u64,
    /// Goal headings tried, H (1 with a fixed goal heading, 36 without).
    pub goal_headings: u64,
}

/// The most work one [`Planner::plan`](super::Planner::plan) can count:
///
/// * free-space checks of start and goal: 2(O + P) collision tests;
/// * candidate search: 2|V| vertex scans (start and goal);
/// * connections: N = C + C·H + H Dubins solves (start candidates, goal candidates over each
///   heading, direct start–goal over each heading), each of ≤ 3 primitives, each tested against
///   every obstacle's box (O), every polygon edge and containment (points + O), and every pop-up
///   (P·(popup_vertices + 1)): 3·N·(2O + points + P·(popup_vertices + 1)) collision tests;
/// * search: |V| heap resets; ≤ |V| pops and ≤ Ks + |E| pushes or decreases of ≤ L = ⌊log2|V|⌋+1
///   levels each; ≤ |E| out-edge and ≤ |V|·Kg goal-link relaxations;
/// * route: ≤ 2(|V| + 1) vertex scans for the two walks back from the goal.
pub fn plan_work_bound(n: &WorkBoundInputs) -> u64 {
    let v = n.vertices;
    let levels = heap_levels(v);
    let connections = n.candidates + n.candidates * n.goal_headings + n.goal_headings;
    let per_primitive = 2 * n.obstacles + n.obstacle_points + n.popups * (n.popup_vertices + 1);
    let candidates = 2 * v;
    let connecting = connections + 3 * connections * per_primitive;
    let search = v + (v + n.start_links + n.edges) * levels + n.edges + v * n.goal_links;
    let route = 2 * (v + 1);
    let endpoints_free = 2 * (n.obstacles + n.popups);
    endpoints_free + candidates + connecting + search + route
}

/// The most work one [`Planner::add_popup`](super::Planner::add_popup) can count: every grid
/// cell of the network visited once (`cells`), every grid entry once (`entries`), each entry's
/// edge's ≤ 3 primitives tested against the pop-up (`popup_vertices + 1` predicate
/// evaluations).
pub fn popup_work_bound(cells: u64, entries: u64, popup_vertices: u64) -> u64 {
    cells + entries * (1 + 3 * (popup_vertices + 1))
}
