//! A landmark pop-up's counted predicate tests. Each Hermite piece the pop-up's box reaches is
//! rebuilt and tested by [`POPUP_CHORDS_PER_PIECE`] chords: one circle test per chord for a
//! disc; for a polygon of n vertices, n edge tests and one containment test per chord. That is
//! the count `landmark_popup_work_bound` is built on, so each shape's tests must equal it
//! exactly: a count that is too low would let the bound pass work it never measured.

use host_tests::scenarios;
use skyroute::planner::{Popup, POPUP_CHORDS_PER_PIECE};
use skyroute::{Planner, Vec2};

type Lp<'n> = Planner<'n, 256, 4096, 4, 256>;

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
