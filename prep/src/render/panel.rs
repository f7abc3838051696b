//! The panel right of the map: title, network figures, legend (a line for every kind of mark
//! drawn), the route's legs and its smallest distances to obstacles and pop-ups, and the scale
//! bar.

use super::decision_layer;
use super::draw::{
    is_terrain, is_voronoi, metres, nice_length, xml, LEG_COLOURS, MARGIN_PX, PANEL_PX,
};
use super::graticule::{spacing_text, GRATICULE_COLOUR};
use super::landmark_layer::symbol as landmark_symbol;
use super::picture::{Picture, PopupMark, Route};
use super::profile_layer::{ALTITUDE_COLOUR, SAFETY_COLOUR, TERRAIN_COLOUR};
use super::route_layer::{route_colour, route_width};
use super::threat_layer::site_symbol;
use skyroute::geometry::predicates::{
    point_in_polygon, primitive_point_distance, primitive_segment_distance, PolygonView,
};
use skyroute::network::Obstacle;
use skyroute::{Network, Primitive, Segment, Vec2};
use std::fmt::Write as _;

/// What the legend shows besides the picture's own marks.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Extras {
    /// The graticule's spacing, degrees, when one is drawn.
    pub(super) graticule_deg: Option<f64>,
    /// Whether the terrain profile strip is drawn.
    pub(super) profile: bool,
}

/// The panel's text from its top, at `px0`: heading, legend and route summary.
pub(super) fn panel(svg: &mut String, pic: &Picture, px0: f64, extras: Extras) {
    let sym_y = heading(svg, pic, px0);
    let sym_y = legend(svg, pic, px0, sym_y, extras);
    match pic.routes.as_slice() {
        [] => {}
        [route] => match &route.decision {
            Some(d) => {
                let y = decision_layer::panel(svg, route, d, px0, sym_y + 4.0);
                closest(svg, pic.network.as_ref(), route, &pic.popups, px0, y);
            }
            None => route_summary(svg, pic, route, px0, sym_y + 4.0),
        },
        routes => routes_summary(svg, pic, routes, px0, sym_y + 4.0),
    }
}

/// A route's legend text: its weight k, length and exposure when it has them.
fn route_label(r: &Route) -> String {
    let mut s = String::new();
    if let Some(k) = r.threat_weight {
        let _ = write!(s, "k = {k:.2}, ");
    }
    let _ = write!(s, "length {:.1} km", r.length_m() / 1000.0);
    if let Some(e) = r.exposure_flown {
        let _ = write!(s, ", exposure {e:.1}");
    }
    s
}

/// Several routes: a legend entry each in its colour, then their smallest distances to
/// obstacles and pop-ups.
fn routes_summary(svg: &mut String, pic: &Picture, routes: &[Route], px0: f64, mut y: f64) {
    y += 8.0;
    let _ = writeln!(
        svg,
        r##"<text x="{px0:.1}" y="{y:.1}" font-size="15" font-weight="bold">{} routes</text>"##,
        routes.len()
    );
    y += 8.0;
    for (i, r) in routes.iter().enumerate() {
        y += 22.0;
        let (c, w) = (route_colour(i), route_width(i, routes.len()));
        let _ = writeln!(
            svg,
            r##"<path d="M{px0:.1} {:.1}h32" stroke="#fff" stroke-width="{:.1}"/><path d="M{px0:.1} {:.1}h32" stroke="{c}" stroke-width="{w:.1}"/>"##,
            y - 5.0,
            w + 3.5,
            y - 5.0,
        );
        let _ = writeln!(
            svg,
            r##"<text class="route-legend" x="{:.1}" y="{y:.1}" font-size="14">{}</text>"##,
            px0 + 44.0,
            xml(&route_label(r))
        );
    }
    if routes
        .iter()
        .any(|r| r.legs.iter().any(|l| l.coarse.len() >= 2))
    {
        y += 22.0;
        let _ = writeln!(
            svg,
            r##"<path d="M{px0:.1} {:.1}h32" stroke="#333" stroke-width="1.2" stroke-dasharray="7 5"/><text x="{:.1}" y="{y:.1}" font-size="14">coarse route (Voronoi edges)</text>"##,
            y - 5.0,
            px0 + 44.0
        );
    }
    let net = pic.network.as_ref();
    let all = Route {
        legs: routes.iter().flat_map(|r| r.legs.iter().cloned()).collect(),
        ..Route::default()
    };
    closest(svg, net, &all, &pic.popups, px0, y);
}

