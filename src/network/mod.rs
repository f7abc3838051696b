//! The preprocessed network: format v4, its validating loader and read-only accessors.
//!
//! [`Network::from_bytes`] checks an image once (magic, version, length, checksum, counts,
//! every index and every float) and then reads it where it lies: the network is never copied
//! into RAM. After a successful load no accessor can panic, and none returns `None` for an
//! index below the corresponding count — except the Dubins views of a Hermite chain
//! ([`Network::edge`], [`Network::edge_path`]), which has none.

mod alternatives;
mod crc;
pub mod elevation;
mod error;
pub mod format;
mod landmark;
mod layout;
mod mode;
mod roadmap;
pub use roadmap::dubins_hull;
mod terrain;
mod validate;
mod verify;
mod vertical;
mod voronoi;
pub use verify::{ImageVerifier, VerifyStep};
#[cfg(feature = "std")]
pub mod write;

pub use alternatives::{AlternativesSummary, StoredAlternative, StoredPopup};
pub use crc::{crc32, crc32_parts};
pub use error::{LoadError, Parameter, Section};
use layout::Layout;
pub use mode::Mode;
use mode::ModeSection;
pub use voronoi::CornerTable;

use crate::geometry::predicates::PolygonView;
use crate::geometry::{DubinsPath, DubinsWord, Pose, Vec2};
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
    /// The mode's own record (and what the loader derived from its tables).
    section: ModeSection,
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

