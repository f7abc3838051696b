//! The onboard core (`skyroute`) against independent references: geometry, predicates, grid
//! traversal, trig, the network loader and the planner. One test binary; the fixtures (RNG,
//! f64 reference geometry, synthetic worlds, tiers) are in `host_tests` (`host-tests/src`).
//! Random counts come from `host_tests::cases` (`SKYROUTE_TIER`, see `docs/TESTING.md`).

/// Bad input to the loader and the planner API not covered elsewhere: an empty network, a
/// header claiming four billion vertices, positions beyond the limit, a zero budget, mode-only
/// calls on a roadmap, bad pop-ups, a pop-up over the start, a full pop-up table, unknown ids.
mod bad_input;
/// The image checksum (CRC-32) against `crc32fast`.
mod checksum;
/// Format v4's compact records: damaged cell lists, Dubins words and edge costs each refused
/// by name; the end check far from the origin; the in-flight checksum pass.
mod compact_records;
/// The collision tests and Dubins solves of the start and goal links, counted exactly.
mod connect_work;
/// The pop-up decision (Ruz et al.) against a brute force over every combination.
mod decision;
/// A start inside an obstacle or pop-up: the exit against a marching f64 reference.
mod drift_exit;
/// Dubins paths against OMPL's CSV and an f64 brute force.
mod dubins;
/// Terrain elevation codes: decoding, rounding up and the blocking code against a scan over
/// every code; a bad coding, widening, altitude or safety height refused at load.
mod elevation_coding;
/// `skyroute::geo` (WGS-84 to the local frame) against PROJ's CSV; its refusals by name.
mod geo;
/// `geometry::grid` traversals against sampled and exact f64 references.
mod grid_traversal;
/// The loader's header checks: each parameter refused by name, each limit tried on both
/// sides; the grid's reach beyond the vertices; a negative edge cost.
mod header_validation;
/// Quintic Hermite segments against f64 derivations.
mod hermite;
/// The loader's error messages: each names its numbers, none reads like another.
mod load_messages;
/// The loader: round trips, each damage its own error, random mutations never panic.
mod network_load;
/// The loader's obstacle checks: each bad obstacle record refused with its own error.
mod obstacle_validation;
/// An endpoint's obstacle window keeps the 32 nearest obstacles in any listing order.
mod obstacle_window;
/// The loader's offset-table checks: first 0, never decreasing, last the total.
mod offset_tables;
/// The planner's and the pop-up table's error messages: each names its numbers, none
/// reads like another.
mod plan_messages;
/// The planner against Bellman–Ford, an edge scan for pop-ups and the work bound.
mod planner;
/// The pop-up grid search: neighbouring cells within the clearance, an f64 brute force, the
/// predicate tests a listed edge costs.
mod popup_grid_search;
/// Pop-up shapes: the radius limit, simple polygons of any vertex count.
mod popup_validation;
/// Collision predicates against sampling and exact rational references.
mod predicates;
/// The radar risk model (Ruz et al.) against a direct f64 evaluation.
mod risk;
/// Bad input and budgets: over-budget reports, overlapping records, huge pop-ups, non-finite
/// routes, degenerate capacities and random extreme call sequences never panic.
mod robustness;
/// The roadmap search's heap levels, relaxations and goal-link resolutions counted exactly by
/// an independent Dijkstra and A*.
mod search_work;
/// Cubic spline smoothing: the corner table and the fit against dense f64 sampling.
mod spline;
/// The pop-up alternatives stored in a network image and the onboard switch (Ruz et al.):
/// read back, refused by name, decided as a brute force, flown round their discs.
mod stored_alternatives;
/// The core's f32 sine and cosine against f64.
mod trig;
/// A three-dimensional roadmap's vertical section: written and read back, bad limits,
/// altitudes and heights refused by name, an edge's climb at the limits' boundary.
mod vertical_network;
/// Planning on a three-dimensional roadmap: a low wall flown over where a planar roadmap
/// goes round, checked by f64 sampling in 3-D; endpoints above or inside a building.
mod vertical_planning;
/// Pop-ups with heights on a three-dimensional roadmap: the edges they block against an f64
/// sampling in 3-D, routes over low ones and round tall ones, endpoints above them.
mod vertical_popups;
/// The vertical profile of Niendorf et al.'s aircraft: the limits, an LP reference, the span
/// below a ceiling against an f64 profile, and buildings of finite height against sampling.
mod vertical_profile;
/// The Voronoi diagram of threat sites against an exact brute force, SciPy's CSV and closed
/// forms for degenerate inputs; its work bound and the clipped graph's shape.
mod voronoi;
/// Judd & McLain's three-point exposure rule against an adaptive f64 integral.
mod voronoi_exposure;
/// The loader's checks of a Voronoi network's record, threat sites, corner table and edges.
mod voronoi_record;
/// Counted work never below independently recomputed lower bounds.
mod work_lower_bounds;
