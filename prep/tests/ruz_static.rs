//! The static planners of Ruz et al. (`skyroute_prep::ruz::static_plan`): the MILP against
//! closed-form answers (a straight line at v_max, a square it must go around, a start inside a
//! disc), A* against a plain Dijkstra on the same grid and the inertia term's effect, and both
//! end to end on ruz-popups through `skyroute static-plan`.

mod common;

use common::{ok, scenario, skyroute, stdout, TempDir};
use skyroute_prep::ruz::static_plan::astar::{self, AstarOptions, Grid, MOVES};
use skyroute_prep::ruz::static_plan::check::check_route;
use skyroute_prep::ruz::static_plan::{problem, Problem};
use std::cmp::Reverse;
use std::collections::BinaryHeap;
use std::path::Path;

/// ruz-popups' problem in its scenario frame.
fn ruz() -> Problem {
    let path = scenario("ruz-popups.geojson");
    let s = skyroute_prep::scenario::load(Path::new(&path)).expect("ruz-popups loads");
    problem(&s, &s.local_frame(), &[]).expect("ruz-popups has a start and a goal")
}

/// Plain Dijkstra over the grid's cells with the grid's allowed moves, costs the move lengths:
/// the least cost from `from` to `to`.
fn dijkstra(problem: &Problem, grid: &Grid, moves: usize, from: usize, to: usize) -> Option<f64> {
    let mut dist = vec![f64::INFINITY; grid.cols * grid.rows];
    let mut heap = BinaryHeap::new();
    dist[from] = 0.0;
    heap.push(Reverse((0u64, from)));
    while let Some(Reverse((d, c))) = heap.pop() {
        let d = f64::from_bits(d);
        if d > dist[c] {
            continue;
        }
        if c == to {
            return Some(d);
        }
        for m in 0..moves {
            if let Some(j) = grid.allowed(problem, c, m) {
                let nd = d + grid.centre(c).dist(grid.centre(j));
                if nd < dist[j] {
                    dist[j] = nd;
                    // Non-negative f64s order as their bit patterns.
                    heap.push(Reverse((nd.to_bits(), j)));
                }
            }
        }
    }
    None
}

/// Direction changes of a cell path, from the cells' coordinates.
fn changes(grid: &Grid, cells: &[usize]) -> usize {
    let step = |a: usize, b: usize| {
        (
            (b % grid.cols) as i64 - (a % grid.cols) as i64,
            (b / grid.cols) as i64 - (a / grid.cols) as i64,
        )
    };
    let steps: Vec<_> = cells.windows(2).map(|w| step(w[0], w[1])).collect();
    steps.windows(2).filter(|w| w[0] != w[1]).count()
}

#[test]
fn astar_without_inertia_or_detection_equals_dijkstra() {
    let pb = ruz();
    for connectivity in [8, 16] {
        let o = AstarOptions {
            cell_m: 500.0,
            connectivity,
            inertia: 0.0,
            risk_weight: 0.0,
            margin_m: 8000.0,
        };
        let grid = Grid::new(&pb, &o);
        let r = astar::plan_on(&pb, &grid, &o).expect("A* finds a path");
        let (a, b) = (r.cells[0], *r.cells.last().unwrap());
        let d = dijkstra(&pb, &grid, connectivity, a, b).expect("Dijkstra finds a path");
        assert!(
            (r.cost - d).abs() < 1e-6,
            "{connectivity} moves: A* {} vs Dijkstra {d}",
            r.cost
        );
        let cell_length: f64 = r
            .cells
            .windows(2)
            .map(|w| grid.centre(w[0]).dist(grid.centre(w[1])))
            .sum();
        assert!((cell_length - r.cost).abs() < 1e-6);
        let c = check_route(&pb, &r.route);
        assert!(c.ok(pb.v_max, f64::INFINITY, 1e-9, 1e-6), "{c:?}");
    }
    assert_eq!(MOVES.len(), 16);
}

#[test]
fn astar_inertia_turns_no_more() {
    let pb = ruz();
    let base = AstarOptions {
        cell_m: 500.0,
        connectivity: 8,
        inertia: 0.0,
        risk_weight: 0.0,
        margin_m: 8000.0,
    };
    let grid = Grid::new(&pb, &base);
    let free = astar::plan_on(&pb, &grid, &base).expect("a path");
    let heavy = AstarOptions {
        inertia: 3000.0,
        ..base.clone()
    };
    let r = astar::plan_on(&pb, &grid, &heavy).expect("a path");
    // L₁ + λ·A₁ ≤ L₀ + λ·A₀ and L₁ ≥ L₀ give A₁ ≤ A₀ (total turning).
    assert!(r.total_turn <= free.total_turn + 1e-9);
    let (n_free, n_heavy) = (changes(&grid, &free.cells), changes(&grid, &r.cells));
    assert!(
        n_heavy <= n_free,
        "{n_heavy} direction changes with inertia, {n_free} without"
    );
    assert_eq!(n_heavy, r.direction_changes);
    assert!(r.route.length() >= free.route.length() - 1e-6);
}

