//! Landmark mode's online ends (Babel's Connect-Endpoints at query time) on babel-I-detour
//! and babel-III-reach: a start that is not a network vertex, or a goal that is not the stored
//! goal, joined by one Hermite piece, checked against a brute force (every overflight's piece
//! plus a search from that overflight, or a Dijkstra of the test's own to it), an independent
//! f64 sampling of the piece (limits, clearance, the joint), the range left, pop-ups and the
//! work bound.

use skyroute::geometry::hermite::{HermiteSegment, LineElement};
use skyroute::network::Network;
use skyroute::planner::{Goal, PlanError, Popup, Query, Search, POPUP_CHORDS_PER_PIECE};
use skyroute::{Planner, Pose, Vec2};
use skyroute_prep::build::Built;
use skyroute_prep::scenario::Scenario;

use host_tests::reference::{dist_polygon, obstacle_polygons, Poly64};
use host_tests::{full_tier_only, scenarios};

type Lp<'n> = Planner<'n, 1024, 40000, 4, 128>;

const SCENARIO: &str = "babel-I-detour";

fn goal(net: &Network) -> Goal {
    let l = net.landmark().unwrap();
    Goal {
        position: net.vertex(l.goal_vertex).unwrap().position,
        heading: None,
    }
}

fn query_from(net: &Network, start: Pose) -> Query {
    Query {
        start,
        goal: goal(net),
        search: Search::Dijkstra,
    }
}

/// The pose at parameter `s` of piece `k` of edge `e`.
fn pose_on(net: &Network, e: u32, k: u32, s: f32) -> Pose {
    let seg = net.chain_piece(e, k).unwrap();
    let t = seg.t_max() * s;
    let v = seg.velocity(t).unwrap();
    let at = seg.position(t).unwrap();
    Pose::new(at.x, at.y, v.y.atan2(v.x))
}

/// Samples `piece` in f64: the vehicle's limits, the clearance from every zone, and its end
/// conditions (position and velocity at both ends, zero acceleration at the end).
fn check_piece(s: &Scenario, built: &Built, piece: &HermiteSegment, from: &Pose, to: &Pose) {
    let v = &s.vehicle;
    let clearance = s.planner.clearance_m.unwrap_or(0.0);
    let polys = obstacle_polygons(&built.obstacles);
    let poly = Poly64::new(piece);
    let (p0, v0, _) = poly.eval(0.0);
    let (p1, v1, a1) = poly.eval(1.0);
    let speed = piece.v_nominal() as f64;
    for (p, vel, pose) in [(p0, v0, from), (p1, v1, to)] {
        let (x, y) = (pose.position.x as f64, pose.position.y as f64);
        assert!((p.0 - x).hypot(p.1 - y) < 0.05, "end {p:?} vs {pose:?}");
        let (hx, hy) = (pose.heading.cos() as f64, pose.heading.sin() as f64);
        assert!(
            (vel.0 - speed * hx).hypot(vel.1 - speed * hy) < 0.05,
            "velocity {vel:?} vs {pose:?}"
        );
    }
    assert!(a1.0.hypot(a1.1) < 0.05, "acceleration at the joint {a1:?}");
    let tol = 1e-3;
    for i in 0..=2000 {
        let (p, vel, acc) = poly.eval(i as f64 / 2000.0);
        let sp = vel.0.hypot(vel.1);
        let a_long = (acc.0 * vel.0 + acc.1 * vel.1) / sp;
        let a_lat = (vel.0 * acc.1 - vel.1 * acc.0).abs() / sp;
        assert!(sp >= v.v_min_mps * (1.0 - tol) && sp <= v.v_max_mps * (1.0 + tol));
        assert!(a_lat <= v.a_lat_max_mps2 * (1.0 + tol));
        assert!(a_long <= v.a_long_max_mps2 + tol && a_long >= v.a_long_min_mps2 - tol);
        for z in &polys {
            assert!(dist_polygon(p, z) >= clearance - 1e-3, "{p:?} too close");
        }
    }
}

