//! The vertical section of a three-dimensional roadmap (Niendorf et al.): the aircraft's
//! vertical limits, an altitude per vertex and a height per obstacle, read in place. Present
//! when the header has [`FLAG_VERTICAL`]; it follows the mode's section (`docs/FORMAT.md`,
//! vertical section). Every edge's altitude change must be a rest-to-rest move within the
//! limits over the edge's length ([`VerticalProfile`]); the loader checks each one.

use super::format::*;
use super::layout::Layout;
use super::mode::Mode;
use super::{LoadError, Network, Parameter, Section};
use crate::geometry::vertical::{VerticalLimits, VerticalProfile};

impl Layout {
    /// Adds the vertical section at the end, or `None` on overflow.
    fn with_vertical(mut self, vertices: u32, obstacles: u32) -> Option<Self> {
        let tables = (vertices as usize).checked_add(obstacles as usize)?;
        self.vertical = self.end;
        self.end = self
            .end
            .checked_add(VerticalRecord::SIZE)?
            .checked_add(tables.checked_mul(F32Record::SIZE)?)?;
        Some(self)
    }
}

/// Lays out the vertical section after the mode's section. Only a roadmap may have one.
pub(super) fn read_section(bytes: &[u8], layout: Layout, h: &Header) -> Result<Layout, LoadError> {
    if Mode::decode(h.mode)? != Mode::Roadmap {
        return Err(LoadError::InvalidParameter {
            parameter: Parameter::Flags,
        });
    }
    // Read (not yet checked) so that a short image is `Truncated` here, like a mode's record.
    let _: VerticalRecord = layout.mode_record(bytes, VerticalRecord::SIZE, Section::Vertical)?;
    layout
        .with_vertical(h.vertex_count, h.obstacle_count)
        .ok_or(LoadError::CountsTooLarge)
}

impl<'a> Network<'a> {
    /// Whether the network is a three-dimensional roadmap.
    pub fn is_three_dimensional(&self) -> bool {
        self.header.flags & FLAG_VERTICAL != 0
    }

    /// A three-dimensional roadmap's vertical limits; `None` for any other network.
    pub fn vertical_limits(&self) -> Option<VerticalLimits> {
        if !self.is_three_dimensional() {
            return None;
        }
        let r: VerticalRecord = self.record(self.layout.vertical, VerticalRecord::SIZE, 0)?;
        Some(VerticalLimits {
            airspeed: r.airspeed,
            climb_rate: r.climb_rate,
            vertical_accel: r.vertical_accel,
        })
    }

    /// A three-dimensional roadmap: vertex `v`'s altitude, metres; `None` for another network
    /// or an index past the vertices.
    pub fn vertex_altitude(&self, v: u32) -> Option<f32> {
        if !self.is_three_dimensional() || v >= self.header.vertex_count {
            return None;
        }
        let altitudes = self.layout.vertical + VerticalRecord::SIZE;
        let r: F32Record = self.record(altitudes, F32Record::SIZE, v as usize)?;
        Some(r.0)
    }

    /// Obstacle `i`'s height, metres: `+∞` in a planar network (every obstacle is a wall no
    /// altitude clears) and for a three-dimensional roadmap's obstacle of unbounded height;
    /// `None` for an index past the obstacles.
    pub fn obstacle_height(&self, i: u32) -> Option<f32> {
        if i >= self.header.obstacle_count {
            return None;
        }
        if !self.is_three_dimensional() {
            return Some(f32::INFINITY);
        }
        // After the altitudes (the layout checked these offsets for overflow).
        let heights = self.layout.vertical
            + VerticalRecord::SIZE
            + self.header.vertex_count as usize * F32Record::SIZE;
        let r: F32Record = self.record(heights, F32Record::SIZE, i as usize)?;
        Some(r.0)
    }

    /// Checks the vertical section: finite positive limits, every altitude finite within
    /// [`MAX_ALTITUDE_M`], every height positive (`+∞` allowed). Work: O(V + O).
    pub(super) fn validate_vertical(&self) -> Result<(), LoadError> {
        let Some(limits) = self.vertical_limits() else {
            return match self.is_three_dimensional() {
                true => Err(LoadError::Malformed {
                    section: Section::Vertical,
                    index: 0,
                }),
                false => Ok(()),
            };
        };
        if !limits.is_valid() {
            return Err(LoadError::InvalidParameter {
                parameter: Parameter::Vertical,
            });
        }
        for v in 0..self.header.vertex_count {
            let ok = self
                .vertex_altitude(v)
                .is_some_and(|z| z.is_finite() && libm::fabsf(z) <= MAX_ALTITUDE_M);
            if !ok {
                return Err(LoadError::BadAltitude {
                    section: Section::Altitudes,
                    index: v,
                });
            }
        }
        for i in 0..self.header.obstacle_count {
            // NaN-safe: `> 0.0` is false for NaN.
            if !self.obstacle_height(i).is_some_and(|h| h > 0.0) {
                return Err(LoadError::BadAltitude {
                    section: Section::ObstacleHeights,
                    index: i,
                });
            }
        }
        Ok(())
    }

    /// A three-dimensional roadmap: edge `i` from `ends.0` to `ends.1`, `length` metres long,
    /// must change altitude by a rest-to-rest move within the limits. Nothing to check in a
    /// planar network.
    pub(super) fn validate_edge_climb(
        &self,
        i: u32,
        ends: (u32, u32),
        length: f32,
    ) -> Result<(), LoadError> {
        let Some(limits) = self.vertical_limits() else {
            return Ok(());
        };
        let from = self.vertex_altitude(ends.0);
        let to = self.vertex_altitude(ends.1);
        match (from, to) {
            (Some(from), Some(to)) if VerticalProfile::new(from, to, length, &limits).is_some() => {
                Ok(())
            }
            _ => Err(LoadError::EdgeTooSteep { edge: i }),
        }
    }

    /// A three-dimensional roadmap: the altitude profile edge `e` flies (from its source's
    /// altitude to its target's over its path's length); `None` for another network or an
    /// unreadable edge.
    pub fn edge_profile(&self, e: u32) -> Option<VerticalProfile> {
        let limits = self.vertical_limits()?;
        let path = self.edge_path(e)?;
        let from = self.vertex_altitude(self.edge_source(e)?)?;
        let to = self.vertex_altitude(self.edge_record(e)?.target as u32)?;
        VerticalProfile::new(from, to, path.length(), &limits)
    }
}
