//! The preprocessed network: format v3, its validating loader and read-only accessors.
//!
//! [`Network::from_bytes`] checks an image once (magic, version, length, checksum, counts,
//! every index and every float) and then reads it where it lies: the network is never copied
//! into RAM. After a successful load no accessor can panic, and none returns `None` for an
//! index below the corresponding count — except the Dubins views of a Hermite chain
//! ([`Network::edge`], [`Network::edge_path`]), which has none.

mod crc;
pub mod elevation;
mod error;
pub mod format;
#[cfg(feature = "std")]
pub mod write;

pub use crc::{crc32, crc32_parts};
pub use error::{LoadError, Parameter, Section};

use crate::geometry::grid::{segment_cells, CellGrid};
use crate::geometry::hermite::{FlyLimits, HermiteSegment, LineElement};
use crate::geometry::predicates::PolygonView;
use crate::geometry::{DubinsPath, DubinsWord, Pose, Segment, Vec2};
use elevation::{ElevationCoding, ELEVATION_BLOCKED};
use format::*;
use serde::de::DeserializeOwned;

/// A validated network image, borrowed from where it lies (for example a static slice in flash).
#[derive(Clone, Copy, Debug)]
pub struct Network<'a> {
    /// The image; `None` for [`Network::empty`] (a null niche, so an empty network is all-zero
    /// bytes where a `&[]` would hold a dangling non-null pointer).
    bytes: Option<&'a [u8]>,
    header: Header,
    layout: Layout,
    /// Terrain mode: the elevation table's grid and coding.
    terrain: Option<TerrainRecord>,
    /// Landmark mode: the landmark record.
    landmark: Option<LandmarkRecord>,
    /// Landmark mode: the most pieces of any edge's chain (0 otherwise).
    max_chain_pieces: u32,
}

/// Byte offsets of each section within the image.
#[derive(Clone, Copy, Debug, Default)]
struct Layout {
    vertices: usize,
    edge_offsets: usize,
    edges: usize,
    obstacles: usize,
    points: usize,
    cell_offsets: usize,
    cell_entries: usize,
    /// Terrain mode: the [`TerrainRecord`], then the elevation table (0 otherwise).
    terrain: usize,
    elevations: usize,
    /// Landmark mode: the [`LandmarkRecord`] and its tables (0 otherwise).
    landmark: usize,
    landmarks: usize,
    rosettes: usize,
    chain_offsets: usize,
    elements: usize,
    /// The provenance records that close the body.
    provenance: usize,
    end: usize,
}

impl Layout {
    /// Section offsets implied by the header's counts, or `None` on arithmetic overflow.
    fn from_header(h: &Header) -> Option<Self> {
        let v = h.vertex_count as usize;
        let cells = (h.grid_nx as usize).checked_mul(h.grid_ny as usize)?;
        let mut at = Header::SIZE;
        let mut next = |count: usize, size: usize| -> Option<usize> {
            let start = at;
            at = at.checked_add(count.checked_mul(size)?)?;
            Some(start)
        };
        Some(Layout {
            vertices: next(v, VertexRecord::SIZE)?,
            edge_offsets: next(v.checked_add(1)?, U32Record::SIZE)?,
            edges: next(h.edge_count as usize, EdgeRecord::SIZE)?,
            obstacles: next(h.obstacle_count as usize, ObstacleRecord::SIZE)?,
            points: next(h.obstacle_point_count as usize, PointRecord::SIZE)?,
            cell_offsets: next(cells.checked_add(1)?, U32Record::SIZE)?,
            cell_entries: next(h.grid_entry_count as usize, U32Record::SIZE)?,
            terrain: 0,
            elevations: 0,
            landmark: 0,
            landmarks: 0,
            rosettes: 0,
            chain_offsets: 0,
            elements: 0,
            provenance: 0,
            end: at,
        })
    }

    /// Adds the provenance records after every other section, or `None` on overflow.
    fn with_provenance(mut self, count: u32) -> Option<Self> {
        self.provenance = self.end;
        self.end = self
            .end
            .checked_add((count as usize).checked_mul(ProvenanceRecord::SIZE)?)?;
        Some(self)
    }

    /// Adds the landmark sections after the common ones, or `None` on overflow.
    fn with_landmark(mut self, l: &LandmarkRecord, edge_count: u32) -> Option<Self> {
        let lm = l.landmark_count as usize;
        let qualities = lm
            .checked_mul(l.weather_count as usize)?
            .checked_mul(l.directions as usize)?;
        let mut at = self.end;
        let mut next = |count: usize, size: usize| -> Option<usize> {
            let start = at;
            at = at.checked_add(count.checked_mul(size)?)?;
            Some(start)
        };
        self.landmark = next(1, LandmarkRecord::SIZE)?;
        self.landmarks = next(lm, LandmarkSiteRecord::SIZE)?;
        self.rosettes = next(qualities, F32Record::SIZE)?;
        self.chain_offsets = next((edge_count as usize).checked_add(1)?, U32Record::SIZE)?;
        self.elements = next(l.element_count as usize, ElementRecord::SIZE)?;
        self.end = at;
        Some(self)
    }

    /// Adds the terrain sections after the common ones, or `None` on overflow.
    fn with_terrain(mut self, t: &TerrainRecord) -> Option<Self> {
        let cells = (t.cols as usize).checked_mul(t.rows as usize)?;
        self.terrain = self.end;
        self.elevations = self.terrain.checked_add(TerrainRecord::SIZE)?;
        self.end = self.elevations.checked_add(cells)?;
        Some(self)
    }
}

/// The checksum of a network image as [`Header::image_crc`] defines it: the CRC-32 of the
/// header's first [`Header::CHECKED_SIZE`] bytes followed by the body (everything after the
/// header). An image shorter than its header has the CRC of what there is. Work: O(bytes).
pub fn image_checksum(image: &[u8]) -> u32 {
    let head = image.get(..Header::CHECKED_SIZE).unwrap_or(image);
    let body = image.get(Header::SIZE..).unwrap_or(&[]);
    crc32_parts(&[head, body])
}

/// A directed edge of the network.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Edge {
    /// Source vertex.
    pub source: u32,
    /// Target vertex.
    pub target: u32,
    /// Cost (≥ 0).
    pub cost: f32,
    /// Its Dubins word.
    pub word: DubinsWord,
    /// Lengths of the word's three pieces, metres.
    pub lengths: [f32; 3],
}

