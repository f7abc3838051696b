//! Digital elevation models for the terrain mode (Medeiros & da Silva): ESRI ASCII grids
//! ([`ascii`], `.asc`) and GeoTIFF ([`geotiff`], `.tif`), read into one [`Dem`].
//!
//! [`load`] reads a file and picks the reader by the file's first bytes (a TIFF or BigTIFF
//! header means GeoTIFF, anything else is read as an ASCII grid), so the extension does not
//! matter.
//!
//! # Rows, columns, units
//!
//! [`Dem`] stores and indexes rows **from the south** (`row 0` is the southernmost), the same
//! convention as [`skyroute::geometry::grid::CellGrid`]: cell `(col, row)` covers
//! `[x + col·cell_x, x + (col+1)·cell_x] × [y + row·cell_y, y + (row+1)·cell_y]` with
//! `(x, y) = (xllcorner, yllcorner)`, in the grid's [`Units`]. Cells need not be square
//! (`cell_x ≠ cell_y`, as in Copernicus GLO-30 north of 50°); an ASCII grid's are.
//!
//! # NODATA
//!
//! NODATA cells are stored as NaN; [`Dem::elevation_at`] returns `None` for them,
//! [`Dem::nodata_count`] counts them and [`Dem::nodata_cells`] lists them. **A caller must
//! treat a NODATA cell as not navigable** (the terrain there is unknown), as
//! [`Dem::is_navigable`] does; [`Dem::min`] and [`Dem::max`] ignore NODATA cells.

pub mod ascii;
pub mod geotiff;
#[cfg(test)]
mod geotiff_tests;
mod placement;

pub use ascii::parse;
pub use placement::Placement;

use std::fmt;
use std::path::{Path, PathBuf};

/// The most cells a DEM may have (2²⁸, 1 GiB of `f32`).
pub const MAX_CELLS: usize = 1 << 28;

/// How the grid's coordinates are to be read.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Units {
    /// Degrees: `x` longitude east, `y` latitude north (WGS-84, or a datum within a metre or two
    /// of it: NAD83, ETRS89).
    Geographic,
    /// Metres in a UTM zone (WGS-84, NAD83 or ETRS89): easting with the false easting of
    /// 500 000 m, northing with a false northing of 10 000 000 m in the south.
    Utm {
        /// The zone, 1 to 60.
        zone: u8,
        /// Whether it is the northern hemisphere's zone (false northing 0).
        north: bool,
    },
    /// Metres in a projection the file does not name (an ASCII grid): cannot be placed on the
    /// earth.
    Projected,
}

/// An elevation model read from an ESRI ASCII grid or a GeoTIFF.
#[derive(Clone, Debug, PartialEq)]
pub struct Dem {
    /// The file it was read from.
    pub path: PathBuf,
    /// Number of columns.
    pub ncols: usize,
    /// Number of rows.
    pub nrows: usize,
    /// West edge of the grid, in [`Dem::units`].
    pub xllcorner: f64,
    /// South edge of the grid, in [`Dem::units`].
    pub yllcorner: f64,
    /// West–east side of a cell, in [`Dem::units`].
    pub cell_x: f64,
    /// South–north side of a cell, in [`Dem::units`].
    pub cell_y: f64,
    /// The file's NODATA value, if it has one.
    pub nodata: Option<f64>,
    /// What the coordinates are; the reader's documentation says how it decides.
    pub units: Units,
    /// Elevations, row-major, rows from the south; NaN for NODATA.
    values: Vec<f32>,
    /// The file line of each row, rows from the north (as in the file); empty for a GeoTIFF.
    row_lines: Vec<usize>,
    nodata_count: usize,
    min: Option<f32>,
    max: Option<f32>,
}

/// The grid of a [`Dem`] without its elevations: size, south-west corner, cell sides, units.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GridSpec {
    /// Columns and rows.
    pub size: (usize, usize),
    /// South-west corner `(x, y)`.
    pub corner: (f64, f64),
    /// Cell sides `(x, y)`.
    pub cell: (f64, f64),
    /// Units of the corner and the cell sides.
    pub units: Units,
}

