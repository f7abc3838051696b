//! Terrain mode end to end on the real Jacksboro DEM (Medeiros & da Silva): scenario → ground
//! build → network bytes → onboard load → turn-feasible search → route, and every route checked
//! independently against the raw DEM (`raw_dem`): sampled densely along its lines and arcs and
//! across its whole clearance band, each sample mapped back to longitude/latitude and looked up
//! in the DEM's own cells. Also: other altitudes (built for, and set in flight), random
//! start–goal pairs, the counted work against the documented bound, the cells per arc check
//! against the paper's Table 4, and bad inputs.

use crate::raw_dem::{raw_navigable, route_violations};
use host_tests::{full_tier_only, scenarios, Rng};
use skyroute::network::format::ProvenanceRecord;
use skyroute::planner::{Goal, PlanError, PlannerConfig, Query, QueryField, Search, TurnRule};
use skyroute::{LoadError, Network, Planner, Pose, Primitive, Vec2};
use skyroute_prep::build::{build, local, local_heading, BuildOptions, Built};
use skyroute_prep::dem::{self, Dem};
use skyroute_prep::frame::LocalFrame;
use skyroute_prep::mission::TERRAIN_CONFIG;
use skyroute_prep::scenario::{self, Scenario};
use std::path::PathBuf;
use std::time::Instant;

/// A host planner with room for the Jacksboro networks' search states: under the paper's turn
/// rule one per transition (2 223 215 with a 700 m level), about 86 MB.
type TerrainPlanner<'n> = Planner<'n, 4194304, 131072, 4, 1024>;

/// Sample spacing along the route, and the most distance between lines across it, metres
/// (below the smallest DEM cell side, 74.4 m).
const STEP: f64 = 5.0;
const ACROSS: f64 = 40.0;

fn scenario_at(altitude: Option<f64>) -> Scenario {
    let path =
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../scenarios/medeiros-jacksboro.geojson");
    let mut s = scenario::load(&path).unwrap();
    if let Some(a) = altitude {
        s.terrain.as_mut().unwrap().altitude_m = a;
    }
    s
}

/// The network for `s`: the process's cached medeiros-jacksboro build when `s` is the scenario
/// as stored (shared by the tests here and `network_images`), else a build of its own.
fn built(s: &Scenario) -> Built {
    if s == scenarios::scenario("medeiros-jacksboro") {
        return scenarios::built("medeiros-jacksboro").clone();
    }
    build(s, &BuildOptions::default(), &|_, _| {}).unwrap()
}

/// The network with a second altitude level, 700 m, for descending in flight.
fn built_with_700_m_level(s: &Scenario) -> Built {
    let options = BuildOptions {
        extra_altitudes_m: vec![700.0],
        ..BuildOptions::default()
    };
    build(s, &options, &|_, _| {}).unwrap()
}

/// Runs `f` on a thread with a stack large enough for planners built on it.
fn with_big_stack(f: impl FnOnce() + Send + 'static) {
    std::thread::Builder::new()
        .stack_size(512 << 20)
        .spawn(f)
        .unwrap()
        .join()
        .unwrap();
}

fn planner(bytes: &[u8]) -> Box<TerrainPlanner<'_>> {
    let mut p: Box<TerrainPlanner<'_>> = Box::new(Planner::new());
    p.load(bytes).unwrap();
    p.set_config(TERRAIN_CONFIG);
    p
}

/// [`planner`] under `turn_rule`.
fn planner_with(bytes: &[u8], turn_rule: TurnRule) -> Box<TerrainPlanner<'_>> {
    let mut p = planner(bytes);
    p.set_config(PlannerConfig {
        turn_rule,
        ..TERRAIN_CONFIG
    });
    p
}

fn endpoints(s: &Scenario, frame: &LocalFrame) -> (Pose, Vec2) {
    let st = s.start.as_ref().unwrap();
    let g = s.goal.as_ref().unwrap();
    let start = Pose {
        position: local(frame, st.lon, st.lat),
        heading: local_heading(frame, st.lon, st.lat, st.heading_deg.unwrap()),
    };
    (start, local(frame, g.lon, g.lat))
}

