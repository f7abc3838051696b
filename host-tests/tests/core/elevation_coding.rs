//! A terrain network's elevation coding (`skyroute::network::elevation`): codes decode to
//! `base + code · step` with 255 unknown (docs/FORMAT.md), encoding rounds up and the blocking
//! code splits the codes exactly as Medeiros & da Silva's rule does, checked by a scan over all
//! 256 codes in f64; and the loader refuses an image whose coding is not finite with a positive
//! step or whose top code's bound overflows, whose widening, altitude or safety height is not
//! a finite number in range, whose widening takes an edge's band beyond any side of the grid,
//! whose edge understates the highest code under its band, which has a static obstacle, or
//! whose edge joins coincident nodes.

use host_tests::damage::{f32_bytes, fix_crc, replace_unique};
use host_tests::Rng;
use skyroute::geometry::grid::CellGrid;
use skyroute::network::elevation::{ElevationCoding, ELEVATION_BLOCKED};
use skyroute::network::write::{
    encode, EdgeSpec, NetworkSpec, ObstacleSpec, TerrainSpec, WriteError,
};
use skyroute::network::{Parameter, Section};
use skyroute::{LoadError, Network, Pose, Vec2};

/// A coding whose two numbers are unlikely to appear elsewhere in the image.
const BASE_M: f32 = 236.265_62;
const STEP_M: f32 = 3.312_5;
/// The terrain record's widening, altitude and safety height (stored side by side).
const WIDEN_M: f32 = 20.0;
const ALTITUDE_M: f32 = 900.0;
const SAFETY_M: f32 = 100.0;

fn coding(base_m: f32, step_m: f32) -> ElevationCoding {
    ElevationCoding { base_m, step_m }
}

/// A coding with a base of −500 to 3 000 m and a step of 0.01 to 40 m.
fn random_coding(rng: &mut Rng) -> ElevationCoding {
    coding(
        rng.range(-500.0, 3000.0) as f32,
        rng.range(0.01, 40.0) as f32,
    )
}

/// The smallest code whose bound reaches `x`, by scanning every code (255 if none below does).
fn scan(c: &ElevationCoding, x: f32) -> u8 {
    (0..ELEVATION_BLOCKED)
        .find(|&k| c.upper_bound(k) >= x)
        .unwrap_or(ELEVATION_BLOCKED)
}

#[test]
fn codes_decode_to_base_plus_code_steps_and_255_is_unknown() {
    let c = coding(BASE_M, STEP_M);
    for code in 0..ELEVATION_BLOCKED {
        let expected = BASE_M as f64 + code as f64 * STEP_M as f64;
        let got = c.upper_bound(code) as f64;
        assert!(
            (got - expected).abs() <= 1e-4 * expected,
            "code {code}: {got}"
        );
    }
    assert_eq!(c.upper_bound(ELEVATION_BLOCKED), f32::INFINITY);
    assert!(c.is_valid());
}

/// For random codings and elevations: `encode` gives the smallest code whose bound reaches the
/// elevation, and `blocking_code(a, s)` the smallest whose bound reaches `a − s`, both found
/// here by scanning every code's bound.
#[test]
fn encode_and_blocking_code_match_a_scan_over_every_code() {
    let mut rng = Rng(0xe1e7_a710);
    for _ in 0..2_000 {
        let c = random_coding(&mut rng);
        let top = c.upper_bound(ELEVATION_BLOCKED - 1);
        let e = rng.range(c.base_m as f64 - 50.0, top as f64 + 50.0) as f32;
        assert_eq!(c.encode(e), scan(&c, e), "{c:?} elevation {e}");
        let safety = rng.range(0.0, 300.0) as f32;
        let altitude = e + safety;
        assert_eq!(
            c.blocking_code(altitude, safety),
            scan(&c, altitude - safety),
            "{c:?} altitude {altitude} safety {safety}"
        );
    }
    let c = coding(BASE_M, STEP_M);
    assert_eq!(c.encode(f32::NAN), ELEVATION_BLOCKED);
    assert_eq!(c.blocking_code(f32::NAN, 100.0), 0);
    // An invalid coding blocks everything (fail safe) and encodes every elevation as unknown.
    for bad in [coding(BASE_M, 0.0), coding(f32::NAN, STEP_M)] {
        assert_eq!(bad.blocking_code(900.0, 100.0), 0, "{bad:?}");
        for elevation in [BASE_M - 100.0, BASE_M + 100.0] {
            assert_eq!(
                bad.encode(elevation),
                ELEVATION_BLOCKED,
                "{bad:?} {elevation}"
            );
        }
    }
}