/// A static obstacle of the network.
#[derive(Clone, Copy, Debug)]
pub enum Obstacle<'a> {
    /// A simple polygon.
    Polygon(PolygonRef<'a>),
    /// A disc.
    Circle {
        /// Centre.
        centre: Vec2,
        /// Radius, metres.
        radius: f32,
    },
}

/// A polygon stored in the network, read in place.
#[derive(Clone, Copy, Debug)]
pub struct PolygonRef<'a> {
    /// The polygon's point records.
    points: &'a [u8],
    count: u32,
}

impl PolygonView for PolygonRef<'_> {
    fn vertex_count(&self) -> usize {
        self.count as usize
    }
    fn vertex(&self, i: usize) -> Option<Vec2> {
        if i >= self.count as usize {
            return None;
        }
        let start = i.checked_mul(PointRecord::SIZE)?;
        let p: PointRecord =
            postcard::from_bytes(self.points.get(start..start + PointRecord::SIZE)?).ok()?;
        Some(Vec2::new(p.x, p.y))
    }
}

/// The grid cells `[x0, x1] × [y0, y1]` (inclusive) that overlap a rectangle.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CellRange {
    /// First column.
    pub x0: u32,
    /// First row.
    pub y0: u32,
    /// Last column.
    pub x1: u32,
    /// Last row.
    pub y1: u32,
}

impl<'a> Network<'a> {
    /// A network with nothing in it: no vertices, edges, obstacles or grid cells. Every byte of
    /// it is zero (so a planner holding it in a `static` lands in `.bss`); its turn radius and
    /// grid cell are 0, which the accessors treat as "no path" and "no cell".
    pub const fn empty() -> Self {
        Network {
            bytes: None,
            header: Header {
                magic: [0; 4],
                version: 0,
                mode: 0,
                flags: 0,
                origin_lat_deg: 0.0,
                origin_lon_deg: 0.0,
                turn_radius_m: 0.0,
                clearance_m: 0.0,
                vertex_count: 0,
                edge_count: 0,
                obstacle_count: 0,
                obstacle_point_count: 0,
                grid_origin_x: 0.0,
                grid_origin_y: 0.0,
                grid_cell_m: 0.0,
                grid_nx: 0,
                grid_ny: 0,
                grid_entry_count: 0,
                provenance_count: 0,
                body_len: 0,
                image_crc: 0,
            },
            layout: Layout {
                vertices: 0,
                edge_offsets: 0,
                edges: 0,
                obstacles: 0,
                points: 0,
                cell_offsets: 0,
                cell_entries: 0,
                terrain: 0,
                elevations: 0,
                landmark: 0,
                landmarks: 0,
                rosettes: 0,
                chain_offsets: 0,
                elements: 0,
                provenance: 0,
                end: 0,
            },
            terrain: None,
            landmark: None,
            max_chain_pieces: 0,
        }
    }

    /// Validates `bytes` as a network image without capacity limits. See
    /// [`Network::from_bytes_with_capacity`].
    pub fn from_bytes(bytes: &'a [u8]) -> Result<Self, LoadError> {
        Self::from_bytes_with_capacity(bytes, usize::MAX, usize::MAX)
    }

    /// Validates `bytes` as a network image for a planner with room for `max_vertices` and
    /// `max_edges`. The header's counts are checked against the capacities and the length
    /// before any body record is decoded; then the checksum; then every record.
    /// Work: O(bytes) once.
    pub fn from_bytes_with_capacity(
        bytes: &'a [u8],
        max_vertices: usize,
        max_edges: usize,
    ) -> Result<Self, LoadError> {
        let head = bytes.get(..Header::SIZE).ok_or(LoadError::Truncated {
            needed: Header::SIZE,
            available: bytes.len(),
        })?;
        if head[..4] != MAGIC {
            let mut found = [0u8; 4];
            found.copy_from_slice(&head[..4]);
            return Err(LoadError::BadMagic { found });
        }
        let header: Header = postcard::from_bytes(head).map_err(|_| LoadError::Malformed {
            section: Section::Header,
            index: 0,
        })?;
        if header.version != FORMAT_VERSION {
            return Err(LoadError::UnsupportedVersion {
                found: header.version,
                supported: FORMAT_VERSION,
            });
        }
        if header.mode != MODE_ROADMAP
            && header.mode != MODE_TERRAIN
            && header.mode != MODE_LANDMARK
        {
            return Err(LoadError::UnknownMode { mode: header.mode });
        }
        if header.vertex_count as usize > max_vertices {
            return Err(LoadError::TooManyVertices {
                count: header.vertex_count,
                capacity: max_vertices,
            });
        }
        if header.edge_count as usize > max_edges {
            return Err(LoadError::TooManyEdges {
                count: header.edge_count,
                capacity: max_edges,
            });
        }
        let mut layout = Layout::from_header(&header).ok_or(LoadError::CountsTooLarge)?;
        let mut terrain = None;
        if header.mode == MODE_TERRAIN {
            // The terrain record sizes the table after it, so it is read before the lengths
            // are compared (the checksum comes after them, as for every section).
            let end = layout.end.saturating_add(TerrainRecord::SIZE);
            let record = bytes.get(layout.end..end).ok_or(LoadError::Truncated {
                needed: end,
                available: bytes.len(),
            })?;
            let t: TerrainRecord =
                postcard::from_bytes(record).map_err(|_| LoadError::Malformed {
                    section: Section::Terrain,
                    index: 0,
                })?;
            layout = layout.with_terrain(&t).ok_or(LoadError::CountsTooLarge)?;
            terrain = Some(t);
        }
        let mut landmark = None;
        if header.mode == MODE_LANDMARK {
            // As for terrain: the record sizes the tables after it.
            let end = layout.end.saturating_add(LandmarkRecord::SIZE);
            let record = bytes.get(layout.end..end).ok_or(LoadError::Truncated {
                needed: end,
                available: bytes.len(),
            })?;
            let l: LandmarkRecord =
                postcard::from_bytes(record).map_err(|_| LoadError::Malformed {
                    section: Section::Landmark,
                    index: 0,
                })?;
            layout = layout
                .with_landmark(&l, header.edge_count)
                .ok_or(LoadError::CountsTooLarge)?;
            landmark = Some(l);
        }
        layout = layout
            .with_provenance(header.provenance_count)
            .ok_or(LoadError::CountsTooLarge)?;
        let expected_body = layout.end - Header::SIZE;
        if header.body_len as usize != expected_body {
            return Err(LoadError::BodyLengthMismatch {
                declared: header.body_len,
                expected: expected_body,
            });
        }
        if bytes.len() < layout.end {
            return Err(LoadError::Truncated {
                needed: layout.end,
                available: bytes.len(),
            });
        }
        if bytes.len() > layout.end {
            return Err(LoadError::TrailingBytes {
                extra: bytes.len() - layout.end,
            });
        }
        let computed = image_checksum(bytes);
        if computed != header.image_crc {
            return Err(LoadError::ChecksumMismatch {
                stored: header.image_crc,
                computed,
            });
        }
        let mut net = Network {
            bytes: Some(bytes),
            header,
            layout,
            terrain,
            landmark,
            max_chain_pieces: 0,
        };
        net.validate_parameters()?;
        net.validate_vertices()?;
        if net.landmark.is_some() {
            net.max_chain_pieces = net.validate_landmark_tables()?;
        }
        net.validate_edges()?;
        net.validate_obstacles()?;
        net.validate_grid()?;
        Ok(net)
    }