/// The route is one connected, tangent-continuous curve from the start pose to the goal, with
/// arcs of the turn radius.
fn check_shape(route: &[Primitive], start: &Pose, goal: &Goal, radius: f32) {
    let first = route.first().unwrap().pose_at(0.0);
    assert!(first.position.distance(start.position) < 0.05);
    assert!(skyroute::geometry::wrap_to_pi(first.heading - start.heading).abs() < 1e-3);
    for w in route.windows(2) {
        let (a, b) = (w[0].pose_at(w[0].length()), w[1].pose_at(0.0));
        assert!(a.position.distance(b.position) < 0.05, "gap {a:?} {b:?}");
        assert!(
            skyroute::geometry::wrap_to_pi(a.heading - b.heading).abs() < 2e-3,
            "kink {a:?} {b:?}"
        );
    }
    for p in route {
        if let Primitive::Arc(a) = p {
            assert!((a.radius - radius).abs() < 1e-3 * radius);
        }
    }
    let last = route.last().unwrap();
    let end = last.pose_at(last.length());
    assert!(end.position.distance(goal.position) < 0.1, "ends {end:?}");
    if let Some(h) = goal.heading {
        assert!(skyroute::geometry::wrap_to_pi(end.heading - h).abs() < 2e-3);
    }
}

/// Checks `route` against the raw DEM below `threshold` with the full band (half the wingspan
/// plus the clearance) and with half the wingspan only; returns the samples looked up.
fn check_against_dem(
    route: &[Primitive],
    dem: &Dem,
    frame: &LocalFrame,
    threshold: f64,
    widen: f64,
    half_wingspan: f64,
) -> u64 {
    let mut samples = 0;
    for w in [widen, half_wingspan] {
        let c = route_violations(route, dem, frame, threshold, w, STEP, ACROSS);
        assert_eq!(
            c.violations,
            0,
            "band ±{w} m, threshold {threshold} m: {} of {} samples over blocked cells; first {}",
            c.violations,
            c.samples,
            c.first.unwrap()
        );
        samples += c.samples;
    }
    samples
}

fn dem_of(s: &Scenario) -> Dem {
    dem::load(&s.terrain.as_ref().unwrap().dem).unwrap()
}

/// Plans P → Q on a network built for `altitude` and checks the route against the raw DEM.
fn plan_scenario_at(altitude: f64) {
    let s = scenario_at(Some(altitude));
    let t0 = Instant::now();
    let b = built(&s);
    let build_time = t0.elapsed();
    let dem = dem_of(&s);
    let t = s.terrain.as_ref().unwrap().clone();
    let widen = b.terrain.as_ref().unwrap().widen_m as f64;
    let bytes = b.bytes.clone();
    let frame = b.frame;
    let wingspan = s.vehicle.wingspan_m;
    let (start, goal_position) = endpoints(&s, &frame);
    with_big_stack(move || {
        let mut p = planner(&bytes);
        let goal = Goal {
            position: goal_position,
            heading: None,
        };
        let q = Query {
            start,
            goal,
            search: Search::Dijkstra,
        };
        let t1 = Instant::now();
        let summary = p.plan(&q, u64::MAX).unwrap();
        let plan_time = t1.elapsed();
        check_shape(p.route(), &start, &goal, p.network().turn_radius());
        let samples = check_against_dem(
            p.route(),
            &dem,
            &frame,
            t.altitude_m - t.safety_height_m,
            widen,
            0.5 * wingspan,
        );
        let stats = p.arc_check_stats();
        let chord = start.position.distance(goal.position);
        eprintln!(
            "altitude {altitude} m: network {} nodes, {} edges, {} bytes (built in {build_time:.2?}); \
             route {:.1} m (chord {chord:.1} m), {} primitives, {} network edges, planned in \
             {plan_time:.2?}, work {} (bound {}); arcs checked {}, cells {} (most {} per arc); \
             {samples} raw DEM samples clear",
            p.network().vertex_count(),
            p.network().edge_count(),
            bytes.len(),
            summary.length,
            summary.primitives,
            summary.network_edges,
            summary.work.total(),
            p.worst_case_work(),
            stats.arcs,
            stats.cells,
            stats.most_cells
        );
        assert!(summary.length >= chord);
        assert!(summary.work.total() <= p.worst_case_work());
        assert!(stats.most_cells <= p.terrain_bound_inputs().cells_per_turn);
    });
}

