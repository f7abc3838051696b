//! Scenario errors: the file, the feature, the field and what is wrong.

use std::fmt;
use std::path::PathBuf;

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

/// `x` as messages print it: plainly (`29.5`, `-3`), but in exponent form (`1e308`,
/// `-2.5e-12`) when it is at least 1e9 or below 1e-6 in size, where the plain form would run to
/// hundreds of digits (`1e308` has 309).
pub(crate) fn compact(x: f64) -> String {
    let a = x.abs();
    if a.is_finite() && a != 0.0 && !(1e-6..1e9).contains(&a) {
        format!("{x:e}")
    } else {
        format!("{x}")
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
    /// A key of a feature's `properties` that its kind does not define; the keys it does.
    UnknownKey(&'static [&'static str]),
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
    /// A hole is not strictly inside its polygon's exterior ring: it crosses or touches the
    /// ring, or lies outside it.
    HoleOutside,
    /// This hole meets the polygon's hole of this index (counting the exterior as 0): their
    /// rings touch or cross, or one lies inside the other.
    HolesMeet(usize),
    /// The polygon's ring has fewer than 3 distinct points.
    TooFewPoints(usize),
    /// More of something than the scenario format's limit allows (see [`super::limits`]).
    TooMany {
        /// What is counted ("bytes", "ring vertices", "waypoints").
        what: &'static str,
        /// The limit.
        limit: u64,
    },
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
    /// A key of the three-dimensional roadmap (a height, an altitude, a vertical limit) in a
    /// planar scenario, one without `planner.altitude_min_m` and `planner.altitude_max_m`.
    Planar,
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
                write!(
                    f,
                    "{} is out of range: expected {expected}",
                    compact(*value)
                )
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
                "unknown planner mode {m:?}: expected one of roadmap, landmark, terrain, voronoi"
            ),
            ErrorKind::UnknownMember => write!(f, "unknown member (misspelt?)"),
            ErrorKind::UnknownKey(known) => {
                write!(f, "unknown key; expected one of {}", known.join(", "))
            }
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
            ErrorKind::HoleOutside => write!(
                f,
                "this hole is not strictly inside the polygon's exterior ring (ring 0): it \
                 touches or crosses it, or lies outside"
            ),
            ErrorKind::HolesMeet(k) => write!(
                f,
                "this hole meets hole {k} of the same polygon: holes must lie apart, neither \
                 touching nor inside another"
            ),
            ErrorKind::TooMany { what, limit } => {
                write!(f, "more than {limit} {what}, the scenario format's limit")
            }
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
                "a rosette has 12 values (headings 0°, 30°, … 330°), found {n}"
            ),
            ErrorKind::QualityOutOfRange(v) => {
                write!(f, "quality {} is outside [0, 1]", compact(*v))
            }
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
            ErrorKind::Planar => write!(
                f,
                "the scenario is planar: this key is read only in a three-dimensional roadmap \
                 scenario, one with planner.altitude_min_m and planner.altitude_max_m"
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
