//! `sr_status_name` against the header: every status's name is the enumerator the header
//! declares with the same number, and the header declares no other.

use skyroute_ffi::{sr_status_name, SrStatus};
use std::ffi::CStr;

const HEADER: &str = include_str!("../include/skyroute.h");

#[test]
fn every_status_name_is_the_header_enumerator_of_its_number() {
    let declared: Vec<&str> = HEADER
        .lines()
        .map(str::trim)
        .filter(|l| l.starts_with("SR_STATUS_") && l.ends_with(','))
        .collect();
    let mut named = 0;
    for code in -1..1000 {
        // SAFETY: `sr_status_name` returns a static NUL-terminated string for any number.
        let name = unsafe { CStr::from_ptr(sr_status_name(code)) }
            .to_str()
            .expect("ASCII");
        match SrStatus::from_code(code) {
            Some(status) => {
                assert_eq!(status.name().to_str().expect("ASCII"), name);
                let line = format!("{name} = {code},");
                assert!(
                    declared.contains(&line.as_str()),
                    "{line} is not in the header"
                );
                named += 1;
            }
            None => assert_eq!(name, "SR_STATUS_UNKNOWN", "code {code}"),
        }
    }
    assert_eq!(
        named,
        declared.len(),
        "the header declares statuses the library has not"
    );
}
