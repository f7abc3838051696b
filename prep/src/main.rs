//! `skyroute`: the ground tool's command line.

use clap::{Parser, Subcommand};
use skyroute_prep::build::{build, BuildOptions};
use skyroute_prep::scenario;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

/// Scenarios in, preprocessed networks out.
#[derive(Parser)]
#[command(name = "skyroute", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Build a scenario's network and write it as a network image.
    Build {
        /// The scenario (GeoJSON).
        scenario: PathBuf,
        /// Where to write the network.
        #[arg(short, long)]
        output: PathBuf,
        /// Override planner.sample_spacing_m.
        #[arg(long)]
        sample_spacing: Option<f32>,
        /// Override planner.neighbour_radius_m.
        #[arg(long)]
        neighbour_radius: Option<f32>,
        /// Check edges with the paper's discretisation (planner.arc_step_m) instead of exactly.
        #[arg(long)]
        discretised: bool,
        /// Side of a grid-index cell, metres (default: twice the turn radius).
        #[arg(long)]
        grid_cell: Option<f32>,
    },
}

fn run(cli: Cli) -> Result<(), Box<dyn std::error::Error>> {
    match cli.command {
        Command::Build { scenario: path, output, sample_spacing, neighbour_radius, discretised, grid_cell } => {
            let t0 = Instant::now();
            let s = scenario::load(&path)?;
            let options = BuildOptions { sample_spacing_m: sample_spacing, neighbour_radius_m: neighbour_radius, discretised, grid_cell_m: grid_cell };
            let progress = |done: usize, total: usize| {
                if total >= 1024 {
                    eprint!("\rconnecting samples: {done}/{total}");
                    if done == total {
                        eprintln!();
                    }
                }
            };
            let built = build(&s, &options, &progress)?;
            std::fs::write(&output, &built.bytes).map_err(|e| format!("{}: {e}", output.display()))?;
            let r = &built.roadmap;
            println!(
                "built {}: {} vertices, {} edges ({} examined, {} check), {} bytes, {:.2} s -> {}",
                path.display(),
                r.vertices.len(),
                r.edges.len(),
                r.edges_examined,
                if discretised { "discretised" } else { "exact" },
                built.bytes.len(),
                t0.elapsed().as_secs_f64(),
                output.display()
            );
            Ok(())
        }
    }
}

fn main() -> ExitCode {
    match run(Cli::parse()) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("skyroute: {e}");
            ExitCode::FAILURE
        }
    }
}
