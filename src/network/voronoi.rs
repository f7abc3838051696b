//! Voronoi mode's section of a network image (Judd & McLain): the Voronoi record, the threat
//! sites and the spline corner table after the common sections, the validation of its line
//! edges, and the accessors. The layout is specified in `docs/FORMAT.md` (Voronoi mode).
//!
//! The common vertices and edges hold the ground tool's Voronoi graph of the threat sites
//! (edges in both directions, straight lines). The planner searches the graph it builds
//! onboard from the sites (and rebuilds when a threat pops up), and refuses an image whose
//! stored graph differs from the one it builds.

use super::format::*;
use super::{Layout, LoadError, ModeSection, Network, Parameter, Section};
use crate::geometry::spline::{
    table::table_is_valid, table_angle, table_ratio, CornerBound, Piece, TABLE_ANGLES, TABLE_RATIOS,
};
use crate::geometry::voronoi::Bounds;
use crate::geometry::Vec2;

impl Layout {
    /// Adds the Voronoi sections after the common ones, or `None` on overflow.
    fn with_voronoi(mut self, v: &VoronoiRecord) -> Option<Self> {
        let table = (v.table_angles as usize).checked_mul(v.table_ratios as usize)?;
        self.voronoi = self.end;
        self.threats = self.voronoi.checked_add(VoronoiRecord::SIZE)?;
        self.corner_table = self
            .threats
            .checked_add((v.threat_count as usize).checked_mul(ThreatSiteRecord::SIZE)?)?;
        self.end = self
            .corner_table
            .checked_add(table.checked_mul(F32Record::SIZE)?)?;
        Some(self)
    }
}

/// Reads the Voronoi record after the common sections (it sizes the tables after it).
pub(super) fn read_section(
    bytes: &[u8],
    layout: Layout,
) -> Result<(ModeSection, Layout), LoadError> {
    let v: VoronoiRecord = layout.mode_record(bytes, VoronoiRecord::SIZE, Section::Voronoi)?;
    let layout = layout.with_voronoi(&v).ok_or(LoadError::CountsTooLarge)?;
    Ok((ModeSection::Voronoi(v), layout))
}

/// Whether every node of the table is at least the curvature, at its parameter midpoint, of
/// the corner piece it bounds (first leg 1 m, so the node is the curvature bound times the
/// leg): the largest curvature is never below the midpoint's, so a table that understates a
/// node there would let the smoothing exceed the curvature limit. Work: one curvature per node
/// (549).
fn table_bounds_midpoints(table: &impl CornerBound) -> bool {
    (1..TABLE_ANGLES).all(|i| {
        (0..TABLE_RATIOS).all(|j| {
            let (Some(theta), Some(rho), Some(node)) =
                (table_angle(i), table_ratio(j), table.node(i, j))
            else {
                return false;
            };
            let corner = Vec2::new(0.0, 0.0);
            let out = Vec2::from_angle(theta);
            let piece = Piece::Cubic {
                p: [Vec2::new(-1.0, 0.0), corner, corner, out * rho],
            };
            node >= piece.curvature(0.5) * (1.0 - 1e-3)
        })
    })
}

/// The corner table of a loaded Voronoi network, read where it lies in the image.
#[derive(Clone, Copy, Debug)]
pub struct CornerTable<'n> {
    network: Network<'n>,
}

impl CornerBound for CornerTable<'_> {
    fn node(&self, angle: usize, ratio: usize) -> Option<f32> {
        if angle >= TABLE_ANGLES || ratio >= TABLE_RATIOS {
            return None;
        }
        let i = angle.checked_mul(TABLE_RATIOS)?.checked_add(ratio)?;
        self.network.corner_value(i)
    }
}

