//! The terrain profile strip under the map, for a terrain network with a route: the terrain
//! elevation under the first route along its length (each cell's stored elevation, the upper
//! bound of its highest terrain), the route's altitude and the altitude less the safety height
//! (the highest terrain the route may fly over), against distance flown.

use super::draw::{metres, nice_length, xml, MARGIN_PX};
use super::picture::Route;
use skyroute::network::elevation::ELEVATION_BLOCKED;
use skyroute::Network;
use std::fmt::Write as _;

/// The strip's height below the map, pixels (title, plot and distance labels).
pub(super) const STRIP_PX: f64 = 210.0;
/// The terrain's fill.
pub(super) const TERRAIN_COLOUR: &str = "#a1887f";
/// The route altitude's colour.
pub(super) const ALTITUDE_COLOUR: &str = "#1565c0";
/// The safety threshold's colour.
pub(super) const SAFETY_COLOUR: &str = "#c62828";
/// The most samples along a route.
const MAX_SAMPLES: usize = 4000;

/// The profile of a route over a terrain network.
#[derive(Clone, Debug)]
pub(super) struct Profile {
    /// `(s, x, y, elevation)`: distance along the route, the point in the local frame
    /// (metres) and the elevation of its cell (metres; `None` over a cell of unknown
    /// elevation).
    pub(super) samples: Vec<(f64, f64, f64, Option<f64>)>,
    /// The route's length, metres.
    pub(super) length_m: f64,
    /// The altitude it flies at, metres.
    pub(super) altitude_m: f64,
    /// The network's safety height, metres.
    pub(super) safety_m: f64,
}

/// The profile of `route` over `net`, sampled every half cell along its primitives (at most
/// [`MAX_SAMPLES`] points); `None` unless `net` is a terrain network and the route has length.
/// The altitude is the route file's `altitude_m`, else the network's.
pub(super) fn profile(net: &Network, route: &Route) -> Option<Profile> {
    let (t, grid, coding) = (net.terrain()?, net.terrain_grid()?, net.elevation_coding()?);
    let prims: Vec<_> = route.legs.iter().flat_map(|l| &l.primitives).collect();
    let length_m: f64 = prims.iter().map(|p| p.length() as f64).sum();
    if !length_m.is_finite() || length_m <= 0.0 {
        return None;
    }
    let step = (0.5 * grid.cell as f64).max(length_m / MAX_SAMPLES as f64);
    let mut samples = Vec::new();
    let mut at = 0.0;
    for p in prims {
        let len = p.length() as f64;
        let n = (len / step).ceil().max(1.0) as usize;
        for k in 0..=n {
            let s = len * k as f64 / n as f64;
            let q = p.pose_at(s as f32).position;
            let e = grid
                .cell_of(q)
                .map(|(c, r)| net.elevation_code(c, r))
                .filter(|&code| code != ELEVATION_BLOCKED)
                .map(|code| coding.upper_bound(code) as f64);
            samples.push((at + s, q.x as f64, q.y as f64, e));
        }
        at += len;
    }
    Some(Profile {
        samples,
        length_m,
        altitude_m: route.altitude_m.unwrap_or(t.altitude_m as f64),
        safety_m: t.safety_height_m as f64,
    })
}

