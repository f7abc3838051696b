//! The status every call returns: success, a misuse of the C API, or the core's error, one
//! code per variant of `LoadError`, `PlanError` and `PopupError` (the matches below are
//! exhaustive, so a variant added to the core fails this crate's build until it has a code).

use core::ffi::{c_char, CStr};
use skyroute::planner::{PlanError, PopupError};
use skyroute::LoadError;

/// What a call did: `SR_STATUS_OK` (0), a misuse of the API (1–99), or why the core refused:
/// loading 100–199, planning 200–299, pop-ups 300–399, latitude and longitude 400–499. The
/// numbers are fixed; the numbers the core's errors carry (counts, indices) are not reported
/// through the C API.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(i32)]
pub enum SrStatus {
    /// Success.
    Ok = 0,
    /// A pointer argument that must not be NULL was NULL.
    NullPointer = 1,
    /// `sr_planner_init`: the memory is not aligned to `sr_planner_align()`.
    MemoryMisaligned = 2,
    /// `sr_planner_init`: the memory is smaller than `sr_planner_size()`.
    MemoryTooSmall = 3,
    /// An argument is out of its domain (an unknown search kind, a polygon of more than
    /// `SR_MAX_POPUP_VERTICES` vertices).
    InvalidArgument = 4,
    /// The caller's array holds fewer primitives than the route has: the first ones were written,
    /// and the count says how many the route has.
    BufferTooSmall = 5,
    /// The call needs a network and none has been loaded (`sr_load`).
    NoNetwork = 6,
    /// `LoadError::Truncated`: The image ends before the header or the body it declares.
    LoadTruncated = 100,
    /// `LoadError::TrailingBytes`: The image continues past the body the header declares.
    LoadTrailingBytes = 101,
    /// `LoadError::BadMagic`: The image does not start with `SKYR`.
    LoadBadMagic = 102,
    /// `LoadError::UnsupportedVersion`: A format version this build does not read.
    LoadUnsupportedVersion = 103,
    /// `LoadError::UnknownMode`: A network mode this build does not know.
    LoadUnknownMode = 104,
    /// `LoadError::TooManyVertices`: More vertices than the planner has room for.
    LoadTooManyVertices = 105,
    /// `LoadError::TooManyEdges`: More edges than the planner has room for.
    LoadTooManyEdges = 106,
    /// `LoadError::CountsTooLarge`: The counts describe a body larger than any address space this
    /// runs in.
    LoadCountsTooLarge = 107,
    /// `LoadError::BodyLengthMismatch`: The body length in the header disagrees with the one its
    /// counts imply.
    LoadBodyLengthMismatch = 108,
    /// `LoadError::ChecksumMismatch`: The body's CRC-32 does not match the header's.
    LoadChecksumMismatch = 109,
    /// `LoadError::InvalidParameter`: A header parameter is out of its domain.
    LoadInvalidParameter = 110,
    /// `LoadError::Malformed`: A record could not be decoded.
    LoadMalformed = 111,
    /// `LoadError::NonFinite`: A value is NaN or infinite.
    LoadNonFinite = 112,
    /// `LoadError::BadOffsets`: Offsets are not non-decreasing from 0 to the count they index.
    LoadBadOffsets = 113,
    /// `LoadError::IndexOutOfRange`: An index points past the end of what it indexes.
    LoadIndexOutOfRange = 114,
    /// `LoadError::BadCellList`: A grid cell's edge list does not decode: a varint runs past the
    /// cell's bytes or is longer than five bytes.
    LoadBadCellList = 115,
    /// `LoadError::WordCannotJoin`: A roadmap edge's Dubins word cannot join its source's pose to
    /// its target's.
    LoadWordCannotJoin = 116,
    /// `LoadError::NegativeValue`: An edge has a negative cost.
    LoadNegativeValue = 117,
    /// `LoadError::UnknownGeometry`: An edge has a geometry kind this build does not know.
    LoadUnknownGeometry = 118,
    /// `LoadError::EdgeMissesTarget`: Flying an edge's geometry from its source does not end at its
    /// target's pose.
    LoadEdgeMissesTarget = 119,
    /// `LoadError::CostBelowLength`: An edge costs less than the length of its geometry.
    LoadCostBelowLength = 120,
    /// `LoadError::BadObstacle`: An obstacle is neither a polygon of at least 3 points nor a circle
    /// of positive radius.
    LoadBadObstacle = 121,
    /// `LoadError::GridTooSmall`: The grid index does not cover the area that the edges can reach
    /// (every vertex's surroundings within four turn radii), so pop-up pruning could miss edges.
    LoadGridTooSmall = 122,
    /// `LoadError::TooManySearchStates`: Terrain mode: the planner's search-state capacity `V` is
    /// below the network's directed edges plus `MAX_LINKS` start links (checked by
    /// `Planner::load`).
    LoadTooManySearchStates = 123,
    /// `LoadError::BadThreat`: Voronoi mode: a threat site is not finite, lies outside the
    /// network's box, or has a radius that is not finite and positive.
    LoadBadThreat = 124,
    /// `LoadError::ThreatSitesRefused`: Voronoi mode: more threat sites than the planner holds
    /// (`MAX_THREATS`), or two at the same position (checked by `Planner::load`, which builds their
    /// diagram).
    LoadThreatSitesRefused = 125,
    /// `LoadError::NeedsVoronoiStorage`: Voronoi mode: `Planner::load` was given a Voronoi network,
    /// whose state needs storage from the caller: use `Planner::load_voronoi`.
    LoadNeedsVoronoiStorage = 126,
    /// `LoadError::NotVoronoi`: `Planner::load_voronoi` was given a network of another mode: use
    /// `Planner::load`.
    LoadNotVoronoi = 127,
    /// `LoadError::VoronoiMismatch`: Voronoi mode: the Voronoi graph stored in the image is not the
    /// one the planner builds onboard from the same threat sites (checked by `Planner::load`).
    LoadVoronoiMismatch = 128,
    /// `LoadError::EdgeOutsideTerrain`: Terrain mode: a line edge's band (its cells within the
    /// widening) reaches outside the elevation grid.
    LoadEdgeOutsideTerrain = 129,
    /// `LoadError::EdgeElevationUnderstated`: Terrain mode: a line edge's stored highest elevation
    /// code is below the highest code among the cells its band touches (recomputed at load), so
    /// altitude pruning could keep it over higher terrain.
    LoadEdgeElevationUnderstated = 130,
    /// `LoadError::LandmarkVertexCount`: Landmark mode: the vertex count is not `landmarks ·
    /// directions` plus one per endpoint (start, goal) the landmark record names.
    LoadLandmarkVertexCount = 131,
    /// `LoadError::EndpointVertexMismatch`: Landmark mode: the start or goal vertex is not where
    /// the layout puts it (the start at `L·D`, the goal after it).
    LoadEndpointVertexMismatch = 132,
    /// `LoadError::VertexOffLandmark`: Landmark mode: an overflight vertex does not lie at its
    /// landmark's position.
    LoadVertexOffLandmark = 133,
    /// `LoadError::QualityOutOfRange`: Landmark mode: a rosette quality is outside `[0, 1]` (or
    /// NaN).
    LoadQualityOutOfRange = 134,
    /// `LoadError::ElementSpeed`: Landmark mode: a line element's speed differs from the nominal
    /// speed by more than 10⁻³ of it.
    LoadElementSpeed = 135,
    /// `LoadError::ChainTooShort`: Landmark mode: an edge's chain has fewer than two line elements.
    LoadChainTooShort = 136,
    /// `LoadError::CoincidentElements`: Landmark mode: two consecutive line elements of a chain lie
    /// at the same position (no Hermite piece joins them).
    LoadCoincidentElements = 137,
    /// `LoadError::ChainMissesVertex`: Landmark mode: a chain's first element is not its source
    /// vertex's line element, or its last not its target's (position within 10⁻⁴ of the coordinate
    /// size plus 1 cm, velocity direction within 10⁻³ rad).
    LoadChainMissesVertex = 138,
    /// `LoadError::ChainShorterThanChords`: Landmark mode: a chain's stored length is shorter than
    /// the polyline through its line elements (no curve through them can be that short).
    LoadChainShorterThanChords = 139,
    /// `LoadError::EdgeOutsideGrid`: Landmark mode: the grid index does not cover an edge's reach
    /// (the box of half-side `length/2` around the midpoint of its ends, which holds every curve of
    /// that length between them), so pop-up pruning could miss it.
    LoadEdgeOutsideGrid = 140,
    /// `LoadError::BadPopupAlternatives`: a stored pop-up, bypass alternative or blocking disc is
    /// out of its domain, or the alternatives tables' counts do not add up to their record's.
    LoadBadPopupAlternatives = 141,
    /// `LoadError::BadAltitude`: a three-dimensional roadmap's vertex altitude is not finite or
    /// beyond 100 km, or an obstacle height is NaN or not positive.
    LoadBadAltitude = 142,
    /// `LoadError::EdgeTooSteep`: a three-dimensional roadmap's edge climbs or descends more
    /// than the vertical limits allow over its length.
    LoadEdgeTooSteep = 143,
    /// `PlanError::NonFinite`: A position or heading is NaN or infinite.
    PlanNonFinite = 200,
    /// `PlanError::OutOfRange`: A position lies beyond `MAX_COORDINATE_M` of the network's origin.
    PlanOutOfRange = 201,
    /// `PlanError::InsideObstacle`: The start or goal lies inside a static obstacle.
    PlanInsideObstacle = 202,
    /// `PlanError::InsidePopup`: The start or goal lies inside an active pop-up.
    PlanInsidePopup = 203,
    /// `PlanError::StartUnconnected`: No collision-free connection from the start to a nearby
    /// vertex (or to the goal); in landmark mode, no flyable clear piece within the range left to
    /// an overflight.
    PlanStartUnconnected = 204,
    /// `PlanError::GoalUnconnected`: No collision-free connection from a nearby vertex to the goal;
    /// in landmark mode, no flyable clear piece from an overflight within its range.
    PlanGoalUnconnected = 205,
    /// `PlanError::NoRoute`: The search exhausted the reachable network without reaching the goal.
    PlanNoRoute = 206,
    /// `PlanError::BudgetExhausted`: The work budget ran out before the query finished.
    PlanBudgetExhausted = 207,
    /// `PlanError::RouteTooLong`: The route has more primitives than the planner's route capacity.
    PlanRouteTooLong = 208,
    /// `PlanError::OverBlockedTerrain`: Terrain mode: the start or goal lies over a cell that is
    /// blocked at the altitude in force (or unknown, or outside the elevation grid).
    PlanOverBlockedTerrain = 209,
    /// `PlanError::InvalidAltitude`: `Planner::set_altitude` got a non-finite altitude or a
    /// negative or non-finite safety height.
    PlanInvalidAltitude = 210,
    /// `PlanError::NotLandmarkNetwork`: Landmark mode only: the operation needs a landmark network.
    PlanNotLandmarkNetwork = 211,
    /// `PlanError::NotTerrainNetwork`: Terrain mode only: the operation needs a terrain network.
    PlanNotTerrainNetwork = 212,
    /// `PlanError::UnknownWeather`: Landmark mode: the weather index is not below the network's
    /// weather count.
    PlanUnknownWeather = 213,
    /// `PlanError::UnknownLandmark`: Landmark mode: the landmark index is not below the network's
    /// landmark count.
    PlanUnknownLandmark = 214,
    /// `PlanError::InvalidRosette`: Landmark mode: a rosette update does not have one quality in
    /// `[0, 1]` per direction (or the network has more than `MAX_ROSETTE_DIRECTIONS` directions).
    PlanInvalidRosette = 215,
    /// `PlanError::RosetteTableFull`: Landmark mode: all `MAX_ROSETTE_OVERRIDES` rosette overrides
    /// are in use (by other landmarks).
    PlanRosetteTableFull = 216,
    /// `PlanError::Smoothing`: Voronoi mode: the coarse route found cannot be smoothed within the
    /// curvature limit while staying clear of no-fly zones and pop-ups, at this corner of the
    /// coarse route (1 the first vertex after the start; 0 the start's lead-in).
    PlanSmoothing = 219,
    /// `PlanError::TooManySearchStates`: Terrain mode: the query's search states (under the paper's
    /// `TurnRule`, one per transition of the graph) exceed the planner's state capacity `V`.
    PlanTooManySearchStates = 220,
    /// `PlanError::Internal`: An internal invariant failed (a bug; reported instead of panicking).
    PlanInternal = 221,
    /// `PlanError::InvalidRange`: Landmark mode: `Planner::set_start_range` got a negative or
    /// non-finite range.
    PlanInvalidRange = 222,
    /// `PlanError::NotDubinsRoute`: Post-processing (`Planner::shortcut` and the passes beside it)
    /// applies to roadmap and terrain routes, chains of Dubins paths; a landmark route (Hermite
    /// pieces) or a Voronoi route (a smoothed spline) is left as it is.
    PlanNotDubinsRoute = 223,
    /// `PlanError::NotThreeDimensional`: the operation needs a three-dimensional roadmap.
    PlanNotThreeDimensional = 224,
    /// `PlanError::AltitudesNeeded`: a three-dimensional roadmap's query needs the start's and
    /// goal's altitudes (`Planner::set_query_altitudes`).
    PlanAltitudesNeeded = 225,
    /// `PopupError::NoFreeSlot`: All `P` pop-up slots are in use.
    PopupNoFreeSlot = 300,
    /// `PopupError::NonFinite`: A coordinate or radius is NaN or infinite.
    PopupNonFinite = 301,
    /// `PopupError::NonPositiveRadius`: A circle's radius is not positive.
    PopupNonPositiveRadius = 302,
    /// `PopupError::OutOfRange`: A coordinate or the radius exceeds `MAX_COORDINATE_M`.
    PopupOutOfRange = 303,
    /// `PopupError::NotSimple`: A polygon has fewer than 3 vertices, a zero-length edge, or edges
    /// that cross.
    PopupNotSimple = 304,
    /// `PopupError::UnknownId`: No active pop-up has this id.
    PopupUnknownId = 305,
    /// `PopupError::BadHeight`: A height is NaN, not positive, or finite beyond
    /// `MAX_ALTITUDE_M`.
    PopupBadHeight = 306,
    /// `PopupError::HeightNeedsAltitudes`: A finite height on a network without altitudes.
    PopupHeightNeedsAltitudes = 307,
    /// `GeoError::NonFinite`: A coordinate or heading is NaN or infinite.
    GeoNonFinite = 400,
    /// `GeoError::Latitude`: A latitude outside [−90, 90] degrees.
    GeoLatitude = 401,
    /// `GeoError::Longitude`: A longitude outside [−180, 180] degrees.
    GeoLongitude = 402,
    /// `GeoError::Heading`: A compass heading outside [−360, 360] degrees.
    GeoHeading = 403,
    /// `GeoError::OutOfFrame`: The point lies outside the local frame's valid region (too far
    /// east or west of the origin's meridian, beyond a pole, or past the planner's coordinate
    /// range).
    GeoOutOfFrame = 404,
}

