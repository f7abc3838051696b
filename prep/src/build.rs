//! From a scenario to a network image: project to the local frame, build the mode's network,
//! encode it.

use crate::build_limits::{check_area, check_grid, check_sampling, encode_checked, landmark_box};
use crate::frame::LocalFrame;
use crate::landmark::{build_landmark_network_with, LandmarkNetwork, RangeRule};
use crate::roadmap::{
    build_roadmap_with, CollisionCheck, Roadmap, RoadmapInput, RoadmapParams, Sagitta,
};
use crate::scenario::{Mode, Scenario};
use crate::terrain::{build_terrain_graph, TerrainGraph, TerrainParams};
use skyroute::network::format::ProvenanceRecord;
use skyroute::network::write::{EdgeSpec, NetworkSpec, ObstacleSpec, TerrainSpec, VerticalSpec};
use skyroute::network::write::{LandmarkSiteSpec, LandmarkSpec};
use skyroute::Pose;
use std::fmt;

pub use crate::local::{local, local_heading, local_obstacles, local_pose, obstacle_containing};

/// Overrides of the scenario's parameters, for experiments and for networks that must fit a
/// smaller target.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct BuildOptions {
    /// Replaces `planner.sample_spacing_m`.
    pub sample_spacing_m: Option<f32>,
    /// Replaces `planner.neighbour_radius_m`.
    pub neighbour_radius_m: Option<f32>,
    /// Use the paper's discretised collision check (`planner.arc_step_m`), with the chord
    /// error added to the clearance or counted in it, instead of the exact one (`None`).
    pub discretised: Option<Sagitta>,
    /// Side of a grid-index cell; default: twice the turn radius (roadmap), 4 km (terrain).
    pub grid_cell_m: Option<f32>,
    /// Terrain mode: nodes closer than this to a kept node are dropped (default 0: none).
    pub node_spacing_m: Option<f64>,
    /// Terrain mode: the longest edge tried (default: every pair of nodes).
    pub max_edge_m: Option<f64>,
    /// Terrain mode: how much farther than the widening a node lies from its corner along
    /// each axis (default 1 m; more leaves room for the turn arcs).
    pub node_margin_m: Option<f64>,
    /// Terrain mode: further altitudes whose terrain also gets nodes (see
    /// [`TerrainParams::extra_altitudes_m`]).
    pub extra_altitudes_m: Vec<f64>,
    /// Landmark mode: which chains are stored ([`RangeRule`]; default: those a straight leg
    /// and the chain's own length allow in the best weather).
    pub landmark_ranges: RangeRule,
}

/// Terrain mode's default node margin, metres. A larger margin leaves room for sharper turns
/// at a node (the turn arc's midpoint moves `r·(sec(θ/2) − 1)` towards the corner), but drops
/// the nodes of valleys narrower than twice the offset. Measured on medeiros-jacksboro with a
/// 700 m level (host test `terrain_plan`, 90 random queries at 750/700/900 m): 1 m routes
/// 24/14/21 of them, 60 m only 21/7/20, though 60 m shortens the P → Q route before
/// post-processing from 29.2 to 27.9 km.
pub const DEFAULT_NODE_MARGIN_M: f64 = 1.0;

