//! The ESRI ASCII grid format (`.asc`).
//!
//! [`parse`] takes a file's text ([`super::load`] reads the file). The format: a header of `key value` lines,
//! then one line per grid row, **northernmost row first**, `ncols` whitespace-separated
//! elevations each:
//!
//! ```text
//! ncols        403
//! nrows        344
//! xllcorner    -84.41375000      (or xllcenter: the centre of the south-west cell)
//! yllcorner    36.44625000       (or yllcenter)
//! cellsize     0.0008333333
//! NODATA_value -9999             (optional)
//! 483 487 491 …
//! ```
//!
//! Header keys are case-insensitive and may come in any order; `*corner` and `*center` are both
//! accepted (each axis on its own) and normalised to the corner. Checked: every required key is
//! present once, no unknown key (GDAL's `dx`/`dy` for non-square cells is not supported), each
//! has exactly one value, `ncols`/`nrows` are positive integers, the coordinates and
//! `NODATA_value` are finite numbers, `cellsize` is finite and positive; every data line holds
//! exactly `ncols` values, there are exactly `nrows` data lines (blank lines are ignored), and
//! every value is a finite number that fits an `f32`. An error names the file, the line and the
//! field:
//!
//! ```text
//! scenarios/x.asc: line 5: cellsize: -30 is not positive
//! scenarios/x.asc: line 19: row 12 (from the north): has 402 values, expected ncols = 403
//! scenarios/x.asc: line 8: row 1 (from the north) column 17: "4o2" is not a number
//! ```
//!
//! # Rows and units
//!
//! The file's last data line is the DEM's row 0 ([`Dem::line_of_row`] gives the file line of a
//! row); cells are square (`cell_x = cell_y = cellsize`), the corner is `(xllcorner, yllcorner)`.
//!
//! The grid is taken as **geographic** (degrees of longitude/latitude, WGS-84) when `cellsize < 1`
//! and its whole extent lies within ±180° × ±90°, and as **projected** (metres) otherwise — the
//! format carries no coordinate system, and a sub-metre projected grid near its projection's
//! origin would be misread; set [`Dem::units`] to override. A projected ASCII grid is
//! [`Units::Projected`]: its projection is unknown, so it cannot be placed on the earth.
//!
//! # NODATA
//!
//! Cells equal to `NODATA_value` are NODATA (NaN in the [`Dem`]).

use super::{Dem, DemError, DemErrorKind, GridSpec, Units, MAX_CELLS};
use std::path::Path;

/// The header keys, in the canonical order.
const KEYS: [&str; 6] = ["ncols", "nrows", "xll", "yll", "cellsize", "NODATA_value"];

