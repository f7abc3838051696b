//! The vertical half of Niendorf et al.'s aircraft model: a Dubins car in the plane plus a
//! vertical double integrator (climb rate at most `v_c`, vertical acceleration at most `a_z`),
//! flown at a constant horizontal airspeed `v`.
//!
//! Every roadmap vertex is a state at rest vertically (its altitude is sampled, its vertical
//! speed is zero), so an edge's vertical motion is a rest-to-rest move of `Δz` over the time the
//! horizontal path takes, `T = L / v`. Measured along the horizontal path (`s = v t`), the
//! limits become a gradient `g = v_c / v` (metres of climb per metre flown) and a curvature
//! `k = a_z / v²` (the bound on `d²z/ds²`).
//!
//! The profile this module builds is the bang-coast-bang move: accelerate at `k` until the
//! gradient reaches `g` (or half the move is done), coast, brake at `k`. It takes the shortest
//! distance of all rest-to-rest moves, so the move is feasible over `L` if and only if this
//! distance is at most `L`. A climb is flown as early as it can be and a descent as late, so the
//! aircraft is at every point of the edge as high as any monotone move between the two
//! altitudes allows: the profile that clears the most buildings.
//!
//! A building of height `h` (and clearance `c`) is a conflict only where the aircraft flies
//! below `h + c`. The profile is monotone, so that part of the edge is one interval of `s`
//! ([`VerticalProfile::span_below`]); the horizontal path cut to it
//! ([`pieces_within`]) is checked against the building's footprint with the planar predicates.

use super::{DubinsPath, Primitive};

/// How much a ceiling is raised, per metre of the largest altitude involved, before the span
/// below it is found. The altitude change to the ceiling (`ceiling − from`) rounds by up to an
/// ulp of that altitude (6·10⁻⁸ of it), and where the gradient is near zero (the ends of the
/// move) a small altitude error is a large error in distance (`u = √(2δ/k)`). Raising the
/// ceiling by far more than the rounding makes the computed distance err on the safe side.
pub const CEILING_MARGIN: f32 = 1e-5;

/// The absolute part of the ceiling's raise, metres.
pub const CEILING_MARGIN_M: f32 = 1e-3;

/// The margin, metres per metre of edge, added to the open end of a span below a ceiling so
/// that the f32 rounding of the inverse profile cannot leave out a point flown below it. The
/// inverse takes a square root and a few products of quantities within the edge's length; its
/// relative error is a few ulp (≈ 10⁻⁶), so 10⁻⁴ of the length is a hundredfold margin.
/// `host-tests/tests/core/vertical_profile.rs` checks the spans against an f64 profile.
pub const SPAN_MARGIN: f32 = 1e-4;

/// The absolute part of the span margin, metres: covers spans near the start of a short edge.
pub const SPAN_MARGIN_M: f32 = 1e-3;

/// The aircraft's vertical limits and its horizontal airspeed.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct VerticalLimits {
    /// Horizontal airspeed `v`, m/s (> 0).
    pub airspeed: f32,
    /// Largest climb or sink rate `v_c`, m/s (> 0).
    pub climb_rate: f32,
    /// Largest vertical acceleration `a_z`, m/s² (> 0).
    pub vertical_accel: f32,
}

impl VerticalLimits {
    /// Niendorf et al.'s aircraft: `v_c` 10 m/s, `a_z` 20 m/s², at `airspeed` m/s.
    pub const fn niendorf(airspeed: f32) -> Self {
        Self {
            airspeed,
            climb_rate: 10.0,
            vertical_accel: 20.0,
        }
    }

    /// Every limit finite and positive.
    pub fn is_valid(&self) -> bool {
        [self.airspeed, self.climb_rate, self.vertical_accel]
            .iter()
            .all(|x| x.is_finite() && *x > 0.0)
    }

    /// The largest gradient `g = v_c / v`, metres of climb per metre flown.
    pub fn gradient(&self) -> f32 {
        self.climb_rate / self.airspeed
    }

    /// The largest `|d²z/ds²|`, `k = a_z / v²`, per metre.
    pub fn curvature(&self) -> f32 {
        self.vertical_accel / (self.airspeed * self.airspeed)
    }

    /// The largest rest-to-rest altitude change over `length` metres of horizontal path:
    /// `k L² / 4` when the move never reaches the gradient limit (`L ≤ 2g/k`), else
    /// `g (L − g/k)` (accelerate over `g/k`, coast, brake over `g/k`). 0 for a non-positive or
    /// NaN length or invalid limits.
    pub fn max_climb(&self, length: f32) -> f32 {
        if !(self.is_valid() && length > 0.0) {
            return 0.0;
        }
        let (g, k) = (self.gradient(), self.curvature());
        if length <= 2.0 * g / k {
            k * length * length / 4.0
        } else {
            g * (length - g / k)
        }
    }
}

/// The altitude flown along one edge: a rest-to-rest move from `from` to `to` over a horizontal
/// path of `length` metres, climbing as early and descending as late as the limits allow.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct VerticalProfile {
    /// Altitude at the start, metres.
    pub from: f32,
    /// Altitude at the end, metres.
    pub to: f32,
    /// Horizontal length of the edge, metres.
    pub length: f32,
    /// Horizontal distance the move takes, metres (≤ `length`).
    ramp: f32,
    /// Horizontal distance of the accelerating (and of the braking) part, metres.
    ease: f32,
    /// The curvature `k` of the accelerating and braking parts, per metre.
    curvature: f32,
}

