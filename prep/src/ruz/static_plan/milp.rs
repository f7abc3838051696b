//! The MILP planner of Ruz et al. (after Richards and How): a receding-horizon mixed-integer
//! linear programme on a point mass in the local frame, solved by HiGHS through `good_lp`.
//!
//! **States and dynamics (eqs 1–3).** Per step k = 1…N of Δt: position p_k and velocity v_k
//! (x, y each). The velocity v_k is held over step k, `p_k = p_{k−1} + Δt·v_k`, so the route
//! between two steps is exactly the straight piece flown at |v_k| (a discretised double
//! integrator whose acceleration is `(v_k − v_{k−1})/Δt`); v_0 is the current velocity.
//!
//! **Bounds (eq. 6).** |v_k| ≤ v_max and |v_k − v_{k−1}| ≤ a_max·Δt, each as the inscribed
//! regular polygon of [`MilpOptions::bound_sides`] sides: `u_s·v ≤ v_max·cos(π/S)` for the S
//! unit normals u_s. The polygon lies inside the circle, so the bound always holds and at most
//! `1 − cos(π/S)` of it is lost (1.9 % for S = 16).
//!
//! **Obstacles (eqs 4–5).** A disc of radius r (+ clearance) is kept out of through the
//! circumscribed polygon of [`MilpOptions::keep_out_sides`] sides: per straight piece k and
//! disc, binaries σ_s (Σ_s σ_s = 1, the paper's "Σ relaxed ≤ sides − 1") select one side, and
//! `u_s·(p − c) ≥ r − M·(1 − σ_s)` holds for **both ends** p_{k−1} and p_k of the piece. A
//! half-plane is convex, so the whole piece lies beyond the side: no corner cutting. A no-fly
//! polygon is taken as its convex hull, each edge's half-plane pushed out by the clearance,
//! with one binary per edge per piece in the same way.
//!
//! **Detection (eqs 13–18).** Per piece and known radar, the distance h ≤ `u_s·(m_k − c) +
//! M·(1 − σ_s)` of the piece's middle m_k from the radar along the chosen side (a lower bound
//! of the true distance, within cos(π/S)), and per ring k ([`super::detection`]) a binary z
//! with `h ≥ ρ_k·(1 − z)`: z = 1 when the piece is inside the ring. The detection charge is
//! `D = Σ p_k·(Δt/Δt_risk)·w_k·z`, the risk model's kill probability to first order with the
//! ring staircase for P_t (radars sum instead of combining). A radar that is also a threat
//! disc shares the side binaries of its disc.
//!
//! **Objective (eq. 37).** `J = μ₁·t + μ₂·D`. t is the time to the goal: binaries b_k "at the
//! goal at step k" (`|p_k − goal| ≤ M·(1 − b_k)` per axis) and b_∞ "not within this horizon",
//! `Σ b = 1`, `t = Σ k·Δt·b_k + b_∞·(N·Δt + d/v_max)` with the terminal cost d ≥
//! `u_s·(p_N − goal) − M·(1 − b_∞)` (the polygonal distance to go). A goal out of reach of the
//! horizon has no b_k and b_∞ = 1.
//!
//! **Receding horizon.** Each solve plans N steps from the current state; the first
//! [`MilpOptions::commit`] are kept and the next solve starts from there, until a solve
//! arrives (its steps up to the arrival are kept). Only discs, zones and rings that the
//! horizon can reach (N·Δt·v_max) enter a solve. Big-M is per constraint: the farthest the
//! constraint's expression can be from its bound within the horizon's reach.

use super::detection::{self, Ring};
use super::{direction, Problem, Pt, StaticRoute};
use good_lp::{
    constraint, variable, Constraint, Expression, ProblemVariables, ResolutionError, Solution,
    SolutionStatus, SolverModel, Variable,
};
use std::time::Instant;

