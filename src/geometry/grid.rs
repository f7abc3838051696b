//! Uniform cell grids (a DEM's raster, an occupancy grid) and exact traversals: every grid cell
//! that a segment or an arc — or the band of half-width `widen` around it — touches.
//!
//! A [`CellGrid`] is `cols × rows` square cells of side `cell` metres; cell `(col, row)` is the
//! **closed** square `[x₀ + col·cell, x₀ + (col+1)·cell] × [y₀ + row·cell, y₀ + (row+1)·cell]`
//! with `(x₀, y₀)` = [`CellGrid::origin`], the south-west corner of cell `(0, 0)`; rows count
//! northwards, columns eastwards.
//!
//! [`segment_cells`] and [`arc_cells`] call a visitor `FnMut(col, row) -> bool` once for every
//! cell within distance `widen` of the primitive (for `widen = 0`: every cell the primitive
//! touches), clipped to the grid, each cell at most once per call; the visitor returns `false`
//! to stop early. They return how many cells they visited. Because cells are closed, a primitive
//! that passes exactly through a cell corner visits all four cells sharing it, and one that runs
//! along a grid line visits the cells on both sides; likewise a band whose edge just reaches a
//! grid line.
//!
//! # Method: row bands, closed-form x-ranges
//!
//! Both traversals work row by row. For the grid row `k` (the band `k ≤ v ≤ k + 1` in *grid
//! units*, `u = (x − x₀)/cell`, `v = (y − y₀)/cell`) they compute in closed form the x-range(s)
//! of the set `S` = {points within `widen` of the primitive} intersected with the band, and visit
//! the columns those ranges overlap.
//!
//! **Why no cell is missed.** A cell of row `k` meets `S` iff it meets `S ∩ band`. If
//! `S ∩ band` is a union of *connected* pieces, a piece meets the cell (the band times a column
//! interval) iff the piece's x-projection — an interval, the piece being connected — overlaps
//! the column interval. So visiting every column that overlaps the pieces' x-intervals visits
//! exactly the cells that meet `S`; no search, and nothing depends on which cells are blocked.
//! * **Segment** (`S` = capsule, convex, so `S ∩ band` is one convex piece). Its x-extremes lie on
//!   the capsule's boundary, which consists of the two end discs of radius `widen` and the two
//!   sides `P ± n·widen → Q ± n·widen` (`n` the unit normal), all inside the capsule: the
//!   x-range is the hull of the discs' chords within the band and the sides clipped to the band
//!   (for `widen = 0`: the segment clipped to the band). A segment shorter than the slack `δ`
//!   below has no stable normal; its capsule lies inside the disc of radius `widen + length`
//!   about either end, which is used instead.
//! * **Arc** (`S` = annular sector `max(0, r − widen) ≤ |p − c| ≤ r + widen` over the swept
//!   angles, plus the discs of radius `widen` at the two end points: a point whose polar angle is
//!   swept is nearest the arc radially, at distance `||p − c| − r|`, any other point is nearest
//!   an end point, since the distance to the circle's point at angle φ grows with the angle
//!   between φ and the point's own; the centre is at distance `r` from every arc point). The sector is
//!   split at the axes into at most five pieces, each within one quadrant. Reflected into the
//!   first quadrant, a piece `{ρ ∈ [r₁, r₂], θ ∈ [a, b]}` meets a band `[y_a, y_b]` in a
//!   connected set (for each θ the admissible ρ form an interval whose ends vary continuously, and
//!   the admissible θ form an interval because `ρ sin θ` is monotone), whose y-range is
//!   `[r₁ sin a, r₂ sin b]`. As `x = ρ cos θ` grows with ρ and falls with θ, the right end of its
//!   x-range is at the smallest admissible θ on the largest admissible ρ: the outer corner
//!   `r₂(cos a, sin a)` if the band contains it, else the ray `a` at height `y_b` (band below the
//!   corner) or the outer circle at height `y_a` (band above). The left end is symmetric: the
//!   inner corner `r₁(cos b, sin b)`, the ray `b` at height `y_a`, or the inner circle at height
//!   `y_b`. With the two end discs that gives at most seven intervals per row, merged before
//!   visiting, so every cell is visited once.
//!
//! **Rounding.** Everything is `f32`. Let `M` be the largest magnitude involved, in cells: the
//! largest coordinate relative to the origin (the arc's centre, the segment's ends) plus the
//! radius plus `widen`. Converting the inputs to grid units moves the geometry by at most about
//! `2.5 ε M` (ε = `f32::EPSILON`; corners `P ± n·widen`, end points `c + r·(cos, sin)`
//! included), and evaluating the formulas above — each a handful of roundings on values of
//! magnitude ≤ `M`, and monotone in the band and the radii, so that the ill-conditioning of a
//! circle's chord near tangency is absorbed by the widened band rather than amplified — adds at
//! most about `4 ε M`. Every band is therefore widened by `δ = SLACK_ULPS · ε · (M + 1)` cells
//! (`SLACK_ULPS` = 16, over twice the sum) on both sides before its x-ranges are computed, and
//! every x-range by `δ` after; the band's margin also decides the "empty or not" tests
//! correctly. Angles are handled apart: the arc's angular range is widened by
//! `e_a = 16 ε (|start_angle| + |sweep| + 8)` radians (the rounding of `start_angle + sweep`, the
//! sine and cosine, the reduction to [0, 2π)), and its end discs by `e_a·r`; a range widened to
//! 2π or more is the whole circle, so an angle too large for `f32` to place still fails safe.
//! Hence the traversal visits a superset of the exact cells, and every visited cell lies within
//! `widen + η` of the primitive, `η = 3δ` cells for a segment and `3δ + 2e_a(r + widen)` for an
//! arc: the only extra cells are those the primitive's band misses by less than `η`. For a grid
//! of 1000 cells across, `δ ≈ 2·10⁻³` cells. (The integration tests check both the superset and
//! the `η` bound against `f64` references, and fail when `SLACK_ULPS` is 0.)
//!
//! # Cost
//!
//! O(R + N) for R rows spanned (the primitive's y-extent plus `2·widen`, over `cell`, plus 2) and
//! N cells visited: a constant amount of work per row (at most 7 intervals for an arc, 4 pieces
//! for a segment) and one visitor call per cell, whatever the visitor does with them. Since every
//! visited cell lies within `ρ = widen/cell + η` cells of the primitive, its whole square lies
//! within `ρ + √2` of it, and the squares do not overlap, so
//! `N ≤ 2(ρ + √2)·L + π(ρ + √2)²` for a primitive of length `L` cells (an arc's length counted up
//! to one full turn; for an arc of radius `r` cells also `N ≤ π(r + ρ + √2)²`). For `widen = 0`
//! a segment in general position visits at most `|Δu| + |Δv| + 3` cells (one plus the grid lines
//! it crosses), its supercover; each grid corner it passes exactly adds the two other cells
//! there.
//!
//! # Errors
//!
//! Invalid input is an error, never a silent empty traversal (which a caller could read as "no
//! cell blocked"): an invalid grid, a negative or non-finite `widen`, a non-finite or
//! negative-radius primitive, or coordinates more than [`MAX_GRID_UNITS`] cells from the origin.
//! Cells outside the grid are never visited: a caller to whom unknown terrain is blocked checks
//! [`CellGrid::covers`] with the primitive's bounding box widened by `widen`.

