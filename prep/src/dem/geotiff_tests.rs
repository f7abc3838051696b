//! The GeoTIFF reader on small files written here tag by tag: what it reads, and an error
//! naming the file and the tag for everything it refuses.

use super::geotiff::{is_tiff, parse};
use super::{Units, MAX_CELLS};
use std::path::Path;

/// A TIFF tag value.
#[derive(Clone)]
enum V {
    Short(Vec<u16>),
    Long(Vec<u32>),
    Double(Vec<f64>),
    Ascii(&'static str),
}

impl V {
    /// (TIFF type, count, bytes).
    fn encode(&self) -> (u16, u32, Vec<u8>) {
        match self {
            V::Short(v) => (
                3,
                v.len() as u32,
                v.iter().flat_map(|x| x.to_le_bytes()).collect(),
            ),
            V::Long(v) => (
                4,
                v.len() as u32,
                v.iter().flat_map(|x| x.to_le_bytes()).collect(),
            ),
            V::Double(v) => (
                12,
                v.len() as u32,
                v.iter().flat_map(|x| x.to_le_bytes()).collect(),
            ),
            V::Ascii(s) => {
                let mut b = s.as_bytes().to_vec();
                b.push(0);
                (2, b.len() as u32, b)
            }
        }
    }
}

/// A little-endian TIFF of one IFD: `data` at byte 8, then the IFD with `entries` (sorted by
/// tag), then the values that do not fit an entry.
fn tiff(entries: &[(u16, V)], data: &[u8]) -> Vec<u8> {
    let mut entries = entries.to_vec();
    entries.sort_by_key(|e| e.0);
    let ifd = (8 + data.len()).next_multiple_of(2);
    let mut out = b"II*\0".to_vec();
    out.extend((ifd as u32).to_le_bytes());
    out.extend(data);
    out.resize(ifd, 0);
    let mut extra_at = ifd + 2 + 12 * entries.len() + 4;
    let mut extra: Vec<u8> = Vec::new();
    out.extend((entries.len() as u16).to_le_bytes());
    for (tag, v) in &entries {
        let (ty, count, bytes) = v.encode();
        out.extend(tag.to_le_bytes());
        out.extend(ty.to_le_bytes());
        out.extend(count.to_le_bytes());
        if bytes.len() <= 4 {
            let mut b = bytes.clone();
            b.resize(4, 0);
            out.extend(b);
        } else {
            out.extend((extra_at as u32).to_le_bytes());
            extra.extend(&bytes);
            extra_at += bytes.len();
        }
    }
    out.extend(0u32.to_le_bytes());
    out.extend(extra);
    out
}

/// WGS 84 geographic GeoKeys.
fn wgs84() -> V {
    V::Short(vec![1, 1, 0, 2, 1024, 0, 1, 2, 2048, 0, 1, 4326])
}

/// A `w × h` Int16 DEM, one strip, north row first, tiepoint (10, 50) and 0.5° × 0.25° cells,
/// with `extra` entries added or replacing the standard ones.
fn int16_dem(w: u32, h: u32, samples: &[i16], extra: &[(u16, V)]) -> Vec<u8> {
    let data: Vec<u8> = samples.iter().flat_map(|x| x.to_le_bytes()).collect();
    let mut entries = vec![
        (256, V::Long(vec![w])),
        (257, V::Long(vec![h])),
        (258, V::Short(vec![16])),
        (259, V::Short(vec![1])),
        (262, V::Short(vec![1])),
        (273, V::Long(vec![8])),
        (277, V::Short(vec![1])),
        (278, V::Long(vec![h])),
        (279, V::Long(vec![data.len() as u32])),
        (339, V::Short(vec![2])),
        (33550, V::Double(vec![0.5, 0.25, 0.0])),
        (33922, V::Double(vec![0.0, 0.0, 0.0, 10.0, 50.0, 0.0])),
        (34735, wgs84()),
    ];
    for (tag, v) in extra {
        entries.retain(|e| e.0 != *tag);
        entries.push((*tag, v.clone()));
    }
    tiff(&entries, &data)
}

/// The error message for `bytes`, which must fail.
fn err(bytes: &[u8]) -> String {
    parse(bytes, Path::new("t/x.tif"))
        .expect_err("should fail")
        .to_string()
}

/// The message names the file and then `field` (or a field that starts with it), and says
/// `what`.
fn expect(bytes: &[u8], field: &str, what: &str) {
    let m = err(bytes);
    let head = format!("t/x.tif: {field}");
    assert!(m.starts_with(&head), "{m:?} does not start with {head:?}");
    assert!(m.contains(what), "{m:?} does not say {what:?}");
}

#[test]
fn a_small_geographic_dem_rows_from_the_south() {
    let nodata = (42113, V::Ascii("-32768"));
    let b = int16_dem(3, 2, &[1, 2, 3, 4, -32768, 6], &[nodata]);
    assert!(is_tiff(&b));
    let dem = parse(&b, Path::new("t/x.tif")).unwrap();
    assert_eq!(dem.units, Units::Geographic);
    assert_eq!(
        (dem.ncols, dem.nrows, dem.cell_x, dem.cell_y),
        (3, 2, 0.5, 0.25)
    );
    assert_eq!((dem.xllcorner, dem.yllcorner), (10.0, 49.5));
    // The file's first row is the northernmost.
    assert_eq!(dem.elevation_at(0, 1), Some(1.0));
    assert_eq!(dem.elevation_at(0, 0), Some(4.0));
    assert_eq!(dem.elevation_at(1, 0), None);
    assert_eq!(dem.nodata, Some(-32768.0));
    assert_eq!(dem.nodata_count(), 1);
    assert_eq!((dem.min(), dem.max()), (Some(1.0), Some(6.0)));
    assert_eq!(dem.line_of_row(0), None);
    assert_eq!(dem.cell_at_lonlat(11.2, 49.6), Some((2, 0)));
    assert_eq!(dem.cell_at_lonlat(11.6, 49.6), None);
}

#[test]
fn pixel_is_point_and_utm() {
    let keys = V::Short(vec![
        1, 1, 0, 3, 1024, 0, 1, 2, 1025, 0, 1, 2, 2048, 0, 1, 4326,
    ]);
    let b = int16_dem(1, 1, &[7], &[(34735, keys)]);
    let dem = parse(&b, Path::new("t/x.tif")).unwrap();
    assert_eq!((dem.xllcorner, dem.yllcorner), (9.75, 49.875));
    let utm = V::Short(vec![1, 1, 0, 2, 1024, 0, 1, 1, 3072, 0, 1, 32733]);
    let tie = V::Double(vec![0.0, 0.0, 0.0, 500_000.0, 6_000_000.0, 0.0]);
    let b = int16_dem(1, 1, &[7], &[(34735, utm), (33922, tie)]);
    let dem = parse(&b, Path::new("t/x.tif")).unwrap();
    let zone = Units::Utm {
        zone: 33,
        north: false,
    };
    assert_eq!(dem.units, zone);
    let (lon, lat) = dem.cell_centre_lonlat(0, 0).unwrap();
    assert!(
        (lon - 15.0).abs() < 1e-5 && lat < -36.0 && lat > -37.0,
        "{lon} {lat}"
    );
}

#[test]
fn an_axis_aligned_transformation_is_read_a_rotated_one_refused() {
    let mut m = vec![0.0; 16];
    (m[0], m[3], m[5], m[7], m[15]) = (0.5, 10.0, -0.25, 50.0, 1.0);
    let t = |m: &Vec<f64>| [(34264, V::Double(m.clone())), (33922, V::Double(vec![]))];
    let b = int16_dem(1, 1, &[7], &t(&m)[..1]);
    let dem = parse(&b, Path::new("t/x.tif")).unwrap();
    assert_eq!(
        (dem.xllcorner, dem.yllcorner, dem.cell_y),
        (10.0, 49.75, 0.25)
    );
    m[1] = 0.01;
    let b = int16_dem(1, 1, &[7], &t(&m)[..1]);
    expect(&b, "tag 34264 (ModelTransformation)", "rotated");
}

#[test]
fn unknown_coordinate_systems_are_refused_by_key() {
    let keys = |k: u16, v: u16| V::Short(vec![1, 1, 0, 1, k, 0, 1, v]);
    let b = int16_dem(1, 1, &[7], &[(34735, keys(3072, 3857))]);
    expect(
        &b,
        "tag 34735 (GeoKeyDirectory) key 3072 (ProjectedCSTypeGeoKey)",
        "3857",
    );
    let b = int16_dem(1, 1, &[7], &[(34735, keys(1024, 3))]);
    let field = "tag 34735 (GeoKeyDirectory) key 1024 (GTModelTypeGeoKey)";
    expect(&b, field, "not supported: 3");
    let b = int16_dem(1, 1, &[7], &[(34735, keys(2048, 4267))]);
    let field = "tag 34735 (GeoKeyDirectory) key 2048 (GeographicTypeGeoKey)";
    expect(&b, field, "4267");
    let feet = V::Short(vec![1, 1, 0, 2, 3072, 0, 1, 32616, 3076, 0, 1, 9002]);
    let b = int16_dem(1, 1, &[7], &[(34735, feet)]);
    let field = "tag 34735 (GeoKeyDirectory) key 3076 (ProjLinearUnitsGeoKey)";
    expect(&b, field, "9002");
    let feet = V::Short(vec![1, 1, 0, 2, 2048, 0, 1, 4326, 4099, 0, 1, 9002]);
    let b = int16_dem(1, 1, &[7], &[(34735, feet)]);
    let field = "tag 34735 (GeoKeyDirectory) key 4099 (VerticalUnitsGeoKey)";
    expect(&b, field, "9002");
    let short = V::Short(vec![1, 1, 0, 5, 1024, 0, 1, 2]);
    let b = int16_dem(1, 1, &[7], &[(34735, short)]);
    expect(&b, "tag 34735 (GeoKeyDirectory)", "too few");
}

#[test]
fn georeferencing_errors_name_the_tag() {
    let b = int16_dem(1, 1, &[7], &[(33922, V::Double(vec![0.0; 12]))]);
    expect(&b, "tag 33922 (ModelTiepoint)", "12 values");
    let b = int16_dem(1, 1, &[7], &[(33550, V::Double(vec![0.5, -0.25, 0.0]))]);
    expect(&b, "tag 33550 (ModelPixelScale)", "positive");
    let b = int16_dem(1, 1, &[7], &[(33922, V::Ascii("x"))]);
    expect(&b, "tag 33922 (ModelTiepoint)", "not numbers");
    let b = int16_dem(1, 1, &[7], &[(42113, V::Ascii("none"))]);
    expect(&b, "tag 42113 (GDAL_NODATA)", "\"none\" is not a number");
    let far = V::Double(vec![0.0, 0.0, 0.0, 179.9, 50.0, 0.0]);
    let b = int16_dem(1, 1, &[7], &[(33922, far)]);
    expect(&b, "tag 33922 (ModelTiepoint)", "not within");
}

#[test]
fn layouts_the_reader_cannot_decode_are_refused_by_tag() {
    let b = int16_dem(1, 1, &[7], &[(259, V::Short(vec![7]))]);
    expect(&b, "tag 259 (Compression)", "compression 7");
    let b = int16_dem(1, 1, &[7], &[(317, V::Short(vec![4]))]);
    expect(&b, "tag 317 (Predictor)", "predictor “4”");
    let rgb = [(277, V::Short(vec![3])), (258, V::Short(vec![16, 16, 16]))];
    let b = int16_dem(1, 1, &[7, 7, 7], &rgb);
    expect(
        &b,
        "tags 277, 258, 339",
        "one 8-, 16-, 32- or 64-bit sample",
    );
}

#[test]
fn a_large_header_over_a_short_file_fails_before_allocating() {
    // 16384 × 16384 Int16 cells (512 MiB) claimed by a file of a few hundred bytes.
    let big = [
        (256, V::Long(vec![16384])),
        (257, V::Long(vec![16384])),
        (278, V::Long(vec![16384])),
    ];
    let b = int16_dem(1, 1, &[7], &big);
    expect(
        &b,
        "tag 279 (StripByteCounts)",
        "uncompressed it needs 536870912",
    );
    let claims = [
        (256, V::Long(vec![16384])),
        (257, V::Long(vec![16384])),
        (278, V::Long(vec![16384])),
        (279, V::Long(vec![1 << 29])),
    ];
    let b = int16_dem(1, 1, &[7], &claims);
    expect(
        &b,
        "tag 279 (StripByteCounts)",
        "ends past the end of the file",
    );
    // Deflate: the byte count cannot bound the grid; the strip fails to decode, and nothing
    // of the grid's size is allocated before (the decoder's own limit, 256 MiB a chunk).
    let deflate = [
        (256, V::Long(vec![16384])),
        (257, V::Long(vec![16384])),
        (278, V::Long(vec![16384])),
        (259, V::Short(vec![8])),
        (33550, V::Double(vec![1e-4, 1e-4, 0.0])),
    ];
    let b = int16_dem(1, 1, &[7], &deflate);
    expect(&b, "strip 0", "cannot decode");
    let strips = [(257, V::Long(vec![4])), (278, V::Long(vec![1]))];
    let b = int16_dem(1, 1, &[7], &strips);
    expect(
        &b,
        "tags 273, 279, 322, 323, 324, 325",
        "inconsistent sizes",
    );
    let too_many = [
        (256, V::Long(vec![16385])),
        (257, V::Long(vec![16384])),
        (278, V::Long(vec![16384])),
    ];
    let b = int16_dem(1, 1, &[7], &too_many);
    let m = err(&b);
    assert!(m.contains(&format!("is more than {MAX_CELLS}")), "{m}");
}

#[test]
fn a_truncated_file_is_an_error_not_a_panic() {
    let b = int16_dem(2, 2, &[1, 2, 3, 4], &[]);
    for n in [4, 8, 12, 40, b.len() - 1] {
        let m = err(&b[..n]);
        assert!(m.starts_with("t/x.tif: "), "{m}");
    }
}

/// Random byte changes to a small tiled-or-striped DEM are errors or DEMs, never panics.
#[test]
fn mutated_files_never_panic() {
    let nodata = (42113, V::Ascii("-32768"));
    let base = int16_dem(3, 2, &[1, 2, 3, 4, -32768, 6], &[nodata]);
    let mut state = 0x9e37_79b9_7f4a_7c15_u64;
    let mut next = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        state
    };
    for _ in 0..5000 {
        let mut b = base.clone();
        for _ in 0..1 + next() % 4 {
            let i = (next() % b.len() as u64) as usize;
            b[i] = next() as u8;
        }
        if let Ok(dem) = parse(&b, Path::new("t/x.tif")) {
            assert_eq!(dem.values().len(), dem.ncols * dem.nrows);
        }
    }
}
