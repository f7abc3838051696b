//! Terrain mode's connections: the start and goal links to the nearest nodes and the direct
//! start–goal path, each checked against the elevation grid and the pop-ups.

use super::fillet::on_node;
use crate::geometry::{DubinsPath, DubinsWord, Pose, Turn, Vec2};
use crate::planner::{Goal, Link, Meter, PlanError, Planner};
use core::f32::consts::PI;

#[cfg(all(test, feature = "std"))]
mod tests;

impl<'n, const V: usize, const E: usize, const P: usize, const R: usize> Planner<'n, V, E, P, R> {
    /// Whether every primitive of `path` is over free terrain and clear of the pop-ups.
    fn terrain_path_is_clear(&self, path: &DubinsPath, meter: &mut Meter) -> bool {
        self.path_is_clear(path, meter)
    }

    /// Start links: a left and a right turn-then-straight to each of the nearest nodes, until
    /// [`PlannerConfig::start_candidates`](crate::planner::PlannerConfig) links are found.
    pub(super) fn connect_terrain_start(
        &mut self,
        start: &Pose,
        meter: &mut Meter,
    ) -> Result<(), PlanError> {
        self.start_links.clear();
        let candidates = self.nearest_vertices(start.position, meter)?;
        let wanted = self.config().start_links();
        let r = self.network.turn_radius();
        for &(_, v) in &candidates {
            let target = self.network.vertex(v).ok_or(PlanError::Internal)?.position;
            if on_node(start.position, target) && self.start_links.len() < wanted {
                // On the node: leave it along the start heading, without a loop.
                let path = DubinsPath {
                    start: *start,
                    radius: r,
                    word: DubinsWord::Lsl,
                    lengths: [0.0; 3],
                };
                let _ = self.start_links.push(Link {
                    vertex: v,
                    path,
                    cost: 0.0,
                    pending: false,
                });
                continue;
            }
            for turn in [Turn::Left, Turn::Right] {
                if self.start_links.len() >= wanted {
                    return Ok(());
                }
                meter.work.dubins_solves += 1;
                let Some(path) = DubinsPath::turn_then_straight(start, r, target, turn) else {
                    continue;
                };
                if self.terrain_path_is_clear(&path, meter) {
                    let _ = self.start_links.push(Link {
                        vertex: v,
                        path,
                        cost: path.length(),
                        pending: false,
                    });
                }
                meter.check()?;
            }
        }
        Ok(())
    }

    /// The paths from node position `from` to the goal: a straight for a free heading; for a
    /// fixed one, a straight and a final left or right arc.
    fn goal_paths(&self, from: Vec2, goal: &Goal) -> [Option<DubinsPath>; 2] {
        let r = self.network.turn_radius();
        match goal.heading {
            None => {
                let d = goal.position - from;
                let straight = DubinsPath {
                    start: Pose {
                        position: from,
                        heading: d.angle(),
                    },
                    radius: r,
                    word: DubinsWord::Lsl,
                    lengths: [0.0, d.norm(), 0.0],
                };
                [Some(straight), None]
            }
            Some(h) => {
                // Flown backwards from the goal: turn, then straight to the node.
                let back = Pose {
                    position: goal.position,
                    heading: h + PI,
                };
                [Turn::Left, Turn::Right].map(|turn| {
                    let rev = DubinsPath::turn_then_straight(&back, r, from, turn)?;
                    let heading = rev.end().heading + PI;
                    // Reversed, a left turn is flown clockwise: the last arc turns the other way.
                    let word = match turn {
                        Turn::Left => DubinsWord::Lsr,
                        Turn::Right => DubinsWord::Rsl,
                    };
                    Some(DubinsPath {
                        start: Pose {
                            position: from,
                            heading,
                        },
                        radius: r,
                        word,
                        lengths: [0.0, rev.lengths[1], rev.lengths[0]],
                    })
                })
            }
        }
    }

    /// Goal links from the nearest nodes, until
    /// [`PlannerConfig::goal_candidates`](crate::planner::PlannerConfig) are found.
    pub(super) fn connect_terrain_goal(
        &mut self,
        goal: &Goal,
        meter: &mut Meter,
    ) -> Result<(), PlanError> {
        self.goal_links.clear();
        let candidates = self.nearest_vertices(goal.position, meter)?;
        let wanted = self.config().goal_links();
        for &(_, v) in &candidates {
            let from = self.network.vertex(v).ok_or(PlanError::Internal)?.position;
            for path in self.goal_paths(from, goal).into_iter().flatten() {
                if self.goal_links.len() >= wanted {
                    return Ok(());
                }
                meter.work.dubins_solves += 1;
                if self.terrain_path_is_clear(&path, meter) {
                    let _ = self.goal_links.push(Link {
                        vertex: v,
                        path,
                        cost: path.length(),
                        pending: false,
                    });
                }
                meter.check()?;
            }
        }
        Ok(())
    }

    /// The shortest clear path straight from the start to the goal, if any: a turn and a
    /// straight for a free goal heading, a Dubins path for a fixed one.
    pub(super) fn direct_terrain_path(
        &self,
        start: &Pose,
        goal: &Goal,
        meter: &mut Meter,
    ) -> Result<Option<DubinsPath>, PlanError> {
        let r = self.network.turn_radius();
        let candidates: [Option<DubinsPath>; 2] = match goal.heading {
            None => [Turn::Left, Turn::Right]
                .map(|t| DubinsPath::turn_then_straight(start, r, goal.position, t)),
            Some(h) => {
                let end = Pose {
                    position: goal.position,
                    heading: h,
                };
                [DubinsPath::shortest(start, &end, r), None]
            }
        };
        let mut best: Option<DubinsPath> = None;
        for path in candidates.into_iter().flatten() {
            meter.work.dubins_solves += 1;
            if best.is_none_or(|b| path.length() < b.length())
                && self.terrain_path_is_clear(&path, meter)
            {
                best = Some(path);
            }
            meter.check()?;
        }
        Ok(best)
    }
}
