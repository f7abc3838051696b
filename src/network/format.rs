//! The records of network format v4 (specified in `docs/FORMAT.md`).
//!
//! Every record is serialized with postcard using fixed-width little-endian integers
//! (`postcard::fixint::le`), `f32`/`f64` as their IEEE-754 bits and `u8` as one byte, so each
//! record kind has a fixed encoded size and record `i` of a section starts at
//! `section_start + i · SIZE`. That lets the onboard loader read any record where it lies in
//! flash, without copying the network into RAM.

use serde::{Deserialize, Serialize};

/// The four bytes every network starts with.
pub const MAGIC: [u8; 4] = *b"SKYR";

/// The format version this crate reads and writes. Older images are refused by
/// [`LoadError::UnsupportedVersion`](crate::LoadError::UnsupportedVersion): version 3 (which
/// stored every edge's geometry, its source, a 32-bit grid entry per (cell, edge) and every
/// chain's line elements in full) and version 2 (whose checksum left the header uncovered).
pub const FORMAT_VERSION: u16 = 4;

/// The most vertices a network may have: edge targets are 16-bit indices.
pub const MAX_VERTICES: u32 = 1 << 16;

/// The most distinct line elements a landmark network may have: chains index them in 16 bits.
pub const MAX_LINE_ELEMENTS: u32 = 1 << 16;

/// Network mode: a multi-query Dubins roadmap (Niendorf et al.).
pub const MODE_ROADMAP: u8 = 0;
/// Network mode: a landmark shortest-path network (Babel 2014): vertices are landmark
/// overflights, edges chains of quintic Hermite pieces; the body ends with a
/// [`LandmarkRecord`] and the landmark tables (`docs/FORMAT.md`, landmark mode).
pub const MODE_LANDMARK: u8 = 1;
/// Network mode: a terrain visibility graph of straight edges over an elevation table
/// (Medeiros & da Silva); the body ends with a [`TerrainRecord`] and the table.
pub const MODE_TERRAIN: u8 = 2;
/// Network mode: a Voronoi graph of radar threat sites with exposure cost and curvature-bounded
/// spline smoothing (Judd & McLain); the body ends with a [`VoronoiRecord`], the threat sites
/// and the spline corner table. Its vertices and edges are the ground tool's Voronoi graph of
/// the sites, which the planner rebuilds onboard and checks against them.
pub const MODE_VORONOI: u8 = 3;

/// Obstacle kind code: a simple polygon.
pub const OBSTACLE_POLYGON: u8 = 0;
/// Obstacle kind code: a circle.
pub const OBSTACLE_CIRCLE: u8 = 1;

/// The fixed header in front of the body.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Header {
    /// [`MAGIC`].
    pub magic: [u8; 4],
    /// [`FORMAT_VERSION`].
    #[serde(with = "postcard::fixint::le")]
    pub version: u16,
    /// Network mode ([`MODE_ROADMAP`], [`MODE_LANDMARK`], [`MODE_TERRAIN`] or [`MODE_VORONOI`]).
    pub mode: u8,
    /// Reserved, zero.
    pub flags: u8,
    /// Latitude of the local frame's origin, degrees (WGS-84).
    pub origin_lat_deg: f64,
    /// Longitude of the local frame's origin, degrees (WGS-84).
    pub origin_lon_deg: f64,
    /// Turn radius of every Dubins edge, metres.
    pub turn_radius_m: f32,
    /// Clearance kept from obstacles, metres.
    pub clearance_m: f32,
    /// Number of vertices.
    #[serde(with = "postcard::fixint::le")]
    pub vertex_count: u32,
    /// Number of edges.
    #[serde(with = "postcard::fixint::le")]
    pub edge_count: u32,
    /// Number of static obstacles.
    #[serde(with = "postcard::fixint::le")]
    pub obstacle_count: u32,
    /// Number of polygon points over all obstacles.
    #[serde(with = "postcard::fixint::le")]
    pub obstacle_point_count: u32,
    /// West edge of the grid index, metres.
    pub grid_origin_x: f32,
    /// South edge of the grid index, metres.
    pub grid_origin_y: f32,
    /// Side of a grid cell, metres.
    pub grid_cell_m: f32,
    /// Grid cells along x.
    #[serde(with = "postcard::fixint::le")]
    pub grid_nx: u32,
    /// Grid cells along y.
    #[serde(with = "postcard::fixint::le")]
    pub grid_ny: u32,
    /// Bytes of the grid index's cell lists (each cell's edges delta-coded as varints).
    #[serde(with = "postcard::fixint::le")]
    pub grid_list_bytes: u32,
    /// Number of [`ProvenanceRecord`]s at the end of the body.
    #[serde(with = "postcard::fixint::le")]
    pub provenance_count: u32,
    /// Bytes in the body that follows the header.
    #[serde(with = "postcard::fixint::le")]
    pub body_len: u32,
    /// CRC-32 of the whole image but this field: the header's first
    /// [`Header::CHECKED_SIZE`] bytes, then the body.
    #[serde(with = "postcard::fixint::le")]
    pub image_crc: u32,
}

