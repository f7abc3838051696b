//! Quintic Hermite segments between line elements: the edges of landmark networks (Babel 2014).
//!
//! A [`LineElement`] is "fly through this point with this velocity" (the velocity has the
//! nominal speed; the acceleration there is zero). A [`HermiteSegment`] joins two of them with
//! the quintic polynomial
//!
//! ```text
//! p(t) = Σ_{k=0..5} c_k t^k,  t ∈ [0, T],
//! p(0) = P0, p'(0) = V0, p''(0) = 0,   p(T) = P1, p'(T) = V1, p''(T) = 0.
//! ```
//!
//! ## The coefficients
//! The start conditions give `c0 = P0`, `c1 = V0`, `c2 = 0` in closed form. The end conditions
//! are the 3 × 3 system in `T` (per axis)
//!
//! ```text
//! | T³    T⁴     T⁵   | |c3|   | P1 − P0 − V0·T |
//! | 3T²   4T³    5T⁴  | |c4| = | V1 − V0        |
//! | 6T    12T²   20T³ | |c5|   | 0              |
//! ```
//!
//! whose condition number grows with `T` (its entries span `T` to `20T³`). Scaling the unknowns to
//! `b_k = c_k T^k` and the rows by `(1, T, T²)` turns it into the same system with the constant,
//! well-conditioned matrix `M = [[1, 1, 1], [3, 4, 5], [6, 12, 20]]` (condition number ≈ 524)
//! and right-hand side `(P1 − P0 − V0·T, (V1 − V0)·T, 0)`, solved with `M`'s exact inverse
//! (`math::solve_hermite`: a constant matrix product, every entry of `M⁻¹` exact in f32). The segment is stored in that
//! normalised form, `p(t) = q(t/T)` with `q(s) = Σ b_k s^k`, `b_k = c_k T^k`, which evaluates
//! without the cancellation of large powers of `t`. The exact solution is the quintic with
//! assigned end positions, velocities and accelerations, e.g. Biagiotti & Melchiorri,
//! *Trajectory Planning for Automatic Machines and Robots* (Springer 2008), the polynomial of
//! degree five, with both accelerations zero:
//! `c3 = (20h − (8V1 + 12V0)T) / (2T³)`, `c4 = (−30h + (14V1 + 16V0)T) / (2T⁴)`,
//! `c5 = (12h − 6(V1 + V0)T) / (2T⁵)`, `h = P1 − P0` (`M⁻¹ = [[10, −4, ½], [−15, 7, −1], [6, −3, ½]]`).
//!
//! ## The duration `T`
//! `T` is chosen so that the segment is flown at the nominal speed `v` on average: its length
//! equals `v·T`. With `b(T) = A + T·B` (`A` from `P1 − P0`, `B` from the velocities), the length
//! `L(T) = ∫₀¹ |A'(s) + T·B'(s)| ds` is a convex function of `T` (an integral of norms of
//! functions affine in `T`), and so is `g(T) = L(T) − v·T`, with `g(chord/v) ≥ 0` because no
//! curve is shorter than its chord. Newton's method on a convex function started where it is
//! positive increases monotonically to its first root, never past it (each tangent lies below
//! the graph); a step whose slope `g'` is not negative proves that `g > 0` for every larger `T`,
//! i.e. that no duration flies this pair at the nominal speed ([`HermiteError::NoSolution`]).
//! The quadrature below is a positive-weighted sum of the same norms, so on a fixed partition
//! the same holds for the discretised `g` (the adaptive partition may differ between steps,
//! which moves `g` by at most the quadrature tolerance). Each step solves the coefficients at its `T` directly (the f32 sum
//! `A + T·B` would cancel badly for near-straight pairs) and integrates `|q'|` and
//! `dL/dT = ∫ q'·B'/|q'| ds` on the same partition. The iteration starts at `T = chord/v` and
//! stops when `|g| ≤ 2·10⁻⁶·v·T` (a few steps: building a segment takes ≈ 4–12 µs on the
//! host, see the host test).
//!
//! ## The length
//! Adaptive composite **5-point Gauss–Legendre** quadrature of `|q'(s)|` over `s ∈ [0, 1]`
//! (exact for polynomials of degree 9): 8 initial sub-intervals; each sub-interval `I` is
//! compared with the sum over its two halves (5 points against 2 × 5) and split further while
//! `|Q(halves) − Q(I)| > 10⁻⁶ · L₀ · |I|` (`L₀` the 8-interval value), down to depth 10 and at
//! most [`QUADRATURE_MAX_SPLITS`] splits. The halves' value is kept, and
//! [`HermiteSegment::length_error_estimate`] is the sum of the `|Q(halves) − Q(I)|` of the kept
//! intervals: for a smooth integrand the halves' own error is about 2⁻¹⁰ of that, so the
//! estimate is a generous bound there; where the speed almost vanishes (a near-cusp, `|q'|`
//! almost a kink) the refinement concentrates at the kink. Measured against dense f64 polylines
//! (host test `hermite.rs`): relative error below 10⁻⁶, within estimate + f32 rounding.
//!
//! ## Bounds
//! Maxima of `|p''|` and `|p'''|` over the segment (or a piece of it) are bounded by the largest
//! Bernstein coefficient of the polynomial on that interval: a polynomial curve lies in the
//! convex hull of its Bernstein control points, so its norm is at most their largest norm.
//! * [`HermiteSegment::check_flyable`] certifies the limits between samples with these
//!   derivative bounds (see its documentation for the exact bounds).
//! * [`HermiteSegment::polyline_bound`] covers the curve by chords with a deviation `ε`
//!   (`(Δs²/8)·max|q''|` on the piece plus a rounding allowance), so the exact line predicates
//!   with clearance `+ ε` never miss a conflict of the curve.
//!
//! Nothing here panics or allocates; NaN inputs give errors, `None`, a violation or (for
//! collision tests) a conflict.

