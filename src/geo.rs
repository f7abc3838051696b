//! WGS-84 longitude/latitude to the network's local frame and back, on the flight computer.
//!
//! The local frame of a network (and of the ground tool, which builds networks in it) is metres
//! east (`x`) and north (`y`) of the frame origin stored in the network header
//! ([`Network::origin_deg`](crate::Network::origin_deg)).
//! [`Network::local_frame`](crate::Network::local_frame) gives the frame; [`LocalFrame::position`],
//! [`LocalFrame::heading`] and [`LocalFrame::pose`] turn an autopilot's latitude, longitude and
//! compass heading into the planner's [`Vec2`] and [`Pose`], and [`LocalFrame::lon_lat`] and
//! [`LocalFrame::compass_deg`] turn the planner's positions and headings back. They reject
//! non-finite and out-of-range input with a [`GeoError`] and never panic.
//!
//! # Method
//!
//! A **transverse Mercator projection on the WGS-84 ellipsoid** whose central meridian is the
//! origin's meridian, with scale factor 1 on that meridian and the false origin at the frame
//! origin (so the origin maps to `(0, 0)`, `x` grows east and `y` north). This is PROJ's
//! `+proj=tmerc +lat_0=φ₀ +lon_0=λ₀ +k=1 +x_0=0 +y_0=0 +ellps=WGS84`. The projection is
//! evaluated in `f64` (with `libm`) with Krüger's series in the third flattening `n`, taken to
//! **6th order** as in C. F. F. Karney, "Transverse Mercator with an accuracy of a few
//! nanometers", J. Geodesy 85 (2011) 475–485, eqs. (7)–(11), (35), (36) (the series the UTM
//! formulas of NGA and JHS 154 use to 4th order). The inverse solves for the latitude from the
//! conformal latitude by Newton's method (Karney 2011, eqs. (19)–(21)). The truncation error of
//! the 6th-order series is about 5 nm within 3 900 km of the central meridian
//! ([`MAX_EAST_WEST_M`], beyond which the checked conversions refuse a point).
//!
//! # Error bounds
//!
//! Measured against PROJ 9.5.1 (pyproj 3.7.2, whose `tmerc` is the Poder/Engsager
//! implementation of the Krüger series, independent of this one) at 150 points within ±50 km
//! (east and north) of the frame origin of each shipped scenario (`scenarios/*.geojson`: eight
//! distinct origins from 36.6° N to 48.2° N, 1 200 points) by `host-tests/tests/core/geo.rs`,
//! on the reference `scripts/pyproj_tmerc_reference.py` wrote to
//! `host-tests/data/pyproj_tmerc.csv`:
//!
//! * **`f64` maths** ([`LocalFrame::to_local`], [`LocalFrame::to_geo`]): at most 3.2·10⁻⁹ m
//!   from PROJ forward, and 4.0·10⁻⁹ m (on the ground) inverse; asserted ≤ 10⁻⁸ m.
//! * **`f32` position the planner receives** ([`LocalFrame::position`]): at most 2.4 mm from
//!   PROJ, which is the rounding of the coordinates to `f32` (spacing 3.9 mm between 32 and
//!   64 km; the rest is below 10⁻⁹ m). Asserted ≤ 2.8 mm, the rounding bound at 64 km.
//! * **Headings** ([`LocalFrame::heading`]): the meridian convergence γ agrees with PROJ's to
//!   4.5·10⁻¹¹ degrees; the `f32` heading the planner receives is within 8.8·10⁻⁷ rad
//!   (5·10⁻⁵ degrees) of `compass − γ` evaluated exactly, mostly the rounding of the grid
//!   heading in degrees to `f32` (spacing 3·10⁻⁵ degrees above 256°). Asserted ≤ 10⁻⁶ rad.
//!
//! Farther out, Karney (2011) bounds the series' truncation error by about 5 nm up to
//! [`MAX_EAST_WEST_M`] (not measured here), while the `f32` rounding grows with the distance `d`
//! from the origin: at most `d·2⁻²⁴` (6·10⁻⁸·`d`).
//!
//! The projection itself distorts lengths by the point scale `k` ([`LocalFrame::scale_factor`]):
//! `k` is 1 on the origin's meridian and `k − 1 = x²/(2ρν) + O(x⁴/R⁴)` at `x` metres east or west
//! of it (ρ, ν the principal radii of curvature), at most 3.1·10⁻⁵ for `|x| ≤ 50 km`. Grid north
//! (+`y`) and true north differ by the meridian convergence γ ≈ Δλ·sin φ (0.5° at 50 km east of a
//! 48° N origin), which [`LocalFrame::heading`] applies.

