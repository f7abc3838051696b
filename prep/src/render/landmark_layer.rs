//! A landmark network's landmarks (a triangle each, labelled by name) and its edges, the
//! Hermite chains between overflights.

use super::draw::{label_box, map_text, overlap, View};
use super::picture::LandmarkMark;
use skyroute::Network;
use std::fmt::Write as _;

/// The landmarks' colour.
pub(super) const LANDMARK_COLOUR: &str = "#6a1b9a";

/// The landmark symbol centred at `(x, y)`: a triangle pointing up, white-edged.
pub(super) fn symbol(x: f64, y: f64) -> String {
    format!(
        r##"<path class="landmark" d="M{x:.1} {:.1}L{:.1} {:.1}H{:.1}Z" fill="{LANDMARK_COLOUR}" stroke="#fff" stroke-width="1.5"/>"##,
        y - 8.0,
        x + 7.0,
        y + 5.0,
        x - 7.0
    )
}

/// The landmarks' symbols (inside the map's clip).
pub(super) fn landmarks(svg: &mut String, marks: &[LandmarkMark], view: &View) {
    for m in marks {
        let (x, y) = view.px(m.position.0, m.position.1);
        let _ = writeln!(svg, "{}", symbol(x, y));
    }
}

/// The landmarks' labels' font size, pixels.
const LABEL_PX: f64 = 12.0;

/// The names of the landmarks on the map, kept inside the map: right of and below each symbol
/// (left of it in the map's right tenth), else the first of the other three corners where the
/// name overlaps neither `avoid` (boxes in pixels: the endpoints' markers and labels) nor a
/// name already placed.
pub(super) fn labels(svg: &mut String, marks: &[LandmarkMark], view: &View, avoid: &[[f64; 4]]) {
    let mut taken = avoid.to_vec();
    for m in marks {
        let (x, y) = view.px(m.position.0, m.position.1);
        if !view.shows((x, y), 1.0) {
            continue;
        }
        let right = (x + 9.0, "start");
        let left = (x - 9.0, "end");
        let sides = if x - super::draw::MARGIN_PX < 0.9 * view.map_w {
            [right, left]
        } else {
            [left, right]
        };
        let candidates = [y + 14.0, y - 9.0]
            .into_iter()
            .flat_map(|ly| sides.map(|(lx, anchor)| ((lx, ly), anchor)));
        let boxed: Vec<_> = candidates
            .map(|(at, anchor)| (at, anchor, label_box(view, at, LABEL_PX, anchor, &m.name)))
            .collect();
        let (at, anchor, b) = boxed
            .iter()
            .find(|(_, _, b)| !taken.iter().any(|t| overlap(t, b)))
            .unwrap_or(&boxed[0]);
        taken.push(*b);
        map_text(svg, view, *at, LABEL_PX, anchor, LANDMARK_COLOUR, &m.name);
    }
}

/// A landmark network's edges: each Hermite chain as a polyline through points about 50 m
/// apart along its pieces, one path.
pub(super) fn chain_edges(net: &Network, view: &View) -> String {
    let mut d = String::new();
    for e in 0..net.edge_count() {
        let mut first = true;
        for k in 0..net.chain_piece_count(e) {
            let Some(seg) = net.chain_piece(e, k) else {
                continue;
            };
            let n = (seg.length() / 50.0).ceil().clamp(1.0, 400.0) as usize;
            for j in 0..=n {
                let Some(q) = seg.position(seg.t_max() * j as f32 / n as f32) else {
                    continue;
                };
                let (x, y) = view.pv(q);
                let _ = write!(d, "{}{x:.1} {y:.1}", if first { "M" } else { "L" });
                first = false;
            }
        }
    }
    d
}
