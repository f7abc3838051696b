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
//! Checked, beyond presence and type of every member: `kind` and `planner.mode` are known; unknown
//! members of `vehicle`, `planner` and `terrain` are rejected (a misspelt parameter would
//! otherwise be silently ignored); numbers are finite (a Python-written `NaN`/`Infinity` or an
//! overflowing `1e999` is reported at its field, not as a bare JSON error); positions are
//! `[lon, lat]` within ±180/±90; no-fly polygons have one closed ring with at least 3 distinct
//! points and no self-intersection (every pair of edges checked with exact orientation
//! predicates, touching counts); the vehicle's limits are consistent; landmark rosettes have 12
//! values in [0, 1] for exactly the listed weathers; at most one start and one goal; and no
//! start, goal or waypoint lies in (or on the edge of) a no-fly polygon, tested in lon/lat
//! with an exact point-in-polygon test. Start and goal may be absent: the caller decides.
//!
//! Members that the format does not define are ignored at the top level and in `properties`.

use crate::frame::LocalFrame;
use serde_json::{Map, Value};
use std::fmt;
use std::path::{Path, PathBuf};

// ------------------------------------------------------------------------------------------------
// The scenario

/// A parsed and checked scenario.
#[derive(Clone, Debug, PartialEq)]
pub struct Scenario {
    /// The collection's `name` (the file stem when absent).
    pub name: String,
    /// The file it was read from.
    pub path: PathBuf,
    /// The collection's `description` (empty when absent).
    pub description: String,
    /// The aircraft.
    pub vehicle: Vehicle,
    /// The planner's mode and parameters.
    pub planner: PlannerParams,
    /// The environmental conditions the landmark rosettes are given for (landmark mode), in file
    /// order; [`Landmark::quality`] follows this order.
    pub weather: Vec<String>,
    /// The terrain model (terrain mode; always present there).
    pub terrain: Option<Terrain>,
    /// No-fly areas, in file order.
    pub no_fly: Vec<NoFly>,
    /// Landmarks, in file order.
    pub landmarks: Vec<Landmark>,
    /// The start, if the file has one.
    pub start: Option<Endpoint>,
    /// The goal, if the file has one.
    pub goal: Option<Endpoint>,
    /// Intermediate waypoints, in file order.
    pub waypoints: Vec<Endpoint>,
    /// Known threats (circles to avoid or to weigh), in file order.
    pub threats: Vec<Circle>,
    /// Pop-up threats, in file order.
    pub popups: Vec<Popup>,
    /// What [`ParseOptions`] allowed through and repaired (empty with the default options).
    pub warnings: Vec<ScenarioError>,
}

impl Scenario {
    /// Every position in the scenario, `(lon, lat)` degrees: no-fly vertices, landmarks, start,
    /// goal, waypoints, threat and pop-up centres.
    pub fn positions(&self) -> impl Iterator<Item = (f64, f64)> + '_ {
        self.no_fly
            .iter()
            .flat_map(|z| z.ring.iter().copied())
            .chain(self.landmarks.iter().map(|l| (l.lon, l.lat)))
            .chain(self.start.iter().map(|e| (e.lon, e.lat)))
            .chain(self.goal.iter().map(|e| (e.lon, e.lat)))
            .chain(self.waypoints.iter().map(|e| (e.lon, e.lat)))
            .chain(self.threats.iter().map(|c| (c.lon, c.lat)))
            .chain(self.popups.iter().map(|p| (p.lon, p.lat)))
    }

    /// The local frame centred on the bounding box of [`Scenario::positions`] (a parsed scenario
    /// always has at least one feature).
    pub fn local_frame(&self) -> LocalFrame {
        LocalFrame::centred_on(self.positions())
    }
}

/// The aircraft's performance figures.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Vehicle {
    /// Cruise speed, m/s.
    pub v_nominal_mps: f64,
    /// Slowest speed, m/s (> 0, ≤ nominal).
    pub v_min_mps: f64,
    /// Fastest speed, m/s (≥ nominal).
    pub v_max_mps: f64,
    /// Largest lateral acceleration, m/s² (> 0).
    pub a_lat_max_mps2: f64,
    /// Largest deceleration, as a non-positive acceleration, m/s².
    pub a_long_min_mps2: f64,
    /// Largest acceleration, m/s² (≥ 0).
    pub a_long_max_mps2: f64,
    /// Wingspan, m (> 0).
    pub wingspan_m: f64,
}

impl Vehicle {
    /// The smallest turn radius at nominal speed, `v_nominal² / a_lat_max`, metres.
    pub fn turn_radius_m(&self) -> f64 {
        self.v_nominal_mps * self.v_nominal_mps / self.a_lat_max_mps2
    }
}

/// The planner's mode.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Mode {
    /// Sampled Dubins roadmap (Niendorf et al.), `"roadmap"`.
    Roadmap,
    /// Landmark-based navigation network (Babel), `"landmark"`.
    Landmark,
    /// Terrain grid (Medeiros & da Silva), `"terrain"`.
    Terrain,
}

impl Mode {
    /// The name used in the file.
    pub fn as_str(self) -> &'static str {
        match self {
            Mode::Roadmap => "roadmap",
            Mode::Landmark => "landmark",
            Mode::Terrain => "terrain",
        }
    }
}

/// The `planner` member. Every parameter but `mode` is optional: a mode may omit what it does not
/// use. Present values are checked for range (lengths positive, clearance and weight
/// non-negative, counts at least 1).
#[derive(Clone, Debug, PartialEq)]
pub struct PlannerParams {
    /// The mode.
    pub mode: Mode,
    /// Clearance to keep from obstacles, m (≥ 0).
    pub clearance_m: Option<f64>,
    /// Spacing of roadmap samples, m (> 0).
    pub sample_spacing_m: Option<f64>,
    /// Radius within which samples are connected, m (> 0).
    pub neighbour_radius_m: Option<f64>,
    /// Neighbours to try when none lies within the radius.
    pub k_nearest_fallback: Option<u32>,
    /// Whether CCC Dubins words are allowed.
    pub allow_ccc: Option<bool>,
    /// Step of the discretised collision check along arcs, m (> 0).
    pub arc_step_m: Option<f64>,
    /// Number of overflight headings per landmark (≥ 1).
    pub directions: Option<u32>,
    /// Line elements per landmark pair (≥ 1).
    pub line_elements_per_pair: Option<u32>,
    /// Weight of threat exposure against length (≥ 0).
    pub threat_weight: Option<f64>,
    /// Random seed.
    pub seed: Option<u64>,
}

/// The `terrain` member.
#[derive(Clone, Debug, PartialEq)]
pub struct Terrain {
    /// The elevation model, resolved against the scenario file's directory.
    pub dem: PathBuf,
    /// Flight altitude, m.
    pub altitude_m: f64,
    /// Height to keep above the terrain, m (≥ 0).
    pub safety_height_m: f64,
}

/// A no-fly polygon.
#[derive(Clone, Debug, PartialEq)]
pub struct NoFly {
    /// Its name.
    pub name: String,
    /// The ring, `(lon, lat)` degrees, in file order, without the closing duplicate (and without
    /// consecutive duplicates). Simple: at least 3 vertices, no self-intersection.
    pub ring: Vec<(f64, f64)>,
}

/// Number of overflight headings in a landmark rosette: 0°, 30°, … 330°.
pub const ROSETTE_HEADINGS: usize = 12;

/// A landmark.
#[derive(Clone, Debug, PartialEq)]
pub struct Landmark {
    /// Its name.
    pub name: String,
    /// Longitude, degrees.
    pub lon: f64,
    /// Latitude, degrees.
    pub lat: f64,
    /// Largest useful distance, m (> 0).
    pub d_max_m: f64,
    /// For each weather of [`Scenario::weather`], in that order: the quality in [0, 1] for the
    /// overflight headings 0°, 30°, … 330°.
    pub quality: Vec<(String, [f64; ROSETTE_HEADINGS])>,
}

/// A start, goal or waypoint.
#[derive(Clone, Debug, PartialEq)]
pub struct Endpoint {
    /// Its name.
    pub name: String,
    /// Longitude, degrees.
    pub lon: f64,
    /// Latitude, degrees.
    pub lat: f64,
    /// Compass heading (degrees clockwise from true north, finite), `None`: any heading.
    pub heading_deg: Option<f64>,
    /// Landmark mode: the largest distance to the first landmark, m (> 0).
    pub dist_m: Option<f64>,
}

/// A known threat.
#[derive(Clone, Debug, PartialEq)]
pub struct Circle {
    /// Its name.
    pub name: String,
    /// Longitude of the centre, degrees.
    pub lon: f64,
    /// Latitude of the centre, degrees.
    pub lat: f64,
    /// Radius, m (> 0).
    pub radius_m: f64,
}

/// A pop-up threat.
#[derive(Clone, Debug, PartialEq)]
pub struct Popup {
    /// Its name.
    pub name: String,
    /// Longitude of the centre, degrees.
    pub lon: f64,
    /// Latitude of the centre, degrees.
    pub lat: f64,
    /// Radius, m (> 0).
    pub radius_m: f64,
    /// Probability that it appears, in [0, 1].
    pub probability: f64,
}

// ------------------------------------------------------------------------------------------------
// Errors

/// A feature, as errors name it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FeatureRef {
    /// 0-based index in `features`.
    pub index: usize,
    /// Its `properties.name`, when it has one.
    pub name: Option<String>,
}

impl fmt::Display for FeatureRef {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.name {
            Some(n) => write!(f, "feature {} ({n})", self.index),
            None => write!(f, "feature {}", self.index),
        }
    }
}