impl Header {
    /// Encoded size of the header.
    pub const SIZE: usize = 84;
    /// The header bytes the checksum covers: all of them but the checksum itself, which is
    /// the header's last field.
    pub const CHECKED_SIZE: usize = Self::SIZE - 4;
}

/// A digest of one thing the network was built from (a no-fly zone, the vehicle, a landmark,
/// the DEM, ...), so that the ground tool can tell whether a scenario still matches the
/// network before it plans with it. The records close the body, in the order they were
/// written. The core stores them and does not interpret them; `kind` codes are the ground
/// tool's (`prep/src/provenance.rs`, `docs/FORMAT.md`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct ProvenanceRecord {
    /// What the digest is of.
    pub kind: u8,
    /// The first 8 bytes of its SHA-256, little-endian.
    #[serde(with = "postcard::fixint::le")]
    pub digest: u64,
}

impl ProvenanceRecord {
    /// Encoded size.
    pub const SIZE: usize = 9;
}

/// A vertex: a pose.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct VertexRecord {
    /// East, metres.
    pub x: f32,
    /// North, metres.
    pub y: f32,
    /// Heading, radians counter-clockwise from east.
    pub heading: f32,
}

impl VertexRecord {
    /// Encoded size.
    pub const SIZE: usize = 12;
}

/// A `u32` (an offset or an index) as a fixed-width record.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct U32Record(#[serde(with = "postcard::fixint::le")] pub u32);

impl U32Record {
    /// Encoded size.
    pub const SIZE: usize = 4;
}

/// A directed edge. Its source is implied by the edge offsets (the edges of vertex `v` are
/// `offset[v] .. offset[v + 1]`), and its geometry by the network's mode and its end vertices:
/// a roadmap edge is the Dubins path of word `aux` between its ends' poses
/// ([`crate::DubinsPath::with_word`], the f32 code the ground tool built and checked it with),
/// a terrain or Voronoi edge the segment between its ends, a landmark edge its chain.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct EdgeRecord {
    /// Target vertex.
    #[serde(with = "postcard::fixint::le")]
    pub target: u16,
    /// Per mode: roadmap, the Dubins word's code ([`crate::DubinsWord::code`]); terrain, the
    /// highest elevation code of the cells within [`TerrainRecord::widen_m`] of the segment;
    /// landmark and Voronoi, 0.
    pub aux: u8,
    /// Cost of traversal (≥ 0): metres of flight for a roadmap, terrain or landmark edge (a
    /// landmark chain's length is its cost), the length-and-exposure cost of a Voronoi edge.
    pub cost: f32,
}

impl EdgeRecord {
    /// Encoded size.
    pub const SIZE: usize = 7;
}

/// Header flag: the body holds the pop-up alternatives section ([`AlternativesRecord`]) after
/// the mode's section (and the vertical section), before the provenance records.
pub const FLAG_POPUP_ALTERNATIVES: u8 = 1;

/// Header flag, roadmap mode only: the network is three-dimensional (Niendorf et al.'s Dubins
/// car with a vertical double integrator). The body holds the vertical section after the mode's
/// section: a [`VerticalRecord`], one [`F32Record`] altitude per vertex, then one
/// [`F32Record`] height per obstacle.
pub const FLAG_VERTICAL: u8 = 2;

/// The largest magnitude of a vertex altitude or a start or goal altitude, metres (100 km).
pub const MAX_ALTITUDE_M: f32 = 1e5;

/// The aircraft's vertical limits in a three-dimensional roadmap ([`FLAG_VERTICAL`]): every
/// edge's altitude change is a rest-to-rest move within them over the edge's length
/// ([`crate::geometry::vertical::VerticalProfile`]).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct VerticalRecord {
    /// Horizontal airspeed, m/s (finite, > 0).
    pub airspeed: f32,
    /// Largest climb or sink rate, m/s (finite, > 0).
    pub climb_rate: f32,
    /// Largest vertical acceleration, m/s² (finite, > 0).
    pub vertical_accel: f32,
}

