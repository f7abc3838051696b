//! Landmark mode's online ends (Babel 2014's Connect-Endpoints at query time): a query whose
//! start is neither the network's stored start nor an overflight is joined to the
//! overflights (and the stored goal) that one direct quintic Hermite piece reaches within the
//! range the aircraft has left; a goal that is not the stored goal is joined from the
//! overflights (and the stored start) whose range reaches it.
//!
//! A piece between a pose and vertex `v` (both line elements at the network's nominal speed,
//! so that it meets `v`'s chains in a line element, as every chain piece does) is a link iff
//! * its length is at most the range: for a start link the range left
//!   ([`Planner::set_start_range`]; the network's start range until one is set), for a goal
//!   link the range `v` allows in the weather and rosettes in force
//!   ([`Planner::overflight_range`]; from the stored start, the start range): Babel's
//!   navigability of the edge;
//! * it is flyable within the network's vehicle limits ([`HermiteSegment::check_flyable`]);
//! * it keeps the network's clearance from every stored obstacle and every active pop-up
//!   (conservative chord tests, [`POPUP_CHORDS_PER_PIECE`] chords, as pop-ups test chains).
//!
//! A goal without a heading is reached along the chord from `v`. Only direct pieces are
//! tried: the ground tool's endpoint chains, which may wind round a zone through sampled line
//! elements, are not searched onboard, so an end whose every overflight lies behind a zone is
//! refused ([`PlanError::StartUnconnected`], [`PlanError::GoalUnconnected`]), and a query with
//! both ends online overflies at least one landmark. Of the links found on each side, the
//! [`MAX_LINKS`] with the smallest lower bound of a route through them (the piece plus the
//! chord to the other end) are kept, and the search is exact over those.

use super::search::Arrival;
use super::state::{LinkSide, ModeState, OnlineLink};
use super::{Meter, PlanError, Planner, Query, MAX_LINKS, POPUP_CHORDS_PER_PIECE};
use crate::geometry::hermite::{HermiteSegment, LineElement};
use crate::geometry::predicates::PolygonView;
use crate::geometry::{Pose, Vec2};
use crate::network::format::LandmarkRecord;
use crate::network::Obstacle;
use heapless::Vec;

impl<'n, const V: usize, const E: usize, const P: usize, const R: usize> Planner<'n, V, E, P, R> {
    /// Landmark mode: sets the range the aircraft has left before it must overfly a landmark,
    /// metres: its last overflight's `d_max·q` ([`Planner::overflight_range`]) less what it has
    /// flown since. It bounds the piece that joins a start that is not a network vertex to the
    /// network (module documentation); until set, the network's start range does. The range
    /// stays in force for every later query, whatever its start, until it is set again or a
    /// network is loaded (which restores the network's start range).
    pub fn set_start_range(&mut self, range_m: f32) -> Result<(), PlanError> {
        self.cancel_plan();
        if !range_m.is_finite() || range_m < 0.0 {
            return Err(PlanError::InvalidRange);
        }
        match &mut self.state {
            ModeState::Landmark(l) => {
                l.start_range_m = Some(range_m);
                Ok(())
            }
            _ => Err(PlanError::NotLandmarkNetwork),
        }
    }

    /// Landmark mode: the range in force for a start that is not a network vertex, metres
    /// ([`Planner::set_start_range`], or the network's start range).
    pub fn start_range(&self) -> Option<f32> {
        match (&self.state, self.network.landmark()) {
            (ModeState::Landmark(state), Some(l)) => {
                Some(state.start_range_m.unwrap_or(l.start_range_m))
            }
            _ => None,
        }
    }

    /// Landmark mode: the range overflight vertex `vertex` (landmark `vertex / D` crossed in
    /// direction `vertex % D`) allows in the weather and rosettes in force, `d_max·q`, metres.
    pub fn overflight_range(&self, vertex: u32) -> Option<f32> {
        let l = self.network.landmark()?;
        let landmark = vertex.checked_div(l.directions)?;
        let direction = vertex.checked_rem(l.directions)?;
        let (_, d_max) = self.network.landmark_site_of(l, landmark)?;
        Some(d_max * self.quality(landmark, direction)?)
    }

    /// Landmark mode: the last route's first piece when it started from a pose that is not a
    /// network vertex: from that pose to the first edge's overflight (or to the goal).
    /// [`Planner::route_edges`] follow it.
    pub fn start_piece(&self) -> Option<HermiteSegment> {
        match &self.state {
            ModeState::Landmark(l) => l.start_piece,
            _ => None,
        }
    }

    /// Landmark mode: the last route's last piece when it ended at a goal that is not the
    /// network's: from its last overflight (or the stored start) to that goal.
    pub fn goal_piece(&self) -> Option<HermiteSegment> {
        match &self.state {
            ModeState::Landmark(l) => l.goal_piece,
            _ => None,
        }
    }

