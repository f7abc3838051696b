//! Radar threats: the exposure heat map under a Voronoi network, each site with a dashed
//! circle at its reference distance, and the heat map's colour bar for the panel.

use super::draw::{xml, View, MARGIN_PX};
use super::picture::ThreatMark;
use std::fmt::Write as _;

/// Side of a heat-map cell, pixels.
const CELL_PX: f64 = 4.0;
/// The heat map's range: log₁₀ of the exposure density at its lowest and highest colour.
/// Cells below the lowest are left uncoloured; cells above take the highest colour.
pub(super) const LOG_RANGE: (f64, f64) = (-2.0, 2.0);
/// Colour steps per decade of the density.
const STEPS_PER_DECADE: f64 = 4.0;
/// The heat map's opacity, so that the grid and network stay visible through it.
const HEAT_OPACITY: f64 = 0.8;
/// A site of the network's threats.
const SITE_COLOUR: &str = "#4a0d0d";
/// A site that popped up in flight.
const POPPED_COLOUR: &str = "#d500f9";

/// Anchors of the heat map's colour ramp, light (low density) to dark (high), yellow–orange–red.
const RAMP: [[f64; 3]; 7] = [
    [255.0, 255.0, 204.0],
    [255.0, 237.0, 160.0],
    [254.0, 217.0, 118.0],
    [254.0, 178.0, 76.0],
    [253.0, 141.0, 60.0],
    [240.0, 59.0, 32.0],
    [189.0, 0.0, 38.0],
];

/// The exposure density Σ_j (r_j/d_j)⁴ at `(x, y)`: the exposure per metre flown there, with
/// the distance floored at 1 % of r_j as the planner's cost does.
pub fn exposure_density(threats: &[ThreatMark], x: f64, y: f64) -> f64 {
    threats
        .iter()
        .map(|t| {
            let d = (x - t.centre.0).hypot(y - t.centre.1).max(0.01 * t.radius);
            (t.radius / d).powi(4)
        })
        .sum()
}

/// The number of colour steps of the ramp.
fn step_count() -> usize {
    ((LOG_RANGE.1 - LOG_RANGE.0) * STEPS_PER_DECADE).round() as usize
}

/// The colour of step `i` of [`step_count`], as `#rrggbb`.
fn step_colour(i: usize) -> String {
    let t = (i as f64 + 0.5) / step_count() as f64 * (RAMP.len() - 1) as f64;
    let k = (t.floor() as usize).min(RAMP.len() - 2);
    let f = t - k as f64;
    let c: Vec<u8> = (0..3)
        .map(|j| (RAMP[k][j] + (RAMP[k + 1][j] - RAMP[k][j]) * f).round() as u8)
        .collect();
    format!("#{:02x}{:02x}{:02x}", c[0], c[1], c[2])
}

/// The colour step of a density, or `None` below the heat map's range.
fn step_of(density: f64) -> Option<usize> {
    let l = density.log10();
    // Also `None` for a NaN density.
    if l.is_nan() || l < LOG_RANGE.0 {
        return None;
    }
    let i = ((l - LOG_RANGE.0) * STEPS_PER_DECADE).floor() as usize;
    Some(i.min(step_count() - 1))
}