impl VerticalRecord {
    /// Encoded size.
    pub const SIZE: usize = 12;
}

/// The most pop-ups the alternatives section stores (the decision's
/// [`MAX_DECISION_POPUPS`](crate::planner::decision::MAX_DECISION_POPUPS)).
pub const MAX_STORED_POPUPS: u32 = 8;

/// The most alternatives a stored pop-up has (the decision's
/// [`MAX_ALTERNATIVES`](crate::planner::decision::MAX_ALTERNATIVES)).
pub const MAX_STORED_ALTERNATIVES: u32 = 4;

/// The most blocking discs an alternative stores.
pub const MAX_BLOCKING_DISCS: u32 = 8;

/// The pop-up alternatives of Ruz et al.: for each potential pop-up threat, bypass routes the
/// ground tool planned around it and scored, from which the aircraft picks one per announced
/// pop-up (`crate::planner::alternatives`). Present when the header has
/// [`FLAG_POPUP_ALTERNATIVES`]; follows the mode's section. Then come `popup_count`
/// [`PopupRecord`]s, `alternative_count` [`AlternativeRecord`]s (pop-up by pop-up, in order)
/// and `disc_count` [`DiscRecord`]s (alternative by alternative, in order).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct AlternativesRecord {
    /// Pop-ups, 1 to [`MAX_STORED_POPUPS`].
    #[serde(with = "postcard::fixint::le")]
    pub popup_count: u32,
    /// Alternatives over all pop-ups.
    #[serde(with = "postcard::fixint::le")]
    pub alternative_count: u32,
    /// Blocking discs over all alternatives.
    #[serde(with = "postcard::fixint::le")]
    pub disc_count: u32,
    /// M of the nominal route (no pop-ups): the time factors' τ = M·Δt.
    #[serde(with = "postcard::fixint::le")]
    pub nominal_steps: u32,
    /// The mission's limit on the mean time factor, T_max.
    pub time_limit: f32,
    /// The mission's limit on the mean fuel factor, F_cmax.
    pub fuel_limit: f32,
}

impl AlternativesRecord {
    /// Encoded size.
    pub const SIZE: usize = 24;
}

/// A potential pop-up threat: its lethal disc and its prior appearance probability.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct PopupRecord {
    /// Centre east, metres.
    pub x: f32,
    /// Centre north, metres.
    pub y: f32,
    /// Radius of the disc every alternative keeps clear of (with the clearance), metres.
    pub radius: f32,
    /// P_A known on the ground, in [0, 1].
    pub probability: f32,
    /// Its alternatives, 1 to [`MAX_STORED_ALTERNATIVES`].
    #[serde(with = "postcard::fixint::le")]
    pub alternative_count: u32,
}

impl PopupRecord {
    /// Encoded size.
    pub const SIZE: usize = 20;
}

/// A bypass alternative: its risk, time and fuel figures (`crate::planner::risk`) and the
/// blocking discs that, with its pop-up's disc, make the planner fly it.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct AlternativeRecord {
    /// M, its steps of Δt (at least 1).
    #[serde(with = "postcard::fixint::le")]
    pub steps: u32,
    /// P_S,known: survival against the known radars, in [0, 1].
    pub survival_known: f32,
    /// P_S,PU: survival against its pop-up's radar alone, in [0, 1].
    pub survival_popup: f32,
    /// F_c, its fuel factor (finite, not negative).
    pub fuel: f32,
    /// Its length as planned on the ground, metres.
    pub length_m: f32,
    /// Its blocking discs, 0 to [`MAX_BLOCKING_DISCS`].
    #[serde(with = "postcard::fixint::le")]
    pub disc_count: u32,
}

impl AlternativeRecord {
    /// Encoded size.
    pub const SIZE: usize = 24;
}

/// A blocking disc of an alternative.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct DiscRecord {
    /// Centre east, metres.
    pub x: f32,
    /// Centre north, metres.
    pub y: f32,
    /// Radius, metres.
    pub radius: f32,
}

impl DiscRecord {
    /// Encoded size.
    pub const SIZE: usize = 12;
}

/// A static obstacle.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct ObstacleRecord {
    /// [`OBSTACLE_POLYGON`] or [`OBSTACLE_CIRCLE`].
    pub kind: u8,
    /// Polygon: index of its first point in the point section.
    #[serde(with = "postcard::fixint::le")]
    pub first_point: u32,
    /// Polygon: number of points (≥ 3).
    #[serde(with = "postcard::fixint::le")]
    pub point_count: u32,
    /// Circle: centre x, centre y, radius (metres); zero for a polygon.
    pub circle: [f32; 3],
    /// Bounding box: min x, min y, max x, max y.
    pub bbox: [f32; 4],
}

