//! The built landmark network: overflight vertices, Hermite-chain edges, endpoint links and
//! statistics.

use super::input::{EndpointSite, LandmarkSite};
use crate::frame::LocalFrame;
use skyroute::geometry::hermite::{FlyLimits, HermiteSegment, LineElement};
use skyroute::network::write::ObstacleSpec;
use skyroute::Pose;
use std::time::Duration;

/// An overflight vertex: landmark `landmark` crossed in direction `direction`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LandmarkVertex {
    /// Index into [`LandmarkNetwork::landmarks`].
    pub landmark: u32,
    /// Direction index (`0..directions`; compass `360·direction/directions` degrees).
    pub direction: u32,
    /// The pose in the local frame (heading: the angle of `element.velocity`).
    pub pose: Pose,
    /// The line element: the landmark's position and the direction's velocity (nominal speed).
    pub element: LineElement,
}

/// A chain of quintic Hermite pieces: `elements[i] → elements[i + 1]` is piece `i`, as
/// `HermiteSegment::new(&elements[i], &elements[i + 1], v_nominal)` builds it.
#[derive(Clone, Debug, PartialEq)]
pub struct HermiteChain {
    /// Total length, metres (the sum of the pieces' lengths).
    pub cost: f32,
    /// The line elements, first to last (one more than the pieces).
    pub elements: Vec<LineElement>,
    /// The pieces (each rebuilt from `elements` gives the same segment).
    pub pieces: Vec<HermiteSegment>,
}

/// A directed edge between overflights.
#[derive(Clone, Debug, PartialEq)]
pub struct LandmarkEdge {
    /// Source vertex index.
    pub source: u32,
    /// Target vertex index.
    pub target: u32,
    /// The flight path.
    pub chain: HermiteChain,
}

/// An edge between an endpoint (start or goal) and an overflight.
#[derive(Clone, Debug, PartialEq)]
pub struct EndpointEdge {
    /// The overflight vertex (the target for the start, the source for the goal).
    pub vertex: u32,
    /// Index into [`EndpointLinks::elements`] (the endpoint's heading used).
    pub endpoint_element: u32,
    /// The flight path, from start to vertex or from vertex to goal.
    pub chain: HermiteChain,
}

/// The connections of the scenario's start or goal (Connect-Endpoints).
#[derive(Clone, Debug, PartialEq)]
pub struct EndpointLinks {
    /// The endpoint.
    pub site: EndpointSite,
    /// Its line elements: one for a given heading; without a heading, one per direction.
    pub elements: Vec<LineElement>,
    /// The edges, ordered by landmark, then vertex, then endpoint element.
    pub edges: Vec<EndpointEdge>,
}

/// What the build did and took.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LandmarkStats {
    /// Landmark pairs closer than the larger of their `d_max`.
    pub pairs: usize,
    /// Basic networks built (pairs plus endpoint connections).
    pub basic_networks: usize,
    /// Line elements kept in all basic networks.
    pub line_elements: usize,
    /// Line elements drawn inside an obstacle's clearance and drawn again.
    pub line_elements_rejected: usize,
    /// Segments built (forward candidates of the neighbour rule).
    pub segments_tried: usize,
    /// Forward segments that passed the flyability check.
    pub segments_flyable: usize,
    /// Forward segments flyable and clear of obstacles.
    pub segments_feasible: usize,
    /// Reversed segments flyable and clear of obstacles.
    pub reverse_feasible: usize,
    /// Dijkstra searches run.
    pub searches: usize,
    /// Overflight edges.
    pub edges: usize,
    /// Source directions skipped because their range is shorter than the pair's distance.
    pub directions_out_of_range: usize,
    /// Edges dropped because their chain is longer than the source's best-weather range.
    pub edges_over_range: usize,
    /// (source, target) overflight pairs with a reachable range but no chain in the basic
    /// network.
    pub unconnected: usize,
    /// Wall time of the whole build.
    pub wall: Duration,
    /// Summed time spent building and checking segments, over all threads.
    pub segment_time: Duration,
    /// Summed time spent in the searches, over all threads.
    pub search_time: Duration,
}

/// The landmark shortest-path network.
#[derive(Clone, Debug, PartialEq)]
pub struct LandmarkNetwork {
    /// The scenario file it was built from.
    pub file: String,
    /// The local frame, when built from a scenario.
    pub frame: Option<LocalFrame>,
    /// Overflight directions per landmark.
    pub directions: usize,
    /// Nominal speed, m/s (the pieces' `v_nominal`).
    pub v_nominal: f32,
    /// The limits every piece was checked against.
    pub limits: FlyLimits,
    /// The clearance every piece keeps, metres.
    pub clearance_m: f32,
    /// Weather names (the rosettes' order).
    pub weather: Vec<String>,
    /// Landmarks with `d_max` and their rosettes per weather.
    pub landmarks: Vec<LandmarkSite>,
    /// The obstacles, local frame.
    pub obstacles: Vec<ObstacleSpec>,
    /// Vertices; vertex `landmark·directions + direction`.
    pub vertices: Vec<LandmarkVertex>,
    /// Edges, ordered by (pair, direction A→B before B→A, source, target).
    pub edges: Vec<LandmarkEdge>,
    /// The start's connections.
    pub start: Option<EndpointLinks>,
    /// The goal's connections.
    pub goal: Option<EndpointLinks>,
    /// Statistics.
    pub stats: LandmarkStats,
}

impl LandmarkNetwork {
    /// Vertex index of overflight `(landmark, direction)`.
    pub fn vertex_index(&self, landmark: usize, direction: usize) -> usize {
        landmark * self.directions + direction
    }
}
