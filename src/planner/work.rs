//! Counted work and its documented worst case.
//!
//! The library reads no clock. Instead every onboard operation counts elementary steps, each of
//! bounded cost, and stops when a caller's budget runs out. The units:
//!
//! | counter | one unit is |
//! |---|---|
//! | `vertex_scans` | reading one vertex's pose (candidate search, heap reset, route walk) |
//! | `dubins_solves` | solving one Dubins path (six words), or picking the next shortest goal path to check (a scan of ≤ 360 stored lengths) and solving its one word again, or (landmark mode) building one online Hermite piece and checking its flyability (at most `NEWTON_MAX_STEPS` quadratures and `65 + 4096` samples) |
//! | `collision_tests` | one obstacle bounding-box test (or the distance of its box from an endpoint, with an insertion into a sorted list of ≤ 32), or one exact predicate against one polygon edge, containment test or circle |
//! | `heap_steps` | one level of a heap sift (push, decrease-key or pop) |
//! | `relaxations` | examining one out-edge or one goal link of a popped vertex |
//! | `cells_visited` | one grid cell visited by a terrain traversal (its elevation code compared) |
//! | `threat_steps` | Voronoi mode: one exposure term (one threat at one sample point), one exact predicate or triangle visit of the onboard diagram, or one step of the spline fit |
//!
//! Pop-ups on a landmark network also count one unit per Hermite piece rebuilt
//! ([`PopupSummary::pieces_rebuilt`](super::PopupSummary::pieces_rebuilt)): a segment
//! construction is a bounded computation (at most `NEWTON_MAX_STEPS` steps of bounded
//! quadrature), but far costlier than a predicate; its time is measured separately.
//!
//! [`plan_work_bound`] gives the most any query can count on a network, as a function of its
//! counts; `host-tests` checks on random queries that the count never exceeds it.

use super::heap::heap_levels;
use super::TurnRule;

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
    /// Terrain cells visited by arc and segment checks.
    pub cells_visited: u64,
    /// Voronoi mode: exposure terms, diagram predicates and spline-fit steps.
    pub threat_steps: u64,
}

impl Work {
    /// No work (the same as `Work::default()`, usable in `const`).
    pub const ZERO: Work = Work {
        vertex_scans: 0,
        dubins_solves: 0,
        collision_tests: 0,
        heap_steps: 0,
        relaxations: 0,
        cells_visited: 0,
        threat_steps: 0,
    };

    /// The sum of all counters: what a budget is compared with.
    pub fn total(&self) -> u64 {
        self.vertex_scans
            + self.dubins_solves
            + self.collision_tests
            + self.heap_steps
            + self.relaxations
            + self.cells_visited
            + self.threat_steps
    }
}

