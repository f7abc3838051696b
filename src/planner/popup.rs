//! Pop-up obstacles: adding one disables exactly the edges whose geometry comes within the
//! network's clearance of it, visiting only the edges the grid index lists for the cells it
//! covers; removing it restores them.

use super::state::ModeState;
use super::{Planner, PopupError};
use crate::geometry::hermite::HermiteSegment;
use crate::geometry::predicates::{
    conflicts_with_circle, conflicts_with_polygon, point_in_polygon, point_segment_distance,
    polygon_is_simple,
};
use crate::geometry::vertical::pieces_within;
use crate::geometry::{
    points_bounding_box, DubinsPath, Primitive, Segment, Vec2, MAX_COORDINATE_M,
};
use crate::network::dubins_hull;
use crate::network::format::MAX_ALTITUDE_M;
use heapless::Vec;

/// The most vertices a pop-up polygon may have.
pub const MAX_POPUP_VERTICES: usize = 16;

/// A pop-up obstacle in the network's local frame.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Popup {
    /// A disc (a threat's lethal radius, a storm cell).
    Circle {
        /// Centre.
        centre: Vec2,
        /// Radius, metres.
        radius: f32,
    },
    /// A simple polygon.
    Polygon(Vec<Vec2, MAX_POPUP_VERTICES>),
}

/// What [`Planner::add_popup`] did.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct PopupSummary {
    /// The pop-up's id, for [`Planner::remove_popup`].
    pub id: u8,
    /// Edges this pop-up blocks (including ones another pop-up blocks too).
    pub edges_blocked: u32,
    /// Grid cells visited.
    pub cells_visited: u32,
    /// Grid entries visited.
    pub entries_visited: u32,
    /// Exact predicate evaluations.
    pub predicate_tests: u32,
    /// Landmark mode: Hermite pieces rebuilt to be tested.
    pub pieces_rebuilt: u32,
}

impl Popup {
    /// Checks the pop-up's shape.
    pub fn validate(&self) -> Result<(), PopupError> {
        match self {
            Popup::Circle { centre, radius } => {
                if !centre.is_finite() || !radius.is_finite() {
                    Err(PopupError::NonFinite)
                } else if *radius <= 0.0 {
                    Err(PopupError::NonPositiveRadius)
                } else if !centre.is_in_range() || *radius > MAX_COORDINATE_M {
                    Err(PopupError::OutOfRange)
                } else {
                    Ok(())
                }
            }
            Popup::Polygon(points) => {
                if points.iter().any(|p| !p.is_finite()) {
                    Err(PopupError::NonFinite)
                } else if points.iter().any(|p| !p.is_in_range()) {
                    Err(PopupError::OutOfRange)
                } else if !polygon_is_simple(points.as_slice()) {
                    Err(PopupError::NotSimple)
                } else {
                    Ok(())
                }
            }
        }
    }

    /// Bounding box `(min, max)`.
    pub fn bounding_box(&self) -> (Vec2, Vec2) {
        match self {
            Popup::Circle { centre, radius } => (
                Vec2::new(centre.x - radius, centre.y - radius),
                Vec2::new(centre.x + radius, centre.y + radius),
            ),
            Popup::Polygon(points) => points_bounding_box(points.iter().copied()),
        }
    }

    /// Whether `prim` comes within `clearance` of the pop-up. Returns the verdict and the
    /// number of exact predicate evaluations it took.
    pub fn conflicts(&self, prim: &Primitive, clearance: f32) -> (bool, u32) {
        match self {
            Popup::Circle { centre, radius } => {
                (conflicts_with_circle(prim, *centre, *radius, clearance), 1)
            }
            Popup::Polygon(points) => (
                conflicts_with_polygon(prim, points.as_slice(), clearance),
                points.len() as u32 + 1,
            ),
        }
    }

    /// Whether the Hermite piece `seg` may come within `clearance` of the pop-up, tested with
    /// `chords` chords (conservative: [`HermiteSegment::conflicts_with_circle`] and
    /// [`HermiteSegment::conflicts_with_polygon`]). Returns the verdict and the number of exact
    /// predicate evaluations it counts: per chord, 1 for a circle and one per polygon edge plus
    /// the containment test for a polygon.
    pub(super) fn conflicts_with_piece(
        &self,
        seg: &HermiteSegment,
        clearance: f32,
        chords: usize,
    ) -> (bool, u32) {
        let chords_u32 = chords as u32;
        match self {
            Popup::Circle { centre, radius } => (
                seg.conflicts_with_circle(*centre, *radius, clearance, chords),
                chords_u32,
            ),
            Popup::Polygon(points) => (
                seg.conflicts_with_polygon(points.as_slice(), clearance, chords),
                chords_u32 * (points.len() as u32 + 1),
            ),
        }
    }