    fn validate_parameters(&self) -> Result<(), LoadError> {
        let h = &self.header;
        let bad = |parameter| Err(LoadError::InvalidParameter { parameter });
        if h.flags != 0 {
            return bad(Parameter::Flags);
        }
        if !(h.turn_radius_m.is_finite() && h.turn_radius_m > 0.0) {
            return bad(Parameter::TurnRadius);
        }
        if !(h.clearance_m.is_finite() && h.clearance_m >= 0.0) {
            return bad(Parameter::Clearance);
        }
        if !(h.origin_lat_deg.abs() <= 90.0 && h.origin_lon_deg.abs() <= 180.0) {
            return bad(Parameter::Origin);
        }
        if !(h.grid_origin_x.is_finite() && h.grid_origin_y.is_finite()) {
            return bad(Parameter::GridOrigin);
        }
        if !(h.grid_cell_m.is_finite() && h.grid_cell_m > 0.0) {
            return bad(Parameter::GridCell);
        }
        if h.grid_nx == 0 || h.grid_ny == 0 {
            return bad(Parameter::GridDimensions);
        }
        if let Some(t) = &self.terrain {
            // Terrain networks carry no static obstacles: their search checks terrain cells
            // and pop-ups only, and their work bound has no obstacle term.
            if h.obstacle_count != 0 || h.obstacle_point_count != 0 {
                return bad(Parameter::Terrain);
            }
            let grid_ok = self.terrain_grid().is_some_and(|g| g.validate().is_ok());
            let coding_ok = self.elevation_coding().is_some_and(|c| c.is_valid());
            let numbers_ok = t.widen_m.is_finite()
                && t.widen_m >= 0.0
                && t.altitude_m.is_finite()
                && t.safety_height_m.is_finite()
                && t.safety_height_m >= 0.0;
            if !(grid_ok && coding_ok && numbers_ok) {
                return bad(Parameter::Terrain);
            }
        }
        if let Some(l) = &self.landmark {
            let ok = l.directions >= 1
                && l.weather_count >= 1
                && l.v_nominal.is_finite()
                && l.v_nominal > 0.0
                && self.fly_limits().is_some_and(|f| f.is_valid())
                && l.start_range_m.is_finite()
                && l.start_range_m >= 0.0;
            if !ok {
                return bad(Parameter::Landmark);
            }
        }
        Ok(())
    }

    fn validate_vertices(&self) -> Result<(), LoadError> {
        for i in 0..self.header.vertex_count {
            let v: VertexRecord = self.checked_record(
                Section::Vertices,
                self.layout.vertices,
                VertexRecord::SIZE,
                i,
            )?;
            if !(v.x.is_finite() && v.y.is_finite() && v.heading.is_finite()) {
                return Err(LoadError::NonFinite {
                    section: Section::Vertices,
                    index: i,
                });
            }
        }
        Ok(())
    }

    fn validate_edges(&self) -> Result<(), LoadError> {
        let (v, e) = (self.header.vertex_count, self.header.edge_count);
        self.validate_offsets(Section::EdgeOffsets, self.layout.edge_offsets, v, e)?;
        let mut source = 0u32;
        for i in 0..e {
            // Advance to the vertex whose range holds edge i (empty ranges are skipped).
            while self.offset(self.layout.edge_offsets, source + 1) <= i {
                source += 1;
            }
            let r: EdgeRecord =
                self.checked_record(Section::Edges, self.layout.edges, EdgeRecord::SIZE, i)?;
            if r.source != source {
                return Err(LoadError::EdgeSourceMismatch {
                    edge: i,
                    stored: r.source,
                    expected: source,
                });
            }
            if r.target >= v {
                return Err(LoadError::IndexOutOfRange {
                    section: Section::Edges,
                    index: i,
                    value: r.target,
                    limit: v,
                });
            }
            if !r.cost.is_finite() || r.params.iter().any(|x| !x.is_finite()) {
                return Err(LoadError::NonFinite {
                    section: Section::Edges,
                    index: i,
                });
            }
            if r.cost < 0.0 || r.params.iter().any(|&x| x < 0.0) {
                return Err(LoadError::NegativeValue { edge: i });
            }
            let unknown = LoadError::UnknownGeometry {
                edge: i,
                code: r.geometry,
            };
            if self.terrain.is_some() {
                if r.geometry != GEOMETRY_LINE {
                    return Err(unknown);
                }
                self.validate_line_edge(i, &r)?;
            } else if self.landmark.is_some() {
                if r.geometry != GEOMETRY_HERMITE_CHAIN {
                    return Err(unknown);
                }
                self.validate_chain_edge(i, &r)?;
            } else {
                let Some(word) = DubinsWord::from_code(r.geometry) else {
                    return Err(unknown);
                };
                self.validate_edge_geometry(i, &r, word)?;
            }
        }
        Ok(())
    }