/// The MILP's settings (`docs/RUZ.md` says why these defaults).
#[derive(Clone, Debug, PartialEq)]
pub struct MilpOptions {
    /// Δt, seconds.
    pub dt: f64,
    /// N, steps per solve.
    pub horizon: usize,
    /// Steps kept per solve (1 ≤ commit ≤ N).
    pub commit: usize,
    /// Sides of the polygons of discs and detection rings.
    pub keep_out_sides: usize,
    /// Sides of the polygons bounding |v|, |a| and the distance to go.
    pub bound_sides: usize,
    /// μ₁, per second of flight time.
    pub time_weight: f64,
    /// μ₂, seconds per unit of detection charge (kill probability).
    pub risk_weight: f64,
    /// The time limit of one solve, seconds (the best solution found so far is taken).
    pub time_limit_s: f64,
    /// The relative gap at which HiGHS stops a solve (its proven bound within this share of
    /// the best solution's objective).
    pub mip_gap: f64,
    /// The most solves before giving up.
    pub max_solves: usize,
}

impl Default for MilpOptions {
    fn default() -> Self {
        Self {
            dt: 20.0,
            horizon: 10,
            commit: 5,
            keep_out_sides: 8,
            bound_sides: 16,
            time_weight: 1.0,
            risk_weight: 10_000.0,
            time_limit_s: 20.0,
            mip_gap: 0.01,
            max_solves: 200,
        }
    }
}

/// What the solves took.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MilpStats {
    /// Solves run.
    pub solves: usize,
    /// Their total wall time (model building and HiGHS), seconds.
    pub solve_time_s: f64,
    /// The slowest solve, seconds.
    pub slowest_solve_s: f64,
    /// The most binaries in one solve.
    pub max_binaries: usize,
    /// Solves stopped by the time limit before reaching the gap.
    pub timed_out: usize,
}

/// A MILP route and how it was found.
#[derive(Clone, Debug, PartialEq)]
pub struct MilpRoute {
    /// The route: the committed steps' positions, the goal last.
    pub route: StaticRoute,
    /// The velocity of each piece, m/s.
    pub velocities: Vec<Pt>,
    /// The detection charge D of the committed pieces (the MILP's staircase).
    pub detection_charge: f64,
    /// Solve statistics.
    pub stats: MilpStats,
}

/// Why the MILP found no route.
#[derive(Debug, Clone, PartialEq)]
pub enum MilpError {
    /// Bad settings.
    BadOptions(String),
    /// A solve had no feasible point (e.g. the goal inside a disc).
    Infeasible {
        /// The solve's index (0: the first).
        solve: usize,
    },
    /// HiGHS failed or found no solution within the time limit.
    Solver(String),
    /// No solve reached the goal within [`MilpOptions::max_solves`].
    NoArrival {
        /// Solves run.
        solves: usize,
        /// The distance left to the goal, metres.
        left_m: f64,
    },
}

impl std::fmt::Display for MilpError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            MilpError::BadOptions(s) => write!(f, "bad MILP settings: {s}"),
            MilpError::Infeasible { solve } => write!(f, "the MILP is infeasible (solve {solve})"),
            MilpError::Solver(s) => write!(f, "HiGHS: {s}"),
            MilpError::NoArrival { solves, left_m } => write!(
                f,
                "the MILP did not reach the goal in {solves} solves ({left_m:.0} m left)"
            ),
        }
    }
}

impl std::error::Error for MilpError {}

