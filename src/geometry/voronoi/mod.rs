//! The exact Voronoi diagram of threat sites, in fixed memory (for the Judd & McLain threat
//! mode: routes along Voronoi edges stay as far as possible from the two nearest threats).
//!
//! Sites are quantised to an integer grid of [`SITE_QUANTUM_M`] (1/16 m). The Delaunay
//! triangulation of the quantised sites is built incrementally ([`Delaunay`], Bowyer–Watson
//! insertion with ghost triangles) with exact integer predicates (orientation in i64, in-circle
//! in i128), so every combinatorial decision — which triangles a new site conflicts with,
//! whether four sites are cocircular — is exact. Voronoi vertices are the circumcentres of the
//! Delaunay triangles, computed from the integer coordinates in f64 and rounded to f32.
//!
//! [`Delaunay::graph`] turns the diagram into the graph a planner searches ([`VoronoiGraph`]):
//! the Voronoi edges clipped to a mission box ([`Bounds`]), plus the box's border split at every
//! clip point and corner, so that the graph is connected and a route may pass outside all
//! threats.
//!
//! ## Degenerate inputs
//! * a site equal to an earlier one after quantisation: [`VoronoiError::DuplicateSite`], the
//!   structure unchanged;
//! * 0, 1 or 2 sites, or all sites collinear: there is no finite triangle; the sites are kept
//!   sorted along their line and the Voronoi edges are the perpendicular bisectors of
//!   consecutive sites (parallel lines);
//! * four or more cocircular sites: the Delaunay triangles sharing that circumcircle (detected
//!   with an in-circle determinant of exactly zero across their common edges) are one Voronoi
//!   vertex, with no zero-length edge between them;
//! * full capacities: [`VoronoiError::TooManySites`], [`VoronoiError::TooManyTriangles`],
//!   [`VoronoiError::GraphFull`]. A failed call leaves the previous diagram intact.

mod delaunay;
mod exact;
mod graph;

pub use delaunay::{delaunay_work_bound, Delaunay};
pub use graph::{
    graph_edge_bound, graph_vertex_bound, graph_work_bound, Bounds, GraphEdge, VoronoiGraph,
    NO_SITE,
};

use super::Vec2;
use core::fmt;

/// The grid sites are quantised to, metres (1/16 m): coordinates are stored as `i32` multiples
/// of it, which keeps the predicates exact (see the bit-size arguments in the source).
pub const SITE_QUANTUM_M: f32 = 1.0 / 16.0;

/// Grid units per metre (the inverse of [`SITE_QUANTUM_M`]).
const UNITS_PER_M: f32 = 16.0;

/// The largest accepted site coordinate, metres (10⁷ m, the planner's
/// [`MAX_COORDINATE_M`](super::MAX_COORDINATE_M)): `1.6·10⁸ < 2²⁸` grid units.
pub const MAX_SITE_COORDINATE_M: f32 = super::MAX_COORDINATE_M;

/// Why a Voronoi operation refused its input. Every refusal leaves the structure as it was.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum VoronoiError {
    /// A site coordinate is NaN or infinite.
    NonFinite,
    /// A site coordinate is beyond [`MAX_SITE_COORDINATE_M`] in magnitude.
    OutOfRange,
    /// The site quantises to the same grid point as site `existing`; `index` is the index it
    /// would have had.
    DuplicateSite {
        /// The index the refused site would have had.
        index: u32,
        /// The earlier site at the same grid point.
        existing: u32,
    },
    /// The structure already holds `capacity` sites.
    TooManySites {
        /// The site capacity `N`.
        capacity: usize,
    },
    /// The triangle storage cannot hold the triangulation after the insertion.
    TooManyTriangles {
        /// The triangle capacity `T`.
        capacity: usize,
    },
    /// The caller's graph capacity (`VV` vertices or `EE` edges, or more than 65 535 vertices)
    /// is too small; [`graph_vertex_bound`] and [`graph_edge_bound`] always suffice.
    GraphFull,
    /// The bounds are not finite, or `min` is not strictly below `max` on both axes.
    InvalidBounds,
    /// An internal consistency check failed (the insertion cavity was not a simple polygon).
    /// Exact predicates make this unreachable; it is checked so that a defect refuses the
    /// insertion, before anything changes, instead of corrupting the triangulation.
    Inconsistent,
}

impl fmt::Display for VoronoiError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            VoronoiError::NonFinite => f.write_str("a site coordinate is not finite"),
            VoronoiError::OutOfRange => f.write_str("a site coordinate is beyond 1e7 m"),
            VoronoiError::DuplicateSite { index, existing } => {
                write!(f, "site {index} duplicates site {existing}")
            }
            VoronoiError::TooManySites { capacity } => {
                write!(f, "more than {capacity} sites")
            }
            VoronoiError::TooManyTriangles { capacity } => {
                write!(f, "more than {capacity} triangles")
            }
            VoronoiError::GraphFull => f.write_str("the graph's capacity is too small"),
            VoronoiError::InvalidBounds => f.write_str("invalid bounds"),
            VoronoiError::Inconsistent => f.write_str("inconsistent triangulation"),
        }
    }
}

#[cfg(feature = "std")]
impl std::error::Error for VoronoiError {}
