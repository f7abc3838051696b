//! The parser: typed access to JSON members, and the feature collection.

use super::error::{ErrorKind, FeatureRef, ScenarioError};
use super::geometry::point_in_zone;
use super::json::{describe, NON_FINITE};
use super::types::{Circle, Endpoint, Landmark, Mode, NoFly, Popup, Scenario, ZoneRings};
use serde_json::{Map, Value};
use std::path::Path;

// ------------------------------------------------------------------------------------------------
// The parser

/// Parses one scenario: the file it came from (for errors and `terrain.dem`), the repair
/// option, and the warnings so far.
pub(super) struct Parser<'a> {
    pub(super) file: &'a Path,
    /// [`ParseOptions::hull_self_intersecting_no_fly`](super::ParseOptions).
    pub(super) hull_self_intersecting_no_fly: bool,
    pub(super) warnings: Vec<ScenarioError>,
}

/// Where an error is: the feature, if any.
#[derive(Clone)]
pub(super) struct At {
    pub(super) feature: Option<FeatureRef>,
}

pub(super) const TOP: At = At { feature: None };

pub(super) type R<T> = Result<T, ScenarioError>;

/// The kinds of point features that may not lie in a no-fly area, with their positions in the
/// feature list.
struct Placed {
    kind: &'static str,
    at: FeatureRef,
    lon: f64,
    lat: f64,
}

/// What the feature loop records beside the scenario: the feature of each no-fly zone (in the
/// order of `Scenario::no_fly`), of the start and of the goal, and the point features that may
/// not lie in a no-fly area.
#[derive(Default)]
struct Seen {
    no_fly: Vec<FeatureRef>,
    start: Option<FeatureRef>,
    goal: Option<FeatureRef>,
    placed: Vec<Placed>,
}

/// The `properties` keys that features of `kind` define (`scenarios/README.md`), in the order
/// messages list them, in a planar scenario or a `three_dimensional` one (which adds a no-fly
/// zone's and a pop-up's `height_m` and an endpoint's `altitude_m`); `None` for an unknown kind. Any other key
/// is refused (a misspelt `heading` or `heigth` would otherwise be ignored).
fn property_keys(kind: &str, three_dimensional: bool) -> Option<&'static [&'static str]> {
    Some(match (kind, three_dimensional) {
        ("no_fly", false) => &["kind", "name"],
        ("no_fly", true) => &["kind", "name", "height_m"],
        ("landmark", _) => &["kind", "name", "d_max_m", "quality"],
        ("start", false) => &["kind", "name", "heading_deg", "dist_m"],
        ("start", true) => &["kind", "name", "heading_deg", "dist_m", "altitude_m"],
        ("goal" | "waypoint", false) => &["kind", "name", "heading_deg"],
        ("goal" | "waypoint", true) => &["kind", "name", "heading_deg", "altitude_m"],
        ("threat", _) => &["kind", "name", "radius_m"],
        ("popup", false) => &["kind", "name", "radius_m", "probability"],
        ("popup", true) => &["kind", "name", "radius_m", "probability", "height_m"],
        _ => return None,
    })
}

/// Whether `key` of a feature of `kind` is a three-dimensional scenario's only.
fn vertical_key(kind: &str, key: &str) -> bool {
    matches!(
        (kind, key),
        ("no_fly" | "popup", "height_m") | ("start" | "goal" | "waypoint", "altitude_m")
    )
}