/// What is wrong.
#[derive(Clone, Debug, PartialEq)]
pub enum ErrorKind {
    /// The file could not be read.
    Io(String),
    /// The text is not JSON.
    Json {
        /// 1-based line.
        line: usize,
        /// 1-based column.
        column: usize,
        /// serde_json's message.
        message: String,
    },
    /// A required member is absent.
    Missing,
    /// A member has the wrong JSON type.
    WrongType {
        /// What was expected.
        expected: &'static str,
        /// What was found.
        found: String,
    },
    /// A number is `NaN`, infinite, or overflows f64 (the token as written).
    NotFinite(String),
    /// A number or count is outside its range.
    OutOfRange {
        /// The value.
        value: f64,
        /// The allowed range, in words.
        expected: &'static str,
    },
    /// A string member has a value that is not one of the allowed ones.
    BadValue {
        /// The value.
        value: String,
        /// The allowed values.
        expected: &'static str,
    },
    /// `properties.kind` is not a known kind.
    UnknownKind(String),
    /// `planner.mode` is not a known mode.
    UnknownMode(String),
    /// A member of `vehicle`, `planner` or `terrain` that the format does not define.
    UnknownMember,
    /// The geometry's type does not suit the feature's kind.
    WrongGeometry {
        /// The type required.
        expected: &'static str,
        /// The type found.
        found: String,
    },
    /// A position is not `[lon, lat]` or `[lon, lat, alt]`.
    BadPosition(usize),
    /// The polygon's ring does not end where it starts.
    RingNotClosed,
    /// The polygon has holes (interior rings), which are not supported.
    Holes(usize),
    /// The polygon's ring has fewer than 3 distinct points.
    TooFewPoints(usize),
    /// Two edges of the polygon's ring meet (0-based edge `i` runs from vertex `i` to `i + 1`).
    SelfIntersecting {
        /// The first edge.
        edge_a: usize,
        /// The second edge.
        edge_b: usize,
        /// Whether they are adjacent edges folding back onto each other.
        overlap: bool,
    },
    /// A landmark rosette does not have 12 values.
    QualityLength(usize),
    /// A landmark rosette value is outside [0, 1].
    QualityOutOfRange(f64),
    /// A landmark has no rosette for a weather listed in the top-level `weather`.
    MissingWeather(String),
    /// A landmark has a rosette for a weather not listed in the top-level `weather`.
    UnlistedWeather(String),
    /// The top-level `weather` lists a name twice.
    DuplicateWeather(String),
    /// The vehicle's limits contradict each other.
    VehicleLimits(String),
    /// A second feature of a kind that may occur once.
    Duplicate {
        /// The kind.
        kind: &'static str,
        /// The first one.
        first: FeatureRef,
    },
    /// A start, goal or waypoint lies inside or on the edge of a no-fly polygon.
    InsideNoFly {
        /// The endpoint's kind.
        kind: &'static str,
        /// The no-fly feature.
        no_fly: FeatureRef,
    },
    /// A self-intersecting no-fly ring was replaced by its convex hull (a warning; see
    /// [`ParseOptions::hull_self_intersecting_no_fly`]).
    ReplacedByHull {
        /// Vertices before.
        before: usize,
        /// Vertices of the hull.
        after: usize,
        /// The intersection that was found.
        edges: (usize, usize),
    },
    /// Something else, in words.
    Invalid(String),
}

impl fmt::Display for ErrorKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ErrorKind::Io(m) => write!(f, "cannot read: {m}"),
            ErrorKind::Json {
                line,
                column,
                message,
            } => write!(f, "line {line} column {column}: invalid JSON: {message}"),
            ErrorKind::Missing => write!(f, "missing"),
            ErrorKind::WrongType { expected, found } => {
                write!(f, "expected {expected}, found {found}")
            }
            ErrorKind::NotFinite(t) => write!(f, "{t} is not a finite number"),
            ErrorKind::OutOfRange { value, expected } => {
                write!(f, "{value} is out of range: expected {expected}")
            }
            ErrorKind::BadValue { value, expected } => {
                write!(f, "{value:?} is not allowed: expected {expected}")
            }
            ErrorKind::UnknownKind(k) => write!(
                f,
                "unknown kind {k:?}: expected one of no_fly, landmark, start, goal, waypoint, \
                 threat, popup"
            ),
            ErrorKind::UnknownMode(m) => write!(
                f,
                "unknown planner mode {m:?}: expected one of roadmap, landmark, terrain"
            ),
            ErrorKind::UnknownMember => write!(f, "unknown member (misspelt?)"),
            ErrorKind::WrongGeometry { expected, found } => {
                write!(f, "expected a {expected} geometry, found {found}")
            }
            ErrorKind::BadPosition(n) => write!(
                f,
                "a position is [longitude, latitude] (optionally with altitude), found {n} values"
            ),
            ErrorKind::RingNotClosed => write!(
                f,
                "polygon ring is not closed (its last position must repeat its first)"
            ),
            ErrorKind::Holes(n) => write!(
                f,
                "polygon has {n} rings: holes are not supported, give one exterior ring"
            ),
            ErrorKind::TooFewPoints(n) => {
                write!(f, "polygon ring has {n} distinct points, fewer than 3")
            }
            ErrorKind::SelfIntersecting {
                edge_a,
                edge_b,
                overlap,
            } => {
                if *overlap {
                    write!(
                        f,
                        "polygon ring is self-intersecting: edges {edge_a} and {edge_b} fold \
                         back onto each other (0-based; edge i joins vertices i and i+1)"
                    )
                } else {
                    write!(
                        f,
                        "polygon ring is self-intersecting: edges {edge_a} and {edge_b} meet \
                         (0-based; edge i joins vertices i and i+1)"
                    )
                }
            }
            ErrorKind::QualityLength(n) => write!(
                f,
                "a rosette has {ROSETTE_HEADINGS} values (headings 0°, 30°, … 330°), found {n}"
            ),
            ErrorKind::QualityOutOfRange(v) => write!(f, "quality {v} is outside [0, 1]"),
            ErrorKind::MissingWeather(w) => write!(
                f,
                "no rosette for weather {w:?}, which the top-level weather lists"
            ),
            ErrorKind::UnlistedWeather(w) => write!(
                f,
                "rosette for weather {w:?}, which the top-level weather does not list"
            ),
            ErrorKind::DuplicateWeather(w) => write!(f, "weather {w:?} is listed twice"),
            ErrorKind::VehicleLimits(m) => write!(f, "{m}"),
            ErrorKind::Duplicate { kind, first } => {
                write!(f, "a second {kind} (the first is {first})")
            }
            ErrorKind::InsideNoFly { kind, no_fly } => {
                write!(f, "the {kind} lies inside no-fly {no_fly}")
            }
            ErrorKind::ReplacedByHull {
                before,
                after,
                edges,
            } => write!(
                f,
                "polygon ring is self-intersecting (edges {} and {} meet); replaced its {before} \
                 vertices by their convex hull of {after}",
                edges.0, edges.1
            ),
            ErrorKind::Invalid(m) => write!(f, "{m}"),
        }
    }
}

/// Why a scenario could not be loaded: the file, the feature, the field and what is wrong
/// ([`ErrorDetail`], reached through `Deref`: `e.field`, `e.kind`). Boxed, so that a `Result`
/// carrying it stays small.
#[derive(Clone, Debug, PartialEq)]
pub struct ScenarioError(Box<ErrorDetail>);

/// The parts of a [`ScenarioError`].
#[derive(Clone, Debug, PartialEq)]
pub struct ErrorDetail {
    /// The scenario file.
    pub file: PathBuf,
    /// The feature, for an error inside `features`.
    pub feature: Option<FeatureRef>,
    /// The member, as a path: `vehicle.v_max_mps`, `geometry.coordinates[0][3]`,
    /// `properties.quality.degraded[4]`; empty for errors about the file as a whole.
    pub field: String,
    /// What is wrong.
    pub kind: ErrorKind,
}

impl ScenarioError {
    /// An error about `field` of `feature` (or of the collection) in `file`.
    pub fn new(
        file: impl Into<PathBuf>,
        feature: Option<FeatureRef>,
        field: impl Into<String>,
        kind: ErrorKind,
    ) -> Self {
        Self(Box::new(ErrorDetail {
            file: file.into(),
            feature,
            field: field.into(),
            kind,
        }))
    }

    /// The parts, by value.
    pub fn into_detail(self) -> ErrorDetail {
        *self.0
    }
}

impl std::ops::Deref for ScenarioError {
    type Target = ErrorDetail;

    fn deref(&self) -> &ErrorDetail {
        &self.0
    }
}

impl fmt::Display for ScenarioError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: ", self.file.display())?;
        if let Some(feature) = &self.feature {
            write!(f, "{feature}: ")?;
        }
        if !self.field.is_empty() {
            write!(f, "{}: ", self.field)?;
        }
        write!(f, "{}", self.kind)
    }
}

impl std::error::Error for ScenarioError {}

// ------------------------------------------------------------------------------------------------
// Entry points

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
    let root = parse_json(text, path)?;
    Parser {
        file: path,
        options,
        warnings: Vec::new(),
    }
    .scenario(&root)
}

// ------------------------------------------------------------------------------------------------
// JSON, with non-finite numbers kept for a better error

/// Marks a string that stood for a non-finite number token in the text.
const NON_FINITE: &str = "\u{0}non-finite:";

fn parse_json(text: &str, path: &Path) -> Result<Value, ScenarioError> {
    match serde_json::from_str::<Value>(text) {
        Ok(v) => Ok(v),
        Err(e) => {
            // JSON has no NaN or infinities; Python writes NaN/Infinity, and 1e999 overflows.
            // Retry with such tokens turned into marked strings so that the field that holds
            // one is named. Any other error is reported as it was first found.
            if let Some(fixed) = mark_non_finite(text) {
                if let Ok(v) = serde_json::from_str::<Value>(&fixed) {
                    return Ok(v);
                }
            }
            let message = e.to_string();
            let suffix = format!(" at line {} column {}", e.line(), e.column());
            let message = message
                .strip_suffix(&suffix)
                .unwrap_or(&message)
                .to_string();
            Err(ScenarioError::new(
                path,
                None,
                "",
                ErrorKind::Json {
                    line: e.line(),
                    column: e.column(),
                    message,
                },
            ))
        }
    }
}

