//! Format v4's compact records as bad input: a grid cell's varint list that runs past its
//! cell, is over-long or names an edge past the count, a roadmap edge whose Dubins word
//! cannot join its ends, and one whose cost undercuts its solved length, each refused with its
//! own error (checksum re-fixed so the field checks decide); the end check's tolerance far
//! from the origin; the edge source the loader derives from the offsets, against a scan; and
//! the on-demand checksum pass that finds a byte corrupted after load.

use host_tests::damage::{fix_crc, leb128};
use host_tests::world::world;
use host_tests::Rng;
use skyroute::network::format::{
    EdgeRecord, Header, ObstacleRecord, PointRecord, U32Record, VertexRecord,
};
use skyroute::network::write::{encode, EdgeSpec, NetworkSpec};
use skyroute::network::{LoadError, Section};
use skyroute::{DubinsPath, DubinsWord, Network, Pose};

/// Byte offsets of the cell offsets and of the cell lists of a roadmap image.
fn grid_at(net: &Network) -> (usize, usize) {
    let h = net.header();
    let (v, e) = (h.vertex_count as usize, h.edge_count as usize);
    let offsets = Header::SIZE
        + v * VertexRecord::SIZE
        + (v + 1) * U32Record::SIZE
        + e * EdgeRecord::SIZE
        + h.obstacle_count as usize * ObstacleRecord::SIZE
        + h.obstacle_point_count as usize * PointRecord::SIZE;
    let cells = (h.grid_nx * h.grid_ny) as usize;
    (offsets, offsets + (cells + 1) * U32Record::SIZE)
}

fn get_u32(b: &[u8], at: usize) -> u32 {
    u32::from_le_bytes(b[at..at + 4].try_into().unwrap())
}

/// The first cell whose list holds at least two edges: its index and its list's byte range.
fn busy_cell(b: &[u8], net: &Network) -> (u32, usize, usize) {
    let (offsets, lists) = grid_at(net);
    let h = net.header();
    (0..h.grid_nx * h.grid_ny)
        .find_map(|c| {
            let (x, y) = (c % h.grid_nx, c / h.grid_nx);
            (net.cell_edges(x, y).count() >= 2).then(|| {
                let start = get_u32(b, offsets + 4 * c as usize) as usize;
                let end = get_u32(b, offsets + 4 * (c as usize + 1)) as usize;
                (c, lists + start, lists + end)
            })
        })
        .expect("a cell lists two edges")
}

#[test]
fn each_cell_list_damage_has_its_own_error() {
    let w = world(2, 600.0, 60.0, 40.0, 3);
    let good = w.bytes.clone();
    let net = Network::from_bytes(&good).unwrap();
    let (cell, start, end) = busy_cell(&good, &net);
    let refused = |b: &mut Vec<u8>| {
        fix_crc(b);
        Network::from_bytes(b).unwrap_err()
    };

    // The cell's last byte gets its continuation bit: the varint runs into the next cell.
    let mut b = good.clone();
    b[end - 1] |= 0x80;
    assert_eq!(refused(&mut b), LoadError::BadCellList { cell });

    // The first edge index past the edge count.
    let e_count = net.edge_count();
    let mut b = good.clone();
    let first_len = good[start..end].iter().position(|x| x & 0x80 == 0).unwrap() + 1;
    // Replace the first varint by the largest value of the same length, 128^len − 1.
    assert!(
        (1u64 << (7 * first_len)) > e_count as u64,
        "the largest {first_len}-byte varint reaches the edge count {e_count}"
    );
    for k in 0..first_len {
        b[start + k] = if k + 1 < first_len { 0xff } else { 0x7f };
    }
    let e = refused(&mut b);
    assert!(
        matches!(
            e,
            LoadError::IndexOutOfRange {
                section: Section::CellEntries,
                index,
                limit,
                ..
            } if index == cell && limit == e_count
        ),
        "{e:?}"
    );

    // A first entry naming edge E itself, one past the last edge: a cell whose first varint
    // has as many bytes as E's gets E in its place.
    let (offsets, lists) = grid_at(&net);
    let h = net.header();
    let mut count_varint = Vec::new();
    leb128(e_count, &mut count_varint);
    let (c, s) = (0..h.grid_nx * h.grid_ny)
        .find_map(|c| {
            let s = lists + get_u32(&good, offsets + 4 * c as usize) as usize;
            let t = lists + get_u32(&good, offsets + 4 * (c as usize + 1)) as usize;
            let len = good[s..t].iter().position(|x| x & 0x80 == 0)? + 1;
            (len == count_varint.len()).then_some((c, s))
        })
        .expect("a cell whose first varint is as long as the edge count's");
    let mut b = good.clone();
    b[s..s + count_varint.len()].copy_from_slice(&count_varint);
    assert_eq!(
        refused(&mut b),
        LoadError::IndexOutOfRange {
            section: Section::CellEntries,
            index: c,
            value: e_count,
            limit: e_count
        }
    );

    // Six continuation bytes in a cell of at least six bytes: longer than any u32 varint.
    let long = (0..h.grid_nx * h.grid_ny).find(|&c| {
        let s = get_u32(&good, offsets + 4 * c as usize) as usize;
        let t = get_u32(&good, offsets + 4 * (c as usize + 1)) as usize;
        t - s >= 6
    });
    let long = long.expect("a cell of six list bytes");
    let s = lists + get_u32(&good, offsets + 4 * long as usize) as usize;
    let mut b = good.clone();
    b[s..s + 6].fill(0x80);
    assert_eq!(refused(&mut b), LoadError::BadCellList { cell: long });
}

