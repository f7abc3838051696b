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
//! and right-hand side `(P1 − P0 − V0·T, (V1 − V0)·T, 0)`, solved with nalgebra's LU
//! decomposition with partial pivoting (backward stable: the end conditions, which are the rows
//! of the system, hold to f32 rounding of the coefficients). The segment is stored in that
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

use nalgebra::{Matrix3, Matrix3x2};

use super::predicates::{self, PolygonView};
use super::{Pose, Primitive, Segment, Vec2};

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

/// 5-point Gauss–Legendre nodes on [−1, 1].
const GL5_X: [f32; 5] = [-0.906_179_85, -0.538_469_3, 0.0, 0.538_469_3, 0.906_179_85];
/// 5-point Gauss–Legendre weights (sum 2).
const GL5_W: [f32; 5] = [
    0.236_926_88,
    0.478_628_67,
    0.568_888_9,
    0.478_628_67,
    0.236_926_88,
];

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

/// `Σ c_k s^k` by Horner's rule.
fn horner<const N: usize>(c: &[Vec2; N], s: f32) -> Vec2 {
    let mut acc = Vec2::default();
    for k in (0..N).rev() {
        acc = acc * s + c[k];
    }
    acc
}

/// The largest norm of the Bernstein coefficients of the cubic `Σ c_k u^k` on [0, 1]: an upper
/// bound of its norm there (convex-hull property). `β_i = Σ_{j≤i} C(i,j)/C(3,j)·c_j`, plus the
/// rounding of those sums (`EVAL_ROUNDING · Σ|c_j|`).
fn bernstein_max_cubic(c: &[Vec2; 4]) -> f32 {
    let b0 = c[0];
    let b1 = c[0] + c[1] * (1.0 / 3.0);
    let b2 = c[0] + c[1] * (2.0 / 3.0) + c[2] * (1.0 / 3.0);
    let b3 = c[0] + c[1] + c[2] + c[3];
    let terms = c[0].norm() + c[1].norm() + c[2].norm() + c[3].norm();
    max4(b0.norm(), b1.norm(), b2.norm(), b3.norm()) + EVAL_ROUNDING * terms
}

/// As [`bernstein_max_cubic`] for a quadratic: `β = (c0, c0 + c1/2, c0 + c1 + c2)`.
fn bernstein_max_quadratic(c: &[Vec2; 3]) -> f32 {
    let b0 = c[0];
    let b1 = c[0] + c[1] * 0.5;
    let b2 = c[0] + c[1] + c[2];
    let terms = c[0].norm() + c[1].norm() + c[2].norm();
    max4(b0.norm(), b1.norm(), b2.norm(), 0.0) + EVAL_ROUNDING * terms
}

/// Maximum of four values; NaN anywhere gives NaN (so that bounds fail closed).
fn max4(a: f32, b: f32, c: f32, d: f32) -> f32 {
    if a.is_nan() || b.is_nan() || c.is_nan() || d.is_nan() {
        return f32::NAN;
    }
    a.max(b).max(c).max(d)
}

/// The cubic `Σ c_k s^k` restricted to `[s0, s0 + h]`, as a cubic in `u ∈ [0, 1]`:
/// coefficients `h^j · p^{(j)}(s0) / j!`.
fn restrict_cubic(c: &[Vec2; 4], s0: f32, h: f32) -> [Vec2; 4] {
    let p = horner(c, s0);
    let d1 = c[1] + (c[2] * 2.0 + c[3] * (3.0 * s0)) * s0;
    let d2 = c[2] + c[3] * (3.0 * s0);
    [p, d1 * h, d2 * (h * h), c[3] * (h * h * h)]
}

/// One 5-point Gauss–Legendre rule over `[a, b]` of an integrand with two components.
fn gl5(f: &impl Fn(f32) -> [f32; 2], a: f32, b: f32) -> [f32; 2] {
    let half = 0.5 * (b - a);
    let mid = 0.5 * (a + b);
    let mut acc = [0.0f32; 2];
    for (x, w) in GL5_X.iter().zip(GL5_W.iter()) {
        let v = f(mid + half * x);
        acc[0] += w * v[0];
        acc[1] += w * v[1];
    }
    [acc[0] * half, acc[1] * half]
}

/// Result of an adaptive quadrature: the integral of both components and the error estimate of
/// the first.
#[derive(Default)]
struct Quadrature {
    value: f32,
    second: f32,
    error: f32,
    splits_left: u32,
}

