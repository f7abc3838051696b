//! How good a landmark network is, beside references that do not come from it: each edge's
//! chain length over the Dubins lower bound between its two overflight poses (radius
//! `v_min² / a_lat_max`, the tightest turn any flyable piece can make, so no flight between the
//! poses is shorter), the edges per landmark pair against the directions whose range reaches,
//! the start's and goal's connections, and which overflights the start reaches.
//!
//! `cargo run --release -p skyroute-prep --example landmark_quality -- scenarios/babel-II-N.geojson`
//! (self-intersecting no-fly polygons are replaced by their hulls).
use skyroute_prep::build::{build, BuildOptions};
use skyroute_prep::scenario::{self, ParseOptions};
fn main() {
    let path = std::env::args()
        .nth(1)
        .expect("usage: landmark_quality SCENARIO");
    let s = scenario::load_with(
        path.as_ref(),
        &ParseOptions {
            hull_self_intersecting_no_fly: true,
        },
    )
    .unwrap();
    let b = build(&s, &BuildOptions::default(), &|_, _| {}).unwrap();
    let n = b.landmark.as_ref().unwrap();
    println!("{:?}", n.stats);
    let d = n.directions;
    let rmin = n.limits.v_min * n.limits.v_min / n.limits.a_lat_max;
    let mut ratios: Vec<f32> = n
        .edges
        .iter()
        .filter_map(|e| {
            let (a, b) = (
                &n.vertices[e.source as usize].pose,
                &n.vertices[e.target as usize].pose,
            );
            skyroute::DubinsPath::shortest(a, b, rmin).map(|p| e.chain.cost / p.length())
        })
        .collect();
    ratios.sort_by(|a, b| a.total_cmp(b));
    let q = |f: f32| ratios[((ratios.len() - 1) as f32 * f) as usize];
    println!(
        "rmin {rmin:.0} m; chain/dubins ratio min {:.3} p10 {:.3} median {:.3} p90 {:.3} max {:.3}",
        q(0.0),
        q(0.1),
        q(0.5),
        q(0.9),
        q(1.0)
    );
    let lm = &n.landmarks;
    let m = lm.len();
    let mut cnt = vec![vec![0usize; m]; m];
    for e in &n.edges {
        cnt[e.source as usize / d][e.target as usize / d] += 1;
    }
    for a in 0..m {
        for bb in 0..m {
            if a != bb {
                let dist = (lm[a].position - lm[bb].position).norm();
                if dist < lm[a].d_max_m.max(lm[bb].d_max_m) {
                    let ranges: Vec<_> = (0..d).filter(|&k| lm[a].range_m(k) >= dist).collect();
                    println!(
                        "{}->{} dist {:.1} km: {} edges; dirs in range {:?}",
                        lm[a].name,
                        lm[bb].name,
                        dist / 1000.0,
                        cnt[a][bb],
                        ranges
                    );
                }
            }
        }
    }
    if let Some(st) = &n.start {
        let mut per = vec![0; m];
        for e in &st.edges {
            per[e.vertex as usize / d] += 1;
        }
        println!("start edges per landmark {:?}", per);
    }
    if let Some(g) = &n.goal {
        let mut per = vec![0; m];
        for e in &g.edges {
            per[e.vertex as usize / d] += 1;
        }
        println!("goal edges per landmark {:?}", per);
    }

    // Which overflights the start reaches through stored edges (any weather), and the goal.
    let nv = n.vertices.len();
    let mut adj = vec![Vec::new(); nv];
    for e in &n.edges {
        adj[e.source as usize].push(e.target as usize);
    }
    let mut seen = vec![false; nv];
    let mut st: Vec<usize> = n
        .start
        .as_ref()
        .map(|s| s.edges.iter().map(|e| e.vertex as usize).collect())
        .unwrap_or_default();
    for &v in &st {
        seen[v] = true;
    }
    while let Some(u) = st.pop() {
        for &t in &adj[u] {
            if !seen[t] {
                seen[t] = true;
                st.push(t);
            }
        }
    }
    let goal_ok = n
        .goal
        .as_ref()
        .map(|g| g.edges.iter().any(|e| seen[e.vertex as usize]))
        .unwrap_or(false);
    println!(
        "reachable overflights {} of {nv}; goal reachable {goal_ok}",
        seen.iter().filter(|x| **x).count()
    );
}
