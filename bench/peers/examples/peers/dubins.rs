//! skyroute's Dubins shortest path (`DubinsPath::shortest`, f32) over the shared pose pairs.

use crate::{read, write, write_json, Args};
use serde_json::json;
use skyroute::{DubinsPath, Pose};
use skyroute_peers::stats;
use std::hint::black_box;
use std::time::Instant;

/// `dubins PAIRS.bin RADIUS OUT.bin OUT.json [REPS]`: times `DubinsPath::shortest` over every
/// pair (`REPS` passes, default 5; the poses are converted to f32 before the clock starts),
/// writes each length as a little-endian f64 (NaN where no path is returned) and the ns per
/// path of every pass.
pub fn dubins(args: &Args) -> Result<(), String> {
    let bytes = read(args.get(0, "pairs")?)?;
    let radius: f32 = args.parse(1, "radius")?;
    let reps: usize = args.parse_or(4, "reps", 5)?;
    let vals: Vec<f32> = bytes
        .chunks_exact(8)
        .map(|c| f64::from_le_bytes(c.try_into().unwrap_or([0; 8])) as f32)
        .collect();
    let poses: Vec<(Pose, Pose)> = vals
        .chunks_exact(6)
        .map(|v| (Pose::new(v[0], v[1], v[2]), Pose::new(v[3], v[4], v[5])))
        .collect();
    let n = poses.len();
    if n == 0 {
        return Err("no pose pairs".into());
    }
    let mut ns = Vec::with_capacity(reps);
    for _ in 0..reps {
        let t0 = Instant::now();
        let mut sum = 0.0f32;
        for (a, b) in &poses {
            sum += shortest_length(black_box(a), black_box(b), radius);
        }
        black_box(sum);
        ns.push(t0.elapsed().as_nanos() as f64 / n as f64);
    }
    let mut out = Vec::with_capacity(n * 8);
    for (a, b) in &poses {
        let l = DubinsPath::shortest(a, b, radius).map_or(f64::NAN, |p| p.length() as f64);
        out.extend_from_slice(&l.to_le_bytes());
    }
    write(args.get(2, "lengths output")?, &out)?;
    write_json(
        args.get(3, "json output")?,
        &json!({
            "solver": "skyroute DubinsPath::shortest (f32)",
            "pairs": n,
            "radius_m": radius,
            "ns_per_path_passes": ns,
            "ns_per_path_median": stats::median(&ns),
        }),
    )
}

/// The length of the shortest path (0 when none is returned, which finite poses never give).
#[inline(never)]
fn shortest_length(a: &Pose, b: &Pose, radius: f32) -> f32 {
    DubinsPath::shortest(a, b, radius).map_or(0.0, |p| p.length())
}
