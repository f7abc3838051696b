//! `skyroute init`: a commented template scenario, one per mode, that parses, builds and plans
//! as written.
//!
//! JSON has no comments, so the template carries them as RFC 7946 *foreign members*, which
//! GeoJSON readers (GDAL, QGIS) and the scenario parser ignore: a top-level `comments` array
//! explaining every section and key, and a `comment` member on each feature (beside `type`,
//! `geometry` and `properties`, never inside `properties`, whose keys are checked). The
//! top-level `description` (a key the format defines) says what the template is.
//!
//! The roadmap, landmark and Voronoi templates are fixed small scenarios east of Munich. The
//! terrain template needs a DEM (`--dem`): it is read, its start and goal are the lowest cells
//! of the DEM's western and eastern quarters (at the middle third of its latitudes), and its
//! altitude the DEM's 75th-percentile elevation plus the safety height, rounded up to 10 m.

use crate::dem::{self, Dem};
use crate::scenario::Mode;
use std::path::{Path, PathBuf};

/// The comments on the vehicle, shared by every template.
const VEHICLE_COMMENTS: &str = r#"    "vehicle: the aircraft. v_nominal_mps is the cruise speed, v_min_mps/v_max_mps the speed range (m/s); a_lat_max_mps2 the largest lateral acceleration: the turn radius is v_nominal^2 / a_lat_max; a_long_*: longitudinal acceleration limits; wingspan_m widens every clearance by half the span.",
    "features: Points and Polygons in [longitude, latitude] WGS-84 degrees (RFC 7946), by properties.kind. Every feature needs a unique properties.name; heading_deg is a compass heading (0 = north, 90 = east). The start needs one; a goal or waypoint without one may be reached at any heading.","#;

/// The vehicle section, shared by every template (the turn radius is 30²/3 = 300 m).
const VEHICLE: &str = r#"  "vehicle": {
    "v_nominal_mps": 30.0,
    "v_min_mps": 25.0,
    "v_max_mps": 35.0,
    "a_lat_max_mps2": 3.0,
    "a_long_min_mps2": -3.0,
    "a_long_max_mps2": 3.0,
    "wingspan_m": 3.0
  },"#;

/// The roadmap template.
const ROADMAP: &str = r#"{
  "type": "FeatureCollection",
  "name": "my-roadmap",
  "description": "A skyroute scenario template, roadmap mode (Niendorf et al.): a sampled Dubins roadmap around no-fly zones. Edit the positions, the vehicle and the planner, then: skyroute build FILE -o net.bin; skyroute plan net.bin --scenario FILE -o route.geojson",
  "comments": [
    "This file is GeoJSON (RFC 7946). 'comments' and each feature's 'comment' are ignored by skyroute and by GIS tools; delete them freely.",
VEHICLE_COMMENTS
    "planner: mode 'roadmap'. sample_spacing_m: distance between roadmap samples (smaller: denser network, longer build); neighbour_radius_m: samples closer than this get Dubins edges (about 3 turn radii); k_nearest_fallback: edges to that many nearest samples when none is in range; allow_ccc: also the three-arc Dubins words; clearance_m: distance kept from every zone; arc_step_m: step of the paper's discretised check (build --discretised, or --discretised=paper for the paper's reading); seed: the sampling's random seed.",
    "no_fly: a Polygon never entered (plus the clearance); rings after the first are holes, areas inside it that are not part of the zone. popup: a circular zone (radius_m) that may appear in flight with probability; plan avoids the scenario's pop-ups."
  ],
