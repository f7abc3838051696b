//! Digital elevation models in the ESRI ASCII grid format (`.asc`), for the terrain mode
//! (Medeiros & da Silva).
//!
//! [`load`] reads a file, [`parse`] takes its text. The format: a header of `key value` lines,
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
//! # Rows, columns, units
//!
//! [`Dem`] stores and indexes rows **from the south** (`row 0` is the file's last data line), the
//! same convention as [`skyroute::geometry::grid::CellGrid`]: cell `(col, row)` covers
//! `[x + col·cellsize, x + (col+1)·cellsize] × [y + row·cellsize, y + (row+1)·cellsize]` with
//! `(x, y) = (xllcorner, yllcorner)`. [`Dem::line_of_row`] gives the file line of a row.
//!
//! The grid is taken as **geographic** (degrees of longitude/latitude, WGS-84) when `cellsize < 1`
//! and its whole extent lies within ±180° × ±90°, and as **projected** (metres) otherwise — the
//! format carries no coordinate system, and a sub-metre projected grid near its projection's
//! origin would be misread; set [`Dem::units`] to override. Only geographic grids have
//! [`Dem::cell_centre_lonlat`].
//!
//! # NODATA
//!
//! Cells equal to `NODATA_value` are stored as NaN; [`Dem::elevation_at`] returns `None` for
//! them, [`Dem::nodata_count`] counts them and [`Dem::nodata_cells`] lists them. **A caller must
//! treat a NODATA cell as not navigable** (the terrain there is unknown), as
//! [`Dem::is_navigable`] does; [`Dem::min`] and [`Dem::max`] ignore NODATA cells.

use std::fmt;
use std::path::{Path, PathBuf};

/// The most cells a DEM may have (2²⁸, 1 GiB of `f32`).
pub const MAX_CELLS: usize = 1 << 28;

/// How the grid's coordinates are to be read.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Units {
    /// Degrees: `x` longitude east, `y` latitude north (WGS-84).
    Geographic,
    /// A projected frame, metres.
    Projected,
}

/// An elevation model read from an ESRI ASCII grid.
#[derive(Clone, Debug, PartialEq)]
pub struct Dem {
    /// The file it was read from.
    pub path: PathBuf,
    /// Number of columns.
    pub ncols: usize,
    /// Number of rows.
    pub nrows: usize,
    /// West edge of the grid (`xllcenter − cellsize/2` when the file gives the centre).
    pub xllcorner: f64,
    /// South edge of the grid (`yllcenter − cellsize/2` when the file gives the centre).
    pub yllcorner: f64,
    /// Side of a cell, in [`Dem::units`].
    pub cellsize: f64,
    /// The file's `NODATA_value`, if it has one.
    pub nodata: Option<f64>,
    /// Geographic or projected, by the rule in the module documentation; may be overridden.
    pub units: Units,
    /// Elevations, row-major, rows from the south; NaN for NODATA.
    values: Vec<f32>,
    /// The file line of each row, rows from the north (as in the file).
    row_lines: Vec<usize>,
    nodata_count: usize,
    min: Option<f32>,
    max: Option<f32>,
}

impl Dem {
    /// The elevations, row-major with row 0 the southernmost, NaN for NODATA cells.
    pub fn values(&self) -> &[f32] {
        &self.values
    }

    /// The elevation of cell `(col, row)` (row 0 southernmost); `None` outside the grid or for a
    /// NODATA cell — either way a cell to treat as not navigable.
    pub fn elevation_at(&self, col: usize, row: usize) -> Option<f32> {
        if col >= self.ncols || row >= self.nrows {
            return None;
        }
        let v = self.values[row * self.ncols + col];
        (!v.is_nan()).then_some(v)
    }

    /// Whether an aircraft at `altitude_m` that must keep `safety_height_m` above the terrain
    /// may fly over cell `(col, row)`: its elevation is below `altitude_m − safety_height_m`.
    /// `false` for NODATA cells, cells outside the grid, and NaN arguments.
    pub fn is_navigable(
        &self,
        col: usize,
        row: usize,
        altitude_m: f64,
        safety_height_m: f64,
    ) -> bool {
        match self.elevation_at(col, row) {
            Some(e) => (e as f64) < altitude_m - safety_height_m,
            None => false,
        }
    }

    /// The lowest elevation, NODATA cells aside (`None` when every cell is NODATA).
    pub fn min(&self) -> Option<f32> {
        self.min
    }

    /// The highest elevation, NODATA cells aside (`None` when every cell is NODATA).
    pub fn max(&self) -> Option<f32> {
        self.max
    }

    /// How many cells are NODATA.
    pub fn nodata_count(&self) -> usize {
        self.nodata_count
    }

