//! Planning in slices: a query begun with [`Planner::start_plan`] and advanced by
//! [`Planner::step`], a bounded amount of work at a time, so that an executor can run other
//! tasks between the slices. [`Planner::plan`] is the same machine run in one step.
//!
//! A query goes through stages, each made of indivisible units of work: a step runs units
//! until the work it counted reaches its slice, so it overruns the slice by less than one
//! unit ([`Planner::step_unit_bound`] bounds a unit; [`roadmap_step_unit_bound`] lists the
//! units of a roadmap query).
//!
//! [`roadmap_step_unit_bound`]: super::roadmap_step_unit_bound

use super::connect::Candidates;
use super::search::{Arrival, Ends, LandmarkEnd};
use super::state::ModeState;
use super::window::{LazyWindow, ObstacleWindow};
use super::{
    roadmap_step_unit_bound, Exit, Meter, Phase, PlanError, Planner, Query, RouteSummary,
    SummarySlot, Work,
};
use crate::geometry::{DubinsPath, Vec2};
use heapless::Vec;

/// What one [`Planner::step`] ended with.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum PlanStep {
    /// The query goes on: call [`Planner::step`] again.
    InProgress {
        /// Work the query has counted since [`Planner::start_plan`].
        work_so_far: u64,
    },
    /// The query has ended with this result, the one [`Planner::plan`] gives for the same
    /// query and budget. On success the route has been replaced; on error the previous route
    /// is kept.
    Done(Result<RouteSummary, PlanError>),
    /// No query is in progress: none was started, the last one is done, or it was cancelled
    /// ([`Planner::cancel_plan`], or any method that changes the planner's state).
    Idle,
}

/// Where a query in progress stands: the unit of work its next step begins with.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(u8)]
pub(super) enum Stage {
    /// No query (discriminant 0: a new planner is idle).
    Idle = 0,
    /// Everything before the connection loops (roadmap: the free-space check of the goal,
    /// the exit, the start's obstacle window and candidates; the other modes: everything
    /// before the search).
    Begin,
    /// Roadmap: one start candidate tried.
    ConnectStart,
    /// Roadmap: the goal's candidates and obstacle window.
    GoalBegin,
    /// Roadmap: one goal candidate tried.
    ConnectGoal,
    /// Roadmap: the direct start–goal path.
    ConnectDirect,
    /// The search's heap reset and start states.
    SearchBegin,
    /// One state of the search expanded.
    Search,
    /// The route written.
    Route,
}

/// A query in progress: its stage and everything its later stages read. The planner keeps it
/// in place ([`Planner::step`] works on it there, by split borrows of the planner's fields);
/// an idle one ([`Flight::IDLE`]) is all-zero bytes, so that a new planner is too.
pub(super) struct Flight<'n> {
    /// The next unit of work.
    pub(super) stage: Stage,
    /// The query (roadmap: its start moved to the exit's end, if it needs one).
    query: Query,
    /// The work counted so far, and the query's budget.
    meter: Meter,
    /// Where the search starts and what it looks for.
    ends: Ends,
    /// Roadmap: the exit from the keep-out region the start lies in (at most one).
    exit: Vec<(DubinsPath, Exit), 1>,
    /// Roadmap: the obstacles around the start (read in [`Stage::Begin`], for the start links
    /// and the direct path).
    start_window: ObstacleWindow<'n>,
    /// Roadmap: the obstacles around the goal, for the goal links and then, read again when
    /// the search first resolves a pending goal link, for the search.
    goal_window: LazyWindow<'n>,
    /// Roadmap: the candidates of the connection under way, and the next one to try.
    candidates: Candidates,
    next: usize,
    /// The cheapest route found so far (at first the direct path, if any), with its cost.
    pub(super) best: Vec<(f32, Arrival), 1>,
}

impl Flight<'_> {
    /// No query in progress, usable in `const` (a new planner): all-zero bytes (the stage's
    /// and the search ends' discriminants, an unread goal window, the windows' unused slots
    /// and a `None` goal heading are all 0; empty vectors have only a zero length).
    pub(super) const IDLE: Self = Self {
        stage: Stage::Idle,
        query: Query {
            start: crate::geometry::Pose {
                position: crate::geometry::Vec2 { x: 0.0, y: 0.0 },
                heading: 0.0,
            },
            goal: super::Goal {
                position: crate::geometry::Vec2 { x: 0.0, y: 0.0 },
                heading: None,
            },
            search: super::Search::Dijkstra,
        },
        meter: Meter::new(0),
        ends: Ends::Links,
        exit: Vec::new(),
        start_window: ObstacleWindow::EMPTY,
        goal_window: LazyWindow::UNREAD,
        candidates: Vec::new(),
        next: 0,
        best: Vec::new(),
    };
}