/// `text` with every bare token outside strings that denotes a non-finite number (`NaN`,
/// `Infinity`, `-Infinity`, `inf`, …, or a numeral that overflows f64) replaced by a string
/// `"\u0000non-finite:<token>"`; `None` if there is none.
fn mark_non_finite(text: &str) -> Option<String> {
    let bytes = text.as_bytes();
    let mut out = String::with_capacity(text.len() + 16);
    let mut changed = false;
    let mut i = 0;
    let mut last = 0;
    while i < bytes.len() {
        let b = bytes[i];
        if b == b'"' {
            i += 1;
            while i < bytes.len() && bytes[i] != b'"' {
                i += if bytes[i] == b'\\' { 2 } else { 1 };
            }
            i += 1;
        } else if b.is_ascii_alphanumeric() || b == b'-' || b == b'+' || b == b'.' {
            let start = i;
            while i < bytes.len()
                && (bytes[i].is_ascii_alphanumeric() || matches!(bytes[i], b'-' | b'+' | b'.'))
            {
                i += 1;
            }
            let token = &text[start..i];
            let bare = token.trim_start_matches(['-', '+']).to_ascii_lowercase();
            let non_finite = matches!(bare.as_str(), "nan" | "inf" | "infinity")
                || (token.starts_with(|c: char| c.is_ascii_digit() || c == '-')
                    && token.parse::<f64>().is_ok_and(|v| !v.is_finite()));
            if non_finite {
                out.push_str(&text[last..start]);
                out.push_str("\"\\u0000non-finite:");
                out.push_str(token);
                out.push('"');
                last = i;
                changed = true;
            }
        } else {
            i += 1;
        }
    }
    if !changed {
        return None;
    }
    out.push_str(&text[last.min(text.len())..]);
    Some(out)
}

/// How a JSON value is named in errors.
fn describe(v: &Value) -> String {
    match v {
        Value::Null => "null".into(),
        Value::Bool(b) => format!("the boolean {b}"),
        Value::Number(n) => format!("the number {n}"),
        Value::String(s) => match s.strip_prefix(NON_FINITE) {
            Some(t) => format!("the non-finite number {t}"),
            None => format!("the string {s:?}"),
        },
        Value::Array(a) => format!("an array of {}", a.len()),
        Value::Object(_) => "an object".into(),
    }
}

// ------------------------------------------------------------------------------------------------
// The parser

struct Parser<'a> {
    file: &'a Path,
    options: &'a ParseOptions,
    warnings: Vec<ScenarioError>,
}

/// Where an error is: the feature, if any.
#[derive(Clone)]
struct At {
    feature: Option<FeatureRef>,
}

const TOP: At = At { feature: None };

type R<T> = Result<T, ScenarioError>;

/// The kinds of point features that may not lie in a no-fly area, with their positions in the
/// feature list.
struct Placed {
    kind: &'static str,
    at: FeatureRef,
    lon: f64,
    lat: f64,
}

const VEHICLE_KEYS: &[&str] = &[
    "v_nominal_mps",
    "v_min_mps",
    "v_max_mps",
    "a_lat_max_mps2",
    "a_long_min_mps2",
    "a_long_max_mps2",
    "wingspan_m",
];
const PLANNER_KEYS: &[&str] = &[
    "mode",
    "clearance_m",
    "sample_spacing_m",
    "neighbour_radius_m",
    "k_nearest_fallback",
    "allow_ccc",
    "arc_step_m",
    "directions",
    "line_elements_per_pair",
    "threat_weight",
    "seed",
];
const TERRAIN_KEYS: &[&str] = &["dem", "altitude_m", "safety_height_m"];

