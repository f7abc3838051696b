//! The network writer (host only, feature `std`): the ground tool's half of format v4.

use super::elevation::ElevationCoding;
use super::format::*;
use super::{image_checksum, Network};
use crate::geometry::grid::{segment_cells, CellGrid};
use crate::geometry::hermite::{FlyLimits, LineElement};
use crate::geometry::{points_bounding_box, DubinsPath, DubinsWord, Pose, Segment, Vec2};
use std::vec::Vec;

mod alternatives;
mod grid;
mod landmark;
#[cfg(test)]
pub(crate) mod tests;
mod vertical;
use alternatives::write_alternatives_section;
pub use alternatives::{AlternativeSpec, AlternativesSpec, PopupSpec};
use grid::GridIndex;
use landmark::{check_landmark, write_landmark_section};
use vertical::write_vertical_section;
pub use vertical::VerticalSpec;

/// A directed edge to write.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EdgeSpec {
    /// Source vertex.
    pub source: u32,
    /// Target vertex.
    pub target: u32,
    /// Cost (≥ 0).
    pub cost: f32,
    /// Dubins word.
    pub word: DubinsWord,
    /// Lengths of the word's pieces, metres.
    pub lengths: [f32; 3],
}

impl EdgeSpec {
    /// A straight edge of `length` metres (terrain mode): the Dubins word whose arcs are empty.
    pub fn line(source: u32, target: u32, length: f32) -> Self {
        EdgeSpec {
            source,
            target,
            cost: length,
            word: DubinsWord::Lsl,
            lengths: [0.0, length, 0.0],
        }
    }
}

impl EdgeSpec {
    /// A Dubins edge flying `path` (roadmap mode), cost = its length: the word and piece
    /// lengths the writer checks against [`DubinsPath::with_word`] between the two poses.
    pub fn dubins(source: u32, target: u32, path: &DubinsPath) -> Self {
        EdgeSpec {
            source,
            target,
            cost: path.length(),
            word: path.word,
            lengths: path.lengths,
        }
    }

    /// A chain of Hermite pieces of total `length` metres (landmark mode), cost = length; its
    /// line elements go in [`LandmarkSpec::chains`] at the same index.
    pub fn chain(source: u32, target: u32, length: f32) -> Self {
        EdgeSpec {
            source,
            target,
            cost: length,
            word: DubinsWord::Lsl,
            lengths: [length, 0.0, 0.0],
        }
    }
}

/// Landmark mode: one landmark.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LandmarkSiteSpec {
    /// Position, metres.
    pub position: Vec2,
    /// Largest distance after an overflight of quality 1, metres.
    pub d_max_m: f32,
}

/// Landmark mode: the landmark tables. The network's vertices must be the `L·D` overflights
/// (vertex `l·D + k`: landmark `l`'s position, heading of direction `k`), then the start, then
/// the goal; every edge an [`EdgeSpec::chain`] whose line elements are `chains[i]` (first at
/// its source vertex, last at its target).
#[derive(Clone, Debug, PartialEq)]
pub struct LandmarkSpec {
    /// Overflight directions per landmark, D.
    pub directions: u32,
    /// Weathers, W.
    pub weather_count: u32,
    /// Nominal speed of the line elements, m/s.
    pub v_nominal: f32,
    /// The limits the pieces were checked against.
    pub limits: FlyLimits,
    /// The landmarks, L.
    pub landmarks: Vec<LandmarkSiteSpec>,
    /// `L·W·D` qualities in `[0, 1]`: landmark-major, then weather, then direction.
    pub qualities: Vec<f32>,
    /// The start's vertex (`L·D`), if any.
    pub start_vertex: Option<u32>,
    /// The goal's vertex (after the start), if any.
    pub goal_vertex: Option<u32>,
    /// The longest start edge that may be flown, metres.
    pub start_range_m: f32,
    /// Per edge of [`NetworkSpec::edges`] (same index): its line elements.
    pub chains: Vec<Vec<LineElement>>,
}