use super::{Arc, Primitive, Segment, Vec2};
use core::f32::consts::{FRAC_PI_2, TAU};
use core::fmt;

/// The most columns or rows a [`CellGrid`] may have: 2²⁴, so that every cell index is exact in
/// `f32`.
pub const MAX_CELLS_PER_AXIS: u32 = 1 << 24;

/// The largest magnitude, in cells, of any coordinate (relative to the grid origin), radius or
/// `widen` that a traversal accepts; beyond it [`GridError::OutOfRange`]. Keeps every product
/// the formulas form finite.
pub const MAX_GRID_UNITS: f32 = 1e18;

/// The slack factor: bands and x-ranges are widened by `SLACK_ULPS · f32::EPSILON · (M + 1)`
/// cells, `M` the largest magnitude in cells among the coordinates (relative to the grid
/// origin), the radius and `widen` (see the [module documentation](self)).
pub const SLACK_ULPS: f32 = 16.0;

/// A uniform grid of square cells: `cols` columns eastwards and `rows` rows northwards from
/// `origin`, the south-west corner of cell `(0, 0)`.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct CellGrid {
    /// South-west corner of cell `(0, 0)`, metres.
    pub origin: Vec2,
    /// Side of a cell, metres (finite, positive).
    pub cell: f32,
    /// Number of columns (1 ..= [`MAX_CELLS_PER_AXIS`]).
    pub cols: u32,
    /// Number of rows (1 ..= [`MAX_CELLS_PER_AXIS`]).
    pub rows: u32,
}

