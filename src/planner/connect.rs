//! Connecting the start and the goal to the network with collision-checked Dubins paths.

use super::state::ModeState;
use super::{Goal, Link, Meter, PlanError, Planner, QueryField, MAX_CANDIDATES};
use crate::geometry::predicates::{
    conflicts_with_circle, conflicts_with_polygon, point_in_polygon,
};
use crate::geometry::{DubinsPath, Pose, Vec2};
use crate::network::Obstacle;
use core::f32::consts::TAU;
use heapless::Vec;

/// The nearest vertices to a point, nearest first.
type Candidates = Vec<(f32, u32), MAX_CANDIDATES>;

impl<'n, const V: usize, const E: usize, const P: usize, const R: usize> Planner<'n, V, E, P, R> {
    /// Rejects a start or goal that lies inside a static obstacle or an active pop-up.
    pub(super) fn check_free(
        &self,
        p: Vec2,
        field: QueryField,
        meter: &mut Meter,
    ) -> Result<(), PlanError> {
        for i in 0..self.network.obstacle_count() {
            let Some((obstacle, (lo, hi))) = self.network.obstacle(i) else {
                return Err(PlanError::Internal);
            };
            meter.work.collision_tests += 1;
            if p.x < lo.x || p.y < lo.y || p.x > hi.x || p.y > hi.y {
                continue;
            }
            let inside = match obstacle {
                Obstacle::Polygon(poly) => point_in_polygon(p, &poly),
                Obstacle::Circle { centre, radius } => p.distance(centre) <= radius,
            };
            if inside {
                return Err(PlanError::InsideObstacle { field, obstacle: i });
            }
        }
        for (id, popup) in self.popups() {
            meter.work.collision_tests += 1;
            if popup.contains(p) {
                return Err(PlanError::InsidePopup { field, popup: id });
            }
        }
        Ok(())
    }

    /// The [`MAX_CANDIDATES`] vertices nearest to `p` within the connect radius, nearest first.
    /// Work: |V| vertex scans (each with an insertion into the sorted list of ≤ 32).
    pub(super) fn nearest_vertices(
        &self,
        p: Vec2,
        meter: &mut Meter,
    ) -> Result<Candidates, PlanError> {
        let k = MAX_CANDIDATES;
        let mut best = Candidates::new();
        let radius = self.config().connect_radius_m;
        for v in 0..self.network.vertex_count() {
            meter.work.vertex_scans += 1;
            let Some(pose) = self.network.vertex(v) else {
                return Err(PlanError::Internal);
            };
            let d = pose.position.distance(p);
            if !(d <= radius) {
                continue;
            }
            // Insertion into a sorted list of at most k entries.
            let at = best
                .iter()
                .position(|(bd, _)| d < *bd)
                .unwrap_or(best.len());
            if at < k {
                if best.len() == k {
                    best.pop();
                }
                let _ = best.insert(at, (d, v));
            }
        }
        meter.check()?;
        Ok(best)
    }

    /// Whether every primitive of `path` keeps the network's clearance from every static
    /// obstacle and active pop-up. Exact predicates, after a bounding-box test per obstacle.
    /// In terrain mode, also that every primitive's band is over free terrain (exact cell
    /// traversal), so shortcuts and smoothing keep terrain routes clear too.
    pub(super) fn path_is_clear(&self, path: &DubinsPath, meter: &mut Meter) -> bool {
        let over_terrain = match self.state {
            ModeState::Roadmap | ModeState::Landmark(_) | ModeState::Voronoi(_) => true,
            ModeState::Terrain(_) => path
                .primitives()
                .into_iter()
                .flatten()
                .all(|p| self.primitive_over_free_terrain(&p, meter)),
        };
        if !over_terrain {
            return false;
        }
        let clearance = self.network.clearance();
        for prim in path.primitives().into_iter().flatten() {
            let (lo, hi) = prim.bounding_box();
            for i in 0..self.network.obstacle_count() {
                let Some((obstacle, (olo, ohi))) = self.network.obstacle(i) else {
                    return false;
                };
                meter.work.collision_tests += 1;
                let apart = lo.x - clearance > ohi.x
                    || hi.x + clearance < olo.x
                    || lo.y - clearance > ohi.y
                    || hi.y + clearance < olo.y;
                if apart {
                    continue;
                }
                let conflict = match obstacle {
                    Obstacle::Polygon(poly) => {
                        meter.work.collision_tests += poly.count_elements();
                        conflicts_with_polygon(&prim, &poly, clearance)
                    }
                    Obstacle::Circle { centre, radius } => {
                        meter.work.collision_tests += 1;
                        conflicts_with_circle(&prim, centre, radius, clearance)
                    }
                };
                if conflict {
                    return false;
                }
            }
            for (_, popup) in self.popups() {
                let (conflict, tests) = popup.conflicts(&prim, clearance);
                meter.work.collision_tests += tests as u64;
                if conflict {
                    return false;
                }
            }
        }
        true
    }