impl Parser<'_> {
    pub(super) fn err(&self, at: &At, field: impl Into<String>, kind: ErrorKind) -> ScenarioError {
        ScenarioError::new(self.file, at.feature.clone(), field, kind)
    }

    // --- typed access ------------------------------------------------------------------------

    pub(super) fn object<'v>(
        &self,
        at: &At,
        v: &'v Value,
        field: &str,
    ) -> R<&'v Map<String, Value>> {
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
    pub(super) fn req<'v>(
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
    pub(super) fn opt<'v>(obj: &'v Map<String, Value>, key: &str) -> Option<&'v Value> {
        obj.get(key).filter(|v| !v.is_null())
    }

    pub(super) fn number(&self, at: &At, v: &Value, field: &str) -> R<f64> {
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

    pub(super) fn string<'v>(&self, at: &At, v: &'v Value, field: &str) -> R<&'v str> {
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

    pub(super) fn integer(&self, at: &At, v: &Value, field: &str, max: u64) -> R<u64> {
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

    pub(super) fn req_number(
        &self,
        at: &At,
        obj: &Map<String, Value>,
        key: &str,
        prefix: &str,
    ) -> R<f64> {
        let field = format!("{prefix}{key}");
        let v = self.req(at, obj, key, &field)?;
        self.number(at, v, &field)
    }

    pub(super) fn opt_number(
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

    pub(super) fn range(
        &self,
        at: &At,
        field: &str,
        value: f64,
        ok: bool,
        expected: &'static str,
    ) -> R<f64> {
        if ok {
            Ok(value)
        } else {
            Err(self.err(at, field, ErrorKind::OutOfRange { value, expected }))
        }
    }

    pub(super) fn positive(&self, at: &At, field: &str, v: f64) -> R<f64> {
        self.range(at, field, v, v > 0.0, "a positive number")
    }

    pub(super) fn non_negative(&self, at: &At, field: &str, v: f64) -> R<f64> {
        self.range(at, field, v, v >= 0.0, "a non-negative number")
    }

    pub(super) fn no_unknown_members(
        &self,
        obj: &Map<String, Value>,
        known: &[&str],
        prefix: &str,
    ) -> R<()> {
        match obj.keys().find(|k| !known.contains(&k.as_str())) {
            Some(k) => Err(self.err(&TOP, format!("{prefix}{k}"), ErrorKind::UnknownMember)),
            None => Ok(()),
        }
    }

    // --- the collection ----------------------------------------------------------------------

    pub(super) fn scenario(mut self, root: &Value) -> R<Scenario> {
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
        let vehicle_obj = self.req(&TOP, root, "vehicle", "vehicle")?;
        let mut vehicle = self.vehicle(vehicle_obj)?;
        let planner = self.planner(self.req(&TOP, root, "planner", "planner")?)?;
        self.vertical(&mut vehicle, vehicle_obj, &planner)?;
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
        let mut seen = Seen::default();
        for (index, fv) in features.iter().enumerate() {
            self.feature(&mut s, &mut seen, index, fv)?;
        }
        self.endpoints_outside_no_fly(&s, &seen)?;
        s.warnings = std::mem::take(&mut self.warnings);
        Ok(s)
    }

    /// Parses feature `index` of the collection into `s`.
    fn feature(&mut self, s: &mut Scenario, seen: &mut Seen, index: usize, fv: &Value) -> R<()> {
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
        let three_dimensional = s.vertical().is_some();
        let known = property_keys(kind, three_dimensional)
            .ok_or_else(|| self.err(&at, "properties.kind", ErrorKind::UnknownKind(kind.into())))?;
        if let Some(k) = props.keys().find(|k| !known.contains(&k.as_str())) {
            // A height or altitude in a planar scenario is known, but would be ignored.
            let why = match vertical_key(kind, k) {
                true => ErrorKind::Planar,
                false => ErrorKind::UnknownKey(known),
            };
            return Err(self.err(&at, format!("properties.{k}"), why));
        }
        let geometry = self.req(&at, f, "geometry", "geometry")?;
        let geometry = self.object(&at, geometry, "geometry")?;
        match kind {
            "no_fly" => {
                // A MultiPolygon's members become zones named "NAME[k]".
                let polygons = self.polygons(&at, geometry)?;
                let height_m = self.zone_height(&at, props, three_dimensional)?;
                let parts = polygons.len();
                for (k, ZoneRings { exterior, holes }) in polygons.into_iter().enumerate() {
                    let name = match parts {
                        1 => name.clone(),
                        _ => format!("{name}[{k}]"),
                    };
                    s.no_fly.push(NoFly {
                        name,
                        ring: exterior,
                        holes,
                        height_m,
                    });
                    seen.no_fly.push(me.clone());
                }
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
                let mut e = self.endpoint(&at, props, geometry, name)?;
                e.altitude_m = self.endpoint_altitude(&at, props, three_dimensional)?;
                // No mode takes a free start heading: the core plans from one start pose, and a
                // landmark network's start vertex has one heading. So a start without one is
                // refused here rather than flown in some default direction.
                if kind == "start" && e.heading_deg.is_none() {
                    return Err(self.err(
                        &at,
                        "properties.heading_deg",
                        ErrorKind::Invalid("missing: the start needs a heading".into()),
                    ));
                }
                self.place_endpoint(s, seen, &at, me, kind, e)?;
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
                let height_m = self.zone_height(&at, props, three_dimensional)?;
                s.popups.push(Popup {
                    name,
                    lon,
                    lat,
                    radius_m,
                    probability,
                    height_m,
                });
            }
            other => {
                return Err(self.err(&at, "properties.kind", ErrorKind::UnknownKind(other.into())))
            }
        }
        Ok(())
    }

    /// A start, goal or waypoint feature's position, heading and distance.
    fn endpoint(
        &self,
        at: &At,
        props: &Map<String, Value>,
        geometry: &Map<String, Value>,
        name: String,
    ) -> R<Endpoint> {
        let (lon, lat) = self.point(at, geometry)?;
        let heading_deg = self.opt_number(at, props, "heading_deg", "properties.")?;
        let dist_m = self
            .opt_number(at, props, "dist_m", "properties.")?
            .map(|d| self.positive(at, "properties.dist_m", d))
            .transpose()?;
        Ok(Endpoint {
            name,
            lon,
            lat,
            heading_deg,
            dist_m,
            altitude_m: None,
        })
    }

    /// Stores the endpoint `e` of `kind` ("start", "goal" or "waypoint") in `s`; a second start
    /// or goal is an error that names the first.
    fn place_endpoint(
        &self,
        s: &mut Scenario,
        seen: &mut Seen,
        at: &At,
        me: FeatureRef,
        kind: &str,
        e: Endpoint,
    ) -> R<()> {
        let (lon, lat) = (e.lon, e.lat);
        let kind: &'static str = match kind {
            "start" => "start",
            "goal" => "goal",
            _ => "waypoint",
        };
        let slot = match kind {
            "start" => Some((&mut s.start, &mut seen.start)),
            "goal" => Some((&mut s.goal, &mut seen.goal)),
            _ => None,
        };
        match slot {
            Some((_, Some(first))) => {
                return Err(self.err(
                    at,
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
            None if s.waypoints.len() >= super::limits::MAX_WAYPOINTS => {
                let too_many = ErrorKind::TooMany {
                    what: "waypoints",
                    limit: super::limits::MAX_WAYPOINTS as u64,
                };
                return Err(self.err(at, "properties.kind", too_many));
            }
            None => s.waypoints.push(e),
        }
        seen.placed.push(Placed {
            kind,
            at: me,
            lon,
            lat,
        });
        Ok(())
    }

    /// Endpoints must be flyable: not inside, nor on the edge of, any no-fly polygon (a point
    /// in one of its holes is outside it).
    fn endpoints_outside_no_fly(&self, s: &Scenario, seen: &Seen) -> R<()> {
        for p in &seen.placed {
            for (zone, zref) in s.no_fly.iter().zip(&seen.no_fly) {
                if point_in_zone((p.lon, p.lat), &zone.ring, &zone.holes) {
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
        Ok(())
    }
}
