//! The landmark section of a network image field by field, on a network small enough to read
//! whole: two landmarks crossed in four directions, two weathers, a start and a goal, and three
//! straight chains, written by the core's own writer. Every accessor reads back what was
//! written; each damage of one field (the checksum re-fixed) is refused by its own check with
//! the numbers it names, and a value just inside each tolerance still loads.

use host_tests::damage::{f32_bytes, find_unique, fix_crc, replace_unique};
use host_tests::world::world;
use skyroute::geometry::hermite::{FlyLimits, LineElement};
use skyroute::network::write::{encode, EdgeSpec, LandmarkSiteSpec, LandmarkSpec, NetworkSpec};
use skyroute::network::{Parameter, Section};
use skyroute::{LoadError, Network, Pose, Vec2};

/// Nominal speed, m/s.
const SPEED: f32 = 25.0;
/// The heading of direction 0 (30°): the chains fly it.
const HEADING: f32 = core::f32::consts::FRAC_PI_6;
/// Directions per landmark.
const D: u32 = 4;
/// Landmarks.
const L: u32 = 2;
/// Weathers.
const W: u32 = 2;

fn along(s: f32) -> Vec2 {
    Vec2::from_angle(HEADING) * s
}

fn element(s: f32) -> LineElement {
    LineElement::new(along(s), Vec2::from_angle(HEADING) * SPEED)
}

/// The quality of landmark `l` in weather `w` and direction `k`: all sixteen distinct.
fn quality(l: u32, w: u32, k: u32) -> f32 {
    ((l * W + w) * D + k + 1) as f32 / 20.0
}

/// Landmark 0 at the origin and landmark 1 1 km along 30°; the start 600 m before landmark 0
/// and the goal 1 km after landmark 1, both heading 30°. Vertices 0–3 and 4–7 are the
/// landmarks' overflights (direction k heading 30° + k·90°), 8 the start, 9 the goal. The
/// edges, grouped by source as written: 0 → 4 through a middle element (2 pieces), 4 → 9 and
/// 8 → 0. The distinct elements in the order the chains first use them: landmark 0, the
/// middle, landmark 1, the goal, the start.
fn spec() -> NetworkSpec {
    let mut vertices = Vec::new();
    for l in 0..L {
        for k in 0..D {
            vertices.push(Pose {
                position: along(1000.0 * l as f32),
                heading: HEADING + k as f32 * core::f32::consts::FRAC_PI_2,
            });
        }
    }
    for s in [-600.0, 2000.0] {
        vertices.push(Pose {
            position: along(s),
            heading: HEADING,
        });
    }
    let qualities = (0..L)
        .flat_map(|l| (0..W).flat_map(move |w| (0..D).map(move |k| quality(l, w, k))))
        .collect();
    NetworkSpec {
        origin_lat_deg: 48.1,
        origin_lon_deg: 11.6,
        turn_radius_m: SPEED * SPEED / 5.0,
        clearance_m: 10.0,
        vertices,
        edges: vec![
            EdgeSpec::chain(0, 4, 1000.0),
            EdgeSpec::chain(4, 9, 1000.0),
            EdgeSpec::chain(8, 0, 600.0),
        ],
        obstacles: Vec::new(),
        grid_cell_m: 100.0,
        terrain: None,
        voronoi: None,
        landmark: Some(LandmarkSpec {
            directions: D,
            weather_count: W,
            v_nominal: SPEED,
            limits: FlyLimits {
                v_min: 15.0,
                v_max: 35.0,
                a_long_min: -3.0,
                a_long_max: 3.0,
                a_lat_max: 5.0,
            },
            landmarks: vec![
                LandmarkSiteSpec {
                    position: along(0.0),
                    d_max_m: 700.0,
                },
                LandmarkSiteSpec {
                    position: along(1000.0),
                    d_max_m: 900.0,
                },
            ],
            qualities,
            start_vertex: Some(8),
            goal_vertex: Some(9),
            start_range_m: 800.0,
            chains: vec![
                vec![element(0.0), element(500.0), element(1000.0)],
                vec![element(1000.0), element(2000.0)],
                vec![element(-600.0), element(0.0)],
            ],
        }),
        provenance: Vec::new(),
    }
}

