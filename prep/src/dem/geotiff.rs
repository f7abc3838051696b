//! GeoTIFF DEMs (SRTM, Copernicus GLO-30, or any single-band elevation GeoTIFF GDAL writes).
//!
//! The raster and the TIFF tags are read with the [`tiff`] crate (image-rs: the maintained
//! pure-Rust TIFF codec the `image` crate uses; no C library), the GeoTIFF tags by this module:
//! the GeoKey directory (tag 34735), ModelPixelScale (33550), ModelTiepoint (33922),
//! ModelTransformation (34264) and GDAL's no-data value (GDAL_NODATA, 42113). The `geotiff`
//! crates were not used: georust's `geotiff` 0.1 announces breaking redesigns, and the others
//! are young single-author projects; the handful of tags a DEM needs is little code.
//!
//! # What is read
//!
//! * **Samples**: one sample per pixel (tag 277), 8/16/32/64-bit unsigned or signed integers or
//!   16/32/64-bit floats (tag 339; SRTM is Int16, Copernicus Float32), in strips or tiles,
//!   uncompressed, LZW, Deflate or PackBits (tag 259), with or without a predictor (tag 317).
//!   Elevations are stored as `f32` (exact for 16-bit integers).
//! * **Where**: one tiepoint and the pixel scale, or a ModelTransformation without rotation or
//!   shear. The cells may be non-square. With `GTRasterTypeGeoKey` = PixelIsPoint the tiepoint
//!   is a cell's centre (and the grid is moved by half a cell, as GDAL does).
//! * **Coordinate system** ([`Units`]): geographic degrees on WGS 84 (EPSG 4326), NAD83 (4269)
//!   or ETRS89 (4258) — these datums lie within about 1.5 m of each other, far below a DEM
//!   cell, and are all taken as WGS-84 — or UTM metres on the same datums (EPSG 32601–32660,
//!   32701–32760, 26901–26923, 25828–25838). Anything else (another projection, a datum far
//!   from WGS-84, units other than degrees or metres) is refused by name. A file without a
//!   GeoKey directory is taken as geographic or unnamed-projected by the rule of the ASCII
//!   reader ([`super::ascii`]). Elevations are metres (a `VerticalUnitsGeoKey` other than
//!   metres is refused); the vertical datum is the file's (EGM96/EGM2008 for SRTM and GLO-30),
//!   and the scenario's `altitude_m` is on the same datum.
//! * **No-data**: the GDAL_NODATA value, and NaN samples, are NODATA.
//!
//! # Limits
//!
//! Before anything is decoded: at most [`MAX_CELLS`] cells, and every strip or tile lies
//! within the file (a header claiming a large grid over a short file fails here, having
//! allocated nothing but the file). The elevations then grow strip by strip (or by one row of
//! tiles, once its first tile has decoded), so memory follows the data actually decoded; the
//! decoder itself refuses a chunk over 256 MiB (the `tiff` crate's default limit).
//!
//! Every error names the file and the tag (or GeoKey, or strip/tile, or cell):
//!
//! ```text
//! dem.tif: tag 34735 (GeoKeyDirectory) key 3072 (ProjectedCSTypeGeoKey): not supported: 3857 …
//! dem.tif: tag 259 (Compression): not supported: compression 34887 …
//! ```

use super::ascii::reverse_rows;
use super::{Dem, DemError, DemErrorKind, GridSpec, Units, MAX_CELLS};
use std::io::Cursor;
use std::path::Path;
use tiff::decoder::{ChunkType, Decoder, DecodingResult};
use tiff::tags::Tag;
use tiff::{ColorType, TiffError, TiffFormatError, TiffUnsupportedError};

/// The GeoKey directory's tag.
const GEO_KEYS: &str = "tag 34735 (GeoKeyDirectory)";

/// Whether `bytes` start with a TIFF or BigTIFF header (either byte order).
pub fn is_tiff(bytes: &[u8]) -> bool {
    matches!(
        bytes.get(..4),
        Some(b"II*\0") | Some(b"MM\0*") | Some(b"II+\0") | Some(b"MM\0+")
    )
}

/// An error about `path`, field `field`.
fn error(path: &Path, field: &str, kind: DemErrorKind) -> DemError {
    DemError {
        path: path.to_path_buf(),
        line: None,
        field: field.to_string(),
        kind,
    }
}

