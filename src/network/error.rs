//! Why a network byte image was rejected.

use core::fmt;

/// A part of the network image, named in [`LoadError`]s.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Section {
    /// The fixed header.
    Header,
    /// The vertex poses.
    Vertices,
    /// The CSR offsets of the edges by source vertex.
    EdgeOffsets,
    /// The edge records.
    Edges,
    /// The obstacle records.
    Obstacles,
    /// The polygon points of the obstacles.
    ObstaclePoints,
    /// The grid index's per-cell offsets.
    CellOffsets,
    /// The grid index's edge lists (delta-coded varints per cell).
    CellEntries,
    /// Terrain mode: the elevation table's grid and coding.
    Terrain,
    /// Landmark mode: the landmark record.
    Landmark,
    /// Landmark mode: the landmarks (position, `d_max`).
    Landmarks,
    /// Landmark mode: the rosette qualities.
    Rosettes,
    /// Landmark mode: the CSR offsets of the chains' line elements by edge.
    ChainOffsets,
    /// Landmark mode: the chains' element index lists.
    ChainIndices,
    /// Landmark mode: the distinct line elements the chains index.
    ChainElements,
    /// Voronoi mode: the Voronoi record.
    Voronoi,
    /// Voronoi mode: the threat sites.
    Threats,
    /// Voronoi mode: the spline corner table.
    CornerTable,
    /// The pop-up alternatives' record.
    PopupAlternatives,
    /// The stored pop-ups.
    StoredPopups,
    /// The stored bypass alternatives.
    StoredAlternatives,
    /// The alternatives' blocking discs.
    BlockingDiscs,
    /// A three-dimensional roadmap's vertical limits.
    Vertical,
    /// A three-dimensional roadmap's vertex altitudes.
    Altitudes,
    /// A three-dimensional roadmap's obstacle heights.
    ObstacleHeights,
}

/// A scalar header parameter, named in [`LoadError::InvalidParameter`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Parameter {
    /// The turn radius must be finite and positive.
    TurnRadius,
    /// The clearance must be finite and not negative.
    Clearance,
    /// The frame origin must be a finite latitude in [−90, 90] and longitude in [−180, 180].
    Origin,
    /// The grid origin must be finite.
    GridOrigin,
    /// The grid cell size must be finite and positive.
    GridCell,
    /// The grid must have at least one cell along each axis.
    GridDimensions,
    /// The flags must be zero but for
    /// [`FLAG_POPUP_ALTERNATIVES`](super::format::FLAG_POPUP_ALTERNATIVES) and, in roadmap
    /// mode, [`FLAG_VERTICAL`](super::format::FLAG_VERTICAL).
    Flags,
    /// A three-dimensional roadmap's vertical limits must be finite and positive.
    Vertical,
    /// The pop-up alternatives' record must store 1 to
    /// [`MAX_STORED_POPUPS`](super::format::MAX_STORED_POPUPS) pop-ups, a nominal route of at
    /// least one step and finite limits of magnitude at most 10⁶.
    PopupAlternatives,
    /// Terrain mode: the elevation grid must be valid (finite origin, positive cell, 1 to 2²⁴
    /// cells per axis), the coding finite with a positive step, the widening, altitude and
    /// safety height finite and not negative where that matters.
    Terrain,
    /// Landmark mode: the landmark record's numbers must be valid: at least one direction and
    /// one weather, a finite positive nominal speed, valid flight limits
    /// ([`FlyLimits::is_valid`](crate::geometry::hermite::FlyLimits::is_valid)) and a finite,
    /// non-negative start range.
    Landmark,
    /// Voronoi mode: the Voronoi record's numbers must be valid: a weight in [0, 1], a finite
    /// positive curvature limit, a finite box of positive size, the corner table's dimensions
    /// those of this build, every table value finite and non-negative (0 for a straight
    /// corner) and none below the curvature of its piece at the piece's midpoint, and no
    /// static circles (a threat is a site, not a disc).
    Voronoi,
}