#[test]
fn a_dubins_word_that_cannot_join_its_ends_is_refused() {
    // Turn radius 10 m, vertices 60 m apart: most edges are longer than four radii.
    let w = world(2, 600.0, 60.0, 10.0, 3);
    let net = Network::from_bytes(&w.bytes).unwrap();
    let r = net.turn_radius();
    // An edge whose ends are more than 4r apart: no CCC word joins them.
    let far = (0..net.edge_count())
        .find(|&e| {
            let link = net.edge_link(e).unwrap();
            let (a, b) = (
                net.vertex(link.source).unwrap(),
                net.vertex(link.target).unwrap(),
            );
            a.position.distance(b.position) > 4.0 * r + 1.0
                && DubinsPath::with_word(&a, &b, r, DubinsWord::Lrl).is_none()
        })
        .expect("an edge longer than four turn radii");
    let at = Header::SIZE
        + net.vertex_count() as usize * (VertexRecord::SIZE + U32Record::SIZE)
        + U32Record::SIZE
        + far as usize * EdgeRecord::SIZE
        + 2;
    let mut b = w.bytes.clone();
    b[at] = DubinsWord::Lrl.code();
    fix_crc(&mut b);
    assert_eq!(
        Network::from_bytes(&b).unwrap_err(),
        LoadError::WordCannotJoin {
            edge: far,
            word: DubinsWord::Lrl.code()
        }
    );
}

/// A roadmap edge's cost may not undercut the length of its path as the loader solves it,
/// within the documented 10⁻⁵ (`docs/FORMAT.md`, validation step 7): each edge's cost set to
/// exactly that length, and to 5·10⁻⁶ below it, loads; 3·10⁻⁵ below it is refused as
/// `CostBelowLength` naming the edge (checksum re-fixed so the field check decides).
#[test]
fn a_roadmap_edge_cost_may_not_undercut_its_solved_length() {
    let w = world(5, 600.0, 60.0, 10.0, 3);
    let net = Network::from_bytes(&w.bytes).unwrap();
    let r = net.turn_radius();
    let v = net.vertex_count() as usize;
    let cost_at = |e: u32| {
        Header::SIZE
            + v * (VertexRecord::SIZE + U32Record::SIZE)
            + U32Record::SIZE
            + e as usize * EdgeRecord::SIZE
            + 3
    };
    let with_cost = |e: u32, cost: f32| {
        let mut b = w.bytes.clone();
        b[cost_at(e)..cost_at(e) + 4].copy_from_slice(&cost.to_le_bytes());
        fix_crc(&mut b);
        b
    };
    let step = (net.edge_count() / 7).max(1);
    let mut checked = 0;
    for e in (0..net.edge_count()).step_by(step as usize) {
        let (a, b, word) = net.dubins_edge_ends(e).unwrap();
        let length = DubinsPath::with_word(&a, &b, r, word).unwrap().length();
        assert!(length > 1.0);
        for cost in [length, length * (1.0 - 5e-6)] {
            let bytes = with_cost(e, cost);
            let loaded = Network::from_bytes(&bytes);
            assert!(
                loaded.is_ok(),
                "edge {e} cost {cost} of {length}: {loaded:?}"
            );
        }
        let bytes = with_cost(e, length * (1.0 - 3e-5));
        assert_eq!(
            Network::from_bytes(&bytes).unwrap_err(),
            LoadError::CostBelowLength { edge: e }
        );
        checked += 1;
    }
    assert!(checked >= 7);
}

