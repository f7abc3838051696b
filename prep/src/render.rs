//! `skyroute render`: a picture of a network, and optionally a planned route, a scenario's
//! endpoints and pop-up threats, as SVG (written by hand) or PNG (the same SVG rasterised with
//! resvg).
//!
//! The map is drawn in the network's local frame with grid north up and the same scale on both
//! axes. Layers, bottom to top: a 100 m / 500 m grid; the clearance band around every obstacle;
//! obstacles (grey); for a terrain network, the cells blocked at its altitude (grey); the network's edges (thin, light); pop-ups (red); the route, one colour per
//! leg, with a white casing and arrowheads every so often in the direction of flight; start,
//! waypoints and goal, labelled by name, with heading ticks where the heading is fixed. A panel
//! on the right holds the title, a legend, the legs with their lengths, the route's smallest
//! distance to any obstacle or pop-up (in red when it is below the network's clearance) and a
//! scale bar.

use crate::export::{network_frame, read_network};
use crate::frame::LocalFrame;
use crate::scenario::{self, Scenario};
use serde_json::Value;
use skyroute::geometry::predicates::{
    point_in_polygon, primitive_point_distance, primitive_segment_distance, PolygonView,
};
use skyroute::network::Obstacle;
use skyroute::{Arc, Network, Primitive, Segment, Vec2};
use std::f64::consts::FRAC_PI_2;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// A leg of a route file written by `skyroute plan`.
#[derive(Clone, Debug, PartialEq)]
pub struct RouteLeg {
    /// Name of the endpoint it leaves.
    pub from: String,
    /// Name of the endpoint it reaches.
    pub to: String,
    /// Length, metres.
    pub length_m: f64,
    /// Its lines and arcs in the local frame.
    pub primitives: Vec<Primitive>,
}

/// A route file written by `skyroute plan`.
#[derive(Clone, Debug, PartialEq)]
pub struct Route {
    /// The scenario it was planned for.
    pub scenario: String,
    /// Origin of its local frame, `(lat, lon)` degrees.
    pub origin_deg: (f64, f64),
    /// Its legs, in order.
    pub legs: Vec<RouteLeg>,
    /// The pop-ups it was planned round (its `popups` member; empty in older files).
    pub popups: Vec<PopupMark>,
}

fn num(v: &Value, field: &str) -> Result<f64, String> {
    v.get(field)
        .and_then(Value::as_f64)
        .ok_or_else(|| format!("{field}: missing or not a number"))
}

fn point(v: &Value, field: &str) -> Result<Vec2, String> {
    match v.get(field).and_then(Value::as_array).map(|a| a.as_slice()) {
        Some([x, y]) => match (x.as_f64(), y.as_f64()) {
            (Some(x), Some(y)) => Ok(Vec2::new(x as f32, y as f32)),
            _ => Err(format!("{field}: expected [x, y] numbers")),
        },
        _ => Err(format!("{field}: expected [x, y]")),
    }
}

/// A primitive from the JSON written by [`crate::route_json::primitive_json`].
pub fn primitive_from_json(v: &Value) -> Result<Primitive, String> {
    match v.get("type").and_then(Value::as_str) {
        Some("line") => Ok(Primitive::Line(Segment::new(
            point(v, "start")?,
            point(v, "end")?,
        ))),
        Some("arc") => {
            let radius = num(v, "radius")?;
            if !radius.is_finite() || radius <= 0.0 {
                return Err(format!("radius: {radius} is not positive"));
            }
            Ok(Primitive::Arc(Arc {
                centre: point(v, "centre")?,
                radius: radius as f32,
                start_angle: num(v, "start_angle")? as f32,
                sweep: num(v, "sweep")? as f32,
            }))
        }
        Some(t) => Err(format!("type: unknown primitive type {t:?}")),
        None => Err("type: missing".to_string()),
    }
}