impl Parser<'_> {
    fn err(&self, at: &At, field: impl Into<String>, kind: ErrorKind) -> ScenarioError {
        ScenarioError::new(self.file, at.feature.clone(), field, kind)
    }

    // --- typed access ------------------------------------------------------------------------

    fn object<'v>(&self, at: &At, v: &'v Value, field: &str) -> R<&'v Map<String, Value>> {
        v.as_object().ok_or_else(|| {
            self.err(
                at,
                field,
                ErrorKind::WrongType {
                    expected: "an object",
                    found: describe(v),
                },
            )
        })
    }

    /// A required member (null counts as present, and is then of the wrong type).
    fn req<'v>(
        &self,
        at: &At,
        obj: &'v Map<String, Value>,
        key: &str,
        field: &str,
    ) -> R<&'v Value> {
        obj.get(key)
            .ok_or_else(|| self.err(at, field, ErrorKind::Missing))
    }

    /// An optional member (null counts as absent).
    fn opt<'v>(obj: &'v Map<String, Value>, key: &str) -> Option<&'v Value> {
        obj.get(key).filter(|v| !v.is_null())
    }

    fn number(&self, at: &At, v: &Value, field: &str) -> R<f64> {
        match v {
            Value::Number(n) => match n.as_f64() {
                Some(x) if x.is_finite() => Ok(x),
                _ => Err(self.err(at, field, ErrorKind::NotFinite(n.to_string()))),
            },
            Value::String(s) if s.starts_with(NON_FINITE) => Err(self.err(
                at,
                field,
                ErrorKind::NotFinite(s[NON_FINITE.len()..].to_string()),
            )),
            _ => Err(self.err(
                at,
                field,
                ErrorKind::WrongType {
                    expected: "a number",
                    found: describe(v),
                },
            )),
        }
    }

    fn string<'v>(&self, at: &At, v: &'v Value, field: &str) -> R<&'v str> {
        match v {
            Value::String(s) if !s.starts_with(NON_FINITE) => Ok(s),
            _ => Err(self.err(
                at,
                field,
                ErrorKind::WrongType {
                    expected: "a string",
                    found: describe(v),
                },
            )),
        }
    }

    fn integer(&self, at: &At, v: &Value, field: &str, max: u64) -> R<u64> {
        let x = self
            .number(at, v, field)
            .map_err(|e| match e.into_detail().kind {
                ErrorKind::WrongType { found, .. } => self.err(
                    at,
                    field,
                    ErrorKind::WrongType {
                        expected: "a non-negative integer",
                        found,
                    },
                ),
                kind => self.err(at, field, kind),
            })?;
        if let Some(u) = v.as_u64() {
            if u <= max {
                return Ok(u);
            }
        } else if x >= 0.0 && x.fract() == 0.0 && x <= max as f64 {
            return Ok(x as u64);
        }
        Err(self.err(
            at,
            field,
            ErrorKind::OutOfRange {
                value: x,
                expected: "a non-negative integer that fits",
            },
        ))
    }

    fn req_number(&self, at: &At, obj: &Map<String, Value>, key: &str, prefix: &str) -> R<f64> {
        let field = format!("{prefix}{key}");
        let v = self.req(at, obj, key, &field)?;
        self.number(at, v, &field)
    }

    fn opt_number(
        &self,
        at: &At,
        obj: &Map<String, Value>,
        key: &str,
        prefix: &str,
    ) -> R<Option<f64>> {
        Self::opt(obj, key)
            .map(|v| self.number(at, v, &format!("{prefix}{key}")))
            .transpose()
    }

    fn range(&self, at: &At, field: &str, value: f64, ok: bool, expected: &'static str) -> R<f64> {
        if ok {
            Ok(value)
        } else {
            Err(self.err(at, field, ErrorKind::OutOfRange { value, expected }))
        }
    }

    fn positive(&self, at: &At, field: &str, v: f64) -> R<f64> {
        self.range(at, field, v, v > 0.0, "a positive number")
    }

    fn non_negative(&self, at: &At, field: &str, v: f64) -> R<f64> {
        self.range(at, field, v, v >= 0.0, "a non-negative number")
    }

    fn no_unknown_members(&self, obj: &Map<String, Value>, known: &[&str], prefix: &str) -> R<()> {
        match obj.keys().find(|k| !known.contains(&k.as_str())) {
            Some(k) => Err(self.err(&TOP, format!("{prefix}{k}"), ErrorKind::UnknownMember)),
            None => Ok(()),
        }
    }

    // --- the collection ----------------------------------------------------------------------

    fn scenario(mut self, root: &Value) -> R<Scenario> {
        let root = self.object(&TOP, root, "(top level)")?;
        let ty = self.req(&TOP, root, "type", "type")?;
        let ty = self.string(&TOP, ty, "type")?;
        if ty != "FeatureCollection" {
            return Err(self.err(
                &TOP,
                "type",
                ErrorKind::BadValue {
                    value: ty.into(),
                    expected: "\"FeatureCollection\"",
                },
            ));
        }
        let name = match Self::opt(root, "name") {
            Some(v) => self.string(&TOP, v, "name")?.to_string(),
            None => self
                .file
                .file_stem()
                .map(|s| s.to_string_lossy().into_owned())
                .unwrap_or_default(),
        };
        let description = match Self::opt(root, "description") {
            Some(v) => self.string(&TOP, v, "description")?.to_string(),
            None => String::new(),
        };
        let vehicle = self.vehicle(self.req(&TOP, root, "vehicle", "vehicle")?)?;
        let planner = self.planner(self.req(&TOP, root, "planner", "planner")?)?;
        let weather = match Self::opt(root, "weather") {
            Some(v) => self.weather(v)?,
            None => Vec::new(),
        };
        let terrain = match Self::opt(root, "terrain") {
            Some(v) => Some(self.terrain(v)?),
            None if planner.mode == Mode::Terrain => {
                return Err(self.err(
                    &TOP,
                    "terrain",
                    ErrorKind::Invalid("missing: required in terrain mode".into()),
                ))
            }
            None => None,
        };

        let features = self.req(&TOP, root, "features", "features")?;
        let features = features.as_array().ok_or_else(|| {
            self.err(
                &TOP,
                "features",
                ErrorKind::WrongType {
                    expected: "an array",
                    found: describe(features),
                },
            )
        })?;
        if features.is_empty() {
            return Err(self.err(
                &TOP,
                "features",
                ErrorKind::Invalid("empty: a scenario needs at least one feature".into()),
            ));
        }

        let mut s = Scenario {
            name,
            path: self.file.to_path_buf(),
            description,
            vehicle,
            planner,
            weather,
            terrain,
            no_fly: Vec::new(),
            landmarks: Vec::new(),
            start: None,
            goal: None,
            waypoints: Vec::new(),
            threats: Vec::new(),
            popups: Vec::new(),
            warnings: Vec::new(),
        };
        let mut no_fly_refs: Vec<FeatureRef> = Vec::new();
        let mut placed: Vec<Placed> = Vec::new();
        let (mut start_ref, mut goal_ref) = (None::<FeatureRef>, None::<FeatureRef>);

        for (index, fv) in features.iter().enumerate() {
            let mut at = At {
                feature: Some(FeatureRef { index, name: None }),
            };
            let f = self.object(&at, fv, "")?;
            let props = self.req(&at, f, "properties", "properties")?;
            let props = self.object(&at, props, "properties")?;
            // The name first, so that every later error can carry it.
            let name_v = self.req(&at, props, "name", "properties.name")?;
            let name = self.string(&at, name_v, "properties.name")?.to_string();
            at.feature = Some(FeatureRef {
                index,
                name: Some(name.clone()),
            });
            let me = at.feature.clone().unwrap();
            let ty = self.req(&at, f, "type", "type")?;
            if self.string(&at, ty, "type")? != "Feature" {
                return Err(self.err(
                    &at,
                    "type",
                    ErrorKind::BadValue {
                        value: ty.as_str().unwrap_or_default().into(),
                        expected: "\"Feature\"",
                    },
                ));
            }
            let kind_v = self.req(&at, props, "kind", "properties.kind")?;
            let kind = self.string(&at, kind_v, "properties.kind")?;
            let geometry = self.req(&at, f, "geometry", "geometry")?;
            let geometry = self.object(&at, geometry, "geometry")?;
            match kind {
                "no_fly" => {
                    let ring = self.polygon(&at, geometry)?;
                    s.no_fly.push(NoFly { name, ring });
                    no_fly_refs.push(me);
                }
                "landmark" => {
                    let (lon, lat) = self.point(&at, geometry)?;
                    let d = self.req_number(&at, props, "d_max_m", "properties.")?;
                    let d_max_m = self.positive(&at, "properties.d_max_m", d)?;
                    let quality = self.quality(&at, props, &s.weather)?;
                    s.landmarks.push(Landmark {
                        name,
                        lon,
                        lat,
                        d_max_m,
                        quality,
                    });
                }
                "start" | "goal" | "waypoint" => {
                    let (lon, lat) = self.point(&at, geometry)?;
                    let heading_deg = self.opt_number(&at, props, "heading_deg", "properties.")?;
                    let dist_m = self
                        .opt_number(&at, props, "dist_m", "properties.")?
                        .map(|d| self.positive(&at, "properties.dist_m", d))
                        .transpose()?;
                    let e = Endpoint {
                        name,
                        lon,
                        lat,
                        heading_deg,
                        dist_m,
                    };
                    let kind: &'static str = match kind {
                        "start" => "start",
                        "goal" => "goal",
                        _ => "waypoint",
                    };
                    let slot = match kind {
                        "start" => Some((&mut s.start, &mut start_ref)),
                        "goal" => Some((&mut s.goal, &mut goal_ref)),
                        _ => None,
                    };
                    match slot {
                        Some((_, Some(first))) => {
                            return Err(self.err(
                                &at,
                                "properties.kind",
                                ErrorKind::Duplicate {
                                    kind,
                                    first: first.clone(),
                                },
                            ))
                        }
                        Some((endpoint, first)) => {
                            *endpoint = Some(e);
                            *first = Some(me.clone());
                        }
                        None => s.waypoints.push(e),
                    }
                    placed.push(Placed {
                        kind,
                        at: me,
                        lon,
                        lat,
                    });
                }
                "threat" => {
                    let (lon, lat) = self.point(&at, geometry)?;
                    let r = self.req_number(&at, props, "radius_m", "properties.")?;
                    let radius_m = self.positive(&at, "properties.radius_m", r)?;
                    s.threats.push(Circle {
                        name,
                        lon,
                        lat,
                        radius_m,
                    });
                }
                "popup" => {
                    let (lon, lat) = self.point(&at, geometry)?;
                    let r = self.req_number(&at, props, "radius_m", "properties.")?;
                    let radius_m = self.positive(&at, "properties.radius_m", r)?;
                    let p = self.req_number(&at, props, "probability", "properties.")?;
                    let probability = self.range(
                        &at,
                        "properties.probability",
                        p,
                        (0.0..=1.0).contains(&p),
                        "a probability in [0, 1]",
                    )?;
                    s.popups.push(Popup {
                        name,
                        lon,
                        lat,
                        radius_m,
                        probability,
                    });
                }
                other => {
                    return Err(self.err(
                        &at,
                        "properties.kind",
                        ErrorKind::UnknownKind(other.into()),
                    ))
                }
            }
        }

        // Endpoints must be flyable: not inside, nor on the edge of, any no-fly polygon.
        for p in &placed {
            for (zone, zref) in s.no_fly.iter().zip(&no_fly_refs) {
                if point_in_ring((p.lon, p.lat), &zone.ring) {
                    return Err(self.err(
                        &At {
                            feature: Some(p.at.clone()),
                        },
                        "geometry.coordinates",
                        ErrorKind::InsideNoFly {
                            kind: p.kind,
                            no_fly: zref.clone(),
                        },
                    ));
                }
            }
        }
        s.warnings = std::mem::take(&mut self.warnings);
        Ok(s)
    }

    fn vehicle(&self, v: &Value) -> R<Vehicle> {
        let o = self.object(&TOP, v, "vehicle")?;
        self.no_unknown_members(o, VEHICLE_KEYS, "vehicle.")?;
        let p = "vehicle.";
        let n = |k: &str| self.req_number(&TOP, o, k, p);
        let veh = Vehicle {
            v_nominal_mps: n("v_nominal_mps")?,
            v_min_mps: n("v_min_mps")?,
            v_max_mps: n("v_max_mps")?,
            a_lat_max_mps2: n("a_lat_max_mps2")?,
            a_long_min_mps2: n("a_long_min_mps2")?,
            a_long_max_mps2: n("a_long_max_mps2")?,
            wingspan_m: n("wingspan_m")?,
        };
        let bad = |field: &str, m: String| Err(self.err(&TOP, field, ErrorKind::VehicleLimits(m)));
        if veh.v_min_mps <= 0.0 {
            return bad(
                "vehicle.v_min_mps",
                format!(
                    "{} is not positive: a fixed-wing aircraft cannot hover",
                    veh.v_min_mps
                ),
            );
        }
        if veh.v_min_mps > veh.v_nominal_mps {
            return bad(
                "vehicle.v_min_mps",
                format!(
                    "{} exceeds v_nominal_mps {} (need v_min ≤ v_nominal ≤ v_max)",
                    veh.v_min_mps, veh.v_nominal_mps
                ),
            );
        }
        if veh.v_max_mps < veh.v_nominal_mps {
            return bad(
                "vehicle.v_max_mps",
                format!(
                    "{} is below v_nominal_mps {} (need v_min ≤ v_nominal ≤ v_max)",
                    veh.v_max_mps, veh.v_nominal_mps
                ),
            );
        }
        if veh.a_lat_max_mps2 <= 0.0 {
            return bad(
                "vehicle.a_lat_max_mps2",
                format!(
                    "{} is not positive: the aircraft could not turn",
                    veh.a_lat_max_mps2
                ),
            );
        }
        if veh.a_long_min_mps2 > 0.0 {
            return bad(
                "vehicle.a_long_min_mps2",
                format!(
                    "{} is positive: the deceleration limit must be ≤ 0",
                    veh.a_long_min_mps2
                ),
            );
        }
        if veh.a_long_max_mps2 < 0.0 {
            return bad(
                "vehicle.a_long_max_mps2",
                format!(
                    "{} is negative: the acceleration limit must be ≥ 0",
                    veh.a_long_max_mps2
                ),
            );
        }
        if veh.wingspan_m <= 0.0 {
            return bad(
                "vehicle.wingspan_m",
                format!("{} is not positive", veh.wingspan_m),
            );
        }
        Ok(veh)
    }

    fn planner(&self, v: &Value) -> R<PlannerParams> {
        let o = self.object(&TOP, v, "planner")?;
        let mode_v = self.req(&TOP, o, "mode", "planner.mode")?;
        let mode = match self.string(&TOP, mode_v, "planner.mode")? {
            "roadmap" => Mode::Roadmap,
            "landmark" => Mode::Landmark,
            "terrain" => Mode::Terrain,
            other => {
                return Err(self.err(&TOP, "planner.mode", ErrorKind::UnknownMode(other.into())))
            }
        };
        self.no_unknown_members(o, PLANNER_KEYS, "planner.")?;
        let p = "planner.";
        let num = |k: &str| self.opt_number(&TOP, o, k, p);
        let pos = |k: &str| -> R<Option<f64>> {
            num(k)?
                .map(|x| self.positive(&TOP, &format!("{p}{k}"), x))
                .transpose()
        };
        let nonneg = |k: &str| -> R<Option<f64>> {
            num(k)?
                .map(|x| self.non_negative(&TOP, &format!("{p}{k}"), x))
                .transpose()
        };
        let int = |k: &str, min: u64, max: u64| -> R<Option<u64>> {
            let field = format!("{p}{k}");
            match Self::opt(o, k) {
                None => Ok(None),
                Some(v) => {
                    let n = self.integer(&TOP, v, &field, max)?;
                    if n < min {
                        Err(self.err(
                            &TOP,
                            field,
                            ErrorKind::OutOfRange {
                                value: n as f64,
                                expected: "at least 1",
                            },
                        ))
                    } else {
                        Ok(Some(n))
                    }
                }
            }
        };
        let allow_ccc = match Self::opt(o, "allow_ccc") {
            None => None,
            Some(Value::Bool(b)) => Some(*b),
            Some(v) => {
                return Err(self.err(
                    &TOP,
                    "planner.allow_ccc",
                    ErrorKind::WrongType {
                        expected: "a boolean",
                        found: describe(v),
                    },
                ))
            }
        };
        let u32max = u32::MAX as u64;
        Ok(PlannerParams {
            mode,
            clearance_m: nonneg("clearance_m")?,
            sample_spacing_m: pos("sample_spacing_m")?,
            neighbour_radius_m: pos("neighbour_radius_m")?,
            k_nearest_fallback: int("k_nearest_fallback", 0, u32max)?.map(|n| n as u32),
            allow_ccc,
            arc_step_m: pos("arc_step_m")?,
            directions: int("directions", 1, u32max)?.map(|n| n as u32),
            line_elements_per_pair: int("line_elements_per_pair", 1, u32max)?.map(|n| n as u32),
            threat_weight: nonneg("threat_weight")?,
            seed: int("seed", 0, u64::MAX)?,
        })
    }

    fn weather(&self, v: &Value) -> R<Vec<String>> {
        let a = v.as_array().ok_or_else(|| {
            self.err(
                &TOP,
                "weather",
                ErrorKind::WrongType {
                    expected: "an array of strings",
                    found: describe(v),
                },
            )
        })?;
        let mut out: Vec<String> = Vec::with_capacity(a.len());
        for (i, w) in a.iter().enumerate() {
            let field = format!("weather[{i}]");
            let w = self.string(&TOP, w, &field)?;
            if w.is_empty() {
                return Err(self.err(&TOP, field, ErrorKind::Invalid("empty name".into())));
            }
            if out.iter().any(|o| o == w) {
                return Err(self.err(&TOP, field, ErrorKind::DuplicateWeather(w.into())));
            }
            out.push(w.into());
        }
        Ok(out)
    }

    fn terrain(&self, v: &Value) -> R<Terrain> {
        let o = self.object(&TOP, v, "terrain")?;
        self.no_unknown_members(o, TERRAIN_KEYS, "terrain.")?;
        let dem_v = self.req(&TOP, o, "dem", "terrain.dem")?;
        let dem = self.string(&TOP, dem_v, "terrain.dem")?;
        if dem.is_empty() {
            return Err(self.err(&TOP, "terrain.dem", ErrorKind::Invalid("empty path".into())));
        }
        let base = self.file.parent().unwrap_or(Path::new(""));
        let altitude_m = self.req_number(&TOP, o, "altitude_m", "terrain.")?;
        let h = self.req_number(&TOP, o, "safety_height_m", "terrain.")?;
        let safety_height_m = self.non_negative(&TOP, "terrain.safety_height_m", h)?;
        Ok(Terrain {
            dem: base.join(dem),
            altitude_m,
            safety_height_m,
        })
    }

    // --- geometry ----------------------------------------------------------------------------

    fn geometry_type(&self, at: &At, g: &Map<String, Value>, expected: &'static str) -> R<()> {
        let t = self.req(at, g, "type", "geometry.type")?;
        let t = self.string(at, t, "geometry.type")?;
        if t != expected {
            return Err(self.err(
                at,
                "geometry.type",
                ErrorKind::WrongGeometry {
                    expected,
                    found: t.into(),
                },
            ));
        }
        Ok(())
    }

    fn position(&self, at: &At, v: &Value, field: &str) -> R<(f64, f64)> {
        let a = v.as_array().ok_or_else(|| {
            self.err(
                at,
                field,
                ErrorKind::WrongType {
                    expected: "a position [longitude, latitude]",
                    found: describe(v),
                },
            )
        })?;
        if a.len() != 2 && a.len() != 3 {
            return Err(self.err(at, field, ErrorKind::BadPosition(a.len())));
        }
        let lon = self.number(at, &a[0], &format!("{field}[0]"))?;
        let lat = self.number(at, &a[1], &format!("{field}[1]"))?;
        if a.len() == 3 {
            self.number(at, &a[2], &format!("{field}[2]"))?;
        }
        self.range(
            at,
            &format!("{field}[0]"),
            lon,
            (-180.0..=180.0).contains(&lon),
            "a longitude in [-180, 180]",
        )?;
        self.range(
            at,
            &format!("{field}[1]"),
            lat,
            (-90.0..=90.0).contains(&lat),
            "a latitude in [-90, 90]",
        )?;
        Ok((lon, lat))
    }

    fn point(&self, at: &At, g: &Map<String, Value>) -> R<(f64, f64)> {
        self.geometry_type(at, g, "Point")?;
        let c = self.req(at, g, "coordinates", "geometry.coordinates")?;
        self.position(at, c, "geometry.coordinates")
    }

    fn polygon(&mut self, at: &At, g: &Map<String, Value>) -> R<Vec<(f64, f64)>> {
        self.geometry_type(at, g, "Polygon")?;
        let field = "geometry.coordinates";
        let c = self.req(at, g, "coordinates", field)?;
        let rings = c.as_array().ok_or_else(|| {
            self.err(
                at,
                field,
                ErrorKind::WrongType {
                    expected: "an array of rings",
                    found: describe(c),
                },
            )
        })?;
        match rings.len() {
            0 => return Err(self.err(at, field, ErrorKind::TooFewPoints(0))),
            1 => {}
            n => return Err(self.err(at, field, ErrorKind::Holes(n))),
        }
        let ring_field = format!("{field}[0]");
        let ring_v = rings[0].as_array().ok_or_else(|| {
            self.err(
                at,
                &ring_field,
                ErrorKind::WrongType {
                    expected: "an array of positions",
                    found: describe(&rings[0]),
                },
            )
        })?;
        let mut ring = Vec::with_capacity(ring_v.len());
        for (i, p) in ring_v.iter().enumerate() {
            ring.push(self.position(at, p, &format!("{ring_field}[{i}]"))?);
        }
        if ring.is_empty() {
            return Err(self.err(at, field, ErrorKind::TooFewPoints(0)));
        }
        if ring.first() != ring.last() || ring.len() < 2 {
            return Err(self.err(at, field, ErrorKind::RingNotClosed));
        }
        ring.pop();
        // Drop consecutive repeats (including last-to-first): they add no vertex.
        ring.dedup();
        while ring.len() > 1 && ring.first() == ring.last() {
            ring.pop();
        }
        let mut distinct: Vec<(u64, u64)> = ring
            .iter()
            .map(|&(x, y)| ((x + 0.0).to_bits(), (y + 0.0).to_bits()))
            .collect();
        distinct.sort_unstable();
        distinct.dedup();
        if distinct.len() < 3 {
            return Err(self.err(at, field, ErrorKind::TooFewPoints(distinct.len())));
        }
        if let Some((edge_a, edge_b, overlap)) = first_self_intersection(&ring) {
            if !self.options.hull_self_intersecting_no_fly {
                return Err(self.err(
                    at,
                    field,
                    ErrorKind::SelfIntersecting {
                        edge_a,
                        edge_b,
                        overlap,
                    },
                ));
            }
            let hull = convex_hull(&ring);
            if hull.len() < 3 {
                return Err(self.err(
                    at,
                    field,
                    ErrorKind::SelfIntersecting {
                        edge_a,
                        edge_b,
                        overlap,
                    },
                ));
            }
            let warning = self.err(
                at,
                field,
                ErrorKind::ReplacedByHull {
                    before: ring.len(),
                    after: hull.len(),
                    edges: (edge_a, edge_b),
                },
            );
            self.warnings.push(warning);
            return Ok(hull);
        }
        Ok(ring)
    }

    fn quality(
        &self,
        at: &At,
        props: &Map<String, Value>,
        weather: &[String],
    ) -> R<Vec<(String, [f64; ROSETTE_HEADINGS])>> {
        let qv = self.req(at, props, "quality", "properties.quality")?;
        let q = self.object(at, qv, "properties.quality")?;
        if let Some(k) = q.keys().find(|k| !weather.contains(k)) {
            return Err(self.err(
                at,
                format!("properties.quality.{k}"),
                ErrorKind::UnlistedWeather(k.clone()),
            ));
        }
        let mut out = Vec::with_capacity(weather.len());
        for w in weather {
            let field = format!("properties.quality.{w}");
            let v = q.get(w).ok_or_else(|| {
                self.err(
                    at,
                    "properties.quality",
                    ErrorKind::MissingWeather(w.clone()),
                )
            })?;
            let a = v.as_array().ok_or_else(|| {
                self.err(
                    at,
                    &field,
                    ErrorKind::WrongType {
                        expected: "an array of 12 numbers",
                        found: describe(v),
                    },
                )
            })?;
            if a.len() != ROSETTE_HEADINGS {
                return Err(self.err(at, field, ErrorKind::QualityLength(a.len())));
            }
            let mut r = [0.0; ROSETTE_HEADINGS];
            for (i, x) in a.iter().enumerate() {
                let f = format!("{field}[{i}]");
                let x = self.number(at, x, &f)?;
                if !(0.0..=1.0).contains(&x) {
                    return Err(self.err(at, f, ErrorKind::QualityOutOfRange(x)));
                }
                r[i] = x;
            }
            out.push((w.clone(), r));
        }
        Ok(out)
    }
}