impl core::ops::AddAssign for Work {
    fn add_assign(&mut self, w: Work) {
        self.vertex_scans += w.vertex_scans;
        self.dubins_solves += w.dubins_solves;
        self.collision_tests += w.collision_tests;
        self.heap_steps += w.heap_steps;
        self.relaxations += w.relaxations;
        self.cells_visited += w.cells_visited;
        self.threat_steps += w.threat_steps;
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
    /// Whether the network is a three-dimensional roadmap (its route's altitudes cost one
    /// more walk back from the goal).
    pub three_dimensional: bool,
}

/// The most work one [`Planner::plan`](super::Planner::plan) can count:
///
/// * free-space checks of start and goal: 2(2O + P) collision tests (a box test per obstacle,
///   a containment test per obstacle whose box holds the point and per pop-up);
/// * candidate search: 2|V| vertex scans (start and goal);
/// * connections: N = 2C + C·H + H paths (start candidates, one probe per goal candidate,
///   goal candidates over each heading, direct start–goal over each heading), each one Dubins
///   solve; picking the next shortest goal path to check and solving its word again, ≤ C·H + H
///   more; the obstacle windows of the start and the goal (in the connection, and once more in
///   the search for pending goal links), 3O collision tests; each path checked at most once,
///   ≤ 3 primitives, each tested against every obstacle's box (O), every polygon edge and
///   containment (points + O), and every pop-up (P·(popup_vertices + 1)): 3·N·(2O + points +
///   P·(popup_vertices + 1)) collision tests;
/// * search: |V| heap resets; ≤ |V| pops and ≤ Ks + |E| pushes or decreases of ≤ L = ⌊log2|V|⌋+1
///   levels each; ≤ |E| out-edge and ≤ |V|·Kg goal-link relaxations;
/// * route: ≤ 2(|V| + 1) vertex scans for the two walks back from the goal, and in a
///   three-dimensional roadmap a third for its altitudes;
/// * the exit from a keep-out region the start lies in: [`exit_work_bound`].
///
/// A three-dimensional roadmap's link checks are within the connections' term: each path is
/// checked against every obstacle and pop-up, and each obstacle against at most the part of
/// each primitive flown below its height.
pub fn plan_work_bound(n: &WorkBoundInputs) -> u64 {
    let v = n.vertices;
    let levels = heap_levels(v);
    let goal_paths = n.candidates * n.goal_headings + n.goal_headings;
    let connections = 2 * n.candidates + goal_paths;
    let per_primitive = 2 * n.obstacles + n.obstacle_points + n.popups * (n.popup_vertices + 1);
    let candidates = 2 * v;
    let solves = connections + goal_paths;
    let windows = 3 * n.obstacles;
    let connecting = solves + windows + 3 * connections * per_primitive;
    let search = v + (v + n.start_links + n.edges) * levels + n.edges + v * n.goal_links;
    let route = route_walks(n) * (v + 1);
    let endpoints_free = 2 * (2 * n.obstacles + n.popups);
    endpoints_free + candidates + connecting + search + route + exit_work_bound(n)
}

/// Walks back from the goal a roadmap route costs: the writer's two, and one for a
/// three-dimensional roadmap's altitudes.
fn route_walks(n: &WorkBoundInputs) -> u64 {
    2 + n.three_dimensional as u64
}

/// The most work one indivisible unit of a roadmap query's [`Planner::step`](super::Planner::step)
/// can count, on a network whose vertices have at most `most_out_degree` out-edges. With
/// `c = 3·(2O + points + P·(popup_vertices + 1))` the tests of one path (≤ 3 primitives) and
/// `g = 2H + H·c` finding the shortest clear path from a point to the goal over H headings, the
/// units are:
///
/// * begin: the goal's free-space check, 2O + P; the exit, [`exit_work_bound`]; the start's
///   obstacle window, O; its candidates, |V|;
/// * one start candidate: 1 + c;
/// * the goal's candidates and obstacle window: |V| + O;
/// * one goal candidate: its probe, 1 + c, and when that is blocked, g;
/// * the direct path: g;
/// * the search's start: |V| heap resets and Ks pushes of ≤ L = ⌊log2|V|⌋ + 1 levels;
/// * one search expansion: the pop, L; Kg goal links examined, of which the one at the vertex
///   may be resolved, O (the goal's window, read once) + g; each out-edge examined and pushed,
///   `most_out_degree`·(1 + L);
/// * the route: 2(|V| + 1) vertex scans for the two walks back, 3(|V| + 1) in a
///   three-dimensional roadmap.
///
/// Returns the largest.
pub fn roadmap_step_unit_bound(n: &WorkBoundInputs, most_out_degree: u64) -> u64 {
    let v = n.vertices;
    let levels = heap_levels(v);
    let path = 3 * (2 * n.obstacles + n.obstacle_points + n.popups * (n.popup_vertices + 1));
    let to_goal = 2 * n.goal_headings + n.goal_headings * path;
    let units = [
        2 * n.obstacles + n.popups + exit_work_bound(n) + n.obstacles + v,
        1 + path,
        v + n.obstacles,
        1 + path + to_goal,
        to_goal,
        v + n.start_links * levels,
        levels + n.goal_links + n.obstacles + to_goal + most_out_degree * (1 + levels),
        route_walks(n) * (v + 1),
    ];
    units.into_iter().max().unwrap_or(0)
}

/// The most work the exit from a keep-out region can count (`planner/exit.rs`). With
/// `Q = 2O + points + P·(popup_vertices + 1)`, the tests that place one point among every
/// obstacle and pop-up (and the cost of checking one primitive against all of them):
///
/// * the regions the start lies in: Q;
/// * each of the 2·EXIT_TURN_STEPS + 1 candidates: the trace of the regions, at most
///   2·(points + P·popup_vertices) + MAX_EXIT_REGIONS (an interval and a crossing per edge,
///   an interval per disc); the sort of at most MAX_EXIT_INTERVALS intervals, counted as its
///   square; its ≤ 3 primitives checked against the rest, 3Q; the regions its end lies in, Q;
/// * a refusal when no candidate is kept: the start's free-space check, 2O + P, and Q.
pub fn exit_work_bound(n: &WorkBoundInputs) -> u64 {
    let q = 2 * n.obstacles + n.obstacle_points + n.popups * (n.popup_vertices + 1);
    let candidates = 2 * super::EXIT_TURN_STEPS as u64 + 1;
    let trace =
        2 * (n.obstacle_points + n.popups * n.popup_vertices) + super::MAX_EXIT_REGIONS as u64;
    let sort = (super::MAX_EXIT_INTERVALS * super::MAX_EXIT_INTERVALS) as u64;
    q + candidates * (trace + sort + 4 * q) + 2 * n.obstacles + n.popups + q
}

/// The most work one [`Planner::add_popup`](super::Planner::add_popup) can count: every grid
/// cell of the network visited once (`cells`), every grid entry once (`entries`), each entry's
/// edge's ≤ 3 primitives tested against the pop-up (`popup_vertices + 1` predicate
/// evaluations).
pub fn popup_work_bound(cells: u64, entries: u64, popup_vertices: u64) -> u64 {
    cells + entries * (1 + 3 * (popup_vertices + 1))
}

/// The counts that bound a terrain query's work ([`terrain_plan_work_bound`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct TerrainBoundInputs {
    /// Vertices in the network, |V|.
    pub vertices: u64,
    /// Directed edges, |E|: the search states besides the start links.
    pub edges: u64,
    /// Turn transitions, `Σ_v indeg(v)·outdeg(v)`: the (edge in, edge out) pairs at a node,
    /// T.
    pub transitions: u64,
    /// The out-edges of every transition's second edge's end, `Σ_(i,o) outdeg(end of o)`
    /// over the transitions: what expanding every paper's-rule pair state examines.
    pub pair_relaxations: u64,
    /// The query's turn rule (it sets the states).
    pub turn_rule: TurnRule,
    /// The largest out-degree of a vertex.
    pub max_out_degree: u64,
    /// Most pop-ups active at once, P.
    pub popups: u64,
    /// Most vertices (polygon) a pop-up has.
    pub popup_vertices: u64,
    /// Vertices tried per endpoint, C.
    pub candidates: u64,
    /// Start links kept, Ks (at most [`MAX_LINKS`](super::MAX_LINKS)).
    pub start_links: u64,
    /// Goal links kept, Kg.
    pub goal_links: u64,
    /// Most cells one turn-arc check visits ([`cells_bound`] of a half-turn arc).
    pub cells_per_turn: u64,
    /// Most cells one connection primitive (a straight to or from the network, or an arc of up
    /// to a full turn) visits.
    pub cells_per_connection: u64,
}