    /// Whether point `p` lies inside the pop-up (boundary included for a circle).
    pub fn contains(&self, p: Vec2) -> bool {
        match self {
            Popup::Circle { centre, radius } => p.distance(*centre) <= *radius,
            Popup::Polygon(points) => point_in_polygon(p, points.as_slice()),
        }
    }
}

impl<'n, const V: usize, const E: usize, const P: usize, const R: usize> Planner<'n, V, E, P, R> {
    /// Adds a pop-up and disables every edge whose geometry comes within the network's
    /// clearance of it (exact predicates on the edges the grid index lists for the cells the
    /// pop-up's box, widened by the clearance, overlaps). Work: at most
    /// [`Planner::worst_case_popup_work`].
    pub fn add_popup(&mut self, popup: Popup) -> Result<PopupSummary, PopupError> {
        self.add_popup_with_height(popup, f32::INFINITY)
    }

    /// Adds a pop-up that reaches up to `height_m` (metres, in the network's datum, like a
    /// static obstacle's height) and disables the edges that fly within the clearance of it
    /// below `height_m` plus the clearance: in a three-dimensional roadmap an edge is tested
    /// only over the part of it its altitude profile flies that low
    /// ([`VerticalProfile::span_below`](crate::geometry::vertical::VerticalProfile)).
    /// `f32::INFINITY` is a wall, as [`Planner::add_popup`]. Refused with
    /// [`PopupError::BadHeight`] for a height that is NaN, not positive or finite beyond
    /// [`MAX_ALTITUDE_M`], and with [`PopupError::HeightNeedsAltitudes`] for a finite height on
    /// a network without altitudes. Work: as [`Planner::add_popup`].
    pub fn add_popup_with_height(
        &mut self,
        popup: Popup,
        height_m: f32,
    ) -> Result<PopupSummary, PopupError> {
        self.cancel_plan();
        popup.validate()?;
        if !(height_m > 0.0 && (height_m <= MAX_ALTITUDE_M || height_m == f32::INFINITY)) {
            return Err(PopupError::BadHeight);
        }
        if height_m.is_finite() && !self.network.is_three_dimensional() {
            return Err(PopupError::HeightNeedsAltitudes);
        }
        // The smallest id no active pop-up has.
        let slot = (0..P)
            .find(|id| self.popups.iter().all(|p| p.id as usize != *id))
            .ok_or(PopupError::NoFreeSlot { capacity: P as u8 })?;
        let bit = 1u16 << slot;
        let clearance = self.network.clearance();
        let mut summary = PopupSummary {
            id: slot as u8,
            edges_blocked: 0,
            cells_visited: 0,
            entries_visited: 0,
            predicate_tests: 0,
            pieces_rebuilt: 0,
        };
        let (lo, hi) = popup.bounding_box();
        let widen = Vec2::new(clearance, clearance);
        if let Some(cells) = self.network.cells_overlapping(lo - widen, hi + widen) {
            for y in cells.y0..=cells.y1 {
                for x in cells.x0..=cells.x1 {
                    summary.cells_visited = summary.cells_visited.saturating_add(1);
                    for e in self.network.cell_edges(x, y) {
                        summary.entries_visited += 1;
                        let Some(mask) = self.blocked_by.get(e as usize).copied() else {
                            continue;
                        };
                        if mask & bit != 0 {
                            continue; // already tested through another cell
                        }
                        let tall = (&popup, height_m);
                        if self.edge_conflicts(e, tall, clearance, &mut summary) {
                            if let Some(m) = self.blocked_by.get_mut(e as usize) {
                                *m |= bit;
                            }
                            summary.edges_blocked += 1;
                        }
                    }
                }
            }
        }
        // Cannot fail: a free id below P means fewer than P pop-ups are active.
        let _ = self.popups.push(ActivePopup {
            id: slot as u8,
            shape: popup,
            height: height_m,
        });
        Ok(summary)
    }

