//! `skyroute`: the ground tool's command line.

use clap::{Parser, Subcommand};
use skyroute_prep::build::BuildOptions;
use skyroute_prep::build_cli::build_command;
use skyroute_prep::cli_values::*;
use skyroute_prep::demo::demo_command;
use skyroute_prep::init::init_command;
use skyroute_prep::plan_cli::{plan_command, CliResult, NoRoute, PlanRequest};
use skyroute_prep::roadmap::Sagitta;
use skyroute_prep::route_mission::{Autopilot, MissionOutput};
use skyroute_prep::ruz::cli::plan_decided_command;
use skyroute_prep::ruz::study_cli::{montecarlo_command, MonteCarloRequest};
use skyroute_prep::scenario::Mode;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

/// Exit codes, for `--help` and the README.
const EXIT_CODES: &str = "Exit codes:
  0  success
  1  bad input: the message names the file, and for scenarios the feature and the field
     (a corrupt network, a scenario that does not match its network, an endpoint or pop-up
     off the network's map, a start inside a no-fly zone, an output path naming an input,
     in a missing folder or with another format's extension, a build parameter beyond its
     limits: see `skyroute build --help`)
  2  usage: an unknown option or a malformed value (clap's message)
  3  no route exists: the message names the leg and why (for a landmark scenario, the proof
     when the scenario's numbers alone rule every route out)
Outputs are written to a temporary file and renamed, so a failure leaves no partial file.";

/// The builder's limits, for `build --help` and the README.
const BUILD_LIMITS: &str =
    "Limits (each checked before the allocation it bounds; exit code 1, and the
message names the file and the field, or the option):
  scenario files: at most 16 MiB (read no further), 100 000 vertices a no-fly ring,
    500 waypoints (each free-heading waypoint costs `plan` about 0.25 s on the urban network)
  roadmap: the scenario's positions span at most 1000 km a side in its local frame;
    sample spacing at least 1 m; at most 1 048 576 sample candidates (2 x area / spacing^2);
    at most 33 554 432 neighbour pairs, estimated as (candidates / 2)^2 x
    min(1, pi x neighbour radius^2 / area)
  landmark: the landmarks, start and goal span at most 1000 km a side
  the grid index has at most 4 194 304 cells (its cell: --grid-cell, by default twice
    the turn radius for roadmaps, 4000 m for terrain, 2000 m for landmarks)
  the network has at least one vertex
Option values must be finite numbers, lengths positive (--node-spacing and --node-margin
may be 0); a malformed value is a usage error, exit code 2. An option of one mode (roadmap:
--sample-spacing, --neighbour-radius, --discretised; terrain: --node-spacing, --max-edge,
--node-margin, --altitude-levels; landmark: --landmark-ranges) given for a scenario of
another mode is refused, exit code 1.";

/// `skyroute plan`'s arguments.
#[derive(clap::Args)]
struct PlanArgs {
    /// The network image.
    network: PathBuf,
    /// The scenario the network was built from, whose start, waypoints and goal to visit.
    #[arg(long)]
    scenario: PathBuf,
    /// A circular pop-up obstacle, `LON,LAT,RADIUS_M[,HEIGHT_M]` (repeatable; HEIGHT_M, its top,
    /// on a three-dimensional roadmap only: without it no altitude clears the pop-up).
    #[arg(long, value_parser = parse_tall_popup)]
    popup: Vec<PopupArg>,
    /// Plan from `LON,LAT,HEADING_DEG` (compass heading) instead of the scenario's start:
    /// re-planning from where the aircraft is. On a landmark network the core joins it to
    /// the overflights one flyable Hermite piece reaches within the range left
    /// (--flown-m, --last-overflight).
    #[arg(long, value_parser = parse_start, allow_hyphen_values = true)]
    start: Option<(f64, f64, f64)>,
    /// Plan to `LON,LAT[,HEADING_DEG]` (compass heading; none: any) instead of the scenario's
    /// goal: a new destination in flight. On a landmark network the core joins it from the
    /// overflights whose range it lies within, by one flyable Hermite piece each.
    #[arg(long, value_parser = parse_goal, allow_hyphen_values = true)]
    goal: Option<(f64, f64, Option<f64>)>,
    /// Landmark networks, with --start: metres flown since the last overflight (default 0).
    /// The range left is the last overflight's d_max x q less this.
    #[arg(long, value_parser = parse_non_negative)]
    flown_m: Option<f64>,
    /// Landmark networks, with --start: `NAME,HEADING_DEG`, the landmark overflown last and
    /// the compass heading it was crossed at (its range: the stored direction nearest that
    /// heading, in the weather planned). Default: the scenario's start, whose `dist_m` is
    /// the range.
    #[arg(long, value_parser = parse_last_overflight)]
    last_overflight: Option<(String, f64)>,
    /// Leave the scenario's `popup` features out (plan the nominal route); the route file
    /// says so.
    #[arg(long)]
    no_scenario_popups: bool,
    /// Connect each leg's start and goal only to vertices within this many metres. By
    /// default the network's radius (1000 m for roadmaps, unbounded for terrain) is
    /// widened to the 32 nearest vertices however far when an end does not connect.
    #[arg(long, value_parser = parse_radius)]
    connect_radius: Option<f32>,
    /// Terrain networks: how the turns at the two ends of a straight share it. `paper`
    /// (the default): the paper's equations 1–2, the two cuts together within the
    /// straight's length (exact; the search needs one state per transition of the graph,
    /// `skyroute info`); `shared-equally`: each cut within half of it (stricter: fewer
    /// routes; one state per edge, what the small firmware runs).
    #[arg(long, value_parser = parse_turn_rule)]
    turn_rule: Option<skyroute::TurnRule>,
    /// How a waypoint without a heading gets one: `cheapest` (the default: every 10° tried,
    /// the cheapest mission kept) or `paper` (Niendorf et al., roadmap networks only: the
    /// heading with the most Dubins paths clear of every zone and pop-up to the network's
    /// vertices within the connect or neighbour radius, among those with one from them, fixed
    /// before the legs are planned).
    #[arg(long, value_parser = parse_free_headings, default_value = "cheapest")]
    free_headings: skyroute_prep::mission::FreeHeadingRule,
    /// Roadmap and terrain networks: the shortcut pass that post-processes each leg, before
    /// heading smoothing. `best` (the default): the shortest chain through any subset of the
    /// leg's junctions, whose shortcuts are never longer than the greedy pass's; n(n-1)/2 pairs
    /// examined for a leg of n paths. `greedy`: Niendorf et al.'s forward pass, one pair per
    /// junction; the default with `--popup-appears`, since the stored alternatives were
    /// planned with it.
    #[arg(long, value_parser = parse_shortcuts)]
    shortcuts: Option<skyroute_prep::mission::Shortcuts>,
    /// Weather for landmark networks, a name from the scenario's `weather` (default: its
    /// first); roadmap and terrain networks have none.
    #[arg(long)]
    weather: Option<String>,
    /// Read the scenario with self-intersecting no-fly polygons replaced by their hulls (as
    /// `build --hull-repair`).
    #[arg(long)]
    hull_repair: bool,
    /// Where to write the route: `.json` the detailed route file (local frame, every
    /// primitive), `.geojson` RFC 7946 GeoJSON (lon/lat, a feature per leg and pop-up),
    /// `.plan` a QGroundControl plan (mission, no-fly zones as geofence, goal as rally
    /// point), `.waypoints` the MAVLink QGC WPL 110 text format, `.kml` KML for Google Earth
    /// (docs/AUTOPILOTS.md).
    #[arg(short, long)]
    output: PathBuf,
    /// Take the scenario as this mode, as the network was built (`build --mode`).
    #[arg(long, value_parser = parse_mode)]
    mode: Option<Mode>,
    /// Voronoi networks: the weight k of length against exposure, in [0, 1] (default: the
    /// scenario's planner.threat_weight, or 0.5). 1 flies the shortest route, 0 the least
    /// exposed. Roadmap networks: plans on the ground instead of with the onboard core (which
    /// does not weigh exposure): Dijkstra over the roadmap's Dubins edges with cost
    /// k·L + (1 − k)·exposure to the scenario's threats (three-point rule), ends joined by
    /// Dubins paths to the nearest vertices, no post-processing.
    #[arg(long, value_parser = parse_weight)]
    threat_weight: Option<f32>,
    /// Voronoi networks: a radar that popped up in flight, `LON,LAT,RADIUS_M` (repeatable;
    /// RADIUS_M is its exposure's reference distance, like a scenario threat's).
    #[arg(long, value_parser = parse_threat)]
    threat: Vec<(f64, f64, f64)>,
    /// Roadmap and terrain networks: the scenario's pop-up NAME may appear, with its
    /// `probability` (repeatable; Ruz et al.). With this option only the named pop-ups are
    /// considered and the scenario's other pop-ups are left out: for each named one, 3
    /// bypass alternatives that never enter its disc are planned and scored by risk, time
    /// and fuel, one per pop-up is chosen (least total risk with the mean time and fuel
    /// factors within --time-limit and --fuel-limit), and the route flies every chosen
    /// alternative. The route file records the alternatives and the choice; when no choice
    /// meets the limits, exit code 3 names the tightest.
    #[arg(long, value_name = "NAME", conflicts_with_all = ["popup", "no_scenario_popups"])]
    popup_appears: Vec<String>,
    /// With --popup-appears: the largest mean time factor f_t = 1 − τ/T (τ the nominal
    /// route's time, T the alternative's).
    #[arg(long, default_value_t = skyroute_prep::ruz::cli::TIME_LIMIT, value_parser = parse_limit)]
    time_limit: f32,
    /// With --popup-appears: the largest mean fuel factor (mean normalised turn effort).
    #[arg(long, default_value_t = skyroute_prep::ruz::cli::FUEL_LIMIT, value_parser = parse_limit)]
    fuel_limit: f32,
    /// `.plan` outputs: the flight stack, `px4` (firmwareType 12) or `ardupilot` (3).
    #[arg(long, default_value = "px4", value_parser = parse_autopilot)]
    autopilot: Autopilot,
    /// `.plan`, `.waypoints` and `.kml` outputs: the altitude, metres above home (default
    /// 100); on a terrain network metres above mean sea level (default the network's
    /// altitude).
    #[arg(long = "altitude", value_parser = parse_altitude)]
    altitude_m: Option<f64>,
}

/// `skyroute init`'s arguments.
#[derive(clap::Args)]
struct InitArgs {
    /// Where to write the scenario.
    output: PathBuf,
    /// The mode: roadmap (default), landmark, terrain (needs --dem) or voronoi.
    #[arg(long, value_parser = parse_mode, default_value = "roadmap")]
    mode: Mode,
    /// Terrain mode: the DEM (ESRI ASCII grid or GeoTIFF) the template flies over.
    #[arg(long)]
    dem: Option<PathBuf>,
    /// Overwrite an existing file.
    #[arg(long)]
    force: bool,
}

/// `skyroute init`: writes the template, prints what it wrote.
fn init(a: &InitArgs) -> CliResult {
    println!(
        "{}",
        init_command(&a.output, a.mode, a.dem.as_deref(), a.force)?
    );
    Ok(())
}

/// Scenarios in, preprocessed networks out.
#[derive(Parser)]
#[command(name = "skyroute", version, about, after_help = EXIT_CODES)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Build, plan and render the embedded niendorf-urban scenario into a folder.
    Demo {
        /// Folder for the scenario, network, route and picture.
        #[arg(short, long, default_value = "skyroute-demo")]
        output: PathBuf,
    },
    /// Build a scenario's network and write it as a network image.
    #[command(after_help = BUILD_LIMITS)]
    Build {
        /// The scenario (GeoJSON).
        scenario: PathBuf,
        /// Where to write the network.
        #[arg(short, long)]
        output: PathBuf,
        /// Override planner.sample_spacing_m (at least 1 m).
        #[arg(long, value_parser = parse_radius, allow_hyphen_values = true)]
        sample_spacing: Option<f32>,
        /// Override planner.neighbour_radius_m.
        #[arg(long, value_parser = parse_radius, allow_hyphen_values = true)]
        neighbour_radius: Option<f32>,
        /// Check edges with the paper's discretisation (planner.arc_step_m) instead of exactly:
        /// `added` (the default) tests chords with the clearance plus the chord error, `paper`
        /// with the clearance alone (the paper's reading: its tunnel includes the error).
        #[arg(long, num_args = 0..=1, require_equals = true, default_missing_value = "added",
              value_parser = parse_sagitta)]
        discretised: Option<Sagitta>,
        /// Side of a grid-index cell, metres (default: twice the turn radius; terrain 4000;
        /// landmark 2000).
        #[arg(long, value_parser = parse_radius, allow_hyphen_values = true)]
        grid_cell: Option<f32>,
        /// Terrain mode: drop nodes closer than this to a kept one, metres (default 0).
        #[arg(long, value_parser = parse_non_negative, allow_hyphen_values = true)]
        node_spacing: Option<f64>,
        /// Terrain mode: the longest edge tried, metres (default: every pair of nodes, the paper's
        /// visibility graph; a bound makes a smaller network for a small target, at the cost of
        /// routes that need a long straight).
        #[arg(long, value_parser = parse_positive, allow_hyphen_values = true)]
        max_edge: Option<f64>,
        /// Terrain mode: extra offset of a node from its corner beyond the widening, metres
        /// (default 1; more leaves room for turn arcs).
        #[arg(long, value_parser = parse_non_negative, allow_hyphen_values = true)]
        node_margin: Option<f64>,
        /// Terrain mode: further flight altitudes to place nodes for, so the aircraft can change
        /// altitude in flight (comma-separated metres, e.g. 650,700,850; finite, and below sea
        /// level allowed as for terrain.altitude_m).
        #[arg(long, value_delimiter = ',', value_parser = parse_finite, allow_hyphen_values = true)]
        altitude_levels: Vec<f64>,
        /// Landmark mode: which chains are stored. `ground` (the default): a direction is
        /// searched only if a straight leg is within its best-weather range, and a chain longer
        /// than that range is dropped. `onboard` (Babel's reading): every direction of every
        /// pair is searched and every chain found stored, for the planner's navigability
        /// pruning to remove in flight (a larger image, the same routes).
        #[arg(long, value_parser = parse_landmark_ranges)]
        landmark_ranges: Option<skyroute_prep::landmark::RangeRule>,
        /// Replace a self-intersecting no-fly polygon by its convex hull (which forbids all it
        /// did, and possibly more) instead of refusing the scenario; a warning names it.
        #[arg(long)]
        hull_repair: bool,
        /// Build the scenario as this mode instead of its planner.mode (roadmap, landmark,
        /// terrain, voronoi), e.g. `voronoi` for a scenario with threats; `plan` and `render`
        /// take the same `--mode` with the network.
        #[arg(long, value_parser = parse_mode)]
        mode: Option<Mode>,
    },
    /// Plan start → waypoints in order → goal through a network with the onboard core.
    ///
    /// Before planning it checks that the scenario is the one the network was built from (the
    /// mode, and digests of the vehicle, clearance, every no-fly zone and threat, the
    /// landmarks and weathers, the DEM: anything changed is named), that the start, waypoints,
    /// goal and every pop-up lie on the network's map, and it applies the scenario's `popup`
    /// features and every `--popup`, recorded in the route file.
    #[command(after_help = EXIT_CODES)]
    Plan(PlanArgs),
    /// The Monte Carlo study of pop-ups under uncertainty (Ruz et al.): missions in which the
    /// scenario's pop-ups appear by their probabilities, flown with the decision on risk, time
    /// and fuel and with a baseline deciding on time and fuel alone (docs/RUZ.md).
    #[command(after_help = EXIT_CODES)]
    Montecarlo {
        /// The network image (roadmap or terrain).
        network: PathBuf,
        /// The scenario it was built from, with its `popup` features.
        #[arg(long)]
        scenario: PathBuf,
        /// Missions to fly.
        #[arg(long, default_value_t = 1_000_000)]
        missions: u64,
        /// The random seed.
        #[arg(long, default_value_t = 1)]
        seed: u64,
        /// The largest mean time factor.
        #[arg(long, default_value_t = skyroute_prep::ruz::cli::TIME_LIMIT, value_parser = parse_limit)]
        time_limit: f32,
        /// The largest mean fuel factor.
        #[arg(long, default_value_t = skyroute_prep::ruz::cli::FUEL_LIMIT, value_parser = parse_limit)]
        fuel_limit: f32,
        /// Where to write the results (JSON; the name ends in `.json`).
        #[arg(short, long)]
        output: PathBuf,
        /// Write the histograms as PREFIX-decision.svg/.png and PREFIX-baseline.svg/.png (the
        /// .png with the `png` feature, on by default).
        #[arg(long, value_name = "PREFIX")]
        histograms: Option<PathBuf>,
    },
    /// Write a commented template scenario (GeoJSON) for a mode, that builds and plans as
    /// written: the comments are foreign members (`comments`, each feature's `comment`) that
    /// skyroute and GIS tools ignore.
    Init(InitArgs),
    /// Write a scenario from the files people have: no-fly zones from KML, the route (home and
    /// mission positions) and its exclusion fences from a QGroundControl .plan, joined to a
    /// base scenario (--base, by default the roadmap template). The result is checked as a
    /// scenario before it is written.
    Import(skyroute_prep::import::ImportArgs),
    /// The static planners of Ruz et al. (MILP, A* with inertia) start → goal, scored by risk.
    StaticPlan(skyroute_prep::ruz::static_plan::cli::StaticPlanArgs),
    /// Describe a network image: mode, counts and bytes, what it records of its scenario, the
    /// planner capacities (`V`, `E`) and RAM it needs onboard, and the worst-case work of a
    /// query and of a pop-up.
    Info {
        /// The network image.
        network: PathBuf,
    },
    /// Write a network image as JSON (vertices, edges with their lines and arcs, obstacles) in
    /// its local frame, for other tools.
    Export {
        /// The network image.
        network: PathBuf,
        /// Where to write the JSON (the name ends in `.json`).
        #[arg(short, long)]
        output: PathBuf,
        /// Indent the JSON (several times larger).
        #[arg(long)]
        pretty: bool,
    },
    /// Draw a network, and optionally routes, a scenario's endpoints and pop-ups, as SVG or PNG.
    ///
    /// Grid north up, equal scale on both axes, with a scale bar. Obstacles grey with their
    /// clearance band, network edges thin and light, the route bold with one colour per leg and
    /// arrowheads in the direction of flight, start/waypoints/goal labelled, pop-ups red. The
    /// panel lists the legs and the route's closest approach to obstacles and pop-ups. A
    /// Voronoi network is drawn over its exposure heat map (Σ (r/d)⁴ per metre, log scale) with
    /// its threat sites and their reference distances dashed; a Voronoi route as its smoothed
    /// pieces with its coarse route dashed, and radars that popped up in flight in magenta.
    Render {
        /// The network image.
        network: PathBuf,
        /// A route written by `skyroute plan` on this network (repeatable: several routes are
        /// drawn one colour each, with a legend entry "k = …, length …, exposure …" each).
        #[arg(long)]
        route: Vec<PathBuf>,
        /// The scenario: draws its start, waypoints, goal and `popup` features, and names a
        /// landmark network's landmarks (numbered L1, L2, … without it).
        #[arg(long)]
        scenario: Option<PathBuf>,
        /// A circular pop-up obstacle to draw, `LON,LAT,RADIUS_M[,HEIGHT_M]` (repeatable; the
        /// height is not drawn).
        #[arg(long, value_parser = parse_tall_popup)]
        popup: Vec<PopupArg>,
        /// Where to write the picture: PNG when the name ends in `.png`, SVG when in `.svg`.
        #[arg(short, long)]
        output: PathBuf,
        /// Also write a PNG of the same picture here (a name ending in `.png`, with an SVG
        /// `--output`).
        #[arg(long)]
        png: Option<PathBuf>,
        /// Width of the map in pixels (a 400-pixel legend panel is added to its right).
        #[arg(long, default_value_t = 1200.0)]
        width: f64,
        /// Leave out the network's edges and vertices.
        #[arg(long)]
        no_edges: bool,
        /// Draw only this part of the network's local frame, `MIN_X,MIN_Y,MAX_X,MAX_Y` metres east
        /// and north of its origin (default: everything).
        #[arg(long, value_parser = parse_area)]
        area: Option<(f64, f64, f64, f64)>,
        /// Take the scenario as this mode, as the network was built (`build --mode`).
        #[arg(long, value_parser = parse_mode)]
        mode: Option<Mode>,
    },
}

