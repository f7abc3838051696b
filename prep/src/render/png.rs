//! PNG output: the SVG rasterised with resvg and written as 8-bit indexed colour.

/// Rasterises an SVG document with resvg, using the system's fonts for text.
#[cfg(feature = "png")]
pub fn svg_to_png(svg: &str) -> Result<Vec<u8>, String> {
    let mut opt = resvg::usvg::Options::default();
    opt.fontdb_mut().load_system_fonts();
    let tree = resvg::usvg::Tree::from_str(svg, &opt).map_err(|e| format!("SVG: {e}"))?;
    let size = tree.size().to_int_size();
    let mut pixmap =
        resvg::tiny_skia::Pixmap::new(size.width(), size.height()).ok_or_else(|| {
            format!(
                "cannot allocate a {}x{} picture",
                size.width(),
                size.height()
            )
        })?;
    resvg::render(
        &tree,
        resvg::tiny_skia::Transform::default(),
        &mut pixmap.as_mut(),
    );
    encode_indexed_png(&pixmap).map_err(|e| format!("PNG: {e}"))
}

/// Why a build without the `png` feature writes no PNG.
pub(crate) const WITHOUT_PNG: &str =
    "PNG output needs the ground tool built with its `png` feature (on by default); write .svg";

/// Refuses: this build of the tool has no PNG encoder (the `png` feature is off).
#[cfg(not(feature = "png"))]
pub fn svg_to_png(_svg: &str) -> Result<Vec<u8>, String> {
    Err(WITHOUT_PNG.to_string())
}

/// Encodes a picture as an 8-bit indexed PNG: a map of thin anti-aliased lines is several times
/// smaller that way than as RGBA, and looks the same. The palette is the picture's 256 most
/// frequent colours (so every fill, line and text colour, each of which covers many pixels, is
/// kept exactly; a picture of at most 256 colours is encoded losslessly), and every other colour
/// — the anti-aliased fringes — becomes its nearest palette colour. Transparent pixels are
/// composed over white (the pictures drawn here are opaque anyway).
#[cfg(feature = "png")]
fn encode_indexed_png(pixmap: &resvg::tiny_skia::Pixmap) -> Result<Vec<u8>, png::EncodingError> {
    use std::collections::HashMap;
    let rgb: Vec<[u8; 3]> = pixmap
        .pixels()
        .iter()
        .map(|p| {
            // Premultiplied, so over white: c + (255 − a).
            let white = 255 - p.alpha();
            [p.red() + white, p.green() + white, p.blue() + white]
        })
        .collect();
    let mut counts: HashMap<[u8; 3], u32> = HashMap::new();
    for c in &rgb {
        *counts.entry(*c).or_insert(0) += 1;
    }
    let mut by_count: Vec<([u8; 3], u32)> = counts.iter().map(|(c, n)| (*c, *n)).collect();
    // Most frequent first; ties by colour, so the output does not depend on hashing order.
    by_count.sort_by(|a, b| b.1.cmp(&a.1).then(a.0.cmp(&b.0)));
    let palette: Vec<[u8; 3]> = by_count.iter().take(256).map(|(c, _)| *c).collect();
    let distance = |a: [u8; 3], b: [u8; 3]| {
        // Weighted RGB distance (red 2, green 4, blue 3): cheap and close enough to perception.
        let d = |i: usize| (a[i] as i32 - b[i] as i32).pow(2);
        2 * d(0) + 4 * d(1) + 3 * d(2)
    };
    let index: HashMap<[u8; 3], u8> = by_count
        .iter()
        .map(|(c, _)| {
            let k = (0..palette.len())
                .min_by_key(|&k| distance(*c, palette[k]))
                .unwrap_or(0);
            (*c, k as u8)
        })
        .collect();
    let indices: Vec<u8> = rgb.iter().map(|c| index[c]).collect();
    let mut out = Vec::new();
    {
        let mut enc = png::Encoder::new(&mut out, pixmap.width(), pixmap.height());
        enc.set_color(png::ColorType::Indexed);
        enc.set_depth(png::BitDepth::Eight);
        enc.set_palette(palette.concat());
        enc.set_compression(png::Compression::High);
        let mut w = enc.write_header()?;
        w.write_image_data(&indices)?;
    }
    Ok(out)
}