/// Checks the DEM text `text`, read from `path` (used in errors; not read).
pub fn parse(text: &str, path: &Path) -> Result<Dem, DemError> {
    let err = |line: usize, field: &str, kind: DemErrorKind| DemError {
        path: path.to_path_buf(),
        line: Some(line),
        field: field.to_string(),
        kind,
    };
    let mut lines = text
        .lines()
        .enumerate()
        .map(|(i, l)| (i + 1, l))
        .filter(|(_, l)| !l.trim().is_empty())
        .peekable();

    // Header: the lines whose first token is not a number.
    // Per key: (line, key as written, value text, is the centre form).
    let mut seen: [Option<(usize, String, String, bool)>; 6] = Default::default();
    while let Some(&(n, line)) = lines.peek() {
        let mut tokens = line.split_ascii_whitespace();
        let key = tokens.next().unwrap_or("");
        if key.parse::<f64>().is_ok() {
            break;
        }
        lines.next();
        let lower = key.to_ascii_lowercase();
        let (slot, centre) = match lower.as_str() {
            "ncols" => (0, false),
            "nrows" => (1, false),
            "xllcorner" => (2, false),
            "xllcenter" => (2, true),
            "yllcorner" => (3, false),
            "yllcenter" => (3, true),
            "cellsize" => (4, false),
            "nodata_value" => (5, false),
            _ => return Err(err(n, key, DemErrorKind::UnknownKey)),
        };
        if let Some((first, ..)) = &seen[slot] {
            let kind = DemErrorKind::DuplicateKey { first_line: *first };
            return Err(err(n, key, kind));
        }
        let Some(value) = tokens.next() else {
            return Err(err(n, key, DemErrorKind::MissingValue));
        };
        if let Some(extra) = tokens.next() {
            return Err(err(n, key, DemErrorKind::ExtraValue(extra.to_string())));
        }
        seen[slot] = Some((n, key.to_string(), value.to_string(), centre));
    }
    // Where the header ended: the first data line, or past the end.
    let data_start = lines.peek().map_or(text.lines().count() + 1, |&(n, _)| n);
    let field_of = |slot: usize| -> Result<(usize, String, String, bool), DemError> {
        seen[slot].clone().ok_or_else(|| {
            let name = match slot {
                2 => "xllcorner (or xllcenter)",
                3 => "yllcorner (or yllcenter)",
                _ => KEYS[slot],
            };
            err(data_start, name, DemErrorKind::MissingKey)
        })
    };
    let count = |slot: usize| -> Result<usize, DemError> {
        let (n, key, value, _) = field_of(slot)?;
        match value.parse::<usize>() {
            Ok(v) if v > 0 => Ok(v),
            _ => Err(err(n, &key, DemErrorKind::NotPositiveInteger(value))),
        }
    };
    let number = |n: usize, key: &str, value: &str| -> Result<f64, DemError> {
        match value.parse::<f64>() {
            Ok(v) if v.is_finite() => Ok(v),
            Ok(_) => Err(err(n, key, DemErrorKind::NotFinite(value.to_string()))),
            Err(_) => Err(err(n, key, DemErrorKind::NotANumber(value.to_string()))),
        }
    };
    let ncols = count(0)?;
    let nrows = count(1)?;
    let (xn, xkey, xvalue, xcentre) = field_of(2)?;
    let (yn, ykey, yvalue, ycentre) = field_of(3)?;
    let (cn, ckey, cvalue, _) = field_of(4)?;
    let cellsize = number(cn, &ckey, &cvalue)?;
    if cellsize <= 0.0 {
        return Err(err(cn, &ckey, DemErrorKind::NotPositive(cellsize)));
    }
    let half = |centre: bool| if centre { 0.5 * cellsize } else { 0.0 };
    let xllcorner = number(xn, &xkey, &xvalue)? - half(xcentre);
    let yllcorner = number(yn, &ykey, &yvalue)? - half(ycentre);
    let nodata = match &seen[5] {
        Some((n, key, value, _)) => Some(number(*n, key, value)?),
        None => None,
    };
    if ncols
        .checked_mul(nrows)
        .filter(|&c| c <= MAX_CELLS)
        .is_none()
    {
        let (n, key, ..) = field_of(1)?;
        return Err(err(n, &key, DemErrorKind::TooLarge(ncols, nrows)));
    }

    // Data: one line per row, northernmost first.
    let Rows { values, row_lines } = read_rows(lines, path, (ncols, nrows), nodata)?;
    if row_lines.len() < nrows {
        let (n, key, ..) = field_of(1)?;
        let kind = DemErrorKind::TooFewRows {
            found: row_lines.len(),
            expected: nrows,
        };
        return Err(err(n, &key, kind));
    }

    let east = xllcorner + ncols as f64 * cellsize;
    let north = yllcorner + nrows as f64 * cellsize;
    let units = units_by_extent(xllcorner, yllcorner, east, north, cellsize);
    let grid = GridSpec {
        size: (ncols, nrows),
        corner: (xllcorner, yllcorner),
        cell: (cellsize, cellsize),
        units,
    };
    Ok(Dem::new(path, grid, nodata, values, row_lines))
}

/// The units of a grid that does not name them, by the rule in the module documentation: its
/// extent (`west`, `south`, `east`, `north`) and largest cell side `cell`.
pub(super) fn units_by_extent(west: f64, south: f64, east: f64, north: f64, cell: f64) -> Units {
    let geographic = cell < 1.0
        && (-180.0..=180.0).contains(&west)
        && (-180.0..=180.0).contains(&east)
        && (-90.0..=90.0).contains(&south)
        && (-90.0..=90.0).contains(&north);
    if geographic {
        Units::Geographic
    } else {
        Units::Projected
    }
}

