//! Errors of the planner's operations.

use core::fmt;

/// Which input of a query was rejected.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum QueryField {
    /// The start pose.
    Start,
    /// The goal position or heading.
    Goal,
}

/// Why [`Planner::plan`](super::Planner::plan) found no route. The previous route is kept.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum PlanError {
    /// A position or heading is NaN or infinite.
    NonFinite {
        /// Which one.
        field: QueryField,
    },
    /// A position lies beyond [`MAX_COORDINATE_M`](crate::geometry::MAX_COORDINATE_M) of the
    /// network's origin.
    OutOfRange {
        /// Which one.
        field: QueryField,
    },
    /// The start or goal lies inside a static obstacle.
    InsideObstacle {
        /// Start or goal.
        field: QueryField,
        /// The obstacle's index in the network.
        obstacle: u32,
    },
    /// The start or goal lies inside an active pop-up.
    InsidePopup {
        /// Start or goal.
        field: QueryField,
        /// The pop-up's id.
        popup: u8,
    },
    /// No collision-free connection from the start to a nearby vertex (or to the goal); in
    /// landmark mode, no flyable clear piece within the range left to an overflight.
    StartUnconnected,
    /// No collision-free connection from a nearby vertex to the goal; in landmark mode, no
    /// flyable clear piece from an overflight within its range.
    GoalUnconnected,
    /// The search exhausted the reachable network without reaching the goal.
    NoRoute,
    /// The work budget ran out before the query finished.
    BudgetExhausted {
        /// Work done when it stopped.
        used: u64,
        /// The budget given.
        budget: u64,
    },
    /// The route has more primitives than the planner's route capacity.
    RouteTooLong {
        /// Primitives the route needs.
        primitives: u32,
        /// The capacity `R`.
        capacity: u32,
    },
    /// Terrain mode: the start or goal lies over a cell that is blocked at the altitude in
    /// force (or unknown, or outside the elevation grid).
    OverBlockedTerrain {
        /// Start or goal.
        field: QueryField,
    },
    /// [`Planner::set_altitude`](super::Planner::set_altitude) got a non-finite altitude or a
    /// negative or non-finite safety height, or
    /// [`Planner::set_query_altitudes`](super::Planner::set_query_altitudes) an altitude that is
    /// not finite or beyond 100 km.
    InvalidAltitude,
    /// Three-dimensional roadmap only: the operation needs a three-dimensional roadmap.
    NotThreeDimensional,
    /// A three-dimensional roadmap's query needs the start's and the goal's altitudes
    /// ([`Planner::set_query_altitudes`](super::Planner::set_query_altitudes)).
    AltitudesNeeded,
    /// Landmark mode only: the operation needs a landmark network.
    NotLandmarkNetwork,
    /// Terrain mode only: the operation needs a terrain network.
    NotTerrainNetwork,
    /// Landmark mode: the weather index is not below the network's weather count.
    UnknownWeather {
        /// The index given.
        weather: u32,
        /// Weathers in the network.
        count: u32,
    },
    /// Landmark mode: the landmark index is not below the network's landmark count.
    UnknownLandmark {
        /// The index given.
        landmark: u32,
        /// Landmarks in the network.
        count: u32,
    },
    /// Landmark mode: a rosette update does not have one quality in `[0, 1]` per direction
    /// (or the network has more than
    /// [`MAX_ROSETTE_DIRECTIONS`](super::MAX_ROSETTE_DIRECTIONS) directions).
    InvalidRosette {
        /// Qualities given.
        given: u32,
        /// Directions of the network.
        directions: u32,
    },
    /// Landmark mode: all [`MAX_ROSETTE_OVERRIDES`](super::MAX_ROSETTE_OVERRIDES) rosette
    /// overrides are in use (by other landmarks).
    RosetteTableFull {
        /// The table's capacity.
        capacity: u32,
    },
    /// Landmark mode: [`Planner::set_start_range`](super::Planner::set_start_range) got a
    /// negative or non-finite range.
    InvalidRange,
    /// Voronoi mode: the coarse route found cannot be smoothed within the curvature limit
    /// while staying clear of no-fly zones and pop-ups, at this corner of the coarse route
    /// (1 the first vertex after the start; 0 the start's lead-in).
    Smoothing {
        /// The corner.
        corner: u32,
    },
    /// Terrain mode: the query's search states (under the paper's
    /// [`TurnRule`](super::TurnRule), one per transition of the graph) exceed the planner's
    /// state capacity `V`.
    TooManySearchStates {
        /// States the query needs.
        needed: u32,
        /// The capacity `V`.
        capacity: u32,
    },
    /// An internal invariant failed (a bug; reported instead of panicking).
    Internal,
    /// Post-processing ([`Planner::shortcut`](super::Planner::shortcut) and the passes beside
    /// it) applies to roadmap and terrain routes, chains of Dubins paths; a landmark route (Hermite
    /// pieces) or a Voronoi route (a smoothed spline) is left as it is.
    NotDubinsRoute,
}

