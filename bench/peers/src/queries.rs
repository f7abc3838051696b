//! Start/goal pose pairs for the query comparison.

use crate::rng::Rng;
use crate::world::World;
use skyroute::{Pose, Vec2};

/// How queries are drawn.
#[derive(Clone, Copy, Debug)]
pub struct QuerySpec {
    /// Number of pairs.
    pub count: usize,
    /// Seed of the generator.
    pub seed: u64,
    /// Both positions lie at least this far beyond the clearance from every obstacle, metres.
    pub min_free_m: f32,
    /// Start and goal lie at least this far apart, metres.
    pub min_separation_m: f32,
    /// Both positions lie at least this far inside the sampled area, metres.
    pub edge_margin_m: f32,
}

/// A start and a goal pose, both with a heading.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PosePair {
    /// Where the aircraft starts.
    pub start: Pose,
    /// Where it must arrive, and with which heading.
    pub goal: Pose,
}

/// Headings are drawn in (−`HEADING_LIMIT`, `HEADING_LIMIT`): a little inside (−π, π), so that
/// their f32 values stay inside OMPL's SO(2) bounds [−π, π] (the f32 nearest π exceeds π).
const HEADING_LIMIT: f64 = std::f64::consts::PI - 1e-5;

/// `spec.count` pairs drawn with `spec.seed`: positions uniform in the area shrunk by the edge
/// margin and accepted when free by the margin, pairs accepted when far enough apart, headings
/// uniform in (−`HEADING_LIMIT`, `HEADING_LIMIT`).
pub fn draw(world: &World, spec: &QuerySpec) -> Vec<PosePair> {
    let mut rng = Rng::new(spec.seed);
    let (lo, hi) = (world.lo, world.hi);
    let m = spec.edge_margin_m as f64;
    let free_position = |rng: &mut Rng| loop {
        let p = Vec2::new(
            rng.uniform(lo.x as f64 + m, hi.x as f64 - m) as f32,
            rng.uniform(lo.y as f64 + m, hi.y as f64 - m) as f32,
        );
        if world.distance(p) >= world.clearance() + spec.min_free_m {
            return p;
        }
    };
    let mut out = Vec::with_capacity(spec.count);
    while out.len() < spec.count {
        let a = free_position(&mut rng);
        let b = free_position(&mut rng);
        if a.distance(b) < spec.min_separation_m {
            continue;
        }
        let ha = rng.uniform(-HEADING_LIMIT, HEADING_LIMIT) as f32;
        let hb = rng.uniform(-HEADING_LIMIT, HEADING_LIMIT) as f32;
        out.push(PosePair {
            start: Pose {
                position: a,
                heading: ha,
            },
            goal: Pose {
                position: b,
                heading: hb,
            },
        });
    }
    out
}

/// The pairs as text, one per line: `sx sy sh gx gy gh`, each f32 printed as an f64 (exact).
pub fn to_text(pairs: &[PosePair]) -> String {
    let mut s = String::new();
    for q in pairs {
        let v = [
            q.start.position.x,
            q.start.position.y,
            q.start.heading,
            q.goal.position.x,
            q.goal.position.y,
            q.goal.heading,
        ];
        let line: Vec<String> = v.iter().map(|x| format!("{}", *x as f64)).collect();
        s.push_str(&line.join(" "));
        s.push('\n');
    }
    s
}

/// Reads [`to_text`]'s format back (`None` on a malformed line).
pub fn from_text(text: &str) -> Option<Vec<PosePair>> {
    let mut out = Vec::new();
    for line in text.lines().filter(|l| !l.trim().is_empty()) {
        let v: Vec<f32> = line
            .split_whitespace()
            .map(|t| t.parse::<f64>().map(|x| x as f32))
            .collect::<Result<_, _>>()
            .ok()?;
        if v.len() != 6 {
            return None;
        }
        out.push(PosePair {
            start: Pose::new(v[0], v[1], v[2]),
            goal: Pose::new(v[3], v[4], v[5]),
        });
    }
    Some(out)
}
