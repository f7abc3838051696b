//! The build: parameters checked, the metric grid (step 1), the nodes at the blocked
//! regions' convex corners (step 2) and the visibility edges between them (step 3).

use super::cells::{is_blocked, segment_clear};
use super::grid::{elevation_coding, highest_elevations, metric_grid};
use super::types::{TerrainError, TerrainGraph, TerrainParams, TerrainStats};
use crate::dem::{Dem, Placement};
use crate::frame::LocalFrame;
use rayon::prelude::*;
use skyroute::geometry::grid::{segment_cells, CellGrid};
use skyroute::network::elevation::ELEVATION_BLOCKED;
use skyroute::{Segment, Vec2};
use std::time::Instant;

/// Builds the metric occupancy grid and the visibility graph of `dem` in `frame` for flight at
/// `altitude_m` keeping `safety_height_m` above the ground and `clearance_m` plus half of
/// `wingspan_m` horizontally from blocked terrain. See the [module documentation](super).
pub fn build_terrain_graph(
    dem: &Dem,
    frame: &LocalFrame,
    altitude_m: f64,
    safety_height_m: f64,
    clearance_m: f64,
    wingspan_m: f64,
    params: &TerrainParams,
) -> Result<TerrainGraph, TerrainError> {
    let placement = Placement::new(dem.units, frame).ok_or(TerrainError::ProjectedDem)?;
    check_parameters(altitude_m, safety_height_m, clearance_m, wingspan_m, params)?;
    let mut stats = TerrainStats {
        dem_cells: dem.ncols * dem.nrows,
        ..TerrainStats::default()
    };

    // ---- 1. The metric grid.
    let t0 = Instant::now();
    let grid = metric_grid(dem, &placement, params, &mut stats)?;
    // DEM navigability (for the statistics), then each metric cell's highest DEM elevation
    // over the DEM cells its footprint's box meets, encoded rounding up.
    let (nc, nr) = (dem.ncols, dem.nrows);
    stats.dem_blocked = (0..nr * nc)
        .into_par_iter()
        .filter(|&i| !dem.is_navigable(i % nc, i / nc, altitude_m, safety_height_m))
        .count();
    let coding = elevation_coding(dem)?;
    let highest = highest_elevations(dem, &placement, &grid, &mut stats);
    let codes: Vec<u8> = highest
        .iter()
        .map(|h| h.map_or(ELEVATION_BLOCKED, |e| coding.encode(e)))
        .collect();
    let blocking = coding.blocking_code(altitude_m as f32, safety_height_m as f32);
    let blocked: Vec<bool> = codes.iter().map(|&k| k >= blocking).collect();
    stats.cells = blocked.len();
    stats.blocked_cells = blocked.iter().filter(|&&b| b).count();
    stats.outside_cells = highest.iter().filter(|h| h.is_none()).count();
    stats.grid_time = t0.elapsed();

    // ---- 2. Nodes.
    let t1 = Instant::now();
    let widen = (0.5 * wingspan_m + clearance_m) as f32;
    let d = 0.5 * wingspan_m + clearance_m + params.node_margin_m;
    let blocked_at = |a: f64| -> Vec<bool> {
        let b = coding.blocking_code(a as f32, safety_height_m as f32);
        codes.iter().map(|&k| k >= b).collect()
    };
    let levels: Vec<Vec<bool>> = params
        .extra_altitudes_m
        .iter()
        .map(|&a| blocked_at(a))
        .collect();
    let mut nodes = place_nodes(&grid, &blocked, &levels, d, widen, &mut stats)?;
    let placed = nodes.len();
    if params.min_node_spacing_m > 0.0 {
        nodes = thin(&nodes, params.min_node_spacing_m);
    }
    nodes.sort_by(|a, b| a.0.x.total_cmp(&b.0.x).then(a.0.y.total_cmp(&b.0.y)));
    nodes.dedup_by(|a, b| a.0 == b.0);
    stats.dropped_thinned = placed - nodes.len();
    let quadrants: Vec<[i8; 2]> = nodes.iter().map(|n| n.1).collect();
    let node_levels: Vec<u8> = nodes.iter().map(|n| n.2).collect();
    let nodes: Vec<Vec2> = nodes.into_iter().map(|n| n.0).collect();
    stats.nodes = nodes.len();
    stats.node_time = t1.elapsed();

    // ---- 3. Edges: between nodes of the same altitude level, tested at that level, so that
    // each level's graph is whole at its altitude (and usable at any higher one).
    let t2 = Instant::now();
    let level_blocked = |level: u8| match level {
        0 => &blocked,
        l => &levels[l as usize - 1],
    };
    let edges = visibility_edges(
        &grid,
        &nodes,
        &quadrants,
        &node_levels,
        &level_blocked,
        widen,
        params,
        &mut stats,
    );
    stats.edge_time = t2.elapsed();

    Ok(TerrainGraph {
        grid,
        coding,
        codes,
        blocking_code: blocking,
        blocked,
        quadrants,
        levels: node_levels,
        widen_m: widen,
        nodes,
        edges,
        stats,
    })
}