use nalgebra::Matrix3x2;

use super::{Pose, Segment, Vec2};

mod checks;
mod math;

use math::{
    bernstein_max_cubic, bernstein_max_quadratic, horner, integrate, restrict_cubic,
    solve_coefficients, solve_hermite,
};

/// Initial sub-intervals of the adaptive length quadrature.
pub const QUADRATURE_INITIAL_INTERVALS: usize = 8;
/// Deepest bisection of an initial sub-interval (its width then is 1/8192 of the segment).
pub const QUADRATURE_MAX_DEPTH: u32 = 10;
/// Relative tolerance of the length quadrature (per unit of the normalised parameter).
pub const QUADRATURE_TOLERANCE: f32 = 1e-6;
/// Most bisections of one length quadrature. A quadrature therefore evaluates `|q'|` at most
/// `5·8 + 10·(8 + 2·512)` = 10,360 times; typical segments need 150–500.
pub const QUADRATURE_MAX_SPLITS: u32 = 512;

/// Most Newton steps for the duration.
pub const NEWTON_MAX_STEPS: u32 = 40;
/// Newton stops when `|L(T) − v·T| ≤ NEWTON_TOLERANCE · v·T`.
pub const NEWTON_TOLERANCE: f32 = 2e-6;

/// Initial equal intervals of [`HermiteSegment::check_flyable`].
pub const FLY_CHECK_INTERVALS: usize = 64;
/// Deepest bisection of one of those intervals in [`HermiteSegment::check_flyable`].
pub const FLY_CHECK_MAX_DEPTH: u32 = 12;
/// Most bisections (each one more sample) in one [`HermiteSegment::check_flyable`]; the check
/// evaluates at most `FLY_CHECK_INTERVALS + 1 + FLY_CHECK_MAX_SPLITS` samples.
pub const FLY_CHECK_MAX_SPLITS: u32 = 4096;

/// Most chords of a [`HermiteSegment::polyline_bound`] (larger requests are clamped).
pub const MAX_PIECES: usize = 4096;

/// Sub-intervals of [`HermiteSegment::speed_range`].
pub const SPEED_RANGE_INTERVALS: usize = 256;

/// Rounding allowance for speeds and accelerations (and the Bernstein bounds), relative to the
/// sum of the magnitudes of the terms summed. Derivation (unit roundoff `u = ε/2`, Higham's
/// `γ_n = nu/(1 − nu)`): the derivative coefficients `k·b_k` round once (`u`); Horner's rule of
/// degree ≤ 4 at an exact `s` (the samples are dyadic) errs by at most `γ_8 ≈ 4ε` of `Σ|c_j|s^j`
/// per component; a vector's two components then err by at most `√2·(4ε + u)·Σ|c_j| < 8ε·Σ|c_j|`.
/// The remaining steps (scaling by `1/T`, norms, dot and cross products, the division by `|v|`)
/// err relative to the result and are added as separate terms (`2ε·v_max` for speeds, `5ε·A`
/// for accelerations, see `certify`).
const EVAL_ROUNDING: f32 = 8.0 * f32::EPSILON;

