//! The onboard switch of Ruz et al.: when pop-up threats are announced in flight, decide among
//! the bypass alternatives stored in the network image and make the planner fly the chosen
//! ones.
//!
//! 1. [`decide_stored`]: each announced pop-up's alternatives get their decision figures from
//!    the stored ones and the announced appearance probability (R_K, f_t, F_c with
//!    [`super::risk::alternative`]); [`decide`] picks one per pop-up (least Σ R_K within the
//!    mean time and fuel limits).
//! 2. [`Planner::fly_alternatives`]: every chosen alternative's discs (its pop-up's lethal disc,
//!    then the blocking discs that steered the ground tool's planner onto that bypass) are
//!    added as pop-ups, so the next query plans the mission round them, as the ground tool
//!    planned the alternative.
//!
//! Work: [`decide_stored`] reads at most `n·(8 + 32)` records and runs [`decide`] (at most
//! [`decision_work_bound`](super::decision::decision_work_bound) nodes, three searches when
//! infeasible); [`Planner::fly_alternatives`] adds at most `P` pop-ups, each within
//! [`Planner::worst_case_popup_work`].

use super::decision::{
    decide, Alternative, Decision, DecisionError, DecisionLimits, MAX_ALTERNATIVES,
    MAX_DECISION_POPUPS,
};
use super::risk::{alternative, RouteFigures};
use super::{Planner, Popup, PopupError};
use crate::network::format::{MAX_STORED_ALTERNATIVES, MAX_STORED_POPUPS};
use crate::network::Network;
use heapless::Vec;

// The format stores no more than one decision takes.
const _: () = assert!(MAX_STORED_POPUPS as usize == MAX_DECISION_POPUPS);
const _: () = assert!(MAX_STORED_ALTERNATIVES as usize == MAX_ALTERNATIVES);

/// A pop-up announced in flight.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Announced {
    /// Its index among the network's stored pop-ups.
    pub popup: u8,
    /// P_A, the probability that it is there (NaN taken as 1; clamped to [0, 1]).
    pub appearance: f32,
}

/// Why the switch could not decide or fly.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum SwitchError {
    /// The network stores no pop-up alternatives.
    NoAlternatives,
    /// An announced pop-up is not stored, or is announced twice.
    UnknownPopup {
        /// The index given.
        popup: u8,
    },
    /// More pop-ups announced than one decision takes.
    TooManyPopups {
        /// Pop-ups announced.
        count: usize,
    },
    /// The choice does not give one stored alternative per announced pop-up.
    BadChoice,
    /// The decision refused its input or found no choice within the limits.
    Decision(DecisionError),
    /// A disc could not be added (all `P` pop-up slots in use): nothing was added.
    Popup(PopupError),
}

/// The stored figures of alternative `k` of pop-up `u`.
fn figures(net: &Network, u: u8, k: u32) -> Option<RouteFigures> {
    let a = net.stored_alternative(u as u32, k)?;
    Some(RouteFigures {
        steps: a.steps,
        survival_known: a.survival_known,
        survival_popup: a.survival_popup,
        fuel: a.fuel,
    })
}

/// Checks the announcements: stored, distinct, at most [`MAX_DECISION_POPUPS`].
fn check_announced(net: &Network, announced: &[Announced]) -> Result<(), SwitchError> {
    let stored = net
        .alternatives_summary()
        .ok_or(SwitchError::NoAlternatives)?;
    if announced.len() > MAX_DECISION_POPUPS {
        return Err(SwitchError::TooManyPopups {
            count: announced.len(),
        });
    }
    for (i, a) in announced.iter().enumerate() {
        let repeated = announced
            .get(..i)
            .is_some_and(|before| before.iter().any(|b| b.popup == a.popup));
        if a.popup as u32 >= stored.popups || repeated {
            return Err(SwitchError::UnknownPopup { popup: a.popup });
        }
    }
    Ok(())
}

/// The decision's figures of every announced pop-up's stored alternatives, in fixed memory.
struct Inputs {
    rows: [[Alternative; MAX_ALTERNATIVES]; MAX_DECISION_POPUPS],
    counts: [usize; MAX_DECISION_POPUPS],
}