/// Why [`Network::from_bytes`](super::Network::from_bytes) rejected an image. Every variant
/// carries the numbers that locate the problem.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum LoadError {
    /// The image ends before the header or the body it declares.
    Truncated {
        /// Bytes the header and body need.
        needed: usize,
        /// Bytes present.
        available: usize,
    },
    /// The image continues past the body the header declares.
    TrailingBytes {
        /// Bytes after the body.
        extra: usize,
    },
    /// The image does not start with `SKYR`.
    BadMagic {
        /// The first four bytes found.
        found: [u8; 4],
    },
    /// A format version this build does not read.
    UnsupportedVersion {
        /// The version in the header.
        found: u16,
        /// The version this build reads.
        supported: u16,
    },
    /// A network mode this build does not know.
    UnknownMode {
        /// The mode code in the header.
        mode: u8,
    },
    /// More vertices than the planner has room for.
    TooManyVertices {
        /// Vertices in the network.
        count: u32,
        /// The planner's capacity.
        capacity: usize,
    },
    /// More edges than the planner has room for.
    TooManyEdges {
        /// Edges in the network.
        count: u32,
        /// The planner's capacity.
        capacity: usize,
    },
    /// The counts describe a body larger than any address space this runs in.
    CountsTooLarge,
    /// The body length in the header disagrees with the one its counts imply.
    BodyLengthMismatch {
        /// Body length in the header.
        declared: u32,
        /// Body length the counts imply.
        expected: usize,
    },
    /// The body's CRC-32 does not match the header's.
    ChecksumMismatch {
        /// CRC in the header.
        stored: u32,
        /// CRC of the body as found.
        computed: u32,
    },
    /// A header parameter is out of its domain.
    InvalidParameter {
        /// Which one.
        parameter: Parameter,
    },
    /// A record could not be decoded.
    Malformed {
        /// Where.
        section: Section,
        /// Record index.
        index: u32,
    },
    /// A value is NaN or infinite.
    NonFinite {
        /// Where.
        section: Section,
        /// Record index.
        index: u32,
    },
    /// Offsets are not non-decreasing from 0 to the count they index.
    BadOffsets {
        /// Which offset table.
        section: Section,
        /// The first offending entry.
        index: u32,
    },
    /// A stored pop-up, bypass alternative or blocking disc is out of its domain (a disc not
    /// finite, out of range or of no positive radius; a probability outside [0, 1]; a count
    /// beyond the format's maxima; no steps, a negative or non-finite fuel factor or length),
    /// or the tables' counts do not add up to the record's totals (`section`
    /// [`Section::PopupAlternatives`], index 0).
    BadPopupAlternatives {
        /// Which table.
        section: Section,
        /// Record index.
        index: u32,
    },
    /// An index points past the end of what it indexes.
    IndexOutOfRange {
        /// Where.
        section: Section,
        /// Record index.
        index: u32,
        /// The stored index.
        value: u32,
        /// The number of items it may point into.
        limit: u32,
    },
    /// A grid cell's edge list does not decode: a varint runs past the cell's bytes or is
    /// longer than five bytes.
    BadCellList {
        /// Cell index, `y · nx + x`.
        cell: u32,
    },
    /// A roadmap edge's Dubins word cannot join its source's pose to its target's.
    WordCannotJoin {
        /// Edge index.
        edge: u32,
        /// The word's code.
        word: u8,
    },
    /// An edge has a negative cost.
    NegativeValue {
        /// Edge index.
        edge: u32,
    },
    /// An edge has a geometry kind this build does not know.
    UnknownGeometry {
        /// Edge index.
        edge: u32,
        /// The kind code.
        code: u8,
    },
    /// Flying an edge's geometry from its source does not end at its target's pose.
    EdgeMissesTarget {
        /// Edge index.
        edge: u32,
        /// How far from the target it ends, millimetres (saturating; a heading mismatch alone
        /// may show a small or zero distance).
        miss_mm: u32,
    },
    /// An edge costs less than the length of its geometry.
    CostBelowLength {
        /// Edge index.
        edge: u32,
    },
    /// A three-dimensional roadmap: a vertex altitude that is not finite or beyond
    /// [`MAX_ALTITUDE_M`](super::format::MAX_ALTITUDE_M), or an obstacle height that is NaN
    /// or not positive.
    BadAltitude {
        /// [`Section::Altitudes`] or [`Section::ObstacleHeights`].
        section: Section,
        /// Vertex or obstacle index.
        index: u32,
    },
    /// A three-dimensional roadmap: an edge's altitude change is more than a rest-to-rest move
    /// within the vertical limits makes over its length.
    EdgeTooSteep {
        /// Edge index.
        edge: u32,
    },
    /// An obstacle is neither a polygon of at least 3 points nor a circle of positive radius.
    BadObstacle {
        /// Obstacle index.
        obstacle: u32,
    },
    /// The grid index does not cover the area that the edges can reach (every vertex's
    /// surroundings within four turn radii), so pop-up pruning could miss edges.
    GridTooSmall {
        /// A vertex outside the covered area.
        vertex: u32,
    },
    /// Terrain mode: the planner's search-state capacity `V` is below the network's directed
    /// edges plus [`MAX_LINKS`](crate::planner::MAX_LINKS) start links (checked by
    /// [`Planner::load`](crate::planner::Planner::load)).
    TooManySearchStates {
        /// States needed.
        needed: usize,
        /// The capacity `V`.
        capacity: usize,
    },
    /// Voronoi mode: a threat site is not finite, lies outside the network's box, or has a
    /// radius that is not finite and positive.
    BadThreat {
        /// Threat index.
        threat: u32,
    },
    /// Voronoi mode: more threat sites than the planner holds
    /// ([`MAX_THREATS`](crate::planner::MAX_THREATS)), or two at the same position (checked by
    /// [`Planner::load`](crate::planner::Planner::load), which builds their diagram).
    ThreatSitesRefused {
        /// Threat sites in the network.
        threats: u32,
        /// The first site the onboard diagram refused.
        refused: u32,
    },
    /// Voronoi mode: [`Planner::load`](crate::planner::Planner::load) was given a Voronoi
    /// network, whose state needs storage from the caller: use
    /// [`Planner::load_voronoi`](crate::planner::Planner::load_voronoi).
    NeedsVoronoiStorage,
    /// [`Planner::load_voronoi`](crate::planner::Planner::load_voronoi) was given a network of
    /// another mode: use [`Planner::load`](crate::planner::Planner::load).
    NotVoronoi {
        /// The network's mode code.
        mode: u8,
    },
    /// Voronoi mode: the Voronoi graph stored in the image is not the one the planner builds
    /// onboard from the same threat sites (checked by
    /// [`Planner::load`](crate::planner::Planner::load)).
    VoronoiMismatch {
        /// Vertices and edges stored.
        stored: (u32, u32),
        /// Vertices and undirected edges built onboard.
        built: (u32, u32),
    },
    /// Terrain mode: a line edge's band (its cells within the widening) reaches outside the
    /// elevation grid.
    EdgeOutsideTerrain {
        /// Edge index.
        edge: u32,
    },
    /// Terrain mode: a line edge's stored highest elevation code is below the highest code
    /// among the cells its band touches (recomputed at load), so altitude pruning could keep
    /// it over higher terrain.
    EdgeElevationUnderstated {
        /// Edge index.
        edge: u32,
        /// The stored code.
        stored: u8,
        /// The highest code found.
        computed: u8,
    },
    /// Landmark mode: the vertex count is not `landmarks · directions` plus one per endpoint
    /// (start, goal) the landmark record names.
    LandmarkVertexCount {
        /// Vertices in the header.
        vertices: u32,
        /// Vertices the landmark record implies (saturating).
        expected: u32,
    },
    /// Landmark mode: the start or goal vertex is not where the layout puts it (the start at
    /// `L·D`, the goal after it).
    EndpointVertexMismatch {
        /// The stored index.
        stored: u32,
        /// The index the layout implies.
        expected: u32,
    },
    /// Landmark mode: an overflight vertex does not lie at its landmark's position.
    VertexOffLandmark {
        /// Vertex index.
        vertex: u32,
    },
    /// Landmark mode: a rosette quality is outside `[0, 1]` (or NaN).
    QualityOutOfRange {
        /// Index into the rosette table.
        index: u32,
    },
    /// Landmark mode: a line element's speed differs from the nominal speed by more than 10⁻³
    /// of it.
    ElementSpeed {
        /// Element index.
        element: u32,
        /// Its speed, mm/s (saturating).
        speed_mm_s: u32,
    },
    /// Landmark mode: an edge's chain has fewer than two line elements.
    ChainTooShort {
        /// Edge index.
        edge: u32,
        /// Its elements.
        elements: u32,
    },
    /// Landmark mode: two consecutive line elements of a chain lie at the same position (no
    /// Hermite piece joins them).
    CoincidentElements {
        /// Edge index.
        edge: u32,
        /// The second element's index.
        element: u32,
    },
    /// Landmark mode: a chain's first element is not its source vertex's line element, or its
    /// last not its target's (position within 10⁻⁴ of the coordinate size plus 1 cm,
    /// velocity direction within 10⁻³ rad).
    ChainMissesVertex {
        /// Edge index.
        edge: u32,
        /// The vertex it should start or end at.
        vertex: u32,
        /// Distance from the vertex, millimetres (saturating; a heading mismatch alone may
        /// show a small or zero distance).
        miss_mm: u32,
    },
    /// Landmark mode: a chain's stored length is shorter than the polyline through its line
    /// elements (no curve through them can be that short).
    ChainShorterThanChords {
        /// Edge index.
        edge: u32,
    },
    /// Landmark mode: the grid index does not cover an edge's reach (the box of half-side
    /// `length/2` around the midpoint of its ends, which holds every curve of that length
    /// between them), so pop-up pruning could miss it.
    EdgeOutsideGrid {
        /// Edge index.
        edge: u32,
    },
}

