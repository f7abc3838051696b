//! Arbitrary sequences of planner calls on valid networks of every mode: pop-ups added (with
//! arbitrary heights too) and removed with arbitrary floats, pop-up threats, weights, weathers,
//! rosette updates, altitudes and a three-dimensional roadmap's query altitudes, the pop-up
//! switch (announcements decided among a network's stored alternatives, the decided or an
//! arbitrary choice flown), queries with arbitrary poses and budgets, and the route's
//! altitudes read anywhere. Nothing may panic, a route found never counts more work than its
//! budget nor more than the documented worst case, a switch that fails adds no pop-up, and an
//! altitude read off a route is finite.
//!
//! The networks (`fuzz/networks/*.bin`, written by `scripts/fuzz-smoke.sh`; the directory is
//! `SKYROUTE_FUZZ_NETWORKS` when set) are loaded once per process: each input starts by
//! resetting the planner's in-flight state (pop-ups, threats, weather, rosettes, altitude,
//! weight) instead of reloading, so that large networks run at thousands of inputs a second.
#![no_main]

use arbitrary::Arbitrary;
use libfuzzer_sys::fuzz_target;
use skyroute::network::Mode;
use skyroute::planner::alternatives::{decide_stored, Announced};
use skyroute::planner::decision::DecisionLimits;
use skyroute::planner::{ThreatOrigin, VoronoiStorage, MAX_POPUP_VERTICES};
use skyroute::{Goal, Planner, Popup, Pose, Query, Search, Vec2};
use std::sync::{Mutex, OnceLock};

type FuzzPlanner = Planner<'static, 8192, 32768, 4, 512>;

/// A coordinate: most inside the network's extent (where routes exist), some raw floats
/// (NaN, infinities, huge values).
#[derive(Arbitrary, Debug, Clone, Copy)]
enum Coord {
    Inside(u16),
    Raw(f32),
}

#[derive(Arbitrary, Debug)]
enum Op {
    PopupCircle {
        x: Coord,
        y: Coord,
        r: f32,
        height: Option<f32>,
    },
    PopupPolygon {
        points: Vec<(Coord, Coord)>,
        height: Option<f32>,
    },
    QueryAltitudes(f32, f32),
    RouteAltitude(u16, f32),
    RemovePopup(u8),
    AddThreat {
        x: Coord,
        y: Coord,
        r: f32,
    },
    RemoveThreat(u8),
    Weight(f32),
    Weather(u32),
    Rosette {
        landmark: u32,
        qualities: Vec<f32>,
    },
    ClearRosette(u32),
    StartRange(f32),
    Altitude(f32, f32),
    Switch {
        announced: Vec<(u8, f32)>,
        limits: (f32, f32),
        choice: Option<Vec<u8>>,
    },
    Plan {
        sx: Coord,
        sy: Coord,
        heading: f32,
        gx: Coord,
        gy: Coord,
        goal_heading: Option<f32>,
        astar: bool,
        budget: Option<u64>,
    },
    PostProcess {
        best: bool,
        headings: u16,
        budget: Option<u64>,
    },
}

#[derive(Arbitrary, Debug)]
struct Input {
    network: u8,
    ops: Vec<Op>,
}

/// A loaded planner and its network's extent and defaults.
struct Loaded {
    planner: Box<FuzzPlanner>,
    lo: Vec2,
    hi: Vec2,
    altitude: Option<(f32, f32)>,
    weight: Option<f32>,
    landmarks: u32,
    /// A three-dimensional roadmap's query altitudes after a reset: vertex 0's, both ways.
    query_altitudes: Option<(f32, f32)>,
}