/// Why a network could not be built.
#[derive(Debug)]
pub enum BuildError {
    /// The scenario lacks what the mode needs: (scenario file, field).
    Missing(String, &'static str),
    /// The scenario's mode is not built yet.
    UnsupportedMode(String, Mode),
    /// The DEM could not be read.
    Dem(crate::dem::DemError),
    /// The terrain graph could not be built: (scenario file, why).
    Terrain(String, crate::terrain::TerrainError),
    /// The landmark network could not be built.
    Landmark(crate::landmark::LandmarkError),
    /// The scenario's digests could not be computed (its DEM could not be read).
    Provenance(String),
    /// Terrain mode: the scenario has a no-fly zone or threat, which terrain networks cannot
    /// hold: (scenario file, the feature's label).
    ZoneInTerrain(String, String),
    /// Voronoi mode: the threats cannot be built into a diagram: (scenario file, why).
    Voronoi(String, String),
    /// Roadmap mode: the pop-ups' bypass alternatives could not be planned or stored:
    /// (scenario file, why).
    Alternatives(String, String),
    /// A three-dimensional scenario (`planner.altitude_min_m`, `planner.altitude_max_m`) taken
    /// as another mode than a roadmap (`--mode`), which would ignore its heights: (scenario
    /// file, the mode).
    NotRoadmap3d(String, Mode),
    /// Out of the builder's limits ([`crate::build_limits`]), no vertices, or refused by the
    /// writer.
    Limit(crate::build_limits::LimitError),
}

impl From<crate::build_limits::LimitError> for BuildError {
    fn from(e: crate::build_limits::LimitError) -> Self {
        BuildError::Limit(e)
    }
}

impl fmt::Display for BuildError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            BuildError::Missing(file, field) => {
                write!(f, "{file}: {field}: required for this mode")
            }
            BuildError::UnsupportedMode(file, mode) => write!(
                f,
                "{file}: planner.mode: {mode:?} networks are not built yet"
            ),
            BuildError::Dem(e) => write!(f, "{e}"),
            BuildError::Terrain(file, e) => write!(f, "{file}: terrain: {e}"),
            BuildError::Landmark(e) => write!(f, "{e}"),
            BuildError::Provenance(e) => write!(f, "{e}"),
            BuildError::ZoneInTerrain(file, what) => write!(
                f,
                "{file}: {what}: terrain networks hold no no-fly zones or threats, and a \
                 network that left it out would fly through it; remove it from the scenario or \
                 give it as a `popup` feature"
            ),
            BuildError::Voronoi(file, why) | BuildError::Alternatives(file, why) => {
                write!(f, "{file}: {why}")
            }
            BuildError::NotRoadmap3d(file, mode) => write!(
                f,
                "{file}: planner.altitude_min_m: the scenario is a three-dimensional roadmap \
                 and cannot be built as a {} network, which would ignore its heights and \
                 altitudes",
                mode.as_str()
            ),
            BuildError::Limit(e) => write!(f, "{e}"),
        }
    }
}

impl std::error::Error for BuildError {}

/// A built network and what it took.
#[derive(Clone, Debug)]
pub struct Built {
    /// The encoded network.
    pub bytes: Vec<u8>,
    /// The frame it is expressed in.
    pub frame: LocalFrame,
    /// Roadmap mode: the roadmap and its statistics.
    pub roadmap: Option<Roadmap>,
    /// Terrain mode: the grid and visibility graph and their statistics.
    pub terrain: Option<TerrainGraph>,
    /// Landmark mode: the landmark network and its statistics.
    pub landmark: Option<Box<LandmarkNetwork>>,
    /// Voronoi mode: the threats, the graph and its box.
    pub voronoi: Option<crate::voronoi::VoronoiNetwork>,
    /// The obstacles in the local frame.
    pub obstacles: Vec<ObstacleSpec>,
}

