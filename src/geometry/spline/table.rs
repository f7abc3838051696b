//! The corner table: the largest curvature of a corner piece, in units of `1/s1`, on a grid of
//! turn angles and leg ratios, and the leg choice that reads it.
//!
//! ## The function tabulated
//! With `u1 = (1, 0)`, `u2 = (cos θ, sin θ)` and `s2 = ρ·s1` the piece of [`super`] has
//! `B′(t) = 3 s1 [(1−t)² u1 + ρ t² u2]`, `B″(t) = 6 s1 [−(1−t) u1 + ρ t u2]`, so
//!
//! ```text
//! κ(t)·s1 = |B′ × B″|·s1 / |B′|³ = (2/3) ρ sin θ t(1−t) / D(t)³,
//! D(t)²   = a(t) + 2ρ w(t) cos θ,   a = (1−t)⁴ + ρ² t⁴,   w = (1−t)² t² ≥ 0,
//! c(θ, ρ) = max over t ∈ [0, 1] of κ(t)·s1.
//! ```
//!
//! ## Between grid angles
//! For `θ ≤ θ' ≤ π`, `cos θ ≥ cos θ'` and `w ≥ 0` give `D(t; θ) ≥ D(t; θ')` at every `t`, hence
//! `κ(t; θ)·s1 ≤ κ(t; θ')·s1 · sin θ / sin θ'` and, taking maxima, `c(θ) ≤ c(θ')·sin θ / sin θ'`.
//! In a cell `[θ_i, θ_{i+1}]` [`corner_bound`] returns `node_{i+1}·sin θ / sin θ_{i+1}`, which
//! is never below `c(θ)` (the node values carry the margin [`TABLE_MARGIN`], which also covers
//! the f32 rounding of this product) and never above the maximum of the cell's nodes times
//! `max(1, sin θ_i / sin θ_{i+1})`: where the cell ends at or below 90° the factor
//! `sin θ / sin θ_{i+1}` is at most 1 (so `c` is non-decreasing there), where it starts at or
//! above 90° it is at most `sin θ_i / sin θ_{i+1}` (the grid step divides 90°, so no cell
//! straddles it). It is exact at the nodes and tight for small angles, where `c` is nearly
//! proportional to `sin θ`. The host test `spline.rs` also finds `c` non-decreasing in `θ`
//! above 90° on a fine grid; the bound does not rely on it.
//!
//! Leg ratios are used only at the grid's ratios: the fit sets `s2 = table_ratio(j)·s1`
//! exactly, so no interpolation in `ρ` is needed (`c` is not monotone in `ρ`: it grows like
//! `ρ^(−3/2)` as `ρ → 0` and like `ρ^(1/2)` as `ρ → ∞`).

use super::super::trig;

/// Number of grid angles: `0°, 2.5°, …, 150°`.
pub const TABLE_ANGLES: usize = 61;
/// The grid's angle step, radians (2.5°; divides 90°).
pub const TABLE_ANGLE_STEP: f32 = 2.5 * core::f32::consts::PI / 180.0;
/// The largest turn angle the table covers, radians (150°). Larger turns are not flown as one
/// corner piece: the fit drops such a corner, or turns in two lead-in corners.
pub const TABLE_MAX_ANGLE: f32 = (TABLE_ANGLES - 1) as f32 * TABLE_ANGLE_STEP;
/// Number of grid leg ratios `ρ = s2/s1`.
pub const TABLE_RATIOS: usize = 9;
/// The grid's leg ratios (each exactly the f32 value tabulated).
pub const RATIOS: [f32; TABLE_RATIOS] = [0.25, 1.0 / 3.0, 0.5, 2.0 / 3.0, 1.0, 1.5, 2.0, 3.0, 4.0];
/// Index of the ratio 1 (symmetric legs) in [`RATIOS`].
pub const RATIO_ONE: usize = 4;
/// Number of values in a table: `TABLE_ANGLES × TABLE_RATIOS` (549 `f32`, 2196 bytes).
pub const TABLE_LEN: usize = TABLE_ANGLES * TABLE_RATIOS;
/// Relative margin the builder adds to each sampled maximum (1 %): it covers the sampling
/// error of the builder (below 10⁻⁹ relative, see `build_corner_table`), the f32 rounding of
/// the stored values and of the lookup, the f32 rounding of the fitted legs' lengths (the fit
/// covers the rounding of their directions by a larger turn angle) and a line of at most 10⁻⁴
/// of its segment absorbed into a leg.
pub const TABLE_MARGIN: f64 = 0.01;

