//! Degenerate inputs against closed forms: no site, one site, collinear sites and two sites
//! (parallel bisectors), cocircular sites (one vertex), duplicates, bad sites and bounds, full
//! capacities; random garbage never panics.

use super::*;

fn graph_of(sites: &[(f32, f32)], b: &Bounds) -> (Box<Dt>, Box<Graph>) {
    let mut dt = Box::new(Dt::new());
    for &(x, y) in sites {
        dt.insert(Vec2::new(x, y)).expect("a valid site");
    }
    let mut g = Box::new(Graph::new());
    dt.graph(b, &mut g).expect("graph");
    check_graph(&dt, &g, b, &format!("{sites:?}"));
    (dt, g)
}

/// The non-border edges as sorted pairs of end points.
fn voronoi_edges(g: &Graph) -> BTreeSet<((i64, i64), (i64, i64))> {
    let key = |v: Vec2| ((v.x * 1000.0).round() as i64, (v.y * 1000.0).round() as i64);
    g.edges()
        .iter()
        .filter(|e| !e.border)
        .map(|e| {
            let (a, b) = (
                key(g.vertices()[e.a as usize]),
                key(g.vertices()[e.b as usize]),
            );
            (a.min(b), a.max(b))
        })
        .collect()
}

#[test]
fn empty_and_single_site_graphs_are_the_box() {
    let b = box_of(100.0);
    for sites in [&[][..], &[(3.0, -7.5)][..]] {
        let (_, g) = graph_of(sites, &b);
        assert_eq!(g.vertices().len(), 4, "{sites:?}");
        assert_eq!(g.edges().len(), 4, "{sites:?}");
        assert!(g.edges().iter().all(|e| e.border));
        let want = if sites.is_empty() { NO_SITE } else { 0 };
        assert!(g.edges().iter().all(|e| e.sites == [want, want]));
    }
}

#[test]
fn collinear_and_two_site_graphs_are_parallel_bisectors() {
    let b = box_of(100.0);
    // Three sites on the x axis (inserted out of order): bisectors x = 5 and x = 20.
    let (_, g) = graph_of(&[(30.0, 0.0), (0.0, 0.0), (10.0, 0.0)], &b);
    let want: BTreeSet<_> = [
        ((5000, -100000), (5000, 100000)),
        ((20000, -100000), (20000, 100000)),
    ]
    .into();
    assert_eq!(voronoi_edges(&g), want);
    assert_eq!((g.vertices().len(), g.edges().len()), (8, 10));
    // A vertical line of four: bisectors y = −15, 5, 27.5.
    let (_, g) = graph_of(&[(1.0, 0.0), (1.0, -30.0), (1.0, 10.0), (1.0, 45.0)], &b);
    let want: BTreeSet<_> = [-15000, 5000, 27500]
        .iter()
        .map(|&y| ((-100000, y), (100000, y)))
        .collect();
    assert_eq!(voronoi_edges(&g), want);
    // Two sites on a diagonal: the bisector x + y = 10 from (−90, 100) to (100, −90).
    let (_, g) = graph_of(&[(0.0, 0.0), (10.0, 10.0)], &b);
    let want: BTreeSet<_> = [((-90000, 100000), (100000, -90000))].into();
    assert_eq!(voronoi_edges(&g), want);
    // A collinear line that misses the box: only the box, each side in one cell.
    let (_, g) = graph_of(&[(500.0, 0.0), (600.0, 0.0)], &b);
    assert_eq!((g.vertices().len(), g.edges().len()), (4, 4));
}

#[test]
fn cocircular_sites_give_one_vertex() {
    let b = box_of(100.0);
    // The 12 integer points of the circle of radius 5 about (2, −1), and a square.
    let mut circle: Vec<(f32, f32)> = Vec::new();
    for (x, y) in [(3, 4), (4, 3), (5, 0), (0, 5)] {
        for (sx, sy) in [(1, 1), (-1, 1), (1, -1), (-1, -1)] {
            let p = ((x * sx + 2) as f32, (y * sy - 1) as f32);
            if !circle.contains(&p) {
                circle.push(p);
            }
        }
    }
    assert_eq!(circle.len(), 12);
    let square = [(0.0, 0.0), (10.0, 0.0), (10.0, 10.0), (0.0, 10.0)];
    for (sites, centre) in [(&circle[..], (2.0, -1.0)), (&square[..], (5.0, 5.0))] {
        let (dt, g) = graph_of(sites, &b);
        assert_eq!(ours_vertices(&dt), vec![centre], "{sites:?}");
        let c = g
            .vertices()
            .iter()
            .position(|v| (v.x, v.y) == (centre.0 as f32, centre.1 as f32));
        let c = c.expect("the centre is a graph vertex") as u16;
        // One ray per site pair adjacent on the circle, all from the centre.
        let rays = g.edges().iter().filter(|e| !e.border).count();
        assert_eq!(rays, sites.len(), "{sites:?}");
        assert!(g
            .edges()
            .iter()
            .filter(|e| !e.border)
            .all(|e| e.a == c || e.b == c));
    }
}

