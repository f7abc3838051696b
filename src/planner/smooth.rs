//! Route post-processing after Niendorf et al., section V, as bounded onboard functions:
//! shortcuts and heading ("azimuth") smoothing of the junctions between the route's Dubins
//! paths. Both keep the route collision-free (every new path passes the same exact checks as a
//! start or goal connection), never make it longer, and count work against a budget.

use super::{Meter, PlanError, Planner, Work};
use crate::geometry::{wrap_to_pi, DubinsPath, Pose};
use core::f32::consts::PI;

/// What a post-processing pass changed.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct SmoothSummary {
    /// Route length before, metres.
    pub length_before: f32,
    /// Route length after, metres.
    pub length_after: f32,
    /// Junctions removed (shortcut) or re-headed (smoothing).
    pub changes: u32,
    /// Work counted.
    pub work: Work,
}

impl<'n, const V: usize, const E: usize, const P: usize, const R: usize> Planner<'n, V, E, P, R> {
    fn route_length(&self) -> f32 {
        self.paths.iter().map(DubinsPath::length).sum()
    }

    fn solve_clear(&self, from: &Pose, to: &Pose, meter: &mut Meter) -> Option<DubinsPath> {
        meter.work.dubins_solves += 1;
        let path = DubinsPath::shortest(from, to, self.network.turn_radius())?;
        self.path_is_clear(&path, meter).then_some(path)
    }

    /// One greedy forward pass of shortcuts: at each junction `i` between paths `i−1` and `i`,
    /// join the previous junction to the next one directly when that Dubins path is
    /// collision-free and shorter than the two it replaces, and drop the junction.
    ///
    /// Work: at most (paths − 1) Dubins solves and clearance checks (each ≤ 3 primitives against
    /// every obstacle and pop-up, as in [`plan_work_bound`](super::plan_work_bound)). If the
    /// budget runs out, the route keeps the shortcuts made so far (each leaves it valid).
    pub fn shortcut(&mut self, budget: u64) -> Result<SmoothSummary, PlanError> {
        self.cancel_plan();
        let mut meter = Meter::new(budget);
        let length_before = self.route_length();
        let mut changes = 0;
        let mut count = self.route.len();
        let mut i = 1;
        let mut result = Ok(());
        while i < self.paths.len() {
            let (Some(a), Some(b)) = (self.paths.get(i - 1).copied(), self.paths.get(i).copied())
            else {
                break;
            };
            let target = b.end();
            match self.solve_clear(&a.start, &target, &mut meter) {
                Some(joined)
                    if joined.length() < a.length() + b.length()
                        && count + pieces(&joined) <= R + pieces(&a) + pieces(&b) =>
                {
                    if let Some(slot) = self.paths.get_mut(i - 1) {
                        *slot = joined;
                    }
                    // `get(i)` above found path i; the test lets the compiler see it.
                    if i < self.paths.len() {
                        self.paths.remove(i);
                    }
                    count = count + pieces(&joined) - pieces(&a) - pieces(&b);
                    changes += 1;
                }
                _ => i += 1,
            }
            if let Err(e) = meter.check() {
                result = Err(e);
                break;
            }
        }
        self.finish(length_before, changes, meter, result)
    }

    /// Heading smoothing: for each junction between two paths (not the start, not the goal),
    /// try `candidates` headings spread ±90° about its current one, and the heading of the chord
    /// from the previous junction to the next (the paper's azimuth, Niendorf et al. section V),
    /// and keep the one that makes the two adjacent paths shortest while both stay
    /// collision-free.
    ///
    /// Work: at most (paths − 1) · (candidates + 1) · 2 Dubins solves and clearance checks. If
    /// the budget runs out, the route keeps the changes made so far (each leaves it valid).
    pub fn smooth_headings(
        &mut self,
        candidates: u16,
        budget: u64,
    ) -> Result<SmoothSummary, PlanError> {
        self.cancel_plan();
        let mut meter = Meter::new(budget);
        let length_before = self.route_length();
        let mut changes = 0;
        let mut result = Ok(());
        let mut count = self.route.len();
        let n = candidates.max(1) as usize;
        'junctions: for i in 1..self.paths.len() {
            let (Some(a), Some(b)) = (self.paths.get(i - 1).copied(), self.paths.get(i).copied())
            else {
                break;
            };
            let junction = b.start;
            let mut best = (a.length() + b.length(), a, b);
            let chord = b.end().position - a.start.position;
            for k in 0..=n {
                // Checked before every candidate, whichever way the previous one ended.
                if let Err(e) = meter.check() {
                    result = Err(e);
                    break 'junctions;
                }
                // Offsets −90° … +90°, evenly spaced (0, the current heading, is already
                // `best`), then the chord's heading.
                let heading = if k == n {
                    if chord.x == 0.0 && chord.y == 0.0 {
                        continue;
                    }
                    chord.angle()
                } else if n == 1 {
                    junction.heading
                } else {
                    wrap_to_pi(junction.heading - PI / 2.0 + PI * k as f32 / (n - 1) as f32)
                };
                let pose = Pose {
                    position: junction.position,
                    heading,
                };
                let Some(first) = self.solve_clear(&a.start, &pose, &mut meter) else {
                    continue;
                };
                if first.length() >= best.0 {
                    continue;
                }
                let Some(second) = self.solve_clear(&pose, &b.end(), &mut meter) else {
                    continue;
                };
                if first.length() + second.length() < best.0 {
                    best = (first.length() + second.length(), first, second);
                }
            }
            let fits = count + pieces(&best.1) + pieces(&best.2) <= R + pieces(&a) + pieces(&b);
            if best.0 < a.length() + b.length() && fits {
                if let Some(slot) = self.paths.get_mut(i - 1) {
                    *slot = best.1;
                }
                if let Some(slot) = self.paths.get_mut(i) {
                    *slot = best.2;
                }
                count = count + pieces(&best.1) + pieces(&best.2) - pieces(&a) - pieces(&b);
                changes += 1;
            }
        }
        self.finish(length_before, changes, meter, result)
    }

    fn finish(
        &mut self,
        length_before: f32,
        changes: u32,
        meter: Meter,
        result: Result<(), PlanError>,
    ) -> Result<SmoothSummary, PlanError> {
        // The last candidate's work must fit the budget too.
        let result = result.and_then(|()| meter.check());
        self.flatten_route();
        let length_after = self.route_length();
        if let Some(s) = self.summary.get_mut() {
            s.length = length_after;
            s.primitives = self.route.len() as u32;
        }
        result.map(|()| SmoothSummary {
            length_before,
            length_after,
            changes,
            work: meter.work,
        })
    }
}

/// Number of primitives (pieces of non-zero length) of a path.
fn pieces(p: &DubinsPath) -> usize {
    p.primitives().iter().flatten().count()
}
