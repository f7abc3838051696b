//! A Voronoi planner's threat storage (`planner/threats.rs`): the stored graph checked at load
//! against the diagram of the network's sites, and threats added and removed in flight, each
//! bad call refused by name with nothing changed.

use crate::voronoi_plan::{planner, query, voronoi, VPlanner};
use host_tests::damage::fix_crc;
use skyroute::network::format::{Header, VertexRecord};
use skyroute::network::write::{encode, NetworkSpec};
use skyroute::planner::{ThreatError, VoronoiStorage, MAX_THREATS};
use skyroute::{LoadError, Planner, Pose, Vec2};
use skyroute_prep::voronoi::voronoi_network;

/// The grid cell the builder gives a Voronoi network (`grid_cell_2km`), metres.
const GRID_CELL_M: f32 = 2_000.0;

/// Loads `spec`'s image into a fresh Voronoi planner.
fn load(spec: &NetworkSpec) -> Result<(), LoadError> {
    let bytes = encode(spec).expect("the writer accepts the spec");
    let storage = Box::leak(Box::new(VoronoiStorage::new()));
    let mut p: Box<VPlanner> = Box::new(Planner::new());
    p.load_voronoi(&bytes, storage)
}

#[test]
fn a_stored_graph_that_is_not_the_diagram_of_its_sites_is_refused() {
    let (_, b) = voronoi("ruz-popups");
    let net = skyroute::Network::from_bytes(&b.bytes).unwrap();
    let (site, radius) = net.threat(0).unwrap();
    let record: Vec<u8> = [site.x, site.y, radius]
        .iter()
        .flat_map(|v| v.to_le_bytes())
        .collect();
    let at = b
        .bytes
        .windows(record.len())
        .position(|w| w == &record[..])
        .expect("threat 0's record is in the image");
    // Threat 0 moved 500 m east: the image is valid, its stored graph is not this diagram.
    let mut moved = b.bytes.clone();
    moved[at..at + 4].copy_from_slice(&(site.x + 500.0).to_le_bytes());
    fix_crc(&mut moved);
    skyroute::Network::from_bytes(&moved).expect("the loader alone cannot tell");
    let mut p: Box<VPlanner> = Box::new(Planner::new());
    assert_eq!(p.load(&b.bytes), Err(LoadError::NeedsVoronoiStorage));
    let storage = Box::leak(Box::new(VoronoiStorage::new()));
    assert!(
        matches!(
            p.load_voronoi(&moved, storage),
            Err(LoadError::VoronoiMismatch { .. })
        ),
        "a network whose graph is not its sites' diagram loads"
    );
    // A stored vertex moved instead: refused by the loader or by the planner.
    let mut shifted = b.bytes.clone();
    let v = Header::SIZE + 3 * VertexRecord::SIZE;
    let x = f32::from_le_bytes(shifted[v..v + 4].try_into().unwrap());
    shifted[v..v + 4].copy_from_slice(&(x + 50.0).to_le_bytes());
    fix_crc(&mut shifted);
    let storage = Box::leak(Box::new(VoronoiStorage::new()));
    assert!(matches!(
        p.load_voronoi(&shifted, storage),
        Err(LoadError::VoronoiMismatch { .. }) | Err(LoadError::EdgeMissesTarget { .. })
    ));
}

