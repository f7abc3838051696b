//! The radar risk model of Ruz et al.: the detection probability of a radar (eq. 7) with the
//! aircraft's radar cross-section from its projected area (eqs 9–12), the kill and survival
//! probabilities along a route sampled every Δt (eq. 22), pop-ups weighted by their appearance
//! probability (eqs 23–25), and the route's time and fuel factors (eqs 27–32), the figures
//! [`crate::planner::decision::decide`] chooses among.
//!
//! **Detection (eq. 7).** `P_t = 1 / (1 + c₂·(R⁴/σ)^{c₁})` for a slant range `R ≤ R_max`, 0
//! beyond. It is evaluated in the scaled form `1 / (1 + ((R/R_½)⁴/σ)^{c₁})` with
//! `c₂ = R_½^{−4c₁}` (σ in m²), which is the same function without the overflow of `R⁸` in f32:
//! [`RadarModel::half_range_m`] `R_½` is the range at which a target of σ = 1 m² is detected
//! with probability ½.
//!
//! **Cross-section (eqs 9–12).** `σ = k·S`, with S the area of the aircraft's projection seen
//! from the radar. The aircraft is an ellipsoid with semi-axes a (half length, along the body
//! x axis), b (half span, y) and c (half height, z). Eq. 12 is garbled in the copies we have,
//! so S is derived here from the ellipsoid itself: the ellipsoid `xᵀ Q x = 1` with
//! `Q = diag(a⁻², b⁻², c⁻²)` projects along the unit direction d onto an ellipse of area
//! `π / sqrt(det Q) · sqrt(dᵀ Q d) = π·a·b·c·sqrt((d_x/a)² + (d_y/b)² + (d_z/c)²)` (the
//! shadow of an ellipsoid: for d along an axis it gives the two other semi-axes' ellipse, π·b·c
//! head-on, π·a·b from below). The direction is the line of sight in the body frame of a
//! wings-level aircraft on its heading (bank in turns is not modelled).
//!
//! **Geometry.** The radars stand on the ground (height 0) and the aircraft flies at a fixed
//! height [`RadarModel::altitude_m`] above them; the slant range is
//! `R = sqrt(horizontal² + altitude²)`. An altitude of 0 makes the model planar.
//!
//! **Along a route (eqs 22, 28).** The route of length L flown at `v` is cut into
//! `M = max(1, ⌈L/(v·Δt)⌉)` steps of equal length, and sampled at each step's middle; its time
//! is `T = M·Δt` (eq. 28). A step is detected by a set of radars with probability
//! `1 − Π_j (1 − P_t,j)` and kills with probability `P_K,i = p_k·(1 − Π_j (1 − P_t,j))`
//! ([`RiskParams::kill_per_step`] p_k); the route's survival is `P_S = Π_i (1 − P_K,i)`.
//!
//! **Pop-ups (eqs 23–25).** A pop-up radar is active with its appearance probability P_A. The
//! survival of a route is then, by total probability over the pop-up's presence,
//! `P_ST = P_S,known · ((1 − P_A) + P_A·P_S,PU)` with `P_S,PU` the route's survival against the
//! pop-up's radar alone, and its risk is `R_K = 1 − P_ST` ([`AlternativeRisk::risk`]). The
//! paper writes `P_ST = α·P_S,PU·Π P_S,i` with `α = 1 − P_A`; taken literally that survival is
//! 0 for a pop-up that surely appears however far it is, and its remark that P_A = 0 makes the
//! pop-up "nonexistent" contradicts it (the literal product keeps the pop-up's full effect
//! then). The mixture above is the reading that satisfies both of its remarks: a more probable
//! pop-up lowers the survival, P_A = 0 removes it and P_A = 1 makes it a fixed radar. The
//! decomposition into the two numbers `P_S,known` and `P_S,PU` per alternative lets the onboard
//! decision recompute R_K when the announced P_A changes.
//!
//! **Time and fuel (eqs 27–32).** The time factor of an alternative is `f_t = 1 − τ/T` with τ
//! the nominal route's time and T the alternative's: the share of the alternative's time that
//! is delay, 0 for the nominal route, growing with the detour, so that a limit `f_t ≤ T_max`
//! bounds the delay (T ≤ τ/(1 − T_max)). The fuel factor is the mean normalised turn effort,
//! `F_c = (1/(M−1)) Σ_i |Δψ_i| / (ω_max·δt)` over the heading changes between consecutive
//! samples, δt = L/(M·v) apart (Δt up to the rounding of M), with `ω_max = a_lat,max / v` the
//! largest turn rate: 0 for a straight route, 1 for one flown in a continuous turn at the
//! tightest radius.
//!
//! Everything is f32, allocates nothing and never panics; the work of [`route_figures`] is
//! `M·(radars + 1)` detection evaluations plus one pass over the primitives.

use crate::geometry::{wrap_to_pi, Pose, Primitive, Vec2};
use crate::planner::decision::Alternative;