    /// Whether edge `e` may come within `clearance` of `popup` below `height` plus the
    /// clearance: exactly for the lines and arcs of Dubins and terrain edges (in a
    /// three-dimensional roadmap over the span of the edge flown that low), conservatively for
    /// Hermite chains ([`Planner::chain_conflicts`]). An edge that cannot be read counts as a
    /// conflict.
    fn edge_conflicts(
        &self,
        e: u32,
        (popup, height): (&Popup, f32),
        clearance: f32,
        summary: &mut PopupSummary,
    ) -> bool {
        match self.state {
            ModeState::Landmark(_) => self.chain_conflicts(e, popup, clearance, summary),
            // Voronoi mode: the stored graph's lines (the search checks its onboard graph's
            // edges against the pop-ups before each search).
            ModeState::Roadmap(_) | ModeState::Terrain(_) | ModeState::Voronoi(_) => {
                let path = match self.network.dubins_edge_ends(e) {
                    // A roadmap edge: first the cheap test on its hull, then the word solved.
                    Some((a, b, word)) => {
                        let radius = self.network.turn_radius();
                        if hull_is_far(&dubins_hull(&a, &b, radius, word), popup, clearance) {
                            summary.predicate_tests = summary.predicate_tests.saturating_add(1);
                            return false;
                        }
                        DubinsPath::with_word(&a, &b, radius, word)
                    }
                    None => self.network.edge_path(e),
                };
                let Some(path) = path else {
                    return true;
                };
                // The pieces of the edge flown below the pop-up's top plus the clearance: all
                // of it for a wall.
                let pieces = match height {
                    f32::INFINITY => path.primitives(),
                    _ => match self
                        .network
                        .edge_profile(e)
                        .map(|profile| profile.span_below(height + clearance))
                    {
                        Some(Some((from, to))) => pieces_within(&path, from, to),
                        Some(None) => {
                            summary.predicate_tests = summary.predicate_tests.saturating_add(1);
                            return false;
                        }
                        None => return true,
                    },
                };
                for prim in pieces.into_iter().flatten() {
                    let (conflict, tests) = popup.conflicts(&prim, clearance);
                    summary.predicate_tests = summary.predicate_tests.saturating_add(tests);
                    if conflict {
                        return true;
                    }
                }
                false
            }
        }
    }

    /// Removes pop-up `id` and re-enables the edges only it blocked. Work: |E| mask updates.
    pub fn remove_popup(&mut self, id: u8) -> Result<(), PopupError> {
        self.cancel_plan();
        let at = self
            .popups
            .iter()
            .position(|p| p.id == id)
            .ok_or(PopupError::UnknownId { id })?;
        self.popups.swap_remove(at);
        let keep = !(1u16 << id);
        for m in self.blocked_by.iter_mut() {
            *m &= keep;
        }
        Ok(())
    }

    /// The active pop-ups with their ids.
    pub fn popups(&self) -> impl Iterator<Item = (u8, &Popup)> {
        self.popups.iter().map(|p| (p.id, &p.shape))
    }

    /// Active pop-up `id`'s height, metres (`+∞` for a wall); `None` when no active pop-up
    /// has this id.
    pub fn popup_height(&self, id: u8) -> Option<f32> {
        self.popups.iter().find(|p| p.id == id).map(|p| p.height)
    }

    /// The active pop-ups with their ids and heights.
    pub(super) fn popups_with_heights(&self) -> impl Iterator<Item = (u8, &Popup, f32)> {
        self.popups.iter().map(|p| (p.id, &p.shape, p.height))
    }
}

/// An active pop-up.
#[derive(Clone, Debug)]
pub(super) struct ActivePopup {
    /// Its id, below `P`.
    id: u8,
    /// Its shape.
    shape: Popup,
    /// Its top, metres in the network's datum; `+∞` for a wall.
    height: f32,
}

/// Whether everything within `hull.1` of segment `hull.0` stays farther than `clearance` from
/// `popup`: the pop-up's bounding circle (its box's centre and half-diagonal) lies beyond
/// `hull.1 + clearance` from the segment, with a margin of 10⁻⁴ of the coordinates' size plus
/// 1 cm against f32 rounding.
fn hull_is_far(hull: &(Segment, f32), popup: &Popup, clearance: f32) -> bool {
    let (segment, reach) = hull;
    let (lo, hi) = popup.bounding_box();
    let centre = (lo + hi) * 0.5;
    let radius = (hi - lo).norm() * 0.5;
    let size = [segment.start, segment.end, centre]
        .iter()
        .fold(0.0f32, |m, p| m.max(libm::fabsf(p.x)).max(libm::fabsf(p.y)));
    let margin = 1e-4 * (size + reach + radius) + 0.01;
    point_segment_distance(centre, segment) > radius + clearance + reach + margin
}