/// Plans start → goal by receding-horizon MILP (module documentation).
pub fn plan(problem: &Problem, o: &MilpOptions) -> Result<MilpRoute, MilpError> {
    validate(o)?;
    let rings = if o.risk_weight > 0.0 {
        detection::rings(&problem.params)
    } else {
        Vec::new()
    };
    let (mut p, mut v) = (problem.start, problem.start_velocity);
    let mut route = StaticRoute {
        points: vec![p],
        times: vec![0.0],
    };
    let (mut velocities, mut stats, mut charge) = (Vec::new(), MilpStats::default(), 0.0);
    for solve in 0..o.max_solves {
        let t0 = Instant::now();
        let h = solve_horizon(problem, &rings, p, v, o).map_err(|e| match e {
            MilpError::Infeasible { .. } => MilpError::Infeasible { solve },
            e => e,
        })?;
        let dt_solve = t0.elapsed().as_secs_f64();
        stats.solves += 1;
        stats.solve_time_s += dt_solve;
        stats.slowest_solve_s = stats.slowest_solve_s.max(dt_solve);
        stats.max_binaries = stats.max_binaries.max(h.binaries);
        stats.timed_out += usize::from(h.timed_out);
        let keep = h.arrival.unwrap_or(o.commit);
        for k in 0..keep {
            let t = route.time() + o.dt;
            route.points.push(h.positions[k]);
            route.times.push(t);
            velocities.push(h.velocities[k]);
            charge += h.charges[k].max(0.0);
        }
        p = h.positions[keep - 1];
        v = h.velocities[keep - 1];
        if h.arrival.is_some() {
            // The arrival constraint holds to HiGHS's tolerance: the goal itself ends the route.
            if let Some(last) = route.points.last_mut() {
                *last = problem.goal;
            }
            return Ok(MilpRoute {
                route,
                velocities,
                detection_charge: charge,
                stats,
            });
        }
    }
    Err(MilpError::NoArrival {
        solves: o.max_solves,
        left_m: p.dist(problem.goal),
    })
}

fn validate(o: &MilpOptions) -> Result<(), MilpError> {
    let bad = |s: &str| Err(MilpError::BadOptions(s.to_string()));
    if !(o.dt.is_finite() && o.dt > 0.0) {
        return bad("Δt must be positive");
    }
    if o.horizon == 0 || o.commit == 0 || o.commit > o.horizon {
        return bad("need 1 ≤ commit ≤ horizon");
    }
    if o.keep_out_sides < 3 || o.bound_sides < 3 {
        return bad("polygons need at least 3 sides");
    }
    if !(o.time_weight >= 0.0 && o.risk_weight >= 0.0 && o.time_limit_s > 0.0) {
        return bad("weights must be ≥ 0 and the time limit > 0");
    }
    if !(0.0..1.0).contains(&o.mip_gap) {
        return bad("the MIP gap must lie in [0, 1)");
    }
    Ok(())
}

/// A disc to keep out of and/or a radar's rings, as one solve sees it.
struct Site {
    centre: Pt,
    /// Radius + clearance, if it is a keep-out disc.
    keep_out: Option<f64>,
    /// The rings the horizon can enter.
    rings: Vec<Ring>,
    /// Big-M: the farthest |u·(p − c)| within the horizon, plus the largest radius.
    big_m: f64,
}

/// The discs and radars one solve from `p0` with reach `reach` must consider.
fn sites(problem: &Problem, rings: &[Ring], p0: Pt, reach: f64) -> Vec<Site> {
    let mut out: Vec<Site> = Vec::new();
    let mut radars: Vec<Pt> = problem.radars.clone();
    for d in &problem.discs {
        let r = d.radius + problem.clearance;
        let radar = radars.iter().position(|c| c.dist(d.centre) < 1.0);
        let own_rings = radar.map_or(Vec::new(), |i| {
            radars.swap_remove(i);
            rings.to_vec()
        });
        out.extend(site(d.centre, Some(r), &own_rings, p0, reach));
    }
    out.extend(
        radars
            .iter()
            .filter_map(|&c| site(c, None, rings, p0, reach)),
    );
    out
}

fn site(centre: Pt, keep_out: Option<f64>, rings: &[Ring], p0: Pt, reach: f64) -> Option<Site> {
    let nearest = p0.dist(centre) - reach;
    let inner = keep_out.unwrap_or(0.0);
    let rings: Vec<Ring> = rings
        .iter()
        .filter(|g| g.radius > nearest && g.radius > inner)
        .copied()
        .collect();
    let keep_out = keep_out.filter(|&r| r > nearest);
    if keep_out.is_none() && rings.is_empty() {
        return None;
    }
    let outer = rings.iter().map(|g| g.radius).fold(inner, f64::max);
    Some(Site {
        centre,
        keep_out,
        rings,
        big_m: p0.dist(centre) + reach + outer + 1.0,
    })
}

