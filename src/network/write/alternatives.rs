//! The writer of the pop-up alternatives section (Ruz et al.; `docs/FORMAT.md`).

use super::{count, push, WriteError};
use crate::network::format::*;
use crate::Vec2;
use std::vec::Vec;

/// A bypass alternative to store: its figures (`crate::planner::risk::RouteFigures`) and the
/// blocking discs that, with its pop-up's disc, make the planner fly it.
#[derive(Clone, Debug, PartialEq)]
pub struct AlternativeSpec {
    /// M, its steps of Δt.
    pub steps: u32,
    /// P_S,known.
    pub survival_known: f32,
    /// P_S,PU against its pop-up's radar.
    pub survival_popup: f32,
    /// F_c.
    pub fuel: f32,
    /// Its length, metres.
    pub length_m: f32,
    /// Its blocking discs: centre and radius, metres.
    pub discs: Vec<(Vec2, f32)>,
}

/// A potential pop-up threat to store, with its alternatives.
#[derive(Clone, Debug, PartialEq)]
pub struct PopupSpec {
    /// Centre of its lethal disc.
    pub centre: Vec2,
    /// Radius of its lethal disc, metres.
    pub radius: f32,
    /// P_A known on the ground.
    pub probability: f32,
    /// Its alternatives, in the order the decision numbers them.
    pub alternatives: Vec<AlternativeSpec>,
}

/// The pop-up alternatives section.
#[derive(Clone, Debug, PartialEq)]
pub struct AlternativesSpec {
    /// M of the nominal route.
    pub nominal_steps: u32,
    /// T_max of the mission.
    pub time_limit: f32,
    /// F_cmax of the mission.
    pub fuel_limit: f32,
    /// The pop-ups.
    pub popups: Vec<PopupSpec>,
}

/// Appends the section to `body`. The counts' domains are the loader's; the writer checks only
/// that they fit their fields (the encoder then loads the image, which checks the rest).
pub(super) fn write_alternatives_section(
    body: &mut Vec<u8>,
    a: &AlternativesSpec,
) -> Result<(), WriteError> {
    let alternatives: usize = a.popups.iter().map(|p| p.alternatives.len()).sum();
    let discs: usize = a
        .popups
        .iter()
        .flat_map(|p| &p.alternatives)
        .map(|k| k.discs.len())
        .sum();
    push(
        body,
        &AlternativesRecord {
            popup_count: count(a.popups.len(), "stored pop-ups")?,
            alternative_count: count(alternatives, "stored alternatives")?,
            disc_count: count(discs, "blocking discs")?,
            nominal_steps: a.nominal_steps,
            time_limit: a.time_limit,
            fuel_limit: a.fuel_limit,
        },
    );
    for p in &a.popups {
        push(
            body,
            &PopupRecord {
                x: p.centre.x,
                y: p.centre.y,
                radius: p.radius,
                probability: p.probability,
                alternative_count: count(p.alternatives.len(), "alternatives of a pop-up")?,
            },
        );
    }
    for k in a.popups.iter().flat_map(|p| &p.alternatives) {
        push(
            body,
            &AlternativeRecord {
                steps: k.steps,
                survival_known: k.survival_known,
                survival_popup: k.survival_popup,
                fuel: k.fuel,
                length_m: k.length_m,
                disc_count: count(k.discs.len(), "blocking discs of an alternative")?,
            },
        );
    }
    for &(c, r) in a
        .popups
        .iter()
        .flat_map(|p| &p.alternatives)
        .flat_map(|k| &k.discs)
    {
        push(
            body,
            &DiscRecord {
                x: c.x,
                y: c.y,
                radius: r,
            },
        );
    }
    Ok(())
}