    /// Flying edge `i` from its source must end at its target's pose, and its cost must not
    /// undercut its length (the A* heuristic and the grid's 4r reach rely on both). Tolerances
    /// cover f32 rounding: 10⁻⁴ of (turn radius + coordinate size + length) plus 1 cm, and
    /// 10⁻³ rad; measured Dubins end errors are below 5·10⁻⁶ of that scale.
    fn validate_edge_geometry(
        &self,
        i: u32,
        r: &EdgeRecord,
        word: DubinsWord,
    ) -> Result<(), LoadError> {
        let malformed = LoadError::Malformed {
            section: Section::Edges,
            index: i,
        };
        let (Some(start), Some(target)) = (self.vertex(r.source), self.vertex(r.target)) else {
            return Err(malformed);
        };
        let path = DubinsPath {
            start,
            radius: self.header.turn_radius_m,
            word,
            lengths: r.params,
        };
        let end = path.end();
        let length = path.length();
        let scale = self.header.turn_radius_m
            + libm::fabsf(target.position.x).max(libm::fabsf(target.position.y))
            + length;
        let miss = end.position.distance(target.position);
        let turn = libm::fabsf(crate::geometry::wrap_to_pi(end.heading - target.heading));
        if !(miss <= 1e-4 * scale + 0.01 && turn <= 1e-3) {
            return Err(LoadError::EdgeMissesTarget {
                edge: i,
                miss_mm: (miss * 1000.0).min(u32::MAX as f32) as u32,
            });
        }
        if !(r.cost >= length * (1.0 - 1e-5)) {
            return Err(LoadError::CostBelowLength { edge: i });
        }
        Ok(())
    }

    /// A terrain edge: its stored length is the distance between its ends (tolerance as for
    /// Dubins edges), its cost does not undercut it, its elevation code is a whole number no
    /// lower than the highest code of the cells within the widening of the segment (recomputed
    /// here with the exact traversal, so altitude pruning can trust it), and that band lies
    /// inside the elevation grid. Work: the cells of the band.
    fn validate_line_edge(&self, i: u32, r: &EdgeRecord) -> Result<(), LoadError> {
        let malformed = LoadError::Malformed {
            section: Section::Edges,
            index: i,
        };
        let (Some(a), Some(b), Some(grid), Some(t)) = (
            self.vertex(r.source),
            self.vertex(r.target),
            self.terrain_grid(),
            self.terrain,
        ) else {
            return Err(malformed);
        };
        let (a, b) = (a.position, b.position);
        let length = r.params[0];
        let chord = a.distance(b);
        // A line between (nearly) coincident nodes has no direction to turn from.
        if !(chord >= 1e-3 * self.header.turn_radius_m && chord > 0.0) {
            return Err(malformed);
        }
        let scale = libm::fabsf(b.x).max(libm::fabsf(b.y)) + length;
        if !(libm::fabsf(chord - length) <= 1e-4 * scale + 0.01) {
            return Err(LoadError::EdgeMissesTarget {
                edge: i,
                miss_mm: (libm::fabsf(chord - length) * 1000.0).min(u32::MAX as f32) as u32,
            });
        }
        if !(r.cost >= length * (1.0 - 1e-5)) {
            return Err(LoadError::CostBelowLength { edge: i });
        }
        let stored = r.params[1];
        if !(stored <= ELEVATION_BLOCKED as f32 && stored == libm::floorf(stored))
            || r.params[2] != 0.0
        {
            return Err(malformed);
        }
        let w = Vec2::new(t.widen_m, t.widen_m);
        let lo = Vec2::new(a.x.min(b.x), a.y.min(b.y)) - w;
        let hi = Vec2::new(a.x.max(b.x), a.y.max(b.y)) + w;
        if !grid.covers(lo, hi) {
            return Err(LoadError::EdgeOutsideTerrain { edge: i });
        }
        let mut highest = 0u8;
        segment_cells(&grid, &Segment::new(a, b), t.widen_m, |c, r| {
            highest = highest.max(self.elevation_code(c, r));
            true
        })
        .map_err(|_| LoadError::EdgeOutsideTerrain { edge: i })?;
        if (stored as u8) < highest {
            return Err(LoadError::EdgeElevationUnderstated {
                edge: i,
                stored: stored as u8,
                computed: highest,
            });
        }
        Ok(())
    }

    /// Landmark mode: the vertex layout (overflights, then start, then goal), every overflight
    /// at its landmark, the landmarks and qualities, the chain offsets and the line elements
    /// (finite, nominal speed). Returns the most pieces of any chain. Work: O(bytes) of these
    /// tables.
    fn validate_landmark_tables(&self) -> Result<u32, LoadError> {
        let Some(l) = self.landmark else {
            return Ok(0);
        };
        let v = self.header.vertex_count;
        let overflights = l.landmark_count.checked_mul(l.directions);
        let mut expected = overflights.unwrap_or(u32::MAX);
        for stored in [l.start_vertex, l.goal_vertex] {
            if stored != LandmarkRecord::ABSENT {
                if stored != expected {
                    return Err(LoadError::EndpointVertexMismatch { stored, expected });
                }
                expected = expected.saturating_add(1);
            }
        }
        if overflights.is_none() || expected != v {
            return Err(LoadError::LandmarkVertexCount {
                vertices: v,
                expected,
            });
        }
        for i in 0..l.landmark_count {
            let site: LandmarkSiteRecord = self.checked_record(
                Section::Landmarks,
                self.layout.landmarks,
                LandmarkSiteRecord::SIZE,
                i,
            )?;
            if !(site.x.is_finite() && site.y.is_finite() && site.d_max.is_finite()) {
                return Err(LoadError::NonFinite {
                    section: Section::Landmarks,
                    index: i,
                });
            }
            if site.d_max < 0.0 {
                return Err(LoadError::InvalidParameter {
                    parameter: Parameter::Landmark,
                });
            }
            let at = Vec2::new(site.x, site.y);
            for k in 0..l.directions {
                let vertex = i * l.directions + k;
                let p = self
                    .vertex(vertex)
                    .ok_or(LoadError::Malformed {
                        section: Section::Vertices,
                        index: vertex,
                    })?
                    .position;
                if p.distance(at) > position_tolerance(at) {
                    return Err(LoadError::VertexOffLandmark { vertex });
                }
            }
        }
        // The product fits: the layout was computed from it without overflow.
        let qualities = (l.landmark_count as u64 * l.weather_count as u64 * l.directions as u64)
            .min(u32::MAX as u64) as u32;
        for i in 0..qualities {
            let F32Record(q) =
                self.checked_record(Section::Rosettes, self.layout.rosettes, F32Record::SIZE, i)?;
            if !(0.0..=1.0).contains(&q) {
                return Err(LoadError::QualityOutOfRange { index: i });
            }
        }
        self.validate_offsets(
            Section::ChainOffsets,
            self.layout.chain_offsets,
            self.header.edge_count,
            l.element_count,
        )?;
        let mut most = 0u32;
        for e in 0..self.header.edge_count {
            let n = self.chain_elements(e).len() as u32;
            if n < 2 {
                return Err(LoadError::ChainTooShort {
                    edge: e,
                    elements: n,
                });
            }
            most = most.max(n - 1);
        }
        for i in 0..l.element_count {
            let r: ElementRecord = self.checked_record(
                Section::ChainElements,
                self.layout.elements,
                ElementRecord::SIZE,
                i,
            )?;
            if ![r.x, r.y, r.vx, r.vy].iter().all(|x| x.is_finite()) {
                return Err(LoadError::NonFinite {
                    section: Section::ChainElements,
                    index: i,
                });
            }
            let speed = Vec2::new(r.vx, r.vy).norm();
            if !(libm::fabsf(speed - l.v_nominal) <= 1e-3 * l.v_nominal) {
                return Err(LoadError::ElementSpeed {
                    element: i,
                    speed_mm_s: (speed * 1000.0).min(u32::MAX as f32) as u32,
                });
            }
        }
        Ok(most)
    }