/// The most cells [`segment_cells`](crate::geometry::grid::segment_cells) or
/// [`arc_cells`](crate::geometry::grid::arc_cells) visits for a primitive of length
/// `length_cells` (in cells; an arc's counted up to one full turn) widened by `widen_cells`:
/// `N ≤ 2(ρ + √2)·L + π(ρ + √2)²` with `ρ = widen + η` (the grid module's bound; `η`, the
/// rounding slack, is below 0.01 cells for grids under 10⁵ cells across).
pub fn cells_bound(length_cells: f32, widen_cells: f32) -> u64 {
    let rho = widen_cells + 0.01 + core::f32::consts::SQRT_2;
    let n = 2.0 * rho * length_cells + core::f32::consts::PI * rho * rho;
    if n.is_finite() && n < u64::MAX as f32 {
        libm::ceilf(n) as u64
    } else {
        u64::MAX
    }
}

/// The most work one terrain [`Planner::plan`](super::Planner::plan) can count:
///
/// * start and goal: 2 cells and 2P pop-up containment tests;
/// * candidate search: 2|V| vertex scans;
/// * connections: 2C start paths (a left and a right turn) and 2C goal paths (one straight for
///   a free heading; a left and a right turn for a fixed one), and 2 direct paths, each one
///   solve and ≤ 3 primitives of ≤ `cells_per_connection` cells and P·(popup_vertices + 1)
///   pop-up tests: N·(1 + 3·(cells + P·(popup_vertices + 1))) with N = 4C + 2;
/// * search over S states (the turn rule's: the equal split S = |E| + Ks; the paper's rule
///   S = (|E| + Ks + 1) + Ks + T + Ks·max_out_degree, its offset table of |E| + Ks + 1 entries
///   written first, one vertex scan each): S heap resets; ≤ S pops, each reading its state
///   and, under the paper's rule, ≤ D = ⌊log2(|E| + Ks + 1)⌋ + 1 table reads to decode it;
///   relaxations: the out-edges of every popped state — the equal split:
///   `transitions + Ks·max_out_degree`; the paper's rule: `pair_relaxations` for the pairs
///   after a network edge, `Ks·max_out_degree²` for those after a start link and
///   `Ks·max_out_degree` for the start links — and Kg goal links per pop; each relaxation or
///   goal link may check one turn arc (`cells_per_turn` cells, and every pop-up) and push or
///   decrease once; every heap operation ≤ L = ⌊log2 S⌋ + 1 levels;
/// * route: ≤ 2(S + 1) state reads for the two walks back, each with ≤ D table reads.
pub fn terrain_plan_work_bound(n: &TerrainBoundInputs) -> u64 {
    let starts = n.start_links.saturating_mul(n.max_out_degree);
    let (s, table, decode, out_relaxations) = match n.turn_rule {
        TurnRule::SharedEqually => (
            n.edges + n.start_links,
            0,
            0,
            n.transitions.saturating_add(starts),
        ),
        TurnRule::Paper => {
            let table = n.edges + n.start_links + 1;
            let s = table
                .saturating_add(n.start_links)
                .saturating_add(n.transitions)
                .saturating_add(starts);
            let relaxations = n
                .pair_relaxations
                .saturating_add(starts.saturating_mul(n.max_out_degree))
                .saturating_add(starts);
            (s, table, heap_levels(table), relaxations)
        }
    };
    let levels = heap_levels(s);
    let connections = 4 * n.candidates + 2;
    let per_connection = n
        .cells_per_connection
        .saturating_add(n.popups * (n.popup_vertices + 1))
        .saturating_mul(3)
        .saturating_add(1);
    let goal_relaxations = s.saturating_mul(n.goal_links);
    let relaxations = out_relaxations.saturating_add(goal_relaxations);
    let search = s
        .saturating_mul(1 + levels)
        .saturating_add(
            relaxations.saturating_mul(
                n.cells_per_turn
                    .saturating_add(1 + levels)
                    // Each turn arc is also tested against every active pop-up.
                    .saturating_add(n.popups * (n.popup_vertices + 1)),
            ),
        )
        // Reading (and decoding) each popped state, and the start links' pushes.
        .saturating_add(s.saturating_mul(1 + decode))
        .saturating_add(n.start_links * levels)
        .saturating_add(table);
    let endpoints = 2 + 2 * n.popups + 2 * n.vertices;
    let route = (s + 1).saturating_mul(2 * (1 + decode));
    endpoints
        .saturating_add(connections.saturating_mul(per_connection))
        .saturating_add(search)
        .saturating_add(route)
}

