//! Voronoi mode's smoothing refusals and route capacity (`planner/voronoi/route.rs`): the
//! corner a refusal names at the goal, a pop-up on a lead segment, and a route whose coarse
//! legs outnumber its chords.

use crate::voronoi_plan::{curvature64, p64, planner, query, voronoi, zones, VPlanner};
use crate::voronoi_route::{coarse_legs, replan_with_popup};
use host_tests::reference::{dist, dist_point_segment, dist_polygon, inside, P};
use skyroute::geometry::spline::{fit, FitError, FitInput, Piece};
use skyroute::planner::VoronoiStorage;
use skyroute::{Goal, PlanError, Planner, Pose, Query, Vec2};

/// The coarse route's inner vertices (the graph vertices it passes), after a plan.
fn waypoints(p: &VPlanner) -> Vec<Vec2> {
    p.route_paths()
        .iter()
        .skip(1)
        .map(|l| l.start.position)
        .collect()
}

/// The smoothing of `q` over `waypoints` with every segment and hull triangle taken as clear.
fn fit_unchecked(p: &VPlanner, q: &Query, waypoints: &[Vec2]) -> Result<Vec<Piece>, FitError> {
    let net = p.network();
    let input = FitInput {
        start: q.start,
        waypoints,
        goal: q.goal.position,
        goal_heading: q.goal.heading,
        kappa_max: net.voronoi().unwrap().kappa_max,
    };
    let mut out: heapless::Vec<Piece, 64> = heapless::Vec::new();
    fit(
        &input,
        &net.corner_table().unwrap(),
        &mut |_| true,
        &mut out,
    )?;
    Ok(out.to_vec())
}

/// Plans `q` without its goal heading (the same search: links are straight), returning the
/// coarse route's inner vertices; then plans `q` and expects `PlanError::Smoothing` at the
/// goal's corner, `n + 1` for `n` coarse vertices, with the previous route kept.
fn refused_at_the_goal_corner(p: &mut VPlanner, q: &Query) -> Vec<Vec2> {
    let free = Query {
        goal: Goal {
            heading: None,
            ..q.goal
        },
        ..*q
    };
    p.plan(&free, p.worst_case_work()).unwrap();
    let coarse = waypoints(p);
    let kept = (p.route().to_vec(), p.route_pieces().to_vec());
    assert_eq!(
        p.plan(q, p.worst_case_work()),
        Err(PlanError::Smoothing {
            corner: coarse.len() as u32 + 1
        })
    );
    assert_eq!((p.route().to_vec(), p.route_pieces().to_vec()), kept);
    coarse
}

/// A goal 550 m south-west of ruz-popups' start, to be reached heading north-east: the fit
/// finds no lead-out onto that heading (`FitError::LeadOutInfeasible`, with every segment and
/// hull clear), and the plan is refused at the goal's corner, `n + 1` for a coarse route of
/// `n` graph vertices (`PlanError::Smoothing`), with the previous route kept.
#[test]
fn a_goal_heading_no_lead_out_reaches_is_refused_at_the_goal_corner() {
    let (s, b) = voronoi("ruz-popups");
    let mut p = planner(&b.bytes);
    let q = Query {
        goal: Goal {
            position: Vec2::new(-30214.963, -266.60962),
            heading: Some(0.9514849),
        },
        ..query(&s, &b)
    };
    let coarse = refused_at_the_goal_corner(&mut p, &q);
    assert_eq!(
        fit_unchecked(&p, &q, &coarse),
        Err(FitError::LeadOutInfeasible)
    );
}

/// A voronoi-dense query whose lead-out onto the goal heading (100°) would cross a no-fly
/// zone: with every check taken as clear, the fit's pieces after the last coarse vertex come
/// within the clearance of a zone (f64, 400 samples a piece) while those before it keep it,
/// and the plan is refused at the goal's corner `n + 1` with the previous route kept.
#[test]
fn a_lead_out_across_a_no_fly_zone_is_refused_at_the_goal_corner() {
    let (s, b) = voronoi("voronoi-dense");
    let mut p = planner(&b.bytes);
    let q = Query {
        start: Pose {
            position: Vec2::new(8104.801, -2206.6484),
            heading: -2.505522,
        },
        goal: Goal {
            position: Vec2::new(756.03516, 14441.244),
            heading: Some(1.7452343),
        },
        ..query(&s, &b)
    };
    let coarse = refused_at_the_goal_corner(&mut p, &q);
    let pieces = fit_unchecked(&p, &q, &coarse).expect("the fit alone flies it");
    let clearance = p.network().clearance() as f64;
    let zones = zones(&b);
    let last = p64(*coarse.last().expect("a coarse vertex"));
    // Pieces from the one nearest the last coarse vertex on: the last corner and the lead-out.
    let (at_last, _) = pieces
        .iter()
        .enumerate()
        .map(|(i, piece)| (i, dist(curvature64(piece, 0.5).0, last)))
        .min_by(|x, y| x.1.total_cmp(&y.1))
        .unwrap();
    let closest = |range: &[Piece]| {
        let mut d = f64::INFINITY;
        for piece in range {
            for j in 0..=400 {
                let x = curvature64(piece, j as f64 / 400.0).0;
                for z in &zones {
                    let to = if inside(x, z) {
                        0.0
                    } else {
                        dist_polygon(x, z)
                    };
                    d = d.min(to);
                }
            }
        }
        d
    };
    assert!(closest(&pieces[..at_last]) >= clearance - 0.5);
    assert!(closest(&pieces[at_last + 1..]) < clearance - 0.5);
}