/// The data rows of a DEM, as [`read_rows`] reads them.
struct Rows {
    /// Elevations, southernmost row first; NaN for NODATA.
    values: Vec<f32>,
    /// The file line of each row read, northernmost first.
    row_lines: Vec<usize>,
}

/// Reads the data lines (`(line number, text)`, one per row, northernmost first) of a DEM of
/// `(ncols, nrows)` cells: every value a finite number, `nodata` stored as NaN. Fewer than
/// `nrows` rows is left to the caller. The values grow with the rows read, so a header that
/// claims more rows than the file holds allocates no more than the file's rows take.
fn read_rows<'t>(
    lines: impl Iterator<Item = (usize, &'t str)>,
    path: &Path,
    (ncols, nrows): (usize, usize),
    nodata: Option<f64>,
) -> Result<Rows, DemError> {
    let err = |line: usize, field: &str, kind: DemErrorKind| DemError {
        path: path.to_path_buf(),
        line: Some(line),
        field: field.to_string(),
        kind,
    };
    let mut values = Vec::new();
    let mut row_lines = Vec::new();
    for (n, line) in lines {
        let file_row = row_lines.len();
        let row_field = format!("row {} (from the north)", file_row + 1);
        if file_row == nrows {
            let kind = DemErrorKind::TooManyRows { expected: nrows };
            return Err(err(n, &row_field, kind));
        }
        let found = line.split_ascii_whitespace().count();
        if found != ncols {
            let kind = DemErrorKind::WrongValueCount {
                found,
                expected: ncols,
            };
            return Err(err(n, &row_field, kind));
        }
        values.reserve(ncols);
        for (col, token) in line.split_ascii_whitespace().enumerate() {
            let field = || format!("{row_field} column {}", col + 1);
            let v = match token.parse::<f64>() {
                Ok(v) if v.is_finite() => v,
                Ok(_) => return Err(err(n, &field(), DemErrorKind::NotFinite(token.into()))),
                Err(_) => return Err(err(n, &field(), DemErrorKind::NotANumber(token.into()))),
            };
            if Some(v) == nodata {
                values.push(f32::NAN);
                continue;
            }
            let e = v as f32;
            if !e.is_finite() {
                return Err(err(n, &field(), DemErrorKind::NotFinite(token.into())));
            }
            values.push(e);
        }
        row_lines.push(n);
    }
    // Read northernmost first; stored southernmost first.
    reverse_rows(&mut values, ncols);
    Ok(Rows { values, row_lines })
}

