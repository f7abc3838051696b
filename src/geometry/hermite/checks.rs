//! The checks of a [`HermiteSegment`]: flyability against the vehicle's limits, certified
//! between samples (`check_flyable`), and clearance from polygons and circles through a
//! polyline with a proven deviation bound (`polyline_bound`, `conflicts_with_*`).

use super::{
    bernstein_max_cubic, horner, restrict_cubic, ChordBound, FlyLimits, HermiteSegment, Limit,
    Violation, EVAL_ROUNDING, FLY_CHECK_INTERVALS, FLY_CHECK_MAX_DEPTH, FLY_CHECK_MAX_SPLITS,
    MAX_PIECES,
};
use crate::geometry::predicates::{self, PolygonView};
use crate::geometry::{Primitive, Segment, Vec2};
use heapless::Vec;

/// Flight quantities at one sample.
#[derive(Clone, Copy)]
struct Sample {
    speed: f32,
    a_long: f32,
    a_lat: f32,
}

/// A parameter interval still to prove flyable: its ends (parameter, sample) and its depth of
/// bisection.
#[derive(Clone, Copy)]
struct Interval {
    a: (f32, Sample),
    b: (f32, Sample),
    depth: u32,
}

impl HermiteSegment {
    // ------------------------------------------------------------------------------------------
    // Flyability.

    fn sample(&self, s: f32) -> Sample {
        let v = horner(&self.velocity_coefficients(), s) * (1.0 / self.t_max);
        let a = horner(&self.acceleration_coefficients(), s) * (1.0 / (self.t_max * self.t_max));
        let speed = v.norm();
        if speed > 0.0 {
            Sample {
                speed,
                a_long: v.dot(a) / speed,
                a_lat: libm::fabsf(v.cross(a)) / speed,
            }
        } else {
            // Zero (or NaN) speed fails v_min > 0 first; the accelerations are then not used.
            Sample {
                speed,
                a_long: 0.0,
                a_lat: 0.0,
            }
        }
    }

    /// A sample beyond a limit (NaN counts as beyond).
    fn sample_violation(limits: &FlyLimits, x: &Sample, t: f32) -> Option<Violation> {
        let v = |limit, value| Some(Violation::Exceeds { limit, t, value });
        if !(x.speed >= limits.v_min) {
            return v(Limit::SpeedMin, x.speed);
        }
        if !(x.speed <= limits.v_max) {
            return v(Limit::SpeedMax, x.speed);
        }
        if !(x.a_long >= limits.a_long_min) {
            return v(Limit::LongitudinalMin, x.a_long);
        }
        if !(x.a_long <= limits.a_long_max) {
            return v(Limit::LongitudinalMax, x.a_long);
        }
        if !(x.a_lat <= limits.a_lat_max) {
            return v(Limit::Lateral, x.a_lat);
        }
        None
    }

    /// Proves the limits on an interval of duration `h` between samples `x` and `y`, or names
    /// the first limit it cannot prove with the end of the enclosure that crosses it.
    fn certify(
        &self,
        limits: &FlyLimits,
        x: &Sample,
        y: &Sample,
        h: f32,
    ) -> Result<(), (Limit, f32)> {
        let half = 0.5 * h;
        let a = self.accel_bound;
        // Sample error of a speed: the terms' rounding plus 2ε of the speed (≤ v_max where it
        // matters: an interval whose enclosure exceeds v_max is not accepted anyway).
        let dv = self.speed_rounding() + 2.0 * f32::EPSILON * limits.v_max;
        // Speed: Lipschitz constant A (|d|v|/dt| ≤ |a|).
        let mid = 0.5 * (x.speed + y.speed);
        let m = a * half + dv;
        let (lo, hi) = (mid - m, mid + m);
        if !(lo >= limits.v_min) {
            return Err((Limit::SpeedMin, lo));
        }
        if !(hi <= limits.v_max) {
            return Err((Limit::SpeedMax, hi));
        }
        // Here |v| ≥ lo ≥ v_min > 0 on the whole interval.
        let v_lo = lo;
        // Sample error of an acceleration: δa (terms, plus 2ε·A for the scaling) in the
        // numerator, |a|·δv/|v| from v's error in v·a and again in the division, and ≈ 3ε·|a|
        // for the products and the division themselves.
        let da = self.accel_rounding() + 5.0 * f32::EPSILON * a + 2.0 * a * dv / v_lo;
        // Longitudinal: |d(u·a)/dt| ≤ |j| + |a⊥|²/|v| ≤ J + A²/v_lo.
        let lip = self.jerk_bound + a * a / v_lo;
        let mid = 0.5 * (x.a_long + y.a_long);
        let m = lip * half + da;
        let (lo, hi) = (mid - m, mid + m);
        if !(lo >= limits.a_long_min) {
            return Err((Limit::LongitudinalMin, lo));
        }
        if !(hi <= limits.a_long_max) {
            return Err((Limit::LongitudinalMax, hi));
        }
        // Lateral: |d(u×a)/dt| ≤ |j| + |a∥||a⊥|/|v| ≤ J + A²/(2·v_lo).
        let lip = self.jerk_bound + 0.5 * a * a / v_lo;
        let hi = 0.5 * (x.a_lat + y.a_lat) + lip * half + da;
        if !(hi <= limits.a_lat_max) {
            return Err((Limit::Lateral, hi));
        }
        Ok(())
    }

