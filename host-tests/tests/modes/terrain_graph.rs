//! The terrain visibility graph (`skyroute_prep::terrain`, Medeiros & da Silva) on the real
//! Jacksboro DEM, checked against the raw DEM independently of the metric grid and the grid
//! traversal: every edge is sampled densely across its whole clearance band, every sample mapped
//! back to longitude/latitude with the frame and looked up in the DEM's own cells.

use crate::raw_dem::{raw_navigable, Check};
use host_tests::full_tier_only;
use rayon::prelude::*;
use skyroute_prep::dem::{self, Dem};
use skyroute_prep::frame::LocalFrame;
use skyroute_prep::scenario::{self, Scenario};
use skyroute_prep::terrain::{blocked_cells_at, build_terrain_graph, TerrainGraph, TerrainParams};
use std::path::PathBuf;
use std::sync::OnceLock;
use std::time::Instant;

fn load() -> (Scenario, Dem, LocalFrame) {
    let path =
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../scenarios/medeiros-jacksboro.geojson");
    let s = scenario::load(&path).unwrap();
    let dem = dem::load(&s.terrain.as_ref().unwrap().dem).unwrap();
    let frame = s.local_frame();
    (s, dem, frame)
}

/// Sample spacing along an edge and along the ends' half circles, metres.
const STEP: f64 = 5.0;
/// Most distance between the lines of samples across an edge's band, metres: with the
/// scenario's band of ±101.5 m, 5 lines 50.75 m apart (the sides, the centre line and the lines
/// half-way), closer than the smallest side of a DEM cell (74.4 m), so a blocked cell lying
/// wholly inside the band is hit too.
const ACROSS: f64 = 55.0;

/// Looks up points over the nodes and the first `max_edges` undirected edges of `g`, with a
/// band of half-width `w` metres, in the raw DEM; counts those over cells not navigable below
/// `threshold`.
fn raw_dem_violations(
    g: &TerrainGraph,
    dem: &Dem,
    frame: &LocalFrame,
    threshold: f64,
    w: f64,
    max_edges: usize,
) -> Check {
    let mut out = Check::default();
    // Nodes: the point and a ring of radius w around it.
    for (i, p) in g.nodes.iter().enumerate() {
        let (x, y) = (p.x as f64, p.y as f64);
        for k in 0..=64 {
            let (dx, dy) = if k == 64 {
                (0.0, 0.0)
            } else {
                let a = k as f64 * std::f64::consts::TAU / 64.0;
                (w * a.cos(), w * a.sin())
            };
            let (lon, lat) = frame.to_geo(x + dx, y + dy);
            out.samples += 1;
            if !raw_navigable(dem, lon, lat, threshold) {
                out.violations += 1;
                out.first.get_or_insert_with(|| {
                    format!("node {i} at ({x}, {y}): ({dx:.1}, {dy:.1}) from it")
                });
            }
        }
    }
    // Edges, each undirected edge once: STEP apart along the edge, on lines across it from −w
    // to +w at most ACROSS apart (the two sides of the band included), and STEP apart along
    // the half circles of radii w and w/2 that close the band at the ends.
    let lines = (2.0 * w / ACROSS).ceil() as i64;
    let arc_steps = (std::f64::consts::PI * w / STEP).ceil() as i64;
    let edges: Vec<_> = g
        .edges
        .iter()
        .filter(|e| e.0 < e.1)
        .take(max_edges)
        .collect();
    edges
        .par_iter()
        .map(|&&(i, j, len)| {
            let (a, b) = (g.nodes[i as usize], g.nodes[j as usize]);
            let (ax, ay) = (a.x as f64, a.y as f64);
            let (dx, dy) = (b.x as f64 - ax, b.y as f64 - ay);
            let l = dx.hypot(dy);
            assert!(
                (l - len as f64).abs() < 1e-2,
                "edge {i}-{j}: length {len} vs {l}"
            );
            let (ux, uy) = (dx / l, dy / l);
            let mut c = Check::default();
            let mut check = |t: f64, s: f64| {
                let (x, y) = (ax + ux * t - uy * s, ay + uy * t + ux * s);
                let (lon, lat) = frame.to_geo(x, y);
                c.samples += 1;
                if !raw_navigable(dem, lon, lat, threshold) {
                    c.violations += 1;
                    c.first.get_or_insert_with(|| {
                        format!(
                            "edge {i}-{j} ({a:?} → {b:?}): the point {t:.1} m along, {s:.1} m \
                             across, ({lon:.6}, {lat:.6})"
                        )
                    });
                }
            };
            let along = (l / STEP).ceil() as i64;
            for k in 0..=along {
                let t = l * k as f64 / along as f64;
                for m in 0..=lines {
                    check(t, -w + 2.0 * w * m as f64 / lines as f64);
                }
            }
            for k in 0..=arc_steps {
                let phi = std::f64::consts::PI * k as f64 / arc_steps as f64;
                let (sn, cs) = phi.sin_cos();
                // Around the start, from +w across through −w along to −w across; and the
                // same around the end.
                for r in [0.5, 1.0] {
                    check(-w * sn * r, w * cs * r);
                    check(l + w * sn * r, w * cs * r);
                }
            }
            c
        })
        .reduce(Check::default, Check::merge)
}