impl Inputs {
    fn gather(net: &Network, announced: &[Announced], nominal_steps: u32) -> Self {
        let mut s = Inputs {
            rows: [[Alternative::default(); MAX_ALTERNATIVES]; MAX_DECISION_POPUPS],
            counts: [0; MAX_DECISION_POPUPS],
        };
        for ((row, count), a) in s.rows.iter_mut().zip(&mut s.counts).zip(announced) {
            for (k, slot) in (0u32..).zip(row.iter_mut()) {
                let Some(f) = figures(net, a.popup, k) else {
                    break;
                };
                *slot = alternative(&f, nominal_steps, a.appearance);
                *count += 1;
            }
        }
        s
    }
}

/// Decides among the stored alternatives of the `announced` pop-ups (module documentation):
/// `decision.choice[i]` is the alternative chosen for `announced[i]`. `limits`: the mission's
/// T_max and F_cmax (the image stores the ground tool's in
/// [`AlternativesSummary`](crate::network::AlternativesSummary)).
pub fn decide_stored(
    net: &Network,
    announced: &[Announced],
    limits: &DecisionLimits,
) -> Result<Decision, SwitchError> {
    check_announced(net, announced)?;
    let nominal_steps = net.alternatives_summary().map_or(0, |s| s.nominal_steps);
    let inputs = Inputs::gather(net, announced, nominal_steps);
    let mut rows: [&[Alternative]; MAX_DECISION_POPUPS] = [&[]; MAX_DECISION_POPUPS];
    for ((r, row), &n) in rows.iter_mut().zip(&inputs.rows).zip(&inputs.counts) {
        *r = row.get(..n).unwrap_or(&[]);
    }
    let rows = rows.get(..announced.len()).unwrap_or(&[]);
    decide(rows, limits).map_err(SwitchError::Decision)
}

impl<'n, const V: usize, const E: usize, const P: usize, const R: usize> Planner<'n, V, E, P, R> {
    /// Adds the discs of the chosen alternatives as pop-ups: for each `announced[i]`, stored
    /// alternative `choice[i]` (as [`decide_stored`] returned it), its pop-up's lethal disc and
    /// its blocking discs. The next query plans round them. All or nothing: when a disc cannot
    /// be added, the ones this call added are removed and the error returned. Returns the ids
    /// of the pop-ups added, for [`Planner::remove_popup`]. Work: one
    /// [`Planner::add_popup`] per disc (at most `P`).
    pub fn fly_alternatives(
        &mut self,
        announced: &[Announced],
        choice: &[u8],
    ) -> Result<Vec<u8, 16>, SwitchError> {
        self.cancel_plan();
        let net = self.network;
        check_announced(&net, announced)?;
        if choice.len() != announced.len() {
            return Err(SwitchError::BadChoice);
        }
        let mut chosen: Vec<(u8, crate::network::StoredAlternative), MAX_DECISION_POPUPS> =
            Vec::new();
        for (a, &k) in announced.iter().zip(choice) {
            let alt = net
                .stored_alternative(a.popup as u32, k as u32)
                .ok_or(SwitchError::BadChoice)?;
            chosen
                .push((a.popup, alt))
                .map_err(|_| SwitchError::BadChoice)?;
        }
        let mut ids: Vec<u8, 16> = Vec::new();
        let mut result = Ok(());
        'discs: for (u, alt) in &chosen {
            let Some(popup) = net.stored_popup(*u as u32) else {
                result = Err(SwitchError::BadChoice);
                break;
            };
            let blocking = (0..alt.discs).filter_map(|j| net.blocking_disc(alt, j));
            for (centre, radius) in core::iter::once((popup.centre, popup.radius)).chain(blocking) {
                match self.add_popup(Popup::Circle { centre, radius }) {
                    Ok(s) if ids.push(s.id).is_ok() => {}
                    Ok(s) => {
                        // More discs than ids can hold (P ≤ 16 makes this unreachable).
                        let _ = self.remove_popup(s.id);
                        result = Err(SwitchError::Popup(PopupError::NoFreeSlot { capacity: 16 }));
                        break 'discs;
                    }
                    Err(e) => {
                        result = Err(SwitchError::Popup(e));
                        break 'discs;
                    }
                }
            }
        }
        match result {
            Ok(()) => Ok(ids),
            Err(e) => {
                for &id in &ids {
                    let _ = self.remove_popup(id);
                }
                Err(e)
            }
        }
    }
}