    /// The NODATA cells as `(col, row)`, row 0 southernmost, in storage order.
    pub fn nodata_cells(&self) -> impl Iterator<Item = (usize, usize)> + '_ {
        let n = self.ncols;
        self.values
            .iter()
            .enumerate()
            .filter(|(_, v)| v.is_nan())
            .map(move |(i, _)| (i % n, i / n))
    }

    /// The centre of cell `(col, row)` in the grid's own units; `None` outside the grid.
    pub fn cell_centre(&self, col: usize, row: usize) -> Option<(f64, f64)> {
        if col >= self.ncols || row >= self.nrows {
            return None;
        }
        Some((
            self.xllcorner + (col as f64 + 0.5) * self.cellsize,
            self.yllcorner + (row as f64 + 0.5) * self.cellsize,
        ))
    }

    /// The centre of cell `(col, row)` as `(longitude, latitude)` degrees; `None` for a projected
    /// grid or outside the grid.
    pub fn cell_centre_lonlat(&self, col: usize, row: usize) -> Option<(f64, f64)> {
        match self.units {
            Units::Geographic => self.cell_centre(col, row),
            Units::Projected => None,
        }
    }

    /// The 1-based line of the file that holds row `row` (row 0 southernmost).
    pub fn line_of_row(&self, row: usize) -> Option<usize> {
        (row < self.nrows).then(|| self.row_lines[self.nrows - 1 - row])
    }
}

/// What is wrong, in a [`DemError`].
#[derive(Clone, Debug, PartialEq)]
pub enum DemErrorKind {
    /// The file could not be read.
    Io(String),
    /// A required header key is absent.
    MissingKey,
    /// A header key the format does not define (misspelt?).
    UnknownKey,
    /// A header key given twice (or both the corner and the centre form of one).
    DuplicateKey {
        /// The line of the first.
        first_line: usize,
    },
    /// A header key without a value.
    MissingValue,
    /// More than one value after a header key.
    ExtraValue(String),
    /// Not a number.
    NotANumber(String),
    /// A number that is NaN or infinite (or overflows an `f32`, for elevations).
    NotFinite(String),
    /// `ncols`/`nrows` must be a positive integer.
    NotPositiveInteger(String),
    /// `cellsize` must be positive.
    NotPositive(f64),
    /// More than [`MAX_CELLS`] cells.
    TooLarge(usize, usize),
    /// A data line with the wrong number of values.
    WrongValueCount {
        /// Values on the line.
        found: usize,
        /// `ncols`.
        expected: usize,
    },
    /// Fewer data lines than `nrows`.
    TooFewRows {
        /// Data lines found.
        found: usize,
        /// `nrows`.
        expected: usize,
    },
    /// More data lines than `nrows`.
    TooManyRows {
        /// `nrows`.
        expected: usize,
    },
}

impl fmt::Display for DemErrorKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            DemErrorKind::Io(m) => write!(f, "cannot read: {m}"),
            DemErrorKind::MissingKey => write!(f, "missing from the header"),
            DemErrorKind::UnknownKey => write!(
                f,
                "unknown header key (expected ncols, nrows, xllcorner/xllcenter, \
                 yllcorner/yllcenter, cellsize, NODATA_value)"
            ),
            DemErrorKind::DuplicateKey { first_line } => {
                write!(f, "given twice (first on line {first_line})")
            }
            DemErrorKind::MissingValue => write!(f, "has no value"),
            DemErrorKind::ExtraValue(t) => write!(f, "unexpected {t:?} after the value"),
            DemErrorKind::NotANumber(t) => write!(f, "{t:?} is not a number"),
            DemErrorKind::NotFinite(t) => write!(f, "{t:?} is not a finite number"),
            DemErrorKind::NotPositiveInteger(t) => write!(f, "{t:?} is not a positive integer"),
            DemErrorKind::NotPositive(v) => write!(f, "{v} is not positive"),
            DemErrorKind::TooLarge(c, r) => {
                write!(f, "{c} x {r} cells is more than {MAX_CELLS}")
            }
            DemErrorKind::WrongValueCount { found, expected } => {
                write!(f, "has {found} values, expected ncols = {expected}")
            }
            DemErrorKind::TooFewRows { found, expected } => {
                write!(
                    f,
                    "the file ends after {found} rows, expected nrows = {expected}"
                )
            }
            DemErrorKind::TooManyRows { expected } => {
                write!(f, "a row beyond nrows = {expected}")
            }
        }
    }
}