/// A route from the JSON text of a route file.
pub fn parse_route(text: &str) -> Result<Route, String> {
    let v: Value = serde_json::from_str(text).map_err(|e| format!("invalid JSON: {e}"))?;
    let frame = v.get("frame").ok_or("frame: missing")?;
    let origin_deg = (
        num(frame, "origin_lat_deg").map_err(|e| format!("frame.{e}"))?,
        num(frame, "origin_lon_deg").map_err(|e| format!("frame.{e}"))?,
    );
    let legs = v
        .get("legs")
        .and_then(Value::as_array)
        .ok_or("legs: missing or not an array")?;
    let mut out = Vec::new();
    for (i, leg) in legs.iter().enumerate() {
        let name = |k: &str| {
            leg.get(k)
                .and_then(Value::as_str)
                .unwrap_or("?")
                .to_string()
        };
        let prims = leg
            .get("primitives")
            .and_then(Value::as_array)
            .ok_or_else(|| format!("legs[{i}].primitives: missing or not an array"))?;
        let primitives = prims
            .iter()
            .enumerate()
            .map(|(k, p)| {
                primitive_from_json(p).map_err(|e| format!("legs[{i}].primitives[{k}].{e}"))
            })
            .collect::<Result<Vec<_>, _>>()?;
        let length_m = leg
            .get("length_m")
            .and_then(Value::as_f64)
            .unwrap_or_else(|| primitives.iter().map(|p| p.length() as f64).sum());
        out.push(RouteLeg {
            from: name("from"),
            to: name("to"),
            length_m,
            primitives,
        });
    }
    let mut popups = Vec::new();
    for (i, p) in v
        .get("popups")
        .and_then(Value::as_array)
        .into_iter()
        .flatten()
        .enumerate()
    {
        let centre = point(p, "centre").map_err(|e| format!("popups[{i}].{e}"))?;
        popups.push(PopupMark {
            name: p
                .get("name")
                .and_then(Value::as_str)
                .unwrap_or("?")
                .to_string(),
            centre: (centre.x as f64, centre.y as f64),
            radius: num(p, "radius_m").map_err(|e| format!("popups[{i}].{e}"))?,
        });
    }
    Ok(Route {
        popups,
        scenario: v
            .get("scenario")
            .and_then(Value::as_str)
            .unwrap_or("")
            .to_string(),
        origin_deg,
        legs: out,
    })
}

/// Reads a route file; errors name it.
pub fn read_route(path: &Path) -> Result<Route, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
    parse_route(&text).map_err(|e| format!("{}: {e}", path.display()))
}

/// A circular pop-up threat to draw, in the local frame.
#[derive(Clone, Debug, PartialEq)]
pub struct PopupMark {
    /// Label.
    pub name: String,
    /// Centre, metres.
    pub centre: (f64, f64),
    /// Radius, metres.
    pub radius: f64,
}

/// A start, waypoint or goal to draw, in the local frame.
#[derive(Clone, Debug, PartialEq)]
pub struct EndpointMark {
    /// Label.
    pub name: String,
    /// `start`, `waypoint` or `goal`.
    pub kind: &'static str,
    /// Position, metres.
    pub position: (f64, f64),
    /// Heading in the local frame (radians counter-clockwise from `x`) when the scenario fixes it.
    pub heading: Option<f64>,
}

/// Everything a picture shows.
#[derive(Clone, Debug, Default)]
pub struct Picture<'a> {
    /// Title (scenario or file name).
    pub title: String,
    /// The network.
    pub network: Option<Network<'a>>,
    /// Draw the network's edges.
    pub edges: bool,
    /// The route, in the network's frame.
    pub route: Option<Route>,
    /// Start, waypoints and goal.
    pub endpoints: Vec<EndpointMark>,
    /// Pop-up threats.
    pub popups: Vec<PopupMark>,
    /// Width of the map in pixels (the legend panel comes on top).
    pub map_width_px: f64,
    /// Draw only this part of the frame, `(min_x, min_y, max_x, max_y)` metres; everything
    /// drawn when `None`.
    pub area: Option<(f64, f64, f64, f64)>,
}

/// The endpoints and pop-ups of a scenario in `frame`.
pub fn scenario_marks(s: &Scenario, frame: &LocalFrame) -> (Vec<EndpointMark>, Vec<PopupMark>) {
    let mark = |e: &scenario::Endpoint, kind: &'static str| {
        let (x, y) = frame.to_local(e.lon, e.lat);
        EndpointMark {
            name: e.name.clone(),
            kind,
            position: (x, y),
            heading: e
                .heading_deg
                .map(|c| crate::local::local_heading(frame, e.lon, e.lat, c) as f64),
        }
    };
    let mut ends: Vec<EndpointMark> = s.start.iter().map(|e| mark(e, "start")).collect();
    ends.extend(s.waypoints.iter().map(|e| mark(e, "waypoint")));
    ends.extend(s.goal.iter().map(|e| mark(e, "goal")));
    let pops = s
        .popups
        .iter()
        .map(|p| PopupMark {
            name: p.name.clone(),
            centre: frame.to_local(p.lon, p.lat),
            radius: p.radius_m,
        })
        .collect();
    (ends, pops)
}

