//! Leaving a keep-out region. A roadmap start that lies inside a static obstacle or an active
//! pop-up, or within the network's clearance of one (position drift, a pop-up announced over
//! the aircraft), is not refused: the route begins with the shortest exit of the family below,
//! then plans on from where the exit ends, and [`RouteSummary::exit`](super::RouteSummary)
//! reports the violation.
//!
//! # The exit
//! The candidates are the paths that turn left or right on the turn radius `r` by
//! `φ = kπ/32` (`k = 0, …, 32`; 65 paths), then fly straight until they leave the union of
//! the regions that contain the start, plus [`EXIT_MARGIN_M`]. The straight's length is
//! exact: the line's trace on each region is a union of intervals in closed form (an end
//! disc, a capsule per polygon edge, the polygon's inside between paired crossings;
//! [`crate::geometry::line_cover`]), and the exit is the end of the union's interval that
//! contains the straight's start. A candidate is kept only if it comes within the clearance of
//! no other obstacle or pop-up and ends outside every region. The shortest kept candidate is
//! the exit: shortest among these 65, which is what "shortest flyable exit" means here (a
//! finer turn step could shorten it by at most the arc of one step, `πr/32`). In a
//! three-dimensional roadmap the exit is flown level at the start's altitude, so an obstacle
//! or pop-up the start is above by the clearance is neither a region nor in its way.
//!
//! # Work
//! Each candidate: the trace of every region the start lies in (one interval per polygon edge
//! or disc, one crossing per edge), an insertion sort of at most [`MAX_EXIT_INTERVALS`]
//! intervals, and the clearance check of its two primitives against every obstacle and pop-up;
//! [`exit_work_bound`](super::work::exit_work_bound) sums it.

use super::connect::conflicts;
use super::popup::Popup;
use super::state::LinkEnd;
use super::{Meter, PlanError, Planner, QueryField};
use crate::geometry::line_cover::{capsule_interval, disc_interval, for_each_crossing};
use crate::geometry::predicates::{conflicts_with_circle, conflicts_with_polygon, PolygonView};
use crate::geometry::{insertion_sort_by, DubinsPath, DubinsWord, Pose, Primitive, Segment, Vec2};
use crate::network::Obstacle;
use core::f32::consts::PI;
use heapless::Vec;

#[cfg(all(test, feature = "std"))]
mod tests;

/// A region the start lay in: a static obstacle (its index in the network) or an active
/// pop-up (its id).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Violation {
    /// A static obstacle of the network.
    Obstacle(u32),
    /// An active pop-up.
    Popup(u8),
}

/// How a route that began in a keep-out region leaves it.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Exit {
    /// The first region the start lay in (obstacles before pop-ups, in index order).
    pub violated: Violation,
    /// How many regions the start lay in.
    pub regions: u32,
    /// The exit path's length, metres: the route's first path, flown within the regions up
    /// to [`EXIT_MARGIN_M`] past their edge.
    pub length: f32,
}

/// The most regions a start may lie in at once and still be given an exit.
pub const MAX_EXIT_REGIONS: usize = 4;
/// Turn angles tried each way: `φ = kπ/EXIT_TURN_STEPS`, `k = 0, …, EXIT_TURN_STEPS`.
pub const EXIT_TURN_STEPS: u32 = 32;
/// How far past the regions' edge (the clearance included) the exit ends, metres.
pub const EXIT_MARGIN_M: f32 = 1.0;
/// The most trace intervals a candidate's straight may have; a candidate with more is not
/// considered (a line meets a polygon's capsules in one interval per edge it passes within
/// the clearance of, so this takes a line grazing 24 or more edges of the regions).
pub const MAX_EXIT_INTERVALS: usize = 32;

/// The regions a point lies in.
type Regions = Vec<Violation, MAX_EXIT_REGIONS>;

/// The start lies in more regions than [`MAX_EXIT_REGIONS`], or in none that is readable.
struct TooManyRegions;

