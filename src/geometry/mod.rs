//! Planar geometry in the network's local frame: vectors, poses, line segments, circular arcs,
//! Dubins paths, curvature-bounded cubic spline smoothing and the exact collision predicates.
//!
//! Everything here is `f32` and uses `libm` for transcendental functions, so it builds for a
//! Cortex-M4F without `std`.

mod dubins;
pub mod grid;
pub mod hermite;
pub mod line_cover;
pub mod predicates;
pub mod spline;
pub mod trig;
pub mod vertical;
pub mod voronoi;

pub use dubins::{DubinsEnd, DubinsPath, DubinsWord, WordSet};

use core::f32::consts::{FRAC_PI_2, PI, TAU};
use core::ops::{Add, Mul, Neg, Sub};

/// Angles within this many radians below 2π are taken as zero when a turn angle is reduced to
/// [0, 2π). f32 rounding of an angle near 0 lands either at +ε or at 2π − ε; without this
/// tolerance a goal lying on the start's turning circle would earn a spurious full loop.
/// At a 1 km turn radius the tolerance is 1 cm of arc.
pub const ANGLE_TOLERANCE: f32 = 1e-5;

/// The largest coordinate or radius, metres, that the planner accepts in a query or pop-up
/// (10 000 km). Beyond it, squared distances in f32 approach overflow and distance tests could
/// fail open.
pub const MAX_COORDINATE_M: f32 = 1e7;

/// A 2-D vector or point, metres east (`x`) and north (`y`).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Vec2 {
    /// East, metres.
    pub x: f32,
    /// North, metres.
    pub y: f32,
}

impl Vec2 {
    /// The vector `(x, y)`.
    pub const fn new(x: f32, y: f32) -> Self {
        Self { x, y }
    }

    /// The unit vector at angle `a` (radians counter-clockwise from east).
    pub fn from_angle(a: f32) -> Self {
        let (s, c) = trig::sin_cos(a);
        Self { x: c, y: s }
    }

    /// Dot product.
    pub fn dot(self, o: Self) -> f32 {
        self.x * o.x + self.y * o.y
    }

    /// The z component of the cross product (positive when `o` lies counter-clockwise of `self`).
    pub fn cross(self, o: Self) -> f32 {
        self.x * o.y - self.y * o.x
    }

    /// Euclidean length. (`sqrt(x² + y²)` in f32: `libm::hypotf` guards against overflow by
    /// working in f64, which a Cortex-M4F emulates; the planner's coordinates are far below
    /// the 1.8·10¹⁹ m where the square would overflow.)
    pub fn norm(self) -> f32 {
        libm::sqrtf(self.dot(self))
    }

    /// Squared length.
    pub fn norm_sq(self) -> f32 {
        self.dot(self)
    }

    /// Distance to `o`.
    pub fn distance(self, o: Self) -> f32 {
        (self - o).norm()
    }

    /// Direction angle `atan2(y, x)` in (−π, π].
    pub fn angle(self) -> f32 {
        libm::atan2f(self.y, self.x)
    }

    /// This vector turned 90° counter-clockwise.
    pub fn perp(self) -> Self {
        Self {
            x: -self.y,
            y: self.x,
        }
    }

    /// Both components are finite.
    pub fn is_finite(self) -> bool {
        self.x.is_finite() && self.y.is_finite()
    }

    /// Both components lie within ±[`MAX_COORDINATE_M`].
    pub fn is_in_range(self) -> bool {
        libm::fabsf(self.x) <= MAX_COORDINATE_M && libm::fabsf(self.y) <= MAX_COORDINATE_M
    }
}

impl Add for Vec2 {
    type Output = Self;
    fn add(self, o: Self) -> Self {
        Self::new(self.x + o.x, self.y + o.y)
    }
}

impl Sub for Vec2 {
    type Output = Self;
    fn sub(self, o: Self) -> Self {
        Self::new(self.x - o.x, self.y - o.y)
    }
}

impl Mul<f32> for Vec2 {
    type Output = Self;
    fn mul(self, k: f32) -> Self {
        Self::new(self.x * k, self.y * k)
    }
}

impl Neg for Vec2 {
    type Output = Self;
    fn neg(self) -> Self {
        Self::new(-self.x, -self.y)
    }
}