/// One solve's answer.
struct Horizon {
    positions: Vec<Pt>,
    velocities: Vec<Pt>,
    /// The detection charge of each piece.
    charges: Vec<f64>,
    /// The step at which it is at the goal (1-based count of steps), if any.
    arrival: Option<usize>,
    binaries: usize,
    timed_out: bool,
}

/// The model of one solve: variables, constraints and objective terms.
struct Model {
    vars: ProblemVariables,
    constraints: Vec<Constraint>,
    objective: Expression,
    binaries: usize,
    /// Per piece: the detection charge's expression.
    charges: Vec<Expression>,
}

impl Model {
    fn binary(&mut self) -> Variable {
        self.binaries += 1;
        self.vars.add(variable().binary())
    }
}

/// Plans N steps from `p0`, `v0` (module documentation).
fn solve_horizon(
    problem: &Problem,
    rings: &[Ring],
    p0: Pt,
    v0: Pt,
    o: &MilpOptions,
) -> Result<Horizon, MilpError> {
    let (n, dt) = (o.horizon, o.dt);
    let reach = n as f64 * dt * problem.v_max;
    let mut m = Model {
        vars: ProblemVariables::new(),
        constraints: Vec::new(),
        objective: Expression::from(0.0),
        binaries: 0,
        charges: vec![Expression::from(0.0); n],
    };
    let vmax = problem.v_max;
    let vel: Vec<(Variable, Variable)> = (0..n)
        .map(|_| {
            let vx = m.vars.add(variable().min(-vmax).max(vmax));
            let vy = m.vars.add(variable().min(-vmax).max(vmax));
            (vx, vy)
        })
        .collect();
    let pos = dynamics(&mut m, p0, v0, &vel, problem, o);
    for s in sites(problem, rings, p0, reach) {
        site_constraints(&mut m, &s, &pos, problem, o);
    }
    for z in &problem.zones {
        zone_constraints(&mut m, z, problem.clearance, &pos, p0, reach);
    }
    let arrival = time_to_goal(&mut m, &pos, problem, p0, reach, o);
    solve(m, &pos, &vel, arrival, o)
}

/// Positions as expressions (p_0 constant), with the dynamics and the |v|, |a| bounds.
fn dynamics(
    m: &mut Model,
    p0: Pt,
    v0: Pt,
    vel: &[(Variable, Variable)],
    problem: &Problem,
    o: &MilpOptions,
) -> Vec<(Expression, Expression)> {
    let sides = o.bound_sides;
    let shrink = (std::f64::consts::PI / sides as f64).cos();
    let mut pos = vec![(Expression::from(p0.x), Expression::from(p0.y))];
    let (mut prev_x, mut prev_y) = (Expression::from(v0.x), Expression::from(v0.y));
    for &(vx, vy) in vel {
        let (px, py) = (m.vars.add(variable()), m.vars.add(variable()));
        let (lx, ly) = pos.last().cloned().unwrap_or_default();
        // eqs 1–2: p_k = p_{k−1} + Δt·v_k.
        m.constraints.push(constraint!(px == lx + o.dt * vx));
        m.constraints.push(constraint!(py == ly + o.dt * vy));
        for s in 0..sides {
            let u = direction(s, sides, 0.0);
            // eq. 6: inscribed polygons of |v| ≤ v_max and |v_k − v_{k−1}| ≤ a_max·Δt.
            m.constraints
                .push(constraint!(u.x * vx + u.y * vy <= problem.v_max * shrink));
            let dvx = vx - prev_x.clone();
            let dvy = vy - prev_y.clone();
            m.constraints.push(constraint!(
                u.x * dvx + u.y * dvy <= problem.a_max * o.dt * shrink
            ));
        }
        pos.push((Expression::from(px), Expression::from(py)));
        prev_x = Expression::from(vx);
        prev_y = Expression::from(vy);
    }
    pos
}

/// `u·(p − c)` as an expression.
fn along(u: Pt, p: &(Expression, Expression), c: Pt) -> Expression {
    u.x * p.0.clone() + u.y * p.1.clone() - u.dot(c)
}