#[test]
fn jacksboro_route_at_750_m_is_clear_of_the_raw_dem() {
    plan_scenario_at(750.0);
}

#[test]
fn jacksboro_routes_at_850_and_1000_m_are_clear_of_the_raw_dem() {
    plan_scenario_at(850.0);
    plan_scenario_at(1000.0);
}

/// The raw DEM's navigable cells below `threshold` in 8-connected components (a label per cell,
/// 0 for blocked cells): two points in different components have no route at all, whatever the
/// planner; a route planner that must also keep a clearance band and fly turns of a minimum
/// radius can connect fewer pairs than share a component.
///
/// With `band > 0` a cell counts as free only if no blocked (or missing) cell's centre lies
/// within `band` metres of its centre (cell sides `ew` × `ns` metres): the free space eroded by
/// the clearance band, a fairer reference for what a planner that keeps the band can connect.
fn components(dem: &Dem, threshold: f64, band: f64, ew: f64, ns: f64) -> Vec<u32> {
    let (nc, nr) = (dem.ncols, dem.nrows);
    let raw = |c: i64, r: i64| {
        c >= 0
            && r >= 0
            && dem
                .elevation_at(c as usize, r as usize)
                .is_some_and(|e| (e as f64) < threshold)
    };
    let (kx, ky) = ((band / ew).ceil() as i64, (band / ns).ceil() as i64);
    let free = |c: usize, r: usize| {
        let (c, r) = (c as i64, r as i64);
        (-ky..=ky).all(|dr| {
            (-kx..=kx)
                .all(|dc| (dc as f64 * ew).hypot(dr as f64 * ns) > band || raw(c + dc, r + dr))
        })
    };
    let mut label = vec![0u32; nc * nr];
    let mut next = 0;
    for start in 0..nc * nr {
        if label[start] != 0 || !free(start % nc, start / nc) {
            continue;
        }
        next += 1;
        label[start] = next;
        let mut stack = vec![start];
        while let Some(i) = stack.pop() {
            let (c, r) = ((i % nc) as i64, (i / nc) as i64);
            for (dc, dr) in [
                (-1, -1),
                (0, -1),
                (1, -1),
                (-1, 0),
                (1, 0),
                (-1, 1),
                (0, 1),
                (1, 1),
            ] {
                let (x, y) = (c + dc, r + dr);
                if x < 0 || y < 0 || x >= nc as i64 || y >= nr as i64 {
                    continue;
                }
                let j = y as usize * nc + x as usize;
                if label[j] == 0 && free(x as usize, y as usize) {
                    label[j] = next;
                    stack.push(j);
                }
            }
        }
    }
    label
}

/// The component label of the raw DEM cell under local point `v` (0: blocked or outside).
fn component_at(dem: &Dem, frame: &LocalFrame, labels: &[u32], v: Vec2) -> u32 {
    let (lon, lat) = frame.to_geo(v.x as f64, v.y as f64);
    let u = ((lon - dem.xllcorner) / dem.cell_x).floor();
    let w = ((lat - dem.yllcorner) / dem.cell_y).floor();
    if u < 0.0 || w < 0.0 || u >= dem.ncols as f64 || w >= dem.nrows as f64 {
        return 0;
    }
    labels[w as usize * dem.ncols + u as usize]
}