/// Why a traversal refused its input.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum GridError {
    /// The grid's origin is not finite, its cell size not finite and positive, or it has no
    /// column or row, or more than [`MAX_CELLS_PER_AXIS`].
    InvalidGrid,
    /// `widen` is negative or not finite.
    InvalidWiden,
    /// A coordinate, angle or radius of the primitive is not finite.
    NonFinite,
    /// The arc's radius is negative.
    NegativeRadius,
    /// A coordinate, the radius or `widen` is more than [`MAX_GRID_UNITS`] cells from the origin.
    OutOfRange,
}

impl fmt::Display for GridError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            GridError::InvalidGrid => "invalid grid (origin, cell size or dimensions)",
            GridError::InvalidWiden => "widen is negative or not finite",
            GridError::NonFinite => "the primitive is not finite",
            GridError::NegativeRadius => "the arc's radius is negative",
            GridError::OutOfRange => "coordinates too far from the grid origin",
        })
    }
}

#[cfg(feature = "std")]
impl std::error::Error for GridError {}

impl CellGrid {
    /// The grid of `cols × rows` cells of side `cell` whose south-west corner is `origin`.
    pub const fn new(origin: Vec2, cell: f32, cols: u32, rows: u32) -> Self {
        Self {
            origin,
            cell,
            cols,
            rows,
        }
    }

    /// Checks the grid: finite origin, finite positive cell size, 1 ..= [`MAX_CELLS_PER_AXIS`]
    /// columns and rows.
    pub fn validate(&self) -> Result<(), GridError> {
        let dims_ok = (1..=MAX_CELLS_PER_AXIS).contains(&self.cols)
            && (1..=MAX_CELLS_PER_AXIS).contains(&self.rows);
        if self.origin.is_finite() && self.cell.is_finite() && self.cell > 0.0 && dims_ok {
            Ok(())
        } else {
            Err(GridError::InvalidGrid)
        }
    }

    /// The closed square of cell `(col, row)` as `(south-west, north-east)` corners, metres.
    /// (Computed in `f32`: the corners are rounded like any coordinate.)
    pub fn cell_rect(&self, col: u32, row: u32) -> (Vec2, Vec2) {
        let x0 = self.origin.x + col as f32 * self.cell;
        let y0 = self.origin.y + row as f32 * self.cell;
        (Vec2::new(x0, y0), Vec2::new(x0 + self.cell, y0 + self.cell))
    }

    /// The cell containing `p`: the one whose half-open square `[x, x + cell) × [y, y + cell)`
    /// holds it, with points on the grid's east and north edges counted in the last column and
    /// row. `None` outside the grid, for a non-finite point or an invalid grid. (A point on a
    /// shared edge belongs to several closed cells; this names one of them.)
    pub fn cell_of(&self, p: Vec2) -> Option<(u32, u32)> {
        self.validate().ok()?;
        let u = (p.x - self.origin.x) / self.cell;
        let v = (p.y - self.origin.y) / self.cell;
        Some((
            half_open_index(u, self.cols)?,
            half_open_index(v, self.rows)?,
        ))
    }

    /// Whether the grid covers the whole box `[lo, hi]` (closed; `false` for a non-finite or
    /// empty box or an invalid grid).
    pub fn covers(&self, lo: Vec2, hi: Vec2) -> bool {
        if self.validate().is_err() || !lo.is_finite() || !hi.is_finite() {
            return false;
        }
        let (sw, _) = self.cell_rect(0, 0);
        let (_, ne) = self.cell_rect(self.cols - 1, self.rows - 1);
        lo.x <= hi.x && lo.y <= hi.y && sw.x <= lo.x && sw.y <= lo.y && hi.x <= ne.x && hi.y <= ne.y
    }

