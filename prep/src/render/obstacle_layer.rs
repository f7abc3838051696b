//! Obstacles with their clearance band, and a terrain network's blocked cells.

use super::draw::View;
use skyroute::geometry::predicates::PolygonView;
use skyroute::network::Obstacle;
use skyroute::Network;
use std::fmt::Write as _;

/// The network's obstacles (grey) over their clearance band.
pub(super) fn obstacles(svg: &mut String, net: &Network, view: &View, clearance: f64) {
    let scale = view.scale;
    // Obstacles and their clearance band (a round-joined stroke of twice the clearance is the
    // set of points within the clearance of the boundary).
    let mut polys = String::new();
    let mut circles = Vec::new();
    for i in 0..net.obstacle_count() {
        match net.obstacle(i) {
            Some((Obstacle::Polygon(poly), _)) => {
                for k in 0..poly.vertex_count() {
                    if let Some(v) = poly.vertex(k) {
                        let (x, y) = view.pv(v);
                        let _ = write!(polys, "{}{x:.1} {y:.1}", if k == 0 { "M" } else { "L" });
                    }
                }
                polys.push('Z');
            }
            Some((Obstacle::Circle { centre, radius }, _)) => {
                circles.push((view.pv(centre), radius as f64 * scale));
            }
            None => {}
        }
    }
    let band = 2.0 * clearance * scale;
    if band > 0.0 {
        let _ = writeln!(
            svg,
            r##"<path d="{polys}" fill="#e9d9c4" stroke="#e9d9c4" stroke-width="{band:.2}" stroke-linejoin="round"/>"##
        );
        for ((x, y), r) in &circles {
            let _ = writeln!(
                svg,
                r##"<circle cx="{x:.1}" cy="{y:.1}" r="{:.1}" fill="#e9d9c4"/>"##,
                r + clearance * scale
            );
        }
    }
    let _ = writeln!(
        svg,
        r##"<path d="{polys}" fill="#8a8a8a" stroke="#555" stroke-width="1" stroke-linejoin="round"/>"##
    );
    for ((x, y), r) in &circles {
        let _ = writeln!(
            svg,
            r##"<circle cx="{x:.1}" cy="{y:.1}" r="{r:.1}" fill="#8a8a8a" stroke="#555" stroke-width="1"/>"##
        );
    }
}

/// Terrain networks: the cells blocked at the network's altitude.
pub(super) fn terrain_cells(svg: &mut String, net: &Network, view: &View) {
    // Terrain networks: the cells blocked at the altitude the network was built for, one
    // rectangle per run of blocked cells in a row.
    if let (Some(t), Some(grid), Some(coding)) =
        (net.terrain(), net.terrain_grid(), net.elevation_coding())
    {
        let blocking = coding.blocking_code(t.altitude_m, t.safety_height_m);
        let mut runs = String::new();
        for r in 0..grid.rows {
            let mut c = 0;
            while c < grid.cols {
                if net.elevation_code(c, r) < blocking {
                    c += 1;
                    continue;
                }
                let first = c;
                while c < grid.cols && net.elevation_code(c, r) >= blocking {
                    c += 1;
                }
                let (lo, _) = grid.cell_rect(first, r);
                let (_, hi) = grid.cell_rect(c - 1, r);
                let (x0, y1) = view.pv(lo);
                let (x1, y0) = view.pv(hi);
                let _ = write!(runs, "M{x0:.1} {y0:.1}H{x1:.1}V{y1:.1}H{x0:.1}Z");
            }
        }
        let _ = writeln!(
            svg,
            r##"<path d="{runs}" fill="#9a9a9a" fill-opacity="0.55" stroke="none"/>"##
        );
    }
}