/// Draws the profile in a strip `width` pixels wide whose top is at `top`.
pub(super) fn strip(svg: &mut String, p: &Profile, top: f64, width: f64) {
    let (x0, plot_top) = (MARGIN_PX + 58.0, top + 30.0);
    let (plot_w, plot_h) = (width - 58.0 - 10.0, STRIP_PX - 30.0 - 46.0);
    let floor = p.altitude_m - p.safety_m;
    let known = p.samples.iter().filter_map(|s| s.3);
    let lo = known.clone().fold(floor.min(p.altitude_m), f64::min);
    let hi = known.fold(p.altitude_m, f64::max);
    let tick = nice_length(((hi - lo) / 3.0).max(1.0));
    let (lo, hi) = ((lo / tick).floor() * tick, (hi / tick).ceil() * tick);
    let sx = |s: f64| x0 + s / p.length_m * plot_w;
    let sy = |e: f64| plot_top + (hi - e) / (hi - lo) * plot_h;
    let bottom = plot_top + plot_h;
    let _ = writeln!(
        svg,
        r##"<g class="profile"><text x="{MARGIN_PX:.1}" y="{:.1}" font-size="14" font-weight="bold">terrain profile along the route: elevation (m) against distance flown</text>"##,
        top + 16.0
    );
    let _ = writeln!(
        svg,
        r##"<rect x="{x0:.1}" y="{plot_top:.1}" width="{plot_w:.1}" height="{plot_h:.1}" fill="#fbfbf8" stroke="#888"/>"##
    );
    // Elevation ticks and labels.
    let mut e = lo;
    while e <= hi + 1e-9 {
        let y = sy(e);
        let _ = writeln!(
            svg,
            r##"<path d="M{x0:.1} {y:.1}h{plot_w:.1}" stroke="#e2e2dc"/><text x="{:.1}" y="{:.1}" font-size="11" text-anchor="end">{e:.0} m</text>"##,
            x0 - 4.0,
            y + 4.0
        );
        e += tick;
    }
    // The terrain, one closed shape per run of known cells.
    let mut d = String::new();
    let mut data = String::new();
    let mut run: Vec<(f64, f64)> = Vec::new();
    let close = |d: &mut String, run: &mut Vec<(f64, f64)>| {
        if let (Some(a), Some(b)) = (run.first(), run.last()) {
            let _ = write!(d, "M{:.1} {bottom:.1}", a.0);
            for (x, y) in run.iter() {
                let _ = write!(d, "L{x:.1} {y:.1}");
            }
            let _ = write!(d, "L{:.1} {bottom:.1}Z", b.0);
        }
        run.clear();
    };
    for &(s, x, y, e) in &p.samples {
        let _ = write!(
            data,
            "{}{s:.1}:{x:.1}:{y:.1}:{}",
            if data.is_empty() { "" } else { " " },
            e.map_or("-".to_string(), |e| format!("{e:.2}"))
        );
        match e {
            Some(e) => run.push((sx(s), sy(e))),
            None => close(&mut d, &mut run),
        }
    }
    close(&mut d, &mut run);
    let _ = writeln!(
        svg,
        r##"<path class="profile-terrain" d="{d}" fill="{TERRAIN_COLOUR}" fill-opacity="0.75" stroke="#6d4c41" stroke-width="1" data-samples="{data}"/>"##
    );
    for (class, alt, colour, extra) in [
        (
            "profile-safety",
            floor,
            SAFETY_COLOUR,
            r#" stroke-dasharray="6 4""#,
        ),
        ("profile-altitude", p.altitude_m, ALTITUDE_COLOUR, ""),
    ] {
        let _ = writeln!(
            svg,
            r##"<path class="{class}" d="M{x0:.1} {:.1}h{plot_w:.1}" stroke="{colour}" stroke-width="2"{extra} data-altitude-m="{alt}"/>"##,
            sy(alt)
        );
    }
    distance_ticks(svg, p.length_m, (x0, bottom, plot_w));
    let _ = writeln!(
        svg,
        r##"<text x="{:.1}" y="{:.1}" font-size="12" fill="#333">{}</text></g>"##,
        x0,
        bottom + 36.0,
        xml(&format!(
            "route altitude {:.0} m (blue); highest terrain it may fly over, {:.0} m (red, \
             dashed); route length {:.1} km",
            p.altitude_m,
            floor,
            p.length_m / 1000.0
        ))
    );
}

/// The distance axis under the plot `(x0, bottom, plot_w)`: ticks at round distances.
fn distance_ticks(svg: &mut String, length_m: f64, (x0, bottom, plot_w): (f64, f64, f64)) {
    let tick = nice_length((length_m / 6.0).max(1.0));
    let mut s = 0.0;
    while s <= length_m + 1e-9 {
        let x = x0 + s / length_m * plot_w;
        let _ = writeln!(
            svg,
            r##"<path d="M{x:.1} {bottom:.1}v5" stroke="#555"/><text x="{x:.1}" y="{:.1}" font-size="11" text-anchor="middle">{}</text>"##,
            bottom + 17.0,
            metres(s)
        );
        s += tick;
    }
}
