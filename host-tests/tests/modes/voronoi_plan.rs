//! Voronoi mode (Judd & McLain) end to end on ruz-popups and voronoi-dense, through the ground
//! tool's builder and the onboard planner, against independent references: a Dijkstra in f64
//! over the planner's graph with exposure recomputed from the paper's formula, dense f64
//! sampling of every smoothed piece (curvature from x′y″ − y′x″, continuity at the knots,
//! clearance from the zones by the f64 reference geometry), and the diagram rebuilt from
//! scratch after a threat pops up.

use host_tests::reference::{dist_polygon, inside, P};
use host_tests::scenarios::scenario;
use skyroute::geometry::spline::Piece;
use skyroute::network::write::ObstacleSpec;
use skyroute::planner::{Threat, VoronoiStorage, MAX_THREATS, VORONOI_GRAPH_VERTICES};
use skyroute::{Goal, LoadError, PlanError, Planner, Pose, Query, Search, Vec2};
use skyroute_prep::build::{build, BuildOptions, Built};
use skyroute_prep::scenario::{Mode, Scenario};
use std::collections::BinaryHeap;

pub(crate) type VPlanner<'n> = Planner<'n, 1024, 1024, 4, 4096>;

/// A diagram of the threats' capacity.
type Diagram = skyroute::geometry::voronoi::Delaunay<MAX_THREATS, { 2 * MAX_THREATS }>;
/// A graph of the planner's capacity.
type Graph = skyroute::geometry::voronoi::VoronoiGraph<
    { VORONOI_GRAPH_VERTICES },
    { skyroute::planner::VORONOI_GRAPH_EDGES },
>;

/// The scenario taken as a Voronoi scenario (as `--mode voronoi`), and its network.
pub(crate) fn voronoi(name: &str) -> (Scenario, Built) {
    let mut s = scenario(name).clone();
    s.planner.mode = Mode::Voronoi;
    let b = build(&s, &BuildOptions::default(), &|_, _| {})
        .unwrap_or_else(|e| panic!("{name} builds as voronoi: {e}"));
    (s, b)
}

/// A planner of the Voronoi network `bytes` (its storage leaked: a test's lifetime).
pub(crate) fn planner(bytes: &[u8]) -> Box<VPlanner<'_>> {
    let storage = Box::leak(Box::new(VoronoiStorage::new()));
    let mut p: Box<VPlanner> = Box::new(Planner::new());
    p.load_voronoi(bytes, storage)
        .expect("the Voronoi network loads");
    p
}

/// The scenario's start pose and goal in the local frame.
pub(crate) fn query(s: &Scenario, b: &Built) -> Query {
    let f = &b.frame;
    let (st, g) = (s.start.as_ref().unwrap(), s.goal.as_ref().unwrap());
    Query {
        start: Pose {
            position: skyroute_prep::build::local(f, st.lon, st.lat),
            heading: skyroute_prep::build::local_heading(
                f,
                st.lon,
                st.lat,
                st.heading_deg.unwrap(),
            ),
        },
        goal: Goal {
            position: skyroute_prep::build::local(f, g.lon, g.lat),
            heading: None,
        },
        search: Search::Dijkstra,
    }
}

pub(crate) fn p64(v: Vec2) -> P {
    (v.x as f64, v.y as f64)
}

/// The paper's three-point exposure of `a → b`, in f64, written from the formula.
fn exposure64(a: P, b: P, threats: &[Threat]) -> f64 {
    let l = ((b.0 - a.0).powi(2) + (b.1 - a.1).powi(2)).sqrt();
    let mut sum = 0.0;
    for f in [1.0 / 6.0, 0.5, 5.0 / 6.0] {
        let q = (a.0 + f * (b.0 - a.0), a.1 + f * (b.1 - a.1));
        for t in threats {
            let r = t.radius as f64;
            let d = ((q.0 - t.position.x as f64).powi(2) + (q.1 - t.position.y as f64).powi(2))
                .sqrt()
                .max(0.01 * r);
            sum += (r / d).powi(4);
        }
    }
    l / 3.0 * sum
}

