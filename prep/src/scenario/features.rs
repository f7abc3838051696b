//! Feature geometries (points, polygons) and landmark rosettes.

use super::error::ErrorKind;
use super::geometry::{convex_hull, first_self_intersection};
use super::json::describe;
use super::parser::{At, Parser, R};
use super::types::*;
use serde_json::{Map, Value};

impl Parser<'_> {
    pub(super) fn geometry_type(
        &self,
        at: &At,
        g: &Map<String, Value>,
        expected: &'static str,
    ) -> R<()> {
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

    pub(super) fn position(&self, at: &At, v: &Value, field: &str) -> R<(f64, f64)> {
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

    pub(super) fn point(&self, at: &At, g: &Map<String, Value>) -> R<(f64, f64)> {
        self.geometry_type(at, g, "Point")?;
        let c = self.req(at, g, "coordinates", "geometry.coordinates")?;
        self.position(at, c, "geometry.coordinates")
    }

    /// The rings of a no-fly geometry: a `Polygon` gives one, a `MultiPolygon` one per member
    /// polygon (each becomes its own zone). Each polygon has exactly one ring: holes are
    /// refused by name.
    pub(super) fn polygons(&mut self, at: &At, g: &Map<String, Value>) -> R<Vec<Vec<(f64, f64)>>> {
        let t = self.req(at, g, "type", "geometry.type")?;
        let t = self.string(at, t, "geometry.type")?.to_owned();
        let field = "geometry.coordinates";
        let c = self.req(at, g, "coordinates", field)?;
        match t.as_str() {
            "Polygon" => Ok(vec![self.polygon(at, c, field)?]),
            "MultiPolygon" => {
                let members = c.as_array().ok_or_else(|| {
                    self.err(
                        at,
                        field,
                        ErrorKind::WrongType {
                            expected: "an array of polygons",
                            found: describe(c),
                        },
                    )
                })?;
                if members.is_empty() {
                    return Err(self.err(at, field, ErrorKind::TooFewPoints(0)));
                }
                members
                    .iter()
                    .enumerate()
                    .map(|(k, m)| self.polygon(at, m, &format!("{field}[{k}]")))
                    .collect()
            }
            _ => Err(self.err(
                at,
                "geometry.type",
                ErrorKind::WrongGeometry {
                    expected: "Polygon or MultiPolygon",
                    found: t,
                },
            )),
        }
    }

    /// One polygon's coordinates `c` (at `field`): its single ring, checked.
    fn polygon(&mut self, at: &At, c: &Value, field: &str) -> R<Vec<(f64, f64)>> {
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
        if ring_v.len() > super::limits::MAX_RING_VERTICES + 1 {
            let too_many = ErrorKind::TooMany {
                what: "ring vertices",
                limit: super::limits::MAX_RING_VERTICES as u64,
            };
            return Err(self.err(at, field, too_many));
        }
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
            if !self.hull_self_intersecting_no_fly {
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

    pub(super) fn quality(
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
