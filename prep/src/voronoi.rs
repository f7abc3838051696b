//! Voronoi mode on the ground (Judd & McLain): the scenario's threats as radar sites, their
//! Voronoi diagram clipped to the mission box (built by the core's exact diagram, the one the
//! aircraft rebuilds and checks at load), its edges costed by length and exposure, the
//! no-fly zones as hard polygons, and the spline corner table, encoded as a network image.

use crate::frame::LocalFrame;
use crate::local::{local, local_obstacles, local_threats};
use crate::scenario::Scenario;
use skyroute::geometry::spline::table::build_corner_table;
use skyroute::geometry::voronoi::{Bounds, Delaunay, VoronoiGraph};
use skyroute::network::write::{EdgeSpec, NetworkSpec, ObstacleSpec, VoronoiSpec};
use skyroute::planner::{
    segment_exposure, Threat, MAX_THREATS, VORONOI_GRAPH_EDGES, VORONOI_GRAPH_VERTICES,
};
use skyroute::{Pose, Vec2};

/// The weight k when the scenario's `planner.threat_weight` is absent: length and exposure
/// count equally.
pub const DEFAULT_THREAT_WEIGHT: f64 = 0.5;

/// The mission box is the extent of the scenario's positions grown by this share of its
/// larger side on every side (at least [`MIN_MARGIN_M`]), so that routes can pass outside the
/// outermost threats.
pub const BOX_MARGIN: f64 = 0.1;

/// The least margin of the mission box around the scenario's positions, metres.
pub const MIN_MARGIN_M: f64 = 2000.0;

/// A built Voronoi network's figures.
#[derive(Clone, Debug)]
pub struct VoronoiNetwork {
    /// The threats, in scenario order.
    pub threats: Vec<Threat>,
    /// The graph's vertices.
    pub vertices: Vec<Vec2>,
    /// The graph's undirected edges as vertex pairs.
    pub edges: Vec<(u32, u32)>,
    /// The mission box.
    pub bounds: Bounds,
    /// The weight k the edge costs were written with.
    pub threat_weight: f32,
}

/// The mission box: the scenario's positions grown by [`BOX_MARGIN`] (at least
/// [`MIN_MARGIN_M`]).
pub fn mission_box(points: impl Iterator<Item = Vec2>) -> Bounds {
    let (lo, hi) = skyroute::geometry::points_bounding_box(points);
    let side = (hi.x - lo.x).max(hi.y - lo.y) as f64;
    let m = (BOX_MARGIN * side).max(MIN_MARGIN_M) as f32;
    Bounds {
        min: Vec2::new(lo.x - m, lo.y - m),
        max: Vec2::new(hi.x + m, hi.y + m),
    }
}

/// The scenario's Voronoi network: its threats' diagram clipped to the mission box (`Err`
/// says why the diagram refuses the threats), and the writer's spec with grid cell
/// `grid_cell_m` (its provenance left empty for the caller).
pub fn voronoi_network(
    s: &Scenario,
    frame: &LocalFrame,
    grid_cell_m: f32,
) -> Result<(VoronoiNetwork, NetworkSpec), String> {
    let threats = local_threats(s, frame);
    if threats.len() > MAX_THREATS {
        return Err(format!(
            "{} threats: a Voronoi network holds at most {MAX_THREATS} (the onboard diagram's \
             fixed storage)",
            threats.len()
        ));
    }
    let bounds = mission_box(s.positions().map(|(lon, lat)| local(frame, lon, lat)));
    let mut diagram: Box<Delaunay<MAX_THREATS, { 2 * MAX_THREATS }>> = Box::new(Delaunay::new());
    for (i, t) in threats.iter().enumerate() {
        diagram.insert(t.position).map_err(|e| {
            format!(
                "threat {:?}: the diagram refuses it: {e}",
                s.threats[i].name
            )
        })?;
    }
    let mut graph: Box<VoronoiGraph<VORONOI_GRAPH_VERTICES, VORONOI_GRAPH_EDGES>> =
        Box::new(VoronoiGraph::new());
    diagram
        .graph(&bounds, &mut graph)
        .map_err(|e| format!("the diagram's graph: {e}"))?;
    let k = s.planner.threat_weight.unwrap_or(DEFAULT_THREAT_WEIGHT) as f32;
    let vertices: Vec<Vec2> = graph.vertices().to_vec();
    let edges: Vec<(u32, u32)> = graph
        .edges()
        .iter()
        .map(|e| (e.a as u32, e.b as u32))
        .collect();
    let mut specs = Vec::with_capacity(2 * edges.len());
    for &(a, b) in &edges {
        let (pa, pb) = (vertices[a as usize], vertices[b as usize]);
        let length = pa.distance(pb);
        let (exposure, _) = segment_exposure(pa, pb, &threats);
        let cost = k * length + (1.0 - k) * exposure;
        for (from, to) in [(a, b), (b, a)] {
            specs.push(EdgeSpec {
                cost,
                ..EdgeSpec::line(from, to, length)
            });
        }
    }
    let turn_radius = s.vehicle.turn_radius_m() as f32;
    let obstacles: Vec<ObstacleSpec> = local_obstacles(s, frame)
        .into_iter()
        .filter(|o| matches!(o, ObstacleSpec::Polygon(_)))
        .collect();
    let (origin_lat, origin_lon) = frame.origin();
    let spec = NetworkSpec {
        origin_lat_deg: origin_lat,
        origin_lon_deg: origin_lon,
        turn_radius_m: turn_radius,
        clearance_m: s.planner.clearance_m.unwrap_or(0.0) as f32,
        vertices: vertices.iter().map(|p| Pose::new(p.x, p.y, 0.0)).collect(),
        edges: specs,
        obstacles,
        grid_cell_m,
        terrain: None,
        landmark: None,
        voronoi: Some(VoronoiSpec {
            threats: threats.iter().map(|t| (t.position, t.radius)).collect(),
            threat_weight: k,
            kappa_max: 1.0 / turn_radius,
            bounds: (bounds.min, bounds.max),
            corner_table: build_corner_table().to_vec(),
        }),
        provenance: Vec::new(),
    };
    let net = VoronoiNetwork {
        threats,
        vertices,
        edges,
        bounds,
        threat_weight: k,
    };
    Ok((net, spec))
}
