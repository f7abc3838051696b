//! GeoTIFF DEMs against an independent reference, GDAL (Debian's gdal-bin, which
//! `scripts/test.sh` installs): the shipped ASCII DEM converted by `gdal_translate` reads the
//! same grid and builds the same network; warped by `gdalwarp` to UTM and to a geographic grid
//! of non-square cells, it reads the elevations `gdallocationinfo` reads, at the same places;
//! a terrain scenario whose `dem` is a `.tif` builds and plans from the command line.
//!
//! Without GDAL the tests say SKIPPED and pass, except in the full tier
//! (`SKYROUTE_TIER=full`), where they fail.

mod common;

use common::{ok, scenario, skyroute, stdout, TempDir};
use skyroute_prep::dem::{self, Dem, Units};
use std::path::Path;
use std::process::Command;

/// Runs a GDAL tool; `None` (after saying SKIPPED) when it is not installed outside the full
/// tier. Panics when it fails.
fn gdal(tool: &str, args: &[&str]) -> Option<String> {
    match Command::new(tool).args(args).output() {
        Ok(o) => {
            assert!(
                o.status.success(),
                "{tool} {args:?}: {}",
                String::from_utf8_lossy(&o.stderr)
            );
            Some(String::from_utf8_lossy(&o.stdout).into_owned())
        }
        Err(e) if std::env::var("SKYROUTE_TIER").as_deref() == Ok("full") => {
            panic!("{tool} (gdal-bin) is needed in the full tier: {e}")
        }
        Err(e) => {
            eprintln!("SKIPPED in the fast tier: the GDAL check (no {tool}: {e})");
            None
        }
    }
}

/// The shipped DEM.
fn ascii_dem() -> String {
    scenario("jacksboro-dem.asc")
}

/// `gdallocationinfo -valonly` at the pixel or (with `-wgs84`) lon/lat points `points`, one
/// value (or an empty line outside the raster) per point.
fn gdal_values(file: &str, wgs84: bool, points: &[(f64, f64)]) -> Option<Vec<Option<f64>>> {
    let input: String = points
        .iter()
        .map(|p| format!("{} {}\n", p.0, p.1))
        .collect();
    let mut args = vec!["-valonly"];
    if wgs84 {
        args.push("-wgs84");
    }
    args.push(file);
    let mut child = match Command::new("gdallocationinfo")
        .args(&args)
        .stdin(std::process::Stdio::piped())
        .stdout(std::process::Stdio::piped())
        .spawn()
    {
        Ok(c) => c,
        Err(_) => return gdal("gdallocationinfo", &[]).map(|_| Vec::new()),
    };
    use std::io::Write;
    child
        .stdin
        .take()
        .unwrap()
        .write_all(input.as_bytes())
        .unwrap();
    let out = child.wait_with_output().unwrap();
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    let values: Vec<Option<f64>> = text.lines().map(|l| l.trim().parse().ok()).collect();
    assert_eq!(values.len(), points.len(), "{text}");
    Some(values)
}

/// A reproducible spread of `n` points in `[0, 1)²` (a 2-D Halton sequence).
fn spread(n: usize) -> Vec<(f64, f64)> {
    let halton = |mut i: usize, b: usize| {
        let (mut f, mut r) = (1.0, 0.0);
        while i > 0 {
            f /= b as f64;
            r += f * (i % b) as f64;
            i /= b;
        }
        r
    };
    (1..=n).map(|i| (halton(i, 2), halton(i, 3))).collect()
}

/// The elevation of `dem` at `(lon, lat)`, NaN for NODATA, `None` outside.
fn dem_value(dem: &Dem, lon: f64, lat: f64) -> Option<f64> {
    let (col, row) = dem.cell_at_lonlat(lon, lat)?;
    Some(dem.elevation_at(col, row).map_or(f64::NAN, f64::from))
}