/// Colours of the route's legs, in turn.
const LEG_COLOURS: [&str; 7] = [
    "#1565c0", "#ef6c00", "#6a1b9a", "#00897b", "#c2185b", "#5d4037", "#827717",
];
const FONT: &str = "DejaVu Sans, Liberation Sans, Arial, Helvetica, sans-serif";
const PANEL_PX: f64 = 400.0;
const MARGIN_PX: f64 = 30.0;

/// Escapes text for XML.
fn xml(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// Maps the local frame (metres, `y` north) to the picture (pixels, `y` down).
#[derive(Clone, Copy, Debug)]
struct View {
    min_x: f64,
    max_y: f64,
    scale: f64,
}

impl View {
    fn px(&self, x: f64, y: f64) -> (f64, f64) {
        (
            MARGIN_PX + (x - self.min_x) * self.scale,
            MARGIN_PX + (self.max_y - y) * self.scale,
        )
    }
    fn pv(&self, p: Vec2) -> (f64, f64) {
        self.px(p.x as f64, p.y as f64)
    }
}

/// Appends path data for a primitive. Starts with a move when `pen` (the current point, pixels)
/// is not already at the primitive's start.
fn path_data(d: &mut String, p: &Primitive, view: &View, pen: &mut Option<(f64, f64)>) {
    let (sx, sy) = view.pv(p.start());
    let near = |a: (f64, f64), b: (f64, f64)| (a.0 - b.0).abs() < 0.05 && (a.1 - b.1).abs() < 0.05;
    if !pen.is_some_and(|q| near(q, (sx, sy))) {
        let _ = write!(d, "M{sx:.1} {sy:.1}");
    }
    match p {
        Primitive::Line(s) => {
            let (x, y) = view.pv(s.end);
            let _ = write!(d, "L{x:.1} {y:.1}");
            *pen = Some((x, y));
        }
        Primitive::Arc(a) => {
            // Quarter circles at most per command: no large-arc ambiguity, no full circles.
            let sweep = a.sweep as f64;
            let n = (sweep.abs() / FRAC_PI_2 - 1e-6).ceil().max(1.0) as usize;
            let r = a.radius as f64 * view.scale;
            // A left turn (counter-clockwise with y north) is counter-clockwise on the screen
            // too, which in SVG's y-down coordinates is sweep-flag 0.
            let flag = if sweep >= 0.0 { 0 } else { 1 };
            let (cx, cy) = (a.centre.x as f64, a.centre.y as f64);
            let mut end = (sx, sy);
            for k in 1..=n {
                let ang = a.start_angle as f64 + sweep * k as f64 / n as f64;
                end = view.px(
                    cx + a.radius as f64 * ang.cos(),
                    cy + a.radius as f64 * ang.sin(),
                );
                let _ = write!(d, "A{r:.1} {r:.1} 0 0 {flag} {:.1} {:.1}", end.0, end.1);
            }
            *pen = Some(end);
        }
    }
}

/// Axis-aligned box `(min_x, min_y, max_x, max_y)` that grows to hold points.
#[derive(Clone, Copy, Debug)]
struct BBox(f64, f64, f64, f64);

impl BBox {
    fn empty() -> Self {
        BBox(
            f64::INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NEG_INFINITY,
        )
    }
    fn add(&mut self, x: f64, y: f64) {
        if x.is_finite() && y.is_finite() {
            *self = BBox(self.0.min(x), self.1.min(y), self.2.max(x), self.3.max(y));
        }
    }
    fn add_box(&mut self, lo: Vec2, hi: Vec2) {
        self.add(lo.x as f64, lo.y as f64);
        self.add(hi.x as f64, hi.y as f64);
    }
    fn is_empty(&self) -> bool {
        !(self.0 <= self.2 && self.1 <= self.3)
    }
}

/// The smallest distance from a primitive to an obstacle (0 inside a polygon or disc).
fn primitive_obstacle_distance(p: &Primitive, o: &Obstacle) -> f64 {
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

/// A round length near `target` metres: 1, 2 or 5 times a power of ten.
fn nice_length(target: f64) -> f64 {
    let p = 10f64.powf(target.log10().floor());
    [5.0, 2.0, 1.0]
        .into_iter()
        .map(|m| m * p)
        .find(|&l| l <= target)
        .unwrap_or(p)
}

fn metres(m: f64) -> String {
    if m >= 1000.0 && (m % 1000.0).abs() < 1e-9 {
        format!("{} km", m / 1000.0)
    } else {
        format!("{m} m")
    }
}

/// Bold text with a white halo, so that it stays legible over lines.
fn text(svg: &mut String, x: f64, y: f64, size: f64, anchor: &str, fill: &str, s: &str) {
    let _ = writeln!(
        svg,
        r##"<text x="{x:.1}" y="{y:.1}" font-size="{size}" text-anchor="{anchor}" font-weight="bold" fill="{fill}" stroke="#fff" stroke-width="3" stroke-linejoin="round" paint-order="stroke">{}</text>"##,
        xml(s)
    );
}

/// Draws the picture as an SVG document.
pub fn render_svg(pic: &Picture) -> String {
    let net = pic.network.as_ref();
    let r_turn = net.map_or(0.0, |n| n.turn_radius() as f64);
    let clearance = net.map_or(0.0, |n| n.clearance() as f64);

    // Extent: everything drawn.
    let mut bb = BBox::empty();
    if let Some(net) = net {
        for i in 0..net.obstacle_count() {
            if let Some((_, (lo, hi))) = net.obstacle(i) {
                bb.add_box(lo, hi);
            }
        }
        if pic.edges {
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
    if let Some(route) = &pic.route {
        for p in route.legs.iter().flat_map(|l| l.primitives.iter()) {
            let (lo, hi) = p.bounding_box();
            bb.add_box(lo, hi);
        }
    }
    for e in &pic.endpoints {
        bb.add(e.position.0, e.position.1);
    }
    for c in &pic.popups {
        bb.add(c.centre.0 - c.radius, c.centre.1 - c.radius);
        bb.add(c.centre.0 + c.radius, c.centre.1 + c.radius);
    }
    if bb.is_empty() {
        bb = BBox(-100.0, -100.0, 100.0, 100.0);
    }
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
    };
    let width = map_w + 2.0 * MARGIN_PX + PANEL_PX;
    let height = (map_h + 2.0 * MARGIN_PX).max(700.0);

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

    // Obstacles and their clearance band (a round-joined stroke of twice the clearance is the
    // set of points within the clearance of the boundary).
    if let Some(net) = net {
        let mut polys = String::new();
        let mut circles = Vec::new();
        for i in 0..net.obstacle_count() {
            match net.obstacle(i) {
                Some((Obstacle::Polygon(poly), _)) => {
                    for k in 0..poly.vertex_count() {
                        if let Some(v) = poly.vertex(k) {
                            let (x, y) = view.pv(v);
                            let _ =
                                write!(polys, "{}{x:.1} {y:.1}", if k == 0 { "M" } else { "L" });
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

        // The network's edges, one path.
        if pic.edges {
            let mut d = String::new();
            for i in 0..net.edge_count() {
                if let Some(path) = net.edge_path(i) {
                    let mut pen = None;
                    for p in path.primitives().iter().flatten() {
                        path_data(&mut d, p, &view, &mut pen);
                    }
                }
            }
            let _ = writeln!(
                svg,
                r##"<path d="{d}" fill="none" stroke="#c9d6e6" stroke-width="1" shape-rendering="crispEdges"/>"##
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
    }

    // Pop-ups: the disc, and the clearance kept from it dashed.
    for c in &pic.popups {
        let (x, y) = view.px(c.centre.0, c.centre.1);
        let r = c.radius * scale;
        if clearance > 0.0 {
            let _ = writeln!(
                svg,
                r##"<circle cx="{x:.1}" cy="{y:.1}" r="{:.1}" fill="none" stroke="#d32f2f" stroke-width="1" stroke-dasharray="4 3"/>"##,
                r + clearance * scale
            );
        }
        let _ = writeln!(
            svg,
            r##"<circle cx="{x:.1}" cy="{y:.1}" r="{r:.1}" fill="#d32f2f" fill-opacity="0.18" stroke="#d32f2f" stroke-width="2.5"/>"##
        );
    }

    // The route: a white casing under every leg, then the legs, then arrowheads.
    if let Some(route) = &pic.route {
        let leg_paths: Vec<String> = route
            .legs
            .iter()
            .map(|l| {
                let mut d = String::new();
                let mut pen = None;
                for p in &l.primitives {
                    path_data(&mut d, p, &view, &mut pen);
                }
                d
            })
            .collect();
        for d in &leg_paths {
            let _ = writeln!(
                svg,
                r##"<path d="{d}" fill="none" stroke="#fff" stroke-width="7" stroke-linejoin="round" stroke-linecap="round"/>"##
            );
        }
        for (k, d) in leg_paths.iter().enumerate() {
            let _ = writeln!(
                svg,
                r##"<path d="{d}" fill="none" stroke="{}" stroke-width="3.5" stroke-linejoin="round" stroke-linecap="round"/>"##,
                LEG_COLOURS[k % LEG_COLOURS.len()]
            );
        }
        // Arrowheads about every 90 px of flight, none within 25 px of a leg's ends.
        let spacing_m = 90.0 / scale;
        let keep_off_m = 25.0 / scale;
        for (k, leg) in route.legs.iter().enumerate() {
            let total: f64 = leg.primitives.iter().map(|p| p.length() as f64).sum();
            let count = ((total - 2.0 * keep_off_m) / spacing_m).floor().max(0.0) as usize + 1;
            if total < 2.0 * keep_off_m {
                continue;
            }
            let mut d = String::new();
            for j in 0..count {
                let s = if count == 1 {
                    total / 2.0
                } else {
                    keep_off_m + (total - 2.0 * keep_off_m) * j as f64 / (count - 1) as f64
                };
                let mut rest = s;
                for p in &leg.primitives {
                    let len = p.length() as f64;
                    if rest <= len {
                        let pose = p.pose_at(rest as f32);
                        let (x, y) = view.pv(pose.position);
                        // Screen direction of the heading (y flipped).
                        let (dx, dy) = ((pose.heading as f64).cos(), -(pose.heading as f64).sin());
                        let (nx, ny) = (-dy, dx);
                        let (a, b) = (7.0, 4.5);
                        let _ = write!(
                            d,
                            "M{:.1} {:.1}L{:.1} {:.1}L{:.1} {:.1}Z",
                            x + dx * a,
                            y + dy * a,
                            x - dx * a * 0.6 + nx * b,
                            y - dy * a * 0.6 + ny * b,
                            x - dx * a * 0.6 - nx * b,
                            y - dy * a * 0.6 - ny * b
                        );
                        break;
                    }
                    rest -= len;
                }
            }
            let _ = writeln!(
                svg,
                r##"<path d="{d}" fill="{}" stroke="#fff" stroke-width="1"/>"##,
                LEG_COLOURS[k % LEG_COLOURS.len()]
            );
        }
    }

    // Endpoints: heading ticks, markers, labels.
    for e in &pic.endpoints {
        let (x, y) = view.px(e.position.0, e.position.1);
        if let Some(h) = e.heading {
            let (dx, dy) = (h.cos(), -h.sin());
            let len = 26.0;
            let (tx, ty) = (x + dx * len, y + dy * len);
            let (nx, ny) = (-dy, dx);
            let _ = writeln!(
                svg,
                r##"<path d="M{x:.1} {y:.1}L{tx:.1} {ty:.1}" stroke="#000" stroke-width="2.5"/><path d="M{:.1} {:.1}L{:.1} {:.1}L{:.1} {:.1}Z" fill="#000"/>"##,
                tx + dx * 8.0,
                ty + dy * 8.0,
                tx + nx * 5.0,
                ty + ny * 5.0,
                tx - nx * 5.0,
                ty - ny * 5.0
            );
        }
        let fill = match e.kind {
            "start" => "#2e7d32",
            "goal" => "#000",
            _ => "#fff",
        };
        let _ = writeln!(
            svg,
            r##"<circle cx="{x:.1}" cy="{y:.1}" r="7" fill="{fill}" stroke="#000" stroke-width="2"/>"##
        );
    }
    let _ = writeln!(svg, "</g>");
    // Labels last, so no line covers them, and unclipped, so none is cut at the map's edge.
    // Each goes on the side away from its heading tick.
    for e in &pic.endpoints {
        let (x, y) = view.px(e.position.0, e.position.1);
        let label = match e.kind {
            "start" => format!("{} (start)", e.name),
            "goal" => format!("{} (goal)", e.name),
            _ => e.name.clone(),
        };
        let (lx, ly, anchor) = match e.heading {
            Some(h) if h.cos() > 0.3 => (x - 12.0, y + 6.0, "end"),
            _ => (x + 12.0, y + 6.0, "start"),
        };
        let ly = if e.heading.is_some_and(|h| h.sin().abs() > 0.9) {
            y - 12.0
        } else {
            ly
        };
        text(&mut svg, lx, ly, 17.0, anchor, "#000", &label);
    }
    for c in &pic.popups {
        let (x, y) = view.px(c.centre.0, c.centre.1);
        text(
            &mut svg,
            x,
            y - c.radius * scale - 6.0,
            14.0,
            "middle",
            "#b71c1c",
            &format!("{} ({:.0} m)", c.name, c.radius),
        );
    }

    // North arrow in the map's top-left corner.
    {
        let (x, y) = (MARGIN_PX + 28.0, MARGIN_PX + 20.0);
        let _ = writeln!(
            svg,
            r##"<path d="M{x:.1} {y:.1}l-9 28l9 -7l9 7Z" fill="#000"/>"##
        );
        text(&mut svg, x, y + 48.0, 16.0, "middle", "#000", "N");
    }

    // Panel.
    let px0 = MARGIN_PX * 2.0 + map_w;
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
    line(&mut svg, 14.0, 20.0, "bold", "#000", &pic.title);
    if let Some(net) = net {
        line(
            &mut svg,
            24.0,
            13.0,
            "normal",
            "#333",
            &format!(
                "network: {} vertices, {} edges, {} obstacles",
                net.vertex_count(),
                net.edge_count(),
                net.obstacle_count()
            ),
        );
        line(
            &mut svg,
            18.0,
            13.0,
            "normal",
            "#333",
            &format!("turn radius {r_turn:.1} m, clearance {clearance:.1} m"),
        );
    }
    let mut sym_y = line(&mut svg, 16.0, 13.0, "normal", "#333", "") + 14.0;
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
            &mut svg,
            r##"<g transform="translate({X} {Y})"><rect x="2" y="-8" width="28" height="16" fill="#9a9a9a" fill-opacity="0.55"/></g>"##.to_string(),
            &format!(
                "terrain blocked at {:.0} m (safety height {:.0} m)",
                t.altitude_m, t.safety_height_m
            ),
        );
    } else if net.is_some() {
        symbol(
            &mut svg,
            r##"<g transform="translate({X} {Y})"><rect x="-2" y="-10" width="34" height="20" fill="#e9d9c4"/><rect x="6" y="-5" width="18" height="10" fill="#8a8a8a" stroke="#555"/></g>"##.to_string(),
            &format!("obstacle, {clearance:.0} m clearance band"),
        );
        if pic.edges {
            symbol(
                &mut svg,
                r##"<g transform="translate({X} {Y})"><path d="M0 4C10 -8 20 8 32 -4" fill="none" stroke="#a9bdd6" stroke-width="1.5"/><circle cx="0" cy="4" r="1.5" fill="#5a7aa0"/></g>"##.to_string(),
                "network edge / vertex",
            );
        }
    }
    if !pic.popups.is_empty() {
        symbol(
            &mut svg,
            r##"<g transform="translate({X} {Y})"><circle cx="16" cy="0" r="9" fill="#d32f2f" fill-opacity="0.18" stroke="#d32f2f" stroke-width="2.5"/></g>"##.to_string(),
            "pop-up threat",
        );
    }
    if pic.endpoints.iter().any(|e| e.kind == "start") {
        symbol(
            &mut svg,
            r##"<g transform="translate({X} {Y})"><circle cx="8" cy="0" r="7" fill="#2e7d32" stroke="#000" stroke-width="2"/><path d="M8 0H26" stroke="#000" stroke-width="2.5"/><path d="M33 0L26 -5L26 5Z"/></g>"##.to_string(),
            "start, with its heading",
        );
    }
    if pic.endpoints.iter().any(|e| e.kind == "waypoint") {
        symbol(
            &mut svg,
            r##"<g transform="translate({X} {Y})"><circle cx="8" cy="0" r="7" fill="#fff" stroke="#000" stroke-width="2"/></g>"##.to_string(),
            "waypoint (in order)",
        );
    }
    if pic.endpoints.iter().any(|e| e.kind == "goal") {
        symbol(
            &mut svg,
            r##"<g transform="translate({X} {Y})"><circle cx="8" cy="0" r="7" fill="#000" stroke="#000" stroke-width="2"/></g>"##.to_string(),
            "goal",
        );
    }
    let mut y = sym_y + 4.0;
    if let Some(route) = &pic.route {
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
        let (d_obs, d_pop) = route_distances(net, route, &pic.popups);
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
    svg.push_str("</svg>\n");
    svg
}

/// Rasterises an SVG document with resvg, using the system's fonts for text.
pub fn svg_to_png(svg: &str) -> Result<Vec<u8>, String> {
    let mut opt = resvg::usvg::Options::default();
    opt.fontdb_mut().load_system_fonts();
    let tree = resvg::usvg::Tree::from_str(svg, &opt).map_err(|e| format!("SVG: {e}"))?;
    let size = tree.size().to_int_size();
    let mut pixmap =
        resvg::tiny_skia::Pixmap::new(size.width(), size.height()).ok_or_else(|| {
            format!(
                "cannot allocate a {}x{} picture",
                size.width(),
                size.height()
            )
        })?;
    resvg::render(
        &tree,
        resvg::tiny_skia::Transform::default(),
        &mut pixmap.as_mut(),
    );
    encode_indexed_png(&pixmap).map_err(|e| format!("PNG: {e}"))
}

/// Encodes a picture as an 8-bit indexed PNG: a map of thin anti-aliased lines is several times
/// smaller so than as RGBA, and looks the same. The palette is the picture's 256 most frequent
/// colours (so every fill, line and text colour, each of which covers many pixels, is kept
/// exactly; a picture of at most 256 colours is encoded losslessly), and every other colour — the
/// anti-aliased fringes — becomes its nearest palette colour. Transparent pixels are composed over
/// white (the pictures drawn here are opaque anyway).
fn encode_indexed_png(pixmap: &resvg::tiny_skia::Pixmap) -> Result<Vec<u8>, png::EncodingError> {
    use std::collections::HashMap;
    let rgb: Vec<[u8; 3]> = pixmap
        .pixels()
        .iter()
        .map(|p| {
            // Premultiplied, so over white: c + (255 − a).
            let white = 255 - p.alpha();
            [p.red() + white, p.green() + white, p.blue() + white]
        })
        .collect();
    let mut counts: HashMap<[u8; 3], u32> = HashMap::new();
    for c in &rgb {
        *counts.entry(*c).or_insert(0) += 1;
    }
    let mut by_count: Vec<([u8; 3], u32)> = counts.iter().map(|(c, n)| (*c, *n)).collect();
    // Most frequent first; ties by colour, so the output does not depend on hashing order.
    by_count.sort_by(|a, b| b.1.cmp(&a.1).then(a.0.cmp(&b.0)));
    let palette: Vec<[u8; 3]> = by_count.iter().take(256).map(|(c, _)| *c).collect();
    let distance = |a: [u8; 3], b: [u8; 3]| {
        // Weighted RGB distance (red 2, green 4, blue 3): cheap and close enough to perception.
        let d = |i: usize| (a[i] as i32 - b[i] as i32).pow(2);
        2 * d(0) + 4 * d(1) + 3 * d(2)
    };
    let index: HashMap<[u8; 3], u8> = by_count
        .iter()
        .map(|(c, _)| {
            let k = (0..palette.len())
                .min_by_key(|&k| distance(*c, palette[k]))
                .unwrap_or(0);
            (*c, k as u8)
        })
        .collect();
    let indices: Vec<u8> = rgb.iter().map(|c| index[c]).collect();
    let mut out = Vec::new();
    {
        let mut enc = png::Encoder::new(&mut out, pixmap.width(), pixmap.height());
        enc.set_color(png::ColorType::Indexed);
        enc.set_depth(png::BitDepth::Eight);
        enc.set_palette(palette.concat());
        enc.set_compression(png::Compression::High);
        let mut w = enc.write_header()?;
        w.write_image_data(&indices)?;
    }
    Ok(out)
}

/// What `skyroute render` is asked to draw.
#[derive(Clone, Debug, Default)]
pub struct RenderRequest {
    /// The network image.
    pub network: PathBuf,
    /// A route file from `skyroute plan`.
    pub route: Option<PathBuf>,
    /// A scenario for the start, waypoints, goal and pop-ups.
    pub scenario: Option<PathBuf>,
    /// Extra pop-ups, `(lon, lat, radius_m)`.
    pub popups: Vec<(f64, f64, f64)>,
    /// The picture: SVG, or PNG when the name ends in `.png`.
    pub output: PathBuf,
    /// Also a PNG here.
    pub png: Option<PathBuf>,
    /// Width of the map, pixels.
    pub map_width_px: f64,
    /// Leave out the network's edges.
    pub no_edges: bool,
    /// Draw only this part of the frame, `(min_x, min_y, max_x, max_y)` metres.
    pub area: Option<(f64, f64, f64, f64)>,
}

fn is_png(p: &Path) -> bool {
    p.extension().is_some_and(|e| e.eq_ignore_ascii_case("png"))
}

/// Reads the inputs, draws, writes the picture(s). Returns the files written. Errors name the
/// file concerned.
pub fn render(req: &RenderRequest) -> Result<Vec<PathBuf>, Box<dyn std::error::Error>> {
    let bytes = read_network(&req.network)?;
    let net = Network::from_bytes(&bytes).map_err(|e| format!("{}: {e}", req.network.display()))?;
    let frame = network_frame(&net);
    let route = req.route.as_deref().map(read_route).transpose()?;
    if let (Some(r), Some(path)) = (&route, &req.route) {
        let (lat, lon) = net.origin_deg();
        if (r.origin_deg.0 - lat).abs() > 1e-9 || (r.origin_deg.1 - lon).abs() > 1e-9 {
            return Err(format!(
                "{}: the route's frame origin ({}, {}) is not the network's ({lat}, {lon}): was it \
                 planned on {}?",
                path.display(),
                r.origin_deg.0,
                r.origin_deg.1,
                req.network.display()
            )
            .into());
        }
    }
    let s = req.scenario.as_deref().map(scenario::load).transpose()?;
    if let Some(s) = &s {
        // Drawn over a network it does not match, a scenario's zones would be missing from
        // the picture and from its clearance figures.
        crate::provenance::check_binding(s, &net)
            .map_err(|e| format!("{} on {}: {e}", s.path.display(), req.network.display()))?;
    }
    let (endpoints, mut popups) = s
        .as_ref()
        .map(|s| scenario_marks(s, &frame))
        .unwrap_or_default();
    // The pop-ups the route was planned round, unless the scenario already drew them.
    for p in route.iter().flat_map(|r| r.popups.iter()) {
        if !popups
            .iter()
            .any(|q| q.centre == p.centre && q.radius == p.radius)
        {
            popups.push(p.clone());
        }
    }
    popups.extend(
        req.popups
            .iter()
            .enumerate()
            .map(|(i, &(lon, lat, r))| PopupMark {
                name: format!("--popup #{}", i + 1),
                centre: frame.to_local(lon, lat),
                radius: r,
            }),
    );
    let title = s
        .as_ref()
        .map(|s| s.name.clone())
        .or_else(|| {
            route
                .as_ref()
                .map(|r| r.scenario.clone())
                .filter(|n| !n.is_empty())
        })
        .unwrap_or_else(|| req.network.display().to_string());
    let pic = Picture {
        title,
        network: Some(net),
        edges: !req.no_edges,
        route,
        endpoints,
        popups,
        map_width_px: if req.map_width_px > 0.0 {
            req.map_width_px
        } else {
            1200.0
        },
        area: req.area,
    };
    let svg = render_svg(&pic);
    let mut written = Vec::new();
    let mut png = None;
    let mut write_png = |path: &Path| -> Result<(), String> {
        if png.is_none() {
            png = Some(svg_to_png(&svg).map_err(|e| format!("{}: {e}", path.display()))?);
        }
        crate::output::write_atomically(path, png.as_deref().unwrap_or_default())
    };
    let mut inputs = vec![req.network.as_path()];
    inputs.extend(req.route.as_deref());
    inputs.extend(req.scenario.as_deref());
    for out in std::iter::once(&req.output).chain(req.png.iter()) {
        crate::output::refuse_overwriting_inputs(out, &inputs)?;
    }
    if is_png(&req.output) {
        write_png(&req.output)?;
    } else {
        crate::output::write_atomically(&req.output, svg.as_bytes())?;
    }
    written.push(req.output.clone());
    if let Some(p) = &req.png {
        write_png(p)?;
        written.push(p.clone());
    }
    Ok(written)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nice_lengths() {
        assert_eq!(nice_length(730.0), 500.0);
        assert_eq!(nice_length(2100.0), 2000.0);
        assert_eq!(nice_length(99.0), 50.0);
        assert_eq!(metres(1000.0), "1 km");
        assert_eq!(metres(250.0), "250 m");
    }

    #[test]
    fn primitives_round_trip_through_json() {
        let a = Primitive::Arc(Arc {
            centre: Vec2::new(1.0, 2.0),
            radius: 64.0,
            start_angle: 0.5,
            sweep: -1.25,
        });
        let l = Primitive::Line(Segment::new(Vec2::new(0.0, 0.0), Vec2::new(3.0, 4.0)));
        for p in [a, l] {
            assert_eq!(
                primitive_from_json(&crate::route_json::primitive_json(&p)).unwrap(),
                p
            );
        }
    }

    #[test]
    fn arcs_turn_the_right_way_on_screen() {
        let view = View {
            min_x: 0.0,
            max_y: 0.0,
            scale: 1.0,
        };
        // A left quarter turn about the origin from (1, 0) to (0, 1): counter-clockwise, flag 0.
        let left = Primitive::Arc(Arc {
            centre: Vec2::new(0.0, 0.0),
            radius: 1.0,
            start_angle: 0.0,
            sweep: FRAC_PI_2 as f32,
        });
        let mut d = String::new();
        path_data(&mut d, &left, &view, &mut None);
        assert!(d.contains(" 0 0 0 "), "{d}");
        let right = Primitive::Arc(Arc {
            centre: Vec2::new(0.0, 0.0),
            radius: 1.0,
            start_angle: 0.0,
            sweep: -std::f32::consts::PI * 1.5,
        });
        let mut d = String::new();
        path_data(&mut d, &right, &view, &mut None);
        assert_eq!(d.matches('A').count(), 3, "{d}");
        assert!(d.contains(" 0 0 1 "), "{d}");
    }
}