    /// Converts a point to grid units relative to the origin.
    fn units(&self, p: Vec2) -> Result<Vec2, GridError> {
        let q = Vec2::new(
            (p.x - self.origin.x) / self.cell,
            (p.y - self.origin.y) / self.cell,
        );
        in_range(q.x)?;
        in_range(q.y)?;
        Ok(q)
    }
}

/// `Ok` when `x` is within [`MAX_GRID_UNITS`] (false for NaN and infinities).
fn in_range(x: f32) -> Result<(), GridError> {
    if libm::fabsf(x) <= MAX_GRID_UNITS {
        Ok(())
    } else {
        Err(GridError::OutOfRange)
    }
}

fn check_widen(widen: f32) -> Result<(), GridError> {
    if widen.is_finite() && widen >= 0.0 {
        Ok(())
    } else {
        Err(GridError::InvalidWiden)
    }
}

/// The slack δ, in cells, for magnitudes up to `m` cells.
fn slack(m: f32) -> f32 {
    SLACK_ULPS * f32::EPSILON * (m + 1.0)
}

/// The indices `i` in `0..n` whose closed interval `[i, i + 1]` meets `[lo, hi]`: from
/// `⌈lo⌉ − 1` to `⌊hi⌋`, clipped to the grid. `None` when none does or on NaN. `1 ≤ n ≤ 2²⁴`.
fn index_range(lo: f32, hi: f32, n: u32) -> Option<(u32, u32)> {
    if !(lo <= hi) {
        return None;
    }
    let last = (n - 1) as f32;
    let a = libm::ceilf(lo) - 1.0;
    let b = libm::floorf(hi);
    if b < 0.0 || a > last {
        return None;
    }
    let a = if a < 0.0 { 0 } else { a as u32 };
    let b = if b > last { n - 1 } else { b as u32 };
    Some((a, b))
}

/// The index `i` in `0..n` with `i ≤ u < i + 1`, or `n − 1` for `u = n`; `None` outside or on
/// NaN.
fn half_open_index(u: f32, n: u32) -> Option<u32> {
    if !(u >= 0.0 && u <= n as f32) {
        return None;
    }
    let i = libm::floorf(u);
    Some(if i >= n as f32 { n - 1 } else { i as u32 })
}

/// A closed interval, or empty.
#[derive(Clone, Copy, Debug)]
struct Span {
    lo: f32,
    hi: f32,
}

impl Span {
    const EMPTY: Span = Span {
        lo: f32::INFINITY,
        hi: f32::NEG_INFINITY,
    };

    fn is_empty(&self) -> bool {
        !(self.lo <= self.hi)
    }

    fn hull(self, o: Option<(f32, f32)>) -> Span {
        match o {
            Some((a, b)) => Span {
                lo: self.lo.min(a).min(b),
                hi: self.hi.max(a).max(b),
            },
            None => self,
        }
    }
}

/// The x-range of the disc `|p − c| ≤ rho` within the band `ya ≤ y ≤ yb`.
fn disc_in_band(c: Vec2, rho: f32, ya: f32, yb: f32) -> Option<(f32, f32)> {
    let dy = if c.y < ya {
        ya - c.y
    } else if c.y > yb {
        c.y - yb
    } else {
        0.0
    };
    if !(dy <= rho) {
        return None;
    }
    let h = libm::sqrtf(((rho - dy) * (rho + dy)).max(0.0));
    Some((c.x - h, c.x + h))
}

/// The x-range of the segment `a b` within the band `ya ≤ y ≤ yb`.
fn segment_in_band(a: Vec2, b: Vec2, ya: f32, yb: f32) -> Option<(f32, f32)> {
    let (lo, hi) = if a.y <= b.y { (a, b) } else { (b, a) };
    if hi.y < ya || lo.y > yb {
        return None;
    }
    let dy = hi.y - lo.y;
    if !(dy > 0.0) {
        return Some((lo.x.min(hi.x), lo.x.max(hi.x)));
    }
    let x_at = |y: f32| {
        let t = ((y - lo.y) / dy).clamp(0.0, 1.0);
        lo.x + t * (hi.x - lo.x)
    };
    let x0 = if lo.y >= ya { lo.x } else { x_at(ya) };
    let x1 = if hi.y <= yb { hi.x } else { x_at(yb) };
    Some((x0.min(x1), x0.max(x1)))
}

