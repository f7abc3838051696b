//! The terrain graph, its parameters, statistics and errors.

use super::cells::{is_blocked, segment_clear};
use skyroute::geometry::grid::{CellGrid, GridError};
use skyroute::network::elevation::ElevationCoding;
use skyroute::Vec2;
use std::fmt;
use std::time::Duration;

/// Tuning of [`build_terrain_graph`](super::build_terrain_graph).
#[derive(Clone, Debug, PartialEq)]
pub struct TerrainParams {
    /// Side of a metric cell, metres; `None`: the smallest metric side of a DEM cell.
    pub cell_m: Option<f64>,
    /// How much farther than `widen` a node lies from its corner along each axis, metres (> 0).
    pub node_margin_m: f64,
    /// Nodes closer than this to an already kept node are dropped, metres (0: no thinning).
    pub min_node_spacing_m: f64,
    /// Longest edge tried, metres; `None` (the default): every pair, the paper's visibility graph.
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
            max_edge_m: None,
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

/// Why [`build_terrain_graph`](super::build_terrain_graph) failed.
#[derive(Clone, Debug, PartialEq)]
pub enum TerrainError {
    /// The DEM is in a projection it does not name (an ASCII grid in metres), so it cannot be
    /// placed in the local frame.
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
                "the DEM is in projected units of an unnamed projection (an ASCII grid); only \
                 geographic (lon/lat) DEMs and GeoTIFFs in a UTM zone can be placed in the local \
                 frame"
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