/// Elevations exactly at a code's bound and one f32 step either side of it: the f32 division
/// that estimates the code can land on either side there, and the result must still be the
/// scan's.
#[test]
fn elevations_at_and_beside_every_bound_encode_as_the_scan_says() {
    let mut rng = Rng(0xb0_0d5);
    for _ in 0..200 {
        let c = random_coding(&mut rng);
        for k in 0..ELEVATION_BLOCKED {
            let b = c.upper_bound(k);
            for x in [b.next_down(), b, b.next_up()] {
                assert_eq!(c.encode(x), scan(&c, x), "{c:?} code {k} elevation {x}");
                assert_eq!(c.blocking_code(x + 50.0, 50.0), scan(&c, x + 50.0 - 50.0));
            }
        }
    }
}

/// A two-node terrain image with the coding above.
fn terrain_image() -> Vec<u8> {
    encode(&terrain_spec()).expect("a valid terrain spec encodes")
}

/// The two-node terrain network of [`terrain_image`].
fn terrain_spec() -> NetworkSpec {
    terrain_spec_between(Vec2::new(200.0, 200.0), Vec2::new(800.0, 700.0))
}

/// A terrain network over a 1 km grid of 100 m cells, all at code 10, with two nodes at `a`
/// and `b` joined both ways.
fn terrain_spec_between(a: Vec2, b: Vec2) -> NetworkSpec {
    let grid = CellGrid {
        origin: Vec2::new(0.0, 0.0),
        cell: 100.0,
        cols: 10,
        rows: 10,
    };
    NetworkSpec {
        origin_lat_deg: 36.5,
        origin_lon_deg: -84.2,
        turn_radius_m: 50.0,
        clearance_m: 20.0,
        vertices: [a, b]
            .iter()
            .map(|&p| Pose {
                position: p,
                heading: 0.0,
            })
            .collect(),
        edges: vec![
            EdgeSpec::line(0, 1, a.distance(b)),
            EdgeSpec::line(1, 0, a.distance(b)),
        ],
        obstacles: Vec::new(),
        grid_cell_m: 1000.0,
        landmark: None,
        voronoi: None,
        terrain: Some(TerrainSpec {
            grid,
            coding: coding(BASE_M, STEP_M),
            codes: vec![10; 100],
            widen_m: WIDEN_M,
            altitude_m: ALTITUDE_M,
            safety_height_m: SAFETY_M,
        }),
        provenance: Vec::new(),
    }
}

/// `bytes` with the consecutive f32 fields `stored` (found once in the image) replaced by
/// `new`, checksum re-fixed.
fn with_fields(bytes: &[u8], stored: &[f32], new: &[f32]) -> Vec<u8> {
    replace_unique(bytes, &f32_bytes(stored), &f32_bytes(new))
}

/// `bytes` with the coding's two numbers (stored side by side) replaced.
fn with_coding(bytes: &[u8], base_m: f32, step_m: f32) -> Vec<u8> {
    with_fields(bytes, &[BASE_M, STEP_M], &[base_m, step_m])
}

#[test]
fn a_terrain_image_with_a_bad_coding_is_refused_at_load() {
    let bytes = terrain_image();
    let net = Network::from_bytes(&bytes).expect("the valid image loads");
    assert_eq!(net.elevation_coding(), Some(coding(BASE_M, STEP_M)));
    // A tiny positive step is a valid coding, and the patched image loads.
    let fine = with_coding(&bytes, 0.0, 1e-3);
    assert!(Network::from_bytes(&fine).is_ok());
    let refused = LoadError::InvalidParameter {
        parameter: Parameter::Terrain,
    };
    for (base, step) in [
        (f32::NAN, STEP_M),
        (f32::INFINITY, STEP_M),
        (BASE_M, f32::NAN),
        (BASE_M, f32::INFINITY),
        (BASE_M, 0.0),
        (BASE_M, -STEP_M),
        // Finite numbers whose top code's bound, 3e38 + 254 · 1e37, overflows f32.
        (3e38, 1e37),
    ] {
        let damaged = with_coding(&bytes, base, step);
        assert_eq!(
            Network::from_bytes(&damaged).err(),
            Some(refused),
            "base {base}, step {step}"
        );
    }
}