fn cost64(a: P, b: P, threats: &[Threat], k: f64) -> f64 {
    let l = ((b.0 - a.0).powi(2) + (b.1 - a.1).powi(2)).sqrt();
    k * l + (1.0 - k) * exposure64(a, b, threats)
}

/// The polygons of the network (no-fly zones), in f64.
pub(crate) fn zones(b: &Built) -> Vec<Vec<P>> {
    b.obstacles
        .iter()
        .filter_map(|o| match o {
            ObstacleSpec::Polygon(points) => Some(points.iter().map(|q| p64(*q)).collect()),
            ObstacleSpec::Circle { .. } => None,
        })
        .collect()
}

/// Whether the segment keeps `clearance` from every zone (f64 reference, sampled at 1 m: the
/// segments checked here are graph edges and links, whose clearance the planner decides
/// exactly; the reference only needs to agree away from touching).
fn segment_clear(a: P, b: P, zones: &[Vec<P>], clearance: f64) -> bool {
    zones.iter().all(|z| {
        host_tests::reference::dist_segment_polygon(a, b, z) > clearance
            && !inside(a, z)
            && !inside(b, z)
    })
}

/// The cheapest coarse route's cost by an independent Dijkstra in f64: start joined to the
/// three nearest graph vertices with a clear segment, the same for the goal, and the direct
/// segment.
fn reference_cost(p: &VPlanner, q: &Query, zones: &[Vec<P>], clearance: f64, k: f64) -> f64 {
    let g = p.threat_graph().unwrap();
    let threats = p.threats();
    let verts: Vec<P> = g.vertices().iter().map(|v| p64(*v)).collect();
    let n = verts.len();
    let (s, t) = (p64(q.start.position), p64(q.goal.position));
    let links = |from: P| -> Vec<usize> {
        let mut order: Vec<usize> = (0..n).collect();
        order.sort_by(|&i, &j| {
            let (di, dj) = (
                host_tests::reference::dist(from, verts[i]),
                host_tests::reference::dist(from, verts[j]),
            );
            di.partial_cmp(&dj).unwrap()
        });
        order
            .into_iter()
            .take(32)
            .filter(|&i| segment_clear(from, verts[i], zones, clearance))
            .take(3)
            .collect()
    };
    let mut adj: Vec<Vec<(usize, f64)>> = vec![Vec::new(); n + 2];
    for e in g.edges() {
        let (a, b) = (e.a as usize, e.b as usize);
        if segment_clear(verts[a], verts[b], zones, clearance) {
            let c = cost64(verts[a], verts[b], threats, k);
            adj[a].push((b, c));
            adj[b].push((a, c));
        }
    }
    for i in links(s) {
        adj[n].push((i, cost64(s, verts[i], threats, k)));
    }
    for i in links(t) {
        adj[i].push((n + 1, cost64(verts[i], t, threats, k)));
    }
    if segment_clear(s, t, zones, clearance) {
        adj[n].push((n + 1, cost64(s, t, threats, k)));
    }
    #[derive(PartialEq)]
    struct Item(f64, usize);
    impl Eq for Item {}
    impl PartialOrd for Item {
        fn partial_cmp(&self, o: &Self) -> Option<std::cmp::Ordering> {
            Some(self.cmp(o))
        }
    }
    impl Ord for Item {
        fn cmp(&self, o: &Self) -> std::cmp::Ordering {
            o.0.partial_cmp(&self.0).unwrap()
        }
    }
    let mut dist = vec![f64::INFINITY; n + 2];
    dist[n] = 0.0;
    let mut heap = BinaryHeap::from([Item(0.0, n)]);
    while let Some(Item(d, u)) = heap.pop() {
        if d > dist[u] {
            continue;
        }
        for &(v, c) in &adj[u] {
            if d + c < dist[v] {
                dist[v] = d + c;
                heap.push(Item(d + c, v));
            }
        }
    }
    dist[n + 1]
}

/// The coarse route the planner flew (start, graph vertices, goal) and its cost in f64.
fn coarse_cost(p: &VPlanner, k: f64) -> (Vec<P>, f64) {
    let paths = p.route_paths();
    let mut pts = vec![p64(paths[0].start.position)];
    pts.extend(paths.iter().map(|q| p64(q.end().position)));
    let c = pts
        .windows(2)
        .map(|w| cost64(w[0], w[1], p.threats(), k))
        .sum();
    (pts, c)
}

