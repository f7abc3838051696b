//! The longitude/latitude graticule: meridians and parallels at a round spacing chosen from the
//! map's extent, drawn as polylines through the frame (transverse Mercator bends them a little),
//! labelled in degrees and minutes where they leave the map: meridians at its bottom edge,
//! parallels at its right edge (a label that would overlap another, or an endpoint's marker or
//! label, is left out).

use super::draw::{label_box, map_text, overlap, BBox, View, MARGIN_PX};
use crate::frame::LocalFrame;
use std::fmt::Write as _;

/// The graticule's line colour.
pub(super) const GRATICULE_COLOUR: &str = "#7d8fa8";
/// Its labels' colour.
const LABEL_COLOUR: &str = "#3f5573";
/// The spacings tried, arc-seconds: 1″ to 10°.
const STEPS_ARCSEC: [f64; 19] = [
    1.0,
    2.0,
    5.0,
    10.0,
    15.0,
    30.0,
    60.0,
    120.0,
    300.0,
    600.0,
    900.0,
    1200.0,
    1800.0,
    3600.0,
    7200.0,
    5.0 * 3600.0,
    10.0 * 3600.0,
    20.0 * 3600.0,
    30.0 * 3600.0,
];
/// Its labels' font size, pixels.
const LABEL_PX: f64 = 11.0;
/// Points per graticule line.
const SAMPLES: usize = 48;

/// The smallest round spacing (degrees) not below `target_deg` (the largest when none is).
fn round_up(target_deg: f64) -> f64 {
    let target = target_deg * 3600.0;
    STEPS_ARCSEC
        .into_iter()
        .find(|&s| s >= target)
        .unwrap_or(STEPS_ARCSEC[STEPS_ARCSEC.len() - 1])
        / 3600.0
}

/// The largest round spacing (degrees) not above `target_deg` (the smallest when none is).
fn round_down(target_deg: f64) -> f64 {
    let target = target_deg * 3600.0;
    STEPS_ARCSEC
        .into_iter()
        .rev()
        .find(|&s| s <= target)
        .unwrap_or(STEPS_ARCSEC[0])
        / 3600.0
}

/// The spacing (degrees) for a map `long_deg` by `short_deg` degrees across: the smallest
/// round one with at most eight lines over the long side; a smaller one where that leaves
/// fewer than three over the short side, but never more than fourteen over the long side.
pub(super) fn spacing_deg(long_deg: f64, short_deg: f64) -> f64 {
    round_up(long_deg / 8.0)
        .min(round_down(short_deg / 3.0))
        .max(round_up(long_deg / 14.0))
}

/// A spacing as text: `10′`, `30″`, `1°`.
pub(super) fn spacing_text(step_deg: f64) -> String {
    let s = (step_deg * 3600.0).round();
    if s >= 3600.0 && s % 3600.0 == 0.0 {
        format!("{}°", s / 3600.0)
    } else if s >= 60.0 && s % 60.0 == 0.0 {
        format!("{}′", s / 60.0)
    } else {
        format!("{s}″")
    }
}

/// An angle in degrees and minutes (and seconds when `step_deg` is not a whole number of
/// minutes), with its hemisphere letter `pos` or `neg`: `48°12′N`, `11°37′30″E`.
pub(super) fn dms(value_deg: f64, step_deg: f64, pos: char, neg: char) -> String {
    let hemisphere = if value_deg < 0.0 { neg } else { pos };
    let total = (value_deg.abs() * 3600.0).round() as i64;
    let (d, m, s) = (total / 3600, total / 60 % 60, total % 60);
    let step = (step_deg * 3600.0).round() as i64;
    if step % 60 != 0 {
        format!("{d}°{m:02}′{s:02}″{hemisphere}")
    } else if step % 3600 != 0 || m != 0 {
        format!("{d}°{m:02}′{hemisphere}")
    } else {
        format!("{d}°{hemisphere}")
    }
}

/// The `(lon, lat)` box of the map `bb` (local metres), from points along its border.
fn geo_box(frame: &LocalFrame, bb: BBox) -> (f64, f64, f64, f64) {
    let mut g = (
        f64::INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::NEG_INFINITY,
    );
    for k in 0..=SAMPLES {
        let t = k as f64 / SAMPLES as f64;
        let (x, y) = (bb.0 + t * (bb.2 - bb.0), bb.1 + t * (bb.3 - bb.1));
        for (px, py) in [(x, bb.1), (x, bb.3), (bb.0, y), (bb.2, y)] {
            let (lon, lat) = frame.to_geo(px, py);
            g = (g.0.min(lon), g.1.min(lat), g.2.max(lon), g.3.max(lat));
        }
    }
    g
}

/// The multiples of `step` in `[lo, hi]`.
fn multiples(lo: f64, hi: f64, step: f64) -> impl Iterator<Item = f64> {
    let first = (lo / step).ceil() as i64;
    let last = (hi / step).floor() as i64;
    (first..=last).map(move |k| k as f64 * step)
}

