//! Format v4 on the scenarios the papers use: each image within its flash goal, and what the
//! aircraft reads back is bit for bit what the ground tool built and checked (a roadmap edge's
//! source, target, cost, word and piece lengths; a terrain edge's ends and cost), so a query
//! finds the same route as with the edges stored in full. The edges' clearance from the
//! buildings, read back this way, is checked against the scenario in f64 by
//! `niendorf_clearance`.

use host_tests::full_tier_only;
use host_tests::scenarios::built;
use skyroute::Network;

/// Flash goals for the network images, bytes.
const NIENDORF_URBAN_GOAL: usize = 256 * 1024;
const BABEL_II_N_GOAL: usize = 384 * 1024;
const MEDEIROS_JACKSBORO_GOAL: usize = 512 * 1024;

#[test]
fn niendorf_urban_reads_back_its_roadmap_bit_for_bit_within_256_kib() {
    let b = built("niendorf-urban");
    assert!(
        b.bytes.len() <= NIENDORF_URBAN_GOAL,
        "{} bytes",
        b.bytes.len()
    );
    let roadmap = b.roadmap.as_ref().expect("a roadmap");
    let net = Network::from_bytes(&b.bytes).unwrap();
    assert_eq!(net.edge_count() as usize, roadmap.edges.len());
    for (i, spec) in roadmap.edges.iter().enumerate() {
        let e = net.edge(i as u32).unwrap();
        assert_eq!((e.source, e.target), (spec.source, spec.target), "edge {i}");
        assert_eq!(e.cost.to_bits(), spec.cost.to_bits(), "edge {i} cost");
        assert_eq!(e.word, spec.word, "edge {i} word");
        for k in 0..3 {
            assert_eq!(
                e.lengths[k].to_bits(),
                spec.lengths[k].to_bits(),
                "edge {i} piece {k}"
            );
        }
    }
}

#[test]
fn medeiros_jacksboro_reads_back_its_graph_bit_for_bit_within_512_kib() {
    if !full_tier_only(
        "medeiros_jacksboro_reads_back_its_graph_bit_for_bit_within_512_kib",
        "builds the full Jacksboro network",
    ) {
        return;
    }
    let b = built("medeiros-jacksboro");
    assert!(
        b.bytes.len() <= MEDEIROS_JACKSBORO_GOAL,
        "{} bytes",
        b.bytes.len()
    );
    let graph = b.terrain.as_ref().expect("a terrain graph");
    let net = Network::from_bytes_with_capacity(&b.bytes, usize::MAX, usize::MAX).unwrap();
    assert_eq!(net.edge_count() as usize, graph.edges.len());
    for (i, &(from, to, length)) in graph.edges.iter().enumerate() {
        let link = net.edge_link(i as u32).unwrap();
        assert_eq!((link.source, link.target), (from, to), "edge {i}");
        assert_eq!(link.cost.to_bits(), length.to_bits(), "edge {i} cost");
    }
}

#[test]
fn babel_ii_n_fits_within_384_kib() {
    if !full_tier_only(
        "babel_ii_n_fits_within_384_kib",
        "builds the babel-II-N network",
    ) {
        return;
    }
    let b = built("babel-II-N");
    assert!(b.bytes.len() <= BABEL_II_N_GOAL, "{} bytes", b.bytes.len());
    let net = Network::from_bytes(&b.bytes).unwrap();
    let l = net.landmark().unwrap();
    assert!(
        l.element_count < l.chain_index_count,
        "chains share line elements"
    );
}
