//! The planner's error messages: each names every number its error carries and which input
//! (start or goal) it is about, and no two read the same.

use crate::load_messages::assert_messages_name_and_differ;
use skyroute::geometry::voronoi::VoronoiError;
use skyroute::planner::QueryField::{Goal, Start};
use skyroute::planner::{ThreatError, MAX_THREATS};
use skyroute::{PlanError, PopupError};

/// Every [`PlanError`], its numbers all distinct, with the words of its message that name
/// them (the start's variant of each error about a query field; the goal's is checked below).
fn every_plan_error() -> Vec<(PlanError, Vec<&'static str>)> {
    use PlanError::*;
    vec![
        (NonFinite { field: Start }, vec!["Start", "NaN"]),
        (OutOfRange { field: Start }, vec!["Start", "10 000 km"]),
        (
            InsideObstacle {
                field: Start,
                obstacle: 201,
            },
            vec!["Start", "obstacle 201"],
        ),
        (
            InsidePopup {
                field: Start,
                popup: 202,
            },
            vec!["Start", "pop-up 202"],
        ),
        (StartUnconnected, vec!["start"]),
        (GoalUnconnected, vec!["goal"]),
        (NoRoute, vec!["cannot be reached"]),
        (
            BudgetExhausted {
                used: 203,
                budget: 204,
            },
            vec!["after 203", "budget of 204"],
        ),
        (
            RouteTooLong {
                primitives: 205,
                capacity: 206,
            },
            vec!["205 primitives", "capacity is 206"],
        ),
        (
            OverBlockedTerrain { field: Start },
            vec!["Start", "terrain"],
        ),
        (InvalidAltitude, vec!["altitude"]),
        (NotThreeDimensional, vec!["three-dimensional"]),
        (AltitudesNeeded, vec!["altitudes"]),
        (NotLandmarkNetwork, vec!["landmark"]),
        (NotTerrainNetwork, vec!["terrain"]),
        (
            UnknownWeather {
                weather: 207,
                count: 208,
            },
            vec!["weather 207", "has 208"],
        ),
        (
            UnknownLandmark {
                landmark: 209,
                count: 210,
            },
            vec!["landmark 209", "has 210"],
        ),
        (
            InvalidRosette {
                given: 211,
                directions: 212,
            },
            vec!["211 qualities", "(212)"],
        ),
        (RosetteTableFull { capacity: 213 }, vec!["213"]),
        (InvalidRange, vec!["range"]),
        (Smoothing { corner: 214 }, vec!["corner 214"]),
        (
            TooManySearchStates {
                needed: 215,
                capacity: 216,
            },
            vec!["215 search states", "capacity is 216"],
        ),
        (Internal, vec!["internal"]),
        (NotDubinsRoute, vec!["post-processing"]),
    ]
}

/// Every [`PopupError`], with the words that name its numbers.
fn every_popup_error() -> Vec<(PopupError, Vec<&'static str>)> {
    use PopupError::*;
    vec![
        (NoFreeSlot { capacity: 221 }, vec!["221"]),
        (NonFinite, vec!["NaN"]),
        (NonPositiveRadius, vec!["radius"]),
        (OutOfRange, vec!["10 000 km"]),
        (NotSimple, vec!["not simple"]),
        (UnknownId { id: 222 }, vec!["id 222"]),
        (BadHeight, vec!["height"]),
        (HeightNeedsAltitudes, vec!["no altitudes"]),
    ]
}

/// Every [`ThreatError`], with the words that name its numbers.
fn every_threat_error() -> Vec<(ThreatError, Vec<&'static str>)> {
    use ThreatError::*;
    assert_eq!(MAX_THREATS, 32, "the words below name the threat capacity");
    vec![
        (NotVoronoi, vec!["not a Voronoi network"]),
        (NonFinite, vec!["not finite"]),
        (OutOfRange, vec!["radius", "weight"]),
        (OutsideBox, vec!["outside the network's box"]),
        (Full, vec!["32 threats"]),
        (Duplicate { existing: 231 }, vec!["threat 231"]),
        (UnknownId { id: 232 }, vec!["id 232"]),
        (GraphFull, vec!["graph"]),
    ]
}

#[test]
fn every_plan_and_popup_error_names_its_numbers_and_reads_unlike_the_others() {
    let mut seen = std::collections::HashSet::new();
    assert_messages_name_and_differ(&every_plan_error(), &mut seen);
    assert_messages_name_and_differ(&every_popup_error(), &mut seen);
    assert_messages_name_and_differ(&every_threat_error(), &mut seen);
    // The goal's variant of each error about a query field names the goal.
    let goal = vec![
        (PlanError::NonFinite { field: Goal }, vec!["Goal"]),
        (PlanError::OutOfRange { field: Goal }, vec!["Goal"]),
        (
            PlanError::InsideObstacle {
                field: Goal,
                obstacle: 201,
            },
            vec!["Goal"],
        ),
        (
            PlanError::InsidePopup {
                field: Goal,
                popup: 202,
            },
            vec!["Goal"],
        ),
        (PlanError::OverBlockedTerrain { field: Goal }, vec!["Goal"]),
    ];
    assert_messages_name_and_differ(&goal, &mut seen);
}

/// The diagram's refusals reach the caller as the threat errors that say why: a site at the
/// position of another names it, a diagram at its site capacity is full, and any other
/// refusal is storage the rebuilt graph does not fit.
#[test]
fn the_diagrams_refusals_become_the_threat_errors_that_name_their_cause() {
    let cases = [
        (
            VoronoiError::DuplicateSite {
                index: 5,
                existing: 3,
            },
            ThreatError::Duplicate { existing: 3 },
        ),
        (
            VoronoiError::TooManySites {
                capacity: MAX_THREATS,
            },
            ThreatError::Full,
        ),
        (
            VoronoiError::TooManyTriangles { capacity: 64 },
            ThreatError::GraphFull,
        ),
        (VoronoiError::GraphFull, ThreatError::GraphFull),
    ];
    for (diagram, threat) in cases {
        assert_eq!(ThreatError::from(diagram), threat, "{diagram:?}");
    }
}
