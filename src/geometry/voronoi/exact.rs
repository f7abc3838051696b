//! Exact predicates on quantised sites, and circumcentres computed from them.
//!
//! A quantised site is a pair of `i32` grid units of [`SITE_QUANTUM_M`](super::SITE_QUANTUM_M)
//! (1/16 m). Accepted coordinates are at most 10⁷ m, i.e. `|q| ≤ 1.6·10⁸ < 2²⁸` units, so every
//! difference of two coordinates is below `2²⁹` in magnitude. The predicates below rely on that
//! bound (stated at each) and are exact: their sign is the sign of the real determinant.

use super::{Vec2, VoronoiError, MAX_SITE_COORDINATE_M, UNITS_PER_M};

/// A quantised site: `[x, y]` in grid units.
pub(super) type Q = [i32; 2];

/// Quantises a site to the grid, refusing non-finite coordinates and coordinates beyond
/// [`MAX_SITE_COORDINATE_M`].
pub(super) fn quantise(v: Vec2) -> Result<Q, VoronoiError> {
    if !v.x.is_finite() || !v.y.is_finite() {
        return Err(VoronoiError::NonFinite);
    }
    if !(libm::fabsf(v.x) <= MAX_SITE_COORDINATE_M) || !(libm::fabsf(v.y) <= MAX_SITE_COORDINATE_M)
    {
        return Err(VoronoiError::OutOfRange);
    }
    // Multiplying by 16 is exact in f32; |result| ≤ 1.6·10⁸ fits i32 (the cast saturates anyway).
    Ok([
        libm::roundf(v.x * UNITS_PER_M) as i32,
        libm::roundf(v.y * UNITS_PER_M) as i32,
    ])
}

fn diff(a: Q, b: Q) -> (i64, i64) {
    (
        i64::from(a[0]) - i64::from(b[0]),
        i64::from(a[1]) - i64::from(b[1]),
    )
}

/// `(b − a) × (c − a)`, exact: positive when `a → b → c` turns left (counter-clockwise), zero
/// when collinear.
///
/// Bit sizes: each difference is below `2²⁹`, each product below `2⁵⁸`, their difference below
/// `2⁵⁹ < 2⁶³`, so i64 never overflows.
pub(super) fn orient(a: Q, b: Q, c: Q) -> i64 {
    let (bx, by) = diff(b, a);
    let (cx, cy) = diff(c, a);
    bx * cy - by * cx
}

/// Whether `p`, collinear with `a` and `b`, lies strictly between them: `(p − a)·(b − a) > 0`
/// and `(p − b)·(a − b) > 0`. Exact in i64 by the same bound as [`orient`].
pub(super) fn strictly_between(a: Q, b: Q, p: Q) -> bool {
    let (pax, pay) = diff(p, a);
    let (bax, bay) = diff(b, a);
    let (pbx, pby) = diff(p, b);
    pax * bax + pay * bay > 0 && pbx * (-bax) + pby * (-bay) > 0
}

/// The in-circle determinant of Guibas & Stolfi (1985): for `a, b, c` counter-clockwise it is
/// positive when `d` lies strictly inside their circumcircle, zero when on it, negative
/// outside.
///
/// ```text
/// | ax−dx  ay−dy  (ax−dx)²+(ay−dy)² |
/// | bx−dx  by−dy  (bx−dx)²+(by−dy)² |
/// | cx−dx  cy−dy  (cx−dx)²+(cy−dy)² |
/// ```
///
/// Bit sizes: differences below `2²⁹`; each lifted term `x² + y²` below `2⁵⁹`; each 2 × 2 minor
/// below `2⁵⁹`; each of the three products below `2¹¹⁸` and their sum below `2¹²⁰ < 2¹²⁷`, so
/// i128 is exact.
pub(super) fn incircle(a: Q, b: Q, c: Q, d: Q) -> i128 {
    let (adx, ady) = diff(a, d);
    let (bdx, bdy) = diff(b, d);
    let (cdx, cdy) = diff(c, d);
    let lift = |x: i64, y: i64| i128::from(x * x + y * y);
    let minor = |x1: i64, y1: i64, x2: i64, y2: i64| i128::from(x1 * y2 - y1 * x2);
    lift(adx, ady) * minor(bdx, bdy, cdx, cdy)
        + lift(bdx, bdy) * minor(cdx, cdy, adx, ady)
        + lift(cdx, cdy) * minor(adx, ady, bdx, bdy)
}

/// The circumcentre of `a, b, c` (not collinear), metres, in f64.
///
/// With `b' = b − a`, `c' = c − a` the centre is `a + (c'_y|b'|² − b'_y|c'|²,
/// b'_x|c'|² − c'_x|b'|²) / (2 (b' × c'))`. The numerators are exact in i128 (each product is
/// below `2²⁹·2⁵⁹ = 2⁸⁸`) and the denominator exact in i64 (below `2⁶⁰`); each is rounded once
/// to f64, so the centre carries a relative error of a few f64 ulps.
pub(super) fn circumcentre(a: Q, b: Q, c: Q) -> (f64, f64) {
    let (bx, by) = diff(b, a);
    let (cx, cy) = diff(c, a);
    let b2 = i128::from(bx * bx + by * by);
    let c2 = i128::from(cx * cx + cy * cy);
    let ux = i128::from(cy) * b2 - i128::from(by) * c2;
    let uy = i128::from(bx) * c2 - i128::from(cx) * b2;
    let d = 2.0 * (bx * cy - by * cx) as f64;
    let scale = f64::from(UNITS_PER_M);
    (
        (f64::from(a[0]) + ux as f64 / d) / scale,
        (f64::from(a[1]) + uy as f64 / d) / scale,
    )
}

/// A quantised site in metres, f64 (exact).
pub(super) fn metres(q: Q) -> (f64, f64) {
    let scale = f64::from(UNITS_PER_M);
    (f64::from(q[0]) / scale, f64::from(q[1]) / scale)
}