impl fmt::Display for PlanError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        use PlanError::*;
        match *self {
            NonFinite { field } => write!(f, "{field:?} has a NaN or infinite value"),
            OutOfRange { field } => write!(f, "{field:?} lies beyond 10 000 km of the origin"),
            InsideObstacle { field, obstacle } => {
                write!(f, "{field:?} lies inside obstacle {obstacle}")
            }
            InsidePopup { field, popup } => write!(f, "{field:?} lies inside pop-up {popup}"),
            OverBlockedTerrain { field } => {
                write!(f, "{field:?} lies over terrain blocked at this altitude")
            }
            InvalidAltitude => write!(f, "altitude or safety height is not a valid number"),
            NotThreeDimensional => write!(f, "the network is not a three-dimensional roadmap"),
            AltitudesNeeded => write!(
                f,
                "a three-dimensional roadmap needs the start's and goal's altitudes"
            ),
            StartUnconnected => write!(f, "no collision-free connection from the start"),
            GoalUnconnected => write!(f, "no collision-free connection to the goal"),
            NoRoute => write!(f, "the goal cannot be reached in the network"),
            BudgetExhausted { used, budget } => {
                write!(f, "work budget of {budget} exhausted after {used}")
            }
            RouteTooLong {
                primitives,
                capacity,
            } => {
                write!(
                    f,
                    "route needs {primitives} primitives, capacity is {capacity}"
                )
            }
            NotLandmarkNetwork => write!(f, "the network is not a landmark network"),
            NotTerrainNetwork => write!(f, "the network is not a terrain network"),
            NotDubinsRoute => write!(
                f,
                "post-processing applies to roadmap and terrain routes only"
            ),
            UnknownWeather { weather, count } => {
                write!(f, "weather {weather} unknown: the network has {count}")
            }
            UnknownLandmark { landmark, count } => {
                write!(f, "landmark {landmark} unknown: the network has {count}")
            }
            InvalidRosette { given, directions } => write!(
                f,
                "rosette of {given} qualities: needs one in [0, 1] per direction ({directions})"
            ),
            RosetteTableFull { capacity } => {
                write!(f, "all {capacity} rosette overrides are in use")
            }
            InvalidRange => write!(f, "the range left must be finite and at least 0"),
            Smoothing { corner } => write!(
                f,
                "the route cannot be smoothed within the curvature limit clear of zones at \
                 corner {corner}"
            ),
            TooManySearchStates { needed, capacity } => write!(
                f,
                "the turn rule needs {needed} search states, capacity is {capacity}"
            ),
            Internal => write!(f, "internal planner invariant failed"),
        }
    }
}

/// Why a pop-up was not added or removed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum PopupError {
    /// All `P` pop-up slots are in use.
    NoFreeSlot {
        /// The capacity `P`.
        capacity: u8,
    },
    /// A coordinate or radius is NaN or infinite.
    NonFinite,
    /// A circle's radius is not positive.
    NonPositiveRadius,
    /// A coordinate or the radius exceeds [`MAX_COORDINATE_M`](crate::geometry::MAX_COORDINATE_M).
    OutOfRange,
    /// A polygon has fewer than 3 vertices, a zero-length edge, or edges that cross.
    NotSimple,
    /// No active pop-up has this id.
    UnknownId {
        /// The id given.
        id: u8,
    },
    /// A height is NaN, not positive, or finite beyond
    /// [`MAX_ALTITUDE_M`](crate::network::format::MAX_ALTITUDE_M).
    BadHeight,
    /// A finite height on a network without altitudes (only a three-dimensional roadmap
    /// can fly over a pop-up).
    HeightNeedsAltitudes,
}

impl fmt::Display for PopupError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            PopupError::NoFreeSlot { capacity } => write!(f, "all {capacity} pop-up slots in use"),
            PopupError::NonFinite => write!(f, "pop-up has a NaN or infinite value"),
            PopupError::NonPositiveRadius => write!(f, "pop-up radius is not positive"),
            PopupError::OutOfRange => write!(f, "pop-up lies beyond 10 000 km of the origin"),
            PopupError::NotSimple => write!(f, "pop-up polygon is not simple"),
            PopupError::UnknownId { id } => write!(f, "no active pop-up with id {id}"),
            PopupError::BadHeight => write!(
                f,
                "pop-up height is NaN, not positive, or finite beyond 100 km"
            ),
            PopupError::HeightNeedsAltitudes => write!(
                f,
                "pop-up has a height but the network has no altitudes (not a 3-D roadmap)"
            ),
        }
    }
}

#[cfg(feature = "std")]
impl std::error::Error for PlanError {}
#[cfg(feature = "std")]
impl std::error::Error for PopupError {}
