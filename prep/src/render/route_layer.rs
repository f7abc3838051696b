//! The route: a white casing under every leg, then the legs, one colour each, then arrowheads
//! in the direction of flight.

use super::draw::{path_data, View, LEG_COLOURS};
use super::picture::Route;
use std::fmt::Write as _;

/// Draws the route's legs and arrowheads.
pub(super) fn route(svg: &mut String, route: &Route, view: &View) {
    let scale = view.scale;
    let leg_paths: Vec<String> = route
        .legs
        .iter()
        .map(|l| {
            let mut d = String::new();
            let mut pen = None;
            for p in &l.primitives {
                path_data(&mut d, p, view, &mut pen);
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
