//! Terrain mode (Medeiros & da Silva, issue 5): the DEM's blocked cells as a metric occupancy grid
//! in the scenario's local frame, and a visibility graph around them.
//!
//! An aircraft flying at altitude `a_n` that must keep the safety height `a_s` above the ground
//! may not fly over a DEM cell whose elevation is `≥ a_n − a_s`; NODATA cells and everything
//! outside the DEM count as blocked too ([`Dem::is_navigable`]). [`build_terrain_graph`] turns
//! that into a [`TerrainGraph`] in three steps.
//!
//! # 1. The metric grid
//!
//! A geographic DEM's cells are not squares in metres (3″ at 36.5° N: about 74.6 m east–west by
//! 92.6 m north–south), and in the transverse Mercator frame ([`LocalFrame`]) they are not even
//! axis-aligned: grid north differs from true north by the meridian convergence
//! γ ≈ Δλ·sin φ, and the metres per degree of longitude change with latitude. Neither is assumed
//! away. Instead a [`CellGrid`] of square cells is laid over the frame and each metric cell is
//! mapped *back* onto the DEM:
//!
//! * **Cell size**: [`TerrainParams::cell_m`], by default the smallest metric side of a DEM
//!   cell at the DEM's four corners and centre (the east–west side at the northern edge; within
//!   the projection's scale error `k − 1 ≤ 1e-5` of the smallest anywhere), as an `f32`.
//! * **Extent**: the bounding box of the DEM's outline projected into the frame (every corner
//!   along the outline), widened by 1 m; the origin is rounded down to whole metres.
//! * **Elevation and blocked cells**: every grid vertex is mapped to `(lon, lat)` with
//!   [`LocalFrame::to_geo`]. A metric cell's footprint on the ellipsoid is the quadrilateral of
//!   its four mapped corners (the edges are not exactly straight in `(lon, lat)`, see below);
//!   its longitude/latitude bounding box, widened by a pad, is intersected with the DEM's cells
//!   as *closed* rectangles (touching counts). The metric cell's elevation is the highest
//!   elevation of the DEM cells it meets, encoded rounding **up** into one byte
//!   ([`ElevationCoding`], base the DEM's lowest metre, 254 steps to its highest: 3.3 m on the
//!   Jacksboro DEM); a box reaching outside the DEM, or meeting a NODATA cell, gets
//!   [`ELEVATION_BLOCKED`]. A cell is blocked at an altitude when its code is at least the
//!   altitude's blocking code — the very table and test the aircraft uses, so ground and air
//!   agree cell for cell. So the union of the blocked metric cells contains the footprint of
//!   every blocked DEM cell: **conservative**, never optimistic. The price is that blocked
//!   regions grow by up to about one metric cell plus one DEM cell (the box of a cell rotated
//!   by γ is a little larger than the cell, and a DEM cell is blocked whole), and cells within
//!   one step (3.3 m) below the threshold count as blocked.
//! * **Error of the footprint**: the only approximation is the straight-edged quadrilateral
//!   (and its bounding box) standing for the image of a straight metric edge, which bows in
//!   `(lon, lat)`. The bow is measured on every edge along the grid's outline (the largest
//!   distance from the central meridian, and the extreme latitudes) as the distance between
//!   the mapped midpoint of an edge and the midpoint of its mapped ends, in metres; over a
//!   30 km DEM it is a fraction of a millimetre ([`TerrainStats::edge_bow_m`]). The box is
//!   widened by `pad = 2·bow + 1 cm` ([`TerrainStats::pad_m`]), converted to degrees with the
//!   smallest metres per degree on the DEM, so it needs no addition to the safety margin.
//! * **For comparison** ([`TerrainStats::axis_aligned_offset_m`]): had the DEM been taken as an
//!   axis-aligned grid in the frame (metres per degree fixed at the DEM's centre, no rotation),
//!   its corners would be off by that much — 48 m at the corners of the Jacksboro DEM, from
//!   the meridian convergence changing by about ±0.1° across it and the metres per degree of
//!   longitude by about ±0.2 % (roughly 28 m each): over half a cell, not negligible, hence
//!   the back-mapping, whose own error is the sub-millimetre bow, covered by the pad.
//!
//! # 2. Nodes at the corners of the blocked regions
//!
//! The paper places the visibility graph's nodes at the safety distance from the corners of the
//! obstacle regions. Here the regions are unions of closed grid squares, and only their
//! **convex** corners get a node: grid vertices where exactly one of the four cells around is
//! blocked (cells outside the grid counting as blocked). Concave corners need none — a shortest
//! path among obstacles bends only at convex vertices (Lozano-Pérez & Wesley 1979).
//!
//! With `widen = wingspan/2 + clearance` the half-width every edge must keep free, the node of a
//! convex corner `V` whose blocked cell lies in the quadrant `s = (±1, ±1)` is
//! `V − s·d` with `d = widen + node_margin`: offset by `d` along **both** axes, i.e. the corner
//! of the blocked region grown by `d` in the max-norm (a mitred offset polygon), `d·√2` from `V`
//! along the outward diagonal. Why not the clearance along the diagonal, as a literal reading
//! of "nodes at the safety distance from the corners" would give: such a node lies within
//! `widen` of its own corner and would be dropped by the check below; and two nodes off the two
//! ends of a straight side of a region must see each other, but the segment between them runs
//! parallel to the side at the nodes' *axis* offset, which must therefore be at least `widen`.
//! The margin (default 1 m) keeps those side-parallel edges clear of rounding: the traversal
//! visits cells up to `3δ` cells beyond `widen` (`skyroute::geometry::grid`), about 0.2 m on a
//! grid of 430 cells across, growing with the grid's size. The turn radius plays no part: the
//! graph is one of straight legs; a smoother that rounds its corners with arcs must check the
//! arcs again (`skyroute::geometry::grid::arc_cells`) — the fillet of a turn around a region
//! lies on the region's side of the corner.
//!
//! A node is dropped if its disc of radius `widen` is not inside the grid ([`CellGrid::covers`])
//! or meets a blocked cell ([`segment_cells`] on the zero-length segment, which visits every
//! cell within `widen` of the point). Then, if [`TerrainParams::min_node_spacing_m`] is
//! positive, nodes are thinned greedily in generation order (grid vertices row by row from the
//! south, west to east): a node within that distance of an already kept one is dropped. (The
//! raster's staircases along oblique boundaries make many corners close together; thinning
//! trades a little path length for a smaller graph. Off by default.) The nodes are finally
//! sorted by `(x, y)`, exact duplicates removed.
//!
//! With [`TerrainParams::extra_altitudes_m`], the corners of the blocked regions at each further
//! altitude get nodes too (tagged with their level), so that an aircraft that descends in flight
//! still finds nodes around the larger regions.
//!
//! # 3. Edges
//!
//! Every pair of nodes of the same level at most [`TerrainParams::max_edge_m`] apart (all pairs
//! for `None`) is joined if the straight segment's capsule of radius `widen` meets no cell
//! blocked at that level's altitude ([`segment_cells`], stopping at the first blocked cell).
//! Since both nodes' discs lie inside the grid, so does the capsule.
//!
//! **Reduced visibility graph** ([`TerrainParams::tangent_edges_only`], on by default): a
//! shortest path among obstacles bends only at a convex vertex it wraps around, so it uses an
//! edge only if the edge's line is *tangent* to the obstacle at both ends — it does not enter
//! the obstacle on either side of the node (the classical reduced visibility graph, e.g.
//! LaValle, *Planning Algorithms* §6.2.4). At a node the grown region is the quadrant `s` of its
//! corner's blocked cell, and the line in direction `u` stays out of it iff
//! `(s_x u_x)(s_y u_y) ≤ 0`. On Jacksboro at 750 m this keeps 29 442 of 69 444 directed edges
//! (and 0.73 M of 3.7 M turn transitions), the difference between a network that fits a flight
//! computer's search state and one that does not. (A route with turns of a minimum radius can
//! in principle need a non-tangent edge to gain room for a turn; the measured completeness is
//! in `docs/BENCHMARKS.md` and the README.)
//!
//! Pairs are tested in parallel (rayon) and collected in a fixed order, so the result does not
//! depend on the number of threads. Each accepted pair gives both directions, `(i, j, length)`
//! and `(j, i, length)`, sorted by `(from, to)`.