/// Checks that every parameter is finite and in range.
fn check_parameters(
    altitude_m: f64,
    safety_height_m: f64,
    clearance_m: f64,
    wingspan_m: f64,
    params: &TerrainParams,
) -> Result<(), TerrainError> {
    let bad = |name: &str, v: f64| Err(TerrainError::InvalidParameter(format!("{name} = {v}")));
    if !altitude_m.is_finite() {
        return bad("altitude_m", altitude_m);
    }
    if !(safety_height_m.is_finite() && safety_height_m >= 0.0) {
        return bad("safety_height_m", safety_height_m);
    }
    if !(clearance_m.is_finite() && clearance_m >= 0.0) {
        return bad("clearance_m", clearance_m);
    }
    if !(wingspan_m.is_finite() && wingspan_m > 0.0) {
        return bad("wingspan_m", wingspan_m);
    }
    if !(params.node_margin_m.is_finite() && params.node_margin_m > 0.0) {
        return bad("node_margin_m", params.node_margin_m);
    }
    if !(params.min_node_spacing_m.is_finite() && params.min_node_spacing_m >= 0.0) {
        return bad("min_node_spacing_m", params.min_node_spacing_m);
    }
    if let Some(m) = params.max_edge_m {
        if !(m.is_finite() && m > 0.0) {
            return bad("max_edge_m", m);
        }
    }
    if let Some(&a) = params.extra_altitudes_m.iter().find(|a| !a.is_finite()) {
        return bad("extra_altitudes_m", a);
    }
    if let Some(c) = params.cell_m {
        if !(c.is_finite() && c > 0.0) {
            return bad("cell_m", c);
        }
    }
    Ok(())
}

/// The nodes: at every grid vertex with exactly one blocked cell around it (at the network's
/// altitude, then at each extra level), offset by `d` away from that cell, unless the node's
/// `widen` box leaves the grid or meets a blocked cell; each with its quadrant and level.
fn place_nodes(
    grid: &CellGrid,
    blocked: &[bool],
    levels: &[Vec<bool>],
    d: f64,
    widen: f32,
    stats: &mut TerrainStats,
) -> Result<Vec<(Vec2, [i8; 2], u8)>, TerrainError> {
    let (cols, rows) = (grid.cols as usize, grid.rows as usize);
    let cell_f = grid.cell as f64;
    let (gx, gy) = (grid.origin.x as f64, grid.origin.y as f64);
    let vertex_local = |c: usize, r: usize| (gx + c as f64 * cell_f, gy + r as f64 * cell_f);
    let mut nodes = Vec::new();
    for (level, blocked) in std::iter::once(blocked)
        .chain(levels.iter().map(Vec::as_slice))
        .enumerate()
    {
        for vr in 0..=rows as i64 {
            for vc in 0..=cols as i64 {
                // The cells around the vertex and the direction from it to each.
                let around = [
                    (vc - 1, vr - 1, -1.0, -1.0),
                    (vc, vr - 1, 1.0, -1.0),
                    (vc - 1, vr, -1.0, 1.0),
                    (vc, vr, 1.0, 1.0),
                ];
                let mut n_blocked = 0;
                let mut dir = (0.0, 0.0);
                for &(c, r, sx, sy) in &around {
                    if is_blocked(grid, blocked, c, r) {
                        n_blocked += 1;
                        dir = (sx, sy);
                    }
                }
                if n_blocked != 1 {
                    continue;
                }
                stats.corners += 1;
                let (x, y) = vertex_local(vc as usize, vr as usize);
                let p = Vec2::new((x - dir.0 * d) as f32, (y - dir.1 * d) as f32);
                let w = Vec2::new(widen, widen);
                if !grid.covers(p - w, p + w) {
                    stats.dropped_outside += 1;
                    continue;
                }
                let mut hit = false;
                segment_cells(grid, &Segment::new(p, p), widen, |c, r| {
                    hit = blocked[r as usize * cols + c as usize];
                    !hit
                })?;
                if hit {
                    stats.dropped_blocked += 1;
                    continue;
                }
                nodes.push((p, [dir.0 as i8, dir.1 as i8], level as u8));
            }
        }
    }
    Ok(nodes)
}