/// Rounding allowance for positions, relative to `|P0|∞ + Σ|b_k|`: Horner's rule of degree 5
/// (`γ_10 ≈ 5ε` per component, `< 7.1ε` for the vector) plus the f32 distance computations of
/// the exact predicates (a few ε of the coordinates' magnitude; their host test allows ≈ 8ε).
const POSITION_ROUNDING: f32 = 20.0 * f32::EPSILON;

/// Flight through `position` with `velocity` (of nominal speed), with zero acceleration there.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct LineElement {
    /// Position, metres.
    pub position: Vec2,
    /// Velocity, metres per second.
    pub velocity: Vec2,
}

impl LineElement {
    /// The line element at `position` with `velocity`.
    pub const fn new(position: Vec2, velocity: Vec2) -> Self {
        Self { position, velocity }
    }

    /// The line element flying `pose` at `speed`.
    pub fn from_pose(pose: &Pose, speed: f32) -> Self {
        Self {
            position: pose.position,
            velocity: pose.direction() * speed,
        }
    }

    /// Position and velocity are finite.
    pub fn is_finite(&self) -> bool {
        self.position.is_finite() && self.velocity.is_finite()
    }
}

/// Why a [`HermiteSegment`] could not be built.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum HermiteError {
    /// A position, velocity or the speed is NaN or infinite (or the distance overflows).
    NonFinite,
    /// The nominal speed (or, for [`HermiteSegment::with_duration`], the duration) is zero or
    /// negative.
    NonPositiveSpeed,
    /// Both line elements lie at the same position: every duration `T` then gives a curve of
    /// length proportional to `T`, so `L(T) = v·T` has no isolated solution.
    CoincidentPositions,
    /// No duration flies the pair at the nominal speed on average: the curve's average speed
    /// exceeds `v` for every `T` (proved by the convexity of `L(T) − v·T`, see the module).
    NoSolution,
    /// The duration iteration did not converge within [`NEWTON_MAX_STEPS`] (a near-double
    /// root), or left the finite positive numbers.
    NoConvergence,
    /// The LU solve reported a singular matrix (cannot happen for the constant matrix `M`;
    /// reported instead of panicking).
    SolveFailed,
}

impl core::fmt::Display for HermiteError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        let s = match self {
            HermiteError::NonFinite => "a position, velocity or the speed is not finite",
            HermiteError::NonPositiveSpeed => "the nominal speed is not positive",
            HermiteError::CoincidentPositions => "both line elements lie at the same position",
            HermiteError::NoSolution => "no duration flies the pair at the nominal speed",
            HermiteError::NoConvergence => "the duration iteration did not converge",
            HermiteError::SolveFailed => "the 3x3 Hermite system could not be solved",
        };
        f.write_str(s)
    }
}

#[cfg(feature = "std")]
impl std::error::Error for HermiteError {}

/// The vehicle's limits for [`HermiteSegment::check_flyable`].
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct FlyLimits {
    /// Lowest airspeed, m/s (positive: a fixed wing stalls below it).
    pub v_min: f32,
    /// Highest airspeed, m/s (≥ `v_min`).
    pub v_max: f32,
    /// Lowest longitudinal acceleration (the strongest deceleration, usually negative), m/s².
    pub a_long_min: f32,
    /// Highest longitudinal acceleration, m/s² (≥ `a_long_min`).
    pub a_long_max: f32,
    /// Highest lateral acceleration magnitude, m/s² (≥ 0).
    pub a_lat_max: f32,
}

impl FlyLimits {
    /// All finite, `0 < v_min ≤ v_max`, `a_long_min ≤ a_long_max`, `a_lat_max ≥ 0`.
    pub fn is_valid(&self) -> bool {
        let all = [
            self.v_min,
            self.v_max,
            self.a_long_min,
            self.a_long_max,
            self.a_lat_max,
        ];
        all.iter().all(|x| x.is_finite())
            && self.v_min > 0.0
            && self.v_max >= self.v_min
            && self.a_long_max >= self.a_long_min
            && self.a_lat_max >= 0.0
    }
}

