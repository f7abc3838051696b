//! Where each section of a network image starts: the byte offsets the header's counts (and the
//! mode's and flags' records) imply, computed with overflow checks before any body record is read.

use super::format::*;
use super::{LoadError, Section};
use serde::de::DeserializeOwned;

/// Byte offsets of each section within the image.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Layout {
    pub(super) vertices: usize,
    pub(super) edge_offsets: usize,
    pub(super) edges: usize,
    pub(super) obstacles: usize,
    pub(super) points: usize,
    pub(super) cell_offsets: usize,
    pub(super) cell_lists: usize,
    /// Terrain mode: the [`TerrainRecord`], then the elevation table (0 otherwise).
    pub(super) terrain: usize,
    pub(super) elevations: usize,
    /// Landmark mode: the [`LandmarkRecord`] and its tables (0 otherwise).
    pub(super) landmark: usize,
    pub(super) landmarks: usize,
    pub(super) rosettes: usize,
    pub(super) chain_offsets: usize,
    pub(super) chain_indices: usize,
    pub(super) elements: usize,
    /// Voronoi mode: the [`VoronoiRecord`], the threat sites and the corner table (0
    /// otherwise).
    pub(super) voronoi: usize,
    pub(super) threats: usize,
    pub(super) corner_table: usize,
    /// A three-dimensional roadmap's vertical record, followed by its vertex altitudes and
    /// obstacle heights, when the header's flag says so (0 otherwise).
    pub(super) vertical: usize,
    /// The pop-up alternatives' record and tables, when the header's flag says so (0
    /// otherwise).
    pub(super) alternatives: usize,
    pub(super) stored_popups: usize,
    pub(super) stored_alternatives: usize,
    pub(super) blocking_discs: usize,
    /// The provenance records that close the body.
    pub(super) provenance: usize,
    pub(super) end: usize,
}

impl Layout {
    /// Every section at offset 0: the layout of [`Network::empty`], and the sections a mode
    /// does not have.
    pub(super) const ZERO: Layout = Layout {
        vertices: 0,
        edge_offsets: 0,
        edges: 0,
        obstacles: 0,
        points: 0,
        cell_offsets: 0,
        cell_lists: 0,
        terrain: 0,
        elevations: 0,
        landmark: 0,
        landmarks: 0,
        rosettes: 0,
        chain_offsets: 0,
        chain_indices: 0,
        elements: 0,
        voronoi: 0,
        threats: 0,
        corner_table: 0,
        vertical: 0,
        alternatives: 0,
        stored_popups: 0,
        stored_alternatives: 0,
        blocking_discs: 0,
        provenance: 0,
        end: 0,
    };

    /// Section offsets implied by the header's counts, or `None` on arithmetic overflow.
    pub(super) fn from_header(h: &Header) -> Option<Self> {
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
            cell_lists: next(h.grid_list_bytes as usize, 1)?,
            end: at,
            ..Self::ZERO
        })
    }

    /// Reads a mode's record of `size` bytes right after the common sections. The record sizes
    /// the mode's tables after it, so it is read before the lengths are compared (the checksum
    /// comes after them): a short image is `Truncated`, an undecodable record `Malformed` in
    /// `section`.
    pub(super) fn mode_record<T: DeserializeOwned>(
        &self,
        bytes: &[u8],
        size: usize,
        section: Section,
    ) -> Result<T, LoadError> {
        let end = self.end.saturating_add(size);
        let record = bytes.get(self.end..end).ok_or(LoadError::Truncated {
            needed: end,
            available: bytes.len(),
        })?;
        postcard::from_bytes(record).map_err(|_| LoadError::Malformed { section, index: 0 })
    }

    /// Adds the provenance records after every other section, or `None` on overflow.
    pub(super) fn with_provenance(mut self, count: u32) -> Option<Self> {
        self.provenance = self.end;
        self.end = self
            .end
            .checked_add((count as usize).checked_mul(ProvenanceRecord::SIZE)?)?;
        Some(self)
    }
}