    /// Proves `limits` on the parameter interval `[sa, sb]` (end samples `xa`, `xb`), bisecting
    /// where the enclosure does not prove them (see [`HermiteSegment::check_flyable`]). Depth
    /// first, the left half before the right, without recursion: a stack of the right halves
    /// still to prove, at most one per level.
    fn refine_flyable(
        &self,
        limits: &FlyLimits,
        (sa, xa): (f32, Sample),
        (sb, xb): (f32, Sample),
        splits_left: &mut u32,
    ) -> Result<(), Violation> {
        let mut pending: Vec<Interval, { FLY_CHECK_MAX_DEPTH as usize + 2 }> = Vec::new();
        let _ = pending.push(Interval {
            a: (sa, xa),
            b: (sb, xb),
            depth: 0,
        });
        while let Some(Interval { a, b, depth }) = pending.pop() {
            let Err((limit, bound)) = self.certify(limits, &a.1, &b.1, (b.0 - a.0) * self.t_max)
            else {
                continue;
            };
            let sm = 0.5 * (a.0 + b.0);
            let unproven = Violation::Unproven {
                limit,
                t: sm * self.t_max,
                bound,
            };
            if depth >= FLY_CHECK_MAX_DEPTH || *splits_left == 0 {
                return Err(unproven);
            }
            *splits_left -= 1;
            let xm = self.sample(sm);
            if let Some(v) = Self::sample_violation(limits, &xm, sm * self.t_max) {
                return Err(v);
            }
            let right = Interval {
                a: (sm, xm),
                b,
                depth: depth + 1,
            };
            let left = Interval {
                a,
                b: (sm, xm),
                depth: depth + 1,
            };
            // Each level leaves at most one right half pending: the stack cannot overflow.
            if pending.push(right).is_err() || pending.push(left).is_err() {
                return Err(unproven);
            }
        }
        Ok(())
    }

    /// Whether the segment respects `limits` everywhere: speed in `[v_min, v_max]`, longitudinal
    /// acceleration `(v·a)/|v|` in `[a_long_min, a_long_max]`, lateral `|v × a|/|v| ≤ a_lat_max`.
    ///
    /// **Conservative**: `Ok` only when proved for every `t ∈ [0, T]`, up to the rounding
    /// allowances. The proof: the quantities are sampled at [`FLY_CHECK_INTERVALS`] + 1 equal
    /// steps (any sample beyond a limit rejects with [`Violation::Exceeds`]); on an interval of
    /// duration `h` with end values `f_a`, `f_b` of a quantity with Lipschitz constant `K`, the
    /// quantity lies within `(f_a + f_b)/2 ± K·h/2` (what it can miss between the samples is at
    /// most `K·h/2`), and that enclosure must lie inside the limits. With `A ≥ max|a|`, `J ≥
    /// max|j|` (Bernstein bounds over the segment) and `v_lo` the enclosure's lower speed on the
    /// interval (≥ `v_min > 0` once the speed is proved), and `u = v/|v|`, `u' = a⊥/|v|`:
    /// * speed: `|d|v|/dt| ≤ |a|`, so `K = A`;
    /// * longitudinal: `d(u·a)/dt = |a⊥|²/|v| + u·j`, so `K = J + A²/v_lo`;
    /// * lateral: `d(u×a)/dt = a∥·(a⊥×u)/|v| + u×j`, and `|a∥||a⊥| ≤ |a|²/2`, so
    ///   `K = J + A²/(2·v_lo)`.
    ///
    /// Each enclosure is widened further by the f32 rounding of the sampled values:
    /// `δv = 8ε·Σ k|b_k|/T + 2ε·v_max` for speed, `8ε·Σ k(k−1)|b_k|/T² + 5ε·A + 2A·δv/v_lo`
    /// for accelerations (see `EVAL_ROUNDING`).
    /// An interval that cannot be proved is bisected (one more sample) down to depth
    /// [`FLY_CHECK_MAX_DEPTH`] and at most [`FLY_CHECK_MAX_SPLITS`] times in all, so the margin
    /// shrinks to `K·T/(64·2¹²)/2`; past that the segment is rejected with
    /// [`Violation::Unproven`]. Work: at most `65 + 4096` samples.
    pub fn check_flyable(&self, limits: &FlyLimits) -> Result<(), Violation> {
        if !limits.is_valid() {
            return Err(Violation::InvalidLimits);
        }
        let n = FLY_CHECK_INTERVALS;
        let s_at = |i: usize| i as f32 / n as f32;
        // First the plain samples: most unflyable segments fail here, cheaply.
        let mut samples = [Sample {
            speed: 0.0,
            a_long: 0.0,
            a_lat: 0.0,
        }; FLY_CHECK_INTERVALS + 1];
        for (i, x) in samples.iter_mut().enumerate() {
            *x = self.sample(s_at(i));
            if let Some(v) = Self::sample_violation(limits, x, s_at(i) * self.t_max) {
                return Err(v);
            }
        }
        let mut splits_left = FLY_CHECK_MAX_SPLITS;
        for i in 0..n {
            self.refine_flyable(
                limits,
                (s_at(i), samples[i]),
                (s_at(i + 1), samples[i + 1]),
                &mut splits_left,
            )?;
        }
        Ok(())
    }