use crate::geometry::{
    compass_deg_from_heading, heading_from_compass_deg, Pose, Vec2, MAX_COORDINATE_M,
};
use core::fmt;

/// WGS-84 semi-major axis `a`, metres.
pub const WGS84_A: f64 = 6_378_137.0;
/// WGS-84 flattening `f`.
pub const WGS84_F: f64 = 1.0 / 298.257_223_563;
/// The farthest a point may lie east or west of the origin's meridian (`|x|`, metres) for the
/// checked conversions: the 6th-order Krüger series is accurate to about 5 nm within it
/// (Karney 2011, § 4).
pub const MAX_EAST_WEST_M: f64 = 3_900_000.0;

/// Why a geographic conversion refused its input.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum GeoError {
    /// A coordinate, origin or heading is NaN or infinite.
    NonFinite,
    /// A latitude outside [−90, 90] degrees.
    Latitude,
    /// A longitude outside [−180, 180] degrees.
    Longitude,
    /// A compass heading outside [−360, 360] degrees.
    Heading,
    /// The point lies more than [`MAX_EAST_WEST_M`] east or west of the origin's meridian,
    /// beyond a pole, or outside the planner's coordinate range (±[`MAX_COORDINATE_M`]).
    OutOfFrame,
}

impl fmt::Display for GeoError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            GeoError::NonFinite => "a coordinate or heading is not finite",
            GeoError::Latitude => "latitude outside [-90, 90] degrees",
            GeoError::Longitude => "longitude outside [-180, 180] degrees",
            GeoError::Heading => "compass heading outside [-360, 360] degrees",
            GeoError::OutOfFrame => "the point lies outside the local frame's valid region",
        })
    }
}

#[cfg(feature = "std")]
impl std::error::Error for GeoError {}

/// The projection constants, which depend only on the ellipsoid.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Ellipsoid {
    /// First eccentricity `e`.
    e: f64,
    /// `e²`.
    e2: f64,
    /// Rectifying radius `A` (metres): the meridian distance from the equator to the pole is `A·π/2`.
    a_rect: f64,
    /// Krüger's forward series coefficients α₁…α₆.
    alpha: [f64; 6],
    /// Krüger's reverse series coefficients β₁…β₆.
    beta: [f64; 6],
}

impl Ellipsoid {
    fn wgs84() -> Self {
        let f = WGS84_F;
        let n = f / (2.0 - f);
        let (n2, n3) = (n * n, n * n * n);
        let (n4, n5, n6) = (n3 * n, n3 * n2, n3 * n3);
        let e2 = f * (2.0 - f);
        // Karney (2011) eq. (14).
        let a_rect = WGS84_A / (1.0 + n) * (1.0 + n2 / 4.0 + n4 / 64.0 + n6 / 256.0);
        // Karney (2011) eq. (35).
        let alpha = [
            n / 2.0 - 2.0 / 3.0 * n2 + 5.0 / 16.0 * n3 + 41.0 / 180.0 * n4 - 127.0 / 288.0 * n5
                + 7891.0 / 37800.0 * n6,
            13.0 / 48.0 * n2 - 3.0 / 5.0 * n3 + 557.0 / 1440.0 * n4 + 281.0 / 630.0 * n5
                - 1_983_433.0 / 1_935_360.0 * n6,
            61.0 / 240.0 * n3 - 103.0 / 140.0 * n4
                + 15061.0 / 26880.0 * n5
                + 167_603.0 / 181_440.0 * n6,
            49561.0 / 161_280.0 * n4 - 179.0 / 168.0 * n5 + 6_601_661.0 / 7_257_600.0 * n6,
            34729.0 / 80640.0 * n5 - 3_418_889.0 / 1_995_840.0 * n6,
            212_378_941.0 / 319_334_400.0 * n6,
        ];
        // Karney (2011) eq. (36).
        let beta = [
            n / 2.0 - 2.0 / 3.0 * n2 + 37.0 / 96.0 * n3 - 1.0 / 360.0 * n4 - 81.0 / 512.0 * n5
                + 96199.0 / 604_800.0 * n6,
            n2 / 48.0 + n3 / 15.0 - 437.0 / 1440.0 * n4 + 46.0 / 105.0 * n5
                - 1_118_711.0 / 3_870_720.0 * n6,
            17.0 / 480.0 * n3 - 37.0 / 840.0 * n4 - 209.0 / 4480.0 * n5 + 5569.0 / 90720.0 * n6,
            4397.0 / 161_280.0 * n4 - 11.0 / 504.0 * n5 - 830_251.0 / 7_257_600.0 * n6,
            4583.0 / 161_280.0 * n5 - 108_847.0 / 3_991_680.0 * n6,
            20_648_693.0 / 638_668_800.0 * n6,
        ];
        Self {
            e: libm::sqrt(e2),
            e2,
            a_rect,
            alpha,
            beta,
        }
    }

