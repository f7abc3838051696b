//! The builder's documented limits, checked before anything large is allocated: the area of the
//! scenario's positions, the roadmap's sample spacing and candidate count, the grid index's
//! cells, and a network with no vertices. Each refusal names the file and the scenario field,
//! or the option that overrode it.

use crate::local::local;
use crate::roadmap::{candidate_count, MAX_SAMPLE_CANDIDATES, MIN_SAMPLE_SPACING_M};
use crate::roadmap::{neighbour_pairs, MAX_NEIGHBOUR_PAIRS};
use crate::scenario::Scenario;
use skyroute::geometry::points_bounding_box;
use skyroute::network::write::{
    encode, encode_three_dimensional, grid_cells, NetworkSpec, VerticalSpec, WriteError,
};
use skyroute::Vec2;

/// A refusal: the parameter out of its limit, the network without vertices, or the writer's
/// refusal ([`crate::build::BuildError::Limit`] carries it).
#[derive(Debug)]
pub enum LimitError {
    /// A parameter is out of its limit.
    Invalid {
        /// The scenario file.
        file: String,
        /// The scenario field, or the option that overrode it.
        field: String,
        /// What is wrong, with the value and the limit.
        why: String,
    },
    /// The network would have no vertices: (scenario file, what left none).
    NoVertices(String, String),
    /// The writer refused the network: (scenario file, why).
    Encode(String, WriteError),
}

impl std::fmt::Display for LimitError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            LimitError::Invalid { file, field, why } => write!(f, "{file}: {field}: {why}"),
            LimitError::NoVertices(file, why) => write!(
                f,
                "{file}: the network would have no vertices ({why}), so nothing could be planned \
                 on it"
            ),
            LimitError::Encode(file, e) => write!(f, "{file}: {e}"),
        }
    }
}

impl std::error::Error for LimitError {}

/// The longest side of the box around a scenario's positions in its local frame, metres
/// (the scenarios in `scenarios/` span at most about 100 km).
pub const MAX_AREA_SIDE_M: f64 = 1_000_000.0;

/// `x` as written in a message: in scientific notation when very small or very large.
fn number(x: f64) -> String {
    if x != 0.0 && !(1e-3..1e9).contains(&x.abs()) {
        format!("{x:e}")
    } else {
        format!("{x}")
    }
}

fn invalid(file: &str, field: &str, why: String) -> LimitError {
    LimitError::Invalid {
        file: file.to_string(),
        field: field.to_string(),
        why,
    }
}

/// The box `[lo, hi]` around the scenario's positions is finite and no side is longer than
/// [`MAX_AREA_SIDE_M`].
pub fn check_area(file: &str, lo: Vec2, hi: Vec2) -> Result<(), LimitError> {
    let (w, h) = ((hi.x - lo.x) as f64, (hi.y - lo.y) as f64);
    // NaN fails the comparisons and is refused too.
    if w <= MAX_AREA_SIDE_M && h <= MAX_AREA_SIDE_M {
        return Ok(());
    }
    Err(invalid(
        file,
        "geometry.coordinates",
        format!(
            "the scenario's positions span {:.0} x {:.0} km in its local frame, more than the \
             limit of {:.0} km a side",
            w / 1000.0,
            h / 1000.0,
            MAX_AREA_SIDE_M / 1000.0
        ),
    ))
}

