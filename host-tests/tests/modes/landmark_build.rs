//! The landmark shortest-path network (Babel 2014, ground side) on the real Babel scenarios:
//! counts beside the paper's, every edge checked independently in f64 (speeds, accelerations,
//! clearance from the no-fly polygons, continuity, rebuilding from the stored line elements),
//! and the same network on any number of threads.
//!
//! Run with `--nocapture` to see the counts and build times. The whole-network tests run in the
//! full tier, on the process's cached builds.

use skyroute::geometry::hermite::{HermiteSegment, LineElement};
use skyroute::network::write::ObstacleSpec;
use skyroute_prep::landmark::{
    build_from_input, build_landmark_network, HermiteChain, LandmarkError, LandmarkInput,
    LandmarkNetwork, LandmarkParams, RangeRule,
};
use skyroute_prep::scenario::{self, ParseOptions, Scenario};
use std::collections::HashSet;
use std::path::PathBuf;
use std::time::Instant;

use host_tests::reference::{dist_polygon, Poly64, P};
use host_tests::{full_tier_only, scenarios};

fn scenario_path(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../scenarios")
        .join(name)
}

/// Loads a scenario, replacing self-intersecting no-fly polygons by their hulls (babel-I).
fn load(name: &str) -> Scenario {
    let options = ParseOptions {
        hull_self_intersecting_no_fly: true,
    };
    scenario::load_with(&scenario_path(name), &options).expect("scenario loads")
}

fn build(s: &Scenario, params: &LandmarkParams) -> LandmarkNetwork {
    let input = LandmarkInput::from_scenario(s, params).expect("landmark input");
    build_from_input(&input, params, &|_, _| {})
}

fn report(name: &str, net: &LandmarkNetwork, secs: f64) {
    let st = &net.stats;
    println!(
        "{name}: {} vertices, {} edges; {} pairs, {} basic networks, {} line elements ({} \
         redrawn), segments tried {} / flyable {} / feasible {} / reversed feasible {}, {} \
         searches, {} directions out of range, {} edges over range, {} unconnected; start edges \
         {}, goal edges {}; build {secs:.1} s wall (segments {:.1} s, searches {:.2} s summed \
         over threads)",
        net.vertices.len(),
        net.edges.len(),
        st.pairs,
        st.basic_networks,
        st.line_elements,
        st.line_elements_rejected,
        st.segments_tried,
        st.segments_flyable,
        st.segments_feasible,
        st.reverse_feasible,
        st.searches,
        st.directions_out_of_range,
        st.edges_over_range,
        st.unconnected,
        net.start.as_ref().map_or(0, |s| s.edges.len()),
        net.goal.as_ref().map_or(0, |g| g.edges.len()),
        st.segment_time.as_secs_f64(),
        st.search_time.as_secs_f64(),
    );
}

// ------------------------------------------------------------------------------------------------
// Independent f64 reference: `host_tests::reference`

/// What the independent check measured over a network.
#[derive(Default, Debug)]
struct Checked {
    pieces: usize,
    samples: usize,
    min_clearance: f64,
    max_speed: f64,
    min_speed: f64,
    max_lat: f64,
    /// Largest distance between a piece's end and its line element, m.
    max_gap_m: f64,
    /// Same for the velocity, m/s.
    max_gap_mps: f64,
}