impl<'a> Network<'a> {
    /// Voronoi mode's numbers: a weight in [0, 1], a finite positive curvature limit, a finite
    /// box of positive size, the corner table of this build's dimensions, valid
    /// ([`table_is_valid`]) and no node below its piece's midpoint curvature, polygons only
    /// among the static obstacles, and every threat site finite, inside the box, with a finite
    /// positive radius. Work: the sites and the table.
    pub(super) fn validate_voronoi_parameters(&self, v: &VoronoiRecord) -> Result<(), LoadError> {
        let [w, s, e, n] = v.bounds;
        let numbers_ok = (0.0..=1.0).contains(&v.threat_weight)
            && v.kappa_max.is_finite()
            && v.kappa_max > 0.0
            && v.bounds.iter().all(|b| b.is_finite())
            && w < e
            && s < n
            && v.table_angles as usize == TABLE_ANGLES
            && v.table_ratios as usize == TABLE_RATIOS;
        let table_ok = self
            .corner_table()
            .is_some_and(|t| table_is_valid(&t) && table_bounds_midpoints(&t));
        let polygons_only = (0..self.header.obstacle_count).all(|i| {
            self.record::<ObstacleRecord>(self.layout.obstacles, ObstacleRecord::SIZE, i as usize)
                .is_some_and(|o| o.kind == OBSTACLE_POLYGON)
        });
        if !(numbers_ok && table_ok && polygons_only) {
            return Err(LoadError::InvalidParameter {
                parameter: Parameter::Voronoi,
            });
        }
        for t in 0..v.threat_count {
            let r: ThreatSiteRecord = self.checked_record(
                Section::Threats,
                self.layout.threats,
                ThreatSiteRecord::SIZE,
                t,
            )?;
            let inside = r.x >= w && r.x <= e && r.y >= s && r.y <= n;
            if !(inside && r.radius.is_finite() && r.radius > 0.0) {
                return Err(LoadError::BadThreat { threat: t });
            }
        }
        Ok(())
    }

    /// A Voronoi edge `ends = (source, target)`: a straight line between distinct points
    /// whose cost is not below `k` times its length (the exposure term is never negative) and
    /// whose `aux` is zero.
    pub(super) fn validate_voronoi_edge(
        &self,
        i: u32,
        ends: (u32, u32),
        r: &EdgeRecord,
        v: &VoronoiRecord,
    ) -> Result<(), LoadError> {
        let malformed = LoadError::Malformed {
            section: Section::Edges,
            index: i,
        };
        let (Some(a), Some(b)) = (self.vertex(ends.0), self.vertex(ends.1)) else {
            return Err(malformed);
        };
        let length = a.position.distance(b.position);
        if !(length > 0.0) || r.aux != 0 {
            return Err(malformed);
        }
        if !(r.cost >= v.threat_weight * length * (1.0 - 1e-5)) {
            return Err(LoadError::CostBelowLength { edge: i });
        }
        Ok(())
    }

    /// Voronoi mode: the record.
    pub fn voronoi(&self) -> Option<&VoronoiRecord> {
        match &self.section {
            ModeSection::Voronoi(v) => Some(v),
            _ => None,
        }
    }

    /// Voronoi mode: the number of threat sites (0 in other modes).
    pub fn threat_count(&self) -> u32 {
        self.voronoi().map_or(0, |v| v.threat_count)
    }

    /// Voronoi mode: threat site `i`, its position and its exposure's reference distance.
    pub fn threat(&self, i: u32) -> Option<(Vec2, f32)> {
        if i >= self.threat_count() {
            return None;
        }
        let r: ThreatSiteRecord =
            self.record(self.layout.threats, ThreatSiteRecord::SIZE, i as usize)?;
        Some((Vec2::new(r.x, r.y), r.radius))
    }

    /// Voronoi mode: the box the diagram is clipped to.
    pub fn voronoi_bounds(&self) -> Option<Bounds> {
        let [w, s, e, n] = self.voronoi()?.bounds;
        Some(Bounds {
            min: Vec2::new(w, s),
            max: Vec2::new(e, n),
        })
    }

    /// Voronoi mode: the spline corner table, read in place.
    pub fn corner_table(&self) -> Option<CornerTable<'a>> {
        self.voronoi()?;
        Some(CornerTable { network: *self })
    }

    /// Voronoi mode: entry `i` of the corner table (angle-major).
    fn corner_value(&self, i: usize) -> Option<f32> {
        let v = self.voronoi()?;
        if i >= (v.table_angles as usize).checked_mul(v.table_ratios as usize)? {
            return None;
        }
        self.record::<F32Record>(self.layout.corner_table, F32Record::SIZE, i)
            .map(|r| r.0)
    }
}
