//! Pop-ups, start, waypoints and goal with their labels, and the north arrow.

use super::draw::{clamp_label, label_box, map_text, text, View, MARGIN_PX};
use super::picture::{EndpointMark, PopupMark};
use std::fmt::Write as _;

/// Pop-ups: the disc, and the clearance kept from it dashed.
pub(super) fn popups(svg: &mut String, popups: &[PopupMark], view: &View, clearance: f64) {
    let scale = view.scale;
    // Pop-ups: the disc, and the clearance kept from it dashed.
    for c in popups {
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
}

/// Endpoints: heading ticks and markers.
pub(super) fn endpoints(svg: &mut String, endpoints: &[EndpointMark], view: &View) {
    // Endpoints: heading ticks, markers, labels.
    for e in endpoints {
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
}

/// The labels of the endpoints and pop-ups on the map (a pop-up's when its disc's box reaches
/// the map). Drawn last, so no line covers them, unclipped and moved inside the map where they
/// would reach past it ([`map_text`]), so none is cut at the map's edge; each endpoint's goes
/// where [`endpoint_label`] puts it.
pub(super) fn labels(
    svg: &mut String,
    endpoints: &[EndpointMark],
    popups: &[PopupMark],
    view: &View,
) {
    let scale = view.scale;
    for (at, anchor, label) in endpoints.iter().filter_map(|e| endpoint_label(e, view)) {
        map_text(svg, view, at, ENDPOINT_LABEL_PX, anchor, "#000", &label);
    }
    for c in popups {
        let (x, y) = view.px(c.centre.0, c.centre.1);
        if !view.shows((x, y), c.radius * scale) {
            continue;
        }
        map_text(
            svg,
            view,
            (x, y - c.radius * scale - 6.0),
            14.0,
            "middle",
            "#b71c1c",
            &format!("{} ({:.0} m)", c.name, c.radius),
        );
    }
}

/// The endpoints' labels' font size, pixels.
const ENDPOINT_LABEL_PX: f64 = 17.0;

/// Where an endpoint's label goes (before [`map_text`] keeps it inside the map), how it is
/// anchored and what it says; `None` for an endpoint off the map. It goes on the side away
/// from the heading tick, or under the marker when it would reach past the map's side.
fn endpoint_label(e: &EndpointMark, view: &View) -> Option<((f64, f64), &'static str, String)> {
    let (x, y) = view.px(e.position.0, e.position.1);
    if !view.shows((x, y), 1.0) {
        return None;
    }
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
    let (cx, _) = clamp_label(view, (lx, ly), ENDPOINT_LABEL_PX, anchor, &label);
    if (cx - lx).abs() > 4.0 {
        Some(((x, y + 28.0), "middle", label))
    } else {
        Some(((lx, ly), anchor, label))
    }
}

/// The boxes (pixels) the endpoints' markers and labels take, for other labels to keep clear
/// of.
pub(super) fn endpoint_boxes(endpoints: &[EndpointMark], view: &View) -> Vec<[f64; 4]> {
    let mut boxes = Vec::new();
    for e in endpoints {
        let (x, y) = view.px(e.position.0, e.position.1);
        boxes.push([x - 8.0, y - 8.0, x + 8.0, y + 8.0]);
        if let Some((at, anchor, label)) = endpoint_label(e, view) {
            boxes.push(label_box(view, at, ENDPOINT_LABEL_PX, anchor, &label));
        }
    }
    boxes
}

/// The north arrow in the map's top-left corner.
pub(super) fn north_arrow(svg: &mut String) {
    let (x, y) = (MARGIN_PX + 28.0, MARGIN_PX + 20.0);
    let _ = writeln!(
        svg,
        r##"<path d="M{x:.1} {y:.1}l-9 28l9 -7l9 7Z" fill="#000"/>"##
    );
    text(svg, x, y + 48.0, 16.0, "middle", "#000", "N");
}