fn networks() -> &'static [Mutex<Loaded>] {
    static NETS: OnceLock<Vec<Mutex<Loaded>>> = OnceLock::new();
    NETS.get_or_init(|| {
        let dir = std::env::var("SKYROUTE_FUZZ_NETWORKS").unwrap_or_else(|_| "networks".into());
        let mut paths: Vec<_> = std::fs::read_dir(&dir)
            .unwrap_or_else(|e| panic!("{dir}: {e} (run scripts/fuzz-smoke.sh to write it)"))
            .filter_map(|e| e.ok().map(|e| e.path()))
            .filter(|p| p.extension().is_some_and(|x| x == "bin"))
            .collect();
        paths.sort();
        paths
            .iter()
            .map(|p| {
                let bytes: &'static [u8] = Box::leak(std::fs::read(p).unwrap().into_boxed_slice());
                let mut planner: Box<FuzzPlanner> = Box::new(Planner::new());
                let mode = skyroute::Network::from_bytes(bytes)
                    .unwrap_or_else(|e| panic!("{}: {e}", p.display()))
                    .mode();
                match mode {
                    Mode::Voronoi => {
                        let storage = Box::leak(Box::new(VoronoiStorage::new()));
                        planner.load_voronoi(bytes, storage)
                    }
                    Mode::Roadmap | Mode::Terrain | Mode::Landmark | Mode::Unknown(_) => {
                        planner.load(bytes)
                    }
                }
                .unwrap_or_else(|e| panic!("{}: {e}", p.display()));
                let (lo, hi) = planner.network().extent();
                let altitude = planner.altitude();
                let weight = planner.threat_weight();
                let landmarks = planner.network().landmark().map_or(0, |l| l.landmark_count);
                let query_altitudes = planner.network().vertex_altitude(0).map(|z| (z, z));
                Mutex::new(Loaded {
                    planner,
                    lo,
                    hi,
                    altitude,
                    weight,
                    landmarks,
                    query_altitudes,
                })
            })
            .collect()
    })
}

fn coord(c: Coord, lo: f32, hi: f32) -> f32 {
    match c {
        Coord::Inside(u) => lo + (hi - lo) * (u as f32 / u16::MAX as f32),
        Coord::Raw(x) => x,
    }
}

/// Back to the state after loading: no pop-ups or pop-up threats, weather 0, no rosette
/// overrides, the network's altitude and weight; on a three-dimensional roadmap, query
/// altitudes at vertex 0's.
fn reset(l: &mut Loaded) {
    let p = &mut l.planner;
    let ids: Vec<u8> = p.popups().map(|(id, _)| id).collect();
    for id in ids {
        p.remove_popup(id).unwrap();
    }
    let threats: Vec<u8> = p
        .threats()
        .iter()
        .filter_map(|t| match t.origin {
            ThreatOrigin::Popped(id) => Some(id),
            ThreatOrigin::Network(_) => None,
        })
        .collect();
    for id in threats {
        p.remove_threat(id).unwrap();
    }
    if l.landmarks > 0 {
        p.set_weather(0).unwrap();
        for lm in 0..l.landmarks {
            p.clear_rosette(lm);
        }
        if let Some(range) = p.network().landmark().map(|r| r.start_range_m) {
            let _ = p.set_start_range(range);
        }
    }
    if let Some((a, s)) = l.altitude {
        p.set_altitude(a, s).unwrap();
    }
    if let Some(k) = l.weight {
        p.set_threat_weight(k).unwrap();
    }
    if let Some((start, goal)) = l.query_altitudes {
        p.set_query_altitudes(start, goal).unwrap();
    }
}