/// `skyroute plan`: a mission on a network, or with `--popup-appears` a decision among its
/// pop-ups' alternatives.
fn plan(a: PlanArgs) -> CliResult {
    let PlanArgs {
        network,
        scenario: scenario_path,
        popup,
        start,
        goal,
        flown_m,
        last_overflight,
        no_scenario_popups,
        connect_radius,
        turn_rule,
        free_headings,
        shortcuts,
        weather,
        hull_repair,
        output,
        mode,
        threat_weight,
        threat,
        popup_appears,
        time_limit,
        fuel_limit,
        autopilot,
        altitude_m,
    } = a;
    let request = PlanRequest {
        network: &network,
        scenario: &scenario_path,
        popups: &popup,
        start,
        goal,
        flown_m,
        last_overflight,
        scenario_popups: !no_scenario_popups,
        connect_radius_m: connect_radius,
        turn_rule,
        free_headings,
        shortcuts,
        weather: weather.as_deref(),
        hull_repair,
        output: &output,
        mode,
        threat_weight,
        threats: &threat,
        popup_appears: &popup_appears,
        limits: limits(time_limit, fuel_limit),
        mission: MissionOutput::new(autopilot, altitude_m),
    };
    let command = match popup_appears.is_empty() {
        true => plan_command,
        false => plan_decided_command,
    };
    command(&request)
}

