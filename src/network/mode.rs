//! The network's mode: what kind of network an image holds, decoded once from the header, and
//! the mode's own record that the loaded network keeps beside the common sections.
//!
//! Every operation that differs between modes matches on [`Mode`] (or on the loaded section)
//! exactly once; `docs/ADDING_A_MODE.md` lists those places.

use super::format::{
    LandmarkRecord, TerrainRecord, VoronoiRecord, MODE_LANDMARK, MODE_ROADMAP, MODE_TERRAIN,
    MODE_VORONOI,
};
use super::LoadError;

/// The kind of network: the header's `mode` byte as a type. A code this build does not know
/// decodes to [`Mode::Unknown`], which the loader refuses ([`LoadError::UnknownMode`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Mode {
    /// A multi-query Dubins roadmap (Niendorf et al.): [`MODE_ROADMAP`].
    Roadmap,
    /// A landmark shortest-path network of Hermite chains (Babel): [`MODE_LANDMARK`].
    Landmark,
    /// A terrain visibility graph over an elevation table (Medeiros & da Silva):
    /// [`MODE_TERRAIN`].
    Terrain,
    /// A Voronoi graph of radar threats with exposure cost and spline smoothing (Judd &
    /// McLain): [`MODE_VORONOI`].
    Voronoi,
    /// A mode code this build does not know.
    Unknown(u8),
}

impl From<u8> for Mode {
    fn from(code: u8) -> Self {
        match code {
            MODE_ROADMAP => Mode::Roadmap,
            MODE_LANDMARK => Mode::Landmark,
            MODE_TERRAIN => Mode::Terrain,
            MODE_VORONOI => Mode::Voronoi,
            other => Mode::Unknown(other),
        }
    }
}

impl Mode {
    /// The header's code for this mode.
    pub fn code(self) -> u8 {
        match self {
            Mode::Roadmap => MODE_ROADMAP,
            Mode::Landmark => MODE_LANDMARK,
            Mode::Terrain => MODE_TERRAIN,
            Mode::Voronoi => MODE_VORONOI,
            Mode::Unknown(code) => code,
        }
    }

    /// The mode's name as scenarios spell it (`planner.mode`): `roadmap`, `landmark`,
    /// `terrain`, `voronoi`, or `unknown`.
    pub fn name(self) -> &'static str {
        match self {
            Mode::Roadmap => "roadmap",
            Mode::Landmark => "landmark",
            Mode::Terrain => "terrain",
            Mode::Voronoi => "voronoi",
            Mode::Unknown(_) => "unknown",
        }
    }

    /// Decodes the header's code, refusing one this build does not know.
    pub fn decode(code: u8) -> Result<Mode, LoadError> {
        match Mode::from(code) {
            Mode::Unknown(mode) => Err(LoadError::UnknownMode { mode }),
            known => Ok(known),
        }
    }
}

/// What a loaded network keeps of its mode's own section.
#[derive(Clone, Copy, Debug)]
pub(crate) enum ModeSection {
    /// Roadmaps have no section of their own.
    Roadmap,
    /// The terrain record (the elevation grid and coding, and what the network was built for).
    Terrain(TerrainRecord),
    /// The landmark record, and the most pieces of any edge's chain (found by the loader).
    Landmark {
        /// The record.
        record: LandmarkRecord,
        /// The most Hermite pieces of any edge.
        max_chain_pieces: u32,
    },
    /// The Voronoi record (threat sites, weight, curvature limit, box, corner table size).
    Voronoi(VoronoiRecord),
}

impl ModeSection {
    /// The mode this section belongs to.
    pub(crate) fn mode(&self) -> Mode {
        match self {
            ModeSection::Roadmap => Mode::Roadmap,
            ModeSection::Terrain(_) => Mode::Terrain,
            ModeSection::Landmark { .. } => Mode::Landmark,
            ModeSection::Voronoi(_) => Mode::Voronoi,
        }
    }
}