#[test]
fn the_stored_graph_is_the_graph_built_onboard() {
    for name in ["ruz-popups", "voronoi-dense"] {
        let (_, b) = voronoi(name);
        let p = planner(&b.bytes);
        let g = p.threat_graph().unwrap();
        let net = p.network();
        assert_eq!(g.vertex_count(), net.vertex_count(), "{name}");
        assert_eq!(2 * g.edges().len() as u32, net.edge_count(), "{name}");
        for v in 0..net.vertex_count() {
            let stored = net.vertex(v).unwrap().position;
            assert_eq!(stored, g.vertex(v).unwrap(), "{name}: vertex {v}");
        }
    }
}

#[test]
fn the_coarse_route_is_the_cheapest_by_an_independent_dijkstra() {
    for name in ["ruz-popups", "voronoi-dense"] {
        let (s, b) = voronoi(name);
        let zs = zones(&b);
        let clearance = s.planner.clearance_m.unwrap_or(0.0);
        for k in [0.1f32, 0.5, 0.9, 1.0] {
            let mut p = planner(&b.bytes);
            p.set_threat_weight(k).unwrap();
            let q = query(&s, &b);
            p.plan(&q, p.worst_case_work())
                .unwrap_or_else(|e| panic!("{name} k={k}: {e}"));
            let (_, got) = coarse_cost(&p, k as f64);
            let want = reference_cost(&p, &q, &zs, clearance, k as f64);
            assert!(
                (got - want).abs() <= 1e-4 * want,
                "{name} k={k}: planner's coarse route costs {got}, the f64 optimum {want}"
            );
        }
    }
}

/// The search graph walks each undirected edge once in each direction: every half-edge in
/// `out_edges(v)` leaves `v` for the edge's other end, and nothing lies past the last vertex,
/// half-edge or edge. After a second search, each edge's price is the paper's cost in f64 and its
/// clear flag the f64 reference's verdict (away from touching).
#[test]
fn the_search_graph_holds_each_edge_once_each_way_priced_by_the_formula() {
    for name in ["ruz-popups", "voronoi-dense"] {
        let (s, b) = voronoi(name);
        let zs = zones(&b);
        let clearance = s.planner.clearance_m.unwrap_or(0.0);
        let k = 0.5f32;
        let mut p = planner(&b.bytes);
        p.set_threat_weight(k).unwrap();
        // Twice: the second search prices and flags every edge again over the first's.
        for _ in 0..2 {
            p.plan(&query(&s, &b), p.worst_case_work())
                .unwrap_or_else(|e| panic!("{name}: {e}"));
        }
        let g = p.threat_graph().unwrap();
        let (n, m) = (g.vertex_count(), g.edges().len() as u32);
        assert_eq!(n as usize, g.vertices().len(), "{name}");
        let mut walked = vec![[0u32; 2]; m as usize];
        let mut slots = 0;
        for v in 0..n {
            for k in g.out_edges(v) {
                let h = g.half_edge(k).unwrap_or_else(|| panic!("{name}: slot {k}"));
                let e = g.edges()[h.edge as usize];
                assert_eq!(h.source as u32, v, "{name}: slot {k} leaves {v}");
                let forward = (e.a, e.b) == (h.source, h.target);
                assert!(
                    forward || (e.b, e.a) == (h.source, h.target),
                    "{name}: slot {k}"
                );
                walked[h.edge as usize][forward as usize] += 1;
                slots += 1;
            }
        }
        assert!(walked.iter().all(|w| *w == [1, 1]), "{name}: {walked:?}");
        assert_eq!(slots, 2 * m, "{name}");
        assert_eq!(g.out_edges(n), 0..0, "{name}");
        assert_eq!(g.half_edge(2 * m), None, "{name}");
        assert_eq!(g.vertex(n), None, "{name}");
        assert_eq!(g.edge_ends(m), None, "{name}");
        let mut clear = 0;
        for (e, ge) in g.edges().iter().enumerate() {
            let (a, b) = g.edge_ends(e as u32).unwrap();
            assert_eq!(
                (a, b),
                (g.vertices()[ge.a as usize], g.vertices()[ge.b as usize])
            );
            let want = cost64(p64(a), p64(b), p.threats(), k as f64);
            let got = g.edge_cost(e as u32).unwrap() as f64;
            assert!(
                (got - want).abs() <= 1e-4 * want,
                "{name}: edge {e} costs {got}, the formula {want}"
            );
            let margin = zs
                .iter()
                .map(|z| host_tests::reference::dist_segment_polygon(p64(a), p64(b), z))
                .fold(f64::INFINITY, f64::min)
                - clearance;
            if margin.abs() > 0.01 {
                assert_eq!(
                    g.is_clear(e as u32),
                    segment_clear(p64(a), p64(b), &zs, clearance),
                    "{name}: edge {e}, {margin} m beyond the clearance"
                );
            }
            clear += g.is_clear(e as u32) as u32;
        }
        assert!(clear > 0, "{name}: no edge clear");
    }
}