VEHICLE
  "planner": {
    "mode": "roadmap",
    "sample_spacing_m": 150.0,
    "neighbour_radius_m": 900.0,
    "k_nearest_fallback": 8,
    "allow_ccc": false,
    "clearance_m": 20.0,
    "arc_step_m": 40.0,
    "seed": 1
  },
  "features": [
    {
      "type": "Feature",
      "comment": "Where the flight starts, and the heading it starts with.",
      "geometry": { "type": "Point", "coordinates": [11.600, 48.100] },
      "properties": { "kind": "start", "name": "S", "heading_deg": 90.0 }
    },
    {
      "type": "Feature",
      "comment": "A waypoint, flown over in file order between the start and the goal; no heading_deg: any heading.",
      "geometry": { "type": "Point", "coordinates": [11.630, 48.112] },
      "properties": { "kind": "waypoint", "name": "W1" }
    },
    {
      "type": "Feature",
      "comment": "Where the flight ends, here with a required heading.",
      "geometry": { "type": "Point", "coordinates": [11.660, 48.100] },
      "properties": { "kind": "goal", "name": "G", "heading_deg": 90.0 }
    },
    {
      "type": "Feature",
      "comment": "A no-fly zone: a simple polygon, first and last position equal.",
      "geometry": {
        "type": "Polygon",
        "coordinates": [[[11.612, 48.096], [11.620, 48.096], [11.620, 48.104], [11.612, 48.104], [11.612, 48.096]]]
      },
      "properties": { "kind": "no_fly", "name": "Z1" }
    },
    {
      "type": "Feature",
      "comment": "A pop-up threat: a circle of radius_m that may appear in flight (probability), avoided by plan.",
      "geometry": { "type": "Point", "coordinates": [11.645, 48.093] },
      "properties": { "kind": "popup", "name": "U1", "radius_m": 300.0, "probability": 0.5 }
    }
  ]
}
"#;

/// The landmark template.
const LANDMARK: &str = r#"{
  "type": "FeatureCollection",
  "name": "my-landmarks",
  "description": "A skyroute scenario template, landmark mode (Babel): routes that fly over navigation landmarks, each seen well only from some headings and weathers. Edit, then: skyroute build FILE -o net.bin; skyroute plan net.bin --scenario FILE --weather nominal -o route.geojson",
  "comments": [
    "This file is GeoJSON (RFC 7946). 'comments' and each feature's 'comment' are ignored by skyroute and by GIS tools; delete them freely.",
VEHICLE_COMMENTS
    "planner: mode 'landmark'. directions: overflight headings per landmark (12: every 30 degrees); line_elements_per_pair: random line elements tried between two landmarks (more: better routes, longer build); clearance_m: distance kept from every no-fly zone; seed: the random seed.",
    "weather: the names of the conditions each landmark's quality is given for; plan --weather picks one.",
    "landmark: d_max_m is the farthest the aircraft may fly after overflying it (its navigation error grows); quality has, per weather, 12 values in [0, 1] for overflight headings 0, 30, ... 330 degrees: the range after an overflight at that heading is d_max_m x quality.",
    "start: dist_m is the farthest the aircraft may fly before its first landmark."
  ],
VEHICLE
  "planner": {
    "mode": "landmark",
    "directions": 12,
    "line_elements_per_pair": 100,
    "clearance_m": 50.0,
    "seed": 1
  },
  "weather": ["nominal", "haze"],
  "features": [
    {
      "type": "Feature",
      "comment": "The start, its heading, and how far it may fly before the first landmark.",
      "geometry": { "type": "Point", "coordinates": [11.000, 48.000] },
      "properties": { "kind": "start", "name": "S", "heading_deg": 90.0, "dist_m": 6000.0 }
    },
    {
      "type": "Feature",
      "comment": "A landmark seen equally well from every heading; a little worse in haze.",
      "geometry": { "type": "Point", "coordinates": [11.060, 48.000] },
      "properties": {
        "kind": "landmark", "name": "A", "d_max_m": 9000.0,
        "quality": {
          "nominal": [1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1],
          "haze": [0.9, 0.9, 0.9, 0.9, 0.9, 0.9, 0.9, 0.9, 0.9, 0.9, 0.9, 0.9]
        }
      }
    },
    {
      "type": "Feature",
      "comment": "A landmark seen poorly when overflown heading east (60-120 degrees).",
      "geometry": { "type": "Point", "coordinates": [11.140, 48.003] },
      "properties": {
        "kind": "landmark", "name": "B", "d_max_m": 9000.0,
        "quality": {
          "nominal": [1, 1, 0.25, 0.2, 0.25, 1, 1, 1, 1, 1, 1, 1],
          "haze": [0.9, 0.9, 0.2, 0.15, 0.2, 0.9, 0.9, 0.9, 0.9, 0.9, 0.9, 0.9]
        }
      }
    },
    {
      "type": "Feature",
      "comment": "A third landmark, within range of the goal.",
      "geometry": { "type": "Point", "coordinates": [11.220, 48.004] },
      "properties": {
        "kind": "landmark", "name": "C", "d_max_m": 10000.0,
        "quality": {
          "nominal": [1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1],
          "haze": [0.9, 0.9, 0.9, 0.9, 0.9, 0.9, 0.9, 0.9, 0.9, 0.9, 0.9, 0.9]
        }
      }
    },
    {
      "type": "Feature",
      "comment": "The goal.",
      "geometry": { "type": "Point", "coordinates": [11.300, 48.000] },
      "properties": { "kind": "goal", "name": "G", "heading_deg": 90.0 }
    },
    {
      "type": "Feature",
      "comment": "A no-fly zone between C and the goal: routes fly round it.",
      "geometry": {
        "type": "Polygon",
        "coordinates": [[[11.252, 47.993], [11.271, 47.993], [11.271, 48.010], [11.252, 48.010], [11.252, 47.993]]]
      },
      "properties": { "kind": "no_fly", "name": "Z1" }
    }
  ]
}
"#;