impl VerticalProfile {
    /// The profile from `from` to `to` over `length` metres under `limits`. `None` when an input
    /// is not finite, the length is negative, the limits are invalid, or the move needs more
    /// than `length` metres (it is not flyable).
    pub fn new(from: f32, to: f32, length: f32, limits: &VerticalLimits) -> Option<Self> {
        if !(from.is_finite() && to.is_finite() && length.is_finite() && length >= 0.0) {
            return None;
        }
        if !limits.is_valid() {
            return None;
        }
        let (g, k) = (limits.gradient(), limits.curvature());
        let d = libm::fabsf(to - from);
        // Rest-to-rest in least distance: the gradient ramps up at k to its peak and back down.
        // If the peak would pass g (d ≥ g²/k), it stops at g and the move coasts between:
        // ease g/k, ramp d/g + g/k. Otherwise the peak is √(k d) at half way: ease √(d/k).
        let (ease, ramp) = if d >= g * g / k {
            (g / k, d / g + g / k)
        } else {
            let ease = libm::sqrtf(d / k);
            (ease, 2.0 * ease)
        };
        // NaN-safe: an overflowing ramp (∞) or a NaN is refused here.
        if !(ramp <= length) {
            return None;
        }
        Some(Self {
            from,
            to,
            length,
            ramp,
            ease,
            curvature: k,
        })
    }

    /// Altitude change made `u` metres into the move, `0 ≤ u ≤ ramp`: `k u²/2` while
    /// accelerating, linear at the peak gradient `k·ease` while coasting, `d − k (ramp − u)²/2`
    /// while braking.
    fn moved(&self, u: f32) -> f32 {
        let k = self.curvature;
        let d = libm::fabsf(self.to - self.from);
        let u = u.max(0.0).min(self.ramp);
        if u <= self.ease {
            0.5 * k * u * u
        } else if u >= self.ramp - self.ease {
            let w = self.ramp - u;
            (d - 0.5 * k * w * w).max(0.0)
        } else {
            0.5 * k * self.ease * self.ease + k * self.ease * (u - self.ease)
        }
        .min(d)
    }

    /// The inverse of [`Self::moved`]: the distance into the move at which the altitude change
    /// reaches `delta` (`0 ≤ delta ≤ d`).
    fn distance_to_move(&self, delta: f32) -> f32 {
        let k = self.curvature;
        let d = libm::fabsf(self.to - self.from);
        let eased = 0.5 * k * self.ease * self.ease;
        if delta <= eased {
            libm::sqrtf(2.0 * delta / k)
        } else if delta >= d - eased {
            self.ramp - libm::sqrtf(((d - delta) * 2.0 / k).max(0.0))
        } else {
            self.ease + (delta - eased) / (k * self.ease)
        }
    }

    /// Where the move starts along the edge: at once for a climb, as late as it can for a
    /// descent.
    fn ramp_start(&self) -> f32 {
        if self.to >= self.from {
            0.0
        } else {
            self.length - self.ramp
        }
    }

    /// Horizontal distance the altitude change takes, metres.
    pub fn ramp(&self) -> f32 {
        self.ramp
    }

    /// The altitude `s` metres along the edge (clamped to the edge).
    pub fn altitude_at(&self, s: f32) -> f32 {
        let u = s.max(0.0).min(self.length) - self.ramp_start();
        let m = self.moved(u);
        if self.to >= self.from {
            self.from + m
        } else {
            self.from - m
        }
    }

    /// The part of the edge flown below `ceiling`, as `(first, last)` metres along it; `None`
    /// when the whole edge is above it. The profile is monotone, so the set is one interval:
    /// the start of a climb, the end of a descent, all or nothing of a level edge. So that
    /// rounding never leaves a point out, the ceiling is first raised by [`CEILING_MARGIN`] of
    /// the largest altitude involved plus [`CEILING_MARGIN_M`], and the interval's open end is
    /// moved out by [`SPAN_MARGIN`] of the length plus [`SPAN_MARGIN_M`]. A NaN ceiling gives
    /// the whole edge.
    pub fn span_below(&self, ceiling: f32) -> Option<(f32, f32)> {
        let scale = libm::fabsf(ceiling)
            .max(libm::fabsf(self.from))
            .max(libm::fabsf(self.to));
        let ceiling = ceiling + CEILING_MARGIN * scale + CEILING_MARGIN_M;
        let low = self.from.min(self.to);
        let high = self.from.max(self.to);
        if ceiling <= low {
            return None;
        }
        if !(ceiling <= high) {
            return Some((0.0, self.length));
        }
        let margin = SPAN_MARGIN * self.length + SPAN_MARGIN_M;
        if self.to > self.from {
            // Climbing: below the ceiling until the move has risen ceiling − from.
            let s = self.ramp_start() + self.distance_to_move(ceiling - self.from);
            Some((0.0, (s + margin).min(self.length)))
        } else {
            // Descending: below the ceiling once the move has sunk more than from − ceiling.
            let s = self.ramp_start() + self.distance_to_move(self.from - ceiling);
            Some(((s - margin).max(0.0), self.length))
        }
    }
}

/// The pieces of `path` between `first` and `last` metres along it (clamped to the path), each
/// cut from the path's own primitives; pieces outside the interval are `None`.
pub fn pieces_within(path: &DubinsPath, first: f32, last: f32) -> [Option<Primitive>; 3] {
    let mut out = [None; 3];
    let mut offset = 0.0;
    for ((prim, len), slot) in path
        .primitives()
        .into_iter()
        .zip(path.lengths)
        .zip(&mut out)
    {
        *slot = prim.and_then(|p| p.trimmed(first - offset, last - offset));
        offset += len;
    }
    out
}