/// The status for a `LoadError`.
pub fn load_status(e: &LoadError) -> SrStatus {
    match e {
        LoadError::Truncated { .. } => SrStatus::LoadTruncated,
        LoadError::TrailingBytes { .. } => SrStatus::LoadTrailingBytes,
        LoadError::BadMagic { .. } => SrStatus::LoadBadMagic,
        LoadError::UnsupportedVersion { .. } => SrStatus::LoadUnsupportedVersion,
        LoadError::UnknownMode { .. } => SrStatus::LoadUnknownMode,
        LoadError::TooManyVertices { .. } => SrStatus::LoadTooManyVertices,
        LoadError::TooManyEdges { .. } => SrStatus::LoadTooManyEdges,
        LoadError::CountsTooLarge => SrStatus::LoadCountsTooLarge,
        LoadError::BodyLengthMismatch { .. } => SrStatus::LoadBodyLengthMismatch,
        LoadError::ChecksumMismatch { .. } => SrStatus::LoadChecksumMismatch,
        LoadError::InvalidParameter { .. } => SrStatus::LoadInvalidParameter,
        LoadError::Malformed { .. } => SrStatus::LoadMalformed,
        LoadError::NonFinite { .. } => SrStatus::LoadNonFinite,
        LoadError::BadOffsets { .. } => SrStatus::LoadBadOffsets,
        LoadError::IndexOutOfRange { .. } => SrStatus::LoadIndexOutOfRange,
        LoadError::BadCellList { .. } => SrStatus::LoadBadCellList,
        LoadError::WordCannotJoin { .. } => SrStatus::LoadWordCannotJoin,
        LoadError::NegativeValue { .. } => SrStatus::LoadNegativeValue,
        LoadError::UnknownGeometry { .. } => SrStatus::LoadUnknownGeometry,
        LoadError::EdgeMissesTarget { .. } => SrStatus::LoadEdgeMissesTarget,
        LoadError::CostBelowLength { .. } => SrStatus::LoadCostBelowLength,
        LoadError::BadObstacle { .. } => SrStatus::LoadBadObstacle,
        LoadError::GridTooSmall { .. } => SrStatus::LoadGridTooSmall,
        LoadError::TooManySearchStates { .. } => SrStatus::LoadTooManySearchStates,
        LoadError::BadThreat { .. } => SrStatus::LoadBadThreat,
        LoadError::ThreatSitesRefused { .. } => SrStatus::LoadThreatSitesRefused,
        LoadError::NeedsVoronoiStorage => SrStatus::LoadNeedsVoronoiStorage,
        LoadError::NotVoronoi { .. } => SrStatus::LoadNotVoronoi,
        LoadError::VoronoiMismatch { .. } => SrStatus::LoadVoronoiMismatch,
        LoadError::EdgeOutsideTerrain { .. } => SrStatus::LoadEdgeOutsideTerrain,
        LoadError::EdgeElevationUnderstated { .. } => SrStatus::LoadEdgeElevationUnderstated,
        LoadError::LandmarkVertexCount { .. } => SrStatus::LoadLandmarkVertexCount,
        LoadError::EndpointVertexMismatch { .. } => SrStatus::LoadEndpointVertexMismatch,
        LoadError::VertexOffLandmark { .. } => SrStatus::LoadVertexOffLandmark,
        LoadError::QualityOutOfRange { .. } => SrStatus::LoadQualityOutOfRange,
        LoadError::ElementSpeed { .. } => SrStatus::LoadElementSpeed,
        LoadError::ChainTooShort { .. } => SrStatus::LoadChainTooShort,
        LoadError::CoincidentElements { .. } => SrStatus::LoadCoincidentElements,
        LoadError::ChainMissesVertex { .. } => SrStatus::LoadChainMissesVertex,
        LoadError::ChainShorterThanChords { .. } => SrStatus::LoadChainShorterThanChords,
        LoadError::EdgeOutsideGrid { .. } => SrStatus::LoadEdgeOutsideGrid,
        LoadError::BadPopupAlternatives { .. } => SrStatus::LoadBadPopupAlternatives,
        LoadError::BadAltitude { .. } => SrStatus::LoadBadAltitude,
        LoadError::EdgeTooSteep { .. } => SrStatus::LoadEdgeTooSteep,
    }
}