    /// tan of the conformal latitude from tan φ (Karney 2011 eqs. (7)–(9)).
    fn taup(&self, tau: f64) -> f64 {
        let tau1 = libm::hypot(tau, 1.0);
        let sig = libm::sinh(self.e * libm::atanh(self.e * tau / tau1));
        tau * libm::hypot(sig, 1.0) - sig * tau1
    }

    /// tan φ from tan of the conformal latitude, by Newton's method (Karney 2011 eqs. (19)–(21)).
    fn tau_from_taup(&self, taup: f64) -> f64 {
        let e2m = 1.0 - self.e2;
        let mut tau = taup / e2m;
        for _ in 0..8 {
            let taupa = self.taup(tau);
            let dtau = (taup - taupa) * (1.0 + e2m * tau * tau)
                / (e2m * libm::hypot(tau, 1.0) * libm::hypot(taupa, 1.0));
            tau += dtau;
            if dtau.abs() <= 1e-15 * tau.abs().max(1.0) {
                break;
            }
        }
        tau
    }

    /// Forward projection with scale 1 on the central meridian and the false origin on the
    /// equator: `(φ, Δλ)` in radians, `|Δλ| < π/2`, to `(η, ξ, p, q, ξ', η', τ')` where
    /// `x = A·η`, `y = A·ξ` and `p − iq` is the derivative of the Krüger series
    /// (Karney 2011 eqs. (10), (11)).
    fn forward(&self, phi: f64, lam: f64) -> Forward {
        let taup = self.taup(libm::tan(phi));
        let (slam, clam) = libm::sincos(lam);
        let xip = libm::atan2(taup, clam);
        let etap = libm::asinh(slam / libm::hypot(taup, clam));
        let (mut xi, mut eta) = (xip, etap);
        let (mut p, mut q) = (1.0, 0.0);
        for (j, a) in self.alpha.iter().enumerate() {
            let m = 2.0 * (j + 1) as f64;
            let (s, c) = libm::sincos(m * xip);
            let (sh, ch) = (libm::sinh(m * etap), libm::cosh(m * etap));
            xi += a * s * ch;
            eta += a * c * sh;
            p += m * a * c * ch;
            q += m * a * s * sh;
        }
        Forward {
            xi,
            eta,
            p,
            q,
            xip,
            etap,
            taup,
        }
    }

    /// Reverse projection (Karney 2011 eq. (11) with the β series, then eqs. (19)–(21)):
    /// `(ξ, η)` (metres / A) to `(φ, Δλ)` in radians.
    fn reverse(&self, xi: f64, eta: f64) -> (f64, f64) {
        let (mut xip, mut etap) = (xi, eta);
        for (j, b) in self.beta.iter().enumerate() {
            let m = 2.0 * (j + 1) as f64;
            let (s, c) = libm::sincos(m * xi);
            xip -= b * s * libm::cosh(m * eta);
            etap -= b * c * libm::sinh(m * eta);
        }
        let (sxip, cxip) = libm::sincos(xip);
        let shetap = libm::sinh(etap);
        let taup = sxip / libm::hypot(shetap, cxip);
        let lam = libm::atan2(shetap, cxip);
        let phi = libm::atan(self.tau_from_taup(taup));
        (phi, lam)
    }
}

/// Intermediate results of the forward series.
struct Forward {
    xi: f64,
    eta: f64,
    p: f64,
    q: f64,
    xip: f64,
    etap: f64,
    taup: f64,
}

