//! Histograms of the Monte Carlo study's realised risk, as SVG (and PNG through
//! [`crate::render::svg_to_png`]).

use std::fmt::Write;

/// What one histogram shows.
pub struct Histogram<'a> {
    /// The title.
    pub title: &'a str,
    /// Counts per bin over [0, `top`).
    pub counts: &'a [u64],
    /// The upper end of the last bin.
    pub top: f64,
    /// The mean, drawn as a vertical line.
    pub mean: f64,
    /// The bars' colour.
    pub colour: &'a str,
}

/// The histogram as an SVG document: bars as the share of missions per bin, the axes with
/// their ticks, the mean marked.
pub fn histogram_svg(h: &Histogram) -> String {
    let (w, ht, left, bottom, top_margin, right) = (900.0, 420.0, 70.0, 60.0, 50.0, 20.0);
    let (pw, ph) = (w - left - right, ht - top_margin - bottom);
    let total: u64 = h.counts.iter().sum::<u64>().max(1);
    let shares: Vec<f64> = h.counts.iter().map(|&c| c as f64 / total as f64).collect();
    let ymax = shares.iter().cloned().fold(0.0, f64::max).max(1e-9);
    let ytop = (ymax * 10.0).ceil() / 10.0;
    let x = |r: f64| left + pw * r / h.top;
    let y = |s: f64| top_margin + ph * (1.0 - s / ytop);
    let mut out = String::new();
    let _ = write!(
        out,
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{ht}\" \
         font-family=\"sans-serif\" font-size=\"13\">\
         <rect width=\"{w}\" height=\"{ht}\" fill=\"white\"/>\
         <text x=\"{}\" y=\"28\" text-anchor=\"middle\" font-size=\"16\">{}</text>",
        w / 2.0,
        h.title
    );
    let bw = pw / h.counts.len().max(1) as f64;
    for (i, &s) in shares.iter().enumerate() {
        if s > 0.0 {
            let _ = write!(
                out,
                "<rect x=\"{:.2}\" y=\"{:.2}\" width=\"{:.2}\" height=\"{:.2}\" fill=\"{}\"/>",
                left + bw * i as f64,
                y(s),
                bw.max(1.0),
                y(0.0) - y(s),
                h.colour
            );
        }
    }
    let _ = write!(
        out,
        "<line x1=\"{left}\" y1=\"{0}\" x2=\"{1}\" y2=\"{0}\" stroke=\"black\"/>\
         <line x1=\"{left}\" y1=\"{top_margin}\" x2=\"{left}\" y2=\"{0}\" stroke=\"black\"/>",
        y(0.0),
        left + pw
    );
    for k in 0..=5 {
        let r = h.top * k as f64 / 5.0;
        let _ = write!(
            out,
            "<text x=\"{:.1}\" y=\"{:.1}\" text-anchor=\"middle\">{r:.3}</text>",
            x(r),
            y(0.0) + 18.0
        );
        let s = ytop * k as f64 / 5.0;
        let _ = write!(
            out,
            "<text x=\"{:.1}\" y=\"{:.1}\" text-anchor=\"end\">{s:.2}</text>",
            left - 6.0,
            y(s) + 4.0
        );
    }
    let (cx, ly, my) = (left + pw / 2.0, ht - 14.0, top_margin + ph / 2.0);
    let (mx, y0, mean) = (x(h.mean), y(0.0), h.mean);
    let _ = write!(
        out,
        "<text x=\"{cx:.1}\" y=\"{ly:.1}\" text-anchor=\"middle\">realised risk (kill \
         probability of the mission)</text>\
         <text x=\"16\" y=\"{my:.1}\" transform=\"rotate(-90 16 {my:.1})\" \
         text-anchor=\"middle\">share of missions</text>\
         <line x1=\"{mx:.2}\" y1=\"{top_margin}\" x2=\"{mx:.2}\" y2=\"{y0:.2}\" \
         stroke=\"black\" stroke-dasharray=\"5,4\"/>\
         <text x=\"{tx:.2}\" y=\"{ty:.1}\">mean {mean:.4}</text></svg>",
        tx = mx + 5.0,
        ty = top_margin + 14.0,
    );
    out
}
