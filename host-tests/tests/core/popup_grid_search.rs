//! The pop-up grid search (`Planner::add_popup` through `Network::cells_overlapping`): the
//! grid index lists each Dubins edge only in the cells its primitives' bounding boxes
//! overlap, so a pop-up within the clearance of an edge but in a neighbouring cell is found
//! only because the pop-up's box is widened by the clearance on every side. Checked on hand-built networks
//! of straight edges (Dubins words whose arcs are empty), whose exact geometry is known in
//! f64: pop-ups just outside each of the four sides of one edge's cells, and random pop-ups
//! near a lattice's edges against a brute force over all edges with the f64 reference
//! distances (`host_tests::reference`).

use host_tests::reference::{dist_point_segment, dist_segment_polygon, P};
use host_tests::{cases, Rng};
use skyroute::geometry::predicates::point_segment_distance;
use skyroute::network::dubins_hull;
use skyroute::network::write::{encode, EdgeSpec, NetworkSpec};
use skyroute::planner::Popup;
use skyroute::{DubinsPath, DubinsWord, Network, Planner, Pose, Vec2};

type Sp<'n> = Planner<'n, 1024, 1024, 4, 64>;

/// Turn radius: the grid's margin is 4r + cell, a multiple of the cell, so with a vertex at
/// the origin every cell boundary lies on a multiple of [`CELL`].
const RADIUS: f32 = 10.0;
const CELL: f32 = 10.0;
/// More than half a cell: a pop-up in the next cell can be within the clearance.
const CLEARANCE: f32 = 8.0;

fn line(source: u32, target: u32, length: f32) -> EdgeSpec {
    EdgeSpec {
        source,
        target,
        cost: length,
        word: DubinsWord::Lsl,
        lengths: [0.0, length, 0.0],
    }
}

fn spec(vertices: Vec<Pose>, edges: Vec<EdgeSpec>) -> NetworkSpec {
    NetworkSpec {
        origin_lat_deg: 48.0,
        origin_lon_deg: 11.6,
        turn_radius_m: RADIUS,
        clearance_m: CLEARANCE,
        vertices,
        edges,
        obstacles: Vec::new(),
        grid_cell_m: CELL,
        landmark: None,
        voronoi: None,
        terrain: None,
        provenance: Vec::new(),
    }
}

fn load(bytes: &[u8]) -> Box<Sp<'_>> {
    let mut p: Box<Sp<'_>> = Box::new(Planner::new());
    p.load(bytes).expect("test network loads");
    p
}

fn square(c: Vec2, half: f32, angle: f32) -> Popup {
    let pts: Vec<Vec2> = (0..4)
        .map(|k| {
            let a = angle + k as f32 * std::f32::consts::FRAC_PI_2;
            c + Vec2::new(a.cos(), a.sin()) * (half * std::f32::consts::SQRT_2)
        })
        .collect();
    Popup::Polygon(heapless::Vec::from_slice(&pts).unwrap())
}

/// Whether the grid index lists edge `e` in any cell the pop-up's own (unwidened) box
/// overlaps.
fn listed_under_popup_box(net: &Network<'_>, popup: &Popup, e: u32) -> bool {
    let (lo, hi) = popup.bounding_box();
    let Some(r) = net.cells_overlapping(lo, hi) else {
        return false;
    };
    (r.y0..=r.y1).any(|y| (r.x0..=r.x1).any(|x| net.cell_edges(x, y).any(|listed| listed == e)))
}

