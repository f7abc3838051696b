//! The loader's checks of a Voronoi network's own numbers (`network/voronoi.rs`): each bad
//! field of the Voronoi record, of a threat site, of the corner table and of an edge is refused
//! by name, even with a valid checksum, and the values at the edge of each range load.

use host_tests::damage::{f32_bytes, replace_unique};
use skyroute::geometry::spline::table::{
    build_corner_table, table_angle, table_ratio, CornerBound, TABLE_ANGLES, TABLE_RATIOS,
};
use skyroute::network::write::{
    encode, EdgeSpec, NetworkSpec, ObstacleSpec, VoronoiSpec, WriteError,
};
use skyroute::network::{Parameter, Section};
use skyroute::{LoadError, Network, Pose, Vec2};

/// Numbers unlikely to appear elsewhere in the image, so each is found once by its bytes.
const WEIGHT: f32 = 0.437_5;
const KAPPA: f32 = 0.003_906_25;
const BOUNDS: [f32; 4] = [-1_003.5, -2_007.25, 5_011.75, 4_013.125];
const SITE: (f32, f32, f32) = (1_517.375, 1_021.625, 733.812_5);

/// Two vertices joined both ways, one polygon obstacle, one threat site, and the corner table.
fn spec() -> NetworkSpec {
    let (a, b) = (Vec2::new(0.0, 0.0), Vec2::new(3_000.0, 2_000.0));
    let length = a.distance(b);
    NetworkSpec {
        origin_lat_deg: 36.5,
        origin_lon_deg: -84.2,
        turn_radius_m: 1.0 / KAPPA,
        clearance_m: 20.0,
        vertices: vec![Pose::new(a.x, a.y, 0.0), Pose::new(b.x, b.y, 0.0)],
        edges: vec![EdgeSpec::line(0, 1, length), EdgeSpec::line(1, 0, length)],
        obstacles: vec![ObstacleSpec::Polygon(vec![
            Vec2::new(2_000.0, -500.0),
            Vec2::new(2_500.0, -500.0),
            Vec2::new(2_500.0, 0.0),
        ])],
        grid_cell_m: 1_000.0,
        landmark: None,
        voronoi: Some(VoronoiSpec {
            threats: vec![(Vec2::new(SITE.0, SITE.1), SITE.2)],
            threat_weight: WEIGHT,
            kappa_max: KAPPA,
            bounds: (
                Vec2::new(BOUNDS[0], BOUNDS[1]),
                Vec2::new(BOUNDS[2], BOUNDS[3]),
            ),
            corner_table: build_corner_table().to_vec(),
        }),
        terrain: None,
        provenance: Vec::new(),
    }
}

/// The record's weight, curvature limit and box, stored side by side, replaced.
fn with_record(bytes: &[u8], weight: f32, kappa: f32, bounds: [f32; 4]) -> Vec<u8> {
    let stored = f32_bytes(&[&[WEIGHT, KAPPA][..], &BOUNDS[..]].concat());
    let new = f32_bytes(&[&[weight, kappa][..], &bounds[..]].concat());
    replace_unique(bytes, &stored, &new)
}

const REFUSED: LoadError = LoadError::InvalidParameter {
    parameter: Parameter::Voronoi,
};

/// The corner table read in place: every node as built, and none past the last angle or the
/// last ratio (either alone, as `CornerBound` documents), where a row-major index would still
/// fall inside the table.
#[test]
fn the_corner_table_reads_back_in_place_and_nothing_outside_its_grid() {
    let bytes = encode(&spec()).unwrap();
    let net = Network::from_bytes(&bytes).unwrap();
    let stored = net.corner_table().expect("a Voronoi network");
    let built = build_corner_table();
    for i in 0..TABLE_ANGLES {
        for j in 0..TABLE_RATIOS {
            assert_eq!(stored.node(i, j), built.node(i, j), "({i}, {j})");
            assert!(stored.node(i, j).is_some());
        }
    }
    for (i, j) in [
        (0, TABLE_RATIOS),
        (TABLE_ANGLES - 2, TABLE_RATIOS + 1),
        (TABLE_ANGLES, 0),
        (usize::MAX, 0),
        (0, usize::MAX),
    ] {
        assert_eq!(stored.node(i, j), None, "({i}, {j})");
        assert_eq!(built.node(i, j), None, "({i}, {j})");
    }
}

/// A straight edge's path leaves its source heading for its target and ends there, as long as
/// the segment; its length is the segment's.
#[test]
fn a_line_edge_runs_from_its_source_to_its_target() {
    let bytes = encode(&spec()).unwrap();
    let net = Network::from_bytes(&bytes).unwrap();
    assert_eq!(net.origin_deg(), (36.5, -84.2));
    for e in 0..net.edge_count() {
        let edge = net.edge(e).unwrap();
        let (a, b) = (
            net.vertex(edge.source).unwrap().position,
            net.vertex(edge.target).unwrap().position,
        );
        let path = net.edge_path(e).unwrap();
        assert_eq!(path.start.position, a);
        assert!((path.length() - a.distance(b)).abs() < 1e-2, "edge {e}");
        assert!(
            (net.edge_length(e).unwrap() - a.distance(b)).abs() < 1e-2,
            "edge {e}"
        );
        let end = path.end().position;
        assert!(
            end.distance(b) < 1e-2,
            "edge {e} ends at {end:?}, its target is {b:?}"
        );
    }
}

