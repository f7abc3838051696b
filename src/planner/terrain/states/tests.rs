//! Terrain search states: the layout, the turn rules' shares, the offset table and capacity,
//! the decoding of every state, the seeding and one expansion, each against values worked out
//! from the layout in the module doc and the closed form of a 1-trajectory's turn: cut
//! `r·tan(θ/2)`, step `(ℓᵢ − kᵢ) + kₒ + r·θ − 2c`.

extern crate std;
use super::super::tests::{at, network, Small, COLS, EDGES, FREE, NODES, ROWS};
use super::*;
use crate::geometry::{Pose, Turn};
use crate::planner::heap::ItemState;
use crate::planner::{Link, PlannerConfig};
use std::vec;
use std::vec::Vec;

const R: f32 = 30.0;

fn node(v: u32) -> Vec2 {
    let (x, y) = NODES[v as usize];
    at(x, y)
}

fn out_degree(v: u32) -> u32 {
    EDGES.iter().filter(|&&(a, _)| a == v).count() as u32
}

/// The cut of the turn between unit directions `a` and `b`, in f64: `r·tan(θ/2)`.
fn cut(a: Vec2, b: Vec2) -> f64 {
    let theta = (a.dot(b) as f64).clamp(-1.0, 1.0).acos();
    R as f64 * (theta / 2.0).tan()
}

/// The length change of that turn's 1-trajectory: `r·θ − 2c`.
fn saving(a: Vec2, b: Vec2) -> f64 {
    let theta = (a.dot(b) as f64).clamp(-1.0, 1.0).acos();
    R as f64 * theta - 2.0 * cut(a, b)
}

fn unit(from: Vec2, to: Vec2) -> Vec2 {
    (to - from) * (1.0 / from.distance(to))
}

/// A start link from `at(20, 150)` heading east to node `v`, turning left.
fn start_link(v: u32) -> Link {
    let start = at(20.0, 150.0);
    let path =
        DubinsPath::turn_then_straight(&Pose::new(start.x, start.y, 0.0), R, node(v), Turn::Left)
            .expect("a link");
    Link {
        vertex: v,
        path,
        cost: path.length(),
        pending: false,
    }
}

/// A planner over the free network with `rule` and start links to `links`.
fn with_links<'n>(image: &'n [u8], rule: TurnRule, links: &[u32]) -> Small<'n> {
    let mut planner = Small::new();
    planner.load(image).unwrap();
    planner.set_config(PlannerConfig {
        turn_rule: rule,
        ..PlannerConfig::DEFAULT
    });
    for &v in links {
        planner.start_links.push(start_link(v)).unwrap();
    }
    planner
}

fn free_network() -> Vec<u8> {
    network(vec![FREE; (COLS * ROWS) as usize], R)
}

/// With 4 edges and 2 start links: the equal split numbers the links 4 and 5; the paper's rule
/// keeps 0..=6 for the offset table, numbers the links 7 and 8, and the pairs from 9.
#[test]
fn the_layout_numbers_the_edges_the_links_and_the_pairs() {
    let image = free_network();
    let equal = with_links(&image, TurnRule::SharedEqually, &[0, 1]).terrain_layout();
    assert_eq!(equal.straights(), 6);
    assert_eq!((equal.link_state(0), equal.link_state(1)), (4, 5));
    let paper = with_links(&image, TurnRule::Paper, &[0, 1]).terrain_layout();
    assert_eq!(paper.straights(), 6);
    assert_eq!((paper.link_state(0), paper.link_state(1)), (7, 8));
    assert_eq!(paper.pair_base(), 9);
    for (layout, first) in [(equal, 4), (paper, 7)] {
        for s in 0..20 {
            let expected = (first..first + 2).contains(&s).then(|| s - first);
            assert_eq!(layout.link_of(s), expected, "state {s}");
        }
    }
}

/// The equal split gives a turn half of the next straight, up to half; the paper's rule its
/// cut, up to the whole. A goal link's straight leaves half or all of itself.
#[test]
fn each_rule_shares_a_straight_up_to_its_bound() {
    let l = 40.0;
    assert_eq!(
        TurnRule::SharedEqually.start_share(20.0, l),
        Some((20.0, 40.0))
    );
    assert_eq!(
        TurnRule::SharedEqually.start_share(7.0, l),
        Some((20.0, 40.0))
    );
    assert_eq!(TurnRule::SharedEqually.start_share(20.001, l), None);
    assert_eq!(TurnRule::Paper.start_share(7.0, l), Some((7.0, 7.0)));
    assert_eq!(TurnRule::Paper.start_share(40.0, l), Some((40.0, 40.0)));
    assert_eq!(TurnRule::Paper.start_share(40.001, l), None);
    assert_eq!(TurnRule::SharedEqually.goal_room(l), 20.0);
    assert_eq!(TurnRule::Paper.goal_room(l), 40.0);
}