impl fmt::Display for LoadError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        use LoadError::*;
        match *self {
            Truncated { needed, available } => {
                write!(
                    f,
                    "network truncated: needs {needed} bytes, {available} present"
                )
            }
            TrailingBytes { extra } => write!(f, "{extra} unexpected bytes after the network body"),
            BadMagic { found } => write!(f, "not a skyroute network (magic {found:02x?})"),
            UnsupportedVersion { found, supported } => {
                write!(
                    f,
                    "network format version {found}, this build reads {supported}"
                )?;
                if found < supported {
                    // Older images may carry checksums that leave the header uncovered and
                    // record nothing of their scenario.
                    write!(f, "; rebuild the network with this version's ground tool")?;
                }
                Ok(())
            }
            UnknownMode { mode } => write!(f, "unknown network mode {mode}"),
            TooManyVertices { count, capacity } => {
                write!(
                    f,
                    "{count} vertices exceed the planner's capacity of {capacity}"
                )
            }
            TooManyEdges { count, capacity } => {
                write!(
                    f,
                    "{count} edges exceed the planner's capacity of {capacity}"
                )
            }
            CountsTooLarge => write!(f, "the header's counts overflow the address space"),
            BodyLengthMismatch { declared, expected } => {
                write!(
                    f,
                    "header declares a {declared}-byte body, its counts imply {expected}"
                )
            }
            ChecksumMismatch { stored, computed } => {
                write!(
                    f,
                    "body CRC-32 {computed:#010x} does not match the header's {stored:#010x}"
                )
            }
            InvalidParameter { parameter } => write!(f, "invalid header parameter {parameter:?}"),
            Malformed { section, index } => write!(f, "{section:?} record {index} is malformed"),
            NonFinite { section, index } => {
                write!(
                    f,
                    "{section:?} record {index} holds a NaN or infinite value"
                )
            }
            BadPopupAlternatives { section, index } => {
                write!(f, "{section:?} record {index} is out of its domain")
            }
            BadOffsets { section, index } => {
                write!(f, "{section:?} offset {index} is out of order")
            }
            IndexOutOfRange {
                section,
                index,
                value,
                limit,
            } => {
                write!(
                    f,
                    "{section:?} record {index} points at {value}, past the limit {limit}"
                )
            }
            BadCellList { cell } => write!(f, "grid cell {cell}'s edge list does not decode"),
            WordCannotJoin { edge, word } => {
                write!(
                    f,
                    "edge {edge}'s Dubins word {word} cannot join its two poses"
                )
            }
            NegativeValue { edge } => write!(f, "edge {edge} has a negative cost"),
            UnknownGeometry { edge, code } => write!(f, "edge {edge} has unknown geometry {code}"),
            EdgeMissesTarget { edge, miss_mm } => {
                write!(
                    f,
                    "edge {edge} ends {miss_mm} mm (or a heading) away from its target"
                )
            }
            CostBelowLength { edge } => write!(f, "edge {edge} costs less than its length"),
            BadAltitude { section, index } => {
                write!(
                    f,
                    "{section:?} record {index} is not a valid altitude or height"
                )
            }
            EdgeTooSteep { edge } => write!(
                f,
                "edge {edge} climbs or descends more than the vertical limits allow over its length"
            ),
            BadObstacle { obstacle } => write!(f, "obstacle {obstacle} is malformed"),
            GridTooSmall { vertex } => {
                write!(f, "grid index does not cover the reach of vertex {vertex}")
            }
            TooManySearchStates { needed, capacity } => write!(
                f,
                "terrain search needs {needed} states (edges + start links), capacity is {capacity}"
            ),
            EdgeOutsideTerrain { .. }
            | BadThreat { .. }
            | ThreatSitesRefused { .. }
            | VoronoiMismatch { .. }
            | NeedsVoronoiStorage
            | NotVoronoi { .. }
            | EdgeElevationUnderstated { .. }
            | LandmarkVertexCount { .. }
            | EndpointVertexMismatch { .. }
            | VertexOffLandmark { .. }
            | QualityOutOfRange { .. }
            | ElementSpeed { .. }
            | ChainTooShort { .. }
            | CoincidentElements { .. }
            | ChainMissesVertex { .. }
            | ChainShorterThanChords { .. }
            | EdgeOutsideGrid { .. } => self.fmt_mode_section(f),
        }
    }
}