/// The graph at the scenario's 750 m with the default parameters, built and checked once per
/// process (shared by the 750 m test and the thinning test).
fn graph_at_750_m() -> &'static TerrainGraph {
    static GRAPH: OnceLock<TerrainGraph> = OnceLock::new();
    GRAPH.get_or_init(|| build_and_check(750.0, &TerrainParams::default()))
}

/// Builds the graph at `altitude` and checks it; returns the graph.
fn build_and_check(altitude: f64, params: &TerrainParams) -> TerrainGraph {
    let (s, dem, frame) = load();
    let t = s.terrain.as_ref().unwrap();
    let clearance = s.planner.clearance_m.unwrap();
    let wingspan = s.vehicle.wingspan_m;
    let start = Instant::now();
    let g = build_terrain_graph(
        &dem,
        &frame,
        altitude,
        t.safety_height_m,
        clearance,
        wingspan,
        params,
    )
    .unwrap();
    let build_time = start.elapsed();
    let st = &g.stats;
    eprintln!(
        "altitude {altitude} m (blocked ≥ {} m): DEM {} cells, {} blocked; metric grid {} x {} \
         of {:.2} m, {} blocked ({} reaching outside the DEM)",
        altitude - t.safety_height_m,
        st.dem_cells,
        st.dem_blocked,
        g.grid.cols,
        g.grid.rows,
        g.grid.cell,
        st.blocked_cells,
        st.outside_cells
    );
    eprintln!(
        "  DEM cell sides: east–west {:.2}–{:.2} m, north–south {:.2}–{:.2} m; axis-aligned \
         offset {:.2} m; edge bow {:.2e} m; pad {:.4} m",
        st.dem_cell_ew_m.0,
        st.dem_cell_ew_m.1,
        st.dem_cell_ns_m.0,
        st.dem_cell_ns_m.1,
        st.axis_aligned_offset_m,
        st.edge_bow_m,
        st.pad_m
    );
    eprintln!(
        "  {} convex corners → {} nodes (dropped: {} outside, {} near blocked cells, {} thinned); \
         {} pairs tested, {} cells visited, {} undirected edges",
        st.corners,
        st.nodes,
        st.dropped_outside,
        st.dropped_blocked,
        st.dropped_thinned,
        st.pairs_tested,
        st.cells_visited,
        st.undirected_edges
    );
    eprintln!(
        "  time: grid {:.1?}, nodes {:.1?}, edges {:.1?}, total {build_time:.1?} ({} threads)",
        st.grid_time,
        st.node_time,
        st.edge_time,
        rayon::current_num_threads()
    );

    assert_eq!(
        st.dem_blocked,
        blocked_cells_at(&dem, altitude, t.safety_height_m)
    );
    assert!(st.nodes > 0 && st.undirected_edges > 0);
    assert_eq!(g.edges.len(), 2 * st.undirected_edges);
    // Both directions of every edge, sorted, no self-loops, within range.
    let max = params.max_edge_m.unwrap_or(f64::INFINITY) as f32;
    for w in g.edges.windows(2) {
        assert!((w[0].0, w[0].1) < (w[1].0, w[1].1));
    }
    for &(i, j, len) in &g.edges {
        assert!(i != j && len <= max);
        assert!(g
            .edges
            .binary_search_by_key(&(j, i), |e| (e.0, e.1))
            .is_ok());
    }
    // The metric grid covers every blocked DEM cell's centre (a necessary consequence of being
    // conservative; the dense sampling below is the real check).
    for r in 0..dem.nrows {
        for c in 0..dem.ncols {
            if !dem.is_navigable(c, r, altitude, t.safety_height_m) {
                let (lon, lat) = dem.cell_centre_lonlat(c, r).unwrap();
                let (x, y) = frame.to_local(lon, lat);
                let (mc, mr) = g
                    .grid
                    .cell_of(skyroute::Vec2::new(x as f32, y as f32))
                    .unwrap();
                assert!(g.is_blocked(mc as i64, mr as i64), "DEM cell ({c}, {r})");
            }
        }
    }
    let t0 = Instant::now();
    let c = raw_dem_violations(
        &g,
        &dem,
        &frame,
        altitude - t.safety_height_m,
        g.widen_m as f64,
        usize::MAX,
    );
    eprintln!(
        "  raw DEM check: {} samples over {} edges and {} nodes in {:.1?}",
        c.samples,
        st.undirected_edges,
        st.nodes,
        t0.elapsed()
    );
    assert_eq!(
        c.violations,
        0,
        "first over a blocked DEM cell: {}",
        c.first.unwrap()
    );
    g
}

