//! The three network modes end to end, through the ground tool's library (`skyroute_prep`) and
//! the core: roadmap build and clearance, missions, the DEM reader, terrain graphs and search,
//! landmark networks and plans, and the byte-identical images of every scenario. One test
//! binary; scenario networks are built once per process (`host_tests::scenarios`), and the
//! tests that build whole Babel networks or full-size networks repeatedly run only in the full
//! tier (`SKYROUTE_TIER=full`, see `docs/TESTING.md`).

/// Format v4 on the papers' scenarios: the flash goals, and edges read back bit for bit.
mod compact_format;
/// The ESRI ASCII reader on the real Jacksboro DEM.
mod dem;
/// Landmark networks (Babel): counts, every edge in f64, thread independence.
mod landmark_build;
/// Babel's figure 4: greedy and best-guess chains fail, the network succeeds.
mod landmark_figure4;
/// Landmark images as bad input, and bad onboard landmark calls.
mod landmark_load;
/// Landmark mode's online start against a brute force, with the range left and pop-ups.
mod landmark_online;
/// Landmark mode end to end: plans in every weather, rosette updates, pop-ups.
mod landmark_plan;
/// A landmark pop-up's predicate tests: chords per rebuilt piece times the shape's tests; a
/// piece straying beyond its chord's box still rebuilt.
mod landmark_popup_work;
/// The landmark tables field by field on a small written network: each read back, each damage
/// refused by its own check.
mod landmark_tables;
/// Missions: inevitable-collision states by name.
mod mission;
/// Every scenario's network image against the recorded length and CRC-32.
mod network_images;
/// The three-dimensional urban mission: clear of every building's prism by f64 sampling, over
/// low buildings, shorter than with every building a wall.
mod niendorf_3d;
/// The niendorf-urban network and route keep clearance from every building (from JSON).
mod niendorf_clearance;
/// Planning in slices (`start_plan` + `step`) against one `plan` call, in every mode.
mod plan_slices;
/// Independent raw-DEM lookups for the terrain tests.
mod raw_dem;
/// The roadmap builder on niendorf-urban: threads, parameters, both collision checks.
mod roadmap_build;
/// Terrain search corner cases on small synthetic networks: degenerate fillets, zero-length
/// edges, nodes at the start or goal, work bounds, ignored sections.
mod terrain_corner_cases;
/// The terrain visibility graph on Jacksboro against the raw DEM.
mod terrain_graph;
/// Terrain mode end to end on Jacksboro against the raw DEM.
mod terrain_plan;
/// The terrain search against an exhaustive walk enumeration.
mod terrain_search;
/// Voronoi mode (Judd & McLain) end to end: the onboard graph, an f64 Dijkstra, flyable
/// smoothed routes, the weight's effect, pop-up threats.
mod voronoi_plan;
/// Voronoi mode's refusals: a goal heading no lead-out reaches, a lead-out across a no-fly
/// zone, a pop-up on a lead-in line, a route of more coarse legs than chords.
mod voronoi_refusals;
/// Voronoi mode's route as written out: chords within their tolerance of the smoothed
/// pieces, a blocked direct segment, a start and goal out of the graph's reach.
mod voronoi_route;
/// Voronoi mode's threat storage: the stored graph checked at load against the sites'
/// diagram, threats added on the box and beyond it, and bad threat calls.
mod voronoi_threats;