/// One limit of [`FlyLimits`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Limit {
    /// `v_min`.
    SpeedMin,
    /// `v_max`.
    SpeedMax,
    /// `a_long_min`.
    LongitudinalMin,
    /// `a_long_max`.
    LongitudinalMax,
    /// `a_lat_max`.
    Lateral,
}

/// Why [`HermiteSegment::check_flyable`] rejected a segment.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Violation {
    /// The limits are not valid (see [`FlyLimits::is_valid`]).
    InvalidLimits,
    /// A sample at time `t` has `value` beyond `limit` (as computed in f32).
    Exceeds {
        /// The limit.
        limit: Limit,
        /// Time from the segment's start, s.
        t: f32,
        /// The sampled speed or acceleration.
        value: f32,
    },
    /// No sample exceeds a limit, but within the work limits the bounds could not prove that
    /// the quantity stays inside `limit` around time `t`: its enclosure reached `bound`. Such a
    /// segment touches the limit within the bounds' margin; the check rejects it (conservative).
    Unproven {
        /// The limit.
        limit: Limit,
        /// Time from the segment's start at the middle of the unproven interval, s.
        t: f32,
        /// The enclosure's end that crossed the limit.
        bound: f32,
    },
}

/// A chord of a [`HermiteSegment::polyline_bound`]: every point of the curve on this piece lies
/// within `epsilon` of `chord`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ChordBound {
    /// From the curve's point at the piece's start to the one at its end.
    pub chord: Segment,
    /// The deviation bound, metres.
    pub epsilon: f32,
}

/// A quintic Hermite segment between two line elements, flown at the nominal speed on average.
/// See the module documentation for the construction and the bounds.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct HermiteSegment {
    /// Normalised coefficients `b_k = c_k T^k`: `p(t) = Σ b_k (t/T)^k`.
    b: [Vec2; 6],
    /// Duration `T`, s.
    t_max: f32,
    /// Nominal speed, m/s.
    v_nominal: f32,
    /// Length, m.
    length: f32,
    /// Quadrature error estimate of `length`, m.
    length_error: f32,
    /// Upper bound of `|p''(t)|` over the segment, m/s².
    accel_bound: f32,
    /// Upper bound of `|p'''(t)|` over the segment, m/s³.
    jerk_bound: f32,
}

// ----------------------------------------------------------------------------------------------
// Small polynomial helpers on vector coefficients (index = power).

impl HermiteSegment {
    /// The segment from `start` to `end` flown at `v_nominal` on average (module documentation).
    pub fn new(
        start: &LineElement,
        end: &LineElement,
        v_nominal: f32,
    ) -> Result<Self, HermiteError> {
        if !start.is_finite() || !end.is_finite() || !v_nominal.is_finite() {
            return Err(HermiteError::NonFinite);
        }
        if !(v_nominal > 0.0) {
            return Err(HermiteError::NonPositiveSpeed);
        }
        let (p0, v0, p1, v1) = (start.position, start.velocity, end.position, end.velocity);
        let h = p1 - p0;
        let chord = h.norm();
        if !chord.is_finite() || !(v0 - v1).is_finite() {
            return Err(HermiteError::NonFinite);
        }
        if !(chord > 0.0) {
            return Err(HermiteError::CoincidentPositions);
        }

        // dq'/dT = B'(s): b1 = V0·T and b3..b5 = M⁻¹·(−V0·T, (V1 − V0)·T, 0) are linear in T.
        #[rustfmt::skip]
        let rhs = Matrix3x2::new(
            -v0.x, -v0.y,
            v1.x - v0.x, v1.y - v0.y,
            0.0, 0.0,
        );
        let x = solve_hermite(&rhs).ok_or(HermiteError::SolveFailed)?;
        let b_d = [
            v0,
            Vec2::default(),
            Vec2::new(x[(0, 0)], x[(0, 1)]) * 3.0,
            Vec2::new(x[(1, 0)], x[(1, 1)]) * 4.0,
            Vec2::new(x[(2, 0)], x[(2, 1)]) * 5.0,
        ];

        let mut t = chord / v_nominal;
        if !t.is_finite() || !(t > 0.0) {
            return Err(HermiteError::NonFinite);
        }
        let mut converged = false;
        for _ in 0..NEWTON_MAX_STEPS {
            // The coefficients at this T solved directly (not as A + T·B, whose f32 sum would
            // not keep the end conditions: for a near-straight pair b3..b5 cancel).
            let b = solve_coefficients(start, end, t)?;
            let vel = [b[1], b[2] * 2.0, b[3] * 3.0, b[4] * 4.0, b[5] * 5.0];
            let q = integrate(&|s: f32| {
                let d = horner(&vel, s);
                let n = d.norm();
                // dL/dT integrand: q'·B'/|q'| (0 at a zero of q', a subgradient of |·| there).
                let dn = if n > 0.0 {
                    d.dot(horner(&b_d, s)) / n
                } else {
                    0.0
                };
                [n, dn]
            });
            let g = q.value - v_nominal * t;
            if !g.is_finite() || !q.second.is_finite() {
                return Err(HermiteError::NoConvergence);
            }
            if libm::fabsf(g) <= NEWTON_TOLERANCE * v_nominal * t {
                converged = true;
                break;
            }
            let slope = q.second - v_nominal;
            if !(slope < 0.0) {
                return Err(if g > 0.0 {
                    HermiteError::NoSolution
                } else {
                    HermiteError::NoConvergence
                });
            }
            let next = t - g / slope;
            if !next.is_finite() || !(next > 0.0) {
                return Err(HermiteError::NoConvergence);
            }
            t = next;
        }
        if !converged {
            return Err(HermiteError::NoConvergence);
        }
        Self::with_duration(start, end, v_nominal, t)
    }

