//! Curvature-bounded cubic spline smoothing of a coarse polyline, after Judd & McLain,
//! "Spline based path planning for unmanned air vehicles" (AIAA GNC 2001): the threat mode's
//! coarse path start → Voronoi vertices → goal becomes straight lines joined by cubic corner
//! pieces whose curvature is at most `κ_max`.
//!
//! ## The corner piece
//! At a corner `P` with incoming unit direction `u1`, outgoing `u2` and turn angle
//! `θ ∈ [0, π)`, the piece is the cubic Bézier with control points
//! `A = P − s1·u1, P, P, B = P + s2·u2`. Its derivatives are
//! `B′(t) = 3[(1−t)² s1 u1 + t² s2 u2]` and `B″(t) = 6[−(1−t) s1 u1 + t s2 u2]`: at both ends
//! `B″ ∥ B′`, so the end curvatures are zero, and the piece joins the straight parts of the
//! polyline (which stay on the coarse segments) with continuous position, heading and
//! curvature (C² with respect to arc length). The piece lies inside the triangle `A, P, B`
//! (convex hull of the control points): that triangle is what the caller's `clear` check is
//! asked about, in closed form, without sampling.
//!
//! ## The table and why two inputs suffice
//! Scaling a piece by `λ` divides its curvature by `λ`, so its largest curvature is
//! `c(θ, ρ)/s1` with `ρ = s2/s1` ([`table`] gives `c` and its bound between grid angles). Judd &
//! McLain tabulate over `(σ̂ = σ/L, â = a/L, r̂ = 1/(κ_max·L))`; here `r̂` is a pure scale (it
//! only multiplies the legs), so the table needs the shape alone: the turn angle and the leg
//! ratio. The table (549 `f32`, 2196 bytes) is built offline in f64
//! (`table::build_corner_table`, host only) and read onboard through [`CornerBound`], so its
//! values can live in the network image.
//!
//! ## Choosing the legs, and the fallback
//! Each corner may use half of each neighbouring segment (a segment whose other end is not a
//! corner, the start or the goal without a heading, belongs wholly to the corner), so
//! neighbouring pieces never overlap; [`table::choose_legs`] picks the shortest legs meeting
//! `κ ≤ κ_max`. A corner where nothing fits, or turning more than [`TABLE_MAX_ANGLE`], is
//! dropped and its neighbours joined by a new straight segment (Judd & McLain's "extend to the
//! next segment"); the caller's `clear` must accept every such segment.
//!
//! ## Start and goal
//! The path begins along the start heading `h0`: a lead-in corner `S′ = S + d·h0` (its first
//! leg lies within `S S′`, so the path starts with a straight stretch of `d − s1 ≥ 0`). Judd &
//! McLain place the middle knot of the initial segment by SQP (threat exposure plus length,
//! curvature constrained); here the exposure is the caller's business (`clear`), so only the
//! length is minimised, and `d` is the smallest feasible lead-in found by a geometric scan
//! (factor [`fit::SCAN_FACTOR`], at most [`fit::SCAN_STEPS`] steps) followed by
//! [`fit::BISECT_STEPS`] bisection steps that keep a feasible upper end: a bounded, derivative-
//! free search whose answer is always feasible, minimal to `2⁻²⁰` of the bracket when
//! feasibility is monotone in it. When no single corner works (the first point behind the
//! start), two lead-in corners turn half each way (`S′ = S + q·h0`, `S″ = S′ + 2q·m`, `m` the
//! heading turned by half the turn, or the other way round). The goal without a heading ends
//! straight along the last segment; with a heading `hg` it mirrors the start with a lead-out
//! corner `G′ = G − d·hg`.
//!
//! Nothing here panics, allocates or uses `unsafe`; the work is bounded by
//! [`fit_work_bound`].

pub mod fit;
pub mod table;

pub use fit::{fit, fit_clear_bound, fit_work_bound, FitError, FitInput, FitSummary, Vertex};
pub use table::{
    choose_legs, corner_bound, table_angle, table_ratio, CornerBound, Legs, TABLE_ANGLES,
    TABLE_LEN, TABLE_MAX_ANGLE, TABLE_RATIOS,
};

use super::Vec2;

/// Number of parameter steps [`Piece::length_bounds`] uses on a cubic.
pub const LENGTH_STEPS: usize = 16;

/// Most chords [`Piece::chords_for_deviation`] returns.
pub const MAX_CHORDS: u32 = 4096;

/// One piece of a smoothed path.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Piece {
    /// A straight segment from `a` to `b`.
    Line {
        /// First point.
        a: Vec2,
        /// Last point.
        b: Vec2,
    },
    /// A cubic Bézier with control points `p` (a corner piece: `p[1] == p[2]`).
    Cubic {
        /// Control points.
        p: [Vec2; 4],
    },
}

impl Piece {
    /// The point at parameter `t ∈ [0, 1]` (clamped).
    pub fn point(&self, t: f32) -> Vec2 {
        let t = clamp01(t);
        match *self {
            Piece::Line { a, b } => a + (b - a) * t,
            Piece::Cubic { p } => {
                let u = 1.0 - t;
                p[0] * (u * u * u)
                    + p[1] * (3.0 * u * u * t)
                    + p[2] * (3.0 * u * t * t)
                    + p[3] * (t * t * t)
            }
        }
    }

    /// The derivative with respect to the parameter at `t ∈ [0, 1]` (clamped).
    pub fn derivative(&self, t: f32) -> Vec2 {
        let t = clamp01(t);
        match *self {
            Piece::Line { a, b } => b - a,
            Piece::Cubic { p } => {
                let u = 1.0 - t;
                ((p[1] - p[0]) * (u * u) + (p[2] - p[1]) * (2.0 * u * t) + (p[3] - p[2]) * (t * t))
                    * 3.0
            }
        }
    }

