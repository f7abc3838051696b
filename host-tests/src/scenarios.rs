//! The repository's scenarios (`scenarios/*.geojson`), loaded and built through the ground
//! tool's library once per process and cached: a test binary that needs babel-II-S in three
//! tests builds it once. Keyed by scenario name and the [`BuildOptions`]; the parse options
//! are fixed per scenario ([`parse_options`]).

use skyroute_prep::build::{build, BuildOptions, Built};
use skyroute_prep::scenario::{self, ParseOptions, Scenario};
use std::collections::HashMap;
use std::path::PathBuf;
use std::sync::{Arc, Mutex, OnceLock};
use std::time::Instant;

/// The repository's `scenarios/` folder.
pub fn scenarios_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../scenarios")
}

/// `scenarios/<name>.geojson`.
pub fn scenario_path(name: &str) -> PathBuf {
    scenarios_dir().join(format!("{name}.geojson"))
}

/// Every scenario in `scenarios/*.geojson`, by name (file stem), sorted.
pub fn all_scenario_names() -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(scenarios_dir())
        .expect("scenarios/ is readable")
        .filter_map(|e| {
            let p = e.ok()?.path();
            (p.extension()? == "geojson").then(|| p.file_stem()?.to_str().map(str::to_owned))?
        })
        .collect();
    names.sort();
    names
}

/// How a scenario is parsed: strict, except babel-I and its variant babel-I-bridged, whose
/// self-intersecting no-fly polygon (feature 1, Z2) is replaced by its convex hull, as
/// `skyroute build --hull-repair` does.
pub fn parse_options(name: &str) -> ParseOptions {
    ParseOptions {
        hull_self_intersecting_no_fly: matches!(name, "babel-I" | "babel-I-bridged"),
    }
}

/// A scenario, parsed once per process (with [`parse_options`]).
pub fn scenario(name: &str) -> &'static Scenario {
    static CACHE: OnceLock<Mutex<HashMap<String, &'static Scenario>>> = OnceLock::new();
    let mut map = CACHE.get_or_init(Default::default).lock().unwrap();
    map.entry(name.to_owned()).or_insert_with(|| {
        let s = scenario::load_with(&scenario_path(name), &parse_options(name))
            .unwrap_or_else(|e| panic!("scenario {name} loads: {e}"));
        Box::leak(Box::new(s))
    })
}

/// A scenario built with `options`, once per process: concurrent callers of the same key
/// wait for the one build. Prints the build time (seen with `--nocapture`).
pub fn built_with(name: &str, options: &BuildOptions) -> &'static Built {
    type Cell = Arc<OnceLock<&'static Built>>;
    static CACHE: OnceLock<Mutex<HashMap<String, Cell>>> = OnceLock::new();
    let key = format!("{name} {options:?}");
    let cell = CACHE
        .get_or_init(Default::default)
        .lock()
        .unwrap()
        .entry(key)
        .or_default()
        .clone();
    cell.get_or_init(|| {
        let s = scenario(name);
        let t = Instant::now();
        let b =
            build(s, options, &|_, _| {}).unwrap_or_else(|e| panic!("scenario {name} builds: {e}"));
        println!(
            "fixture: {name} built in {:.1} s ({} bytes)",
            t.elapsed().as_secs_f64(),
            b.bytes.len()
        );
        Box::leak(Box::new(b))
    })
}

/// A scenario built with the default options, once per process.
pub fn built(name: &str) -> &'static Built {
    built_with(name, &BuildOptions::default())
}
