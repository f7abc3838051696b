//! Plans the `roadmap` firmware's query on the host, for profiling: reads the fixture the
//! firmware embeds (`firmware-example/fixture/`: `network.bin` and the constants of
//! `query.rs`), adds its pop-up and plans its query `CYCLES` times with the fixture's
//! connection settings, as the firmware does, and prints each phase's work and wall time.
//!
//! ```text
//! plan_profile [FIXTURE_DIR] [--cycles N]
//! valgrind --tool=callgrind --dump-before='*phase_boundary*' target/release/plan_profile
//! ```
//!
//! Every phase boundary calls [`phase_boundary`] (never inlined), so callgrind's
//! `--dump-before` writes one profile per phase: the instructions between two boundaries are
//! one phase's. `scripts/profile-urban.sh` runs that and prints the table.

use skyroute::planner::{Phase, PlannerConfig, TurnRule, Work};
use skyroute::{Goal, Planner, Popup, Pose, Query, Search, Vec2};
use std::hint::black_box;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

/// Generous capacities: they only gate `load` (the fixture's own are for the firmware's RAM).
type HostPlanner<'n> = Planner<'n, 4096, 65536, 4, 128>;

/// The constants of a fixture's `query.rs` that the query needs.
struct Fixture {
    config: PlannerConfig,
    start: Pose,
    goal: Goal,
    popup: (f32, f32, f32),
    expected_length: f32,
    expected_primitives: u32,
}

/// The text of `pub const NAME ... ;` in `source`.
fn constant<'s>(source: &'s str, name: &str) -> Result<&'s str, String> {
    let key = format!("pub const {name}:");
    let at = source
        .find(&key)
        .ok_or(format!("query.rs: no constant {name}"))?;
    let rest = &source[at + key.len()..];
    let end = rest
        .find(';')
        .ok_or(format!("query.rs: {name} has no end"))?;
    Ok(&rest[..end])
}

/// The `f32` literals (`1.5_f32`, `-2.0_f32`) in `text`, in order.
fn floats(text: &str) -> Result<Vec<f32>, String> {
    text.split(|c: char| !(c.is_ascii_alphanumeric() || c == '.' || c == '-' || c == '_'))
        .filter_map(|token| token.strip_suffix("_f32"))
        .map(|x| x.parse::<f32>().map_err(|e| format!("{x}: {e}")))
        .collect()
}

/// The value after `field:` in `text`, up to the next comma or closing brace.
fn field<'s>(text: &'s str, field: &str) -> Result<&'s str, String> {
    let key = format!("{field}:");
    let at = text
        .find(&key)
        .ok_or(format!("query.rs: no field {field}"))?;
    let rest = &text[at + key.len()..];
    let end = rest.find([',', '}']).unwrap_or(rest.len());
    Ok(rest[..end].trim())
}

fn parse_fixture(source: &str) -> Result<Fixture, String> {
    let config = constant(source, "CONFIG")?;
    let int = |f: &str| -> Result<u64, String> {
        let v = field(config, f)?;
        v.parse::<u64>()
            .map_err(|e| format!("CONFIG.{f} {v:?}: {e}"))
    };
    let radius = field(config, "connect_radius_m")?;
    let connect_radius_m = if radius == "f32::INFINITY" {
        f32::INFINITY
    } else {
        *floats(radius)?.first().ok_or("CONFIG.connect_radius_m")?
    };
    let config = PlannerConfig {
        start_candidates: int("start_candidates")? as u8,
        goal_candidates: int("goal_candidates")? as u8,
        connect_radius_m,
        free_goal_headings: int("free_goal_headings")? as u16,
        turn_rule: if field(config, "turn_rule")?.ends_with("SharedEqually") {
            TurnRule::SharedEqually
        } else {
            TurnRule::Paper
        },
    };
    let start = floats(constant(source, "START")?)?;
    let goal_text = constant(source, "GOAL")?;
    let goal = floats(goal_text)?;
    let popup = floats(constant(source, "POPUP")?)?;
    let length = floats(constant(source, "EXPECTED_LENGTH")?)?;
    let primitives = constant(source, "EXPECTED_PRIMITIVES")?;
    let ([x, y, h], [gx, gy, ..], [px, py, pr], [l]) = (
        start.as_slice(),
        goal.as_slice(),
        popup.as_slice(),
        length.as_slice(),
    ) else {
        return Err("query.rs: START, GOAL, POPUP or EXPECTED_LENGTH malformed".into());
    };
    Ok(Fixture {
        config,
        start: Pose::new(*x, *y, *h),
        goal: Goal {
            position: Vec2::new(*gx, *gy),
            heading: field(goal_text, "heading")?
                .starts_with("Some")
                .then(|| goal.get(2).copied())
                .flatten(),
        },
        popup: (*px, *py, *pr),
        expected_length: *l,
        expected_primitives: primitives
            .rsplit(' ')
            .next()
            .unwrap_or_default()
            .trim()
            .parse()
            .map_err(|e| format!("EXPECTED_PRIMITIVES: {e}"))?,
    })
}