/// The counts that bound a Voronoi query's work ([`voronoi_plan_work_bound`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct VoronoiBoundInputs {
    /// Vertices of the search graph, at most
    /// [`VORONOI_GRAPH_VERTICES`](super::VORONOI_GRAPH_VERTICES).
    pub graph_vertices: u64,
    /// Undirected edges of the search graph.
    pub graph_edges: u64,
    /// Threats in force, T.
    pub threats: u64,
    /// Static obstacles (no-fly polygons), O.
    pub obstacles: u64,
    /// Polygon points over all obstacles.
    pub obstacle_points: u64,
    /// Most pop-ups active at once, P.
    pub popups: u64,
    /// Most vertices (polygon) a pop-up has.
    pub popup_vertices: u64,
    /// Graph vertices tried per endpoint, C.
    pub candidates: u64,
    /// The spline fit's bound for a coarse route through every graph vertex
    /// ([`fit_work_bound`](crate::geometry::spline::fit_work_bound)).
    pub fit_steps: u64,
    /// The most clearance queries the fit makes for such a route
    /// ([`fit_clear_bound`](crate::geometry::spline::fit_clear_bound)).
    pub fit_clears: u64,
}

/// The most work one Voronoi [`Planner::plan`](super::Planner::plan) can count. With
/// `c = points + 2·O + P·(p + 1)` the tests of one segment against the zones and pop-ups, and
/// `x = 3·T` the exposure terms of one segment:
/// * the start and goal inside a zone or pop-up: 2(2O + P) (a box and a containment test per
///   zone, a containment test per pop-up);
/// * pricing: every graph edge, x + c;
/// * links: 2·|V_g| vertex scans, ≤ 2C candidates and the direct segment, x + c each;
/// * search: |V_g| heap resets; ≤ |V_g| pops, ≤ 3 + 2|E_g| pushes or decreases, each ≤
///   L = ⌊log2 |V_g|⌋ + 1 levels; ≤ 2|E_g| + 3|V_g| relaxations (half-edges and goal links);
/// * walk-back: ≤ |V_g| + 1 vertex scans;
/// * smoothing: its fit steps, and its clearance queries, each of a segment (c) or of a
///   triangle (its three sides and a containment test per zone and pop-up, 3c + O + P).
pub fn voronoi_plan_work_bound(n: &VoronoiBoundInputs) -> u64 {
    let v = n.graph_vertices;
    let e = n.graph_edges;
    let levels = heap_levels(v);
    let segment = n.obstacle_points + 2 * n.obstacles + n.popups * (n.popup_vertices + 1);
    let exposure = 3 * n.threats;
    let per_segment = segment + exposure;
    let endpoints = 2 * (2 * n.obstacles + n.popups);
    let pricing = e.saturating_mul(per_segment);
    let links = (2 * v).saturating_add((2 * n.candidates + 1).saturating_mul(per_segment));
    let search = v
        .saturating_add((v + 3 + 2 * e).saturating_mul(levels))
        .saturating_add(2 * e + 3 * v);
    let walk = v + 1;
    let smoothing = n.fit_steps.saturating_add(
        n.fit_clears
            .saturating_mul(3 * segment + n.obstacles + n.popups),
    );
    endpoints
        .saturating_add(pricing)
        .saturating_add(links)
        .saturating_add(search)
        .saturating_add(walk)
        .saturating_add(smoothing)
}

