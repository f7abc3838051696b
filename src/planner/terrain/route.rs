//! Terrain mode's route: the walk back from the goal through the search states, written out as
//! a chain of Dubins paths (turn, straight, and for a goal with a heading a final arc).

use super::fillet::Fillet;
use super::states::{goal_direction, Arrived, NO_PREVIOUS};
use crate::geometry::{DubinsPath, DubinsWord, Pose, Turn};
use crate::planner::search::Arrival;
use crate::planner::{Meter, PlanError, Planner, RouteSummary};

#[cfg(all(test, feature = "std"))]
mod tests;

impl<'n, const V: usize, const E: usize, const P: usize, const R: usize> Planner<'n, V, E, P, R> {
    /// Walks the route of `arrival` back from the goal, calling `visit` with each path (goal
    /// end first): the leg after each node starts at its turn's entry point with the turn arc,
    /// then the straight to the next turn's entry (then, to a goal with a heading, the final
    /// arc). Returns the number of network edges on the route.
    fn walk_terrain_route(
        &self,
        arrival: &Arrival,
        meter: &mut Meter,
        visit: &mut dyn FnMut(&DubinsPath),
    ) -> Result<u32, PlanError> {
        let (state, link) = match *arrival {
            Arrival::Direct(p) => {
                visit(&p);
                return Ok(0);
            }
            Arrival::FromState { state, link } => (state, link),
            Arrival::AtVertex => return Err(PlanError::Internal),
        };
        let r = self.network.turn_radius();
        let link = *self.goal_links.get(link).ok_or(PlanError::Internal)?;
        // The leg leaving the state's node: turn, straight of `straight`, and a last arc.
        let leg = |at: &Arrived, fillet: &Fillet, straight: f32, last: Option<(Turn, f32)>| {
            let first = fillet.turn;
            let (third, third_len) = last.unwrap_or((first, 0.0));
            let word = match (first, third) {
                (Turn::Left, Turn::Left) => DubinsWord::Lsl,
                (Turn::Right, Turn::Right) => DubinsWord::Rsr,
                (Turn::Left, Turn::Right) => DubinsWord::Lsr,
                (Turn::Right, Turn::Left) => DubinsWord::Rsl,
            };
            DubinsPath {
                start: Pose {
                    position: at.position - at.direction * fillet.cut,
                    heading: at.direction.angle(),
                },
                radius: r,
                word,
                lengths: [r * fillet.angle, straight.max(0.0), third_len],
            }
        };

        let mut reads = 0u64;
        let mut at = self.arrived(state, &mut reads)?;
        let goal_out = goal_direction(&at, &link.path);
        let fillet = Fillet::new(at.direction, goal_out, r);
        let last = (link.path.lengths[2] > 0.0)
            .then(|| (link.path.word.letters().2, link.path.lengths[2]));
        visit(&leg(&at, &fillet, link.path.lengths[1] - fillet.cut, last));
        let mut next_cut = fillet.cut;
        let layout = self.terrain_layout();
        // States form a tree over at most V states.
        let edges = self.walk_states(state, V as u32, meter, |s| {
            if let Some(k) = layout.link_of(s) {
                // A start link: its straight ends where the first turn begins.
                let start = self
                    .start_links
                    .get(k as usize)
                    .ok_or(PlanError::Internal)?;
                let mut path = start.path;
                path.lengths[1] = (path.lengths[1] - next_cut).max(0.0);
                visit(&path);
                return Ok(None);
            }
            let previous = *self.via.get(s as usize).ok_or(PlanError::Internal)?;
            if previous == NO_PREVIOUS {
                return Err(PlanError::Internal);
            }
            let before = self.arrived(previous, &mut reads)?;
            let fillet = Fillet::new(before.direction, at.direction, r);
            visit(&leg(
                &before,
                &fillet,
                at.length - fillet.cut - next_cut,
                None,
            ));
            next_cut = fillet.cut;
            at = before;
            Ok(Some(previous))
        })?;
        meter.work.vertex_scans += reads;
        Ok(edges)
    }

    /// Replaces the route with the one `arrival` describes, if it fits in `R` paths and `R`
    /// primitives; otherwise leaves it untouched.
    #[inline(never)] // once per query; inlined, its frame would add to the step's (slice.rs)
    pub(in crate::planner) fn write_terrain_route(
        &mut self,
        arrival: Arrival,
        meter: &mut Meter,
    ) -> Result<RouteSummary, PlanError> {
        self.write_path_route(meter, true, |me, meter, visit| {
            me.walk_terrain_route(&arrival, meter, visit)
        })
    }
}