/// Builds the scenario's network. The ground tool's per-mode seam: the scenario's
/// [`Mode`] picks the builder here, and `skyroute plan` picks the planner by the same mode.
pub fn build(
    s: &Scenario,
    options: &BuildOptions,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<Built, BuildError> {
    let provenance = crate::provenance::scenario_items(s)
        .map(|items| crate::provenance::records(&items))
        .map_err(|e| BuildError::Provenance(e.to_string()))?;
    if s.vertical().is_some() && s.planner.mode != Mode::Roadmap {
        return Err(BuildError::NotRoadmap3d(
            s.path.display().to_string(),
            s.planner.mode,
        ));
    }
    match s.planner.mode {
        Mode::Roadmap => build_roadmap_network(s, options, progress, provenance),
        Mode::Terrain => build_terrain(s, options, provenance),
        Mode::Landmark => build_landmark(s, options, progress, provenance),
        Mode::Voronoi => build_voronoi(s, options, provenance),
    }
}

/// Roadmap mode: the sampled Dubins roadmap ([`crate::roadmap`]) over the bounding box of the
/// scenario's positions; three-dimensional ([`crate::roadmap::vertical`]) when the scenario is.
fn build_roadmap_network(
    s: &Scenario,
    options: &BuildOptions,
    progress: &(dyn Fn(usize, usize) + Sync),
    provenance: Vec<ProvenanceRecord>,
) -> Result<Built, BuildError> {
    let file = s.path.display().to_string();
    let p = &s.planner;
    let need = |v: Option<f64>, field: &'static str| {
        v.ok_or_else(|| BuildError::Missing(file.clone(), field))
    };
    let turn_radius = s.vehicle.turn_radius_m() as f32;
    let spacing = match options.sample_spacing_m {
        Some(v) => (v as f64, "--sample-spacing"),
        None => (
            need(p.sample_spacing_m, "planner.sample_spacing_m")?,
            "planner.sample_spacing_m",
        ),
    };
    let radius = match options.neighbour_radius_m {
        Some(v) => (v as f64, "--neighbour-radius"),
        None => (
            need(p.neighbour_radius_m, "planner.neighbour_radius_m")?,
            "planner.neighbour_radius_m",
        ),
    };
    let params = RoadmapParams {
        turn_radius_m: turn_radius,
        sample_spacing_m: spacing.0 as f32,
        neighbour_radius_m: radius.0 as f32,
        k_nearest_fallback: p.k_nearest_fallback.unwrap_or(8) as usize,
        allow_ccc: p.allow_ccc.unwrap_or(true),
        clearance_m: p.clearance_m.unwrap_or(0.0) as f32,
        seed: p.seed.unwrap_or(1),
        check: match options.discretised {
            Some(sagitta) => CollisionCheck::Discretised {
                arc_step_m: need(p.arc_step_m, "planner.arc_step_m")? as f32,
                sagitta,
            },
            None => CollisionCheck::Exact,
        },
    };
    let frame = s.local_frame();
    let obstacles = local_obstacles(s, &frame);
    let (lo, hi) = skyroute::geometry::points_bounding_box(
        s.positions().map(|(lon, lat)| local(&frame, lon, lat)),
    );
    check_area(&file, lo, hi)?;
    check_sampling(&file, lo, hi, spacing, radius)?;
    let grid_cell = options.grid_cell_m.unwrap_or(2.0 * turn_radius);
    let grid_field = if options.grid_cell_m.is_some() {
        "--grid-cell"
    } else {
        "vehicle.v_nominal_mps and vehicle.a_lat_max_mps2 (the default grid cell is twice the \
         turn radius v_nominal_mps² / a_lat_max_mps2)"
    };
    // The vertices lie in [lo, hi]: the writer's grid has at most these cells.
    check_grid(
        &file,
        grid_field,
        grid_cell,
        (lo, hi),
        4.0 * turn_radius + grid_cell,
    )?;
    let vertical = crate::roadmap::vertical::vertical_input(s, &frame);
    let input = RoadmapInput {
        area_min: lo,
        area_max: hi,
        obstacles: obstacles.clone(),
        fixed_vertices: Vec::new(),
    };
    let roadmap = build_roadmap_with(&input, &params, vertical.as_ref(), progress);
    let (origin_lat, origin_lon) = frame.origin();
    let spec = NetworkSpec {
        origin_lat_deg: origin_lat,
        origin_lon_deg: origin_lon,
        turn_radius_m: turn_radius,
        clearance_m: params.clearance_m,
        vertices: roadmap.vertices.clone(),
        edges: roadmap.edges.clone(),
        obstacles: obstacles.clone(),
        grid_cell_m: grid_cell,
        landmark: None,
        terrain: None,
        voronoi: None,
        provenance,
    };
    let why = "every sample lies within planner.clearance_m of a no-fly zone or threat";
    let vertical_spec = vertical.map(|v| VerticalSpec {
        limits: v.limits,
        altitudes: roadmap.altitudes.clone(),
        heights: v.heights,
    });
    let mut bytes = encode_checked(&spec, vertical_spec.as_ref(), &file, grid_field, why)?;
    // The stored bypass alternatives go round each pop-up's disc in the plane; a
    // three-dimensional roadmap stores none (`plan` applies the pop-ups with their heights).
    if !s.popups.is_empty() && vertical_spec.is_none() {
        bytes = crate::ruz::stored::with_alternatives(s, &frame, &spec, &bytes)
            .map_err(|e| BuildError::Alternatives(file.clone(), e))?;
    }
    Ok(Built {
        bytes,
        frame,
        roadmap: Some(roadmap),
        terrain: None,
        landmark: None,
        voronoi: None,
        obstacles,
    })
}

