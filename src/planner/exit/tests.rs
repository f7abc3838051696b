//! The exit's counted work against the documented work model, worked out here in f64 from the
//! regions' definitions: the regions the start lies in, then for each of the 65 candidates
//! the trace of every region (2 per polygon edge, 1 per disc), the insertion sort (the square
//! of the trace's interval count) and, for a candidate shorter than the best so far, the
//! clearance check of its primitives (one box test per obstacle that is not a region) and the
//! regions its end lies in.

extern crate std;
use crate::geometry::{Pose, Vec2};
use crate::network::write::{encode, NetworkSpec, ObstacleSpec};
use crate::planner::exit::{EXIT_MARGIN_M, EXIT_TURN_STEPS};
use crate::planner::{Meter, Planner, Popup};
use std::boxed::Box;
use std::vec::Vec;

const RADIUS: f64 = 30.0;
const CLEARANCE: f64 = 5.0;

type P = (f64, f64);

/// The region the start lies in: a static square.
const SQUARE: [P; 4] = [(-40.0, -40.0), (40.0, -40.0), (40.0, 40.0), (-40.0, 40.0)];
/// Four static rectangles 3 km out, each apart from everything near the start along one side
/// of the box only (left, right, below, above).
const FAR: [[P; 4]; 4] = [
    [
        (-3100.0, -2500.0),
        (-3000.0, -2500.0),
        (-3000.0, 2500.0),
        (-3100.0, 2500.0),
    ],
    [
        (3000.0, -2500.0),
        (3100.0, -2500.0),
        (3100.0, 2500.0),
        (3000.0, 2500.0),
    ],
    [
        (-2500.0, -3100.0),
        (2500.0, -3100.0),
        (2500.0, -3000.0),
        (-2500.0, -3000.0),
    ],
    [
        (-2500.0, 3000.0),
        (2500.0, 3000.0),
        (2500.0, 3100.0),
        (-2500.0, 3100.0),
    ],
];
/// The pop-up disc the start lies in: centre and radius.
const DISC: (P, f64) = ((-5.0, 4.0), 35.0);

/// The pop-up pentagon the start lies in: radius 50 around (10, 5).
fn pentagon() -> Vec<P> {
    (0..5)
        .map(|i| {
            let a = 0.2 + i as f64 * 2.0 * core::f64::consts::PI / 5.0;
            (10.0 + 50.0 * a.cos(), 5.0 + 50.0 * a.sin())
        })
        .collect()
}

fn v(p: P) -> Vec2 {
    Vec2::new(p.0 as f32, p.1 as f32)
}

fn network() -> Vec<u8> {
    let polygon = |points: &[P]| ObstacleSpec::Polygon(points.iter().map(|p| v(*p)).collect());
    let mut obstacles = std::vec![polygon(&SQUARE)];
    obstacles.extend(FAR.iter().map(|f| polygon(f)));
    let spec = NetworkSpec {
        origin_lat_deg: 48.0,
        origin_lon_deg: 11.6,
        turn_radius_m: RADIUS as f32,
        clearance_m: CLEARANCE as f32,
        vertices: [
            (-4000.0, -4000.0),
            (4000.0, -4000.0),
            (-4000.0, 4000.0),
            (4000.0, 4000.0),
        ]
        .iter()
        .map(|&(x, y)| Pose::new(x, y, 0.0))
        .collect(),
        edges: Vec::new(),
        obstacles,
        grid_cell_m: 500.0,
        terrain: None,
        landmark: None,
        voronoi: None,
        provenance: Vec::new(),
    };
    encode(&spec).expect("a valid roadmap")
}

fn cross(a: P, b: P) -> f64 {
    a.0 * b.1 - a.1 * b.0
}

fn sub(a: P, b: P) -> P {
    (a.0 - b.0, a.1 - b.1)
}

fn norm(a: P) -> f64 {
    a.0.hypot(a.1)
}

/// Distance from `p` to the segment `a → b`.
fn point_segment(p: P, a: P, b: P) -> f64 {
    let d = sub(b, a);
    let t = ((p.0 - a.0) * d.0 + (p.1 - a.1) * d.1) / (d.0 * d.0 + d.1 * d.1);
    let t = t.clamp(0.0, 1.0);
    norm(sub(p, (a.0 + t * d.0, a.1 + t * d.1)))
}

/// Whether `p` lies inside `poly` or within `c` of it.
fn near_polygon(p: P, poly: &[P], c: f64) -> bool {
    let n = poly.len();
    let mut inside = false;
    for i in 0..n {
        let (a, b) = (poly[i], poly[(i + 1) % n]);
        if point_segment(p, a, b) <= c {
            return true;
        }
        if (a.1 > p.1) != (b.1 > p.1) && p.0 < a.0 + (p.1 - a.1) / (b.1 - a.1) * (b.0 - a.0) {
            inside = !inside;
        }
    }
    inside
}

/// The trace intervals of the line `o + t·u` on `poly` widened by `c`: one per edge the line
/// passes within `c` of, and one per pair of edges it crosses. Panics on a near tie.
fn polygon_intervals(o: P, u: P, poly: &[P], c: f64) -> u64 {
    let n = poly.len();
    let (mut capsules, mut crossings) = (0, 0);
    for i in 0..n {
        let (a, b) = (poly[i], poly[(i + 1) % n]);
        let (sa, sb) = (cross(u, sub(a, o)), cross(u, sub(b, o)));
        let distance = if (sa >= 0.0) != (sb >= 0.0) {
            crossings += 1;
            0.0
        } else {
            sa.abs().min(sb.abs())
        };
        assert!((distance - c).abs() > 1e-3, "an edge at the clearance");
        capsules += u64::from(distance <= c);
    }
    capsules + crossings / 2
}