/// Visits the columns `[c0, c1]` of row `k`, ascending or descending; `false` when the visitor
/// stopped.
fn visit_run<F: FnMut(u32, u32) -> bool>(
    (c0, c1): (u32, u32),
    k: u32,
    ascending: bool,
    count: &mut u64,
    visit: &mut F,
) -> bool {
    for j in 0..=(c1 - c0) {
        let c = if ascending { c0 + j } else { c1 - j };
        *count += 1;
        if !visit(c, k) {
            return false;
        }
    }
    true
}

/// Calls `visit(col, row)` for every cell within distance `widen` (metres, ≥ 0) of `seg`,
/// clipped to the grid, each at most once; stops early when `visit` returns `false`. Returns
/// the number of calls made.
///
/// Cells are closed squares: a segment through a cell corner visits all four cells sharing it,
/// one along a grid line the cells on both sides. For `widen = 0` the result is the segment's
/// supercover (what a supercover Amanatides–Woo DDA with tie handling yields), computed per row
/// in closed form instead of by stepping, so no rounding accumulates along the segment; cells are
/// visited in the order the segment reaches them (rows from the start's towards the end's,
/// columns in the direction of travel). For `widen > 0` it is every cell that the capsule (the
/// Minkowski sum of the segment and a disc of radius `widen`) touches, in the same order row by
/// row. Extra cells: only those missed by less than `3δ` cells (rounding slack, see the
/// [module documentation](self), which also bounds the count and proves completeness).
///
/// ```
/// use skyroute::geometry::grid::{segment_cells, CellGrid};
/// use skyroute::{Segment, Vec2};
/// let grid = CellGrid::new(Vec2::new(0.0, 0.0), 10.0, 10, 10);
/// let mut cells = Vec::new();
/// let seg = Segment::new(Vec2::new(5.0, 5.0), Vec2::new(25.0, 5.0));
/// let n = segment_cells(&grid, &seg, 0.0, |c, r| { cells.push((c, r)); true }).unwrap();
/// assert_eq!(cells, [(0, 0), (1, 0), (2, 0)]);
/// assert_eq!(n, 3);
/// ```
pub fn segment_cells<F: FnMut(u32, u32) -> bool>(
    grid: &CellGrid,
    seg: &Segment,
    widen: f32,
    mut visit: F,
) -> Result<u64, GridError> {
    grid.validate()?;
    check_widen(widen)?;
    if !seg.start.is_finite() || !seg.end.is_finite() {
        return Err(GridError::NonFinite);
    }
    let p = grid.units(seg.start)?;
    let q = grid.units(seg.end)?;
    let w = widen / grid.cell;
    in_range(w)?;
    let m = libm::fabsf(p.x)
        .max(libm::fabsf(p.y))
        .max(libm::fabsf(q.x))
        .max(libm::fabsf(q.y))
        + w;
    let d = slack(m);

    // The capsule's pieces: end discs (radius w, or w + length for a segment too short for a
    // stable normal, which then lies inside them) and the two sides.
    let dir = q - p;
    let len = dir.norm();
    let sides = if w > 0.0 && len >= d {
        let n = dir.perp() * (w / len);
        Some(((p + n, q + n), (p - n, q - n)))
    } else {
        None
    };
    let rho = if sides.is_some() || w == 0.0 {
        w
    } else {
        w + len
    };
    let in_band = |ya: f32, yb: f32| -> Span {
        let mut s = Span::EMPTY;
        if w == 0.0 {
            return s.hull(segment_in_band(p, q, ya, yb));
        }
        s = s.hull(disc_in_band(p, rho, ya, yb));
        s = s.hull(disc_in_band(q, rho, ya, yb));
        if let Some(((a, b), (c, e))) = sides {
            s = s.hull(segment_in_band(a, b, ya, yb));
            s = s.hull(segment_in_band(c, e, ya, yb));
        }
        s
    };

    let ylo = p.y.min(q.y) - rho - d;
    let yhi = p.y.max(q.y) + rho + d;
    let Some((k0, k1)) = index_range(ylo, yhi, grid.rows) else {
        return Ok(0);
    };
    // The direction of travel, from the inputs (the conversion may round a tiny difference away).
    let up = seg.end.y >= seg.start.y;
    let east = seg.end.x >= seg.start.x;
    let mut count = 0u64;
    for i in 0..=(k1 - k0) {
        let k = if up { k0 + i } else { k1 - i };
        let kf = k as f32;
        let span = in_band(kf - d, kf + 1.0 + d);
        if span.is_empty() {
            continue;
        }
        if let Some(cols) = index_range(span.lo - d, span.hi + d, grid.cols) {
            if !visit_run(cols, k, east, &mut count, &mut visit) {
                break;
            }
        }
    }
    Ok(count)
}