/// The axis-aligned bounding box `(min, max)` of some points; `(+∞, −∞)` when there are none.
pub fn points_bounding_box(points: impl IntoIterator<Item = Vec2>) -> (Vec2, Vec2) {
    let mut lo = Vec2::new(f32::INFINITY, f32::INFINITY);
    let mut hi = Vec2::new(f32::NEG_INFINITY, f32::NEG_INFINITY);
    for p in points {
        lo = Vec2::new(lo.x.min(p.x), lo.y.min(p.y));
        hi = Vec2::new(hi.x.max(p.x), hi.y.max(p.y));
    }
    (lo, hi)
}

/// The Euclidean distance from `p` to the axis-aligned box `(lo, hi)`: 0 inside it or on its
/// edge, else the distance to its nearest point. Per axis, the gap is `lo − p` left of the box,
/// `p − hi` right of it and 0 between (at most one of the two differences is positive when
/// `lo ≤ hi`); the distance is the hypotenuse of the two gaps. Meant for finite inputs: `max`
/// skips a NaN operand, so a NaN coordinate need not give NaN.
pub fn point_box_distance(p: Vec2, lo: Vec2, hi: Vec2) -> f32 {
    let dx = (lo.x - p.x).max(p.x - hi.x).max(0.0);
    let dy = (lo.y - p.y).max(p.y - hi.y).max(0.0);
    libm::sqrtf(dx * dx + dy * dy)
}

/// `libm::fmodf(a, τ)`, exactly: `a` itself when |a| < τ (what `fmodf` returns then), so
/// that the common case costs one comparison instead of a call.
fn fmod_tau(a: f32) -> f32 {
    if libm::fabsf(a) < TAU {
        a
    } else {
        libm::fmodf(a, TAU)
    }
}

/// Reduces an angle to [0, 2π), taking values within [`ANGLE_TOLERANCE`] of 2π as 0.
pub fn wrap_to_tau(a: f32) -> f32 {
    let mut r = fmod_tau(a);
    if r < 0.0 {
        r += TAU;
    }
    if r >= TAU - ANGLE_TOLERANCE {
        0.0
    } else {
        r
    }
}

/// Reduces an angle to (−π, π].
pub fn wrap_to_pi(a: f32) -> f32 {
    let r = fmod_tau(a);
    if r > PI {
        r - TAU
    } else if r <= -PI {
        r + TAU
    } else {
        r
    }
}

/// Converts a compass heading (degrees clockwise from north, the direction of flight) to the
/// mathematical heading used throughout the crate (radians counter-clockwise from east).
pub fn heading_from_compass_deg(compass_deg: f32) -> f32 {
    wrap_to_pi(FRAC_PI_2 - compass_deg.to_radians())
}

/// Converts a mathematical heading back to a compass heading in degrees [0, 360).
pub fn compass_deg_from_heading(heading: f32) -> f32 {
    let d = wrap_to_tau(FRAC_PI_2 - heading).to_degrees();
    if d >= 360.0 {
        0.0
    } else {
        d
    }
}

/// A position and a heading.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Pose {
    /// Position, metres.
    pub position: Vec2,
    /// Heading, radians counter-clockwise from east.
    pub heading: f32,
}

impl Pose {
    /// The pose at `(x, y)` with `heading` (radians counter-clockwise from east).
    pub const fn new(x: f32, y: f32, heading: f32) -> Self {
        Self {
            position: Vec2::new(x, y),
            heading,
        }
    }

    /// Position and heading are finite.
    pub fn is_finite(&self) -> bool {
        self.position.is_finite() && self.heading.is_finite()
    }

    /// The unit vector of the direction of flight.
    pub fn direction(&self) -> Vec2 {
        Vec2::from_angle(self.heading)
    }
}

/// The direction of a turn.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Turn {
    /// Counter-clockwise.
    Left,
    /// Clockwise.
    Right,
}

impl Turn {
    /// +1 for left, −1 for right: the sign of the arc's sweep.
    pub fn sign(self) -> f32 {
        match self {
            Turn::Left => 1.0,
            Turn::Right => -1.0,
        }
    }

    /// The centre of the turning circle of radius `r` that a pose turning this way flies around.
    pub fn centre(self, pose: &Pose, r: f32) -> Vec2 {
        pose.position + pose.direction().perp() * (r * self.sign())
    }
}

