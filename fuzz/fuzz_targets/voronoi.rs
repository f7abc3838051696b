//! The onboard Voronoi diagram on arbitrary sites (many on a small lattice, so collinear,
//! cocircular and duplicate sites are common, and raw floats): insertions and rebuilds never
//! panic, refused sites leave the diagram as it was, the counted work stays within
//! `delaunay_work_bound`, and the clipped graph fits its documented bounds (its size and its
//! counted work, `graph_work_bound`) with every vertex inside the box.
#![no_main]

use arbitrary::Arbitrary;
use libfuzzer_sys::fuzz_target;
use skyroute::geometry::voronoi::{
    delaunay_work_bound, graph_edge_bound, graph_vertex_bound, graph_work_bound, Bounds, Delaunay,
    VoronoiGraph,
};
use skyroute::Vec2;

const N: usize = 32;

#[derive(Arbitrary, Debug, Clone, Copy)]
enum Site {
    Lattice(u8, u8),
    Raw(f32, f32),
}

#[derive(Arbitrary, Debug)]
struct Input {
    sites: Vec<Site>,
    rebuild_at: Option<u8>,
    box_half: u16,
}

fuzz_target!(|input: Input| {
    let mut d: Box<Delaunay<N, { 2 * N }>> = Box::new(Delaunay::new());
    let mut inserted: Vec<Vec2> = Vec::new();
    let mut calls = 0u64;
    for (i, s) in input.sites.iter().take(64).enumerate() {
        let p = match *s {
            Site::Lattice(a, b) => Vec2::new((a % 16) as f32 * 100.0, (b % 16) as f32 * 100.0),
            Site::Raw(x, y) => Vec2::new(x, y),
        };
        calls += 1;
        let before = d.site_count();
        if d.insert(p).is_ok() {
            inserted.push(p);
        } else {
            assert_eq!(d.site_count(), before, "a refused site changed the diagram");
        }
        assert!(
            d.work() <= delaunay_work_bound(calls),
            "work over its bound"
        );
        if input.rebuild_at == Some(i as u8) {
            d.rebuild(&inserted)
                .expect("sites accepted before are accepted again");
            calls = inserted.len() as u64;
        }
    }
    let h = 100.0 + input.box_half as f32;
    let bounds = Bounds {
        min: Vec2::new(750.0 - h, 750.0 - h),
        max: Vec2::new(750.0 + h, 750.0 + h),
    };
    let mut g: Box<VoronoiGraph<{ graph_vertex_bound(N) }, { graph_edge_bound(N) }>> =
        Box::new(VoronoiGraph::new());
    if d.graph(&bounds, &mut g).is_ok() {
        let n = d.site_count();
        assert!(g.vertices().len() <= graph_vertex_bound(n));
        assert!(g.edges().len() <= graph_edge_bound(n));
        assert!(g.work() <= graph_work_bound(n), "graph work over its bound");
        let slack = 1e-3 * (h + 750.0);
        for v in g.vertices() {
            assert!(
                v.x >= bounds.min.x - slack
                    && v.x <= bounds.max.x + slack
                    && v.y >= bounds.min.y - slack
                    && v.y <= bounds.max.y + slack,
                "graph vertex {v:?} outside the box"
            );
        }
    }
});