/// One quadrant piece of an arc's annular sector: quadrant `q` (0: x ≥ 0, y ≥ 0; 1: x ≤ 0,
/// y ≥ 0; 2: both ≤ 0; 3: x ≥ 0, y ≤ 0) and its two bounding unit directions.
#[derive(Clone, Copy, Debug)]
struct Piece {
    q: u8,
    from: Vec2,
    to: Vec2,
}

impl Piece {
    /// The reflection signs that take quadrant `q` to the first.
    fn signs(&self) -> (f32, f32) {
        match self.q {
            0 => (1.0, 1.0),
            1 => (-1.0, 1.0),
            2 => (-1.0, -1.0),
            _ => (1.0, -1.0),
        }
    }

    /// The bounding directions reflected into the first quadrant, ordered by polar angle: `(a, b)`
    /// with `a.y ≤ b.y`.
    fn reflected(&self) -> (Vec2, Vec2) {
        let (sx, sy) = self.signs();
        let f = Vec2::new((sx * self.from.x).max(0.0), (sy * self.from.y).max(0.0));
        let t = Vec2::new((sx * self.to.x).max(0.0), (sy * self.to.y).max(0.0));
        if f.y <= t.y {
            (f, t)
        } else {
            (t, f)
        }
    }

    /// The y-range, relative to the centre, of the piece with radii `[r1, r2]`.
    fn y_range(&self, r1: f32, r2: f32) -> (f32, f32) {
        let (a, b) = self.reflected();
        let (lo, hi) = (r1 * a.y, r2 * b.y);
        if self.signs().1 > 0.0 {
            (lo, hi)
        } else {
            (-hi, -lo)
        }
    }

    /// The x-range, relative to the centre, of the piece with radii `[r1, r2]` within the band
    /// `ya ≤ y ≤ yb` (relative to the centre). See the module documentation for the derivation.
    fn x_range(&self, r1: f32, r2: f32, ya: f32, yb: f32) -> Option<(f32, f32)> {
        let (sx, sy) = self.signs();
        let (ya, yb) = if sy > 0.0 { (ya, yb) } else { (-yb, -ya) };
        let (a, b) = self.reflected();
        // The piece's y-range is [r1 sin a, r2 sin b].
        if !(r1 * a.y <= yb && ya <= r2 * b.y) {
            return None;
        }
        let outer_a = r2 * a.y;
        let xmax = if outer_a > yb {
            yb * a.x / a.y // on the ray a at height yb (a.y > 0 here)
        } else if outer_a < ya {
            root_diff(r2, ya) // on the outer circle at height ya
        } else {
            r2 * a.x // the outer corner
        };
        let inner_b = r1 * b.y;
        let xmin = if inner_b < ya {
            ya * b.x / b.y // on the ray b at height ya (b.y > 0 here)
        } else if inner_b > yb {
            root_diff(r1, yb) // on the inner circle at height yb
        } else {
            r1 * b.x // the inner corner
        };
        let (lo, hi) = (xmin.min(xmax), xmin.max(xmax));
        Some(if sx > 0.0 { (lo, hi) } else { (-hi, -lo) })
    }
}

