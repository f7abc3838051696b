//! The bypass alternatives of each pop-up, planned with the onboard core and scored by the
//! risk model.
//!
//! The nominal route is the mission planned without pop-ups. For each pop-up of the scenario
//! [`ALTERNATIVES`] entire routes start → goal are planned that never enter its disc (the core
//! keeps the network's clearance from every pop-up disc it is given):
//!
//! - alternative 1: the mission with the pop-up's disc added, the shortest bypass;
//! - alternative k > 1: the mission with the pop-up's disc and one *blocking disc* per earlier
//!   alternative, centred on that alternative's point nearest the pop-up's centre (where it
//!   passes the pop-up), of radius [`BLOCK_RADIUS_M`] doubled up to
//!   [`BLOCK_DOUBLINGS`] times until the route found is *distinct*: more than
//!   [`DISTINCT_SHARE`] of its length lies farther than [`DISTINCT_TOLERANCE_M`] from every
//!   earlier alternative. A blocking disc that would cover the start or the goal is not used.
//!
//! A pop-up whose disc (radius + clearance) does not touch the nominal route still gets its
//! alternatives (the first is then the nominal route itself): its radar's risk reaches beyond
//! its disc, so passing it farther off can be worth a detour. Each alternative is scored with
//! [`route_figures`] among the scenario's threats (the known radars) and the pop-up's radar.

use crate::frame::LocalFrame;
use crate::local::local;
use crate::mission::{plan_mission_with, LocalPopup, Mission, MissionError, MissionOptions};
use crate::scenario::{Popup as ScenarioPopup, Scenario};
use skyroute::planner::risk::{route_figures, RiskParams, RouteFigures};
use skyroute::{Primitive, Vec2};

/// n_a: alternatives per pop-up.
pub const ALTERNATIVES: usize = 3;
/// The first radius of a blocking disc, metres.
pub const BLOCK_RADIUS_M: f32 = 1000.0;
/// How many times a blocking disc's radius is doubled at most while the route stays too close
/// to an earlier alternative.
pub const BLOCK_DOUBLINGS: u32 = 3;
/// The share of a route's length that must lie away from every earlier alternative.
pub const DISTINCT_SHARE: f64 = 0.05;
/// How far from an earlier alternative a part of a route must lie to count as different,
/// metres.
pub const DISTINCT_TOLERANCE_M: f64 = 250.0;
/// Spacing of the points at which routes are compared, metres.
const COMPARE_STEP_M: f32 = 50.0;

/// A planned route and its figures.
#[derive(Clone, Debug)]
pub struct ScoredRoute {
    /// The discs it was planned with (the pop-up's first, then the blocking discs).
    pub discs: Vec<LocalPopup>,
    /// Its lines and arcs, start to goal.
    pub route: Vec<Primitive>,
    /// Its length, metres.
    pub length_m: f64,
    /// Its risk figures (survival against the pop-up's radar: 1 for the nominal route).
    pub figures: RouteFigures,
    /// The mission as the core planned it.
    pub mission: Mission,
}

/// A pop-up and its alternatives.
#[derive(Clone, Debug)]
pub struct PopupAlternatives {
    /// The pop-up's name in the scenario.
    pub name: String,
    /// Its centre in the local frame.
    pub centre: Vec2,
    /// Its disc's radius, metres.
    pub radius_m: f32,
    /// P_A, its appearance probability.
    pub probability: f64,
    /// The nominal route's least distance from its centre, metres.
    pub nominal_distance_m: f64,
    /// Whether its disc, widened by the clearance, touches the nominal route.
    pub touches_nominal: bool,
    /// The alternatives, shortest first.
    pub alternatives: Vec<ScoredRoute>,
}

/// The nominal route and every pop-up's alternatives.
#[derive(Clone, Debug)]
pub struct Study {
    /// The risk model's parameters.
    pub params: RiskParams,
    /// The known radars (the scenario's threats) in the local frame.
    pub radars: Vec<Vec2>,
    /// The nominal route (no pop-ups).
    pub nominal: ScoredRoute,
    /// The scenario's pop-ups in its order, with their alternatives.
    pub popups: Vec<PopupAlternatives>,
}

