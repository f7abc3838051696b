//! Step 1 of the build: the metric occupancy grid over the DEM, and each cell's highest DEM
//! elevation, encoded.

use super::types::{TerrainError, TerrainParams, TerrainStats};
use crate::dem::{Dem, Placement, Units};
use rayon::prelude::*;
use skyroute::geometry::grid::{CellGrid, MAX_CELLS_PER_AXIS};
use skyroute::network::elevation::{ElevationCoding, ELEVATION_BLOCKED};
use skyroute::Vec2;

/// How many DEM cells are not navigable at `altitude_m` with `safety_height_m` (NODATA cells
/// included): [`Dem::is_navigable`] over the grid.
pub fn blocked_cells_at(dem: &Dem, altitude_m: f64, safety_height_m: f64) -> usize {
    (0..dem.nrows)
        .flat_map(|r| (0..dem.ncols).map(move |c| (c, r)))
        .filter(|&(c, r)| !dem.is_navigable(c, r, altitude_m, safety_height_m))
        .count()
}

/// The elevation coding for `dem`: base at its lowest elevation (rounded down to a metre), step
/// such that its highest elevation encodes below [`ELEVATION_BLOCKED`].
pub fn elevation_coding(dem: &Dem) -> Result<ElevationCoding, TerrainError> {
    let (Some(lo), Some(hi)) = (dem.min(), dem.max()) else {
        return Err(TerrainError::InvalidParameter(
            "the DEM has no elevation (every cell is NODATA)".into(),
        ));
    };
    let base = lo.floor();
    let mut step = (((hi - base) as f64 / 253.0).max(0.01)) as f32;
    let mut coding = ElevationCoding {
        base_m: base,
        step_m: step,
    };
    while coding.encode(hi) == ELEVATION_BLOCKED {
        step *= 1.001;
        coding = ElevationCoding {
            base_m: base,
            step_m: step,
        };
    }
    Ok(coding)
}

/// The metric sides of a DEM cell in the frame, `((min, max) along the DEM's x, (min, max)
/// along its y)`, metres, at the four corners of the DEM and its centre (the sides vary
/// monotonically with latitude and distance from the central meridian).
fn dem_cell_sides(dem: &Dem, frame: &Placement) -> ((f64, f64), (f64, f64)) {
    let (x0, y0, csx, csy) = (dem.xllcorner, dem.yllcorner, dem.cell_x, dem.cell_y);
    let (nc, nr) = (dem.ncols, dem.nrows);
    let dem_corner = |c: usize, r: usize| (x0 + c as f64 * csx, y0 + r as f64 * csy);
    let dist = |a: (f64, f64), b: (f64, f64)| (a.0 - b.0).hypot(a.1 - b.1);
    let (mut ew, mut ns) = ((f64::MAX, 0.0f64), (f64::MAX, 0.0f64));
    for (c, r) in [
        (0, 0),
        (nc - 1, 0),
        (0, nr - 1),
        (nc - 1, nr - 1),
        (nc / 2, nr / 2),
    ] {
        let (lon, lat) = dem_corner(c, r);
        let p = frame.to_local(lon, lat);
        let e = dist(p, frame.to_local(lon + csx, lat));
        let n = dist(p, frame.to_local(lon, lat + csy));
        ew = (ew.0.min(e), ew.1.max(e));
        ns = (ns.0.min(n), ns.1.max(n));
    }
    (ew, ns)
}