/// The brute force: for every overflight (and the goal), the direct piece from `start` if
/// it is within `range`, flyable and clear (the core's conservative chord test), plus the
/// route a separate query plans from that overflight. The shortest total, and the number of
/// pieces that passed.
fn brute_force(
    net: &Network,
    bytes: &[u8],
    weather: u32,
    start: &Pose,
    range: f32,
    popups: &[Popup],
) -> Option<(f32, usize)> {
    let l = *net.landmark().unwrap();
    let limits = net.fly_limits().unwrap();
    let mut from_vertex: Box<Lp> = Box::new(Planner::new());
    from_vertex.load(bytes).unwrap();
    from_vertex.set_weather(weather).unwrap();
    for p in popups {
        from_vertex.add_popup(p.clone()).unwrap();
    }
    let clearance = net.clearance();
    let mut best: Option<f32> = None;
    let mut links = 0;
    for v in (0..l.landmark_count * l.directions).chain([l.goal_vertex]) {
        let to = net.vertex(v).unwrap();
        let Ok(piece) = HermiteSegment::new(
            &LineElement::from_pose(start, l.v_nominal),
            &LineElement::from_pose(&to, l.v_nominal),
            l.v_nominal,
        ) else {
            continue;
        };
        if piece.length() > range || piece.check_flyable(&limits).is_err() {
            continue;
        }
        let blocked = (0..net.obstacle_count()).any(|i| match net.obstacle(i).unwrap().0 {
            skyroute::network::Obstacle::Polygon(poly) => {
                piece.conflicts_with_polygon(&poly, clearance, POPUP_CHORDS_PER_PIECE)
            }
            skyroute::network::Obstacle::Circle { centre, radius } => {
                piece.conflicts_with_circle(centre, radius, clearance, POPUP_CHORDS_PER_PIECE)
            }
        }) || popups.iter().any(|p| match p {
            Popup::Circle { centre, radius } => {
                piece.conflicts_with_circle(*centre, *radius, clearance, POPUP_CHORDS_PER_PIECE)
            }
            Popup::Polygon(points) => {
                piece.conflicts_with_polygon(points.as_slice(), clearance, POPUP_CHORDS_PER_PIECE)
            }
        });
        if blocked {
            continue;
        }
        links += 1;
        let rest = if v == l.goal_vertex {
            0.0
        } else {
            match from_vertex.plan(&query_from(net, to), u64::MAX) {
                Ok(summary) => summary.length,
                Err(_) => continue,
            }
        };
        let total = piece.length() + rest;
        if best.is_none_or(|b| total < b) {
            best = Some(total);
        }
    }
    best.map(|b| (b, links))
}

/// Plans online starts on `name`'s stored route (part way along the first two legs, and the
/// same poses 400 m to the side with the heading turned 30°) with `range` left, in every
/// weather, against [`brute_force`]. Returns the routes planned and the most links found
/// (pieces built that passed) by one query.
fn online_starts_against_brute_force(name: &str, range: f32) -> (usize, usize) {
    let (s, built) = (scenarios::scenario(name), scenarios::built(name));
    let net = Network::from_bytes(&built.bytes).unwrap();
    let l = *net.landmark().unwrap();
    let mut p: Box<Lp> = Box::new(Planner::new());
    p.load(&built.bytes).unwrap();
    let stored = p.plan(
        &query_from(&net, net.vertex(l.start_vertex).unwrap()),
        u64::MAX,
    );
    let stored = stored.expect("the stored start plans");
    let edges = p.route_edges().to_vec();
    let mut starts = Vec::new();
    for (e, frac) in [(edges[0], 0.4f32), (edges[1], 0.5)] {
        let k = net.chain_piece_count(e) / 2;
        let on = pose_on(&net, e, k, frac);
        let side = Vec2::new(-on.heading.sin(), on.heading.cos()) * 400.0;
        starts.push(on);
        let off = on.position + side;
        starts.push(Pose::new(off.x, off.y, on.heading + 0.5));
    }
    let (mut planned, mut most_links) = (0, 0);
    for (i, start) in starts.iter().enumerate() {
        for weather in 0..l.weather_count {
            p.set_weather(weather).unwrap();
            p.set_start_range(range).unwrap();
            let online = p.plan(&query_from(&net, *start), u64::MAX);
            let reference = brute_force(&net, &built.bytes, weather, start, range, &[]);
            println!(
                "{name} start {i} weather {weather}: online {:?} m, brute force {:?} m ({} links)",
                online.as_ref().map(|r| r.length),
                reference.map(|r| r.0),
                reference.map_or(0, |r| r.1)
            );
            most_links = most_links.max(reference.map_or(0, |r| r.1));
            match (online, reference) {
                (Ok(r), Some((b, _))) => {
                    assert!(
                        (r.length - b).abs() <= 1e-4 * b,
                        "online {} vs brute force {b}",
                        r.length
                    );
                    let piece = p.start_piece().expect("an online route has a start piece");
                    assert!(piece.length() <= range);
                    let first = p
                        .route_edges()
                        .first()
                        .map_or(l.goal_vertex, |&e| net.edge_source(e).unwrap());
                    check_piece(s, built, &piece, start, &net.vertex(first).unwrap());
                    assert!(r.work.total() <= p.worst_case_work());
                    planned += 1;
                }
                (Err(PlanError::StartUnconnected | PlanError::NoRoute), None) => {}
                (online, reference) => panic!("online {online:?}, brute force {reference:?}"),
            }
        }
    }
    // The stored start still plans as before, without a start piece.
    p.set_weather(0).unwrap();
    let again = p
        .plan(
            &query_from(&net, net.vertex(l.start_vertex).unwrap()),
            u64::MAX,
        )
        .unwrap();
    assert_eq!(again.length, stored.length);
    assert!(p.start_piece().is_none());
    (planned, most_links)
}