/// Terrain mode: the visibility graph over the scenario's DEM at its altitude
/// ([`crate::terrain`]), encoded with the elevation table so that the aircraft can change
/// altitude in flight.
fn build_terrain(
    s: &Scenario,
    options: &BuildOptions,
    provenance: Vec<ProvenanceRecord>,
) -> Result<Built, BuildError> {
    let file = s.path.display().to_string();
    let t = s
        .terrain
        .as_ref()
        .ok_or_else(|| BuildError::Missing(file.clone(), "terrain"))?;
    let zone = s
        .no_fly
        .first()
        .map(|z| format!("no-fly zone {:?}", z.name));
    if let Some(what) = zone.or_else(|| s.threats.first().map(|t| format!("threat {:?}", t.name))) {
        return Err(BuildError::ZoneInTerrain(file, what));
    }
    let dem = crate::dem::load(&t.dem).map_err(BuildError::Dem)?;
    if dem.max().is_none() {
        // The DEM is at fault, not the scenario: the message names the DEM's file.
        return Err(BuildError::Terrain(
            t.dem.display().to_string(),
            crate::terrain::TerrainError::InvalidParameter(
                "every cell is NODATA: the DEM has no elevation".into(),
            ),
        ));
    }
    let frame = s.local_frame();
    let clearance = s.planner.clearance_m.unwrap_or(0.0);
    let params = TerrainParams {
        min_node_spacing_m: options.node_spacing_m.unwrap_or(0.0),
        max_edge_m: options.max_edge_m,
        node_margin_m: options.node_margin_m.unwrap_or(DEFAULT_NODE_MARGIN_M),
        extra_altitudes_m: options.extra_altitudes_m.clone(),
        ..TerrainParams::default()
    };
    let graph = build_terrain_graph(
        &dem,
        &frame,
        t.altitude_m,
        t.safety_height_m,
        clearance,
        s.vehicle.wingspan_m,
        &params,
    )
    .map_err(|e| BuildError::Terrain(file.clone(), e))?;
    let (origin_lat, origin_lon) = frame.origin();
    let spec = NetworkSpec {
        origin_lat_deg: origin_lat,
        origin_lon_deg: origin_lon,
        turn_radius_m: s.vehicle.turn_radius_m() as f32,
        clearance_m: clearance as f32,
        vertices: graph
            .nodes
            .iter()
            .map(|&p| Pose {
                position: p,
                heading: 0.0,
            })
            .collect(),
        edges: graph
            .edges
            .iter()
            .map(|&(a, b, len)| EdgeSpec::line(a, b, len))
            .collect(),
        obstacles: Vec::new(),
        grid_cell_m: options.grid_cell_m.unwrap_or(4000.0),
        landmark: None,
        voronoi: None,
        terrain: Some(TerrainSpec {
            grid: graph.grid,
            coding: graph.coding,
            codes: graph.codes.clone(),
            widen_m: graph.widen_m,
            altitude_m: t.altitude_m as f32,
            safety_height_m: t.safety_height_m as f32,
        }),
        provenance,
    };
    let grid_field = if options.grid_cell_m.is_some() {
        "--grid-cell"
    } else {
        "terrain.dem (its extent, in the default grid cell of 4000 m)"
    };
    let why = "no corner of terrain blocked at terrain.altitude_m or an --altitude-levels level \
               gives a node";
    let bytes = encode_checked(&spec, None, &file, grid_field, why)?;
    Ok(Built {
        bytes,
        frame,
        roadmap: None,
        terrain: Some(graph),
        landmark: None,
        voronoi: None,
        obstacles: Vec::new(),
    })
}

/// The pop-up grid's cell of the landmark and Voronoi modes (`--grid-cell`, default 2 km), and
/// the field an error about its size names.
fn grid_cell_2km(options: &BuildOptions) -> (f32, &'static str) {
    match options.grid_cell_m {
        Some(cell) => (cell, "--grid-cell"),
        None => (
            2000.0,
            "geometry.coordinates (their extent, in the default grid cell of 2000 m)",
        ),
    }
}

/// Voronoi mode: the Voronoi graph of the scenario's threats over the mission box
/// ([`crate::voronoi`]), with the no-fly polygons and the spline corner table. Default grid
/// cell: 2 km.
fn build_voronoi(
    s: &Scenario,
    options: &BuildOptions,
    provenance: Vec<ProvenanceRecord>,
) -> Result<Built, BuildError> {
    let file = s.path.display().to_string();
    let frame = s.local_frame();
    let (cell, grid_field) = grid_cell_2km(options);
    let bounds =
        crate::voronoi::mission_box(s.positions().map(|(lon, lat)| local(&frame, lon, lat)));
    check_area(&file, bounds.min, bounds.max)?;
    check_grid(&file, grid_field, cell, (bounds.min, bounds.max), cell)?;
    let (net, mut spec) = crate::voronoi::voronoi_network(s, &frame, cell)
        .map_err(|why| BuildError::Voronoi(file.clone(), why))?;
    spec.provenance = provenance;
    let why = "the Voronoi graph has no vertices";
    let bytes = encode_checked(&spec, None, &file, grid_field, why)?;
    Ok(Built {
        bytes,
        frame,
        roadmap: None,
        terrain: None,
        landmark: None,
        obstacles: spec.obstacles.clone(),
        voronoi: Some(net),
    })
}

