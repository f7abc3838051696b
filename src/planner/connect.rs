//! Connecting the start and the goal to the network with collision-checked Dubins paths.

use super::state::{LinkEnd, ModeState};
use super::window::{ObstacleWindow, Slot};
use super::{Goal, Link, Meter, PlanError, Planner, QueryField, MAX_CANDIDATES, MAX_GOAL_HEADINGS};
use crate::geometry::predicates::{
    conflicts_with_circle, conflicts_with_polygon, point_in_polygon,
};
use crate::geometry::{
    wrap_to_tau, DubinsEnd, DubinsPath, DubinsWord, Pose, Primitive, Vec2, WordSet,
};
use crate::network::Obstacle;
use core::f32::consts::TAU;
use heapless::Vec;

/// The nearest vertices to a point, nearest first.
pub(super) type Candidates = Vec<(f32, u32), MAX_CANDIDATES>;

impl<'n, const V: usize, const E: usize, const P: usize, const R: usize> Planner<'n, V, E, P, R> {
    /// Rejects a start or goal that lies inside a static obstacle or an active pop-up (in a
    /// three-dimensional roadmap, one whose height its altitude does not reach above). Work:
    /// a box test per obstacle, a containment test per obstacle whose box holds `p` and per
    /// pop-up; at most 2O + P.
    pub(super) fn check_free(
        &self,
        p: Vec2,
        field: QueryField,
        meter: &mut Meter,
    ) -> Result<(), PlanError> {
        let end = match field {
            QueryField::Start => LinkEnd::Start,
            QueryField::Goal => LinkEnd::Goal,
        };
        for i in 0..self.network.obstacle_count() {
            let Some((obstacle, (lo, hi))) = self.network.obstacle(i) else {
                return Err(PlanError::Internal);
            };
            meter.work.collision_tests += 1;
            if p.x < lo.x || p.y < lo.y || p.x > hi.x || p.y > hi.y {
                continue;
            }
            let height = self.network.obstacle_height(i).unwrap_or(f32::INFINITY);
            if self.end_is_above(end, height, 0.0) {
                continue;
            }
            meter.work.collision_tests += 1; // the containment test
            let inside = match obstacle {
                Obstacle::Polygon(poly) => point_in_polygon(p, &poly),
                Obstacle::Circle { centre, radius } => p.distance(centre) <= radius,
            };
            if inside {
                return Err(PlanError::InsideObstacle { field, obstacle: i });
            }
        }
        for (id, popup, height) in self.popups_with_heights() {
            meter.work.collision_tests += 1;
            if popup.contains(p) && !self.end_is_above(end, height, 0.0) {
                return Err(PlanError::InsidePopup { field, popup: id });
            }
        }
        Ok(())
    }

    /// The [`MAX_CANDIDATES`] vertices nearest to `p` within the connect radius, nearest first
    /// (equally near ones in index order). Work: |V| vertex scans (each with, for a vertex
    /// nearer than the farthest kept, a scan of the ≤ 32 kept for the new farthest).
    pub(super) fn nearest_vertices(
        &self,
        p: Vec2,
        meter: &mut Meter,
    ) -> Result<Candidates, PlanError> {
        let radius = self.config().connect_radius_m;
        // The kept vertices as (distance, vertex, squared distance), unordered, and the index
        // of the farthest (the largest distance, then the largest index) once they are
        // MAX_CANDIDATES: a later vertex replaces it only if strictly nearer. A vertex whose
        // squared distance is no smaller than the farthest's is no nearer (the square root
        // rounds monotonically), so it is passed over without its square root.
        let mut kept: Vec<(f32, u32, f32), MAX_CANDIDATES> = Vec::new();
        let mut farthest = 0;
        meter.work.vertex_scans += self.network.vertex_count() as u64;
        for v in 0..self.network.vertex_count() {
            let Some(pose) = self.network.vertex(v) else {
                return Err(PlanError::Internal);
            };
            let square = (pose.position - p).norm_sq();
            let full = kept.is_full();
            if full && kept.get(farthest).is_some_and(|f| square >= f.2) {
                continue;
            }
            let d = libm::sqrtf(square); // `pose.position.distance(p)`
            if !(d <= radius) {
                continue;
            }
            if !full {
                let _ = kept.push((d, v, square));
            } else if let Some(f) = kept.get_mut(farthest).filter(|f| d < f.0) {
                *f = (d, v, square);
            } else {
                continue;
            }
            if kept.is_full() {
                farthest = kept
                    .iter()
                    .enumerate()
                    .max_by(|(_, a), (_, b)| {
                        (a.0, a.1)
                            .partial_cmp(&(b.0, b.1))
                            .unwrap_or(core::cmp::Ordering::Equal)
                    })
                    .map_or(0, |(i, _)| i);
            }
        }
        // Nearest first, equally near ones in index order (insertion sort of ≤ 32).
        let mut best = Candidates::new();
        for &(d, v, _) in &kept {
            let at = best
                .iter()
                .position(|&(bd, bv)| (d, v) < (bd, bv))
                .unwrap_or(best.len());
            let _ = best.insert(at, (d, v));
        }
        meter.check()?;
        Ok(best)
    }

