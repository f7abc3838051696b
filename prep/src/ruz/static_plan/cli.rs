//! `skyroute static-plan`: the static planners ([`super::astar`], and [`super::milp`] with the
//! `milp` feature) on a scenario in its network's frame, or the scoring of a route file
//! (`--method route`, e.g. `skyroute plan`'s), printing the figures the comparison in
//! `docs/RUZ.md` uses: length, flight time, known-radar risk R_K, solve time.

use super::astar::{self, AstarOptions};
use super::check::check_route;
use super::{problem, score, Problem, Pt, StaticRoute};
use crate::output::{refuse_overwriting_inputs, write_atomically};
use crate::plan_cli::{load_scenario, CliResult, NoRoute};
use crate::provenance::check_binding;
use crate::route_json::{primitive_json, sampled_lon_lat};
use serde_json::{json, Value};
use skyroute::geometry::{Arc, Segment};
use skyroute::{Primitive, Vec2};
use std::path::{Path, PathBuf};
use std::time::Instant;

/// The planner of `static-plan`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Method {
    /// The receding-horizon MILP (needs the `milp` feature).
    Milp,
    /// A* with the inertia term on a grid.
    Astar,
    /// No planning: score the route file given with --route.
    Route,
}

/// The arguments of `skyroute static-plan`.
#[derive(Clone, Debug, clap::Args)]
pub struct StaticPlanArgs {
    /// The network image the scenario was built into (its frame is the route's).
    pub network: PathBuf,
    /// The scenario: start, goal, threat discs (kept out of) and known radars.
    #[arg(long)]
    pub scenario: PathBuf,
    /// The planner.
    #[arg(long, value_enum)]
    pub method: Method,
    /// MILP: Δt, seconds per step.
    #[arg(long, default_value_t = 20.0)]
    pub dt: f64,
    /// MILP: N, steps per solve.
    #[arg(long, default_value_t = 10)]
    pub horizon: usize,
    /// MILP: steps kept per solve.
    #[arg(long, default_value_t = 5)]
    pub commit: usize,
    /// MILP: the time limit of one solve, seconds (the best route found by then is taken).
    #[arg(long, default_value_t = 20.0)]
    pub solve_limit: f64,
    /// MILP: the relative gap at which a solve stops.
    #[arg(long, default_value_t = 0.01)]
    pub mip_gap: f64,
    /// μ₂: seconds of flight one unit of kill probability is worth (0: shortest time or
    /// length alone).
    #[arg(long, default_value_t = 10_000.0)]
    pub risk_weight: f64,
    /// A*: λ, metres per radian of direction change.
    #[arg(long, default_value_t = 500.0)]
    pub inertia: f64,
    /// A*: the grid's cell, metres.
    #[arg(long, default_value_t = 250.0)]
    pub cell: f64,
    /// A*: 8 or 16 moves per cell.
    #[arg(long, default_value_t = 16, value_parser = parse_connectivity)]
    pub connectivity: usize,
    /// Keep out of the scenario's pop-up NAME's disc as well (repeatable).
    #[arg(long, value_name = "NAME")]
    pub popup: Vec<String>,
    /// --method route: the route file to score (`skyroute plan -o ROUTE.json`).
    #[arg(long)]
    pub route: Option<PathBuf>,
    /// Where to write the route (a route file as `skyroute plan` writes, `.json`; `skyroute
    /// render --route` draws it).
    #[arg(short, long)]
    pub output: Option<PathBuf>,
}

fn parse_connectivity(s: &str) -> Result<usize, String> {
    match s.trim() {
        "8" => Ok(8),
        "16" => Ok(16),
        _ => Err(format!("expected 8 or 16, got {s:?}")),
    }
}