#[test]
fn bad_threat_calls_are_refused_and_change_nothing() {
    let (s, b) = voronoi("ruz-popups");
    let mut p = planner(&b.bytes);
    let threats = p.threats().to_vec();
    let inside_box = threats[0].position + Vec2::new(100.0, 0.0);
    assert_eq!(
        p.add_threat(Vec2::new(f32::NAN, 0.0), 1.0),
        Err(ThreatError::NonFinite)
    );
    assert_eq!(
        p.add_threat(inside_box, f32::INFINITY),
        Err(ThreatError::NonFinite)
    );
    assert_eq!(p.add_threat(inside_box, 0.0), Err(ThreatError::OutOfRange));
    assert_eq!(p.add_threat(inside_box, -5.0), Err(ThreatError::OutOfRange));
    // A radius at the coordinate limit is accepted, one beyond it refused.
    let limit = skyroute::geometry::MAX_COORDINATE_M;
    assert_eq!(
        p.add_threat(inside_box, 2.0 * limit),
        Err(ThreatError::OutOfRange)
    );
    let at_limit = p
        .add_threat(inside_box, limit)
        .expect("a radius at the limit");
    p.remove_threat(at_limit.id).unwrap();
    assert_eq!(
        p.add_threat(Vec2::new(9e6, 9e6), 100.0),
        Err(ThreatError::OutsideBox)
    );
    assert!(matches!(
        p.add_threat(threats[2].position, 100.0),
        Err(ThreatError::Duplicate { .. })
    ));
    assert_eq!(p.remove_threat(7), Err(ThreatError::UnknownId { id: 7 }));
    let k = p.threat_weight().expect("a Voronoi planner's weight");
    assert_eq!(p.set_threat_weight(1.5), Err(ThreatError::OutOfRange));
    assert_eq!(p.set_threat_weight(f32::NAN), Err(ThreatError::NonFinite));
    assert_eq!(p.threat_weight(), Some(k));
    p.set_threat_weight(0.25).unwrap();
    assert_eq!(p.threat_weight(), Some(0.25));
    p.set_threat_weight(k).unwrap();
    assert_eq!(p.threats(), &threats[..]);
    let bounds = p.network().voronoi_bounds().unwrap();
    let mut added = 0;
    let mut k = 0u32;
    while p.threats().len() < MAX_THREATS {
        k += 1;
        let at = Vec2::new(
            bounds.min.x + 997.0 * k as f32 % (bounds.max.x - bounds.min.x),
            bounds.min.y + 313.0 * k as f32 % (bounds.max.y - bounds.min.y),
        );
        if p.add_threat(at, 1000.0).is_ok() {
            added += 1;
        }
    }
    assert!(added > 0);
    assert_eq!(p.add_threat(inside_box, 100.0), Err(ThreatError::Full));
    // Still plans with a full diagram, within the bound.
    let q = query(&s, &b);
    if let Ok(r) = p.plan(&q, p.worst_case_work()) {
        assert!(r.work.total() <= p.worst_case_work());
    }
}

/// The stored graph must have the diagram's numbers of vertices and of edges: an image with
/// one edge fewer (both directions), or one vertex more, whose other vertices all match, is
/// refused with both counts.
#[test]
fn a_stored_graph_with_an_edge_fewer_or_a_vertex_more_than_the_diagram_is_refused() {
    let (s, b) = voronoi("ruz-popups");
    let (_, spec) = voronoi_network(&s, &b.frame, GRID_CELL_M).unwrap();
    let n = spec.vertices.len() as u32;
    let m = spec.edges.len() as u32 / 2;
    assert_eq!(load(&spec), Ok(()), "the builder's own spec");

    let mut fewer_edges = spec.clone();
    let dropped = fewer_edges.edges.split_off(2 * (m as usize - 1));
    assert_eq!(
        (dropped[0].source, dropped[0].target),
        (dropped[1].target, dropped[1].source),
        "the last two edges are one edge both ways"
    );
    assert_eq!(
        load(&fewer_edges),
        Err(LoadError::VoronoiMismatch {
            stored: (n, m - 1),
            built: (n, m),
        })
    );

    let mut more_vertices = spec.clone();
    let (lo, hi) = spec.voronoi.as_ref().unwrap().bounds;
    more_vertices
        .vertices
        .push(Pose::new((lo.x + hi.x) / 2.0, (lo.y + hi.y) / 2.0, 0.0));
    assert_eq!(
        load(&more_vertices),
        Err(LoadError::VoronoiMismatch {
            stored: (n + 1, m),
            built: (n, m),
        })
    );
}

/// A threat on any side of the network's box is added (and removed again); one a metre beyond
/// that side is refused, and the threats in force stay as they were.
#[test]
fn a_threat_on_a_side_of_the_box_is_added_and_one_a_metre_beyond_it_refused() {
    let (_, b) = voronoi("ruz-popups");
    let mut p = planner(&b.bytes);
    let before = p.threats().to_vec();
    let bounds = p.network().voronoi_bounds().unwrap();
    let (lo, hi) = (bounds.min, bounds.max);
    let mid = Vec2::new((lo.x + hi.x) / 2.0, (lo.y + hi.y) / 2.0);
    let sides = [
        (Vec2::new(lo.x, mid.y), Vec2::new(-1.0, 0.0)),
        (Vec2::new(hi.x, mid.y), Vec2::new(1.0, 0.0)),
        (Vec2::new(mid.x, lo.y), Vec2::new(0.0, -1.0)),
        (Vec2::new(mid.x, hi.y), Vec2::new(0.0, 1.0)),
    ];
    for (on, outward) in sides {
        let added = p
            .add_threat(on, 500.0)
            .unwrap_or_else(|e| panic!("a threat at {on:?} on the box: {e}"));
        assert_eq!(added.threats as usize, before.len() + 1);
        p.remove_threat(added.id).unwrap();
        assert_eq!(
            p.add_threat(on + outward, 500.0),
            Err(ThreatError::OutsideBox),
            "a threat at {:?}, a metre outside",
            on + outward
        );
        assert_eq!(p.threats(), &before[..]);
    }
}