    /// Landmark mode: a chain edge's params are `[length, 0, 0]` with the cost not below the
    /// length and the length not below the polyline through its elements; its first element
    /// is its source vertex's line element and its last its target's; consecutive elements are
    /// distinct; and the grid covers its reach. Work: its elements.
    fn validate_chain_edge(&self, i: u32, r: &EdgeRecord) -> Result<(), LoadError> {
        let malformed = LoadError::Malformed {
            section: Section::Edges,
            index: i,
        };
        if r.params[1] != 0.0 || r.params[2] != 0.0 {
            return Err(malformed);
        }
        let length = r.params[0];
        if !(r.cost >= length * (1.0 - 1e-5)) {
            return Err(LoadError::CostBelowLength { edge: i });
        }
        let range = self.chain_elements(i);
        let mut chords = 0.0f32;
        let mut previous: Option<LineElement> = None;
        for k in range.clone() {
            let el = self.chain_element(k).ok_or(LoadError::Malformed {
                section: Section::ChainElements,
                index: k,
            })?;
            if let Some(p) = previous {
                let d = p.position.distance(el.position);
                if !(d > 0.0) {
                    return Err(LoadError::CoincidentElements {
                        edge: i,
                        element: k,
                    });
                }
                chords += d;
            }
            previous = Some(el);
        }
        let (Some(first), Some(last)) = (
            self.chain_element(range.start),
            range.end.checked_sub(1).and_then(|k| self.chain_element(k)),
        ) else {
            return Err(malformed);
        };
        for (el, vertex) in [(first, r.source), (last, r.target)] {
            let pose = self.vertex(vertex).ok_or(malformed)?;
            let miss = el.position.distance(pose.position);
            let turn = libm::fabsf(crate::geometry::wrap_to_pi(
                el.velocity.angle() - pose.heading,
            ));
            if !(miss <= position_tolerance(pose.position) && turn <= 1e-3) {
                return Err(LoadError::ChainMissesVertex {
                    edge: i,
                    vertex,
                    miss_mm: (miss * 1000.0).min(u32::MAX as f32) as u32,
                });
            }
        }
        if !(length >= chords * (1.0 - 1e-5) - 0.01) {
            return Err(LoadError::ChainShorterThanChords { edge: i });
        }
        let (lo, hi) = self.edge_reach(first.position, last.position, length);
        let h = &self.header;
        let (x1, y1) = (
            h.grid_origin_x + h.grid_cell_m * h.grid_nx as f32,
            h.grid_origin_y + h.grid_cell_m * h.grid_ny as f32,
        );
        if !(lo.x >= h.grid_origin_x && lo.y >= h.grid_origin_y && hi.x <= x1 && hi.y <= y1) {
            return Err(LoadError::EdgeOutsideGrid { edge: i });
        }
        Ok(())
    }

    /// The box that holds every curve of length `length` from `a` to `b`: the ellipse
    /// `|PA| + |PB| ≤ length` lies within `length / 2` of the midpoint (widened by 10⁻⁴ of the
    /// length plus 1 cm against rounding).
    pub fn edge_reach(&self, a: Vec2, b: Vec2, length: f32) -> (Vec2, Vec2) {
        let mid = (a + b) * 0.5;
        let r = 0.5 * length + 1e-4 * length + 0.01;
        (mid - Vec2::new(r, r), mid + Vec2::new(r, r))
    }

    fn validate_obstacles(&self) -> Result<(), LoadError> {
        let points = self.header.obstacle_point_count;
        for i in 0..self.header.obstacle_point_count {
            let p: PointRecord = self.checked_record(
                Section::ObstaclePoints,
                self.layout.points,
                PointRecord::SIZE,
                i,
            )?;
            if !(p.x.is_finite() && p.y.is_finite()) {
                return Err(LoadError::NonFinite {
                    section: Section::ObstaclePoints,
                    index: i,
                });
            }
        }
        // Polygons own back-to-back point ranges that together use every point exactly once:
        // the work bound charges each point once.
        let mut next_point = 0u64;
        for i in 0..self.header.obstacle_count {
            let o: ObstacleRecord = self.checked_record(
                Section::Obstacles,
                self.layout.obstacles,
                ObstacleRecord::SIZE,
                i,
            )?;
            if o.circle.iter().chain(o.bbox.iter()).any(|x| !x.is_finite()) {
                return Err(LoadError::NonFinite {
                    section: Section::Obstacles,
                    index: i,
                });
            }
            let ok = match o.kind {
                OBSTACLE_POLYGON => {
                    let end = o.first_point as u64 + o.point_count as u64;
                    if o.first_point as u64 != next_point {
                        return Err(LoadError::BadOffsets {
                            section: Section::Obstacles,
                            index: i,
                        });
                    }
                    if end > points as u64 {
                        return Err(LoadError::IndexOutOfRange {
                            section: Section::Obstacles,
                            index: i,
                            value: o.first_point.saturating_add(o.point_count),
                            limit: points,
                        });
                    }
                    next_point = end;
                    o.point_count >= 3
                }
                OBSTACLE_CIRCLE => o.circle[2] > 0.0,
                _ => false,
            };
            if !ok || o.bbox[0] > o.bbox[2] || o.bbox[1] > o.bbox[3] {
                return Err(LoadError::BadObstacle { obstacle: i });
            }
        }
        if next_point != points as u64 {
            // Points that no polygon uses.
            return Err(LoadError::BadOffsets {
                section: Section::ObstaclePoints,
                index: next_point as u32,
            });
        }
        Ok(())
    }

