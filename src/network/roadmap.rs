//! Roadmap mode's part of a network image (Niendorf et al.): Dubins edges, whose validation
//! solves each edge's word between its ends and flies it from its source's pose. Roadmap networks have no section of their own
//! beyond the common ones (`docs/FORMAT.md`).

use super::format::*;
use super::{LoadError, ModeSection, Network, Section};
use crate::geometry::{DubinsPath, DubinsWord, Pose, Segment};

impl<'a> Network<'a> {
    /// Edge `i` joins `ends = (source, target)` by a Dubins word: the word must be solvable
    /// between their poses, flying the solved path from the source must end at the target's
    /// pose, and its cost must not undercut its length (the A* heuristic and the grid's 4r
    /// reach rely on both). The path is [`DubinsPath::with_word`] of the stored poses, the f32
    /// code the ground tool built and collision-checked the edge with, so the onboard geometry
    /// is bit for bit the checked one; the end check guards the solve. Tolerances cover f32
    /// rounding: 10⁻⁴ of (turn radius + coordinate size + length) plus 1 cm, and 10⁻³ rad;
    /// measured Dubins end errors are below 5·10⁻⁶ of that scale.
    pub(super) fn validate_edge_geometry(
        &self,
        i: u32,
        ends: (u32, u32),
        r: &EdgeRecord,
        word: DubinsWord,
    ) -> Result<(), LoadError> {
        let malformed = LoadError::Malformed {
            section: Section::Edges,
            index: i,
        };
        let (Some(start), Some(target)) = (self.vertex(ends.0), self.vertex(ends.1)) else {
            return Err(malformed);
        };
        let path = DubinsPath::with_word(&start, &target, self.header.turn_radius_m, word).ok_or(
            LoadError::WordCannotJoin {
                edge: i,
                word: r.aux,
            },
        )?;
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
        self.validate_edge_climb(i, ends, length)
    }

    /// Roadmap mode: edge `e`'s end poses and word, what its path is solved from.
    pub fn dubins_edge_ends(&self, e: u32) -> Option<(Pose, Pose, DubinsWord)> {
        let ModeSection::Roadmap = self.section else {
            return None;
        };
        let r = self.edge_record(e)?;
        let word = DubinsWord::from_code(r.aux)?;
        Some((
            self.vertex(self.edge_source(e)?)?,
            self.vertex(r.target as u32)?,
            word,
        ))
    }
}

/// A region holding the whole Dubins path of `word` with turn radius `radius` from pose `a` to
/// pose `b`, from the poses alone (no word solve): the path lies within the returned distance
/// of the returned segment, which joins the centres of its first and last turning circles. A
/// CSC path is an arc of the first circle, a tangent between the two and an arc of the last,
/// so it lies within `radius` of the segment (a convex set holding all three); a CCC path's
/// middle circle is tangent to both (its centre 2·radius from each), so its points are within
/// 3·radius of either end.
pub fn dubins_hull(a: &Pose, b: &Pose, radius: f32, word: DubinsWord) -> (Segment, f32) {
    let (first, middle, last) = word.letters();
    let reach = if middle.is_some() { 3.0 } else { 1.0 } * radius;
    (
        Segment::new(first.centre(a, radius), last.centre(b, radius)),
        reach,
    )
}