/// Roadmap mode: the sample spacing `spacing_m` (from `field`) is at least
/// [`MIN_SAMPLE_SPACING_M`] and gives at most [`MAX_SAMPLE_CANDIDATES`] candidates over
/// `[lo, hi]`; the neighbour radius is a finite `f32`; together they give at most
/// [`MAX_NEIGHBOUR_PAIRS`] neighbour pairs (estimated by [`neighbour_pairs`]).
pub fn check_sampling(
    file: &str,
    lo: Vec2,
    hi: Vec2,
    (spacing_m, spacing_field): (f64, &str),
    (radius_m, radius_field): (f64, &str),
) -> Result<(), LimitError> {
    if !(spacing_m >= MIN_SAMPLE_SPACING_M && (spacing_m as f32).is_finite()) {
        return Err(invalid(
            file,
            spacing_field,
            format!(
                "{} m: expected at least {MIN_SAMPLE_SPACING_M} m (and finite)",
                number(spacing_m)
            ),
        ));
    }
    let candidates = candidate_count(lo, hi, spacing_m as f32).ceil();
    // NaN is refused too.
    if candidates.is_nan() || candidates > MAX_SAMPLE_CANDIDATES {
        return Err(invalid(
            file,
            spacing_field,
            format!(
                "{} m over the {:.1} x {:.1} km area gives {} sample candidates, more than \
                 the limit of {MAX_SAMPLE_CANDIDATES:.0}",
                number(spacing_m),
                (hi.x - lo.x) / 1000.0,
                (hi.y - lo.y) / 1000.0,
                number(candidates)
            ),
        ));
    }
    if !(radius_m > 0.0 && (radius_m as f32).is_finite()) {
        return Err(invalid(
            file,
            radius_field,
            format!(
                "{} m: expected a positive finite number of metres",
                number(radius_m)
            ),
        ));
    }
    let pairs = neighbour_pairs(lo, hi, spacing_m as f32, radius_m as f32);
    if pairs.is_nan() || pairs > MAX_NEIGHBOUR_PAIRS {
        return Err(invalid(
            file,
            &format!("{spacing_field} and {radius_field}"),
            format!(
                "a spacing of {} m and a neighbour radius of {} m give about {pairs:.3e} \
                 neighbour pairs to examine, more than the limit of {MAX_NEIGHBOUR_PAIRS:.0}",
                number(spacing_m),
                number(radius_m),
            ),
        ));
    }
    Ok(())
}

/// The grid index of side `cell` over `[lo, hi]` grown by `reach` on every side fits the
/// writer's limit (`skyroute::network::write::MAX_GRID_CELLS`); `field` names where the cell
/// came from.
pub fn check_grid(
    file: &str,
    field: &str,
    cell: f32,
    (lo, hi): (Vec2, Vec2),
    reach: f32,
) -> Result<(), LimitError> {
    grid_cells(cell, hi.x - lo.x + 2.0 * reach, hi.y - lo.y + 2.0 * reach)
        .map(|_| ())
        .map_err(|e| grid_error(file, field, e))
}

/// A writer's error, with the grid's refusals naming `field`.
fn grid_error(file: &str, field: &str, e: WriteError) -> LimitError {
    match e {
        WriteError::GridTooLarge(..) | WriteError::BadGridCell(_) => {
            invalid(file, field, format!("{e}; give a larger --grid-cell"))
        }
        e => LimitError::Encode(file.to_string(), e),
    }
}

/// Landmark mode: the box around the landmarks, the start and the goal in the local frame
/// (the grid index covers at least that).
pub fn landmark_box(s: &Scenario) -> (Vec2, Vec2) {
    let frame = s.local_frame();
    let ends = s.start.iter().chain(s.goal.iter()).map(|e| (e.lon, e.lat));
    let sites = s.landmarks.iter().map(|l| (l.lon, l.lat)).chain(ends);
    points_bounding_box(sites.map(|(lon, lat)| local(&frame, lon, lat)))
}

/// Encodes `spec`, three-dimensional with `vertical`, refusing a network with no vertices
/// (`why` says what left none) and naming `grid_field` when the grid index is refused.
pub fn encode_checked(
    spec: &NetworkSpec,
    vertical: Option<&VerticalSpec>,
    file: &str,
    grid_field: &str,
    why: &str,
) -> Result<Vec<u8>, LimitError> {
    if spec.vertices.is_empty() {
        return Err(LimitError::NoVertices(file.to_string(), why.to_string()));
    }
    match vertical {
        Some(v) => encode_three_dimensional(spec, v, None),
        None => encode(spec),
    }
    .map_err(|e| grid_error(file, grid_field, e))
}