    fn validate_grid(&self) -> Result<(), LoadError> {
        let h = &self.header;
        let cells = h
            .grid_nx
            .checked_mul(h.grid_ny)
            .ok_or(LoadError::CountsTooLarge)?;
        self.validate_offsets(
            Section::CellOffsets,
            self.layout.cell_offsets,
            cells,
            h.grid_entry_count,
        )?;
        for i in 0..h.grid_entry_count {
            let U32Record(e) = self.checked_record(
                Section::CellEntries,
                self.layout.cell_entries,
                U32Record::SIZE,
                i,
            )?;
            if e >= h.edge_count {
                return Err(LoadError::IndexOutOfRange {
                    section: Section::CellEntries,
                    index: i,
                    value: e,
                    limit: h.edge_count,
                });
            }
        }
        // Every Dubins path stays within 4r of its start (CSC within 2r; the middle circle of a
        // CCC word is 2r from the first circle's centre, so its points are within 4r).
        let reach = 4.0 * h.turn_radius_m;
        let (x1, y1) = (
            h.grid_origin_x + h.grid_cell_m * h.grid_nx as f32,
            h.grid_origin_y + h.grid_cell_m * h.grid_ny as f32,
        );
        for i in 0..h.vertex_count {
            let p = self
                .vertex(i)
                .ok_or(LoadError::Malformed {
                    section: Section::Vertices,
                    index: i,
                })?
                .position;
            if p.x - reach < h.grid_origin_x
                || p.y - reach < h.grid_origin_y
                || p.x + reach > x1
                || p.y + reach > y1
            {
                return Err(LoadError::GridTooSmall { vertex: i });
            }
        }
        Ok(())
    }

    /// Checks that `count + 1` offsets at `base` run non-decreasing from 0 to `total`.
    fn validate_offsets(
        &self,
        section: Section,
        base: usize,
        count: u32,
        total: u32,
    ) -> Result<(), LoadError> {
        let mut previous = 0u32;
        for i in 0..=count {
            let U32Record(o) = self.checked_record(section, base, U32Record::SIZE, i)?;
            let first_ok = i != 0 || o == 0;
            let last_ok = i != count || o == total;
            if o < previous || o > total || !first_ok || !last_ok {
                return Err(LoadError::BadOffsets { section, index: i });
            }
            previous = o;
        }
        Ok(())
    }

    fn checked_record<T: DeserializeOwned>(
        &self,
        section: Section,
        base: usize,
        size: usize,
        i: u32,
    ) -> Result<T, LoadError> {
        self.record(base, size, i as usize)
            .ok_or(LoadError::Malformed { section, index: i })
    }

    /// Decodes record `i` of the section at `base` whose records are `size` bytes long.
    fn record<T: DeserializeOwned>(&self, base: usize, size: usize, i: usize) -> Option<T> {
        let start = base.checked_add(i.checked_mul(size)?)?;
        postcard::from_bytes(self.bytes?.get(start..start.checked_add(size)?)?).ok()
    }

    /// Offset `i` of an offset table (0 if unreadable, which validation rules out).
    fn offset(&self, base: usize, i: u32) -> u32 {
        self.record::<U32Record>(base, U32Record::SIZE, i as usize)
            .map_or(0, |r| r.0)
    }

    /// Landmark mode: the landmark record.
    pub fn landmark(&self) -> Option<&LandmarkRecord> {
        self.landmark.as_ref()
    }

    /// Landmark mode: the vehicle limits every piece was checked against.
    pub fn fly_limits(&self) -> Option<FlyLimits> {
        self.landmark.map(|l| FlyLimits {
            v_min: l.v_min,
            v_max: l.v_max,
            a_long_min: l.a_long_min,
            a_long_max: l.a_long_max,
            a_lat_max: l.a_lat_max,
        })
    }

    /// Landmark mode: landmark `l`'s position and `d_max` (metres).
    pub fn landmark_site(&self, l: u32) -> Option<(Vec2, f32)> {
        let rec = self.landmark?;
        if l >= rec.landmark_count {
            return None;
        }
        let r: LandmarkSiteRecord =
            self.record(self.layout.landmarks, LandmarkSiteRecord::SIZE, l as usize)?;
        Some((Vec2::new(r.x, r.y), r.d_max))
    }

    /// Landmark mode: the stored quality `q(direction, weather)` of landmark `l`, in `[0, 1]`.
    pub fn rosette_quality(&self, l: u32, weather: u32, direction: u32) -> Option<f32> {
        let rec = self.landmark?;
        if l >= rec.landmark_count || weather >= rec.weather_count || direction >= rec.directions {
            return None;
        }
        let i = (l as usize * rec.weather_count as usize + weather as usize)
            * rec.directions as usize
            + direction as usize;
        self.record::<F32Record>(self.layout.rosettes, F32Record::SIZE, i)
            .map(|r| r.0)
    }

    /// Landmark mode: the indices of edge `e`'s line elements (empty for other modes).
    pub fn chain_elements(&self, e: u32) -> core::ops::Range<u32> {
        if self.landmark.is_none() || e >= self.header.edge_count {
            return 0..0;
        }
        self.offset(self.layout.chain_offsets, e)..self.offset(self.layout.chain_offsets, e + 1)
    }

    /// Landmark mode: line element `k` (an index into all chains' elements).
    pub fn chain_element(&self, k: u32) -> Option<LineElement> {
        if k >= self.landmark?.element_count {
            return None;
        }
        let r: ElementRecord =
            self.record(self.layout.elements, ElementRecord::SIZE, k as usize)?;
        Some(LineElement::new(Vec2::new(r.x, r.y), Vec2::new(r.vx, r.vy)))
    }

    /// Landmark mode: the number of Hermite pieces of edge `e` (its elements minus one).
    pub fn chain_piece_count(&self, e: u32) -> u32 {
        (self.chain_elements(e).len() as u32).saturating_sub(1)
    }

    /// Landmark mode: the most pieces of any edge.
    pub fn max_chain_pieces(&self) -> u32 {
        self.max_chain_pieces
    }

