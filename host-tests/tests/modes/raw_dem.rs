//! Independent terrain checks against the raw DEM: points are mapped back to longitude and
//! latitude with the frame and looked up in the DEM's own cells, bypassing the metric grid, the
//! elevation codes and the grid traversal that the code under test uses.
#![allow(dead_code)]

use skyroute::{Pose, Primitive};
use skyroute_prep::dem::Dem;
use skyroute_prep::frame::LocalFrame;

/// The raw DEM cell holding `(lon, lat)` — `floor` of the offset from the south-west corner in
/// cells — is navigable: inside the DEM, not NODATA, elevation below `threshold`.
pub fn raw_navigable(dem: &Dem, lon: f64, lat: f64, threshold: f64) -> bool {
    let u = (lon - dem.xllcorner) / dem.cell_x;
    let v = (lat - dem.yllcorner) / dem.cell_y;
    if !(u >= 0.0 && v >= 0.0) {
        return false;
    }
    let (c, r) = (u.floor() as usize, v.floor() as usize);
    match dem.elevation_at(c, r) {
        Some(e) => (e as f64) < threshold,
        None => false,
    }
}

/// What a raw-DEM check found.
#[derive(Default)]
pub struct Check {
    /// Points looked up.
    pub samples: u64,
    /// Points over a blocked (or NODATA, or outside) DEM cell.
    pub violations: u64,
    /// The first of them, in words.
    pub first: Option<String>,
}

impl Check {
    /// Both checks' counts.
    pub fn merge(mut self, o: Check) -> Check {
        self.samples += o.samples;
        self.violations += o.violations;
        self.first = self.first.or(o.first);
        self
    }

    fn look_up(
        &mut self,
        dem: &Dem,
        frame: &LocalFrame,
        x: f64,
        y: f64,
        threshold: f64,
        what: impl Fn() -> String,
    ) {
        let (lon, lat) = frame.to_geo(x, y);
        self.samples += 1;
        if !raw_navigable(dem, lon, lat, threshold) {
            self.violations += 1;
            self.first.get_or_insert_with(|| {
                format!("{} at ({x:.1}, {y:.1}) = ({lon:.6}, {lat:.6})", what())
            });
        }
    }
}

/// Samples a route densely and looks every point up in the raw DEM: every `step` metres along
/// each line and arc (by arc length, in f64 from the primitive's parameters), on lines across
/// the path from `−w` to `+w` at most `across` apart (for an arc: radii `r − w … r + w`), and
/// rings of radius `w` around the route's two ends. Counts the points over cells not navigable
/// below `threshold`.
pub fn route_violations(
    route: &[Primitive],
    dem: &Dem,
    frame: &LocalFrame,
    threshold: f64,
    w: f64,
    step: f64,
    across: f64,
) -> Check {
    let mut out = Check::default();
    let lines = ((2.0 * w / across).ceil() as i64).max(1);
    let offsets: Vec<f64> = (0..=lines)
        .map(|m| -w + 2.0 * w * m as f64 / lines as f64)
        .collect();
    for (i, p) in route.iter().enumerate() {
        match p {
            Primitive::Line(seg) => {
                let (ax, ay) = (seg.start.x as f64, seg.start.y as f64);
                let (dx, dy) = (seg.end.x as f64 - ax, seg.end.y as f64 - ay);
                let l = dx.hypot(dy);
                if l == 0.0 {
                    continue;
                }
                let (ux, uy) = (dx / l, dy / l);
                let n = (l / step).ceil().max(1.0) as i64;
                for k in 0..=n {
                    let t = l * k as f64 / n as f64;
                    for &s in &offsets {
                        let (x, y) = (ax + ux * t - uy * s, ay + uy * t + ux * s);
                        out.look_up(dem, frame, x, y, threshold, || {
                            format!("line {i}: {t:.1} m along, {s:.1} m across")
                        });
                    }
                }
            }
            Primitive::Arc(a) => {
                let (cx, cy, r) = (a.centre.x as f64, a.centre.y as f64, a.radius as f64);
                let sweep = a.sweep as f64;
                let n = ((r * sweep.abs()) / step).ceil().max(1.0) as i64;
                for k in 0..=n {
                    let phi = a.start_angle as f64 + sweep * k as f64 / n as f64;
                    for &s in &offsets {
                        let rho = r + s;
                        let (x, y) = (cx + rho * phi.cos(), cy + rho * phi.sin());
                        out.look_up(dem, frame, x, y, threshold, || {
                            format!("arc {i}: angle {phi:.4}, radius {rho:.1}")
                        });
                    }
                }
            }
        }
    }
    let ends = [
        route.first().map(|p| p.pose_at(0.0)),
        route.last().map(|p| p.pose_at(p.length())),
    ];
    for pose in ends.into_iter().flatten() {
        ring(&mut out, dem, frame, &pose, w, threshold);
    }
    out
}

/// The points of a ring of radius `w` and one of `w/2` around `pose`.
fn ring(out: &mut Check, dem: &Dem, frame: &LocalFrame, pose: &Pose, w: f64, threshold: f64) {
    let (x0, y0) = (pose.position.x as f64, pose.position.y as f64);
    let n = ((std::f64::consts::TAU * w / 5.0).ceil() as i64).max(8);
    for rr in [0.5 * w, w] {
        for k in 0..n {
            let a = std::f64::consts::TAU * k as f64 / n as f64;
            out.look_up(
                dem,
                frame,
                x0 + rr * a.cos(),
                y0 + rr * a.sin(),
                threshold,
                || format!("end ring of radius {rr:.1}"),
            );
        }
    }
}