/// A goal link leaves its node along its own start heading, except a free-heading goal on the
/// node (no arcs, a straight of at most [`ON_NODE_M`]), which leaves along the arrival.
#[test]
fn a_goal_link_leaves_along_its_heading_unless_it_is_on_the_node() {
    let arrival = Vec2::new(0.6, 0.8);
    let at_node = Arrived {
        straight: 0,
        node: 1,
        position: node(1),
        direction: arrival,
        length: 180.0,
        start_share: 0.0,
        key_point: 0.0,
        from: Some(0),
    };
    let link = |lengths: [f32; 3]| DubinsPath {
        start: Pose::new(node(1).x, node(1).y, 0.0),
        radius: R,
        word: crate::geometry::DubinsWord::Lsl,
        lengths,
    };
    let east = Vec2::new(1.0, 0.0);
    assert_eq!(goal_direction(&at_node, &link([0.0, 0.0, 0.0])), arrival);
    assert_eq!(
        goal_direction(&at_node, &link([0.0, ON_NODE_M, 0.0])),
        arrival
    );
    assert_eq!(goal_direction(&at_node, &link([0.0, 0.0011, 0.0])), east);
    assert_eq!(goal_direction(&at_node, &link([0.5, 0.0, 0.0])), east);
    assert_eq!(goal_direction(&at_node, &link([0.0, 0.0, 0.5])), east);
    assert_eq!(goal_direction(&at_node, &link([0.0, 30.0, 0.0])), east);
}

/// The room a turn at the end has is `ℓ − s` (at least [`ON_NODE_M`] on a start link); what the
/// key leaves out is `ℓ − k`.
#[test]
fn an_arrival_leaves_its_length_less_its_share_to_the_next_turn() {
    let mut arrived = Arrived {
        straight: 0,
        node: 1,
        position: node(1),
        direction: Vec2::new(1.0, 0.0),
        length: 50.0,
        start_share: 12.0,
        key_point: 5.0,
        from: Some(0),
    };
    assert_eq!(arrived.room(), 38.0);
    assert_eq!(arrived.uncounted(), 45.0);
    arrived.from = None;
    assert_eq!(arrived.room(), 38.0);
    arrived.length = 0.0;
    arrived.start_share = 0.0;
    assert_eq!(arrived.room(), ON_NODE_M);
    arrived.from = Some(0);
    assert_eq!(arrived.room(), 0.0);
}

/// The end node of straight `p`: an edge's target, then the links' vertices.
fn straight_end(p: usize, links: &[u32]) -> u32 {
    match EDGES.get(p) {
        Some(&(_, b)) => b,
        None => links[p - EDGES.len()],
    }
}

/// The paper's rule's offset table, `O[p] = Σ_{q<p} outdeg(end of straight q)`, for
/// `p = 0..=|E| + Ks`.
fn offsets(links: &[u32]) -> Vec<u32> {
    let mut table = vec![0];
    for p in 0..EDGES.len() + links.len() {
        table.push(table[p] + out_degree(straight_end(p, links)));
    }
    table
}

/// The paper's rule writes the offset table into `via` (one vertex scan per entry) and needs
/// `|E| + 2·Ks + 1 + O[|E| + Ks]` states; the equal split `|E| + Ks`, without scans.
#[test]
fn the_state_count_and_the_offset_table_follow_the_out_degrees() {
    let image = free_network();
    let links = [0, 1];
    let mut paper = with_links(&image, TurnRule::Paper, &links);
    let mut meter = Meter::new(u64::MAX);
    let table = offsets(&links);
    assert_eq!(table, [0, 2, 3, 4, 6, 7, 9], "worked by hand");
    assert_eq!(paper.prepare_edge_states(&mut meter), Ok(4 + 4 + 1 + 9));
    assert_eq!(&paper.via[..table.len()], table.as_slice());
    assert_eq!(meter.work.vertex_scans, 7);
    assert_eq!(meter.work.total(), 7);
    let mut equal = with_links(&image, TurnRule::SharedEqually, &links);
    let mut meter = Meter::new(u64::MAX);
    assert_eq!(equal.prepare_edge_states(&mut meter), Ok(6));
    assert_eq!(meter.work.total(), 0);
}

