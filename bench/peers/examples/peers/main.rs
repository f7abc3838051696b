//! `peers`: the Rust side of `bench/compare.sh`. Each subcommand writes one input the peers
//! read, or times skyroute (and petgraph) in-process and writes JSON:
//!
//! ```text
//! peers map NET.bin OUT.txt                      the map for the C++ program; prints counts
//! peers queries NET.bin COUNT SEED OUT.txt       start/goal pose pairs in free space, >= 1 km apart
//! peers plan NET.bin QUERIES.txt OUT.json [REPS] time Planner::plan (A*) per query, in-process
//! peers check NET.bin ROUTES.txt OUT.json        OMPL's routes checked with skyroute's exact predicates
//! peers validity NET.bin COUNT SEED OUT.txt      sample points with skyroute's verdicts
//! peers pairs COUNT SEED RADIUS OUT.bin          random Dubins pose pairs (f64, f32-exact)
//! peers dubins PAIRS.bin RADIUS OUT.bin OUT.json skyroute's Dubins shortest path over the pairs
//! peers sssp NET.bin SOURCES SEED DIST.bin OUT.json  single-source distances: ours and petgraph
//! ```
//!
//! Run it with a large stack (it does so itself: the planner lives on a 256 MiB thread).

mod dubins;
mod inputs;
mod plan;
mod sssp;

use std::process::ExitCode;

/// The command line, parsed by position.
pub struct Args(Vec<String>);

impl Args {
    /// Argument `i` (after the subcommand), or an error naming what is missing.
    pub fn get(&self, i: usize, what: &str) -> Result<&str, String> {
        self.0
            .get(i)
            .map(String::as_str)
            .ok_or_else(|| format!("missing argument {}: {what}", i + 1))
    }

    /// Argument `i` parsed as `T`.
    pub fn parse<T: std::str::FromStr>(&self, i: usize, what: &str) -> Result<T, String> {
        let s = self.get(i, what)?;
        s.parse()
            .map_err(|_| format!("argument {} ({what}): cannot parse {s:?}", i + 1))
    }

    /// Argument `i` parsed as `T`, or `default` when absent.
    pub fn parse_or<T: std::str::FromStr>(
        &self,
        i: usize,
        what: &str,
        default: T,
    ) -> Result<T, String> {
        if self.0.len() > i {
            self.parse(i, what)
        } else {
            Ok(default)
        }
    }
}

/// Reads a whole file, naming it on error.
pub fn read(path: &str) -> Result<Vec<u8>, String> {
    std::fs::read(path).map_err(|e| format!("{path}: {e}"))
}

/// Writes a whole file, naming it on error.
pub fn write(path: &str, bytes: &[u8]) -> Result<(), String> {
    std::fs::write(path, bytes).map_err(|e| format!("{path}: {e}"))
}

/// Writes `value` as pretty JSON.
pub fn write_json(path: &str, value: &serde_json::Value) -> Result<(), String> {
    let text = serde_json::to_string_pretty(value).map_err(|e| e.to_string())?;
    write(path, text.as_bytes())
}

/// Loads and validates a network image's bytes.
pub fn network(bytes: &[u8]) -> Result<skyroute::Network<'_>, String> {
    skyroute::Network::from_bytes(bytes).map_err(|e| format!("network: {e:?}"))
}

fn run(cmd: &str, args: &Args) -> Result<(), String> {
    match cmd {
        "map" => inputs::map(args),
        "queries" => inputs::queries(args),
        "validity" => inputs::validity(args),
        "pairs" => inputs::pairs(args),
        "plan" => plan::plan(args),
        "check" => plan::check(args),
        "dubins" => dubins::dubins(args),
        "sssp" => sssp::sssp(args),
        _ => Err(format!(
            "unknown subcommand {cmd:?}: map, queries, validity, pairs, plan, check, dubins, sssp"
        )),
    }
}

fn main() -> ExitCode {
    let mut all: Vec<String> = std::env::args().skip(1).collect();
    if all.is_empty() {
        eprintln!("usage: peers SUBCOMMAND ARGS... (see the source's header)");
        return ExitCode::from(2);
    }
    let cmd = all.remove(0);
    let args = Args(all);
    let worker = std::thread::Builder::new()
        .stack_size(256 << 20)
        .spawn(move || run(&cmd, &args));
    match worker.map(|h| h.join()) {
        Ok(Ok(Ok(()))) => ExitCode::SUCCESS,
        Ok(Ok(Err(e))) => {
            eprintln!("peers: {e}");
            ExitCode::FAILURE
        }
        _ => {
            eprintln!("peers: the worker thread failed");
            ExitCode::FAILURE
        }
    }
}