#[test]
fn a_voronoi_record_out_of_range_is_refused_at_load() {
    let bytes = encode(&spec()).expect("the Voronoi spec encodes");
    let v = *Network::from_bytes(&bytes)
        .expect("the valid image loads")
        .voronoi()
        .unwrap();
    assert_eq!(
        (v.threat_weight, v.kappa_max, v.bounds),
        (WEIGHT, KAPPA, BOUNDS)
    );
    // The ends of the weight's range load (the edge costs, k · length, stay above the bound).
    for weight in [0.0, 1.0] {
        let ok = with_record(&bytes, weight, KAPPA, BOUNDS);
        assert!(Network::from_bytes(&ok).is_ok(), "weight {weight}");
    }
    let [w, s, e, n] = BOUNDS;
    for (weight, kappa, bounds) in [
        (-1e-3, KAPPA, BOUNDS),
        (1.001, KAPPA, BOUNDS),
        (f32::NAN, KAPPA, BOUNDS),
        (WEIGHT, 0.0, BOUNDS),
        (WEIGHT, -KAPPA, BOUNDS),
        (WEIGHT, f32::INFINITY, BOUNDS),
        (WEIGHT, f32::NAN, BOUNDS),
        (WEIGHT, KAPPA, [f32::NAN, s, e, n]),
        (WEIGHT, KAPPA, [w, f32::NEG_INFINITY, e, n]),
        (WEIGHT, KAPPA, [w, s, f32::INFINITY, n]),
        (WEIGHT, KAPPA, [w, s, e, f32::NAN]),
        (WEIGHT, KAPPA, [e, s, e, n]),
        (WEIGHT, KAPPA, [w, n, e, n]),
        (WEIGHT, KAPPA, [e, n, w, s]),
    ] {
        let damaged = with_record(&bytes, weight, kappa, bounds);
        assert_eq!(
            Network::from_bytes(&damaged).err(),
            Some(REFUSED),
            "weight {weight}, kappa {kappa}, bounds {bounds:?}"
        );
    }
    // The table's dimensions, stored after the box, size the table: other dimensions in the
    // same image disagree with its length.
    for (angles, ratios) in [
        (TABLE_ANGLES - 1, TABLE_RATIOS),
        (TABLE_ANGLES, TABLE_RATIOS + 1),
    ] {
        let dims = |a: usize, r: usize| [a as u32, r as u32].map(u32::to_le_bytes).concat();
        let stored = [f32_bytes(&BOUNDS[2..]), dims(TABLE_ANGLES, TABLE_RATIOS)].concat();
        let new = [f32_bytes(&BOUNDS[2..]), dims(angles, ratios)].concat();
        let damaged = replace_unique(&bytes, &stored, &new);
        let err = Network::from_bytes(&damaged).err();
        assert!(
            matches!(err, Some(LoadError::BodyLengthMismatch { .. })),
            "a {angles} × {ratios} table: {err:?}"
        );
    }
}

#[test]
fn a_bad_corner_table_node_is_refused_at_load() {
    let bytes = encode(&spec()).unwrap();
    let table = build_corner_table();
    // Each node found by its row of nodes. Far below its piece's midpoint curvature (a node in
    // the middle of the table, and the last), negative, not finite, and non-zero on the
    // zero-angle row (a straight piece has no curvature).
    let (mid, last) = (
        (TABLE_ANGLES / 2, TABLE_RATIOS / 2),
        (TABLE_ANGLES - 1, TABLE_RATIOS - 1),
    );
    for ((angle, ratio), value) in [
        (mid, Some(1e-6)),
        (last, Some(1e-6)),
        (mid, Some(-1.0)),
        (mid, Some(f32::NAN)),
        (last, Some(f32::INFINITY)),
        ((0, 3), Some(0.5)),
        (mid, None),
    ] {
        // The zero-angle row is all zeros: found with the row after it.
        let end = (angle + 1 + (angle == 0) as usize) * TABLE_RATIOS;
        let row = &table[angle * TABLE_RATIOS..end];
        let mut changed = row.to_vec();
        // None: the node raised, which keeps the table a bound.
        changed[ratio] = value.unwrap_or(row[ratio] * 2.0);
        let damaged = replace_unique(&bytes, &f32_bytes(row), &f32_bytes(&changed));
        let want = value.map(|_| REFUSED);
        let got = Network::from_bytes(&damaged).err();
        assert_eq!(got, want, "node ({angle}, {ratio}) = {value:?}");
    }
}