#[test]
fn an_online_start_is_planned_as_the_best_overflight_of_a_brute_force() {
    if !full_tier_only(
        "landmark_online::an_online_start_is_planned_as_the_best_overflight_of_a_brute_force",
        "builds babel-I-detour and babel-III-reach",
    ) {
        return;
    }
    let (planned, _) = online_starts_against_brute_force(SCENARIO, 6000.0);
    assert!(
        planned >= 4,
        "only {planned} online starts planned on {SCENARIO}"
    );
    // babel-III-reach: 50 landmarks, 15 km of range.
    let (planned, most_links) = online_starts_against_brute_force("babel-III-reach", 15000.0);
    assert!(
        planned >= 4,
        "only {planned} online starts planned on babel-III-reach"
    );
    // The choice of the MAX_LINKS best is tested on its own (`keep_cheapest`'s unit test):
    // on these scenarios fewer pieces pass.
    println!("at most {most_links} links passed on babel-III-reach");
}

#[test]
fn the_range_left_pop_ups_and_the_budget_bound_the_online_start() {
    if !full_tier_only(
        "landmark_online::the_range_left_pop_ups_and_the_budget_bound_the_online_start",
        "builds babel-I-detour",
    ) {
        return;
    }
    let (s, built) = (scenarios::scenario(SCENARIO), scenarios::built(SCENARIO));
    let net = Network::from_bytes(&built.bytes).unwrap();
    let l = *net.landmark().unwrap();
    let mut p: Box<Lp> = Box::new(Planner::new());
    p.load(&built.bytes).unwrap();
    assert_eq!(p.start_range(), Some(l.start_range_m));
    p.plan(
        &query_from(&net, net.vertex(l.start_vertex).unwrap()),
        u64::MAX,
    )
    .unwrap();
    let first = p.route_edges()[0];
    let start = pose_on(&net, first, net.chain_piece_count(first) / 2, 0.5);
    let q = query_from(&net, start);
    let r = p.plan(&q, u64::MAX).expect("the online start plans");
    let piece = p.start_piece().unwrap();
    let edges = p.route_edges().to_vec();

    // Bad ranges are refused and lose nothing.
    for bad in [f32::NAN, -1.0, f32::INFINITY] {
        assert_eq!(p.set_start_range(bad), Err(PlanError::InvalidRange));
    }
    assert_eq!(p.route_edges(), &edges[..]);
    assert_eq!(p.start_piece(), Some(piece));

    // A budget one short of the count is refused; the route stays.
    let work = r.work.total();
    assert!(
        work <= p.worst_case_work(),
        "{work} > {}",
        p.worst_case_work()
    );
    assert!(matches!(
        p.plan(&q, work - 1),
        Err(PlanError::BudgetExhausted { .. })
    ));
    assert_eq!(p.route_edges(), &edges[..]);
    assert_eq!(p.start_piece(), Some(piece));

    // No range left: nothing is reachable.
    p.set_start_range(0.0).unwrap();
    assert_eq!(p.plan(&q, u64::MAX), Err(PlanError::StartUnconnected));
    // A range just short of the chosen piece: another link, within that range, or none.
    p.set_start_range(piece.length() - 1.0).unwrap();
    match p.plan(&q, u64::MAX) {
        Ok(_) => assert!(p.start_piece().unwrap().length() <= piece.length() - 1.0),
        Err(e) => assert!(matches!(
            e,
            PlanError::StartUnconnected | PlanError::NoRoute
        )),
    }

    // A pop-up on the chosen piece: the new piece keeps the clearance from it.
    p.set_start_range(l.start_range_m).unwrap();
    let middle = piece.position(piece.t_max() * 0.5).unwrap();
    let popup = Popup::Circle {
        centre: middle,
        radius: 150.0,
    };
    p.add_popup(popup.clone()).unwrap();
    let with_popup = p.plan(&q, u64::MAX);
    let reference = brute_force(&net, &built.bytes, 0, &start, l.start_range_m, &[popup]);
    println!(
        "pop-up on the start piece: {:?} m, brute force {reference:?} m",
        with_popup.as_ref().map(|r| r.length)
    );
    match (with_popup, reference.map(|r| r.0)) {
        (Ok(r), Some(b)) => {
            assert!((r.length - b).abs() <= 1e-4 * b, "{} vs {b}", r.length);
            let detour = p.start_piece().unwrap();
            let poly = Poly64::new(&detour);
            let clearance = s.planner.clearance_m.unwrap_or(0.0);
            for i in 0..=2000 {
                let (q, _, _) = poly.eval(i as f64 / 2000.0);
                let d = (q.0 - middle.x as f64).hypot(q.1 - middle.y as f64) - 150.0;
                assert!(d >= clearance - 1e-3, "{d} m from the pop-up");
            }
        }
        (Err(_), None) => {}
        (online, reference) => panic!("online {online:?}, brute force {reference:?}"),
    }
}

