//! The pop-up alternatives section of a network image (Ruz et al.): for each potential pop-up
//! threat, the bypass alternatives the ground tool planned and scored, read in place. Present
//! when the header has [`FLAG_POPUP_ALTERNATIVES`]; it follows the mode's section
//! (`docs/FORMAT.md`, pop-up alternatives). The decision among them and the switch to the
//! chosen ones are `crate::planner::alternatives`.
//!
//! The tables are small (at most [`MAX_STORED_POPUPS`] pop-ups of
//! [`MAX_STORED_ALTERNATIVES`] alternatives of [`MAX_BLOCKING_DISCS`] discs), so an alternative
//! is found by summing the counts before it: at most 8 + 32 records read per access.

use super::format::*;
use super::{Layout, LoadError, Network, Parameter, Section};
use crate::geometry::{Vec2, MAX_COORDINATE_M};

/// The largest magnitude of a stored fuel factor or limit (the decision's
/// [`MAX_FACTOR`](crate::planner::decision::MAX_FACTOR)).
const MAX_STORED_FACTOR: f32 = 1e6;

/// What the alternatives section holds in all.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct AlternativesSummary {
    /// Pop-ups stored.
    pub popups: u32,
    /// M of the nominal route (the time factors' τ = M·Δt).
    pub nominal_steps: u32,
    /// The mission's T_max.
    pub time_limit: f32,
    /// The mission's F_cmax.
    pub fuel_limit: f32,
}

/// A stored potential pop-up threat.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct StoredPopup {
    /// Centre of its lethal disc.
    pub centre: Vec2,
    /// Radius of its lethal disc, metres.
    pub radius: f32,
    /// P_A known on the ground.
    pub probability: f32,
    /// Its alternatives (at least 1).
    pub alternatives: u32,
}

/// A stored bypass alternative.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct StoredAlternative {
    /// M, its steps of Δt.
    pub steps: u32,
    /// P_S,known.
    pub survival_known: f32,
    /// P_S,PU against its own pop-up's radar.
    pub survival_popup: f32,
    /// F_c.
    pub fuel: f32,
    /// Its length as planned on the ground, metres.
    pub length_m: f32,
    /// Its blocking discs.
    pub discs: u32,
    /// Index of its first blocking disc in the disc table.
    first_disc: u32,
}

impl Layout {
    /// Adds the alternatives section at the end, or `None` on overflow.
    fn with_alternatives(mut self, a: &AlternativesRecord) -> Option<Self> {
        let size = |count: u32, record: usize| (count as usize).checked_mul(record);
        self.alternatives = self.end;
        self.stored_popups = self.end.checked_add(AlternativesRecord::SIZE)?;
        self.stored_alternatives = self
            .stored_popups
            .checked_add(size(a.popup_count, PopupRecord::SIZE)?)?;
        self.blocking_discs = self
            .stored_alternatives
            .checked_add(size(a.alternative_count, AlternativeRecord::SIZE)?)?;
        self.end = self
            .blocking_discs
            .checked_add(size(a.disc_count, DiscRecord::SIZE)?)?;
        Some(self)
    }
}

/// Reads the alternatives record after the mode's section (it sizes the tables after it).
pub(super) fn read_section(bytes: &[u8], layout: Layout) -> Result<Layout, LoadError> {
    let a: AlternativesRecord =
        layout.mode_record(bytes, AlternativesRecord::SIZE, Section::PopupAlternatives)?;
    layout
        .with_alternatives(&a)
        .ok_or(LoadError::CountsTooLarge)
}

/// Whether `x` is a probability.
fn is_probability(x: f32) -> bool {
    (0.0..=1.0).contains(&x)
}

/// Whether a disc is finite, in range and of positive radius.
fn is_disc(centre: Vec2, radius: f32) -> bool {
    centre.is_finite()
        && centre.is_in_range()
        && radius.is_finite()
        && radius > 0.0
        && radius <= MAX_COORDINATE_M
}

impl<'a> Network<'a> {
    /// Whether the image has the alternatives section.
    fn has_alternatives(&self) -> bool {
        self.header.flags & FLAG_POPUP_ALTERNATIVES != 0
    }

    fn alternatives_record(&self) -> Option<AlternativesRecord> {
        if !self.has_alternatives() {
            return None;
        }
        self.record(self.layout.alternatives, AlternativesRecord::SIZE, 0)
    }