fuzz_target!(|input: Input| {
    let nets = networks();
    if nets.is_empty() {
        return;
    }
    let mut guard = nets[input.network as usize % nets.len()].lock().unwrap();
    let l = &mut *guard;
    reset(l);
    let (lo, hi) = (l.lo, l.hi);
    let x = |c| coord(c, lo.x, hi.x);
    let y = |c| coord(c, lo.y, hi.y);
    let p = &mut l.planner;
    for op in input.ops.into_iter().take(64) {
        match op {
            Op::PopupCircle {
                x: cx,
                y: cy,
                r,
                height,
            } => {
                let circle = Popup::Circle {
                    centre: Vec2::new(x(cx), y(cy)),
                    radius: r,
                };
                let _ = p.add_popup_with_height(circle, height.unwrap_or(f32::INFINITY));
            }
            Op::PopupPolygon { points, height } => {
                let mut poly = heapless::Vec::<Vec2, MAX_POPUP_VERTICES>::new();
                for (px, py) in points.into_iter().take(MAX_POPUP_VERTICES) {
                    let _ = poly.push(Vec2::new(x(px), y(py)));
                }
                let polygon = Popup::Polygon(poly);
                let _ = p.add_popup_with_height(polygon, height.unwrap_or(f32::INFINITY));
            }
            Op::QueryAltitudes(start, goal) => {
                let _ = p.set_query_altitudes(start, goal);
            }
            Op::RouteAltitude(k, s) => {
                if let Some(z) = p.route_altitude_at(k as usize, s) {
                    assert!(z.is_finite(), "altitude {z} at {s} m into primitive {k}");
                }
            }
            Op::RemovePopup(id) => {
                let _ = p.remove_popup(id);
            }
            Op::AddThreat { x: tx, y: ty, r } => {
                let _ = p.add_threat(Vec2::new(x(tx), y(ty)), r);
            }
            Op::RemoveThreat(id) => {
                let _ = p.remove_threat(id);
            }
            Op::Weight(k) => {
                let _ = p.set_threat_weight(k);
            }
            Op::Weather(w) => {
                let _ = p.set_weather(w);
            }
            Op::Rosette {
                landmark,
                qualities,
            } => {
                let _ = p.update_rosette(landmark, &qualities);
            }
            Op::ClearRosette(lm) => {
                let _ = p.clear_rosette(lm);
            }
            Op::StartRange(range) => {
                let _ = p.set_start_range(range);
            }
            Op::Altitude(a, s) => {
                let _ = p.set_altitude(a, s);
            }
            Op::Switch {
                announced,
                limits,
                choice,
            } => {
                let announced: Vec<Announced> = announced
                    .into_iter()
                    .take(9)
                    .map(|(popup, appearance)| Announced { popup, appearance })
                    .collect();
                let limits = DecisionLimits {
                    time_max: limits.0,
                    fuel_max: limits.1,
                };
                let net = *p.network();
                let decided = decide_stored(&net, &announced, &limits);
                let choice = match (choice, decided) {
                    (Some(c), _) => c,
                    (None, Ok(d)) => d.choice.to_vec(),
                    (None, Err(_)) => continue,
                };
                let before = p.popups().count();
                match p.fly_alternatives(&announced, &choice) {
                    Ok(ids) => assert_eq!(p.popups().count(), before + ids.len()),
                    Err(e) => assert_eq!(p.popups().count(), before, "{e:?} added pop-ups"),
                }
            }
            Op::Plan {
                sx,
                sy,
                heading,
                gx,
                gy,
                goal_heading,
                astar,
                budget,
            } => {
                let query = Query {
                    start: Pose::new(x(sx), y(sy), heading),
                    goal: Goal {
                        position: Vec2::new(x(gx), y(gy)),
                        heading: goal_heading,
                    },
                    search: if astar {
                        Search::AStar
                    } else {
                        Search::Dijkstra
                    },
                };
                let bound = p.worst_case_work();
                let budget = budget.unwrap_or(bound);
                if let Ok(s) = p.plan(&query, budget) {
                    assert!(
                        s.work.total() <= budget,
                        "work {} over budget {budget}",
                        s.work.total()
                    );
                    assert!(
                        s.work.total() <= bound,
                        "work {} over the bound {bound}",
                        s.work.total()
                    );
                    assert!(s.length.is_finite());
                }
            }
            Op::PostProcess {
                best,
                headings,
                budget,
            } => {
                let budget = budget.unwrap_or(u64::MAX);
                let before = p.route_summary().map(|s| s.length);
                let cut = match best {
                    true => p.shortcut_best(budget),
                    false => p.shortcut(budget),
                };
                let smooth = p.smooth_headings(headings % 64, budget);
                for s in [cut, smooth].into_iter().flatten() {
                    assert!(s.work.total() <= budget, "post-processing over its budget");
                    assert!(s.length_after <= s.length_before + 1e-2 * (1.0 + s.length_before));
                    assert!(s.length_after.is_finite());
                }
                if let (Some(before), Some(after)) = (before, p.route_summary().map(|s| s.length)) {
                    assert!(
                        after <= before + 1e-2 * (1.0 + before),
                        "{before} -> {after}"
                    );
                }
            }
        }
    }
});