/// The heat map over the map's `map_w` × `map_h` pixels: the density at each cell's centre,
/// one rectangle per run of cells of the same colour in a row.
pub(super) fn heat_map(
    svg: &mut String,
    threats: &[ThreatMark],
    view: &View,
    map_w: f64,
    map_h: f64,
) {
    let cols = (map_w / CELL_PX).ceil() as usize;
    let rows = (map_h / CELL_PX).ceil() as usize;
    let mut by_step: Vec<String> = vec![String::new(); step_count()];
    for r in 0..rows {
        let py = MARGIN_PX + (r as f64 + 0.5) * CELL_PX;
        let y = view.max_y - (py - MARGIN_PX) / view.scale;
        let steps: Vec<Option<usize>> = (0..cols)
            .map(|c| {
                let px = MARGIN_PX + (c as f64 + 0.5) * CELL_PX;
                let x = view.min_x + (px - MARGIN_PX) / view.scale;
                step_of(exposure_density(threats, x, y))
            })
            .collect();
        let mut c = 0;
        while c < cols {
            let first = c;
            while c < cols && steps[c] == steps[first] {
                c += 1;
            }
            if let Some(i) = steps[first] {
                let x0 = MARGIN_PX + first as f64 * CELL_PX;
                let _ = write!(
                    by_step[i],
                    "M{x0:.1} {:.1}h{:.1}v{CELL_PX}h{:.1}Z",
                    MARGIN_PX + r as f64 * CELL_PX,
                    (c - first) as f64 * CELL_PX,
                    -((c - first) as f64 * CELL_PX)
                );
            }
        }
    }
    let _ = writeln!(svg, r##"<g fill-opacity="{HEAT_OPACITY}">"##);
    for (i, d) in by_step.iter().enumerate().filter(|(_, d)| !d.is_empty()) {
        let _ = writeln!(
            svg,
            r##"<path d="{d}" fill="{}" shape-rendering="crispEdges"/>"##,
            step_colour(i)
        );
    }
    let _ = writeln!(svg, "</g>");
}

/// The sites: a dashed circle at each one's reference distance and a marker at the site; the
/// network's in dark red, pop-up ones in magenta.
pub(super) fn sites(svg: &mut String, threats: &[ThreatMark], view: &View) {
    for t in threats {
        let (x, y) = view.px(t.centre.0, t.centre.1);
        let colour = if t.popped { POPPED_COLOUR } else { SITE_COLOUR };
        let _ = writeln!(
            svg,
            r##"<circle class="threat" cx="{x:.1}" cy="{y:.1}" r="{:.1}" fill="none" stroke="{colour}" stroke-width="1.5" stroke-dasharray="6 4"/>"##,
            t.radius * view.scale
        );
        let _ = writeln!(
            svg,
            r##"<path d="M{:.1} {y:.1}l6 -6l6 6l-6 6Z" fill="{colour}" stroke="#fff" stroke-width="1"/>"##,
            x - 6.0
        );
    }
}

/// The legend symbol of a threat site (`popped`: one that popped up in flight), for the panel's
/// legend (`{X}`, `{Y}` stand for its position).
pub(super) fn site_symbol(popped: bool) -> String {
    let colour = if popped { POPPED_COLOUR } else { SITE_COLOUR };
    format!(
        r##"<g transform="translate({{X}} {{Y}})"><circle cx="16" cy="0" r="12" fill="none" stroke="{colour}" stroke-width="1.5" stroke-dasharray="4 3"/><path d="M10 0l6 -6l6 6l-6 6Z" fill="{colour}"/></g>"##
    )
}

/// The heat map's colour bar with its decades, `width` pixels wide, its top at `(x, y)`.
pub(super) fn colour_bar(svg: &mut String, x: f64, y: f64, width: f64) {
    let _ = writeln!(
        svg,
        r##"<text x="{x:.1}" y="{:.1}" font-size="13" fill="#333">{}</text>"##,
        y - 6.0,
        xml("exposure per metre flown, Σ (r/d)⁴ (log scale)")
    );
    let n = step_count();
    let w = width / n as f64;
    for i in 0..n {
        let _ = writeln!(
            svg,
            r##"<rect x="{:.1}" y="{y:.1}" width="{:.2}" height="12" fill="{}" fill-opacity="{HEAT_OPACITY}"/>"##,
            x + i as f64 * w,
            w + 0.3,
            step_colour(i)
        );
    }
    let _ = writeln!(
        svg,
        r##"<rect x="{x:.1}" y="{y:.1}" width="{width:.1}" height="12" fill="none" stroke="#555" stroke-width="0.8"/>"##
    );
    let decades = (LOG_RANGE.1 - LOG_RANGE.0).round() as i32;
    for d in 0..=decades {
        let e = LOG_RANGE.0 as i32 + d;
        let tx = x + width * d as f64 / decades as f64;
        let label = match e {
            0 => "1".to_string(),
            1 => "10".to_string(),
            _ => format!("10{}", superscript(e)),
        };
        let _ = writeln!(
            svg,
            r##"<path d="M{tx:.1} {:.1}v5" stroke="#555"/><text x="{tx:.1}" y="{:.1}" font-size="12" text-anchor="middle" fill="#333">{label}</text>"##,
            y + 12.0,
            y + 29.0
        );
    }
}

/// An integer in superscript digits.
fn superscript(e: i32) -> String {
    let digits = ['⁰', '¹', '²', '³', '⁴', '⁵', '⁶', '⁷', '⁸', '⁹'];
    let mut s = String::new();
    if e < 0 {
        s.push('⁻');
    }
    for ch in e.unsigned_abs().to_string().chars() {
        s.push(digits[ch.to_digit(10).unwrap_or(0) as usize]);
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn density_is_one_at_the_reference_distance_and_steps_cover_the_range() {
        let t = [ThreatMark {
            centre: (0.0, 0.0),
            radius: 2000.0,
            popped: false,
        }];
        assert!((exposure_density(&t, 2000.0, 0.0) - 1.0).abs() < 1e-12);
        assert_eq!(step_of(0.009), None);
        assert_eq!(step_of(0.01), Some(0));
        assert_eq!(step_of(1e9), Some(step_count() - 1));
        assert_eq!(superscript(-2), "⁻²");
        assert_eq!(step_colour(0).len(), 7);
    }
}