/// Read access to a corner table, wherever its values live (a static array, the network
/// image): row-major by angle, `node(i, j)` is `(1 + margin)·c(table_angle(i), table_ratio(j))`.
pub trait CornerBound {
    /// The value at grid angle `angle` and grid ratio `ratio`; `None` outside the grid.
    fn node(&self, angle: usize, ratio: usize) -> Option<f32>;
}

impl CornerBound for [f32; TABLE_LEN] {
    fn node(&self, angle: usize, ratio: usize) -> Option<f32> {
        if angle >= TABLE_ANGLES || ratio >= TABLE_RATIOS {
            return None;
        }
        self.get(angle * TABLE_RATIOS + ratio).copied()
    }
}

/// Grid angle `i` (radians), `None` outside the grid.
pub fn table_angle(i: usize) -> Option<f32> {
    (i < TABLE_ANGLES).then_some(i as f32 * TABLE_ANGLE_STEP)
}

/// Grid ratio `j`, `None` outside the grid.
pub fn table_ratio(j: usize) -> Option<f32> {
    RATIOS.get(j).copied()
}

/// Whether every node is finite and non-negative and the zero-angle row is 0 (a straight
/// piece has no curvature): what [`fit`](fn@super::fit) requires of a table before using it.
pub fn table_is_valid(table: &impl CornerBound) -> bool {
    for i in 0..TABLE_ANGLES {
        for j in 0..TABLE_RATIOS {
            match table.node(i, j) {
                Some(v) if v.is_finite() && v >= 0.0 && (i > 0 || v == 0.0) => {}
                _ => return false,
            }
        }
    }
    true
}

/// An upper bound on `c(θ, table_ratio(ratio))` for any turn angle `theta ∈ [0, TABLE_MAX_ANGLE]`
/// (see the module documentation for why it is never below the true value); `None` outside
/// the table or for a non-finite angle.
pub fn corner_bound(table: &impl CornerBound, theta: f32, ratio: usize) -> Option<f32> {
    // NaN is outside the range.
    if !(0.0..=TABLE_MAX_ANGLE).contains(&theta) {
        return None;
    }
    // The cell [θ_i, θ_{i+1}] holding θ; θ = TABLE_MAX_ANGLE falls in the last cell.
    let i = ((theta / TABLE_ANGLE_STEP) as usize).min(TABLE_ANGLES - 2);
    let hi = table.node(i + 1, ratio)?;
    let a1 = table_angle(i + 1)?;
    // c(θ) ≤ c(θ_{i+1})·sin θ / sin θ_{i+1} for θ ≤ θ_{i+1} (module documentation).
    let v = hi * (trig::sin_cos(theta).0 / trig::sin_cos(a1).0);
    (v.is_finite() && v >= 0.0).then_some(v)
}

/// Legs `(s1, s2)` of a corner piece: the first control leg along the incoming segment, the
/// second along the outgoing one.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Legs {
    /// Leg along the incoming direction, metres.
    pub s1: f32,
    /// Leg along the outgoing direction, metres.
    pub s2: f32,
}