#[test]
fn duplicates_are_refused_and_change_nothing() {
    let b = box_of(100.0);
    let mut dt = Box::new(Dt::new());
    for (x, y) in [(0.0, 0.0), (10.0, 1.0), (3.0, 8.0), (-4.0, 5.0)] {
        dt.insert(Vec2::new(x, y)).unwrap();
    }
    let mut before = Box::new(Graph::new());
    dt.graph(&b, &mut before).unwrap();
    // Same grid point: exactly, and within a half quantum (1/32 m) of it.
    for (x, y, existing) in [(10.0, 1.0, 1), (3.01, 7.99, 2), (-4.03, 5.0, 3)] {
        assert_eq!(
            dt.insert(Vec2::new(x, y)),
            Err(VoronoiError::DuplicateSite { index: 4, existing })
        );
        assert_eq!(dt.site_count(), 4);
        let mut after = Box::new(Graph::new());
        dt.graph(&b, &mut after).unwrap();
        assert_eq!(
            (before.vertices(), before.edges()),
            (after.vertices(), after.edges())
        );
    }
    // The same for a collinear structure.
    dt.clear();
    dt.insert(Vec2::new(0.0, 0.0)).unwrap();
    dt.insert(Vec2::new(1.0, 0.0)).unwrap();
    assert_eq!(
        dt.insert(Vec2::new(0.0, 0.0)),
        Err(VoronoiError::DuplicateSite {
            index: 2,
            existing: 0
        })
    );
    // rebuild refuses a duplicate before clearing anything.
    assert_eq!(
        dt.rebuild(&[Vec2::new(5.0, 5.0), Vec2::new(5.0, 5.0)]),
        Err(VoronoiError::DuplicateSite {
            index: 1,
            existing: 0
        })
    );
    assert_eq!(dt.site_count(), 2);
    assert_eq!(dt.site(1), Some(Vec2::new(1.0, 0.0)));
}

#[test]
fn bad_sites_bounds_and_capacities_are_refused() {
    let mut small: Delaunay<4, 8> = Delaunay::new();
    for (x, y) in [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (1.0, 1.0)] {
        small.insert(Vec2::new(x, y)).unwrap();
    }
    assert_eq!(
        small.insert(Vec2::new(2.0, 2.0)),
        Err(VoronoiError::TooManySites { capacity: 4 })
    );
    assert_eq!(small.site_count(), 4);
    assert_eq!(
        small.rebuild(&[Vec2::new(0.0, 0.0); 5]),
        Err(VoronoiError::TooManySites { capacity: 4 })
    );
    let mut dt = Box::new(Dt::new());
    for (v, e) in [
        (Vec2::new(f32::NAN, 0.0), VoronoiError::NonFinite),
        (Vec2::new(0.0, f32::INFINITY), VoronoiError::NonFinite),
        (Vec2::new(1.0e7 + 1.0, 0.0), VoronoiError::OutOfRange),
        (Vec2::new(0.0, -1.0e30), VoronoiError::OutOfRange),
    ] {
        assert_eq!(dt.insert(v), Err(e));
    }
    assert_eq!(dt.site_count(), 0);
    // The largest coordinates are accepted, and exact.
    for v in [
        Vec2::new(1.0e7, 1.0e7),
        Vec2::new(-1.0e7, 1.0e7),
        Vec2::new(1.0e7, -1.0e7),
    ] {
        dt.insert(v).unwrap();
    }
    dt.insert(Vec2::new(-1.0e7, -1.0e7)).unwrap();
    assert_eq!(ours_vertices(&dt), vec![(0.0, 0.0)]);
    // Bounds.
    let mut g = Box::new(Graph::new());
    for b in [
        Bounds {
            min: Vec2::new(0.0, 0.0),
            max: Vec2::new(0.0, 1.0),
        },
        Bounds {
            min: Vec2::new(1.0, 0.0),
            max: Vec2::new(0.0, 1.0),
        },
        Bounds {
            min: Vec2::new(f32::NAN, 0.0),
            max: Vec2::new(1.0, 1.0),
        },
        Bounds {
            min: Vec2::new(0.0, 0.0),
            max: Vec2::new(1.0, f32::INFINITY),
        },
    ] {
        assert_eq!(
            dt.graph(&b, &mut g),
            Err(VoronoiError::InvalidBounds),
            "{b:?}"
        );
    }
    // A graph too small: refused and left empty.
    let mut tiny: VoronoiGraph<3, 8> = VoronoiGraph::new();
    assert_eq!(
        Dt::new().graph(&box_of(1.0), &mut tiny),
        Err(VoronoiError::GraphFull)
    );
    assert!(tiny.vertices().is_empty() && tiny.edges().is_empty());
    let mut few_edges: VoronoiGraph<64, 5> = VoronoiGraph::new();
    assert_eq!(
        dt.graph(&box_of(2.0e7), &mut few_edges),
        Err(VoronoiError::GraphFull)
    );
    assert!(few_edges.edges().is_empty());
}

