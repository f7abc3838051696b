//! The DEM readers on arbitrary bytes: ESRI ASCII grids (as text) and GeoTIFF (the corpus is
//! the shipped DEM and small GeoTIFFs): an error naming the file, or a grid whose values match
//! its size; never a panic or an unbounded allocation.
#![no_main]

use libfuzzer_sys::fuzz_target;
use skyroute_prep::dem::{ascii, geotiff};
use std::path::Path;

fuzz_target!(|bytes: &[u8]| {
    let path = Path::new("fuzz.dem");
    let result = if geotiff::is_tiff(bytes) {
        geotiff::parse(bytes, path)
    } else if let Ok(text) = std::str::from_utf8(bytes) {
        ascii::parse(text, path)
    } else {
        return;
    };
    match result {
        Ok(dem) => assert!(!dem.values().is_empty()),
        Err(e) => assert!(e.to_string().starts_with("fuzz.dem")),
    }
});