/// The visibility edges: both directions of every pair of same-level nodes at most
/// `max_edge_m` apart (and, with `tangent_edges_only`, tangent to both nodes' corners) whose
/// segment, widened by `widen`, meets no cell blocked at their level. Sorted by (from, to).
#[allow(clippy::too_many_arguments)]
fn visibility_edges<'b>(
    grid: &CellGrid,
    nodes: &[Vec2],
    quadrants: &[[i8; 2]],
    node_levels: &[u8],
    level_blocked: &(dyn Fn(u8) -> &'b Vec<bool> + Sync),
    widen: f32,
    params: &TerrainParams,
    stats: &mut TerrainStats,
) -> Vec<(u32, u32, f32)> {
    let max_edge = params.max_edge_m.map_or(f32::INFINITY, |m| m as f32);
    let per_node: Vec<NodeEdges> = (0..nodes.len())
        .into_par_iter()
        .map(|i| {
            let a = nodes[i];
            let mut out = Vec::new();
            let (mut tested, mut visited) = (0u64, 0u64);
            for (j, &b) in nodes.iter().enumerate().skip(i + 1) {
                if b.x - a.x > max_edge {
                    break; // sorted by x
                }
                let len = a.distance(b);
                if len > max_edge {
                    continue;
                }
                if params.tangent_edges_only
                    && !(is_tangent(quadrants[i], b - a) && is_tangent(quadrants[j], b - a))
                {
                    continue;
                }
                let level = node_levels[i];
                if node_levels[j] != level {
                    continue;
                }
                let level_blocked = level_blocked(level);
                tested += 1;
                let (clear, n) = segment_clear(grid, level_blocked, widen, a, b);
                visited += n;
                if clear {
                    out.push((i as u32, j as u32, len));
                }
            }
            (out, tested, visited)
        })
        .collect();
    let mut edges = Vec::new();
    for (out, tested, visited) in per_node {
        stats.pairs_tested += tested;
        stats.cells_visited += visited;
        stats.undirected_edges += out.len();
        for (i, j, len) in out {
            edges.push((i, j, len));
            edges.push((j, i, len));
        }
    }
    edges.sort_unstable_by_key(|&(i, j, _)| (i, j));
    edges
}

/// The edges found from one node to the later ones, with the pairs tested and cells visited.
type NodeEdges = (Vec<(u32, u32, f32)>, u64, u64);

/// Whether the line through a node in direction `u` stays out of the interior of the node's
/// blocked quadrant `s` on both sides of the node: `(s_x u_x)(s_y u_y) ≤ 0`. The grown region
/// near the node is the quadrant `{s_x(x − p_x) ≥ 0, s_y(y − p_y) ≥ 0}`; the point `p + t u`
/// is inside it iff `s_x u_x t > 0` and `s_y u_y t > 0`, for some `t` of either sign iff the
/// two products have the same strict sign.
fn is_tangent(s: [i8; 2], u: Vec2) -> bool {
    (s[0] as f32 * u.x) * (s[1] as f32 * u.y) <= 0.0
}

/// Greedy thinning in the given order: keeps a node unless a kept one lies within `spacing`.
fn thin(nodes: &[(Vec2, [i8; 2], u8)], spacing: f64) -> Vec<(Vec2, [i8; 2], u8)> {
    use std::collections::HashMap;
    let s = spacing as f32;
    let key = |p: Vec2| ((p.x / s).floor() as i64, (p.y / s).floor() as i64);
    let mut buckets: HashMap<(i64, i64), Vec<Vec2>> = HashMap::new();
    let mut kept = Vec::new();
    for &(p, quadrant, level) in nodes {
        let (kx, ky) = key(p);
        let near = (-1..=1).any(|dx| {
            (-1..=1).any(|dy| {
                buckets
                    .get(&(kx + dx, ky + dy))
                    .is_some_and(|v| v.iter().any(|q| q.distance(p) < s))
            })
        });
        if !near {
            buckets.entry((kx, ky)).or_default().push(p);
            kept.push((p, quadrant, level));
        }
    }
    kept
}