    /// Whether every primitive of `path` keeps the network's clearance from every static
    /// obstacle and active pop-up. Exact predicates, after a bounding-box test per obstacle.
    /// In terrain mode, also that every primitive's band is over free terrain (exact cell
    /// traversal), so shortcuts and smoothing keep terrain routes clear too. Not inlined: its
    /// many callers share one copy.
    #[inline(never)]
    pub(super) fn path_is_clear(&self, path: &DubinsPath, meter: &mut Meter) -> bool {
        let count = self.network.obstacle_count() as usize;
        self.path_clear_of(path, count, |i| self.network.obstacle(i as u32), meter)
    }

    /// [`Planner::path_is_clear`], the same answer, checking only the obstacles `window` keeps
    /// when they are all that the path can come near ([`ObstacleWindow::covering`]).
    fn path_is_clear_near(
        &self,
        path: &DubinsPath,
        window: &ObstacleWindow<'n>,
        meter: &mut Meter,
    ) -> bool {
        match window.covering(path, self.network.clearance()) {
            Some(near) => self.path_clear_of(
                path,
                near.len(),
                |i| near.get(i).and_then(Slot::obstacle),
                meter,
            ),
            None => self.path_is_clear(path, meter),
        }
    }

    /// Whether a link's `path` is clear: in a three-dimensional roadmap (`altitudes` given,
    /// in the direction of flight) flyable and clear in 3-D ([`Planner::path_is_clear_climbing`],
    /// against every obstacle), otherwise clear of the obstacles `window` keeps where it covers
    /// the path.
    fn link_is_clear(
        &self,
        path: &DubinsPath,
        altitudes: Option<(f32, f32)>,
        window: &ObstacleWindow<'n>,
        meter: &mut Meter,
    ) -> bool {
        match altitudes {
            Some(ends) => self.path_is_clear_climbing(path, ends, meter),
            None => self.path_is_clear_near(path, window, meter),
        }
    }