/// Terrain mode: the elevation table and what it was built for.
#[derive(Clone, Debug, PartialEq)]
pub struct TerrainSpec {
    /// The elevation grid.
    pub grid: CellGrid,
    /// How the codes map to metres.
    pub coding: ElevationCoding,
    /// One code per cell, row-major from the south.
    pub codes: Vec<u8>,
    /// Half-width kept free around edges, nodes and arcs, metres.
    pub widen_m: f32,
    /// Flight altitude the network was built for, metres.
    pub altitude_m: f32,
    /// Safety height the network was built for, metres.
    pub safety_height_m: f32,
}

/// Voronoi mode: the threat sites and what the network was built for. The network's vertices
/// and edges must be the Voronoi graph of the sites clipped to `bounds` (as
/// `skyroute::geometry::voronoi` builds it, each edge in both directions, every edge an
/// [`EdgeSpec::line`]), which the planner checks when it loads the network.
#[derive(Clone, Debug, PartialEq)]
pub struct VoronoiSpec {
    /// Threat sites: position and exposure reference distance, metres.
    pub threats: Vec<(Vec2, f32)>,
    /// The weight k of length against exposure, in [0, 1].
    pub threat_weight: f32,
    /// The curvature limit, 1/m.
    pub kappa_max: f32,
    /// The box the diagram is clipped to: `(min, max)`.
    pub bounds: (Vec2, Vec2),
    /// The spline corner table, angle-major
    /// (`skyroute::geometry::spline::TABLE_ANGLES · TABLE_RATIOS` values).
    pub corner_table: Vec<f32>,
}

/// A static obstacle to write.
#[derive(Clone, Debug, PartialEq)]
pub enum ObstacleSpec {
    /// A simple polygon (not closed: the last point joins the first implicitly).
    Polygon(Vec<Vec2>),
    /// A disc.
    Circle {
        /// Centre.
        centre: Vec2,
        /// Radius, metres.
        radius: f32,
    },
}

/// Everything a roadmap network holds.
#[derive(Clone, Debug, PartialEq)]
pub struct NetworkSpec {
    /// Latitude of the local frame's origin, degrees.
    pub origin_lat_deg: f64,
    /// Longitude of the local frame's origin, degrees.
    pub origin_lon_deg: f64,
    /// Turn radius, metres.
    pub turn_radius_m: f32,
    /// Clearance from obstacles, metres.
    pub clearance_m: f32,
    /// Vertex poses.
    pub vertices: Vec<Pose>,
    /// Edges in any order (written grouped by source, keeping their relative order).
    pub edges: Vec<EdgeSpec>,
    /// Static obstacles.
    pub obstacles: Vec<ObstacleSpec>,
    /// Side of a grid-index cell, metres.
    pub grid_cell_m: f32,
    /// Terrain mode: the elevation table (then every edge must be [`EdgeSpec::line`], and
    /// vertex headings are ignored).
    pub terrain: Option<TerrainSpec>,
    /// Landmark mode: the landmark tables (then every edge must be an [`EdgeSpec::chain`]).
    pub landmark: Option<LandmarkSpec>,
    /// Voronoi mode: the threat sites and the corner table (then every edge must be an
    /// [`EdgeSpec::line`]).
    pub voronoi: Option<VoronoiSpec>,
    /// Digests of what the network was built from, written as they are at the end of the body.
    pub provenance: Vec<ProvenanceRecord>,
}