/// Checks one piece densely in f64; panics with `what` on a violation.
fn check_piece(
    net: &LandmarkNetwork,
    seg: &HermiteSegment,
    polys: &[Vec<P>],
    out: &mut Checked,
    what: &str,
) {
    let l = &net.limits;
    let poly = Poly64::new(seg);
    // About one sample per metre, at least 256.
    let m = ((seg.length() as f64).ceil() as usize).max(256);
    let (v_tol, a_tol) = (1e-4 * l.v_max as f64, 1e-3 * (l.a_lat_max as f64).max(1.0));
    let clearance = net.clearance_m as f64;
    // Polygons that a point of the piece can come within the clearance of: every point lies
    // within the piece's length of its start.
    let (p0, _, _) = poly.eval(0.0);
    let reach = seg.length() as f64 * 1.01 + clearance + 10.0;
    let near: Vec<&Vec<P>> = polys
        .iter()
        .filter(|pg| dist_polygon(p0, pg) < reach)
        .collect();
    let mut prev: Option<P> = None;
    let mut max_step = 0.0f64;
    let mut min_d = f64::INFINITY;
    for i in 0..=m {
        let s = i as f64 / m as f64;
        let (p, v, a) = poly.eval(s);
        let speed = (v.0 * v.0 + v.1 * v.1).sqrt();
        let a_long = (v.0 * a.0 + v.1 * a.1) / speed;
        let a_lat = (v.0 * a.1 - v.1 * a.0).abs() / speed;
        assert!(
            speed >= l.v_min as f64 - v_tol && speed <= l.v_max as f64 + v_tol,
            "{what}: speed {speed} outside [{}, {}] at s = {s}",
            l.v_min,
            l.v_max
        );
        assert!(
            a_long >= l.a_long_min as f64 - a_tol && a_long <= l.a_long_max as f64 + a_tol,
            "{what}: longitudinal acceleration {a_long} at s = {s}"
        );
        assert!(
            a_lat <= l.a_lat_max as f64 + a_tol,
            "{what}: lateral acceleration {a_lat} > {} at s = {s}",
            l.a_lat_max
        );
        out.max_speed = out.max_speed.max(speed);
        out.min_speed = out.min_speed.min(speed);
        out.max_lat = out.max_lat.max(a_lat);
        for pg in &near {
            min_d = min_d.min(dist_polygon(p, pg));
        }
        if let Some(q) = prev {
            max_step = max_step.max(((p.0 - q.0).powi(2) + (p.1 - q.1).powi(2)).sqrt());
        }
        prev = Some(p);
    }
    // Between samples the distance can dip by at most half a step.
    assert!(
        min_d >= clearance - 0.5 * max_step - 1e-2,
        "{what}: within {min_d} m of a no-fly polygon (clearance {clearance}, step {max_step})"
    );
    out.min_clearance = out.min_clearance.min(min_d);
    out.samples += m + 1;
    out.pieces += 1;
}

/// Checks a chain: starts at `first`, ends at `last`, pieces continuous, each piece rebuilt
/// identically from its line elements, cost the sum of lengths and at most `max_cost`.
#[allow(clippy::too_many_arguments)]
fn check_chain(
    net: &LandmarkNetwork,
    c: &HermiteChain,
    first: &LineElement,
    last: &LineElement,
    max_cost: f32,
    polys: &[Vec<P>],
    seen: &mut HashSet<Vec<u32>>,
    out: &mut Checked,
    what: &str,
) {
    assert!(!c.pieces.is_empty(), "{what}: no pieces");
    assert_eq!(
        c.elements.len(),
        c.pieces.len() + 1,
        "{what}: element count"
    );
    assert_eq!(
        c.elements[0], *first,
        "{what}: does not start at its source"
    );
    assert_eq!(
        c.elements[c.elements.len() - 1],
        *last,
        "{what}: does not end at its target"
    );
    let sum: f32 = c.pieces.iter().map(|p| p.length()).sum();
    assert!(
        (sum - c.cost).abs() <= 1e-3 * c.cost,
        "{what}: cost {} vs sum {sum}",
        c.cost
    );
    assert!(
        c.cost <= max_cost,
        "{what}: cost {} above the range {max_cost}",
        c.cost
    );
    let chord = first.position.distance(last.position);
    assert!(
        c.cost >= chord * (1.0 - 1e-5),
        "{what}: shorter than the chord"
    );
    for (i, seg) in c.pieces.iter().enumerate() {
        let (a, b) = (&c.elements[i], &c.elements[i + 1]);
        let rebuilt = HermiteSegment::new(a, b, net.v_nominal).expect("rebuilds");
        assert_eq!(
            rebuilt, *seg,
            "{what}: piece {i} does not rebuild from its line elements"
        );
        // Continuity in f64: the piece starts and ends at its line elements, with zero
        // acceleration, to the f32 rounding of its coefficients (relative to their sizes: the
        // end conditions hold to a few ε of Σ|b_k|, the sizes the core's rounding allowances use).
        let poly = Poly64::new(seg);
        let norm = |p: &P| (p.0 * p.0 + p.1 * p.1).sqrt();
        let sum_b: f64 = poly.b[1..].iter().map(norm).sum();
        let (pos_tol, vel_tol, acc_tol) = (
            8.0 * f32::EPSILON as f64 * (norm(&poly.b[0]) + sum_b),
            8.0 * f32::EPSILON as f64 * 5.0 * sum_b / poly.t,
            8.0 * f32::EPSILON as f64 * 20.0 * sum_b / (poly.t * poly.t),
        );
        for (s, e) in [(0.0, a), (1.0, b)] {
            let (p, v, acc) = poly.eval(s);
            let gp = norm(&(p.0 - e.position.x as f64, p.1 - e.position.y as f64));
            let gv = norm(&(v.0 - e.velocity.x as f64, v.1 - e.velocity.y as f64));
            assert!(
                gp <= pos_tol,
                "{what}: piece {i} misses its line element position at s = {s} by {gp} m \
                 (allowed {pos_tol})"
            );
            assert!(
                gv <= vel_tol,
                "{what}: piece {i} misses its line element velocity at s = {s} by {gv} m/s \
                 (allowed {vel_tol})"
            );
            assert!(
                norm(&acc) <= acc_tol,
                "{what}: piece {i} has acceleration {acc:?} at s = {s} (allowed {acc_tol})"
            );
            out.max_gap_m = out.max_gap_m.max(gp);
            out.max_gap_mps = out.max_gap_mps.max(gv);
        }
        let key: Vec<u32> = seg
            .normalized_coefficients()
            .iter()
            .flat_map(|v| [v.x.to_bits(), v.y.to_bits()])
            .chain([seg.t_max().to_bits()])
            .collect();
        if seen.insert(key) {
            check_piece(net, seg, polys, out, &format!("{what} piece {i}"));
        }
    }
}

