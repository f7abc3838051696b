//! Landmark mode's section of a network image (Babel 2014): the landmark record and tables
//! (landmarks, rosettes, chain offsets, chain index lists, distinct line elements) after the
//! common sections, their
//! validation, and the accessors of landmarks, rosettes and Hermite chains. The layout is
//! specified in `docs/FORMAT.md` (landmark mode).

use super::format::*;
use super::{position_tolerance, Layout, LoadError, ModeSection, Network, Parameter, Section};
use crate::geometry::hermite::{FlyLimits, HermiteSegment, LineElement};
use crate::geometry::Vec2;

impl Layout {
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
        self.chain_indices = next(l.chain_index_count as usize, U16Record::SIZE)?;
        self.elements = next(l.element_count as usize, ElementRecord::SIZE)?;
        self.end = at;
        Some(self)
    }
}

/// Reads the landmark record after the common sections (it sizes the tables after it, so it is
/// read before the lengths are compared; the checksum comes after them, as for every section).
pub(super) fn read_section(
    bytes: &[u8],
    layout: Layout,
    edge_count: u32,
) -> Result<(ModeSection, Layout), LoadError> {
    let l: LandmarkRecord = layout.mode_record(bytes, LandmarkRecord::SIZE, Section::Landmark)?;
    let layout = layout
        .with_landmark(&l, edge_count)
        .ok_or(LoadError::CountsTooLarge)?;
    Ok((
        ModeSection::Landmark {
            record: l,
            max_chain_pieces: 0,
        },
        layout,
    ))
}

impl<'a> Network<'a> {
    /// Landmark mode's record numbers: at least one direction and weather, a positive finite
    /// nominal speed, valid limits, a finite non-negative start range.
    pub(super) fn validate_landmark_parameters(&self, l: &LandmarkRecord) -> Result<(), LoadError> {
        let ok = l.directions >= 1
            && l.weather_count >= 1
            && l.v_nominal.is_finite()
            && l.v_nominal > 0.0
            && self.fly_limits().is_some_and(|f| f.is_valid())
            && l.start_range_m.is_finite()
            && l.start_range_m >= 0.0;
        if !ok {
            return Err(LoadError::InvalidParameter {
                parameter: Parameter::Landmark,
            });
        }
        Ok(())
    }