/// Reads the GeoTIFF `bytes`, read from `path` (used in errors; not read).
pub fn parse(bytes: &[u8], path: &Path) -> Result<Dem, DemError> {
    let invalid = |field: &str, m: String| error(path, field, DemErrorKind::Invalid(m));
    let mut dec = Decoder::new(Cursor::new(bytes)).map_err(|e| {
        invalid(
            &decoder_error_field(&e),
            format!("not a readable TIFF: {e}"),
        )
    })?;
    let dims_field = "tags 256, 257 (ImageWidth, ImageLength)";
    let (w, h) = dec
        .dimensions()
        .map_err(|e| invalid(dims_field, e.to_string()))?;
    let (ncols, nrows) = (w as usize, h as usize);
    if ncols == 0 || nrows == 0 {
        return Err(invalid(dims_field, format!("{ncols} x {nrows} cells")));
    }
    if ncols.checked_mul(nrows).is_none_or(|c| c > MAX_CELLS) {
        return Err(error(
            path,
            dims_field,
            DemErrorKind::TooLarge(ncols, nrows),
        ));
    }
    check_layout(&mut dec, path, bytes.len() as u64)?;
    let grid = georeferencing(&mut dec, path, (ncols, nrows))?;
    let nodata = match dec.find_tag(Tag::GdalNodata) {
        Ok(None) => None,
        Ok(Some(v)) => {
            let field = "tag 42113 (GDAL_NODATA)";
            let text = v
                .into_string()
                .map_err(|e| invalid(field, format!("not text: {e}")))?;
            let t = text.trim_matches(|c: char| c == '\0' || c.is_whitespace());
            Some(
                t.parse::<f64>()
                    .map_err(|_| error(path, field, DemErrorKind::NotANumber(t.to_string())))?,
            )
        }
        Err(e) => return Err(invalid("tag 42113 (GDAL_NODATA)", e.to_string())),
    };
    let mut values = read_samples(&mut dec, path, (ncols, nrows), nodata)?;
    reverse_rows(&mut values, ncols);
    Ok(Dem::new(path, grid, nodata, values, Vec::new()))
}

/// The tag a [`Decoder::new`] error is about, as far as the error says; empty when it is about
/// the whole file.
fn decoder_error_field(e: &TiffError) -> String {
    let tag = |t: &Tag| format!("tag {} ({t:?})", t.to_u16());
    let field = match e {
        TiffError::FormatError(f) => match f {
            TiffFormatError::UnknownPredictor(_) => "tag 317 (Predictor)",
            TiffFormatError::UnknownPlanarConfiguration(_) => "tag 284 (PlanarConfiguration)",
            TiffFormatError::InvalidDimensions(..) => "tags 256, 257 (ImageWidth, ImageLength)",
            TiffFormatError::SamplesPerPixelIsZero => "tag 277 (SamplesPerPixel)",
            TiffFormatError::InconsistentSizesEncountered
            | TiffFormatError::StripTileTagConflict => {
                "tags 273, 279, 322, 323, 324, 325 (the strips' or tiles' sizes and offsets)"
            }
            TiffFormatError::RequiredTagNotFound(t)
            | TiffFormatError::InvalidTagValueType(t)
            | TiffFormatError::InvalidCountForTag(t, _) => return tag(t),
            _ => "",
        },
        TiffError::UnsupportedError(u) => match u {
            TiffUnsupportedError::FloatingPointPredictor(_)
            | TiffUnsupportedError::HorizontalPredictor(_) => "tag 317 (Predictor)",
            TiffUnsupportedError::UnknownCompressionMethod
            | TiffUnsupportedError::UnsupportedCompressionMethod(_) => "tag 259 (Compression)",
            TiffUnsupportedError::UnsupportedSampleFormat(_) => "tag 339 (SampleFormat)",
            TiffUnsupportedError::InconsistentBitsPerSample(_)
            | TiffUnsupportedError::UnsupportedSampleDepth(_) => "tag 258 (BitsPerSample)",
            TiffUnsupportedError::InterpretationWithBits(..)
            | TiffUnsupportedError::UnknownInterpretation => "tag 262 (PhotometricInterpretation)",
            _ => "",
        },
        _ => "",
    };
    field.to_string()
}

