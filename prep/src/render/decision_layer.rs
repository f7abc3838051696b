//! A route that flies a decision among pop-up bypass alternatives (`plan --popup-appears`): on
//! the map the nominal route (grey, dashed), every alternative thin in its pop-up's colour and
//! the chosen ones bold, under the route flown; in the panel a legend with each alternative's
//! length, risk R_K, time factor and fuel factor, the choice marked, and the decision's figures
//! against the limits.

use super::draw::{path_data, xml, View};
use super::picture::{DecisionMark, Route};
use skyroute::Primitive;
use std::fmt::Write as _;

/// Colours of the pop-ups' alternatives, one per pop-up in turn (apart from the route flown's
/// near-black and the pop-up discs' red).
const POPUP_COLOURS: [&str; 8] = [
    "#ef6c00", "#2e7d32", "#1565c0", "#8e24aa", "#00838f", "#9e9d24", "#6d4c41", "#d81b60",
];
/// The route flown over the alternatives.
pub(super) const FLOWN_COLOUR: &str = "#111111";
/// Its line width.
pub(super) const FLOWN_WIDTH: f64 = 2.0;
/// Line widths of an alternative not chosen and of a chosen one.
const THIN: f64 = 1.6;
const BOLD: f64 = 6.0;
/// The nominal route's colour.
const NOMINAL_COLOUR: &str = "#757575";

/// The colour of pop-up `u`'s alternatives.
fn popup_colour(u: usize) -> &'static str {
    POPUP_COLOURS[u % POPUP_COLOURS.len()]
}

/// Path data of a route's primitives.
fn path(prims: &[Primitive], view: &View) -> String {
    let mut d = String::new();
    let mut pen = None;
    for p in prims {
        path_data(&mut d, p, view, &mut pen);
    }
    d
}

/// Draws the decision on the map: the nominal route, the chosen alternatives bold, then every
/// other alternative thin (`class="alternative"`, chosen ones also `chosen`).
pub(super) fn map(svg: &mut String, d: &DecisionMark, view: &View) {
    let _ = writeln!(
        svg,
        r##"<path class="nominal" d="{}" fill="none" stroke="{NOMINAL_COLOUR}" stroke-width="2" stroke-dasharray="10 6"/>"##,
        path(&d.nominal, view)
    );
    for chosen in [true, false] {
        for (u, p) in d.popups.iter().enumerate() {
            for (k, a) in p.alternatives.iter().enumerate() {
                if (k == p.chosen) != chosen {
                    continue;
                }
                let _ = writeln!(
                    svg,
                    r##"<path class="alternative{}" data-popup="{}" data-alternative="{}" d="{}" fill="none" stroke="{}" stroke-width="{:.1}" stroke-opacity="{}" stroke-linejoin="round" stroke-linecap="round"/>"##,
                    if chosen { " chosen" } else { "" },
                    xml(&p.name),
                    k + 1,
                    path(&a.primitives, view),
                    popup_colour(u),
                    if chosen { BOLD } else { THIN },
                    if chosen { "0.55" } else { "0.9" }
                );
            }
        }
    }
}

/// One legend line: a symbol of `colour`, `width` and `dash` and the `label`, at `y`.
fn line(svg: &mut String, px0: f64, y: f64, colour: &str, width: f64, dash: &str, label: &str) {
    let _ = writeln!(
        svg,
        r##"<path d="M{px0:.1} {:.1}h28" stroke="{colour}" stroke-width="{width:.1}" stroke-dasharray="{dash}"/><text class="decision-legend" x="{:.1}" y="{y:.1}" font-size="12.5">{}</text>"##,
        y - 4.0,
        px0 + 36.0,
        xml(label)
    );
}

/// The panel's part for a route flying a decision, from `y` down: the route flown, the nominal
/// route, each pop-up's alternatives (length, R_K, f_t, F_c; the choice marked) and the
/// decision's figures against the limits. Returns where it ends.
pub(super) fn panel(
    svg: &mut String,
    route: &Route,
    d: &DecisionMark,
    px0: f64,
    mut y: f64,
) -> f64 {
    y += 8.0;
    let _ = writeln!(
        svg,
        r##"<text x="{px0:.1}" y="{y:.1}" font-size="15" font-weight="bold">decision among the bypass alternatives</text>"##
    );
    y += 22.0;
    let flown = format!("route flown: {:.2} km", route.length_m() / 1000.0);
    line(svg, px0, y, FLOWN_COLOUR, FLOWN_WIDTH, "none", &flown);
    y += 19.0;
    let nominal: f64 = d.nominal.iter().map(|p| p.length() as f64).sum();
    let nominal = format!("nominal route (no pop-ups): {:.2} km", nominal / 1000.0);
    line(svg, px0, y, NOMINAL_COLOUR, 2.0, "8 4", &nominal);
    y += 21.0;
    let _ = writeln!(
        svg,
        r##"<text x="{:.1}" y="{y:.1}" font-size="12" fill="#555">alternative: length, risk R_K, time f_t, fuel F_c</text>"##,
        px0 + 36.0
    );
    for (u, p) in d.popups.iter().enumerate() {
        y += 20.0;
        let _ = writeln!(
            svg,
            r##"<text x="{px0:.1}" y="{y:.1}" font-size="13.5" font-weight="bold" fill="{}">{} (P_A {})</text>"##,
            popup_colour(u),
            xml(&p.name),
            p.probability
        );
        for (k, a) in p.alternatives.iter().enumerate() {
            y += 18.0;
            let chosen = k == p.chosen;
            let label = format!(
                "{} {}: {:.2} km, {:.4}, {:.3}, {:.3}{}",
                if chosen { "▶" } else { " " },
                k + 1,
                a.length_m / 1000.0,
                a.risk,
                a.time,
                a.fuel,
                if chosen { "  chosen" } else { "" }
            );
            let width = if chosen { BOLD } else { THIN };
            line(svg, px0, y, popup_colour(u), width, "none", &label);
        }
    }
    y += 24.0;
    let _ = writeln!(
        svg,
        r##"<text class="decision-legend" x="{px0:.1}" y="{y:.1}" font-size="13" font-weight="bold">choice: Σ R_K {:.4}</text>"##,
        d.total_risk
    );
    y += 18.0;
    let _ = writeln!(
        svg,
        r##"<text class="decision-legend" x="{px0:.1}" y="{y:.1}" font-size="13" font-weight="bold">mean f_t {:.3} ≤ {:.3}, mean F_c {:.3} ≤ {:.3}</text>"##,
        d.mean_time, d.limits.0, d.mean_fuel, d.limits.1
    );
    y
}