/// One edge from (82, 45) to (88, 45): its cells are column [80, 90) and row [40, 50), 2 m
/// from the west and east boundaries and 5 m from the south and north ones. A pop-up 3 m west,
/// 3 m east, 6 m south or 6 m north of it (≤ 8 m clearance) lies wholly in the neighbouring
/// cell and must block it; the same pop-ups moved to 8.5 m must not.
#[test]
fn popups_in_each_neighbouring_cell_within_the_clearance_block_the_edge() {
    let vertices = vec![
        Pose::new(0.0, 0.0, 0.0), // fixes the grid: cell boundaries at multiples of 10 m
        Pose::new(82.0, 45.0, 0.0),
        Pose::new(88.0, 45.0, 0.0),
    ];
    let bytes = encode(&spec(vertices, vec![line(1, 2, 6.0)])).unwrap();
    let mut p = load(&bytes);
    let net = *p.network();
    assert_eq!(net.edge_count(), 1);
    // Where the edge is listed: exactly one cell, the one holding (85, 45).
    let listed: Vec<(u32, u32)> = (0..net.header().grid_ny)
        .flat_map(|y| (0..net.header().grid_nx).map(move |x| (x, y)))
        .filter(|&(x, y)| net.cell_edges(x, y).next().is_some())
        .collect();
    let home = net
        .cells_overlapping(Vec2::new(85.0, 45.0), Vec2::new(85.0, 45.0))
        .unwrap();
    assert_eq!(listed, vec![(home.x0, home.y0)]);

    let r = 0.5;
    // (side, nearest point of the edge, outward unit direction, gap to the edge)
    let sides = [
        ("west", Vec2::new(82.0, 45.0), Vec2::new(-1.0, 0.0), 3.0),
        ("east", Vec2::new(88.0, 45.0), Vec2::new(1.0, 0.0), 3.0),
        ("south", Vec2::new(85.0, 45.0), Vec2::new(0.0, -1.0), 6.0),
        ("north", Vec2::new(85.0, 45.0), Vec2::new(0.0, 1.0), 6.0),
    ];
    for (side, q, out, gap) in sides {
        for (gap, blocks) in [(gap, true), (CLEARANCE + 0.5, false)] {
            let shapes = [
                Popup::Circle {
                    centre: q + out * (gap + r),
                    radius: r,
                },
                square(q + out * (gap + r), r, 0.0),
            ];
            for popup in shapes {
                if blocks {
                    assert!(
                        !listed_under_popup_box(&net, &popup, 0),
                        "{side}: the pop-up's own box reaches the edge's cell, so the case \
                         would not need the widening: {popup:?}"
                    );
                }
                let s = p.add_popup(popup.clone()).unwrap();
                assert_eq!(
                    (s.edges_blocked == 1, p.is_edge_enabled(0)),
                    (blocks, !blocks),
                    "{side} at {gap} m: {popup:?}"
                );
                p.remove_popup(s.id).unwrap();
            }
        }
    }
}

/// A lattice of straight edges: positions `(7i, 7j)`, 0 ≤ i, j < 10; at each, one vertex per
/// direction of [`DIRECTIONS`], with an edge to the same direction's vertex at the next
/// lattice position that way. Returns the spec and each edge's end points in f64.
fn lattice() -> (NetworkSpec, Vec<(P, P)>) {
    const DIRECTIONS: [(i32, i32); 6] = [(1, 0), (0, 1), (1, 1), (-1, 1), (2, 1), (-1, 2)];
    const N: i32 = 10;
    const STEP: f32 = 7.0;
    let index = |i: i32, j: i32, d: usize| ((j * N + i) as usize * DIRECTIONS.len() + d) as u32;
    let mut vertices = Vec::new();
    let mut edges = Vec::new();
    let mut ends = Vec::new();
    for j in 0..N {
        for i in 0..N {
            for (d, &(di, dj)) in DIRECTIONS.iter().enumerate() {
                let heading = (dj as f32).atan2(di as f32);
                vertices.push(Pose::new(i as f32 * STEP, j as f32 * STEP, heading));
                let (ti, tj) = (i + di, j + dj);
                if (0..N).contains(&ti) && (0..N).contains(&tj) {
                    let length = STEP * ((di * di + dj * dj) as f32).sqrt();
                    edges.push(line(index(i, j, d), index(ti, tj, d), length));
                    ends.push((
                        (i as f64 * STEP as f64, j as f64 * STEP as f64),
                        (ti as f64 * STEP as f64, tj as f64 * STEP as f64),
                    ));
                }
            }
        }
    }
    (spec(vertices, edges), ends)
}