/// A radar's detection model (eq. 7), the same for every radar.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct RadarModel {
    /// R_max: no detection beyond this slant range, metres.
    pub range_max_m: f32,
    /// R_½: the slant range at which σ = 1 m² is detected with probability ½, metres
    /// (`c₂ = R_½^{−4c₁}`).
    pub half_range_m: f32,
    /// The exponent c₁.
    pub c1: f32,
    /// The aircraft's height above the radars, metres (0: planar).
    pub altitude_m: f32,
}

/// The aircraft as an ellipsoid, and its cross-section factor k (σ = k·S).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Airframe {
    /// a: half length, metres.
    pub half_length_m: f32,
    /// b: half span, metres.
    pub half_span_m: f32,
    /// c: half height, metres.
    pub half_height_m: f32,
    /// k: radar cross-section per square metre of projected area.
    pub k: f32,
}

/// Everything the risk of a route depends on besides the route and the radars.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct RiskParams {
    /// The radars' detection model.
    pub radar: RadarModel,
    /// The aircraft's shape.
    pub airframe: Airframe,
    /// Δt: the sampling step, seconds.
    pub dt_s: f32,
    /// v: the nominal speed, m/s.
    pub speed_mps: f32,
    /// p_k: the kill probability of one step in which the aircraft is detected.
    pub kill_per_step: f32,
    /// ω_max: the largest turn rate, rad/s (`a_lat,max / v`).
    pub max_turn_rate: f32,
}

/// Why [`RiskParams::validate`] refused the parameters: the field named.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct BadRiskParam {
    /// The field, as written in [`RiskParams`] and its members.
    pub field: &'static str,
}

impl RiskParams {
    /// Checks every parameter: lengths, Δt, v, ω_max, c₁ and k finite and positive, the
    /// altitude finite and not negative, p_k in [0, 1].
    pub fn validate(&self) -> Result<(), BadRiskParam> {
        let positive = [
            ("radar.range_max_m", self.radar.range_max_m),
            ("radar.half_range_m", self.radar.half_range_m),
            ("radar.c1", self.radar.c1),
            ("airframe.half_length_m", self.airframe.half_length_m),
            ("airframe.half_span_m", self.airframe.half_span_m),
            ("airframe.half_height_m", self.airframe.half_height_m),
            ("airframe.k", self.airframe.k),
            ("dt_s", self.dt_s),
            ("speed_mps", self.speed_mps),
            ("max_turn_rate", self.max_turn_rate),
        ];
        for (field, v) in positive {
            if !(v.is_finite() && v > 0.0) {
                return Err(BadRiskParam { field });
            }
        }
        let altitude = self.radar.altitude_m;
        if !(altitude.is_finite() && altitude >= 0.0) {
            return Err(BadRiskParam {
                field: "radar.altitude_m",
            });
        }
        if !(0.0..=1.0).contains(&self.kill_per_step) {
            return Err(BadRiskParam {
                field: "kill_per_step",
            });
        }
        Ok(())
    }

    /// The length of one step at the nominal speed, metres.
    pub fn step_m(&self) -> f32 {
        self.speed_mps * self.dt_s
    }
}

/// The area of the ellipsoid's projection along the unit direction `d` (body frame: x ahead,
/// y along the span, z up), m²: `π·a·b·c·sqrt((d_x/a)² + (d_y/b)² + (d_z/c)²)`.
pub fn projected_area(airframe: &Airframe, d: [f32; 3]) -> f32 {
    let (a, b, c) = (
        airframe.half_length_m,
        airframe.half_span_m,
        airframe.half_height_m,
    );
    let q = (d[0] / a) * (d[0] / a) + (d[1] / b) * (d[1] / b) + (d[2] / c) * (d[2] / c);
    core::f32::consts::PI * a * b * c * libm::sqrtf(q)
}

/// The detection probability of eq. 7 for a target of cross-section `sigma_m2` at slant range
/// `range_m`: `1 / (1 + ((R/R_½)⁴/σ)^{c₁})`, 0 beyond `R_max`.
pub fn detection_probability(radar: &RadarModel, sigma_m2: f32, range_m: f32) -> f32 {
    if range_m > radar.range_max_m {
        return 0.0;
    }
    let r = range_m / radar.half_range_m;
    let r2 = r * r;
    let x = r2 * r2 / sigma_m2;
    let p = 1.0 / (1.0 + libm::powf(x, radar.c1));
    if p.is_nan() {
        0.0
    } else {
        p
    }
}

/// The detection probability of a radar at `radar` for the aircraft at `pose` (eqs 7–12): the
/// slant range at the model's altitude, the line of sight in the body frame, the projected
/// area and σ = k·S.
pub fn detection_at(params: &RiskParams, pose: &Pose, radar: Vec2) -> f32 {
    let h = params.radar.altitude_m;
    let to = radar - pose.position;
    let range = libm::sqrtf(to.norm_sq() + h * h);
    if range <= 0.0 {
        return 1.0;
    }
    let ahead = pose.direction();
    let d = [ahead.dot(to) / range, ahead.cross(to) / range, -h / range];
    let sigma = params.airframe.k * projected_area(&params.airframe, d);
    detection_probability(&params.radar, sigma, range)
}