use crate::dem::{Dem, Units};
use crate::frame::LocalFrame;
use rayon::prelude::*;
use skyroute::geometry::grid::{segment_cells, CellGrid, GridError, MAX_CELLS_PER_AXIS};
use skyroute::network::elevation::{ElevationCoding, ELEVATION_BLOCKED};
use skyroute::{Segment, Vec2};
use std::fmt;
use std::time::{Duration, Instant};

/// Tuning of [`build_terrain_graph`].
#[derive(Clone, Debug, PartialEq)]
pub struct TerrainParams {
    /// Side of a metric cell, metres; `None`: the smallest metric side of a DEM cell.
    pub cell_m: Option<f64>,
    /// How much farther than `widen` a node lies from its corner along each axis, metres (> 0).
    pub node_margin_m: f64,
    /// Nodes closer than this to an already kept node are dropped, metres (0: no thinning).
    pub min_node_spacing_m: f64,
    /// Longest edge tried, metres; `None`: every pair.
    pub max_edge_m: Option<f64>,
    /// Keep only edges whose line is tangent to the blocked region at both nodes (the reduced
    /// visibility graph; see the module documentation).
    pub tangent_edges_only: bool,
    /// Further flight altitudes (same safety height) whose region corners also get nodes, so
    /// that the network serves an aircraft that changes altitude in flight. Each level's nodes
    /// are joined among themselves, tested at that level's altitude: the union holds every
    /// level's whole graph, usable at its altitude and any higher one, and the aircraft prunes
    /// what its altitude blocks by the edges' stored elevation codes. Empty: one altitude.
    pub extra_altitudes_m: Vec<f64>,
}