/// Adaptive composite Gauss–Legendre quadrature over [0, 1] (module documentation). The
/// refinement follows the first component; the second is integrated on the same partition.
fn integrate(f: &impl Fn(f32) -> [f32; 2]) -> Quadrature {
    let m = QUADRATURE_INITIAL_INTERVALS;
    let mut coarse = [[0.0f32; 2]; QUADRATURE_INITIAL_INTERVALS];
    let mut total = 0.0f32;
    for (i, c) in coarse.iter_mut().enumerate() {
        *c = gl5(f, i as f32 / m as f32, (i + 1) as f32 / m as f32);
        total += c[0];
    }
    let density = QUADRATURE_TOLERANCE * libm::fabsf(total);
    let mut q = Quadrature {
        splits_left: QUADRATURE_MAX_SPLITS,
        ..Quadrature::default()
    };
    for (i, c) in coarse.iter().enumerate() {
        let (a, b) = (i as f32 / m as f32, (i + 1) as f32 / m as f32);
        refine(f, a, b, *c, density, 0, &mut q);
    }
    q
}

/// Compares `[a, b]`'s rule `whole` with its halves; keeps the halves or splits further.
fn refine(
    f: &impl Fn(f32) -> [f32; 2],
    a: f32,
    b: f32,
    whole: [f32; 2],
    density: f32,
    depth: u32,
    q: &mut Quadrature,
) {
    let mid = 0.5 * (a + b);
    let l = gl5(f, a, mid);
    let r = gl5(f, mid, b);
    let diff = libm::fabsf(l[0] + r[0] - whole[0]);
    // `!(diff > …)`: a NaN difference is kept (and propagates to the value) rather than split.
    if !(diff > density * (b - a)) || depth >= QUADRATURE_MAX_DEPTH || q.splits_left == 0 {
        q.value += l[0] + r[0];
        q.second += l[1] + r[1];
        q.error += diff;
        return;
    }
    q.splits_left -= 1;
    refine(f, a, mid, l, density, depth + 1, q);
    refine(f, mid, b, r, density, depth + 1, q);
}

/// Solves `M x = rhs` for the normalised Hermite matrix `M` with nalgebra's LU decomposition
/// (partial pivoting). Rows: position, velocity, acceleration at `s = 1`.
fn solve_hermite<const C: usize>(
    rhs: &nalgebra::SMatrix<f32, 3, C>,
) -> Option<nalgebra::SMatrix<f32, 3, C>> {
    #[rustfmt::skip]
    let m = Matrix3::new(
        1.0, 1.0, 1.0,
        3.0, 4.0, 5.0,
        6.0, 12.0, 20.0,
    );
    m.lu().solve(rhs)
}

/// The normalised coefficients `b_0..b_5` for duration `t`: `b0 = P0`, `b1 = V0·t`, `b2 = 0`,
/// `(b3, b4, b5) = M⁻¹ · (P1 − P0 − V0·t, (V1 − V0)·t, 0)` per axis.
fn solve_coefficients(
    start: &LineElement,
    end: &LineElement,
    t: f32,
) -> Result<[Vec2; 6], HermiteError> {
    let (p0, v0, p1, v1) = (start.position, start.velocity, end.position, end.velocity);
    let d = p1 - p0 - v0 * t;
    let e = (v1 - v0) * t;
    #[rustfmt::skip]
    let rhs = Matrix3x2::new(
        d.x, d.y,
        e.x, e.y,
        0.0, 0.0,
    );
    let x = solve_hermite(&rhs).ok_or(HermiteError::SolveFailed)?;
    Ok([
        p0,
        v0 * t,
        Vec2::default(),
        Vec2::new(x[(0, 0)], x[(0, 1)]),
        Vec2::new(x[(1, 0)], x[(1, 1)]),
        Vec2::new(x[(2, 0)], x[(2, 1)]),
    ])
}

/// Flight quantities at one sample.
#[derive(Clone, Copy)]
struct Sample {
    speed: f32,
    a_long: f32,
    a_lat: f32,
}

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

    #[allow(clippy::too_many_arguments)]
    fn refine_flyable(
        &self,
        limits: &FlyLimits,
        sa: f32,
        xa: &Sample,
        sb: f32,
        xb: &Sample,
        depth: u32,
        splits_left: &mut u32,
    ) -> Result<(), Violation> {
        let Err((limit, bound)) = self.certify(limits, xa, xb, (sb - sa) * self.t_max) else {
            return Ok(());
        };
        let sm = 0.5 * (sa + sb);
        if depth >= FLY_CHECK_MAX_DEPTH || *splits_left == 0 {
            return Err(Violation::Unproven {
                limit,
                t: sm * self.t_max,
                bound,
            });
        }
        *splits_left -= 1;
        let xm = self.sample(sm);
        if let Some(v) = Self::sample_violation(limits, &xm, sm * self.t_max) {
            return Err(v);
        }
        self.refine_flyable(limits, sa, xa, sm, &xm, depth + 1, splits_left)?;
        self.refine_flyable(limits, sm, &xm, sb, xb, depth + 1, splits_left)
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
                s_at(i),
                &samples[i],
                s_at(i + 1),
                &samples[i + 1],
                0,
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