/// The written image and where its landmark tables start.
struct Image {
    bytes: Vec<u8>,
    /// The landmark record.
    record: usize,
    /// The landmark sites (12 bytes each: x, y, d_max).
    sites: usize,
    /// The qualities (4 bytes each).
    rosettes: usize,
    /// The chain offsets (4 bytes each).
    offsets: usize,
    /// The chain index list (2 bytes each).
    indices: usize,
    /// The distinct elements (16 bytes each: x, y, vx, vy).
    elements: usize,
}

fn image() -> Image {
    let bytes = encode(&spec()).expect("the small landmark network is written");
    let mut key = Vec::new();
    for x in [L, D, W] {
        key.extend_from_slice(&x.to_le_bytes());
    }
    key.extend_from_slice(&SPEED.to_le_bytes());
    let record = find_unique(&bytes, &key);
    let sites = record + 56;
    let rosettes = sites + 12 * L as usize;
    let offsets = rosettes + 4 * (L * W * D) as usize;
    let indices = offsets + 4 * 4;
    let elements = indices + 2 * 7;
    assert_eq!(
        bytes.len(),
        elements + 16 * 5,
        "nothing follows the elements"
    );
    Image {
        bytes,
        record,
        sites,
        rosettes,
        offsets,
        indices,
        elements,
    }
}

impl Image {
    /// The image with `f` applied and the checksum re-fixed, as the loader answers it.
    fn damaged(&self, f: impl FnOnce(&mut Vec<u8>)) -> Result<(), LoadError> {
        let mut b = self.bytes.clone();
        f(&mut b);
        fix_crc(&mut b);
        Network::from_bytes(&b).map(|_| ())
    }

    fn with_f32(&self, at: usize, x: f32) -> Result<(), LoadError> {
        self.damaged(|b| b[at..at + 4].copy_from_slice(&x.to_le_bytes()))
    }

    fn with_u32(&self, at: usize, x: u32) -> Result<(), LoadError> {
        self.damaged(|b| b[at..at + 4].copy_from_slice(&x.to_le_bytes()))
    }

    /// The image with element `i`'s velocity turned by `angle` and scaled by `scale`.
    fn with_velocity(&self, i: usize, angle: f32, scale: f32) -> Result<(), LoadError> {
        let v = Vec2::from_angle(HEADING + angle) * (SPEED * scale);
        let at = self.elements + 16 * i + 8;
        self.damaged(|b| b[at..at + 8].copy_from_slice(&f32_bytes(&[v.x, v.y])))
    }

    /// The image with element `i` moved to `p`.
    fn with_position(&self, i: usize, p: Vec2) -> Result<(), LoadError> {
        let at = self.elements + 16 * i;
        self.damaged(|b| b[at..at + 8].copy_from_slice(&f32_bytes(&[p.x, p.y])))
    }
}

fn invalid_landmark_parameter(r: Result<(), LoadError>) -> bool {
    matches!(
        r,
        Err(LoadError::InvalidParameter {
            parameter: Parameter::Landmark
        })
    )
}