// ------------------------------------------------------------------------------------------------
// Exact planar predicates on f64 coordinates (here: degrees of longitude and latitude)

/// `a + b` as `(s, e)` with `s + e == a + b` exactly (Knuth's TwoSum).
fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bb = s - a;
    let e = (a - (s - bb)) + (b - bb);
    (s, e)
}

/// `a · b` as `(p, e)` with `p + e == a · b` exactly (barring underflow), by a fused multiply-add.
fn two_prod(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    (p, a.mul_add(b, -p))
}

/// Adds `b` to the non-overlapping expansion `e` (smallest component first), exactly
/// (Shewchuk's Grow-Expansion).
fn grow(e: &mut Vec<f64>, b: f64) {
    let mut q = b;
    let mut out = Vec::with_capacity(e.len() + 1);
    for &c in e.iter() {
        let (s, h) = two_sum(q, c);
        if h != 0.0 {
            out.push(h);
        }
        q = s;
    }
    if q != 0.0 {
        out.push(q);
    }
    *e = out;
}

/// The exact sign of `Σ sᵢ · (aᵢ − bᵢ) · (cᵢ − dᵢ)` with `sᵢ = ±1`.
fn exact_sign(terms: &[(f64, f64, f64, f64, f64)]) -> i32 {
    let mut e: Vec<f64> = Vec::with_capacity(4 * terms.len() * 2);
    for &(s, a, b, c, d) in terms {
        let (u1, u0) = two_sum(a, -b);
        let (v1, v0) = two_sum(c, -d);
        for x in [u1, u0] {
            for y in [v1, v0] {
                let (p, q) = two_prod(x, y);
                grow(&mut e, s * p);
                grow(&mut e, s * q);
            }
        }
    }
    match e.last() {
        Some(&x) if x > 0.0 => 1,
        Some(&x) if x < 0.0 => -1,
        _ => 0,
    }
}