impl ObstacleRecord {
    /// Encoded size.
    pub const SIZE: usize = 37;
}

/// A polygon point.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct PointRecord {
    /// East, metres.
    pub x: f32,
    /// North, metres.
    pub y: f32,
}

impl PointRecord {
    /// Encoded size.
    pub const SIZE: usize = 8;
}

/// Terrain mode: the elevation table's grid and coding, after the cell entries. The table
/// follows: `cols · rows` bytes, row-major from the south (row 0 the southernmost), each an
/// elevation code ([`crate::network::elevation`]).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct TerrainRecord {
    /// West edge of the elevation grid, metres.
    pub origin_x: f32,
    /// South edge of the elevation grid, metres.
    pub origin_y: f32,
    /// Side of an elevation cell, metres.
    pub cell_m: f32,
    /// Cells along x.
    #[serde(with = "postcard::fixint::le")]
    pub cols: u32,
    /// Cells along y.
    #[serde(with = "postcard::fixint::le")]
    pub rows: u32,
    /// Elevation of code 0, metres.
    pub elevation_base_m: f32,
    /// Metres per elevation code.
    pub elevation_step_m: f32,
    /// Half-width kept free of blocked cells around every edge, node and turn arc
    /// (half the wingspan plus the horizontal clearance), metres.
    pub widen_m: f32,
    /// The flight altitude the network was built for, metres.
    pub altitude_m: f32,
    /// The safety height above the terrain the network was built for, metres.
    pub safety_height_m: f32,
}

impl TerrainRecord {
    /// Encoded size.
    pub const SIZE: usize = 40;
}

/// Landmark mode: the counts and vehicle numbers of the landmark tables, after the cell
/// entries. The tables follow: `landmark_count` [`LandmarkSiteRecord`]s; the rosettes,
/// `landmark_count · weather_count · directions` [`F32Record`] qualities (landmark-major, then
/// weather, then direction); `edge_count + 1` [`U32Record`] chain offsets into the chain
/// index list; `chain_index_count` [`U16Record`] element indices; `element_count`
/// [`ElementRecord`]s, each distinct line element once.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct LandmarkRecord {
    /// Landmarks, L.
    #[serde(with = "postcard::fixint::le")]
    pub landmark_count: u32,
    /// Overflight directions per landmark, D: vertex `l·D + k` is landmark `l` crossed in
    /// direction `k`.
    #[serde(with = "postcard::fixint::le")]
    pub directions: u32,
    /// Weathers the rosettes are given for, W.
    #[serde(with = "postcard::fixint::le")]
    pub weather_count: u32,
    /// Nominal speed of every line element and piece, m/s.
    pub v_nominal: f32,
    /// Lowest airspeed the pieces were checked against, m/s.
    pub v_min: f32,
    /// Highest airspeed, m/s.
    pub v_max: f32,
    /// Lowest longitudinal acceleration, m/s².
    pub a_long_min: f32,
    /// Highest longitudinal acceleration, m/s².
    pub a_long_max: f32,
    /// Highest lateral acceleration, m/s².
    pub a_lat_max: f32,
    /// The start's vertex (`L·D`), or `u32::MAX` when the network has no start.
    #[serde(with = "postcard::fixint::le")]
    pub start_vertex: u32,
    /// The goal's vertex (`L·D`, or `L·D + 1` after a start), or `u32::MAX`.
    #[serde(with = "postcard::fixint::le")]
    pub goal_vertex: u32,
    /// The longest start edge that may be flown (the start's `dist_m`), metres.
    pub start_range_m: f32,
    /// Distinct line elements (at most [`MAX_LINE_ELEMENTS`]).
    #[serde(with = "postcard::fixint::le")]
    pub element_count: u32,
    /// Entries of the chain index list: the chains' lengths in elements, summed.
    #[serde(with = "postcard::fixint::le")]
    pub chain_index_count: u32,
}

impl LandmarkRecord {
    /// Encoded size.
    pub const SIZE: usize = 56;
    /// The value of `start_vertex` or `goal_vertex` when there is none.
    pub const ABSENT: u32 = u32::MAX;
}