/// `√(r² − y²)`, as `√((r − y)(r + y))`, 0 when negative.
fn root_diff(r: f32, y: f32) -> f32 {
    libm::sqrtf(((r - y) * (r + y)).max(0.0))
}

/// The axis direction at quadrant boundary `k` (0: east, 1: north, 2: west, 3: south).
fn axis(k: u32) -> Vec2 {
    match k % 4 {
        0 => Vec2::new(1.0, 0.0),
        1 => Vec2::new(0.0, 1.0),
        2 => Vec2::new(-1.0, 0.0),
        _ => Vec2::new(0.0, -1.0),
    }
}

/// Calls `visit(col, row)` for every cell within distance `widen` (metres, ≥ 0) of `arc`,
/// clipped to the grid, each at most once; stops early when `visit` returns `false`. Returns
/// the number of calls made.
///
/// Cells are closed squares (an arc through a corner visits the four cells sharing it). The arc
/// sweeps `arc.sweep` radians from `arc.start_angle` (either sign; `|sweep| ≥ 2π` is the whole
/// circle); a radius of 0 is the point `arc.centre`. Cells are visited row by row from the south,
/// west to east within a row. The set is exact up to the rounding slack (extra cells only where
/// the arc's band misses them by less than `3δ` cells); the [module documentation](self) has the
/// proof of completeness and the bound on the count.
///
/// ```
/// use skyroute::geometry::grid::{arc_cells, CellGrid};
/// use skyroute::{Arc, Vec2};
/// let grid = CellGrid::new(Vec2::new(0.0, 0.0), 10.0, 10, 10);
/// // A quarter circle of radius 15 m about (50, 50), from east (65, 50) to north (50, 65):
/// // both ends lie on grid lines, so the cells south of the start and west of the end count.
/// let arc = Arc { centre: Vec2::new(50.0, 50.0), radius: 15.0, start_angle: 0.0,
///                 sweep: core::f32::consts::FRAC_PI_2 };
/// let mut cells = Vec::new();
/// arc_cells(&grid, &arc, 0.0, |c, r| { cells.push((c, r)); true }).unwrap();
/// assert_eq!(cells, [(6, 4), (6, 5), (4, 6), (5, 6), (6, 6)]);
/// ```
pub fn arc_cells<F: FnMut(u32, u32) -> bool>(
    grid: &CellGrid,
    arc: &Arc,
    widen: f32,
    mut visit: F,
) -> Result<u64, GridError> {
    grid.validate()?;
    check_widen(widen)?;
    if !arc.centre.is_finite()
        || !arc.radius.is_finite()
        || !arc.start_angle.is_finite()
        || !arc.sweep.is_finite()
    {
        return Err(GridError::NonFinite);
    }
    if arc.radius < 0.0 {
        return Err(GridError::NegativeRadius);
    }
    let c = grid.units(arc.centre)?;
    let r = arc.radius / grid.cell;
    let w = widen / grid.cell;
    in_range(r)?;
    in_range(w)?;
    let d = slack(libm::fabsf(c.x).max(libm::fabsf(c.y)) + r + w);

    // Counter-clockwise from a0 through s ≥ 0, widened by the angle error ea on both sides.
    let s0 = libm::fabsf(arc.sweep);
    let a0 = if arc.sweep.is_sign_negative() {
        arc.start_angle + arc.sweep
    } else {
        arc.start_angle
    };
    let ea = 16.0 * f32::EPSILON * (libm::fabsf(arc.start_angle) + s0 + 8.0);
    let s = s0 + 2.0 * ea;
    let full = !(s < TAU);

    let (pieces, n_pieces) = sector_pieces(a0 - ea, s, full);
    let pieces = pieces.get(..n_pieces).unwrap_or(&[]);
    let r1 = (r - w).max(0.0);
    let r2 = r + w;

    // End discs: radius w, plus the end points' angle error times the radius.
    let caps = if full || w == 0.0 {
        None
    } else {
        let p0 = c + Vec2::from_angle(arc.start_angle) * r;
        let p1 = c + Vec2::from_angle(arc.start_angle + arc.sweep) * r;
        Some((p0, p1, w + ea * r))
    };

    let mut ylo = f32::INFINITY;
    let mut yhi = f32::NEG_INFINITY;
    for piece in pieces {
        let (lo, hi) = piece.y_range(r1, r2);
        ylo = ylo.min(c.y + lo);
        yhi = yhi.max(c.y + hi);
    }
    if let Some((p0, p1, rho)) = caps {
        ylo = ylo.min(p0.y - rho).min(p1.y - rho);
        yhi = yhi.max(p0.y + rho).max(p1.y + rho);
    }
    let Some((k0, k1)) = index_range(ylo - d, yhi + d, grid.rows) else {
        return Ok(0);
    };

    let mut count = 0u64;
    for k in k0..=k1 {
        let kf = k as f32;
        let (ya, yb) = (kf - d, kf + 1.0 + d);
        // Column runs of this row: one per piece and cap, then merged.
        let mut runs = [(0u32, 0u32); 7];
        let mut n = 0;
        let mut push = |range: Option<(f32, f32)>, dx: f32| {
            if let Some((lo, hi)) = range {
                if let (Some(cols), Some(slot)) = (
                    index_range(dx + lo - d, dx + hi + d, grid.cols),
                    runs.get_mut(n),
                ) {
                    *slot = cols;
                    n += 1;
                }
            }
        };
        for piece in pieces {
            push(piece.x_range(r1, r2, ya - c.y, yb - c.y), c.x);
        }
        if let Some((p0, p1, rho)) = caps {
            push(disc_in_band(p0, rho, ya, yb), 0.0);
            push(disc_in_band(p1, rho, ya, yb), 0.0);
        }
        let runs = runs.get_mut(..n).unwrap_or(&mut []);
        super::insertion_sort_by(runs, |run| run.0);
        let mut i = 0;
        while i < runs.len() {
            let (lo, mut hi) = runs[i];
            i += 1;
            while i < runs.len() && runs[i].0 <= hi.saturating_add(1) {
                hi = hi.max(runs[i].1);
                i += 1;
            }
            if !visit_run((lo, hi), k, true, &mut count, &mut visit) {
                return Ok(count);
            }
        }
    }
    Ok(count)
}

