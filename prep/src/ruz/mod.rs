//! Pop-up threats under uncertainty (Ruz et al.) on the ground: the risk model's parameters
//! for a scenario, the bypass alternatives of each pop-up scored by risk, time and fuel
//! ([`alternatives`]), the decision from `skyroute plan --popup-appears` ([`cli`]) and the
//! Monte Carlo study ([`montecarlo`], [`histogram`]), the alternatives kept in the network
//! image ([`stored`]), and the static planners MILP and A* ([`static_plan`]). The model itself is the core's
//! [`skyroute::planner::risk`]; the decision is [`skyroute::planner::decision::decide`].
//! `docs/RUZ.md` states every parameter and the results.

pub mod alternatives;
pub mod cli;
pub mod histogram;
pub mod montecarlo;
pub mod static_plan;
pub mod stored;
pub mod study_cli;

use crate::mission::{MissionOptions, Shortcuts};
use crate::scenario::Scenario;
use skyroute::planner::decision::DecisionLimits;
use skyroute::planner::risk::{Airframe, RadarModel, RiskParams};

/// The paper's limit on the mean time factor.
pub const TIME_LIMIT: f32 = 0.35;
/// The paper's limit on the mean fuel factor.
pub const FUEL_LIMIT: f32 = 0.40;
/// The paper's limits.
pub const LIMITS: DecisionLimits = DecisionLimits {
    time_max: TIME_LIMIT,
    fuel_max: FUEL_LIMIT,
};

/// R_max: the radars' range, metres (the paper's 50 km).
pub const RANGE_MAX_M: f32 = 50_000.0;
/// R_½: the slant range at which a target of σ = 1 m² is detected with probability ½, metres.
pub const HALF_RANGE_M: f32 = 8_000.0;
/// c₁, the exponent of eq. 7 (the classic `1/(1 + (R/R_½)^8)` fall-off of a `R⁴` radar).
pub const C1: f32 = 2.0;
/// The aircraft's height above the radars, metres.
pub const ALTITUDE_M: f32 = 1_000.0;
/// a: half length as a share of the wingspan (length 0.6 × span, a small fixed-wing UAV).
pub const HALF_LENGTH_PER_SPAN: f32 = 0.3;
/// c: half height as a share of the wingspan (height 0.1 × span).
pub const HALF_HEIGHT_PER_SPAN: f32 = 0.05;
/// k: cross-section per square metre of projected area. 1 would be the optical limit of a
/// smooth convex metal body (a sphere's cross-section is its projected area); small composite
/// UAVs measure about a tenth of their projected area, 0.1–1 m².
pub const K: f32 = 0.1;
/// Δt, seconds (one step: 50 m at the scenario's 50 m/s).
pub const DT_S: f32 = 1.0;
/// p_k: the kill probability of one step (Δt) of certain detection: 2·10⁻⁴, so that a
/// minute in a radar's view kills with about 1.2 % and the nominal route of ruz-popups, 20
/// minutes among 12 radars, with 9.4 %.
pub const KILL_PER_STEP: f32 = 0.0002;

/// The risk model's parameters for the scenario's vehicle: the constants of this module, the
/// half span from `vehicle.wingspan_m`, v from `vehicle.v_nominal_mps` and ω_max from
/// `vehicle.a_lat_max_mps2 / v`.
pub fn risk_params(s: &Scenario) -> RiskParams {
    let span = s.vehicle.wingspan_m as f32;
    let v = s.vehicle.v_nominal_mps as f32;
    RiskParams {
        radar: RadarModel {
            range_max_m: RANGE_MAX_M,
            half_range_m: HALF_RANGE_M,
            c1: C1,
            altitude_m: ALTITUDE_M,
        },
        airframe: Airframe {
            half_length_m: HALF_LENGTH_PER_SPAN * span,
            half_span_m: 0.5 * span,
            half_height_m: HALF_HEIGHT_PER_SPAN * span,
            k: K,
        },
        dt_s: DT_S,
        speed_mps: v,
        kill_per_step: KILL_PER_STEP,
        max_turn_rate: s.vehicle.a_lat_max_mps2 as f32 / v,
    }
}

/// The mission options the pop-up alternatives are planned with, stored by `build` and flown by
/// `plan --popup-appears` and the firmware's `ruz` binary: the defaults but the greedy shortcut
/// pass, the one `docs/RUZ.md`'s figures were measured with.
pub fn alternatives_options() -> MissionOptions {
    MissionOptions {
        shortcuts: Shortcuts::Greedy,
        ..MissionOptions::default()
    }
}
