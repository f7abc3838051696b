//! Puts `../memory.x` (the STM32F405's flash and RAM) on the linker's search path for
//! cortex-m-rt's `link.x`, and checks that the generated fixture exists.

use std::path::PathBuf;

fn main() {
    let manifest = PathBuf::from(std::env::var_os("CARGO_MANIFEST_DIR").expect("cargo sets it"));
    let out = PathBuf::from(std::env::var_os("OUT_DIR").expect("cargo sets it"));
    let memory = manifest.join("../memory.x");
    std::fs::copy(&memory, out.join("memory.x"))
        .unwrap_or_else(|e| panic!("copying {}: {e}", memory.display()));
    println!("cargo:rustc-link-search={}", out.display());
    println!("cargo:rerun-if-changed={}", memory.display());
    println!("cargo:rerun-if-changed=build.rs");

    let terrain = std::env::var_os("CARGO_FEATURE_TERRAIN").is_some();
    let landmark = std::env::var_os("CARGO_FEATURE_LANDMARK").is_some();
    let dir = match (terrain, landmark) {
        (true, true) => panic!("the features `terrain` and `landmark` exclude each other"),
        (true, false) => "fixture-terrain",
        (false, true) => "fixture-landmark",
        (false, false) => "fixture",
    };
    for f in ["network.bin", "query.rs"].map(|f| format!("{dir}/{f}")) {
        let path = manifest.join(f);
        if !path.exists() {
            panic!(
                "{} is missing: generate the fixture first, e.g.\n  \
                 cargo run --release -p host-tests --bin firmware_fixture -- --synthetic \
                 firmware-example/fixture\n(from the repository root; scripts/test.sh does this \
                 for {dir}/)",
                path.display()
            );
        }
        println!("cargo:rerun-if-changed={}", path.display());
    }
}
