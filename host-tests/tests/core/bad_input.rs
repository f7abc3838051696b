//! Bad input to the loader and the planner API that the other modules do not cover, each a row
//! of the "Bad input" table in `docs/RELIABILITY.md`: an empty network (it plans the direct
//! path), a header claiming more vertices than exist, a position beyond the coordinate limit,
//! a zero budget, the mode-only calls on the wrong mode, pop-ups with a negative or infinite
//! radius, a pop-up over the start, a full pop-up table and an unknown pop-up id. Each refused
//! call returns its own typed error and keeps the route.

use host_tests::world::{free_pose, world};
use host_tests::Rng;
use skyroute::network::format::Header;
use skyroute::network::write::{encode, NetworkSpec};
use skyroute::network::LoadError;
use skyroute::planner::{Goal, PlanError, Popup, Query, QueryField, Search};
use skyroute::{Network, Planner, PopupError, Pose, Vec2};

type TestPlanner<'n> = Planner<'n, 4096, 65536, 4, 512>;

fn planner(bytes: &[u8]) -> Box<TestPlanner<'_>> {
    let mut p: Box<TestPlanner<'_>> = Box::new(Planner::new());
    p.load(bytes).expect("test network loads");
    p
}

/// A planner on a small world with a route planned, and the query that planned it.
fn planned<'n>(bytes: &'n [u8], w: &host_tests::world::World) -> (Box<TestPlanner<'n>>, Query) {
    let mut p = planner(bytes);
    let mut rng = Rng(15);
    loop {
        let (s, g) = (free_pose(&mut rng, w, 10.0), free_pose(&mut rng, w, 10.0));
        let q = Query {
            start: s,
            goal: Goal {
                position: g.position,
                heading: None,
            },
            search: Search::AStar,
        };
        if p.plan(&q, u64::MAX).is_ok() {
            return (p, q);
        }
    }
}

#[test]
fn an_empty_network_loads_and_plans_only_the_direct_path() {
    let spec = NetworkSpec {
        origin_lat_deg: 48.0,
        origin_lon_deg: 11.6,
        turn_radius_m: 40.0,
        clearance_m: 5.0,
        vertices: Vec::new(),
        edges: Vec::new(),
        obstacles: Vec::new(),
        grid_cell_m: 80.0,
        landmark: None,
        voronoi: None,
        terrain: None,
        provenance: Vec::new(),
    };
    let bytes = encode(&spec).expect("an empty network encodes");
    let net = Network::from_bytes(&bytes).unwrap();
    assert_eq!((net.vertex_count(), net.edge_count()), (0, 0));
    let mut p = planner(&bytes);
    let q = Query {
        start: Pose::new(0.0, 0.0, 0.0),
        goal: Goal {
            position: Vec2::new(500.0, 0.0),
            heading: None,
        },
        search: Search::Dijkstra,
    };
    // Nothing to avoid: the direct Dubins path, through no network edge.
    let s = p.plan(&q, u64::MAX).unwrap();
    assert_eq!((s.primitives, s.network_edges), (1, 0));
    assert!((s.length - 500.0).abs() < 1e-3, "{}", s.length);
}

