//! The map's background grid and the network's edges and vertices.

use super::draw::{is_landmark, is_voronoi, nice_length, path_data, BBox, View, MARGIN_PX};
use skyroute::Network;
use std::fmt::Write as _;

/// The grid: fine and coarse lines at round distances over `bb`; returns their spacings
/// `(fine, coarse)`, metres.
pub(super) fn grid(svg: &mut String, view: &View, bb: BBox, map_w: f64, map_h: f64) -> (f64, f64) {
    let (w_m, h_m) = (bb.2 - bb.0, bb.3 - bb.1);
    // Grid: fine and coarse lines at round distances.
    let coarse = nice_length(w_m.max(h_m) / 6.0);
    let fine = coarse / 5.0;
    for (step, colour) in [(fine, "#eeeeea"), (coarse, "#dcdcd4")] {
        let mut d = String::new();
        let mut x = (bb.0 / step).ceil() * step;
        while x <= bb.2 {
            let (px, _) = view.px(x, 0.0);
            let _ = write!(d, "M{px:.1} {MARGIN_PX}V{:.1}", MARGIN_PX + map_h);
            x += step;
        }
        let mut y = (bb.1 / step).ceil() * step;
        while y <= bb.3 {
            let (_, py) = view.px(0.0, y);
            let _ = write!(d, "M{MARGIN_PX} {py:.1}H{:.1}", MARGIN_PX + map_w);
            y += step;
        }
        let _ = writeln!(
            svg,
            r##"<path d="{d}" fill="none" stroke="{colour}" stroke-width="1"/>"##
        );
    }

    (fine, coarse)
}

/// The network's edges, one path, and its vertices as dots (a Voronoi network's darker, to show
/// over the heat map; a landmark network's edges are its Hermite chains).
pub(super) fn edges(svg: &mut String, net: &Network, view: &View) {
    let (edge_colour, edge_width, rendering) = if is_voronoi(net) {
        ("#34495e", 1.3, "geometricPrecision")
    } else if is_landmark(net) {
        ("#b4c6dc", 0.8, "geometricPrecision")
    } else {
        ("#c9d6e6", 1.0, "crispEdges")
    };
    let d = if is_landmark(net) {
        super::landmark_layer::chain_edges(net, view)
    } else {
        let mut d = String::new();
        for i in 0..net.edge_count() {
            if let Some(path) = net.edge_path(i) {
                let mut pen = None;
                for p in path.primitives().iter().flatten() {
                    path_data(&mut d, p, view, &mut pen);
                }
            }
        }
        d
    };
    let _ = writeln!(
        svg,
        r##"<path class="edges" d="{d}" fill="none" stroke="{edge_colour}" stroke-width="{edge_width}" shape-rendering="{rendering}"/>"##
    );
    let mut dots = String::new();
    for i in 0..net.vertex_count() {
        if let Some(v) = net.vertex(i) {
            let (x, y) = view.pv(v.position);
            let _ = write!(dots, "M{x:.1} {y:.1}h0");
        }
    }
    let _ = writeln!(
        svg,
        r##"<path d="{dots}" stroke="#5a7aa0" stroke-opacity="0.6" stroke-width="2" stroke-linecap="round"/>"##
    );
}