    /// Landmark mode: piece `k` of edge `e`, rebuilt from its two line elements with
    /// [`HermiteSegment::new`] at the nominal speed — bit for bit the segment the ground tool
    /// built and checked. Work: one segment construction (a few Newton steps of adaptive
    /// quadrature); the loader does not rebuild pieces, so a construction that fails (which the
    /// ground tool rules out) gives `None`.
    pub fn chain_piece(&self, e: u32, k: u32) -> Option<HermiteSegment> {
        let range = self.chain_elements(e);
        let i = range.start.checked_add(k)?;
        if i.checked_add(1)? >= range.end {
            return None;
        }
        let (a, b) = (self.chain_element(i)?, self.chain_element(i + 1)?);
        HermiteSegment::new(&a, &b, self.landmark?.v_nominal).ok()
    }

    /// The length of edge `e` (its first geometry parameter for lines and Hermite chains; the
    /// sum of the piece lengths for Dubins words).
    pub fn edge_length(&self, e: u32) -> Option<f32> {
        if e >= self.header.edge_count {
            return None;
        }
        let r: EdgeRecord = self.record(self.layout.edges, EdgeRecord::SIZE, e as usize)?;
        Some(match r.geometry {
            GEOMETRY_LINE | GEOMETRY_HERMITE_CHAIN => r.params[0],
            _ => r.params.iter().sum(),
        })
    }

    /// Edge `i`'s record as stored (any geometry).
    pub fn edge_record(&self, i: u32) -> Option<EdgeRecord> {
        if i >= self.header.edge_count {
            return None;
        }
        self.record(self.layout.edges, EdgeRecord::SIZE, i as usize)
    }

    /// The source of edge `e`.
    pub fn edge_source(&self, e: u32) -> Option<u32> {
        if e >= self.header.edge_count {
            return None;
        }
        let r: EdgeRecord = self.record(self.layout.edges, EdgeRecord::SIZE, e as usize)?;
        Some(r.source)
    }

    /// The header.
    pub fn header(&self) -> &Header {
        &self.header
    }

    /// The image's length in bytes.
    pub fn byte_len(&self) -> usize {
        self.bytes.map_or(0, <[u8]>::len)
    }

    /// The network's mode: [`MODE_ROADMAP`], [`MODE_LANDMARK`] or [`MODE_TERRAIN`].
    pub fn mode(&self) -> u8 {
        self.header.mode
    }

    /// The rectangle the network covers, `(south-west, north-east)` corners in metres: its
    /// grid index, which the loader has checked holds every vertex with four turn radii around
    /// it. Nothing the aircraft can fly through the network lies outside it.
    pub fn extent(&self) -> (Vec2, Vec2) {
        let h = &self.header;
        let lo = Vec2::new(h.grid_origin_x, h.grid_origin_y);
        let size = Vec2::new(
            h.grid_nx as f32 * h.grid_cell_m,
            h.grid_ny as f32 * h.grid_cell_m,
        );
        (lo, lo + size)
    }

    /// Number of provenance records (digests of what the network was built from).
    pub fn provenance_count(&self) -> u32 {
        self.header.provenance_count
    }

    /// Provenance record `i`, in the order written; `None` past the count.
    pub fn provenance(&self, i: u32) -> Option<ProvenanceRecord> {
        if i >= self.header.provenance_count {
            return None;
        }
        self.record(self.layout.provenance, ProvenanceRecord::SIZE, i as usize)
    }

    /// Terrain mode: the elevation table's grid and coding record.
    pub fn terrain(&self) -> Option<&TerrainRecord> {
        self.terrain.as_ref()
    }

    /// Terrain mode: the elevation table's grid.
    pub fn terrain_grid(&self) -> Option<CellGrid> {
        self.terrain
            .map(|t| CellGrid::new(Vec2::new(t.origin_x, t.origin_y), t.cell_m, t.cols, t.rows))
    }

    /// Terrain mode: how elevation codes map to metres.
    pub fn elevation_coding(&self) -> Option<ElevationCoding> {
        self.terrain.map(|t| ElevationCoding {
            base_m: t.elevation_base_m,
            step_m: t.elevation_step_m,
        })
    }

    /// Terrain mode: the elevation code of cell `(col, row)`; [`ELEVATION_BLOCKED`] outside
    /// the grid or without terrain.
    pub fn elevation_code(&self, col: u32, row: u32) -> u8 {
        let Some(t) = &self.terrain else {
            return ELEVATION_BLOCKED;
        };
        if col >= t.cols || row >= t.rows {
            return ELEVATION_BLOCKED;
        }
        let i = row as usize * t.cols as usize + col as usize;
        self.bytes
            .and_then(|b| b.get(self.layout.elevations.checked_add(i)?))
            .copied()
            .unwrap_or(ELEVATION_BLOCKED)
    }

    /// Terrain mode: the highest elevation code within the widening of line edge `i`.
    pub fn edge_highest_code(&self, i: u32) -> Option<u8> {
        self.terrain?;
        if i >= self.header.edge_count {
            return None;
        }
        let r: EdgeRecord = self.record(self.layout.edges, EdgeRecord::SIZE, i as usize)?;
        Some(r.params[1] as u8)
    }

    /// Number of vertices.
    pub fn vertex_count(&self) -> u32 {
        self.header.vertex_count
    }

    /// Number of edges.
    pub fn edge_count(&self) -> u32 {
        self.header.edge_count
    }

    /// Number of static obstacles.
    pub fn obstacle_count(&self) -> u32 {
        self.header.obstacle_count
    }

    /// Turn radius of the Dubins edges, metres.
    pub fn turn_radius(&self) -> f32 {
        self.header.turn_radius_m
    }

    /// Clearance kept from obstacles, metres.
    pub fn clearance(&self) -> f32 {
        self.header.clearance_m
    }

    /// The local frame's origin `(latitude, longitude)` in degrees.
    pub fn origin_deg(&self) -> (f64, f64) {
        (self.header.origin_lat_deg, self.header.origin_lon_deg)
    }

    /// Vertex `i`'s pose.
    pub fn vertex(&self, i: u32) -> Option<Pose> {
        if i >= self.header.vertex_count {
            return None;
        }
        let v: VertexRecord = self.record(self.layout.vertices, VertexRecord::SIZE, i as usize)?;
        Some(Pose::new(v.x, v.y, v.heading))
    }

    /// The edge indices leaving vertex `v`, as a half-open range.
    pub fn out_edges(&self, v: u32) -> core::ops::Range<u32> {
        if v >= self.header.vertex_count {
            return 0..0;
        }
        self.offset(self.layout.edge_offsets, v)..self.offset(self.layout.edge_offsets, v + 1)
    }