/// Curvature of a piece at `t` in f64 from its control points.
pub(crate) fn curvature64(piece: &Piece, t: f64) -> (P, P, f64) {
    match piece {
        Piece::Line { a, b } => {
            let d = (b.x as f64 - a.x as f64, b.y as f64 - a.y as f64);
            ((a.x as f64 + t * d.0, a.y as f64 + t * d.1), d, 0.0)
        }
        Piece::Cubic { p } => {
            let c: Vec<P> = p.iter().map(|q| p64(*q)).collect();
            let u = 1.0 - t;
            let pos = (
                u * u * u * c[0].0
                    + 3.0 * u * u * t * c[1].0
                    + 3.0 * u * t * t * c[2].0
                    + t * t * t * c[3].0,
                u * u * u * c[0].1
                    + 3.0 * u * u * t * c[1].1
                    + 3.0 * u * t * t * c[2].1
                    + t * t * t * c[3].1,
            );
            let d1 = |i: usize| (c[i + 1].0 - c[i].0, c[i + 1].1 - c[i].1);
            let (q0, q1, q2) = (d1(0), d1(1), d1(2));
            let v = (
                3.0 * (u * u * q0.0 + 2.0 * u * t * q1.0 + t * t * q2.0),
                3.0 * (u * u * q0.1 + 2.0 * u * t * q1.1 + t * t * q2.1),
            );
            let a = (
                6.0 * (u * (q1.0 - q0.0) + t * (q2.0 - q1.0)),
                6.0 * (u * (q1.1 - q0.1) + t * (q2.1 - q1.1)),
            );
            let speed = (v.0 * v.0 + v.1 * v.1).sqrt();
            let k = if speed > 0.0 {
                (v.0 * a.1 - v.1 * a.0) / speed.powi(3)
            } else {
                0.0
            };
            (pos, v, k)
        }
    }
}

