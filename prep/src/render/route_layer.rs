//! A route: for a Voronoi route its coarse polyline thin and dashed, then a white casing under
//! every leg, then the legs (a Voronoi route's smoothed pieces, sampled densely; otherwise its
//! lines and arcs), then arrowheads in the direction of flight.

use super::draw::{path_data, View, LEG_COLOURS};
use super::picture::{Route, RouteLeg};
use skyroute::geometry::spline::Piece;
use std::fmt::Write as _;

/// Colours of the routes when a picture has several, in turn (one per route; distinct from the
/// heat map's yellow to red).
const ROUTE_COLOURS: [&str; 6] = [
    "#0d47a1", "#00838f", "#6a1b9a", "#111111", "#2e7d32", "#c2185b",
];

/// The colour of route `i` of several.
pub(super) fn route_colour(i: usize) -> &'static str {
    ROUTE_COLOURS[i % ROUTE_COLOURS.len()]
}

/// The line width of route `i` of `n`: earlier routes wider, so that where routes coincide
/// each stays visible round the later ones.
pub(super) fn route_width(i: usize, n: usize) -> f64 {
    2.5 + 2.2 * (n - 1 - i) as f64
}

/// Points per cubic piece when a leg is drawn from its pieces.
const CUBIC_SAMPLES: u32 = 64;

/// How a route is coloured: each leg its own colour (a picture of one route), or all of it one
/// colour (one of several routes), with the width of its line.
#[derive(Clone, Copy, Debug)]
pub(super) enum Colouring {
    /// A colour per leg, from `LEG_COLOURS`.
    PerLeg,
    /// One colour and line width for the whole route.
    Whole(&'static str, f64),
}

impl Colouring {
    fn leg(self, k: usize) -> (&'static str, f64) {
        match self {
            Colouring::PerLeg => (LEG_COLOURS[k % LEG_COLOURS.len()], 3.5),
            Colouring::Whole(c, w) => (c, w),
        }
    }
}

/// The path data of a leg: its pieces sampled densely when it has them, else its primitives.
fn leg_path(l: &RouteLeg, view: &View) -> String {
    let mut d = String::new();
    if l.pieces.is_empty() {
        let mut pen = None;
        for p in &l.primitives {
            path_data(&mut d, p, view, &mut pen);
        }
        return d;
    }
    for (i, piece) in l.pieces.iter().enumerate() {
        let n = match piece {
            Piece::Line { .. } => 1,
            Piece::Cubic { .. } => CUBIC_SAMPLES,
        };
        for j in 0..=n {
            if i > 0 && j == 0 {
                continue;
            }
            let (x, y) = view.pv(piece.point(j as f32 / n as f32));
            let _ = write!(
                d,
                "{}{x:.1} {y:.1}",
                if i == 0 && j == 0 { "M" } else { "L" }
            );
        }
    }
    d
}

/// Draws a route's coarse polyline (a Voronoi route's) and the white casing under its legs:
/// for several routes, every route's before any route's legs, so that no casing covers another
/// route.
pub(super) fn underlay(svg: &mut String, route: &Route, view: &View, colouring: Colouring) {
    for (k, l) in route.legs.iter().enumerate() {
        if l.coarse.len() >= 2 {
            let mut d = String::new();
            for (i, p) in l.coarse.iter().enumerate() {
                let (x, y) = view.pv(*p);
                let _ = write!(d, "{}{x:.1} {y:.1}", if i == 0 { "M" } else { "L" });
            }
            let _ = writeln!(
                svg,
                r##"<path class="coarse" d="{d}" fill="none" stroke="{}" stroke-width="1.2" stroke-dasharray="7 5" stroke-opacity="0.85"/>"##,
                colouring.leg(k).0
            );
        }
    }
    for (k, l) in route.legs.iter().enumerate() {
        let _ = writeln!(
            svg,
            r##"<path d="{}" fill="none" stroke="#fff" stroke-width="{:.1}" stroke-linejoin="round" stroke-linecap="round"/>"##,
            leg_path(l, view),
            colouring.leg(k).1 + 3.5
        );
    }
}

/// Draws a route's legs and arrowheads (over its [`underlay`]).
pub(super) fn route(svg: &mut String, route: &Route, view: &View, colouring: Colouring) {
    let scale = view.scale;
    let leg_paths: Vec<String> = route.legs.iter().map(|l| leg_path(l, view)).collect();
    for (k, d) in leg_paths.iter().enumerate() {
        let (colour, width) = colouring.leg(k);
        let _ = writeln!(
            svg,
            r##"<path d="{d}" fill="none" stroke="{colour}" stroke-width="{width:.1}" stroke-linejoin="round" stroke-linecap="round"/>"##
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
            colouring.leg(k).0
        );
    }
}