#[test]
fn edge_sources_found_by_binary_search_match_a_scan_of_the_offsets() {
    let w = world(3, 700.0, 60.0, 40.0, 2);
    let net = Network::from_bytes(&w.bytes).unwrap();
    let mut checked = 0;
    for v in 0..net.vertex_count() {
        for e in net.out_edges(v) {
            assert_eq!(net.edge_source(e), Some(v), "edge {e}");
            checked += 1;
        }
    }
    assert_eq!(checked, net.edge_count());
    assert_eq!(net.edge_source(net.edge_count()), None);
}

#[test]
fn an_image_corrupted_after_load_is_found_by_verify_in_bounded_steps() {
    use skyroute::network::{image_checksum, ImageVerifier, VerifyStep};
    let w = world(4, 600.0, 60.0, 40.0, 3);
    let net = Network::from_bytes(&w.bytes).unwrap();
    let crc = net.header().image_crc;
    assert_eq!(net.verify(), Ok(()));
    // A pass in 1000-byte steps: in progress until the last, then intact, and again.
    let covered = w.bytes.len() - 4;
    let steps = covered.div_ceil(1000);
    let mut v = ImageVerifier::new();
    for pass in 0..2 {
        for k in 1..steps {
            assert_eq!(
                net.verify_step(&mut v, 1000),
                VerifyStep::InProgress {
                    done: 1000 * k,
                    total: covered
                },
                "pass {pass}, step {k}"
            );
        }
        assert_eq!(net.verify_step(&mut v, 1000), VerifyStep::Intact);
    }
    // The same pass over copies with one bit flipped (header, body, last byte): each found,
    // with the CRC it has now.
    for at in [5, 40, Header::SIZE, w.bytes.len() / 2, w.bytes.len() - 1] {
        let mut bad = w.bytes.clone();
        bad[at] ^= 0x10;
        let mut v = ImageVerifier::new();
        let verdict = loop {
            match v.step(&bad, crc, 777) {
                VerifyStep::InProgress { .. } => continue,
                other => break other,
            }
        };
        assert_eq!(
            verdict,
            VerifyStep::Corrupted(skyroute::LoadError::ChecksumMismatch {
                stored: crc,
                computed: image_checksum(&bad)
            }),
            "byte {at}"
        );
    }
    // A step of 0 bytes still moves; an image cut inside its header is corrupted at once.
    let mut v = ImageVerifier::new();
    assert!(matches!(
        v.step(&w.bytes, crc, 0),
        VerifyStep::InProgress { done: 1, .. }
    ));
    let mut v = ImageVerifier::new();
    assert!(matches!(
        v.step(&w.bytes[..10], crc, usize::MAX),
        VerifyStep::Corrupted(_)
    ));
}

/// A roadmap 200 km from its frame's origin, where an f32 coordinate's step is 1.6 cm: flying
/// each solved edge from its source ends farther from the target than the 1 cm floor of the
/// end check, and within the check's term in the coordinates' size (10⁻⁴ of radius +
/// coordinate + length, `docs/FORMAT.md` step 7), so the image loads.
#[test]
fn a_roadmap_far_from_its_origin_loads_within_the_end_tolerance() {
    let mut rng = Rng(17);
    let radius = 50.0;
    let vertices: Vec<Pose> = (0..12)
        .map(|_| {
            Pose::new(
                200_000.0 + rng.range_f32(0.0, 2000.0),
                -150_000.0 + rng.range_f32(0.0, 2000.0),
                rng.range_f32(-3.1, 3.1),
            )
        })
        .collect();
    let mut edges = Vec::new();
    let mut worst = 0f32;
    for i in 0..vertices.len() {
        for j in 0..vertices.len() {
            if i == j {
                continue;
            }
            let path = DubinsPath::shortest(&vertices[i], &vertices[j], radius).unwrap();
            worst = worst.max(path.end().position.distance(vertices[j].position));
            edges.push(EdgeSpec::dubins(i as u32, j as u32, &path));
        }
    }
    let spec = NetworkSpec {
        origin_lat_deg: 10.0,
        origin_lon_deg: 20.0,
        turn_radius_m: radius,
        clearance_m: 5.0,
        vertices,
        edges,
        obstacles: Vec::new(),
        grid_cell_m: 2000.0,
        landmark: None,
        voronoi: None,
        terrain: None,
        provenance: Vec::new(),
    };
    let bytes = encode(&spec).unwrap();
    println!("worst end miss {worst} m");
    assert!(worst > 0.01, "the 1 cm floor alone would pass: {worst} m");
    assert!(Network::from_bytes(&bytes).is_ok());
}