impl Default for TerrainParams {
    fn default() -> Self {
        Self {
            cell_m: None,
            node_margin_m: 1.0,
            min_node_spacing_m: 0.0,
            max_edge_m: Some(10_000.0),
            tangent_edges_only: true,
            extra_altitudes_m: Vec::new(),
        }
    }
}

/// What [`build_terrain_graph`] counted and measured.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TerrainStats {
    /// DEM cells.
    pub dem_cells: usize,
    /// DEM cells not navigable (NODATA included).
    pub dem_blocked: usize,
    /// Smallest and largest east–west side of a DEM cell on the DEM, metres.
    pub dem_cell_ew_m: (f64, f64),
    /// Smallest and largest north–south side of a DEM cell on the DEM, metres.
    pub dem_cell_ns_m: (f64, f64),
    /// Largest offset of a projected DEM corner from an axis-aligned DEM grid (module docs).
    pub axis_aligned_offset_m: f64,
    /// Largest bow of a metric cell edge mapped to `(lon, lat)`, metres (module docs).
    pub edge_bow_m: f64,
    /// The pad added to each metric cell's footprint, metres.
    pub pad_m: f64,
    /// Metric cells.
    pub cells: usize,
    /// Blocked metric cells (those reaching outside the DEM included).
    pub blocked_cells: usize,
    /// Metric cells blocked because they reach outside the DEM.
    pub outside_cells: usize,
    /// Convex corners of the blocked set.
    pub corners: usize,
    /// Nodes dropped because their disc leaves the grid.
    pub dropped_outside: usize,
    /// Nodes dropped because their disc meets a blocked cell.
    pub dropped_blocked: usize,
    /// Nodes dropped by thinning or as exact duplicates.
    pub dropped_thinned: usize,
    /// Nodes kept.
    pub nodes: usize,
    /// Pairs within range, tested for visibility.
    pub pairs_tested: u64,
    /// Cells visited by all the pair tests.
    pub cells_visited: u64,
    /// Pairs joined (undirected edges; the graph holds twice as many directed ones).
    pub undirected_edges: usize,
    /// Time to build the metric grid.
    pub grid_time: Duration,
    /// Time to place the nodes.
    pub node_time: Duration,
    /// Time to test the pairs.
    pub edge_time: Duration,
}

/// The terrain's occupancy grid and visibility graph, in the local frame.
#[derive(Clone, Debug, PartialEq)]
pub struct TerrainGraph {
    /// The metric grid.
    pub grid: CellGrid,
    /// How [`TerrainGraph::codes`] map to metres.
    pub coding: ElevationCoding,
    /// Per cell, row-major from the south: an upper bound of its highest terrain, encoded
    /// ([`ElevationCoding`]; [`ELEVATION_BLOCKED`] for cells reaching outside the DEM or over
    /// NODATA). This is the table the network carries.
    pub codes: Vec<u8>,
    /// Cells with a code at or above this are blocked at the graph's altitude.
    pub blocking_code: u8,
    /// Per cell, row-major from the south: blocked (`codes[i] >= blocking_code`).
    pub blocked: Vec<bool>,
    /// Per node: the quadrant `(±1, ±1)` its corner's blocked cell lies in, seen from the node.
    pub quadrants: Vec<[i8; 2]>,
    /// Per node: its altitude level, 0 for the graph's altitude, `k` for
    /// `TerrainParams::extra_altitudes_m[k − 1]`.
    pub levels: Vec<u8>,
    /// The half-width kept free around every edge and node: `wingspan/2 + clearance`, metres.
    pub widen_m: f32,
    /// The nodes, sorted by `(x, y)`.
    pub nodes: Vec<Vec2>,
    /// Directed edges `(from, to, length in metres)`, both directions, sorted by `(from, to)`.
    pub edges: Vec<(u32, u32, f32)>,
    /// Counts and timings.
    pub stats: TerrainStats,
}

