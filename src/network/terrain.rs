//! Terrain mode's section of a network image (Medeiros & da Silva): the terrain record and the
//! elevation table after the common sections, the validation of line edges against it, and the
//! accessors of the elevation grid. The layout is specified in `docs/FORMAT.md` (terrain mode).

use super::elevation::{ElevationCoding, ELEVATION_BLOCKED};
use super::format::*;
use super::{Layout, LoadError, ModeSection, Network, Parameter, Section};
use crate::geometry::grid::{segment_cells, CellGrid};
use crate::geometry::{Segment, Vec2};

impl Layout {
    /// Adds the terrain sections after the common ones, or `None` on overflow.
    fn with_terrain(mut self, t: &TerrainRecord) -> Option<Self> {
        let cells = (t.cols as usize).checked_mul(t.rows as usize)?;
        self.terrain = self.end;
        self.elevations = self.terrain.checked_add(TerrainRecord::SIZE)?;
        self.end = self.elevations.checked_add(cells)?;
        Some(self)
    }
}

/// Reads the terrain record after the common sections (it sizes the elevation table after it,
/// so it is read before the lengths are compared; the checksum comes after them).
pub(super) fn read_section(
    bytes: &[u8],
    layout: Layout,
) -> Result<(ModeSection, Layout), LoadError> {
    let t: TerrainRecord = layout.mode_record(bytes, TerrainRecord::SIZE, Section::Terrain)?;
    let layout = layout.with_terrain(&t).ok_or(LoadError::CountsTooLarge)?;
    Ok((ModeSection::Terrain(t), layout))
}

impl<'a> Network<'a> {
    /// Terrain mode's numbers: no static obstacles (the terrain search checks terrain cells
    /// and pop-ups only, and its work bound has no obstacle term), a valid elevation grid, a
    /// finite coding with a positive step, finite non-negative widening and safety height, a
    /// finite altitude.
    pub(super) fn validate_terrain_parameters(&self, t: &TerrainRecord) -> Result<(), LoadError> {
        let h = &self.header;
        let grid_ok = self.terrain_grid().is_some_and(|g| g.validate().is_ok());
        let coding_ok = self.elevation_coding().is_some_and(|c| c.is_valid());
        let numbers_ok = t.widen_m.is_finite()
            && t.widen_m >= 0.0
            && t.altitude_m.is_finite()
            && t.safety_height_m.is_finite()
            && t.safety_height_m >= 0.0;
        let no_obstacles = h.obstacle_count == 0 && h.obstacle_point_count == 0;
        if !(no_obstacles && grid_ok && coding_ok && numbers_ok) {
            return Err(LoadError::InvalidParameter {
                parameter: Parameter::Terrain,
            });
        }
        Ok(())
    }

    /// A terrain edge `ends = (source, target)`: its ends at least 10⁻³ turn radii apart, its
    /// cost not below the distance between them, its elevation code (`aux`) no lower than the
    /// highest code of the cells within the widening of the segment (recomputed here with the
    /// exact traversal, so altitude pruning can trust it), and that band inside the elevation
    /// grid. Work: the cells of the band.
    pub(super) fn validate_line_edge(
        &self,
        i: u32,
        ends: (u32, u32),
        r: &EdgeRecord,
    ) -> Result<(), LoadError> {
        let malformed = LoadError::Malformed {
            section: Section::Edges,
            index: i,
        };
        let (Some(a), Some(b), Some(grid), Some(t)) = (
            self.vertex(ends.0),
            self.vertex(ends.1),
            self.terrain_grid(),
            self.terrain().copied(),
        ) else {
            return Err(malformed);
        };
        let (a, b) = (a.position, b.position);
        let length = a.distance(b);
        // A line between (nearly) coincident nodes has no direction to turn from.
        if !(length >= 1e-3 * self.header.turn_radius_m && length > 0.0) {
            return Err(malformed);
        }
        if !(r.cost >= length * (1.0 - 1e-5)) {
            return Err(LoadError::CostBelowLength { edge: i });
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
        if r.aux < highest {
            return Err(LoadError::EdgeElevationUnderstated {
                edge: i,
                stored: r.aux,
                computed: highest,
            });
        }
        Ok(())
    }

    /// Terrain mode: the elevation table's grid and coding record.
    pub fn terrain(&self) -> Option<&TerrainRecord> {
        match &self.section {
            ModeSection::Terrain(t) => Some(t),
            _ => None,
        }
    }

    /// Terrain mode: the elevation table's grid.
    pub fn terrain_grid(&self) -> Option<CellGrid> {
        self.terrain()
            .map(|t| CellGrid::new(Vec2::new(t.origin_x, t.origin_y), t.cell_m, t.cols, t.rows))
    }

    /// Terrain mode: how elevation codes map to metres.
    pub fn elevation_coding(&self) -> Option<ElevationCoding> {
        self.terrain().map(|t| ElevationCoding {
            base_m: t.elevation_base_m,
            step_m: t.elevation_step_m,
        })
    }

    /// Terrain mode: the elevation code of cell `(col, row)`; [`ELEVATION_BLOCKED`] outside
    /// the grid or without terrain.
    pub fn elevation_code(&self, col: u32, row: u32) -> u8 {
        let Some(t) = self.terrain() else {
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
        self.terrain()?;
        self.edge_record(i).map(|r| r.aux)
    }
}