/// Shortest navigable distance from `from` to every vertex, by a Dijkstra of the test's own
/// over the network's edges (usable iff the core calls them navigable in its weather).
fn distances_from(net: &Network, p: &Lp, from: u32) -> Vec<f64> {
    use std::cmp::Reverse;
    use std::collections::BinaryHeap;
    let n = net.vertex_count() as usize;
    let mut dist = vec![f64::INFINITY; n];
    let mut heap = BinaryHeap::new();
    dist[from as usize] = 0.0;
    heap.push((Reverse(0u64), from));
    while let Some((Reverse(key), u)) = heap.pop() {
        let du = f64::from_bits(key);
        if du > dist[u as usize] {
            continue;
        }
        for e in net.out_edges(u) {
            let (cost, to) = net.edge_cost_target(e).unwrap();
            let d = du + cost as f64;
            if p.is_navigable(e) && d < dist[to as usize] {
                dist[to as usize] = d;
                heap.push((Reverse(d.to_bits()), to));
            }
        }
    }
    dist
}

#[test]
fn an_online_goal_is_planned_as_the_best_overflight_of_a_brute_force() {
    if !full_tier_only(
        "landmark_online::an_online_goal_is_planned_as_the_best_overflight_of_a_brute_force",
        "builds babel-I-detour",
    ) {
        return;
    }
    let (s, built) = (scenarios::scenario(SCENARIO), scenarios::built(SCENARIO));
    let net = Network::from_bytes(&built.bytes).unwrap();
    let l = *net.landmark().unwrap();
    let limits = net.fly_limits().unwrap();
    let mut p: Box<Lp> = Box::new(Planner::new());
    p.load(&built.bytes).unwrap();
    let start = net.vertex(l.start_vertex).unwrap();
    p.plan(&query_from(&net, start), u64::MAX).unwrap();
    let edges = p.route_edges().to_vec();
    // Goals on the stored route (on its last and second-to-last legs) without a heading, and
    // 500 m to the side with one.
    let mut goals = Vec::new();
    for e in [edges[edges.len() - 1], edges[edges.len() - 2]] {
        let on = pose_on(&net, e, net.chain_piece_count(e) / 2, 0.5);
        goals.push(Goal {
            position: on.position,
            heading: None,
        });
        let side = Vec2::new(-on.heading.sin(), on.heading.cos()) * 500.0;
        goals.push(Goal {
            position: on.position + side,
            heading: Some(on.heading - 0.4),
        });
    }
    let mut planned = 0;
    for weather in 0..l.weather_count {
        p.set_weather(weather).unwrap();
        let dist = distances_from(&net, &p, l.start_vertex);
        for (i, goal) in goals.iter().enumerate() {
            let q = Query {
                start,
                goal: *goal,
                search: Search::Dijkstra,
            };
            let online = p.plan(&q, u64::MAX);
            // The brute force: every overflight reached, and the piece from it to the goal
            // within its range, flyable and clear (the core's conservative chord test).
            let mut best: Option<f64> = None;
            for v in 0..l.landmark_count * l.directions {
                let (Some(range), true) = (p.overflight_range(v), dist[v as usize].is_finite())
                else {
                    continue;
                };
                let at = net.vertex(v).unwrap();
                let d = goal.position - at.position;
                let heading = goal.heading.unwrap_or(d.y.atan2(d.x));
                let to = Pose::new(goal.position.x, goal.position.y, heading);
                let Ok(piece) = HermiteSegment::new(
                    &LineElement::from_pose(&at, l.v_nominal),
                    &LineElement::from_pose(&to, l.v_nominal),
                    l.v_nominal,
                ) else {
                    continue;
                };
                let clear =
                    (0..net.obstacle_count()).all(|k| match net.obstacle(k).unwrap().0 {
                        skyroute::network::Obstacle::Polygon(poly) => !piece
                            .conflicts_with_polygon(&poly, net.clearance(), POPUP_CHORDS_PER_PIECE),
                        skyroute::network::Obstacle::Circle { .. } => false,
                    });
                if piece.length() <= range && piece.check_flyable(&limits).is_ok() && clear {
                    let total = dist[v as usize] + piece.length() as f64;
                    best = Some(best.map_or(total, |b: f64| b.min(total)));
                }
            }
            println!(
                "goal {i} weather {weather}: online {:?} m, brute force {best:?} m",
                online.as_ref().map(|r| r.length)
            );
            match (online, best) {
                (Ok(r), Some(b)) => {
                    assert!(
                        (r.length as f64 - b).abs() <= 1e-4 * b,
                        "online {} vs brute force {b}",
                        r.length
                    );
                    let piece = p.goal_piece().expect("an online goal has a goal piece");
                    let last = net.edge_link(*p.route_edges().last().unwrap()).unwrap();
                    let from = net.vertex(last.target).unwrap();
                    let end_heading = goal.heading.unwrap_or_else(|| {
                        let d = goal.position - from.position;
                        d.y.atan2(d.x)
                    });
                    let to = Pose::new(goal.position.x, goal.position.y, end_heading);
                    check_piece(s, built, &piece, &from, &to);
                    assert!(p.start_piece().is_none());
                    assert!(r.work.total() <= p.worst_case_work());
                    planned += 1;
                }
                (Err(PlanError::GoalUnconnected | PlanError::NoRoute), None) => {}
                (online, reference) => panic!("online {online:?}, brute force {reference:?}"),
            }
        }
    }
    assert!(planned >= 4, "only {planned} online goals planned");

    // Both ends online: a start on the first leg to the first goal; each piece checked.
    p.set_weather(0).unwrap();
    let first = edges[0];
    let from = pose_on(&net, first, net.chain_piece_count(first) / 2, 0.5);
    let q = Query {
        start: from,
        goal: goals[0],
        search: Search::Dijkstra,
    };
    let r = p.plan(&q, u64::MAX).expect("both ends online");
    let (a, b) = (p.start_piece().unwrap(), p.goal_piece().unwrap());
    let route = p.route_edges();
    let pieces: u32 = route.iter().map(|&e| net.chain_piece_count(e)).sum();
    assert_eq!(r.primitives, pieces + 2);
    let edge_length: f32 = route.iter().map(|&e| net.edge_length(e).unwrap()).sum();
    assert!((r.length - (a.length() + edge_length + b.length())).abs() < 0.01);
    let first_vertex = net.vertex(net.edge_source(route[0]).unwrap()).unwrap();
    check_piece(s, built, &a, &from, &first_vertex);
    assert!(r.work.total() <= p.worst_case_work());
}