#[test]
fn jacksboro_graph_at_750_m_is_clear_of_the_raw_dem() {
    let (s, dem, frame) = load();
    let t = s.terrain.as_ref().unwrap();
    assert_eq!((t.altitude_m, t.safety_height_m), (750.0, 100.0));
    assert_eq!(s.planner.clearance_m, Some(100.0));
    assert!((s.vehicle.turn_radius_m() - 300.0).abs() < 1e-9);
    // Start and goal over navigable cells.
    let threshold = t.altitude_m - t.safety_height_m;
    for e in [s.start.as_ref().unwrap(), s.goal.as_ref().unwrap()] {
        assert!(raw_navigable(&dem, e.lon, e.lat, threshold), "{}", e.name);
        let u = ((e.lon - dem.xllcorner) / dem.cell_x).floor() as usize;
        let v = ((e.lat - dem.yllcorner) / dem.cell_y).floor() as usize;
        assert!(dem.is_navigable(u, v, t.altitude_m, t.safety_height_m));
        let (x, y) = frame.to_local(e.lon, e.lat);
        eprintln!(
            "{} ({}, {}) at ({x:.1}, {y:.1}) m: elevation {} m",
            e.name,
            e.lon,
            e.lat,
            dem.elevation_at(u, v).unwrap()
        );
    }
    assert_eq!(t.altitude_m, 750.0);
    graph_at_750_m();
}

#[test]
fn jacksboro_graph_at_850_m_is_clear_of_the_raw_dem() {
    if !full_tier_only(
        "terrain_graph::jacksboro_graph_at_850_m_is_clear_of_the_raw_dem",
        "a full Jacksboro graph at 850 m",
    ) {
        return;
    }
    build_and_check(850.0, &TerrainParams::default());
}

#[test]
fn jacksboro_graph_at_1000_m_is_clear_of_the_raw_dem() {
    if !full_tier_only(
        "terrain_graph::jacksboro_graph_at_1000_m_is_clear_of_the_raw_dem",
        "a full Jacksboro graph at 1000 m",
    ) {
        return;
    }
    build_and_check(1000.0, &TerrainParams::default());
}

#[test]
fn same_graph_on_any_number_of_threads() {
    let (s, dem, frame) = load();
    let t = s.terrain.as_ref().unwrap();
    let run = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| {
            build_terrain_graph(
                &dem,
                &frame,
                850.0,
                t.safety_height_m,
                s.planner.clearance_m.unwrap(),
                s.vehicle.wingspan_m,
                &TerrainParams::default(),
            )
            .unwrap()
        })
    };
    let (a, b) = (run(1), run(3));
    assert_eq!(a.blocked, b.blocked);
    assert_eq!(a.nodes, b.nodes);
    assert_eq!(a.edges, b.edges);
}

#[test]
fn thinning_keeps_the_spacing() {
    let (s, dem, frame) = load();
    let t = s.terrain.as_ref().unwrap();
    let build = |spacing: f64| {
        let params = TerrainParams {
            min_node_spacing_m: spacing,
            ..TerrainParams::default()
        };
        build_terrain_graph(
            &dem,
            &frame,
            t.altitude_m,
            t.safety_height_m,
            s.planner.clearance_m.unwrap(),
            s.vehicle.wingspan_m,
            &params,
        )
        .unwrap()
    };
    // (The unthinned graph is the 750 m one of `graph_at_750_m`, built once.)
    assert_eq!(t.altitude_m, 750.0);
    let (full, thin) = (graph_at_750_m(), build(300.0));
    eprintln!(
        "thinning to 300 m: {} → {} nodes, {} → {} undirected edges",
        full.stats.nodes,
        thin.stats.nodes,
        full.stats.undirected_edges,
        thin.stats.undirected_edges
    );
    assert!(thin.stats.nodes < full.stats.nodes && thin.stats.undirected_edges > 0);
    assert_eq!(
        thin.stats.nodes + thin.stats.dropped_thinned,
        full.stats.nodes
    );
    for (i, a) in thin.nodes.iter().enumerate() {
        assert!(full.nodes.contains(a));
        for b in &thin.nodes[i + 1..] {
            assert!(a.distance(*b) >= 300.0 - 1e-3);
        }
    }
}

/// The raw DEM check is not vacuous: a graph built with no clearance (band ±1.5 m), checked
/// with the scenario's band of ±101.5 m, has points over blocked cells.
#[test]
fn raw_dem_check_catches_a_graph_without_clearance() {
    let (s, dem, frame) = load();
    let t = s.terrain.as_ref().unwrap();
    let g = build_terrain_graph(
        &dem,
        &frame,
        t.altitude_m,
        t.safety_height_m,
        0.0,
        s.vehicle.wingspan_m,
        &TerrainParams::default(),
    )
    .unwrap();
    let w = 0.5 * s.vehicle.wingspan_m + s.planner.clearance_m.unwrap();
    let threshold = t.altitude_m - t.safety_height_m;
    let c = raw_dem_violations(&g, &dem, &frame, threshold, w, 2000);
    eprintln!(
        "no clearance, checked at ±{w} m: {} of {} samples over blocked cells",
        c.violations, c.samples
    );
    assert!(c.violations > 0);
    let c = raw_dem_violations(&g, &dem, &frame, threshold, g.widen_m as f64, 2000);
    assert_eq!(c.violations, 0, "{:?}", c.first);
}
