//! The pop-up alternatives kept in the network image: `skyroute build` plans and scores every
//! pop-up's alternatives ([`super::alternatives::plan_study`]) on the network it has just
//! encoded and writes them into it ([`with_alternatives`]); `skyroute plan --popup-appears`,
//! `montecarlo` and the aircraft ([`skyroute::planner::alternatives`]) then decide among the
//! stored ones. [`study`] reads them back ([`stored_study`]): each alternative's route is
//! planned again from its stored discs (for the route file and `render`), its figures are the
//! stored ones, which the aircraft decides with.

use super::alternatives::{plan_study, study_with, Planning, ScoredRoute, Study};
use super::{risk_params, LIMITS};
use crate::frame::LocalFrame;
use crate::mission::LocalPopup;
use crate::scenario::Scenario;
use skyroute::network::write::{
    encode_with_alternatives, AlternativeSpec, AlternativesSpec, NetworkSpec, PopupSpec,
};
use skyroute::network::{StoredAlternative, StoredPopup};
use skyroute::planner::risk::{RiskParams, RouteFigures};
use skyroute::Network;

/// The section's contents for `study`: every pop-up with its alternatives' figures and their
/// blocking discs (each alternative's discs after its pop-up's own), under the paper's limits.
pub fn alternatives_spec(study: &Study) -> AlternativesSpec {
    AlternativesSpec {
        nominal_steps: study.nominal.figures.steps,
        time_limit: LIMITS.time_max,
        fuel_limit: LIMITS.fuel_max,
        popups: study
            .popups
            .iter()
            .map(|p| PopupSpec {
                centre: p.centre,
                radius: p.radius_m,
                probability: p.probability as f32,
                alternatives: p
                    .alternatives
                    .iter()
                    .map(|a| AlternativeSpec {
                        steps: a.figures.steps,
                        survival_known: a.figures.survival_known,
                        survival_popup: a.figures.survival_popup,
                        fuel: a.figures.fuel,
                        length_m: a.length_m as f32,
                        discs: a
                            .discs
                            .iter()
                            .skip(1)
                            .map(|d| (d.centre, d.radius))
                            .collect(),
                    })
                    .collect(),
            })
            .collect(),
    }
}

/// Plans and scores the alternatives of every pop-up of `s` on `bytes` (the network just
/// encoded from `spec`) and encodes the network again with them. Work: the study's
/// `1 + n·(1 + 4·(n_a − 1))` missions at most.
pub fn with_alternatives(
    s: &Scenario,
    frame: &LocalFrame,
    spec: &NetworkSpec,
    bytes: &[u8],
) -> Result<Vec<u8>, String> {
    let planning = Planning {
        bytes,
        scenario: s,
        frame,
        options: super::alternatives_options(),
    };
    let all: Vec<usize> = (0..s.popups.len()).collect();
    let study = plan_study(&planning, &risk_params(s), &all)
        .map_err(|e| format!("the pop-ups' bypass alternatives: {e}"))?;
    encode_with_alternatives(spec, &alternatives_spec(&study))
        .map_err(|e| format!("the pop-ups' bypass alternatives could not be stored: {e:?}"))
}

/// The figures stored for an alternative.
fn stored_figures(a: &StoredAlternative) -> RouteFigures {
    RouteFigures {
        steps: a.steps,
        survival_known: a.survival_known,
        survival_popup: a.survival_popup,
        fuel: a.fuel,
    }
}

/// The discs of stored alternative `a` of pop-up `p` (named `name`): the pop-up's own, then the
/// blocking discs.
fn stored_discs(
    net: &Network,
    name: &str,
    p: &StoredPopup,
    a: &StoredAlternative,
) -> Vec<LocalPopup> {
    let mut discs = vec![LocalPopup {
        name: format!("pop-up {name:?}"),
        centre: p.centre,
        radius: p.radius,
        height: None,
    }];
    for j in 0..a.discs {
        if let Some((centre, radius)) = net.blocking_disc(a, j) {
            discs.push(LocalPopup {
                name: format!("pop-up {name:?} block {}", j + 1),
                centre,
                radius,
                height: None,
            });
        }
    }
    discs
}

/// The nominal route and the alternatives of the scenario's pop-ups whose indices `which`
/// lists (in that order): those stored in the network image ([`stored_study`]), or, for an
/// image that stores none, planned now ([`plan_study`]).
pub fn study(planning: &Planning, params: &RiskParams, which: &[usize]) -> Result<Study, String> {
    let net = Network::from_bytes(planning.bytes).map_err(|e| e.to_string())?;
    match stored_study(planning, &net, params, which)? {
        Some(study) => Ok(study),
        None => plan_study(planning, params, which),
    }
}

/// The study of the scenario pop-ups `which` from the alternatives stored in `net` (the image
/// `planning.bytes`), or `Ok(None)` when it stores none. A stored pop-up that is not where the
/// scenario puts it is refused (the provenance check makes that a rebuilt scenario).
pub fn stored_study(
    planning: &Planning,
    net: &Network,
    params: &RiskParams,
    which: &[usize],
) -> Result<Option<Study>, String> {
    let Some(summary) = net.alternatives_summary() else {
        return Ok(None);
    };
    let s = planning.scenario;
    if let Some(&i) = which
        .iter()
        .find(|&&i| s.popups.get(i).is_none() || net.stored_popup(i as u32).is_none())
    {
        return Err(format!(
            "pop-up {i}: the network stores the alternatives of {} pop-ups; rebuild it",
            summary.popups
        ));
    }
    let mut study = study_with(planning, params, which, |i, sp, centre, radars| {
        let p = net
            .stored_popup(i as u32)
            .ok_or_else(|| format!("pop-up {:?}: not stored", sp.name))?;
        if centre.distance(p.centre) > 1.0 || (sp.radius_m as f32 - p.radius).abs() > 1e-3 {
            return Err(format!(
                "pop-up {:?}: the network's stored pop-up is not the scenario's; rebuild it",
                sp.name
            ));
        }
        let mut alternatives = Vec::new();
        for k in 0..p.alternatives {
            let Some(a) = net.stored_alternative(i as u32, k) else {
                break;
            };
            let discs = stored_discs(net, &sp.name, &p, &a);
            let mut route: ScoredRoute = planning
                .score(params, radars, discs, Some(centre))
                .map_err(|e| format!("pop-up {:?}, alternative {}: {e}", sp.name, k + 1))?;
            route.figures = stored_figures(&a);
            alternatives.push(route);
        }
        Ok(alternatives)
    })?;
    study.nominal.figures.steps = summary.nominal_steps;
    Ok(Some(study))
}
