//! Routes as KML 2.2 for Google Earth (OGC 07-147r2): one `LineString` placemark per leg
//! (longitude,latitude,altitude, sampled along its lines and arcs at most
//! [`crate::route_geojson::SAMPLE_STEP_M`] apart), the scenario's no-fly zones and the route's
//! pop-ups (64-gons) as `Polygon`s, and the start, waypoints, goal and landmarks as `Point`
//! placemarks. Altitudes are those of the mission ([`crate::route_mission::mission_altitude`]):
//! `absolute` on a terrain network, else `relativeToGround`.

use crate::route_geojson::SAMPLE_STEP_M;
use crate::route_json::{sampled_lon_lat, sampled_lon_lat_alt};
use crate::route_mission::{
    mission_altitude, mission_route, popup_rings, MissionOutput, FRAME_GLOBAL,
};
use crate::scenario::Scenario;
use serde_json::Value;
use std::fmt::Write;

/// Text with XML's five special characters escaped.
fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
        .replace('\'', "&apos;")
}

/// `lon,lat,alt` tuples separated by spaces.
fn coordinates(points: impl Iterator<Item = (f64, f64)>, alt: f64) -> String {
    points
        .map(|(lon, lat)| format!("{lon},{lat},{alt}"))
        .collect::<Vec<_>>()
        .join(" ")
}

/// A polygon placemark of a ring `(lon, lat)` and its holes (each closed here).
fn polygon(
    out: &mut String,
    name: &str,
    style: &str,
    ring: &[(f64, f64)],
    holes: &[Vec<(f64, f64)>],
) {
    let boundary = |r: &[(f64, f64)]| {
        format!(
            "<LinearRing><coordinates>{}</coordinates></LinearRing>",
            coordinates(r.iter().chain(r.first()).copied(), 0.0)
        )
    };
    let inner: String = holes
        .iter()
        .map(|h| format!("<innerBoundaryIs>{}</innerBoundaryIs>", boundary(h)))
        .collect();
    let _ = writeln!(
        out,
        "<Placemark><name>{}</name><styleUrl>#{style}</styleUrl><Polygon><tessellate>1</tessellate>\
         <outerBoundaryIs>{}</outerBoundaryIs>{inner}</Polygon></Placemark>",
        escape(name),
        boundary(ring)
    );
}

/// A point placemark.
fn point(out: &mut String, name: &str, style: &str, lon: f64, lat: f64, alt: f64, mode: &str) {
    let _ = writeln!(
        out,
        "<Placemark><name>{}</name><styleUrl>#{style}</styleUrl><Point><altitudeMode>{mode}\
         </altitudeMode><coordinates>{lon},{lat},{alt}</coordinates></Point></Placemark>",
        escape(name)
    );
}

const STYLES: &str = "<Style id=\"leg\"><LineStyle><color>ff0000ff</color><width>3</width>\
</LineStyle></Style>\n<Style id=\"zone\"><LineStyle><color>ff000000</color></LineStyle>\
<PolyStyle><color>7f0000ff</color></PolyStyle></Style>\n<Style id=\"popup\"><LineStyle>\
<color>ff00a5ff</color></LineStyle><PolyStyle><color>4000a5ff</color></PolyStyle></Style>\n\
<Style id=\"endpoint\"><IconStyle><scale>1.1</scale></IconStyle></Style>\n\
<Style id=\"landmark\"><IconStyle><color>ff00ff00</color></IconStyle></Style>\n";

/// The KML document of a detailed route file's JSON and its scenario.
pub fn route_kml(route_json: &Value, s: &Scenario, out: &MissionOutput) -> Result<String, String> {
    let m = mission_route(route_json, s)?;
    let (altitude, frame) = mission_altitude(route_json, s, out);
    let mode = if frame == FRAME_GLOBAL {
        "absolute"
    } else {
        "relativeToGround"
    };
    let mut k = String::from(
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<kml xmlns=\"http://www.opengis.net/kml/2.2\">\n<Document>\n",
    );
    let _ = writeln!(k, "<name>{}</name>", escape(&m.route.scenario));
    k.push_str(STYLES);
    k.push_str("<Folder><name>Route</name>\n");
    for (i, leg) in m.route.legs.iter().enumerate() {
        // A three-dimensional route's points at their own altitudes, above the ground.
        let pts: Vec<[f64; 3]> =
            if leg.vertical.len() == leg.primitives.len() && !leg.vertical.is_empty() {
                sampled_lon_lat_alt(&leg.primitives, &leg.vertical, &m.frame, SAMPLE_STEP_M)
            } else {
                sampled_lon_lat(&leg.primitives, &m.frame, SAMPLE_STEP_M)
                    .iter()
                    .map(|p| [p[0], p[1], altitude])
                    .collect()
            };
        let _ = writeln!(
            k,
            "<Placemark><name>leg {i}: {} - {}</name><description>{:.1} m</description>\
             <styleUrl>#leg</styleUrl><LineString><tessellate>1</tessellate><altitudeMode>{mode}\
             </altitudeMode><coordinates>{}</coordinates></LineString></Placemark>",
            escape(&leg.from),
            escape(&leg.to),
            leg.length_m,
            pts.iter()
                .map(|p| format!("{},{},{}", p[0], p[1], p[2]))
                .collect::<Vec<_>>()
                .join(" ")
        );
    }
    k.push_str("</Folder>\n<Folder><name>Start, waypoints and goal</name>\n");
    for w in m.plan.waypoints.iter().filter(|w| w.name.is_some()) {
        let (lon, lat) = m.frame.to_geo(w.position.0, w.position.1);
        let name = w.name.as_deref().unwrap_or_default();
        // A three-dimensional scenario's endpoints at their own altitudes.
        let own = (s.start.iter().chain(&s.waypoints).chain(s.goal.iter()))
            .find(|e| e.name == name)
            .and_then(|e| e.altitude_m);
        point(
            &mut k,
            name,
            "endpoint",
            lon,
            lat,
            own.unwrap_or(altitude),
            mode,
        );
    }
    k.push_str("</Folder>\n<Folder><name>No-fly zones</name>\n");
    for z in &s.no_fly {
        polygon(&mut k, &z.name, "zone", &z.ring, &z.holes);
    }
    k.push_str("</Folder>\n<Folder><name>Pop-ups</name>\n");
    for (name, ring) in popup_rings(&m) {
        let ring: Vec<(f64, f64)> = ring.iter().map(|&(lat, lon)| (lon, lat)).collect();
        polygon(&mut k, &name, "popup", &ring, &[]);
    }
    k.push_str("</Folder>\n");
    if !s.landmarks.is_empty() {
        k.push_str("<Folder><name>Landmarks</name>\n");
        for l in &s.landmarks {
            point(
                &mut k,
                &l.name,
                "landmark",
                l.lon,
                l.lat,
                0.0,
                "clampToGround",
            );
        }
        k.push_str("</Folder>\n");
    }
    k.push_str("</Document>\n</kml>\n");
    Ok(k)
}