    /// The segment from `start` to `end` with the given duration `t_max` (not chosen for the
    /// nominal speed; `v_nominal` is only recorded). For tests and for callers that fix the
    /// timing themselves.
    pub fn with_duration(
        start: &LineElement,
        end: &LineElement,
        v_nominal: f32,
        t_max: f32,
    ) -> Result<Self, HermiteError> {
        if !start.is_finite() || !end.is_finite() || !v_nominal.is_finite() || !t_max.is_finite() {
            return Err(HermiteError::NonFinite);
        }
        if !(v_nominal > 0.0) || !(t_max > 0.0) {
            return Err(HermiteError::NonPositiveSpeed);
        }
        let b = solve_coefficients(start, end, t_max)?;
        if !b.iter().all(|c| c.is_finite()) {
            return Err(HermiteError::NonFinite);
        }
        let mut seg = Self {
            b,
            t_max,
            v_nominal,
            length: 0.0,
            length_error: 0.0,
            accel_bound: 0.0,
            jerk_bound: 0.0,
        };
        let vel = seg.velocity_coefficients();
        let q = integrate(&|s: f32| [horner(&vel, s).norm(), 0.0]);
        seg.length = q.value;
        seg.length_error = q.error;
        let t2 = t_max * t_max;
        // (1 + 4ε): the divisions.
        seg.accel_bound =
            bernstein_max_cubic(&seg.acceleration_coefficients()) / t2 * (1.0 + 4.0 * f32::EPSILON);
        seg.jerk_bound = bernstein_max_quadratic(&seg.jerk_coefficients()) / (t2 * t_max)
            * (1.0 + 4.0 * f32::EPSILON);
        if !seg.length.is_finite() || !seg.accel_bound.is_finite() || !seg.jerk_bound.is_finite() {
            return Err(HermiteError::NonFinite);
        }
        Ok(seg)
    }

    // ------------------------------------------------------------------------------------------
    // Coefficients.

    /// `d q / ds` as coefficients of `s^0..s^4`.
    fn velocity_coefficients(&self) -> [Vec2; 5] {
        let b = &self.b;
        [b[1], b[2] * 2.0, b[3] * 3.0, b[4] * 4.0, b[5] * 5.0]
    }

    /// `d² q / ds²` as coefficients of `s^0..s^3`.
    fn acceleration_coefficients(&self) -> [Vec2; 4] {
        let b = &self.b;
        [b[2] * 2.0, b[3] * 6.0, b[4] * 12.0, b[5] * 20.0]
    }

    /// `d³ q / ds³` as coefficients of `s^0..s^2`.
    fn jerk_coefficients(&self) -> [Vec2; 3] {
        let b = &self.b;
        [b[3] * 6.0, b[4] * 24.0, b[5] * 60.0]
    }