/// With room for 32 states: seven start links at n0 (out-degree 1) need
/// 4 + 14 + 1 + (6 + 7) = 32 and fit; eight need 35 and are refused with both numbers.
#[test]
fn the_paper_rules_states_fit_exactly_or_are_refused_with_the_count() {
    let image = free_network();
    for (links, expected) in [
        (7, Ok(32)),
        (
            8,
            Err(PlanError::TooManySearchStates {
                needed: 35,
                capacity: 32,
            }),
        ),
    ] {
        let mut planner: Planner<'_, 32, 256, 4, 64> = Planner::new();
        planner.load(&image).unwrap();
        planner.set_config(PlannerConfig::DEFAULT);
        for _ in 0..links {
            planner.start_links.push(start_link(0)).unwrap();
        }
        let mut meter = Meter::new(u64::MAX);
        assert_eq!(
            planner.prepare_edge_states(&mut meter),
            expected,
            "{links} links"
        );
    }
}

/// The direction of straight `p`: an edge's, or the end heading of a start link.
fn direction_of(p: usize, planner: &Small) -> Vec2 {
    match EDGES.get(p) {
        Some(&(a, b)) => unit(node(a), node(b)),
        None => Vec2::from_angle(planner.start_links[p - EDGES.len()].path.end().heading),
    }
}

/// `(node, direction, length, start share, key point, from)` of straight `p` arrived along
/// with the share `share` and key `key`.
fn expected_arrival(p: usize, planner: &Small, links: &[u32], share: f64, key: f64) -> Arrived {
    let (length, from) = match EDGES.get(p) {
        Some(&(a, b)) => (node(a).distance(node(b)), Some(a)),
        None => (planner.start_links[p - EDGES.len()].path.lengths[1], None),
    };
    let end = straight_end(p, links);
    Arrived {
        straight: p as u32,
        node: end,
        position: node(end),
        direction: direction_of(p, planner),
        length,
        start_share: share as f32,
        key_point: key as f32,
        from,
    }
}

fn assert_arrival(found: &Arrived, expected: &Arrived, what: &str) {
    assert_eq!(
        (found.straight, found.node, found.from),
        (expected.straight, expected.node, expected.from),
        "{what}"
    );
    assert!(found.position.distance(expected.position) < 1e-3, "{what}");
    assert!(
        found.direction.distance(expected.direction) < 1e-5,
        "{what}"
    );
    assert!((found.length - expected.length).abs() < 1e-3, "{what}");
    for (f, e) in [
        (found.start_share, expected.start_share),
        (found.key_point, expected.key_point),
    ] {
        // A reversal's cut is infinite (r·tan(θ/2) in f64 is about 10¹⁷ there); a near one's
        // is large, and rounds relatively.
        let same = if e > 1e6 {
            f.is_infinite()
        } else {
            (f - e).abs() < 1e-3 + 2e-5 * e
        };
        assert!(same, "{what}: {found:?}, expected {expected:?}");
    }
}

