//! The elevation table of a terrain network: one byte per grid cell, an upper bound of the
//! cell's terrain elevation.
//!
//! A code `k < 255` stands for "the highest terrain in this cell is at most
//! `base + k · step` metres"; [`ELEVATION_BLOCKED`] (255) for "unknown or outside the DEM:
//! never fly over it". The ground tool encodes each cell's highest DEM elevation with
//! [`ElevationCoding::encode`], which rounds **up**, so decoding never lowers the terrain:
//! the quantisation can only make a cell look higher (by less than one `step`), never lower.
//!
//! At flight altitude `a_n` with safety height `a_s` a cell is not navigable when its elevation
//! is at least `a_n − a_s` (Medeiros & da Silva). With upper bounds increasing in the code,
//! that is the same as `code ≥ c*`, where `c*` = [`ElevationCoding::blocking_code`] is the
//! smallest code whose bound reaches `a_n − a_s`. So an altitude change costs one such
//! computation, and every cell or edge test afterwards is an integer comparison with the
//! stored codes: the planner re-derives navigability from the stored elevations without a
//! pass over the table.

/// The code of a cell that is never navigable (NODATA, or reaching outside the DEM).
pub const ELEVATION_BLOCKED: u8 = 255;

/// How elevation codes map to metres: `base + code · step`.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ElevationCoding {
    /// Elevation of code 0, metres.
    pub base_m: f32,
    /// Metres per code step (> 0).
    pub step_m: f32,
}

impl ElevationCoding {
    /// Whether both numbers are finite and the step positive, and the top code's bound is
    /// finite.
    pub fn is_valid(&self) -> bool {
        self.base_m.is_finite()
            && self.step_m.is_finite()
            && self.step_m > 0.0
            && self.upper_bound(ELEVATION_BLOCKED - 1).is_finite()
    }

    /// The elevation bound that `code` stands for, metres (`+∞` for [`ELEVATION_BLOCKED`]).
    pub fn upper_bound(&self, code: u8) -> f32 {
        if code == ELEVATION_BLOCKED {
            f32::INFINITY
        } else {
            self.base_m + code as f32 * self.step_m
        }
    }

    /// The smallest code whose bound is at least `elevation_m` (rounding up, so the bound never
    /// undercuts the elevation); [`ELEVATION_BLOCKED`] when no code below 255 reaches it or the
    /// elevation is NaN.
    pub fn encode(&self, elevation_m: f32) -> u8 {
        if elevation_m.is_nan() || !self.is_valid() {
            return ELEVATION_BLOCKED;
        }
        self.smallest_code_reaching(elevation_m)
    }

    /// The smallest code `c*` such that a cell with `code ≥ c*` is not navigable at
    /// `altitude_m` with `safety_height_m`, i.e. whose bound is at least `altitude_m −
    /// safety_height_m` (computed in `f32`); [`ELEVATION_BLOCKED`] when only unknown cells are
    /// blocked. NaN inputs give 0: everything blocked (fail safe).
    pub fn blocking_code(&self, altitude_m: f32, safety_height_m: f32) -> u8 {
        let threshold = altitude_m - safety_height_m;
        if threshold.is_nan() || !self.is_valid() {
            return 0;
        }
        self.smallest_code_reaching(threshold)
    }

    /// The smallest code in `0..=255` whose bound is `≥ x`, for `x` not NaN (255's bound is
    /// `+∞`, so one always qualifies). The bounds `base + code · step` do not decrease with the
    /// code (`step > 0`, and f32 rounding is monotone), so a binary search over the 256 codes
    /// finds it in 8 steps.
    fn smallest_code_reaching(&self, x: f32) -> u8 {
        let (mut low, mut high) = (0u8, ELEVATION_BLOCKED);
        while low < high {
            let mid = low + (high - low) / 2;
            if self.upper_bound(mid) >= x {
                high = mid;
            } else {
                low = mid + 1;
            }
        }
        low
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn encoding_rounds_up_and_blocking_matches_the_rule() {
        let c = ElevationCoding {
            base_m: 236.0,
            step_m: 3.31,
        };
        for i in 0..200_000 {
            let e = 236.0 + i as f32 * 0.0042;
            let k = c.encode(e);
            assert!(c.upper_bound(k) >= e);
            assert!(k == 0 || c.upper_bound(k - 1) < e);
        }
        for t in [0.0f32, 236.0, 500.0, 650.0, 1076.0, 1200.0, 5000.0] {
            let b = c.blocking_code(t + 100.0, 100.0);
            for k in 0..=255u8 {
                assert_eq!(k >= b, c.upper_bound(k) >= t, "threshold {t}, code {k}");
            }
        }
        assert_eq!(c.encode(f32::NAN), ELEVATION_BLOCKED);
        assert_eq!(c.blocking_code(f32::NAN, 1.0), 0);
    }
}