impl<'n, const V: usize, const E: usize, const P: usize, const R: usize> Planner<'n, V, E, P, R> {
    /// Starts planning from `query.start` to `query.goal`, counting work against `budget` over
    /// the whole query, as [`Planner::plan`] does; [`Planner::step`] then does the work a
    /// slice at a time. A query already in progress is cancelled. Refuses a query whose
    /// numbers are not finite or out of range with the error `plan` gives (the previous route
    /// is kept, and no query is in progress). Work: none.
    ///
    /// While the query is in progress the previous route stays readable
    /// ([`Planner::route`]); it is replaced only when the query succeeds. Any method that
    /// changes the planner (`load`, `load_voronoi`, `set_config`, `add_popup`,
    /// `remove_popup`, `fly_alternatives`, `set_altitude`, `set_weather`, the rosette and
    /// threat methods, `shortcut`, `smooth_headings`) cancels the query first: the next [`Planner::step`] returns [`PlanStep::Idle`] and the route is the
    /// previous one. Start the query again to plan with the new state.
    pub fn start_plan(&mut self, query: &Query, budget: u64) -> Result<(), PlanError> {
        self.cancel_plan();
        Self::check_query(query)?;
        let f = &mut self.flight;
        f.query = *query;
        f.meter = Meter::new(budget);
        f.ends = Ends::Links;
        f.exit.clear();
        f.start_window.clear();
        f.goal_window.forget();
        f.candidates.clear();
        f.next = 0;
        f.best.clear();
        f.stage = Stage::Begin;
        Ok(())
    }

    /// Advances the query in progress by about `slice_work` units of work: runs indivisible
    /// units until the work counted in this call reaches `slice_work` (at least one unit), so
    /// a call counts less than `slice_work` plus [`Planner::step_unit_bound`]. Returns
    /// [`PlanStep::Done`] with the query's result when it ends (the result, work included, is
    /// the one [`Planner::plan`] gives), [`PlanStep::InProgress`] when there is more to do, and
    /// [`PlanStep::Idle`] when no query is in progress.
    pub fn step(&mut self, slice_work: u64) -> PlanStep {
        self.step_observed(slice_work, &mut |_, _| {})
    }

    /// Whether a query is in progress (started and neither done nor cancelled).
    pub fn is_planning(&self) -> bool {
        self.flight.stage != Stage::Idle
    }

    /// Abandons the query in progress, if any: the route stays the previous one, and
    /// [`Planner::step`] returns [`PlanStep::Idle`] until a query is started.
    pub fn cancel_plan(&mut self) {
        self.flight.stage = Stage::Idle;
    }

    /// The most work one indivisible unit of [`Planner::step`] can count on the loaded
    /// network, for any query: a step of slice `k` counts at most `k − 1` plus this. Roadmap
    /// queries are sliced in every stage ([`roadmap_step_unit_bound`]); terrain, landmark and
    /// Voronoi queries only in their search, their preparation (checks, connections,
    /// pricing) and their route being one unit each, so for them this is
    /// [`Planner::worst_case_work`].
    pub fn step_unit_bound(&self) -> u64 {
        match self.state {
            ModeState::Roadmap(_) => {
                let net = &self.network;
                let most_out = (0..net.vertex_count())
                    .map(|v| net.out_edges(v).len() as u64)
                    .max()
                    .unwrap_or(0);
                roadmap_step_unit_bound(&self.work_bound_inputs(false), most_out)
            }
            ModeState::Terrain(_) | ModeState::Landmark(_) | ModeState::Voronoi(_) => {
                self.worst_case_work()
            }
        }
    }

    /// [`Planner::step`], telling `observe` as [`Planner::plan_observed`] does. The query
    /// state stays in the planner; only its meter is taken out for the step.
    pub(super) fn step_observed(
        &mut self,
        slice_work: u64,
        observe: &mut dyn FnMut(Phase, &Work),
    ) -> PlanStep {
        if self.flight.stage == Stage::Idle {
            return PlanStep::Idle;
        }
        let mut meter = core::mem::replace(&mut self.flight.meter, Meter::new(0));
        let limit = meter.work.total().saturating_add(slice_work);
        let ended = loop {
            match self.advance(&mut meter, limit, observe) {
                Ok(None) => {}
                Ok(Some(summary)) => break Some(Ok(summary)),
                Err(e) => break Some(Err(e)),
            }
            if meter.work.total() >= limit {
                break None;
            }
        };
        match ended {
            Some(result) => {
                self.flight.stage = Stage::Idle;
                observe(Phase::Done, &meter.work);
                PlanStep::Done(result)
            }
            None => {
                let work_so_far = meter.work.total();
                self.flight.meter = meter;
                PlanStep::InProgress { work_so_far }
            }
        }
    }