/// The legs of a corner turning `theta` with at most `a1` of the incoming and `a2` of the
/// outgoing segment available, whose curvature is at most `kappa_max` by the table: the
/// symmetric legs `s = c(θ, 1)/κ_max` when both fit, else among the grid ratios the fitting
/// pair `s1 = c(θ, ρ_j)/κ_max`, `s2 = ρ_j·s1` with the smallest `s1 + s2`. `None` when none
/// fits, the angle is outside the table, or an input is not finite and positive.
pub fn choose_legs(
    table: &impl CornerBound,
    theta: f32,
    a1: f32,
    a2: f32,
    kappa_max: f32,
) -> Option<Legs> {
    if !(kappa_max > 0.0 && kappa_max.is_finite() && a1 > 0.0 && a2 > 0.0) {
        return None;
    }
    let fits = |s1: f32, s2: f32| s1 > 0.0 && s2 > 0.0 && s1 <= a1 && s2 <= a2 && s1.is_finite();
    let s = corner_bound(table, theta, RATIO_ONE)? / kappa_max;
    if fits(s, s) {
        return Some(Legs { s1: s, s2: s });
    }
    let mut best: Option<Legs> = None;
    for (j, &rho) in RATIOS.iter().enumerate() {
        let s1 = corner_bound(table, theta, j)? / kappa_max;
        let s2 = rho * s1;
        if fits(s1, s2) && best.is_none_or(|b| s1 + s2 < b.s1 + b.s2) {
            best = Some(Legs { s1, s2 });
        }
    }
    best
}

/// `c(θ, ρ)` in f64: the largest of 4001 equally spaced samples of `κ(t)·s1`, refined by 80
/// golden-section steps on the two sample intervals around it. `κ(t)·s1` is smooth and has one
/// interior maximum on each sampled grid (the sampled curve rises then falls), so the refined
/// value is the maximum to about 10⁻¹² relative.
#[cfg(feature = "std")]
pub fn corner_curvature_f64(theta: f64, rho: f64) -> f64 {
    let (s, c) = (theta.sin(), theta.cos());
    let f = |t: f64| {
        let (u, w) = (1.0 - t, t);
        let dx = u * u + rho * w * w * c;
        let dy = rho * w * w * s;
        let d2 = dx * dx + dy * dy;
        if d2 <= 0.0 {
            return 0.0;
        }
        (2.0 / 3.0) * rho * s * t * u / (d2 * d2.sqrt())
    };
    const N: usize = 4000;
    let mut best = (0.0, 0usize);
    for k in 0..=N {
        let v = f(k as f64 / N as f64);
        if v > best.0 {
            best = (v, k);
        }
    }
    let (mut lo, mut hi) = (
        best.1.saturating_sub(1) as f64 / N as f64,
        (best.1 + 1).min(N) as f64 / N as f64,
    );
    let g = (5f64.sqrt() - 1.0) / 2.0;
    for _ in 0..80 {
        let (m1, m2) = (hi - g * (hi - lo), lo + g * (hi - lo));
        if f(m1) < f(m2) {
            lo = m1;
        } else {
            hi = m2;
        }
    }
    best.0.max(f(0.5 * (lo + hi)))
}

/// Builds the corner table offline (host only): node `(i, j)` is
/// `(1 + TABLE_MARGIN)·c(table_angle(i), table_ratio(j))` from [`corner_curvature_f64`],
/// rounded up to f32.
#[cfg(feature = "std")]
pub fn build_corner_table() -> [f32; TABLE_LEN] {
    let mut out = [0f32; TABLE_LEN];
    for i in 0..TABLE_ANGLES {
        let theta = (i as f32 * TABLE_ANGLE_STEP) as f64;
        for (j, &rho) in RATIOS.iter().enumerate() {
            let v = corner_curvature_f64(theta, rho as f64) * (1.0 + TABLE_MARGIN);
            let mut x = v as f32;
            if (x as f64) < v {
                x = x.next_up();
            }
            if let Some(slot) = out.get_mut(i * TABLE_RATIOS + j) {
                *slot = x;
            }
        }
    }
    out
}