/// The Voronoi template.
const VORONOI: &str = r#"{
  "type": "FeatureCollection",
  "name": "my-threats",
  "description": "A skyroute scenario template, Voronoi mode (Judd & McLain): a route between radar threats along their Voronoi diagram, trading length for exposure. Edit, then: skyroute build FILE -o net.bin; skyroute plan net.bin --scenario FILE -o route.geojson",
  "comments": [
    "This file is GeoJSON (RFC 7946). 'comments' and each feature's 'comment' are ignored by skyroute and by GIS tools; delete them freely.",
VEHICLE_COMMENTS
    "planner: mode 'voronoi'. clearance_m: distance kept from every no-fly zone and threat circle; threat_weight in [0, 1]: 0 minimises length, 1 exposure to the threats.",
    "threat: a radar at the point, radius_m its lethal range (never entered). no_fly: a Polygon never entered."
  ],
VEHICLE
  "planner": {
    "mode": "voronoi",
    "clearance_m": 50.0,
    "threat_weight": 0.5
  },
  "features": [
    {
      "type": "Feature",
      "comment": "A radar threat and its lethal range.",
      "geometry": { "type": "Point", "coordinates": [11.700, 48.230] },
      "properties": { "kind": "threat", "name": "R1", "radius_m": 2500.0 }
    },
    {
      "type": "Feature",
      "comment": "Another radar threat.",
      "geometry": { "type": "Point", "coordinates": [11.780, 48.170] },
      "properties": { "kind": "threat", "name": "R2", "radius_m": 3000.0 }
    },
    {
      "type": "Feature",
      "comment": "Another radar threat.",
      "geometry": { "type": "Point", "coordinates": [11.860, 48.240] },
      "properties": { "kind": "threat", "name": "R3", "radius_m": 2000.0 }
    },
    {
      "type": "Feature",
      "comment": "Another radar threat.",
      "geometry": { "type": "Point", "coordinates": [11.930, 48.180] },
      "properties": { "kind": "threat", "name": "R4", "radius_m": 2500.0 }
    },
    {
      "type": "Feature",
      "comment": "A no-fly zone.",
      "geometry": {
        "type": "Polygon",
        "coordinates": [[[11.810, 48.280], [11.840, 48.280], [11.840, 48.300], [11.810, 48.300], [11.810, 48.280]]]
      },
      "properties": { "kind": "no_fly", "name": "Z1" }
    },
    {
      "type": "Feature",
      "comment": "The start and its heading.",
      "geometry": { "type": "Point", "coordinates": [11.600, 48.200] },
      "properties": { "kind": "start", "name": "P", "heading_deg": 90.0 }
    },
    {
      "type": "Feature",
      "comment": "The goal; no heading_deg: any heading.",
      "geometry": { "type": "Point", "coordinates": [12.030, 48.200] },
      "properties": { "kind": "goal", "name": "Q" }
    }
  ]
}
"#;

