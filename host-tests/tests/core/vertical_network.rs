//! A three-dimensional roadmap's vertical section (`docs/FORMAT.md`): written and read back,
//! each bad value refused by name, and every edge's climb checked against the vertical limits
//! at the boundary the limits set (the largest rest-to-rest climb over the edge's length, a
//! closed form checked against an LP in `vertical_profile`).

use host_tests::damage::fix_crc;
use host_tests::world::lattice_spec;
use skyroute::geometry::vertical::VerticalLimits;
use skyroute::network::format::{Header, FLAG_VERTICAL};
use skyroute::network::write::{
    encode, encode_three_dimensional, NetworkSpec, ObstacleSpec, VerticalSpec, WriteError,
};
use skyroute::network::{LoadError, Network, Parameter, Section};
use skyroute::Vec2;

/// A 3 × 3 lattice 100 m apart (turn radius 30 m) with two obstacles outside it, every vertex
/// at 50 m, limits of Niendorf et al.'s aircraft at 25 m/s.
fn spec() -> (NetworkSpec, VerticalSpec) {
    let mut spec = lattice_spec(3, 100.0, 0.0, 30.0);
    spec.obstacles = vec![
        ObstacleSpec::Circle {
            centre: Vec2::new(-200.0, -200.0),
            radius: 20.0,
        },
        ObstacleSpec::Polygon(vec![
            Vec2::new(400.0, 400.0),
            Vec2::new(450.0, 400.0),
            Vec2::new(450.0, 450.0),
        ]),
    ];
    let vertical = VerticalSpec {
        limits: VerticalLimits::niendorf(25.0),
        altitudes: vec![50.0; spec.vertices.len()],
        heights: vec![30.0, f32::INFINITY],
    };
    (spec, vertical)
}

fn refused(spec: &NetworkSpec, vertical: &VerticalSpec) -> LoadError {
    match encode_three_dimensional(spec, vertical, None) {
        Err(WriteError::Invalid(e)) => e,
        other => panic!("expected a load error, got {other:?}"),
    }
}

#[test]
fn a_three_dimensional_roadmap_reads_back_its_limits_altitudes_and_heights() {
    let (spec, mut vertical) = spec();
    for (i, z) in vertical.altitudes.iter_mut().enumerate() {
        *z = 40.0 + (i % 4) as f32 * 0.5;
    }
    let image = encode_three_dimensional(&spec, &vertical, None).expect("writes");
    let net = Network::from_bytes(&image).expect("loads");
    assert!(net.is_three_dimensional());
    assert_eq!(net.vertical_limits(), Some(vertical.limits));
    for (v, &z) in vertical.altitudes.iter().enumerate() {
        assert_eq!(net.vertex_altitude(v as u32), Some(z));
    }
    assert_eq!(net.vertex_altitude(vertical.altitudes.len() as u32), None);
    assert_eq!(net.obstacle_height(0), Some(30.0));
    assert_eq!(net.obstacle_height(1), Some(f32::INFINITY));
    assert_eq!(net.obstacle_height(2), None);
    for e in 0..net.edge_count() {
        let profile = net.edge_profile(e).expect("every edge has a profile");
        let source = net.edge_source(e).unwrap();
        let target = net.edge(e).unwrap().target;
        assert_eq!(profile.from, net.vertex_altitude(source).unwrap());
        assert_eq!(profile.to, net.vertex_altitude(target).unwrap());
        assert_eq!(profile.length, net.edge_path(e).unwrap().length());
    }
    // The same network without the section is planar: no altitudes, walls of unbounded height.
    let planar = encode(&spec).expect("writes");
    let net = Network::from_bytes(&planar).expect("loads");
    assert!(!net.is_three_dimensional());
    assert_eq!(net.vertical_limits(), None);
    assert_eq!(net.vertex_altitude(0), None);
    assert_eq!(net.edge_profile(0), None);
    assert_eq!(net.obstacle_height(0), Some(f32::INFINITY));
    assert_eq!(
        image.len(),
        planar.len() + 12 + 4 * (spec.vertices.len() + 2)
    );
}