/// Landmark mode: the landmark shortest-path network ([`crate::landmark`]) encoded with its
/// rosettes and chains (`docs/FORMAT.md`, landmark mode). The start and the goal each need one
/// heading (a free-heading endpoint has one line element per direction, which one vertex
/// cannot stand for). Default grid cell: 2 km.
fn build_landmark(
    s: &Scenario,
    options: &BuildOptions,
    progress: &(dyn Fn(usize, usize) + Sync),
    provenance: Vec<ProvenanceRecord>,
) -> Result<Built, BuildError> {
    let file = s.path.display().to_string();
    let (cell, grid_field) = grid_cell_2km(options);
    let (lo, hi) = landmark_box(s);
    check_area(&file, lo, hi)?;
    // The grid covers about the landmarks and endpoints grown by a cell, and more: refused
    // here before the build, what fits is checked exactly by the writer.
    check_grid(&file, grid_field, cell, (lo, hi), cell)?;
    let net = build_landmark_network_with(s, options.landmark_ranges, progress)
        .map_err(BuildError::Landmark)?;
    let frame = net.frame.unwrap_or_else(|| s.local_frame());
    let mut spec = landmark_spec(&net, cell, &frame)
        .map_err(|field| BuildError::Missing(file.clone(), field))?;
    spec.provenance = provenance;
    let why = "the scenario has no landmarks, start or goal";
    let bytes = encode_checked(&spec, None, &file, grid_field, why)?;
    Ok(Built {
        bytes,
        frame,
        roadmap: None,
        terrain: None,
        obstacles: net.obstacles.clone(),
        landmark: Some(Box::new(net)),
        voronoi: None,
    })
}

/// The writer's spec of a landmark network: overflights, then the start, then the goal.
/// `Err` names what is missing (an endpoint with a single heading).
pub fn landmark_spec(
    net: &LandmarkNetwork,
    grid_cell_m: f32,
    frame: &LocalFrame,
) -> Result<NetworkSpec, &'static str> {
    let d = net.directions;
    let mut vertices: Vec<Pose> = net.vertices.iter().map(|v| v.pose).collect();
    let mut edges = Vec::new();
    let mut chains = Vec::new();
    for e in &net.edges {
        edges.push(EdgeSpec::chain(e.source, e.target, e.chain.cost));
        chains.push(e.chain.elements.clone());
    }
    let single = |links: &crate::landmark::EndpointLinks| -> Result<Pose, &'static str> {
        match links.elements.as_slice() {
            [el] => Ok(Pose {
                position: el.position,
                heading: el.velocity.angle(),
            }),
            _ => Err("heading_deg of the start and goal (landmark networks need one each)"),
        }
    };
    let mut start_vertex = None;
    let mut start_range_m = 0.0;
    if let Some(st) = &net.start {
        let v = vertices.len() as u32;
        vertices.push(single(st)?);
        start_vertex = Some(v);
        start_range_m = st.site.dist_m.unwrap_or(0.0);
        for e in &st.edges {
            edges.push(EdgeSpec::chain(v, e.vertex, e.chain.cost));
            chains.push(e.chain.elements.clone());
        }
    }
    let mut goal_vertex = None;
    if let Some(g) = &net.goal {
        let v = vertices.len() as u32;
        vertices.push(single(g)?);
        goal_vertex = Some(v);
        for e in &g.edges {
            edges.push(EdgeSpec::chain(e.vertex, v, e.chain.cost));
            chains.push(e.chain.elements.clone());
        }
    }
    let mut qualities = Vec::new();
    for site in &net.landmarks {
        for r in &site.rosettes {
            for k in 0..d {
                qualities.push(r.quality.get(k).copied().unwrap_or(0.0));
            }
        }
    }
    let (origin_lat, origin_lon) = frame.origin();
    let v = net.v_nominal;
    Ok(NetworkSpec {
        origin_lat_deg: origin_lat,
        origin_lon_deg: origin_lon,
        turn_radius_m: v * v / net.limits.a_lat_max.max(f32::MIN_POSITIVE),
        clearance_m: net.clearance_m,
        vertices,
        edges,
        obstacles: net.obstacles.clone(),
        grid_cell_m,
        terrain: None,
        voronoi: None,
        landmark: Some(LandmarkSpec {
            directions: d as u32,
            weather_count: net.weather.len() as u32,
            v_nominal: v,
            limits: net.limits,
            landmarks: net
                .landmarks
                .iter()
                .map(|l| LandmarkSiteSpec {
                    position: l.position,
                    d_max_m: l.d_max_m,
                })
                .collect(),
            qualities,
            start_vertex,
            goal_vertex,
            start_range_m,
            chains,
        }),
        provenance: Vec::new(),
    })
}