/// Marks a phase boundary for callgrind's `--dump-before` (see the module documentation).
#[inline(never)]
fn phase_boundary(phase: Phase) {
    black_box(phase);
}

/// One phase's work and wall time, summed over the cycles.
#[derive(Default, Clone, Copy)]
struct PhaseCost {
    work: u64,
    nanos: u128,
}

const PHASES: [Phase; 6] = [
    Phase::CheckFree,
    Phase::ConnectStart,
    Phase::ConnectGoal,
    Phase::ConnectDirect,
    Phase::Search,
    Phase::Route,
];

fn run(dir: &Path, cycles: u32) -> Result<(), String> {
    let read = |name: &str| {
        let path = dir.join(name);
        std::fs::read(&path).map_err(|e| format!("{}: {e}", path.display()))
    };
    let bytes = read("network.bin")?;
    let source = String::from_utf8(read("query.rs")?).map_err(|e| format!("query.rs: {e}"))?;
    let fixture = parse_fixture(&source)?;
    let mut planner: Box<HostPlanner<'_>> = Box::new(Planner::new());
    planner.load(&bytes).map_err(|e| format!("load: {e}"))?;
    planner.set_config(fixture.config);
    let (x, y, r) = fixture.popup;
    planner
        .add_popup(Popup::Circle {
            centre: Vec2::new(x, y),
            radius: r,
        })
        .map_err(|e| format!("add_popup: {e}"))?;
    let query = Query {
        start: fixture.start,
        goal: fixture.goal,
        search: Search::Dijkstra,
    };
    let budget = planner.worst_case_work();
    let mut costs = [PhaseCost::default(); PHASES.len()];
    let mut last = Work::default();
    for _ in 0..cycles {
        let mut open: Option<(usize, Instant, u64)> = None;
        let summary = planner
            .plan_observed(&query, budget, &mut |phase, work| {
                phase_boundary(phase);
                let now = Instant::now();
                if let Some((i, t, w)) = open.take() {
                    costs[i].work += work.total() - w;
                    costs[i].nanos += now.duration_since(t).as_nanos();
                }
                if let Some(i) = PHASES.iter().position(|p| *p == phase) {
                    open = Some((i, now, work.total()));
                }
                last = *work;
            })
            .map_err(|e| format!("plan: {e}"))?;
        if summary.length != fixture.expected_length
            || summary.primitives != fixture.expected_primitives
        {
            return Err(format!(
                "route {} m, {} primitives; the fixture expects {} m, {}",
                summary.length,
                summary.primitives,
                fixture.expected_length,
                fixture.expected_primitives
            ));
        }
    }
    println!(
        "route {} m, {} primitives (as the fixture), work {} of {budget}: {last:?}",
        fixture.expected_length,
        fixture.expected_primitives,
        last.total()
    );
    println!("{:<14} {:>10} {:>12}", "phase", "work", "µs / plan");
    for (phase, cost) in PHASES.iter().zip(costs) {
        println!(
            "{:<14} {:>10} {:>12.1}",
            format!("{phase:?}"),
            cost.work / cycles as u64,
            cost.nanos as f64 / 1e3 / cycles as f64
        );
    }
    Ok(())
}

fn main() -> ExitCode {
    let mut dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../firmware-example/fixture");
    let mut cycles = 3;
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        match a.as_str() {
            "--cycles" => match args.next().and_then(|n| n.parse().ok()) {
                Some(n) if n > 0 => cycles = n,
                _ => {
                    eprintln!("plan_profile: --cycles needs a positive count");
                    return ExitCode::from(2);
                }
            },
            _ => dir = PathBuf::from(a),
        }
    }
    match run(&dir, cycles) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("plan_profile: {}: {e}", dir.display());
            ExitCode::FAILURE
        }
    }
}