#[test]
fn every_accessor_reads_back_what_was_written() {
    let img = image();
    let net = Network::from_bytes(&img.bytes).expect("the small landmark network loads");
    let spec = spec();
    let written = spec.landmark.as_ref().unwrap();
    let record = net.landmark().expect("a landmark network has its record");
    assert_eq!(
        (
            record.landmark_count,
            record.directions,
            record.weather_count
        ),
        (L, D, W)
    );
    assert_eq!((record.start_vertex, record.goal_vertex), (8, 9));
    assert_eq!((record.element_count, record.chain_index_count), (5, 7));
    assert_eq!(net.fly_limits(), Some(written.limits));
    for (l, site) in written.landmarks.iter().enumerate() {
        assert_eq!(
            net.landmark_site(l as u32),
            Some((site.position, site.d_max_m))
        );
    }
    assert_eq!(net.landmark_site(L), None);
    for l in 0..L {
        for w in 0..W {
            for k in 0..D {
                assert_eq!(net.rosette_quality(l, w, k), Some(quality(l, w, k)));
            }
        }
    }
    for (l, w, k) in [(L, 0, 0), (0, W, 0), (0, 0, D), (L, W, D)] {
        assert_eq!(net.rosette_quality(l, w, k), None, "({l}, {w}, {k})");
    }
    // The chains: elements, pieces and their ends.
    for (e, chain) in written.chains.iter().enumerate() {
        let e = e as u32;
        let range = net.chain_elements(e);
        let read: Vec<LineElement> = range
            .clone()
            .map(|k| net.chain_element(k).unwrap())
            .collect();
        assert_eq!(&read, chain, "edge {e}'s elements");
        let pieces = chain.len() as u32 - 1;
        assert_eq!(net.chain_piece_count(e), pieces);
        for k in 0..pieces {
            let piece = net.chain_piece(e, k).expect("each piece is rebuilt");
            assert_eq!(piece.start(), chain[k as usize]);
            assert_eq!(piece.end(), chain[k as usize + 1]);
        }
        assert!(
            net.chain_piece(e, pieces).is_none(),
            "edge {e} has {pieces} pieces"
        );
    }
    assert_eq!(
        (
            net.chain_elements(0),
            net.chain_elements(1),
            net.chain_elements(2)
        ),
        (0..3, 3..5, 5..7)
    );
    assert_eq!(net.chain_elements(3), 0..0, "there are three edges");
    assert!(net.chain_element(7).is_none() && net.chain_piece(3, 0).is_none());
    assert_eq!(net.max_chain_pieces(), 2);
    // A roadmap network has none of it.
    let roadmap = world(1, 800.0, 60.0, 40.0, 1).bytes;
    let roadmap = Network::from_bytes(&roadmap).unwrap();
    assert!(roadmap.landmark().is_none() && roadmap.fly_limits().is_none());
    assert!(roadmap.landmark_site(0).is_none() && roadmap.rosette_quality(0, 0, 0).is_none());
    assert_eq!(
        (roadmap.chain_elements(0), roadmap.max_chain_pieces()),
        (0..0, 0)
    );
    assert!(roadmap.chain_element(0).is_none() && roadmap.chain_piece(0, 0).is_none());
}

/// Every curve of length ℓ from a to b lies in the ellipse `|PA| + |PB| ≤ ℓ`, within ℓ/2 of
/// the midpoint: the box is the midpoint ± (ℓ/2 + 10⁻⁴ℓ + 1 cm).
#[test]
fn an_edges_reach_is_the_box_of_its_length_ellipse() {
    let img = image();
    let net = Network::from_bytes(&img.bytes).unwrap();
    let (a, b) = (Vec2::new(-100.0, 20.0), Vec2::new(200.0, 420.0)); // 500 m apart
    let (lo, hi) = net.edge_reach(a, b, 600.0);
    let r = 300.0 + 0.06 + 0.01;
    let close = |p: Vec2, q: Vec2| p.distance(q) < 1e-3;
    assert!(close(lo, Vec2::new(50.0 - r, 220.0 - r)), "{lo:?}");
    assert!(close(hi, Vec2::new(50.0 + r, 220.0 + r)), "{hi:?}");
    // The ellipse's points (semi-axes 300 and √(300² − 250²)) all lie in the box.
    let (major, minor) = (300.0f32, (300.0f32 * 300.0 - 250.0 * 250.0).sqrt());
    let axis = (b - a) * (1.0 / 500.0);
    for i in 0..360 {
        let t = (i as f32).to_radians();
        let p = Vec2::new(50.0, 220.0) + axis * (major * t.cos()) + axis.perp() * (minor * t.sin());
        assert!((p.distance(a) + p.distance(b) - 600.0).abs() < 0.01);
        assert!(
            p.x >= lo.x && p.y >= lo.y && p.x <= hi.x && p.y <= hi.y,
            "{p:?}"
        );
    }
}

/// The record's numbers: the nominal speed, the vehicle limits and the start range.
#[test]
fn each_bad_number_of_the_landmark_record_is_refused() {
    let img = image();
    let rec = img.record;
    for v in [f32::INFINITY, 0.0, -SPEED] {
        assert!(
            invalid_landmark_parameter(img.with_f32(rec + 12, v)),
            "nominal speed {v}"
        );
    }
    // v_min above v_max.
    assert!(invalid_landmark_parameter(img.with_f32(rec + 16, 40.0)));
    for range in [-1.0, f32::INFINITY, f32::NAN] {
        assert!(
            invalid_landmark_parameter(img.with_f32(rec + 44, range)),
            "start range {range}"
        );
    }
    assert_eq!(
        img.with_f32(rec + 44, 0.0),
        Ok(()),
        "a start range of 0 is valid"
    );
}

