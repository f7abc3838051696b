//! The loader: a valid image round-trips; each kind of damage gets its own `LoadError`; random
//! mutations never panic the loader or a planner using what it accepted.

use host_tests::damage::fix_crc;
use host_tests::world::world;
use host_tests::{cases, Rng};
use skyroute::network::format::{
    EdgeRecord, Header, ProvenanceRecord, U32Record, VertexRecord, FORMAT_VERSION,
};
use skyroute::network::{LoadError, Section};
use skyroute::planner::{Goal, Popup, Query, Search};
use skyroute::{Network, Planner, Vec2};

type TestPlanner<'n> = Planner<'n, 2048, 65536, 4, 512>;

fn vertices_at(_bytes: &[u8]) -> usize {
    Header::SIZE
}

fn edges_at(n_vertices: usize) -> usize {
    Header::SIZE + n_vertices * VertexRecord::SIZE + (n_vertices + 1) * U32Record::SIZE
}

#[test]
fn valid_image_round_trips() {
    let w = world(1, 800.0, 60.0, 40.0, 4);
    let net = Network::from_bytes(&w.bytes).expect("valid");
    assert_eq!(net.vertex_count() as usize, w.spec.vertices.len());
    assert_eq!(net.edge_count() as usize, w.spec.edges.len());
    for (i, v) in w.spec.vertices.iter().enumerate() {
        assert_eq!(net.vertex(i as u32), Some(*v));
    }
    // Every spec edge is stored exactly once, under its source.
    let mut stored = 0;
    for v in 0..net.vertex_count() {
        for e in net.out_edges(v) {
            let edge = net.edge(e).unwrap();
            assert_eq!(edge.source, v);
            stored += 1;
        }
    }
    assert_eq!(stored, w.spec.edges.len());
    assert!(net.vertex(net.vertex_count()).is_none());
    assert!(net.edge(net.edge_count()).is_none());
}

/// The checksum covers the whole image, header included: CRC-32 detects every single-bit
/// error, so no flipped bit anywhere may load (before the header was covered, a flip in the
/// origin, the clearance or the grid cell loaded and moved the map under the route).
#[test]
fn every_single_bit_flip_of_the_header_and_of_a_body_sample_is_refused() {
    let w = world(5, 600.0, 60.0, 40.0, 3);
    let mut spec = w.spec.clone();
    spec.provenance = (0..5u8)
        .map(|kind| ProvenanceRecord {
            kind,
            digest: 0x0123_4567_89ab_cdef ^ kind as u64,
        })
        .collect();
    let good = skyroute::network::write::encode(&spec).unwrap();
    let net = Network::from_bytes(&good).unwrap();
    assert_eq!(net.provenance_count(), 5);
    assert_eq!(net.provenance(4), Some(spec.provenance[4]));
    assert_eq!(net.provenance(5), None);
    let provenance_at = good.len() - 5 * ProvenanceRecord::SIZE;
    let bytes = (0..Header::SIZE)
        .chain((Header::SIZE..good.len()).step_by(7))
        .chain(provenance_at..good.len());
    let mut tried = 0;
    for byte in bytes {
        for bit in 0..8 {
            let mut b = good.clone();
            b[byte] ^= 1 << bit;
            tried += 1;
            if let Ok(n) = Network::from_bytes(&b) {
                panic!(
                    "byte {byte} bit {bit} flipped loads (origin {:?}, clearance {})",
                    n.origin_deg(),
                    n.clearance()
                );
            }
        }
    }
    assert!(tried > 8 * (Header::SIZE + 45), "{tried}");

    // An image of an older version is refused as such, with what to do about it.
    let mut old = good.clone();
    old[4..6].copy_from_slice(&(FORMAT_VERSION - 1).to_le_bytes());
    let e = Network::from_bytes(&old).unwrap_err();
    assert_eq!(
        e,
        LoadError::UnsupportedVersion {
            found: FORMAT_VERSION - 1,
            supported: FORMAT_VERSION
        }
    );
    assert!(e.to_string().contains("rebuild"), "{e}");
}