/// The most work one landmark [`Planner::plan`](super::Planner::plan) can count on a network
/// (of its counts, `n`, only the vertices, edges, obstacles, their points, the pop-ups and
/// their vertices are read):
///
/// * matching the goal and the start against the stored goal, the stored start and every
///   overflight: |V| + 1 vertex scans;
/// * joining a start that is not a vertex online (`planner/landmark_connect.rs`): |V| + 1
///   vertex scans, and for each of those vertices one piece (a `dubins_solves` unit), one
///   relaxation, a box test per obstacle and pop-up, and [`POPUP_CHORDS_PER_PIECE`] chords
///   each tested against every polygon edge and containment or circle:
///   `w = 1 + 1 + O + P + c·(points + O + P·(popup_vertices + 1))`; a goal that is not the
///   stored goal likewise;
/// * the search: |V| heap resets, ≤ |V| pops and ≤ [`MAX_LINKS`] + |E| pushes or decreases
///   of ≤ L = ⌊log2|V|⌋ + 1 levels, ≤ |E| relaxations (each also reads the weather's quality
///   or an override: O(1)), and ≤ [`MAX_LINKS`] online goal links examined per pop;
/// * the route: ≤ 2(|V| + 1) vertex scans for the two walks back, and the two online pieces
///   built again, `2w`.
///
/// [`POPUP_CHORDS_PER_PIECE`]: super::POPUP_CHORDS_PER_PIECE
/// [`MAX_LINKS`]: super::MAX_LINKS
pub fn landmark_plan_work_bound(n: &WorkBoundInputs) -> u64 {
    let v = n.vertices;
    let levels = heap_levels(v);
    let links = super::MAX_LINKS as u64;
    let chords = super::POPUP_CHORDS_PER_PIECE as u64;
    let piece = 2
        + n.obstacles
        + n.popups
        + chords * (n.obstacle_points + n.obstacles + n.popups * (n.popup_vertices + 1));
    let matching = v + 1;
    let online = 2 * (v + 1) * (1 + piece);
    let search = v + (v + links + n.edges) * levels + n.edges + v * links;
    let route = 2 * (v + 1) + 2 * piece;
    matching + online + search + route
}