/// A route's figures: its steps, its survival against the known radars and against the
/// pop-up's radar alone, and its turn effort.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct RouteFigures {
    /// M, the number of steps (T = M·Δt).
    pub steps: u32,
    /// P_S,known: survival against the known radars.
    pub survival_known: f32,
    /// P_S,PU: survival against the pop-up's radar alone (1 without a pop-up).
    pub survival_popup: f32,
    /// F_c, the mean normalised turn effort.
    pub fuel: f32,
}

impl RouteFigures {
    /// T = M·Δt, seconds.
    pub fn time_s(&self, params: &RiskParams) -> f32 {
        self.steps as f32 * params.dt_s
    }
}

/// The two survival figures of an alternative from which its risk follows for any appearance
/// probability.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct AlternativeRisk {
    /// P_S,known.
    pub survival_known: f32,
    /// P_S,PU.
    pub survival_popup: f32,
}

impl AlternativeRisk {
    /// `R_K = 1 − P_S,known·((1 − P_A) + P_A·P_S,PU)` for appearance probability
    /// `appearance` (clamped to [0, 1]; NaN taken as 1). The result lies in [0, 1].
    pub fn risk(&self, appearance: f32) -> f32 {
        let p = if appearance.is_nan() {
            1.0
        } else {
            appearance.clamp(0.0, 1.0)
        };
        let survival = self.survival_known * ((1.0 - p) + p * self.survival_popup);
        let r = 1.0 - survival;
        if r.is_nan() {
            1.0
        } else {
            r.clamp(0.0, 1.0)
        }
    }
}

/// The time factor `f_t = 1 − τ/T` of an alternative of `steps` steps against a nominal route
/// of `nominal_steps` (0 for no steps).
pub fn time_factor(nominal_steps: u32, steps: u32) -> f32 {
    if steps == 0 {
        return 0.0;
    }
    1.0 - nominal_steps as f32 / steps as f32
}

/// The decision's figures of an alternative: its risk for appearance probability
/// `appearance`, its time factor against the nominal route and its fuel factor.
pub fn alternative(figures: &RouteFigures, nominal_steps: u32, appearance: f32) -> Alternative {
    let risk = AlternativeRisk {
        survival_known: figures.survival_known,
        survival_popup: figures.survival_popup,
    };
    Alternative {
        risk: risk.risk(appearance),
        time: time_factor(nominal_steps, figures.steps),
        fuel: figures.fuel,
    }
}

/// Walks the route's primitives to the poses at given arc lengths, in increasing order.
struct Walker<'r> {
    route: &'r [Primitive],
    index: usize,
    /// Arc length at the start of primitive `index`.
    base: f32,
}

impl Walker<'_> {
    /// The pose at arc length `s` (not below the previous call's).
    fn pose_at(&mut self, s: f32) -> Pose {
        while let Some(p) = self.route.get(self.index) {
            let len = p.length();
            if s <= self.base + len || self.index + 1 == self.route.len() {
                return p.pose_at(s - self.base);
            }
            self.base += len;
            self.index += 1;
        }
        Pose {
            position: Vec2::new(0.0, 0.0),
            heading: 0.0,
        }
    }
}

/// The figures of `route` among the `known` radars and, if given, a pop-up radar at `popup`
/// (eqs 22–32; module documentation). An empty route has no steps, survival 1 and no turn
/// effort. Work: `M·(known.len() + 1)` detection evaluations, M as the module says.
pub fn route_figures(
    params: &RiskParams,
    route: &[Primitive],
    known: &[Vec2],
    popup: Option<Vec2>,
) -> RouteFigures {
    let length: f32 = route.iter().map(|p| p.length()).sum();
    if route.is_empty() || !(length > 0.0) || params.validate().is_err() {
        return RouteFigures {
            steps: 0,
            survival_known: 1.0,
            survival_popup: 1.0,
            fuel: 0.0,
        };
    }
    let steps = libm::ceilf(length / params.step_m()).clamp(1.0, u32::MAX as f32) as u32;
    let ds = length / steps as f32;
    let mut walker = Walker {
        route,
        index: 0,
        base: 0.0,
    };
    let (mut known_survival, mut popup_survival, mut turn) = (1.0f32, 1.0f32, 0.0f32);
    let mut previous: Option<f32> = None;
    for i in 0..steps {
        let pose = walker.pose_at((i as f32 + 0.5) * ds);
        let unseen = known
            .iter()
            .map(|&r| 1.0 - detection_at(params, &pose, r))
            .product::<f32>();
        known_survival *= 1.0 - params.kill_per_step * (1.0 - unseen);
        if let Some(r) = popup {
            popup_survival *= 1.0 - params.kill_per_step * detection_at(params, &pose, r);
        }
        if let Some(h) = previous {
            turn += libm::fabsf(wrap_to_pi(pose.heading - h));
        }
        previous = Some(pose.heading);
    }
    let fuel = if steps > 1 {
        turn / ((steps - 1) as f32 * params.max_turn_rate * (ds / params.speed_mps))
    } else {
        0.0
    };
    RouteFigures {
        steps,
        survival_known: known_survival,
        survival_popup: popup_survival,
        fuel,
    }
}
