//! A landmark pop-up's counted predicate tests. Each Hermite piece the pop-up's box reaches is
//! rebuilt and tested by [`POPUP_CHORDS_PER_PIECE`] chords: one circle test per chord for a
//! disc; for a polygon of n vertices, n edge tests and one containment test per chord. That is
//! the count `landmark_popup_work_bound` is built on, so each shape's tests must equal it
//! exactly: a count that is too low would let the bound pass work it never measured. Which
//! pieces the box reaches is bounded by the edge's length, not the piece's chord: a piece
//! that strays beyond its chord's box is still rebuilt.

use host_tests::scenarios;
use skyroute::planner::{Popup, POPUP_CHORDS_PER_PIECE};
use skyroute::{Planner, Vec2};

type Lp<'n> = Planner<'n, 256, 4096, 4, 256>;
/// A planner large enough for babel-III's network.
type LargeLp<'n> = Planner<'n, 1024, 48000, 4, 128>;

/// A regular polygon of `n` vertices of circumradius `r` around `c`.
fn regular_polygon(c: Vec2, r: f32, n: usize) -> Popup {
    let points = (0..n)
        .map(|k| {
            let a = k as f32 * core::f32::consts::TAU / n as f32;
            Vec2::new(c.x + r * a.cos(), c.y + r * a.sin())
        })
        .collect();
    Popup::Polygon(points)
}

#[test]
fn each_rebuilt_piece_costs_its_chords_times_the_shape_tests() {
    let built = scenarios::built("babel-I-bridged");
    let mut planner: Box<Lp> = Box::new(Planner::new());
    planner.load(&built.bytes).unwrap();
    let net = *planner.network();
    // The middle of the first piece of the first edge that has one: a pop-up there rebuilds
    // at least that piece.
    let e = (0..net.edge_count())
        .find(|&e| net.chain_piece_count(e) > 0)
        .expect("a chain edge");
    let piece = net.chain_piece(e, 0).unwrap();
    let c = piece.position(piece.t_max() * 0.5).unwrap();
    let chords = POPUP_CHORDS_PER_PIECE as u32;
    let shapes = [
        (
            Popup::Circle {
                centre: c,
                radius: 400.0,
            },
            1,
        ),
        (regular_polygon(c, 400.0, 3), 3 + 1),
        (regular_polygon(c, 400.0, 4), 4 + 1),
        (regular_polygon(c, 400.0, 7), 7 + 1),
    ];
    for (popup, tests_per_chord) in shapes {
        let s = planner.add_popup(popup.clone()).unwrap();
        assert!(s.pieces_rebuilt > 0, "{popup:?} rebuilt no piece");
        assert!(s.edges_blocked > 0, "{popup:?} on edge {e} blocked nothing");
        assert_eq!(
            s.predicate_tests,
            s.pieces_rebuilt * chords * tests_per_chord,
            "{popup:?}: {} pieces rebuilt",
            s.pieces_rebuilt
        );
        planner.remove_popup(s.id).unwrap();
    }
}

/// A piece's reach is bounded by its edge's length less the other pieces' chords, not by its
/// own chord: on babel-III, where a piece strays farthest (per axis) beyond the box of half its
/// chord around the chord's midpoint, a disc placed beyond that point along the same axis,
/// its edge within the clearance of the point but its box widened by the clearance clear of
/// the chord's box, blocks the piece's edge.
#[test]
fn a_disc_near_where_a_piece_strays_beyond_its_chord_box_blocks_its_edge() {
    let built = scenarios::built("babel-III");
    let mut planner: Box<LargeLp> = Box::new(Planner::new());
    planner.load(&built.bytes).unwrap();
    let net = *planner.network();
    // The farthest stray: (edge, point, its offset from the chord's midpoint, the stray).
    let mut farthest: Option<(u32, Vec2, Vec2, f32)> = None;
    for e in 0..net.edge_count() {
        for k in 0..net.chain_piece_count(e) {
            let piece = net.chain_piece(e, k).unwrap();
            let t_max = piece.t_max();
            let (a, b) = (piece.position(0.0).unwrap(), piece.position(t_max).unwrap());
            let mid = (a + b) * 0.5;
            // The chord's box as it would be bounded from the chord alone, with the reach's
            // rounding allowance doubled.
            let half = 0.5 * a.distance(b) * (1.0 + 2e-4) + 0.02;
            for i in 0..=200 {
                let p = piece.position(t_max * i as f32 / 200.0).unwrap();
                let d = p - mid;
                let stray = d.x.abs().max(d.y.abs()) - half;
                if farthest.is_none_or(|(.., s)| stray > s) {
                    farthest = Some((e, p, d, stray));
                }
            }
        }
    }
    let (e, p, d, stray) = farthest.expect("chain pieces");
    let clearance = net.clearance();
    assert!(
        stray > 2.0 && stray < clearance,
        "the farthest stray beyond a chord box: {stray} m"
    );
    // The disc's edge `gap` beyond the point: within the clearance of it, yet its box widened
    // by the clearance ends `stray / 2` short of the chord's box.
    let (radius, gap) = (1.0f32, clearance - 0.5 * stray);
    let axis = if d.x.abs() >= d.y.abs() {
        Vec2::new(d.x.signum(), 0.0)
    } else {
        Vec2::new(0.0, d.y.signum())
    };
    let centre = p + axis * (gap + radius);
    assert!(planner.is_edge_usable(e));
    planner.add_popup(Popup::Circle { centre, radius }).unwrap();
    assert!(
        !planner.is_edge_usable(e),
        "a disc {gap} m from edge {e} at {p:?} (clearance {clearance} m) left it usable"
    );
}