/// The terrain record's other numbers: a widening, altitude or safety height that is not
/// finite, and a negative widening or safety height, are refused; zero widening and safety
/// height and a negative altitude (below the datum) load; a widening that takes an edge's band
/// beyond the elevation grid is refused naming the edge.
#[test]
fn a_terrain_image_with_bad_heights_or_widening_is_refused_at_load() {
    let bytes = terrain_image();
    let stored = [WIDEN_M, ALTITUDE_M, SAFETY_M];
    for ok in [
        [0.0, ALTITUDE_M, 0.0],
        [WIDEN_M, -50.0, SAFETY_M],
        [150.0, 0.0, 1e4],
    ] {
        let patched = with_fields(&bytes, &stored, &ok);
        let net = Network::from_bytes(&patched).unwrap_or_else(|e| panic!("{ok:?}: {e:?}"));
        let t = net.terrain().unwrap();
        assert_eq!([t.widen_m, t.altitude_m, t.safety_height_m], ok);
    }
    let refused = Some(LoadError::InvalidParameter {
        parameter: Parameter::Terrain,
    });
    for bad in [
        [f32::NAN, ALTITUDE_M, SAFETY_M],
        [f32::INFINITY, ALTITUDE_M, SAFETY_M],
        [-1.0, ALTITUDE_M, SAFETY_M],
        [WIDEN_M, f32::NAN, SAFETY_M],
        [WIDEN_M, f32::INFINITY, SAFETY_M],
        [WIDEN_M, f32::NEG_INFINITY, SAFETY_M],
        [WIDEN_M, ALTITUDE_M, f32::NAN],
        [WIDEN_M, ALTITUDE_M, f32::INFINITY],
        [WIDEN_M, ALTITUDE_M, -1.0],
    ] {
        let damaged = with_fields(&bytes, &stored, &bad);
        assert_eq!(Network::from_bytes(&damaged).err(), refused, "{bad:?}");
    }
    // The edges run from (200, 200) to (800, 700) in a 1 km grid: a band of 201 m crosses
    // the grid's edge at 0 m, one of 199 m does not.
    let near = with_fields(&bytes, &stored, &[199.0, ALTITUDE_M, SAFETY_M]);
    assert!(Network::from_bytes(&near).is_ok());
    let beyond = with_fields(&bytes, &stored, &[201.0, ALTITUDE_M, SAFETY_M]);
    assert_eq!(
        Network::from_bytes(&beyond).err(),
        Some(LoadError::EdgeOutsideTerrain { edge: 0 })
    );
}

/// A terrain edge's own checks (the writer validates what it writes with the loader and
/// returns its verdict): a cost below the distance between the nodes (beyond the 10⁻⁵
/// rounding allowance) is refused naming the edge, and so is a line between nodes closer than
/// 10⁻³ turn radii (5 cm here), which has no direction to turn from.
#[test]
fn a_terrain_edge_below_its_length_or_between_nodes_too_close_is_refused() {
    let length = terrain_spec().edges[1].cost;
    let mut cheap = terrain_spec();
    cheap.edges[1].cost = length * (1.0 - 1e-4);
    assert_eq!(
        encode(&cheap).err(),
        Some(WriteError::Invalid(LoadError::CostBelowLength { edge: 1 }))
    );
    let mut rounded = terrain_spec();
    rounded.edges[1].cost = length * (1.0 - 1e-6);
    assert!(encode(&rounded).is_ok(), "within the rounding allowance");

    for (gap, loads) in [(0.049, false), (0.0, false), (0.06, true)] {
        let mut close = terrain_spec();
        let a = close.vertices[0].position;
        close.vertices[1].position = a + Vec2::new(gap, 0.0);
        close.edges = vec![EdgeSpec::line(0, 1, gap)];
        let malformed = LoadError::Malformed {
            section: Section::Edges,
            index: 0,
        };
        let got = encode(&close).err();
        if loads {
            assert_eq!(got, None, "nodes {gap} m apart");
        } else {
            assert_eq!(
                got,
                Some(WriteError::Invalid(malformed)),
                "nodes {gap} m apart"
            );
        }
    }
}

/// The band of an edge (the segment widened by the record's widening) must lie inside the
/// elevation grid on each of its four sides: with the nodes 100 m from one side of the 1 km
/// grid and at least 300 m from the others, a widening of 99 m loads and one of 101 m is
/// refused naming the edge.
#[test]
fn a_terrain_edge_band_beyond_any_one_side_of_the_grid_is_refused() {
    let sides = [
        ("west", Vec2::new(100.0, 400.0), Vec2::new(600.0, 600.0)),
        ("east", Vec2::new(400.0, 400.0), Vec2::new(900.0, 600.0)),
        ("south", Vec2::new(400.0, 100.0), Vec2::new(600.0, 600.0)),
        ("north", Vec2::new(400.0, 400.0), Vec2::new(600.0, 900.0)),
    ];
    let stored = [WIDEN_M, ALTITUDE_M, SAFETY_M];
    for (side, a, b) in sides {
        let bytes = encode(&terrain_spec_between(a, b)).expect("a valid terrain spec encodes");
        let inside = with_fields(&bytes, &stored, &[99.0, ALTITUDE_M, SAFETY_M]);
        assert!(Network::from_bytes(&inside).is_ok(), "{side}: 99 m");
        let beyond = with_fields(&bytes, &stored, &[101.0, ALTITUDE_M, SAFETY_M]);
        assert_eq!(
            Network::from_bytes(&beyond).err(),
            Some(LoadError::EdgeOutsideTerrain { edge: 0 }),
            "{side}: 101 m"
        );
    }
}