/// Every state decodes to its straight: under the equal split edge `e` with share `ℓ/2` and
/// key `ℓ`, a start link with share 0 and key `ℓ`; under the paper's rule a start link with
/// share and key 0, and the pair (straight `p`, `j`-th out-edge of its end), state
/// `pair base + O[p] + j`, as that edge with share and key the cut of the turn from `p` into
/// it. A pair state's decoding reads the table by binary search (⌊log₂ 6⌋ to ⌈log₂ 6⌉ reads);
/// a state in the table's range is no state.
#[test]
fn every_state_decodes_to_its_straight_and_share() {
    let image = free_network();
    let links = [0, 1];
    let mut equal = with_links(&image, TurnRule::SharedEqually, &links);
    let states = equal
        .prepare_edge_states(&mut Meter::new(u64::MAX))
        .unwrap();
    for s in 0..states {
        let p = s;
        let length = expected_arrival(p, &equal, &links, 0.0, 0.0).length as f64;
        let share = if p < EDGES.len() { 0.5 * length } else { 0.0 };
        let expected = expected_arrival(p, &equal, &links, share, length);
        let mut reads = 0;
        let found = equal.arrived(s as u32, &mut reads).unwrap();
        assert_arrival(&found, &expected, &std::format!("equal split, state {s}"));
        assert_eq!(reads, 0);
    }

    let mut paper = with_links(&image, TurnRule::Paper, &links);
    let states = paper
        .prepare_edge_states(&mut Meter::new(u64::MAX))
        .unwrap();
    let table = offsets(&links);
    let mut decoded = 0;
    for s in 0..7u32 {
        let refused = paper.arrived(s, &mut 0);
        assert!(
            matches!(refused, Err(PlanError::Internal)),
            "state {s}: {refused:?}"
        );
    }
    for k in 0..links.len() {
        let s = 7 + k as u32;
        let expected = expected_arrival(EDGES.len() + k, &paper, &links, 0.0, 0.0);
        let mut reads = 0;
        let found = paper.arrived(s, &mut reads).unwrap();
        assert_arrival(&found, &expected, &std::format!("paper's rule, link {k}"));
        assert_eq!(reads, 0);
        decoded += 1;
    }
    for (p, &first) in table.iter().enumerate().take(EDGES.len() + links.len()) {
        let end = straight_end(p, &links);
        let outs: Vec<usize> = (0..EDGES.len()).filter(|&e| EDGES[e].0 == end).collect();
        for (j, &e) in outs.iter().enumerate() {
            let s = 9 + first + j as u32;
            let c = cut(direction_of(p, &paper), direction_of(e, &paper));
            let expected = expected_arrival(e, &paper, &links, c, c);
            let mut reads = 0;
            let found = paper.arrived(s, &mut reads).unwrap();
            assert_arrival(
                &found,
                &expected,
                &std::format!("pair ({p}, {e}), state {s}"),
            );
            assert!((2..=3).contains(&reads), "{reads} reads");
            decoded += 1;
        }
    }
    assert_eq!(decoded, states - 7);
}

/// The start links are queued at their keys (the link's length under the equal split, its
/// arcs under the paper's rule) with no previous state; the second key is the larger, so each
/// push sifts no level and counts 1.
#[test]
fn the_start_links_are_seeded_at_their_keys() {
    let image = free_network();
    let links = [0, 1];
    for rule in [TurnRule::SharedEqually, TurnRule::Paper] {
        let mut planner = with_links(&image, rule, &links);
        let states = planner
            .prepare_edge_states(&mut Meter::new(u64::MAX))
            .unwrap();
        planner.heap.clear(states);
        let mut meter = Meter::new(u64::MAX);
        planner.seed_edge_states(&mut meter).unwrap();
        let first = match rule {
            TurnRule::SharedEqually => 4,
            TurnRule::Paper => 7,
        };
        let mut keys = Vec::new();
        for k in 0..links.len() {
            let path = planner.start_links[k].path;
            let key = match rule {
                TurnRule::SharedEqually => path.length(),
                TurnRule::Paper => path.lengths[0] + path.lengths[2],
            };
            let s = first + k;
            assert_eq!(planner.dist[s], key, "{rule:?} link {k}");
            assert_eq!(planner.via[s], NO_PREVIOUS);
            assert_eq!(planner.heap.state(s as u32), ItemState::Queued);
            keys.push(key);
        }
        assert!(keys[1] >= keys[0]);
        assert_eq!(meter.work.heap_steps, 2, "{rule:?}");
        for s in (0..states).filter(|s| !(first..first + 2).contains(s)) {
            assert_eq!(
                planner.heap.state(s as u32),
                ItemState::Unseen,
                "{rule:?} state {s}"
            );
        }
    }
}

/// A straight goal link from n2 heading east, `length` metres.
fn goal_link(length: f32) -> Link {
    let path = DubinsPath {
        start: Pose::new(node(2).x, node(2).y, 0.0),
        radius: R,
        word: crate::geometry::DubinsWord::Lsl,
        lengths: [0.0, length, 0.0],
    };
    Link {
        vertex: 2,
        path,
        cost: length,
        pending: false,
    }
}

/// A search begun by hand: one start link to n0 (30 m east), goal links of 20 and 17 m east
/// from n2, the states prepared and the link seeded.
fn begun<'n>(image: &'n [u8], rule: TurnRule) -> Small<'n> {
    let mut planner = with_links(image, rule, &[0]);
    planner.goal_links.push(goal_link(20.0)).unwrap();
    planner.goal_links.push(goal_link(17.0)).unwrap();
    let states = planner
        .prepare_edge_states(&mut Meter::new(u64::MAX))
        .unwrap();
    planner.heap.clear(states);
    planner.seed_edge_states(&mut Meter::new(u64::MAX)).unwrap();
    planner
}

