//! The SVG document: the map's extent and view, then the layers bottom to top, then the panel.

use super::draw::{is_landmark, is_voronoi, xml, BBox, View, FONT, MARGIN_PX, PANEL_PX};
use super::picture::Picture;
use super::route_layer::{route_colour, route_width, Colouring};
use super::{
    decision_layer, graticule, landmark_layer, mark_layer, network_layer, obstacle_layer, panel,
    profile_layer, route_layer, threat_layer,
};
use std::fmt::Write as _;

/// Draws the picture as an SVG document.
pub fn render_svg(pic: &Picture) -> String {
    let net = pic.network.as_ref();
    let clearance = net.map_or(0.0, |n| n.clearance() as f64);
    let bb = extent(pic);
    let pad = 0.03 * (bb.2 - bb.0).max(bb.3 - bb.1).max(1.0);
    let bb = match pic.area {
        Some((x0, y0, x1, y1)) => BBox(x0, y0, x1, y1),
        None => BBox(bb.0 - pad, bb.1 - pad, bb.2 + pad, bb.3 + pad),
    };
    let (w_m, h_m) = (bb.2 - bb.0, bb.3 - bb.1);
    let map_w = pic.map_width_px.max(200.0);
    let scale = map_w / w_m;
    let map_h = h_m * scale;
    let view = View {
        min_x: bb.0,
        max_y: bb.3,
        scale,
        map_w,
        map_h,
    };
    let profile = net.and_then(|n| profile_layer::profile(n, pic.routes.first()?));
    let strip = if profile.is_some() {
        profile_layer::STRIP_PX
    } else {
        0.0
    };
    let width = map_w + 2.0 * MARGIN_PX + PANEL_PX;
    let height = (map_h + 2.0 * MARGIN_PX + strip).max(700.0);

    let mut svg = String::new();
    let _ = writeln!(
        svg,
        r##"<svg xmlns="http://www.w3.org/2000/svg" width="{width:.0}" height="{height:.0}" viewBox="0 0 {width:.0} {height:.0}" font-family="{FONT}">"##
    );
    let _ = writeln!(svg, "<title>{}</title>", xml(&pic.title));
    let _ = writeln!(svg, r##"<rect width="100%" height="100%" fill="#fff"/>"##);
    let _ = writeln!(
        svg,
        r##"<defs><clipPath id="map"><rect x="{MARGIN_PX}" y="{MARGIN_PX}" width="{map_w:.1}" height="{map_h:.1}"/></clipPath></defs>"##
    );
    let _ = writeln!(
        svg,
        r##"<rect x="{MARGIN_PX}" y="{MARGIN_PX}" width="{map_w:.1}" height="{map_h:.1}" fill="#fbfbf8" stroke="#888" stroke-width="1"/>"##
    );
    let _ = writeln!(svg, r##"<g clip-path="url(#map)">"##);

    let voronoi = net.is_some_and(is_voronoi);
    if voronoi {
        threat_layer::heat_map(&mut svg, &pic.threats, &view, map_w, map_h);
    }
    let (fine, coarse) = network_layer::grid(&mut svg, &view, bb, map_w, map_h);
    let graticule =
        net.and_then(|n| graticule::lines(&mut svg, &crate::export::network_frame(n), &view, bb));
    if let Some(net) = net {
        obstacle_layer::obstacles(&mut svg, net, &view, clearance);
        obstacle_layer::terrain_cells(&mut svg, net, &view);
        if pic.edges {
            network_layer::edges(&mut svg, net, &view);
        }
    }
    mark_layer::popups(&mut svg, &pic.popups, &view, clearance);
    threat_layer::sites(&mut svg, &pic.threats, &view);
    let n = pic.routes.len();
    for d in pic.routes.iter().filter_map(|r| r.decision.as_ref()) {
        decision_layer::map(&mut svg, d, &view);
    }
    let colouring = |i: usize| {
        if n == 1 && pic.routes[0].decision.is_some() {
            Colouring::Whole(decision_layer::FLOWN_COLOUR, decision_layer::FLOWN_WIDTH)
        } else if n == 1 {
            Colouring::PerLeg
        } else {
            Colouring::Whole(route_colour(i), route_width(i, n))
        }
    };
    for (i, route) in pic.routes.iter().enumerate() {
        route_layer::underlay(&mut svg, route, &view, colouring(i));
    }
    for (i, route) in pic.routes.iter().enumerate() {
        route_layer::route(&mut svg, route, &view, colouring(i));
    }
    landmark_layer::landmarks(&mut svg, &pic.landmarks, &view);
    mark_layer::endpoints(&mut svg, &pic.endpoints, &view);
    let _ = writeln!(svg, "</g>");
    let taken = mark_layer::endpoint_boxes(&pic.endpoints, &view);
    if let Some((_, labels)) = &graticule {
        graticule::labels(&mut svg, &view, labels, &taken);
    }
    landmark_layer::labels(&mut svg, &pic.landmarks, &view, &taken);
    mark_layer::labels(&mut svg, &pic.endpoints, &pic.popups, &view);
    mark_layer::north_arrow(&mut svg);
    if let Some(p) = &profile {
        profile_layer::strip(&mut svg, p, MARGIN_PX + map_h + 20.0, map_w);
    }
    let px0 = MARGIN_PX * 2.0 + map_w;
    let extras = panel::Extras {
        graticule_deg: graticule.as_ref().map(|g| g.0),
        profile: profile.is_some(),
    };
    panel::panel(&mut svg, pic, px0, extras);
    panel::scale_bar(&mut svg, px0, height, scale, (fine, coarse));
    if voronoi {
        threat_layer::colour_bar(&mut svg, px0, height - MARGIN_PX - 110.0, PANEL_PX - 60.0);
    }
    svg.push_str("</svg>\n");
    svg
}

/// The box of everything drawn (obstacles, edges or vertices, landmarks, route, endpoints,
/// pop-ups), or a 200 m square round the origin when there is nothing.
fn extent(pic: &Picture) -> BBox {
    let net = pic.network.as_ref();
    let mut bb = BBox::empty();
    if let Some(net) = net {
        for i in 0..net.obstacle_count() {
            if let Some((_, (lo, hi))) = net.obstacle(i) {
                bb.add_box(lo, hi);
            }
        }
        if pic.edges && is_landmark(net) {
            for e in 0..net.edge_count() {
                for k in 0..net.chain_piece_count(e) {
                    if let Some(seg) = net.chain_piece(e, k) {
                        for t in [0.0, 0.25, 0.5, 0.75, 1.0] {
                            if let Some(q) = seg.position(seg.t_max() * t) {
                                bb.add(q.x as f64, q.y as f64);
                            }
                        }
                    }
                }
            }
        } else if pic.edges {
            for i in 0..net.edge_count() {
                if let Some(path) = net.edge_path(i) {
                    for p in path.primitives().iter().flatten() {
                        let (lo, hi) = p.bounding_box();
                        bb.add_box(lo, hi);
                    }
                }
            }
        } else {
            for i in 0..net.vertex_count() {
                if let Some(v) = net.vertex(i) {
                    bb.add(v.position.x as f64, v.position.y as f64);
                }
            }
        }
    }
    for route in &pic.routes {
        let decided = route.decision.iter().flat_map(|d| {
            d.nominal.iter().chain(
                d.popups
                    .iter()
                    .flat_map(|p| p.alternatives.iter())
                    .flat_map(|a| a.primitives.iter()),
            )
        });
        for p in route
            .legs
            .iter()
            .flat_map(|l| l.primitives.iter())
            .chain(decided)
        {
            let (lo, hi) = p.bounding_box();
            bb.add_box(lo, hi);
        }
    }
    for e in &pic.endpoints {
        bb.add(e.position.0, e.position.1);
    }
    for l in &pic.landmarks {
        bb.add(l.position.0, l.position.1);
    }
    for c in &pic.popups {
        bb.add(c.centre.0 - c.radius, c.centre.1 - c.radius);
        bb.add(c.centre.0 + c.radius, c.centre.1 + c.radius);
    }
    if bb.is_empty() {
        bb = BBox(-100.0, -100.0, 100.0, 100.0);
    }
    bb
}
