//! No-fly zones from a KML document (Google Earth, QGIS, GDAL's KML driver): every placemark's
//! polygons, with their holes.
//!
//! A `Placemark` holding a `Polygon`, or a `MultiGeometry` of them, becomes one zone named by
//! the placemark's `<name>`: its `outerBoundaryIs` ring is the exterior, each `innerBoundaryIs`
//! ring a hole. Points and lines have no role a scenario can give them (a KML point carries no
//! heading, nor whether it is a start or a landmark), so they are counted and left out.

use super::{Imported, Zone};

/// The zones of the KML document `text` (read from `file`, named in errors).
pub fn zones(text: &str, file: &str) -> Result<Imported, String> {
    let doc = roxmltree::Document::parse(text).map_err(|e| format!("{file}: not XML: {e}"))?;
    if !doc.root_element().has_tag_name("kml") {
        return Err(format!(
            "{file}: the root element is <{}>, not <kml>",
            doc.root_element().tag_name().name()
        ));
    }
    let mut out = Imported::default();
    for (k, pm) in doc
        .descendants()
        .filter(|n| n.has_tag_name("Placemark"))
        .enumerate()
    {
        let name = pm
            .children()
            .find(|c| c.has_tag_name("name"))
            .and_then(|c| c.text())
            .map(str::trim)
            .filter(|n| !n.is_empty())
            .map_or_else(|| format!("placemark {}", k + 1), str::to_owned);
        let mut polygons = Vec::new();
        for g in pm.descendants() {
            if g.has_tag_name("Polygon") {
                polygons.push(polygon(g, file, &name)?);
            } else if g.has_tag_name("Point") {
                out.skipped.push(format!("point {name:?}"));
            } else if g.has_tag_name("LineString") && !inside_polygon(g) {
                out.skipped.push(format!("line {name:?}"));
            }
        }
        if !polygons.is_empty() {
            out.zones.push(Zone { name, polygons });
        }
    }
    Ok(out)
}

/// Whether `n` lies inside a `Polygon` (KML rings are `LinearRing`s, but some writers use
/// `LineString` there).
fn inside_polygon(n: roxmltree::Node) -> bool {
    n.ancestors().skip(1).any(|a| a.has_tag_name("Polygon"))
}

/// One `Polygon`: its outer ring, then its inner rings, each `(lon, lat)` as written (closed).
fn polygon(g: roxmltree::Node, file: &str, name: &str) -> Result<Vec<Vec<(f64, f64)>>, String> {
    let ring_of = |boundary: roxmltree::Node| -> Result<Vec<(f64, f64)>, String> {
        let coords = boundary
            .descendants()
            .find(|c| c.has_tag_name("coordinates"))
            .and_then(|c| c.text())
            .ok_or_else(|| {
                format!(
                    "{file}: placemark {name:?}: a <{}> without <coordinates>",
                    boundary.tag_name().name()
                )
            })?;
        coordinates(coords).map_err(|e| format!("{file}: placemark {name:?}: {e}"))
    };
    let outer = g
        .children()
        .find(|c| c.has_tag_name("outerBoundaryIs"))
        .ok_or_else(|| {
            format!("{file}: placemark {name:?}: a <Polygon> without outerBoundaryIs")
        })?;
    let mut rings = vec![ring_of(outer)?];
    // An innerBoundaryIs holds one LinearRing by the schema; Google Earth accepts several.
    for inner in g.children().filter(|c| c.has_tag_name("innerBoundaryIs")) {
        for ring in inner.children().filter(|c| c.has_tag_name("LinearRing")) {
            rings.push(ring_of(ring)?);
        }
    }
    Ok(rings)
}

/// A KML `<coordinates>` text: tuples `lon,lat[,alt]` separated by white space.
fn coordinates(text: &str) -> Result<Vec<(f64, f64)>, String> {
    text.split_whitespace()
        .map(|tuple| {
            let v: Vec<&str> = tuple.split(',').collect();
            let num = |s: &str| s.trim().parse::<f64>().ok().filter(|x| x.is_finite());
            match v[..] {
                [lon, lat] | [lon, lat, _] => match (num(lon), num(lat)) {
                    (Some(lon), Some(lat)) => Ok((lon, lat)),
                    _ => Err(format!("coordinates {tuple:?}: not two finite numbers")),
                },
                _ => Err(format!("coordinates {tuple:?}: expected lon,lat[,alt]")),
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    const DOC: &str = r#"<?xml version="1.0" encoding="UTF-8"?>
<kml xmlns="http://www.opengis.net/kml/2.2"><Document><Folder>
<Placemark><name>Airfield</name><Polygon><outerBoundaryIs><LinearRing><coordinates>
11.0,48.0,0 11.1,48.0,0 11.1,48.1,0 11.0,48.1,0 11.0,48.0,0
</coordinates></LinearRing></outerBoundaryIs><innerBoundaryIs><LinearRing><coordinates>
11.02,48.02 11.04,48.02 11.04,48.04 11.02,48.02</coordinates></LinearRing><LinearRing><coordinates>
11.06,48.06 11.08,48.06 11.08,48.08 11.06,48.06</coordinates></LinearRing></innerBoundaryIs>
</Polygon></Placemark>
<Placemark><Point><coordinates>11.5,48.5</coordinates></Point></Placemark>
<Placemark><name>Range</name><MultiGeometry>
<Polygon><outerBoundaryIs><LinearRing><coordinates>12,48 12.1,48 12.1,48.1 12,48</coordinates></LinearRing></outerBoundaryIs></Polygon>
<Polygon><outerBoundaryIs><LinearRing><coordinates>13,48 13.1,48 13.1,48.1 13,48</coordinates></LinearRing></outerBoundaryIs></Polygon>
</MultiGeometry></Placemark>
</Folder></Document></kml>"#;

    #[test]
    fn polygons_with_holes_and_multigeometries_become_zones_and_points_are_counted() {
        let got = zones(DOC, "a.kml").unwrap();
        assert_eq!(got.zones.len(), 2);
        assert_eq!(got.zones[0].name, "Airfield");
        assert_eq!(got.zones[0].polygons.len(), 1);
        assert_eq!(
            got.zones[0].polygons[0].len(),
            3,
            "exterior and two holes in one boundary"
        );
        assert_eq!(got.zones[0].polygons[0][1][1], (11.04, 48.02));
        assert_eq!(got.zones[1].polygons.len(), 2);
        assert_eq!(got.skipped, ["point \"placemark 2\""]);
    }

    #[test]
    fn malformed_documents_are_named() {
        let e = zones("<kml><Placemark><name>Z</name><Polygon><outerBoundaryIs><LinearRing><coordinates>11,48 x,48</coordinates></LinearRing></outerBoundaryIs></Polygon></Placemark></kml>", "b.kml").unwrap_err();
        assert!(
            e.contains("b.kml: placemark \"Z\": coordinates \"x,48\""),
            "{e}"
        );
        let e = zones("<gpx/>", "c.kml").unwrap_err();
        assert!(e.contains("c.kml: the root element is <gpx>"), "{e}");
        let e = zones("<kml><unclosed></kml>", "d.kml").unwrap_err();
        assert!(e.starts_with("d.kml: not XML"), "{e}");
    }
}
