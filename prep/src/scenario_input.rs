//! Reading a scenario file for a command: a file that is recognisably another format (a DEM,
//! a GeoTIFF, KML, a network image) is named as what it is rather than reported as invalid
//! JSON.

use crate::scenario;
use std::path::Path;

/// Reads the scenario `path` (as [`scenario::load_in_mode`]); a file that does not parse and
/// is recognisably another format (a DEM, a GeoTIFF, KML, a network image) is named as what it
/// is rather than reported as invalid JSON.
pub fn read_scenario(
    path: &Path,
    options: &scenario::ParseOptions,
    mode: Option<scenario::Mode>,
) -> Result<scenario::Scenario, Box<dyn std::error::Error>> {
    scenario::load_in_mode(path, options, mode).map_err(|e| match foreign_format(path) {
        Some(what) => format!(
            "{}: this is {what}, not a scenario: scenarios are GeoJSON FeatureCollections",
            path.display()
        )
        .into(),
        None => e.into(),
    })
}

/// What the first bytes of `path` say it is, when it is a format the ground tool is often
/// given by mistake for a scenario.
fn foreign_format(path: &Path) -> Option<&'static str> {
    use std::io::Read;
    let mut head = Vec::with_capacity(512);
    std::fs::File::open(path)
        .ok()?
        .take(512)
        .read_to_end(&mut head)
        .ok()?;
    if head.starts_with(b"II*\0") || head.starts_with(b"MM\0*") {
        return Some("a TIFF image (a GeoTIFF DEM belongs in the scenario's terrain.dem)");
    }
    if head.starts_with(b"\x89PNG") {
        return Some("a PNG image");
    }
    if head.starts_with(b"SKYR") {
        return Some("a skyroute network image (give the GeoJSON it was built from)");
    }
    let text = String::from_utf8_lossy(&head).to_ascii_lowercase();
    let text = text.trim_start_matches('\u{feff}').trim_start();
    if text.starts_with('<') {
        return Some(if text.contains("<kml") {
            "a KML document (convert it to GeoJSON)"
        } else {
            "an XML document"
        });
    }
    if text.starts_with("ncols") || text.starts_with("nrows") {
        return Some("an ESRI ASCII grid (a DEM belongs in the scenario's terrain.dem)");
    }
    None
}