/// The independent check of every edge and endpoint edge of `net`.
fn check_network(name: &str, net: &LandmarkNetwork) -> Checked {
    let polys: Vec<Vec<P>> = net
        .obstacles
        .iter()
        .filter_map(|o| match o {
            ObstacleSpec::Polygon(p) => Some(p.iter().map(|v| (v.x as f64, v.y as f64)).collect()),
            ObstacleSpec::Circle { .. } => None,
        })
        .collect();
    let mut out = Checked {
        min_clearance: f64::INFINITY,
        min_speed: f64::INFINITY,
        ..Default::default()
    };
    let mut seen = HashSet::new();
    let n = net.directions;
    assert_eq!(net.vertices.len(), net.landmarks.len() * n);
    for (i, v) in net.vertices.iter().enumerate() {
        assert_eq!(v.landmark as usize, i / n);
        assert_eq!(v.direction as usize, i % n);
        assert_eq!(v.element.position, net.landmarks[i / n].position);
        assert!((v.element.velocity.norm() - net.v_nominal).abs() <= 1e-3 * net.v_nominal);
    }
    let mut pairs = HashSet::new();
    for (i, e) in net.edges.iter().enumerate() {
        assert!(
            pairs.insert((e.source, e.target)),
            "{name}: edge {i} duplicated"
        );
        let (s, t) = (
            &net.vertices[e.source as usize],
            &net.vertices[e.target as usize],
        );
        assert_ne!(s.landmark, t.landmark, "{name}: edge {i} is a loop");
        let range = net.landmarks[s.landmark as usize].range_m(s.direction as usize);
        let what = format!("{name} edge {i} ({} -> {})", e.source, e.target);
        check_chain(
            net, &e.chain, &s.element, &t.element, range, &polys, &mut seen, &mut out, &what,
        );
    }
    if let Some(st) = &net.start {
        let dist = st.site.dist_m.unwrap_or(f32::INFINITY);
        for (i, e) in st.edges.iter().enumerate() {
            let v = &net.vertices[e.vertex as usize];
            let what = format!("{name} start edge {i}");
            let first = &st.elements[e.endpoint_element as usize];
            check_chain(
                net, &e.chain, first, &v.element, dist, &polys, &mut seen, &mut out, &what,
            );
        }
    }
    if let Some(g) = &net.goal {
        for (i, e) in g.edges.iter().enumerate() {
            let v = &net.vertices[e.vertex as usize];
            let range = net.landmarks[v.landmark as usize].range_m(v.direction as usize);
            let what = format!("{name} goal edge {i}");
            let last = &g.elements[e.endpoint_element as usize];
            check_chain(
                net, &e.chain, &v.element, last, range, &polys, &mut seen, &mut out, &what,
            );
        }
    }
    println!(
        "{name}: checked {} distinct pieces at {} f64 samples: speed {:.2}..{:.2} m/s, lateral \
         acceleration ≤ {:.2} m/s², closest approach to a no-fly polygon {:.1} m (clearance {} m); \
         pieces meet their line elements within {:.1e} m and {:.1e} m/s",
        out.pieces,
        out.samples,
        out.min_speed,
        out.max_speed,
        out.max_lat,
        out.min_clearance,
        net.clearance_m,
        out.max_gap_m,
        out.max_gap_mps
    );
    out
}