/// Random start poses and goals (free and fixed headings) over navigable DEM cells, planned on
/// the 750 m network with a 700 m level at its own altitude and, in flight, at 700 m (more
/// terrain blocked, edges pruned by their stored elevation codes) and 900 m, under each turn
/// rule: every route found is clear of the raw DEM at the altitude in force; every count of
/// work is within the bound; the paper's rule routes every query the equal split routes, never
/// longer; the cells per arc check are compared with the paper's Table 4. Prints the
/// completeness figures of `docs/PAPERS.md` (pairs whose ends share a component of the eroded
/// free space, and how many of them each rule routes).
#[test]
fn random_queries_at_three_altitudes_are_clear_of_the_raw_dem() {
    if !full_tier_only(
        "terrain_plan::random_queries_at_three_altitudes_are_clear_of_the_raw_dem",
        "a full medeiros-jacksboro build with a 700 m level, 90 queries under two turn rules",
    ) {
        return;
    }
    let s = scenario_at(None);
    let b = built_with_700_m_level(&s);
    let dem = dem_of(&s);
    let widen = b.terrain.as_ref().unwrap().widen_m as f64;
    let frame = b.frame;
    let bytes = b.bytes.clone();
    let half_wingspan = 0.5 * s.vehicle.wingspan_m;
    with_big_stack(move || {
        let mut shared = planner_with(&bytes, TurnRule::SharedEqually);
        let mut paper = planner_with(&bytes, TurnRule::Paper);
        let grid = shared.network().terrain_grid().unwrap();
        let (w, h) = (grid.cell * grid.cols as f32, grid.cell * grid.rows as f32);
        let mut rng = Rng(7);
        let mut stats = Totals::default();
        let mut report = String::new();
        for (altitude, queries) in [(750.0f32, 40), (700.0, 25), (900.0, 25)] {
            shared.set_altitude(altitude, 100.0).unwrap();
            paper.set_altitude(altitude, 100.0).unwrap();
            let threshold = altitude as f64 - 100.0;
            let labels = components(&dem, threshold, 0.0, 74.5, 92.5);
            let eroded = components(&dem, threshold, widen, 74.5, 92.5);
            let mut c = Completeness::default();
            let mut tried = 0;
            while tried < queries {
                let mut point = || {
                    Vec2::new(
                        grid.origin.x + (0.1 + 0.8 * rng.unit() as f32) * w,
                        grid.origin.y + (0.1 + 0.8 * rng.unit() as f32) * h,
                    )
                };
                let (a, g) = (point(), point());
                let free = |v: Vec2| {
                    let (lon, lat) = frame.to_geo(v.x as f64, v.y as f64);
                    raw_navigable(&dem, lon, lat, threshold)
                };
                if !free(a) || !free(g) || a.distance(g) < 2000.0 {
                    continue;
                }
                tried += 1;
                let start = Pose {
                    position: a,
                    heading: (rng.unit() * std::f64::consts::TAU) as f32,
                };
                let goal = Goal {
                    position: g,
                    heading: (tried % 2 == 0).then(|| (rng.unit() * std::f64::consts::TAU) as f32),
                };
                let q = Query {
                    start,
                    goal,
                    search: Search::Dijkstra,
                };
                let same = |l: &[u32]| {
                    component_at(&dem, &frame, l, a) != 0
                        && component_at(&dem, &frame, l, a) == component_at(&dem, &frame, l, g)
                };
                let (same_component, wide_component) = (same(&labels), same(&eroded));
                c.connected += same_component as u32;
                c.wide += wide_component as u32;
                let check = |p: &mut TerrainPlanner<'_>, stats: &mut Totals| {
                    let result = p.plan(&q, u64::MAX);
                    if result.is_ok() {
                        // A route between raw components would cross blocked terrain.
                        assert!(
                            same_component,
                            "a route between separate raw DEM components"
                        );
                    }
                    if let Ok(summary) = result {
                        let d = (&dem, &frame, threshold, widen, half_wingspan);
                        check_random_route(p, &q, &summary, d, stats);
                    }
                    stats.arc_stats(p);
                    result.map(|summary| summary.length)
                };
                let by_shared = check(&mut shared, &mut stats);
                let by_paper = check(&mut paper, &mut stats);
                c.count(&by_shared, &by_paper, wide_component);
                if let Ok(l) = by_shared {
                    // The paper's rule is the weaker condition: it routes, no longer.
                    let l_paper = by_paper.as_ref().expect("the paper's rule routes it too");
                    assert!(*l_paper <= l * (1.0 + 1e-4) + 0.05, "{l_paper} > {l}");
                }
            }
            report += &format!(
                "altitude {altitude} m, {queries} random queries: {} have both ends in one raw \
                 DEM component, {} in one component of the free space eroded by the ±{widen} m \
                 band; of those {}, the equal split routes {} and the paper's rule {} (all \
                 queries: {} and {}; {} shorter under the paper's rule); refused (equal split) {:?}, (paper) {:?}\n",
                c.connected,
                c.wide,
                c.wide,
                c.ok_wide[0],
                c.ok_wide[1],
                c.ok[0],
                c.ok[1],
                c.shorter,
                c.refused[0],
                c.refused[1],
            );
            // A regression guard on completeness: at least half of the pairs that the eroded
            // free space connects get a route.
            assert!(c.ok_wide[0] * 2 >= c.wide, "too few routes at {altitude} m");
        }
        eprint!("{report}");
        eprintln!(
            "arc checks: {}, {} cells, {:.1} per check on average, {} most (bound {}; the \
             paper's Table 4: 384 at worst); work at most {:.4} of the bound; {} raw DEM \
             samples clear",
            stats.arcs,
            stats.cells,
            stats.cells as f64 / stats.arcs.max(1) as f64,
            stats.most_cells,
            shared.terrain_bound_inputs().cells_per_turn,
            stats.most_work_ratio,
            stats.samples
        );
    });
}