/// The most work one [`Planner::add_popup`](super::Planner::add_popup) can count on a landmark
/// network: every grid cell once, every entry once, and for each entry each of its edge's
/// ≤ `max_pieces` pieces rebuilt once (1 unit) and tested with
/// [`POPUP_CHORDS_PER_PIECE`](super::POPUP_CHORDS_PER_PIECE) chords, each chord
/// `popup_vertices + 1` predicate evaluations.
pub fn landmark_popup_work_bound(
    cells: u64,
    entries: u64,
    max_pieces: u64,
    popup_vertices: u64,
) -> u64 {
    let per_piece = 1 + super::POPUP_CHORDS_PER_PIECE as u64 * (popup_vertices + 1);
    cells.saturating_add(entries.saturating_mul(1 + max_pieces.saturating_mul(per_piece)))
}

/// Each bound evaluated on inputs of distinct values, against the worked sum of its documented
/// terms. The numbers were worked out from the doc comments above, term by term, independently
/// of this code (`⌊log2 n⌋ + 1` levels: 6 for 37 vertices, 4 for 10, 7 for 107 states, 9 for
/// 388, 5 for 29): a bound that drops, doubles or mixes up a term fails here even where the
/// planner's counted work stays far below it.
#[cfg(test)]
mod tests {
    use super::*;

    /// The constants the worked examples assume.
    #[test]
    fn the_worked_examples_constants() {
        assert_eq!(super::super::EXIT_TURN_STEPS, 32);
        assert_eq!(super::super::MAX_EXIT_REGIONS, 4);
        assert_eq!(super::super::MAX_EXIT_INTERVALS, 32);
        assert_eq!(super::super::MAX_LINKS, 16);
        assert_eq!(super::super::POPUP_CHORDS_PER_PIECE, 16);
    }

    /// |V| = 37, |E| = 101, O = 5 with 23 points, P = 3 pop-ups of 7 vertices, C = 4, Ks = 6,
    /// Kg = 9, H = 11.
    fn roadmap(three_dimensional: bool) -> WorkBoundInputs {
        WorkBoundInputs {
            vertices: 37,
            edges: 101,
            obstacles: 5,
            obstacle_points: 23,
            popups: 3,
            popup_vertices: 7,
            candidates: 4,
            start_links: 6,
            goal_links: 9,
            goal_headings: 11,
            three_dimensional,
        }
    }

    #[test]
    fn work_total_is_the_sum_of_every_counter() {
        let w = Work {
            vertex_scans: 1,
            dubins_solves: 2,
            collision_tests: 4,
            heap_steps: 8,
            relaxations: 16,
            cells_visited: 32,
            threat_steps: 64,
        };
        assert_eq!(w.total(), 127);
        assert_eq!(Work::ZERO.total(), 0);
        let mut sum = w;
        sum += w;
        sum += Work::ZERO;
        assert_eq!(
            sum,
            Work {
                vertex_scans: 2,
                dubins_solves: 4,
                collision_tests: 8,
                heap_steps: 16,
                relaxations: 32,
                cells_visited: 64,
                threat_steps: 128,
            }
        );
    }

    /// Q = 2·5 + 23 + 3·8 = 57; 65 candidates of trace 2·(23 + 21) + 4 = 92, sort 32² = 1024
    /// and 4Q = 228; a refusal 2·5 + 3 + 57 = 70.
    #[test]
    fn exit_work_bound_is_its_documented_sum() {
        assert_eq!(
            exit_work_bound(&roadmap(false)),
            57 + 65 * (92 + 1024 + 228) + 70
        );
        assert_eq!(exit_work_bound(&roadmap(false)), 87_487);
    }

    /// N = 2·4 + 4·11 + 11 = 63 connections, each primitive's tests 2·5 + 23 + 3·8 = 57.
    #[test]
    fn plan_work_bound_is_its_documented_sum() {
        let endpoints_free = 2 * (2 * 5 + 3); // 26
        let candidates = 2 * 37; // 74
        let connecting = 63 + (44 + 11) + 3 * 5 + 3 * 63 * 57; // 10 906
        let search = 37 + (37 + 6 + 101) * 6 + 101 + 37 * 9; // 1 335
        let exit = 87_487;
        let expected = endpoints_free + candidates + connecting + search + exit;
        assert_eq!(plan_work_bound(&roadmap(false)), expected + 2 * 38);
        // A three-dimensional roadmap walks back from the goal a third time.
        assert_eq!(plan_work_bound(&roadmap(true)), expected + 3 * 38);
        assert_eq!(plan_work_bound(&roadmap(true)), 99_942);
    }