/// An edge's ends and cost, whatever its geometry ([`Network::edge_link`]).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct EdgeLink {
    /// Source vertex.
    pub source: u32,
    /// Target vertex.
    pub target: u32,
    /// Cost of traversal.
    pub cost: f32,
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
                grid_list_bytes: 0,
                provenance_count: 0,
                body_len: 0,
                image_crc: 0,
            },
            layout: Layout::ZERO,
            section: ModeSection::Roadmap,
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
        let mode = Mode::decode(header.mode)?;
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
        let layout = Layout::from_header(&header).ok_or(LoadError::CountsTooLarge)?;
        // The mode's record sizes its tables, so it is read before the lengths are compared
        // (the checksum comes after them, as for every section).
        let (section, layout) = match mode {
            Mode::Roadmap => (ModeSection::Roadmap, layout),
            Mode::Terrain => terrain::read_section(bytes, layout)?,
            Mode::Landmark => landmark::read_section(bytes, layout, header.edge_count)?,
            Mode::Voronoi => voronoi::read_section(bytes, layout)?,
            Mode::Unknown(mode) => return Err(LoadError::UnknownMode { mode }),
        };
        let layout = match header.flags & FLAG_VERTICAL {
            0 => layout,
            _ => vertical::read_section(bytes, layout, &header)?,
        };
        let layout = match header.flags & FLAG_POPUP_ALTERNATIVES {
            0 => layout,
            _ => alternatives::read_section(bytes, layout)?,
        };
        let layout = layout
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
            section,
        };
        net.validate_parameters()?;
        net.validate_vertices()?;
        net.validate_vertical()?;
        // The mode's own tables come before the edges that index them.
        net.section = match section {
            ModeSection::Roadmap | ModeSection::Terrain(_) | ModeSection::Voronoi(_) => section,
            ModeSection::Landmark { record, .. } => ModeSection::Landmark {
                record,
                max_chain_pieces: net.validate_landmark_tables(&record)?,
            },
        };
        net.validate_edges()?;
        net.validate_obstacles()?;
        net.validate_grid()?;
        net.validate_alternatives()?;
        Ok(net)
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

    /// Offset `i` of an offset table (0 if unreadable, which validation rules out): a
    /// little-endian `u32` read in place, the [`U32Record`] encoding without a decoder (the
    /// edge-source binary search and every vertex expansion read offsets).
    fn offset(&self, base: usize, i: u32) -> u32 {
        let start = (i as usize)
            .checked_mul(U32Record::SIZE)
            .and_then(|at| at.checked_add(base));
        start
            .and_then(|at| self.bytes?.get(at..at.checked_add(U32Record::SIZE)?))
            .and_then(|b| b.try_into().ok())
            .map_or(0, u32::from_le_bytes)
    }

    /// The length of edge `e`: its Dubins path's, its segment's, or (landmark mode, where the
    /// cost is the chain's length) its cost.
    pub fn edge_length(&self, e: u32) -> Option<f32> {
        match self.section {
            ModeSection::Landmark { .. } => self.edge_record(e).map(|r| r.cost),
            _ => self.edge(e).map(|edge| edge.lengths.iter().sum()),
        }
    }

    /// Edge `i`'s record as stored (any mode).
    pub fn edge_record(&self, i: u32) -> Option<EdgeRecord> {
        if i >= self.header.edge_count {
            return None;
        }
        self.record(self.layout.edges, EdgeRecord::SIZE, i as usize)
    }

    /// Edge `i`'s source, target and cost (any mode). Work: [`Network::edge_source`]'s binary
    /// search and one record.
    pub fn edge_link(&self, i: u32) -> Option<EdgeLink> {
        let r = self.edge_record(i)?;
        Some(EdgeLink {
            source: self.edge_source(i)?,
            target: r.target as u32,
            cost: r.cost,
        })
    }

    /// The source of edge `e`: the vertex whose range of the edge offsets holds it, found by
    /// binary search. Work: ⌈log₂(V + 1)⌉ offset reads.
    pub fn edge_source(&self, e: u32) -> Option<u32> {
        if e >= self.header.edge_count {
            return None;
        }
        // The last vertex v with offset[v] ≤ e; offsets run from 0 and never decrease
        // (validated), so the range of that v holds e.
        let (mut lo, mut hi) = (0u32, self.header.vertex_count);
        while hi - lo > 1 {
            let mid = lo + (hi - lo) / 2;
            if self.offset(self.layout.edge_offsets, mid) <= e {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        Some(lo)
    }

    /// The header.
    pub fn header(&self) -> &Header {
        &self.header
    }

    /// The image's length in bytes.
    pub fn byte_len(&self) -> usize {
        self.bytes.map_or(0, <[u8]>::len)
    }

    /// The network's mode, decoded from the header (never [`Mode::Unknown`] for a loaded
    /// network: the loader refuses those).
    pub fn mode(&self) -> Mode {
        self.section.mode()
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

    /// The network's local frame: the transverse Mercator centred on the header's origin
    /// ([`Network::origin_deg`]) in which every position and heading of the network is expressed.
    /// Its [`pose`](crate::geo::LocalFrame::pose) and [`position`](crate::geo::LocalFrame::position)
    /// turn latitude, longitude and compass heading into the planner's coordinates.
    pub fn local_frame(&self) -> crate::geo::LocalFrame {
        // The loader refused a non-finite origin or a latitude outside [−90, 90]
        // (`Parameter::Origin`).
        crate::geo::LocalFrame::new_valid(self.header.origin_lat_deg, self.header.origin_lon_deg)
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

    /// Edge `i` with its Dubins geometry (a line is the word whose arcs are empty), rebuilt
    /// from its end vertices: a roadmap edge's word is solved between their poses with
    /// [`DubinsPath::with_word`], bit for bit the path the ground tool checked. `None` for a
    /// Hermite chain (landmark mode), which has no Dubins form: read it with
    /// [`Network::edge_cost_target`], [`Network::edge_source`] and [`Network::chain_piece`].
    /// Work: a binary search for the source and, for a roadmap edge, one Dubins word solve.
    pub fn edge(&self, i: u32) -> Option<Edge> {
        let r = self.edge_record(i)?;
        let source = self.edge_source(i)?;
        let target = r.target as u32;
        let (word, lengths) = match self.section {
            ModeSection::Landmark { .. } => return None,
            ModeSection::Roadmap => {
                let word = DubinsWord::from_code(r.aux)?;
                let (a, b) = (self.vertex(source)?, self.vertex(target)?);
                let path = DubinsPath::with_word(&a, &b, self.header.turn_radius_m, word)?;
                (word, path.lengths)
            }
            ModeSection::Terrain(_) | ModeSection::Voronoi(_) => {
                // A straight line is the Dubins word whose two arcs are empty.
                let (a, b) = (self.vertex(source)?, self.vertex(target)?);
                (DubinsWord::Lsl, [0.0, a.position.distance(b.position), 0.0])
            }
        };
        Some(Edge {
            source,
            target,
            cost: r.cost,
            word,
            lengths,
        })
    }

    /// The cost and target of edge `i`, the two fields the search reads.
    pub fn edge_cost_target(&self, i: u32) -> Option<(f32, u32)> {
        self.edge_record(i).map(|r| (r.cost, r.target as u32))
    }

    /// Edge `i`'s geometry as a Dubins path from its source's pose.
    pub fn edge_path(&self, i: u32) -> Option<DubinsPath> {
        let e = self.edge(i)?;
        let mut start = self.vertex(e.source)?;
        match self.section {
            ModeSection::Roadmap | ModeSection::Landmark { .. } => {}
            ModeSection::Terrain(_) | ModeSection::Voronoi(_) => {
                // Terrain vertices have no heading: a line leaves towards its target.
                let d = self.vertex(e.target)?.position - start.position;
                start.heading = libm::atan2f(d.y, d.x);
            }
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

    /// The number of elementary predicate evaluations one primitive costs against every
    /// obstacle: one per polygon edge, plus one containment test per polygon and one test per
    /// circle (the units of [`crate::planner::Work`]'s `collision_tests`).
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

    /// The edges listed in grid cell `(x, y)`, in increasing order (none outside the grid).
    /// Work: the cell's list bytes.
    pub fn cell_edges(&self, x: u32, y: u32) -> CellEdges<'a> {
        let h = &self.header;
        if x >= h.grid_nx || y >= h.grid_ny {
            return CellEdges::default();
        }
        let c = y * h.grid_nx + x;
        let (start, end) = (
            self.offset(self.layout.cell_offsets, c) as usize,
            self.offset(self.layout.cell_offsets, c + 1) as usize,
        );
        let list = self.bytes.and_then(|b| {
            b.get(
                self.layout.cell_lists.checked_add(start)?
                    ..self.layout.cell_lists.checked_add(end)?,
            )
        });
        CellEdges {
            rest: list.unwrap_or(&[]),
            previous: None,
        }
    }

    /// The largest number of grid entries in any one cell. Work: the whole grid index.
    pub fn max_cell_entries(&self) -> u32 {
        let h = &self.header;
        let mut most = 0;
        for y in 0..h.grid_ny {
            for x in 0..h.grid_nx {
                most = most.max(self.cell_edges(x, y).count() as u32);
            }
        }
        most
    }

    /// The number of (cell, edge) entries of the grid index. Work: the whole grid index.
    pub fn grid_entry_count(&self) -> u64 {
        let h = &self.header;
        let mut total = 0u64;
        for y in 0..h.grid_ny {
            for x in 0..h.grid_nx {
                total += self.cell_edges(x, y).count() as u64;
            }
        }
        total
    }
}

/// The edges of one grid cell, decoded from its list: the first edge index as a varint, then
/// each next one as the varint of its difference from the previous minus one (so the list is
/// strictly increasing). Varints are postcard's (LEB128, at most five bytes for a `u32`). A
/// list the loader validated decodes to the end; any other stops at its first bad byte.
#[derive(Clone, Debug, Default)]
pub struct CellEdges<'a> {
    rest: &'a [u8],
    previous: Option<u32>,
}

impl Iterator for CellEdges<'_> {
    type Item = u32;

    fn next(&mut self) -> Option<u32> {
        if self.rest.is_empty() {
            return None;
        }
        let Ok((value, rest)) = postcard::take_from_bytes::<u32>(self.rest) else {
            self.rest = &[];
            return None;
        };
        self.rest = rest;
        let edge = match self.previous {
            None => Some(value),
            Some(p) => p.checked_add(value).and_then(|e| e.checked_add(1)),
        };
        if edge.is_none() {
            self.rest = &[];
        }
        self.previous = edge;
        edge
    }
}

/// The tolerance of a stored position against another: 10⁻⁴ of the coordinate size plus 1 cm.
pub(crate) fn position_tolerance(at: Vec2) -> f32 {
    1e-4 * libm::fabsf(at.x).max(libm::fabsf(at.y)) + 0.01
}