/// The terrain template, with `{DEM}`, `{ALT}`, `{SAFETY}`, `{START}` and `{GOAL}` to fill in.
const TERRAIN: &str = r#"{
  "type": "FeatureCollection",
  "name": "my-terrain",
  "description": "A skyroute scenario template, terrain mode (Medeiros & da Silva): a route at constant altitude around the terrain that rises above it. Edit, then: skyroute build FILE -o net.bin; skyroute plan net.bin --scenario FILE -o route.geojson",
  "comments": [
    "This file is GeoJSON (RFC 7946). 'comments' and each feature's 'comment' are ignored by skyroute and by GIS tools; delete them freely.",
VEHICLE_COMMENTS
    "planner: mode 'terrain'. clearance_m: horizontal distance kept from terrain that is too high.",
    "terrain: dem is the elevation model, relative to this file: an ESRI ASCII grid (.asc, geographic) or a GeoTIFF (.tif: WGS 84 degrees or UTM metres); altitude_m the flight altitude (metres, the DEM's vertical datum); safety_height_m how far above the terrain the aircraft must stay: cells at or above altitude_m - safety_height_m, and NODATA cells, are not flown over. This template's altitude: the DEM's 75th-percentile elevation plus the safety height.",
    "start and goal: here the lowest cells of the DEM's western and eastern quarters; both must lie on the DEM, on cells the aircraft may fly over."
  ],
VEHICLE
  "planner": {
    "mode": "terrain",
    "clearance_m": 100.0
  },
  "terrain": {
    "dem": {DEM},
    "altitude_m": {ALT},
    "safety_height_m": {SAFETY}
  },
  "features": [
    {
      "type": "Feature",
      "comment": "The start and its heading.",
      "geometry": { "type": "Point", "coordinates": {START} },
      "properties": { "kind": "start", "name": "P", "heading_deg": 90.0 }
    },
    {
      "type": "Feature",
      "comment": "The goal; no heading_deg: any heading.",
      "geometry": { "type": "Point", "coordinates": {GOAL} },
      "properties": { "kind": "goal", "name": "Q" }
    }
  ]
}
"#;

/// The terrain template's safety height, metres.
const SAFETY_HEIGHT_M: f64 = 100.0;

/// The template for `mode`, to be written to `output`; terrain needs `dem` (read here).
pub fn template(mode: Mode, dem: Option<&Path>, output: &Path) -> Result<String, String> {
    let fill = |t: &str| {
        t.replace("VEHICLE_COMMENTS\n", &format!("{VEHICLE_COMMENTS}\n"))
            .replace("VEHICLE\n", &format!("{VEHICLE}\n"))
    };
    match mode {
        Mode::Roadmap => Ok(fill(ROADMAP)),
        Mode::Landmark => Ok(fill(LANDMARK)),
        Mode::Voronoi => Ok(fill(VORONOI)),
        Mode::Terrain => {
            let Some(dem_path) = dem else {
                return Err(format!(
                    "{}: --mode terrain needs --dem FILE (the DEM the template flies over)",
                    output.display()
                ));
            };
            let d = dem::load(dem_path).map_err(|e| e.to_string())?;
            let TerrainPlaces {
                start,
                goal,
                altitude_m,
            } = terrain_places(&d)?;
            let reference = serde_json::to_string(&dem_reference(dem_path, output))
                .map_err(|e| e.to_string())?;
            let point = |p: (f64, f64)| format!("[{:.7}, {:.7}]", p.0, p.1);
            Ok(fill(TERRAIN)
                .replace("{DEM}", &reference)
                .replace("{ALT}", &format!("{altitude_m:.1}"))
                .replace("{SAFETY}", &format!("{SAFETY_HEIGHT_M:.1}"))
                .replace("{START}", &point(start))
                .replace("{GOAL}", &point(goal)))
        }
    }
}

/// Where the terrain template flies over a DEM.
struct TerrainPlaces {
    /// The start, `(lon, lat)`.
    start: (f64, f64),
    /// The goal, `(lon, lat)`.
    goal: (f64, f64),
    /// The flight altitude, metres.
    altitude_m: f64,
}