/// A pop-up disc on a line of the smoothed route that is not on the coarse route (a lead-in
/// line, flown because the start heading is turned off the first leg), farther than the
/// clearance from every coarse leg and from every corner's hull triangle: only the fit's
/// segment test can see it, and the plan is refused at the start's corner 0 with the route
/// kept.
#[test]
fn a_popup_on_a_lead_in_line_refuses_the_start_corner() {
    let (s, b) = voronoi("voronoi-dense");
    let base = query(&s, &b);
    let mut p = planner(&b.bytes);
    let clearance = p.network().clearance() as f64;
    let radius = 1.0;
    // The first start heading (turned from the scenario's by 30° steps) that flies such a line.
    let found = (1..12).find_map(|k| {
        let q = Query {
            start: Pose {
                heading: base.start.heading + k as f32 * core::f32::consts::PI / 6.0,
                ..base.start
            },
            ..base
        };
        p.plan(&q, p.worst_case_work()).ok()?;
        let legs = coarse_legs(&p);
        let hulls: Vec<[P; 3]> = p
            .route_pieces()
            .iter()
            .filter_map(|piece| match piece {
                Piece::Cubic { p: c } => Some([p64(c[0]), p64(c[1]), p64(c[3])]),
                Piece::Line { .. } => None,
            })
            .collect();
        let margin = |m: P| {
            let to_legs = legs
                .iter()
                .map(|(a, b)| dist_point_segment(m, *a, *b))
                .fold(f64::INFINITY, f64::min);
            let to_hulls = hulls
                .iter()
                .map(|h| {
                    if inside(m, h) {
                        0.0
                    } else {
                        dist_polygon(m, h)
                    }
                })
                .fold(f64::INFINITY, f64::min);
            to_legs.min(to_hulls)
        };
        let line = p.route_pieces().iter().find_map(|piece| match piece {
            Piece::Line { .. } => {
                let m = curvature64(piece, 0.5).0;
                (margin(m) > radius + clearance + 1.0).then_some(m)
            }
            Piece::Cubic { .. } => None,
        })?;
        Some((q, line))
    });
    let (q, centre) = found.expect("a start heading with a lead-in line off the coarse route");
    let disc = skyroute::Popup::Circle {
        centre: Vec2::new(centre.0 as f32, centre.1 as f32),
        radius: radius as f32,
    };
    let distance = |at: P| dist(at, centre) - radius;
    assert_eq!(
        replan_with_popup(&mut p, &q, disc, &distance, clearance),
        Some(0)
    );
}

/// ruz-popups with 16 more threats in a 4 × 4 lattice 100–130 m apart and weight 0.078: a
/// query across the lattice has a coarse route of 9 legs whose smoothing drops most of its
/// close vertices, 5 chords in all. A planner holding 8 primitives refuses it
/// (`RouteTooLong`, 9 legs) and keeps its route; one holding 9 flies it, as the large planner
/// does.
#[test]
fn a_route_of_more_coarse_legs_than_chords_needs_room_for_its_legs() {
    const LATTICE: [(f32, f32); 16] = [
        (1919.1825, -2425.299),
        (1891.4313, -2311.7102),
        (1901.8024, -2221.3967),
        (1888.7207, -2105.062),
        (2030.9176, -2416.2544),
        (2032.98, -2317.3452),
        (2032.9266, -2226.9932),
        (2023.6941, -2123.173),
        (2127.3254, -2456.2068),
        (2102.5745, -2319.7231),
        (2106.4963, -2232.6165),
        (2101.808, -2138.003),
        (2226.8494, -2456.0955),
        (2223.3384, -2337.0916),
        (2217.398, -2233.4888),
        (2244.7583, -2101.644),
    ];
    let (s, b) = voronoi("ruz-popups");
    let q = Query {
        start: Pose {
            position: Vec2::new(2789.7905, -2136.5784),
            heading: -2.8794854,
        },
        goal: Goal {
            position: Vec2::new(2072.606, -2355.8499),
            heading: None,
        },
        ..query(&s, &b)
    };
    fn threaten<const R: usize>(p: &mut Planner<'_, 1024, 1024, 4, R>) {
        for (x, y) in LATTICE {
            p.add_threat(Vec2::new(x, y), 2000.0).unwrap();
        }
        p.set_threat_weight(0.07807846).unwrap();
    }
    let mut large = planner(&b.bytes);
    threaten(&mut large);
    let full = large.plan(&q, large.worst_case_work()).unwrap();
    let legs = large.route_paths().len();
    assert_eq!((full.primitives, legs), (5, 9), "chords and legs");
    let storage = Box::leak(Box::new(VoronoiStorage::new()));
    let mut short: Box<Planner<'_, 1024, 1024, 4, 8>> = Box::new(Planner::new());
    short.load_voronoi(&b.bytes, storage).unwrap();
    threaten(&mut short);
    let before = short.route().to_vec();
    assert_eq!(
        short.plan(&q, short.worst_case_work()),
        Err(PlanError::RouteTooLong {
            primitives: 9,
            capacity: 8
        })
    );
    assert_eq!(short.route(), &before[..]);
    let storage = Box::leak(Box::new(VoronoiStorage::new()));
    let mut exact: Box<Planner<'_, 1024, 1024, 4, 9>> = Box::new(Planner::new());
    exact.load_voronoi(&b.bytes, storage).unwrap();
    threaten(&mut exact);
    exact.plan(&q, exact.worst_case_work()).unwrap();
    assert_eq!(exact.route(), large.route());
    assert_eq!(exact.route_paths().len(), 9);
}