/// Random f32 bit patterns and extreme values for sites, bounds and capacities, in random call
/// sequences: nothing panics, every refusal leaves the site count as it was, and every graph
/// that is produced passes the graph checks.
#[test]
fn garbage_never_panics() {
    let mut rng = Rng(0x5EED_0003);
    let specials = [
        f32::NAN,
        f32::INFINITY,
        f32::NEG_INFINITY,
        1e30,
        -1e30,
        1e7,
        -1e7,
        1e-30,
        0.0,
        -0.0,
        f32::MAX,
        f32::MIN_POSITIVE,
        1e7 + 1.0,
    ];
    let value = |rng: &mut Rng| match rng.below(4) {
        0 => f32::from_bits(rng.next_u64() as u32),
        1 => specials[rng.below(specials.len() as u64) as usize],
        2 => rng.range_f32(-50.0, 50.0).round() / 4.0,
        _ => rng.range_f32(-1e7, 1e7),
    };
    let mut dt = Box::new(Dt::new());
    let mut small: Box<Delaunay<5, 10>> = Box::new(Delaunay::new());
    let mut g = Box::new(Graph::new());
    let mut tiny: VoronoiGraph<9, 12> = VoronoiGraph::new();
    for _ in 0..cases(3000, 30000) {
        let v = Vec2::new(value(&mut rng), value(&mut rng));
        let before = (dt.site_count(), small.site_count());
        if dt.insert(v).is_err() {
            assert_eq!(dt.site_count(), before.0);
        }
        if small.insert(v).is_err() {
            assert_eq!(small.site_count(), before.1);
        }
        if rng.chance(0.05) {
            let sites: Vec<Vec2> = (0..rng.below(80))
                .map(|_| Vec2::new(value(&mut rng), value(&mut rng)))
                .collect();
            let n = dt.site_count();
            if dt.rebuild(&sites).is_err() {
                assert_eq!(dt.site_count(), n);
            }
        }
        if rng.chance(0.1) {
            let (a, c) = (
                Vec2::new(value(&mut rng), value(&mut rng)),
                Vec2::new(value(&mut rng), value(&mut rng)),
            );
            let b = Bounds { min: a, max: c };
            if dt.graph(&b, &mut g).is_ok() && (c.x - a.x).abs() < 1e6 && (c.y - a.y).abs() < 1e6 {
                check_graph_shape(&g, &b);
            }
            let _ = small.graph(&b, &mut tiny);
        }
        if rng.chance(0.02) {
            dt.clear();
        }
    }
}

/// The shape checks that need no tolerance: inside the box, connected.
fn check_graph_shape(g: &Graph, b: &Bounds) {
    for v in g.vertices() {
        assert!(v.x >= b.min.x && v.x <= b.max.x && v.y >= b.min.y && v.y <= b.max.y);
    }
    let mut adj = vec![Vec::new(); g.vertices().len()];
    for e in g.edges() {
        adj[e.a as usize].push(e.b as usize);
        adj[e.b as usize].push(e.a as usize);
    }
    let mut seen = vec![false; adj.len()];
    let mut stack = vec![0];
    while let Some(v) = stack.pop() {
        if !std::mem::replace(&mut seen[v], true) {
            stack.extend(&adj[v]);
        }
    }
    assert!(seen.iter().all(|&s| s), "graph not connected");
}
