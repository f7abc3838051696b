//! The static obstacles near an endpoint, read from the network once for all of the
//! endpoint's connections.
//!
//! Connecting the start or the goal checks up to hundreds of Dubins paths that all begin or end
//! at one point, each against every obstacle. An [`ObstacleWindow`] keeps the
//! [`WINDOW_OBSTACLES`] obstacles whose bounding boxes lie nearest to that point, read once, and
//! the distance `reach` of the nearest box it left out. Every point of a path of length `L`
//! starting at `s` lies within `L + |s − centre|` of the centre, so when that plus the clearance
//! stays below `reach` (with a margin far above f32 rounding), no obstacle left out can come
//! within the clearance of the path, and checking the kept ones decides exactly what checking
//! all of them would.

use super::Meter;
use crate::geometry::{point_box_distance, DubinsPath, Vec2};
use crate::network::{Network, Obstacle};

/// Obstacles an [`ObstacleWindow`] keeps.
pub(super) const WINDOW_OBSTACLES: usize = 32;

/// An obstacle as the window keeps it: the distance of its bounding box from the centre, the
/// obstacle, and its bounding box `(min, max)`.
pub(super) type NearObstacle<'n> = (f32, Obstacle<'n>, (Vec2, Vec2));

/// A slot of a window's array: unused, or a kept obstacle. An enum with an explicit `u8` tag
/// whose unused variant is 0, so that an unused slot is all-zero bytes (an [`Obstacle`] of
/// zero bytes would be a polygon with a null reference, which no value may be): an idle window
/// keeps a new planner all-zero, and a `static` one in `.bss`.
#[repr(u8)]
#[derive(Clone, Copy)]
pub(super) enum Slot<'n> {
    /// Not in use.
    Unused = 0,
    /// A kept obstacle.
    Kept(NearObstacle<'n>) = 1,
}

impl<'n> Slot<'n> {
    /// The kept obstacle with its bounding box (`None`: an unused slot).
    #[inline(always)]
    pub(super) fn obstacle(&self) -> Option<(Obstacle<'n>, (Vec2, Vec2))> {
        match self {
            Self::Kept((_, o, bbox)) => Some((*o, *bbox)),
            Self::Unused => None,
        }
    }

    /// The distance of the kept obstacle's bounding box from the centre (−∞: unused).
    fn distance(&self) -> f32 {
        match self {
            Self::Kept((d, ..)) => *d,
            Self::Unused => f32::NEG_INFINITY,
        }
    }
}

/// The obstacles nearest to a point (see the module documentation). A planner keeps its
/// windows in place across the steps of a query; all-zero bytes are an empty window
/// ([`ObstacleWindow::EMPTY`]).
pub(super) struct ObstacleWindow<'n> {
    centre: Vec2,
    /// The kept obstacles (the first `len` slots), every one at most as far as any left out,
    /// in no particular order.
    near: [Slot<'n>; WINDOW_OBSTACLES],
    len: usize,
    /// Distance of the nearest box left out (+∞ when every obstacle is kept).
    reach: f32,
}

impl<'n> ObstacleWindow<'n> {
    /// A window that keeps nothing and covers no path (every check reads the network): a reach
    /// of 0 is below any path's extent. All-zero bytes.
    pub(super) const EMPTY: Self = Self {
        centre: Vec2 { x: 0.0, y: 0.0 },
        near: [Slot::Unused; WINDOW_OBSTACLES],
        len: 0,
        reach: 0.0,
    };

    /// Makes this a window that keeps nothing and covers no path, in place.
    pub(super) fn clear(&mut self) {
        (self.len, self.reach) = (0, 0.0);
    }

    /// The kept obstacles.
    fn kept(&self) -> &[Slot<'n>] {
        self.near.get(..self.len).unwrap_or(&[])
    }

    /// Makes this the window around `centre`, in place. Work: one collision test per obstacle
    /// (the distance of its bounding box, with, for an obstacle nearer than the farthest kept,
    /// a scan of the ≤ [`WINDOW_OBSTACLES`] kept for the new farthest). A record that cannot
    /// be read (validation rules that out) leaves a window that keeps nothing and covers no
    /// path, so that every check reads the network.
    pub(super) fn read_around(&mut self, network: &Network<'n>, centre: Vec2, meter: &mut Meter) {
        let window = self;
        (window.centre, window.len, window.reach) = (centre, 0, f32::INFINITY);
        // Once the window is full, the index of its farthest box: a nearer one replaces it.
        let mut farthest = 0;
        for i in 0..network.obstacle_count() {
            meter.work.collision_tests += 1;
            let Some((obstacle, (lo, hi))) = network.obstacle(i) else {
                (window.len, window.reach) = (0, f32::NEG_INFINITY);
                return;
            };
            let d = point_box_distance(centre, lo, hi);
            if !(d >= 0.0) {
                // Not finite: validation rules it out.
                (window.len, window.reach) = (0, f32::NEG_INFINITY);
                return;
            }
            let entry = Slot::Kept((d, obstacle, (lo, hi)));
            if let Some(free) = window.near.get_mut(window.len) {
                *free = entry;
                window.len += 1;
            } else if let Some(f) = window.near.get_mut(farthest).filter(|f| d < f.distance()) {
                window.reach = window.reach.min(f.distance());
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
                    .max_by(|(_, a), (_, b)| a.distance().total_cmp(&b.distance()))
                    .map_or(0, |(k, _)| k);
            }
        }
    }

    /// The kept obstacles, if they are all that can come within `clearance` of `path`;
    /// `None` when the path may reach beyond the window (check it against every obstacle).
    pub(super) fn covering(&self, path: &DubinsPath, clearance: f32) -> Option<&[Slot<'n>]> {
        // Every point of the path lies within its length of its start.
        let extent = path.length() + path.start.position.distance(self.centre) + clearance;
        // Far above the rounding of the primitives and predicates (≈ 10⁻⁶ relative).
        let margin = 1.0 + 1e-3 * (extent + self.centre.x.abs() + self.centre.y.abs());
        (extent + margin < self.reach).then_some(self.kept())
    }
}

/// A window read only when first needed (the obstacles around the goal, for the search's
/// pending goal links). All-zero bytes are an unread window ([`LazyWindow::UNREAD`]).
pub(super) struct LazyWindow<'n> {
    /// Whether `window` has been read.
    read: bool,
    window: ObstacleWindow<'n>,
}

impl<'n> LazyWindow<'n> {
    /// Not read. All-zero bytes.
    pub(super) const UNREAD: Self = Self {
        read: false,
        window: ObstacleWindow::EMPTY,
    };

    /// Marks the window unread, in place: the next [`LazyWindow::read_once`] reads it.
    pub(super) fn forget(&mut self) {
        self.read = false;
    }

    /// Reads the window around `centre` now ([`ObstacleWindow::read_around`]).
    pub(super) fn read(&mut self, network: &Network<'n>, centre: Vec2, meter: &mut Meter) {
        self.window.read_around(network, centre, meter);
        self.read = true;
    }

    /// Reads the window around `centre` unless it has been read (work:
    /// [`ObstacleWindow::read_around`] on the first call, none after).
    pub(super) fn read_once(&mut self, network: &Network<'n>, centre: Vec2, meter: &mut Meter) {
        if !self.read {
            self.read(network, centre, meter);
        }
    }

    /// The window if it has been read.
    pub(super) fn get(&self) -> Option<&ObstacleWindow<'n>> {
        self.read.then_some(&self.window)
    }
}
