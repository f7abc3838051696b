//! The static obstacles near an endpoint, found once for all of the endpoint's connections.
//!
//! Connecting the start or the goal checks up to hundreds of Dubins paths that all begin or end
//! at one point, each against every obstacle. An [`ObstacleWindow`] keeps the
//! [`WINDOW_OBSTACLES`] obstacles whose bounding boxes lie nearest to that point, found once
//! (their indices; a check reads each kept obstacle's record again), and the distance `reach` of the nearest box it left out. Every point of a path of length `L`
//! starting at `s` lies within `L + |s − centre|` of the centre, so when that plus the clearance
//! stays below `reach` (with a margin far above f32 rounding), no obstacle left out can come
//! within the clearance of the path, and checking the kept ones decides exactly what checking
//! all of them would.

use super::Meter;
use crate::geometry::{DubinsPath, Vec2};
use crate::network::Network;

/// Obstacles an [`ObstacleWindow`] keeps.
pub(super) const WINDOW_OBSTACLES: usize = 32;

/// An obstacle as the window keeps it: the distance of its bounding box from the centre, the
/// obstacle's index in the network, and its bounding box `(min, max)`.
pub(super) type NearObstacle = (f32, u32, (Vec2, Vec2));

/// An unused slot of a window's array.
const UNUSED: NearObstacle = (0.0, 0, (Vec2 { x: 0.0, y: 0.0 }, Vec2 { x: 0.0, y: 0.0 }));

/// The obstacles nearest to a point (see the module documentation), by index. Plain numbers
/// in arrays: a planner keeps windows across the steps of a query, and an idle window is all
/// zero bytes, so that it adds none but zeros to a new planner's `const` image.
#[derive(Clone, Copy)]
pub(super) struct ObstacleWindow {
    centre: Vec2,
    /// The kept obstacles (the first `len`), every one at most as far as any left out, in no
    /// particular order.
    near: [NearObstacle; WINDOW_OBSTACLES],
    len: usize,
    /// Distance of the nearest box left out (+∞ when every obstacle is kept).
    reach: f32,
}

impl ObstacleWindow {
    /// A window that keeps nothing and covers no path (every check reads the network), in
    /// `const` and all-zero: a reach of 0 is below any path's extent.
    pub(super) const EMPTY: Self = Self {
        centre: Vec2 { x: 0.0, y: 0.0 },
        near: [UNUSED; WINDOW_OBSTACLES],
        len: 0,
        reach: 0.0,
    };

    /// A window that keeps nothing and covers no path: every check reads the network.
    pub(super) fn none(centre: Vec2) -> Self {
        Self {
            centre,
            reach: f32::NEG_INFINITY,
            ..Self::EMPTY
        }
    }

    /// The kept obstacles.
    fn kept(&self) -> &[NearObstacle] {
        self.near.get(..self.len).unwrap_or(&[])
    }

    /// The window around `centre`. Work: one collision test per obstacle (the distance of its
    /// bounding box, with, for an obstacle nearer than the farthest kept, a scan of the ≤
    /// [`WINDOW_OBSTACLES`] kept for the new farthest). A record that cannot be read
    /// (validation rules that out) gives [`ObstacleWindow::none`].
    pub(super) fn around(network: &Network<'_>, centre: Vec2, meter: &mut Meter) -> Self {
        let mut window = Self {
            centre,
            reach: f32::INFINITY,
            ..Self::EMPTY
        };
        // Once the window is full, the index of its farthest box: a nearer one replaces it.
        let mut farthest = 0;
        for i in 0..network.obstacle_count() {
            meter.work.collision_tests += 1;
            let Some((_, (lo, hi))) = network.obstacle(i) else {
                return Self::none(centre);
            };
            let dx = (lo.x - centre.x).max(centre.x - hi.x).max(0.0);
            let dy = (lo.y - centre.y).max(centre.y - hi.y).max(0.0);
            let d = libm::sqrtf(dx * dx + dy * dy);
            if !(d >= 0.0) {
                return Self::none(centre); // not finite: validation rules it out
            }
            let entry = (d, i, (lo, hi));
            if let Some(free) = window.near.get_mut(window.len) {
                *free = entry;
                window.len += 1;
            } else if let Some(f) = window.near.get_mut(farthest).filter(|f| d < f.0) {
                window.reach = window.reach.min(f.0);
                *f = entry;
            } else {
                window.reach = window.reach.min(d);
                continue;
            }
            if window.len == WINDOW_OBSTACLES {
                farthest = window
                    .near
                    .iter()
                    .enumerate()
                    .max_by(|(_, a), (_, b)| a.0.total_cmp(&b.0))
                    .map_or(0, |(k, _)| k);
            }
        }
        window
    }

    /// The kept obstacles, if they are all that can come within `clearance` of `path`;
    /// `None` when the path may reach beyond the window (check it against every obstacle).
    pub(super) fn covering(&self, path: &DubinsPath, clearance: f32) -> Option<&[NearObstacle]> {
        // Every point of the path lies within its length of its start.
        let extent = path.length() + path.start.position.distance(self.centre) + clearance;
        // Far above the rounding of the primitives and predicates (≈ 10⁻⁶ relative).
        let margin = 1.0 + 1e-3 * (extent + self.centre.x.abs() + self.centre.y.abs());
        (extent + margin < self.reach).then_some(self.kept())
    }
}

/// A window read only when first needed (the obstacles around the goal, for the search's
/// pending goal links).
#[derive(Clone, Copy)]
pub(super) struct LazyWindow {
    /// Whether `window` has been read.
    read: bool,
    window: ObstacleWindow,
}

impl LazyWindow {
    /// Not read. `const` and all-zero.
    pub(super) const UNREAD: Self = Self {
        read: false,
        window: ObstacleWindow::EMPTY,
    };

    /// `window`, already read.
    pub(super) fn of(window: ObstacleWindow) -> Self {
        Self { read: true, window }
    }

    /// The window, read around `centre` on the first call (work: [`ObstacleWindow::around`]).
    pub(super) fn get_or_read(
        &mut self,
        network: &Network<'_>,
        centre: Vec2,
        meter: &mut Meter,
    ) -> &ObstacleWindow {
        if !self.read {
            self.window = ObstacleWindow::around(network, centre, meter);
            self.read = true;
        }
        &self.window
    }

    /// The window if it has been read.
    pub(super) fn get(&self) -> Option<&ObstacleWindow> {
        self.read.then_some(&self.window)
    }
}
