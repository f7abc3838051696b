//! A no-fly zone with holes as simple polygons, the only obstacle the core knows.
//!
//! The zone is the exterior ring's region less its holes. It is cut, hole by hole, by a strip
//! across the hole: the pieces left and right of the strip each overlap it, so the hole opens
//! into a notch of both and the pieces' union is the zone again. Because the two pieces overlap
//! (rather than meet along the cut), every interior point of the zone is an interior point of
//! some piece: a path may not slip between two pieces along a shared edge.
//!
//! The strip is chosen so that it holds no other hole whole (see [`strip_across`]), so every
//! other hole ends up a hole of at most one piece, or opened. Every piece a cut makes has fewer
//! holes than the polygon cut, which is what ends the loop; a piece that comes back from the
//! clipping with as many holes (a hole so thin that the clipping's grid closes the strip) keeps
//! its exterior only. So does a hole less than [`MIN_HOLE_WIDTH_M`] wide, which the `f32`
//! coordinates the core is given could not keep open with an overlap. Filling a hole only
//! forbids more: every fallback is on the safe side. For a convex exterior each hole adds about
//! one piece; a ragged exterior can fall into more pieces at each cut.

use geo::{BooleanOps, Coord, LineString, Polygon, Rect};

/// A planar point, metres (the local frame).
pub type Point = (f64, f64);

/// The narrowest hole kept open, metres across (its widest gap between vertex abscissae): the
/// overlap of two pieces is half of it, and must stay wider than the `f32` spacing of the core's
/// coordinates (under 8 mm within its ±64 km range).
pub const MIN_HOLE_WIDTH_M: f64 = 0.05;

/// The simple polygons whose union is the region inside `exterior` and outside every one of
/// `holes` (rings without a closing repeat; the holes lie strictly inside the exterior and
/// apart from each other, as the scenario parser checks). Without holes the exterior is
/// returned as it is.
pub fn simple_pieces(exterior: &[Point], holes: &[Vec<Point>]) -> Vec<Vec<Point>> {
    if holes.is_empty() {
        return vec![exterior.to_vec()];
    }
    let mut queue = vec![Polygon::new(
        ring_of(exterior),
        holes.iter().map(|h| ring_of(h)).collect(),
    )];
    let mut out = Vec::new();
    while let Some(p) = queue.pop() {
        let Some(hole) = p.interiors().first() else {
            let piece = open_ring(p.exterior());
            if piece.len() >= 3 {
                out.push(piece);
            }
            continue;
        };
        let holes = p.interiors().len();
        let Some((c, eps)) = strip_across(hole, &p.interiors()[1..]) else {
            // Too thin to keep open: the hole is filled.
            let others = p.interiors()[1..].to_vec();
            queue.push(Polygon::new(p.exterior().clone(), others));
            continue;
        };
        let (lo, hi) = y_span(p.exterior());
        let x_span = x_range(p.exterior());
        let left = Rect::new(
            Coord {
                x: x_span.0 - 1.0,
                y: lo - 1.0,
            },
            Coord {
                x: c + eps,
                y: hi + 1.0,
            },
        )
        .to_polygon();
        let right = Rect::new(
            Coord {
                x: c - eps,
                y: lo - 1.0,
            },
            Coord {
                x: x_span.1 + 1.0,
                y: hi + 1.0,
            },
        )
        .to_polygon();
        for piece in p
            .intersection(&left)
            .into_iter()
            .chain(p.intersection(&right))
        {
            if piece.interiors().len() < holes {
                queue.push(piece);
            } else {
                queue.push(Polygon::new(piece.exterior().clone(), vec![]));
            }
        }
    }
    out
}

/// The vertical strip `[c − ε, c + ε]` that cuts across `hole`: `c` is the middle of the widest
/// gap between the hole's consecutive vertex abscissae, so every line of the strip crosses the
/// hole's interior (a vertical line strictly inside a simple ring's x-range meets its interior,
/// and no vertex lies within the gap); ε is at most a quarter of that gap, and below half of
/// the largest distance from `c` of each other hole's vertices, so no other hole fits in the
/// strip whole. `None` for a hole narrower than [`MIN_HOLE_WIDTH_M`].
fn strip_across(hole: &LineString<f64>, others: &[LineString<f64>]) -> Option<(f64, f64)> {
    let mut xs: Vec<f64> = hole.coords().map(|c| c.x).collect();
    xs.sort_by(f64::total_cmp);
    xs.dedup();
    let (mut c, mut gap) = (*xs.first()?, 0.0);
    for w in xs.windows(2) {
        if w[1] - w[0] > gap {
            (c, gap) = (0.5 * (w[0] + w[1]), w[1] - w[0]);
        }
    }
    // `gap` is finite: the parser refuses non-finite coordinates.
    if gap < MIN_HOLE_WIDTH_M {
        return None;
    }
    let mut eps = 0.25 * gap;
    for o in others {
        let reach = o.coords().map(|p| (p.x - c).abs()).fold(0.0, f64::max);
        eps = eps.min(0.5 * reach);
    }
    Some((c, eps))
}