/// The start and goal vertices follow the overflights, in that order; without them the
/// vertex count must still match.
#[test]
fn the_start_and_goal_vertices_must_follow_the_overflights() {
    let img = image();
    let (start, goal) = (img.record + 36, img.record + 40);
    let absent = u32::MAX;
    assert_eq!(
        img.with_u32(start, 9),
        Err(LoadError::EndpointVertexMismatch {
            stored: 9,
            expected: 8
        })
    );
    assert_eq!(
        img.with_u32(goal, 8),
        Err(LoadError::EndpointVertexMismatch {
            stored: 8,
            expected: 9
        })
    );
    assert_eq!(
        img.with_u32(start, absent),
        Err(LoadError::EndpointVertexMismatch {
            stored: 9,
            expected: 8
        })
    );
    let neither = img.damaged(|b| {
        b[start..start + 4].copy_from_slice(&absent.to_le_bytes());
        b[goal..goal + 4].copy_from_slice(&absent.to_le_bytes());
    });
    assert_eq!(
        neither,
        Err(LoadError::LandmarkVertexCount {
            vertices: 10,
            expected: 8
        })
    );
}

/// Landmark sites must be finite with a non-negative `d_max`, and each landmark's overflights
/// at its position; qualities must lie in [0, 1].
#[test]
fn each_bad_site_or_quality_is_refused() {
    let img = image();
    let site1 = img.sites + 12;
    for field in 0..3 {
        assert_eq!(
            img.with_f32(site1 + 4 * field, f32::NAN),
            Err(LoadError::NonFinite {
                section: Section::Landmarks,
                index: 1
            }),
            "field {field}"
        );
    }
    assert!(invalid_landmark_parameter(img.with_f32(site1 + 8, -1.0)));
    assert_eq!(img.with_f32(site1 + 8, 0.0), Ok(()), "d_max 0 is valid");
    // Landmark 1 moved 1 m along y: its first overflight, vertex 4, is off it.
    let y = along(1000.0).y + 1.0;
    assert_eq!(
        img.with_f32(site1 + 4, y),
        Err(LoadError::VertexOffLandmark { vertex: 4 })
    );
    assert_eq!(
        img.with_f32(img.sites, 1.0),
        Err(LoadError::VertexOffLandmark { vertex: 0 })
    );
    // Landmark 0 (at the origin, as its overflights are) moved north by exactly its tolerance,
    // 10⁻⁴ of the coordinate plus 1 cm: the f32 offset d whose distance `√(d²)` equals
    // `10⁻⁴·d + 0.01` loads; the next f32 above it does not.
    let exact: Vec<f32> = (0..250_000u32)
        .map(|i| f32::from_bits(0.0099f32.to_bits() + i))
        .filter(|&d| (d * d).sqrt() == 1e-4 * d + 0.01)
        .collect();
    assert_eq!(exact.len(), 1, "{exact:?}");
    let d = exact[0];
    assert_eq!(img.with_f32(img.sites + 4, d), Ok(()), "{d} m off");
    assert_eq!(
        img.with_f32(img.sites + 4, f32::from_bits(d.to_bits() + 1)),
        Err(LoadError::VertexOffLandmark { vertex: 0 })
    );
    let last = (L * W * D - 1) as usize;
    for (i, q) in [(0, -0.01), (last, 1.01), (7, f32::NAN)] {
        assert_eq!(
            img.with_f32(img.rosettes + 4 * i, q),
            Err(LoadError::QualityOutOfRange { index: i as u32 }),
            "quality {q} at {i}"
        );
    }
    for (i, q) in [(0, 0.0), (last, 1.0)] {
        assert_eq!(img.with_f32(img.rosettes + 4 * i, q), Ok(()), "quality {q}");
    }
}