/// Checks what the decoder must handle (one sample per pixel, a sample type and compression
/// it reads) and that every strip or tile lies within the file's `len` bytes.
fn check_layout(dec: &mut Decoder<Cursor<&[u8]>>, path: &Path, len: u64) -> Result<(), DemError> {
    let unsupported = |field: &str, m: String| error(path, field, DemErrorKind::Unsupported(m));
    let invalid = |field: &str, m: String| error(path, field, DemErrorKind::Invalid(m));
    let field = "tag 259 (Compression)";
    let compression = dec
        .find_tag_unsigned::<u16>(Tag::Compression)
        .map_err(|e| invalid(field, e.to_string()))?
        .unwrap_or(1);
    if !matches!(compression, 1 | 5 | 8 | 32773 | 32946) {
        return Err(unsupported(
            field,
            format!(
                "compression {compression} (this reader decodes none (1), LZW (5), Deflate (8, \
                 32946) and PackBits (32773))"
            ),
        ));
    }
    let field = "tag 317 (Predictor)";
    let predictor = dec
        .find_tag_unsigned::<u16>(Tag::Predictor)
        .map_err(|e| invalid(field, e.to_string()))?
        .unwrap_or(1);
    if !matches!(predictor, 1..=3) {
        return Err(unsupported(field, format!("predictor {predictor}")));
    }
    let field = "tags 277, 258, 339 (SamplesPerPixel, BitsPerSample, SampleFormat)";
    let bytes_per_sample = match dec.colortype() {
        Ok(ColorType::Gray(b @ (8 | 16 | 32 | 64))) => b as u64 / 8,
        Ok(c) => {
            return Err(unsupported(
                field,
                format!("{c:?} (a DEM has one 8-, 16-, 32- or 64-bit sample per pixel)"),
            ))
        }
        Err(e) => return Err(unsupported(field, e.to_string())),
    };
    let (kind, offsets, counts) = match dec.get_chunk_type() {
        ChunkType::Strip => (
            "strip",
            (Tag::StripOffsets, "tag 273 (StripOffsets)"),
            (Tag::StripByteCounts, "tag 279 (StripByteCounts)"),
        ),
        ChunkType::Tile => (
            "tile",
            (Tag::TileOffsets, "tag 324 (TileOffsets)"),
            (Tag::TileByteCounts, "tag 325 (TileByteCounts)"),
        ),
    };
    let starts = dec
        .get_tag_u64_vec(offsets.0)
        .map_err(|e| invalid(offsets.1, e.to_string()))?;
    let sizes = dec
        .get_tag_u64_vec(counts.0)
        .map_err(|e| invalid(counts.1, e.to_string()))?;
    let (w, h) = dec
        .dimensions()
        .map_err(|e| invalid("tag 256 (ImageWidth)", e.to_string()))?;
    let (cw, ch) = dec.chunk_dimensions();
    let (cw, ch) = (cw.max(1) as u64, ch.max(1) as u64);
    let expected = (w as u64).div_ceil(cw) * (h as u64).div_ceil(ch);
    for (tag, n) in [(offsets.1, starts.len()), (counts.1, sizes.len())] {
        if n as u64 != expected {
            let m = format!("{n} values for the {expected} {kind}s of the image");
            return Err(invalid(tag, m));
        }
    }
    for (i, (&start, &size)) in starts.iter().zip(&sizes).enumerate() {
        let end = start.checked_add(size);
        if end.is_none_or(|e| e > len) {
            let m = format!(
                "{kind} {i} (bytes {start} + {size}) ends past the end of the file ({len} bytes)"
            );
            return Err(invalid(counts.1, m));
        }
        // Uncompressed, a chunk holds all its samples: a strip `w` wide (the last may have
        // fewer rows), a tile `cw × ch` with its padding.
        let rows = if kind == "strip" {
            ch.min(h as u64 - (i as u64 * ch).min(h as u64))
        } else {
            ch
        };
        let need = cw * rows * bytes_per_sample;
        if compression == 1 && size < need {
            let m = format!("{kind} {i} has {size} bytes, uncompressed it needs {need}");
            return Err(invalid(counts.1, m));
        }
    }
    Ok(())
}