    /// Edge `i` with its Dubins geometry (a line is the word whose arcs are empty). `None`
    /// for a Hermite chain (landmark mode), which has no Dubins form: read it with
    /// [`Network::edge_cost_target`], [`Network::edge_source`] and [`Network::chain_piece`].
    pub fn edge(&self, i: u32) -> Option<Edge> {
        if i >= self.header.edge_count {
            return None;
        }
        let r: EdgeRecord = self.record(self.layout.edges, EdgeRecord::SIZE, i as usize)?;
        if r.geometry == GEOMETRY_HERMITE_CHAIN {
            return None;
        }
        let (word, lengths) = if r.geometry == GEOMETRY_LINE {
            // A straight line is the Dubins word whose two arcs are empty.
            (DubinsWord::Lsl, [0.0, r.params[0], 0.0])
        } else {
            (DubinsWord::from_code(r.geometry)?, r.params)
        };
        Some(Edge {
            source: r.source,
            target: r.target,
            cost: r.cost,
            word,
            lengths,
        })
    }

    /// The cost and target of edge `i`, the two fields the search reads.
    pub fn edge_cost_target(&self, i: u32) -> Option<(f32, u32)> {
        if i >= self.header.edge_count {
            return None;
        }
        let r: EdgeRecord = self.record(self.layout.edges, EdgeRecord::SIZE, i as usize)?;
        Some((r.cost, r.target))
    }

    /// Edge `i`'s geometry as a Dubins path from its source's pose.
    pub fn edge_path(&self, i: u32) -> Option<DubinsPath> {
        let e = self.edge(i)?;
        let mut start = self.vertex(e.source)?;
        if self.terrain.is_some() {
            // Terrain vertices have no heading: a line leaves towards its target.
            let d = self.vertex(e.target)?.position - start.position;
            start.heading = libm::atan2f(d.y, d.x);
        }
        Some(DubinsPath {
            start,
            radius: self.header.turn_radius_m,
            word: e.word,
            lengths: e.lengths,
        })
    }

    /// Static obstacle `i` and its bounding box `(min, max)`.
    pub fn obstacle(&self, i: u32) -> Option<(Obstacle<'a>, (Vec2, Vec2))> {
        if i >= self.header.obstacle_count {
            return None;
        }
        let o: ObstacleRecord =
            self.record(self.layout.obstacles, ObstacleRecord::SIZE, i as usize)?;
        let bbox = (
            Vec2::new(o.bbox[0], o.bbox[1]),
            Vec2::new(o.bbox[2], o.bbox[3]),
        );
        let obstacle = match o.kind {
            OBSTACLE_POLYGON => {
                let start = (o.first_point as usize)
                    .checked_mul(PointRecord::SIZE)?
                    .checked_add(self.layout.points)?;
                let len = (o.point_count as usize).checked_mul(PointRecord::SIZE)?;
                Obstacle::Polygon(PolygonRef {
                    points: self.bytes?.get(start..start.checked_add(len)?)?,
                    count: o.point_count,
                })
            }
            _ => Obstacle::Circle {
                centre: Vec2::new(o.circle[0], o.circle[1]),
                radius: o.circle[2],
            },
        };
        Some((obstacle, bbox))
    }

    /// Total number of polygon edges and circles over all obstacles: the number of elementary
    /// predicate evaluations one primitive costs against every obstacle.
    pub fn obstacle_elements(&self) -> u32 {
        self.header
            .obstacle_point_count
            .saturating_add(self.header.obstacle_count)
    }

    /// The grid cells overlapping the rectangle `[min, max]`, clamped to the grid; `None` when
    /// the rectangle lies wholly outside the grid or is not finite.
    pub fn cells_overlapping(&self, min: Vec2, max: Vec2) -> Option<CellRange> {
        let h = &self.header;
        let to_cell = |v: f32, origin: f32, n: u32| -> Option<f32> {
            let c = libm::floorf((v - origin) / h.grid_cell_m);
            c.is_finite().then_some(c.clamp(-1.0, n as f32))
        };
        let (x0, x1) = (
            to_cell(min.x, h.grid_origin_x, h.grid_nx)?,
            to_cell(max.x, h.grid_origin_x, h.grid_nx)?,
        );
        let (y0, y1) = (
            to_cell(min.y, h.grid_origin_y, h.grid_ny)?,
            to_cell(max.y, h.grid_origin_y, h.grid_ny)?,
        );
        if x1 < 0.0
            || y1 < 0.0
            || x0 >= h.grid_nx as f32
            || y0 >= h.grid_ny as f32
            || x0 > x1
            || y0 > y1
        {
            return None;
        }
        let last = |c: f32, n: u32| (c as u32).min(n - 1);
        Some(CellRange {
            x0: x0.max(0.0) as u32,
            y0: y0.max(0.0) as u32,
            x1: last(x1, h.grid_nx),
            y1: last(y1, h.grid_ny),
        })
    }

    /// The range of grid entries for cell `(x, y)`; read them with [`Network::cell_entry`].
    pub fn cell_entries(&self, x: u32, y: u32) -> core::ops::Range<u32> {
        let h = &self.header;
        if x >= h.grid_nx || y >= h.grid_ny {
            return 0..0;
        }
        let c = y * h.grid_nx + x;
        self.offset(self.layout.cell_offsets, c)..self.offset(self.layout.cell_offsets, c + 1)
    }

    /// Grid entry `k`: an edge index.
    pub fn cell_entry(&self, k: u32) -> Option<u32> {
        if k >= self.header.grid_entry_count {
            return None;
        }
        self.record::<U32Record>(self.layout.cell_entries, U32Record::SIZE, k as usize)
            .map(|r| r.0)
    }

    /// The largest number of grid entries in any one cell.
    pub fn max_cell_entries(&self) -> u32 {
        let h = &self.header;
        let mut most = 0;
        for y in 0..h.grid_ny {
            for x in 0..h.grid_nx {
                let r = self.cell_entries(x, y);
                most = most.max(r.end.saturating_sub(r.start));
            }
        }
        most
    }
}

/// The tolerance of a stored position against another: 10⁻⁴ of the coordinate size plus 1 cm.
fn position_tolerance(at: Vec2) -> f32 {
    1e-4 * libm::fabsf(at.x).max(libm::fabsf(at.y)) + 0.01
}