/// Expanding state `s` at its key; returns the best goal arrival offered and the work.
fn expand(planner: &mut Small, s: u32) -> (Option<(f32, Arrival)>, crate::planner::Work) {
    let mut best = None;
    let mut meter = Meter::new(u64::MAX);
    let ds = planner.dist[s as usize];
    assert_eq!(
        planner.expand_edge_state(s, ds, &mut best, &mut meter),
        Ok(false)
    );
    (best, meter.work)
}

/// One route n0 → n1 → n2 → goal expanded state by state, under each rule: each transition
/// is queued at `ds + (ℓᵢ − kᵢ) + kₒ + r·θ − 2c` with its predecessor, in the state the layout
/// gives it (the equal split: the edge; the paper's rule: `9 − 2 + O[p] + slot`); the reversal
/// at n1 queues nothing; at n2 the goal links whose straight leaves the turn room (the equal
/// split: half of it; the paper's rule: all of it) are offered at the same step plus their
/// length, the cheaper kept (the 17 m link, offered second, replaces the 20 m one). Each
/// expansion counts one relaxation per goal link and out-edge, one vertex scan and its
/// decoding's reads, and one heap step for the push behind the link's state.
#[test]
fn an_expansion_queues_each_fitting_turn_at_its_step_cost() {
    let image = free_network();
    let (n0, n1, n2) = (node(0), node(1), node(2));
    let (east, d01, d12) = (Vec2::new(1.0, 0.0), unit(n0, n1), unit(n1, n2));
    let (l01, l12) = (n0.distance(n1) as f64, n1.distance(n2) as f64);
    for rule in [TurnRule::SharedEqually, TurnRule::Paper] {
        let mut planner = begun(&image, rule);
        let link = planner.start_links[0].path;
        let l_link = link.lengths[1] as f64;
        // (link state, e0's state from the link, e2's after e0, e1's after e0 (a reversal)).
        let (s_link, s01, s12, s10) = match rule {
            TurnRule::SharedEqually => (4u32, 0u32, 2u32, 1u32),
            // Table O = [0, 2, 3, 4, 6, 7]; pair base 4 + 1 + 1 + 1 = 7.
            TurnRule::Paper => (6, 7 + 6, 7 + 1, 7),
        };
        // (ℓ − k) of an arrival along a straight of length `l` with key point `k`, and kₒ of
        // a next straight of length `l` entered with cut `c`.
        let (uncounted_link, key): (f64, fn(f64, f64) -> f64) = match rule {
            TurnRule::SharedEqually => (0.0, |l, _c| l),
            TurnRule::Paper => (l_link, |_l, c| c),
        };
        let ds = planner.dist[s_link as usize] as f64;
        let (best, work) = expand(&mut planner, s_link);
        assert!(best.is_none());
        assert_eq!((work.relaxations, work.vertex_scans), (3, 1), "{rule:?}");
        assert_eq!(work.heap_steps, 1, "one push, behind the link's state");
        let c0 = cut(east, d01);
        let expected01 = ds + uncounted_link + key(l01, c0) + saving(east, d01);
        assert!(
            (planner.dist[s01 as usize] as f64 - expected01).abs() < 1e-3,
            "{rule:?}"
        );
        assert_eq!(planner.via[s01 as usize], s_link);
        assert_eq!(planner.heap.state(s01), ItemState::Queued);
        assert_eq!(planner.arc_check_stats().arcs, 1);

        let ds = planner.dist[s01 as usize] as f64;
        let (best, work) = expand(&mut planner, s01);
        assert!(best.is_none());
        let reads = work.vertex_scans - 1;
        assert_eq!(work.relaxations, 2 + 2, "{rule:?}");
        assert!(match rule {
            TurnRule::SharedEqually => reads == 0,
            TurnRule::Paper => (2..=3).contains(&reads),
        });
        let uncounted01 = l01 - key(l01, c0);
        let c1 = cut(d01, d12);
        assert!((c1 - 20.0).abs() < 1e-3, "tan(atan(2/3)) r = 20 m: {c1}");
        let expected12 = ds + uncounted01 + key(l12, c1) + saving(d01, d12);
        assert!(
            (planner.dist[s12 as usize] as f64 - expected12).abs() < 1e-3,
            "{rule:?}"
        );
        assert_eq!(planner.via[s12 as usize], s01);
        assert_eq!(planner.heap.state(s10), ItemState::Unseen, "no reversal");

        let ds = planner.dist[s12 as usize] as f64;
        let (best, _) = expand(&mut planner, s12);
        let c2 = cut(d12, east);
        assert!(
            c2 > 8.5 && c2 < 10.0,
            "{c2}: more than half of 17 m, less than half of 20 m"
        );
        let (total, arrival) = best.expect("a goal link fits");
        let (link, length) = match rule {
            TurnRule::SharedEqually => (0, 20.0),
            TurnRule::Paper => (1, 17.0),
        };
        let expected = ds + (l12 - key(l12, c1)) + length + saving(d12, east);
        assert!(
            (total as f64 - expected).abs() < 1e-3,
            "{rule:?}: {total}, expected {expected}"
        );
        assert!(
            matches!(arrival, Arrival::FromState { state, link: k } if state == s12 && k == link)
        );
    }
}

