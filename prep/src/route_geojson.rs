//! Routes as RFC 7946 GeoJSON, for GIS tools (GDAL's `ogrinfo`/`ogr2ogr`, QGIS, shapely).
//!
//! The file is a `FeatureCollection` in WGS-84 longitude/latitude (RFC 7946 §4): one
//! `LineString` feature per leg, sampled along its lines and arcs at most
//! [`SAMPLE_STEP_M`] apart (and at every primitive's end), with the leg's names, length,
//! start and end headings (compass degrees from true north) and each arc's centre, radius,
//! turn and sweep; one `Polygon` feature per pop-up the route was planned round (its circle as a
//! 64-gon, exterior ring counter-clockwise as §3.1.6 asks). The planner's local frame, in which
//! every number of the detailed `.json` route file is given, is recorded as a PROJ string in
//! the foreign member `skyroute.frame.proj` (a transverse Mercator on WGS-84 centred on the
//! frame origin with scale 1, `prep/src/frame.rs`).

use crate::frame::LocalFrame;
use crate::render::{route_from_json, Route};
use serde_json::{json, Value};
use skyroute::geometry::compass_deg_from_heading;
use skyroute::{Primitive, Turn};

/// The largest distance between consecutive points of a leg's line, metres.
pub const SAMPLE_STEP_M: f32 = 10.0;

/// Vertices of a pop-up's circle.
const CIRCLE_VERTICES: usize = 64;

/// The PROJ definition of the local frame with origin `(lat, lon)` degrees.
pub fn proj_string(lat0: f64, lon0: f64) -> String {
    format!(
        "+proj=tmerc +lat_0={lat0} +lon_0={lon0} +k=1 +x_0=0 +y_0=0 +ellps=WGS84 +units=m +no_defs"
    )
}

/// A local heading (radians counter-clockwise from the frame's `x`) at local `(x, y)` as a
/// compass heading from true north, degrees in `[0, 360)`.
fn true_heading_deg(frame: &LocalFrame, x: f32, y: f32, heading: f32) -> f64 {
    let grid = compass_deg_from_heading(heading) as f64;
    frame
        .heading_to_geo(x as f64, y as f64, grid)
        .rem_euclid(360.0)
}

fn lon_lat(frame: &LocalFrame, x: f32, y: f32) -> [f64; 2] {
    let (lon, lat) = frame.to_geo(x as f64, y as f64);
    [lon, lat]
}

/// A leg as a feature.
fn leg_feature(
    frame: &LocalFrame,
    index: usize,
    leg: &crate::render::RouteLeg,
    altitude: Option<f64>,
) -> Value {
    // A three-dimensional route's positions carry their altitude (RFC 7946 §3.1.1).
    let three_d = !leg.vertical.is_empty() && leg.vertical.len() == leg.primitives.len();
    let mut coords: Vec<Vec<f64>> = Vec::new();
    let mut arcs = Vec::new();
    for (i, p) in leg.primitives.iter().enumerate() {
        let n = (p.length() / SAMPLE_STEP_M).ceil().max(1.0) as usize;
        let first = usize::from(!coords.is_empty());
        for k in first..=n {
            let s = p.length() * k as f32 / n as f32;
            let q = p.pose_at(s).position;
            let mut point = lon_lat(frame, q.x, q.y).to_vec();
            if let Some((profile, offset)) = leg.vertical.get(i).filter(|_| three_d) {
                point.push(profile.altitude_at(offset + s) as f64);
            }
            coords.push(point);
        }
        if let Primitive::Arc(a) = p {
            arcs.push(json!({
                "centre": lon_lat(frame, a.centre.x, a.centre.y),
                "radius_m": a.radius,
                "turn": if a.turn() == Turn::Left { "left" } else { "right" },
                "sweep_deg": a.sweep.abs().to_degrees(),
            }));
        }
    }
    let heading = |at_end: bool| -> Option<f64> {
        let p = if at_end {
            leg.primitives.last()?
        } else {
            leg.primitives.first()?
        };
        let pose = p.pose_at(if at_end { p.length() } else { 0.0 });
        Some(true_heading_deg(
            frame,
            pose.position.x,
            pose.position.y,
            pose.heading,
        ))
    };
    json!({
        "type": "Feature",
        "geometry": {"type": "LineString", "coordinates": coords},
        "properties": {
            "kind": "leg",
            "index": index,
            "from": leg.from,
            "to": leg.to,
            "length_m": leg.length_m,
            "start_heading_deg": heading(false),
            "end_heading_deg": heading(true),
            "altitude_m": altitude,
            "arcs": arcs,
        },
    })
}

/// A pop-up as a polygon feature.
fn popup_feature(frame: &LocalFrame, p: &crate::render::PopupMark) -> Value {
    let ring: Vec<[f64; 2]> = (0..=CIRCLE_VERTICES)
        .map(|k| {
            let a = std::f64::consts::TAU * (k % CIRCLE_VERTICES) as f64 / CIRCLE_VERTICES as f64;
            let (x, y) = (
                p.centre.0 + p.radius * a.cos(),
                p.centre.1 + p.radius * a.sin(),
            );
            let (lon, lat) = frame.to_geo(x, y);
            [lon, lat]
        })
        .collect();
    json!({
        "type": "Feature",
        "geometry": {"type": "Polygon", "coordinates": [ring]},
        "properties": {"kind": "popup", "name": p.name, "radius_m": p.radius},
    })
}

/// The RFC 7946 FeatureCollection of a detailed route file's JSON (what `skyroute plan` writes
/// to a `.json` output). `Err` says what the route JSON lacks.
pub fn route_geojson(route_json: &Value) -> Result<Value, String> {
    let route: Route = route_from_json(route_json)?;
    let (lat0, lon0) = route.origin_deg;
    let frame = LocalFrame::new(lat0, lon0);
    let altitude = route_json.get("altitude_m").and_then(Value::as_f64);
    let mut features: Vec<Value> = route
        .legs
        .iter()
        .enumerate()
        .map(|(i, leg)| leg_feature(&frame, i, leg, altitude))
        .collect();
    features.extend(route.popups.iter().map(|p| popup_feature(&frame, p)));
    Ok(json!({
        "type": "FeatureCollection",
        "features": features,
        "skyroute": {
            "scenario": route.scenario,
            "length_m": route_json.get("length_m"),
            "frame": {
                "origin_lat_deg": lat0,
                "origin_lon_deg": lon0,
                "proj": proj_string(lat0, lon0),
            },
        },
    }))
}