#[test]
fn each_damage_has_its_own_error() {
    let w = world(2, 600.0, 60.0, 40.0, 3);
    let good = &w.bytes;
    let n_v = w.spec.vertices.len();

    // Truncated: every cut inside the header and a sample of cuts in the body.
    for cut in (0..good.len())
        .step_by(97)
        .chain([0, 10, Header::SIZE - 1, good.len() - 1])
    {
        match Network::from_bytes(&good[..cut]) {
            Err(LoadError::Truncated { needed, available }) => {
                assert_eq!(available, cut);
                assert!(needed > cut);
            }
            Err(LoadError::BadMagic { .. }) if cut < 4 => {}
            other => panic!("cut at {cut}: {other:?}"),
        }
    }
    // Trailing bytes.
    let mut longer = good.clone();
    longer.extend_from_slice(&[0, 0, 0]);
    assert_eq!(
        Network::from_bytes(&longer).unwrap_err(),
        LoadError::TrailingBytes { extra: 3 }
    );

    // Bad magic.
    let mut b = good.clone();
    b[0] = b'X';
    assert!(
        matches!(Network::from_bytes(&b), Err(LoadError::BadMagic { found }) if found == *b"XKYR")
    );

    // Wrong version.
    let mut b = good.clone();
    b[4] = 7;
    assert_eq!(
        Network::from_bytes(&b).unwrap_err(),
        LoadError::UnsupportedVersion {
            found: 7,
            supported: skyroute::network::format::FORMAT_VERSION
        }
    );

    // A bit flipped in the body.
    let mut b = good.clone();
    let at = Header::SIZE + (good.len() - Header::SIZE) / 2;
    b[at] ^= 0x10;
    assert!(matches!(
        Network::from_bytes(&b),
        Err(LoadError::ChecksumMismatch { .. })
    ));

    // Over capacity, refused before the body is read.
    let err = Network::from_bytes_with_capacity(good, n_v - 1, usize::MAX).unwrap_err();
    assert_eq!(
        err,
        LoadError::TooManyVertices {
            count: n_v as u32,
            capacity: n_v - 1
        }
    );
    let n_e = w.spec.edges.len();
    let err = Network::from_bytes_with_capacity(good, usize::MAX, 10).unwrap_err();
    assert_eq!(
        err,
        LoadError::TooManyEdges {
            count: n_e as u32,
            capacity: 10
        }
    );
    let mut small: Planner<'_, 16, 16, 1, 8> = Planner::new();
    assert!(matches!(
        small.load(good),
        Err(LoadError::TooManyVertices { .. })
    ));

    // NaN in a vertex (CRC rewritten so the field check is reached).
    let mut b = good.clone();
    let v3 = vertices_at(good) + 3 * VertexRecord::SIZE;
    b[v3..v3 + 4].copy_from_slice(&f32::NAN.to_le_bytes());
    fix_crc(&mut b);
    assert_eq!(
        Network::from_bytes(&b).unwrap_err(),
        LoadError::NonFinite {
            section: Section::Vertices,
            index: 3
        }
    );

    // NaN heading.
    let mut b = good.clone();
    let h5 = vertices_at(good) + 5 * VertexRecord::SIZE + 8;
    b[h5..h5 + 4].copy_from_slice(&f32::INFINITY.to_le_bytes());
    fix_crc(&mut b);
    assert_eq!(
        Network::from_bytes(&b).unwrap_err(),
        LoadError::NonFinite {
            section: Section::Vertices,
            index: 5
        }
    );

    // An edge target out of range.
    let mut b = good.clone();
    let e2 = edges_at(n_v) + 2 * EdgeRecord::SIZE;
    b[e2..e2 + 2].copy_from_slice(&(n_v as u16 + 9).to_le_bytes());
    fix_crc(&mut b);
    assert_eq!(
        Network::from_bytes(&b).unwrap_err(),
        LoadError::IndexOutOfRange {
            section: Section::Edges,
            index: 2,
            value: n_v as u32 + 9,
            limit: n_v as u32
        }
    );

    // A NaN edge cost.
    let mut b = good.clone();
    let c4 = edges_at(n_v) + 4 * EdgeRecord::SIZE + 3;
    b[c4..c4 + 4].copy_from_slice(&f32::NAN.to_le_bytes());
    fix_crc(&mut b);
    assert_eq!(
        Network::from_bytes(&b).unwrap_err(),
        LoadError::NonFinite {
            section: Section::Edges,
            index: 4
        }
    );

    // An unknown Dubins word.
    let mut b = good.clone();
    let g1 = edges_at(n_v) + EdgeRecord::SIZE + 2;
    b[g1] = 42;
    fix_crc(&mut b);
    assert_eq!(
        Network::from_bytes(&b).unwrap_err(),
        LoadError::UnknownGeometry { edge: 1, code: 42 }
    );

    // Body length that disagrees with the counts.
    let mut b = good.clone();
    let len_at = Header::SIZE - 8;
    let declared = u32::from_le_bytes(b[len_at..len_at + 4].try_into().unwrap()) + 1;
    b[len_at..len_at + 4].copy_from_slice(&declared.to_le_bytes());
    assert!(matches!(
        Network::from_bytes(&b),
        Err(LoadError::BodyLengthMismatch { .. })
    ));

    // A NaN turn radius in the header (the checksum, which covers the header, fixed).
    let mut b = good.clone();
    let r_at = 4 + 2 + 1 + 1 + 8 + 8;
    b[r_at..r_at + 4].copy_from_slice(&f32::NAN.to_le_bytes());
    fix_crc(&mut b);
    assert!(matches!(
        Network::from_bytes(&b),
        Err(LoadError::InvalidParameter { .. })
    ));
}