/// The documented count of the exit's work from `start`, and its length.
fn reference(start: (P, f64)) -> (u64, f64) {
    let pentagon = pentagon();
    let near_any = |p: P| {
        near_polygon(p, &SQUARE, CLEARANCE)
            || near_polygon(p, &pentagon, CLEARANCE)
            || norm(sub(p, DISC.0)) <= DISC.1 + CLEARANCE
    };
    // The regions a point lies in, each counted: a box test per obstacle (5) and the exact
    // test of the square when the point is in its box widened by the clearance (4 edges and
    // the containment test); each pop-up's exact test (the pentagon's 5 edges and containment,
    // the disc 1).
    let regions_at = |p: P| {
        let in_box = p.0.abs() <= 40.0 + CLEARANCE && p.1.abs() <= 40.0 + CLEARANCE;
        5 + if in_box { 5 } else { 0 } + 6 + 1
    };
    let ((x, y), h) = start;
    assert!(near_any((x, y)), "the start lies in the regions");
    let mut work = regions_at((x, y));
    let mut best: Option<f64> = None;
    for k in 0..=EXIT_TURN_STEPS {
        for left in [true, false] {
            if k == 0 && !left {
                continue;
            }
            let phi = k as f64 * core::f64::consts::PI / EXIT_TURN_STEPS as f64;
            let s = if left { 1.0 } else { -1.0 };
            // The arc's end: around the centre on the turn's side, heading h ± φ.
            let centre = (x - s * RADIUS * h.sin(), y + s * RADIUS * h.cos());
            let heading = h + s * phi;
            let o = (
                centre.0 + s * RADIUS * heading.sin(),
                centre.1 - s * RADIUS * heading.cos(),
            );
            let u = (heading.cos(), heading.sin());
            // The trace: the square (2·4), the pentagon (2·5), the disc (1), then the sort.
            let disc_distance = cross(u, sub(DISC.0, o)).abs();
            assert!((disc_distance - DISC.1 - CLEARANCE).abs() > 1e-3);
            let intervals = polygon_intervals(o, u, &SQUARE, CLEARANCE)
                + polygon_intervals(o, u, &pentagon, CLEARANCE)
                + u64::from(disc_distance <= DISC.1 + CLEARANCE);
            work += 19 + intervals * intervals;
            // The reach: where the line leaves the union it is in at t = 0 (the regions are
            // convex, so each one's trace is one interval), by steps of 0.25 m and bisection.
            let at = |t: f64| (o.0 + t * u.0, o.1 + t * u.1);
            let reach = if near_any(o) {
                let mut hi = 0.25;
                while near_any(at(hi)) {
                    hi += 0.25;
                }
                let mut lo = hi - 0.25;
                for _ in 0..60 {
                    let mid = 0.5 * (lo + hi);
                    if near_any(at(mid)) {
                        lo = mid;
                    } else {
                        hi = mid;
                    }
                }
                lo
            } else {
                0.0
            };
            let length = RADIUS * phi + reach + EXIT_MARGIN_M as f64;
            if let Some(b) = best {
                assert!((b - length).abs() > 1e-3, "two candidates of one length");
                if b <= length {
                    continue;
                }
            }
            // Shorter: its clearance check, a box test of each far rectangle per primitive
            // (the arc when it turns, the straight), then the regions at its end, which it
            // leaves clear of.
            let end = at(reach + EXIT_MARGIN_M as f64);
            assert!(!near_any(end), "the end lies outside the regions");
            let primitives = if k > 0 { 2 } else { 1 };
            work += 4 * primitives + regions_at(end);
            best = Some(length);
        }
    }
    (work, best.expect("a candidate"))
}

/// From starts at three headings inside a static square, a pop-up pentagon and a pop-up disc,
/// with four static rectangles far away: the exit counts exactly the documented work, and is
/// the shortest candidate found here.
#[test]
fn the_exit_counts_each_candidates_trace_sort_and_clearance_check() {
    let image = network();
    let mut p: Box<Planner<'_, 64, 64, 4, 64>> = Box::default();
    p.load(&image).unwrap();
    let pentagon: heapless::Vec<Vec2, 16> = pentagon().iter().map(|q| v(*q)).collect();
    p.add_popup(Popup::Polygon(pentagon)).unwrap();
    p.add_popup(Popup::Circle {
        centre: v(DISC.0),
        radius: DISC.1 as f32,
    })
    .unwrap();
    for (start, heading) in [
        ((3.0, -2.0), 0.3),
        ((-12.0, 20.0), 2.0),
        ((20.0, -20.0), -1.2),
    ] {
        let (work, length) = reference((start, heading));
        let mut meter = Meter::new(u64::MAX);
        let pose = Pose {
            position: v(start),
            heading: heading as f32,
        };
        let (path, exit) = p.exit_from(&pose, &mut meter).unwrap().expect("an exit");
        assert_eq!(exit.regions, 3);
        assert!(
            (f64::from(path.length()) - length).abs() < 0.01,
            "exit of {} m, the reference's {length} m",
            path.length()
        );
        assert_eq!(meter.work.collision_tests, work, "from {start:?}");
        assert_eq!(meter.work.total(), work);
    }
}