/// A transition is relaxed only when it improves its state: a dearer arrival leaves it, a
/// cheaper one lowers it (and re-checks the turn), a done state is never touched; a turn that
/// cuts more than the arrival's straight leaves (a start link of 5 m into a turn of 9 m) is
/// not taken.
#[test]
fn a_transition_is_relaxed_only_when_it_improves_and_fits() {
    let image = free_network();
    let mut planner = begun(&image, TurnRule::SharedEqually);
    let (s_link, s01) = (4u32, 0u32);
    let mut best = None;
    let key = planner.dist[s_link as usize];
    let mut meter = Meter::new(u64::MAX);
    planner
        .expand_edge_state(s_link, key, &mut best, &mut meter)
        .unwrap();
    let first = planner.dist[s01 as usize];
    planner
        .expand_edge_state(s_link, key + 5.0, &mut best, &mut meter)
        .unwrap();
    assert_eq!(planner.dist[s01 as usize], first, "a dearer arrival");
    assert_eq!(planner.arc_check_stats().arcs, 1, "its turn is not checked");
    planner
        .expand_edge_state(s_link, key, &mut best, &mut meter)
        .unwrap();
    assert_eq!(
        planner.arc_check_stats().arcs,
        1,
        "nor that of an equal one"
    );
    planner
        .expand_edge_state(s_link, key - 5.0, &mut best, &mut meter)
        .unwrap();
    assert!(
        (planner.dist[s01 as usize] - (first - 5.0)).abs() < 1e-3,
        "a cheaper one"
    );
    assert_eq!(planner.arc_check_stats().arcs, 2);
    let popped = [planner.heap.pop().unwrap().0, planner.heap.pop().unwrap().0];
    assert_eq!(popped, [s_link, s01], "in key order");
    planner
        .expand_edge_state(s_link, key - 10.0, &mut best, &mut meter)
        .unwrap();
    assert!(
        (planner.dist[s01 as usize] - (first - 5.0)).abs() < 1e-3,
        "done"
    );

    let mut short = Small::new();
    short.load(&image).unwrap();
    short.set_config(PlannerConfig {
        turn_rule: TurnRule::SharedEqually,
        ..PlannerConfig::DEFAULT
    });
    let start = at(45.0, 150.0);
    let path =
        DubinsPath::turn_then_straight(&Pose::new(start.x, start.y, 0.0), R, node(0), Turn::Left)
            .unwrap();
    assert!(
        (path.lengths[1] - 5.0).abs() < 1e-3
            && cut(Vec2::new(1.0, 0.0), unit(node(0), node(1))) > 9.0
    );
    short
        .start_links
        .push(Link {
            vertex: 0,
            path,
            cost: 5.0,
            pending: false,
        })
        .unwrap();
    let states = short
        .prepare_edge_states(&mut Meter::new(u64::MAX))
        .unwrap();
    short.heap.clear(states);
    short.seed_edge_states(&mut Meter::new(u64::MAX)).unwrap();
    // A goal link leaving n0 northward: a quarter turn of cut 30 m, more than the 5 m the
    // link leaves, though its straight (100 m) would hold it.
    let north = DubinsPath {
        start: Pose::new(node(0).x, node(0).y, 0.5 * core::f32::consts::PI),
        radius: R,
        word: crate::geometry::DubinsWord::Lsl,
        lengths: [0.0, 100.0, 0.0],
    };
    short
        .goal_links
        .push(Link {
            vertex: 0,
            path: north,
            cost: 100.0,
            pending: false,
        })
        .unwrap();
    let (best, _) = expand(&mut short, 4);
    assert_eq!(
        short.heap.state(0),
        ItemState::Unseen,
        "the turn does not fit"
    );
    assert!(best.is_none(), "nor does the goal link's turn: {best:?}");
}