/// The box `[min x, min y, max x, max y]` of the DEM's outline in `frame`; records in `stats`
/// how far the DEM's corners lie from an axis-aligned grid.
fn dem_outline(dem: &Dem, frame: &Placement, stats: &mut TerrainStats) -> [f64; 4] {
    let (x0, y0, csx, csy) = (dem.xllcorner, dem.yllcorner, dem.cell_x, dem.cell_y);
    let (nc, nr) = (dem.ncols, dem.nrows);
    let dem_corner = |c: usize, r: usize| (x0 + c as f64 * csx, y0 + r as f64 * csy);
    let dist = |a: (f64, f64), b: (f64, f64)| (a.0 - b.0).hypot(a.1 - b.1);
    // The DEM's corners in the frame: its outline for the extent, all of them for the
    // comparison with an axis-aligned grid.
    let (lon_c, lat_c) = (x0 + 0.5 * nc as f64 * csx, y0 + 0.5 * nr as f64 * csy);
    let (xc, yc) = frame.to_local(lon_c, lat_c);
    // A step of 1e-4 degrees, or of 1 m in a projected DEM.
    let h = if dem.units == Units::Geographic {
        1e-4
    } else {
        1.0
    };
    let sx = (frame.to_local(lon_c + h, lat_c).0 - frame.to_local(lon_c - h, lat_c).0) / (2.0 * h);
    let sy = (frame.to_local(lon_c, lat_c + h).1 - frame.to_local(lon_c, lat_c - h).1) / (2.0 * h);
    let per_row: Vec<(f64, [f64; 4])> = (0..=nr)
        .into_par_iter()
        .map(|r| {
            let mut worst: f64 = 0.0;
            let mut bb = [f64::MAX, f64::MAX, f64::MIN, f64::MIN];
            for c in 0..=nc {
                let (lon, lat) = dem_corner(c, r);
                let p = frame.to_local(lon, lat);
                let q = (xc + (lon - lon_c) * sx, yc + (lat - lat_c) * sy);
                worst = worst.max(dist(p, q));
                if r == 0 || r == nr || c == 0 || c == nc {
                    bb = [
                        bb[0].min(p.0),
                        bb[1].min(p.1),
                        bb[2].max(p.0),
                        bb[3].max(p.1),
                    ];
                }
            }
            (worst, bb)
        })
        .collect();
    let mut bb = [f64::MAX, f64::MAX, f64::MIN, f64::MIN];
    for (worst, b) in &per_row {
        stats.axis_aligned_offset_m = stats.axis_aligned_offset_m.max(*worst);
        bb = [
            bb[0].min(b[0]),
            bb[1].min(b[1]),
            bb[2].max(b[2]),
            bb[3].max(b[3]),
        ];
    }
    bb
}

/// The metric grid over the DEM's outline (cell side `cell_m`, or the DEM cell's smallest
/// metric side); records the cell sides in `stats`.
pub(super) fn metric_grid(
    dem: &Dem,
    frame: &Placement,
    params: &TerrainParams,
    stats: &mut TerrainStats,
) -> Result<CellGrid, TerrainError> {
    let (ew, ns) = dem_cell_sides(dem, frame);
    stats.dem_cell_ew_m = ew;
    stats.dem_cell_ns_m = ns;
    let cell = params.cell_m.unwrap_or(ew.0.min(ns.0)) as f32;
    let cell_f = cell as f64;
    let bb = dem_outline(dem, frame, stats);
    let ox = (bb[0] - 1.0).floor();
    let oy = (bb[1] - 1.0).floor();
    let cols_f = ((bb[2] + 1.0 - ox) / cell_f).ceil();
    let rows_f = ((bb[3] + 1.0 - oy) / cell_f).ceil();
    if !(cols_f <= MAX_CELLS_PER_AXIS as f64 && rows_f <= MAX_CELLS_PER_AXIS as f64)
        || cols_f * rows_f > crate::dem::MAX_CELLS as f64
    {
        return Err(TerrainError::TooLarge {
            cols: cols_f as u64,
            rows: rows_f as u64,
        });
    }
    let (cols, rows) = (cols_f as usize, rows_f as usize);
    let grid = CellGrid::new(
        Vec2::new(ox as f32, oy as f32),
        cell,
        cols as u32,
        rows as u32,
    );
    grid.validate()?;
    Ok(grid)
}