/// The title and the network's figures; returns where the legend starts.
fn heading(svg: &mut String, pic: &Picture, px0: f64) -> f64 {
    let net = pic.network.as_ref();
    let r_turn = net.map_or(0.0, |n| n.turn_radius() as f64);
    let clearance = net.map_or(0.0, |n| n.clearance() as f64);
    let mut y = MARGIN_PX + 8.0;
    let mut line = |svg: &mut String, dy: f64, size: f64, weight: &str, fill: &str, s: &str| {
        y += dy;
        let _ = writeln!(
            svg,
            r##"<text x="{px0:.1}" y="{y:.1}" font-size="{size}" font-weight="{weight}" fill="{fill}">{}</text>"##,
            xml(s)
        );
        y
    };
    line(svg, 14.0, 20.0, "bold", "#000", &pic.title);
    if let Some(net) = net {
        let threats = if is_voronoi(net) {
            format!(", {} threats", net.threat_count())
        } else {
            String::new()
        };
        line(
            svg,
            24.0,
            13.0,
            "normal",
            "#333",
            &format!(
                "network: {} vertices, {} edges, {} obstacles{threats}",
                net.vertex_count(),
                net.edge_count(),
                net.obstacle_count()
            ),
        );
        line(
            svg,
            18.0,
            13.0,
            "normal",
            "#333",
            &format!("turn radius {r_turn:.1} m, clearance {clearance:.1} m"),
        );
    }
    line(svg, 16.0, 13.0, "normal", "#333", "") + 14.0
}

/// The legend's symbols, from `sym_y` down; returns where it ends.
fn legend(svg: &mut String, pic: &Picture, px0: f64, mut sym_y: f64, extras: Extras) -> f64 {
    let net = pic.network.as_ref();
    let clearance = net.map_or(0.0, |n| n.clearance() as f64);
    let mut symbol = |svg: &mut String, shape: String, label: &str| {
        let _ = writeln!(
            svg,
            "{}",
            shape
                .replace("{X}", &format!("{px0:.1}"))
                .replace("{Y}", &format!("{sym_y:.1}"))
        );
        let _ = writeln!(
            svg,
            r##"<text x="{:.1}" y="{:.1}" font-size="14" fill="#000">{}</text>"##,
            px0 + 44.0,
            sym_y + 5.0,
            xml(label)
        );
        sym_y += 24.0;
    };
    if let Some(t) = net.and_then(|n| n.terrain()) {
        symbol(
            svg,
            r##"<g transform="translate({X} {Y})"><rect x="2" y="-8" width="28" height="16" fill="#9a9a9a" fill-opacity="0.55"/></g>"##.to_string(),
            &format!(
                "terrain blocked at {:.0} m (safety height {:.0} m)",
                t.altitude_m, t.safety_height_m
            ),
        );
    } else if net.is_some_and(|n| n.obstacle_count() > 0) {
        symbol(
            svg,
            r##"<g transform="translate({X} {Y})"><rect x="-2" y="-10" width="34" height="20" fill="#e9d9c4"/><rect x="6" y="-5" width="18" height="10" fill="#8a8a8a" stroke="#555"/></g>"##.to_string(),
            &format!("obstacle, {clearance:.0} m clearance band"),
        );
    }
    if pic.edges && net.is_some_and(|n| !is_terrain(n)) {
        let voronoi = net.is_some_and(is_voronoi);
        symbol(
            svg,
            format!(
                r##"<g transform="translate({{X}} {{Y}})"><path d="M0 4C10 -8 20 8 32 -4" fill="none" stroke="{}" stroke-width="1.5"/><circle cx="0" cy="4" r="1.5" fill="#5a7aa0"/></g>"##,
                if voronoi { "#34495e" } else { "#a9bdd6" }
            ),
            if voronoi {
                "Voronoi edge (and the box border) / vertex"
            } else {
                "network edge / vertex"
            },
        );
    }
    if let Some(step) = extras.graticule_deg {
        symbol(
            svg,
            format!(
                r##"<path d="M{{X}} {{Y}}h32" stroke="{GRATICULE_COLOUR}" stroke-width="0.9" stroke-dasharray="6 4"/>"##
            ),
            &format!("graticule (lon/lat), every {}", spacing_text(step)),
        );
    }
    if !pic.landmarks.is_empty() {
        symbol(
            svg,
            format!(
                r##"<g transform="translate({{X}} {{Y}})">{}</g>"##,
                landmark_symbol(16.0, 1.0)
            ),
            "landmark, with its name",
        );
    }
    if extras.profile {
        symbol(
            svg,
            format!(
                r##"<g transform="translate({{X}} {{Y}})"><path d="M0 8L8 -2L16 3L24 -6L32 8Z" fill="{TERRAIN_COLOUR}" fill-opacity="0.75" stroke="#6d4c41"/></g>"##
            ),
            "profile: terrain under the route",
        );
        symbol(
            svg,
            format!(
                r##"<g transform="translate({{X}} {{Y}})"><path d="M0 -3h32" stroke="{ALTITUDE_COLOUR}" stroke-width="2"/><path d="M0 5h32" stroke="{SAFETY_COLOUR}" stroke-width="2" stroke-dasharray="6 4"/></g>"##
            ),
            "profile: route altitude / less safety height",
        );
    }
    if pic.threats.iter().any(|t| !t.popped) {
        symbol(
            svg,
            site_symbol(false),
            "radar threat, dashed at its reference distance",
        );
    }
    if pic.threats.iter().any(|t| t.popped) {
        symbol(svg, site_symbol(true), "radar threat popped up in flight");
    }
    if !pic.popups.is_empty() {
        symbol(
            svg,
            r##"<g transform="translate({X} {Y})"><circle cx="16" cy="0" r="9" fill="#d32f2f" fill-opacity="0.18" stroke="#d32f2f" stroke-width="2.5"/></g>"##.to_string(),
            "pop-up threat",
        );
    }
    if pic.endpoints.iter().any(|e| e.kind == "start") {
        symbol(
            svg,
            r##"<g transform="translate({X} {Y})"><circle cx="8" cy="0" r="7" fill="#2e7d32" stroke="#000" stroke-width="2"/><path d="M8 0H26" stroke="#000" stroke-width="2.5"/><path d="M33 0L26 -5L26 5Z"/></g>"##.to_string(),
            "start, with its heading",
        );
    }
    if pic.endpoints.iter().any(|e| e.kind == "waypoint") {
        symbol(
            svg,
            r##"<g transform="translate({X} {Y})"><circle cx="8" cy="0" r="7" fill="#fff" stroke="#000" stroke-width="2"/></g>"##.to_string(),
            "waypoint (in order)",
        );
    }
    if pic.endpoints.iter().any(|e| e.kind == "goal") {
        symbol(
            svg,
            r##"<g transform="translate({X} {Y})"><circle cx="8" cy="0" r="7" fill="#000" stroke="#000" stroke-width="2"/></g>"##.to_string(),
            "goal",
        );
    }
    sym_y
}

