//! `skyroute import`: a scenario from the files people already have. KML documents give no-fly
//! zones ([`kml`]); QGroundControl `.plan` files give the route (home, then the mission's
//! positions) and their exclusion fences as zones ([`qgc_plan`]). They join a base scenario,
//! which brings the vehicle, the planner and any features of its own (by default the roadmap
//! template of `skyroute init`); a route imported replaces the base's start, waypoints and goal.
//!
//! The scenario is assembled as JSON, then read back by the scenario parser before it is
//! written: a zone that is not simple, a hole outside its zone or a waypoint inside a zone is
//! refused with the parser's message, and nothing is written.

pub mod kml;
pub mod qgc_plan;

use crate::scenario::Mode;
use serde_json::{json, Map, Value};
use std::collections::HashSet;
use std::path::{Path, PathBuf};

/// `skyroute import`'s arguments.
#[derive(clap::Args)]
pub struct ImportArgs {
    /// The files to import: KML (`.kml`) for no-fly zones, QGroundControl plans (`.plan`) for
    /// the route and the exclusion fences. At most one may give a route.
    #[arg(required = true)]
    pub inputs: Vec<PathBuf>,
    /// Where to write the scenario (`.geojson` or `.json`).
    #[arg(short, long)]
    pub output: PathBuf,
    /// The scenario the imported features join, with its vehicle and planner (by default the
    /// roadmap template of `skyroute init`).
    #[arg(long)]
    pub base: Option<PathBuf>,
    /// Overwrite an existing output.
    #[arg(long)]
    pub force: bool,
}

/// What one input file gives.
#[derive(Debug, Default)]
pub struct Imported {
    /// No-fly zones.
    pub zones: Vec<Zone>,
    /// The route's positions in order, each named; empty when the file has no route.
    pub route: Vec<qgc_plan::Waypoint>,
    /// What was left out, for the summary ("point \"A\"", "inclusion fence polygon 0").
    pub skipped: Vec<String>,
}

/// An imported no-fly zone.
#[derive(Debug)]
pub struct Zone {
    /// Its name.
    pub name: String,
    /// Its polygons, each rings of `(lon, lat)` (closed): the exterior, then the holes.
    pub polygons: Vec<Vec<Vec<(f64, f64)>>>,
}

/// The largest input read, bytes (the scenario format's own limit).
const MAX_INPUT_BYTES: u64 = crate::scenario::limits::MAX_SCENARIO_BYTES;

/// Runs `skyroute import`; returns the summary printed on success.
pub fn import_command(a: &ImportArgs) -> Result<String, String> {
    let out = &a.output;
    if !out
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("geojson") || e.eq_ignore_ascii_case("json"))
    {
        return Err(format!(
            "{}: import writes a GeoJSON scenario; name the output .geojson or .json",
            out.display()
        ));
    }
    let mut inputs: Vec<&Path> = a.inputs.iter().map(PathBuf::as_path).collect();
    inputs.extend(a.base.as_deref());
    crate::output::refuse_overwriting_inputs(out, &inputs)?;
    if out.exists() && !a.force {
        return Err(format!(
            "{}: exists; pass --force to overwrite it",
            out.display()
        ));
    }
    let mut doc = base_document(a.base.as_deref(), out)?;
    let mut route_from: Option<&Path> = None;
    let mut summary = Vec::new();
    for input in &a.inputs {
        let got = read_input(input)?;
        if !got.route.is_empty() {
            if let Some(first) = route_from {
                return Err(format!(
                    "{}: a second route (the first came from {}): import one mission at a time",
                    input.display(),
                    first.display()
                ));
            }
            route_from = Some(input);
        }
        summary.push(describe(input, &got));
        add_features(&mut doc, got, input)?;
    }
    let text = serde_json::to_string_pretty(&doc).map_err(|e| e.to_string())? + "\n";
    crate::scenario::parse(&text, out).map_err(|e| {
        let names: Vec<String> = inputs.iter().map(|p| p.display().to_string()).collect();
        format!(
            "the scenario assembled from {} is not valid, nothing was written: {e} (each \
             feature's `comment` names the input it came from)",
            names.join(", ")
        )
    })?;
    crate::output::write_atomically(out, text.as_bytes())?;
    Ok(format!("{} -> {}", summary.join("; "), out.display()))
}

/// The base scenario as JSON: the file given, or the roadmap template without its features.
fn base_document(base: Option<&Path>, out: &Path) -> Result<Value, String> {
    let Some(base) = base else {
        let text = crate::init::template(Mode::Roadmap, None, out)?;
        let mut doc: Value = serde_json::from_str(&text).map_err(|e| e.to_string())?;
        let name = out.file_stem().map(|s| s.to_string_lossy().into_owned());
        doc["name"] = json!(name.unwrap_or_else(|| "imported".into()));
        doc["description"] = json!(
            "Imported by skyroute import onto the roadmap template: check the vehicle and the \
             planner before building."
        );
        doc["features"] = json!([]);
        return Ok(doc);
    };
    let text = read_bounded(base)?;
    // The base must itself be a valid scenario: its errors are named against its own file.
    crate::scenario::parse(&text, base).map_err(|e| e.to_string())?;
    let mut doc: Value =
        serde_json::from_str(&text).map_err(|e| format!("{}: {e}", base.display()))?;
    rebase_dem(&mut doc, base, out);
    Ok(doc)
}