/// `d` reduced to [0, 360) (`d` finite).
fn wrap_360(d: f64) -> f64 {
    let r = libm::fmod(d, 360.0);
    let r = if r < 0.0 { r + 360.0 } else { r };
    // `r + 360` rounds to exactly 360 for tiny negative `r`.
    if r >= 360.0 {
        0.0
    } else {
        r
    }
}

/// An angle in degrees reduced to [−180, 180).
pub fn wrap_deg(d: f64) -> f64 {
    if (-180.0..180.0).contains(&d) {
        return d;
    }
    let r = wrap_360(d + 180.0) - 180.0;
    if r >= 180.0 {
        r - 360.0
    } else {
        r
    }
}

/// A local metric frame: transverse Mercator on WGS-84 centred on the origin's meridian, scale 1
/// there, false origin at the frame origin. See the [module documentation](self) for the method
/// and its error bounds.
///
/// Coordinates are `(lon, lat)` in degrees (GeoJSON order) on the geographic side and `(x, y)` in
/// metres, `x` east and `y` north (grid north, see [`LocalFrame::convergence_deg`]), on the
/// local side. Only [`LocalFrame::new`] and [`LocalFrame::origin`] put latitude first.
///
/// The `f64` methods ([`LocalFrame::to_local`], [`LocalFrame::to_geo`],
/// [`LocalFrame::heading_to_local`], …) evaluate the maths as they are and return non-finite
/// values for input outside its domain; the checked methods ([`LocalFrame::position`],
/// [`LocalFrame::heading`], [`LocalFrame::pose`], [`LocalFrame::lon_lat`],
/// [`LocalFrame::compass_deg`]) validate their input and give the planner's `f32` types.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LocalFrame {
    lat0_deg: f64,
    lon0_deg: f64,
    /// Northing of the origin in the equator-based projection, metres.
    y0: f64,
    ell: Ellipsoid,
}

impl LocalFrame {
    /// The frame with its origin at latitude `origin_lat_deg`, longitude `origin_lon_deg`
    /// (degrees; note the order: latitude first). The longitude may be any finite value (it is
    /// reduced to [−180, 180)); the latitude must lie in [−90, 90].
    pub fn new(origin_lat_deg: f64, origin_lon_deg: f64) -> Result<Self, GeoError> {
        if !origin_lat_deg.is_finite() || !origin_lon_deg.is_finite() {
            return Err(GeoError::NonFinite);
        }
        if !(-90.0..=90.0).contains(&origin_lat_deg) {
            return Err(GeoError::Latitude);
        }
        Ok(Self::new_valid(origin_lat_deg, origin_lon_deg))
    }

    /// [`LocalFrame::new`] for an origin already known to be finite with the latitude in
    /// [−90, 90] (a loaded network's header).
    pub(crate) fn new_valid(origin_lat_deg: f64, origin_lon_deg: f64) -> Self {
        let ell = Ellipsoid::wgs84();
        let y0 = ell.a_rect * ell.forward(origin_lat_deg.to_radians(), 0.0).xi;
        Self {
            lat0_deg: origin_lat_deg,
            lon0_deg: wrap_deg(origin_lon_deg),
            y0,
            ell,
        }
    }

    /// The origin `(lat, lon)` in degrees: latitude first, the order [`LocalFrame::new`] takes.
    pub fn origin(&self) -> (f64, f64) {
        (self.lat0_deg, self.lon0_deg)
    }

    fn dlam(&self, lon: f64) -> f64 {
        wrap_deg(lon - self.lon0_deg).to_radians()
    }

    /// `(lon, lat)` in degrees to `(x, y)` in metres east and north of the origin:
    /// `x = A·η`, `y = A·ξ − y₀` (Karney 2011 eqs. (7)–(11), (35)).
    ///
    /// Meaningful for points within a few thousand kilometres of the origin's meridian (and
    /// accurate as documented within [`MAX_EAST_WEST_M`]); returns non-finite values for a point
    /// 90° or more of longitude away. [`LocalFrame::position`] is the checked form.
    pub fn to_local(&self, lon: f64, lat: f64) -> (f64, f64) {
        let f = self.ell.forward(lat.to_radians(), self.dlam(lon));
        (self.ell.a_rect * f.eta, self.ell.a_rect * f.xi - self.y0)
    }