/// The start, goal and altitude of the terrain template over `d` (see the module
/// documentation).
fn terrain_places(d: &Dem) -> Result<TerrainPlaces, String> {
    let field = |m: &str| format!("{}: {m}", d.path.display());
    let mut elevations: Vec<f32> = d.values().iter().copied().filter(|v| !v.is_nan()).collect();
    if elevations.is_empty() {
        return Err(field("every cell is NODATA"));
    }
    let k = (elevations.len() - 1) * 3 / 4;
    let (_, &mut q75, _) = elevations.select_nth_unstable_by(k, f32::total_cmp);
    let altitude = ((q75 as f64 + SAFETY_HEIGHT_M) / 10.0).ceil() * 10.0;
    let (nc, nr) = (d.ncols, d.nrows);
    let rows = nr / 3..(2 * nr / 3).max(nr / 3 + 1);
    let lowest = |cols: std::ops::Range<usize>| {
        let mut best: Option<(f32, usize, usize)> = None;
        for r in rows.clone() {
            for c in cols.clone() {
                if let Some(e) = d.elevation_at(c, r) {
                    if best.is_none_or(|b| e < b.0) {
                        best = Some((e, c, r));
                    }
                }
            }
        }
        best.and_then(|(_, c, r)| d.cell_centre_lonlat(c, r))
    };
    let quarter = (nc / 4).max(1);
    let start = lowest(0..quarter);
    let goal = lowest(nc - quarter..nc);
    match (start, goal) {
        (Some(start), Some(goal)) => Ok(TerrainPlaces {
            start,
            goal,
            altitude_m: altitude,
        }),
        _ => Err(field(
            "no start and goal: the DEM is not placed on the earth (an ASCII grid in metres) \
             or its western or eastern quarter is all NODATA",
        )),
    }
}

/// `dem` as the template's `terrain.dem`: relative to the folder of `output` when it lies
/// under it, absolute otherwise.
fn dem_reference(dem: &Path, output: &Path) -> String {
    let cwd = std::env::current_dir().unwrap_or_default();
    let absolute = |p: &Path| -> PathBuf {
        if p.is_absolute() {
            p.to_path_buf()
        } else {
            cwd.join(p)
        }
    };
    let dem = absolute(dem);
    let folder = absolute(output)
        .parent()
        .map(Path::to_path_buf)
        .unwrap_or_default();
    dem.strip_prefix(&folder)
        .map(Path::to_path_buf)
        .unwrap_or(dem)
        .display()
        .to_string()
}

/// `skyroute init`: writes the template for `mode` to `output` (refusing an existing file
/// unless `force`); returns the line to print.
pub fn init_command(
    output: &Path,
    mode: Mode,
    dem: Option<&Path>,
    force: bool,
) -> Result<String, String> {
    if !force && output.exists() {
        return Err(format!(
            "{}: exists; pass --force to overwrite it",
            output.display()
        ));
    }
    let text = template(mode, dem, output)?;
    crate::output::write_atomically(output, text.as_bytes())?;
    Ok(format!(
        "wrote a {} scenario template to {}: edit it, then `skyroute build {} -o net.bin`",
        mode.as_str(),
        output.display(),
        output.display()
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every fixed template is JSON, parses as its mode's scenario, and has a comment on every
    /// feature.
    #[test]
    fn fixed_templates_parse_as_their_mode() {
        for mode in [Mode::Roadmap, Mode::Landmark, Mode::Voronoi] {
            let text = template(mode, None, Path::new("t/x.geojson")).unwrap();
            let v: serde_json::Value = serde_json::from_str(&text).unwrap();
            assert!(v["comments"].as_array().unwrap().len() >= 3);
            for f in v["features"].as_array().unwrap() {
                assert!(f["comment"].is_string(), "{mode:?}: {f}");
            }
            let s = crate::scenario::parse(&text, Path::new("t/x.geojson")).unwrap();
            assert_eq!(s.planner.mode, mode);
        }
    }

    #[test]
    fn terrain_needs_a_dem() {
        let e = template(Mode::Terrain, None, Path::new("t/x.geojson")).unwrap_err();
        assert!(e.contains("t/x.geojson: --mode terrain needs --dem"), "{e}");
    }

    #[test]
    fn a_dem_under_the_scenarios_folder_is_named_relative_to_it() {
        let r = dem_reference(Path::new("/a/b/dem.tif"), Path::new("/a/s.geojson"));
        assert_eq!(r, "b/dem.tif");
        let r = dem_reference(Path::new("/c/dem.tif"), Path::new("/a/s.geojson"));
        assert_eq!(r, "/c/dem.tif");
    }
}