impl TerrainGraph {
    /// Whether metric cell `(col, row)` is blocked; `true` outside the grid.
    pub fn is_blocked(&self, col: i64, row: i64) -> bool {
        is_blocked(&self.grid, &self.blocked, col, row)
    }

    /// Whether the capsule of radius [`TerrainGraph::widen_m`] around the segment `a b` lies
    /// inside the grid and meets no blocked cell (the test every edge passed).
    pub fn segment_clear(&self, a: Vec2, b: Vec2) -> bool {
        segment_clear(&self.grid, &self.blocked, self.widen_m, a, b).0
    }
}

/// Why [`build_terrain_graph`] failed.
#[derive(Clone, Debug, PartialEq)]
pub enum TerrainError {
    /// The DEM is projected: the format carries no coordinate system, so it cannot be placed in
    /// the local frame.
    ProjectedDem,
    /// A parameter is out of range (named, with the value).
    InvalidParameter(String),
    /// The metric grid would have too many columns or rows.
    TooLarge {
        /// Columns.
        cols: u64,
        /// Rows.
        rows: u64,
    },
    /// The traversal refused its input (should not happen for a valid grid).
    Grid(GridError),
}

impl fmt::Display for TerrainError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            TerrainError::ProjectedDem => write!(
                f,
                "the DEM is in projected units; only geographic (lon/lat) DEMs can be placed in \
                 the local frame"
            ),
            TerrainError::InvalidParameter(m) => write!(f, "invalid parameter: {m}"),
            TerrainError::TooLarge { cols, rows } => {
                write!(f, "metric grid of {cols} x {rows} cells is too large")
            }
            TerrainError::Grid(e) => write!(f, "grid traversal: {e}"),
        }
    }
}

impl std::error::Error for TerrainError {}

impl From<GridError> for TerrainError {
    fn from(e: GridError) -> Self {
        TerrainError::Grid(e)
    }
}

/// How many DEM cells are not navigable at `altitude_m` with `safety_height_m` (NODATA cells
/// included): [`Dem::is_navigable`] over the grid.
pub fn blocked_cells_at(dem: &Dem, altitude_m: f64, safety_height_m: f64) -> usize {
    (0..dem.nrows)
        .flat_map(|r| (0..dem.ncols).map(move |c| (c, r)))
        .filter(|&(c, r)| !dem.is_navigable(c, r, altitude_m, safety_height_m))
        .count()
}

