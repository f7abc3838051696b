//! `skyroute info`: what a network image holds and what it needs onboard — its mode, counts and
//! bytes, the provenance it records, the planner capacities and RAM, the worst-case work of a
//! query and of a pop-up.

use crate::capacity::{
    needs, paper_turn_states, planner_bytes, with_headroom, FIRMWARE_POPUPS, FIRMWARE_ROUTE,
};
use skyroute::network::format::FORMAT_VERSION;
use skyroute::network::Mode;
use skyroute::{Network, Planner};
use std::fmt::Write as _;
use std::path::Path;

/// The report of `skyroute info` for the image `bytes` read from `path`. Errors name the file.
pub fn describe(path: &Path, bytes: &[u8]) -> Result<String, String> {
    let net = Network::from_bytes(bytes).map_err(|e| format!("{}: {e}", path.display()))?;
    let h = *net.header();
    let mut out = String::new();
    let w = &mut out;
    let _ = writeln!(
        w,
        "{}: {} network, format v{FORMAT_VERSION}, {} bytes",
        path.display(),
        net.mode().name(),
        bytes.len()
    );
    let _ = writeln!(
        w,
        "  {} vertices, {} edges, {} obstacles ({} polygon points)",
        h.vertex_count, h.edge_count, h.obstacle_count, h.obstacle_point_count
    );
    let (lo, hi) = net.extent();
    let _ = writeln!(
        w,
        "  frame origin {:.6}°N {:.6}°E; extent {:.1} x {:.1} km; turn radius {} m, clearance {} m",
        h.origin_lat_deg,
        h.origin_lon_deg,
        (hi.x - lo.x) / 1000.0,
        (hi.y - lo.y) / 1000.0,
        h.turn_radius_m,
        h.clearance_m
    );
    let _ = writeln!(
        w,
        "  pop-up grid index: {} x {} cells of {} m, {} entries in {} bytes (at most {} in a cell)",
        h.grid_nx,
        h.grid_ny,
        h.grid_cell_m,
        net.grid_entry_count(),
        h.grid_list_bytes,
        net.max_cell_entries()
    );
    mode_section(w, &net);
    vertical_section(w, &net);
    alternatives_section(w, &net);
    let _ = writeln!(
        w,
        "  provenance: {} digests of what it was built from (checked by `skyroute plan`)",
        h.provenance_count
    );
    onboard(w, bytes, &net);
    Ok(out)
}

/// The mode's own section.
fn mode_section(w: &mut String, net: &Network) {
    match net.mode() {
        Mode::Roadmap | Mode::Unknown(_) => {}
        Mode::Terrain => {
            if let (Some(t), Some(g)) = (net.terrain(), net.terrain_grid()) {
                let _ = writeln!(
                    w,
                    "  terrain: elevation grid {} x {} cells of {:.1} m; built for altitude {} m, \
                     safety height {} m; band half-width {} m",
                    g.cols, g.rows, g.cell, t.altitude_m, t.safety_height_m, t.widen_m
                );
            }
        }
        Mode::Voronoi => {
            if let (Some(v), Some(b)) = (net.voronoi(), net.voronoi_bounds()) {
                let _ = writeln!(
                    w,
                    "  voronoi: {} threat sites, weight k = {}, curvature limit {:.5} 1/m (turn \
                     radius {:.0} m), box {:.0} x {:.0} m, corner table {} x {}",
                    v.threat_count,
                    v.threat_weight,
                    v.kappa_max,
                    1.0 / v.kappa_max,
                    b.max.x - b.min.x,
                    b.max.y - b.min.y,
                    v.table_angles,
                    v.table_ratios
                );
            }
        }
        Mode::Landmark => {
            if let Some(l) = net.landmark() {
                let _ = writeln!(
                    w,
                    "  landmarks: {} x {} overflight directions, {} weather{}, {} line elements \
                     ({} distinct; at most {} Hermite pieces an edge), nominal speed {} m/s",
                    l.landmark_count,
                    l.directions,
                    l.weather_count,
                    if l.weather_count == 1 { "" } else { "s" },
                    l.chain_index_count,
                    l.element_count,
                    net.max_chain_pieces(),
                    l.v_nominal
                );
            }
        }
    }
}

/// A three-dimensional roadmap's vertical section (Niendorf et al.): its limits, the range of
/// its vertices' altitudes and its obstacles' heights.
fn vertical_section(w: &mut String, net: &Network) {
    let Some(l) = net.vertical_limits() else {
        return;
    };
    let h = net.header();
    let range = |values: &mut dyn Iterator<Item = f32>| {
        values.fold(None, |r: Option<(f32, f32)>, z| {
            Some(r.map_or((z, z), |(lo, hi)| (lo.min(z), hi.max(z))))
        })
    };
    let altitudes = range(&mut (0..h.vertex_count).filter_map(|v| net.vertex_altitude(v)));
    let heights: Vec<f32> = (0..h.obstacle_count)
        .filter_map(|i| net.obstacle_height(i))
        .collect();
    let bounded = range(&mut heights.iter().copied().filter(|x| x.is_finite()));
    let _ = writeln!(
        w,
        "  three-dimensional roadmap (Niendorf et al.): airspeed {} m/s, climb rate {} m/s, \
         vertical acceleration {} m/s² (at most {:.1} m of climb per 100 m flown); vertex \
         altitudes {}",
        l.airspeed,
        l.climb_rate,
        l.vertical_accel,
        l.max_climb(100.0),
        altitudes.map_or("none".into(), |(lo, hi)| format!("{lo:.1} to {hi:.1} m"))
    );
    let unbounded = heights.iter().filter(|x| !x.is_finite()).count();
    let _ = writeln!(
        w,
        "  obstacle heights: {} of bounded height{}, {unbounded} unbounded (no altitude clears \
         them)",
        heights.len() - unbounded,
        bounded.map_or(String::new(), |(lo, hi)| format!(" ({lo:.1} to {hi:.1} m)"))
    );
}