/// Why a network could not be written.
#[derive(Clone, Debug, PartialEq)]
pub enum WriteError {
    /// A count does not fit the format's 32-bit fields.
    TooLarge(&'static str),
    /// An edge names a vertex that does not exist.
    BadEdge {
        /// Edge index in the spec.
        edge: usize,
    },
    /// The written image failed its own validation (a bug, or non-finite input).
    Invalid(super::LoadError),
    /// Terrain mode: an edge is not a straight line, or the table does not match its grid.
    BadTerrain(&'static str),
    /// Voronoi mode: an edge is not a straight line.
    BadVoronoi(&'static str),
    /// A three-dimensional roadmap: the vertical tables do not match the vertices or the
    /// obstacles, or the network is not a roadmap.
    BadVertical(&'static str),
    /// Roadmap mode: an edge's lengths are not those of its word's path between its end
    /// poses ([`DubinsPath::with_word`]), which is what the image keeps and the aircraft flies.
    EdgeGeometry {
        /// Edge index in the spec.
        edge: usize,
    },
    /// Landmark mode: the tables do not match the vertices and edges, or a piece cannot be
    /// built.
    BadLandmark(&'static str),
    /// The grid index's cell side is not a positive finite number of metres.
    BadGridCell(f32),
    /// The grid index would have more than [`MAX_GRID_CELLS`] cells: (cell side, columns,
    /// rows), the counts as computed (possibly beyond any integer type).
    GridTooLarge(f32, f64, f64),
}

/// The most cells the writer gives a grid index (4 Mi: 16 MiB of offsets in the image). A grid
/// of more cells is refused with [`WriteError::GridTooLarge`] before anything is allocated.
pub const MAX_GRID_CELLS: u64 = 1 << 22;

/// The columns and rows of a grid index of side `cell` over a box of `width` × `height`
/// metres, as [`encode`] computes them (f32, rounded up, at least 1), or why it is refused.
pub fn grid_cells(cell: f32, width: f32, height: f32) -> Result<(u32, u32), WriteError> {
    if !(cell.is_finite() && cell > 0.0) {
        return Err(WriteError::BadGridCell(cell));
    }
    let (nx, ny) = (
        (width / cell).ceil().max(1.0),
        (height / cell).ceil().max(1.0),
    );
    // NaN fails the comparison and is refused too.
    if !(nx as f64 * ny as f64 <= MAX_GRID_CELLS as f64) {
        return Err(WriteError::GridTooLarge(cell, nx as f64, ny as f64));
    }
    Ok((nx as u32, ny as u32))
}

impl core::fmt::Display for WriteError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            WriteError::TooLarge(what) => write!(f, "too many {what} for the network format"),
            WriteError::BadEdge { edge } => write!(f, "edge {edge} names a missing vertex"),
            WriteError::Invalid(e) => write!(f, "the network does not validate: {e}"),
            WriteError::BadTerrain(what) => write!(f, "terrain network: {what}"),
            WriteError::BadLandmark(what) => write!(f, "landmark network: {what}"),
            WriteError::BadVoronoi(what) => write!(f, "Voronoi network: {what}"),
            WriteError::BadVertical(what) => write!(f, "three-dimensional roadmap: {what}"),
            WriteError::EdgeGeometry { edge } => write!(
                f,
                "edge {edge}'s lengths are not its Dubins word's between its two poses"
            ),
            WriteError::BadGridCell(cell) => {
                write!(f, "grid cell {cell} m is not a positive finite size")
            }
            WriteError::GridTooLarge(cell, nx, ny) => {
                f.write_str("a grid index of ")?;
                write_number(f, *nx)?;
                f.write_str(" x ")?;
                write_number(f, *ny)?;
                f.write_str(" cells of ")?;
                if (1e-3..1e9).contains(cell) {
                    write!(f, "{cell}")?; // as given, without the digits of its f64 widening
                } else {
                    write_number(f, *cell as f64)?;
                }
                write!(
                    f,
                    " m exceeds the limit of {MAX_GRID_CELLS} cells (a larger grid cell makes \
                     fewer)"
                )
            }
        }
    }
}

impl std::error::Error for WriteError {}

/// `x` in scientific notation when very small or very large, else as it is.
fn write_number(f: &mut core::fmt::Formatter<'_>, x: f64) -> core::fmt::Result {
    if x != 0.0 && !(1e-3..1e9).contains(&x.abs()) {
        write!(f, "{x:.4e}")
    } else {
        write!(f, "{x}")
    }
}

fn count(n: usize, what: &'static str) -> Result<u32, WriteError> {
    u32::try_from(n).map_err(|_| WriteError::TooLarge(what))
}

fn push<T: serde::Serialize>(out: &mut Vec<u8>, record: &T) {
    // Serializing a fixed-size record into a Vec cannot fail.
    if let Ok(bytes) = postcard::to_stdvec(record) {
        out.extend_from_slice(&bytes);
    }
}

/// Encodes a network and validates the result with [`Network::from_bytes`].
pub fn encode(spec: &NetworkSpec) -> Result<Vec<u8>, WriteError> {
    encode_image(spec, None, None)
}

/// Encodes a three-dimensional roadmap (header flag [`FLAG_VERTICAL`]), with the pop-up
/// alternatives section too when `alternatives` is given, and validates the result with
/// [`Network::from_bytes`].
pub fn encode_three_dimensional(
    spec: &NetworkSpec,
    vertical: &VerticalSpec,
    alternatives: Option<&AlternativesSpec>,
) -> Result<Vec<u8>, WriteError> {
    if spec.terrain.is_some() || spec.landmark.is_some() || spec.voronoi.is_some() {
        return Err(WriteError::BadVertical(
            "only a roadmap can be three-dimensional",
        ));
    }
    encode_image(spec, alternatives, Some(vertical))
}

/// Encodes a network with the pop-up alternatives section (header flag
/// [`FLAG_POPUP_ALTERNATIVES`]) and validates the result with [`Network::from_bytes`].
pub fn encode_with_alternatives(
    spec: &NetworkSpec,
    alternatives: &AlternativesSpec,
) -> Result<Vec<u8>, WriteError> {
    encode_image(spec, Some(alternatives), None)
}

fn encode_image(
    spec: &NetworkSpec,
    alternatives: Option<&AlternativesSpec>,
    vertical: Option<&VerticalSpec>,
) -> Result<Vec<u8>, WriteError> {
    if spec.vertices.len() as u64 > MAX_VERTICES as u64 {
        return Err(WriteError::TooLarge(
            "vertices (edge targets are 16-bit: at most 65536)",
        ));
    }
    let vertex_count = count(spec.vertices.len(), "vertices")?;
    let edge_count = count(spec.edges.len(), "edges")?;
    for (i, e) in spec.edges.iter().enumerate() {
        if e.source >= vertex_count || e.target >= vertex_count {
            return Err(WriteError::BadEdge { edge: i });
        }
    }
    if spec.terrain.is_none() && spec.landmark.is_none() && spec.voronoi.is_none() {
        check_dubins_edges(spec)?;
    }
    // Stable: keeps each source's order; chains follow their edges.
    let mut order: Vec<usize> = (0..spec.edges.len()).collect();
    order.sort_by_key(|&i| spec.edges[i].source);
    let edges: Vec<EdgeSpec> = order.iter().map(|&i| spec.edges[i]).collect();
    let mode = mode_of(spec, &edges)?;
    let chains: Vec<&[LineElement]> = match &spec.landmark {
        Some(l) => {
            check_landmark(spec, l, &edges)?;
            order.iter().map(|&i| l.chains[i].as_slice()).collect()
        }
        None => Vec::new(),
    };
    if let Some(t) = &spec.terrain {
        if t.codes.len() as u64 != t.grid.cols as u64 * t.grid.rows as u64 {
            return Err(WriteError::BadTerrain(
                "table size differs from cols x rows",
            ));
        }
        if edges
            .iter()
            .any(|e| e.word != DubinsWord::Lsl || e.lengths[0] != 0.0 || e.lengths[2] != 0.0)
        {
            return Err(WriteError::BadTerrain("an edge is not a straight line"));
        }
    }

    let mut body = Vec::new();
    for v in &spec.vertices {
        push(
            &mut body,
            &VertexRecord {
                x: v.position.x,
                y: v.position.y,
                heading: v.heading,
            },
        );
    }
    let mut offset = 0u32;
    push(&mut body, &U32Record(0));
    for v in 0..vertex_count {
        offset += edges[offset as usize..]
            .iter()
            .take_while(|e| e.source == v)
            .count() as u32;
        push(&mut body, &U32Record(offset));
    }
    for e in &edges {
        let aux = match &spec.terrain {
            Some(t) => {
                let (a, b) = (
                    spec.vertices[e.source as usize].position,
                    spec.vertices[e.target as usize].position,
                );
                highest_code(t, a, b).ok_or(WriteError::BadTerrain(
                    "an edge's band leaves the elevation grid",
                ))?
            }
            None if spec.landmark.is_some() || spec.voronoi.is_some() => 0,
            None => e.word.code(),
        };
        push(
            &mut body,
            &EdgeRecord {
                // Below MAX_VERTICES, checked above.
                target: e.target as u16,
                aux,
                cost: e.cost,
            },
        );
    }
    let point_count = write_obstacles(&mut body, &spec.obstacles)?;
    let grid = GridIndex::build(spec, &edges, &chains)?;
    for o in &grid.offsets {
        push(&mut body, &U32Record(*o));
    }
    body.extend_from_slice(&grid.lists);
    if let Some(t) = &spec.terrain {
        write_terrain_section(&mut body, t);
    }
    if let Some(l) = &spec.landmark {
        write_landmark_section(&mut body, l, &chains)?;
    }
    if let Some(v) = &spec.voronoi {
        write_voronoi_section(&mut body, v);
    }
    if let Some(v) = vertical {
        write_vertical_section(&mut body, v, spec.vertices.len(), spec.obstacles.len())?;
    }
    if let Some(a) = alternatives {
        write_alternatives_section(&mut body, a)?;
    }
    for record in &spec.provenance {
        push(&mut body, record);
    }

    let header = Header {
        magic: MAGIC,
        version: FORMAT_VERSION,
        mode,
        flags: alternatives.map_or(0, |_| FLAG_POPUP_ALTERNATIVES)
            | vertical.map_or(0, |_| FLAG_VERTICAL),
        origin_lat_deg: spec.origin_lat_deg,
        origin_lon_deg: spec.origin_lon_deg,
        turn_radius_m: spec.turn_radius_m,
        clearance_m: spec.clearance_m,
        vertex_count,
        edge_count,
        obstacle_count: count(spec.obstacles.len(), "obstacles")?,
        obstacle_point_count: point_count,
        grid_origin_x: grid.origin.x,
        grid_origin_y: grid.origin.y,
        grid_cell_m: spec.grid_cell_m,
        grid_nx: grid.nx,
        grid_ny: grid.ny,
        grid_list_bytes: count(grid.lists.len(), "grid list bytes")?,
        provenance_count: count(spec.provenance.len(), "provenance records")?,
        body_len: count(body.len(), "body bytes")?,
        image_crc: 0,
    };
    let mut out = Vec::with_capacity(Header::SIZE + body.len());
    push(&mut out, &header);
    out.extend_from_slice(&body);
    let crc = image_checksum(&out);
    out[Header::CHECKED_SIZE..Header::SIZE].copy_from_slice(&crc.to_le_bytes());
    Network::from_bytes(&out).map_err(WriteError::Invalid)?;
    Ok(out)
}

/// The mode code of the spec: at most one of the terrain, landmark and Voronoi sections, and a
/// Voronoi network's edges all straight lines.
fn mode_of(spec: &NetworkSpec, edges: &[EdgeSpec]) -> Result<u8, WriteError> {
    let line =
        |e: &EdgeSpec| e.word == DubinsWord::Lsl && e.lengths[0] == 0.0 && e.lengths[2] == 0.0;
    match (&spec.terrain, &spec.landmark, &spec.voronoi) {
        (None, None, None) => Ok(MODE_ROADMAP),
        (Some(_), None, None) => Ok(MODE_TERRAIN),
        (None, Some(_), None) => Ok(MODE_LANDMARK),
        (None, None, Some(_)) if edges.iter().all(line) => Ok(MODE_VORONOI),
        (None, None, Some(_)) => Err(WriteError::BadVoronoi("an edge is not a straight line")),
        _ => Err(WriteError::BadLandmark(
            "a network is of one mode: terrain, landmark or Voronoi",
        )),
    }
}

/// Writes the obstacle records, then their polygons' points; returns the number of points.
fn write_obstacles(body: &mut Vec<u8>, obstacles: &[ObstacleSpec]) -> Result<u32, WriteError> {
    let mut point_count = 0u32;
    for o in obstacles {
        let record = match o {
            ObstacleSpec::Polygon(points) => {
                let (lo, hi) = o.bounding_box();
                let r = ObstacleRecord {
                    kind: OBSTACLE_POLYGON,
                    first_point: point_count,
                    point_count: count(points.len(), "polygon points")?,
                    circle: [0.0; 3],
                    bbox: [lo.x, lo.y, hi.x, hi.y],
                };
                point_count = point_count
                    .checked_add(r.point_count)
                    .ok_or(WriteError::TooLarge("polygon points"))?;
                r
            }
            ObstacleSpec::Circle { centre, radius } => ObstacleRecord {
                kind: OBSTACLE_CIRCLE,
                first_point: 0,
                point_count: 0,
                circle: [centre.x, centre.y, *radius],
                bbox: {
                    let (lo, hi) = o.bounding_box();
                    [lo.x, lo.y, hi.x, hi.y]
                },
            },
        };
        push(body, &record);
    }
    for o in obstacles {
        if let ObstacleSpec::Polygon(points) = o {
            for p in points {
                push(body, &PointRecord { x: p.x, y: p.y });
            }
        }
    }
    Ok(point_count)
}

/// Terrain mode: writes the terrain record and the elevation table.
fn write_terrain_section(body: &mut Vec<u8>, t: &TerrainSpec) {
    push(
        body,
        &TerrainRecord {
            origin_x: t.grid.origin.x,
            origin_y: t.grid.origin.y,
            cell_m: t.grid.cell,
            cols: t.grid.cols,
            rows: t.grid.rows,
            elevation_base_m: t.coding.base_m,
            elevation_step_m: t.coding.step_m,
            widen_m: t.widen_m,
            altitude_m: t.altitude_m,
            safety_height_m: t.safety_height_m,
        },
    );
    body.extend_from_slice(&t.codes);
}

/// Voronoi mode: writes the Voronoi record, the threat sites and the corner table.
fn write_voronoi_section(body: &mut Vec<u8>, v: &VoronoiSpec) {
    let table_angles = crate::geometry::spline::TABLE_ANGLES as u32;
    push(
        body,
        &VoronoiRecord {
            threat_count: v.threats.len() as u32,
            threat_weight: v.threat_weight,
            kappa_max: v.kappa_max,
            bounds: [v.bounds.0.x, v.bounds.0.y, v.bounds.1.x, v.bounds.1.y],
            table_angles,
            table_ratios: crate::geometry::spline::TABLE_RATIOS as u32,
        },
    );
    for (p, radius) in &v.threats {
        push(
            body,
            &ThreatSiteRecord {
                x: p.x,
                y: p.y,
                radius: *radius,
            },
        );
    }
    for c in &v.corner_table {
        push(body, &F32Record(*c));
    }
}

/// Roadmap mode: every edge's lengths are bit for bit its word's path between its end poses,
/// the geometry the image keeps (it stores the word, and the aircraft solves it again).
fn check_dubins_edges(spec: &NetworkSpec) -> Result<(), WriteError> {
    for (i, e) in spec.edges.iter().enumerate() {
        let (a, b) = (
            &spec.vertices[e.source as usize],
            &spec.vertices[e.target as usize],
        );
        let same = DubinsPath::with_word(a, b, spec.turn_radius_m, e.word).is_some_and(|p| {
            p.lengths
                .iter()
                .zip(&e.lengths)
                .all(|(x, y)| x.to_bits() == y.to_bits())
        });
        if !same {
            return Err(WriteError::EdgeGeometry { edge: i });
        }
    }
    Ok(())
}

/// The highest code among the cells within the widening of segment `a b`, as the loader
/// recomputes it; `None` if the band leaves the grid.
fn highest_code(t: &TerrainSpec, a: Vec2, b: Vec2) -> Option<u8> {
    let w = Vec2::new(t.widen_m, t.widen_m);
    let lo = Vec2::new(a.x.min(b.x), a.y.min(b.y)) - w;
    let hi = Vec2::new(a.x.max(b.x), a.y.max(b.y)) + w;
    if !t.grid.covers(lo, hi) {
        return None;
    }
    let cols = t.grid.cols as usize;
    let mut highest = 0u8;
    segment_cells(&t.grid, &Segment::new(a, b), t.widen_m, |c, r| {
        highest = highest.max(t.codes[r as usize * cols + c as usize]);
        true
    })
    .ok()?;
    Some(highest)
}

impl ObstacleSpec {
    /// Axis-aligned bounding box `(min, max)`.
    pub fn bounding_box(&self) -> (Vec2, Vec2) {
        match self {
            ObstacleSpec::Polygon(points) => points_bounding_box(points.iter().copied()),
            ObstacleSpec::Circle { centre, radius } => (
                Vec2::new(centre.x - radius, centre.y - radius),
                Vec2::new(centre.x + radius, centre.y + radius),
            ),
        }
    }
}