    /// [`Planner::path_is_clear`] against the `count` obstacles `obstacle` gives (with their
    /// bounding boxes; `None`: unreadable, so not clear).
    fn path_clear_of(
        &self,
        path: &DubinsPath,
        count: usize,
        obstacle: impl Fn(usize) -> Option<(Obstacle<'n>, (Vec2, Vec2))>,
        meter: &mut Meter,
    ) -> bool {
        let over_terrain = match self.state {
            ModeState::Roadmap(_) | ModeState::Landmark(_) | ModeState::Voronoi(_) => true,
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
            let bbox = prim.bounding_box();
            for i in 0..count {
                let Some((obstacle, obox)) = obstacle(i) else {
                    return false;
                };
                meter.work.collision_tests += 1;
                if conflicts_within(&prim, bbox, &obstacle, obox, clearance, meter) {
                    return false;
                }
            }
            if !self.primitive_clear_of_popups(&prim, meter) {
                return false;
            }
        }
        true
    }

    /// Whether `prim` keeps the clearance from every active pop-up (exact predicates).
    pub(super) fn primitive_clear_of_popups(&self, prim: &Primitive, meter: &mut Meter) -> bool {
        let clearance = self.network.clearance();
        for (_, popup) in self.popups() {
            let (conflict, tests) = popup.conflicts(prim, clearance);
            meter.work.collision_tests += tests as u64;
            if conflict {
                return false;
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

    /// Begins connecting the start: clears the start links and returns the
    /// [`MAX_CANDIDATES`] vertices nearest the start, which
    /// [`Planner::connect_start_candidate`] then tries in order until
    /// [`PlannerConfig::start_candidates`](super::PlannerConfig) succeed.
    pub(super) fn connect_start_begin(
        &mut self,
        start: &Pose,
        meter: &mut Meter,
    ) -> Result<Candidates, PlanError> {
        self.start_links.clear();
        self.nearest_vertices(start.position, meter)
    }

    /// Whether the start links are complete: as many as
    /// [`PlannerConfig::start_candidates`](super::PlannerConfig) asks for.
    pub(super) fn start_links_full(&self) -> bool {
        self.start_links.len() >= self.config().start_links()
    }

    /// Tries start candidate `v`: adds a start link if the shortest Dubins path from the start
    /// reaches it collision-free (one Dubins solve and one path check), checked against the
    /// obstacles around the start (the query's start window).
    pub(super) fn connect_start_candidate(
        &mut self,
        start: &Pose,
        v: u32,
        meter: &mut Meter,
    ) -> Result<(), PlanError> {
        let Some(target) = self.network.vertex(v) else {
            return Err(PlanError::Internal);
        };
        meter.work.dubins_solves += 1;
        let path = DubinsEnd::new(start)
            .zip(DubinsEnd::new(&target))
            .and_then(|(from, to)| {
                DubinsPath::shortest_between(&from, &to, self.network.turn_radius(), WordSet::ALL)
            });
        let Some(path) = path else {
            return Ok(());
        };
        let altitudes = self.link_altitudes(LinkEnd::Start, v);
        if self.link_is_clear(&path, altitudes, self.start_window(), meter) {
            let _ = self.start_links.push(Link {
                vertex: v,
                path,
                cost: path.length(),
                pending: false,
            });
        }
        meter.check()
    }

    /// Begins connecting the goal: clears the goal links and returns the [`MAX_CANDIDATES`]
    /// vertices nearest the goal; the obstacles around the goal ([`ObstacleWindow`]) are read
    /// next, once for all of them. [`Planner::connect_goal_candidate`] then tries the
    /// candidates in order until [`PlannerConfig::goal_candidates`](super::PlannerConfig) reach
    /// the goal.
    pub(super) fn connect_goal_begin(
        &mut self,
        goal: &Goal,
        meter: &mut Meter,
    ) -> Result<Candidates, PlanError> {
        self.goal_links.clear();
        self.nearest_vertices(goal.position, meter)
    }

    /// Whether the goal links are complete: as many as
    /// [`PlannerConfig::goal_candidates`](super::PlannerConfig) asks for.
    pub(super) fn goal_links_full(&self) -> bool {
        self.goal_links.len() >= self.config().goal_links()
    }

    /// Tries goal candidate `v`: adds a goal link if it reaches the goal by a collision-free
    /// Dubins path, checked against the obstacles around the goal (the query's goal window,
    /// read before the first candidate).
    ///
    /// With one goal heading a link is that heading's shortest path. With several, the
    /// vertex's shortest clear path over all of them is what the search needs, but only when it
    /// pops the vertex and the link could still improve the route; so a link is made *pending*
    /// as soon as one path is clear — the one to the heading nearest the bearing from the
    /// vertex to the goal — with [`DubinsPath::length_lower_bound`] as its cost, and the search
    /// finds its shortest clear path if it needs it ([`Planner::resolve_goal_link`]). A vertex
    /// whose probe is blocked has its shortest clear path, if any, found here.
    pub(super) fn connect_goal_candidate(
        &mut self,
        goal: &Goal,
        v: u32,
        meter: &mut Meter,
    ) -> Result<(), PlanError> {
        let Some(from) = self.network.vertex(v) else {
            return Err(PlanError::Internal);
        };
        let window = self.goal_window().ok_or(PlanError::Internal)?;
        let altitudes = self.link_altitudes(LinkEnd::Goal, v);
        if self.config().headings(goal) > 1 {
            if let Some(path) = self.probe_goal_path(&from, goal, altitudes, window, meter) {
                let radius = self.network.turn_radius();
                let bound = DubinsPath::length_lower_bound(from.position, goal.position, radius);
                let _ = self.goal_links.push(Link {
                    vertex: v,
                    path,
                    cost: bound,
                    pending: true,
                });
                return meter.check();
            }
        }
        if let Some(path) = self.best_clear_path_to_goal(&from, goal, altitudes, window, meter)? {
            let _ = self.goal_links.push(Link {
                vertex: v,
                path,
                cost: path.length(),
                pending: false,
            });
        }
        Ok(())
    }

    /// The shortest path from `from` to the goal heading nearest the bearing from `from` to the
    /// goal, if it is collision-free (one Dubins solve and one path check).
    fn probe_goal_path(
        &self,
        from: &Pose,
        goal: &Goal,
        altitudes: Option<(f32, f32)>,
        window: &ObstacleWindow<'n>,
        meter: &mut Meter,
    ) -> Option<DubinsPath> {
        let headings = self.config().headings(goal) as f32;
        let bearing = wrap_to_tau((goal.position - from.position).angle());
        let k = (bearing / (TAU / headings) + 0.5) as u16 % self.config().headings(goal);
        meter.work.dubins_solves += 1;
        let (from, to) = (
            DubinsEnd::new(from)?,
            DubinsEnd::new(&self.goal_pose(goal, k))?,
        );
        let path =
            DubinsPath::shortest_between(&from, &to, self.network.turn_radius(), WordSet::ALL)?;
        self.link_is_clear(&path, altitudes, window, meter)
            .then_some(path)
    }

    /// Makes goal link `k` exact if it is pending: finds the shortest clear path from its vertex
    /// to the goal ([`Planner::best_clear_path_to_goal`], against the obstacles around the
    /// goal: the query's goal window, read on the first call). Its probe was clear, so one
    /// exists. Not inlined: called at most once per goal link, it would only crowd the search's
    /// loop.
    #[inline(never)]
    pub(super) fn resolve_goal_link(
        &mut self,
        k: usize,
        goal: &Goal,
        meter: &mut Meter,
    ) -> Result<Link, PlanError> {
        let link = *self.goal_links.get(k).ok_or(PlanError::Internal)?;
        if !link.pending {
            return Ok(link);
        }
        let from = self
            .network
            .vertex(link.vertex)
            .ok_or(PlanError::Internal)?;
        self.read_goal_window_once(goal.position, meter);
        let window = self.goal_window().ok_or(PlanError::Internal)?;
        let altitudes = self.link_altitudes(LinkEnd::Goal, link.vertex);
        let path = self
            .best_clear_path_to_goal(&from, goal, altitudes, window, meter)?
            .ok_or(PlanError::Internal)?;
        let exact = Link {
            path,
            cost: path.length(),
            pending: false,
            ..link
        };
        *self.goal_links.get_mut(k).ok_or(PlanError::Internal)? = exact;
        Ok(exact)
    }

    /// The shortest collision-free Dubins path from `from` to the goal over the goal headings
    /// (among equally long ones, the first heading's), checking against the obstacles that
    /// `window` keeps where it covers the path.
    ///
    /// Solves every heading's shortest path first (one Dubins solve each), then checks them in
    /// order of length (ties: heading order) and returns the first clear one: the shortest
    /// clear path, found with as few collision checks as there are shorter blocked paths, plus
    /// one. Picking the next path (a scan of the ≤ [`MAX_GOAL_HEADINGS`] stored lengths) and
    /// solving its word again counts one Dubins solve.
    pub(super) fn best_clear_path_to_goal(
        &self,
        from: &Pose,
        goal: &Goal,
        altitudes: Option<(f32, f32)>,
        window: &ObstacleWindow<'n>,
        meter: &mut Meter,
    ) -> Result<Option<DubinsPath>, PlanError> {
        let headings = self.config().headings(goal) as usize;
        let radius = self.network.turn_radius();
        let Some(from) = DubinsEnd::new(from) else {
            meter.work.dubins_solves += headings as u64; // every heading tried, none solved
            return Ok(None);
        };
        let goal_end = |k: usize| DubinsEnd::new(&self.goal_pose(goal, k as u16));
        // Each heading's shortest length and word (+∞: none, or already checked).
        let mut lengths = [f32::INFINITY; MAX_GOAL_HEADINGS as usize];
        let mut words = [DubinsWord::Lsl; MAX_GOAL_HEADINGS as usize];
        let mut left = 0;
        for (k, (length, word)) in lengths
            .iter_mut()
            .zip(&mut words)
            .take(headings)
            .enumerate()
        {
            meter.work.dubins_solves += 1;
            let path = goal_end(k)
                .and_then(|to| DubinsPath::shortest_between(&from, &to, radius, WordSet::ALL));
            if let Some(path) = path {
                (*length, *word) = (path.length(), path.word);
                left += 1;
            }
        }
        meter.check()?;
        while left > 0 {
            meter.work.dubins_solves += 1;
            let mut pick: Option<(usize, f32)> = None;
            for (k, &length) in lengths.iter().enumerate().take(headings) {
                if length < pick.map_or(f32::INFINITY, |(_, l)| l) {
                    pick = Some((k, length));
                }
            }
            let (Some((k, _)), Some(&word)) = (pick, pick.and_then(|(k, _)| words.get(k))) else {
                return Err(PlanError::Internal); // `left` counts the finite lengths
            };
            lengths[k] = f32::INFINITY;
            left -= 1;
            let path = goal_end(k)
                .and_then(|to| DubinsPath::word_between(&from, &to, radius, word))
                .ok_or(PlanError::Internal)?; // solved above, with the same numbers
            if self.link_is_clear(&path, altitudes, window, meter) {
                return Ok(Some(path));
            }
            meter.check()?;
        }
        Ok(None)
    }
}

/// [`conflicts`] after a test of the bounding boxes, `prim`'s (`bbox`) widened by the
/// clearance against the obstacle's (`obox`): boxes that far apart cannot conflict, and cost
/// no predicate test.
#[inline(always)]
pub(super) fn conflicts_within(
    prim: &Primitive,
    (lo, hi): (Vec2, Vec2),
    obstacle: &Obstacle<'_>,
    (olo, ohi): (Vec2, Vec2),
    clearance: f32,
    meter: &mut Meter,
) -> bool {
    let apart = lo.x - clearance > ohi.x
        || hi.x + clearance < olo.x
        || lo.y - clearance > ohi.y
        || hi.y + clearance < olo.y;
    !apart && conflicts(prim, obstacle, clearance, meter)
}

/// Whether `prim` comes within `clearance` of `obstacle` (exact predicates), counting one
/// collision test per polygon edge and one for its containment test, or one for a circle.
#[inline(always)]
pub(super) fn conflicts(
    prim: &Primitive,
    obstacle: &Obstacle<'_>,
    clearance: f32,
    meter: &mut Meter,
) -> bool {
    match obstacle {
        Obstacle::Polygon(poly) => {
            meter.work.collision_tests += poly.count_elements();
            conflicts_with_polygon(prim, poly, clearance)
        }
        Obstacle::Circle { centre, radius } => {
            meter.work.collision_tests += 1;
            conflicts_with_circle(prim, *centre, *radius, clearance)
        }
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
