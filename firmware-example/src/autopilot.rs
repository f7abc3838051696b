//! The planner as an autopilot task drives it: replan at a fixed period from the current state
//! estimate, hand each route to guidance, sleep for the rest of the period.
//!
//! The task touches the hardware only through traits: an `embedded_hal::delay::DelayNs` to
//! wait, and a [`Ticks`] clock to measure (embedded-hal 1.0 has no clock trait; a board HAL's
//! monotonic timer, RTIC's `Monotonic` or `embassy_time::Instant` fill that role). Where an
//! integrator's code plugs in:
//!
//! * **delay / clock:** the board HAL's `DelayNs` and timer (here: SysTick, `crate::clock`);
//! * **query source:** the closure [`RouteTask::run`] calls each cycle; on an aircraft it reads
//!   the navigation filter's pose and the mission's current goal;
//! * **route sink:** the closure that receives each [`Cycle`]; on an aircraft it hands the
//!   primitives to the path-following controller (or queues them for the telemetry link);
//! * **pop-ups:** [`RouteTask::planner`] gives the planner to the threat/geofence feed between
//!   cycles (`add_popup` / `remove_popup`).
//!
//! Under an RTOS or an async executor the same body becomes a task whose `delay` is the
//! executor's timer.

use embedded_hal::delay::DelayNs;
use skyroute::planner::RouteSummary;
use skyroute::{PlanError, Planner, Primitive, Query};

/// A free-running tick counter.
pub trait Ticks {
    /// Ticks since some fixed instant; never decreases.
    fn ticks(&self) -> u64;
    /// Ticks per second.
    fn hz(&self) -> u32;
}

/// What one planning cycle produced, handed to the route sink.
pub struct Cycle<'r> {
    /// 0, 1, 2, …
    pub index: u32,
    /// The query planned.
    pub query: Query,
    /// The planner's verdict. On an error the planner keeps its previous route, which
    /// [`Cycle::route`] then still shows.
    pub outcome: Result<RouteSummary, PlanError>,
    /// The route's primitives (lines and arcs from the start pose to the goal).
    pub route: &'r [Primitive],
    /// Clock ticks the `plan` call took.
    pub plan_ticks: u64,
}

/// Whether the task goes on after a cycle.
#[derive(Clone, Copy, PartialEq, Eq, defmt::Format)]
pub enum Next {
    /// Plan again after the period.
    Continue,
    /// Return from [`RouteTask::run`].
    Stop,
}

/// A periodic replanning task over a planner that lives in a `static`.
pub struct RouteTask<
    'p,
    'n,
    D: DelayNs,
    C: Ticks,
    const V: usize,
    const E: usize,
    const P: usize,
    const R: usize,
> {
    planner: &'p mut Planner<'n, V, E, P, R>,
    delay: D,
    clock: C,
    period_ms: u32,
    budget: u64,
}

impl<
        'p,
        'n,
        D: DelayNs,
        C: Ticks,
        const V: usize,
        const E: usize,
        const P: usize,
        const R: usize,
    > RouteTask<'p, 'n, D, C, V, E, P, R>
{
    /// A task that plans every `period_ms` with at most `budget` work per plan (compare
    /// [`Planner::worst_case_work`]).
    pub fn new(
        planner: &'p mut Planner<'n, V, E, P, R>,
        delay: D,
        clock: C,
        period_ms: u32,
        budget: u64,
    ) -> Self {
        Self {
            planner,
            delay,
            clock,
            period_ms,
            budget,
        }
    }

    /// The planner, e.g. for the pop-up feed between cycles.
    pub fn planner(&mut self) -> &mut Planner<'n, V, E, P, R> {
        self.planner
    }

    /// One cycle planning `query`: the outcome and the ticks `plan` took.
    pub fn plan_once(&mut self, query: Query) -> (Result<RouteSummary, PlanError>, u64) {
        let mut result = (Err(PlanError::Internal), 0);
        self.run(
            |_| query,
            |cycle: &Cycle<'_>| {
                result = (cycle.outcome, cycle.plan_ticks);
                Next::Stop
            },
        );
        result
    }

    /// Runs cycles until `on_route` says [`Next::Stop`]; returns the number of cycles run.
    /// Each cycle asks `query` for the current query, plans, hands the result to `on_route`,
    /// then waits for the rest of the period (no wait when planning overran it).
    pub fn run(
        &mut self,
        mut query: impl FnMut(u32) -> Query,
        mut on_route: impl FnMut(&Cycle<'_>) -> Next,
    ) -> u32 {
        let period_ticks = self.period_ms as u64 * self.clock.hz() as u64 / 1000;
        let mut index = 0;
        loop {
            let cycle_start = self.clock.ticks();
            let q = query(index);
            let (outcome, plan_ticks) = crate::with_stack_peak("plan", || {
                let t0 = self.clock.ticks();
                let outcome = self.planner.plan(&q, self.budget);
                (outcome, self.clock.ticks() - t0)
            });
            let next = on_route(&Cycle {
                index,
                query: q,
                outcome,
                route: self.planner.route(),
                plan_ticks,
            });
            index += 1;
            if next == Next::Stop {
                return index;
            }
            let spent = self.clock.ticks() - cycle_start;
            if let Some(rest) = period_ticks.checked_sub(spent) {
                let us = rest * 1_000_000 / self.clock.hz() as u64;
                self.delay.delay_us(us.min(u32::MAX as u64) as u32);
            }
        }
    }
}