    /// The coefficients `c_0..c_5` of `p(t) = Σ c_k t^k` (computed as `b_k / T^k`).
    pub fn coefficients(&self) -> [Vec2; 6] {
        let mut c = self.b;
        let mut tk = 1.0f32;
        for ck in c.iter_mut() {
            *ck = *ck * (1.0 / tk);
            tk *= self.t_max;
        }
        c
    }

    /// The normalised coefficients `b_k = c_k T^k` of `p(t) = Σ b_k (t/T)^k`: what the segment
    /// stores and evaluates.
    pub fn normalized_coefficients(&self) -> [Vec2; 6] {
        self.b
    }

    // ------------------------------------------------------------------------------------------
    // Scalars.

    /// The duration `T`, s.
    pub fn t_max(&self) -> f32 {
        self.t_max
    }

    /// The nominal speed the segment was built for, m/s.
    pub fn v_nominal(&self) -> f32 {
        self.v_nominal
    }

    /// The length, metres (adaptive Gauss–Legendre quadrature, module documentation).
    pub fn length(&self) -> f32 {
        self.length
    }

    /// The quadrature's error estimate of [`length`](Self::length), metres (module
    /// documentation). f32 rounding of the sum adds up to about 10⁻⁶ of the length.
    pub fn length_error_estimate(&self) -> f32 {
        self.length_error
    }

    /// An upper bound of `|p''(t)|` over the segment, m/s² (Bernstein coefficients of `q''`).
    pub fn acceleration_bound(&self) -> f32 {
        self.accel_bound
    }

    /// An upper bound of `|p'''(t)|` over the segment, m/s³ (Bernstein coefficients of `q'''`).
    pub fn jerk_bound(&self) -> f32 {
        self.jerk_bound
    }

    /// The start line element as the segment reproduces it.
    pub fn start(&self) -> LineElement {
        LineElement::new(self.b[0], self.b[1] * (1.0 / self.t_max))
    }

    /// The end line element as the segment reproduces it (to f32 rounding).
    pub fn end(&self) -> LineElement {
        let s = 1.0;
        LineElement::new(
            horner(&self.b, s),
            horner(&self.velocity_coefficients(), s) * (1.0 / self.t_max),
        )
    }

    // ------------------------------------------------------------------------------------------
    // Evaluation. `t` is clamped to [0, T]; NaN gives None.

    fn param(&self, t: f32) -> Option<f32> {
        if t.is_nan() {
            return None;
        }
        Some((t / self.t_max).clamp(0.0, 1.0))
    }

    /// The position at time `t` (clamped to [0, T]); `None` for NaN.
    pub fn position(&self, t: f32) -> Option<Vec2> {
        let s = self.param(t)?;
        Some(horner(&self.b, s))
    }

    /// The velocity at time `t` (clamped to [0, T]); `None` for NaN.
    pub fn velocity(&self, t: f32) -> Option<Vec2> {
        let s = self.param(t)?;
        Some(horner(&self.velocity_coefficients(), s) * (1.0 / self.t_max))
    }

    /// The acceleration at time `t` (clamped to [0, T]); `None` for NaN.
    pub fn acceleration(&self, t: f32) -> Option<Vec2> {
        let s = self.param(t)?;
        let t2 = self.t_max * self.t_max;
        Some(horner(&self.acceleration_coefficients(), s) * (1.0 / t2))
    }

    /// The speed `|p'(t)|` at time `t` (clamped); `None` for NaN.
    pub fn speed(&self, t: f32) -> Option<f32> {
        Some(self.velocity(t)?.norm())
    }

    /// The lateral acceleration `|v × a| / |v|` at time `t` (clamped); `None` for NaN or where
    /// the speed is zero.
    pub fn lateral_acceleration(&self, t: f32) -> Option<f32> {
        let (v, a) = (self.velocity(t)?, self.acceleration(t)?);
        let n = v.norm();
        (n > 0.0).then(|| libm::fabsf(v.cross(a)) / n)
    }

    /// The longitudinal acceleration `(v · a) / |v|` at time `t` (clamped); `None` for NaN or
    /// where the speed is zero.
    pub fn longitudinal_acceleration(&self, t: f32) -> Option<f32> {
        let (v, a) = (self.velocity(t)?, self.acceleration(t)?);
        let n = v.norm();
        (n > 0.0).then(|| v.dot(a) / n)
    }

