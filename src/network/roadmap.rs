//! Roadmap mode's part of a network image (Niendorf et al.): Dubins edges, whose validation
//! flies each word from its source's pose. Roadmap networks have no section of their own
//! beyond the common ones (`docs/FORMAT.md`).

use super::format::*;
use super::{LoadError, Network, Section};
use crate::geometry::{DubinsPath, DubinsWord};

impl<'a> Network<'a> {
    /// Flying edge `i` from its source must end at its target's pose, and its cost must not
    /// undercut its length (the A* heuristic and the grid's 4r reach rely on both). Tolerances
    /// cover f32 rounding: 10⁻⁴ of (turn radius + coordinate size + length) plus 1 cm, and
    /// 10⁻³ rad; measured Dubins end errors are below 5·10⁻⁶ of that scale.
    pub(super) fn validate_edge_geometry(
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
}
