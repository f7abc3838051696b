//! Three-dimensional roadmaps onboard (Niendorf et al. in 3-D; `docs/FORMAT.md`, vertical
//! section): the query's altitudes, links checked with their climb, and the route's altitudes.
//!
//! The network's edges were checked on the ground; what the aircraft builds in flight (the
//! links from the start and to the goal, and post-processing's new paths) is checked here the
//! same way: the altitude change must be a rest-to-rest move within the vertical limits over
//! the path's length ([`VerticalProfile`]), and each obstacle is checked against the part of
//! the path flown below its height plus the clearance ([`VerticalProfile::span_below`], the
//! path cut there by [`Primitive::trimmed`]), with the planar exact predicates; pop-ups added
//! with a height ([`Planner::add_popup_with_height`]) likewise. Obstacles and pop-ups of
//! unbounded height are checked against the whole path.

use super::connect::conflicts_within;
use super::search::Arrival;
use super::state::{LinkEnd, ModeState};
use super::{Meter, PlanError, Planner};
use crate::geometry::vertical::VerticalProfile;
use crate::geometry::DubinsPath;
use crate::network::format::MAX_ALTITUDE_M;

impl<'n, const V: usize, const E: usize, const P: usize, const R: usize> Planner<'n, V, E, P, R> {
    /// Three-dimensional roadmap: sets the start's and the goal's altitudes (metres, in the
    /// network's datum) for the queries that follow. Refused with
    /// [`PlanError::NotThreeDimensional`] on any other network, and with
    /// [`PlanError::InvalidAltitude`] for a value that is not finite or beyond
    /// [`MAX_ALTITUDE_M`] (the setting is kept). Cancels a query in progress.
    pub fn set_query_altitudes(&mut self, start_m: f32, goal_m: f32) -> Result<(), PlanError> {
        self.cancel_plan();
        if !self.network.is_three_dimensional() {
            return Err(PlanError::NotThreeDimensional);
        }
        let ModeState::Roadmap(state) = &mut self.state else {
            return Err(PlanError::NotThreeDimensional);
        };
        let valid = |z: f32| z.is_finite() && libm::fabsf(z) <= MAX_ALTITUDE_M;
        if !(valid(start_m) && valid(goal_m)) {
            return Err(PlanError::InvalidAltitude);
        }
        state.altitudes = Some((start_m, goal_m));
        Ok(())
    }

    /// Three-dimensional roadmap: the start's and goal's altitudes set for the queries;
    /// `None` until set, and for any other network.
    pub fn query_altitudes(&self) -> Option<(f32, f32)> {
        match &self.state {
            ModeState::Roadmap(state) if self.network.is_three_dimensional() => state.altitudes,
            _ => None,
        }
    }

    /// Three-dimensional roadmap: the last route's altitude at the end of each of its paths
    /// ([`Planner::route_paths`]), metres; path `k` flies from the altitude before it (the
    /// start's for the first) to this one, climbing as early and descending as late as the
    /// limits allow ([`VerticalProfile`]). Empty for any other network.
    pub fn route_altitudes(&self) -> &[f32] {
        match &self.state {
            ModeState::Roadmap(state) => &state.route_altitudes,
            _ => &[],
        }
    }

    /// Three-dimensional roadmap: the altitude profile of the last route's path `k`; `None`
    /// past the route or for any other network.
    pub fn route_profile(&self, k: usize) -> Option<VerticalProfile> {
        let limits = self.network.vertical_limits()?;
        let altitudes = self.route_altitudes();
        let from = match k {
            0 => self.query_altitudes()?.0,
            _ => *altitudes.get(k - 1)?,
        };
        let to = *altitudes.get(k)?;
        VerticalProfile::new(from, to, self.paths.get(k)?.length(), &limits)
    }

    /// Three-dimensional roadmap: the altitude, metres, `s` metres into primitive `k` of the
    /// last route ([`Planner::route`]: the paths' lines and arcs in turn), `s` clamped to the
    /// primitive (NaN counts as 0); `None` past the route and on any other network. The
    /// altitude follows the profile of the path the primitive belongs to
    /// ([`Planner::route_profile`]), so an autopilot that flies it keeps the clearance over
    /// the buildings and pop-ups the route passes above. Work: O(route length).
    pub fn route_altitude_at(&self, k: usize, s: f32) -> Option<f32> {
        let mut index = 0;
        for (p, path) in self.paths.iter().enumerate() {
            let mut offset = 0.0;
            for (prim, length) in path.primitives().iter().zip(path.lengths) {
                if prim.is_some() {
                    if index == k {
                        let profile = self.route_profile(p)?;
                        return Some(profile.altitude_at(offset + s.max(0.0).min(length)));
                    }
                    index += 1;
                }
                offset += length;
            }
        }
        None
    }