/// Voronoi mode: what the network was built for. Follows the common sections; then come
/// `threat_count` [`ThreatSiteRecord`]s and the corner table (`table_angles · table_ratios`
/// [`F32Record`]s, angle-major).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct VoronoiRecord {
    /// Number of threat sites.
    #[serde(with = "postcard::fixint::le")]
    pub threat_count: u32,
    /// The weight k of length against exposure in an edge's cost k·L + (1 − k)·exposure, in
    /// [0, 1].
    pub threat_weight: f32,
    /// The largest curvature the smoothed route may have, 1/m.
    pub kappa_max: f32,
    /// The mission box the diagram is clipped to: west, south, east, north, metres.
    pub bounds: [f32; 4],
    /// Turn angles in the corner table (`skyroute::geometry::spline::TABLE_ANGLES`).
    #[serde(with = "postcard::fixint::le")]
    pub table_angles: u32,
    /// Leg ratios in the corner table (`skyroute::geometry::spline::TABLE_RATIOS`).
    #[serde(with = "postcard::fixint::le")]
    pub table_ratios: u32,
}

impl VoronoiRecord {
    /// Encoded size.
    pub const SIZE: usize = 36;
}

/// Voronoi mode: a radar threat site.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct ThreatSiteRecord {
    /// East, metres.
    pub x: f32,
    /// North, metres.
    pub y: f32,
    /// The reference distance of its exposure, metres: flying at this distance from the site
    /// costs as much exposure per metre as length.
    pub radius: f32,
}

impl ThreatSiteRecord {
    /// Encoded size.
    pub const SIZE: usize = 12;
}

/// Landmark mode: a landmark.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct LandmarkSiteRecord {
    /// East, metres.
    pub x: f32,
    /// North, metres.
    pub y: f32,
    /// Largest distance that may be flown after overflying it with quality 1, metres.
    pub d_max: f32,
}

impl LandmarkSiteRecord {
    /// Encoded size.
    pub const SIZE: usize = 12;
}

/// A `u16` (a line element's index in a chain) as a fixed-width record.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct U16Record(#[serde(with = "postcard::fixint::le")] pub u16);

impl U16Record {
    /// Encoded size.
    pub const SIZE: usize = 2;
}

/// An `f32` as a fixed-width record: a rosette quality, a Voronoi corner-table value, or in a
/// three-dimensional roadmap a vertex's altitude (metres, finite, at most [`MAX_ALTITUDE_M`] in
/// magnitude) or an obstacle's height (metres above the altitudes' datum, positive, `+∞` for an
/// obstacle no altitude clears).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct F32Record(pub f32);

impl F32Record {
    /// Encoded size.
    pub const SIZE: usize = 4;
}

/// Landmark mode: a line element of a chain (position and velocity of nominal speed).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct ElementRecord {
    /// East, metres.
    pub x: f32,
    /// North, metres.
    pub y: f32,
    /// Velocity east, m/s.
    pub vx: f32,
    /// Velocity north, m/s.
    pub vy: f32,
}

impl ElementRecord {
    /// Encoded size.
    pub const SIZE: usize = 16;
}

#[cfg(all(test, feature = "std"))]
mod tests {
    use super::*;