/// Loads `bytes` and, when they are accepted, exercises a planner on them.
fn load_and_use(bytes: &[u8], rng: &mut Rng) -> Result<(), LoadError> {
    let mut planner: Box<TestPlanner<'_>> = Box::new(Planner::new());
    planner.load(bytes)?;
    let net = *planner.network();
    let _ = planner.add_popup(Popup::Circle {
        centre: Vec2::new(rng.range_f32(0.0, 600.0), rng.range_f32(0.0, 600.0)),
        radius: 50.0,
    });
    for v in 0..net.vertex_count().min(8) {
        let _ = net.vertex(v);
        for e in net.out_edges(v) {
            let _ = net.edge_path(e);
        }
    }
    let q = Query {
        start: skyroute::Pose::new(rng.range_f32(0.0, 600.0), rng.range_f32(0.0, 600.0), 0.3),
        goal: Goal {
            position: Vec2::new(rng.range_f32(0.0, 600.0), rng.range_f32(0.0, 600.0)),
            heading: None,
        },
        search: Search::Dijkstra,
    };
    let _ = planner.plan(&q, planner.worst_case_work());
    Ok(())
}

#[test]
fn random_mutations_never_panic() {
    let w = world(3, 600.0, 70.0, 40.0, 3);
    let mut rng = Rng(99);
    let (mut accepted, mut rejected) = (0u32, 0u32);
    let n = cases(10_000, 100_000) as u32;
    for case in 0..n {
        let mut b = w.bytes.clone();
        let flips = 1 + rng.below(4);
        for _ in 0..flips {
            let at = rng.below(b.len() as u64) as usize;
            match rng.below(4) {
                0 => b[at] ^= 1 << rng.below(8),
                1 => b[at] = rng.next_u64() as u8,
                2 => b[at] = 0xFF,
                _ => {
                    let cut = rng.below(b.len() as u64) as usize;
                    b.truncate(cut.max(1));
                    break;
                }
            }
        }
        // Half the cases get a valid CRC so the field checks, not the checksum, decide.
        if case % 2 == 0 && b.len() > Header::SIZE {
            fix_crc(&mut b);
        }
        match load_and_use(&b, &mut rng) {
            Ok(()) => accepted += 1,
            Err(_) => rejected += 1,
        }
    }
    assert_eq!(accepted + rejected, n);
    println!("random mutations: {accepted} accepted, {rejected} rejected, no panic");
}

/// The header's mode byte as `docs/FORMAT.md` defines it (`0` roadmap, `1` landmark, `2`
/// terrain, `3` Voronoi), and each mode's name as scenarios spell `planner.mode`: every code
/// round-trips through `Mode`, the four known ones by their documented number and name, and
/// `decode` refuses every other code by name.
#[test]
fn mode_codes_and_names_follow_the_format() {
    use skyroute::network::Mode;
    let known = [
        (0u8, Mode::Roadmap, "roadmap"),
        (1, Mode::Landmark, "landmark"),
        (2, Mode::Terrain, "terrain"),
        (3, Mode::Voronoi, "voronoi"),
    ];
    for (code, mode, name) in known {
        assert_eq!(Mode::from(code), mode);
        assert_eq!(mode.code(), code);
        assert_eq!(mode.name(), name);
        assert_eq!(Mode::decode(code), Ok(mode));
    }
    for code in 4..=255u8 {
        assert_eq!(Mode::from(code), Mode::Unknown(code));
        assert_eq!(Mode::Unknown(code).code(), code);
        assert_eq!(Mode::Unknown(code).name(), "unknown");
        assert_eq!(
            Mode::decode(code),
            Err(LoadError::UnknownMode { mode: code })
        );
    }
}