    /// Refuses a query on a three-dimensional roadmap whose altitudes were not set.
    pub(super) fn check_query_altitudes(&self) -> Result<(), PlanError> {
        match self.network.is_three_dimensional() && self.query_altitudes().is_none() {
            true => Err(PlanError::AltitudesNeeded),
            false => Ok(()),
        }
    }

    /// Three-dimensional roadmap: whether the query's `end` is at or above `height` plus
    /// `margin` (so no point there lies in an obstacle or pop-up of that height, or within
    /// `margin` of it from below); false in a planar network and for an unbounded height.
    pub(super) fn end_is_above(&self, end: LinkEnd, height: f32, margin: f32) -> bool {
        let Some((start, goal)) = self.query_altitudes() else {
            return false;
        };
        let z = match end {
            LinkEnd::Start => start,
            LinkEnd::Goal => goal,
        };
        z >= height + margin
    }

    /// Three-dimensional roadmap: the altitudes a link between the query's `end` and vertex
    /// `v` flies between, in the direction of flight; `None` in a planar network. An
    /// unreadable altitude is NaN, which no profile accepts.
    pub(super) fn link_altitudes(&self, end: LinkEnd, v: u32) -> Option<(f32, f32)> {
        let (start, goal) = self.query_altitudes()?;
        let at_vertex = self.network.vertex_altitude(v).unwrap_or(f32::NAN);
        Some(match end {
            LinkEnd::Start => (start, at_vertex),
            LinkEnd::Goal => (at_vertex, goal),
        })
    }

    /// Whether `path`, flown from altitude `from` to `to`, is flyable (a rest-to-rest move
    /// within the vertical limits over its length) and keeps the clearance from every static
    /// obstacle and active pop-up below its height. Work: as [`Planner::path_is_clear`], one
    /// collision test per obstacle or pop-up element a piece is checked against (a piece flown
    /// wholly above an obstacle costs one test, its bounding box; above a pop-up, one). Not
    /// inlined: its frame would add to the stack of every roadmap query, planar ones too.
    #[inline(never)]
    pub(super) fn path_is_clear_climbing(
        &self,
        path: &DubinsPath,
        (from, to): (f32, f32),
        meter: &mut Meter,
    ) -> bool {
        let Some(profile) = self
            .network
            .vertical_limits()
            .and_then(|limits| VerticalProfile::new(from, to, path.length(), &limits))
        else {
            return false;
        };
        let clearance = self.network.clearance();
        let mut offset = 0.0;
        for (prim, &length) in path.primitives().iter().zip(&path.lengths) {
            let Some(prim) = prim else {
                offset += length;
                continue;
            };
            // The part of this primitive flown below `height` plus the clearance.
            let piece_below = |height: f32| match height {
                f32::INFINITY => Some(*prim),
                _ => profile
                    .span_below(height + clearance)
                    .and_then(|(a, b)| prim.trimmed(a - offset, b - offset)),
            };
            let (lo, hi) = prim.bounding_box();
            for i in 0..self.network.obstacle_count() {
                let (Some((obstacle, obox)), Some(height)) =
                    (self.network.obstacle(i), self.network.obstacle_height(i))
                else {
                    return false;
                };
                meter.work.collision_tests += 1;
                // The whole primitive's box first: a piece of it lies within it, so boxes this
                // far apart clear the piece too, without its span computed.
                let (olo, ohi) = obox;
                if lo.x - clearance > ohi.x
                    || hi.x + clearance < olo.x
                    || lo.y - clearance > ohi.y
                    || hi.y + clearance < olo.y
                {
                    continue;
                }
                let Some(piece) = piece_below(height) else {
                    continue;
                };
                let bbox = piece.bounding_box();
                if conflicts_within(&piece, bbox, &obstacle, obox, clearance, meter) {
                    return false;
                }
            }
            for (_, popup, height) in self.popups_with_heights() {
                let Some(piece) = piece_below(height) else {
                    meter.work.collision_tests += 1;
                    continue;
                };
                let (conflict, tests) = popup.conflicts(&piece, clearance);
                meter.work.collision_tests += tests as u64;
                if conflict {
                    return false;
                }
            }
            offset += length;
        }
        true
    }

    /// Three-dimensional roadmap: the altitude at junction `k` of the route (the start's for
    /// 0, else the end of path `k − 1`); NaN when there is none, which no profile accepts.
    fn junction_altitude(&self, k: usize) -> f32 {
        let found = match k {
            0 => self.query_altitudes().map(|(start, _)| start),
            _ => self.route_altitudes().get(k - 1).copied(),
        };
        found.unwrap_or(f32::NAN)
    }

