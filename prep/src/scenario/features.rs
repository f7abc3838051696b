//! Feature geometries (points, polygons) and landmark rosettes.

use super::error::ErrorKind;
use super::geometry::{convex_hull, first_rings_meeting, first_self_intersection, point_in_ring};
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

    /// The polygons of a no-fly geometry: a `Polygon` gives one, a `MultiPolygon` one per
    /// member polygon (each becomes its own zone). Each polygon is its exterior ring and its
    /// holes, checked (see [`Self::polygon`]).
    pub(super) fn polygons(&mut self, at: &At, g: &Map<String, Value>) -> R<Vec<ZoneRings>> {
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

    /// One polygon's coordinates `c` (at `field`): its exterior ring and its holes (RFC 7946
    /// §3.1.6: the first ring is the exterior, the others are holes). Every ring is checked as
    /// [`Self::ring`] does; each hole must lie strictly inside the exterior, and the holes
    /// strictly apart from one another (no shared point, none inside another).
    fn polygon(&mut self, at: &At, c: &Value, field: &str) -> R<ZoneRings> {
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
        if rings.is_empty() {
            return Err(self.err(at, field, ErrorKind::TooFewPoints(0)));
        }
        if rings.len() - 1 > super::limits::MAX_HOLES {
            let too_many = ErrorKind::TooMany {
                what: "holes in one polygon",
                limit: super::limits::MAX_HOLES as u64,
            };
            return Err(self.err(at, field, too_many));
        }
        let exterior = self.ring(at, &rings[0], field, 0, true)?;
        let mut holes = Vec::with_capacity(rings.len() - 1);
        for (k, hole) in rings.iter().enumerate().skip(1) {
            holes.push(self.ring(at, hole, field, k, false)?);
        }
        let all: Vec<&[(f64, f64)]> = std::iter::once(exterior.as_slice())
            .chain(holes.iter().map(Vec::as_slice))
            .collect();
        if let Some((a, b)) = first_rings_meeting(&all) {
            let kind = match a {
                0 => ErrorKind::HoleOutside,
                _ => ErrorKind::HolesMeet(a),
            };
            return Err(self.err(at, format!("{field}[{b}]"), kind));
        }
        for (k, hole) in holes.iter().enumerate() {
            // The rings do not meet, so one vertex tells where a whole ring lies.
            if !point_in_ring(hole[0], &exterior) {
                return Err(self.err(at, format!("{field}[{}]", k + 1), ErrorKind::HoleOutside));
            }
            if let Some(j) = (0..holes.len()).find(|&j| j != k && point_in_ring(holes[j][0], hole))
            {
                let field = format!("{field}[{}]", j + 1);
                return Err(self.err(at, field, ErrorKind::HolesMeet(k + 1)));
            }
        }
        Ok(ZoneRings { exterior, holes })
    }

    /// Ring `k` of a polygon (`c` at `field[k]`): closed, within the vertex limit, at least 3
    /// distinct points, simple. A self-intersecting exterior is replaced by its convex hull when
    /// [`super::ParseOptions::hull_self_intersecting_no_fly`] allows it (with a warning); a
    /// hole never is, since its hull would shrink the zone.
    fn ring(
        &mut self,
        at: &At,
        c: &Value,
        field: &str,
        k: usize,
        exterior: bool,
    ) -> R<Vec<(f64, f64)>> {
        let ring_field = format!("{field}[{k}]");
        let ring_v = c.as_array().ok_or_else(|| {
            self.err(
                at,
                &ring_field,
                ErrorKind::WrongType {
                    expected: "an array of positions",
                    found: describe(c),
                },
            )
        })?;
        // The exterior's errors name the polygon (its only ring in most scenarios); a hole's
        // name the hole.
        let whole = if exterior { field } else { ring_field.as_str() };
        if ring_v.len() > super::limits::MAX_RING_VERTICES + 1 {
            let too_many = ErrorKind::TooMany {
                what: "ring vertices",
                limit: super::limits::MAX_RING_VERTICES as u64,
            };
            return Err(self.err(at, whole, too_many));
        }
        let mut ring = Vec::with_capacity(ring_v.len());
        for (i, p) in ring_v.iter().enumerate() {
            ring.push(self.position(at, p, &format!("{ring_field}[{i}]"))?);
        }
        if ring.is_empty() {
            return Err(self.err(at, whole, ErrorKind::TooFewPoints(0)));
        }
        if ring.first() != ring.last() || ring.len() < 2 {
            return Err(self.err(at, whole, ErrorKind::RingNotClosed));
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
            return Err(self.err(at, whole, ErrorKind::TooFewPoints(distinct.len())));
        }
        if let Some((edge_a, edge_b, overlap)) = first_self_intersection(&ring) {
            let refused = ErrorKind::SelfIntersecting {
                edge_a,
                edge_b,
                overlap,
            };
            if !(exterior && self.hull_self_intersecting_no_fly) {
                return Err(self.err(at, whole, refused));
            }
            let hull = convex_hull(&ring);
            if hull.len() < 3 {
                return Err(self.err(at, whole, refused));
            }
            let warning = self.err(
                at,
                whole,
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