/// Keep-out (eqs 4–5, both ends of each piece) and detection rings (eqs 13–18) of one site.
fn site_constraints(
    m: &mut Model,
    s: &Site,
    pos: &[(Expression, Expression)],
    problem: &Problem,
    o: &MilpOptions,
) {
    let sides = o.keep_out_sides;
    let big = s.big_m;
    let outer = s.rings.iter().map(|g| g.radius).fold(0.0, f64::max);
    let charge = detection::charge_per_second(&problem.params) * o.dt;
    for k in 0..pos.len() - 1 {
        let sigma: Vec<Variable> = (0..sides).map(|_| m.binary()).collect();
        let sum: Expression = sigma.iter().copied().map(Expression::from).sum();
        m.constraints.push(constraint!(sum == 1.0));
        let mid = (
            0.5 * (pos[k].0.clone() + pos[k + 1].0.clone()),
            0.5 * (pos[k].1.clone() + pos[k + 1].1.clone()),
        );
        let h = (!s.rings.is_empty()).then(|| m.vars.add(variable().min(0.0).max(outer)));
        for (i, &sg) in sigma.iter().enumerate() {
            let u = direction(i, sides, 0.0);
            if let Some(r) = s.keep_out {
                for p in [&pos[k], &pos[k + 1]] {
                    let e = along(u, p, s.centre);
                    m.constraints.push(constraint!(e >= r - big + big * sg));
                }
            }
            if let Some(h) = h {
                let e = along(u, &mid, s.centre);
                m.constraints.push(constraint!(h <= e + big - big * sg));
            }
        }
        let Some(h) = h else { continue };
        for g in &s.rings {
            let z = m.binary();
            // z = 1 when the piece's middle is inside ring ρ: h ≥ ρ·(1 − z).
            m.constraints
                .push(constraint!(h >= g.radius - g.radius * z));
            let term = charge * g.increment * z;
            m.charges[k] += term.clone();
            m.objective += o.risk_weight * term;
        }
    }
}

/// Keep-out of a no-fly polygon's convex hull, pushed out by the clearance (eqs 4–5).
fn zone_constraints(
    m: &mut Model,
    z: &super::Zone,
    clearance: f64,
    pos: &[(Expression, Expression)],
    p0: Pt,
    reach: f64,
) {
    let hull = convex_hull(&z.ring);
    let near = hull
        .iter()
        .map(|q| q.dist(p0))
        .fold(f64::INFINITY, f64::min);
    let span = hull.iter().map(|q| q.dist(hull[0])).fold(0.0, f64::max);
    if near - span - clearance > reach || hull.len() < 3 {
        return;
    }
    let edges: Vec<(Pt, f64)> = (0..hull.len())
        .map(|i| {
            let (a, b) = (hull[i], hull[(i + 1) % hull.len()]);
            let e = b.minus(a).scale(1.0 / a.dist(b));
            let normal = Pt::new(e.y, -e.x); // outward for a counter-clockwise hull
            (normal, normal.dot(a) + clearance)
        })
        .collect();
    for k in 0..pos.len() - 1 {
        let tau: Vec<Variable> = edges.iter().map(|_| m.binary()).collect();
        let sum: Expression = tau.iter().copied().map(Expression::from).sum();
        m.constraints.push(constraint!(sum == 1.0));
        for (&(normal, b), &t) in edges.iter().zip(&tau) {
            let big = (b - normal.dot(p0)).abs() + reach + 1.0;
            for p in [&pos[k], &pos[k + 1]] {
                let e = normal.x * p.0.clone() + normal.y * p.1.clone();
                m.constraints.push(constraint!(e >= b - big + big * t));
            }
        }
    }
}

/// The convex hull of `points`, counter-clockwise (Andrew's monotone chain).
pub fn convex_hull(points: &[Pt]) -> Vec<Pt> {
    let mut p: Vec<Pt> = points.to_vec();
    p.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
    p.dedup();
    if p.len() < 3 {
        return p;
    }
    let mut hull: Vec<Pt> = Vec::new();
    for pass in 0..2 {
        let start = hull.len();
        let iter: Box<dyn Iterator<Item = &Pt>> = if pass == 0 {
            Box::new(p.iter())
        } else {
            Box::new(p.iter().rev())
        };
        for &q in iter {
            while hull.len() >= start + 2 {
                let (a, b) = (hull[hull.len() - 2], hull[hull.len() - 1]);
                if b.minus(a).cross(q.minus(a)) <= 0.0 {
                    hull.pop();
                } else {
                    break;
                }
            }
            hull.push(q);
        }
        hull.pop();
    }
    hull
}