/// A closed geo ring of an open ring of points.
fn ring_of(points: &[Point]) -> LineString<f64> {
    LineString::from(points.to_vec())
}

/// The points of a closed geo ring without its closing repeat, consecutive repeats and
/// vertices exactly on the line through their neighbours (the clipping leaves both where a cut
/// crosses an edge's end).
fn open_ring(ring: &LineString<f64>) -> Vec<Point> {
    let mut pts: Vec<Point> = ring.coords().map(|c| (c.x, c.y)).collect();
    pts.dedup();
    while pts.len() > 1 && pts.first() == pts.last() {
        pts.pop();
    }
    let mut k = 0;
    while pts.len() > 3 && k < pts.len() {
        let n = pts.len();
        let (a, b, c) = (pts[(k + n - 1) % n], pts[k], pts[(k + 1) % n]);
        let cross = (b.0 - a.0) * (c.1 - a.1) - (b.1 - a.1) * (c.0 - a.0);
        if cross == 0.0 {
            pts.remove(k);
        } else {
            k += 1;
        }
    }
    pts
}

/// The least and greatest ordinate of a ring.
fn y_span(ring: &LineString<f64>) -> (f64, f64) {
    ring.coords()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), c| {
            (lo.min(c.y), hi.max(c.y))
        })
}

/// The least and greatest abscissa of a ring.
fn x_range(ring: &LineString<f64>) -> (f64, f64) {
    ring.coords()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), c| {
            (lo.min(c.x), hi.max(c.x))
        })
}

#[cfg(test)]
mod tests {
    use super::*;
    use geo::{Area, Contains, Coord, Distance, Euclidean, MultiPolygon};

    /// A square of side `s` centred on `(cx, cy)`.
    fn square(cx: f64, cy: f64, s: f64) -> Vec<Point> {
        let h = 0.5 * s;
        vec![
            (cx - h, cy - h),
            (cx + h, cy - h),
            (cx + h, cy + h),
            (cx - h, cy + h),
        ]
    }

    /// A star-shaped ring: `n` vertices around `(cx, cy)` at radii alternating `r` and `0.6 r`.
    fn star(cx: f64, cy: f64, r: f64, n: usize) -> Vec<Point> {
        (0..n)
            .map(|k| {
                let t = std::f64::consts::TAU * k as f64 / n as f64 + 0.1;
                let rr = if k % 2 == 0 { r } else { 0.6 * r };
                (cx + rr * t.cos(), cy + rr * t.sin())
            })
            .collect()
    }

    fn zone(exterior: &[Point], holes: &[Vec<Point>]) -> Polygon<f64> {
        Polygon::new(
            ring_of(exterior),
            holes.iter().map(|h| ring_of(h)).collect(),
        )
    }

    fn polygon(piece: &[Point]) -> Polygon<f64> {
        Polygon::new(ring_of(piece), vec![])
    }