/// Reports and checks one scenario's landmark network: the process's cached build
/// (`skyroute_prep::build::build` keeps `build_landmark_network`'s network as it is; babel-I
/// with hull repair), shared with `landmark_plan` and `network_images`.
fn build_and_check(name: &str) -> &'static LandmarkNetwork {
    let t = Instant::now();
    let net = scenarios::built(name)
        .landmark
        .as_deref()
        .expect("a landmark network");
    report(name, net, t.elapsed().as_secs_f64());
    let checked = check_network(name, net);
    assert!(checked.pieces > 0);
    net
}

// ------------------------------------------------------------------------------------------------
// Tests

#[test]
fn babel_ii_n_and_s_beside_the_paper_every_edge_checked() {
    if !full_tier_only(
        "landmark_build::babel_ii_n_and_s_beside_the_paper_every_edge_checked",
        "builds babel-II-N and babel-II-S",
    ) {
        return;
    }
    println!(
        "paper, scenario II: 240 vertices, ~6000 edges, 500 line elements per basic network, \
         preprocessing ~30 min (Matlab, 2.2 GHz i7)"
    );
    for name in ["babel-II-N", "babel-II-S"] {
        let net = build_and_check(name);
        assert_eq!(net.vertices.len(), 240);
        assert!(net.stats.pairs > 20, "{name}: {} pairs", net.stats.pairs);
        assert!(
            net.edges.len() > 1500,
            "{name}: only {} edges",
            net.edges.len()
        );
        assert!(
            !net.start.as_ref().unwrap().edges.is_empty(),
            "{name}: start unconnected"
        );
        assert!(
            !net.goal.as_ref().unwrap().edges.is_empty(),
            "{name}: goal unconnected"
        );
    }
}

#[test]
fn babel_i_with_hull_repair_and_babel_iii_every_edge_checked() {
    if !full_tier_only(
        "landmark_build::babel_i_with_hull_repair_and_babel_iii_every_edge_checked",
        "builds babel-I and babel-III",
    ) {
        return;
    }
    let s = load("babel-I.geojson");
    assert!(!s.warnings.is_empty(), "babel-I needs the hull repair");
    for name in ["babel-I", "babel-III"] {
        let net = build_and_check(name);
        assert!(!net.edges.is_empty(), "{name}: no edges");
    }
}

#[test]
fn same_network_on_any_number_of_threads() {
    if !full_tier_only(
        "landmark_build::same_network_on_any_number_of_threads",
        "three babel-II-N builds",
    ) {
        return;
    }
    let s = load("babel-II-N.geojson");
    let mut params = LandmarkParams::from_scenario(&s);
    params.line_elements_per_pair = 150;
    let on = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| build(&s, &params))
    };
    let (one, three) = (on(1), on(3));
    assert!(!one.edges.is_empty());
    assert_eq!(one.vertices, three.vertices);
    assert_eq!(one.edges, three.edges);
    assert_eq!(one.start, three.start);
    assert_eq!(one.goal, three.goal);
    assert_eq!(one.stats.segments_tried, three.stats.segments_tried);
    // A different seed gives a different network.
    let mut other = params.clone();
    other.seed ^= 0x5eed;
    let input = LandmarkInput::from_scenario(&s, &other).unwrap();
    let reseeded = build_from_input(&input, &other, &|_, _| {});
    assert_ne!(reseeded.edges, one.edges);
}

