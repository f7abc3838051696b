//! The writer's grid index: each cell's edges, delta-coded as varints.

use super::{count, grid_cells, EdgeSpec, NetworkSpec, WriteError};
use crate::geometry::grid::{segment_cells, CellGrid};
use crate::geometry::hermite::{HermiteSegment, LineElement};
use crate::geometry::{points_bounding_box, DubinsPath, Segment, Vec2};
use std::vec;
use std::vec::Vec;

/// The uniform grid index: for each cell, the edges whose geometry, widened by a small margin
/// against rounding, may meet the cell: a straight (terrain or Voronoi) edge's segment, a
/// Dubins edge's primitives' bounding boxes, a landmark chain's pieces' Bernstein boxes. A
/// superset of the edges whose geometry passes through the cell, which is what pop-up pruning
/// needs.
pub(super) struct GridIndex {
    pub(super) origin: Vec2,
    pub(super) nx: u32,
    pub(super) ny: u32,
    /// Byte offsets of each cell's list in `lists` (nx·ny + 1).
    pub(super) offsets: Vec<u32>,
    /// The cells' lists, each strictly increasing edge indices delta-coded as varints.
    pub(super) lists: Vec<u8>,
}

impl GridIndex {
    pub(super) fn build(
        spec: &NetworkSpec,
        edges: &[EdgeSpec],
        chains: &[&[LineElement]],
    ) -> Result<Self, WriteError> {
        let cell = spec.grid_cell_m;
        let reach = 4.0 * spec.turn_radius_m + cell;
        let (mut lo, mut hi) = if spec.vertices.is_empty() {
            (Vec2::default(), Vec2::default())
        } else {
            points_bounding_box(spec.vertices.iter().map(|v| v.position))
        };
        // Landmark mode: the pieces, and every edge's reach (the box the loader checks).
        let mut pieces: Vec<Vec<(Vec2, Vec2)>> = Vec::new();
        if let Some(l) = &spec.landmark {
            for (e, chain) in edges.iter().zip(chains) {
                let mut boxes = Vec::with_capacity(chain.len().saturating_sub(1));
                for w in chain.windows(2) {
                    let seg = HermiteSegment::new(&w[0], &w[1], l.v_nominal)
                        .map_err(|_| WriteError::BadLandmark("a piece cannot be built"))?;
                    boxes.push(seg.bounding_box());
                }
                pieces.push(boxes);
                if let (Some(a), Some(b)) = (chain.first(), chain.last()) {
                    let mid = (a.position + b.position) * 0.5;
                    let r =
                        0.5 * e.lengths[0] * (1.0 + 1e-4) + 0.01 + reach - 4.0 * spec.turn_radius_m;
                    lo = Vec2::new(lo.x.min(mid.x - r), lo.y.min(mid.y - r));
                    hi = Vec2::new(hi.x.max(mid.x + r), hi.y.max(mid.y + r));
                }
            }
        }
        let origin = Vec2::new(lo.x - reach, lo.y - reach);
        let (nx, ny) = grid_cells(cell, hi.x - lo.x + 2.0 * reach, hi.y - lo.y + 2.0 * reach)?;
        // At most MAX_GRID_CELLS: the product fits.
        let mut cells: Vec<Vec<u32>> = vec![Vec::new(); nx as usize * ny as usize];
        let margin = 1e-3 * cell + 0.01;
        let cx = |v: f32| (((v - origin.x) / cell).floor().max(0.0) as u32).min(nx - 1);
        let cy = |v: f32| (((v - origin.y) / cell).floor().max(0.0) as u32).min(ny - 1);
        if spec.landmark.is_some() {
            // Each piece's Bernstein box, widened by the clearance and the margin.
            let w = spec.clearance_m + margin;
            for (i, boxes) in pieces.iter().enumerate() {
                let mut touched: Vec<u32> = Vec::new();
                for (a, b) in boxes {
                    for y in cy(a.y - w)..=cy(b.y + w) {
                        for x in cx(a.x - w)..=cx(b.x + w) {
                            touched.push(y * nx + x);
                        }
                    }
                }
                touched.sort_unstable();
                touched.dedup();
                for c in touched {
                    cells[c as usize].push(i as u32);
                }
            }
        }
        // Terrain and Voronoi edges are straight lines: each is listed in the cells its segment,
        // widened by the margin, meets (`segment_cells`: complete, and exact up to its rounding
        // slack), far fewer than its bounding box overlaps when it runs diagonally.
        let line_edges = spec.terrain.is_some() || spec.voronoi.is_some();
        let index_grid = CellGrid {
            origin,
            cell,
            cols: nx,
            rows: ny,
        };
        for (i, e) in edges.iter().enumerate() {
            if spec.landmark.is_some() {
                break;
            }
            let mut start = spec.vertices[e.source as usize];
            let end = spec.vertices[e.target as usize].position;
            let mut touched: Vec<u32> = Vec::new();
            let listed_exactly = line_edges
                && segment_cells(
                    &index_grid,
                    &Segment::new(start.position, end),
                    margin,
                    |x, y| {
                        touched.push(y * nx + x);
                        true
                    },
                )
                .is_ok();
            if !listed_exactly {
                // Each primitive's bounding box, widened by the margin (also a straight edge
                // whose traversal refuses its coordinates).
                touched.clear();
                if line_edges {
                    let d = end - start.position;
                    start.heading = d.y.atan2(d.x);
                }
                let path = DubinsPath {
                    start,
                    radius: spec.turn_radius_m,
                    word: e.word,
                    lengths: e.lengths,
                };
                for prim in path.primitives().into_iter().flatten() {
                    let (a, b) = prim.bounding_box();
                    for y in cy(a.y - margin)..=cy(b.y + margin) {
                        for x in cx(a.x - margin)..=cx(b.x + margin) {
                            touched.push(y * nx + x);
                        }
                    }
                }
            }
            touched.sort_unstable();
            touched.dedup();
            for c in touched {
                cells[c as usize].push(i as u32);
            }
        }
        let mut offsets = Vec::with_capacity(cells.len() + 1);
        let mut lists = Vec::new();
        offsets.push(0);
        for c in &cells {
            // Edges are pushed in increasing order, once per cell: the first index, then each
            // difference minus one, as postcard varints.
            let mut previous: Option<u32> = None;
            for &e in c {
                let delta = previous.map_or(e, |p| e - p - 1);
                lists.extend_from_slice(
                    &postcard::to_stdvec(&delta)
                        .map_err(|_| WriteError::TooLarge("grid entries"))?,
                );
                previous = Some(e);
            }
            offsets.push(count(lists.len(), "grid list bytes")?);
        }
        Ok(GridIndex {
            origin,
            nx,
            ny,
            offsets,
            lists,
        })
    }
}