/// The time to the goal (module documentation) added to the objective with weight μ₁;
/// returns the arrival binaries b_1…b_N when the goal is within reach.
fn time_to_goal(
    m: &mut Model,
    pos: &[(Expression, Expression)],
    problem: &Problem,
    p0: Pt,
    reach: f64,
    o: &MilpOptions,
) -> Vec<Variable> {
    let (n, g) = (o.horizon, problem.goal);
    let big = p0.dist(g) + reach + 1.0;
    let v_eff = problem.v_max * (std::f64::consts::PI / o.bound_sides as f64).cos();
    let d = m.vars.add(variable().min(0.0));
    let in_reach = p0.dist(g) <= reach;
    let arrive: Vec<Variable> = if in_reach {
        (0..n).map(|_| m.binary()).collect()
    } else {
        Vec::new()
    };
    let last = &pos[n];
    let mut time = Expression::from(0.0);
    if in_reach {
        let never = m.binary();
        let sum: Expression = arrive
            .iter()
            .copied()
            .map(Expression::from)
            .sum::<Expression>()
            + never;
        m.constraints.push(constraint!(sum == 1.0));
        for (k, &b) in arrive.iter().enumerate() {
            let (x, y) = (&pos[k + 1].0, &pos[k + 1].1);
            m.constraints
                .push(constraint!(x.clone() - g.x <= big - big * b));
            m.constraints
                .push(constraint!(g.x - x.clone() <= big - big * b));
            m.constraints
                .push(constraint!(y.clone() - g.y <= big - big * b));
            m.constraints
                .push(constraint!(g.y - y.clone() <= big - big * b));
            time += ((k + 1) as f64 * o.dt) * b;
        }
        time += (n as f64 * o.dt) * never;
        for s in 0..o.bound_sides {
            let u = direction(s, o.bound_sides, 0.0);
            let e = along(u, last, g);
            m.constraints.push(constraint!(d >= e - big + big * never));
        }
    } else {
        for s in 0..o.bound_sides {
            let u = direction(s, o.bound_sides, 0.0);
            let e = along(u, last, g);
            m.constraints.push(constraint!(d >= e));
        }
    }
    time += d / v_eff;
    m.objective += o.time_weight * time;
    arrive
}

/// Solves the model with HiGHS and reads the horizon back.
fn solve(
    m: Model,
    pos: &[(Expression, Expression)],
    vel: &[(Variable, Variable)],
    arrive: Vec<Variable>,
    o: &MilpOptions,
) -> Result<Horizon, MilpError> {
    let Model {
        vars,
        constraints,
        objective,
        binaries,
        charges,
    } = m;
    let model = vars
        .minimise(objective)
        .using(good_lp::highs)
        .set_option("output_flag", false)
        .set_time_limit(o.time_limit_s)
        .set_option("mip_rel_gap", o.mip_gap)
        .with_all(constraints);
    let sol = model.solve().map_err(|e| match e {
        ResolutionError::Infeasible => MilpError::Infeasible { solve: 0 },
        e => MilpError::Solver(e.to_string()),
    })?;
    let timed_out = matches!(sol.status(), SolutionStatus::TimeLimit);
    let at = |e: &Expression| sol.eval(e.clone());
    let arrival = arrive
        .iter()
        .position(|&b| sol.value(b) > 0.5)
        .map(|k| k + 1);
    Ok(Horizon {
        positions: pos[1..]
            .iter()
            .map(|p| Pt::new(at(&p.0), at(&p.1)))
            .collect(),
        velocities: vel
            .iter()
            .map(|&(x, y)| Pt::new(sol.value(x), sol.value(y)))
            .collect(),
        charges: charges.iter().map(at).collect(),
        arrival,
        binaries,
        timed_out,
    })
}