/// Where the polyline `pts` (pixels) first crosses `coord = value`, `coord` 0 for `x`, 1 for `y`.
fn crossing(pts: &[(f64, f64)], coord: usize, value: f64) -> Option<(f64, f64)> {
    let c = |p: &(f64, f64)| if coord == 0 { p.0 } else { p.1 };
    pts.windows(2).find_map(|w| {
        let (a, b) = (c(&w[0]) - value, c(&w[1]) - value);
        if a == b || a.signum() == b.signum() && a != 0.0 {
            return None;
        }
        let t = a / (a - b);
        Some((
            w[0].0 + t * (w[1].0 - w[0].0),
            w[0].1 + t * (w[1].1 - w[0].1),
        ))
    })
}

/// A graticule line in pixels through `SAMPLES + 1` points of `geo(t)`, `t` in `[0, 1]`.
fn line_px(frame: &LocalFrame, view: &View, geo: impl Fn(f64) -> (f64, f64)) -> Vec<(f64, f64)> {
    (0..=SAMPLES)
        .map(|k| {
            let (lon, lat) = geo(k as f64 / SAMPLES as f64);
            let (x, y) = frame.to_local(lon, lat);
            view.px(x, y)
        })
        .collect()
}

/// The graticule's lines over the map `bb` (inside the map's clip); returns its spacing in
/// degrees and the labels to draw `(x, y, anchor, text)` in pixels, or `None` when the map
/// is too large for one (more than 60° across).
pub(super) fn lines(
    svg: &mut String,
    frame: &LocalFrame,
    view: &View,
    bb: BBox,
) -> Option<(f64, Vec<Label>)> {
    let g = geo_box(frame, bb);
    let (span, short) = ((g.2 - g.0).max(g.3 - g.1), (g.2 - g.0).min(g.3 - g.1));
    if !(span.is_finite() && span > 0.0 && span <= 60.0) {
        return None;
    }
    let step = spacing_deg(span, short);
    let (right, bottom) = (MARGIN_PX + view.map_w, MARGIN_PX + view.map_h);
    let inside = |v: f64, lo: f64, hi: f64| v >= lo - 0.5 && v <= hi + 0.5;
    let mut labels = Vec::new();
    let polyline = |svg: &mut String, pts: &[(f64, f64)]| {
        let mut p = String::new();
        for (x, y) in pts {
            let _ = write!(p, "{}{x:.1},{y:.1}", if p.is_empty() { "" } else { " " });
        }
        let _ = writeln!(
            svg,
            r##"<polyline class="graticule" points="{p}" fill="none" stroke="{GRATICULE_COLOUR}" stroke-width="0.9" stroke-dasharray="6 4"/>"##
        );
    };
    for lon in multiples(g.0, g.2, step) {
        let pts = line_px(frame, view, |t| (lon, g.1 + t * (g.3 - g.1)));
        polyline(svg, &pts);
        if let Some((x, _)) = crossing(&pts, 1, bottom).filter(|p| inside(p.0, MARGIN_PX, right)) {
            labels.push(Label {
                at: (x, bottom - 5.0),
                anchor: "middle",
                text: dms(lon, step, 'E', 'W'),
            });
        }
    }
    for lat in multiples(g.1, g.3, step) {
        let pts = line_px(frame, view, |t| (g.0 + t * (g.2 - g.0), lat));
        polyline(svg, &pts);
        if let Some((_, y)) = crossing(&pts, 0, right).filter(|p| inside(p.1, MARGIN_PX, bottom)) {
            labels.push(Label {
                at: (right - 5.0, y - 4.0),
                anchor: "end",
                text: dms(lat, step, 'N', 'S'),
            });
        }
    }
    Some((step, spaced(labels)))
}

/// The labels left when those that would overlap an earlier one along the same edge are
/// dropped (meridians' by their estimated width, parallels' by their height).
fn spaced(labels: Vec<Label>) -> Vec<Label> {
    let mut kept: Vec<Label> = Vec::new();
    for l in labels {
        let clear = kept.iter().filter(|k| k.anchor == l.anchor).all(|k| {
            if l.anchor == "middle" {
                let half = |k: &Label| 0.34 * LABEL_PX * k.text.chars().count() as f64 + 4.0;
                (l.at.0 - k.at.0).abs() >= half(k) + half(&l)
            } else {
                (l.at.1 - k.at.1).abs() >= LABEL_PX + 4.0
            }
        });
        if clear {
            kept.push(l);
        }
    }
    kept
}

/// A graticule label: where, how anchored, what.
pub(super) struct Label {
    at: (f64, f64),
    anchor: &'static str,
    text: String,
}

/// The graticule's labels (outside the map's clip, kept inside the map), but for those that
/// would overlap one of the boxes `avoid` (pixels: the endpoints' markers and labels).
pub(super) fn labels(svg: &mut String, view: &View, labels: &[Label], avoid: &[[f64; 4]]) {
    for l in labels {
        let b = label_box(view, l.at, LABEL_PX, l.anchor, &l.text);
        if !avoid.iter().any(|a| overlap(a, &b)) {
            map_text(svg, view, l.at, LABEL_PX, l.anchor, LABEL_COLOUR, &l.text);
        }
    }
}