/// Why a DEM could not be loaded: the file, the line (1-based; absent for I/O errors), the field
/// (`cellsize`, `row 12 (from the north) column 17`, …) and what is wrong.
#[derive(Clone, Debug, PartialEq)]
pub struct DemError {
    /// The file.
    pub path: PathBuf,
    /// The line, 1-based.
    pub line: Option<usize>,
    /// The header key or the data row and column; empty for errors about the whole file.
    pub field: String,
    /// What is wrong.
    pub kind: DemErrorKind,
}

impl fmt::Display for DemError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: ", self.path.display())?;
        if let Some(line) = self.line {
            write!(f, "line {line}: ")?;
        }
        if !self.field.is_empty() {
            write!(f, "{}: ", self.field)?;
        }
        write!(f, "{}", self.kind)
    }
}

impl std::error::Error for DemError {}

/// Reads and checks the DEM at `path`.
pub fn load(path: &Path) -> Result<Dem, DemError> {
    let text = std::fs::read_to_string(path).map_err(|e| DemError {
        path: path.to_path_buf(),
        line: None,
        field: String::new(),
        kind: DemErrorKind::Io(e.to_string()),
    })?;
    parse(&text, path)
}

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
    let cells = ncols.checked_mul(nrows).filter(|&c| c <= MAX_CELLS);
    let Some(cells) = cells else {
        let (n, key, ..) = field_of(1)?;
        return Err(err(n, &key, DemErrorKind::TooLarge(ncols, nrows)));
    };

    // Data: one line per row, northernmost first.
    let Rows {
        values,
        row_lines,
        nodata_count,
        min,
        max,
    } = read_rows(lines, path, (ncols, nrows), nodata)?;
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
    let geographic = cellsize < 1.0
        && (-180.0..=180.0).contains(&xllcorner)
        && (-180.0..=180.0).contains(&east)
        && (-90.0..=90.0).contains(&yllcorner)
        && (-90.0..=90.0).contains(&north);
    let any = nodata_count < cells;
    Ok(Dem {
        path: path.to_path_buf(),
        ncols,
        nrows,
        xllcorner,
        yllcorner,
        cellsize,
        nodata,
        units: if geographic {
            Units::Geographic
        } else {
            Units::Projected
        },
        values,
        row_lines,
        nodata_count,
        min: any.then_some(min),
        max: any.then_some(max),
    })
}

/// The data rows of a DEM, as [`read_rows`] reads them.
struct Rows {
    /// Elevations, southernmost row first; NaN for NODATA.
    values: Vec<f32>,
    /// The file line of each row read, northernmost first.
    row_lines: Vec<usize>,
    /// Cells equal to the NODATA value.
    nodata_count: usize,
    /// Smallest and largest elevation of the other cells (infinite when there is none).
    min: f32,
    max: f32,
}

/// Reads the data lines (`(line number, text)`, one per row, northernmost first) of a DEM of
/// `(ncols, nrows)` cells: every value a finite number, `nodata` stored as NaN. Fewer than
/// `nrows` rows is left to the caller.
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
    let cells = ncols * nrows;
    let mut values = vec![f32::NAN; cells];
    let mut row_lines = Vec::with_capacity(nrows);
    let mut nodata_count = 0;
    let (mut min, mut max) = (f32::INFINITY, f32::NEG_INFINITY);
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
        let south_row = nrows - 1 - file_row;
        let out = &mut values[south_row * ncols..(south_row + 1) * ncols];
        for (col, (token, slot)) in line.split_ascii_whitespace().zip(out).enumerate() {
            let field = || format!("{row_field} column {}", col + 1);
            let v = match token.parse::<f64>() {
                Ok(v) if v.is_finite() => v,
                Ok(_) => return Err(err(n, &field(), DemErrorKind::NotFinite(token.into()))),
                Err(_) => return Err(err(n, &field(), DemErrorKind::NotANumber(token.into()))),
            };
            if Some(v) == nodata {
                nodata_count += 1;
                continue; // stays NaN
            }
            let e = v as f32;
            if !e.is_finite() {
                return Err(err(n, &field(), DemErrorKind::NotFinite(token.into())));
            }
            *slot = e;
            min = min.min(e);
            max = max.max(e);
        }
        row_lines.push(n);
    }
    Ok(Rows {
        values,
        row_lines,
        nodata_count,
        min,
        max,
    })
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
        assert_eq!((dem.ncols, dem.nrows, dem.cellsize), (3, 2, 5.0));
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
        let e = load(Path::new("t/definitely-missing.asc")).unwrap_err();
        assert!(e
            .to_string()
            .starts_with("t/definitely-missing.asc: cannot read"));
        assert_eq!(e.line, None);
    }

    #[test]
    fn too_large() {
        let text = "ncols 100000\nnrows 100000\nxllcorner 0\nyllcorner 0\ncellsize 1\n";
        expect(text, 2, "nrows", "cells is more than");
    }
}