    /// `(x, y)` in metres east and north of the origin to `(lon, lat)` in degrees, longitude in
    /// [−180, 180) (Karney 2011 eqs. (11), (36), (19)–(21)). [`LocalFrame::lon_lat`] is the
    /// checked form.
    pub fn to_geo(&self, x: f64, y: f64) -> (f64, f64) {
        let (phi, lam) = self
            .ell
            .reverse((y + self.y0) / self.ell.a_rect, x / self.ell.a_rect);
        (wrap_deg(self.lon0_deg + lam.to_degrees()), phi.to_degrees())
    }

    /// The point scale `k` at `(lon, lat)`: a short length `ds` on the ellipsoid there is `k·ds`
    /// long in the frame (Karney 2011 eq. (28)). 1 on the origin's meridian, about
    /// `1 + x²/(2R²)` at `x` metres east or west of it.
    pub fn scale_factor(&self, lon: f64, lat: f64) -> f64 {
        let phi = lat.to_radians();
        let lam = self.dlam(lon);
        let f = self.ell.forward(phi, lam);
        let tau = libm::tan(phi);
        let s = libm::sin(phi);
        (self.ell.a_rect / WGS84_A)
            * libm::sqrt(1.0 - self.ell.e2 * s * s)
            * libm::hypot(tau, 1.0)
            * libm::hypot(f.p, f.q)
            / libm::hypot(f.taup, libm::cos(lam))
    }

    /// The meridian convergence γ at `(lon, lat)` in degrees: the direction of grid north (+`y`)
    /// measured clockwise from true north (Karney 2011 eq. (29)). Positive east of the origin's
    /// meridian in the northern hemisphere, about `Δλ·sin φ`.
    pub fn convergence_deg(&self, lon: f64, lat: f64) -> f64 {
        let f = self.ell.forward(lat.to_radians(), self.dlam(lon));
        let gamma1 = libm::atan2(
            libm::sin(f.xip) * libm::sinh(f.etap),
            libm::cos(f.xip) * libm::cosh(f.etap),
        );
        (gamma1 + libm::atan2(f.q, f.p)).to_degrees()
    }

    /// A compass heading at `(lon, lat)` (degrees clockwise from true north) as a grid heading
    /// (degrees clockwise from +`y`), `heading − γ` in [0, 360).
    pub fn heading_to_local(&self, lon: f64, lat: f64, heading_deg: f64) -> f64 {
        let h = heading_deg - self.convergence_deg(lon, lat);
        if h.is_finite() {
            wrap_360(h)
        } else {
            h
        }
    }

    /// A grid heading at local `(x, y)` (degrees clockwise from +`y`) as a compass heading
    /// (degrees clockwise from true north), `heading + γ` in [0, 360).
    pub fn heading_to_geo(&self, x: f64, y: f64, grid_heading_deg: f64) -> f64 {
        let (lon, lat) = self.to_geo(x, y);
        let h = grid_heading_deg + self.convergence_deg(lon, lat);
        if h.is_finite() {
            wrap_360(h)
        } else {
            h
        }
    }

    /// Checks a `(lon, lat)` in degrees: finite, latitude in [−90, 90], longitude in
    /// [−180, 180].
    fn check_lon_lat(lon: f64, lat: f64) -> Result<(), GeoError> {
        if !lon.is_finite() || !lat.is_finite() {
            Err(GeoError::NonFinite)
        } else if !(-90.0..=90.0).contains(&lat) {
            Err(GeoError::Latitude)
        } else if !(-180.0..=180.0).contains(&lon) {
            Err(GeoError::Longitude)
        } else {
            Ok(())
        }
    }

    /// Checks a local `(x, y)`: within [`MAX_EAST_WEST_M`] of the origin's meridian, between the
    /// poles, and within the planner's coordinate range.
    fn check_local(&self, x: f64, y: f64) -> Result<(), GeoError> {
        if !x.is_finite() || !y.is_finite() {
            return Err(GeoError::NonFinite);
        }
        let quadrant = self.ell.a_rect * core::f64::consts::FRAC_PI_2;
        if x.abs() <= MAX_EAST_WEST_M
            && (y + self.y0).abs() <= quadrant
            && x.abs() <= MAX_COORDINATE_M as f64
            && y.abs() <= MAX_COORDINATE_M as f64
        {
            Ok(())
        } else {
            Err(GeoError::OutOfFrame)
        }
    }