    /// Landmark mode: the vertex layout (overflights, then start, then goal), every overflight
    /// at its landmark, the landmarks and qualities, the chain offsets and the line elements
    /// (finite, nominal speed). Returns the most pieces of any chain. Work: O(bytes) of these
    /// tables.
    pub(super) fn validate_landmark_tables(&self, l: &LandmarkRecord) -> Result<u32, LoadError> {
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
            l.chain_index_count,
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
        for k in 0..l.chain_index_count {
            let U16Record(i) = self.checked_record(
                Section::ChainIndices,
                self.layout.chain_indices,
                U16Record::SIZE,
                k,
            )?;
            if i as u32 >= l.element_count {
                return Err(LoadError::IndexOutOfRange {
                    section: Section::ChainIndices,
                    index: k,
                    value: i as u32,
                    limit: l.element_count,
                });
            }
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

    /// Landmark mode: chain edge `i` from `ends.0` to `ends.1` has `aux` 0 and a cost (its
    /// length) not below the polyline through its elements; its first element is its source
    /// vertex's line element and its last its target's; consecutive elements are distinct; and
    /// the grid covers its reach. Work: its elements.
    pub(super) fn validate_chain_edge(
        &self,
        i: u32,
        ends: (u32, u32),
        r: &EdgeRecord,
    ) -> Result<(), LoadError> {
        let malformed = LoadError::Malformed {
            section: Section::Edges,
            index: i,
        };
        if r.aux != 0 {
            return Err(malformed);
        }
        let length = r.cost;
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
        for (el, vertex) in [(first, ends.0), (last, ends.1)] {
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

    /// Landmark mode: the landmark record.
    pub fn landmark(&self) -> Option<&LandmarkRecord> {
        match &self.section {
            ModeSection::Landmark { record, .. } => Some(record),
            _ => None,
        }
    }

    /// Landmark mode: the vehicle limits every piece was checked against.
    pub fn fly_limits(&self) -> Option<FlyLimits> {
        self.landmark().map(|l| FlyLimits {
            v_min: l.v_min,
            v_max: l.v_max,
            a_long_min: l.a_long_min,
            a_long_max: l.a_long_max,
            a_lat_max: l.a_lat_max,
        })
    }

    /// Landmark mode: landmark `l`'s position and `d_max` (metres).
    pub fn landmark_site(&self, l: u32) -> Option<(Vec2, f32)> {
        self.landmark_site_of(self.landmark()?, l)
    }

    /// [`Network::landmark_site`] with the landmark record already at hand (the search reads
    /// it once per edge).
    #[inline(always)]
    pub(crate) fn landmark_site_of(&self, rec: &LandmarkRecord, l: u32) -> Option<(Vec2, f32)> {
        if l >= rec.landmark_count {
            return None;
        }
        let r: LandmarkSiteRecord =
            self.record(self.layout.landmarks, LandmarkSiteRecord::SIZE, l as usize)?;
        Some((Vec2::new(r.x, r.y), r.d_max))
    }

    /// Landmark mode: the stored quality `q(direction, weather)` of landmark `l`, in `[0, 1]`.
    pub fn rosette_quality(&self, l: u32, weather: u32, direction: u32) -> Option<f32> {
        self.rosette_quality_of(self.landmark()?, l, weather, direction)
    }

    /// [`Network::rosette_quality`] with the landmark record already at hand.
    #[inline(always)]
    pub(crate) fn rosette_quality_of(
        &self,
        rec: &LandmarkRecord,
        l: u32,
        weather: u32,
        direction: u32,
    ) -> Option<f32> {
        if l >= rec.landmark_count || weather >= rec.weather_count || direction >= rec.directions {
            return None;
        }
        let i = (l as usize * rec.weather_count as usize + weather as usize)
            * rec.directions as usize
            + direction as usize;
        self.record::<F32Record>(self.layout.rosettes, F32Record::SIZE, i)
            .map(|r| r.0)
    }

    /// Landmark mode: the positions of edge `e`'s line elements in the chain index list (empty
    /// for other modes); read them with [`Network::chain_element`].
    pub fn chain_elements(&self, e: u32) -> core::ops::Range<u32> {
        let ModeSection::Landmark { .. } = self.section else {
            return 0..0;
        };
        if e >= self.header.edge_count {
            return 0..0;
        }
        self.offset(self.layout.chain_offsets, e)..self.offset(self.layout.chain_offsets, e + 1)
    }

    /// Landmark mode: the line element at position `k` of the chain index list (the chains'
    /// elements end to end, as [`Network::chain_elements`] ranges them).
    pub fn chain_element(&self, k: u32) -> Option<LineElement> {
        let l = self.landmark()?;
        if k >= l.chain_index_count {
            return None;
        }
        let U16Record(i) = self.record(self.layout.chain_indices, U16Record::SIZE, k as usize)?;
        if i as u32 >= l.element_count {
            return None;
        }
        let r: ElementRecord =
            self.record(self.layout.elements, ElementRecord::SIZE, i as usize)?;
        Some(LineElement::new(Vec2::new(r.x, r.y), Vec2::new(r.vx, r.vy)))
    }

    /// Landmark mode: the number of Hermite pieces of edge `e` (its elements minus one).
    pub fn chain_piece_count(&self, e: u32) -> u32 {
        (self.chain_elements(e).len() as u32).saturating_sub(1)
    }

    /// Landmark mode: the most pieces of any edge.
    pub fn max_chain_pieces(&self) -> u32 {
        match self.section {
            ModeSection::Landmark {
                max_chain_pieces, ..
            } => max_chain_pieces,
            _ => 0,
        }
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
        HermiteSegment::new(&a, &b, self.landmark()?.v_nominal).ok()
    }
}