/// A base's relative `terrain.dem` path is relative to the base's folder; written next to the
/// output it would point elsewhere, so it becomes the absolute path when the folders differ.
fn rebase_dem(doc: &mut Value, base: &Path, out: &Path) {
    let folder = |p: &Path| {
        let f = p.parent().unwrap_or(Path::new(""));
        std::fs::canonicalize(if f.as_os_str().is_empty() {
            Path::new(".")
        } else {
            f
        })
        .ok()
    };
    let Some(dem) = doc["terrain"]["dem"].as_str().map(PathBuf::from) else {
        return;
    };
    if dem.is_relative() && folder(base) != folder(out) {
        if let Some(abs) = folder(base).map(|f| f.join(&dem)) {
            doc["terrain"]["dem"] = json!(abs.display().to_string());
        }
    }
}

/// The text of `path`, at most [`MAX_INPUT_BYTES`].
fn read_bounded(path: &Path) -> Result<String, String> {
    use std::io::Read;
    let mut bytes = Vec::new();
    std::fs::File::open(path)
        .and_then(|f| f.take(MAX_INPUT_BYTES + 1).read_to_end(&mut bytes))
        .map_err(|e| format!("{}: {e}", path.display()))?;
    if bytes.len() as u64 > MAX_INPUT_BYTES {
        return Err(format!(
            "{}: more than {MAX_INPUT_BYTES} bytes, import's limit",
            path.display()
        ));
    }
    String::from_utf8(bytes).map_err(|e| format!("{}: not UTF-8 text: {e}", path.display()))
}

/// Reads one input by its extension.
fn read_input(path: &Path) -> Result<Imported, String> {
    let ext = path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase())
        .unwrap_or_default();
    let file = path.display().to_string();
    match ext.as_str() {
        "kml" => kml::zones(&read_bounded(path)?, &file),
        "plan" => qgc_plan::read(&read_bounded(path)?, &file),
        _ => Err(format!(
            "{file}: import reads KML (.kml) and QGroundControl plans (.plan), not {:?}",
            ext
        )),
    }
}

/// One line of the summary for an input.
fn describe(path: &Path, got: &Imported) -> String {
    let mut s = format!("{}: {} zone(s)", path.display(), got.zones.len());
    if !got.route.is_empty() {
        s += &format!(", a route of {} positions", got.route.len());
    }
    if !got.skipped.is_empty() {
        s += &format!(" (left out: {})", got.skipped.join(", "));
    }
    s
}

/// Adds an input's zones and route to the scenario document; names that the document already
/// uses get a suffix ` (2)`, ` (3)`, ….
fn add_features(doc: &mut Value, got: Imported, input: &Path) -> Result<(), String> {
    let features = doc["features"]
        .as_array_mut()
        .ok_or("the base scenario has no features array")?;
    // The base start's other properties (a landmark start's dist_m) pass to the imported one.
    let mut start_extra = Map::new();
    if !got.route.is_empty() {
        if let Some(props) = features
            .iter()
            .find(|f| f["properties"]["kind"] == "start")
            .and_then(|f| f["properties"].as_object())
        {
            start_extra = props.clone();
            for k in ["kind", "name", "heading_deg"] {
                start_extra.remove(k);
            }
        }
        features.retain(|f| {
            !matches!(
                f["properties"]["kind"].as_str(),
                Some("start" | "waypoint" | "goal")
            )
        });
    }
    let mut names: HashSet<String> = features
        .iter()
        .filter_map(|f| f["properties"]["name"].as_str().map(str::to_owned))
        .collect();
    let mut unique = |name: &str| {
        let mut candidate = name.to_owned();
        let mut k = 2;
        while !names.insert(candidate.clone()) {
            candidate = format!("{name} ({k})");
            k += 1;
        }
        candidate
    };
    let from = format!("imported from {}", input.display());
    for z in got.zones {
        let geometry = match z.polygons.len() {
            1 => json!({"type": "Polygon", "coordinates": rings_json(&z.polygons[0])}),
            _ => json!({
                "type": "MultiPolygon",
                "coordinates": z.polygons.iter().map(|p| rings_json(p)).collect::<Vec<_>>(),
            }),
        };
        let mut props = Map::new();
        props.insert("kind".into(), json!("no_fly"));
        props.insert("name".into(), json!(unique(&z.name)));
        features.push(
            json!({"type": "Feature", "comment": from, "geometry": geometry, "properties": props}),
        );
    }
    let n = got.route.len();
    for (k, (name, p)) in got.route.iter().enumerate() {
        let kind = match k {
            0 => "start",
            _ if k + 1 == n => "goal",
            _ => "waypoint",
        };
        let mut props = Map::new();
        props.insert("kind".into(), json!(kind));
        props.insert("name".into(), json!(unique(name)));
        if let (0, Some((_, next))) = (k, got.route.get(1)) {
            props.extend(start_extra.clone());
            // The start needs a heading: towards the next position.
            let h = qgc_plan::bearing_deg(*p, *next);
            props.insert("heading_deg".into(), json!((h * 1e6).round() / 1e6));
        }
        features.push(json!({
            "type": "Feature",
            "comment": from,
            "geometry": {"type": "Point", "coordinates": [p.0, p.1]},
            "properties": props,
        }));
    }
    Ok(())
}

/// Rings as GeoJSON coordinates.
fn rings_json(rings: &[Vec<(f64, f64)>]) -> Value {
    json!(rings
        .iter()
        .map(|r| r
            .iter()
            .map(|&(lon, lat)| vec![lon, lat])
            .collect::<Vec<_>>())
        .collect::<Vec<_>>())
}
