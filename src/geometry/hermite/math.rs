//! The numerics of Hermite segments: polynomial evaluation, Bernstein bounds, the adaptive
//! Gauss–Legendre length and the normalised coefficient solve (the module documentation of
//! [`super`] gives the equations and bounds).

use super::{
    HermiteError, LineElement, EVAL_ROUNDING, QUADRATURE_INITIAL_INTERVALS, QUADRATURE_MAX_DEPTH,
    QUADRATURE_MAX_SPLITS, QUADRATURE_TOLERANCE,
};
use crate::geometry::Vec2;
use nalgebra::{Matrix3, Matrix3x2};

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

/// `Σ c_k s^k` by Horner's rule.
pub(super) fn horner<const N: usize>(c: &[Vec2; N], s: f32) -> Vec2 {
    let mut acc = Vec2::default();
    for k in (0..N).rev() {
        acc = acc * s + c[k];
    }
    acc
}

/// The largest norm of the Bernstein coefficients of the cubic `Σ c_k u^k` on [0, 1]: an upper
/// bound of its norm there (convex-hull property). `β_i = Σ_{j≤i} C(i,j)/C(3,j)·c_j`, plus the
/// rounding of those sums (`EVAL_ROUNDING · Σ|c_j|`).
pub(super) fn bernstein_max_cubic(c: &[Vec2; 4]) -> f32 {
    let b0 = c[0];
    let b1 = c[0] + c[1] * (1.0 / 3.0);
    let b2 = c[0] + c[1] * (2.0 / 3.0) + c[2] * (1.0 / 3.0);
    let b3 = c[0] + c[1] + c[2] + c[3];
    let terms = c[0].norm() + c[1].norm() + c[2].norm() + c[3].norm();
    max4(b0.norm(), b1.norm(), b2.norm(), b3.norm()) + EVAL_ROUNDING * terms
}

/// As [`bernstein_max_cubic`] for a quadratic: `β = (c0, c0 + c1/2, c0 + c1 + c2)`.
pub(super) fn bernstein_max_quadratic(c: &[Vec2; 3]) -> f32 {
    let b0 = c[0];
    let b1 = c[0] + c[1] * 0.5;
    let b2 = c[0] + c[1] + c[2];
    let terms = c[0].norm() + c[1].norm() + c[2].norm();
    max4(b0.norm(), b1.norm(), b2.norm(), 0.0) + EVAL_ROUNDING * terms
}

/// Maximum of four values; NaN anywhere gives NaN (so that bounds fail closed).
pub(super) fn max4(a: f32, b: f32, c: f32, d: f32) -> f32 {
    if a.is_nan() || b.is_nan() || c.is_nan() || d.is_nan() {
        return f32::NAN;
    }
    a.max(b).max(c).max(d)
}

/// The cubic `Σ c_k s^k` restricted to `[s0, s0 + h]`, as a cubic in `u ∈ [0, 1]`:
/// coefficients `h^j · p^{(j)}(s0) / j!`.
pub(super) fn restrict_cubic(c: &[Vec2; 4], s0: f32, h: f32) -> [Vec2; 4] {
    let p = horner(c, s0);
    let d1 = c[1] + (c[2] * 2.0 + c[3] * (3.0 * s0)) * s0;
    let d2 = c[2] + c[3] * (3.0 * s0);
    [p, d1 * h, d2 * (h * h), c[3] * (h * h * h)]
}

/// One 5-point Gauss–Legendre rule over `[a, b]` of an integrand with two components.
pub(super) fn gl5(f: &impl Fn(f32) -> [f32; 2], a: f32, b: f32) -> [f32; 2] {
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
pub(super) struct Quadrature {
    pub(super) value: f32,
    pub(super) second: f32,
    pub(super) error: f32,
    pub(super) splits_left: u32,
}

/// Adaptive composite Gauss–Legendre quadrature over [0, 1] (module documentation). The
/// refinement follows the first component; the second is integrated on the same partition.
pub(super) fn integrate(f: &impl Fn(f32) -> [f32; 2]) -> Quadrature {
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

/// Compares `[a, b]`'s rule `whole` with its halves; keeps the halves or splits further,
/// depth first and left half first, with an explicit stack rather than recursion: each level
/// leaves at most its right half pending, so [`QUADRATURE_MAX_DEPTH`] + 1 entries suffice.
pub(super) fn refine(
    f: &impl Fn(f32) -> [f32; 2],
    a: f32,
    b: f32,
    whole: [f32; 2],
    density: f32,
    depth: u32,
    q: &mut Quadrature,
) {
    const PENDING: usize = QUADRATURE_MAX_DEPTH as usize + 2;
    let mut pending = [(0.0f32, 0.0f32, [0.0f32; 2], 0u32); PENDING];
    let mut len = 0usize;
    if let Some(slot) = pending.get_mut(len) {
        *slot = (a, b, whole, depth);
        len += 1;
    }
    while let Some(&(a, b, whole, depth)) = len.checked_sub(1).and_then(|i| pending.get(i)) {
        len -= 1;
        let mid = 0.5 * (a + b);
        let l = gl5(f, a, mid);
        let r = gl5(f, mid, b);
        let diff = libm::fabsf(l[0] + r[0] - whole[0]);
        // `!(diff > …)`: a NaN difference is kept (and propagates to the value) rather than
        // split. A full stack (unreachable: see above) keeps the halves too.
        if !(diff > density * (b - a))
            || depth >= QUADRATURE_MAX_DEPTH
            || q.splits_left == 0
            || len + 2 > PENDING
        {
            q.value += l[0] + r[0];
            q.second += l[1] + r[1];
            q.error += diff;
            continue;
        }
        q.splits_left -= 1;
        // The right half below the left: the left is refined first, as a recursion would.
        for half in [(mid, b, r, depth + 1), (a, mid, l, depth + 1)] {
            if let Some(slot) = pending.get_mut(len) {
                *slot = half;
                len += 1;
            }
        }
    }
}

/// Solves `M x = rhs` for the normalised Hermite matrix `M = [[1, 1, 1], [3, 4, 5], [6, 12,
/// 20]]` (rows: position, velocity, acceleration at `s = 1`) as `x = M⁻¹ rhs`, with the exact
/// inverse `M⁻¹ = [[10, −4, 1/2], [−15, 7, −1], [6, −3, 1/2]]` (det M = 2, adjugate / 2; every
/// entry exact in f32). One constant matrix product: no pivoting, nothing that can fail or
/// panic, and each entry of `x` is three products summed, within `3ε·|M⁻¹|·|rhs|` of the
/// exact solution. `None` never (the signature keeps the callers' error path).
pub(super) fn solve_hermite<const C: usize>(
    rhs: &nalgebra::SMatrix<f32, 3, C>,
) -> Option<nalgebra::SMatrix<f32, 3, C>> {
    #[rustfmt::skip]
    let m_inv = Matrix3::new(
        10.0, -4.0, 0.5,
        -15.0, 7.0, -1.0,
        6.0, -3.0, 0.5,
    );
    Some(m_inv * rhs)
}

/// The normalised coefficients `b_0..b_5` for duration `t`: `b0 = P0`, `b1 = V0·t`, `b2 = 0`,
/// `(b3, b4, b5) = M⁻¹ · (P1 − P0 − V0·t, (V1 − V0)·t, 0)` per axis.
pub(super) fn solve_coefficients(
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