/// Builds the metric occupancy grid and the visibility graph of `dem` in `frame` for flight at
/// `altitude_m` keeping `safety_height_m` above the ground and `clearance_m` plus half of
/// `wingspan_m` horizontally from blocked terrain. See the [module documentation](self).
pub fn build_terrain_graph(
    dem: &Dem,
    frame: &LocalFrame,
    altitude_m: f64,
    safety_height_m: f64,
    clearance_m: f64,
    wingspan_m: f64,
    params: &TerrainParams,
) -> Result<TerrainGraph, TerrainError> {
    if dem.units != Units::Geographic {
        return Err(TerrainError::ProjectedDem);
    }
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
    let mut stats = TerrainStats {
        dem_cells: dem.ncols * dem.nrows,
        ..TerrainStats::default()
    };

    // ---- 1. The metric grid.
    let t0 = Instant::now();
    let (x0, y0, cs) = (dem.xllcorner, dem.yllcorner, dem.cellsize);
    let (nc, nr) = (dem.ncols, dem.nrows);
    let dem_corner = |c: usize, r: usize| (x0 + c as f64 * cs, y0 + r as f64 * cs);
    let dist = |a: (f64, f64), b: (f64, f64)| (a.0 - b.0).hypot(a.1 - b.1);
    // Metric sides of DEM cells, at the four corners of the DEM and its centre (the sides vary
    // monotonically with latitude and distance from the central meridian).
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
        let e = dist(p, frame.to_local(lon + cs, lat));
        let n = dist(p, frame.to_local(lon, lat + cs));
        ew = (ew.0.min(e), ew.1.max(e));
        ns = (ns.0.min(n), ns.1.max(n));
    }
    stats.dem_cell_ew_m = ew;
    stats.dem_cell_ns_m = ns;
    let cell = params.cell_m.unwrap_or(ew.0.min(ns.0)) as f32;
    let cell_f = cell as f64;

    // The DEM's corners in the frame: its outline for the extent, all of them for the
    // comparison with an axis-aligned grid.
    let (lon_c, lat_c) = (x0 + 0.5 * nc as f64 * cs, y0 + 0.5 * nr as f64 * cs);
    let (xc, yc) = frame.to_local(lon_c, lat_c);
    let h = 1e-4;
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
    let (gx, gy) = (grid.origin.x as f64, grid.origin.y as f64);
    let vertex_local = |c: usize, r: usize| (gx + c as f64 * cell_f, gy + r as f64 * cell_f);

    // Every grid vertex in (lon, lat).
    let vertices: Vec<(f64, f64)> = (0..=rows)
        .into_par_iter()
        .flat_map_iter(|r| {
            (0..=cols).map(move |c| {
                let (x, y) = vertex_local(c, r);
                frame.to_geo(x, y)
            })
        })
        .collect();
    let vtx = |c: usize, r: usize| vertices[r * (cols + 1) + c];

    // Metres per degree, the smallest on the DEM (to turn metres into degrees conservatively),
    // and the bow of the metric cell edges along the grid's outline.
    let m_per_deg_lon = ew.0 / cs;
    let m_per_deg_lat = ns.0 / cs;
    let bow = |a: (usize, usize), b: (usize, usize)| {
        let (pa, pb) = (vertex_local(a.0, a.1), vertex_local(b.0, b.1));
        let mid = frame.to_geo(0.5 * (pa.0 + pb.0), 0.5 * (pa.1 + pb.1));
        let (ga, gb) = (vtx(a.0, a.1), vtx(b.0, b.1));
        let chord = (0.5 * (ga.0 + gb.0), 0.5 * (ga.1 + gb.1));
        // Degrees to metres with the largest metres per degree (an upper bound).
        let (ml, mp) = (ew.1 / cs, ns.1 / cs);
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

    // DEM navigability (for the statistics), then each metric cell's highest DEM elevation
    // over the DEM cells its footprint's box meets, encoded rounding up.
    stats.dem_blocked = (0..nr * nc)
        .into_par_iter()
        .filter(|&i| !dem.is_navigable(i % nc, i / nc, altitude_m, safety_height_m))
        .count();
    let coding = elevation_coding(dem)?;
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
            let dc = range((lon_lo - x0) / cs, (lon_hi - x0) / cs, nc);
            let dr = range((lat_lo - y0) / cs, (lat_hi - y0) / cs, nr);
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
    let mut nodes = Vec::new();
    let blocked_at = |a: f64| -> Vec<bool> {
        let b = coding.blocking_code(a as f32, safety_height_m as f32);
        codes.iter().map(|&k| k >= b).collect()
    };
    let levels: Vec<Vec<bool>> = params
        .extra_altitudes_m
        .iter()
        .map(|&a| blocked_at(a))
        .collect();
    for (level, blocked) in std::iter::once(&blocked).chain(levels.iter()).enumerate() {
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
                    if is_blocked(&grid, blocked, c, r) {
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
                segment_cells(&grid, &Segment::new(p, p), widen, |c, r| {
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
                let level_blocked = match level {
                    0 => &blocked,
                    l => &levels[l as usize - 1],
                };
                tested += 1;
                let (clear, n) = segment_clear(&grid, level_blocked, widen, a, b);
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

/// The edges found from one node to the later ones, with the pairs tested and cells visited.
type NodeEdges = (Vec<(u32, u32, f32)>, u64, u64);

/// Whether cell `(col, row)` is blocked, `true` outside the grid.
fn is_blocked(grid: &CellGrid, blocked: &[bool], col: i64, row: i64) -> bool {
    if col < 0 || row < 0 || col >= grid.cols as i64 || row >= grid.rows as i64 {
        return true;
    }
    blocked[row as usize * grid.cols as usize + col as usize]
}

/// Whether the capsule of radius `widen` around `a b` is inside the grid and meets no blocked
/// cell, and how many cells were visited finding out.
fn segment_clear(grid: &CellGrid, blocked: &[bool], widen: f32, a: Vec2, b: Vec2) -> (bool, u64) {
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

/// Whether the line through a node in direction `u` stays out of the interior of the node's
/// blocked quadrant `s` on both sides of the node: `(s_x u_x)(s_y u_y) ≤ 0`. The grown region
/// near the node is the quadrant `{s_x(x − p_x) ≥ 0, s_y(y − p_y) ≥ 0}`; the point `p + t u`
/// is inside it iff `s_x u_x t > 0` and `s_y u_y t > 0`, for some `t` of either sign iff the
/// two products have the same strict sign.
fn is_tangent(s: [i8; 2], u: Vec2) -> bool {
    (s[0] as f32 * u.x) * (s[1] as f32 * u.y) <= 0.0
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