/// What the studies plan with.
pub struct Planning<'a> {
    /// The network image.
    pub bytes: &'a [u8],
    /// The scenario it was built from.
    pub scenario: &'a Scenario,
    /// The network's frame.
    pub frame: &'a LocalFrame,
    /// Connection settings.
    pub options: MissionOptions,
}

impl Planning<'_> {
    /// Plans the mission with `discs` and scores it (the pop-up radar at `popup`, if given).
    pub fn score(
        &self,
        params: &RiskParams,
        radars: &[Vec2],
        discs: Vec<LocalPopup>,
        popup: Option<Vec2>,
    ) -> Result<ScoredRoute, MissionError> {
        let m = plan_mission_with(self.bytes, self.scenario, self.frame, &discs, &self.options)?;
        let route: Vec<Primitive> = m
            .legs
            .iter()
            .flat_map(|l| l.primitives.iter().copied())
            .collect();
        let figures = route_figures(params, &route, radars, popup);
        Ok(ScoredRoute {
            discs,
            route,
            length_m: m.length,
            figures,
            mission: m,
        })
    }
}

/// Points every [`COMPARE_STEP_M`] along the route (and its end), f64.
pub fn sample_points(route: &[Primitive]) -> Vec<(f64, f64)> {
    let mut out = Vec::new();
    for p in route {
        let n = (p.length() / COMPARE_STEP_M).ceil().max(1.0) as usize;
        for i in 0..n {
            let q = p.pose_at(p.length() * i as f32 / n as f32).position;
            out.push((q.x as f64, q.y as f64));
        }
    }
    if let Some(last) = route.last() {
        let q = last.pose_at(last.length()).position;
        out.push((q.x as f64, q.y as f64));
    }
    out
}

/// The share of `a`'s sample points farther than [`DISTINCT_TOLERANCE_M`] from every sample
/// point of `b`.
fn share_apart(a: &[(f64, f64)], b: &[(f64, f64)]) -> f64 {
    if a.is_empty() {
        return 0.0;
    }
    let t2 = DISTINCT_TOLERANCE_M * DISTINCT_TOLERANCE_M;
    let apart = a
        .iter()
        .filter(|p| {
            b.iter()
                .all(|q| (p.0 - q.0).powi(2) + (p.1 - q.1).powi(2) > t2)
        })
        .count();
    apart as f64 / a.len() as f64
}

/// Whether `route` is distinct from every route of `earlier`.
fn is_distinct(route: &[Primitive], earlier: &[ScoredRoute]) -> bool {
    let a = sample_points(route);
    earlier
        .iter()
        .all(|e| share_apart(&a, &sample_points(&e.route)) > DISTINCT_SHARE)
}

/// The least distance from `c` to the route's sample points, and the nearest point.
pub fn nearest_point(route: &[Primitive], c: Vec2) -> (f64, Vec2) {
    sample_points(route)
        .into_iter()
        .map(|(x, y)| {
            let d = (x - c.x as f64).hypot(y - c.y as f64);
            (d, Vec2::new(x as f32, y as f32))
        })
        .fold((f64::INFINITY, c), |a, b| if b.0 < a.0 { b } else { a })
}

/// Plans and scores the nominal route and the alternatives of the scenario's pop-ups whose
/// indices `which` lists (in that order), as the module documentation says.
pub fn plan_study(
    planning: &Planning,
    params: &RiskParams,
    which: &[usize],
) -> Result<Study, String> {
    study_with(planning, params, which, |_, p, centre, radars| {
        alternatives_of(planning, params, radars, &p.name, centre, p.radius_m)
    })
}

