//! Every scenario's network image is byte-identical to the recorded one: each
//! `scenarios/*.geojson` is built through `skyroute_prep::build::build` with the default
//! options (babel-I and babel-I-bridged with hull repair, as `skyroute build --hull-repair`), and the image's
//! length and the CRC-32 in its header (which covers the whole image) are compared with
//! `host-tests/expected-images.txt`. Full tier only (it builds every scenario).
//!
//! To regenerate the file after a deliberate format change:
//! `SKYROUTE_TIER=full SKYROUTE_RECORD_IMAGES=1 cargo test -p host-tests --test modes network_images`.

use host_tests::full_tier_only;
use host_tests::scenarios::{all_scenario_names, built};
use skyroute::Network;
use std::path::PathBuf;

fn expected_path() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("expected-images.txt")
}

const HEADER: &str = "\
# The network image of every scenario in scenarios/*.geojson, built by
# skyroute_prep::build::build with the default BuildOptions (babel-I and babel-I-bridged with
# hull repair, as `skyroute build --hull-repair`):
#   name  bytes  crc32 (hex, the header's image_crc, covering the whole image)
# Checked by the full tier (host-tests/tests/modes/network_images.rs). A change here is only
# allowed together with a network format change (docs/FORMAT.md) or a deliberate change of
# the ground tool's output, said so in the same commit. Regenerate with
#   SKYROUTE_TIER=full SKYROUTE_RECORD_IMAGES=1 cargo test -p host-tests --test modes network_images
";

/// `(name, bytes, crc)` of every scenario, built now.
fn measured() -> Vec<(String, usize, u32)> {
    all_scenario_names()
        .into_iter()
        .map(|name| {
            let b = built(&name);
            let net = Network::from_bytes(&b.bytes)
                .unwrap_or_else(|e| panic!("{name}: the built image does not load: {e}"));
            let crc = net.header().image_crc;
            (name, b.bytes.len(), crc)
        })
        .collect()
}

fn parse(text: &str) -> Vec<(String, usize, u32)> {
    text.lines()
        .map(str::trim)
        .filter(|l| !l.is_empty() && !l.starts_with('#'))
        .map(|l| {
            let f: Vec<&str> = l.split_whitespace().collect();
            assert_eq!(f.len(), 3, "expected-images.txt: bad line {l:?}");
            let bytes = f[1].parse().expect("bytes");
            let crc = u32::from_str_radix(f[2].trim_start_matches("0x"), 16).expect("crc in hex");
            (f[0].to_owned(), bytes, crc)
        })
        .collect()
}

#[test]
fn every_scenario_builds_the_recorded_image() {
    if !full_tier_only(
        "network_images::every_scenario_builds_the_recorded_image",
        "builds every scenario",
    ) {
        return;
    }
    let got = measured();
    if std::env::var_os("SKYROUTE_RECORD_IMAGES").is_some() {
        let mut text = HEADER.to_owned();
        for (name, bytes, crc) in &got {
            text += &format!("{name:<20} {bytes:>8}  {crc:08x}\n");
        }
        std::fs::write(expected_path(), text).expect("writes expected-images.txt");
        println!(
            "recorded {} images in {}",
            got.len(),
            expected_path().display()
        );
        return;
    }
    let text = std::fs::read_to_string(expected_path()).expect("expected-images.txt is readable");
    let want = parse(&text);
    let mut problems = Vec::new();
    for (name, bytes, crc) in &got {
        match want.iter().find(|w| &w.0 == name) {
            None => problems.push(format!(
                "{name}: not recorded ({bytes} bytes, crc {crc:08x})"
            )),
            Some((_, wb, wc)) if (wb, wc) != (bytes, crc) => problems.push(format!(
                "{name}: {bytes} bytes, crc {crc:08x}; recorded {wb} bytes, crc {wc:08x}"
            )),
            Some(_) => println!("{name}: {bytes} bytes, crc {crc:08x}: as recorded"),
        }
    }
    for (name, _, _) in &want {
        if !got.iter().any(|g| &g.0 == name) {
            problems.push(format!("{name}: recorded, but no scenarios/{name}.geojson"));
        }
    }
    assert!(
        problems.is_empty(),
        "network images differ from host-tests/expected-images.txt (a change is only allowed \
         with a format change; see the file's header):\n{}",
        problems.join("\n")
    );
}