    /// Each unit of a roadmap step that can be the largest made so in turn (c = 3·Q' the
    /// tests of one path, g = 2H + H·c). The other three never are: one start candidate
    /// (1 + c) and the direct path (g) are below one goal candidate (1 + c + g), the goal's
    /// candidates and window (|V| + O) below the begin unit.
    #[test]
    fn roadmap_step_unit_bound_is_its_largest_documented_unit() {
        // The begin unit: O = 3 of 12 points, P = 2 pop-ups of 4 vertices, 10 vertices. Its
        // exit: Q = 6 + 12 + 10 = 28; 65·(2·(12 + 8) + 4 + 1024 + 4·28) + (6 + 2) + 28.
        let small = WorkBoundInputs {
            vertices: 10,
            obstacles: 3,
            obstacle_points: 12,
            popups: 2,
            popup_vertices: 4,
            start_links: 1,
            goal_links: 1,
            goal_headings: 1,
            ..roadmap(false)
        };
        let exit = 28 + 65 * (44 + 1024 + 112) + 8 + 28;
        assert_eq!(
            roadmap_step_unit_bound(&small, 3),
            2 * 3 + 2 + exit + 3 + 10
        );
        // One goal candidate, with H = 1000: c = 3·57 = 171, g = 2000 + 171 000.
        let headings = WorkBoundInputs {
            vertices: 10,
            goal_headings: 1000,
            ..roadmap(false)
        };
        assert_eq!(
            roadmap_step_unit_bound(&headings, 3),
            1 + 171 + 2000 + 171_000
        );
        // The search's start: Ks = 100 000 pushes of 4 levels.
        let links = WorkBoundInputs {
            vertices: 10,
            start_links: 100_000,
            ..roadmap(false)
        };
        assert_eq!(roadmap_step_unit_bound(&links, 3), 10 + 400_000);
        // One expansion with 100 000 out-edges: g = 22 + 11·171 = 1 903.
        let small_v = WorkBoundInputs {
            vertices: 10,
            ..roadmap(false)
        };
        assert_eq!(
            roadmap_step_unit_bound(&small_v, 100_000),
            4 + 9 + 5 + 1903 + 100_000 * 5
        );
        // The route of a million vertices: two walks back, three in three dimensions.
        let big = WorkBoundInputs {
            vertices: 1_000_000,
            ..roadmap(false)
        };
        assert_eq!(roadmap_step_unit_bound(&big, 3), 2 * 1_000_001);
        let big_3d = WorkBoundInputs {
            three_dimensional: true,
            ..big
        };
        assert_eq!(roadmap_step_unit_bound(&big_3d, 3), 3 * 1_000_001);
    }

    /// 13 cells, 17 entries, pop-ups of 5 vertices; landmark edges of at most 3 pieces.
    #[test]
    fn popup_work_bounds_are_their_documented_sums() {
        assert_eq!(popup_work_bound(13, 17, 5), 13 + 17 * (1 + 3 * 6));
        assert_eq!(
            landmark_popup_work_bound(13, 17, 3, 5),
            13 + 17 * (1 + 3 * (1 + 16 * 6))
        );
        assert_eq!(landmark_popup_work_bound(u64::MAX, 1, 3, 5), u64::MAX);
        assert_eq!(landmark_popup_work_bound(1, u64::MAX, 3, 5), u64::MAX);
    }

    /// w = 1 + 1 + 5 + 3 + 16·(23 + 5 + 24) = 842 for one online piece.
    #[test]
    fn landmark_plan_work_bound_is_its_documented_sum() {
        let w = 842;
        let matching = 38;
        let online = 2 * (38 + 38 * w);
        let search = 37 + (37 + 16 + 101) * 6 + 101 + 37 * 16;
        let route = 2 * 38 + 2 * w;
        assert_eq!(
            landmark_plan_work_bound(&roadmap(false)),
            matching + online + search + route
        );
        assert_eq!(landmark_plan_work_bound(&roadmap(false)), 67_520);
    }