impl<'n, const V: usize, const E: usize, const P: usize, const R: usize> Planner<'n, V, E, P, R> {
    /// The regions (obstacles, then pop-ups) that `p` lies in or within the clearance of.
    fn regions_at(&self, p: Vec2, meter: &mut Meter) -> Result<Regions, TooManyRegions> {
        let c = self.network.clearance();
        // The point as a zero-length line, for the shared clearance predicates.
        let point = Primitive::Line(Segment { start: p, end: p });
        let mut found = Regions::new();
        for i in 0..self.network.obstacle_count() {
            let Some((obstacle, (lo, hi))) = self.network.obstacle(i) else {
                return Err(TooManyRegions);
            };
            meter.work.collision_tests += 1;
            if p.x < lo.x - c || p.y < lo.y - c || p.x > hi.x + c || p.y > hi.y + c {
                continue;
            }
            // In a three-dimensional roadmap the start (and its level exit) may fly above it.
            let height = self.network.obstacle_height(i).unwrap_or(f32::INFINITY);
            if self.end_is_above(LinkEnd::Start, height, c) {
                continue;
            }
            let within = match obstacle {
                Obstacle::Polygon(poly) => {
                    meter.work.collision_tests += poly.vertex_count() as u64 + 1;
                    conflicts_with_polygon(&point, &poly, c)
                }
                Obstacle::Circle { centre, radius } => {
                    meter.work.collision_tests += 1;
                    conflicts_with_circle(&point, centre, radius, c)
                }
            };
            if within {
                found
                    .push(Violation::Obstacle(i))
                    .map_err(|_| TooManyRegions)?;
            }
        }
        for (id, popup, height) in self.popups_with_heights() {
            if self.end_is_above(LinkEnd::Start, height, c) {
                meter.work.collision_tests += 1;
                continue;
            }
            let (within, tests) = popup.conflicts(&point, c);
            meter.work.collision_tests += tests as u64;
            if within {
                found
                    .push(Violation::Popup(id))
                    .map_err(|_| TooManyRegions)?;
            }
        }
        Ok(found)
    }

    /// The exit from the regions `start` lies in (`None` when it lies in none), or the error
    /// that refuses the start: [`PlanError::InsideObstacle`] or [`PlanError::InsidePopup`]
    /// naming the first region, when no candidate is kept or the start lies in more than
    /// [`MAX_EXIT_REGIONS`] regions.
    pub(super) fn exit_from(
        &self,
        start: &Pose,
        meter: &mut Meter,
    ) -> Result<Option<(DubinsPath, Exit)>, PlanError> {
        let regions = match self.regions_at(start.position, meter) {
            Ok(r) if r.is_empty() => return Ok(None),
            Ok(r) => r,
            Err(TooManyRegions) => return Err(self.refusal(start.position, meter)),
        };
        let radius = self.network.turn_radius();
        let mut best: Option<DubinsPath> = None;
        for k in 0..=EXIT_TURN_STEPS {
            for word in [DubinsWord::Lsl, DubinsWord::Rsr] {
                if k == 0 && word == DubinsWord::Rsr {
                    continue; // φ = 0 is the same path either way
                }
                let turn = radius * (k as f32 * PI / EXIT_TURN_STEPS as f32);
                let arc = DubinsPath {
                    start: *start,
                    radius,
                    word,
                    lengths: [turn, 0.0, 0.0],
                };
                let end = arc.end();
                let direction = Vec2::from_angle(end.heading);
                let Some(reach) = self.exit_reach(end.position, direction, &regions, meter) else {
                    continue;
                };
                let path = DubinsPath {
                    lengths: [turn, reach.max(0.0) + EXIT_MARGIN_M, 0.0],
                    ..arc
                };
                if best.is_some_and(|b| b.length() <= path.length()) {
                    continue;
                }
                if self.exit_is_clear(&path, &regions, meter) {
                    best = Some(path);
                }
            }
        }
        meter.check()?;
        let (Some(path), Some(&violated)) = (best, regions.first()) else {
            return Err(self.refusal(start.position, meter));
        };
        let exit = Exit {
            violated,
            regions: regions.len() as u32,
            length: path.length(),
        };
        Ok(Some((path, exit)))
    }

    /// The refusal of a start that has no exit: the obstacle or pop-up it lies inside, or
    /// within the clearance of.
    fn refusal(&self, p: Vec2, meter: &mut Meter) -> PlanError {
        let field = QueryField::Start;
        match self.check_free(p, field, meter) {
            Err(e) => e,
            Ok(()) => match self
                .regions_at(p, meter)
                .ok()
                .and_then(|r| r.first().copied())
            {
                Some(Violation::Obstacle(obstacle)) => {
                    PlanError::InsideObstacle { field, obstacle }
                }
                Some(Violation::Popup(popup)) => PlanError::InsidePopup { field, popup },
                None => PlanError::StartUnconnected,
            },
        }
    }