type P = (f64, f64);

/// Exact sign of the orientation of `(a, b, c)`: +1 counter-clockwise, −1 clockwise, 0 collinear.
fn orient(a: P, b: P, c: P) -> i32 {
    exact_sign(&[(1.0, b.0, a.0, c.1, a.1), (-1.0, b.1, a.1, c.0, a.0)])
}

/// Exact sign of `(u − s) · (w − s)`.
fn dot_sign(s: P, u: P, w: P) -> i32 {
    exact_sign(&[(1.0, u.0, s.0, w.0, s.0), (1.0, u.1, s.1, w.1, s.1)])
}

/// Whether `p`, collinear with `a` and `b`, lies on the closed segment `ab`.
fn within(a: P, b: P, p: P) -> bool {
    a.0.min(b.0) <= p.0 && p.0 <= a.0.max(b.0) && a.1.min(b.1) <= p.1 && p.1 <= a.1.max(b.1)
}

/// Whether the closed segments `ab` and `cd` meet.
fn segments_meet(a: P, b: P, c: P, d: P) -> bool {
    let (o1, o2) = (orient(a, b, c), orient(a, b, d));
    let (o3, o4) = (orient(c, d, a), orient(c, d, b));
    if o1 * o2 < 0 && o3 * o4 < 0 {
        return true;
    }
    (o1 == 0 && within(a, b, c))
        || (o2 == 0 && within(a, b, d))
        || (o3 == 0 && within(c, d, a))
        || (o4 == 0 && within(c, d, b))
}

/// The first pair of edges `(i, j, overlap)` of the closed ring (no repeated consecutive
/// vertices) that meet other than at their shared vertex: non-adjacent edges that touch or
/// cross, or adjacent edges that fold back onto each other (`overlap`).
fn first_self_intersection(ring: &[P]) -> Option<(usize, usize, bool)> {
    let n = ring.len();
    let edge = |i: usize| (ring[i], ring[(i + 1) % n]);
    for i in 0..n {
        for j in i + 1..n {
            let (a, b) = edge(i);
            let (c, d) = edge(j);
            if j == i + 1 || (i == 0 && j == n - 1) {
                // Adjacent: they share one vertex s; they overlap iff the other two ends lie on
                // the same ray from s.
                let (s, u, w) = if j == i + 1 { (b, a, d) } else { (a, b, c) };
                if orient(u, s, w) == 0 && dot_sign(s, u, w) > 0 {
                    return Some((i, j, true));
                }
            } else if segments_meet(a, b, c, d) {
                return Some((i, j, false));
            }
        }
    }
    None
}

/// Whether `p` lies inside or on the boundary of the simple polygon `ring` (exact winding
/// number).
fn point_in_ring(p: P, ring: &[P]) -> bool {
    let n = ring.len();
    let mut winding = 0i32;
    for i in 0..n {
        let (a, b) = (ring[i], ring[(i + 1) % n]);
        let o = orient(a, b, p);
        if o == 0 && within(a, b, p) {
            return true;
        }
        if a.1 <= p.1 {
            if b.1 > p.1 && o > 0 {
                winding += 1;
            }
        } else if b.1 <= p.1 && o < 0 {
            winding -= 1;
        }
    }
    winding != 0
}

/// The convex hull of `points`, counter-clockwise, without collinear vertices (Andrew's
/// monotone chain with the exact orientation test).
fn convex_hull(points: &[P]) -> Vec<P> {
    let mut pts = points.to_vec();
    pts.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
    pts.dedup();
    if pts.len() < 3 {
        return pts;
    }
    let mut hull: Vec<P> = Vec::with_capacity(2 * pts.len());
    for pass in 0..2 {
        let start = hull.len();
        let iter: Box<dyn Iterator<Item = &P>> = if pass == 0 {
            Box::new(pts.iter())
        } else {
            Box::new(pts.iter().rev())
        };
        for &p in iter {
            while hull.len() >= start + 2
                && orient(hull[hull.len() - 2], hull[hull.len() - 1], p) <= 0
            {
                hull.pop();
            }
            hull.push(p);
        }
        hull.pop();
    }
    hull
}

// ------------------------------------------------------------------------------------------------

#[cfg(test)]
mod tests {
    use super::*;