/// The status for a `PlanError`.
pub fn plan_status(e: &PlanError) -> SrStatus {
    match e {
        PlanError::NonFinite { .. } => SrStatus::PlanNonFinite,
        PlanError::OutOfRange { .. } => SrStatus::PlanOutOfRange,
        PlanError::InsideObstacle { .. } => SrStatus::PlanInsideObstacle,
        PlanError::InsidePopup { .. } => SrStatus::PlanInsidePopup,
        PlanError::StartUnconnected => SrStatus::PlanStartUnconnected,
        PlanError::GoalUnconnected => SrStatus::PlanGoalUnconnected,
        PlanError::NoRoute => SrStatus::PlanNoRoute,
        PlanError::BudgetExhausted { .. } => SrStatus::PlanBudgetExhausted,
        PlanError::RouteTooLong { .. } => SrStatus::PlanRouteTooLong,
        PlanError::OverBlockedTerrain { .. } => SrStatus::PlanOverBlockedTerrain,
        PlanError::InvalidAltitude => SrStatus::PlanInvalidAltitude,
        PlanError::NotLandmarkNetwork => SrStatus::PlanNotLandmarkNetwork,
        PlanError::NotTerrainNetwork => SrStatus::PlanNotTerrainNetwork,
        PlanError::UnknownWeather { .. } => SrStatus::PlanUnknownWeather,
        PlanError::UnknownLandmark { .. } => SrStatus::PlanUnknownLandmark,
        PlanError::InvalidRosette { .. } => SrStatus::PlanInvalidRosette,
        PlanError::RosetteTableFull { .. } => SrStatus::PlanRosetteTableFull,
        PlanError::InvalidRange => SrStatus::PlanInvalidRange,
        PlanError::NotDubinsRoute => SrStatus::PlanNotDubinsRoute,
        PlanError::NotThreeDimensional => SrStatus::PlanNotThreeDimensional,
        PlanError::AltitudesNeeded => SrStatus::PlanAltitudesNeeded,
        PlanError::Smoothing { .. } => SrStatus::PlanSmoothing,
        PlanError::TooManySearchStates { .. } => SrStatus::PlanTooManySearchStates,
        PlanError::Internal => SrStatus::PlanInternal,
    }
}

