//! `skyroute demo`: the niendorf-urban scenario, built into the binary, built, planned and
//! drawn in a folder of the user's choice.

use crate::build::BuildOptions;
use crate::build_cli::build_command;
use crate::plan_cli::{plan_command, CliResult, PlanRequest};
use crate::route_mission::MissionOutput;
use std::path::Path;

/// The scenario `skyroute demo` runs, built into the binary.
const DEMO_SCENARIO: &str = include_str!("../demo/niendorf-urban.geojson");

/// `skyroute demo`: build, plan and render the embedded niendorf-urban scenario.
pub fn demo_command(dir: &Path) -> CliResult {
    std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let scenario_path = dir.join("niendorf-urban.geojson");
    std::fs::write(&scenario_path, DEMO_SCENARIO)
        .map_err(|e| format!("{}: {e}", scenario_path.display()))?;
    let (network, route, picture) = (
        dir.join("niendorf-urban.bin"),
        dir.join("route.json"),
        // A PNG, or an SVG from a tool built without its `png` feature.
        dir.join(if cfg!(feature = "png") {
            "niendorf-urban.png"
        } else {
            "niendorf-urban.svg"
        }),
    );
    build_command(
        &scenario_path,
        &network,
        &BuildOptions::default(),
        false,
        None,
        &[],
    )?;
    plan_command(&PlanRequest {
        network: &network,
        scenario: &scenario_path,
        popups: &[],
        start: None,
        goal: None,
        flown_m: None,
        last_overflight: None,
        scenario_popups: true,
        connect_radius_m: None,
        turn_rule: None,
        free_headings: Default::default(),
        shortcuts: None,
        weather: None,
        hull_repair: false,
        output: &route,
        mode: None,
        threat_weight: None,
        threats: &[],
        popup_appears: &[],
        limits: crate::ruz::cli::LIMITS,
        mission: MissionOutput::default(),
    })?;
    let request = crate::render::RenderRequest {
        network,
        mode: None,
        routes: vec![route],
        scenario: Some(scenario_path),
        popups: Vec::new(),
        output: picture.clone(),
        png: None,
        map_width_px: 1200.0,
        no_edges: false,
        area: None,
    };
    crate::render::render(&request)?;
    println!(
        "demo: open {} to see the network and the planned route",
        picture.display()
    );
    Ok(())
}