/// Each metric cell's highest DEM elevation over the DEM cells its footprint's box (padded by
/// the bow of the cell edges) meets, NaN for NODATA, `None` where the footprint reaches
/// outside the DEM; records the bow and the pad in `stats`.
pub(super) fn highest_elevations(
    dem: &Dem,
    frame: &Placement,
    grid: &CellGrid,
    stats: &mut TerrainStats,
) -> Vec<Option<f32>> {
    let (x0, y0, csx, csy) = (dem.xllcorner, dem.yllcorner, dem.cell_x, dem.cell_y);
    let (nc, nr) = (dem.ncols, dem.nrows);
    let (ew, ns) = (stats.dem_cell_ew_m, stats.dem_cell_ns_m);
    let (cols, rows) = (grid.cols as usize, grid.rows as usize);
    let cell_f = grid.cell as f64;
    let (gx, gy) = (grid.origin.x as f64, grid.origin.y as f64);
    let vertex_local = |c: usize, r: usize| (gx + c as f64 * cell_f, gy + r as f64 * cell_f);

    // Every grid vertex in the DEM's coordinates.
    let vertices: Vec<(f64, f64)> = (0..=rows)
        .into_par_iter()
        .flat_map_iter(|r| {
            (0..=cols).map(move |c| {
                let (x, y) = vertex_local(c, r);
                frame.to_dem(x, y)
            })
        })
        .collect();
    let vtx = |c: usize, r: usize| vertices[r * (cols + 1) + c];

    // Metres per DEM unit (degree or metre), the smallest on the DEM (to turn metres into DEM
    // units conservatively), and the bow of the metric cell edges along the grid's outline.
    let m_per_deg_lon = ew.0 / csx;
    let m_per_deg_lat = ns.0 / csy;
    let bow = |a: (usize, usize), b: (usize, usize)| {
        let (pa, pb) = (vertex_local(a.0, a.1), vertex_local(b.0, b.1));
        let mid = frame.to_dem(0.5 * (pa.0 + pb.0), 0.5 * (pa.1 + pb.1));
        let (ga, gb) = (vtx(a.0, a.1), vtx(b.0, b.1));
        let chord = (0.5 * (ga.0 + gb.0), 0.5 * (ga.1 + gb.1));
        // DEM units to metres with the largest metres per unit (an upper bound).
        let (ml, mp) = (ew.1 / csx, ns.1 / csy);
        ((mid.0 - chord.0) * ml).hypot((mid.1 - chord.1) * mp)
    };
    let mut edge_bow: f64 = 0.0;
    for c in 0..cols {
        for r in [0, rows] {
            edge_bow = edge_bow.max(bow((c, r), (c + 1, r)));
        }
    }
    for r in 0..rows {
        for c in [0, cols] {
            edge_bow = edge_bow.max(bow((c, r), (c, r + 1)));
        }
    }
    stats.edge_bow_m = edge_bow;
    stats.pad_m = 2.0 * edge_bow + 0.01;
    let pad_lon = stats.pad_m / m_per_deg_lon;
    let pad_lat = stats.pad_m / m_per_deg_lat;

    // Indices i in 0..n whose closed interval [i, i + 1] meets [lo, hi]; Err when it reaches
    // outside [0, n].
    let range = |lo: f64, hi: f64, n: usize| -> Result<(usize, usize), ()> {
        if !(lo >= 0.0 && hi <= n as f64) {
            return Err(());
        }
        let a = (lo.ceil() - 1.0).max(0.0);
        let b = hi.floor().min((n - 1) as f64);
        Ok((a as usize, b as usize))
    };
    // `None`: the footprint reaches outside the DEM.
    let highest: Vec<Option<f32>> = (0..rows * cols)
        .into_par_iter()
        .map(|i| {
            let (c, r) = (i % cols, i / cols);
            let corners = [vtx(c, r), vtx(c + 1, r), vtx(c, r + 1), vtx(c + 1, r + 1)];
            let lon_lo = corners.iter().map(|p| p.0).fold(f64::MAX, f64::min) - pad_lon;
            let lon_hi = corners.iter().map(|p| p.0).fold(f64::MIN, f64::max) + pad_lon;
            let lat_lo = corners.iter().map(|p| p.1).fold(f64::MAX, f64::min) - pad_lat;
            let lat_hi = corners.iter().map(|p| p.1).fold(f64::MIN, f64::max) + pad_lat;
            let dc = range((lon_lo - x0) / csx, (lon_hi - x0) / csx, nc);
            let dr = range((lat_lo - y0) / csy, (lat_hi - y0) / csy, nr);
            match (dc, dr) {
                (Ok((c0, c1)), Ok((r0, r1))) => Some(
                    (r0..=r1)
                        .flat_map(|rr| (c0..=c1).map(move |cc| dem.values()[rr * nc + cc]))
                        // NaN (NODATA) wins the maximum: encoded as blocked.
                        .fold(f32::NEG_INFINITY, |m, e| {
                            if e.is_nan() || m.is_nan() {
                                f32::NAN
                            } else {
                                m.max(e)
                            }
                        }),
                ),
                _ => None,
            }
        })
        .collect();
    highest
}