/// The nominal route (scored against the scenario's threats) and, for each scenario pop-up
/// whose index `which` lists (in that order; an index past them is skipped), the alternatives
/// `alternatives(index, pop-up, its centre, the known radars)` gives.
pub fn study_with(
    planning: &Planning,
    params: &RiskParams,
    which: &[usize],
    mut alternatives: impl FnMut(
        usize,
        &ScenarioPopup,
        Vec2,
        &[Vec2],
    ) -> Result<Vec<ScoredRoute>, String>,
) -> Result<Study, String> {
    let s = planning.scenario;
    let frame = planning.frame;
    let radars: Vec<Vec2> = s
        .threats
        .iter()
        .map(|t| local(frame, t.lon, t.lat))
        .collect();
    let nominal = planning
        .score(params, &radars, Vec::new(), None)
        .map_err(|e| format!("the nominal route: {e}"))?;
    let clearance = planning.scenario.planner.clearance_m.unwrap_or(0.0);
    let mut popups = Vec::new();
    for &i in which {
        let Some(p) = s.popups.get(i) else {
            continue;
        };
        let centre = local(frame, p.lon, p.lat);
        let (d, _) = nearest_point(&nominal.route, centre);
        let alternatives = alternatives(i, p, centre, &radars)?;
        popups.push(PopupAlternatives {
            name: p.name.clone(),
            centre,
            radius_m: p.radius_m as f32,
            probability: p.probability,
            nominal_distance_m: d,
            touches_nominal: d <= p.radius_m + clearance,
            alternatives,
        });
    }
    Ok(Study {
        params: *params,
        radars,
        nominal,
        popups,
    })
}

/// The [`ALTERNATIVES`] alternatives of the pop-up `name` (module documentation): fewer when no
/// blocking disc yields a further distinct route. Each goes round the disc: a scenario
/// pop-up's `height_m` is not used here (no alternative flies over it).
fn alternatives_of(
    planning: &Planning,
    params: &RiskParams,
    radars: &[Vec2],
    name: &str,
    centre: Vec2,
    radius_m: f64,
) -> Result<Vec<ScoredRoute>, String> {
    let disc = LocalPopup {
        name: format!("pop-up {name:?}"),
        centre,
        radius: radius_m as f32,
        height: None,
    };
    let first = planning
        .score(params, radars, vec![disc.clone()], Some(centre))
        .map_err(|e| format!("pop-up {name:?}: no route around it: {e}"))?;
    let mut out = vec![first];
    let ends = endpoints(planning);
    while out.len() < ALTERNATIVES {
        let Some(next) = next_alternative(planning, params, radars, &disc, &out, &ends) else {
            break;
        };
        out.push(next);
    }
    Ok(out)
}

/// The start and the goal in the local frame.
fn endpoints(planning: &Planning) -> Vec<Vec2> {
    let s = planning.scenario;
    s.start
        .iter()
        .chain(s.goal.iter())
        .map(|e| local(planning.frame, e.lon, e.lat))
        .collect()
}

/// The next distinct alternative around `disc` after `earlier`, or `None`.
fn next_alternative(
    planning: &Planning,
    params: &RiskParams,
    radars: &[Vec2],
    disc: &LocalPopup,
    earlier: &[ScoredRoute],
    ends: &[Vec2],
) -> Option<ScoredRoute> {
    let passes: Vec<Vec2> = earlier
        .iter()
        .map(|e| nearest_point(&e.route, disc.centre).1)
        .collect();
    for doubling in 0..=BLOCK_DOUBLINGS {
        let r = BLOCK_RADIUS_M * (1u32 << doubling) as f32;
        let mut discs = vec![disc.clone()];
        for (k, &c) in passes.iter().enumerate() {
            if ends.iter().all(|e| e.distance(c) > r + 1.0) {
                discs.push(LocalPopup {
                    name: format!("{} block {}", disc.name, k + 1),
                    centre: c,
                    radius: r,
                    height: None,
                });
            }
        }
        let Ok(route) = planning.score(params, radars, discs, Some(disc.centre)) else {
            continue;
        };
        if is_distinct(&route.route, earlier) {
            return Some(route);
        }
    }
    None
}