/// The status for a `PopupError`.
pub fn popup_status(e: &PopupError) -> SrStatus {
    match e {
        PopupError::NoFreeSlot { .. } => SrStatus::PopupNoFreeSlot,
        PopupError::NonFinite => SrStatus::PopupNonFinite,
        PopupError::NonPositiveRadius => SrStatus::PopupNonPositiveRadius,
        PopupError::OutOfRange => SrStatus::PopupOutOfRange,
        PopupError::NotSimple => SrStatus::PopupNotSimple,
        PopupError::UnknownId { .. } => SrStatus::PopupUnknownId,
        PopupError::BadHeight => SrStatus::PopupBadHeight,
        PopupError::HeightNeedsAltitudes => SrStatus::PopupHeightNeedsAltitudes,
    }
}

impl SrStatus {
    /// The status's name as the header spells it (`SR_STATUS_…`).
    pub fn name(self) -> &'static CStr {
        match self {
            SrStatus::Ok => c"SR_STATUS_OK",
            SrStatus::NullPointer => c"SR_STATUS_NULL_POINTER",
            SrStatus::MemoryMisaligned => c"SR_STATUS_MEMORY_MISALIGNED",
            SrStatus::MemoryTooSmall => c"SR_STATUS_MEMORY_TOO_SMALL",
            SrStatus::InvalidArgument => c"SR_STATUS_INVALID_ARGUMENT",
            SrStatus::BufferTooSmall => c"SR_STATUS_BUFFER_TOO_SMALL",
            SrStatus::NoNetwork => c"SR_STATUS_NO_NETWORK",
            SrStatus::LoadTruncated => c"SR_STATUS_LOAD_TRUNCATED",
            SrStatus::LoadTrailingBytes => c"SR_STATUS_LOAD_TRAILING_BYTES",
            SrStatus::LoadBadMagic => c"SR_STATUS_LOAD_BAD_MAGIC",
            SrStatus::LoadUnsupportedVersion => c"SR_STATUS_LOAD_UNSUPPORTED_VERSION",
            SrStatus::LoadUnknownMode => c"SR_STATUS_LOAD_UNKNOWN_MODE",
            SrStatus::LoadTooManyVertices => c"SR_STATUS_LOAD_TOO_MANY_VERTICES",
            SrStatus::LoadTooManyEdges => c"SR_STATUS_LOAD_TOO_MANY_EDGES",
            SrStatus::LoadCountsTooLarge => c"SR_STATUS_LOAD_COUNTS_TOO_LARGE",
            SrStatus::LoadBodyLengthMismatch => c"SR_STATUS_LOAD_BODY_LENGTH_MISMATCH",
            SrStatus::LoadChecksumMismatch => c"SR_STATUS_LOAD_CHECKSUM_MISMATCH",
            SrStatus::LoadInvalidParameter => c"SR_STATUS_LOAD_INVALID_PARAMETER",
            SrStatus::LoadMalformed => c"SR_STATUS_LOAD_MALFORMED",
            SrStatus::LoadNonFinite => c"SR_STATUS_LOAD_NON_FINITE",
            SrStatus::LoadBadOffsets => c"SR_STATUS_LOAD_BAD_OFFSETS",
            SrStatus::LoadIndexOutOfRange => c"SR_STATUS_LOAD_INDEX_OUT_OF_RANGE",
            SrStatus::LoadBadCellList => c"SR_STATUS_LOAD_BAD_CELL_LIST",
            SrStatus::LoadWordCannotJoin => c"SR_STATUS_LOAD_WORD_CANNOT_JOIN",
            SrStatus::LoadNegativeValue => c"SR_STATUS_LOAD_NEGATIVE_VALUE",
            SrStatus::LoadUnknownGeometry => c"SR_STATUS_LOAD_UNKNOWN_GEOMETRY",
            SrStatus::LoadEdgeMissesTarget => c"SR_STATUS_LOAD_EDGE_MISSES_TARGET",
            SrStatus::LoadCostBelowLength => c"SR_STATUS_LOAD_COST_BELOW_LENGTH",
            SrStatus::LoadBadObstacle => c"SR_STATUS_LOAD_BAD_OBSTACLE",
            SrStatus::LoadGridTooSmall => c"SR_STATUS_LOAD_GRID_TOO_SMALL",
            SrStatus::LoadTooManySearchStates => c"SR_STATUS_LOAD_TOO_MANY_SEARCH_STATES",
            SrStatus::LoadBadThreat => c"SR_STATUS_LOAD_BAD_THREAT",
            SrStatus::LoadThreatSitesRefused => c"SR_STATUS_LOAD_THREAT_SITES_REFUSED",
            SrStatus::LoadNeedsVoronoiStorage => c"SR_STATUS_LOAD_NEEDS_VORONOI_STORAGE",
            SrStatus::LoadNotVoronoi => c"SR_STATUS_LOAD_NOT_VORONOI",
            SrStatus::LoadVoronoiMismatch => c"SR_STATUS_LOAD_VORONOI_MISMATCH",
            SrStatus::LoadEdgeOutsideTerrain => c"SR_STATUS_LOAD_EDGE_OUTSIDE_TERRAIN",
            SrStatus::LoadEdgeElevationUnderstated => c"SR_STATUS_LOAD_EDGE_ELEVATION_UNDERSTATED",
            SrStatus::LoadLandmarkVertexCount => c"SR_STATUS_LOAD_LANDMARK_VERTEX_COUNT",
            SrStatus::LoadEndpointVertexMismatch => c"SR_STATUS_LOAD_ENDPOINT_VERTEX_MISMATCH",
            SrStatus::LoadVertexOffLandmark => c"SR_STATUS_LOAD_VERTEX_OFF_LANDMARK",
            SrStatus::LoadQualityOutOfRange => c"SR_STATUS_LOAD_QUALITY_OUT_OF_RANGE",
            SrStatus::LoadElementSpeed => c"SR_STATUS_LOAD_ELEMENT_SPEED",
            SrStatus::LoadChainTooShort => c"SR_STATUS_LOAD_CHAIN_TOO_SHORT",
            SrStatus::LoadCoincidentElements => c"SR_STATUS_LOAD_COINCIDENT_ELEMENTS",
            SrStatus::LoadChainMissesVertex => c"SR_STATUS_LOAD_CHAIN_MISSES_VERTEX",
            SrStatus::LoadChainShorterThanChords => c"SR_STATUS_LOAD_CHAIN_SHORTER_THAN_CHORDS",
            SrStatus::LoadEdgeOutsideGrid => c"SR_STATUS_LOAD_EDGE_OUTSIDE_GRID",
            SrStatus::LoadBadPopupAlternatives => c"SR_STATUS_LOAD_BAD_POPUP_ALTERNATIVES",
            SrStatus::LoadBadAltitude => c"SR_STATUS_LOAD_BAD_ALTITUDE",
            SrStatus::LoadEdgeTooSteep => c"SR_STATUS_LOAD_EDGE_TOO_STEEP",
            SrStatus::PlanNonFinite => c"SR_STATUS_PLAN_NON_FINITE",
            SrStatus::PlanOutOfRange => c"SR_STATUS_PLAN_OUT_OF_RANGE",
            SrStatus::PlanInsideObstacle => c"SR_STATUS_PLAN_INSIDE_OBSTACLE",
            SrStatus::PlanInsidePopup => c"SR_STATUS_PLAN_INSIDE_POPUP",
            SrStatus::PlanStartUnconnected => c"SR_STATUS_PLAN_START_UNCONNECTED",
            SrStatus::PlanGoalUnconnected => c"SR_STATUS_PLAN_GOAL_UNCONNECTED",
            SrStatus::PlanNoRoute => c"SR_STATUS_PLAN_NO_ROUTE",
            SrStatus::PlanBudgetExhausted => c"SR_STATUS_PLAN_BUDGET_EXHAUSTED",
            SrStatus::PlanRouteTooLong => c"SR_STATUS_PLAN_ROUTE_TOO_LONG",
            SrStatus::PlanOverBlockedTerrain => c"SR_STATUS_PLAN_OVER_BLOCKED_TERRAIN",
            SrStatus::PlanInvalidAltitude => c"SR_STATUS_PLAN_INVALID_ALTITUDE",
            SrStatus::PlanNotLandmarkNetwork => c"SR_STATUS_PLAN_NOT_LANDMARK_NETWORK",
            SrStatus::PlanNotTerrainNetwork => c"SR_STATUS_PLAN_NOT_TERRAIN_NETWORK",
            SrStatus::PlanUnknownWeather => c"SR_STATUS_PLAN_UNKNOWN_WEATHER",
            SrStatus::PlanUnknownLandmark => c"SR_STATUS_PLAN_UNKNOWN_LANDMARK",
            SrStatus::PlanInvalidRosette => c"SR_STATUS_PLAN_INVALID_ROSETTE",
            SrStatus::PlanRosetteTableFull => c"SR_STATUS_PLAN_ROSETTE_TABLE_FULL",
            SrStatus::PlanInvalidRange => c"SR_STATUS_PLAN_INVALID_RANGE",
            SrStatus::PlanNotDubinsRoute => c"SR_STATUS_PLAN_NOT_DUBINS_ROUTE",
            SrStatus::PlanNotThreeDimensional => c"SR_STATUS_PLAN_NOT_THREE_DIMENSIONAL",
            SrStatus::PlanAltitudesNeeded => c"SR_STATUS_PLAN_ALTITUDES_NEEDED",
            SrStatus::PlanSmoothing => c"SR_STATUS_PLAN_SMOOTHING",
            SrStatus::PlanTooManySearchStates => c"SR_STATUS_PLAN_TOO_MANY_SEARCH_STATES",
            SrStatus::PlanInternal => c"SR_STATUS_PLAN_INTERNAL",
            SrStatus::PopupNoFreeSlot => c"SR_STATUS_POPUP_NO_FREE_SLOT",
            SrStatus::PopupNonFinite => c"SR_STATUS_POPUP_NON_FINITE",
            SrStatus::PopupNonPositiveRadius => c"SR_STATUS_POPUP_NON_POSITIVE_RADIUS",
            SrStatus::PopupOutOfRange => c"SR_STATUS_POPUP_OUT_OF_RANGE",
            SrStatus::PopupNotSimple => c"SR_STATUS_POPUP_NOT_SIMPLE",
            SrStatus::PopupUnknownId => c"SR_STATUS_POPUP_UNKNOWN_ID",
            SrStatus::PopupBadHeight => c"SR_STATUS_POPUP_BAD_HEIGHT",
            SrStatus::PopupHeightNeedsAltitudes => c"SR_STATUS_POPUP_HEIGHT_NEEDS_ALTITUDES",
            SrStatus::GeoNonFinite => c"SR_STATUS_GEO_NON_FINITE",
            SrStatus::GeoLatitude => c"SR_STATUS_GEO_LATITUDE",
            SrStatus::GeoLongitude => c"SR_STATUS_GEO_LONGITUDE",
            SrStatus::GeoHeading => c"SR_STATUS_GEO_HEADING",
            SrStatus::GeoOutOfFrame => c"SR_STATUS_GEO_OUT_OF_FRAME",
        }
    }
}

