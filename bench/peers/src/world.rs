//! A network's map as the peers see it: obstacles, clearance, turn radius and the sampled area,
//! with skyroute's own exact predicates for points and Dubins paths.

use skyroute::geometry::predicates::{
    conflicts_with_circle, conflicts_with_polygon, point_in_polygon, point_segment_distance,
    PolygonView,
};
use skyroute::network::Obstacle;
use skyroute::{DubinsPath, Network, Primitive, Vec2};
use std::fmt::Write as _;

/// The map of a loaded network.
#[derive(Clone, Copy, Debug)]
pub struct World<'a> {
    /// The network.
    pub net: Network<'a>,
    /// South-west corner of the sampled area: the bounding box of the network's vertices,
    /// which `skyroute build` draws inside the scenario's bounding box.
    pub lo: Vec2,
    /// North-east corner of the sampled area.
    pub hi: Vec2,
}

impl<'a> World<'a> {
    /// The map of `net`, its area the bounding box of its vertices.
    pub fn new(net: Network<'a>) -> Self {
        let (mut lo, mut hi) = (Vec2::new(f32::MAX, f32::MAX), Vec2::new(f32::MIN, f32::MIN));
        for v in (0..net.vertex_count()).filter_map(|v| net.vertex(v)) {
            lo = Vec2::new(lo.x.min(v.position.x), lo.y.min(v.position.y));
            hi = Vec2::new(hi.x.max(v.position.x), hi.y.max(v.position.y));
        }
        Self { net, lo, hi }
    }

    /// The clearance, metres.
    pub fn clearance(&self) -> f32 {
        self.net.clearance()
    }

    /// Distance from `p` to the nearest static obstacle (0 inside one), with skyroute's point
    /// predicates; `f32::INFINITY` without obstacles.
    pub fn distance(&self, p: Vec2) -> f32 {
        let mut best = f32::INFINITY;
        for i in 0..self.net.obstacle_count() {
            let Some((obstacle, _)) = self.net.obstacle(i) else {
                continue;
            };
            let d = match obstacle {
                Obstacle::Polygon(poly) => {
                    if point_in_polygon(p, &poly) {
                        0.0
                    } else {
                        (0..poly.vertex_count())
                            .filter_map(|k| poly.edge(k))
                            .map(|e| point_segment_distance(p, &e))
                            .fold(f32::INFINITY, f32::min)
                    }
                }
                Obstacle::Circle { centre, radius } => (p.distance(centre) - radius).max(0.0),
            };
            best = best.min(d);
        }
        best
    }

    /// Whether a point is blocked: within the clearance of an obstacle (boundary included) or
    /// inside one, the rule `skyroute build` applies to its samples.
    pub fn point_blocked(&self, p: Vec2) -> bool {
        self.distance(p) <= self.clearance()
    }

    /// Whether a primitive comes within the clearance of a static obstacle: the planner's own
    /// exact check (`path_is_clear` in `src/planner/connect.rs`: a bounding-box test, then
    /// `conflicts_with_polygon` or `conflicts_with_circle`).
    pub fn primitive_conflicts(&self, prim: &Primitive) -> bool {
        let clearance = self.clearance();
        let (lo, hi) = prim.bounding_box();
        for i in 0..self.net.obstacle_count() {
            let Some((obstacle, (olo, ohi))) = self.net.obstacle(i) else {
                return true;
            };
            let apart = lo.x - clearance > ohi.x
                || hi.x + clearance < olo.x
                || lo.y - clearance > ohi.y
                || hi.y + clearance < olo.y;
            if apart {
                continue;
            }
            let conflict = match obstacle {
                Obstacle::Polygon(poly) => conflicts_with_polygon(prim, &poly, clearance),
                Obstacle::Circle { centre, radius } => {
                    conflicts_with_circle(prim, centre, radius, clearance)
                }
            };
            if conflict {
                return true;
            }
        }
        false
    }

    /// Whether any primitive of a Dubins path comes within the clearance of a static obstacle.
    pub fn path_conflicts(&self, path: &DubinsPath) -> bool {
        path.primitives()
            .into_iter()
            .flatten()
            .any(|p| self.primitive_conflicts(&p))
    }

    /// The map as the text the C++ program (`bench/ompl_cpp`) reads:
    ///
    /// ```text
    /// radius R clearance C
    /// bounds X0 Y0 X1 Y1
    /// polygons N
    /// K x1 y1 ... xK yK          (one line per polygon)
    /// circles M
    /// x y r                      (one line per circle)
    /// ```
    ///
    /// Every number is the f32 value printed as an f64, so that the reader gets it exactly.
    pub fn to_text(&self) -> String {
        let f = |x: f32| x as f64;
        let mut s = String::new();
        let _ = writeln!(
            s,
            "radius {} clearance {}",
            f(self.net.turn_radius()),
            f(self.clearance())
        );
        let _ = writeln!(
            s,
            "bounds {} {} {} {}",
            f(self.lo.x),
            f(self.lo.y),
            f(self.hi.x),
            f(self.hi.y)
        );
        let (mut polys, mut circles) = (Vec::new(), Vec::new());
        for i in 0..self.net.obstacle_count() {
            match self.net.obstacle(i).map(|o| o.0) {
                Some(Obstacle::Polygon(poly)) => {
                    let mut line = format!("{}", poly.vertex_count());
                    for k in 0..poly.vertex_count() {
                        if let Some(v) = poly.vertex(k) {
                            let _ = write!(line, " {} {}", f(v.x), f(v.y));
                        }
                    }
                    polys.push(line);
                }
                Some(Obstacle::Circle { centre, radius }) => {
                    circles.push(format!("{} {} {}", f(centre.x), f(centre.y), f(radius)))
                }
                None => {}
            }
        }
        let _ = writeln!(s, "polygons {}", polys.len());
        for p in polys {
            let _ = writeln!(s, "{p}");
        }
        let _ = writeln!(s, "circles {}", circles.len());
        for c in circles {
            let _ = writeln!(s, "{c}");
        }
        s
    }
}