fn run(cli: Cli) -> CliResult {
    match cli.command {
        Command::Build {
            scenario: path,
            output,
            sample_spacing,
            neighbour_radius,
            discretised,
            grid_cell,
            node_spacing,
            max_edge,
            node_margin,
            altitude_levels,
            landmark_ranges,
            hull_repair,
            mode,
        } => {
            let given = [
                ("--sample-spacing", sample_spacing.is_some(), Mode::Roadmap),
                (
                    "--neighbour-radius",
                    neighbour_radius.is_some(),
                    Mode::Roadmap,
                ),
                ("--discretised", discretised.is_some(), Mode::Roadmap),
                ("--node-spacing", node_spacing.is_some(), Mode::Terrain),
                ("--max-edge", max_edge.is_some(), Mode::Terrain),
                ("--node-margin", node_margin.is_some(), Mode::Terrain),
                (
                    "--altitude-levels",
                    !altitude_levels.is_empty(),
                    Mode::Terrain,
                ),
                (
                    "--landmark-ranges",
                    landmark_ranges.is_some(),
                    Mode::Landmark,
                ),
            ];
            let mode_options: Vec<(&str, Mode)> = given
                .iter()
                .filter(|(_, is_given, _)| *is_given)
                .map(|&(option, _, applies_to)| (option, applies_to))
                .collect();
            let options = BuildOptions {
                sample_spacing_m: sample_spacing,
                neighbour_radius_m: neighbour_radius,
                discretised,
                grid_cell_m: grid_cell,
                node_spacing_m: node_spacing,
                max_edge_m: max_edge,
                node_margin_m: node_margin,
                extra_altitudes_m: altitude_levels,
                landmark_ranges: landmark_ranges.unwrap_or_default(),
            };
            build_command(&path, &output, &options, hull_repair, mode, &mode_options)
        }
        Command::Plan(a) => plan(a),
        Command::Demo { output } => demo_command(&output),
        Command::Montecarlo {
            network,
            scenario,
            missions,
            seed,
            time_limit,
            fuel_limit,
            output,
            histograms,
        } => montecarlo_command(&MonteCarloRequest {
            network: &network,
            scenario: &scenario,
            missions,
            seed,
            limits: limits(time_limit, fuel_limit),
            output: &output,
            histograms: histograms.as_deref(),
        }),
        Command::Init(a) => init(&a),
        Command::Import(a) => {
            println!("{}", skyroute_prep::import::import_command(&a)?);
            Ok(())
        }
        Command::StaticPlan(a) => skyroute_prep::ruz::static_plan::cli::static_plan_command(&a),
        Command::Info { network } => info(&network),
        Command::Export {
            network,
            output,
            pretty,
        } => {
            let t0 = Instant::now();
            let (v, e, o) = skyroute_prep::export::export_file(&network, &output, pretty)?;
            println!(
                "exported {}: {v} vertices, {e} edges, {o} obstacles, {:.2} s -> {}",
                network.display(),
                t0.elapsed().as_secs_f64(),
                output.display()
            );
            Ok(())
        }
        Command::Render {
            network,
            route,
            scenario: scenario_path,
            popup,
            output,
            png,
            width,
            no_edges,
            area,
            mode,
        } => {
            let t0 = Instant::now();
            if !(width.is_finite() && (200.0..=20000.0).contains(&width)) {
                return Err(format!("--width {width}: expected 200 to 20000 pixels").into());
            }
            let request = skyroute_prep::render::RenderRequest {
                network,
                mode,
                routes: route,
                scenario: scenario_path,
                popups: popup.iter().map(|p| (p.lon, p.lat, p.radius_m)).collect(),
                output,
                png,
                map_width_px: width,
                no_edges,
                area,
            };
            let written = skyroute_prep::render::render(&request)?;
            let names: Vec<String> = written.iter().map(|p| p.display().to_string()).collect();
            println!(
                "rendered {}, {:.2} s -> {}",
                request.network.display(),
                t0.elapsed().as_secs_f64(),
                names.join(", ")
            );
            Ok(())
        }
    }
}

/// `skyroute info NETWORK`: prints what the network holds and what a planner needs for it.
fn info(network: &std::path::Path) -> Result<(), Box<dyn std::error::Error>> {
    let bytes = std::fs::read(network).map_err(|e| format!("{}: {e}", network.display()))?;
    print!("{}", skyroute_prep::info::describe(network, &bytes)?);
    Ok(())
}

fn main() -> ExitCode {
    match run(Cli::parse()) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("skyroute: {e}");
            if e.downcast_ref::<NoRoute>().is_some() {
                ExitCode::from(3)
            } else {
                ExitCode::from(1)
            }
        }
    }
}