    /// An enclosure `(lo, hi)` of the speed over the whole segment: every speed lies in it.
    /// From [`SPEED_RANGE_INTERVALS`] equal intervals with endpoint speeds `f_a`, `f_b` and
    /// `|d|v|/dt| ≤ |a| ≤ A` ([`acceleration_bound`](Self::acceleration_bound)): on an interval
    /// of duration `h`, `|v|` lies within `(f_a + f_b)/2 ± A·h/2` (the lower envelope of the two
    /// Lipschitz cones meets there), plus the rounding allowance. So each end is within
    /// `A·T/512` (plus rounding) of the true extreme.
    pub fn speed_range(&self) -> (f32, f32) {
        let n = SPEED_RANGE_INTERVALS;
        let margin = 0.5 * self.accel_bound * (self.t_max / n as f32) + self.speed_rounding();
        let vel = self.velocity_coefficients();
        let speed_at = |i: usize| horner(&vel, i as f32 / n as f32).norm() / self.t_max;
        let (mut lo, mut hi) = (f32::INFINITY, 0.0f32);
        let mut prev = speed_at(0);
        for i in 1..=n {
            let next = speed_at(i);
            let mid = 0.5 * (prev + next);
            let m = margin + 2.0 * f32::EPSILON * mid;
            lo = lo.min(mid - m);
            hi = hi.max(mid + m);
            prev = next;
        }
        (lo.max(0.0), hi)
    }

    /// An axis-aligned box `(min, max)` that contains the whole curve: the box of the
    /// Bernstein control points of `q` (convex-hull property), widened by the rounding
    /// allowance.
    pub fn bounding_box(&self) -> (Vec2, Vec2) {
        let b = &self.b;
        // Bernstein coefficients of a quintic: β_i = Σ_{j≤i} C(i,j)/C(5,j)·b_j.
        const INV_C5: [f32; 6] = [1.0, 0.2, 0.1, 0.1, 0.2, 1.0];
        const BINOM: [[f32; 6]; 6] = [
            [1.0, 0.0, 0.0, 0.0, 0.0, 0.0],
            [1.0, 1.0, 0.0, 0.0, 0.0, 0.0],
            [1.0, 2.0, 1.0, 0.0, 0.0, 0.0],
            [1.0, 3.0, 3.0, 1.0, 0.0, 0.0],
            [1.0, 4.0, 6.0, 4.0, 1.0, 0.0],
            [1.0, 5.0, 10.0, 10.0, 5.0, 1.0],
        ];
        let mut lo = Vec2::new(f32::INFINITY, f32::INFINITY);
        let mut hi = Vec2::new(f32::NEG_INFINITY, f32::NEG_INFINITY);
        for row in BINOM.iter() {
            let mut beta = Vec2::default();
            for (j, c) in row.iter().enumerate() {
                beta = beta + b[j] * (c * INV_C5[j]);
            }
            lo = Vec2::new(lo.x.min(beta.x), lo.y.min(beta.y));
            hi = Vec2::new(hi.x.max(beta.x), hi.y.max(beta.y));
        }
        let r = self.position_rounding();
        (lo - Vec2::new(r, r), hi + Vec2::new(r, r))
    }

    // ------------------------------------------------------------------------------------------
    // Rounding allowances (absolute), from the magnitudes of the terms summed.

    /// Positions: `POSITION_ROUNDING · (|P0|∞ + Σ_{k≥1} |b_k|)` metres.
    fn position_rounding(&self) -> f32 {
        let p0 = self.b[0];
        let mut m = libm::fabsf(p0.x).max(libm::fabsf(p0.y));
        for c in &self.b[1..] {
            m += c.norm();
        }
        POSITION_ROUNDING * m
    }

    /// Speeds, the terms' part: `EVAL_ROUNDING · Σ k|b_k| / T` m/s.
    fn speed_rounding(&self) -> f32 {
        let m: f32 = self.velocity_coefficients().iter().map(|c| c.norm()).sum();
        EVAL_ROUNDING * m / self.t_max
    }

    /// Accelerations, the terms' part: `EVAL_ROUNDING · Σ k(k−1)|b_k| / T²` m/s².
    fn accel_rounding(&self) -> f32 {
        let m: f32 = self
            .acceleration_coefficients()
            .iter()
            .map(|c| c.norm())
            .sum();
        EVAL_ROUNDING * m / (self.t_max * self.t_max)
    }
}