/// An edge's stored highest code (`aux`) may not understate the cells under its band: one
/// cell raised above it in the table is refused naming the edge and both codes. Every cell
/// lowered below it loads (an overstated code is conservative: the edge is only blocked at
/// more altitudes).
#[test]
fn a_terrain_edge_code_below_its_cells_is_refused_and_one_above_loads() {
    let bytes = terrain_image();
    let net = Network::from_bytes(&bytes).expect("loads");
    let t = *net.terrain().expect("terrain record");
    assert_eq!(net.edge_highest_code(0), Some(10));
    let grid = net.terrain_grid().expect("grid");
    // With no provenance records the elevation table closes the image.
    let table = bytes.len() - (t.cols * t.rows) as usize;
    let (c, r) = grid
        .cell_of(Vec2::new(500.0, 450.0))
        .expect("the edge's middle");
    let mut raised = bytes.clone();
    raised[table + (r * t.cols + c) as usize] = 11;
    fix_crc(&mut raised);
    assert_eq!(
        Network::from_bytes(&raised).err(),
        Some(LoadError::EdgeElevationUnderstated {
            edge: 0,
            stored: 10,
            computed: 11
        })
    );
    let mut lowered = bytes.clone();
    lowered[table..].fill(9);
    fix_crc(&mut lowered);
    let net = Network::from_bytes(&lowered).expect("an overstated code loads");
    assert_eq!(net.edge_highest_code(0), Some(10));
    assert_eq!(net.elevation_code(c, r), 9);
}

/// A terrain network has no static obstacles (its search checks terrain cells and pop-ups,
/// and its work bound has no obstacle term): a circle obstacle, which has no polygon points,
/// is refused as well as a polygon.
#[test]
fn a_terrain_network_with_a_static_obstacle_is_refused() {
    let refused = Some(WriteError::Invalid(LoadError::InvalidParameter {
        parameter: Parameter::Terrain,
    }));
    let mut circle = terrain_spec();
    circle.obstacles.push(ObstacleSpec::Circle {
        centre: Vec2::new(500.0, 200.0),
        radius: 20.0,
    });
    assert_eq!(encode(&circle).err(), refused, "a circle");
    let mut polygon = terrain_spec();
    polygon.obstacles.push(ObstacleSpec::Polygon(vec![
        Vec2::new(500.0, 100.0),
        Vec2::new(600.0, 100.0),
        Vec2::new(550.0, 150.0),
    ]));
    assert_eq!(encode(&polygon).err(), refused, "a polygon");
}

/// Coincident nodes are refused even with a turn radius so small (10⁻⁴⁴ m, a subnormal f32)
/// that 10⁻³ of it rounds to zero, so the minimum length between nodes is no guard.
#[test]
fn coincident_terrain_nodes_are_refused_at_any_turn_radius() {
    let mut tiny = terrain_spec();
    tiny.turn_radius_m = 1e-44;
    assert_eq!(1e-3 * tiny.turn_radius_m, 0.0);
    assert!(encode(&tiny).is_ok(), "distinct nodes load at any radius");
    let a = tiny.vertices[0].position;
    tiny.vertices[1].position = a;
    tiny.edges = vec![EdgeSpec::line(0, 1, 0.0)];
    assert_eq!(
        encode(&tiny).err(),
        Some(WriteError::Invalid(LoadError::Malformed {
            section: Section::Edges,
            index: 0
        }))
    );
}

/// Only a roadmap may be three-dimensional: a terrain network is neither written with the
/// vertical section nor loaded with its flag.
#[test]
fn a_terrain_network_with_the_vertical_flag_is_refused() {
    let mut flagged = terrain_image();
    flagged[7] |= skyroute::network::format::FLAG_VERTICAL;
    fix_crc(&mut flagged);
    assert_eq!(
        Network::from_bytes(&flagged).unwrap_err(),
        LoadError::InvalidParameter {
            parameter: Parameter::Flags
        }
    );
    let spec = terrain_spec();
    let vertical = skyroute::network::write::VerticalSpec {
        limits: skyroute::geometry::vertical::VerticalLimits::niendorf(25.0),
        altitudes: vec![0.0; spec.vertices.len()],
        heights: Vec::new(),
    };
    assert!(matches!(
        skyroute::network::write::encode_three_dimensional(&spec, &vertical, None),
        Err(skyroute::network::write::WriteError::BadVertical(_))
    ));
}
