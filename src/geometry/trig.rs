//! Single-precision sine and cosine for the flight computer.
//!
//! `libm::sincosf` (the musl port) evaluates its kernels in `f64`, which a Cortex-M4F emulates
//! in software: about 2,200 instructions a call. This is Cody–Waite reduction by π/2 with a
//! three-part constant and the minimax polynomials of Cephes' `sinf`/`cosf` (S. L. Moshier),
//! all in `f32`: a few dozen instructions. For |x| ≤ 8192 (Cephes' domain) the products k·C1 and
//! k·C2 of the reduction are exact (C1 and C2 have few significant bits, k < 2¹³), and the result is within
//! 1.5·10⁻⁷ of the true value (9.2·10⁻⁸ measured against `f64` in `host-tests/tests/core/trig.rs`); larger
//! arguments, which the planner never produces, fall back to `libm`.

/// π/2 split as C1 + C2 + C3, C1 and C2 with trailing zero bits (Cephes DP1..DP3 ×2).
const C1: f32 = 1.570_312_5;
const C2: f32 = 4.837_513e-4;
const C3: f32 = 7.549_79e-8;
const TWO_OVER_PI: f32 = core::f32::consts::FRAC_2_PI;
const LIMIT: f32 = 8192.0;

/// `(sin x, cos x)`.
pub fn sin_cos(x: f32) -> (f32, f32) {
    if !(libm::fabsf(x) <= LIMIT) {
        return libm::sincosf(x); // large or not finite
    }
    let k = libm::floorf(x * TWO_OVER_PI + 0.5);
    let r = ((x - k * C1) - k * C2) - k * C3; // |r| ≤ π/4 (to rounding)
    let z = r * r;
    // Cephes sinf and cosf polynomials on [−π/4, π/4].
    let s = r + r * z * (-1.666_665_5e-1 + z * (8.332_161e-3 + z * -1.951_529_6e-4));
    let c = 1.0 - 0.5 * z + z * z * (4.166_664_6e-2 + z * (-1.388_731_6e-3 + z * 2.443_315_7e-5));
    match (k as i32) & 3 {
        0 => (s, c),
        1 => (c, -s),
        2 => (-s, -c),
        _ => (-c, s),
    }
}
