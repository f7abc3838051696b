//! The inputs every peer reads: the map, the queries, sample points, Dubins pose pairs.

use crate::{network, read, write, Args};
use serde_json::json;
use skyroute::geometry::predicates::PolygonView;
use skyroute::network::Obstacle;
use skyroute::Vec2;
use skyroute_peers::queries::{self, QuerySpec};
use skyroute_peers::rng::Rng;
use skyroute_peers::world::World;
use std::f64::consts::PI;

/// `map NET.bin OUT.txt`: writes the map for the C++ program and prints the network's counts,
/// radius, clearance and area as JSON.
pub fn map(args: &Args) -> Result<(), String> {
    let bytes = read(args.get(0, "network")?)?;
    let world = World::new(network(&bytes)?);
    write(args.get(1, "output")?, world.to_text().as_bytes())?;
    let info = json!({
        "vertices": world.net.vertex_count(),
        "edges": world.net.edge_count(),
        "obstacles": world.net.obstacle_count(),
        "turn_radius_m": world.net.turn_radius(),
        "clearance_m": world.clearance(),
        "area": [world.lo.x, world.lo.y, world.hi.x, world.hi.y],
    });
    println!("{info}");
    Ok(())
}

/// `queries NET.bin COUNT SEED OUT.txt`: pose pairs whose positions lie 20 m beyond the
/// clearance and 50 m inside the area, at least 1 km apart.
pub fn queries(args: &Args) -> Result<(), String> {
    let bytes = read(args.get(0, "network")?)?;
    let world = World::new(network(&bytes)?);
    let spec = QuerySpec {
        count: args.parse(1, "count")?,
        seed: args.parse(2, "seed")?,
        min_free_m: 20.0,
        min_separation_m: 1000.0,
        edge_margin_m: 50.0,
    };
    let pairs = queries::draw(&world, &spec);
    write(args.get(3, "output")?, queries::to_text(&pairs).as_bytes())
}

/// `validity NET.bin COUNT SEED OUT.txt`: `COUNT` points, `x y blocked distance` per line with
/// skyroute's verdict (blocked: within the clearance or inside) and its distance to the
/// nearest obstacle. Half are uniform over the area and 100 m around it; half lie near the
/// clearance contour (a polygon edge point or corner moved by the clearance plus a normal
/// offset of σ = 1.5 m), where two checkers would disagree if either were wrong.
pub fn validity(args: &Args) -> Result<(), String> {
    let bytes = read(args.get(0, "network")?)?;
    let world = World::new(network(&bytes)?);
    let count: usize = args.parse(1, "count")?;
    let mut rng = Rng::new(args.parse(2, "seed")?);
    let edges = polygon_edges(&world);
    let mut out = String::new();
    for k in 0..count {
        let p = if k % 2 == 0 || edges.is_empty() {
            Vec2::new(
                rng.uniform(world.lo.x as f64 - 100.0, world.hi.x as f64 + 100.0) as f32,
                rng.uniform(world.lo.y as f64 - 100.0, world.hi.y as f64 + 100.0) as f32,
            )
        } else {
            let (a, b) = edges[rng.below(edges.len() as u64) as usize];
            let t = rng.unit().min(1.0) as f32;
            let on = a + (b - a) * t;
            // Away from the edge on either side, or from its corner in any direction.
            let off = world.clearance() as f64 + 1.5 * rng.normal();
            let dir = if rng.unit() < 0.8 {
                let n = (b - a).perp() * (1.0 / (b - a).norm());
                if rng.unit() < 0.5 {
                    n
                } else {
                    n * -1.0
                }
            } else {
                Vec2::from_angle(rng.uniform(-PI, PI) as f32)
            };
            let base = if rng.unit() < 0.8 { on } else { a };
            base + dir * off as f32
        };
        let d = world.distance(p);
        out.push_str(&format!(
            "{} {} {} {}\n",
            p.x as f64,
            p.y as f64,
            u8::from(d <= world.clearance()),
            d
        ));
    }
    write(args.get(3, "output")?, out.as_bytes())
}

/// Every polygon edge of the map, as end point pairs.
fn polygon_edges(world: &World) -> Vec<(Vec2, Vec2)> {
    let mut edges = Vec::new();
    for i in 0..world.net.obstacle_count() {
        if let Some((Obstacle::Polygon(poly), _)) = world.net.obstacle(i) {
            for k in 0..poly.vertex_count() {
                if let Some(e) = poly.edge(k) {
                    edges.push((e.start, e.end));
                }
            }
        }
    }
    edges
}

/// `pairs COUNT SEED RADIUS OUT.bin`: `COUNT` pose pairs as little-endian f64
/// `x0 y0 h0 x1 y1 h1`, every value an f32 (so that the f32 and f64 solvers get the same
/// poses). Even pairs: both positions uniform in a 3 km square; odd pairs: the goal uniform
/// in the disc of 4 turn radii about the start, where the CCC words and the special cases
/// live. Headings uniform in [−π, π).
pub fn pairs(args: &Args) -> Result<(), String> {
    let count: usize = args.parse(0, "count")?;
    let mut rng = Rng::new(args.parse(1, "seed")?);
    let radius: f64 = args.parse(2, "radius")?;
    let mut out = Vec::with_capacity(count * 48);
    for k in 0..count {
        let (x0, y0) = (rng.uniform(-1500.0, 1500.0), rng.uniform(-1500.0, 1500.0));
        let (x1, y1) = if k % 2 == 0 {
            (rng.uniform(-1500.0, 1500.0), rng.uniform(-1500.0, 1500.0))
        } else {
            let (rho, phi) = (4.0 * radius * rng.unit().sqrt(), rng.uniform(-PI, PI));
            (x0 + rho * phi.cos(), y0 + rho * phi.sin())
        };
        let (h0, h1) = (rng.uniform(-PI, PI), rng.uniform(-PI, PI));
        for v in [x0, y0, h0, x1, y1, h1] {
            out.extend_from_slice(&((v as f32) as f64).to_le_bytes());
        }
    }
    write(args.get(3, "output")?, &out)
}