/// The grid's corner, cell sides and units from the GeoTIFF tags.
fn georeferencing(
    dec: &mut Decoder<Cursor<&[u8]>>,
    path: &Path,
    (ncols, nrows): (usize, usize),
) -> Result<GridSpec, DemError> {
    let unsupported = |field: &str, m: String| error(path, field, DemErrorKind::Unsupported(m));
    let invalid = |field: &str, m: String| error(path, field, DemErrorKind::Invalid(m));
    let doubles = |dec: &mut Decoder<Cursor<&[u8]>>, tag: u16, field: &str| match dec
        .find_tag(Tag::Unknown(tag))
    {
        Ok(None) => Ok(None),
        Ok(Some(v)) => match v.into_f64_vec() {
            Ok(v) if v.iter().all(|x| x.is_finite()) => Ok(Some(v)),
            Ok(v) => Err(invalid(field, format!("{v:?} holds a non-finite number"))),
            Err(e) => Err(invalid(field, format!("not numbers: {e}"))),
        },
        Err(e) => Err(invalid(field, e.to_string())),
    };
    let transform_field = "tag 34264 (ModelTransformation)";
    let tie_field = "tag 33922 (ModelTiepoint)";
    let scale_field = "tag 33550 (ModelPixelScale)";
    // (west edge, north edge, cell x, cell y)
    let (west, north, sx, sy, field) = if let Some(m) = doubles(dec, 34264, transform_field)? {
        if m.len() != 16 {
            return Err(invalid(
                transform_field,
                format!("{} values, not 16", m.len()),
            ));
        }
        if m[1] != 0.0 || m[4] != 0.0 || !(m[0] > 0.0 && m[5] < 0.0) {
            let m = format!(
                "a rotated, sheared or flipped raster (x = {} col + {} row + {}, y = {} col + {} \
                 row + {}); only north-up rasters are read",
                m[0], m[1], m[3], m[4], m[5], m[7]
            );
            return Err(unsupported(transform_field, m));
        }
        (m[3], m[7], m[0], -m[5], transform_field)
    } else {
        let tie = doubles(dec, 33922, tie_field)?;
        let scale = doubles(dec, 33550, scale_field)?;
        let (Some(tie), Some(scale)) = (tie, scale) else {
            let m = "missing: a GeoTIFF DEM needs ModelTiepoint (33922) and ModelPixelScale \
                     (33550), or ModelTransformation (34264)";
            return Err(invalid(tie_field, m.into()));
        };
        if tie.len() != 6 {
            let m = format!(
                "{} values: only one tiepoint (6 values) with a pixel scale is read, not \
                 ground control points",
                tie.len()
            );
            return Err(unsupported(tie_field, m));
        }
        if scale.len() < 2 || !(scale[0] > 0.0 && scale[1] > 0.0) {
            return Err(invalid(
                scale_field,
                format!("{scale:?}: the cell sides must be positive"),
            ));
        }
        let (sx, sy) = (scale[0], scale[1]);
        (
            tie[3] - tie[0] * sx,
            tie[4] + tie[1] * sy,
            sx,
            sy,
            tie_field,
        )
    };
    let keys = geo_keys(dec, path)?;
    let key = |id: u16| keys.iter().find(|k| k.0 == id).map(|k| k.1);
    let (west, north) = if key(1025) == Some(2) {
        // PixelIsPoint: the tiepoint is the centre of its cell.
        (west - 0.5 * sx, north + 0.5 * sy)
    } else {
        (west, north)
    };
    let (east, south) = (west + ncols as f64 * sx, north - nrows as f64 * sy);
    let units = match units_of(&keys, path)? {
        Some(u) => u,
        None => super::ascii::units_by_extent(west, south, east, north, sx.max(sy)),
    };
    let inside = (-180.0..=180.0).contains(&west)
        && (-180.0..=180.0).contains(&east)
        && (-90.0..=90.0).contains(&south)
        && (-90.0..=90.0).contains(&north);
    if units == Units::Geographic && !inside {
        let m = format!(
            "the grid spans longitude {west}..{east}, latitude {south}..{north}: not within \
             ±180° × ±90° for a geographic DEM"
        );
        return Err(invalid(field, m));
    }
    Ok(GridSpec {
        size: (ncols, nrows),
        corner: (west, south),
        cell: (sx, sy),
        units,
    })
}