    /// How far the line `o + t·u` runs, from `t = 0`, within the union of `regions` widened by
    /// the clearance: the end of the union's interval that contains 0 (0 when none does).
    /// `None` when the trace has more than [`MAX_EXIT_INTERVALS`] intervals or a region is
    /// unreadable.
    fn exit_reach(&self, o: Vec2, u: Vec2, regions: &Regions, meter: &mut Meter) -> Option<f32> {
        let c = self.network.clearance();
        let mut intervals: Vec<(f32, f32), MAX_EXIT_INTERVALS> = Vec::new();
        for &region in regions {
            match region {
                Violation::Obstacle(i) => match self.network.obstacle(i)?.0 {
                    Obstacle::Polygon(poly) => {
                        meter.work.collision_tests += 2 * poly.vertex_count() as u64;
                        trace_polygon(o, u, &poly, c, &mut intervals)?
                    }
                    Obstacle::Circle { centre, radius } => {
                        meter.work.collision_tests += 1;
                        if let Some(i) = disc_interval(o, u, centre, radius + c) {
                            intervals.push(i).ok()?;
                        }
                    }
                },
                Violation::Popup(id) => match self.popups().find(|(p, _)| *p == id)?.1 {
                    Popup::Polygon(points) => {
                        meter.work.collision_tests += 2 * points.len() as u64;
                        trace_polygon(o, u, points.as_slice(), c, &mut intervals)?
                    }
                    Popup::Circle { centre, radius } => {
                        meter.work.collision_tests += 1;
                        if let Some(i) = disc_interval(o, u, *centre, radius + c) {
                            intervals.push(i).ok()?;
                        }
                    }
                },
            }
        }
        meter.work.collision_tests += intervals.len() as u64 * intervals.len() as u64;
        // Sorted by start, the intervals that overlap the reach so far extend it.
        insertion_sort_by(&mut intervals, |i| i.0);
        let mut reach = 0.0f32;
        for &(from, to) in &intervals {
            if from > reach {
                break;
            }
            reach = reach.max(to);
        }
        reach.is_finite().then_some(reach)
    }

    /// Whether the exit `path` keeps the clearance from every obstacle and pop-up outside
    /// `regions`, and ends outside every region. The exit is flown level at the start's
    /// altitude, so in a three-dimensional roadmap the obstacles and pop-ups it is above by
    /// the clearance are passed over.
    fn exit_is_clear(&self, path: &DubinsPath, regions: &Regions, meter: &mut Meter) -> bool {
        let c = self.network.clearance();
        for prim in path.primitives().into_iter().flatten() {
            let (lo, hi) = prim.bounding_box();
            for i in 0..self.network.obstacle_count() {
                let height = self.network.obstacle_height(i).unwrap_or(f32::INFINITY);
                if regions.contains(&Violation::Obstacle(i))
                    || self.end_is_above(LinkEnd::Start, height, c)
                {
                    continue;
                }
                let Some((obstacle, (olo, ohi))) = self.network.obstacle(i) else {
                    return false;
                };
                meter.work.collision_tests += 1;
                let apart =
                    lo.x - c > ohi.x || hi.x + c < olo.x || lo.y - c > ohi.y || hi.y + c < olo.y;
                if !apart && conflicts(&prim, &obstacle, c, meter) {
                    return false;
                }
            }
            for (id, popup, height) in self.popups_with_heights() {
                if regions.contains(&Violation::Popup(id))
                    || self.end_is_above(LinkEnd::Start, height, c)
                {
                    continue;
                }
                let (conflict, tests) = popup.conflicts(&prim, c);
                meter.work.collision_tests += tests as u64;
                if conflict {
                    return false;
                }
            }
        }
        self.regions_at(path.end().position, meter)
            .is_ok_and(|r| r.is_empty())
    }
}

/// Adds to `intervals` the trace of `polygon` widened by `c` on the line `o + t·u`: one
/// capsule interval per edge, and the inside between consecutive pairs of the sorted
/// crossings. `None` when the intervals overflow or a vertex is unreadable.
fn trace_polygon(
    o: Vec2,
    u: Vec2,
    polygon: &(impl PolygonView + ?Sized),
    c: f32,
    intervals: &mut Vec<(f32, f32), MAX_EXIT_INTERVALS>,
) -> Option<()> {
    for i in 0..polygon.vertex_count() {
        let e = polygon.edge(i)?;
        if let Some(t) = capsule_interval(o, u, e.start, e.end, c) {
            intervals.push(t).ok()?;
        }
    }
    let mut crossings: Vec<f32, MAX_EXIT_INTERVALS> = Vec::new();
    let mut overflow = false;
    let readable = for_each_crossing(o, u, polygon, |t| overflow |= crossings.push(t).is_err());
    if !readable || overflow {
        return None;
    }
    insertion_sort_by(&mut crossings, |&t| t);
    for pair in crossings.chunks_exact(2) {
        if let [from, to] = *pair {
            intervals.push((from, to)).ok()?;
        }
    }
    Some(())
}