/// `skyroute static-plan`.
pub fn static_plan_command(a: &StaticPlanArgs) -> CliResult {
    if let Some(out) = &a.output {
        refuse_overwriting_inputs(out, &[&a.network, &a.scenario])?;
        if out.extension().and_then(|e| e.to_str()) != Some("json") {
            return Err(format!("{}: the route file's name ends in .json", out.display()).into());
        }
    }
    let bytes = std::fs::read(&a.network).map_err(|e| format!("{}: {e}", a.network.display()))?;
    let net = skyroute::Network::from_bytes(&bytes)
        .map_err(|e| format!("{}: {e}", a.network.display()))?;
    let s = load_scenario(&a.scenario, false, None)?;
    check_binding(&s, &net)
        .map_err(|e| format!("{} on {}: {e}", a.scenario.display(), a.network.display()))?;
    let frame = crate::export::network_frame(&net);
    let popups = a
        .popup
        .iter()
        .map(|n| {
            s.popups
                .iter()
                .position(|p| &p.name == n)
                .ok_or_else(|| format!("--popup {n}: the scenario has no pop-up of that name"))
        })
        .collect::<Result<Vec<_>, _>>()?;
    let pb = problem(&s, &frame, &popups)?;
    let t0 = Instant::now();
    let (route, mut extra, read) = match a.method {
        Method::Milp => plan_milp(&pb, a).map(|(r, x)| (r, x, None))?,
        Method::Astar => plan_astar(&pb, a).map(|(r, x)| (r, x, None))?,
        Method::Route => {
            let (r, p) = read_route_file(a.route.as_deref(), pb.v_nominal)?;
            (r, json!({}), Some(p))
        }
    };
    let solve_s = t0.elapsed().as_secs_f64();
    let prims = read.unwrap_or_else(|| route.primitives());
    let sc = score(&pb.params, &prims, &pb.radars);
    let model_time = sc.steps as f64 * pb.params.dt_s as f64;
    println!(
        "static-plan {:?} on {}: {:.1} m, flight time {:.1} s on its schedule ({:.1} s at the \
         nominal {} m/s), known-radar risk R_K {:.4}, solve {:.2} s",
        a.method,
        s.name,
        sc.length_m,
        route.time(),
        model_time,
        pb.v_nominal,
        sc.risk_known,
        solve_s
    );
    if a.method != Method::Route {
        report_check(&pb, &route);
    }
    extra["method"] = json!(format!("{:?}", a.method).to_lowercase());
    extra["risk_known"] = json!(sc.risk_known);
    extra["risk_steps"] = json!(sc.steps);
    extra["flight_time_s"] = json!(route.time());
    extra["solve_s"] = json!(solve_s);
    if let Some(out) = &a.output {
        let v = route_file_json(&route, &prims, &frame, &s.name, extra);
        write_atomically(out, serde_json::to_string(&v)?.as_bytes())?;
        println!("  -> {}", out.display());
    }
    Ok(())
}

/// Prints the route's check (`super::check`).
fn report_check(pb: &Problem, route: &StaticRoute) {
    let c = check_route(pb, route);
    let (depth, piece, name) =
        c.worst_intrusion
            .clone()
            .unwrap_or((f64::NEG_INFINITY, 0, "nothing".into()));
    println!(
        "  check: ends {:.3} m off, times {}, speed {:.1}–{:.1} m/s (v_max {}), acceleration ≤ \
         {:.2} m/s² (a_max {}), least clearance margin {:+.3} m (piece {piece}, {name}; \
         negative: inside)",
        c.end_gap_m,
        if c.times_increase {
            "increase"
        } else {
            "DO NOT increase"
        },
        c.min_speed,
        c.max_speed,
        pb.v_max,
        c.max_accel,
        pb.a_max,
        -depth,
    );
}

#[cfg(feature = "milp")]
fn plan_milp(
    pb: &Problem,
    a: &StaticPlanArgs,
) -> Result<(StaticRoute, Value), Box<dyn std::error::Error>> {
    use super::milp::{plan, MilpError, MilpOptions};
    let o = MilpOptions {
        dt: a.dt,
        horizon: a.horizon,
        commit: a.commit,
        risk_weight: a.risk_weight,
        time_limit_s: a.solve_limit,
        mip_gap: a.mip_gap,
        ..MilpOptions::default()
    };
    let r = plan(pb, &o).map_err(|e| -> Box<dyn std::error::Error> {
        match e {
            MilpError::BadOptions(_) => e.to_string().into(),
            e => Box::new(NoRoute(e.to_string())),
        }
    })?;
    let st = &r.stats;
    if o.risk_weight > 0.0 {
        let rings: Vec<String> = super::detection::rings(&pb.params)
            .iter()
            .map(|g| format!("{:.0} m (+{:.3})", g.radius, g.increment))
            .collect();
        println!(
            "  detection rings (radius, charged P_t): {}",
            rings.join(", ")
        );
    }
    println!(
        "  MILP: Δt {} s, N {}, {} kept per solve: {} solves, {:.2} s in all (slowest {:.2} s), \
         up to {} binaries, {} stopped by the time limit; detection charge D {:.4}",
        o.dt,
        o.horizon,
        o.commit,
        st.solves,
        st.solve_time_s,
        st.slowest_solve_s,
        st.max_binaries,
        st.timed_out,
        r.detection_charge
    );
    let extra = json!({"milp": {"dt_s": o.dt, "horizon": o.horizon, "commit": o.commit,
        "risk_weight": o.risk_weight, "mip_gap": o.mip_gap, "solve_limit_s": o.time_limit_s, "solves": st.solves, "solve_time_s": st.solve_time_s,
        "max_binaries": st.max_binaries, "timed_out": st.timed_out,
        "detection_charge": r.detection_charge}});
    Ok((r.route, extra))
}

