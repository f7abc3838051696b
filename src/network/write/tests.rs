//! The writer against its definitions: the grid's sizing and index (`docs/FORMAT.md`, "Grid
//! index"), worked out in f64 on sampled networks, the writer's own checks and its messages.
//! A roadmap edge is listed in every cell that the bounding box of one of its lines or arcs,
//! widened by `10⁻³·cell + 1 cm`, overlaps; a terrain edge in every cell its segment comes
//! within that margin of; no edge anywhere else. A cell within 1 mm of the boundary either way
//! is not judged (the writer works in f32), nor one a terrain edge misses by less than the
//! segment traversal's documented rounding slack.

extern crate std;
use super::*;
use crate::geometry::Primitive;
use crate::test_rng::Rng;
use std::vec;

/// How far past a boundary (metres) a cell must lie to be judged.
const TOLERANCE: f64 = 1e-3;

/// Whether a cell and a set of geometry certainly meet, certainly do not, or lie within the
/// tolerance of touching.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Verdict {
    Meets,
    Misses,
    Borderline,
}

/// The cell `(x, y)` of the network's grid index as a closed box `(min, max)`, f64.
fn cell_box(net: &Network<'_>, x: u32, y: u32) -> ([f64; 2], [f64; 2]) {
    let h = net.header();
    let (o, c) = (
        [h.grid_origin_x as f64, h.grid_origin_y as f64],
        h.grid_cell_m as f64,
    );
    (
        [o[0] + x as f64 * c, o[1] + y as f64 * c],
        [o[0] + (x + 1) as f64 * c, o[1] + (y + 1) as f64 * c],
    )
}

/// A box `(lo, hi)` against the cell `(clo, chi)`: the largest gap between them along an axis
/// (negative when they overlap along both, by that much at the least).
fn box_gap(lo: [f64; 2], hi: [f64; 2], clo: [f64; 2], chi: [f64; 2]) -> f64 {
    (0..2)
        .map(|k| (lo[k] - chi[k]).max(clo[k] - hi[k]))
        .fold(f64::NEG_INFINITY, f64::max)
}

fn verdict(gap: f64) -> Verdict {
    if gap < -TOLERANCE {
        Verdict::Meets
    } else if gap > TOLERANCE {
        Verdict::Misses
    } else {
        Verdict::Borderline
    }
}

/// A primitive's bounding box in f64: a line's end points; an arc's end points and the
/// circle's points at 0, 90, 180 and 270° that its sweep passes.
fn primitive_box(p: &Primitive) -> ([f64; 2], [f64; 2]) {
    let mut points: Vec<[f64; 2]> = Vec::new();
    match p {
        Primitive::Line(s) => {
            points.push([s.start.x as f64, s.start.y as f64]);
            points.push([s.end.x as f64, s.end.y as f64]);
        }
        Primitive::Arc(a) => {
            let (cx, cy, r) = (a.centre.x as f64, a.centre.y as f64, a.radius as f64);
            let (from, sweep) = (a.start_angle as f64, a.sweep as f64);
            let at = |t: f64| [cx + r * t.cos(), cy + r * t.sin()];
            points.push(at(from));
            points.push(at(from + sweep));
            let (lo, hi) = (from.min(from + sweep), from.max(from + sweep));
            let quarter = core::f64::consts::FRAC_PI_2;
            let mut k = (lo / quarter).ceil();
            while k * quarter <= hi {
                points.push(at(k * quarter));
                k += 1.0;
            }
        }
    }
    let lo = [0, 1].map(|k| points.iter().map(|p| p[k]).fold(f64::INFINITY, f64::min));
    let hi = [0, 1].map(|k| {
        points
            .iter()
            .map(|p| p[k])
            .fold(f64::NEG_INFINITY, f64::max)
    });
    (lo, hi)
}