/// The GeoKey directory's SHORT keys `(id, value)` (keys whose value lies in another tag are
/// left out; none of those this reader uses is one); empty when the file has no directory.
fn geo_keys(dec: &mut Decoder<Cursor<&[u8]>>, path: &Path) -> Result<Vec<(u16, u16)>, DemError> {
    let invalid = |m: String| error(path, GEO_KEYS, DemErrorKind::Invalid(m));
    let dir = match dec.find_tag(Tag::Unknown(34735)) {
        Ok(None) => return Ok(Vec::new()),
        Ok(Some(v)) => v
            .into_u16_vec()
            .map_err(|e| invalid(format!("not SHORT values: {e}")))?,
        Err(e) => return Err(invalid(e.to_string())),
    };
    let n = dir.get(3).copied().unwrap_or(0) as usize;
    if dir.len() < 4 || dir.len() < 4 + 4 * n {
        return Err(invalid(format!(
            "{} values, too few for its header and {n} keys",
            dir.len()
        )));
    }
    Ok(dir[4..4 + 4 * n]
        .chunks_exact(4)
        .filter(|k| k[1] == 0)
        .map(|k| (k[0], k[3]))
        .collect())
}

/// The units the GeoKeys name; `None` when there are no keys (see the module documentation).
fn units_of(keys: &[(u16, u16)], path: &Path) -> Result<Option<Units>, DemError> {
    if keys.is_empty() {
        return Ok(None);
    }
    let key = |id: u16| keys.iter().find(|k| k.0 == id).map(|k| k.1);
    let refuse = |id: u16, name: &str, value: u16, what: &str| {
        let field = format!("{GEO_KEYS} key {id} ({name})");
        error(
            path,
            &field,
            DemErrorKind::Unsupported(format!("{value}: {what}")),
        )
    };
    if let Some(u) = key(4099).filter(|&u| u != 9001) {
        let what = "elevations in units other than metres (9001)";
        return Err(refuse(4099, "VerticalUnitsGeoKey", u, what));
    }
    let model = key(1024).or(if key(3072).is_some() {
        Some(1)
    } else if key(2048).is_some() {
        Some(2)
    } else {
        None
    });
    match model {
        Some(2) => {
            let geographic = key(2048).unwrap_or(32767);
            let datum_ok = match geographic {
                4326 | 4269 | 4258 => true,
                32767 => matches!(key(2050), Some(6326 | 6269 | 6258)),
                _ => false,
            };
            if !datum_ok {
                let what = "only WGS 84 (4326), NAD83 (4269) and ETRS89 (4258) are read";
                return Err(refuse(2048, "GeographicTypeGeoKey", geographic, what));
            }
            if let Some(u) = key(2054).filter(|&u| u != 9102) {
                let what = "angular units other than degrees (9102)";
                return Err(refuse(2054, "GeogAngularUnitsGeoKey", u, what));
            }
            Ok(Some(Units::Geographic))
        }
        Some(1) => {
            let code = key(3072).unwrap_or(0);
            let utm = match code {
                32601..=32660 => Some((code - 32600, true)),
                32701..=32760 => Some((code - 32700, false)),
                26901..=26923 => Some((code - 26900, true)),
                25828..=25838 => Some((code - 25800, true)),
                _ => None,
            };
            let Some((zone, north)) = utm else {
                let what = "only UTM zones on WGS 84 (32601-32660, 32701-32760), NAD83 \
                            (26901-26923) or ETRS89 (25828-25838) are read";
                return Err(refuse(3072, "ProjectedCSTypeGeoKey", code, what));
            };
            if let Some(u) = key(3076).filter(|&u| u != 9001) {
                let what = "linear units other than metres (9001)";
                return Err(refuse(3076, "ProjLinearUnitsGeoKey", u, what));
            }
            Ok(Some(Units::Utm {
                zone: zone as u8,
                north,
            }))
        }
        Some(m) => Err(refuse(
            1024,
            "GTModelTypeGeoKey",
            m,
            "only projected (1) and geographic (2) rasters are read",
        )),
        None => Err(error(
            path,
            GEO_KEYS,
            DemErrorKind::Invalid("names no coordinate system (no key 1024, 2048 or 3072)".into()),
        )),
    }
}

