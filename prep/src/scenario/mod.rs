//! Mission scenarios: the GeoJSON files described in `scenarios/README.md`, parsed and checked
//! into typed structs.
//!
//! [`load`] reads a file, [`parse`] takes its text. Everything the format says is checked, and an
//! error names the file, the feature (its 0-based index in `features` and its `name` when it has
//! one) and the field, e.g.
//!
//! ```text
//! scenarios/x.geojson: feature 12 (B7): geometry.coordinates: polygon ring is not closed (...)
//! scenarios/x.geojson: vehicle.v_max_mps: 20 is below v_nominal_mps 25
//! scenarios/x.geojson: line 7 column 3: invalid JSON: trailing comma
//! ```
//!
//! Checked, beyond presence and type of every member: no object has a key twice (JSON parsers
//! differ on which one wins); `kind` and `planner.mode` are known; unknown members of `vehicle`,
//! `planner` and `terrain`, and `properties` keys that the feature's kind does not define, are
//! rejected (a misspelt parameter would otherwise be silently ignored); numbers are finite (a Python-written `NaN`/`Infinity` or an
//! overflowing `1e999` is reported at its field, not as a bare JSON error); positions are
//! `[lon, lat]` within ±180/±90; no-fly polygons have one closed ring with at least 3 distinct
//! points and no self-intersection (every pair of edges checked with exact orientation
//! predicates, touching counts); the vehicle's limits are consistent; landmark rosettes have 12
//! values in [0, 1] for exactly the listed weathers; at most one start and one goal; and no
//! start, goal or waypoint lies in (or on the edge of) a no-fly polygon, tested in lon/lat
//! with an exact point-in-polygon test. Start and goal may be absent: the caller decides; a start
//! that is present has a `heading_deg` in every mode (no mode can take a free start heading).
//!
//! Members that the format does not define are ignored at the top level (GeoJSON allows foreign
//! members there) and in a feature outside `properties`. A UTF-8 byte-order mark at the start
//! of the text is skipped.

mod error;
mod features;
mod geometry;
mod json;
mod parser;
mod sections;
mod types;

pub use error::{ErrorDetail, ErrorKind, FeatureRef, ScenarioError};
pub use types::{
    Circle, Endpoint, Landmark, Mode, NoFly, PlannerParams, Popup, Scenario, Terrain, Vehicle,
    ROSETTE_HEADINGS,
};

use json::parse_json;
use parser::Parser;
use std::path::Path;

/// Options for [`load_with`] and [`parse_with`]. The default is strict.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ParseOptions {
    /// Replace a self-intersecting no-fly ring by the convex hull of its vertices instead of
    /// rejecting it, and record a [`ErrorKind::ReplacedByHull`] warning in
    /// [`Scenario::warnings`]. The hull contains the whole of the original area, so the repaired
    /// scenario forbids everything the original did, and possibly more.
    pub hull_self_intersecting_no_fly: bool,
}

/// Reads and checks the scenario at `path` (strict: [`ParseOptions::default`]).
pub fn load(path: &Path) -> Result<Scenario, ScenarioError> {
    load_with(path, &ParseOptions::default())
}

/// Reads and checks the scenario at `path`.
pub fn load_with(path: &Path, options: &ParseOptions) -> Result<Scenario, ScenarioError> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| ScenarioError::new(path, None, "", ErrorKind::Io(e.to_string())))?;
    parse_with(&text, path, options)
}

/// Reads and checks the scenario at `path`, taken as `mode` instead of its `planner.mode`
/// when given (the command line's `--mode`: e.g. a roadmap scenario with threats built as a
/// Voronoi network).
pub fn load_in_mode(
    path: &Path,
    options: &ParseOptions,
    mode: Option<Mode>,
) -> Result<Scenario, ScenarioError> {
    let mut s = load_with(path, options)?;
    if let Some(m) = mode {
        s.planner.mode = m;
    }
    Ok(s)
}

/// Checks the scenario text `text`, read from `path` (used in errors and to resolve
/// `terrain.dem`; not read).
pub fn parse(text: &str, path: &Path) -> Result<Scenario, ScenarioError> {
    parse_with(text, path, &ParseOptions::default())
}

/// Checks the scenario text `text`, read from `path`.
pub fn parse_with(
    text: &str,
    path: &Path,
    options: &ParseOptions,
) -> Result<Scenario, ScenarioError> {
    // A UTF-8 byte-order mark (which some Windows editors write) is not JSON, and serde_json
    // would report it as "expected value" at line 1 column 1: one at the very start is skipped.
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let root = parse_json(text, path)?;
    Parser {
        file: path,
        hull_self_intersecting_no_fly: options.hull_self_intersecting_no_fly,
        warnings: Vec::new(),
    }
    .scenario(&root)
}

#[cfg(test)]
mod tests;
#[cfg(test)]
mod tests_inputs;
