//! The landmark network's parameters, range rule and build error.

use crate::scenario::Scenario;
use std::fmt;

/// Standard deviation of the chord-leaning headings of line elements, degrees.
pub const CHORD_HEADING_SPREAD_DEG: f64 = 25.0;

/// At most this many line elements are drawn per kept one (positions inside obstacles are drawn
/// again; an ellipse almost filled by obstacles stops here).
pub const MAX_DRAW_FACTOR: usize = 20;

/// The landmark network's parameters.
#[derive(Clone, Debug, PartialEq)]
pub struct LandmarkParams {
    /// Overflight headings per landmark (`planner.directions`, default 12), equally spaced from
    /// compass 0°.
    pub directions: usize,
    /// Random line elements per basic network (`planner.line_elements_per_pair`, default 500).
    pub line_elements_per_pair: usize,
    /// Clearance from obstacles, metres (`planner.clearance_m`, default 0).
    pub clearance_m: f32,
    /// Seed (`planner.seed`, default 1).
    pub seed: u64,
    /// Longest chord tried between two line elements, metres (default 20 turn radii).
    pub neighbour_radius_m: f32,
    /// Nearest targets (and sources) tried per line element (default 48).
    pub max_neighbours: usize,
    /// Which length an edge's range limits (default [`RangeRule::PathLength`]).
    pub range_rule: RangeRule,
    /// Radius of the guide turns, in turn radii `v_nominal² / a_lat_max` (default 1.5; 0: no
    /// guide elements). See *Guide elements*.
    pub guide_radius_factor: f32,
    /// Share of the random line elements whose heading leans along the chord (default 0.5; 0:
    /// all uniform). See *Line elements*.
    pub chord_heading_share: f64,
}

/// What the best-weather range `d_max · max_ω q(α, ω)` of a source overflight limits. Under
/// [`RangeRule::PathLength`] and [`RangeRule::PairDistance`] a direction whose range is shorter
/// than the straight distance to the target gets no edge there; [`RangeRule::Onboard`] limits
/// nothing on the ground.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum RangeRule {
    /// Also the length of the flown chain (Babel: the navigation error grows with the distance
    /// flown since the last overflight): longer chains are dropped.
    #[default]
    PathLength,
    /// Only the straight distance between the two sites: every chain found is kept, and its
    /// `cost` lets the planner apply its own rule.
    PairDistance,
    /// Babel's reading of the network: every direction of every pair is searched, whatever
    /// its range, and every chain found is stored; navigability is left entirely to the
    /// planner's pruning onboard (`skyroute build --landmark-ranges onboard`).
    Onboard,
}

impl RangeRule {
    /// Whether a source direction of range `range` gets a search towards a site `d` metres
    /// away: under [`RangeRule::Onboard`] always, otherwise only if a straight leg reaches.
    pub fn searches(self, range: f32, d: f32) -> bool {
        self == RangeRule::Onboard || range >= d
    }
}

impl LandmarkParams {
    /// The scenario's parameters with this module's defaults for what it leaves out.
    pub fn from_scenario(s: &Scenario) -> Self {
        let p = &s.planner;
        Self {
            directions: p.directions.unwrap_or(12) as usize,
            line_elements_per_pair: p.line_elements_per_pair.unwrap_or(500) as usize,
            clearance_m: p.clearance_m.unwrap_or(0.0) as f32,
            seed: p.seed.unwrap_or(1),
            neighbour_radius_m: 20.0 * s.vehicle.turn_radius_m() as f32,
            max_neighbours: 48,
            range_rule: RangeRule::PathLength,
            guide_radius_factor: 1.5,
            chord_heading_share: 0.5,
        }
    }
}

/// Why a landmark network could not be built. Each variant names the scenario file.
#[derive(Clone, Debug, PartialEq)]
pub enum LandmarkError {
    /// The scenario lacks something landmark mode needs: (file, what).
    Missing(String, &'static str),
    /// A value is unusable: (file, field, why).
    Invalid(String, String, String),
}

impl fmt::Display for LandmarkError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            LandmarkError::Missing(file, what) => {
                write!(f, "{file}: {what}: required for a landmark network")
            }
            LandmarkError::Invalid(file, field, why) => write!(f, "{file}: {field}: {why}"),
        }
    }
}

impl std::error::Error for LandmarkError {}