    /// The checks every decomposition must pass, against geo's own predicates on the zone with
    /// its holes: each piece is simple and lies in the zone, the union has the zone's area, a
    /// grid of points is in some piece exactly when it is in the zone, and every piece edge's
    /// midpoint that is interior to the zone is interior to another piece (no internal seam).
    fn check(exterior: &[Point], holes: &[Vec<Point>]) -> usize {
        let z = zone(exterior, holes);
        let pieces = simple_pieces(exterior, holes);
        let polys: Vec<Polygon<f64>> = pieces.iter().map(|p| polygon(p)).collect();
        for (i, p) in polys.iter().enumerate() {
            assert!(p.interiors().is_empty());
            let n = pieces[i].len();
            let ring: Vec<(f64, f64)> = pieces[i].clone();
            // Simple: no two non-adjacent edges meet (brute force over the small rings here).
            for a in 0..n {
                for b in a + 2..n {
                    if a == 0 && b == n - 1 {
                        continue;
                    }
                    let e1 = geo::Line::new(ring[a], ring[(a + 1) % n]);
                    let e2 = geo::Line::new(ring[b], ring[(b + 1) % n]);
                    assert!(
                        !geo::Intersects::intersects(&e1, &e2),
                        "piece {i} edges {a} and {b} meet"
                    );
                }
            }
            let outside = p.difference(&z).unsigned_area();
            assert!(
                outside < 1e-6 * z.unsigned_area(),
                "piece {i} leaves the zone"
            );
        }
        let union = polys.iter().fold(MultiPolygon::new(vec![]), |u, p| {
            u.union(&MultiPolygon::new(vec![p.clone()]))
        });
        let rel = (union.unsigned_area() - z.unsigned_area()).abs() / z.unsigned_area();
        // The clipping rounds to a fixed grid (i_overlay): areas agree to well under 1e-7.
        assert!(rel < 1e-7, "union area off by {rel}");
        let (x0, x1) = x_range(z.exterior());
        let (y0, y1) = y_span(z.exterior());
        for i in 0..=60 {
            for j in 0..=60 {
                let q = Coord {
                    x: x0 + (x1 - x0) * (i as f64 + 0.37) / 61.0,
                    y: y0 + (y1 - y0) * (j as f64 + 0.61) / 61.0,
                };
                let in_zone = z.contains(&q);
                let in_piece = polys.iter().any(|p| p.contains(&q));
                assert_eq!(in_zone, in_piece, "{q:?}");
            }
        }
        for (i, p) in pieces.iter().enumerate() {
            for k in 0..p.len() {
                let (a, b) = (p[k], p[(k + 1) % p.len()]);
                let m = Coord {
                    x: 0.5 * (a.0 + b.0),
                    y: 0.5 * (a.1 + b.1),
                };
                // Edges on the zone's boundary are not seams (within the clipping's rounding).
                let to_boundary = std::iter::once(z.exterior())
                    .chain(z.interiors())
                    .map(|r| Euclidean.distance(&geo::Point::from(m), r))
                    .fold(f64::INFINITY, f64::min);
                if !z.contains(&m) || to_boundary < 1e-6 * (x1 - x0) {
                    continue;
                }
                assert!(
                    polys
                        .iter()
                        .enumerate()
                        .any(|(j, o)| j != i && o.contains(&m)),
                    "piece {i} edge {k}'s midpoint {m:?} is a seam inside the zone"
                );
            }
        }
        pieces.len()
    }

    #[test]
    fn a_zone_without_holes_is_its_exterior() {
        let e = square(0.0, 0.0, 10.0);
        assert_eq!(simple_pieces(&e, &[]), vec![e]);
    }

    #[test]
    fn a_square_with_a_square_hole() {
        assert_eq!(check(&square(0.0, 0.0, 10.0), &[square(0.0, 0.0, 4.0)]), 2);
    }

    #[test]
    fn a_star_with_three_holes_and_one_under_another() {
        // The second and third holes sit one above the other, so one strip crosses both.
        let holes = vec![
            square(-300.0, 0.0, 120.0),
            square(200.0, 200.0, 80.0),
            square(200.0, -200.0, 80.0),
        ];
        let n = check(&star(0.0, 0.0, 1000.0, 24), &holes);
        assert!(n <= 2 * holes.len() + 2, "{n} pieces");
    }

    #[test]
    fn a_small_hole_beside_a_wide_one_is_not_duplicated() {
        // A narrow hole near the wide hole's widest gap: the strip must not hold it whole.
        let holes = vec![
            vec![
                (-400.0, -50.0),
                (400.0, -50.0),
                (400.0, 50.0),
                (-400.0, 50.0),
            ],
            vec![(1.0, 200.0), (3.0, 200.0), (2.0, 260.0)],
        ];
        check(&square(0.0, 0.0, 2000.0), &holes);
    }

    #[test]
    fn another_holes_vertex_on_the_strip_edge() {
        // The square hole's widest gap is [-10, 10]: c = 0, and ε = 1 puts the triangle's
        // vertex (1, 50) exactly on the strip's edge x = c + ε.
        let holes = vec![
            square(0.0, 0.0, 20.0),
            vec![(-2.0, 50.0), (1.0, 50.0), (0.0, 60.0)],
        ];
        check(&square(0.0, 20.0, 200.0), &holes);
    }

    #[test]
    fn a_hole_thinner_than_the_limit_is_filled() {
        let thin = vec![(0.0, 0.0), (0.01, 0.0), (0.005, 30.0)];
        let pieces = simple_pieces(&square(0.0, 0.0, 200.0), &[thin]);
        assert_eq!(pieces, vec![square(0.0, 0.0, 200.0)]);
    }

    #[test]
    fn star_shaped_holes_in_a_star() {
        let holes = vec![
            star(-250.0, 100.0, 150.0, 10),
            star(300.0, -150.0, 200.0, 14),
        ];
        check(&star(0.0, 0.0, 1500.0, 30), &holes);
    }
}