    /// The obstacles around the query's start ([`Stage::Begin`] reads them).
    pub(super) fn start_window(&self) -> &ObstacleWindow<'n> {
        &self.flight.start_window
    }

    /// The obstacles around the query's goal, if read: in [`Stage::GoalBegin`] for the goal
    /// links, and again in the search when it first resolves a pending goal link
    /// ([`Planner::read_goal_window_once`]).
    pub(super) fn goal_window(&self) -> Option<&ObstacleWindow<'n>> {
        self.flight.goal_window.get()
    }

    /// Reads the obstacles around the goal at `centre` into the query's goal window unless it
    /// has been read since the search began (work: [`ObstacleWindow::read_around`] the first
    /// time).
    pub(super) fn read_goal_window_once(&mut self, centre: Vec2, meter: &mut Meter) {
        self.flight
            .goal_window
            .read_once(&self.network, centre, meter);
    }

    /// Runs the unit of work the stage names and moves the query on (in the search, further
    /// expansions too, one at a time while the work counted stays below `limit`: the step's
    /// loop, without leaving the search between them). Returns the route's summary when the
    /// query is done.
    #[inline(never)] // one copy of the search's loop, shared by `plan` and `step`
    fn advance(
        &mut self,
        meter: &mut Meter,
        limit: u64,
        observe: &mut dyn FnMut(Phase, &Work),
    ) -> Result<Option<RouteSummary>, PlanError> {
        let q = self.flight.query;
        match self.flight.stage {
            Stage::Idle => return Err(PlanError::Internal),
            Stage::Begin => return self.begin(meter, observe).map(|()| None),
            Stage::ConnectStart => match self.next_candidate() {
                Some(v) if !self.start_links_full() => {
                    self.flight.next += 1;
                    self.connect_start_candidate(&q.start, v, meter)?;
                }
                _ => self.flight.stage = Stage::GoalBegin,
            },
            Stage::GoalBegin => {
                observe(Phase::ConnectGoal, &meter.work);
                self.flight.candidates = self.connect_goal_begin(&q.goal, meter)?;
                self.flight.next = 0;
                self.flight
                    .goal_window
                    .read(&self.network, q.goal.position, meter);
                self.flight.stage = Stage::ConnectGoal;
            }
            Stage::ConnectGoal => match self.next_candidate() {
                Some(v) if !self.goal_links_full() => {
                    self.flight.next += 1;
                    self.connect_goal_candidate(&q.goal, v, meter)?;
                }
                _ => self.flight.stage = Stage::ConnectDirect,
            },
            Stage::ConnectDirect => {
                observe(Phase::ConnectDirect, &meter.work);
                let direct = if q.start.position.distance(q.goal.position)
                    <= self.config().connect_radius_m
                {
                    let altitudes = self.query_altitudes();
                    let window = self.start_window();
                    self.best_clear_path_to_goal(&q.start, &q.goal, altitudes, window, meter)?
                } else {
                    None
                };
                self.check_connected(direct.is_some())?;
                let f = &mut self.flight;
                f.best.clear();
                if let Some(p) = direct {
                    let _ = f.best.push((p.length(), Arrival::Direct(p)));
                }
                f.stage = Stage::SearchBegin;
            }
            Stage::SearchBegin => {
                if self.observes_phases() {
                    observe(Phase::Search, &meter.work);
                }
                self.flight.goal_window.forget();
                self.search_begin(&q, self.flight.ends, meter)?;
                self.flight.stage = Stage::Search;
            }
            Stage::Search => {
                let ends = self.flight.ends;
                let mut best = self.flight.best.first().copied();
                let over = loop {
                    let over = self.search_expand(&q, ends, &mut best, meter)?;
                    if over || meter.work.total() >= limit {
                        break over;
                    }
                };
                let f = &mut self.flight;
                f.best.clear();
                if let Some(b) = best {
                    let _ = f.best.push(b);
                }
                if over {
                    f.stage = Stage::Route;
                }
            }
            Stage::Route => {
                let arrival = self
                    .flight
                    .best
                    .first()
                    .map(|&(_, a)| a)
                    .ok_or(PlanError::NoRoute)?;
                if self.observes_phases() {
                    observe(Phase::Route, &meter.work);
                }
                return self.finish_query(arrival, meter).map(Some);
            }
        }
        Ok(None)
    }

    /// The vertex of the connection's next candidate, if any is left.
    fn next_candidate(&self) -> Option<u32> {
        let f = &self.flight;
        f.candidates.get(f.next).map(|&(_, v)| v)
    }

    /// The [`Stage::Begin`] unit: everything before the roadmap's connection loops, or before
    /// the search in the other modes.
    #[inline(never)] // once per query; inlined, its frame would add to the search loop's
    fn begin(
        &mut self,
        meter: &mut Meter,
        observe: &mut dyn FnMut(Phase, &Work),
    ) -> Result<(), PlanError> {
        let q = self.flight.query;
        let direct = match self.state {
            ModeState::Roadmap(_) => {
                self.check_query_altitudes()?;
                observe(Phase::CheckFree, &meter.work);
                self.check_free(q.goal.position, super::QueryField::Goal, meter)?;
                let exit = self.exit_from(&q.start, meter)?;
                if let Some((path, e)) = exit {
                    // The query goes on from where the exit ends.
                    self.flight.query.start = path.end();
                    let _ = self.flight.exit.push((path, e));
                }
                observe(Phase::ConnectStart, &meter.work);
                let start = self.flight.query.start;
                self.flight
                    .start_window
                    .read_around(&self.network, start.position, meter);
                self.flight.candidates = self.connect_start_begin(&start, meter)?;
                self.flight.next = 0;
                self.flight.stage = Stage::ConnectStart;
                return Ok(());
            }
            ModeState::Terrain(_) => self.terrain_prepare(&q, meter, observe)?,
            ModeState::Voronoi(_) => self.voronoi_prepare(&q, meter)?,
            ModeState::Landmark(_) => {
                self.flight.ends = self.landmark_prepare(&q, meter)?;
                None
            }
        };
        if let Some((cost, p)) = direct {
            let _ = self.flight.best.push((cost, Arrival::Direct(p)));
        }
        self.flight.stage = Stage::SearchBegin;
        Ok(())
    }

    /// Refuses a roadmap query whose start or goal has no link and no direct path.
    fn check_connected(&self, direct: bool) -> Result<(), PlanError> {
        if self.start_links.is_empty() && !direct {
            return Err(PlanError::StartUnconnected);
        }
        if self.goal_links.is_empty() && !direct {
            return Err(PlanError::GoalUnconnected);
        }
        Ok(())
    }

    /// Whether the loaded mode's queries report their phases to an observer (roadmap and
    /// terrain).
    fn observes_phases(&self) -> bool {
        matches!(self.state, ModeState::Roadmap(_) | ModeState::Terrain(_))
    }

    /// The [`Stage::Route`] unit: writes the route the search found, the mode's way.
    #[inline(never)] // once per query; inlined, its frame would add to the search loop's
    fn finish_query(
        &mut self,
        arrival: Arrival,
        meter: &mut Meter,
    ) -> Result<RouteSummary, PlanError> {
        match self.state {
            ModeState::Roadmap(_) => {
                let exit = self.flight.exit.first().copied();
                self.charge_route_altitudes(&arrival, meter)?;
                let mut summary =
                    self.write_route(arrival, exit.as_ref().map(|(path, _)| path), meter)?;
                self.fill_route_altitudes(&arrival, exit.is_some())?;
                summary.exit = exit.map(|(_, e)| e);
                self.summary = SummarySlot::Full(summary);
                Ok(summary)
            }
            ModeState::Terrain(_) => self.write_terrain_route(arrival, meter),
            ModeState::Voronoi(_) => {
                let query = self.flight.query;
                self.write_voronoi_route(&query, arrival, meter)
            }
            ModeState::Landmark(_) => {
                let query = self.flight.query;
                let ends = match (arrival, self.flight.ends) {
                    (
                        Arrival::AtVertex,
                        Ends::Landmark {
                            from,
                            to: LandmarkEnd::Vertex(to),
                        },
                    ) => (from, to, None),
                    (
                        Arrival::FromState { state, link },
                        Ends::Landmark {
                            from,
                            to: LandmarkEnd::Online,
                        },
                    ) => (from, state, Some(link)),
                    _ => return Err(PlanError::Internal),
                };
                self.write_landmark_route(&query, ends, meter)
            }
        }
    }
}