    #[test]
    fn encoded_sizes_match_the_constants() {
        let h = Header {
            magic: MAGIC,
            version: FORMAT_VERSION,
            mode: 0,
            flags: 0,
            origin_lat_deg: 1.0,
            origin_lon_deg: 2.0,
            turn_radius_m: 3.0,
            clearance_m: 4.0,
            vertex_count: u32::MAX,
            edge_count: 5,
            obstacle_count: 6,
            obstacle_point_count: 7,
            grid_origin_x: 0.0,
            grid_origin_y: 0.0,
            grid_cell_m: 1.0,
            grid_nx: u32::MAX,
            grid_ny: 1,
            grid_list_bytes: 0,
            provenance_count: 3,
            body_len: 0,
            image_crc: 0,
        };
        assert_eq!(postcard::to_stdvec(&h).unwrap().len(), Header::SIZE);
        let p = ProvenanceRecord {
            kind: 3,
            digest: u64::MAX,
        };
        assert_eq!(
            postcard::to_stdvec(&p).unwrap().len(),
            ProvenanceRecord::SIZE
        );
        let v = VertexRecord {
            x: 1.0,
            y: 2.0,
            heading: 3.0,
        };
        assert_eq!(postcard::to_stdvec(&v).unwrap().len(), VertexRecord::SIZE);
        assert_eq!(
            postcard::to_stdvec(&U32Record(u32::MAX)).unwrap().len(),
            U32Record::SIZE
        );
        let e = EdgeRecord {
            target: u16::MAX,
            aux: 3,
            cost: 1.0,
        };
        assert_eq!(postcard::to_stdvec(&e).unwrap().len(), EdgeRecord::SIZE);
        let o = ObstacleRecord {
            kind: 0,
            first_point: u32::MAX,
            point_count: 1,
            circle: [0.0; 3],
            bbox: [0.0; 4],
        };
        assert_eq!(postcard::to_stdvec(&o).unwrap().len(), ObstacleRecord::SIZE);
        let t = TerrainRecord {
            origin_x: 0.0,
            origin_y: 0.0,
            cell_m: 1.0,
            cols: u32::MAX,
            rows: 1,
            elevation_base_m: 0.0,
            elevation_step_m: 1.0,
            widen_m: 1.0,
            altitude_m: 1.0,
            safety_height_m: 1.0,
        };
        assert_eq!(postcard::to_stdvec(&t).unwrap().len(), TerrainRecord::SIZE);
        let l = LandmarkRecord {
            landmark_count: u32::MAX,
            directions: 12,
            weather_count: 2,
            v_nominal: 1.0,
            v_min: 1.0,
            v_max: 1.0,
            a_long_min: -1.0,
            a_long_max: 1.0,
            a_lat_max: 1.0,
            start_vertex: u32::MAX,
            goal_vertex: u32::MAX,
            start_range_m: 1.0,
            element_count: u32::MAX,
            chain_index_count: u32::MAX,
        };
        assert_eq!(postcard::to_stdvec(&l).unwrap().len(), LandmarkRecord::SIZE);
        let vr = VoronoiRecord {
            threat_count: u32::MAX,
            threat_weight: 0.5,
            kappa_max: 0.01,
            bounds: [0.0; 4],
            table_angles: 1,
            table_ratios: 1,
        };
        assert_eq!(postcard::to_stdvec(&vr).unwrap().len(), VoronoiRecord::SIZE);
        let ts = ThreatSiteRecord {
            x: 1.0,
            y: 2.0,
            radius: 3.0,
        };
        assert_eq!(
            postcard::to_stdvec(&ts).unwrap().len(),
            ThreatSiteRecord::SIZE
        );
        let site = LandmarkSiteRecord {
            x: 1.0,
            y: 2.0,
            d_max: 3.0,
        };
        assert_eq!(
            postcard::to_stdvec(&site).unwrap().len(),
            LandmarkSiteRecord::SIZE
        );
        assert_eq!(
            postcard::to_stdvec(&U16Record(u16::MAX)).unwrap().len(),
            U16Record::SIZE
        );
        assert_eq!(
            postcard::to_stdvec(&F32Record(1.0)).unwrap().len(),
            F32Record::SIZE
        );
        let el = ElementRecord {
            x: 1.0,
            y: 2.0,
            vx: 3.0,
            vy: 4.0,
        };
        assert_eq!(postcard::to_stdvec(&el).unwrap().len(), ElementRecord::SIZE);
        assert_eq!(
            postcard::to_stdvec(&PointRecord { x: 1.0, y: 2.0 })
                .unwrap()
                .len(),
            PointRecord::SIZE
        );
    }

    #[test]
    fn alternatives_records_encode_to_their_sizes() {
        let a = AlternativesRecord {
            popup_count: u32::MAX,
            alternative_count: 1,
            disc_count: 2,
            nominal_steps: 3,
            time_limit: 0.35,
            fuel_limit: 0.4,
        };
        assert_eq!(
            postcard::to_stdvec(&a).unwrap().len(),
            AlternativesRecord::SIZE
        );
        let p = PopupRecord {
            x: 1.0,
            y: 2.0,
            radius: 3.0,
            probability: 0.5,
            alternative_count: u32::MAX,
        };
        assert_eq!(postcard::to_stdvec(&p).unwrap().len(), PopupRecord::SIZE);
        let alt = AlternativeRecord {
            steps: u32::MAX,
            survival_known: 0.9,
            survival_popup: 0.8,
            fuel: 0.1,
            length_m: 1.0,
            disc_count: u32::MAX,
        };
        assert_eq!(
            postcard::to_stdvec(&alt).unwrap().len(),
            AlternativeRecord::SIZE
        );
        let d = DiscRecord {
            x: 1.0,
            y: 2.0,
            radius: 3.0,
        };
        assert_eq!(postcard::to_stdvec(&d).unwrap().len(), DiscRecord::SIZE);
    }
}