#[test]
fn smoothed_routes_are_flyable_and_clear_for_every_weight() {
    for name in ["ruz-popups", "voronoi-dense"] {
        let (s, b) = voronoi(name);
        let zs = zones(&b);
        let clearance = s.planner.clearance_m.unwrap_or(0.0);
        for k in [0.1f32, 0.5, 0.9, 1.0] {
            let mut p = planner(&b.bytes);
            p.set_threat_weight(k).unwrap();
            let q = query(&s, &b);
            p.plan(&q, p.worst_case_work()).unwrap();
            let kappa = 1.0 / p.network().turn_radius() as f64;
            let pieces = p.route_pieces().to_vec();
            assert!(!pieces.is_empty());
            let (first, v0, _) = curvature64(&pieces[0], 0.0);
            assert!(host_tests::reference::dist(first, p64(q.start.position)) < 0.01);
            let h = v0.1.atan2(v0.0);
            let dh = (h - q.start.heading as f64 + std::f64::consts::PI)
                .rem_euclid(std::f64::consts::TAU)
                - std::f64::consts::PI;
            assert!(
                dh.abs() < 1e-3,
                "{name} k={k}: leaves at {h}, start heading {}",
                q.start.heading
            );
            let (last, _, _) = curvature64(pieces.last().unwrap(), 1.0);
            assert!(host_tests::reference::dist(last, p64(q.goal.position)) < 0.05);
            let mut prev: Option<(P, f64, f64)> = None;
            for (i, piece) in pieces.iter().enumerate() {
                for j in 0..=400 {
                    let t = j as f64 / 400.0;
                    let (pos, v, kap) = curvature64(piece, t);
                    assert!(
                        kap.abs() <= kappa * 1.001 + 1e-9,
                        "{name} k={k}: piece {i} t={t}: curvature {kap} > {kappa}"
                    );
                    for z in &zs {
                        assert!(
                            !inside(pos, z) && dist_polygon(pos, z) >= clearance - 0.5,
                            "{name} k={k}: piece {i} within the clearance of a zone"
                        );
                    }
                    if j == 0 {
                        if let Some((end, heading, kend)) = prev {
                            assert!(
                                host_tests::reference::dist(end, pos) < 0.01,
                                "{name} k={k}: gap before piece {i}"
                            );
                            let hh = v.1.atan2(v.0);
                            let d = (hh - heading + std::f64::consts::PI)
                                .rem_euclid(std::f64::consts::TAU)
                                - std::f64::consts::PI;
                            assert!(
                                d.abs() < 1e-3,
                                "{name} k={k}: heading jumps {d} rad before piece {i}"
                            );
                            assert!(
                                (kap - kend).abs() <= 1e-3 * kappa + 1e-9,
                                "{name} k={k}: curvature jumps {kend} -> {kap} before piece {i}"
                            );
                        }
                    }
                }
                let (end, v, kend) = curvature64(piece, 1.0);
                prev = Some((end, v.1.atan2(v.0), kend));
            }
        }
    }
}

#[test]
fn exposure_falls_and_length_grows_as_the_weight_falls() {
    for name in ["ruz-popups", "voronoi-dense"] {
        let (s, b) = voronoi(name);
        let mut last: Option<(f64, f64, f32)> = None;
        for k in [1.0f32, 0.9, 0.5, 0.1] {
            let mut p = planner(&b.bytes);
            p.set_threat_weight(k).unwrap();
            p.plan(&query(&s, &b), p.worst_case_work()).unwrap();
            let (pts, _) = coarse_cost(&p, k as f64);
            let length: f64 = pts
                .windows(2)
                .map(|w| host_tests::reference::dist(w[0], w[1]))
                .sum();
            let exposure: f64 = pts
                .windows(2)
                .map(|w| exposure64(w[0], w[1], p.threats()))
                .sum();
            if let Some((l0, e0, k0)) = last {
                assert!(
                    exposure <= e0 * (1.0 + 1e-4),
                    "{name}: exposure {exposure} at k={k} above {e0} at k={k0}"
                );
                assert!(
                    length >= l0 * (1.0 - 1e-4),
                    "{name}: length {length} at k={k} below {l0} at k={k0}"
                );
            }
            last = Some((length, exposure, k));
        }
    }
}

