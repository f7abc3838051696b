//! Drawing helpers shared by the layers: the page's constants, XML escaping, the map view, path
//! data for lines and arcs, bounding boxes, round lengths and labels.

use skyroute::network::Mode;
use skyroute::{Network, Primitive, Vec2};
use std::f64::consts::FRAC_PI_2;
use std::fmt::Write as _;

/// Colours of the route's legs, in turn.
pub(super) const LEG_COLOURS: [&str; 7] = [
    "#1565c0", "#ef6c00", "#6a1b9a", "#00897b", "#c2185b", "#5d4037", "#827717",
];
pub(super) const FONT: &str = "DejaVu Sans, Liberation Sans, Arial, Helvetica, sans-serif";
pub(super) const PANEL_PX: f64 = 400.0;
pub(super) const MARGIN_PX: f64 = 30.0;

/// Escapes text for XML.
pub(super) fn xml(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// Maps the local frame (metres, `y` north) to the picture (pixels, `y` down), and the map's
/// size in pixels (its top-left corner is at `(MARGIN_PX, MARGIN_PX)`).
#[derive(Clone, Copy, Debug)]
pub(super) struct View {
    pub(super) min_x: f64,
    pub(super) max_y: f64,
    pub(super) scale: f64,
    pub(super) map_w: f64,
    pub(super) map_h: f64,
}

impl View {
    pub(super) fn px(&self, x: f64, y: f64) -> (f64, f64) {
        (
            MARGIN_PX + (x - self.min_x) * self.scale,
            MARGIN_PX + (self.max_y - y) * self.scale,
        )
    }
    pub(super) fn pv(&self, p: Vec2) -> (f64, f64) {
        self.px(p.x as f64, p.y as f64)
    }
    /// Whether the pixel `(x, y)` lies on the map, or within `reach` pixels of it.
    pub(super) fn shows(&self, (x, y): (f64, f64), reach: f64) -> bool {
        let inside = |v: f64, len: f64| v >= MARGIN_PX - reach && v <= MARGIN_PX + len + reach;
        inside(x, self.map_w) && inside(y, self.map_h)
    }
}

/// Appends path data for a primitive. Starts with a move when `pen` (the current point, pixels)
/// is not already at the primitive's start.
pub(super) fn path_data(d: &mut String, p: &Primitive, view: &View, pen: &mut Option<(f64, f64)>) {
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
pub(super) struct BBox(
    pub(super) f64,
    pub(super) f64,
    pub(super) f64,
    pub(super) f64,
);

impl BBox {
    pub(super) fn empty() -> Self {
        BBox(
            f64::INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NEG_INFINITY,
        )
    }
    pub(super) fn add(&mut self, x: f64, y: f64) {
        if x.is_finite() && y.is_finite() {
            *self = BBox(self.0.min(x), self.1.min(y), self.2.max(x), self.3.max(y));
        }
    }
    pub(super) fn add_box(&mut self, lo: Vec2, hi: Vec2) {
        self.add(lo.x as f64, lo.y as f64);
        self.add(hi.x as f64, hi.y as f64);
    }
    pub(super) fn is_empty(&self) -> bool {
        !(self.0 <= self.2 && self.1 <= self.3)
    }
}

/// A round length near `target` metres: 1, 2 or 5 times a power of ten.
pub(super) fn nice_length(target: f64) -> f64 {
    let p = 10f64.powf(target.log10().floor());
    [5.0, 2.0, 1.0]
        .into_iter()
        .map(|m| m * p)
        .find(|&l| l <= target)
        .unwrap_or(p)
}

pub(super) fn metres(m: f64) -> String {
    if m >= 1000.0 && (m % 1000.0).abs() < 1e-9 {
        format!("{} km", m / 1000.0)
    } else {
        format!("{m} m")
    }
}

/// Bold text with a white halo, so that it stays legible over lines.
pub(super) fn text(svg: &mut String, x: f64, y: f64, size: f64, anchor: &str, fill: &str, s: &str) {
    let _ = writeln!(
        svg,
        r##"<text x="{x:.1}" y="{y:.1}" font-size="{size}" text-anchor="{anchor}" font-weight="bold" fill="{fill}" stroke="#fff" stroke-width="3" stroke-linejoin="round" paint-order="stroke">{}</text>"##,
        xml(s)
    );
}

/// [`text`] at `(x, y)` moved as little as needed to lie wholly inside the map (its width
/// estimated from the number of characters), so that no label is cut at the map's edge or
/// reaches past the picture.
pub(super) fn map_text(
    svg: &mut String,
    view: &View,
    (x, y): (f64, f64),
    size: f64,
    anchor: &str,
    fill: &str,
    s: &str,
) {
    let (x, y) = clamp_label(view, (x, y), size, anchor, s);
    text(svg, x, y, size, anchor, fill, s);
}

/// The position of a label of `s` at `size` anchored `anchor` at `(x, y)`, moved to lie wholly
/// inside the map: bold sans-serif characters are taken as at most 0.68 `size` wide, the text
/// as reaching `size` above its baseline and a quarter of it below.
pub(super) fn clamp_label(
    view: &View,
    (x, y): (f64, f64),
    size: f64,
    anchor: &str,
    s: &str,
) -> (f64, f64) {
    let w = 0.68 * size * s.chars().count() as f64;
    let before = match anchor {
        "end" => w,
        "middle" => w / 2.0,
        _ => 0.0,
    };
    let pad = 3.0;
    let (x0, x1) = (MARGIN_PX + pad, MARGIN_PX + view.map_w - pad);
    let (y0, y1) = (MARGIN_PX + pad, MARGIN_PX + view.map_h - pad);
    // The left edge wins when the text is wider than the map.
    let x = x.min(x1 - (w - before)).max(x0 + before);
    let y = y.min(y1 - 0.25 * size).max(y0 + size);
    (x, y)
}

/// The box `[x0, y0, x1, y1]` (pixels) a label takes once [`clamp_label`] has placed it, by the
/// same estimate of its size.
pub(super) fn label_box(view: &View, at: (f64, f64), size: f64, anchor: &str, s: &str) -> [f64; 4] {
    let (x, y) = clamp_label(view, at, size, anchor, s);
    let w = 0.68 * size * s.chars().count() as f64;
    let left = match anchor {
        "end" => x - w,
        "middle" => x - w / 2.0,
        _ => x,
    };
    [left, y - size, left + w, y + 0.25 * size]
}

/// Whether two boxes `[x0, y0, x1, y1]` overlap.
pub(super) fn overlap(a: &[f64; 4], b: &[f64; 4]) -> bool {
    a[0] < b[2] && b[0] < a[2] && a[1] < b[3] && b[1] < a[3]
}

/// Whether a network is drawn as a Voronoi network (heat map, threat sites, dark edges).
pub(super) fn is_voronoi(net: &Network) -> bool {
    match net.mode() {
        Mode::Voronoi => true,
        Mode::Roadmap | Mode::Landmark | Mode::Terrain | Mode::Unknown(_) => false,
    }
}

/// Whether a network is a landmark network (landmark symbols, Hermite chain edges).
pub(super) fn is_landmark(net: &Network) -> bool {
    match net.mode() {
        Mode::Landmark => true,
        Mode::Roadmap | Mode::Terrain | Mode::Voronoi | Mode::Unknown(_) => false,
    }
}

/// Whether a network is drawn as a terrain network (blocked cells, no edge legend).
pub(super) fn is_terrain(net: &Network) -> bool {
    match net.mode() {
        Mode::Terrain => true,
        Mode::Roadmap | Mode::Landmark | Mode::Voronoi | Mode::Unknown(_) => false,
    }
}
