//! Niendorf et al.'s roadmap studies on a scenario (the urban mission by default), each printed
//! as a Markdown table for `docs/PAPERS.md`:
//!
//! 1. **CCC words**: the share of three-arc (RLR, LRL) Dubins edges among the edges whose
//!    endpoints are 0–1, 1–2, 2–3 and over 3 r_min apart (a CCC word can be the shortest only
//!    below 4 r_min), and the mission's length with CCC edges and without them
//!    (`planner.allow_ccc` false).
//! 2. **Neighbour radius** (the paper's figures 12–13): build time, edges and the mission's
//!    length for radii from 1 to 3.5 r_min.
//! 3. **Sample spacing** at 3 r_min: how dense the roadmap can be made within the paper's build
//!    time (180 s), and what the density buys in length, up to the host planner's capacity.
//!
//! Every mission is planned as `skyroute plan NETWORK --scenario SCENARIO` plans it (start,
//! waypoints and goal through the onboard core, free headings by the default rule), and again
//! with `--shortcuts greedy` for the second length. Times are
//! wall clock on the machine it runs on.
//!
//! `cargo run --release -p skyroute-prep --example niendorf_studies -- scenarios/niendorf-urban.geojson [spacings...]`
use skyroute::network::Network;
use skyroute::DubinsWord;
use skyroute_prep::build::{build, BuildOptions};
use skyroute_prep::mission::{plan_mission_with, MissionOptions, Shortcuts, PLANNER_STACK};
use skyroute_prep::scenario::{self, Scenario};
use std::time::Instant;

/// The host planner's edge capacity (`skyroute_prep::mission::HostPlanner`).
const HOST_EDGES: u32 = 262_144;

/// The paper's roadmap build time, seconds (Pentium 4).
const PAPER_BUILD_S: f64 = 180.0;

/// One built network and its mission.
struct Run {
    build_s: f64,
    vertices: u32,
    edges: u32,
    bytes: usize,
    /// The mission's length after post-processing with the best chain of shortcuts (the
    /// default), with the greedy pass, and as planned (the sum of its legs' searched lengths);
    /// `None` when it could not be planned (the reason is printed).
    length_m: Option<(f64, f64, f64)>,
    /// Seconds to plan the mission with the default post-processing.
    plan_s: f64,
}

fn run(s: &Scenario, options: &BuildOptions) -> Result<(Run, Vec<u8>), String> {
    let t = Instant::now();
    let built = build(s, options, &|_, _| {}).map_err(|e| e.to_string())?;
    let build_s = t.elapsed().as_secs_f64();
    let net = Network::from_bytes(&built.bytes).map_err(|e| format!("{e:?}"))?;
    let (vertices, edges) = (net.vertex_count(), net.edge_count());
    let frame = s.local_frame();
    let t = Instant::now();
    let mission = |shortcuts| {
        let options = MissionOptions {
            shortcuts,
            ..MissionOptions::default()
        };
        plan_mission_with(&built.bytes, s, &frame, &[], &options)
    };
    let best = (edges <= HOST_EDGES).then(|| mission(Shortcuts::Best));
    let plan_s = t.elapsed().as_secs_f64();
    let length_m = match best {
        Some(Ok(m)) => {
            let greedy = mission(Shortcuts::Greedy).map_or(f64::NAN, |g| g.length);
            let planned = m.legs.iter().map(|l| l.planned_length as f64).sum();
            Some((m.length, greedy, planned))
        }
        Some(Err(e)) => {
            eprintln!("mission not planned: {e}");
            None
        }
        None => None,
    };
    let r = Run {
        build_s,
        vertices,
        edges,
        bytes: built.bytes.len(),
        length_m,
        plan_s,
    };
    Ok((r, built.bytes))
}

fn length(r: &Run) -> String {
    r.length_m.map_or("—".into(), |(best, greedy, planned)| {
        format!("{best:.1} / {greedy:.1} ({planned:.1})")
    })
}

/// Per band of endpoint distance (0–1, 1–2, 2–3, over 3 r_min): (edges, CCC edges).
fn ccc_by_distance(bytes: &[u8]) -> [(u32, u32); 4] {
    let net = Network::from_bytes(bytes).expect("a network just built loads");
    let r = net.turn_radius();
    let mut bands = [(0u32, 0u32); 4];
    for e in 0..net.edge_count() {
        let Some((a, b, word)) = net.dubins_edge_ends(e) else {
            continue;
        };
        let band = ((b.position - a.position).norm() / r).min(3.0) as usize;
        if let Some(slot) = bands.get_mut(band) {
            slot.0 += 1;
            slot.1 += matches!(word, DubinsWord::Rlr | DubinsWord::Lrl) as u32;
        }
    }
    bands
}