/// The counter-clockwise sector from angle `a` through `s` radians (the whole circle when
/// `full`) cut at the axes into at most five quadrant pieces; returns them and their count.
fn sector_pieces(a: f32, s: f32, full: bool) -> ([Piece; 5], usize) {
    let mut pieces = [Piece {
        q: 0,
        from: axis(0),
        to: axis(1),
    }; 5];
    let mut n_pieces = 0;
    if full {
        for (k, piece) in pieces.iter_mut().take(4).enumerate() {
            *piece = Piece {
                q: k as u8,
                from: axis(k as u32),
                to: axis(k as u32 + 1),
            };
        }
        n_pieces = 4;
    } else {
        let from = Vec2::from_angle(a);
        let to = Vec2::from_angle(a + s);
        let mut t0 = libm::atan2f(from.y, from.x);
        if t0 < 0.0 {
            t0 += TAU;
        }
        let t1 = t0 + s;
        let mut q = (libm::floorf(t0 / FRAC_PI_2) as u32).min(3);
        let mut start = from;
        while n_pieces < 5 {
            let boundary = (q + 1) as f32 * FRAC_PI_2;
            if t1 > boundary && n_pieces < 4 {
                pieces[n_pieces] = Piece {
                    q: (q % 4) as u8,
                    from: start,
                    to: axis(q + 1),
                };
                start = axis(q + 1);
                q += 1;
            } else {
                pieces[n_pieces] = Piece {
                    q: (q % 4) as u8,
                    from: start,
                    to,
                };
                n_pieces += 1;
                break;
            }
            n_pieces += 1;
        }
    }
    (pieces, n_pieces)
}

/// [`segment_cells`] or [`arc_cells`], by the primitive's kind.
pub fn primitive_cells<F: FnMut(u32, u32) -> bool>(
    grid: &CellGrid,
    primitive: &Primitive,
    widen: f32,
    visit: F,
) -> Result<u64, GridError> {
    match primitive {
        Primitive::Line(seg) => segment_cells(grid, seg, widen, visit),
        Primitive::Arc(arc) => arc_cells(grid, arc, widen, visit),
    }
}
