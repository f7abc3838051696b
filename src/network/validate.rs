//! The loader's checks of the common sections: header parameters, vertices, edges (each by
//! its mode's rule), obstacles and the grid index. Each failure is its own [`LoadError`].

use super::format::*;
use super::{LoadError, ModeSection, Network, Parameter, Section};
use crate::geometry::DubinsWord;

impl<'a> Network<'a> {
    /// The header's numbers, then the mode record's.
    pub(super) fn validate_parameters(&self) -> Result<(), LoadError> {
        let h = &self.header;
        let bad = |parameter| Err(LoadError::InvalidParameter { parameter });
        let allowed = match self.section {
            ModeSection::Roadmap => FLAG_POPUP_ALTERNATIVES | FLAG_VERTICAL,
            _ => FLAG_POPUP_ALTERNATIVES,
        };
        if h.flags & !allowed != 0 {
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
        match &self.section {
            ModeSection::Roadmap => Ok(()),
            ModeSection::Terrain(t) => self.validate_terrain_parameters(t),
            ModeSection::Landmark { record, .. } => self.validate_landmark_parameters(record),
            ModeSection::Voronoi(v) => self.validate_voronoi_parameters(v),
        }
    }

    pub(super) fn validate_vertices(&self) -> Result<(), LoadError> {
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

    pub(super) fn validate_edges(&self) -> Result<(), LoadError> {
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
            if r.target as u32 >= v {
                return Err(LoadError::IndexOutOfRange {
                    section: Section::Edges,
                    index: i,
                    value: r.target as u32,
                    limit: v,
                });
            }
            if !r.cost.is_finite() {
                return Err(LoadError::NonFinite {
                    section: Section::Edges,
                    index: i,
                });
            }
            if r.cost < 0.0 {
                return Err(LoadError::NegativeValue { edge: i });
            }
            let ends = (source, r.target as u32);
            // Each mode has its own edge geometry.
            match &self.section {
                ModeSection::Roadmap => {
                    let word = DubinsWord::from_code(r.aux).ok_or(LoadError::UnknownGeometry {
                        edge: i,
                        code: r.aux,
                    })?;
                    self.validate_edge_geometry(i, ends, &r, word)?;
                }
                ModeSection::Terrain(_) => self.validate_line_edge(i, ends, &r)?,
                ModeSection::Landmark { .. } => self.validate_chain_edge(i, ends, &r)?,
                ModeSection::Voronoi(v) => self.validate_voronoi_edge(i, ends, &r, v)?,
            }
        }
        Ok(())
    }

    pub(super) fn validate_obstacles(&self) -> Result<(), LoadError> {
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
            // A box that encloses a point is not inverted, so this refuses inverted boxes too.
            if !ok || !self.box_encloses(&o) {
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

    /// Whether obstacle `o`'s stored box encloses its geometry: every point of a polygon, the
    /// whole disc of a circle (`centre ± radius` in f32, as the writer computes it). The
    /// planner skips an obstacle whose box a primitive's misses, so a box too small would hide
    /// part of the obstacle. A polygon's point range is checked before this is called.
    fn box_encloses(&self, o: &ObstacleRecord) -> bool {
        let inside =
            |x: f32, y: f32| o.bbox[0] <= x && x <= o.bbox[2] && o.bbox[1] <= y && y <= o.bbox[3];
        match o.kind {
            OBSTACLE_POLYGON => {
                (o.first_point..o.first_point.saturating_add(o.point_count)).all(|k| {
                    self.record::<PointRecord>(self.layout.points, PointRecord::SIZE, k as usize)
                        .is_some_and(|p| inside(p.x, p.y))
                })
            }
            OBSTACLE_CIRCLE => {
                let [x, y, r] = o.circle;
                inside(x - r, y - r) && inside(x + r, y + r)
            }
            _ => false,
        }
    }

    pub(super) fn validate_grid(&self) -> Result<(), LoadError> {
        let h = &self.header;
        let cells = h
            .grid_nx
            .checked_mul(h.grid_ny)
            .ok_or(LoadError::CountsTooLarge)?;
        self.validate_offsets(
            Section::CellOffsets,
            self.layout.cell_offsets,
            cells,
            h.grid_list_bytes,
        )?;
        for c in 0..cells {
            self.validate_cell_list(c)?;
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

    /// Cell `c`'s list decodes to its last byte as strictly increasing edge indices below E
    /// (each varint whole, within the cell's bytes, and at most five bytes long).
    fn validate_cell_list(&self, c: u32) -> Result<(), LoadError> {
        let h = &self.header;
        let bad = LoadError::BadCellList { cell: c };
        let (start, end) = (
            self.offset(self.layout.cell_offsets, c) as usize,
            self.offset(self.layout.cell_offsets, c + 1) as usize,
        );
        let mut rest = self
            .bytes
            .and_then(|b| b.get(self.layout.cell_lists + start..self.layout.cell_lists + end))
            .ok_or(bad)?;
        let mut previous: Option<u32> = None;
        while !rest.is_empty() {
            let (value, tail) = postcard::take_from_bytes::<u32>(rest).map_err(|_| bad)?;
            rest = tail;
            let edge = match previous {
                None => Some(value),
                Some(p) => p.checked_add(value).and_then(|e| e.checked_add(1)),
            };
            match edge {
                Some(e) if e < h.edge_count => previous = Some(e),
                _ => {
                    return Err(LoadError::IndexOutOfRange {
                        section: Section::CellEntries,
                        index: c,
                        value: edge.unwrap_or(u32::MAX),
                        limit: h.edge_count,
                    })
                }
            }
        }
        Ok(())
    }

    /// Checks that `count + 1` offsets at `base` run non-decreasing from 0 to `total`.
    pub(super) fn validate_offsets(
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
}
