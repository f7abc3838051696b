//! The radar detection of the risk model as the planners use it: the detection probability
//! P_t (eq. 7 with the cross-section of eqs 9–12) averaged over the aircraft's heading, as a
//! function of the horizontal distance to the radar, and its piecewise-constant form in rings
//! (the piecewise-linear detection of eqs 13–18 in the MILP).
//!
//! **Rings.** For the probability levels [`RING_LEVELS`] q₁ > q₂ > … the ring radius ρ_k is
//! the distance at which the heading-averaged P_t falls to q_k. Inside ring k and outside ring
//! k − 1 (ρ₀ = 0) the MILP charges the band's value `(q_{k−1} + q_k)/2` (q₀ = 1), outside the
//! last ring 0: a staircase within ±(q_{k−1} − q_k)/2 of the model in each band, and within
//! q_K beyond. As increments, `w_k = value_k − value_{k+1}` is charged for each ring the
//! aircraft is inside.

use super::Pt;
use skyroute::planner::risk::{detection_at, RiskParams};
use skyroute::{Pose, Vec2};

/// The probability levels at which the detection rings are drawn.
pub const RING_LEVELS: [f64; 4] = [0.8, 0.5, 0.2, 0.05];
/// Headings over which P_t is averaged.
const HEADINGS: usize = 36;

/// The heading-averaged detection probability of one radar at horizontal distance `d`, metres.
pub fn mean_detection(params: &RiskParams, d: f64) -> f64 {
    let sum: f64 = (0..HEADINGS)
        .map(|k| {
            let pose = Pose {
                position: Vec2::new(d as f32, 0.0),
                heading: (std::f64::consts::TAU * k as f64 / HEADINGS as f64) as f32,
            };
            detection_at(params, &pose, Vec2::new(0.0, 0.0)) as f64
        })
        .sum();
    sum / HEADINGS as f64
}

/// One detection ring of a radar.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ring {
    /// ρ_k, metres.
    pub radius: f64,
    /// w_k, the detection probability charged for being inside it (on top of the outer rings').
    pub increment: f64,
}

/// The rings of [`RING_LEVELS`], innermost first (module documentation). A level that the
/// averaged P_t never reaches (even above the radar) gives no ring.
pub fn rings(params: &RiskParams) -> Vec<Ring> {
    let mut radii = Vec::new();
    let mut values = Vec::new();
    let mut upper = 1.0;
    for &q in &RING_LEVELS {
        if mean_detection(params, 0.0) >= q {
            radii.push(distance_of_level(params, q));
            values.push(0.5 * (upper + q));
        }
        upper = q;
    }
    (0..radii.len())
        .map(|k| Ring {
            radius: radii[k],
            increment: values[k] - values.get(k + 1).copied().unwrap_or(0.0),
        })
        .collect()
}

/// The staircase's detection probability at distance `d` from a radar with `rings`.
pub fn ring_detection(rings: &[Ring], d: f64) -> f64 {
    rings
        .iter()
        .filter(|r| d < r.radius)
        .map(|r| r.increment)
        .sum()
}

/// The distance at which the averaged P_t falls to `q` (bisection; P_t decreases with the
/// distance), metres.
fn distance_of_level(params: &RiskParams, q: f64) -> f64 {
    let (mut lo, mut hi) = (0.0, params.radar.range_max_m as f64);
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if mean_detection(params, mid) > q {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// The risk model's detection charge of flying `duration_s` seconds: p_k per Δt of certain
/// detection (eq. 22 to first order), so that Σ charge·P_t approximates the kill probability.
pub fn charge_per_second(params: &RiskParams) -> f64 {
    params.kill_per_step as f64 / params.dt_s as f64
}

/// The heading-averaged detection of every radar summed at `p` (the union's probability to
/// first order), used as A*'s detection density.
pub fn summed_detection(params: &RiskParams, radars: &[Pt], p: Pt) -> f64 {
    radars
        .iter()
        .map(|r| mean_detection(params, p.dist(*r)))
        .sum()
}