    /// |V_g| = 29, |E_g| = 41, T = 6, O = 5 with 23 points, P = 3 of 7 vertices, C = 4, 1 000
    /// fit steps and 67 clearance queries: c = 23 + 10 + 24 = 57, x = 18.
    #[test]
    fn voronoi_plan_work_bound_is_its_documented_sum() {
        let n = VoronoiBoundInputs {
            graph_vertices: 29,
            graph_edges: 41,
            threats: 6,
            obstacles: 5,
            obstacle_points: 23,
            popups: 3,
            popup_vertices: 7,
            candidates: 4,
            fit_steps: 1000,
            fit_clears: 67,
        };
        let endpoints = 2 * (10 + 3);
        let pricing = 41 * (18 + 57);
        let links = 58 + 9 * (18 + 57);
        let search = 29 + (29 + 3 + 82) * 5 + 82 + 87;
        let walk = 30;
        let smoothing = 1000 + 67 * (3 * 57 + 5 + 3);
        assert_eq!(
            voronoi_plan_work_bound(&n),
            endpoints + pricing + links + search + walk + smoothing
        );
        assert_eq!(voronoi_plan_work_bound(&n), 17_625);
    }

    /// |V| = 37, |E| = 101, T = 250 transitions, 700 pair relaxations, out-degree ≤ 4, P = 3 of
    /// 7 vertices, C = 4, Ks = 6, Kg = 9, 40 cells per turn and 120 per connection.
    fn terrain(turn_rule: TurnRule) -> TerrainBoundInputs {
        TerrainBoundInputs {
            vertices: 37,
            edges: 101,
            transitions: 250,
            pair_relaxations: 700,
            turn_rule,
            max_out_degree: 4,
            popups: 3,
            popup_vertices: 7,
            candidates: 4,
            start_links: 6,
            goal_links: 9,
            cells_per_turn: 40,
            cells_per_connection: 120,
        }
    }

    #[test]
    fn terrain_plan_work_bound_is_its_documented_sum() {
        let endpoints = 2 + 6 + 74;
        let connections = 18 * (1 + 3 * (120 + 24));
        // The equal split: S = 107 states of L = 7 levels; relaxations 250 + 6·4 and 107·9
        // goal links, each a turn arc of 40 cells, 24 pop-up tests, itself and a heap operation.
        let search = 107 * 8 + (274 + 963) * (40 + 24 + 1 + 7) + 107 + 6 * 7;
        let route = 2 * 108;
        assert_eq!(
            terrain_plan_work_bound(&terrain(TurnRule::SharedEqually)),
            endpoints + connections + search + route
        );
        // The paper's rule: a table of 108 entries (D = 7 reads to decode), S = 108 + 6 + 250
        // + 24 = 388 states of L = 9 levels; relaxations 700 + 6·16 + 6·4 and 388·9.
        let search = 388 * 10 + (820 + 3492) * (40 + 24 + 1 + 9) + 388 * 8 + 6 * 9 + 108;
        let route = 2 * 389 * 8;
        assert_eq!(
            terrain_plan_work_bound(&terrain(TurnRule::Paper)),
            endpoints + connections + search + route
        );
        // A turn arc whose cells overflow (`cells_bound` of a non-finite arc) saturates.
        for rule in [TurnRule::SharedEqually, TurnRule::Paper] {
            let huge = TerrainBoundInputs {
                cells_per_turn: u64::MAX,
                ..terrain(rule)
            };
            assert_eq!(terrain_plan_work_bound(&huge), u64::MAX);
        }
    }

    /// `2(ρ + √2)·L + π(ρ + √2)²` with ρ = widen + 0.01, rounded up (values computed in f64, none
    /// within 0.05 of an integer).
    #[test]
    fn cells_bound_is_the_grid_bound_rounded_up() {
        assert_eq!(cells_bound(10.0, 1.0), 67); // 66.947
        assert_eq!(cells_bound(0.0, 0.0), 7); // 6.372
        assert_eq!(cells_bound(250.5, 3.25), 2411); // 2 410.419
        assert_eq!(cells_bound(1000.0, 0.0), 2855); // 2 854.799
        assert_eq!(cells_bound(f32::INFINITY, 0.0), u64::MAX);
        assert_eq!(cells_bound(f32::NAN, 1.0), u64::MAX);
        assert_eq!(cells_bound(1e30, 1.0), u64::MAX);
    }
}