/// The route's length, its legs, and its smallest distances to obstacles and pop-ups (red when
/// below the network's clearance), from `y` down.
fn route_summary(svg: &mut String, pic: &Picture, route: &Route, px0: f64, mut y: f64) {
    let net = pic.network.as_ref();
    let total: f64 = route.legs.iter().map(|l| l.length_m).sum();
    y += 8.0;
    let _ = writeln!(
        svg,
        r##"<text x="{px0:.1}" y="{y:.1}" font-size="15" font-weight="bold">route: {:.0} m, {} legs</text>"##,
        total,
        route.legs.len()
    );
    y += 8.0;
    for (k, l) in route.legs.iter().enumerate() {
        y += 22.0;
        let c = LEG_COLOURS[k % LEG_COLOURS.len()];
        let _ = writeln!(
            svg,
            r##"<path d="M{px0:.1} {:.1}h32" stroke="#fff" stroke-width="7"/><path d="M{px0:.1} {:.1}h32" stroke="{c}" stroke-width="3.5"/><path d="M{:.1} {:.1}l-8 -4.5v9Z" fill="{c}"/>"##,
            y - 5.0,
            y - 5.0,
            px0 + 24.0,
            y - 5.0
        );
        let _ = writeln!(
            svg,
            r##"<text x="{:.1}" y="{y:.1}" font-size="14">{} → {}: {:.1} m</text>"##,
            px0 + 44.0,
            xml(&l.from),
            xml(&l.to),
            l.length_m
        );
    }
    if route.threat_weight.is_some() || route.exposure_flown.is_some() {
        y += 22.0;
        let _ = writeln!(
            svg,
            r##"<text class="route-legend" x="{px0:.1}" y="{y:.1}" font-size="14">{}</text>"##,
            xml(&route_label(route))
        );
    }
    if route.legs.iter().any(|l| l.coarse.len() >= 2) {
        y += 22.0;
        let _ = writeln!(
            svg,
            r##"<path d="M{px0:.1} {:.1}h32" stroke="{}" stroke-width="1.2" stroke-dasharray="7 5"/><text x="{:.1}" y="{y:.1}" font-size="14">coarse route (Voronoi edges)</text>"##,
            y - 5.0,
            LEG_COLOURS[0],
            px0 + 44.0
        );
    }
    closest(svg, net, route, &pic.popups, px0, y);
}

