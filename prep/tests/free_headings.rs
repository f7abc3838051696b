//! `plan --free-headings paper`: Niendorf et al.'s rule fixes a free waypoint's heading as the
//! one with the most clear out-edges. A waypoint 37 m west of a no-fly zone, with a 300 m turn
//! radius, has no clear way east, so the rule must not point it east; the default rule plans the
//! same mission too.

mod common;
use common::{ok, skyroute, stdout, TempDir};

/// The `skyroute init` template of `mode` in `dir`, with `edit.0` replaced by `edit.1`, and
/// its network built: their paths.
fn template_network(dir: &TempDir, mode: &str, edit: (&str, &str)) -> (String, String) {
    let sc = dir.file("s.geojson");
    ok(skyroute(&["init", &sc, "--mode", mode]), "init");
    if !edit.0.is_empty() {
        let text = std::fs::read_to_string(&sc)
            .unwrap()
            .replace(edit.0, edit.1);
        std::fs::write(&sc, text).unwrap();
    }
    let net = dir.file("n.bin");
    ok(skyroute(&["build", &sc, "-o", &net]), "build");
    (sc, net)
}

#[test]
fn the_papers_rule_turns_a_waypoint_beside_a_zone_away_from_it() {
    let dir = TempDir::new("free-headings");
    // The template's waypoint W1 moves next to the west side (lon 11.612) of zone Z1.
    let (sc, net) = template_network(&dir, "roadmap", ("[11.630, 48.112]", "[11.6115, 48.100]"));
    let route = dir.file("r.json");
    let o = ok(
        skyroute(&[
            "plan",
            &net,
            "--scenario",
            &sc,
            "--free-headings",
            "paper",
            "-o",
            &route,
        ]),
        "plan --free-headings paper",
    );
    let said = stdout(&o);
    let line = said
        .lines()
        .find(|l| l.contains("W1: heading"))
        .unwrap_or_else(|| panic!("no fixed heading for W1 in {said}"));
    let compass: f64 = line
        .split("heading ")
        .nth(1)
        .and_then(|r| r.split('°').next())
        .and_then(|d| d.parse().ok())
        .unwrap();
    let clear: usize = line
        .split(", ")
        .nth(1)
        .and_then(|r| r.split(' ').next())
        .and_then(|n| n.parse().ok())
        .unwrap();
    let from_east = (compass - 90.0)
        .rem_euclid(360.0)
        .min((90.0 - compass).rem_euclid(360.0));
    assert!(
        from_east > 60.0,
        "W1 heads {compass}°, toward the zone: {line}"
    );
    assert!(clear > 0, "{line}");
    ok(
        skyroute(&["plan", &net, "--scenario", &sc, "-o", &route]),
        "plan (default rule)",
    );
}

#[test]
fn the_papers_rule_is_refused_where_there_is_no_roadmap() {
    let dir = TempDir::new("free-headings-voronoi");
    let (sc, net) = template_network(&dir, "voronoi", ("", ""));
    let e = common::one_line_error(&skyroute(&[
        "plan",
        &net,
        "--scenario",
        &sc,
        "--free-headings",
        "paper",
        "-o",
        &dir.file("r.json"),
    ]));
    assert!(
        e.contains("--free-headings paper counts a roadmap's clear out-edges"),
        "{e}"
    );
    assert!(e.contains("voronoi network"), "{e}");
}
