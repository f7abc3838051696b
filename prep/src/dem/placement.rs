//! A DEM's coordinates in a scenario's local frame and back: [`Placement`].
//!
//! A geographic DEM's `(lon, lat)` go through [`LocalFrame::to_local`] as they are. A UTM
//! DEM's `(easting, northing)` are first turned into `(lon, lat)` by the inverse of the zone's
//! transverse Mercator projection (scale 0.9996 on the central meridian `6·zone − 183`°, false
//! easting 500 000 m, false northing 10 000 000 m in the south), evaluated by the same
//! 6th-order Krüger series as the local frame itself (a [`LocalFrame`] with its origin on the
//! equator at the zone's central meridian, scaled): a round trip is exact to nanometres.

use super::Units;
use crate::frame::LocalFrame;

/// UTM's scale on the central meridian.
const UTM_K0: f64 = 0.9996;
/// UTM's false easting, metres.
const UTM_FALSE_EASTING: f64 = 500_000.0;
/// UTM's false northing in the southern hemisphere, metres.
const UTM_FALSE_NORTHING_SOUTH: f64 = 10_000_000.0;

/// The transverse Mercator frame of UTM zone `zone` (scale 1: UTM's is applied by the caller)
/// and the zone's false northing.
fn utm_frame(zone: u8, north: bool) -> (LocalFrame, f64) {
    let central = 6.0 * zone as f64 - 183.0;
    let false_northing = if north { 0.0 } else { UTM_FALSE_NORTHING_SOUTH };
    (LocalFrame::new(0.0, central), false_northing)
}

/// `(easting, northing)` in UTM zone `zone` to `(lon, lat)` degrees.
pub(super) fn utm_to_geo(zone: u8, north: bool, e: f64, n: f64) -> (f64, f64) {
    let (tm, fnorth) = utm_frame(zone, north);
    tm.to_geo((e - UTM_FALSE_EASTING) / UTM_K0, (n - fnorth) / UTM_K0)
}

/// `(lon, lat)` degrees to `(easting, northing)` in UTM zone `zone`.
pub(super) fn geo_to_utm(zone: u8, north: bool, lon: f64, lat: f64) -> (f64, f64) {
    let (tm, fnorth) = utm_frame(zone, north);
    let (u, v) = tm.to_local(lon, lat);
    (UTM_FALSE_EASTING + UTM_K0 * u, fnorth + UTM_K0 * v)
}

/// How a DEM's coordinates map into a local frame.
#[derive(Clone, Copy, Debug)]
pub struct Placement {
    frame: LocalFrame,
    /// For a UTM DEM: the zone's transverse Mercator frame and false northing.
    utm: Option<(LocalFrame, f64)>,
}

impl Placement {
    /// The placement of a DEM in `units` in `frame`; `None` for [`Units::Projected`] (an
    /// unnamed projection cannot be placed).
    pub fn new(units: Units, frame: &LocalFrame) -> Option<Self> {
        let utm = match units {
            Units::Geographic => None,
            Units::Utm { zone, north } => Some(utm_frame(zone, north)),
            Units::Projected => return None,
        };
        Some(Placement { frame: *frame, utm })
    }

    /// The DEM's `(x, y)` to `(lon, lat)` degrees.
    pub fn to_geo(&self, x: f64, y: f64) -> (f64, f64) {
        match &self.utm {
            None => (x, y),
            Some((tm, fnorth)) => {
                tm.to_geo((x - UTM_FALSE_EASTING) / UTM_K0, (y - fnorth) / UTM_K0)
            }
        }
    }

    /// The DEM's `(x, y)` to the frame's `(x, y)`, metres.
    pub fn to_local(&self, x: f64, y: f64) -> (f64, f64) {
        let (lon, lat) = self.to_geo(x, y);
        self.frame.to_local(lon, lat)
    }

    /// The frame's `(x, y)` to the DEM's `(x, y)`.
    pub fn to_dem(&self, x: f64, y: f64) -> (f64, f64) {
        let (lon, lat) = self.frame.to_geo(x, y);
        match &self.utm {
            None => (lon, lat),
            Some((tm, fnorth)) => {
                let (u, v) = tm.to_local(lon, lat);
                (UTM_FALSE_EASTING + UTM_K0 * u, fnorth + UTM_K0 * v)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A point of known UTM coordinates: 84.2° W 36.5° N is (750 784.178 m, 4 043 054.724 m) in
    /// zone 16 N (PROJ: `echo 36.5 -84.2 | cs2cs EPSG:4326 EPSG:32616 -f %.3f`).
    #[test]
    fn utm_round_trip_and_a_known_point() {
        let (lon, lat) = utm_to_geo(16, true, 750_784.178, 4_043_054.724);
        assert!(
            (lon + 84.2).abs() < 1e-7 && (lat - 36.5).abs() < 1e-7,
            "{lon} {lat}"
        );
        let frame = LocalFrame::new(36.5, -84.2);
        let p = Placement::new(
            Units::Utm {
                zone: 16,
                north: true,
            },
            &frame,
        )
        .unwrap();
        let (e, n) = p.to_dem(0.0, 0.0);
        let (lon, lat) = p.to_geo(e, n);
        assert!(
            (lon + 84.2).abs() < 1e-9 && (lat - 36.5).abs() < 1e-9,
            "{lon} {lat}"
        );
        let (x, y) = p.to_local(e + 1000.0, n);
        assert!((x.hypot(y) - 1000.0).abs() < 1.0, "{x} {y}");
        let s = Placement::new(
            Units::Utm {
                zone: 33,
                north: false,
            },
            &frame,
        )
        .unwrap();
        let (lon, lat) = s.to_geo(500_000.0, 10_000_000.0);
        assert!(
            (lon - 15.0).abs() < 1e-12 && lat.abs() < 1e-9,
            "{lon} {lat}"
        );
        assert!(Placement::new(Units::Projected, &frame).is_none());
    }
}