/// Random circles and squares placed near random edges (up to 20 m, more than two cells,
/// beyond the clearance): every edge's blocked state after `add_popup` equals the brute
/// force "f64 distance from the pop-up to the edge's segment ≤ clearance" over all edges.
/// Distances within 1 mm of the clearance are left out (f32 rounding may go either way).
#[test]
fn popup_blocking_matches_an_f64_brute_force_over_all_edges() {
    let (spec, ends) = lattice();
    let bytes = encode(&spec).unwrap();
    let mut p = load(&bytes);
    let net = *p.network();
    assert_eq!(net.edge_count() as usize, ends.len());
    // The writer groups edges by source, keeping order: map stored index -> spec index.
    let mut order: Vec<usize> = (0..spec.edges.len()).collect();
    order.sort_by_key(|&i| spec.edges[i].source);
    let c = CLEARANCE as f64;
    let mut rng = Rng(15);
    let (mut blocked_total, mut via_neighbour, mut skipped) = (0u64, 0u64, 0u64);
    let n = cases(300, 3000);
    for case in 0..n {
        let (a, b) = ends[rng.below(ends.len() as u64) as usize];
        let t = rng.unit();
        let q = (a.0 + t * (b.0 - a.0), a.1 + t * (b.1 - a.1));
        let (ux, uy) = rng.unit_vector();
        let gap = rng.range(0.0, 20.0);
        let size = rng.range(0.1, 3.0);
        let centre = Vec2::new(
            (q.0 + ux * (gap + size)) as f32,
            (q.1 + uy * (gap + size)) as f32,
        );
        let popup = if case % 2 == 0 {
            Popup::Circle {
                centre,
                radius: size as f32,
            }
        } else {
            square(centre, size as f32, rng.range_f32(0.0, 1.6))
        };
        let distance = |(a, b): (P, P)| -> f64 {
            match &popup {
                Popup::Circle { centre, radius } => {
                    dist_point_segment((centre.x as f64, centre.y as f64), a, b) - *radius as f64
                }
                Popup::Polygon(pts) => {
                    let poly: Vec<P> = pts.iter().map(|p| (p.x as f64, p.y as f64)).collect();
                    dist_segment_polygon(a, b, &poly)
                }
            }
        };
        let s = p.add_popup(popup.clone()).unwrap();
        for (stored, &spec_index) in order.iter().enumerate() {
            let d = distance(ends[spec_index]);
            if (d - c).abs() < 1e-3 {
                skipped += 1;
                continue;
            }
            let expected = d <= c;
            let blocked = !p.is_edge_enabled(stored as u32);
            assert_eq!(
                blocked, expected,
                "case {case}: edge {stored} {:?} at {d} m from {popup:?}",
                ends[spec_index]
            );
            if expected {
                blocked_total += 1;
                if !listed_under_popup_box(&net, &popup, stored as u32) {
                    via_neighbour += 1;
                }
            }
        }
        p.remove_popup(s.id).unwrap();
    }
    println!(
        "{n} pop-ups: {blocked_total} edges blocked, {via_neighbour} of them only through the \
         widening into neighbouring cells, {skipped} edge distances within 1 mm of the \
         clearance left out"
    );
    assert!(
        via_neighbour >= n as u64 / 10,
        "too few neighbouring-cell cases"
    );
    assert!(skipped <= n as u64, "too many ambiguous distances");
}