/// What the random queries checked, over both rules.
#[derive(Default)]
struct Totals {
    arcs: u64,
    cells: u64,
    most_cells: u64,
    samples: u64,
    most_work_ratio: f64,
}

impl Totals {
    /// Adds the last query's arc checks (each within the bound).
    fn arc_stats(&mut self, p: &TerrainPlanner<'_>) {
        let st = p.arc_check_stats();
        self.arcs += st.arcs;
        self.cells += st.cells;
        self.most_cells = self.most_cells.max(st.most_cells);
        assert!(st.most_cells <= p.terrain_bound_inputs().cells_per_turn);
    }
}

/// One altitude's completeness under the two rules (index 0 the equal split, 1 the paper's).
#[derive(Default)]
struct Completeness {
    connected: u32,
    wide: u32,
    ok: [u32; 2],
    ok_wide: [u32; 2],
    /// Routed by both, shorter (by over 0.5 m) under the paper's rule.
    shorter: u32,
    refused: [std::collections::BTreeMap<String, u32>; 2],
}

impl Completeness {
    fn count(
        &mut self,
        shared: &Result<f32, PlanError>,
        paper: &Result<f32, PlanError>,
        wide: bool,
    ) {
        if let (Ok(s), Ok(p)) = (shared, paper) {
            self.shorter += (*p < *s - 0.5) as u32;
        }
        for (k, r) in [shared, paper].into_iter().enumerate() {
            match r {
                Ok(_) => {
                    self.ok[k] += 1;
                    self.ok_wide[k] += wide as u32;
                }
                Err(e) => *self.refused[k].entry(format!("{e:?}")).or_default() += 1,
            }
        }
    }
}

/// A random query's route: its shape, clear of the raw DEM (`d`: the DEM, frame, threshold,
/// band and half wingspan), its work within the bound, and one unit less budget fails and
/// keeps the route.
fn check_random_route(
    p: &mut TerrainPlanner<'_>,
    q: &Query,
    summary: &skyroute::RouteSummary,
    d: (&Dem, &LocalFrame, f64, f64, f64),
    stats: &mut Totals,
) {
    let (dem, frame, threshold, widen, half_wingspan) = d;
    check_shape(p.route(), &q.start, &q.goal, p.network().turn_radius());
    stats.samples += check_against_dem(p.route(), dem, frame, threshold, widen, half_wingspan);
    let bound = p.worst_case_work();
    assert!(summary.work.total() <= bound);
    stats.most_work_ratio = stats
        .most_work_ratio
        .max(summary.work.total() as f64 / bound as f64);
    let before = p.route().to_vec();
    let short = p.plan(q, summary.work.total() - 1);
    assert!(matches!(short, Err(PlanError::BudgetExhausted { .. })));
    assert_eq!(p.route(), &before[..]);
}