#[test]
fn gdal_translate_of_the_ascii_dem_reads_the_same_grid() {
    let dir = TempDir::new("geotiff-same");
    let asc = dem::load(Path::new(&ascii_dem())).unwrap();
    // Strips of Int32 (GDAL's type for the integer grid), and Deflate tiles of Int16.
    let (strips, tiles) = (dir.file("strips.tif"), dir.file("tiles.tif"));
    let srs = ["-q", "-a_srs", "EPSG:4326"];
    let tiled = [
        "-ot",
        "Int16",
        "-co",
        "TILED=YES",
        "-co",
        "BLOCKXSIZE=64",
        "-co",
        "BLOCKYSIZE=32",
        "-co",
        "COMPRESS=DEFLATE",
        "-co",
        "PREDICTOR=2",
    ];
    let asc_path = ascii_dem();
    let a = [&srs[..], &[&asc_path, &strips]].concat();
    let b = [&srs[..], &tiled[..], &[&asc_path, &tiles]].concat();
    if gdal("gdal_translate", &a).is_none() || gdal("gdal_translate", &b).is_none() {
        return;
    }
    for file in [&strips, &tiles] {
        let tif = dem::load(Path::new(file)).unwrap();
        assert_eq!(tif.units, Units::Geographic);
        assert_eq!((tif.ncols, tif.nrows), (asc.ncols, asc.nrows));
        assert_eq!((tif.cell_x, tif.cell_y), (asc.cell_x, asc.cell_y));
        assert_eq!(tif.xllcorner, asc.xllcorner);
        assert_eq!(tif.yllcorner, asc.yllcorner, "{file}");
        assert_eq!(tif.nodata, asc.nodata);
        assert_eq!(tif.values(), asc.values(), "{file}");
        assert_eq!(tif.line_of_row(0), None);
    }
}

/// A network image without its provenance records (at the end of the body) and the header's
/// checksum.
fn without_dem_digest(bytes: &[u8]) -> Vec<u8> {
    let header = skyroute::network::format::Header::SIZE;
    let checked = skyroute::network::format::Header::CHECKED_SIZE;
    let n = skyroute::Network::from_bytes(bytes)
        .unwrap()
        .provenance_count() as usize;
    let end = bytes.len() - n * skyroute::network::format::ProvenanceRecord::SIZE;
    [&bytes[..checked], &bytes[header..end]].concat()
}

#[test]
fn a_geotiff_scenario_builds_the_network_of_the_ascii_scenario() {
    let dir = TempDir::new("geotiff-network");
    let tif = dir.file("jacksboro.tif");
    let args = ["-q", "-a_srs", "EPSG:4326", &ascii_dem(), &tif];
    if gdal("gdal_translate", &args).is_none() {
        return;
    }
    let mut s: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(scenario("medeiros-jacksboro.geojson")).unwrap(),
    )
    .unwrap();
    s["terrain"]["dem"] = serde_json::json!(tif);
    let tif_scenario = dir.file("jacksboro-tif.geojson");
    std::fs::write(&tif_scenario, s.to_string()).unwrap();
    let (net_asc, net_tif) = (dir.file("asc.bin"), dir.file("tif.bin"));
    let jacksboro = scenario("medeiros-jacksboro.geojson");
    ok(
        skyroute(&["build", &jacksboro, "-o", &net_asc]),
        "build asc",
    );
    ok(
        skyroute(&["build", &tif_scenario, "-o", &net_tif]),
        "build tif",
    );
    let (a, b) = (
        std::fs::read(&net_asc).unwrap(),
        std::fs::read(&net_tif).unwrap(),
    );
    assert_eq!(a.len(), b.len());
    // Byte for byte the same, but for the DEM file's digest (and so the checksum).
    assert!(without_dem_digest(&a) == without_dem_digest(&b));
    assert_ne!(a, b, "the DEM digest covers the file's bytes");
    let route = dir.file("route.json");
    let o = skyroute(&["plan", &net_tif, "--scenario", &tif_scenario, "-o", &route]);
    ok(o, "plan with the GeoTIFF scenario");
}

