//! Blocked-cell tests on the metric grid, shared by the build and [`super::TerrainGraph`].

use skyroute::geometry::grid::{segment_cells, CellGrid};
use skyroute::{Segment, Vec2};

/// Whether cell `(col, row)` is blocked, `true` outside the grid.
pub(super) fn is_blocked(grid: &CellGrid, blocked: &[bool], col: i64, row: i64) -> bool {
    if col < 0 || row < 0 || col >= grid.cols as i64 || row >= grid.rows as i64 {
        return true;
    }
    blocked[row as usize * grid.cols as usize + col as usize]
}

/// Whether the capsule of radius `widen` around `a b` is inside the grid and meets no blocked
/// cell, and how many cells were visited finding out.
pub(super) fn segment_clear(
    grid: &CellGrid,
    blocked: &[bool],
    widen: f32,
    a: Vec2,
    b: Vec2,
) -> (bool, u64) {
    let w = Vec2::new(widen, widen);
    let lo = Vec2::new(a.x.min(b.x), a.y.min(b.y)) - w;
    let hi = Vec2::new(a.x.max(b.x), a.y.max(b.y)) + w;
    if !grid.covers(lo, hi) {
        return (false, 0);
    }
    let cols = grid.cols as usize;
    let mut clear = true;
    let n = segment_cells(grid, &Segment::new(a, b), widen, |c, r| {
        clear = !blocked[r as usize * cols + c as usize];
        clear
    });
    match n {
        Ok(n) => (clear, n),
        Err(_) => (false, 0),
    }
}