    /// Three-dimensional roadmap: the altitudes a new path from junction `j` to junction `k`
    /// flies between; `None` in a planar network.
    pub(super) fn leg_altitudes(&self, j: usize, k: usize) -> Option<(f32, f32)> {
        self.network
            .is_three_dimensional()
            .then(|| (self.junction_altitude(j), self.junction_altitude(k)))
    }

    /// Forgets the route's altitudes, with the route.
    pub(super) fn forget_route_altitudes(&mut self) {
        if let ModeState::Roadmap(state) = &mut self.state {
            state.route_altitudes.clear();
        }
    }

    /// After junction `k` was dropped from the route (paths `k − 1` and `k` joined): drops its
    /// altitude, the end of path `k − 1`.
    pub(super) fn forget_junction_altitude(&mut self, k: usize) {
        if let ModeState::Roadmap(state) = &mut self.state {
            if k >= 1 && k <= state.route_altitudes.len() {
                state.route_altitudes.remove(k - 1);
            }
        }
    }

    /// After the route became the chain through junctions `chain` (0 first): keeps the
    /// altitudes of the chain's junctions after the first.
    pub(super) fn keep_junction_altitudes(&mut self, chain: &[u32]) {
        let kept: heapless::Vec<f32, R> = chain
            .iter()
            .skip(1)
            .map(|&k| self.junction_altitude(k as usize))
            .collect();
        if let ModeState::Roadmap(state) = &mut self.state {
            if !state.route_altitudes.is_empty() {
                state.route_altitudes = kept;
            }
        }
    }

    /// Charges the walk back from the goal that finds the route's altitudes
    /// ([`Planner::fill_route_altitudes`]) before the route is written, counting one vertex
    /// scan per step (|V| + 1 at most: a third walk beside the writer's two in
    /// [`plan_work_bound`]), so that the budget is settled before the old route is touched.
    /// Nothing in a planar network. Not inlined, like the filling: their frames stay off the
    /// stack of the route writer and of planar queries.
    ///
    /// [`plan_work_bound`]: super::plan_work_bound
    #[inline(never)]
    pub(super) fn charge_route_altitudes(
        &self,
        arrival: &Arrival,
        meter: &mut Meter,
    ) -> Result<(), PlanError> {
        if self.query_altitudes().is_none() {
            return Ok(());
        }
        if let Arrival::FromState { link, .. } = arrival {
            let vertex = self.goal_links.get(*link).map_or(u32::MAX, |l| l.vertex);
            self.walk_vertices(vertex, meter, |_| Ok(()))?;
        }
        meter.check()
    }

    /// Records the altitude at the end of each of the new route's paths, start to goal: the
    /// exit's end at the start's altitude (an exit is flown level), each network vertex's own,
    /// then the goal's. Replays the walk [`Planner::charge_route_altitudes`] charged, the one
    /// the route was written by ([`Arrival`]), so it cannot fail unless the route is
    /// inconsistent, which clears the altitudes and reports [`PlanError::Internal`]. A planar
    /// network's route has none.
    #[inline(never)]
    pub(super) fn fill_route_altitudes(
        &mut self,
        arrival: &Arrival,
        exit: bool,
    ) -> Result<(), PlanError> {
        let ModeState::Roadmap(state) = &mut self.state else {
            return Ok(());
        };
        let mut altitudes = core::mem::take(&mut state.route_altitudes);
        altitudes.clear();
        let Some((start, goal)) = self.query_altitudes() else {
            return Ok(());
        };
        let mut full = altitudes.push(goal).is_err();
        if let Arrival::FromState { link, .. } = arrival {
            let vertex = self.goal_links.get(*link).map_or(u32::MAX, |l| l.vertex);
            let mut replay = Meter::new(u64::MAX);
            let walked = self.walk_vertices(vertex, &mut replay, |e| {
                let target = self.network.edge(e).map(|edge| edge.target);
                let z = target.and_then(|v| self.network.vertex_altitude(v));
                full |= altitudes.push(z.ok_or(PlanError::Internal)?).is_err();
                Ok(())
            });
            let first = walked.ok().and_then(|(_, start_link)| {
                let v = self.start_links.get(start_link?)?.vertex;
                self.network.vertex_altitude(v)
            });
            full |= first.is_none_or(|z| altitudes.push(z).is_err());
        }
        if exit {
            full |= altitudes.push(start).is_err();
        }
        altitudes.reverse();
        let consistent = !full && altitudes.len() == self.paths.len();
        if !consistent {
            altitudes.clear();
        }
        if let ModeState::Roadmap(state) = &mut self.state {
            state.route_altitudes = altitudes;
        }
        match consistent {
            true => Ok(()),
            false => Err(PlanError::Internal),
        }
    }
}

#[cfg(all(test, feature = "std"))]
mod tests;
