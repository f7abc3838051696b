//! Planning and the route: `sr_plan` and `sr_route_primitives`.

use crate::status::plan_status;
use crate::{planner_mut, planner_ref, SrPlanner, SrStatus};
use skyroute::planner::{Exit, Violation};
use skyroute::{Goal, Pose, Primitive, Query, RouteSummary, Search, Vec2, Work};

/// `sr_query.search`: Dijkstra's algorithm.
pub const SR_SEARCH_DIJKSTRA: u8 = 0;
/// `sr_query.search`: A* with the straight-line distance to the goal.
pub const SR_SEARCH_A_STAR: u8 = 1;

/// `sr_primitive.kind`: a straight line (`sr_primitive.line`).
pub const SR_PRIMITIVE_LINE: u32 = 0;
/// `sr_primitive.kind`: a circular arc (`sr_primitive.arc`).
pub const SR_PRIMITIVE_ARC: u32 = 1;

/// `sr_route_summary.exit_kind`: the start lay clear of every obstacle and pop-up.
pub const SR_EXIT_NONE: u8 = 0;
/// `sr_route_summary.exit_kind`: the route begins by leaving static obstacle `exit_index`.
pub const SR_EXIT_OBSTACLE: u8 = 1;
/// `sr_route_summary.exit_kind`: the route begins by leaving pop-up `exit_index`.
pub const SR_EXIT_POPUP: u8 = 2;

/// One planning request, in the network's local frame: metres east (`x`) and north (`y`) of
/// its origin; headings in radians counter-clockwise from east.
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C)]
pub struct SrQuery {
    /// The aircraft's position, east, metres.
    pub start_x: f32,
    /// The aircraft's position, north, metres.
    pub start_y: f32,
    /// The aircraft's heading, radians counter-clockwise from east.
    pub start_heading: f32,
    /// The goal, east, metres.
    pub goal_x: f32,
    /// The goal, north, metres.
    pub goal_y: f32,
    /// The heading to arrive with, read only when `goal_has_heading` is not 0.
    pub goal_heading: f32,
    /// 0: any arrival heading (tried at 36 evenly spaced headings); otherwise `goal_heading`.
    pub goal_has_heading: u8,
    /// `SR_SEARCH_DIJKSTRA` or `SR_SEARCH_A_STAR`.
    pub search: u8,
}

/// The work a query counted, by kind; a budget is compared with `total`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[repr(C)]
pub struct SrWork {
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
    /// Voronoi exposure terms, diagram predicates and spline-fit steps (0 here).
    pub threat_steps: u64,
    /// The sum of the counters above.
    pub total: u64,
}

/// What a successful `sr_plan` found (its lines and arcs: `sr_route_primitives`).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[repr(C)]
pub struct SrRouteSummary {
    /// Length of the route, metres.
    pub length: f32,
    /// The heading the route arrives with, radians counter-clockwise from east.
    pub arrival_heading: f32,
    /// Lines and arcs in the route (at most `SR_MAX_ROUTE_PRIMITIVES`).
    pub primitives: u32,
    /// Network edges the route uses.
    pub network_edges: u32,
    /// The work the query counted.
    pub work: SrWork,
    /// `SR_EXIT_NONE`, or the kind of region the start lay in and the route leaves first:
    /// `SR_EXIT_OBSTACLE` or `SR_EXIT_POPUP`.
    pub exit_kind: u8,
    /// The obstacle's index or the pop-up's id (0 with `SR_EXIT_NONE`).
    pub exit_index: u32,
    /// How many regions the start lay in (0 with `SR_EXIT_NONE`).
    pub exit_regions: u32,
    /// Length of the route's first path, which leaves the regions, metres (0 with
    /// `SR_EXIT_NONE`).
    pub exit_length: f32,
}

/// A straight line from `(x0, y0)` to `(x1, y1)`, metres.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[repr(C)]
pub struct SrLine {
    /// First point, east.
    pub x0: f32,
    /// First point, north.
    pub y0: f32,
    /// Last point, east.
    pub x1: f32,
    /// Last point, north.
    pub y1: f32,
}

/// A circular arc: from polar angle `start_angle` about `(cx, cy)`, `sweep` radians
/// (positive: counter-clockwise, a left turn).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[repr(C)]
pub struct SrArc {
    /// Centre, east, metres.
    pub cx: f32,
    /// Centre, north, metres.
    pub cy: f32,
    /// Radius, metres.
    pub radius: f32,
    /// Polar angle of the first point about the centre, radians.
    pub start_angle: f32,
    /// Signed swept angle, radians.
    pub sweep: f32,
}

/// One piece of a route: `kind` says which of `line` and `arc` holds it (the other is all
/// zero).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[repr(C)]
pub struct SrPrimitive {
    /// `SR_PRIMITIVE_LINE` or `SR_PRIMITIVE_ARC`.
    pub kind: u32,
    /// The line, when `kind` is `SR_PRIMITIVE_LINE`.
    pub line: SrLine,
    /// The arc, when `kind` is `SR_PRIMITIVE_ARC`.
    pub arc: SrArc,
}

impl SrQuery {
    /// The core's query, or `None` for an unknown search kind.
    pub fn to_query(&self) -> Option<Query> {
        let search = match self.search {
            SR_SEARCH_DIJKSTRA => Search::Dijkstra,
            SR_SEARCH_A_STAR => Search::AStar,
            _ => return None,
        };
        Some(Query {
            start: Pose::new(self.start_x, self.start_y, self.start_heading),
            goal: Goal {
                position: Vec2::new(self.goal_x, self.goal_y),
                heading: (self.goal_has_heading != 0).then_some(self.goal_heading),
            },
            search,
        })
    }
}

