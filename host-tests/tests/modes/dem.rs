//! The ESRI ASCII grid reader (`skyroute_prep::dem`) on the real Jacksboro DEM
//! (`scenarios/jacksboro-dem.asc`: 403 × 344 cells of 3 arc-seconds, Tennessee), checked against
//! the file's text read by a trivial independent parser and against numbers from numpy.

use skyroute_prep::dem::{self, Units};
use std::path::PathBuf;

fn dem_path() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../scenarios/jacksboro-dem.asc")
}

/// The data lines of the file as numbers, northernmost first: every line after the first six,
/// split on whitespace.
fn raw_rows(text: &str) -> Vec<Vec<f64>> {
    text.lines()
        .skip(6)
        .filter(|l| !l.trim().is_empty())
        .map(|l| l.split_whitespace().map(|t| t.parse().unwrap()).collect())
        .collect()
}

#[test]
fn jacksboro_header_extremes_and_cells() {
    let path = dem_path();
    let text = std::fs::read_to_string(&path).unwrap();
    let dem = dem::load(&path).unwrap();

    // Header.
    assert_eq!((dem.ncols, dem.nrows), (403, 344));
    assert_eq!(dem.xllcorner, -84.41375);
    assert_eq!(dem.yllcorner, 36.44625);
    assert_eq!(dem.cell_x, 0.0008333333); // 3 arc-seconds
    assert_eq!(dem.cell_y, dem.cell_x);
    assert_eq!(dem.nodata, Some(-9999.0));
    assert_eq!(dem.units, Units::Geographic);
    assert_eq!(dem.values().len(), 403 * 344);

    // Extremes and NODATA, from numpy:
    //   python3 -c "import numpy as np; a=np.loadtxt('scenarios/jacksboro-dem.asc',skiprows=6);
    //     print(a.shape, a.min(), a.max(), (a==-9999).sum(), a.sum())"
    //   → (344, 403) 236.0 1076.0 0 73617913.0
    // and again from the text with the trivial parser above.
    assert_eq!((dem.min(), dem.max()), (Some(236.0), Some(1076.0)));
    assert_eq!(dem.nodata_count(), 0);
    assert_eq!(dem.nodata_cells().count(), 0);
    let rows = raw_rows(&text);
    assert_eq!(rows.len(), 344);
    assert!(rows.iter().all(|r| r.len() == 403));
    let all = rows.iter().flatten().copied();
    let (lo, hi) = all
        .clone()
        .fold((f64::MAX, f64::MIN), |(l, h), v| (l.min(v), h.max(v)));
    assert_eq!((dem.min(), dem.max()), (Some(lo as f32), Some(hi as f32)));
    let sum: f64 = all.sum();
    assert_eq!(sum, 73617913.0);
    let dem_sum: f64 = dem.values().iter().map(|&v| v as f64).sum();
    assert_eq!(dem_sum, sum);

    // Spot checks against the raw text. numpy (file rows from the north):
    //   a[0,0] = 483, a[0,402] = 444, a[343,0] = 545, a[343,402] = 272, a[100,200] = 522;
    //   the minimum at a[288,347], the maximum at a[297,219].
    // The reader's rows count from the south: file row i is row 343 − i.
    let numpy = [
        (0, 0, 483.0),
        (0, 402, 444.0),
        (343, 0, 545.0),
        (343, 402, 272.0),
        (100, 200, 522.0),
        (288, 347, 236.0),
        (297, 219, 1076.0),
    ];
    for (file_row, col, want) in numpy {
        let row = 343 - file_row;
        assert_eq!(
            dem.elevation_at(col, row),
            Some(want),
            "file row {file_row} col {col}"
        );
        assert_eq!(rows[file_row][col], want as f64);
        // The reader names the line the row came from: the header is 6 lines.
        let line = dem.line_of_row(row).unwrap();
        assert_eq!(line, 7 + file_row);
        let token = text
            .lines()
            .nth(line - 1)
            .unwrap()
            .split_whitespace()
            .nth(col);
        assert_eq!(token.unwrap().parse::<f32>().unwrap(), want);
    }
    // Every cell, through the independent parser.
    for (file_row, values) in rows.iter().enumerate() {
        for (col, &v) in values.iter().enumerate() {
            assert_eq!(dem.elevation_at(col, 343 - file_row), Some(v as f32));
        }
    }
    assert_eq!(dem.elevation_at(403, 0), None);
    assert_eq!(dem.elevation_at(0, 344), None);

    // Geographic: the south-west cell's centre, and the north-east one's.
    let (lon, lat) = dem.cell_centre_lonlat(0, 0).unwrap();
    assert!((lon - (-84.41375 + 0.0008333333 / 2.0)).abs() < 1e-12);
    assert!((lat - (36.44625 + 0.0008333333 / 2.0)).abs() < 1e-12);
    let (lon, lat) = dem.cell_centre_lonlat(402, 343).unwrap();
    assert!((lon - (-84.41375 + 402.5 * 0.0008333333)).abs() < 1e-12);
    assert!((lat - (36.44625 + 343.5 * 0.0008333333)).abs() < 1e-12);
    assert_eq!(dem.cell_centre_lonlat(403, 0), None);

    // The terrain rule of the paper's scenario: altitude 750 m, safety height 100 m: a cell is
    // navigable iff its elevation is below 650 m.
    let navigable = (0..344)
        .flat_map(|r| (0..403).map(move |c| (c, r)))
        .filter(|&(c, r)| dem.is_navigable(c, r, 750.0, 100.0))
        .count();
    let below = rows.iter().flatten().filter(|&&v| v < 650.0).count();
    assert_eq!(navigable, below);
    assert!(navigable > 0 && navigable < 403 * 344);
}

#[test]
fn errors_name_the_file_line_and_field() {
    let path = dem_path();
    let text = std::fs::read_to_string(&path).unwrap();
    // Drop one value from the 12th data line (file line 18).
    let broken: String = text
        .lines()
        .enumerate()
        .map(|(i, l)| {
            if i == 17 {
                l.rsplit_once(' ').unwrap().0.to_string()
            } else {
                l.to_string()
            }
        })
        .collect::<Vec<_>>()
        .join("\n");
    let e = dem::parse(&broken, &path).unwrap_err();
    let m = e.to_string();
    assert!(
        m.ends_with(
            "jacksboro-dem.asc: line 18: row 12 (from the north): has 402 values, expected ncols = 403"
        ),
        "{m}"
    );
    assert_eq!(e.line, Some(18));
}