#[cfg(feature = "milp")]
mod milp {
    use super::*;
    use skyroute_prep::ruz::static_plan::milp::{plan, MilpError, MilpOptions};
    use skyroute_prep::ruz::static_plan::{Disc, Pt, Zone};

    /// ruz-popups' vehicle and risk model with nothing in the way and no radars.
    fn empty(start: Pt, velocity: Pt, goal: Pt) -> Problem {
        let mut p = ruz();
        p.start = start;
        p.start_velocity = velocity;
        p.goal = goal;
        p.discs.clear();
        p.zones.clear();
        p.radars.clear();
        p
    }

    fn options() -> MilpOptions {
        MilpOptions {
            dt: 10.0,
            horizon: 10,
            commit: 5,
            risk_weight: 0.0,
            time_limit_s: 20.0,
            ..MilpOptions::default()
        }
    }

    /// Along a vertex direction of the 16-gon (angle π/16) the largest speed is exactly
    /// v_max, reached only at the vertex: k steps at v_max along the line is the only way to
    /// arrive in k·Δt, one metre more takes a step more.
    #[test]
    fn milp_straight_line_at_v_max() {
        let o = options();
        let dir = Pt::new(
            (std::f64::consts::PI / 16.0).cos(),
            (std::f64::consts::PI / 16.0).sin(),
        );
        let vmax = ruz().v_max;
        let k = 6;
        let d = k as f64 * vmax * o.dt;
        let start = Pt::new(1000.0, -2000.0);
        let pb = empty(start, dir.scale(vmax), start.plus(dir.scale(d)));
        let r = plan(&pb, &o).expect("a route");
        assert_eq!(r.route.points.len(), k + 1);
        assert!((r.route.time() - k as f64 * o.dt).abs() < 1e-9);
        for (i, p) in r.route.points.iter().enumerate() {
            let want = start.plus(dir.scale(vmax * o.dt * i as f64));
            assert!(p.dist(want) < 1e-2, "point {i}: {p:?} vs {want:?}");
        }
        let c = check_route(&pb, &r.route);
        assert!(c.ok(pb.v_max, pb.a_max, 1e-6, 1e-3), "{c:?}");
        let farther = empty(start, dir.scale(vmax), start.plus(dir.scale(d + 1.0)));
        let r = plan(&farther, &o).expect("a route");
        assert!((r.route.time() - (k + 1) as f64 * o.dt).abs() < 1e-9);
    }

    #[test]
    fn milp_goes_around_a_square() {
        let o = options();
        let mut pb = empty(
            Pt::new(0.0, 0.0),
            Pt::new(50.0, 0.0),
            Pt::new(10_000.0, 0.0),
        );
        let sq = [
            (4000.0, -1000.0),
            (6000.0, -1000.0),
            (6000.0, 1000.0),
            (4000.0, 1000.0),
        ];
        pb.zones.push(Zone {
            name: "square".into(),
            ring: sq.iter().map(|&(x, y)| Pt::new(x, y)).collect(),
        });
        let r = plan(&pb, &o).expect("a route");
        let c = check_route(&pb, &r.route);
        assert!(c.ok(pb.v_max, pb.a_max, 1e-6, 1e-3), "{c:?}");
        // The taut path round the bare square is a lower bound of any route round it.
        let around = 2.0 * 4000f64.hypot(1000.0) + 2000.0;
        assert!(
            r.route.length() >= around,
            "{} < {around}",
            r.route.length()
        );
        // The same without the square flies straight and sooner.
        let mut open = pb.clone();
        open.zones.clear();
        let straight = plan(&open, &o).expect("a route");
        assert!(straight.route.time() < r.route.time());
    }

    #[test]
    fn milp_keeps_segments_out_of_discs() {
        // Pieces of up to 1.8 km against a disc of 1.5 km: points alone outside it would let
        // a piece cut through.
        let o = MilpOptions {
            dt: 30.0,
            ..options()
        };
        let mut pb = empty(
            Pt::new(0.0, 0.0),
            Pt::new(50.0, 0.0),
            Pt::new(12_000.0, 300.0),
        );
        pb.discs.push(Disc {
            name: "disc".into(),
            centre: Pt::new(6000.0, 0.0),
            radius: 1500.0,
        });
        let r = plan(&pb, &o).expect("a route");
        let c = check_route(&pb, &r.route);
        assert!(c.ok(pb.v_max, pb.a_max, 1e-6, 1e-3), "{c:?}");
    }

