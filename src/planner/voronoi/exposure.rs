//! Threat exposure and the edge cost of Judd & McLain.
//!
//! The paper costs an edge of length L as J = k·J_fuel + (1 − k)·J_threat with J_fuel = L and
//! J_threat = L·Σ_j (d_{1/6,j}⁻⁴ + d_{1/2,j}⁻⁴ + d_{5/6,j}⁻⁴), d_{f,j} being the distance from
//! the edge's point at f·L to threat j. That J_threat is in m⁻³ while J_fuel is in metres, so
//! k alone says nothing to a user. Here each threat carries a reference distance r_j (the
//! scenario's `radius_m`) and
//!
//! J_threat = (L/3)·Σ_j Σ_{f ∈ {1/6, 1/2, 5/6}} (r_j / d_{f,j})⁴,
//!
//! which is the paper's sum with each threat scaled by r_j⁴/3: flying at distance r_j from a
//! single threat costs one unit of exposure per metre, so k = 0.5 weighs a metre flown there
//! as two metres flown far from every threat.
//!
//! The three points are the composite midpoint rule with three panels for the integral
//! ∫₀ᴸ Σ_j (r_j/d_j(s))⁴ ds. Along a line passing a threat at distance h, the integrand
//! (r/√(h² + s²))⁴ is concave within |s| < h/√5 of the closest point and convex beyond, so
//! the rule over-estimates an edge whose samples straddle a near pass (one sample close to
//! the site weighs a third of the edge) and under-estimates one that passes close to a site
//! between two samples (the peak falls between them). `host-tests` (`voronoi_exposure`)
//! measures both against a dense integral.

use crate::geometry::Vec2;
use crate::planner::threats::Threat;

/// The fractions of an edge's length at which exposure is sampled: L/6, L/2, 5L/6.
pub const EXPOSURE_POINTS: [f32; 3] = [1.0 / 6.0, 0.5, 5.0 / 6.0];

/// The smallest distance to a site a sample counts, as a fraction of the site's reference
/// distance: a sample on the site itself weighs (1/0.01)⁴ = 10⁸ per metre instead of infinity,
/// which keeps every cost finite in f32.
const MIN_DISTANCE_FRACTION: f32 = 0.01;

/// The exposure J_threat of the segment `a → b` to `threats` (module documentation), and the
/// number of terms evaluated (3 per threat).
pub fn segment_exposure(a: Vec2, b: Vec2, threats: &[Threat]) -> (f32, u64) {
    let length = a.distance(b);
    let mut sum = 0.0f32;
    for f in EXPOSURE_POINTS {
        let p = a + (b - a) * f;
        for t in threats {
            let d = p.distance(t.position).max(MIN_DISTANCE_FRACTION * t.radius);
            let q = t.radius / d;
            let q2 = q * q;
            sum += q2 * q2;
        }
    }
    (length / 3.0 * sum, 3 * threats.len() as u64)
}

/// The cost k·L + (1 − k)·J_threat of the segment `a → b`, and the terms evaluated.
pub(super) fn segment_cost(a: Vec2, b: Vec2, threats: &[Threat], k: f32) -> (f32, u64) {
    let (exposure, terms) = segment_exposure(a, b, threats);
    (k * a.distance(b) + (1.0 - k) * exposure, terms)
}