    /// Checks the alternatives section: its record's counts and limits, then every pop-up,
    /// alternative and disc, and that the per-record counts add up to the record's totals.
    /// Work: O(pop-ups + alternatives + discs), each bounded by the format's maxima.
    pub(super) fn validate_alternatives(&self) -> Result<(), LoadError> {
        let Some(a) = self.alternatives_record() else {
            return match self.has_alternatives() {
                true => Err(LoadError::Malformed {
                    section: Section::PopupAlternatives,
                    index: 0,
                }),
                false => Ok(()),
            };
        };
        let factor = |x: f32| x.is_finite() && libm::fabsf(x) <= MAX_STORED_FACTOR;
        let record_ok = (1..=MAX_STORED_POPUPS).contains(&a.popup_count)
            && a.nominal_steps > 0
            && factor(a.time_limit)
            && factor(a.fuel_limit);
        if !record_ok {
            return Err(LoadError::InvalidParameter {
                parameter: Parameter::PopupAlternatives,
            });
        }
        let bad = |section, index| LoadError::BadPopupAlternatives { section, index };
        let mut alternatives = 0u32;
        for u in 0..a.popup_count {
            let p: PopupRecord = self.checked_record(
                Section::StoredPopups,
                self.layout.stored_popups,
                PopupRecord::SIZE,
                u,
            )?;
            let ok = is_disc(Vec2::new(p.x, p.y), p.radius)
                && is_probability(p.probability)
                && (1..=MAX_STORED_ALTERNATIVES).contains(&p.alternative_count);
            if !ok {
                return Err(bad(Section::StoredPopups, u));
            }
            alternatives += p.alternative_count;
        }
        if alternatives != a.alternative_count {
            return Err(bad(Section::PopupAlternatives, 0));
        }
        let mut discs = 0u32;
        for k in 0..a.alternative_count {
            let r: AlternativeRecord = self.checked_record(
                Section::StoredAlternatives,
                self.layout.stored_alternatives,
                AlternativeRecord::SIZE,
                k,
            )?;
            let ok = r.steps > 0
                && is_probability(r.survival_known)
                && is_probability(r.survival_popup)
                && factor(r.fuel)
                && r.fuel >= 0.0
                && r.length_m.is_finite()
                && r.length_m > 0.0
                && r.disc_count <= MAX_BLOCKING_DISCS;
            if !ok {
                return Err(bad(Section::StoredAlternatives, k));
            }
            discs += r.disc_count;
        }
        if discs != a.disc_count {
            return Err(bad(Section::PopupAlternatives, 0));
        }
        for d in 0..a.disc_count {
            let r: DiscRecord = self.checked_record(
                Section::BlockingDiscs,
                self.layout.blocking_discs,
                DiscRecord::SIZE,
                d,
            )?;
            if !is_disc(Vec2::new(r.x, r.y), r.radius) {
                return Err(bad(Section::BlockingDiscs, d));
            }
        }
        Ok(())
    }

    /// The alternatives section's totals, or `None` when the image has none.
    pub fn alternatives_summary(&self) -> Option<AlternativesSummary> {
        let a = self.alternatives_record()?;
        Some(AlternativesSummary {
            popups: a.popup_count,
            nominal_steps: a.nominal_steps,
            time_limit: a.time_limit,
            fuel_limit: a.fuel_limit,
        })
    }

    /// Stored pop-up `u`, or `None` past the stored ones (or without the section).
    pub fn stored_popup(&self, u: u32) -> Option<StoredPopup> {
        let a = self.alternatives_record()?;
        if u >= a.popup_count {
            return None;
        }
        let p: PopupRecord =
            self.record(self.layout.stored_popups, PopupRecord::SIZE, u as usize)?;
        Some(StoredPopup {
            centre: Vec2::new(p.x, p.y),
            radius: p.radius,
            probability: p.probability,
            alternatives: p.alternative_count,
        })
    }

    /// Alternative `k` of stored pop-up `u`, or `None` past them. Work: at most
    /// [`MAX_STORED_POPUPS`] + [`MAX_STORED_POPUPS`]·[`MAX_STORED_ALTERNATIVES`] record reads.
    pub fn stored_alternative(&self, u: u32, k: u32) -> Option<StoredAlternative> {
        if k >= self.stored_popup(u)?.alternatives {
            return None;
        }
        // Its index in the alternative table: the alternatives of the pop-ups before it.
        let before: u32 = (0..u)
            .filter_map(|w| self.stored_popup(w))
            .map(|p| p.alternatives)
            .sum();
        let index = before.checked_add(k)?;
        let mut first_disc = 0u32;
        for i in 0..index {
            let r: AlternativeRecord = self.record(
                self.layout.stored_alternatives,
                AlternativeRecord::SIZE,
                i as usize,
            )?;
            first_disc = first_disc.checked_add(r.disc_count)?;
        }
        let r: AlternativeRecord = self.record(
            self.layout.stored_alternatives,
            AlternativeRecord::SIZE,
            index as usize,
        )?;
        Some(StoredAlternative {
            steps: r.steps,
            survival_known: r.survival_known,
            survival_popup: r.survival_popup,
            fuel: r.fuel,
            length_m: r.length_m,
            discs: r.disc_count,
            first_disc,
        })
    }

    /// Blocking disc `j` of `alternative` (as [`Network::stored_alternative`] returned it):
    /// centre and radius, or `None` past its discs.
    pub fn blocking_disc(&self, alternative: &StoredAlternative, j: u32) -> Option<(Vec2, f32)> {
        if j >= alternative.discs {
            return None;
        }
        let index = alternative.first_disc.checked_add(j)?;
        let d: DiscRecord =
            self.record(self.layout.blocking_discs, DiscRecord::SIZE, index as usize)?;
        Some((Vec2::new(d.x, d.y), d.radius))
    }
}
