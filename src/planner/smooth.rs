//! Route post-processing after Niendorf et al., section V, as bounded onboard functions:
//! shortcuts and heading ("azimuth") smoothing of the junctions between the route's Dubins
//! paths. Both keep the route collision-free (every new path passes the same exact checks as a
//! start or goal connection), never make it longer, and count work against a budget.

use super::state::ModeState;
use super::{Meter, PlanError, Planner, Work};
use crate::geometry::{wrap_to_pi, DubinsPath, Pose};
use core::f32::consts::PI;
use heapless::Vec;

#[cfg(all(test, feature = "std"))]
mod tests;

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
    /// Post-processing rewrites a route from its chain of Dubins paths: roadmap and terrain
    /// routes only. A landmark route (Hermite pieces) or a Voronoi route (a spline smoothed
    /// within the curvature limit) is refused, and stays as it is.
    fn ensure_dubins_route(&self) -> Result<(), PlanError> {
        match self.state {
            ModeState::Roadmap(_) | ModeState::Terrain(_) => Ok(()),
            ModeState::Landmark(_) | ModeState::Voronoi(_) => Err(PlanError::NotDubinsRoute),
        }
    }

    fn route_length(&self) -> f32 {
        self.paths.iter().map(DubinsPath::length).sum()
    }

    /// The shortest Dubins path from `from` to `to` if it is clear: in a three-dimensional
    /// roadmap flown between `altitudes` (junction indices, [`Planner::leg_altitudes`]).
    fn solve_clear(
        &self,
        from: &Pose,
        to: &Pose,
        altitudes: Option<(f32, f32)>,
        meter: &mut Meter,
    ) -> Option<DubinsPath> {
        meter.work.dubins_solves += 1;
        let path = DubinsPath::shortest(from, to, self.network.turn_radius())?;
        self.leg_is_clear(&path, altitudes, meter).then_some(path)
    }

    /// Whether a new path of the route is clear: flyable and clear in 3-D between `altitudes`
    /// in a three-dimensional roadmap, clear of every obstacle and pop-up otherwise.
    fn leg_is_clear(
        &self,
        path: &DubinsPath,
        altitudes: Option<(f32, f32)>,
        meter: &mut Meter,
    ) -> bool {
        match altitudes {
            Some(ends) => self.path_is_clear_climbing(path, ends, meter),
            None => self.path_is_clear(path, meter),
        }
    }

    /// One greedy forward pass of shortcuts: at each junction `i` between paths `i−1` and `i`,
    /// join the previous junction to the next one directly when that Dubins path is
    /// collision-free and shorter than the two it replaces, and drop the junction.
    ///
    /// Work: at most (paths − 1) Dubins solves and clearance checks (each ≤ 3 primitives against
    /// every obstacle and pop-up, as in [`plan_work_bound`](super::plan_work_bound)). If the
    /// budget runs out, the route keeps the shortcuts made so far (each leaves it valid).
    pub fn shortcut(&mut self, budget: u64) -> Result<SmoothSummary, PlanError> {
        self.ensure_dubins_route()?;
        self.cancel_plan();
        let mut meter = Meter::new(budget);
        let length_before = self.route_length();
        let (changes, result) = self.greedy_shortcuts(&mut meter);
        self.finish(length_before, changes, meter, result)
    }

    /// The shortest chain of shortcuts: of every chain from the start to the goal through a
    /// subset of the route's junctions (each kept junction with its pose), where consecutive
    /// kept junctions are joined by the route's own path between them or, further apart, by a
    /// collision-free shortest Dubins path, the route becomes the shortest. Every chain the
    /// greedy [`shortcut`](Self::shortcut) can make is one of these, so the result is never
    /// longer than the greedy pass's.
    ///
    /// Method: a shortest path over the junctions in route order (a DAG, so one forward pass;
    /// Niendorf et al. §V describe the greedy pass). A pair whose straight distance
    /// ([`DubinsPath::length_lower_bound`]) cannot beat the chain already found is not solved.
    ///
    /// Work: at most n(n−1)/2 pairs examined for a route of n paths, each with at most one
    /// Dubins solve and one clearance check. If the shortest chain needs more than `R`
    /// primitives, the greedy pass runs instead, within its own bound. If the budget runs out
    /// before the chain is known, the route is left as it was.
    pub fn shortcut_best(&mut self, budget: u64) -> Result<SmoothSummary, PlanError> {
        self.ensure_dubins_route()?;
        self.cancel_plan();
        let mut meter = Meter::new(budget);
        let length_before = self.route_length();
        let (changes, result) = match self.shortest_chain(&mut meter) {
            Ok(Some(chain)) => {
                let changes = self.paths.len() - (chain.len() - 1);
                self.write_chain(&chain);
                (changes as u32, Ok(()))
            }
            Ok(None) => self.greedy_shortcuts(&mut meter),
            Err(e) => (0, Err(e)),
        };
        self.finish(length_before, changes, meter, result)
    }

    /// The greedy pass of [`shortcut`](Self::shortcut): the junctions dropped, and the budget's
    /// verdict.
    fn greedy_shortcuts(&mut self, meter: &mut Meter) -> (u32, Result<(), PlanError>) {
        let mut changes = 0;
        let mut count = self.route.len();
        let mut i = 1;
        while i < self.paths.len() {
            let (Some(a), Some(b)) = (self.paths.get(i - 1).copied(), self.paths.get(i).copied())
            else {
                break;
            };
            let target = b.end();
            let altitudes = self.leg_altitudes(i - 1, i + 1);
            match self.solve_clear(&a.start, &target, altitudes, meter) {
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
                    self.forget_junction_altitude(i);
                    count = count + pieces(&joined) - pieces(&a) - pieces(&b);
                    changes += 1;
                }
                _ => i += 1,
            }
            if let Err(e) = meter.check() {
                return (changes, Err(e));
            }
        }
        (changes, Ok(()))
    }

    /// Junction `k` of the route: the start of path `k`, or the goal for `k` = paths.
    fn junction(&self, k: usize) -> Option<Pose> {
        match self.paths.get(k) {
            Some(path) => Some(path.start),
            None => self
                .paths
                .last()
                .filter(|_| k == self.paths.len())
                .map(DubinsPath::end),
        }
    }

    /// The kept junctions (0 first, the goal last) of the shortest chain, or `None` when it
    /// would not fit in `R` primitives.
    fn shortest_chain(&self, meter: &mut Meter) -> Result<Option<Vec<u32, R>>, PlanError> {
        let n = self.paths.len();
        // reach[k − 1]: the shortest chain to junction k found so far: its length, the junction
        // before k, and the primitives of its last link.
        let mut reach: Vec<(f32, u32, u8), R> = Vec::new();
        let radius = self.network.turn_radius();
        for k in 1..=n {
            let (Some(to), Some(own)) = (self.junction(k), self.paths.get(k - 1)) else {
                return Err(PlanError::Internal);
            };
            let before = |j: usize| {
                if j == 0 {
                    0.0
                } else {
                    reach.get(j - 1).map_or(f32::INFINITY, |r| r.0)
                }
            };
            let mut best = (
                before(k - 1) + own.length(),
                (k - 1) as u32,
                pieces(own) as u8,
            );
            for j in 0..k.saturating_sub(1) {
                meter.work.relaxations += 1;
                meter.check()?;
                let Some(from) = self.junction(j) else {
                    return Err(PlanError::Internal);
                };
                let so_far = before(j);
                if so_far + DubinsPath::length_lower_bound(from.position, to.position, radius)
                    >= best.0
                {
                    continue;
                }
                meter.work.dubins_solves += 1;
                let Some(path) = DubinsPath::shortest(&from, &to, radius) else {
                    continue;
                };
                let altitudes = self.leg_altitudes(j, k);
                if so_far + path.length() < best.0 && self.leg_is_clear(&path, altitudes, meter) {
                    best = (so_far + path.length(), j as u32, pieces(&path) as u8);
                }
            }
            meter.check()?;
            reach.push(best).map_err(|_| PlanError::Internal)?;
        }
        // Walk back from the goal.
        let mut chain: Vec<u32, R> = Vec::new();
        let (mut k, mut primitives) = (n, 0usize);
        while k > 0 {
            let Some(&(_, j, p)) = reach.get(k - 1) else {
                return Err(PlanError::Internal);
            };
            chain.push(k as u32).map_err(|_| PlanError::Internal)?;
            primitives += p as usize;
            k = j as usize;
        }
        if primitives > R || chain.push(0).is_err() {
            return Ok(None);
        }
        chain.reverse();
        Ok(Some(chain))
    }

    /// Replaces the route's paths by the links of `chain` (kept junctions, 0 first): the
    /// route's own path between neighbours, the shortest Dubins path otherwise (the same solve
    /// that [`shortest_chain`](Self::shortest_chain) checked).
    fn write_chain(&mut self, chain: &[u32]) {
        let radius = self.network.turn_radius();
        // Link t is written to slot t after reading junctions ≥ t, so nothing is read after
        // it is overwritten; the goal's pose is read first, since the last slot may go.
        let links = chain.len().saturating_sub(1);
        for t in 0..links {
            let (Some(&j), Some(&k)) = (chain.get(t), chain.get(t + 1)) else {
                break;
            };
            let (j, k) = (j as usize, k as usize);
            let link = if k == j + 1 {
                self.paths.get(j).copied()
            } else {
                match (self.junction(j), self.junction(k)) {
                    (Some(from), Some(to)) => DubinsPath::shortest(&from, &to, radius),
                    _ => None,
                }
            };
            match (link, self.paths.get_mut(t)) {
                (Some(link), Some(slot)) => *slot = link,
                _ => return self.clear_route(),
            }
        }
        self.paths.truncate(links);
        self.keep_junction_altitudes(chain);
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
        self.ensure_dubins_route()?;
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
                let (into, out) = (self.leg_altitudes(i - 1, i), self.leg_altitudes(i, i + 1));
                let Some(first) = self.solve_clear(&a.start, &pose, into, &mut meter) else {
                    continue;
                };
                if first.length() >= best.0 {
                    continue;
                }
                let Some(second) = self.solve_clear(&pose, &b.end(), out, &mut meter) else {
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