    /// The online links of the query in progress, on one side.
    pub(super) fn online_links(&self, side: LinkSide) -> &[OnlineLink] {
        match (&self.state, side) {
            (ModeState::Landmark(l), LinkSide::Start) => &l.start_links,
            (ModeState::Landmark(l), LinkSide::Goal) => &l.goal_links,
            _ => &[],
        }
    }

    /// Joins one end of `query` to the network (module documentation): on the start side to
    /// the overflights and `extra` (the stored goal, when the search ends there), on the goal
    /// side from the overflights and `extra` (the stored start, when the search starts
    /// there). Counts per vertex one vertex scan; per vertex within range one piece (a
    /// `dubins_solves` unit: its construction and flyability check, bounded computations
    /// measured in `docs/BENCHMARKS.md`), a box test per obstacle and pop-up,
    /// [`POPUP_CHORDS_PER_PIECE`] predicates per polygon edge, and containment or circle where
    /// a box meets the piece's reach, and one relaxation.
    pub(super) fn connect_online(
        &mut self,
        l: &LandmarkRecord,
        query: &Query,
        side: LinkSide,
        extra: Option<u32>,
        meter: &mut Meter,
    ) -> Result<(), PlanError> {
        let mut kept: Vec<(f32, OnlineLink), MAX_LINKS> = Vec::new();
        let overflights = l.landmark_count.saturating_mul(l.directions);
        for v in (0..overflights).chain(extra) {
            meter.work.vertex_scans += 1;
            let Some((from, to, range)) = self.online_ends(l, query, side, v) else {
                continue;
            };
            // A curve is at least as long as its chord.
            if !(from.position.distance(to.position) <= range) {
                continue;
            }
            if let Some(piece) = self.online_piece(l, &from, &to, range, meter) {
                meter.work.relaxations += 1;
                // A lower bound of a route through the link: the piece, then the chord to
                // the query's other end.
                let rest = match side {
                    LinkSide::Start => to.position.distance(query.goal.position),
                    LinkSide::Goal => query.start.position.distance(from.position),
                };
                keep_cheapest(&mut kept, piece.length() + rest, link(v, &piece));
            }
            meter.check()?;
        }
        self.store_links(side, &kept)
    }

    /// The poses the piece of a `side` link with vertex `v` joins, and the range it may use:
    /// from the query's start to `v` within the range left, or from `v` to the query's goal
    /// within `v`'s range (the start range from the stored start).
    fn online_ends(
        &self,
        l: &LandmarkRecord,
        query: &Query,
        side: LinkSide,
        v: u32,
    ) -> Option<(Pose, Pose, f32)> {
        let at = self.network.vertex(v)?;
        match side {
            LinkSide::Start => Some((query.start, at, self.start_range()?)),
            LinkSide::Goal => {
                let range = match v == l.start_vertex {
                    true => l.start_range_m,
                    false => self.overflight_range(v)?,
                };
                Some((at, goal_pose(query, &at), range))
            }
        }
    }

    /// Replaces one side's online links by `kept`; an empty side leaves its end unconnected.
    fn store_links(&mut self, side: LinkSide, kept: &[(f32, OnlineLink)]) -> Result<(), PlanError> {
        let ModeState::Landmark(state) = &mut self.state else {
            return Err(PlanError::NotLandmarkNetwork);
        };
        let (links, unconnected) = match side {
            LinkSide::Start => (&mut state.start_links, PlanError::StartUnconnected),
            LinkSide::Goal => (&mut state.goal_links, PlanError::GoalUnconnected),
        };
        links.clear();
        for (_, link) in kept {
            let _ = links.push(*link);
        }
        match links.is_empty() {
            true => Err(unconnected),
            false => Ok(()),
        }
    }

    /// Offers the online goal links that leave vertex `u`, reached at cost `du`, to `best`.
    pub(super) fn offer_online_goal_links(
        &self,
        u: u32,
        du: f32,
        best: &mut Option<(f32, Arrival)>,
        meter: &mut Meter,
    ) {
        let links = self.online_links(LinkSide::Goal);
        meter.work.relaxations += links.len() as u64;
        for (k, link) in links.iter().enumerate() {
            let total = du + link.length;
            if link.vertex == u && best.is_none_or(|(b, _)| total < b) {
                *best = Some((total, Arrival::FromState { state: u, link: k }));
            }
        }
    }

