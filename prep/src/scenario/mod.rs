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
//! A roadmap scenario with `planner.altitude_min_m` and `planner.altitude_max_m` is
//! three-dimensional (Niendorf et al.; [`Scenario::vertical`]): its no-fly zones may have a
//! `height_m`, its vehicle a `climb_rate_mps` and a `vertical_accel_mps2`, and each start, goal
//! and waypoint must have an `altitude_m`. In a planar scenario any of these keys is refused by
//! name ([`ErrorKind::Planar`]), never ignored.
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
mod vertical;

pub use error::{ErrorDetail, ErrorKind, FeatureRef, ScenarioError};
pub use types::{
    Circle, Endpoint, Landmark, Mode, NoFly, PlannerParams, Popup, Scenario, Terrain, Vehicle,
    Vertical, DEFAULT_CLIMB_RATE_MPS, DEFAULT_VERTICAL_ACCEL_MPS2, MAX_ALTITUDE_M,
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

/// The scenario format's size limits, checked before the input is read or stored whole. They
/// are far above the shipped scenarios (the largest is 41 kB, 10 vertices a no-fly ring, 4
/// waypoints) and keep a wrong or hostile file from taking unbounded memory or time.
pub mod limits {
    /// The largest scenario file read, bytes (a longer file is refused after reading this
    /// many bytes, so `/dev/zero` fails at once).
    pub const MAX_SCENARIO_BYTES: u64 = 16 << 20;
    /// The most vertices in one no-fly ring.
    pub const MAX_RING_VERTICES: usize = 100_000;
    /// The most holes in one no-fly polygon (each hole adds at least one piece to the obstacles
    /// the core checks, see `zone_pieces`).
    pub const MAX_HOLES: usize = 1_000;
    /// The most waypoints in a scenario: each free-heading waypoint costs `plan` about a
    /// quarter of a second on the urban network, so this is two minutes of planning.
    pub const MAX_WAYPOINTS: usize = 500;
}

/// Reads and checks the scenario at `path`.
pub fn load_with(path: &Path, options: &ParseOptions) -> Result<Scenario, ScenarioError> {
    let text = read_bounded(path)?;
    parse_with(&text, path, options)
}

/// The text of `path`, refused when it is longer than [`limits::MAX_SCENARIO_BYTES`] or not
/// UTF-8.
fn read_bounded(path: &Path) -> Result<String, ScenarioError> {
    use std::io::Read;
    let io = |e: std::io::Error| ScenarioError::new(path, None, "", ErrorKind::Io(e.to_string()));
    let file = std::fs::File::open(path).map_err(io)?;
    let mut bytes = Vec::new();
    file.take(limits::MAX_SCENARIO_BYTES + 1)
        .read_to_end(&mut bytes)
        .map_err(io)?;
    if bytes.len() as u64 > limits::MAX_SCENARIO_BYTES {
        let too_long = ErrorKind::TooMany {
            what: "bytes",
            limit: limits::MAX_SCENARIO_BYTES,
        };
        return Err(ScenarioError::new(path, None, "", too_long));
    }
    String::from_utf8(bytes).map_err(|e| {
        let why = format!("not UTF-8 text (byte {})", e.utf8_error().valid_up_to());
        ScenarioError::new(path, None, "", ErrorKind::Io(why))
    })
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
mod tests_geometry;
#[cfg(test)]
mod tests_holes;
#[cfg(test)]
mod tests_inputs;
#[cfg(test)]
mod tests_vertical;