impl Dem {
    /// A DEM of `grid` with `values` (row-major, rows from the south, NaN for NODATA, exactly
    /// `ncols·nrows` of them) read from `path`; `row_lines` as in [`Dem::line_of_row`].
    pub(crate) fn new(
        path: &Path,
        grid: GridSpec,
        nodata: Option<f64>,
        values: Vec<f32>,
        row_lines: Vec<usize>,
    ) -> Self {
        let (mut min, mut max) = (f32::INFINITY, f32::NEG_INFINITY);
        let mut nodata_count = 0;
        for &v in &values {
            if v.is_nan() {
                nodata_count += 1;
            } else {
                min = min.min(v);
                max = max.max(v);
            }
        }
        let any = nodata_count < values.len();
        Dem {
            path: path.to_path_buf(),
            ncols: grid.size.0,
            nrows: grid.size.1,
            xllcorner: grid.corner.0,
            yllcorner: grid.corner.1,
            cell_x: grid.cell.0,
            cell_y: grid.cell.1,
            nodata,
            units: grid.units,
            values,
            row_lines,
            nodata_count,
            min: any.then_some(min),
            max: any.then_some(max),
        }
    }

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
            self.xllcorner + (col as f64 + 0.5) * self.cell_x,
            self.yllcorner + (row as f64 + 0.5) * self.cell_y,
        ))
    }

    /// The centre of cell `(col, row)` as `(longitude, latitude)` degrees (WGS-84); `None` for
    /// a grid in an unnamed projection or outside the grid.
    pub fn cell_centre_lonlat(&self, col: usize, row: usize) -> Option<(f64, f64)> {
        let (x, y) = self.cell_centre(col, row)?;
        match self.units {
            Units::Geographic => Some((x, y)),
            Units::Utm { zone, north } => Some(placement::utm_to_geo(zone, north, x, y)),
            Units::Projected => None,
        }
    }

    /// The cell `(col, row)` (row 0 southernmost) under `(lon, lat)` degrees (WGS-84); `None`
    /// outside the grid or for a grid in an unnamed projection.
    pub fn cell_at_lonlat(&self, lon: f64, lat: f64) -> Option<(usize, usize)> {
        let (x, y) = match self.units {
            Units::Geographic => (lon, lat),
            Units::Utm { zone, north } => placement::geo_to_utm(zone, north, lon, lat),
            Units::Projected => return None,
        };
        let c = ((x - self.xllcorner) / self.cell_x).floor();
        let r = ((y - self.yllcorner) / self.cell_y).floor();
        let inside = c >= 0.0 && r >= 0.0 && c < self.ncols as f64 && r < self.nrows as f64;
        inside.then_some((c as usize, r as usize))
    }

    /// The 1-based line of the file that holds row `row` (row 0 southernmost); `None` outside
    /// the grid and for a GeoTIFF.
    pub fn line_of_row(&self, row: usize) -> Option<usize> {
        if row >= self.nrows {
            return None;
        }
        self.row_lines.get(self.nrows - 1 - row).copied()
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
    /// A GeoTIFF value this reader does not support (the field names the tag or key).
    Unsupported(String),
    /// A GeoTIFF tag or key that is missing, malformed or inconsistent with the file.
    Invalid(String),
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
            DemErrorKind::Unsupported(m) => write!(f, "not supported: {m}"),
            DemErrorKind::Invalid(m) => write!(f, "{m}"),
        }
    }
}

/// Why a DEM could not be loaded: the file, the line (1-based; ASCII grids only, absent for
/// I/O errors), the field (`cellsize`, `row 12 (from the north) column 17`, `tag 33550
/// (ModelPixelScale)`, …) and what is wrong.
#[derive(Clone, Debug, PartialEq)]
pub struct DemError {
    /// The file.
    pub path: PathBuf,
    /// The line, 1-based.
    pub line: Option<usize>,
    /// The header key, the data row and column, or the TIFF tag; empty for errors about the
    /// whole file.
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

/// Reads and checks the DEM at `path`: a GeoTIFF ([`geotiff::parse`]) when the file starts
/// with a TIFF or BigTIFF header, an ESRI ASCII grid ([`ascii::parse`]) otherwise.
pub fn load(path: &Path) -> Result<Dem, DemError> {
    let bytes = std::fs::read(path).map_err(|e| DemError {
        path: path.to_path_buf(),
        line: None,
        field: String::new(),
        kind: DemErrorKind::Io(e.to_string()),
    })?;
    if geotiff::is_tiff(&bytes) {
        return geotiff::parse(&bytes, path);
    }
    let text = String::from_utf8(bytes).map_err(|e| DemError {
        path: path.to_path_buf(),
        line: None,
        field: String::new(),
        kind: DemErrorKind::Io(format!(
            "neither a TIFF nor an ASCII grid (not UTF-8 text: {e})"
        )),
    })?;
    ascii::parse(&text, path)
}
