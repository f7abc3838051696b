//! The route formats `skyroute plan -o FILE` writes, chosen by the file's extension.

use crate::route_geojson::route_geojson;
use crate::route_kml::route_kml;
use crate::route_mission::{qgc_plan, wpl_text, MissionOutput};
use crate::scenario::Scenario;
use serde_json::Value;

/// The route formats, by extension.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RouteFormat {
    /// `.json`: the detailed route file (local frame, every primitive and Hermite piece, work).
    Detailed,
    /// `.geojson`: RFC 7946 GeoJSON in longitude/latitude.
    GeoJson,
    /// `.plan`: a QGroundControl plan file (mission, geofence, rally point).
    QgcPlan,
    /// `.waypoints`: the MAVLink `QGC WPL 110` text format.
    Waypoints,
    /// `.kml`: KML 2.2 for Google Earth.
    Kml,
}

impl RouteFormat {
    /// The format of `path` by its extension; `Err` names the extension and the known ones.
    pub fn of(path: &std::path::Path) -> Result<Self, String> {
        let ext = path
            .extension()
            .map(|e| e.to_string_lossy().to_lowercase())
            .unwrap_or_default();
        match ext.as_str() {
            "json" => Ok(RouteFormat::Detailed),
            "geojson" => Ok(RouteFormat::GeoJson),
            "plan" => Ok(RouteFormat::QgcPlan),
            "waypoints" => Ok(RouteFormat::Waypoints),
            "kml" => Ok(RouteFormat::Kml),
            other => Err(format!(
                "{}: route format {:?} unknown by its extension; use .json (the detailed route \
                 file), .geojson (RFC 7946 GeoJSON), .plan (QGroundControl plan), .waypoints \
                 (MAVLink QGC WPL 110) or .kml (KML 2.2 for Google Earth)",
                path.display(),
                if other.is_empty() { "(none)" } else { other }
            )),
        }
    }

    /// Whether the format is a mission for an autopilot (`.plan`, `.waypoints`).
    pub fn is_mission(self) -> bool {
        matches!(self, RouteFormat::QgcPlan | RouteFormat::Waypoints)
    }
}

/// The text of a detailed route file's JSON in `format`; `s` is the scenario it was planned
/// for (zones, landmarks, speed and clearance of the missions and KML).
pub fn route_text(
    format: RouteFormat,
    route_json: &Value,
    s: &Scenario,
    out: &MissionOutput,
) -> Result<String, Box<dyn std::error::Error>> {
    if format.is_mission() && route_json.get("vertical").is_some() {
        return Err("a three-dimensional route's altitude changes along its paths, and the                     mission formats (.plan, .waypoints) are written at one altitude: write the                     route as .json, .geojson or .kml, whose points carry their altitudes"
            .into());
    }
    Ok(match format {
        RouteFormat::Detailed => serde_json::to_string_pretty(route_json)?,
        RouteFormat::GeoJson => serde_json::to_string(&route_geojson(route_json)?)?,
        RouteFormat::QgcPlan => serde_json::to_string_pretty(&qgc_plan(route_json, s, out)?)?,
        RouteFormat::Waypoints => wpl_text(route_json, s, out)?,
        RouteFormat::Kml => route_kml(route_json, s, out)?,
    })
}