/// The work a pop-up charges for one listed roadmap edge: a single predicate test when the
/// edge's hull (`dubins_hull`: the segment joining its first and last turning circles'
/// centres, widened by the radius) is farther than the clearance, and otherwise one test per
/// primitive of the solved path, as `Popup::conflicts` counts them: one for a circle, one per
/// edge and one for containment for a polygon. One curved edge (three non-empty pieces) in one
/// large index cell, with a pop-up far from it and pop-ups beside it.
#[test]
fn a_listed_edge_costs_one_predicate_test_when_its_hull_is_far() {
    let (a, b) = (Pose::new(0.0, 0.0, 0.0), Pose::new(60.0, 40.0, 0.0));
    let path = DubinsPath::shortest(&a, &b, RADIUS).unwrap();
    let prims: Vec<_> = path.primitives().into_iter().flatten().collect();
    assert_eq!(prims.len(), 3, "{path:?}");
    assert!(path.lengths.iter().all(|&l| l > 1.0), "{path:?}");
    let edge = EdgeSpec::dubins(0, 1, &path);
    let mut s = spec(vec![a, b], vec![edge]);
    s.grid_cell_m = 1000.0; // one cell holds the edge and both pop-ups
    let bytes = encode(&s).unwrap();
    let mut p = load(&bytes);

    let far = Popup::Circle {
        centre: Vec2::new(30.0, 200.0),
        radius: 1.0,
    };
    let summary = p.add_popup(far).unwrap();
    assert_eq!(summary.entries_visited, 1);
    assert_eq!(
        summary.predicate_tests, 1,
        "the hull test alone: {summary:?}"
    );
    assert_eq!(summary.edges_blocked, 0);
    p.remove_popup(summary.id).unwrap();

    // Beside the edge: a pop-up within the clearance of the hull's band but clear of every
    // primitive, so the hull test does not decide and each primitive is tested (the hull
    // test itself is then not counted).
    let (hull, reach) = dubins_hull(&a, &b, RADIUS, path.word);
    let hull64 = (
        (hull.start.x as f64, hull.start.y as f64),
        (hull.end.x as f64, hull.end.y as f64),
    );
    let circle = |centre| Popup::Circle {
        centre,
        radius: 1.0,
    };
    let centre = (-40..100)
        .flat_map(|x| (-40..80).map(move |y| Vec2::new(x as f32, y as f32)))
        .find(|&c| {
            let to_hull = dist_point_segment((c.x as f64, c.y as f64), hull64.0, hull64.1);
            to_hull < (reach + 1.0 + CLEARANCE) as f64 - 1.0
                && prims.iter().all(|q| !circle(c).conflicts(q, CLEARANCE).0)
        })
        .expect("a point near the hull and clear of the path");
    // A circle costs one test per primitive; a polygon of n vertices (here inscribed in that
    // circle, so just as clear) one per edge and one for containment, per primitive.
    let beside = circle(centre);
    let summary = p.add_popup(beside.clone()).unwrap();
    assert_eq!(summary.edges_blocked, 0, "{beside:?}");
    assert_eq!(summary.predicate_tests, 3, "{beside:?}: {summary:?}");
    p.remove_popup(summary.id).unwrap();
    for n in [3u32, 4, 7, 16] {
        let points: Vec<Vec2> = (0..n)
            .map(|k| {
                let a = k as f32 * std::f32::consts::TAU / n as f32;
                centre + Vec2::new(a.cos(), a.sin())
            })
            .collect();
        let polygon = Popup::Polygon(heapless::Vec::from_slice(&points).unwrap());
        let summary = p.add_popup(polygon).unwrap();
        assert_eq!(summary.edges_blocked, 0, "{n} vertices");
        assert_eq!(
            summary.predicate_tests,
            3 * (n + 1),
            "{n} vertices: {summary:?}"
        );
        p.remove_popup(summary.id).unwrap();
    }

    // At the hull test's bound: a square of half-side 20 m, whose bounding circle (its box's
    // half-diagonal, 28.3 m) is what the test widens by, placed on the perpendicular through the
    // hull segment's middle where its centre lies `gap` beyond the bound the core computes
    // (`hull_is_far`: radius + clearance + reach + 10⁻⁴·(size + reach + radius) + 1 cm, in
    // f32). 1 m and 1 mm beyond, the hull test alone decides; 1 mm inside, every primitive is
    // tested (and the square, 30 m from the path's band, is not in conflict), and on the bound
    // itself too. So a bound moved by a millimetre either way, a radius widened, a margin
    // narrowed or the strict comparison relaxed, shows in the count.
    let middle = (hull.start + hull.end) * 0.5;
    let along = hull.end - hull.start;
    let normal = Vec2::new(-along.y, along.x) * (1.0 / along.norm());
    let square = |c: Vec2| {
        let corners = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)];
        let points: Vec<Vec2> = corners
            .iter()
            .map(|&(x, y)| c + Vec2::new(20.0 * x, 20.0 * y))
            .collect();
        Popup::Polygon(heapless::Vec::from_slice(&points).unwrap())
    };
    let beyond_bound = |t: f32| {
        let (lo, hi) = square(middle + normal * t).bounding_box();
        let c = (lo + hi) * 0.5;
        let radius = (hi - lo).norm() * 0.5;
        let size = [hull.start, hull.end, c]
            .iter()
            .fold(0.0f32, |m, q| m.max(q.x.abs()).max(q.y.abs()));
        let margin = 1e-4 * (size + reach + radius) + 0.01;
        point_segment_distance(c, &hull) - (radius + CLEARANCE + reach + margin)
    };
    // The offset along the normal whose centre lies `gap` beyond the bound (bisection: the
    // excess grows with the offset).
    let at_gap = |gap: f32| {
        let (mut lo, mut hi) = (0.0f32, 500.0f32);
        for _ in 0..100 {
            let mid = 0.5 * (lo + hi);
            if beyond_bound(mid) < gap {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        hi
    };
    for (gap, tests) in [(1.0f32, 1u32), (1e-3, 1), (-1e-3, 3 * 5)] {
        let t = at_gap(gap);
        assert!(
            (beyond_bound(t) - gap).abs() < 2e-4,
            "gap {gap}: {}",
            beyond_bound(t)
        );
        let summary = p.add_popup(square(middle + normal * t)).unwrap();
        assert_eq!(summary.edges_blocked, 0, "gap {gap}");
        assert_eq!(summary.predicate_tests, tests, "gap {gap}: {summary:?}");
        p.remove_popup(summary.id).unwrap();
    }
    // On the bound itself (an offset whose distance equals it in f32, found among the offsets
    // next to the bisection's): not far, so the primitives are tested.
    let mut t = at_gap(0.0);
    for _ in 0..16 {
        t = t.next_down();
    }
    let on_bound = (0..32)
        .scan(t, |t, _| {
            *t = t.next_up();
            Some(*t)
        })
        .find(|&t| beyond_bound(t) == 0.0)
        .expect("an offset whose centre lies exactly on the bound");
    let summary = p.add_popup(square(middle + normal * on_bound)).unwrap();
    assert_eq!(summary.predicate_tests, 3 * 5, "on the bound: {summary:?}");
}

/// On a sparse grid (two short edges 2.8 km apart, 10 m cells: tens of thousands of empty
/// cells, a few dozen entries) a pop-up over the whole grid visits every one of its
/// `nx · ny` cells, and its counted work stays within `worst_case_popup_work`, which charges
/// each cell once ([`skyroute::planner::popup_work_bound`]).
#[test]
fn a_popup_over_a_sparse_grid_visits_every_cell_within_the_bound() {
    let vertices = vec![
        Pose::new(0.0, 0.0, 0.0),
        Pose::new(20.0, 0.0, 0.0),
        Pose::new(2000.0, 2000.0, 0.0),
        Pose::new(2020.0, 2000.0, 0.0),
    ];
    let bytes = encode(&spec(vertices, vec![line(0, 1, 20.0), line(2, 3, 20.0)])).unwrap();
    let mut p = load(&bytes);
    let h = *p.network().header();
    let cells = h.grid_nx as u64 * h.grid_ny as u64;
    assert!(cells > 40_000, "{} × {} cells", h.grid_nx, h.grid_ny);
    let summary = p
        .add_popup(Popup::Circle {
            centre: Vec2::new(1010.0, 1000.0),
            radius: 2000.0,
        })
        .unwrap();
    assert_eq!(summary.cells_visited as u64, cells);
    assert_eq!(summary.edges_blocked, 2);
    assert!(summary.entries_visited < 100, "{summary:?}");
    let counted = cells + summary.entries_visited as u64 + summary.predicate_tests as u64;
    let bound = p.worst_case_popup_work();
    assert!(counted <= bound, "{counted} above {bound}");
}