    /// A radar halfway with no disc: weighing detection, the route keeps farther from it, its
    /// charge and its R_K by the risk model are lower, and it takes longer.
    #[test]
    fn milp_detection_pushes_the_route_away_from_a_radar() {
        let mut pb = empty(
            Pt::new(0.0, 0.0),
            Pt::new(50.0, 0.0),
            Pt::new(20_000.0, 0.0),
        );
        pb.radars.push(Pt::new(10_000.0, 500.0));
        let blind = MilpOptions {
            dt: 20.0,
            ..options()
        };
        let seeing = MilpOptions {
            risk_weight: 10_000.0,
            ..blind.clone()
        };
        let (a, b) = (
            plan(&pb, &blind).expect("a route"),
            plan(&pb, &seeing).expect("a route"),
        );
        let closest = |r: &skyroute_prep::ruz::static_plan::StaticRoute| {
            r.points
                .windows(2)
                .map(|w| {
                    skyroute_prep::ruz::static_plan::check::point_segment_distance(
                        pb.radars[0],
                        w[0],
                        w[1],
                    )
                })
                .fold(f64::INFINITY, f64::min)
        };
        assert!(closest(&b.route) > closest(&a.route) + 1000.0);
        let risk = |r: &skyroute_prep::ruz::static_plan::StaticRoute| {
            skyroute_prep::ruz::static_plan::score(&pb.params, &r.primitives(), &pb.radars)
                .risk_known
        };
        assert!(risk(&b.route) < risk(&a.route));
        assert!(b.route.time() > a.route.time());
        let c = check_route(&pb, &b.route);
        assert!(c.ok(pb.v_max, pb.a_max, 1e-6, 1e-3), "{c:?}");
    }

    #[test]
    fn milp_start_inside_a_disc_is_infeasible() {
        let mut pb = empty(Pt::new(0.0, 0.0), Pt::new(50.0, 0.0), Pt::new(5000.0, 0.0));
        pb.discs.push(Disc {
            name: "disc".into(),
            centre: Pt::new(100.0, 0.0),
            radius: 500.0,
        });
        assert_eq!(
            plan(&pb, &options()),
            Err(MilpError::Infeasible { solve: 0 })
        );
    }
}

/// The figure after `key` in a line of `text`.
fn figure(text: &str, key: &str) -> f64 {
    let at = text
        .find(key)
        .unwrap_or_else(|| panic!("{key:?} in {text}"))
        + key.len();
    text[at..]
        .trim_start()
        .split(|c: char| !(c.is_ascii_digit() || c == '.'))
        .next()
        .and_then(|x| x.parse().ok())
        .unwrap_or_else(|| panic!("a number after {key:?} in {text}"))
}

#[test]
fn ruz_popups_static_plans_end_to_end() {
    let dir = TempDir::new("ruz-static");
    let (net, sc) = (dir.file("n.bin"), scenario("ruz-popups.geojson"));
    ok(skyroute(&["build", &sc, "-o", &net]), "build");
    let pb = ruz();
    let straight = pb.start.dist(pb.goal);
    let mut methods = vec![vec!["--method", "astar", "--cell", "500"]];
    if !cfg!(feature = "milp") {
        let o = skyroute(&["static-plan", &net, "--scenario", &sc, "--method", "milp"]);
        assert!(!o.status.success());
        assert!(
            common::stderr(&o).contains("built without the milp feature: rebuild with"),
            "{}",
            common::stderr(&o)
        );
    }
    if cfg!(feature = "milp") {
        // Detection off keeps the solves well under a second each (docs/RUZ.md).
        methods.push(vec![
            "--method",
            "milp",
            "--risk-weight",
            "0",
            "--dt",
            "30",
            "--horizon",
            "8",
            "--commit",
            "4",
        ]);
    }
    for m in methods {
        let out = dir.file(&format!("{}.json", m[1]));
        let mut args = vec!["static-plan", &net, "--scenario", &sc, "-o", &out];
        args.extend(&m);
        let text = stdout(&ok(skyroute(&args), m[1]));
        let length = figure(&text, "ruz-popups: ");
        let risk = figure(&text, "risk R_K");
        assert!(length >= straight && length < 1.5 * straight, "{text}");
        assert!(risk > 0.0 && risk < 1.0, "{text}");
        // Every piece keeps the clearance (to HiGHS's feasibility tolerance).
        let margin: f64 = text
            .split("least clearance margin ")
            .nth(1)
            .and_then(|t| t.split(' ').next())
            .and_then(|x| x.parse().ok())
            .unwrap_or_else(|| panic!("a clearance margin in {text}"));
        assert!(margin >= -1e-3, "{text}");
        // The route file scores the same by `--method route`.
        let again = stdout(&ok(
            skyroute(&[
                "static-plan",
                &net,
                "--scenario",
                &sc,
                "--method",
                "route",
                "--route",
                &out,
            ]),
            "route",
        ));
        assert!((figure(&again, "risk R_K") - risk).abs() < 1e-4, "{again}");
        ok(
            skyroute(&[
                "render",
                &net,
                "--route",
                &out,
                "--no-edges",
                "-o",
                &dir.file("r.svg"),
            ]),
            "render",
        );
    }
}
