//! The roadmap builder on the real `niendorf-urban` scenario: deterministic over thread counts,
//! parameters honoured, both collision checks compared. The default build is the process's
//! cached one (shared with `niendorf_clearance` and `network_images`); the further builds
//! (other thread counts, no CCC words, the discretised check) take about a second each, so
//! every test here runs in both tiers.

use host_tests::scenarios;
use skyroute::geometry::predicates::point_segment_distance;
use skyroute::network::write::ObstacleSpec;
use skyroute::{Network, Segment};
use skyroute_prep::build::{build, BuildOptions, Built};
use skyroute_prep::roadmap::{primitive_conflicts, Sagitta};
use skyroute_prep::scenario;
use std::path::PathBuf;

fn scenario_path(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../scenarios")
        .join(name)
}

fn build_with_threads(threads: usize, options: &BuildOptions) -> Built {
    let s = scenario::load(&scenario_path("niendorf-urban.geojson")).unwrap();
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    pool.install(|| build(&s, options, &|_, _| {})).unwrap()
}

#[test]
fn same_bytes_on_any_number_of_threads() {
    let one = build_with_threads(1, &BuildOptions::default());
    let three = build_with_threads(3, &BuildOptions::default());
    assert_eq!(one.bytes, three.bytes);
    assert!(one.roadmap.as_ref().unwrap().edges.len() > 6000);
}

#[test]
fn samples_keep_spacing_and_clearance_and_use_ccc_words() {
    let s = scenarios::scenario("niendorf-urban");
    let spacing = s.planner.sample_spacing_m.unwrap() as f32;
    let clearance = s.planner.clearance_m.unwrap() as f32;
    let built = scenarios::built("niendorf-urban");
    let v = &built.roadmap.as_ref().unwrap().vertices;
    for (i, a) in v.iter().enumerate() {
        for b in &v[i + 1..] {
            assert!(
                a.position.distance(b.position) >= spacing - 1e-3,
                "samples closer than the spacing"
            );
        }
        for o in &built.obstacles {
            if let ObstacleSpec::Polygon(p) = o {
                let inside =
                    skyroute::geometry::predicates::point_in_polygon(a.position, p.as_slice());
                let near = (0..p.len()).any(|k| {
                    point_segment_distance(a.position, &Segment::new(p[k], p[(k + 1) % p.len()]))
                        <= clearance
                });
                assert!(!inside && !near, "sample within clearance of a building");
            }
        }
    }
    let net = Network::from_bytes(&built.bytes).unwrap();
    let ccc = (0..net.edge_count())
        .filter(|&e| net.edge(e).unwrap().word.is_ccc())
        .count();
    assert!(ccc > 0, "with allow_ccc the roadmap uses some CCC words");
}

#[test]
fn ccc_words_can_be_excluded() {
    let s = scenarios::scenario("niendorf-urban");
    let mut no_ccc = s.clone();
    no_ccc.planner.allow_ccc = Some(false);
    let built = build(&no_ccc, &BuildOptions::default(), &|_, _| {}).unwrap();
    let net = Network::from_bytes(&built.bytes).unwrap();
    assert!((0..net.edge_count()).all(|e| !net.edge(e).unwrap().word.is_ccc()));
}

#[test]
fn exact_and_discretised_checks_are_both_reported() {
    let exact = scenarios::built("niendorf-urban");
    let discretised = build_with_threads(
        2,
        &BuildOptions {
            discretised: Some(Sagitta::Added),
            ..Default::default()
        },
    );
    let (e, d) = (
        exact.roadmap.as_ref().unwrap().edges.len(),
        discretised.roadmap.as_ref().unwrap().edges.len(),
    );
    let pairs = |b: &Built| {
        b.roadmap
            .as_ref()
            .unwrap()
            .edges
            .iter()
            .map(|x| (x.source, x.target))
            .collect::<std::collections::BTreeSet<_>>()
    };
    let (pe, pd) = (pairs(exact), pairs(&discretised));
    let unsafe_accepted = pd.difference(&pe).count();
    let safe_rejected = pe.difference(&pd).count();
    println!(
        "niendorf-urban edges accepted: exact {e}, discretised (arc step 40 m) {d}; \
         discretised accepts {unsafe_accepted} edges that violate the clearance and rejects {safe_rejected} that keep it"
    );
    assert_eq!(
        exact.roadmap.as_ref().unwrap().vertices,
        discretised.roadmap.as_ref().unwrap().vertices
    );
    assert_eq!(
        unsafe_accepted, 0,
        "the chord check with the sagitta margin is conservative"
    );
    assert!(
        d < e,
        "the exact check should accept edges the discretised one loses"
    );
}

#[test]
fn the_papers_discretised_reading_keeps_the_clearance_less_the_chord_error() {
    let s = scenarios::scenario("niendorf-urban");
    let added = build_with_threads(
        2,
        &BuildOptions {
            discretised: Some(Sagitta::Added),
            ..Default::default()
        },
    );
    let paper = build_with_threads(
        2,
        &BuildOptions {
            discretised: Some(Sagitta::InClearance),
            ..Default::default()
        },
    );
    let net = Network::from_bytes(&paper.bytes).unwrap();
    let (r, clearance) = (net.turn_radius(), net.clearance());
    let d = s.planner.arc_step_m.unwrap() as f32;
    // The largest deviation of a chord of length d from an arc of radius r.
    let f = r * (1.0 - (d / (2.0 * r)).cos());
    let mut within_clearance = 0;
    for e in 0..net.edge_count() {
        let prims: Vec<_> = net
            .edge_path(e)
            .unwrap()
            .primitives()
            .into_iter()
            .flatten()
            .collect();
        let conflicts = |m: f32| {
            prims
                .iter()
                .any(|p| paper.obstacles.iter().any(|o| primitive_conflicts(p, o, m)))
        };
        assert!(
            !conflicts(clearance - f - 0.01),
            "edge {e} comes within the clearance less f ({} m)",
            clearance - f
        );
        within_clearance += conflicts(clearance) as usize;
    }
    let (na, np) = (
        added.roadmap.as_ref().unwrap().edges.len(),
        paper.roadmap.as_ref().unwrap().edges.len(),
    );
    println!(
        "niendorf-urban, arc step {d} m, f = {f:.2} m: the chord error added to the clearance \
         accepts {na} edges; counted in it (the paper's reading) {np}, of which \
         {within_clearance} come within the {clearance} m clearance (none within {:.2} m)",
        clearance - f
    );
    assert!(
        np >= na,
        "the smaller margin accepts fewer edges: {np} < {na}"
    );
}