/// The distance from segment `a`–`b` to the closed box `(lo, hi)`, f64: 0 when they meet,
/// else the least of the end points' distances to the box and the box corners' to the segment.
pub(crate) fn segment_box_distance(a: [f64; 2], b: [f64; 2], lo: [f64; 2], hi: [f64; 2]) -> f64 {
    let point_box = |p: [f64; 2]| {
        let d = [0, 1].map(|k| (lo[k] - p[k]).max(p[k] - hi[k]).max(0.0));
        d[0].hypot(d[1])
    };
    let point_segment = |p: [f64; 2]| {
        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
        let t = (((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / (dx * dx + dy * dy)).clamp(0.0, 1.0);
        (a[0] + t * dx - p[0]).hypot(a[1] + t * dy - p[1])
    };
    // The segment meets the box iff its parameter interval clipped to each slab is non-empty
    // (Liang–Barsky).
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for k in 0..2 {
        let d = b[k] - a[k];
        if d == 0.0 {
            if a[k] < lo[k] || a[k] > hi[k] {
                t0 = 2.0;
            }
        } else {
            let (u, v) = ((lo[k] - a[k]) / d, (hi[k] - a[k]) / d);
            t0 = t0.max(u.min(v));
            t1 = t1.min(u.max(v));
        }
    }
    if t0 <= t1 {
        return 0.0;
    }
    let corners = [lo, hi, [lo[0], hi[1]], [hi[0], lo[1]]];
    let ends = point_box(a).min(point_box(b));
    corners
        .iter()
        .map(|&c| point_segment(c))
        .fold(ends, f64::min)
}

/// Checks every cell of `net`'s grid index against `judge(edge, cell)`: an edge that meets the
/// cell is listed in it, one that misses it is not. Returns the listings judged `Meets`.
fn check_index(net: &Network<'_>, judge: impl Fn(u32, ([f64; 2], [f64; 2])) -> Verdict) -> u32 {
    let h = net.header();
    let mut met = 0;
    for y in 0..h.grid_ny {
        for x in 0..h.grid_nx {
            let listed: Vec<u32> = net.cell_edges(x, y).collect();
            let cell = cell_box(net, x, y);
            for e in 0..net.edge_count() {
                match judge(e, cell) {
                    Verdict::Meets => {
                        assert!(listed.contains(&e), "edge {e} not in cell ({x}, {y})");
                        met += 1;
                    }
                    Verdict::Misses => {
                        assert!(!listed.contains(&e), "edge {e} in cell ({x}, {y})")
                    }
                    Verdict::Borderline => {}
                }
            }
        }
    }
    met
}

/// [`check_index`] with each edge meeting a cell where one of its boxes `(lo, hi)` does.
pub(crate) fn check_boxes(net: &Network<'_>, boxes: &[Vec<([f64; 2], [f64; 2])>]) -> u32 {
    check_index(net, |e, (clo, chi)| {
        let gap = boxes[e as usize]
            .iter()
            .map(|&(lo, hi)| box_gap(lo, hi, clo, chi))
            .fold(f64::INFINITY, f64::min);
        verdict(gap)
    })
}

/// The index's rounding margin for cells of side `cell`, f64.
pub(crate) fn margin(cell: f32) -> f64 {
    1e-3 * cell as f64 + 0.01
}

/// Thirty vertices in a 600 m square with random headings, and 40 shortest Dubins edges
/// between random pairs, turn radius 30 m, cells of `cell` metres.
fn sampled_roadmap(rng: &mut Rng, cell: f32) -> NetworkSpec {
    let vertices: Vec<Pose> = (0..30)
        .map(|_| {
            let (x, y) = (rng.range(0.0, 600.0), rng.range(0.0, 600.0));
            Pose::new(
                x,
                y,
                rng.range(-core::f32::consts::PI, core::f32::consts::PI),
            )
        })
        .collect();
    let mut edges = Vec::new();
    while edges.len() < 40 {
        let (a, b) = ((rng.unit() * 30.0) as u32, (rng.unit() * 30.0) as u32);
        if a != b {
            let (pa, pb) = (&vertices[a as usize], &vertices[b as usize]);
            let path = DubinsPath::shortest(pa, pb, 30.0).unwrap();
            edges.push(EdgeSpec::dubins(a, b, &path));
        }
    }
    NetworkSpec {
        origin_lat_deg: 48.1,
        origin_lon_deg: 11.6,
        turn_radius_m: 30.0,
        clearance_m: 5.0,
        vertices,
        edges,
        obstacles: Vec::new(),
        grid_cell_m: cell,
        terrain: None,
        landmark: None,
        voronoi: None,
        provenance: Vec::new(),
    }
}

/// The box of `spec`'s vertices, `(min, max)`, f64.
pub(crate) fn vertex_box(spec: &NetworkSpec) -> ([f64; 2], [f64; 2]) {
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for v in &spec.vertices {
        let p = [v.position.x as f64, v.position.y as f64];
        lo = [lo[0].min(p[0]), lo[1].min(p[1])];
        hi = [hi[0].max(p[0]), hi[1].max(p[1])];
    }
    (lo, hi)
}

/// The grid of `net`, written from `spec`: the box `(lo, hi)` widened by `4r + cell`, in whole
/// cells (`docs/FORMAT.md`), worked out in f64.
pub(crate) fn check_extent(net: &Network<'_>, spec: &NetworkSpec, (lo, hi): ([f64; 2], [f64; 2])) {
    let h = net.header();
    let cell = spec.grid_cell_m as f64;
    let widen = 4.0 * spec.turn_radius_m as f64 + cell;
    let origin = [h.grid_origin_x as f64, h.grid_origin_y as f64];
    let counts = [h.grid_nx as f64, h.grid_ny as f64];
    for k in 0..2 {
        assert!(
            (origin[k] - (lo[k] - widen)).abs() < 0.01,
            "axis {k}: {origin:?} for {lo:?}"
        );
        let cells = (hi[k] - lo[k] + 2.0 * widen) / cell;
        assert!(
            counts[k] > cells - 1e-3 && counts[k] < cells + 1.0 + 1e-3,
            "axis {k}: {counts:?}"
        );
    }
}

/// Sampled roadmaps with cells of 7–90 m: the grid's extent, and each edge listed exactly in
/// the cells its primitives' widened boxes overlap.
#[test]
fn a_roadmap_edge_is_listed_in_the_cells_its_primitives_boxes_overlap() {
    let mut rng = Rng(0x9e1d_0f0f_2026_1206);
    let mut met = 0;
    for _ in 0..12 {
        let cell = rng.range(7.0, 90.0);
        let spec = sampled_roadmap(&mut rng, cell);
        let bytes = encode(&spec).unwrap();
        let net = Network::from_bytes(&bytes).unwrap();
        check_extent(&net, &spec, vertex_box(&spec));
        let boxes: Vec<Vec<([f64; 2], [f64; 2])>> = (0..net.edge_count())
            .map(|e| {
                let path = net.edge_path(e).unwrap();
                let w = margin(cell);
                path.primitives()
                    .iter()
                    .flatten()
                    .map(|p| {
                        let (lo, hi) = primitive_box(p);
                        (lo.map(|v| v - w), hi.map(|v| v + w))
                    })
                    .collect()
            })
            .collect();
        met += check_boxes(&net, &boxes);
    }
    assert!(met > 5000, "{met} listings");
}

/// Thirty nodes in a 1 km square (headings 0: a terrain node has none) and 40 straight edges
/// between random pairs, over a flat elevation grid of 20 m cells, index cells of `cell` m.
fn sampled_terrain(rng: &mut Rng, cell: f32) -> NetworkSpec {
    let nodes: Vec<Vec2> = (0..30)
        .map(|_| Vec2::new(rng.range(0.0, 1000.0), rng.range(0.0, 1000.0)))
        .collect();
    let mut edges = Vec::new();
    while edges.len() < 40 {
        let (a, b) = ((rng.unit() * 30.0) as usize, (rng.unit() * 30.0) as usize);
        if a != b {
            let length = nodes[a].distance(nodes[b]);
            edges.push(EdgeSpec::line(a as u32, b as u32, length));
        }
    }
    NetworkSpec {
        origin_lat_deg: 36.5,
        origin_lon_deg: -84.2,
        turn_radius_m: 30.0,
        clearance_m: 0.0,
        vertices: nodes.iter().map(|p| Pose::new(p.x, p.y, 0.0)).collect(),
        edges,
        obstacles: Vec::new(),
        grid_cell_m: cell,
        terrain: Some(TerrainSpec {
            grid: CellGrid::new(Vec2::new(-200.0, -200.0), 20.0, 70, 70),
            coding: ElevationCoding {
                base_m: 0.0,
                step_m: 1.0,
            },
            codes: vec![0; 70 * 70],
            widen_m: 10.0,
            altitude_m: 100.0,
            safety_height_m: 0.0,
        }),
        landmark: None,
        voronoi: None,
        provenance: Vec::new(),
    }
}

/// Sampled terrain networks with cells of 7–90 m: each edge listed exactly in the cells its
/// segment comes within the margin of (not the cells its bounding box overlaps, nor those along
/// its source's heading).
#[test]
fn a_terrain_edge_is_listed_in_the_cells_its_segment_comes_near() {
    let mut rng = Rng(0x7e22_a1a1_2026_1206);
    let (mut met, mut box_only) = (0, 0);
    for _ in 0..12 {
        let cell = rng.range(7.0, 90.0);
        let spec = sampled_terrain(&mut rng, cell);
        let bytes = encode(&spec).unwrap();
        let net = Network::from_bytes(&bytes).unwrap();
        check_extent(&net, &spec, vertex_box(&spec));
        let segment = |e: u32| {
            let edge = net.edge(e).unwrap();
            let (a, b) = (
                net.vertex(edge.source).unwrap(),
                net.vertex(edge.target).unwrap(),
            );
            let f = |p: Vec2| [p.x as f64, p.y as f64];
            (f(a.position), f(b.position))
        };
        // `segment_cells` may add cells within its rounding slack η = 3δ cells,
        // δ = 16·ε·(M + 1) for magnitudes of M cells (`geometry::grid`).
        let h = net.header();
        let cells = h.grid_nx.max(h.grid_ny) as f64 + 1.0;
        let slack = 3.0 * 16.0 * f32::EPSILON as f64 * cells * cell as f64;
        met += check_index(&net, |e, (clo, chi)| {
            let (a, b) = segment(e);
            match segment_box_distance(a, b, clo, chi) - margin(cell) {
                d if d > 0.0 && d <= slack + TOLERANCE => Verdict::Borderline,
                d => verdict(d),
            }
        });
        // Cells the segment's box overlaps but the segment does not come near: listed by a
        // box rule, not by this one.
        for e in 0..net.edge_count() {
            let (a, b) = segment(e);
            let (lo, hi) = (
                [a[0].min(b[0]), a[1].min(b[1])],
                [a[0].max(b[0]), a[1].max(b[1])],
            );
            for (x, y) in (0..h.grid_ny).flat_map(|y| (0..h.grid_nx).map(move |x| (x, y))) {
                let (clo, chi) = cell_box(&net, x, y);
                box_only += u32::from(
                    box_gap(lo, hi, clo, chi) < -1.0
                        && segment_box_distance(a, b, clo, chi) > margin(cell) + 1.0,
                );
            }
        }
    }
    assert!(
        met > 5000 && box_only > 1000,
        "{met} listings, {box_only} box-only cells"
    );
}

/// A roadmap edge whose box lies 10 cm and 12 cm short of a cell boundary, with cells of
/// 100 m (margin 11 cm): listed in the cell beyond in the first case only.
#[test]
fn the_index_margin_is_a_thousandth_of_the_cell_plus_a_centimetre() {
    for (gap, listed) in [(0.10f32, true), (0.12, false)] {
        let mut spec = sampled_roadmap(&mut Rng(1), 100.0);
        // One straight edge eastward along y = 300 whose end stops `gap` short of x = 700
        // measured from the grid origin; its box is that line.
        spec.edges.clear();
        let origin = encode(&spec)
            .map(|b| Network::from_bytes(&b).unwrap().header().grid_origin_x)
            .unwrap();
        let end = origin + 700.0 - gap;
        spec.vertices[0] = Pose::new(end - 150.0, 300.0, 0.0);
        spec.vertices[1] = Pose::new(end, 300.0, 0.0);
        let path = DubinsPath::shortest(&spec.vertices[0], &spec.vertices[1], 30.0).unwrap();
        spec.edges.push(EdgeSpec::dubins(0, 1, &path));
        let bytes = encode(&spec).unwrap();
        let net = Network::from_bytes(&bytes).unwrap();
        assert_eq!(net.header().grid_origin_x, origin, "the same grid");
        let h = net.header();
        let row = ((300.0 - h.grid_origin_y) / h.grid_cell_m) as u32;
        let beyond: Vec<u32> = net.cell_edges(7, row).collect();
        assert_eq!(beyond.contains(&0), listed, "gap {gap}");
        assert!(net.cell_edges(6, row).any(|e| e == 0));
    }
}

/// The grid's columns and rows: `⌈extent / cell⌉`, at least 1; a cell that is not a positive
/// finite size refused as such; a grid of more than `MAX_GRID_CELLS` cells refused with its
/// counts, one of exactly that many accepted.
#[test]
fn grid_cells_rounds_up_and_refuses_bad_cells_and_oversized_grids() {
    assert_eq!(grid_cells(10.0, 95.0, 0.0), Ok((10, 1)));
    assert_eq!(grid_cells(10.0, 100.0, 101.0), Ok((10, 11)));
    for cell in [0.0, -0.0, -5.0, f32::NAN, f32::INFINITY, f32::NEG_INFINITY] {
        assert!(
            matches!(
                grid_cells(cell, 100.0, 100.0),
                Err(WriteError::BadGridCell(_))
            ),
            "{cell}"
        );
    }
    assert_eq!(grid_cells(1.0, 2048.0, 2048.0), Ok((2048, 2048)));
    assert_eq!(grid_cells(1.0, 4194304.0, 1.0), Ok((4194304, 1)));
    assert_eq!(
        grid_cells(1.0, 2049.0, 2048.0),
        Err(WriteError::GridTooLarge(1.0, 2049.0, 2048.0))
    );
    assert_eq!(
        grid_cells(1.0, 4194305.0, 0.5),
        Err(WriteError::GridTooLarge(1.0, 4194305.0, 1.0))
    );
    assert!(matches!(
        grid_cells(1e-30, 1e30, 1e30),
        Err(WriteError::GridTooLarge(..))
    ));
}

/// A roadmap of one straight edge, 0 → 1, 100 m east.
fn one_edge_roadmap() -> NetworkSpec {
    let mut spec = sampled_roadmap(&mut Rng(7), 50.0);
    spec.vertices.truncate(2);
    spec.vertices[0] = Pose::new(100.0, 100.0, 0.0);
    spec.vertices[1] = Pose::new(200.0, 100.0, 0.0);
    let path = DubinsPath::shortest(&spec.vertices[0], &spec.vertices[1], 30.0).unwrap();
    spec.edges = vec![EdgeSpec::dubins(0, 1, &path)];
    spec
}

/// A terrain network of two nodes 100 m apart and one straight edge, over a flat 20 m grid
/// from (−200, −200) of 70 × 70 cells, widening 10 m.
fn one_edge_terrain() -> NetworkSpec {
    let mut spec = sampled_terrain(&mut Rng(7), 50.0);
    spec.vertices.truncate(2);
    spec.vertices[0] = Pose::new(100.0, 100.0, 0.0);
    spec.vertices[1] = Pose::new(200.0, 100.0, 0.0);
    spec.edges = vec![EdgeSpec::line(0, 1, 100.0)];
    spec
}

/// A Voronoi section that names nothing real: the writer refuses what it checks before the
/// loader would read it.
fn any_voronoi() -> VoronoiSpec {
    VoronoiSpec {
        threats: vec![(Vec2::new(0.0, 0.0), 100.0)],
        threat_weight: 0.5,
        kappa_max: 0.02,
        bounds: (Vec2::new(-500.0, -500.0), Vec2::new(500.0, 500.0)),
        corner_table: Vec::new(),
    }
}

/// `spec` with edge 0 no longer straight: its word `RSR` (`change` 0), or a first (1) or third
/// (2) length of 1 m.
fn bent(spec: &NetworkSpec, change: usize) -> NetworkSpec {
    let mut bent = spec.clone();
    let e = &mut bent.edges[0];
    match change {
        0 => e.word = DubinsWord::Rsr,
        1 => e.lengths[0] = 1.0,
        _ => e.lengths[2] = 1.0,
    }
    bent
}

/// Each thing the writer checks itself is refused with its own error, and only that: the
/// vertex limit (65 536 written, 65 537 refused), an edge naming a missing vertex at either
/// end, an edge whose lengths are one ulp off its word's, a terrain table of the wrong size,
/// a terrain edge that is not straight by any one of its word and outer lengths, a terrain
/// band leaving the elevation grid on any side, a Voronoi edge that is not straight (and straight ones
/// let through), a network of two modes, and a three-dimensional network of each other mode.
#[test]
fn the_writers_own_checks_refuse_by_name() {
    let mut spec = one_edge_roadmap();
    assert!(encode(&spec).is_ok());
    let mut many = spec.clone();
    many.edges.clear();
    many.vertices = (0..MAX_VERTICES)
        .map(|i| Pose::new((i % 256) as f32, (i / 256) as f32, 0.0))
        .collect();
    assert!(encode(&many).is_ok(), "exactly MAX_VERTICES");
    many.vertices.push(Pose::new(0.0, 0.0, 0.0));
    assert_eq!(
        encode(&many),
        Err(WriteError::TooLarge(
            "vertices (edge targets are 16-bit: at most 65536)"
        ))
    );
    for (source, target) in [(2, 1), (0, 2)] {
        let mut bad = spec.clone();
        (bad.edges[0].source, bad.edges[0].target) = (source, target);
        assert_eq!(encode(&bad), Err(WriteError::BadEdge { edge: 0 }));
    }
    spec.edges[0].lengths[1] = f32::from_bits(spec.edges[0].lengths[1].to_bits() + 1);
    assert_eq!(encode(&spec), Err(WriteError::EdgeGeometry { edge: 0 }));

    let terrain = one_edge_terrain();
    assert!(encode(&terrain).is_ok());
    let mut bad = terrain.clone();
    bad.terrain.as_mut().unwrap().codes.pop();
    let size = WriteError::BadTerrain("table size differs from cols x rows");
    assert_eq!(encode(&bad), Err(size));
    let crooked = WriteError::BadTerrain("an edge is not a straight line");
    for change in 0..3 {
        let bad = bent(&terrain, change);
        assert_eq!(encode(&bad), Err(crooked.clone()), "change {change}");
    }
    // 5 m inside each side of the elevation grid (−200 to 1 200): the nodes are inside, the
    // 10 m band is not.
    let band = WriteError::BadTerrain("an edge's band leaves the elevation grid");
    for (axis, at) in [(1, -195.0), (1, 1195.0), (0, -195.0), (0, 1195.0)] {
        let mut edge = terrain.clone();
        for v in &mut edge.vertices {
            match axis {
                0 => (v.position.x, v.position.y) = (at, v.position.x),
                _ => v.position.y = at,
            }
        }
        assert_eq!(encode(&edge), Err(band.clone()), "axis {axis} at {at}");
    }

    let mut voronoi = one_edge_terrain();
    voronoi.terrain = None;
    voronoi.voronoi = Some(any_voronoi());
    let not_line = WriteError::BadVoronoi("an edge is not a straight line");
    assert_ne!(encode(&voronoi), Err(not_line.clone()), "a straight edge");
    for change in 0..3 {
        let bad = bent(&voronoi, change);
        assert_eq!(encode(&bad), Err(not_line.clone()), "change {change}");
    }
    let mut two = terrain.clone();
    two.voronoi = Some(any_voronoi());
    assert_eq!(
        encode(&two),
        Err(WriteError::BadLandmark(
            "a network is of one mode: terrain, landmark or Voronoi"
        ))
    );

    let vertical = VerticalSpec {
        limits: crate::geometry::vertical::VerticalLimits::niendorf(25.0),
        altitudes: vec![100.0; 2],
        heights: Vec::new(),
    };
    assert!(encode_three_dimensional(&one_edge_roadmap(), &vertical, None).is_ok());
    let flat = WriteError::BadVertical("only a roadmap can be three-dimensional");
    for other in [&terrain, &voronoi] {
        let got = encode_three_dimensional(other, &vertical, None);
        assert_eq!(got, Err(flat.clone()));
    }
}

/// Every error's message, and the numbers in a grid's: plain from 10⁻³ to 10⁹ (and 0), in
/// scientific notation outside; a cell within that range as given.
#[test]
fn write_errors_name_what_is_wrong() {
    let cases = [
        (
            WriteError::TooLarge("edges"),
            "too many edges for the network format",
        ),
        (
            WriteError::BadEdge { edge: 3 },
            "edge 3 names a missing vertex",
        ),
        (WriteError::BadTerrain("x"), "terrain network: x"),
        (WriteError::BadLandmark("x"), "landmark network: x"),
        (WriteError::BadVoronoi("x"), "Voronoi network: x"),
        (WriteError::BadVertical("x"), "three-dimensional roadmap: x"),
        (
            WriteError::EdgeGeometry { edge: 2 },
            "edge 2's lengths are not its Dubins word's between its two poses",
        ),
        (
            WriteError::BadGridCell(-5.0),
            "grid cell -5 m is not a positive finite size",
        ),
        (
            WriteError::GridTooLarge(1.0, 2049.0, 2048.0),
            "a grid index of 2049 x 2048 cells of 1 m exceeds the limit of 4194304 cells \
             (a larger grid cell makes fewer)",
        ),
        (
            WriteError::GridTooLarge(1e-30, 1e30, 0.0),
            "a grid index of 1.0000e30 x 0 cells of 1.0000e-30 m exceeds the limit of 4194304 \
             cells (a larger grid cell makes fewer)",
        ),
        (
            WriteError::GridTooLarge(2e9, 1e9, 0.001),
            "a grid index of 1.0000e9 x 0.001 cells of 2.0000e9 m exceeds the limit of 4194304 \
             cells (a larger grid cell makes fewer)",
        ),
    ];
    for (error, message) in cases {
        assert_eq!(std::format!("{error}"), message);
    }
    let invalid = WriteError::Invalid(crate::network::LoadError::CountsTooLarge);
    let inner = std::format!("{}", crate::network::LoadError::CountsTooLarge);
    assert!(!inner.is_empty());
    assert_eq!(
        std::format!("{invalid}"),
        std::format!("the network does not validate: {inner}")
    );
}
