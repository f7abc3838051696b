//! Puts the target's memory map on the linker's search path as `memory.x` for cortex-m-rt's
//! `link.x`: `../memory.x` (the STM32F405's flash and RAM), or with the `mps2-an500` feature
//! `memory-mps2-an500.x` (the larger target). Tells each binary where its fixture is
//! (`ROADMAP_FIXTURE`, `TERRAIN_FIXTURE`, `LANDMARK_FIXTURE`, `VORONOI_FIXTURE`: `fixture/`,
//! `fixture-terrain/` (`fixture-terrain-full/` on the larger target), `fixture-landmark/`,
//! `fixture-voronoi/`), or, when `SKYROUTE_FIXTURE_DIR` is set, that one directory for all of
//! them (`scripts/onboard-figures.sh` builds one scenario at a time that way).
//!
//! The fixtures are not this script's business: each binary `include!`s its own
//! (`src/bin/roadmap.rs` ← `fixture/`, `terrain.rs` ← `fixture-terrain/`, `landmark.rs` ←
//! `fixture-landmark/`, `voronoi.rs` ← `fixture-voronoi/`, `ruz.rs` ← `fixture-ruz/query.rs`),
//! rustc tracks those files, and a binary whose fixture has not been generated fails to compile naming the missing file, while
//! the others build.

use std::path::PathBuf;

fn main() {
    let manifest = PathBuf::from(std::env::var_os("CARGO_MANIFEST_DIR").expect("cargo sets it"));
    let out = PathBuf::from(std::env::var_os("OUT_DIR").expect("cargo sets it"));
    let large = std::env::var_os("CARGO_FEATURE_MPS2_AN500").is_some();
    let memory = manifest.join(if large {
        "memory-mps2-an500.x"
    } else {
        "../memory.x"
    });
    let terrain_fixture = if large {
        "fixture-terrain-full"
    } else {
        "fixture-terrain"
    };
    let one_dir = std::env::var_os("SKYROUTE_FIXTURE_DIR").map(PathBuf::from);
    for (name, dir) in [
        ("ROADMAP_FIXTURE", "fixture"),
        ("TERRAIN_FIXTURE", terrain_fixture),
        ("LANDMARK_FIXTURE", "fixture-landmark"),
        ("VORONOI_FIXTURE", "fixture-voronoi"),
    ] {
        let path = one_dir.clone().unwrap_or_else(|| manifest.join(dir));
        println!("cargo:rustc-env={name}={}", path.display());
    }
    println!("cargo:rerun-if-env-changed=SKYROUTE_FIXTURE_DIR");
    std::fs::copy(&memory, out.join("memory.x"))
        .unwrap_or_else(|e| panic!("copying {}: {e}", memory.display()));
    println!("cargo:rustc-link-search={}", out.display());
    println!("cargo:rerun-if-changed={}", memory.display());
    println!("cargo:rerun-if-changed=build.rs");
}