/// Decodes every strip or tile into elevations, rows from the north; NODATA (`nodata`, or a
/// NaN sample) as NaN.
fn read_samples(
    dec: &mut Decoder<Cursor<&[u8]>>,
    path: &Path,
    (ncols, nrows): (usize, usize),
    nodata: Option<f64>,
) -> Result<Vec<f32>, DemError> {
    let (cw, ch) = dec.chunk_dimensions();
    let (cw, ch) = (cw.max(1) as usize, ch.max(1) as usize);
    let tiled = dec.get_chunk_type() == ChunkType::Tile;
    let kind = if tiled { "tile" } else { "strip" };
    let across = if tiled { ncols.div_ceil(cw) } else { 1 };
    let bands = nrows.div_ceil(ch);
    let mut values: Vec<f32> = Vec::new();
    for band in 0..bands {
        let top = band * ch;
        let band_rows = ch.min(nrows - top);
        let start = values.len();
        for t in 0..across {
            let index = (band * across + t) as u32;
            let field = format!("{kind} {index}");
            let chunk = dec.read_chunk(index).map_err(|e| {
                error(
                    path,
                    &field,
                    DemErrorKind::Invalid(format!("cannot decode: {e}")),
                )
            })?;
            let (w, h) = dec.chunk_data_dimensions(index);
            let (w, h) = (w as usize, h as usize);
            let left = t * cw;
            if h != band_rows || left + w > ncols {
                let m = format!("{w} x {h} samples do not fit the grid at row {top}");
                return Err(error(path, &field, DemErrorKind::Invalid(m)));
            }
            // The band's cells, once its first chunk has decoded.
            if values.len() == start {
                values.resize(start + band_rows * ncols, f32::NAN);
            }
            let mut put = |i: usize, v: f64, single: bool| -> Result<(), DemError> {
                let (r, c) = (i / w, i % w);
                let is_nodata = v.is_nan()
                    || Some(v) == nodata
                    || (single && nodata.is_some_and(|n| n as f32 == v as f32));
                if is_nodata || r >= h {
                    return Ok(());
                }
                let e = v as f32;
                if !e.is_finite() {
                    let field = format!(
                        "row {} (from the north) column {}",
                        top + r + 1,
                        left + c + 1
                    );
                    let kind = DemErrorKind::NotFinite(v.to_string());
                    return Err(error(path, &field, kind));
                }
                values[start + r * ncols + left + c] = e;
                Ok(())
            };
            let n = for_each_sample(&chunk, &mut put)?;
            if n != w * h {
                let m = format!("{n} samples decoded, {w} x {h} expected");
                return Err(error(path, &field, DemErrorKind::Invalid(m)));
            }
        }
    }
    Ok(values)
}

/// Calls `f(index, value, is_single_precision)` for every sample of `chunk`; returns how many
/// there were.
fn for_each_sample<E>(
    chunk: &DecodingResult,
    f: &mut impl FnMut(usize, f64, bool) -> Result<(), E>,
) -> Result<usize, E> {
    macro_rules! each {
        ($v:expr, $single:expr) => {{
            for (i, &x) in $v.iter().enumerate() {
                f(i, f64::from(x), $single)?;
            }
            $v.len()
        }};
    }
    let n = match chunk {
        DecodingResult::U8(v) => each!(v, false),
        DecodingResult::U16(v) => each!(v, false),
        DecodingResult::U32(v) => each!(v, false),
        DecodingResult::I8(v) => each!(v, false),
        DecodingResult::I16(v) => each!(v, false),
        DecodingResult::I32(v) => each!(v, false),
        DecodingResult::F16(v) => each!(v, true),
        DecodingResult::F32(v) => each!(v, true),
        DecodingResult::F64(v) => each!(v, false),
        DecodingResult::U64(v) => {
            for (i, &x) in v.iter().enumerate() {
                f(i, x as f64, false)?;
            }
            v.len()
        }
        DecodingResult::I64(v) => {
            for (i, &x) in v.iter().enumerate() {
                f(i, x as f64, false)?;
            }
            v.len()
        }
    };
    Ok(n)
}