/// The route's smallest distances to obstacles and pop-ups (red when below the network's
/// clearance), from `y` down.
fn closest(
    svg: &mut String,
    net: Option<&Network>,
    route: &Route,
    popups: &[PopupMark],
    px0: f64,
    mut y: f64,
) {
    let clearance = net.map_or(0.0, |n| n.clearance() as f64);
    let (d_obs, d_pop) = route_distances(net, route, popups);
    let tol = 1e-2;
    for (what, d) in [("obstacle", d_obs), ("pop-up", d_pop)] {
        if let Some(d) = d {
            let ok = d >= clearance - tol;
            y += 24.0;
            let _ = writeln!(
                svg,
                r##"<text x="{px0:.1}" y="{y:.1}" font-size="14" font-weight="bold" fill="{}">closest {what}: {d:.2} m {}</text>"##,
                if ok { "#1b5e20" } else { "#c62828" },
                if ok {
                    format!("(≥ {clearance:.1} m clearance)")
                } else {
                    format!("(BELOW {clearance:.1} m clearance)")
                }
            );
        }
    }
}

/// The scale bar and the notes at the bottom of the panel.
pub(super) fn scale_bar(svg: &mut String, px0: f64, height: f64, scale: f64, grid: (f64, f64)) {
    let (fine, coarse) = grid;
    // Scale bar and notes at the bottom of the panel.
    let bar_m = nice_length((PANEL_PX - 60.0) / scale);
    let bar_px = bar_m * scale;
    let by = height - MARGIN_PX - 40.0;
    let _ = writeln!(
        svg,
        r##"<g><rect x="{px0:.1}" y="{by:.1}" width="{:.1}" height="8" fill="#000"/><rect x="{:.1}" y="{by:.1}" width="{:.1}" height="8" fill="#fff" stroke="#000"/><rect x="{px0:.1}" y="{by:.1}" width="{bar_px:.1}" height="8" fill="none" stroke="#000"/></g>"##,
        bar_px / 2.0,
        px0 + bar_px / 2.0,
        bar_px / 2.0
    );
    let _ = writeln!(
        svg,
        r##"<text x="{px0:.1}" y="{:.1}" font-size="13" text-anchor="start">0</text><text x="{:.1}" y="{:.1}" font-size="13" text-anchor="middle">{}</text><text x="{:.1}" y="{:.1}" font-size="13" text-anchor="middle">{}</text>"##,
        by - 5.0,
        px0 + bar_px / 2.0,
        by - 5.0,
        metres(bar_m / 2.0),
        px0 + bar_px,
        by - 5.0,
        metres(bar_m)
    );
    let _ = writeln!(
        svg,
        r##"<text x="{px0:.1}" y="{:.1}" font-size="12" fill="#555">grid north up, equal scale; grid {} / {}</text>"##,
        by + 28.0,
        metres(fine),
        metres(coarse)
    );
}

/// The smallest distance from a primitive to an obstacle (0 inside a polygon or disc).
pub(crate) fn primitive_obstacle_distance(p: &Primitive, o: &Obstacle) -> f64 {
    match o {
        Obstacle::Polygon(poly) => {
            if point_in_polygon(p.start(), poly) {
                return 0.0;
            }
            let n = poly.vertex_count();
            (0..n)
                .filter_map(|i| Some(Segment::new(poly.vertex(i)?, poly.vertex((i + 1) % n)?)))
                .map(|s| primitive_segment_distance(p, &s) as f64)
                .fold(f64::INFINITY, f64::min)
        }
        Obstacle::Circle { centre, radius } => {
            (primitive_point_distance(p, *centre) as f64 - *radius as f64).max(0.0)
        }
    }
}

/// The route's smallest distance to any static obstacle and to any pop-up.
fn route_distances(
    net: Option<&Network>,
    route: &Route,
    popups: &[PopupMark],
) -> (Option<f64>, Option<f64>) {
    let prims: Vec<&Primitive> = route
        .legs
        .iter()
        .flat_map(|l| l.primitives.iter())
        .collect();
    let obstacles = net.map(|net| {
        (0..net.obstacle_count())
            .filter_map(|i| net.obstacle(i))
            .flat_map(|(o, _)| {
                prims
                    .iter()
                    .map(move |p| primitive_obstacle_distance(p, &o))
            })
            .fold(f64::INFINITY, f64::min)
    });
    let pops = (!popups.is_empty()).then(|| {
        popups
            .iter()
            .flat_map(|c| {
                let centre = Vec2::new(c.centre.0 as f32, c.centre.1 as f32);
                prims
                    .iter()
                    .map(move |p| (primitive_point_distance(p, centre) as f64 - c.radius).max(0.0))
            })
            .fold(f64::INFINITY, f64::min)
    });
    (
        obstacles.filter(|d| d.is_finite()),
        pops.filter(|d| d.is_finite()),
    )
}