/// The curvature at its parameter midpoint of the corner piece a table node bounds: the cubic
/// Bézier with control points (−1, 0), the corner (0, 0) twice, and ρ·(cos θ, sin θ). At
/// t = ½, B′ = ¾ (a + b) and B″ = 3 (b − a) with a = (1, 0), b = ρ (cos θ, sin θ), so
/// B′ × B″ = 4.5 ρ sin θ and κ = 4.5 ρ sin θ / (¾ |a + b|)³. In f64, from the closed form.
fn midpoint_curvature(theta: f64, rho: f64) -> f64 {
    let speed = 0.75 * (1.0 + 2.0 * rho * theta.cos() + rho * rho).sqrt();
    4.5 * rho * theta.sin() / speed.powi(3)
}

#[test]
fn a_corner_table_node_within_the_stated_tolerance_of_its_midpoint_curvature_loads() {
    let bytes = encode(&spec()).unwrap();
    let table = build_corner_table();
    // The loader allows a node 10⁻³ below its piece's midpoint curvature (f32 rounding of
    // the curvature): half of that loads, twice that is refused.
    for (angle, ratio) in [(TABLE_ANGLES / 2, TABLE_RATIOS / 2), (TABLE_ANGLES - 1, 0)] {
        let theta = table_angle(angle).unwrap() as f64;
        let rho = table_ratio(ratio).unwrap() as f64;
        let kappa = midpoint_curvature(theta, rho);
        let row = &table[angle * TABLE_RATIOS..(angle + 1) * TABLE_RATIOS];
        assert!(
            row[ratio] as f64 >= kappa,
            "the built node bounds its midpoint"
        );
        for (factor, loads) in [(1.0 - 5e-4, true), (1.0 - 2e-3, false)] {
            let mut changed = row.to_vec();
            changed[ratio] = (kappa * factor) as f32;
            let damaged = replace_unique(&bytes, &f32_bytes(row), &f32_bytes(&changed));
            let got = Network::from_bytes(&damaged).err();
            let want = (!loads).then_some(REFUSED);
            assert_eq!(got, want, "node ({angle}, {ratio}) at {factor} of {kappa}");
        }
    }
}

#[test]
fn a_bad_threat_site_circle_obstacle_or_edge_is_refused_at_load() {
    let bytes = encode(&spec()).unwrap();
    let [w, s, e, n] = BOUNDS;
    // On the box's edges: loads.
    for (x, y) in [(w, s), (e, n)] {
        let ok = replace_unique(&bytes, &f32_bytes(&[SITE.0, SITE.1]), &f32_bytes(&[x, y]));
        assert!(Network::from_bytes(&ok).is_ok(), "site at ({x}, {y})");
    }
    let bad_site = Some(LoadError::BadThreat { threat: 0 });
    for (x, y, r) in [
        (w - 1.0, SITE.1, SITE.2),
        (e + 1.0, SITE.1, SITE.2),
        (SITE.0, s - 1.0, SITE.2),
        (SITE.0, n + 1.0, SITE.2),
        (f32::NAN, SITE.1, SITE.2),
        (SITE.0, SITE.1, 0.0),
        (SITE.0, SITE.1, -SITE.2),
        (SITE.0, SITE.1, f32::INFINITY),
        (SITE.0, SITE.1, f32::NAN),
    ] {
        let damaged = replace_unique(
            &bytes,
            &f32_bytes(&[SITE.0, SITE.1, SITE.2]),
            &f32_bytes(&[x, y, r]),
        );
        let got = Network::from_bytes(&damaged).err();
        assert_eq!(got, bad_site, "site ({x}, {y}) radius {r}");
    }

    // The writer validates what it writes with the loader, so these reach the loader's
    // checks through it. A circle among the static obstacles (the Voronoi search's clearance
    // is polygons only):
    let mut with_circle = spec();
    with_circle.obstacles.push(ObstacleSpec::Circle {
        centre: Vec2::new(-500.0, 1_000.0),
        radius: 100.0,
    });
    assert_eq!(
        encode(&with_circle).err(),
        Some(WriteError::Invalid(REFUSED))
    );

    // An edge whose cost is below k times its length (at k times it: loads), and one between
    // coincident vertices.
    let mut cheap = spec();
    let length = cheap.edges[1].cost;
    cheap.edges[1].cost = WEIGHT * length * 0.999;
    assert_eq!(
        encode(&cheap).err(),
        Some(WriteError::Invalid(LoadError::CostBelowLength { edge: 1 }))
    );
    let mut exact = spec();
    exact.edges[1].cost = WEIGHT * length;
    assert!(Network::from_bytes(&encode(&exact).unwrap()).is_ok());
    let mut coincident = spec();
    coincident.vertices[1] = coincident.vertices[0];
    coincident.edges = vec![EdgeSpec::line(0, 1, 0.0)];
    let malformed = LoadError::Malformed {
        section: Section::Edges,
        index: 0,
    };
    assert_eq!(
        encode(&coincident).err(),
        Some(WriteError::Invalid(malformed))
    );
}
