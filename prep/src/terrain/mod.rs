//! Terrain mode (Medeiros & da Silva): the DEM's blocked cells as a metric occupancy grid
//! in the scenario's local frame, and a visibility graph around them.
//!
//! An aircraft flying at altitude `a_n` that must keep the safety height `a_s` above the ground
//! may not fly over a DEM cell whose elevation is `≥ a_n − a_s`; NODATA cells and everything
//! outside the DEM count as blocked too ([`Dem::is_navigable`]). [`build_terrain_graph`] turns
//! that into a [`TerrainGraph`] in three steps.
//!
//! # 1. The metric grid
//!
//! A geographic DEM's cells are not squares in metres (3″ at 36.5° N: about 74.6 m east–west by
//! 92.6 m north–south), and in the transverse Mercator frame ([`LocalFrame`]) they are not even
//! axis-aligned: grid north differs from true north by the meridian convergence
//! γ ≈ Δλ·sin φ, and the metres per degree of longitude change with latitude. Neither is assumed
//! away. Instead a [`CellGrid`] of square cells is laid over the frame and each metric cell is
//! mapped *back* onto the DEM:
//!
//! * **Cell size**: [`TerrainParams::cell_m`], by default the smallest metric side of a DEM
//!   cell at the DEM's four corners and centre (the east–west side at the northern edge; within
//!   the projection's scale error `k − 1 ≤ 1e-5` of the smallest anywhere), as an `f32`.
//! * **Extent**: the bounding box of the DEM's outline projected into the frame (every corner
//!   along the outline), widened by 1 m; the origin is rounded down to whole metres.
//! * **Elevation and blocked cells**: every grid vertex is mapped to `(lon, lat)` with
//!   [`LocalFrame::to_geo`]. A metric cell's footprint on the ellipsoid is the quadrilateral of
//!   its four mapped corners (the edges are not exactly straight in `(lon, lat)`, see below);
//!   its longitude/latitude bounding box, widened by a pad, is intersected with the DEM's cells
//!   as *closed* rectangles (touching counts). The metric cell's elevation is the highest
//!   elevation of the DEM cells it meets, encoded rounding **up** into one byte
//!   ([`ElevationCoding`], base the DEM's lowest metre, 254 steps to its highest: 3.3 m on the
//!   Jacksboro DEM); a box reaching outside the DEM, or meeting a NODATA cell, gets
//!   [`ELEVATION_BLOCKED`]. A cell is blocked at an altitude when its code is at least the
//!   altitude's blocking code — the very table and test the aircraft uses, so ground and air
//!   agree cell for cell. So the union of the blocked metric cells contains the footprint of
//!   every blocked DEM cell: **conservative**, never optimistic. The price is that blocked
//!   regions grow by up to about one metric cell plus one DEM cell (the box of a cell rotated
//!   by γ is a little larger than the cell, and a DEM cell is blocked whole), and cells within
//!   one step (3.3 m) below the threshold count as blocked.
//! * **Error of the footprint**: the only approximation is the straight-edged quadrilateral
//!   (and its bounding box) standing for the image of a straight metric edge, which bows in
//!   `(lon, lat)`. The bow is measured on every edge along the grid's outline (the largest
//!   distance from the central meridian, and the extreme latitudes) as the distance between
//!   the mapped midpoint of an edge and the midpoint of its mapped ends, in metres; over a
//!   30 km DEM it is a fraction of a millimetre ([`TerrainStats::edge_bow_m`]). The box is
//!   widened by `pad = 2·bow + 1 cm` ([`TerrainStats::pad_m`]), converted to degrees with the
//!   smallest metres per degree on the DEM, so it needs no addition to the safety margin.
//! * **For comparison** ([`TerrainStats::axis_aligned_offset_m`]): had the DEM been taken as an
//!   axis-aligned grid in the frame (metres per degree fixed at the DEM's centre, no rotation),
//!   its corners would be off by that much — 48 m at the corners of the Jacksboro DEM, from
//!   the meridian convergence changing by about ±0.1° across it and the metres per degree of
//!   longitude by about ±0.2 % (roughly 28 m each): over half a cell, not negligible, hence
//!   the back-mapping, whose own error is the sub-millimetre bow, covered by the pad.
//! * **Other DEMs** ([`crate::dem`]): the same holds for any north-up DEM the frame can be
//!   reached from, through [`crate::dem::Placement`]. A geographic DEM's cells may be
//!   non-square in degrees (`cell_x ≠ cell_y`, Copernicus GLO-30 north of 50°): the DEM-cell
//!   ranges use each axis's side, and the metric cell is the smallest metric side of either. A
//!   UTM DEM (GeoTIFF) is mapped the same way, its easting/northing to `(lon, lat)` by the
//!   zone's inverse transverse Mercator (exact to nanometres) and on into the frame; the bow and
//!   the pad are then measured in the DEM's metres. So no DEM is resampled or interpolated:
//!   each metric cell takes the highest elevation of every DEM cell its footprint meets,
//!   whatever the DEM's coordinates.
//!
//! # 2. Nodes at the corners of the blocked regions
//!
//! The paper places the visibility graph's nodes at the safety distance from the corners of the
//! obstacle regions. Here the regions are unions of closed grid squares, and only their
//! **convex** corners get a node: grid vertices where exactly one of the four cells around is
//! blocked (cells outside the grid counting as blocked). Concave corners need none — a shortest
//! path among obstacles bends only at convex vertices (Lozano-Pérez & Wesley 1979).
//!
//! With `widen = wingspan/2 + clearance` the half-width every edge must keep free, the node of a
//! convex corner `V` whose blocked cell lies in the quadrant `s = (±1, ±1)` is
//! `V − s·d` with `d = widen + node_margin`: offset by `d` along **both** axes, i.e. the corner
//! of the blocked region grown by `d` in the max-norm (a mitred offset polygon), `d·√2` from `V`
//! along the outward diagonal. Why not the clearance along the diagonal, as a literal reading
//! of "nodes at the safety distance from the corners" would give: such a node lies within
//! `widen` of its own corner and would be dropped by the check below; and two nodes off the two
//! ends of a straight side of a region must see each other, but the segment between them runs
//! parallel to the side at the nodes' *axis* offset, which must therefore be at least `widen`.
//! The margin (default 1 m) keeps those side-parallel edges clear of rounding: the traversal
//! visits cells up to `3δ` cells beyond `widen` (`skyroute::geometry::grid`), about 0.2 m on a
//! grid of 430 cells across, growing with the grid's size. The turn radius plays no part: the
//! graph is one of straight legs; a smoother that rounds its corners with arcs must check the
//! arcs again (`skyroute::geometry::grid::arc_cells`) — the fillet of a turn around a region
//! lies on the region's side of the corner.
//!
//! A node is dropped if its disc of radius `widen` is not inside the grid ([`CellGrid::covers`])
//! or meets a blocked cell ([`segment_cells`] on the zero-length segment, which visits every
//! cell within `widen` of the point). Then, if [`TerrainParams::min_node_spacing_m`] is
//! positive, nodes are thinned greedily in generation order (grid vertices row by row from the
//! south, west to east): a node within that distance of an already kept one is dropped. (The
//! raster's staircases along oblique boundaries make many corners close together; thinning
//! trades a little path length for a smaller graph. Off by default.) The nodes are finally
//! sorted by `(x, y)`, exact duplicates removed.
//!
//! With [`TerrainParams::extra_altitudes_m`], the corners of the blocked regions at each further
//! altitude get nodes too (tagged with their level), so that an aircraft that descends in flight
//! still finds nodes around the larger regions.
//!
//! # 3. Edges
//!
//! Every pair of nodes of the same level at most [`TerrainParams::max_edge_m`] apart (all pairs
//! for `None`, the default: the paper's visibility graph) is joined if the straight segment's capsule of radius `widen` meets no cell
//! blocked at that level's altitude ([`segment_cells`], stopping at the first blocked cell).
//! Since both nodes' discs lie inside the grid, so does the capsule.
//!
//! **Reduced visibility graph** ([`TerrainParams::tangent_edges_only`], on by default): a
//! shortest path among obstacles bends only at a convex vertex it wraps around, so it uses an
//! edge only if the edge's line is *tangent* to the obstacle at both ends — it does not enter
//! the obstacle on either side of the node (the classical reduced visibility graph, e.g.
//! LaValle, *Planning Algorithms* §6.2.4). At a node the grown region is the quadrant `s` of its
//! corner's blocked cell, and the line in direction `u` stays out of it iff
//! `(s_x u_x)(s_y u_y) ≤ 0`. On Jacksboro at 750 m this keeps 32 222 of 75 486 directed edges,
//! the difference between a network that fits a flight computer's search state and one that
//! does not. (A route with turns of a minimum radius can
//! in principle need a non-tangent edge to gain room for a turn; the measured completeness is
//! in `docs/BENCHMARKS.md` and the README.)
//!
//! Pairs are tested in parallel (rayon) and collected in a fixed order, so the result does not
//! depend on the number of threads. Each accepted pair gives both directions, `(i, j, length)`
//! and `(j, i, length)`, sorted by `(from, to)`.

mod cells;
mod graph;
mod grid;
mod types;

pub use graph::build_terrain_graph;
pub use grid::{blocked_cells_at, elevation_coding};
pub use types::{TerrainError, TerrainGraph, TerrainParams, TerrainStats};