#[test]
fn terrain_bad_inputs_are_refused() {
    let s = scenario_at(None);
    let b = built(&s);
    let frame = b.frame;
    let (start, goal_position) = endpoints(&s, &frame);
    let bytes = b.bytes.clone();
    // A blocked cell: the highest point of the DEM.
    let dem = dem_of(&s);
    let (mut best, mut at) = (f32::MIN, (0, 0));
    for r in 0..dem.nrows {
        for c in 0..dem.ncols {
            if let Some(e) = dem.elevation_at(c, r) {
                if e > best {
                    best = e;
                    at = (c, r);
                }
            }
        }
    }
    let (lon, lat) = dem.cell_centre_lonlat(at.0, at.1).unwrap();
    let peak = local(&frame, lon, lat);
    with_big_stack(move || {
        let mut p = planner(&bytes);
        let q = Query {
            start,
            goal: Goal {
                position: goal_position,
                heading: None,
            },
            search: Search::Dijkstra,
        };
        p.plan(&q, u64::MAX).unwrap();
        let kept = p.route().to_vec();
        let over_peak = Query {
            start: Pose {
                position: peak,
                heading: 0.0,
            },
            ..q
        };
        assert_eq!(
            p.plan(&over_peak, u64::MAX),
            Err(PlanError::OverBlockedTerrain {
                field: QueryField::Start
            })
        );
        let to_peak = Query {
            goal: Goal {
                position: peak,
                heading: None,
            },
            ..q
        };
        assert_eq!(
            p.plan(&to_peak, u64::MAX),
            Err(PlanError::OverBlockedTerrain {
                field: QueryField::Goal
            })
        );
        assert_eq!(
            p.set_altitude(f32::NAN, 100.0),
            Err(PlanError::InvalidAltitude)
        );
        assert_eq!(p.set_altitude(750.0, -1.0), Err(PlanError::InvalidAltitude));
        // Far too low: the start itself is blocked.
        p.set_altitude(300.0, 100.0).unwrap();
        assert!(matches!(
            p.plan(&q, u64::MAX),
            Err(PlanError::OverBlockedTerrain { .. })
        ));
        assert_eq!(p.route(), &kept[..]);
        // The network does not fit a planner with too few search states.
        let mut small: Box<Planner<'_, 4096, 65536, 4, 64>> = Box::new(Planner::new());
        assert!(matches!(
            small.load(&bytes),
            Err(LoadError::TooManySearchStates { .. })
        ));
    });
}

/// Damaged terrain networks are refused with the error naming the damage, even with a valid
/// checksum: a table code lowered under an edge, a table cut short.
#[test]
fn damaged_terrain_networks_are_refused() {
    let s = scenario_at(None);
    let b = built(&s);
    let bytes = b.bytes.clone();
    let net = Network::from_bytes(&bytes).unwrap();
    let t = *net.terrain().unwrap();
    let grid = net.terrain_grid().unwrap();
    // The table comes last but for the provenance records that close every body.
    let provenance = ProvenanceRecord::SIZE * net.provenance_count() as usize;
    let table = bytes.len() - provenance - (t.cols * t.rows) as usize;
    // The cell under the middle of edge 0's segment, lowered to 0.
    let e = net.edge(0).unwrap();
    let (a, z) = (
        net.vertex(e.source).unwrap().position,
        net.vertex(e.target).unwrap().position,
    );
    let mid = (a + z) * 0.5;
    let (c, r) = grid.cell_of(mid).unwrap();
    // Raise the cell first so that it is the edge's highest (the stored code then understates
    // nothing); then lower the stored code by editing the cell instead: set the cell *above*
    // the stored highest code, which the loader must notice.
    let stored = net.edge_highest_code(0).unwrap();
    let mut damaged = bytes.clone();
    damaged[table + (r * t.cols + c) as usize] = stored.saturating_add(1);
    let crc = skyroute::network::image_checksum(&damaged);
    let at = skyroute::network::format::Header::CHECKED_SIZE;
    damaged[at..at + 4].copy_from_slice(&crc.to_le_bytes());
    match Network::from_bytes(&damaged) {
        Err(LoadError::EdgeElevationUnderstated {
            stored: s,
            computed,
            ..
        }) => assert!(computed > s),
        other => panic!("expected EdgeElevationUnderstated, got {other:?}"),
    }
    // Truncated in the table.
    let cut = &bytes[..bytes.len() - 10];
    assert!(matches!(
        Network::from_bytes(cut),
        Err(LoadError::Truncated { .. })
    ));
}