/// A chain of fewer than two elements, an index past the elements, a non-finite element or
/// one off the nominal speed by more than 10⁻³ of it are refused.
#[test]
fn each_bad_chain_table_entry_is_refused() {
    let img = image();
    // Offsets 0, 1, 5, 7: edge 0 keeps one element.
    assert_eq!(
        img.with_u32(img.offsets + 4, 1),
        Err(LoadError::ChainTooShort {
            edge: 0,
            elements: 1
        })
    );
    // The last index (edge 2's landmark-0 element, 0) set to 5.
    let at = img.indices + 2 * 6;
    assert_eq!(
        img.damaged(|b| b[at..at + 2].copy_from_slice(&5u16.to_le_bytes())),
        Err(LoadError::IndexOutOfRange {
            section: Section::ChainIndices,
            index: 6,
            value: 5,
            limit: 5
        })
    );
    for field in 0..4 {
        assert_eq!(
            img.with_f32(img.elements + 16 * 3 + 4 * field, f32::NAN),
            Err(LoadError::NonFinite {
                section: Section::ChainElements,
                index: 3
            }),
            "field {field}"
        );
    }
    // The middle element (1) 0.05 % fast loads; 0.2 % fast is refused, its speed named.
    assert_eq!(img.with_velocity(1, 0.0, 1.0005), Ok(()));
    match img.with_velocity(1, 0.0, 1.002) {
        Err(LoadError::ElementSpeed {
            element: 1,
            speed_mm_s,
        }) => assert!((25_049..=25_051).contains(&speed_mm_s), "{speed_mm_s}"),
        other => panic!("{other:?}"),
    }
}

/// Each chain edge: `aux` 0, distinct consecutive elements, its first and last elements on its
/// vertices' poses (position and heading), a cost not below its chords, its reach in the grid.
#[test]
fn each_bad_chain_edge_is_refused() {
    let img = image();
    // Edge 0's record: target 4, aux 0, cost 1000.
    let mut stored = 4u16.to_le_bytes().to_vec();
    stored.push(0);
    stored.extend_from_slice(&1000.0f32.to_le_bytes());
    let with_record = |aux: u8, cost: f32| {
        let mut new = stored.clone();
        new[2] = aux;
        new[3..].copy_from_slice(&cost.to_le_bytes());
        Network::from_bytes(&replace_unique(&img.bytes, &stored, &new)).map(|_| ())
    };
    assert_eq!(
        with_record(1, 1000.0),
        Err(LoadError::Malformed {
            section: Section::Edges,
            index: 0
        })
    );
    // The chords sum to 1 000 m: a cost 1.5 cm short loads, 2.5 cm short does not.
    assert_eq!(with_record(0, 999.985), Ok(()));
    assert_eq!(
        with_record(0, 999.975),
        Err(LoadError::ChainShorterThanChords { edge: 0 })
    );
    // The middle element moved onto the first.
    assert_eq!(
        img.with_position(1, along(0.0)),
        Err(LoadError::CoincidentElements {
            edge: 0,
            element: 1
        })
    );
    // The goal's element (3, edge 1's last) 5 m off the goal.
    match img.with_position(3, along(2000.0) + Vec2::new(0.0, 5.0)) {
        Err(LoadError::ChainMissesVertex {
            edge: 1,
            vertex: 9,
            miss_mm,
        }) => assert!((4_999..=5_001).contains(&miss_mm), "{miss_mm}"),
        other => panic!("{other:?}"),
    }
    // The start's element (4, edge 2's first) turned 0.01 rad off the start's heading; 5·10⁻⁴
    // rad is within the tolerance.
    assert_eq!(
        img.with_velocity(4, 0.01, 1.0),
        Err(LoadError::ChainMissesVertex {
            edge: 2,
            vertex: 8,
            miss_mm: 0
        })
    );
    assert_eq!(img.with_velocity(4, 5e-4, 1.0), Ok(()));
}

/// The grid moved north (its origin's y) to 400 m south of landmark 0: the southernmost reach
/// (edge 2's: its midpoint 150 m south of landmark 0, half-width 300.07 m) leaves it on the
/// south side alone, and that edge is refused (edges are checked before the vertices' margins).
/// Moved to 1 000 m south, every reach and margin still fits.
#[test]
fn an_edge_reaching_out_of_the_grid_on_one_side_is_refused() {
    let img = image();
    let net = Network::from_bytes(&img.bytes).unwrap();
    let y = net.header().grid_origin_y;
    let (stored, moved) = (y.to_le_bytes(), (-400.0f32).to_le_bytes());
    assert!(y < -1000.0, "the grid starts {y} m south");
    let b = replace_unique(&img.bytes, &stored, &moved);
    assert_eq!(
        Network::from_bytes(&b).map(|_| ()),
        Err(LoadError::EdgeOutsideGrid { edge: 2 })
    );
    let b = replace_unique(&img.bytes, &stored, &(-1000.0f32).to_le_bytes());
    assert_eq!(
        Network::from_bytes(&b).map(|_| ()),
        Ok(()),
        "1 000 m south holds it"
    );
}