#[test]
fn bad_vertical_limits_altitudes_and_heights_are_refused_by_name() {
    let (spec, vertical) = spec();
    let limits = vertical.limits;
    for limits in host_tests::damage::bad_vertical_limits(limits) {
        let v = VerticalSpec {
            limits,
            ..vertical.clone()
        };
        assert_eq!(
            refused(&spec, &v),
            LoadError::InvalidParameter {
                parameter: Parameter::Vertical
            }
        );
    }
    for bad in [f32::NAN, f32::INFINITY, -f32::INFINITY, 1.0001e5, -1.0001e5] {
        let mut v = vertical.clone();
        v.altitudes[7] = bad;
        assert_eq!(
            refused(&spec, &v),
            LoadError::BadAltitude {
                section: Section::Altitudes,
                index: 7
            }
        );
    }
    for bad in [0.0, -1.0, f32::NAN, -f32::INFINITY] {
        let mut v = vertical.clone();
        v.heights[1] = bad;
        assert_eq!(
            refused(&spec, &v),
            LoadError::BadAltitude {
                section: Section::ObstacleHeights,
                index: 1
            }
        );
    }
    // The extremes that load: ±100 km altitudes with flat edges, a height of one f32 step.
    let mut v = vertical.clone();
    v.altitudes.iter_mut().for_each(|z| *z = -1e5);
    v.heights[0] = f32::from_bits(1);
    assert!(encode_three_dimensional(&spec, &v, None).is_ok());
    // Tables that do not match the vertices or obstacles, and a mode other than roadmap.
    let mut v = vertical.clone();
    v.altitudes.pop();
    assert!(matches!(
        encode_three_dimensional(&spec, &v, None),
        Err(WriteError::BadVertical(_))
    ));
    let mut v = vertical.clone();
    v.heights.push(10.0);
    assert!(matches!(
        encode_three_dimensional(&spec, &v, None),
        Err(WriteError::BadVertical(_))
    ));
}

/// Raises the lattice's centre position (its four vertices) by `height`; the edges to and from
/// it then climb or descend `height` over their own lengths.
fn raised_centre(spec: &NetworkSpec, vertical: &VerticalSpec, height: f32) -> VerticalSpec {
    let centre = Vec2::new(100.0, 100.0);
    let mut v = vertical.clone();
    for (z, pose) in v.altitudes.iter_mut().zip(&spec.vertices) {
        if pose.position == centre {
            *z += height;
        }
    }
    v
}

#[test]
fn an_edge_climbing_more_than_the_limits_allow_is_refused_and_one_just_within_loads() {
    let (spec, vertical) = spec();
    let centre = Vec2::new(100.0, 100.0);
    let limits = vertical.limits;
    // The edges touching the centre, in the order the image stores them (by source, stable).
    let mut order: Vec<usize> = (0..spec.edges.len()).collect();
    order.sort_by_key(|&i| spec.edges[i].source);
    let touching = |i: usize| {
        let e = &spec.edges[i];
        spec.vertices[e.source as usize].position == centre
            || spec.vertices[e.target as usize].position == centre
    };
    let length = |i: usize| spec.edges[i].lengths.iter().sum::<f32>();
    let shortest = order
        .iter()
        .filter(|&&i| touching(i))
        .map(|&i| length(i))
        .fold(f32::INFINITY, f32::min);
    let within = limits.max_climb(shortest) * (1.0 - 1e-4);
    for sign in [1.0, -1.0] {
        let v = raised_centre(&spec, &vertical, sign * within);
        assert!(
            encode_three_dimensional(&spec, &v, None).is_ok(),
            "{within} m within"
        );
    }
    let beyond = limits.max_climb(shortest) * (1.0 + 1e-3) + 1e-3;
    let first_too_steep = order
        .iter()
        .position(|&i| touching(i) && limits.max_climb(length(i)) < beyond)
        .expect("the shortest edge is too steep") as u32;
    for sign in [1.0, -1.0] {
        let v = raised_centre(&spec, &vertical, sign * beyond);
        assert_eq!(
            refused(&spec, &v),
            LoadError::EdgeTooSteep {
                edge: first_too_steep
            }
        );
    }
}

#[test]
fn the_vertical_flag_on_another_mode_or_a_short_section_is_refused() {
    let (spec, vertical) = spec();
    let image = encode_three_dimensional(&spec, &vertical, None).expect("writes");
    // The section cut short: the header's body length no longer matches.
    let mut short = image.clone();
    short.truncate(image.len() - 4);
    assert!(Network::from_bytes(&short).is_err());
    // A planar roadmap's image with the flag set: the section it announces is missing.
    let mut flagged = encode(&spec).expect("writes");
    flagged[7] |= FLAG_VERTICAL;
    fix_crc(&mut flagged);
    assert!(matches!(
        Network::from_bytes(&flagged),
        Err(LoadError::BodyLengthMismatch { .. } | LoadError::Truncated { .. })
    ));
    // The flags byte is the header's eighth.
    assert_eq!(Header::SIZE, 84);
    assert_eq!(image[7], FLAG_VERTICAL);
}