/// The capacities and RAM a planner needs, and the worst-case work of its operations.
fn onboard(w: &mut String, bytes: &[u8], net: &Network) {
    const P: usize = FIRMWARE_POPUPS;
    const R: usize = FIRMWARE_ROUTE;
    let n = needs(net);
    let (v, e) = (with_headroom(n.states, 64), with_headroom(n.edges, 256));
    let _ = writeln!(
        w,
        "  onboard: Planner<V, E, P, R> needs V >= {} (search states), E >= {}; with P = {P} \
         pop-ups and R = {R} route primitives it takes about {} bytes of RAM (the firmware \
         example's headroom, V = {v}, E = {e}: {} bytes; sizes as laid out on this host, a \
         32-bit target's a little less); the image stays in flash",
        n.states,
        n.edges,
        planner_bytes::<P, R>(n.states, n.edges),
        planner_bytes::<P, R>(v, e)
    );
    if let Some(states) = paper_turn_states(net) {
        let _ = writeln!(
            w,
            "  the paper's turn rule (the default, `plan --turn-rule paper`) needs V >= {states} \
             search states (one per transition), about {} bytes of RAM; the figures above are \
             the equal split's (`--turn-rule shared-equally`)",
            planner_bytes::<P, R>(states, n.edges)
        );
    }
    let mut storage = Box::new(skyroute::planner::VoronoiStorage::new());
    // The work bounds depend on the pop-up and route capacities: those of the RAM line above.
    let mut p: Box<Planner<'_, { 1 << 17 }, { 1 << 18 }, P, R>> = Box::new(Planner::new());
    let loaded = match net.mode() {
        Mode::Voronoi => {
            let _ = writeln!(
                w,
                "  voronoi storage (Planner::load_voronoi): {} bytes of RAM beside the planner, \
                 for up to {} threats (graph of at most {} vertices, {} edges)",
                std::mem::size_of::<skyroute::planner::VoronoiStorage>(),
                skyroute::planner::MAX_THREATS,
                skyroute::planner::VORONOI_GRAPH_VERTICES,
                skyroute::planner::VORONOI_GRAPH_EDGES
            );
            p.load_voronoi(bytes, &mut storage).is_ok()
        }
        Mode::Roadmap | Mode::Terrain | Mode::Landmark | Mode::Unknown(_) => p.load(bytes).is_ok(),
    };
    if loaded {
        let _ = writeln!(
            w,
            "  worst-case work with P = {P} and R = {R}: a query {}, adding a pop-up {} (counted \
             units, docs/BENCHMARKS.md){}",
            p.worst_case_work(),
            p.worst_case_popup_work(),
            match net.mode() {
                Mode::Terrain => "; a terrain query under the paper's turn rule",
                Mode::Roadmap | Mode::Landmark | Mode::Voronoi | Mode::Unknown(_) => "",
            }
        );
    }
}

/// The pop-up alternatives (Ruz et al.) the image stores, if any: per pop-up its disc, P_A and
/// each alternative's length, steps, survival figures, fuel factor and blocking discs.
fn alternatives_section(w: &mut String, net: &Network) {
    let Some(a) = net.alternatives_summary() else {
        return;
    };
    let _ = writeln!(
        w,
        "  pop-up alternatives (Ruz et al.): {} pop-ups; nominal route {} steps; limits: mean \
         time factor {}, mean fuel factor {}",
        a.popups, a.nominal_steps, a.time_limit, a.fuel_limit
    );
    for u in 0..a.popups {
        let Some(p) = net.stored_popup(u) else {
            continue;
        };
        let _ = writeln!(
            w,
            "    pop-up {u}: disc ({:.0}, {:.0}) m, radius {} m, P_A {}",
            p.centre.x, p.centre.y, p.radius, p.probability
        );
        for k in 0..p.alternatives {
            let Some(alt) = net.stored_alternative(u, k) else {
                continue;
            };
            let _ = writeln!(
                w,
                "      alternative {}: {:.0} m, {} steps, P_S,known {}, P_S,PU {}, F_c {}, {} \
                 blocking discs",
                k + 1,
                alt.length_m,
                alt.steps,
                alt.survival_known,
                alt.survival_popup,
                alt.fuel,
                alt.discs
            );
        }
    }
}