/// A straight line segment from `start` to `end`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Segment {
    /// First point.
    pub start: Vec2,
    /// Last point.
    pub end: Vec2,
}

impl Segment {
    /// The segment from `start` to `end`.
    pub const fn new(start: Vec2, end: Vec2) -> Self {
        Self { start, end }
    }

    /// Length, metres.
    pub fn length(&self) -> f32 {
        self.start.distance(self.end)
    }

    /// The point at arc length `s` from the start (clamped to the segment).
    pub fn point_at(&self, s: f32) -> Vec2 {
        let len = self.length();
        if len <= 0.0 {
            return self.start;
        }
        let t = (s / len).clamp(0.0, 1.0);
        self.start + (self.end - self.start) * t
    }
}

/// A circular arc: `centre`, `radius`, the polar angle of its first point about the centre, and
/// the signed angle it sweeps (positive: counter-clockwise, a left turn).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Arc {
    /// Centre of the circle.
    pub centre: Vec2,
    /// Radius, metres (positive).
    pub radius: f32,
    /// Polar angle of the first point about the centre, radians.
    pub start_angle: f32,
    /// Signed swept angle, radians: positive counter-clockwise (left turn), negative clockwise.
    pub sweep: f32,
}

impl Arc {
    /// The turn direction this arc flies.
    pub fn turn(&self) -> Turn {
        // By sign bit, so that a zero-length right arc (sweep −0.0) still turns right.
        if !self.sweep.is_sign_negative() {
            Turn::Left
        } else {
            Turn::Right
        }
    }

    /// Length, metres.
    pub fn length(&self) -> f32 {
        self.radius * libm::fabsf(self.sweep)
    }

    /// The point at polar angle `a` on the circle.
    pub fn point_at_angle(&self, a: f32) -> Vec2 {
        self.centre + Vec2::from_angle(a) * self.radius
    }

    /// The pose at arc length `s` from the start (clamped to the arc).
    pub fn pose_at(&self, s: f32) -> Pose {
        // max/min rather than clamp: no panic when the length is NaN.
        let s = s.max(0.0).min(self.length());
        let sign = self.turn().sign();
        let a = self.start_angle + sign * s / self.radius;
        let p = self.point_at_angle(a);
        // Flying counter-clockwise the heading leads the polar angle by 90°, clockwise it lags.
        Pose {
            position: p,
            heading: wrap_to_pi(a + sign * FRAC_PI_2),
        }
    }

    /// First point.
    pub fn start(&self) -> Vec2 {
        self.point_at_angle(self.start_angle)
    }

    /// Last point.
    pub fn end(&self) -> Vec2 {
        self.point_at_angle(self.start_angle + self.sweep)
    }

    /// Whether polar angle `a` lies within the swept range (inclusive).
    pub fn contains_angle(&self, a: f32) -> bool {
        // Offset from the start, measured in the direction of the sweep, in [0, 2π).
        let offset = if !self.sweep.is_sign_negative() {
            wrap_to_tau(a - self.start_angle)
        } else {
            wrap_to_tau(self.start_angle - a)
        };
        offset <= libm::fabsf(self.sweep)
    }

    /// The arc a pose flies when it turns `turn` through `angle` radians (≥ 0) on radius `r`.
    pub fn from_pose(pose: &Pose, turn: Turn, r: f32, angle: f32) -> Self {
        let centre = turn.centre(pose, r);
        Self {
            centre,
            radius: r,
            start_angle: wrap_to_pi(pose.heading - turn.sign() * FRAC_PI_2),
            sweep: turn.sign() * angle,
        }
    }
}

/// One piece of a route: a line or an arc.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Primitive {
    /// A straight segment.
    Line(Segment),
    /// A circular arc.
    Arc(Arc),
}

impl Default for Primitive {
    fn default() -> Self {
        Primitive::Line(Segment::default())
    }
}

impl Primitive {
    /// Length, metres.
    pub fn length(&self) -> f32 {
        match self {
            Primitive::Line(s) => s.length(),
            Primitive::Arc(a) => a.length(),
        }
    }