/// A radar popped up in the middle of the longest coarse leg: the graph rebuilt in flight is
/// the graph of all the sites built from scratch, the counted work is the insertion's, the
/// graph's and the grouping's of that build, the route re-planned is less exposed to it than
/// the old one, and its removal (counted as a rebuild from the sites left) restores the route.
#[test]
fn a_popped_threat_reroutes_and_its_removal_restores_the_route() {
    let (s, b) = voronoi("ruz-popups");
    let mut p = planner(&b.bytes);
    let q = query(&s, &b);
    p.plan(&q, p.worst_case_work()).unwrap();
    let before: Vec<Piece> = p.route_pieces().to_vec();
    let (pts, _) = coarse_cost(&p, 0.5);
    // A radar in the middle of the longest coarse leg.
    let (i, _) = pts
        .windows(2)
        .enumerate()
        .map(|(i, w)| (i, host_tests::reference::dist(w[0], w[1])))
        .max_by(|a, b| a.1.partial_cmp(&b.1).unwrap())
        .unwrap();
    let at = Vec2::new(
        ((pts[i].0 + pts[i + 1].0) / 2.0) as f32,
        ((pts[i].1 + pts[i + 1].1) / 2.0) as f32,
    );
    let old_exposure_with_it: f64 = {
        let mut threats = p.threats().to_vec();
        threats.push(Threat {
            position: at,
            radius: 3000.0,
            origin: skyroute::planner::ThreatOrigin::Popped(0),
        });
        pts.windows(2)
            .map(|w| exposure64(w[0], w[1], &threats))
            .sum()
    };
    let added = p.add_threat(at, 3000.0).unwrap();
    assert!(added.work <= skyroute::planner::threat_rebuild_work_bound(p.threats().len() as u64));
    // The incrementally updated graph is the graph of all the sites built from scratch, one
    // site at a time as the load and the addition did.
    let sites: Vec<Vec2> = p.threats().iter().map(|t| t.position).collect();
    let (last, earlier) = sites.split_last().unwrap();
    let mut fresh = Box::new(Diagram::new());
    for s in earlier {
        fresh.insert(*s).unwrap();
    }
    let before_last = fresh.work();
    fresh.insert(*last).unwrap();
    let bounds = p.network().voronoi_bounds().unwrap();
    let mut g = Box::new(Graph::new());
    fresh.graph(&bounds, &mut g).unwrap();
    assert_eq!(g.vertices(), p.threat_graph().unwrap().vertices());
    assert_eq!(g.edges(), p.threat_graph().unwrap().edges());
    // Its counted work: the insertion, the graph and the grouping of its half-edges by
    // source, each edge twice and each vertex once.
    let grouping = |g: &Graph| 2 * g.edges().len() as u64 + g.vertices().len() as u64;
    assert_eq!(
        added.work,
        fresh.work() - before_last + g.work() + grouping(&g)
    );
    p.plan(&q, p.worst_case_work()).unwrap();
    let (new_pts, _) = coarse_cost(&p, 0.5);
    let new_exposure: f64 = new_pts
        .windows(2)
        .map(|w| exposure64(w[0], w[1], p.threats()))
        .sum();
    assert!(new_exposure < old_exposure_with_it, "re-planned exposure {new_exposure} not below the old route's {old_exposure_with_it} under the new threat");
    let removed = p.remove_threat(added.id).unwrap();
    // A removal rebuilds the diagram from the sites left.
    fresh.rebuild(earlier).unwrap();
    fresh.graph(&bounds, &mut g).unwrap();
    assert_eq!(removed.work, fresh.work() + g.work() + grouping(&g));
    p.plan(&q, p.worst_case_work()).unwrap();
    assert_eq!(
        p.route_pieces(),
        &before[..],
        "removing the threat restores the route"
    );
}

/// A Voronoi planner needs room for the most vertices the graph can have after threats pop up:
/// with exactly that many it loads, with one fewer it is refused by name.
#[test]
fn a_planner_one_vertex_short_of_the_graph_bound_is_refused() {
    type Exact<'n> = Planner<'n, { VORONOI_GRAPH_VERTICES }, 1024, 4, 4096>;
    type Short<'n> = Planner<'n, { VORONOI_GRAPH_VERTICES - 1 }, 1024, 4, 4096>;
    let (_, b) = voronoi("ruz-popups");
    let mut short: Box<Short> = Box::new(Planner::new());
    let storage = Box::leak(Box::new(VoronoiStorage::new()));
    assert!(matches!(
        short.load_voronoi(&b.bytes, storage),
        Err(LoadError::TooManySearchStates { .. })
    ));
    let mut exact: Box<Exact> = Box::new(Planner::new());
    let storage = Box::leak(Box::new(VoronoiStorage::new()));
    assert_eq!(exact.load_voronoi(&b.bytes, storage), Ok(()));
}