/// The name of `status` as the header spells it (`"SR_STATUS_PLAN_NO_ROUTE"`), a static
/// NUL-terminated string; `"SR_STATUS_UNKNOWN"` for a number that is no status.
#[no_mangle]
pub extern "C" fn sr_status_name(status: i32) -> *const c_char {
    match SrStatus::from_code(status) {
        Some(s) => s.name().as_ptr(),
        None => c"SR_STATUS_UNKNOWN".as_ptr(),
    }
}

impl SrStatus {
    /// The status whose number is `code`, if any.
    pub fn from_code(code: i32) -> Option<SrStatus> {
        ALL.iter().copied().find(|s| *s as i32 == code)
    }
}

/// Every status, in the order of their numbers.
const ALL: [SrStatus; 88] = [
    SrStatus::Ok,
    SrStatus::NullPointer,
    SrStatus::MemoryMisaligned,
    SrStatus::MemoryTooSmall,
    SrStatus::InvalidArgument,
    SrStatus::BufferTooSmall,
    SrStatus::NoNetwork,
    SrStatus::LoadTruncated,
    SrStatus::LoadTrailingBytes,
    SrStatus::LoadBadMagic,
    SrStatus::LoadUnsupportedVersion,
    SrStatus::LoadUnknownMode,
    SrStatus::LoadTooManyVertices,
    SrStatus::LoadTooManyEdges,
    SrStatus::LoadCountsTooLarge,
    SrStatus::LoadBodyLengthMismatch,
    SrStatus::LoadChecksumMismatch,
    SrStatus::LoadInvalidParameter,
    SrStatus::LoadMalformed,
    SrStatus::LoadNonFinite,
    SrStatus::LoadBadOffsets,
    SrStatus::LoadIndexOutOfRange,
    SrStatus::LoadBadCellList,
    SrStatus::LoadWordCannotJoin,
    SrStatus::LoadNegativeValue,
    SrStatus::LoadUnknownGeometry,
    SrStatus::LoadEdgeMissesTarget,
    SrStatus::LoadCostBelowLength,
    SrStatus::LoadBadObstacle,
    SrStatus::LoadGridTooSmall,
    SrStatus::LoadTooManySearchStates,
    SrStatus::LoadBadThreat,
    SrStatus::LoadThreatSitesRefused,
    SrStatus::LoadNeedsVoronoiStorage,
    SrStatus::LoadNotVoronoi,
    SrStatus::LoadVoronoiMismatch,
    SrStatus::LoadEdgeOutsideTerrain,
    SrStatus::LoadEdgeElevationUnderstated,
    SrStatus::LoadLandmarkVertexCount,
    SrStatus::LoadEndpointVertexMismatch,
    SrStatus::LoadVertexOffLandmark,
    SrStatus::LoadQualityOutOfRange,
    SrStatus::LoadElementSpeed,
    SrStatus::LoadChainTooShort,
    SrStatus::LoadCoincidentElements,
    SrStatus::LoadChainMissesVertex,
    SrStatus::LoadChainShorterThanChords,
    SrStatus::LoadEdgeOutsideGrid,
    SrStatus::LoadBadPopupAlternatives,
    SrStatus::LoadBadAltitude,
    SrStatus::LoadEdgeTooSteep,
    SrStatus::PlanNonFinite,
    SrStatus::PlanOutOfRange,
    SrStatus::PlanInsideObstacle,
    SrStatus::PlanInsidePopup,
    SrStatus::PlanStartUnconnected,
    SrStatus::PlanGoalUnconnected,
    SrStatus::PlanNoRoute,
    SrStatus::PlanBudgetExhausted,
    SrStatus::PlanRouteTooLong,
    SrStatus::PlanOverBlockedTerrain,
    SrStatus::PlanInvalidAltitude,
    SrStatus::PlanNotLandmarkNetwork,
    SrStatus::PlanNotTerrainNetwork,
    SrStatus::PlanUnknownWeather,
    SrStatus::PlanUnknownLandmark,
    SrStatus::PlanInvalidRosette,
    SrStatus::PlanRosetteTableFull,
    SrStatus::PlanSmoothing,
    SrStatus::PlanTooManySearchStates,
    SrStatus::PlanInternal,
    SrStatus::PlanInvalidRange,
    SrStatus::PlanNotDubinsRoute,
    SrStatus::PlanNotThreeDimensional,
    SrStatus::PlanAltitudesNeeded,
    SrStatus::PopupNoFreeSlot,
    SrStatus::PopupNonFinite,
    SrStatus::PopupNonPositiveRadius,
    SrStatus::PopupOutOfRange,
    SrStatus::PopupNotSimple,
    SrStatus::PopupUnknownId,
    SrStatus::PopupBadHeight,
    SrStatus::PopupHeightNeedsAltitudes,
    SrStatus::GeoNonFinite,
    SrStatus::GeoLatitude,
    SrStatus::GeoLongitude,
    SrStatus::GeoHeading,
    SrStatus::GeoOutOfFrame,
];
