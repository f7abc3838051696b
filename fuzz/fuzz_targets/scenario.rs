//! The scenario parser on arbitrary text (and text near a real scenario: the corpus is the
//! shipped scenarios): an error naming the file, or a scenario whose checks hold; never a
//! panic, a hang or an unbounded allocation.
#![no_main]

use libfuzzer_sys::fuzz_target;
use std::path::Path;

fuzz_target!(|bytes: &[u8]| {
    let Ok(text) = std::str::from_utf8(bytes) else {
        return;
    };
    let path = Path::new("fuzz.geojson");
    match skyroute_prep::scenario::parse(text, path) {
        Ok(s) => {
            // What the parser promises of every accepted scenario.
            for z in &s.no_fly {
                assert!(
                    z.ring.len() >= 3,
                    "zone {:?} has {} vertices",
                    z.name,
                    z.ring.len()
                );
                assert!(z
                    .ring
                    .iter()
                    .all(|&(lon, lat)| lon.abs() <= 180.0 && lat.abs() <= 90.0));
            }
            assert!(s.waypoints.len() <= skyroute_prep::scenario::limits::MAX_WAYPOINTS);
        }
        Err(e) => assert!(e.to_string().starts_with("fuzz.geojson")),
    }
});