    /// The piece of online link `k` on `side`, built again from `query` as when it was found
    /// (the same inputs, so the same piece).
    pub(super) fn rebuild_online_piece(
        &self,
        query: &Query,
        side: LinkSide,
        k: usize,
        meter: &mut Meter,
    ) -> Result<HermiteSegment, PlanError> {
        let l = *self.network.landmark().ok_or(PlanError::Internal)?;
        let link = *self.online_links(side).get(k).ok_or(PlanError::Internal)?;
        let (from, to, range) = self
            .online_ends(&l, query, side, link.vertex)
            .ok_or(PlanError::Internal)?;
        self.online_piece(&l, &from, &to, range, meter)
            .ok_or(PlanError::Internal)
    }

    /// The piece from pose `start` to pose `to` if it is a link (module documentation):
    /// within `range`, flyable, and clear.
    fn online_piece(
        &self,
        l: &LandmarkRecord,
        start: &Pose,
        to: &Pose,
        range: f32,
        meter: &mut Meter,
    ) -> Option<HermiteSegment> {
        meter.work.dubins_solves += 1;
        let limits = self.network.fly_limits()?;
        let piece = HermiteSegment::new(
            &LineElement::from_pose(start, l.v_nominal),
            &LineElement::from_pose(to, l.v_nominal),
            l.v_nominal,
        )
        .ok()?;
        if !(piece.length() <= range) || piece.check_flyable(&limits).is_err() {
            return None;
        }
        let reach = self
            .network
            .edge_reach(start.position, to.position, piece.length());
        (!self.piece_conflicts(&piece, reach, meter)).then_some(piece)
    }

    /// Whether `piece`, within the box `reach`, may come within the network's clearance of a
    /// stored obstacle or an active pop-up (conservative; an unreadable obstacle conflicts).
    fn piece_conflicts(
        &self,
        piece: &HermiteSegment,
        reach: (Vec2, Vec2),
        meter: &mut Meter,
    ) -> bool {
        let clearance = self.network.clearance();
        let chords = POPUP_CHORDS_PER_PIECE;
        let w = Vec2::new(clearance, clearance);
        let meets = |(lo, hi): (Vec2, Vec2)| {
            let (lo, hi) = (lo - w, hi + w);
            !(reach.1.x < lo.x || reach.1.y < lo.y || reach.0.x > hi.x || reach.0.y > hi.y)
        };
        for i in 0..self.network.obstacle_count() {
            meter.work.collision_tests += 1;
            let Some((obstacle, bbox)) = self.network.obstacle(i) else {
                return true;
            };
            if !meets(bbox) {
                continue;
            }
            let hit = match obstacle {
                Obstacle::Polygon(polygon) => {
                    meter.work.collision_tests += (chords * (polygon.vertex_count() + 1)) as u64;
                    piece.conflicts_with_polygon(&polygon, clearance, chords)
                }
                Obstacle::Circle { centre, radius } => {
                    meter.work.collision_tests += chords as u64;
                    piece.conflicts_with_circle(centre, radius, clearance, chords)
                }
            };
            if hit {
                return true;
            }
        }
        for (_, popup) in self.popups() {
            meter.work.collision_tests += 1;
            if !meets(popup.bounding_box()) {
                continue;
            }
            let (hit, tests) = popup.conflicts_with_piece(piece, clearance, chords);
            meter.work.collision_tests += tests as u64;
            if hit {
                return true;
            }
        }
        false
    }
}

/// Keeps `link` in `kept` (sorted by key, at most [`MAX_LINKS`]) if its `key` is among the
/// [`MAX_LINKS`] smallest offered; ties keep the earlier.
fn keep_cheapest(kept: &mut Vec<(f32, OnlineLink), MAX_LINKS>, key: f32, link: OnlineLink) {
    if kept.is_full() {
        match kept.last() {
            Some((worst, _)) if *worst > key => {
                kept.pop();
            }
            _ => return,
        }
    }
    let at = kept.iter().take_while(|(k, _)| *k <= key).count();
    if kept.push((key, link)).is_err() {
        return;
    }
    // The new entry is last: rotate it into place.
    if let Some(tail) = kept.get_mut(at..) {
        if !tail.is_empty() {
            tail.rotate_right(1);
        }
    }
}

/// The link to (or from) vertex `v` by `piece`.
fn link(v: u32, piece: &HermiteSegment) -> OnlineLink {
    OnlineLink {
        vertex: v,
        length: piece.length(),
    }
}

/// The pose a goal link from `from` ends at: the query's goal with its heading, or along the
/// chord from `from` when it has none.
fn goal_pose(query: &Query, from: &Pose) -> Pose {
    let p = query.goal.position;
    let heading = query.goal.heading.unwrap_or_else(|| {
        let d = p - from.position;
        libm::atan2f(d.y, d.x)
    });
    Pose::new(p.x, p.y, heading)
}

#[cfg(all(test, feature = "std"))]
mod tests;