/// Reverses the order of the rows of `ncols` values each in `values`, in place.
pub(super) fn reverse_rows(values: &mut [f32], ncols: usize) {
    let rows = values.len() / ncols.max(1);
    for r in 0..rows / 2 {
        let (top, bottom) = values.split_at_mut((rows - 1 - r) * ncols);
        top[r * ncols..(r + 1) * ncols].swap_with_slice(&mut bottom[..ncols]);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const HEADER: &str = "ncols 3\nnrows 2\nxllcorner 10\nyllcorner 20\ncellsize 5\n";

    fn parse_err(text: &str) -> String {
        let e = parse(text, Path::new("t/x.asc")).expect_err("should fail");
        e.to_string()
    }

    /// The message names the file, the line and the field, and says what is wrong.
    fn expect(text: &str, line: usize, field: &str, what: &str) {
        let m = parse_err(text);
        let head = format!("t/x.asc: line {line}: {field}: ");
        assert!(m.starts_with(&head), "{m:?} does not start with {head:?}");
        assert!(m.contains(what), "{m:?} does not say {what:?}");
    }

    #[test]
    fn small_grid_rows_from_the_south() {
        let text = format!("{HEADER}NODATA_value -1\n1 2 3\n4 -1 6.5\n");
        let dem = parse(&text, Path::new("t/x.asc")).unwrap();
        assert_eq!(
            (dem.ncols, dem.nrows, dem.cell_x, dem.cell_y),
            (3, 2, 5.0, 5.0)
        );
        assert_eq!((dem.xllcorner, dem.yllcorner), (10.0, 20.0));
        assert_eq!(dem.units, Units::Projected);
        // The file's last line is row 0.
        assert_eq!(dem.elevation_at(0, 0), Some(4.0));
        assert_eq!(dem.elevation_at(1, 0), None); // NODATA
        assert_eq!(dem.elevation_at(2, 1), Some(3.0));
        assert_eq!(dem.elevation_at(3, 0), None);
        assert_eq!(dem.line_of_row(0), Some(8));
        assert_eq!(dem.line_of_row(1), Some(7));
        assert_eq!((dem.min(), dem.max()), (Some(1.0), Some(6.5)));
        assert_eq!(dem.nodata_count(), 1);
        assert_eq!(dem.nodata_cells().collect::<Vec<_>>(), [(1, 0)]);
        assert!(!dem.is_navigable(1, 0, 1e6, 0.0)); // NODATA: never
        assert!(dem.is_navigable(0, 0, 105.0, 100.0)); // 4 < 5
        assert!(!dem.is_navigable(0, 0, 104.0, 100.0)); // 4 ≥ 4
        assert!(!dem.is_navigable(0, 0, f64::NAN, 0.0));
        assert_eq!(dem.cell_centre(1, 1), Some((17.5, 27.5)));
        assert_eq!(dem.cell_centre_lonlat(1, 1), None);
    }

    #[test]
    fn centre_keys_case_and_order() {
        let text = "CELLSIZE 0.5\nNRows 1\nNCOLS 2\nYLLCENTER 40.25\nxllcenter -3.25\n7 8\n";
        let dem = parse(text, Path::new("t/x.asc")).unwrap();
        assert_eq!((dem.xllcorner, dem.yllcorner), (-3.5, 40.0));
        assert_eq!(dem.units, Units::Geographic);
        assert_eq!(dem.cell_centre_lonlat(1, 0), Some((-2.75, 40.25)));
        assert_eq!(dem.nodata, None);
        assert_eq!(dem.nodata_count(), 0);
    }

    #[test]
    fn missing_key() {
        let text = "ncols 3\nnrows 2\nxllcorner 10\ncellsize 5\n1 2 3\n4 5 6\n";
        expect(text, 5, "yllcorner (or yllcenter)", "missing");
        expect("ncols 3\n", 2, "nrows", "missing");
    }

    #[test]
    fn unknown_key() {
        let text = format!("{HEADER}dx 5\n1 2 3\n4 5 6\n");
        expect(&text, 6, "dx", "unknown header key");
    }

    #[test]
    fn duplicate_key() {
        let text = format!("{HEADER}xllcenter 12.5\n1 2 3\n4 5 6\n");
        expect(&text, 6, "xllcenter", "given twice (first on line 3)");
    }

    #[test]
    fn missing_or_extra_header_value() {
        expect("ncols\nnrows 2\n", 1, "ncols", "has no value");
        expect("ncols 3 4\n", 1, "ncols", "unexpected \"4\"");
    }

    #[test]
    fn malformed_header_values() {
        let text = "ncols 3.5\nnrows 2\nxllcorner 10\nyllcorner 20\ncellsize 5\n1 2 3\n";
        expect(text, 1, "ncols", "\"3.5\" is not a positive integer");
        let text = "ncols 3\nnrows 0\nxllcorner 10\nyllcorner 20\ncellsize 5\n1 2 3\n";
        expect(text, 2, "nrows", "\"0\" is not a positive integer");
        let text = "ncols 3\nnrows 2\nxllcorner ten\nyllcorner 20\ncellsize 5\n1 2 3\n";
        expect(text, 3, "xllcorner", "\"ten\" is not a number");
        let text = "ncols 3\nnrows 2\nxllcorner 10\nyllcorner inf\ncellsize 5\n1 2 3\n";
        expect(text, 4, "yllcorner", "\"inf\" is not a finite number");
        let text = format!("{HEADER}NODATA_value NaN\n1 2 3\n4 5 6\n");
        expect(&text, 6, "NODATA_value", "\"NaN\" is not a finite number");
    }

    #[test]
    fn non_positive_cellsize() {
        let text = "ncols 3\nnrows 2\nxllcorner 10\nyllcorner 20\ncellsize -30\n1 2 3\n";
        expect(text, 5, "cellsize", "-30 is not positive");
        let text = "ncols 3\nnrows 2\nxllcorner 10\nyllcorner 20\ncellsize 0\n1 2 3\n";
        expect(text, 5, "cellsize", "0 is not positive");
    }

    #[test]
    fn non_numeric_and_non_finite_values() {
        let text = format!("{HEADER}1 2 3\n4 5o 6\n");
        expect(
            &text,
            7,
            "row 2 (from the north) column 2",
            "\"5o\" is not a number",
        );
        let text = format!("{HEADER}1 inf 3\n4 5 6\n");
        expect(
            &text,
            6,
            "row 1 (from the north) column 2",
            "\"inf\" is not a finite",
        );
        let text = format!("{HEADER}1 2 3\n4 5 1e39\n"); // overflows f32
        expect(
            &text,
            7,
            "row 2 (from the north) column 3",
            "\"1e39\" is not a finite",
        );
        // A data line starting with NaN is data, not a header key.
        let text = format!("{HEADER}nan 2 3\n4 5 6\n");
        expect(
            &text,
            6,
            "row 1 (from the north) column 1",
            "\"nan\" is not a finite",
        );
    }

    #[test]
    fn short_and_long_rows() {
        let text = format!("{HEADER}1 2 3\n4 5\n");
        expect(
            &text,
            7,
            "row 2 (from the north)",
            "has 2 values, expected ncols = 3",
        );
        let text = format!("{HEADER}1 2 3 9\n4 5 6\n");
        expect(
            &text,
            6,
            "row 1 (from the north)",
            "has 4 values, expected ncols = 3",
        );
    }

    #[test]
    fn wrong_number_of_rows() {
        let text = format!("{HEADER}1 2 3\n");
        expect(
            &text,
            2,
            "nrows",
            "the file ends after 1 rows, expected nrows = 2",
        );
        let text = format!("{HEADER}1 2 3\n\n4 5 6\n7 8 9\n");
        expect(&text, 9, "row 3 (from the north)", "a row beyond nrows = 2");
    }

    #[test]
    fn nodata_cells_are_counted_and_excluded() {
        let text = format!("{HEADER}NODATA_value -9999\n-9999 -9999 -9999\n-9999 -9999 -9999\n");
        let dem = parse(&text, Path::new("t/x.asc")).unwrap();
        assert_eq!(dem.nodata_count(), 6);
        assert_eq!((dem.min(), dem.max()), (None, None));
        assert_eq!(dem.nodata_cells().count(), 6);
        assert!((0..3).all(|c| !dem.is_navigable(c, 0, 1e9, 0.0)));
    }

    #[test]
    fn io_error_names_the_file() {
        let e = super::super::load(Path::new("t/definitely-missing.asc")).unwrap_err();
        assert!(e
            .to_string()
            .starts_with("t/definitely-missing.asc: cannot read"));
        assert_eq!(e.line, None);
    }

    #[test]
    fn a_large_header_over_a_short_file_fails_at_its_first_row() {
        // 16384 × 16384 cells claimed, three values given: the grid grows a row at a time, so
        // this fails having reserved one row (`skyroute build` on it peaks at 5 MB).
        let text = "ncols 16384\nnrows 16384\nxllcorner 0\nyllcorner 0\ncellsize 30\n\
                    NODATA_value -9999\n1 2 3\n";
        expect(
            text,
            7,
            "row 1 (from the north)",
            "has 3 values, expected ncols = 16384",
        );
    }

    #[test]
    fn too_large() {
        let text = "ncols 100000\nnrows 100000\nxllcorner 0\nyllcorner 0\ncellsize 1\n";
        expect(text, 2, "nrows", "cells is more than");
    }
}