    /// The goal poses to try: the goal's own heading, or evenly spaced headings.
    pub(super) fn goal_pose(&self, goal: &Goal, k: u16) -> Pose {
        let heading = match goal.heading {
            Some(h) => h,
            None => k as f32 * TAU / self.config().headings(goal) as f32,
        };
        Pose {
            position: goal.position,
            heading,
        }
    }

    /// Fills the start links: collision-free Dubins paths from the start to the nearest vertices
    /// they reach, trying the [`MAX_CANDIDATES`] nearest in order until
    /// [`PlannerConfig::start_candidates`](super::PlannerConfig) succeed.
    pub(super) fn connect_start(
        &mut self,
        start: &Pose,
        meter: &mut Meter,
    ) -> Result<(), PlanError> {
        self.start_links.clear();
        let candidates = self.nearest_vertices(start.position, meter)?;
        let wanted = self.config().start_links();
        for &(_, v) in &candidates {
            if self.start_links.len() >= wanted {
                break;
            }
            let Some(target) = self.network.vertex(v) else {
                return Err(PlanError::Internal);
            };
            meter.work.dubins_solves += 1;
            let Some(path) = DubinsPath::shortest(start, &target, self.network.turn_radius())
            else {
                continue;
            };
            if self.path_is_clear(&path, meter) {
                let _ = self.start_links.push(Link {
                    vertex: v,
                    path,
                    cost: path.length(),
                });
            }
            meter.check()?;
        }
        Ok(())
    }

    /// Fills the goal links: for the vertices nearest the goal, the shortest collision-free
    /// Dubins path to the goal over the goal headings tried; the [`MAX_CANDIDATES`] nearest are
    /// tried in order until [`PlannerConfig::goal_candidates`](super::PlannerConfig) succeed.
    pub(super) fn connect_goal(&mut self, goal: &Goal, meter: &mut Meter) -> Result<(), PlanError> {
        self.goal_links.clear();
        let candidates = self.nearest_vertices(goal.position, meter)?;
        let wanted = self.config().goal_links();
        for &(_, v) in &candidates {
            if self.goal_links.len() >= wanted {
                break;
            }
            let Some(from) = self.network.vertex(v) else {
                return Err(PlanError::Internal);
            };
            if let Some(path) = self.best_clear_path_to_goal(&from, goal, meter)? {
                let _ = self.goal_links.push(Link {
                    vertex: v,
                    path,
                    cost: path.length(),
                });
            }
        }
        Ok(())
    }

    /// The shortest collision-free Dubins path from `from` to the goal over the goal headings.
    pub(super) fn best_clear_path_to_goal(
        &self,
        from: &Pose,
        goal: &Goal,
        meter: &mut Meter,
    ) -> Result<Option<DubinsPath>, PlanError> {
        let mut best: Option<DubinsPath> = None;
        for k in 0..self.config().headings(goal) {
            let target = self.goal_pose(goal, k);
            meter.work.dubins_solves += 1;
            let Some(path) = DubinsPath::shortest(from, &target, self.network.turn_radius()) else {
                continue;
            };
            if best.is_some_and(|b| b.length() <= path.length()) {
                continue;
            }
            if self.path_is_clear(&path, meter) {
                best = Some(path);
            }
            meter.check()?;
        }
        Ok(best)
    }
}

/// Predicate evaluations a polygon costs one primitive: one per edge and one containment test.
trait CountElements {
    fn count_elements(&self) -> u64;
}

impl CountElements for crate::network::PolygonRef<'_> {
    fn count_elements(&self) -> u64 {
        use crate::geometry::predicates::PolygonView;
        self.vertex_count() as u64 + 1
    }
}