impl From<&Work> for SrWork {
    fn from(w: &Work) -> Self {
        SrWork {
            vertex_scans: w.vertex_scans,
            dubins_solves: w.dubins_solves,
            collision_tests: w.collision_tests,
            heap_steps: w.heap_steps,
            relaxations: w.relaxations,
            cells_visited: w.cells_visited,
            threat_steps: w.threat_steps,
            total: w.total(),
        }
    }
}

impl From<&RouteSummary> for SrRouteSummary {
    fn from(s: &RouteSummary) -> Self {
        let (exit_kind, exit_index) = match s.exit {
            None => (SR_EXIT_NONE, 0),
            Some(Exit {
                violated: Violation::Obstacle(i),
                ..
            }) => (SR_EXIT_OBSTACLE, i),
            Some(Exit {
                violated: Violation::Popup(id),
                ..
            }) => (SR_EXIT_POPUP, id as u32),
        };
        SrRouteSummary {
            length: s.length,
            arrival_heading: s.arrival_heading,
            primitives: s.primitives,
            network_edges: s.network_edges,
            work: SrWork::from(&s.work),
            exit_kind,
            exit_index,
            exit_regions: s.exit.map_or(0, |e| e.regions),
            exit_length: s.exit.map_or(0.0, |e| e.length),
        }
    }
}

impl From<&Primitive> for SrPrimitive {
    fn from(p: &Primitive) -> Self {
        match p {
            Primitive::Line(s) => SrPrimitive {
                kind: SR_PRIMITIVE_LINE,
                line: SrLine {
                    x0: s.start.x,
                    y0: s.start.y,
                    x1: s.end.x,
                    y1: s.end.y,
                },
                arc: SrArc::default(),
            },
            Primitive::Arc(a) => SrPrimitive {
                kind: SR_PRIMITIVE_ARC,
                line: SrLine::default(),
                arc: SrArc {
                    cx: a.centre.x,
                    cy: a.centre.y,
                    radius: a.radius,
                    start_angle: a.start_angle,
                    sweep: a.sweep,
                },
            },
        }
    }
}

/// Plans `query` with at most `budget` work (`sr_worst_case_work` gives a budget that always
/// suffices) and writes the route's summary to `*summary`. On an error `*summary` is not
/// written and the planner keeps its previous route. The route's lines and arcs:
/// `sr_route_primitives`.
///
/// # Safety
/// `planner` is NULL or a handle from `sr_planner_init`; `query` is NULL or points to a
/// readable `sr_query`; `summary` is NULL or points to a writable `sr_route_summary`.
#[no_mangle]
pub unsafe extern "C" fn sr_plan(
    planner: *mut SrPlanner,
    query: *const SrQuery,
    budget: u64,
    summary: *mut SrRouteSummary,
) -> SrStatus {
    // SAFETY: the caller passes NULL or a handle from `sr_planner_init`, used by this call
    // alone.
    let Some(p) = (unsafe { planner_mut(planner) }) else {
        return SrStatus::NullPointer;
    };
    // SAFETY: the caller passes NULL or a readable query (any bytes are a valid `SrQuery`).
    let Some(q) = (unsafe { query.as_ref() }) else {
        return SrStatus::NullPointer;
    };
    if summary.is_null() {
        return SrStatus::NullPointer;
    }
    let Some(query) = q.to_query() else {
        return SrStatus::InvalidArgument;
    };
    match p.plan(&query, budget) {
        Ok(s) => {
            // SAFETY: `summary` is non-null and the caller gives it writable.
            unsafe { summary.write(SrRouteSummary::from(&s)) };
            SrStatus::Ok
        }
        Err(e) => plan_status(&e),
    }
}

/// Copies the last route's lines and arcs, start to goal, into `out[0..capacity]` and writes
/// how many the route has to `*count` (0 before any route; a landmark route's curves are not
/// lines and arcs, and count 0). Writes `min(capacity, count)` of them and returns
/// `SR_STATUS_BUFFER_TOO_SMALL` if `capacity < count`. `out` may be NULL when `capacity` is 0,
/// to ask for the count alone. An array of `SR_MAX_ROUTE_PRIMITIVES` always suffices.
///
/// # Safety
/// `planner` is NULL or a handle from `sr_planner_init`; `out` is NULL or points to
/// `capacity` writable `sr_primitive`s; `count` is NULL or points to a writable integer.
#[no_mangle]
pub unsafe extern "C" fn sr_route_primitives(
    planner: *const SrPlanner,
    out: *mut SrPrimitive,
    capacity: usize,
    count: *mut usize,
) -> SrStatus {
    // SAFETY: the caller passes NULL or a handle from `sr_planner_init`.
    let Some(p) = (unsafe { planner_ref(planner) }) else {
        return SrStatus::NullPointer;
    };
    if count.is_null() || (out.is_null() && capacity > 0) {
        return SrStatus::NullPointer;
    }
    let route = p.route();
    for (i, prim) in route.iter().take(capacity).enumerate() {
        // SAFETY: `out` is non-null (capacity > 0 here) and points to `capacity` writable
        // primitives, as the caller guarantees; `i < capacity`.
        unsafe { out.add(i).write(SrPrimitive::from(prim)) };
    }
    // SAFETY: `count` is non-null and the caller gives it writable.
    unsafe { count.write(route.len()) };
    if capacity < route.len() {
        SrStatus::BufferTooSmall
    } else {
        SrStatus::Ok
    }
}