    /// A longitude and latitude (degrees) as the planner's position: [`LocalFrame::to_local`]
    /// rounded to `f32` (within 2.4 mm of PROJ over ±50 km, see the
    /// [module documentation](self)).
    ///
    /// Refuses a non-finite coordinate ([`GeoError::NonFinite`]), a latitude outside [−90, 90]
    /// ([`GeoError::Latitude`]), a longitude outside [−180, 180] ([`GeoError::Longitude`]) and a
    /// point more than [`MAX_EAST_WEST_M`] east or west of the origin ([`GeoError::OutOfFrame`]).
    pub fn position(&self, lon: f64, lat: f64) -> Result<Vec2, GeoError> {
        Self::check_lon_lat(lon, lat)?;
        if wrap_deg(lon - self.lon0_deg).abs() >= 90.0 {
            return Err(GeoError::OutOfFrame);
        }
        let (x, y) = self.to_local(lon, lat);
        self.check_local(x, y)?;
        Ok(Vec2::new(x as f32, y as f32))
    }

    /// A compass heading (degrees clockwise from true north) at `(lon, lat)` as the planner's
    /// heading (radians counter-clockwise from the frame's `x` axis, in (−π, π]): the grid
    /// heading `compass − γ` ([`LocalFrame::heading_to_local`], γ the meridian convergence of
    /// Karney 2011 eq. (29)) through
    /// [`heading_from_compass_deg`].
    ///
    /// Refuses what [`LocalFrame::position`] refuses, and a heading that is not finite
    /// ([`GeoError::NonFinite`]) or outside [−360, 360] ([`GeoError::Heading`]).
    pub fn heading(&self, lon: f64, lat: f64, compass_deg: f64) -> Result<f32, GeoError> {
        self.position(lon, lat)?;
        Self::check_compass(compass_deg)?;
        Ok(self.planner_heading(lon, lat, compass_deg))
    }

    /// The planner's heading of a checked compass heading at a checked `(lon, lat)`.
    fn planner_heading(&self, lon: f64, lat: f64, compass_deg: f64) -> f32 {
        heading_from_compass_deg(self.heading_to_local(lon, lat, compass_deg) as f32)
    }

    fn check_compass(compass_deg: f64) -> Result<(), GeoError> {
        if !compass_deg.is_finite() {
            Err(GeoError::NonFinite)
        } else if !(-360.0..=360.0).contains(&compass_deg) {
            Err(GeoError::Heading)
        } else {
            Ok(())
        }
    }

    /// The aircraft's pose from its longitude, latitude (degrees) and compass heading (degrees
    /// clockwise from true north): [`LocalFrame::position`] and [`LocalFrame::heading`], with the
    /// same refusals.
    pub fn pose(&self, lon: f64, lat: f64, compass_deg: f64) -> Result<Pose, GeoError> {
        let position = self.position(lon, lat)?;
        Self::check_compass(compass_deg)?;
        Ok(Pose {
            position,
            heading: self.planner_heading(lon, lat, compass_deg),
        })
    }

    /// A planner position as `(lon, lat)` in degrees ([`LocalFrame::to_geo`]), longitude in
    /// [−180, 180).
    ///
    /// Refuses a non-finite position ([`GeoError::NonFinite`]) and one more than
    /// [`MAX_EAST_WEST_M`] east or west of the origin, beyond a pole or outside the planner's
    /// coordinate range ([`GeoError::OutOfFrame`]).
    pub fn lon_lat(&self, p: Vec2) -> Result<(f64, f64), GeoError> {
        let (x, y) = (p.x as f64, p.y as f64);
        self.check_local(x, y)?;
        Ok(self.to_geo(x, y))
    }

    /// A planner heading (radians counter-clockwise from the frame's `x` axis) at the pose's
    /// position as a compass heading (degrees clockwise from true north, in [0, 360)): the grid
    /// heading through [`compass_deg_from_heading`],
    /// plus the meridian convergence γ ([`LocalFrame::heading_to_geo`]).
    ///
    /// Refuses what [`LocalFrame::lon_lat`] refuses, and a non-finite heading
    /// ([`GeoError::NonFinite`]).
    pub fn compass_deg(&self, pose: &Pose) -> Result<f64, GeoError> {
        if !pose.heading.is_finite() {
            return Err(GeoError::NonFinite);
        }
        let (x, y) = (pose.position.x as f64, pose.position.y as f64);
        self.check_local(x, y)?;
        let grid = compass_deg_from_heading(pose.heading) as f64;
        Ok(self.heading_to_geo(x, y, grid))
    }
}