impl LoadError {
    /// The messages of the terrain, landmark and Voronoi sections' errors.
    fn fmt_mode_section(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        use LoadError::*;
        match *self {
            EdgeOutsideTerrain { edge } => {
                write!(f, "edge {edge} reaches outside the elevation grid")
            }
            EdgeElevationUnderstated {
                edge,
                stored,
                computed,
            } => write!(
                f,
                "edge {edge} stores highest elevation code {stored}, but its cells reach {computed}"
            ),
            LandmarkVertexCount { vertices, expected } => write!(
                f,
                "{vertices} vertices, the landmark record implies {expected}"
            ),
            EndpointVertexMismatch { stored, expected } => write!(
                f,
                "endpoint vertex {stored} should be {expected} (after the overflights)"
            ),
            VertexOffLandmark { vertex } => {
                write!(f, "overflight vertex {vertex} is not at its landmark")
            }
            QualityOutOfRange { index } => {
                write!(f, "rosette quality {index} is outside [0, 1]")
            }
            ElementSpeed {
                element,
                speed_mm_s,
            } => write!(
                f,
                "line element {element} flies {speed_mm_s} mm/s, not the nominal speed"
            ),
            ChainTooShort { edge, elements } => write!(
                f,
                "edge {edge} has a chain of {elements} line elements (needs at least 2)"
            ),
            CoincidentElements { edge, element } => write!(
                f,
                "edge {edge}: line element {element} lies on the one before it"
            ),
            ChainMissesVertex {
                edge,
                vertex,
                miss_mm,
            } => write!(
                f,
                "edge {edge}: its chain misses vertex {vertex} by {miss_mm} mm (or a heading)"
            ),
            ChainShorterThanChords { edge } => write!(
                f,
                "edge {edge} is shorter than the polyline through its line elements"
            ),
            EdgeOutsideGrid { edge } => {
                write!(f, "grid index does not cover the reach of edge {edge}")
            }
            BadThreat { threat } => write!(
                f,
                "threat {threat} is not finite, lies outside the box or has no positive radius"
            ),
            ThreatSitesRefused { threats, refused } => write!(
                f,
                "the onboard Voronoi diagram refuses threat {refused} of {threats} (too many, \
                 or at the position of another)"
            ),
            NeedsVoronoiStorage => write!(
                f,
                "a Voronoi network needs the planner's Voronoi storage (Planner::load_voronoi)"
            ),
            NotVoronoi { mode } => write!(
                f,
                "the network (mode {mode}) is not a Voronoi network: load it with Planner::load"
            ),
            VoronoiMismatch { stored, built } => write!(
                f,
                "the stored Voronoi graph ({} vertices, {} edges) is not the one built onboard \
                 ({} vertices, {} edges)",
                stored.0, stored.1, built.0, built.1
            ),
            // The other variants are written by `Display::fmt`, which sends only these here.
            _ => Ok(()),
        }
    }
}

#[cfg(feature = "std")]
impl std::error::Error for LoadError {}