#[cfg(not(feature = "milp"))]
fn plan_milp(
    _: &Problem,
    _: &StaticPlanArgs,
) -> Result<(StaticRoute, Value), Box<dyn std::error::Error>> {
    Err(
        "built without the milp feature: rebuild with `cargo install --path prep --features \
         milp` (HiGHS is built from source: needs cmake, a C++ compiler and libclang)"
            .into(),
    )
}

fn plan_astar(
    pb: &Problem,
    a: &StaticPlanArgs,
) -> Result<(StaticRoute, Value), Box<dyn std::error::Error>> {
    let o = AstarOptions {
        cell_m: a.cell,
        connectivity: a.connectivity,
        inertia: a.inertia,
        risk_weight: a.risk_weight,
        ..AstarOptions::default()
    };
    if !(o.cell_m.is_finite() && o.cell_m > 0.0 && o.inertia >= 0.0 && o.risk_weight >= 0.0) {
        return Err("--cell must be positive, --inertia and --risk-weight ≥ 0".into());
    }
    let r = astar::plan(pb, &o).ok_or_else(|| NoRoute("A*: no path on the grid".into()))?;
    println!(
        "  A*: {} m cells, {} moves, λ {} m/rad: {} states expanded, cost {:.1}, {} direction \
         changes ({:.2} rad)",
        o.cell_m, o.connectivity, o.inertia, r.expanded, r.cost, r.direction_changes, r.total_turn
    );
    let extra = json!({"astar": {"cell_m": o.cell_m, "connectivity": o.connectivity,
        "inertia": o.inertia, "risk_weight": o.risk_weight, "expanded": r.expanded,
        "cost": r.cost, "direction_changes": r.direction_changes}});
    Ok((r.route, extra))
}

/// The route file: the layout of `skyroute plan`'s (frame, one leg of line primitives,
/// a lon/lat LineString) with a `static_plan` member.
fn route_file_json(
    route: &StaticRoute,
    prims: &[Primitive],
    frame: &crate::frame::LocalFrame,
    scenario: &str,
    extra: Value,
) -> Value {
    let (lat0, lon0) = frame.origin();
    json!({
        "scenario": scenario,
        "frame": {"origin_lat_deg": lat0, "origin_lon_deg": lon0, "method": "transverse Mercator on WGS-84 centred on the origin (prep/src/frame.rs)"},
        "length_m": route.length(),
        "legs": [{"from": "start", "to": "goal", "length_m": route.length(),
                  "primitives": prims.iter().map(primitive_json).collect::<Vec<_>>()}],
        "times_s": route.times,
        "geometry": {"type": "LineString", "coordinates": sampled_lon_lat(prims, frame, 5.0)},
        "static_plan": extra,
    })
}

/// A route file's legs as one route, sampled every 10 m and timed at `speed`, and its
/// primitives.
fn read_route_file(
    path: Option<&Path>,
    speed: f64,
) -> Result<(StaticRoute, Vec<Primitive>), Box<dyn std::error::Error>> {
    let path = path.ok_or("--method route needs --route ROUTE.json")?;
    let at = |e: &dyn std::fmt::Display| format!("{}: {e}", path.display());
    let text = std::fs::read_to_string(path).map_err(|e| at(&e))?;
    let v: Value = serde_json::from_str(&text).map_err(|e| at(&e))?;
    let mut prims = Vec::new();
    for leg in v["legs"].as_array().ok_or_else(|| at(&"no legs"))? {
        for p in leg["primitives"]
            .as_array()
            .ok_or_else(|| at(&"a leg without primitives"))?
        {
            prims.push(primitive_of(p).ok_or_else(|| at(&format!("bad primitive {p}")))?);
        }
    }
    let mut points = Vec::new();
    for p in &prims {
        let n = (p.length() / 10.0).ceil().max(1.0) as usize;
        let first = usize::from(!points.is_empty());
        for i in first..=n {
            points.push(Pt::of(p.pose_at(p.length() * i as f32 / n as f32).position));
        }
    }
    let mut times = vec![0.0];
    for w in points.windows(2) {
        times.push(times.last().copied().unwrap_or(0.0) + w[0].dist(w[1]) / speed);
    }
    Ok((StaticRoute { points, times }, prims))
}

/// A primitive from its route-file JSON (`crate::route_json::primitive_json`).
fn primitive_of(p: &Value) -> Option<Primitive> {
    let pt = |k: &str| -> Option<Vec2> {
        let a = p[k].as_array()?;
        Some(Vec2::new(
            a.first()?.as_f64()? as f32,
            a.get(1)?.as_f64()? as f32,
        ))
    };
    match p["type"].as_str()? {
        "line" => Some(Primitive::Line(Segment::new(pt("start")?, pt("end")?))),
        "arc" => Some(Primitive::Arc(Arc {
            centre: pt("centre")?,
            radius: p["radius"].as_f64()? as f32,
            start_angle: p["start_angle"].as_f64()? as f32,
            sweep: p["sweep"].as_f64()? as f32,
        })),
        _ => None,
    }
}