/// Reads `file`, written by GDAL from the shipped DEM, and compares its elevations with
/// `gdallocationinfo`'s at 600 lon/lat points spread over the DEM (GDAL reprojects them to the
/// file's coordinate system, the reader here through [`Dem::cell_at_lonlat`]), and at 600
/// pixels.
fn same_elevations_as_gdal(file: &str, units: Units) -> Option<()> {
    let tif = dem::load(Path::new(file)).unwrap();
    assert_eq!(tif.units, units);
    let asc = dem::load(Path::new(&ascii_dem())).unwrap();
    let (w, s) = (asc.xllcorner, asc.yllcorner);
    let (e, n) = (
        w + asc.ncols as f64 * asc.cell_x,
        s + asc.nrows as f64 * asc.cell_y,
    );
    let lonlat: Vec<(f64, f64)> = spread(600)
        .into_iter()
        .map(|(u, v)| (w + u * (e - w), s + v * (n - s)))
        .collect();
    let theirs = gdal_values(file, true, &lonlat)?;
    let mut compared = 0;
    for (&(lon, lat), theirs) in lonlat.iter().zip(&theirs) {
        let ours = dem_value(&tif, lon, lat);
        match (ours, theirs) {
            (Some(o), Some(t)) if tif.nodata == Some(*t) => assert!(o.is_nan(), "{lon} {lat}"),
            (Some(o), Some(t)) => {
                // GDAL prints 15 significant digits: the same f32.
                assert_eq!(o as f32, *t as f32, "{file} at {lon} {lat}");
                compared += 1;
            }
            (None, None) => {}
            (o, t) => panic!("{file} at {lon} {lat}: ours {o:?}, GDAL's {t:?}"),
        }
    }
    assert!(compared > 500, "{compared}");
    let pixels: Vec<(f64, f64)> = spread(600)
        .into_iter()
        .map(|(u, v)| {
            let c = (u * tif.ncols as f64).floor();
            let r = (v * tif.nrows as f64).floor();
            (c, r)
        })
        .collect();
    let theirs = gdal_values(file, false, &pixels)?;
    for (&(c, r), t) in pixels.iter().zip(&theirs) {
        let (c, r) = (c as usize, tif.nrows - 1 - r as usize);
        let ours = tif.elevation_at(c, r);
        match t {
            Some(t) if tif.nodata == Some(*t) => assert_eq!(ours, None),
            t => assert_eq!(
                ours,
                t.map(|t| t as f32),
                "{file} pixel {c} {r} (from the south)"
            ),
        }
    }
    Some(())
}

#[test]
fn a_utm_geotiff_reads_gdals_elevations_at_gdals_places() {
    let dir = TempDir::new("geotiff-utm");
    let utm = dir.file("utm.tif");
    let args = [
        "-q",
        "-s_srs",
        "EPSG:4326",
        "-t_srs",
        "EPSG:32616",
        "-tr",
        "30",
        "30",
        "-r",
        "bilinear",
        "-ot",
        "Float32",
        "-dstnodata",
        "-9999",
        "-co",
        "COMPRESS=LZW",
        "-co",
        "PREDICTOR=3",
        &ascii_dem(),
        &utm,
    ];
    if gdal("gdalwarp", &args).is_none() {
        return;
    }
    let zone = Units::Utm {
        zone: 16,
        north: true,
    };
    same_elevations_as_gdal(&utm, zone);
}

#[test]
fn a_geographic_geotiff_of_non_square_cells_reads_gdals_elevations() {
    let dir = TempDir::new("geotiff-geo");
    let geo = dir.file("geo.tif");
    // 4″ × 3″ cells, as Copernicus GLO-30 has them at 50–60° N (there 1.5″ × 1″).
    let args = [
        "-q",
        "-s_srs",
        "EPSG:4326",
        "-t_srs",
        "EPSG:4326",
        "-tr",
        "0.00111111111111",
        "0.00083333333333",
        "-r",
        "near",
        "-co",
        "TILED=YES",
        "-co",
        "COMPRESS=DEFLATE",
        &ascii_dem(),
        &geo,
    ];
    if gdal("gdalwarp", &args).is_none() {
        return;
    }
    same_elevations_as_gdal(&geo, Units::Geographic);
}

