//! `skyroute build`: a scenario in, its network out, with a progress bar while the builder
//! connects the samples and a one-line summary of what was built.

use crate::build::{build, BuildOptions};
use crate::output::{refuse_overwriting_inputs, write_atomically};
use crate::plan_cli::{load_scenario, CliResult};
use crate::roadmap::Sagitta;
use crate::scenario::Mode;
use indicatif::{ProgressBar, ProgressStyle};
use std::path::Path;
use std::time::Instant;

/// `skyroute build`. `mode_options` names the options given that apply to one mode only, with
/// that mode: each is refused on a scenario of another mode.
pub fn build_command(
    path: &Path,
    output: &Path,
    options: &BuildOptions,
    hull_repair: bool,
    mode: Option<Mode>,
    mode_options: &[(&str, Mode)],
) -> CliResult {
    let t0 = Instant::now();
    let s = load_scenario(path, hull_repair, mode)?;
    if let Some((option, applies_to)) = mode_options
        .iter()
        .find(|(_, applies_to)| *applies_to != s.planner.mode)
    {
        return Err(format!(
            "{}: {option} applies to {} networks, and this is a {} scenario",
            path.display(),
            applies_to.as_str(),
            s.planner.mode.as_str()
        )
        .into());
    }
    let mut inputs = vec![path];
    inputs.extend(crate::provenance::dem_path(&s));
    refuse_overwriting_inputs(output, &inputs)?;
    let bar = ProgressBar::new(0).with_style(
        ProgressStyle::with_template("{msg} {bar:40} {pos}/{len} samples ({eta} left)")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    bar.set_message("connecting");
    let progress = |done: usize, total: usize| {
        bar.set_length(total as u64);
        bar.set_position(done as u64);
    };
    let built = build(&s, options, &progress)?;
    bar.finish_and_clear();
    write_atomically(output, &built.bytes)?;
    if let Some(g) = &built.terrain {
        let st = &g.stats;
        println!(
            "built {}: terrain graph {} nodes, {} edges ({} corners, {} pairs tested), elevation \
             grid {} x {} of {:.2} m, {} blocked at the scenario's altitude, {} bytes, {:.2} s -> {}",
            path.display(),
            g.nodes.len(),
            g.edges.len(),
            st.corners,
            st.pairs_tested,
            g.grid.cols,
            g.grid.rows,
            g.grid.cell,
            st.blocked_cells,
            built.bytes.len(),
            t0.elapsed().as_secs_f64(),
            output.display()
        );
        return Ok(());
    }
    if let Some(n) = &built.landmark {
        let st = &n.stats;
        println!(
            "built {}: landmark network {} overflights, {} edges between them ({} pairs, {} basic \
             networks, {} line elements, {} searches; {} directions out of range, {} chains over \
             range, {} unconnected), {} start and {} goal edges, {} bytes, {:.2} s -> {}",
            path.display(),
            n.vertices.len(),
            n.edges.len(),
            st.pairs,
            st.basic_networks,
            st.line_elements,
            st.searches,
            st.directions_out_of_range,
            st.edges_over_range,
            st.unconnected,
            n.start.as_ref().map_or(0, |x| x.edges.len()),
            n.goal.as_ref().map_or(0, |x| x.edges.len()),
            built.bytes.len(),
            t0.elapsed().as_secs_f64(),
            output.display()
        );
        return Ok(());
    }
    if let Some(v) = &built.voronoi {
        println!(
            "built {}: Voronoi graph of {} threats: {} vertices, {} edges (each stored both ways), \
             box {:.1} x {:.1} km, k = {}, {} bytes, {:.2} s -> {}",
            path.display(),
            v.threats.len(),
            v.vertices.len(),
            v.edges.len(),
            (v.bounds.max.x - v.bounds.min.x) / 1000.0,
            (v.bounds.max.y - v.bounds.min.y) / 1000.0,
            v.threat_weight,
            built.bytes.len(),
            t0.elapsed().as_secs_f64(),
            output.display()
        );
        return Ok(());
    }
    let Some(r) = &built.roadmap else {
        return Err("the build produced no network".into());
    };
    println!(
        "built {}: {} vertices, {} edges ({} examined, {}), {} bytes, {:.2} s -> {}",
        path.display(),
        r.vertices.len(),
        r.edges.len(),
        r.edges_examined,
        match options.discretised {
            Some(Sagitta::Added) => "discretised check",
            Some(Sagitta::InClearance) => "discretised check, the paper's reading",
            None => "exact check",
        },
        built.bytes.len(),
        t0.elapsed().as_secs_f64(),
        output.display()
    );
    if let Some(line) = crate::roadmap::vertical::summary(r) {
        println!("  {line}");
        if !s.popups.is_empty() {
            println!(
                "  scenario pop-ups: {}; `plan` applies them with their heights, and no bypass alternatives are \
                 stored (`plan --popup-appears` plans them on the ground)",
                s.popups.len()
            );
        }
    }
    Ok(())
}
