//! The writer's landmark half against its definitions, on the small network of
//! [`super::tests`]: the grid index lists each chain in exactly the cells its pieces' widened
//! Bernstein boxes overlap, the grid covers every chain's reach, and the writer's own landmark
//! checks refuse by name.

extern crate std;
use super::tests::spec;
use crate::geometry::Vec2;
use crate::network::write::{encode, EdgeSpec};
use std::vec;
use std::vec::Vec as StdVec;

/// The grid index of the small network with cells of 7–90 m: each chain edge listed exactly in
/// the cells that one of its pieces' Bernstein boxes, widened by the clearance and the index's
/// rounding margin, overlaps (`docs/FORMAT.md`, landmark mode's grid index), worked out in f64.
#[test]
fn a_chain_is_listed_in_the_cells_its_pieces_widened_boxes_overlap() {
    use crate::network::write::tests::{check_boxes, margin};
    let mut rng = crate::test_rng::Rng(0x1a2d_9a1d_2026_1206);
    let mut met = 0;
    for _ in 0..10 {
        let mut s = spec();
        s.grid_cell_m = rng.range(7.0, 90.0);
        let bytes = encode(&s).unwrap();
        let net = crate::network::Network::from_bytes(&bytes).unwrap();
        let w = s.clearance_m as f64 + margin(s.grid_cell_m);
        let boxes: StdVec<StdVec<([f64; 2], [f64; 2])>> = (0..net.edge_count())
            .map(|e| {
                (0..net.chain_piece_count(e))
                    .map(|k| {
                        let (lo, hi) = net.chain_piece(e, k).unwrap().bounding_box();
                        (
                            [lo.x as f64 - w, lo.y as f64 - w],
                            [hi.x as f64 + w, hi.y as f64 + w],
                        )
                    })
                    .collect()
            })
            .collect();
        met += check_boxes(&net, &boxes);
    }
    assert!(met > 2000, "{met} listings");
}

/// A chain whose stored length (6 km) is six times its chord reaches far past the vertices'
/// surroundings: the grid is the box of the vertices and of every edge's reach widened by one
/// cell, widened again by four turn radii and a cell (`docs/FORMAT.md`, landmark mode's grid
/// index), worked out in f64 for cells of 7–90 m.
#[test]
fn the_grid_covers_every_chains_reach_and_the_vertices_surroundings() {
    use crate::network::write::tests::{check_extent, vertex_box};
    let mut rng = crate::test_rng::Rng(0x9a1d_ec4e_2026_1206);
    for _ in 0..8 {
        let mut s = spec();
        s.grid_cell_m = rng.range(7.0, 90.0);
        s.edges[1] = EdgeSpec::chain(4, 9, 6000.0);
        let bytes = encode(&s).unwrap();
        let net = crate::network::Network::from_bytes(&bytes).unwrap();
        let cell = s.grid_cell_m as f64;
        let f = |p: Vec2| [p.x as f64, p.y as f64];
        let (mut lo, mut hi) = vertex_box(&s);
        let chains = &s.landmark.as_ref().unwrap().chains;
        for (e, chain) in s.edges.iter().zip(chains) {
            let (a, b) = (f(chain[0].position), f(chain[chain.len() - 1].position));
            let half = 0.5 * e.cost as f64 * (1.0 + 1e-4) + 0.01 + cell;
            for k in 0..2 {
                let mid = 0.5 * (a[k] + b[k]);
                lo[k] = lo[k].min(mid - half);
                hi[k] = hi[k].max(mid + half);
            }
        }
        check_extent(&net, &s, (lo, hi));
        assert!(
            lo[0] < -1500.0,
            "the reach, not the vertices, sets the west edge"
        );
    }
}

/// The writer's landmark checks, each refused by name: a vertex too many for landmarks ×
/// directions plus the endpoints, a quality count that is not landmarks × weathers ×
/// directions, a chain missing, an edge with a word other than `EdgeSpec::chain`'s or a second
/// or third length, a chain of one element; and a landmark network written as
/// three-dimensional.
#[test]
fn the_writers_landmark_checks_refuse_by_name() {
    use crate::network::write::{encode_three_dimensional, VerticalSpec, WriteError};
    let bad = |what| Err(WriteError::BadLandmark(what));
    let mut s = spec();
    s.vertices.push(s.vertices[0]);
    let vertices = "vertex count is not landmarks x directions plus the endpoints";
    assert_eq!(encode(&s), bad(vertices));
    let mut s = spec();
    s.landmark.as_mut().unwrap().qualities.pop();
    let qualities = "quality count is not landmarks x weathers x directions";
    assert_eq!(encode(&s), bad(qualities));
    let mut s = spec();
    s.landmark.as_mut().unwrap().chains.pop();
    assert_eq!(encode(&s), bad("one chain per edge needed"));
    for k in [0, 1, 2] {
        let mut s = spec();
        match k {
            0 => s.edges[0].word = crate::geometry::DubinsWord::Rsr,
            _ => s.edges[0].lengths[k] = 1.0,
        }
        let not_chain = "an edge is not a Hermite chain (EdgeSpec::chain)";
        assert_eq!(encode(&s), bad(not_chain), "change {k}");
    }
    let mut s = spec();
    s.landmark.as_mut().unwrap().chains[1].truncate(1);
    assert_eq!(encode(&s), bad("a chain has fewer than 2 line elements"));
    let vertical = VerticalSpec {
        limits: crate::geometry::vertical::VerticalLimits::niendorf(25.0),
        altitudes: vec![100.0; spec().vertices.len()],
        heights: StdVec::new(),
    };
    assert_eq!(
        encode_three_dimensional(&spec(), &vertical, None),
        Err(WriteError::BadVertical(
            "only a roadmap can be three-dimensional"
        ))
    );
}