    // ------------------------------------------------------------------------------------------
    // Collision enclosure.

    /// A conservative polyline enclosure of the curve: `pieces` chords (clamped to
    /// `1..=MAX_PIECES`) over equal parameter steps `Δs = 1/pieces`, each with a deviation bound
    /// `ε = (Δs²/8)·max_piece|q''| + rounding`, so that every point of the curve lies within `ε`
    /// of its piece's chord.
    ///
    /// Why: on a piece, `e(s) = q(s) − ℓ(s)` (`ℓ` the linear interpolant of the piece's end
    /// points, a point of the chord) vanishes at both ends, so
    /// `e(s) = −∫ G(s, σ) q''(σ) dσ` with the Green's function `G ≥ 0` of `d²/ds²` whose
    /// integral is `(s − s_i)(s_{i+1} − s)/2 ≤ Δs²/8`; hence `|e| ≤ (Δs²/8)·max|q''|`.
    /// `max|q''|` on the piece is bounded by the Bernstein coefficients of `q''` restricted to
    /// it (in `s`, so `ε` is in metres; equal to `(Δt²/8)·max|p''|` with `Δt = T·Δs`).
    /// The rounding allowance `20ε_f32·(|P0|∞ + Σ|b_k|)` covers the f32 evaluation of the chord's
    /// end points and of the predicates' distances.
    pub fn polyline_bound(&self, pieces: usize) -> impl Iterator<Item = ChordBound> + '_ {
        let n = pieces.clamp(1, MAX_PIECES);
        let acc = self.acceleration_coefficients();
        let rounding = self.position_rounding();
        // The restriction's own rounding is relative to the unrestricted coefficients.
        let restrict_rounding = EVAL_ROUNDING * acc.iter().map(|c| c.norm()).sum::<f32>();
        (0..n).map(move |i| {
            let (s0, s1) = (i as f32 / n as f32, (i + 1) as f32 / n as f32);
            let ds = s1 - s0;
            let local = restrict_cubic(&acc, s0, ds);
            let max_acc = bernstein_max_cubic(&local) + restrict_rounding;
            ChordBound {
                chord: Segment::new(horner(&self.b, s0), horner(&self.b, s1)),
                epsilon: ds * ds * 0.125 * max_acc * (1.0 + 4.0 * f32::EPSILON) + rounding,
            }
        })
    }

    /// Whether the curve may come within `clearance` of the simple `polygon` (or lie inside
    /// it). **Conservative**: never `false` when the curve conflicts; it may be `true` for a
    /// curve that keeps up to `max ε` more than `clearance` away (see
    /// [`polyline_bound`](Self::polyline_bound)). Each chord is tested with the exact predicate
    /// [`predicates::conflicts_with_polygon`] at `clearance + ε`. A negative clearance counts
    /// as 0; NaN (in the clearance or a vertex) gives `true`.
    pub fn conflicts_with_polygon(
        &self,
        polygon: &(impl PolygonView + ?Sized),
        clearance: f32,
        pieces: usize,
    ) -> bool {
        let finite_vertices =
            (0..polygon.vertex_count()).all(|i| polygon.vertex(i).is_some_and(|v| v.is_finite()));
        if clearance.is_nan() || !finite_vertices {
            return true;
        }
        let clearance = clearance.max(0.0);
        self.polyline_bound(pieces).any(|c| {
            let e = clearance + c.epsilon;
            e.is_nan() || predicates::conflicts_with_polygon(&Primitive::Line(c.chord), polygon, e)
        })
    }

    /// Whether the curve may come within `clearance` of the disc (`centre`, `radius`).
    /// **Conservative** as [`conflicts_with_polygon`](Self::conflicts_with_polygon), with
    /// [`predicates::conflicts_with_circle`] at `clearance + ε`. A negative clearance counts as
    /// 0; NaN or an infinite centre gives `true`.
    pub fn conflicts_with_circle(
        &self,
        centre: Vec2,
        radius: f32,
        clearance: f32,
        pieces: usize,
    ) -> bool {
        if !centre.is_finite() || radius.is_nan() || clearance.is_nan() {
            return true;
        }
        let clearance = clearance.max(0.0);
        self.polyline_bound(pieces).any(|c| {
            let e = clearance + c.epsilon;
            e.is_nan()
                || predicates::conflicts_with_circle(&Primitive::Line(c.chord), centre, radius, e)
        })
    }
}