/// Babel's reading (`--landmark-ranges onboard`): every direction searched, every chain kept.
/// The ground rule's edges come back unchanged, each further edge is one the ground rule
/// refuses by its own definition (its source direction's best-weather range is below the
/// landmarks' distance, or its chain is longer than that range), and the chains refused for
/// their length come back: as many as the ground build counted over range, less those of the
/// start and goal links.
#[test]
fn onboard_rule_keeps_the_ground_rules_edges_and_adds_only_refused_ones() {
    if !full_tier_only(
        "landmark_build::onboard_rule_keeps_the_ground_rules_edges_and_adds_only_refused_ones",
        "two babel-II-N builds",
    ) {
        return;
    }
    // babel-II-N: its rosettes leave some directions out of range (babel-I's are all 1).
    let s = load("babel-II-N.geojson");
    let mut params = LandmarkParams::from_scenario(&s);
    params.line_elements_per_pair = 100;
    let ground = build(&s, &params);
    params.range_rule = RangeRule::Onboard;
    let onboard = build(&s, &params);
    assert!(ground.stats.directions_out_of_range > 0);
    assert_eq!(onboard.stats.directions_out_of_range, 0);
    assert_eq!(onboard.stats.edges_over_range, 0);
    let input = LandmarkInput::from_scenario(&s, &params).unwrap();
    let n = params.directions;
    let kept: HashSet<(u32, u32)> = ground.edges.iter().map(|e| (e.source, e.target)).collect();
    let (mut extra, mut too_long) = (0, 0);
    for e in &onboard.edges {
        if kept.contains(&(e.source, e.target)) {
            let g = ground
                .edges
                .iter()
                .find(|g| (g.source, g.target) == (e.source, e.target))
                .unwrap();
            assert_eq!(g, e, "a chain both rules keep is the same chain");
            continue;
        }
        extra += 1;
        let (a, ka) = (e.source as usize / n, e.source as usize % n);
        let b = e.target as usize / n;
        let lm = &input.landmarks;
        let d = lm[a].position.distance(lm[b].position);
        let range = lm[a].range_m(ka);
        too_long += usize::from(range >= d);
        assert!(
            range < d || e.chain.cost > range,
            "edge {} -> {}: range {range} m, distance {d} m, chain {} m: the ground rule keeps it",
            e.source,
            e.target,
            e.chain.cost
        );
    }
    assert_eq!(onboard.edges.len(), ground.edges.len() + extra);
    assert!(extra > 0);
    // The ground build's over-range count also holds its start and goal links dropped.
    let endpoints = |n: &LandmarkNetwork| {
        n.start.as_ref().map_or(0, |s| s.edges.len()) + n.goal.as_ref().map_or(0, |g| g.edges.len())
    };
    assert!(too_long > 0);
    assert!(too_long <= ground.stats.edges_over_range, "{too_long}");
    assert!(
        too_long + (endpoints(&onboard) - endpoints(&ground)) >= ground.stats.edges_over_range,
        "{too_long} pair chains and {} endpoint links back of {} dropped",
        endpoints(&onboard) - endpoints(&ground),
        ground.stats.edges_over_range
    );
}

#[test]
fn pair_distance_rule_keeps_the_longer_chains() {
    let s = load("babel-I.geojson");
    let mut params = LandmarkParams::from_scenario(&s);
    params.line_elements_per_pair = 200;
    let strict = build(&s, &params);
    params.range_rule = RangeRule::PairDistance;
    let loose = build(&s, &params);
    let all = |n: &LandmarkNetwork| {
        n.edges.len()
            + n.start.as_ref().map_or(0, |s| s.edges.len())
            + n.goal.as_ref().map_or(0, |g| g.edges.len())
    };
    assert!(strict.stats.edges_over_range > 0);
    assert_eq!(
        all(&loose),
        all(&strict) + strict.stats.edges_over_range,
        "every dropped chain comes back"
    );
    assert_eq!(loose.stats.edges_over_range, 0);
}

#[test]
fn errors_name_the_file_and_field() {
    // A roadmap scenario has no landmarks.
    let s = scenario::load(&scenario_path("niendorf-urban.geojson")).unwrap();
    let e = build_landmark_network(&s, &|_, _| {}).unwrap_err();
    assert!(matches!(e, LandmarkError::Missing(..)));
    let msg = e.to_string();
    assert!(
        msg.contains("niendorf-urban.geojson") && msg.contains("landmark"),
        "{msg}"
    );

    let s = load("babel-I.geojson");
    let mut params = LandmarkParams::from_scenario(&s);
    params.directions = 0;
    let msg = LandmarkInput::from_scenario(&s, &params)
        .unwrap_err()
        .to_string();
    assert!(
        msg.contains("babel-I.geojson") && msg.contains("planner.directions"),
        "{msg}"
    );

    let mut no_dist = s.clone();
    no_dist.start.as_mut().unwrap().dist_m = None;
    let msg = build_landmark_network(&no_dist, &|_, _| {})
        .unwrap_err()
        .to_string();
    assert!(msg.contains("dist_m"), "{msg}");
}