fn pct(part: u32, whole: u32) -> f64 {
    100.0 * part as f64 / whole.max(1) as f64
}

fn ccc_study(s: &Scenario) {
    println!("\n### CCC words\n");
    println!("| network | edges | CCC edges | CCC share at 0–1 / 1–2 / 2–3 / over 3 r_min apart (edges in the band) | mission length, m: best shortcuts / greedy (as planned) | build (s) |");
    println!("|---|---:|---:|---|---:|---:|");
    for allow in [true, false] {
        let mut s = s.clone();
        s.planner.allow_ccc = Some(allow);
        let (r, bytes) = run(&s, &BuildOptions::default()).expect("build");
        let bands = ccc_by_distance(&bytes);
        let all: u32 = bands.iter().map(|b| b.0).sum();
        let ccc: u32 = bands.iter().map(|b| b.1).sum();
        let per: Vec<String> = bands
            .iter()
            .map(|&(n, c)| format!("{:.1} % ({n})", pct(c, n)))
            .collect();
        println!(
            "| {} | {all} | {ccc} ({:.1} %) | {} | {} | {:.2} |",
            if allow {
                "CSC and CCC"
            } else {
                "CSC only (`allow_ccc` false)"
            },
            pct(ccc, all),
            per.join(" / "),
            length(&r),
            r.build_s
        );
    }
}

fn radius_study(s: &Scenario, r_min: f64) {
    println!("\n### Neighbour radius (figures 12–13)\n");
    println!(
        "| radius | vertices | edges | build (s) | mission length, m: best shortcuts / greedy (as planned) | mission planned in (s) |"
    );
    println!("|---|---:|---:|---:|---:|---:|");
    for k in [1.0, 1.5, 2.0, 2.5, 3.0, 3.5] {
        let options = BuildOptions {
            neighbour_radius_m: Some((k * r_min) as f32),
            ..BuildOptions::default()
        };
        match run(s, &options) {
            Ok((r, _)) => println!(
                "| {k} r_min = {:.0} m | {} | {} | {:.2} | {} | {:.1} |",
                k * r_min,
                r.vertices,
                r.edges,
                r.build_s,
                length(&r),
                r.plan_s
            ),
            Err(e) => println!("| {k} r_min | refused: {e} | | | | |"),
        }
    }
}

fn spacing_study(s: &Scenario, r_min: f64, spacings: &[f32]) {
    println!("\n### Sample spacing at 3 r_min, within the paper's {PAPER_BUILD_S:.0} s\n");
    println!("| spacing (m) | vertices | edges | image (bytes) | build (s) | mission length, m: best shortcuts / greedy (as planned) | mission planned in (s) |");
    println!("|---:|---:|---:|---:|---:|---:|---:|");
    for &spacing in spacings {
        let options = BuildOptions {
            sample_spacing_m: Some(spacing),
            neighbour_radius_m: Some((3.0 * r_min) as f32),
            ..BuildOptions::default()
        };
        match run(s, &options) {
            Ok((r, _)) => {
                let note = if r.edges > HOST_EDGES {
                    format!("— (over the host planner's {HOST_EDGES} edges)")
                } else {
                    length(&r)
                };
                println!(
                    "| {spacing} | {} | {} | {} | {:.2} | {note} | {:.1} |",
                    r.vertices, r.edges, r.bytes, r.build_s, r.plan_s
                );
                if r.build_s > PAPER_BUILD_S {
                    break;
                }
            }
            Err(e) => {
                println!("| {spacing} | refused: {e} | | | | | |");
                break;
            }
        }
    }
}

fn main() {
    let mut args = std::env::args().skip(1);
    let path = args
        .next()
        .expect("usage: niendorf_studies SCENARIO [SPACING_M ...]");
    let mut spacings: Vec<f32> = args
        .map(|a| a.parse().expect("a spacing in metres"))
        .collect();
    if spacings.is_empty() {
        spacings = vec![50.0, 40.0, 35.0, 30.0, 25.0];
    }
    let s = scenario::load(path.as_ref()).expect("scenario");
    let r_min = s.vehicle.turn_radius_m();
    std::thread::Builder::new()
        .stack_size(PLANNER_STACK)
        .spawn(move || {
            println!("{} (r_min {r_min:.1} m)", s.name);
            ccc_study(&s);
            radius_study(&s, r_min);
            spacing_study(&s, r_min, &spacings);
        })
        .expect("thread")
        .join()
        .expect("the studies");
}