    /// The pose at arc length `s` from the start (clamped).
    pub fn pose_at(&self, s: f32) -> Pose {
        match self {
            Primitive::Line(seg) => {
                let d = seg.end - seg.start;
                let heading = if d.norm_sq() > 0.0 { d.angle() } else { 0.0 };
                Pose {
                    position: seg.point_at(s),
                    heading,
                }
            }
            Primitive::Arc(a) => a.pose_at(s),
        }
    }

    /// The part of the primitive between arc lengths `first` and `last` from its start (clamped
    /// to it), flown the same way; `None` when the interval misses it (or a bound is NaN).
    pub fn trimmed(&self, first: f32, last: f32) -> Option<Primitive> {
        let len = self.length();
        let (first, last) = (first.max(0.0), last.min(len));
        if !(first <= last) {
            return None;
        }
        Some(match self {
            Primitive::Line(seg) => {
                Primitive::Line(Segment::new(seg.point_at(first), seg.point_at(last)))
            }
            Primitive::Arc(a) => Primitive::Arc(Arc {
                start_angle: a.start_angle + a.turn().sign() * first / a.radius,
                sweep: a.turn().sign() * (last - first) / a.radius,
                ..*a
            }),
        })
    }

    /// First point.
    pub fn start(&self) -> Vec2 {
        match self {
            Primitive::Line(s) => s.start,
            Primitive::Arc(a) => a.start(),
        }
    }

    /// Last point.
    pub fn end(&self) -> Vec2 {
        match self {
            Primitive::Line(s) => s.end,
            Primitive::Arc(a) => a.end(),
        }
    }

    /// Axis-aligned bounding box `(min, max)`; for an arc the box of its end points and of the
    /// circle's extreme points that the sweep passes.
    pub fn bounding_box(&self) -> (Vec2, Vec2) {
        match self {
            Primitive::Line(s) => (
                Vec2::new(s.start.x.min(s.end.x), s.start.y.min(s.end.y)),
                Vec2::new(s.start.x.max(s.end.x), s.start.y.max(s.end.y)),
            ),
            Primitive::Arc(a) => {
                let (p, q) = (a.start(), a.end());
                let mut lo = Vec2::new(p.x.min(q.x), p.y.min(q.y));
                let mut hi = Vec2::new(p.x.max(q.x), p.y.max(q.y));
                for k in 0..4 {
                    let ang = k as f32 * FRAC_PI_2;
                    if a.contains_angle(ang) {
                        let e = a.point_at_angle(ang);
                        lo = Vec2::new(lo.x.min(e.x), lo.y.min(e.y));
                        hi = Vec2::new(hi.x.max(e.x), hi.y.max(e.y));
                    }
                }
                (lo, hi)
            }
        }
    }
}

/// Sorts a short slice by `key` (ascending, stable) by insertion: O(n²) comparisons, no
/// recursion and no allocation. The core's few sorts are of at most a few dozen items (the
/// exit's trace intervals, a grid band's runs), where this is as fast as `sort_unstable` and
/// keeps the firmware's call graph free of `core`'s recursive quicksort.
/// Keys that do not compare (a NaN) are left in place relative to each other.
pub fn insertion_sort_by<T: Copy, K: PartialOrd>(items: &mut [T], key: impl Fn(&T) -> K) {
    for i in 1..items.len() {
        let mut j = i;
        while j > 0 {
            let (Some(a), Some(b)) = (items.get(j - 1), items.get(j)) else {
                break;
            };
            if !(key(a) > key(b)) {
                break;
            }
            items.swap(j - 1, j);
            j -= 1;
        }
    }
}

#[cfg(test)]
mod sort_tests {
    use super::insertion_sort_by;

    #[test]
    fn insertion_sort_matches_the_standard_stable_sort() {
        let mut state = 0x2545_F491_4F6C_DD1Du64;
        for n in 0..40 {
            let mut items: [(u32, u32); 40] = [(0, 0); 40];
            for (i, item) in items.iter_mut().enumerate().take(n) {
                state ^= state << 13;
                state ^= state >> 7;
                state ^= state << 17;
                *item = ((state % 7) as u32, i as u32);
            }
            let mut expected = items;
            expected[..n].sort_by_key(|p| p.0);
            insertion_sort_by(&mut items[..n], |p| p.0);
            assert_eq!(items[..n], expected[..n]);
        }
    }
}