    fn shared(name: &str) -> PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../shared/scenarios")
            .join(name)
    }

    const FILES: [&str; 7] = [
        "babel-I.geojson",
        "babel-II-N.geojson",
        "babel-II-S.geojson",
        "babel-III.geojson",
        "medeiros-jacksboro.geojson",
        "niendorf-urban.geojson",
        "ruz-popups.geojson",
    ];

    #[test]
    fn shared_scenarios_parse() {
        let mut strict_failures = Vec::new();
        for f in FILES {
            let path = shared(f);
            match load(&path) {
                Ok(s) => {
                    assert!(s.warnings.is_empty());
                    assert!(s.start.is_some() && s.goal.is_some(), "{f}");
                }
                Err(e) => strict_failures.push(e),
            }
            // With the hull repair every file loads.
            let s = load_with(
                &path,
                &ParseOptions {
                    hull_self_intersecting_no_fly: true,
                },
            )
            .unwrap_or_else(|e| panic!("{e}"));
            assert!(s.start.is_some() && s.goal.is_some(), "{f}");
            for z in &s.no_fly {
                assert!(z.ring.len() >= 3 && first_self_intersection(&z.ring).is_none());
            }
        }
        // The shared data has one defect, which the strict loader reports: babel-I's Z2 is a
        // bow-tie (its edge 0 crosses its edge 2).
        let msgs: Vec<String> = strict_failures.iter().map(|e| e.to_string()).collect();
        assert_eq!(msgs.len(), 1, "{msgs:#?}");
        assert!(msgs[0].ends_with(
            "babel-I.geojson: feature 1 (Z2): geometry.coordinates: polygon ring is \
             self-intersecting: edges 0 and 2 meet (0-based; edge i joins vertices i and i+1)"
        ));
    }

    #[test]
    fn shared_scenario_contents() {
        let repair = ParseOptions {
            hull_self_intersecting_no_fly: true,
        };
        let s = load_with(&shared("babel-I.geojson"), &repair).unwrap();
        assert_eq!(s.name, "babel-I");
        assert_eq!(s.planner.mode, Mode::Landmark);
        assert_eq!(s.planner.directions, Some(12));
        assert_eq!(s.planner.line_elements_per_pair, Some(500));
        assert_eq!(s.planner.sample_spacing_m, None);
        assert_eq!(s.weather, ["nominal", "degraded"]);
        assert_eq!((s.no_fly.len(), s.landmarks.len()), (3, 10));
        assert_eq!(s.landmarks[0].quality[1].0, "degraded");
        assert_eq!(s.landmarks[0].quality[1].1, [0.5; 12]);
        let start = s.start.as_ref().unwrap();
        assert_eq!(
            (start.name.as_str(), start.heading_deg, start.dist_m),
            ("P", Some(90.0), Some(7000.0))
        );
        assert_eq!(s.no_fly[0].ring.len(), 5);
        assert_eq!(s.warnings.len(), 1);
        assert_eq!(s.vehicle.turn_radius_m(), 45.0);

        let s = load(&shared("niendorf-urban.geojson")).unwrap();
        assert_eq!(s.planner.mode, Mode::Roadmap);
        assert_eq!((s.no_fly.len(), s.waypoints.len()), (60, 4));
        assert_eq!(
            s.waypoints
                .iter()
                .map(|w| w.name.as_str())
                .collect::<Vec<_>>(),
            ["W1", "W2", "W3", "W4"]
        );
        assert!(s.waypoints.iter().all(|w| w.heading_deg.is_none()));
        assert_eq!(s.planner.allow_ccc, Some(true));
        assert_eq!(s.planner.k_nearest_fallback, Some(8));
        assert!((s.vehicle.turn_radius_m() - 63.71).abs() < 0.01);

        let s = load(&shared("medeiros-jacksboro.geojson")).unwrap();
        assert_eq!(s.planner.mode, Mode::Terrain);
        let t = s.terrain.as_ref().unwrap();
        assert_eq!(t.dem, shared("jacksboro-dem.asc"));
        assert!(t.dem.is_file());
        assert_eq!((t.altitude_m, t.safety_height_m), (750.0, 100.0));
        assert_eq!(s.goal.as_ref().unwrap().heading_deg, None);

        let s = load(&shared("ruz-popups.geojson")).unwrap();
        assert_eq!((s.threats.len(), s.popups.len()), (12, 3));
        assert_eq!(
            s.popups.iter().map(|p| p.probability).collect::<Vec<_>>(),
            [0.5, 0.2, 0.8]
        );
        assert_eq!(s.planner.threat_weight, Some(0.5));

        let s = load(&shared("babel-III.geojson")).unwrap();
        assert_eq!((s.no_fly.len(), s.landmarks.len()), (18, 50));
        let frame = s.local_frame();
        let (lat0, lon0) = frame.origin();
        assert!((lat0 - 48.23).abs() < 0.01 && (lon0 - 12.28).abs() < 0.01);
    }

    // --- error classes: each message names the file, the feature and the field --------------

    const FILE: &str = "scenarios/x.geojson";

    fn doc(features: &str) -> String {
        doc_with(
            r#""vehicle": {"v_nominal_mps": 30, "v_min_mps": 25, "v_max_mps": 35,
                "a_lat_max_mps2": 20, "a_long_min_mps2": -3, "a_long_max_mps2": 3,
                "wingspan_m": 4},
               "planner": {"mode": "landmark", "directions": 12, "seed": 1},
               "weather": ["nominal", "degraded"]"#,
            features,
        )
    }

    fn doc_with(top: &str, features: &str) -> String {
        format!(r#"{{"type": "FeatureCollection", "name": "x", {top}, "features": [{features}]}}"#)
    }

    const ZONE: &str = r#"{"type": "Feature", "properties": {"kind": "no_fly", "name": "Z1"},
        "geometry": {"type": "Polygon", "coordinates": [[[11.0, 48.0], [11.1, 48.0],
        [11.1, 48.1], [11.0, 48.1], [11.0, 48.0]]]}}"#;

    fn point(kind: &str, name: &str, lon: f64, lat: f64, extra: &str) -> String {
        format!(
            r#"{{"type": "Feature", "properties": {{"kind": "{kind}", "name": "{name}"{extra}}},
               "geometry": {{"type": "Point", "coordinates": [{lon}, {lat}]}}}}"#
        )
    }

    fn polygon(name: &str, ring: &str) -> String {
        format!(
            r#"{{"type": "Feature", "properties": {{"kind": "no_fly", "name": "{name}"}},
               "geometry": {{"type": "Polygon", "coordinates": [{ring}]}}}}"#
        )
    }

    fn start() -> String {
        point("start", "P", 10.0, 48.0, r#", "heading_deg": 90"#)
    }

    /// Parses `text`, expects an error, and checks its message holds every part.
    fn fails(text: &str, parts: &[&str]) -> ScenarioError {
        let e = parse(text, Path::new(FILE)).expect_err("should not parse");
        let m = e.to_string();
        assert!(m.starts_with(&format!("{FILE}: ")), "{m}");
        for p in parts {
            assert!(m.contains(p), "{m:?} lacks {p:?}");
        }
        e
    }

    #[test]
    fn the_fixture_itself_parses() {
        let s = parse(&doc(&format!("{ZONE}, {}", start())), Path::new(FILE)).unwrap();
        assert_eq!(s.no_fly[0].ring.len(), 4);
        assert_eq!(s.start.unwrap().heading_deg, Some(90.0));
    }

    #[test]
    fn invalid_json_names_line_and_column() {
        let e = fails(
            "{\n  \"type\": \"FeatureCollection\",\n  ]",
            &["line 3 column 3", "invalid JSON"],
        );
        assert!(matches!(
            e.kind,
            ErrorKind::Json {
                line: 3,
                column: 3,
                ..
            }
        ));
        // No duplicated position in the message.
        assert!(!e.to_string().contains(" at line "), "{e}");
    }

    #[test]
    fn missing_member() {
        let f = r#"{"type": "Feature", "properties": {"kind": "threat", "name": "T1"},
                    "geometry": {"type": "Point", "coordinates": [10.5, 48.5]}}"#;
        fails(
            &doc(f),
            &["feature 0 (T1)", "properties.radius_m", "missing"],
        );
        let text = doc(&start()).replace(r#""wingspan_m": 4"#, r#""wingspan": 4"#);
        fails(&text, &["vehicle.wingspan"]);
        let text = doc_with(r#""planner": {"mode": "roadmap"}"#, &start());
        fails(&text, &[": vehicle: missing"]);
        let f = r#"{"type": "Feature", "properties": {"kind": "goal"},
                    "geometry": {"type": "Point", "coordinates": [10.5, 48.5]}}"#;
        fails(&doc(f), &["feature 0: properties.name: missing"]);
    }

    #[test]
    fn ill_typed_member() {
        let f = point("threat", "T1", 10.5, 48.5, r#", "radius_m": "3 km""#);
        fails(
            &doc(&f),
            &[
                "feature 0 (T1)",
                "properties.radius_m",
                "expected a number",
                "\"3 km\"",
            ],
        );
        let f = r#"{"type": "Feature", "properties": {"kind": "goal", "name": "Q"},
                    "geometry": {"type": "Point", "coordinates": "here"}}"#;
        fails(
            &doc(f),
            &[
                "feature 0 (Q)",
                "geometry.coordinates",
                "expected a position",
            ],
        );
        let text = doc(&start()).replace(r#""seed": 1"#, r#""seed": 1.5"#);
        fails(&text, &["planner.seed", "integer"]);
    }

    #[test]
    fn unknown_kind() {
        let f = point("tower", "T9", 10.5, 48.5, "");
        let e = fails(
            &doc(&format!("{}, {f}", start())),
            &[
                "feature 1 (T9)",
                "properties.kind",
                "unknown kind \"tower\"",
            ],
        );
        assert_eq!(e.kind, ErrorKind::UnknownKind("tower".into()));
    }

    #[test]
    fn unknown_planner_mode() {
        let text = doc(&start()).replace(r#""mode": "landmark""#, r#""mode": "rrt""#);
        let e = fails(&text, &["planner.mode", "unknown planner mode \"rrt\""]);
        assert_eq!(e.kind, ErrorKind::UnknownMode("rrt".into()));
    }

    #[test]
    fn polygon_not_closed() {
        let z = polygon(
            "B7",
            "[[11.0, 48.0], [11.1, 48.0], [11.1, 48.1], [11.0, 48.1]]",
        );
        let e = fails(
            &doc(&format!("{}, {z}", start())),
            &["feature 1 (B7)", "geometry.coordinates", "not closed"],
        );
        assert_eq!(e.kind, ErrorKind::RingNotClosed);
        assert_eq!(
            e.to_string(),
            "scenarios/x.geojson: feature 1 (B7): geometry.coordinates: polygon ring is not \
             closed (its last position must repeat its first)"
        );
    }

    #[test]
    fn polygon_with_fewer_than_three_distinct_points() {
        let z = polygon(
            "B2",
            "[[11.0, 48.0], [11.1, 48.0], [11.1, 48.0], [11.0, 48.0], [11.0, 48.0]]",
        );
        let e = fails(
            &doc(&format!("{}, {z}", start())),
            &[
                "feature 1 (B2)",
                "geometry.coordinates",
                "2 distinct points",
            ],
        );
        assert_eq!(e.kind, ErrorKind::TooFewPoints(2));
    }

    #[test]
    fn polygon_self_intersecting() {
        // A bow-tie: edges 0 and 2 cross.
        let z = polygon(
            "B3",
            "[[11.0, 48.0], [11.1, 48.1], [11.1, 48.0], [11.0, 48.1], [11.0, 48.0]]",
        );
        let e = fails(
            &doc(&format!("{}, {z}", start())),
            &[
                "feature 1 (B3)",
                "geometry.coordinates",
                "self-intersecting",
                "edges 0 and 2",
            ],
        );
        assert!(matches!(
            e.kind,
            ErrorKind::SelfIntersecting {
                edge_a: 0,
                edge_b: 2,
                overlap: false
            }
        ));
        // Touching at a vertex counts: the ring passes through (11.05, 48.05) twice.
        let z = polygon(
            "B4",
            "[[11.0, 48.0], [11.05, 48.05], [11.1, 48.0], [11.1, 48.1], [11.05, 48.05], [11.0, 48.1], [11.0, 48.0]]",
        );
        fails(
            &doc(&format!("{}, {z}", start())),
            &["feature 1 (B4)", "self-intersecting"],
        );
        // A spike folding back onto the previous edge.
        let z = polygon(
            "B5",
            "[[11.0, 48.0], [11.2, 48.0], [11.1, 48.0], [11.1, 48.1], [11.0, 48.0]]",
        );
        let e = fails(
            &doc(&format!("{}, {z}", start())),
            &["feature 1 (B5)", "fold back"],
        );
        assert!(matches!(
            e.kind,
            ErrorKind::SelfIntersecting {
                edge_a: 0,
                edge_b: 1,
                overlap: true
            }
        ));
        // Three collinear points enclose nothing.
        let z = polygon(
            "B6",
            "[[11.0, 48.0], [11.1, 48.0], [11.2, 48.0], [11.0, 48.0]]",
        );
        fails(
            &doc(&format!("{}, {z}", start())),
            &["feature 1 (B6)", "self-intersecting"],
        );
        // Decided exactly: a notch whose tip comes within 1e-300 degrees of the opposite edge is
        // simple; touching it, or crossing it by 1e-300, is not.
        for (tip, simple) in [("1e-300", true), ("0.0", false), ("-1e-300", false)] {
            let z = polygon(
                "B8",
                &format!(
                    "[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.5, {tip}], [0.0, 1.0], [0.0, 0.0]]"
                ),
            );
            let r = parse(&doc(&format!("{}, {z}", start())), Path::new(FILE));
            assert_eq!(r.is_ok(), simple, "tip {tip}: {r:?}");
        }
        // The repair option turns the error into a warning and a convex hull.
        let z = polygon(
            "B3",
            "[[11.0, 48.0], [11.1, 48.1], [11.1, 48.0], [11.0, 48.1], [11.0, 48.0]]",
        );
        let s = parse_with(
            &doc(&format!("{}, {z}", start())),
            Path::new(FILE),
            &ParseOptions {
                hull_self_intersecting_no_fly: true,
            },
        )
        .unwrap();
        assert_eq!(
            s.no_fly[0].ring,
            [(11.0, 48.0), (11.1, 48.0), (11.1, 48.1), (11.0, 48.1)]
        );
        let w = s.warnings[0].to_string();
        assert!(
            w.contains("feature 1 (B3): geometry.coordinates: ") && w.contains("convex hull"),
            "{w}"
        );
    }

    #[test]
    fn polygon_with_holes_rejected() {
        let z = polygon(
            "B9",
            "[[11.0, 48.0], [11.1, 48.0], [11.1, 48.1], [11.0, 48.0]], [[11.05, 48.01], [11.06, 48.01], [11.06, 48.02], [11.05, 48.01]]",
        );
        fails(
            &doc(&format!("{}, {z}", start())),
            &["feature 1 (B9)", "geometry.coordinates", "holes"],
        );
    }

    #[test]
    fn heading_not_a_number() {
        let f = point("start", "P", 10.0, 48.0, r#", "heading_deg": "north""#);
        let e = fails(
            &doc(&f),
            &[
                "feature 0 (P)",
                "properties.heading_deg",
                "expected a number",
                "\"north\"",
            ],
        );
        assert!(matches!(e.kind, ErrorKind::WrongType { .. }));
    }

    #[test]
    fn heading_not_finite() {
        for token in ["NaN", "Infinity", "-Infinity", "1e999"] {
            let f = point(
                "goal",
                "Q",
                10.0,
                48.0,
                &format!(r#", "heading_deg": {token}"#),
            );
            let e = fails(
                &doc(&format!("{}, {f}", start())),
                &[
                    "feature 1 (Q)",
                    "properties.heading_deg",
                    "not a finite number",
                ],
            );
            assert_eq!(e.kind, ErrorKind::NotFinite(token.into()));
        }
        // Such a token inside a string is left alone, and when the text has a real syntax error
        // as well, the first error is reported where it was found (here: at the NaN, the first
        // thing serde_json rejects).
        let f = point("goal", "NaN Infinity", 10.0, 48.0, "");
        parse(&doc(&f), Path::new(FILE)).unwrap();
        let text = doc(&point("goal", "Q", 10.0, 48.0, r#", "heading_deg": NaN"#)) + ",";
        let e = fails(&text, &["invalid JSON"]);
        let nan_at = text.find("NaN").unwrap();
        let line = text[..nan_at].matches('\n').count() + 1;
        let column = nan_at - text[..nan_at].rfind('\n').map_or(0, |i| i + 1) + 1;
        assert!(
            matches!(e.kind, ErrorKind::Json { line: l, column: c, .. } if (l, c) == (line, column)),
            "{e}"
        );
        let text = doc(&point("goal", "Q", 10.0, 48.0, r#", "heading_deg": 1"#)) + ",";
        fails(&text, &["invalid JSON", "trailing"]);
    }

    #[test]
    fn quality_wrong_length() {
        let q = r#", "d_max_m": 7000, "quality": {"nominal": [1,1,1,1,1,1,1,1,1,1,1], "degraded": [0.5,0.5,0.5,0.5,0.5,0.5,0.5,0.5,0.5,0.5,0.5,0.5]}"#;
        let f = point("landmark", "L1", 10.5, 48.5, q);
        let e = fails(
            &doc(&f),
            &["feature 0 (L1)", "properties.quality.nominal", "found 11"],
        );
        assert_eq!(e.kind, ErrorKind::QualityLength(11));
    }

    #[test]
    fn quality_out_of_range() {
        let q = r#", "d_max_m": 7000, "quality": {"nominal": [1,1,1,1,1,1,1,1,1,1,1,1], "degraded": [0.5,0.5,0.5,1.5,0.5,0.5,0.5,0.5,0.5,0.5,0.5,0.5]}"#;
        let f = point("landmark", "L2", 10.5, 48.5, q);
        let e = fails(
            &doc(&f),
            &[
                "feature 0 (L2)",
                "properties.quality.degraded[3]",
                "outside [0, 1]",
            ],
        );
        assert_eq!(e.kind, ErrorKind::QualityOutOfRange(1.5));
    }

    #[test]
    fn quality_missing_weather() {
        let q = r#", "d_max_m": 7000, "quality": {"nominal": [1,1,1,1,1,1,1,1,1,1,1,1]}"#;
        let f = point("landmark", "L3", 10.5, 48.5, q);
        let e = fails(
            &doc(&f),
            &[
                "feature 0 (L3)",
                "properties.quality",
                "no rosette for weather \"degraded\"",
            ],
        );
        assert_eq!(e.kind, ErrorKind::MissingWeather("degraded".into()));
        // And one the top level does not list.
        let q = r#", "d_max_m": 7000, "quality": {"nominal": [1,1,1,1,1,1,1,1,1,1,1,1], "degraded": [1,1,1,1,1,1,1,1,1,1,1,1], "fog": [1,1,1,1,1,1,1,1,1,1,1,1]}"#;
        let f = point("landmark", "L4", 10.5, 48.5, q);
        fails(
            &doc(&f),
            &["feature 0 (L4)", "properties.quality.fog", "does not list"],
        );
    }

    #[test]
    fn vehicle_limits_contradict() {
        let base = doc(&start());
        let cases = [
            (
                r#""v_min_mps": 25"#,
                r#""v_min_mps": 31"#,
                "vehicle.v_min_mps",
                "exceeds v_nominal_mps",
            ),
            (
                r#""v_max_mps": 35"#,
                r#""v_max_mps": 29"#,
                "vehicle.v_max_mps",
                "below v_nominal_mps",
            ),
            (
                r#""v_min_mps": 25"#,
                r#""v_min_mps": 0"#,
                "vehicle.v_min_mps",
                "not positive",
            ),
            (
                r#""a_lat_max_mps2": 20"#,
                r#""a_lat_max_mps2": 0"#,
                "vehicle.a_lat_max_mps2",
                "not positive",
            ),
            (
                r#""a_long_min_mps2": -3"#,
                r#""a_long_min_mps2": 1"#,
                "vehicle.a_long_min_mps2",
                "must be ≤ 0",
            ),
            (
                r#""a_long_max_mps2": 3"#,
                r#""a_long_max_mps2": -1"#,
                "vehicle.a_long_max_mps2",
                "must be ≥ 0",
            ),
            (
                r#""wingspan_m": 4"#,
                r#""wingspan_m": -4"#,
                "vehicle.wingspan_m",
                "not positive",
            ),
        ];
        for (from, to, field, words) in cases {
            assert!(base.contains(from));
            let e = fails(
                &base.replace(from, to),
                &[&format!("{FILE}: {field}: "), words],
            );
            assert!(matches!(e.kind, ErrorKind::VehicleLimits(_)));
            assert_eq!(e.feature, None);
        }
    }

    #[test]
    fn coordinates_out_of_range() {
        let f = point("waypoint", "W1", 190.0, 48.0, "");
        let e = fails(
            &doc(&format!("{}, {f}", start())),
            &[
                "feature 1 (W1)",
                "geometry.coordinates[0]",
                "190",
                "longitude",
            ],
        );
        assert!(matches!(e.kind, ErrorKind::OutOfRange { .. }));
        let f = point("waypoint", "W2", 10.0, -91.0, "");
        fails(
            &doc(&format!("{}, {f}", start())),
            &["feature 1 (W2)", "geometry.coordinates[1]", "latitude"],
        );
        let z = polygon(
            "B1",
            "[[11.0, 48.0], [11.1, 48.0], [11.1, 98.1], [11.0, 48.0]]",
        );
        fails(
            &doc(&format!("{}, {z}", start())),
            &[
                "feature 1 (B1)",
                "geometry.coordinates[0][2][1]",
                "latitude",
            ],
        );
    }

    #[test]
    fn endpoint_inside_no_fly() {
        let w = point("waypoint", "W3", 11.05, 48.05, "");
        let e = fails(
            &doc(&format!("{ZONE}, {}, {w}", start())),
            &[
                "feature 2 (W3)",
                "geometry.coordinates",
                "waypoint lies inside no-fly feature 0 (Z1)",
            ],
        );
        assert!(matches!(
            e.kind,
            ErrorKind::InsideNoFly {
                kind: "waypoint",
                ..
            }
        ));
        // On the edge counts as inside; the goal names both features too.
        let g = point("goal", "Q", 11.1, 48.05, "");
        fails(
            &doc(&format!("{ZONE}, {}, {g}", start())),
            &["feature 2 (Q)", "goal lies inside no-fly feature 0 (Z1)"],
        );
        let p = point("start", "P", 11.02, 48.09, "");
        fails(
            &doc(&format!("{ZONE}, {p}")),
            &["feature 1 (P)", "start lies inside no-fly feature 0 (Z1)"],
        );
        // Just outside (1e-7 degrees, about 1 cm) is fine.
        let g = point("goal", "Q", 11.1000001, 48.05, "");
        parse(&doc(&format!("{ZONE}, {}, {g}", start())), Path::new(FILE)).unwrap();
    }

    #[test]
    fn duplicate_start() {
        let p2 = point("start", "P2", 10.1, 48.0, "");
        fails(
            &doc(&format!("{}, {p2}", start())),
            &[
                "feature 1 (P2)",
                "properties.kind",
                "a second start (the first is feature 0 (P))",
            ],
        );
    }

    #[test]
    fn missing_start_and_goal_are_allowed() {
        let s = parse(&doc(ZONE), Path::new(FILE)).unwrap();
        assert!(s.start.is_none() && s.goal.is_none());
    }

    #[test]
    fn terrain_mode_needs_terrain_and_resolves_the_dem() {
        let veh = r#""vehicle": {"v_nominal_mps": 30, "v_min_mps": 25, "v_max_mps": 35,
                "a_lat_max_mps2": 20, "a_long_min_mps2": -3, "a_long_max_mps2": 3,
                "wingspan_m": 4}"#;
        let text = doc_with(
            &format!(r#"{veh}, "planner": {{"mode": "terrain"}}"#),
            &start(),
        );
        fails(&text, &["terrain: missing"]);
        let text = doc_with(
            &format!(
                r#"{veh}, "planner": {{"mode": "terrain"}},
                   "terrain": {{"dem": "d.asc", "altitude_m": 750, "safety_height_m": 100}}"#
            ),
            &start(),
        );
        let s = parse(&text, Path::new(FILE)).unwrap();
        assert_eq!(s.terrain.unwrap().dem, Path::new("scenarios/d.asc"));
    }

    #[test]
    fn exact_predicates() {
        // Collinear in exact arithmetic although naive f64 evaluation says otherwise.
        let a = (0.1, 0.1);
        let b = (0.2, 0.2);
        let c = (0.30000000000000004, 0.30000000000000004);
        assert_eq!(orient(a, b, c), 0);
        assert_eq!(orient((0.0, 0.0), (1.0, 0.0), (0.5, 1e-300)), 1);
        assert_eq!(orient((0.0, 0.0), (1.0, 0.0), (0.5, -1e-300)), -1);
        // Points that f64 rounding makes look collinear.
        let p = (0.5, 0.5);
        let q = (12.0, 12.0);
        let r = (24.0 + f64::EPSILON * 16.0, 24.0);
        assert_eq!(orient(p, q, r), -1);
        // Point in ring, exactly: one ulp east of the edge x = 11.1 is outside, on it inside.
        let ring = [(11.0, 48.0), (11.1, 48.0), (11.1, 48.1), (11.0, 48.1)];
        assert!(point_in_ring((11.1, 48.05), &ring));
        assert!(point_in_ring((11.099999999999998, 48.05), &ring));
        assert!(!point_in_ring((11.100000000000001, 48.05), &ring));
        assert!(point_in_ring((11.0, 48.0), &ring));
        assert!(!point_in_ring((10.9, 48.05), &ring));
        assert_eq!(
            convex_hull(&[(0.0, 0.0), (1.0, 1.0), (1.0, 0.0), (0.0, 1.0), (0.5, 0.5)]).len(),
            4
        );
    }
}