#[test]
fn utm_and_non_square_geotiff_scenarios_build_and_plan() {
    let dir = TempDir::new("geotiff-cli");
    let (utm, geo) = (dir.file("utm.tif"), dir.file("geo.tif"));
    let warp = |srs: &str, res: [&str; 2], out: &str| {
        let args = [
            "-q",
            "-s_srs",
            "EPSG:4326",
            "-t_srs",
            srs,
            "-tr",
            res[0],
            res[1],
            "-r",
            "max",
            &ascii_dem(),
            out,
        ];
        gdal("gdalwarp", &args)
    };
    if warp("EPSG:32616", ["60", "60"], &utm).is_none()
        || warp("EPSG:4326", ["0.00111111111111", "0.00083333333333"], &geo).is_none()
    {
        return;
    }
    for (dem, name) in [(&utm, "utm"), (&geo, "geo")] {
        let mut s: serde_json::Value = serde_json::from_str(
            &std::fs::read_to_string(scenario("medeiros-jacksboro.geojson")).unwrap(),
        )
        .unwrap();
        s["terrain"]["dem"] = serde_json::json!(dem);
        let sc = dir.file(&format!("{name}.geojson"));
        std::fs::write(&sc, s.to_string()).unwrap();
        let (net, route) = (
            dir.file(&format!("{name}.bin")),
            dir.file(&format!("{name}.json")),
        );
        let o = ok(skyroute(&["build", &sc, "-o", &net]), "build");
        assert!(stdout(&o).contains(" edges"), "{}", stdout(&o));
        ok(
            skyroute(&["plan", &net, "--scenario", &sc, "-o", &route]),
            "plan",
        );
        let r: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(&route).unwrap()).unwrap();
        assert!(r.is_object(), "{name}: {r}");
    }
}

/// GDAL's tiled Deflate and striped LZW (floating-point predictor) files with random bytes
/// changed are errors or DEMs, never panics.
#[test]
fn mutated_gdal_files_never_panic() {
    let dir = TempDir::new("geotiff-mutated");
    let (tiled, lzw) = (dir.file("tiled.tif"), dir.file("lzw.tif"));
    let asc = ascii_dem();
    let a = [
        "-q",
        "-a_srs",
        "EPSG:4326",
        "-ot",
        "Int16",
        "-co",
        "TILED=YES",
        "-co",
        "BLOCKXSIZE=64",
        "-co",
        "BLOCKYSIZE=64",
        "-co",
        "COMPRESS=DEFLATE",
        &asc,
        &tiled,
    ];
    let b = [
        "-q",
        "-a_srs",
        "EPSG:4326",
        "-ot",
        "Float32",
        "-co",
        "COMPRESS=LZW",
        "-co",
        "PREDICTOR=3",
        &asc,
        &lzw,
    ];
    if gdal("gdal_translate", &a).is_none() || gdal("gdal_translate", &b).is_none() {
        return;
    }
    let mut state = 0x2545_f491_4f6c_dd1d_u64;
    let mut next = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        state
    };
    for file in [&tiled, &lzw] {
        let base = std::fs::read(file).unwrap();
        for _ in 0..300 {
            let mut bytes = base.clone();
            for _ in 0..1 + next() % 8 {
                // Half the changes in the first 1 KiB (header, IFD, tags), half anywhere.
                let span = if next() % 2 == 0 { 1024 } else { bytes.len() };
                let i = (next() % span.min(bytes.len()) as u64) as usize;
                bytes[i] = next() as u8;
            }
            if let Ok(dem) = dem::geotiff::parse(&bytes, Path::new(file)) {
                assert_eq!(dem.values().len(), dem.ncols * dem.nrows);
            }
        }
    }
}