#[test]
fn random_queries_and_threats_stay_within_the_work_bound() {
    use host_tests::rng::Rng;
    let mut rng = Rng(29);
    for name in ["ruz-popups", "voronoi-dense"] {
        let (_, b) = voronoi(name);
        let mut p = planner(&b.bytes);
        let bounds = p.network().voronoi_bounds().unwrap();
        let mut routes = 0;
        for i in 0..host_tests::cases(40, 400) {
            let at = |rng: &mut Rng| {
                Vec2::new(
                    rng.range(bounds.min.x as f64, bounds.max.x as f64) as f32,
                    rng.range(bounds.min.y as f64, bounds.max.y as f64) as f32,
                )
            };
            if i % 7 == 3 {
                let r = rng.range(500.0, 5000.0) as f32;
                let _ = p.add_threat(at(&mut rng), r);
            }
            if i % 11 == 5 {
                let ids: Vec<u8> = p
                    .threats()
                    .iter()
                    .filter_map(|t| match t.origin {
                        skyroute::planner::ThreatOrigin::Popped(id) => Some(id),
                        skyroute::planner::ThreatOrigin::Network(_) => None,
                    })
                    .collect();
                if let Some(id) = ids.first() {
                    p.remove_threat(*id).unwrap();
                }
            }
            p.set_threat_weight(rng.unit() as f32).unwrap();
            let q = Query {
                start: Pose {
                    position: at(&mut rng),
                    heading: rng.range(-3.2, 3.2) as f32,
                },
                goal: Goal {
                    position: at(&mut rng),
                    heading: rng.chance(0.5).then(|| rng.range(-3.2, 3.2) as f32),
                },
                search: Search::Dijkstra,
            };
            let bound = p.worst_case_work();
            match p.plan(&q, bound) {
                Ok(r) => {
                    routes += 1;
                    assert!(
                        r.work.total() <= bound,
                        "{name}: work {} > bound {bound}",
                        r.work.total()
                    );
                }
                // A start or goal in a zone or within its clearance (no clear segment leaves
                // it), or an end the curvature cannot meet nearby.
                Err(PlanError::InsideObstacle { .. })
                | Err(PlanError::StartUnconnected)
                | Err(PlanError::GoalUnconnected)
                | Err(PlanError::Smoothing { .. }) => {}
                Err(e) => panic!("{name}: query {i} {q:?}: {e}"),
            }
        }
        println!("{name}: {routes} routes");
        assert!(routes > 0);
    }
}

#[test]
fn a_popup_obstacle_in_flight_is_kept_clear_of() {
    let (s, b) = voronoi("voronoi-dense");
    let mut p = planner(&b.bytes);
    let q = query(&s, &b);
    p.plan(&q, p.worst_case_work()).unwrap();
    // A 1.5 km disc on the middle of the first route's longest straight piece.
    let (a, c) = p
        .route_pieces()
        .iter()
        .filter_map(|piece| match piece {
            Piece::Line { a, b } => Some((*a, *b)),
            Piece::Cubic { .. } => None,
        })
        .max_by(|x, y| x.0.distance(x.1).partial_cmp(&y.0.distance(y.1)).unwrap())
        .unwrap();
    let centre = (a + c) * 0.5;
    let radius = 1500.0;
    p.add_popup(skyroute::Popup::Circle { centre, radius })
        .unwrap();
    p.plan(&q, p.worst_case_work()).unwrap();
    let clearance = p.network().clearance() as f64;
    for (i, piece) in p.route_pieces().iter().enumerate() {
        for j in 0..=400 {
            let (pos, _, _) = curvature64(piece, j as f64 / 400.0);
            let d = host_tests::reference::dist(pos, p64(centre));
            assert!(
                d >= radius as f64 + clearance - 0.5,
                "piece {i} passes {d} m from the pop-up's centre"
            );
        }
    }
}

#[test]
fn post_processing_refuses_a_voronoi_route_and_keeps_it() {
    let (s, b) = voronoi("voronoi-dense");
    let mut p = planner(&b.bytes);
    p.plan(&query(&s, &b), p.worst_case_work()).unwrap();
    let (route, summary) = (p.route().to_vec(), *p.route_summary().unwrap());
    assert_eq!(p.shortcut(u64::MAX), Err(PlanError::NotDubinsRoute));
    assert_eq!(p.shortcut_best(u64::MAX), Err(PlanError::NotDubinsRoute));
    assert_eq!(
        p.smooth_headings(9, u64::MAX),
        Err(PlanError::NotDubinsRoute)
    );
    assert_eq!(p.route(), &route[..], "the smoothed spline stays");
    assert_eq!(p.route_summary(), Some(&summary));
}