#[test]
fn a_header_claiming_four_billion_vertices_is_refused_before_the_body_is_read() {
    let w = world(3, 600.0, 60.0, 40.0, 2);
    let mut b = w.bytes.clone();
    // vertex_count: after magic, version, mode, flags, the origin and two f32 parameters.
    let at = 4 + 2 + 1 + 1 + 8 + 8 + 4 + 4;
    b[at..at + 4].copy_from_slice(&u32::MAX.to_le_bytes());
    let mut p: Box<TestPlanner<'_>> = Box::new(Planner::new());
    assert_eq!(
        p.load(&b),
        Err(LoadError::TooManyVertices {
            count: u32::MAX,
            capacity: 4096
        })
    );
    // Without a capacity, the counts imply a body the header's length does not declare.
    match Network::from_bytes(&b) {
        Err(LoadError::BodyLengthMismatch { declared, expected }) => {
            assert_eq!(declared as usize, w.bytes.len() - Header::SIZE);
            assert!(expected > u32::MAX as usize, "{expected}");
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn positions_beyond_the_coordinate_limit_are_refused_by_field() {
    let w = world(4, 800.0, 60.0, 40.0, 3);
    let (mut p, q) = planned(&w.bytes, &w);
    let kept = p.route().to_vec();
    let far = Query {
        start: Pose::new(1.0e8, 0.0, 0.0),
        ..q
    };
    assert_eq!(
        p.plan(&far, u64::MAX),
        Err(PlanError::OutOfRange {
            field: QueryField::Start
        })
    );
    let far_goal = Query {
        goal: Goal {
            position: Vec2::new(0.0, -1.0e30),
            heading: None,
        },
        ..q
    };
    assert_eq!(
        p.plan(&far_goal, u64::MAX),
        Err(PlanError::OutOfRange {
            field: QueryField::Goal
        })
    );
    let nan_start = Query {
        start: Pose::new(f32::NAN, 0.0, 0.0),
        ..q
    };
    assert_eq!(
        p.plan(&nan_start, u64::MAX),
        Err(PlanError::NonFinite {
            field: QueryField::Start
        })
    );
    assert_eq!(p.route(), &kept[..]);
}

#[test]
fn a_zero_budget_is_refused_and_keeps_the_route() {
    let w = world(5, 800.0, 60.0, 40.0, 3);
    let (mut p, q) = planned(&w.bytes, &w);
    let kept = p.route().to_vec();
    match p.plan(&q, 0) {
        Err(PlanError::BudgetExhausted { budget: 0, used }) => assert!(used >= 1, "{used}"),
        other => panic!("{other:?}"),
    }
    assert_eq!(p.route(), &kept[..]);
}

#[test]
fn mode_only_calls_on_a_roadmap_are_refused() {
    let w = world(6, 600.0, 60.0, 40.0, 2);
    let mut p = planner(&w.bytes);
    assert_eq!(p.set_weather(0), Err(PlanError::NotLandmarkNetwork));
    assert_eq!(p.set_weather(u32::MAX), Err(PlanError::NotLandmarkNetwork));
    assert_eq!(
        p.set_altitude(700.0, 50.0),
        Err(PlanError::NotTerrainNetwork)
    );
    assert_eq!(
        p.set_altitude(f32::NAN, 50.0),
        Err(PlanError::NotTerrainNetwork)
    );
    assert_eq!(p.weather(), 0);
    assert_eq!(p.altitude(), None);
}

#[test]
fn bad_popups_are_refused_with_their_own_errors() {
    let w = world(7, 600.0, 60.0, 40.0, 2);
    let mut p = planner(&w.bytes);
    let circle = |x: f32, r: f32| Popup::Circle {
        centre: Vec2::new(x, 300.0),
        radius: r,
    };
    assert_eq!(
        p.add_popup(circle(100.0, -5.0)),
        Err(PopupError::NonPositiveRadius)
    );
    assert_eq!(
        p.add_popup(circle(100.0, f32::INFINITY)),
        Err(PopupError::NonFinite)
    );
    assert_eq!(
        p.add_popup(circle(f32::NEG_INFINITY, 5.0)),
        Err(PopupError::NonFinite)
    );
    assert_eq!(p.popups().count(), 0, "refused pop-ups are not added");
    // All four slots used: the fifth is refused, a removal frees one.
    let ids: Vec<u8> = (0..4)
        .map(|i| p.add_popup(circle(100.0 * i as f32, 10.0)).unwrap().id)
        .collect();
    assert_eq!(
        p.add_popup(circle(450.0, 10.0)),
        Err(PopupError::NoFreeSlot { capacity: 4 })
    );
    let unknown = (0..=u8::MAX).find(|id| !ids.contains(id)).unwrap();
    assert_eq!(
        p.remove_popup(unknown),
        Err(PopupError::UnknownId { id: unknown })
    );
    p.remove_popup(ids[1]).unwrap();
    assert_eq!(
        p.remove_popup(ids[1]),
        Err(PopupError::UnknownId { id: ids[1] })
    );
    p.add_popup(circle(450.0, 10.0)).unwrap();
}

#[test]
fn a_popup_over_the_start_is_left_by_an_exit_and_one_over_the_goal_keeps_the_route() {
    let w = world(8, 800.0, 60.0, 40.0, 3);
    let (mut p, q) = planned(&w.bytes, &w);
    let id = p
        .add_popup(Popup::Circle {
            centre: q.start.position + Vec2::new(5.0, 0.0),
            radius: 20.0,
        })
        .unwrap()
        .id;
    let summary = p.plan(&q, u64::MAX).expect("the exit leaves the pop-up");
    let exit = summary.exit.expect("the start lies in the pop-up");
    assert_eq!(exit.violated, skyroute::planner::Violation::Popup(id));
    assert_eq!(p.route_paths()[0].start, q.start);
    p.remove_popup(id).unwrap();
    let kept = p.route().to_vec();
    let over_goal = p
        .add_popup(Popup::Circle {
            centre: q.goal.position,
            radius: 20.0,
        })
        .unwrap()
        .id;
    assert_eq!(
        p.plan(&q, u64::MAX),
        Err(PlanError::InsidePopup {
            field: QueryField::Goal,
            popup: over_goal
        })
    );
    assert_eq!(p.route(), &kept[..]);
}