    /// The second derivative with respect to the parameter at `t ∈ [0, 1]` (clamped).
    pub fn second_derivative(&self, t: f32) -> Vec2 {
        let t = clamp01(t);
        match *self {
            Piece::Line { .. } => Vec2::new(0.0, 0.0),
            Piece::Cubic { p } => {
                ((p[2] - p[1] * 2.0 + p[0]) * (1.0 - t) + (p[3] - p[2] * 2.0 + p[1]) * t) * 6.0
            }
        }
    }

    /// The unit tangent at `t`; `None` where the derivative vanishes (a zero-length piece).
    pub fn tangent(&self, t: f32) -> Option<Vec2> {
        unit(self.derivative(t))
    }

    /// The signed curvature at `t`, 1/metres (positive turning left): `(x′y″ − y′x″)/|B′|³`;
    /// 0 where the derivative vanishes.
    pub fn curvature(&self, t: f32) -> f32 {
        let d1 = self.derivative(t);
        let n2 = d1.norm_sq();
        if !(n2 > 0.0) {
            return 0.0;
        }
        d1.cross(self.second_derivative(t)) / (n2 * libm::sqrtf(n2))
    }

    /// First point.
    pub fn start(&self) -> Vec2 {
        match *self {
            Piece::Line { a, .. } => a,
            Piece::Cubic { p } => p[0],
        }
    }

    /// Last point.
    pub fn end(&self) -> Vec2 {
        match *self {
            Piece::Line { b, .. } => b,
            Piece::Cubic { p } => p[3],
        }
    }

    /// Lower and upper bounds on the length, metres. A line is exact. A cubic is split into
    /// [`LENGTH_STEPS`] equal parameter steps; on each the arc is at least its chord and at most
    /// the control polygon of the sub-curve (`q0 = B(t0)`, `q1 = q0 + h·B′(t0)/3`,
    /// `q2 = q3 − h·B′(t1)/3`, `q3 = B(t1)`), because a Bézier curve is never longer than its
    /// control polygon. Both sums are in f32 (relative rounding about 10⁻⁶).
    pub fn length_bounds(&self) -> (f32, f32) {
        match *self {
            Piece::Line { a, b } => {
                let l = a.distance(b);
                (l, l)
            }
            Piece::Cubic { .. } => {
                let h = 1.0 / LENGTH_STEPS as f32;
                let (mut lo, mut hi) = (0.0f32, 0.0f32);
                for k in 0..LENGTH_STEPS {
                    let (t0, t1) = (k as f32 * h, (k + 1) as f32 * h);
                    let (q0, q3) = (self.point(t0), self.point(t1));
                    let q1 = q0 + self.derivative(t0) * (h / 3.0);
                    let q2 = q3 - self.derivative(t1) * (h / 3.0);
                    lo += q0.distance(q3);
                    hi += q0.distance(q1) + q1.distance(q2) + q2.distance(q3);
                }
                (lo, hi.max(lo))
            }
        }
    }

    /// The length estimate, metres: the mean of [`Piece::length_bounds`], within half their
    /// difference of the true length.
    pub fn length(&self) -> f32 {
        let (lo, hi) = self.length_bounds();
        0.5 * (lo + hi)
    }

    /// `max |B″|` over the piece: `B″` is linear in `t`, so its norm is largest at an end.
    pub fn second_derivative_bound(&self) -> f32 {
        self.second_derivative(0.0)
            .norm()
            .max(self.second_derivative(1.0).norm())
    }

    /// The largest distance between the piece and its `n` equal-parameter chords (`n ≥ 1`):
    /// with `Δt = 1/n`, linear interpolation of a C² curve errs by at most `max|B″|·Δt²/8`
    /// (the interpolation error is `∫ G(t, τ) B″(τ) dτ` with a Green's kernel whose absolute
    /// integral is at most `Δt²/8`). Plus f32 rounding of the chord end points.
    pub fn chord_deviation(&self, n: u32) -> f32 {
        let n = n.max(1) as f32;
        self.second_derivative_bound() / (8.0 * n * n)
    }

    /// The fewest equal-parameter chords whose [`Piece::chord_deviation`] is at most `tol`
    /// metres, at most [`MAX_CHORDS`]; `None` when `tol` is not positive or more chords would
    /// be needed. A line needs 1.
    pub fn chords_for_deviation(&self, tol: f32) -> Option<u32> {
        if !(tol > 0.0) {
            return None;
        }
        let m = self.second_derivative_bound();
        if !m.is_finite() {
            return None;
        }
        // n ≥ sqrt(max|B″| / (8 tol)).
        let n = libm::ceilf(libm::sqrtf(m / (8.0 * tol))).max(1.0);
        (n <= MAX_CHORDS as f32).then_some(n as u32)
    }

    /// The end points of `n` equal-parameter chords (`n + 1` points, first the start, last the
    /// end; `n` is taken as at least 1).
    pub fn chord_points(&self, n: u32) -> impl Iterator<Item = Vec2> + '_ {
        let n = n.max(1);
        (0..=n).map(move |k| {
            if k == n {
                self.end()
            } else {
                self.point(k as f32 / n as f32)
            }
        })
    }
}

fn clamp01(t: f32) -> f32 {
    if t >= 1.0 {
        1.0
    } else if t > 0.0 {
        t
    } else {
        0.0
    }
}

/// `v / |v|`, `None` for a zero or non-finite vector.
pub(crate) fn unit(v: Vec2) -> Option<Vec2> {
    let n = v.norm();
    (n > 0.0 && n.is_finite()).then(|| v * (1.0 / n))
}
