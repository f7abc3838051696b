//! `skyroute plan`: check the scenario against the network (`crate::provenance`,
//! `crate::plan_checks`), apply the pop-ups, plan with the onboard core (missions, or the
//! landmark route), and write the route file in the format its extension names.

use crate::landmark_mission::{landmark_route_json, plan_landmark, LandmarkPlanError, OnlineStart};
use crate::landmark_reach::no_route_proof;
use crate::local::local;
use crate::mission::{plan_mission_with, LocalPopup, MissionOptions};
use crate::output::{refuse_overwriting_inputs, write_atomically};
use crate::plan_checks::{
    check_ends_clear_of_popups, check_query, gather_popups, PopupInput, PopupSource,
};
use crate::provenance::check_binding;
use crate::route_mission::{mission_route, mission_summary, MissionOutput};
use crate::route_output::{route_text, RouteFormat};
use crate::scenario;
use std::path::Path;
use std::time::Instant;

/// What a command returns: any error, reported by `main` (exit 1, or 3 for [`NoRoute`]).
pub type CliResult = Result<(), Box<dyn std::error::Error>>;

/// A planning failure in which no route exists (exit code 3), as opposed to bad input.
#[derive(Debug)]
pub struct NoRoute(pub String);

impl std::fmt::Display for NoRoute {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for NoRoute {}

/// What `skyroute plan` was asked.
pub struct PlanRequest<'a> {
    pub network: &'a Path,
    pub scenario: &'a Path,
    pub popups: &'a [crate::cli_values::PopupArg],
    /// `--start`: `(lon, lat, compass heading)` replacing the scenario's start.
    pub start: Option<(f64, f64, f64)>,
    /// `--goal`: `(lon, lat, compass heading or none)` replacing the scenario's goal.
    pub goal: Option<(f64, f64, Option<f64>)>,
    /// `--flown-m`: landmark networks, metres flown since the last overflight.
    pub flown_m: Option<f64>,
    /// `--last-overflight`: landmark networks, the landmark overflown last and the compass
    /// heading it was crossed at.
    pub last_overflight: Option<(String, f64)>,
    pub scenario_popups: bool,
    pub connect_radius_m: Option<f32>,
    /// `--turn-rule`: terrain networks' turn rule (`None`: the paper's).
    pub turn_rule: Option<skyroute::TurnRule>,
    /// How a waypoint without a heading gets one (roadmap and terrain missions).
    pub free_headings: crate::mission::FreeHeadingRule,
    /// `--shortcuts`: the shortcut pass of post-processing (`None`: the best chain for a
    /// mission, the greedy pass with `--popup-appears`).
    pub shortcuts: Option<crate::mission::Shortcuts>,
    pub weather: Option<&'a str>,
    pub hull_repair: bool,
    pub output: &'a Path,
    /// `--mode`: the mode to take the scenario as.
    pub mode: Option<scenario::Mode>,
    /// `--threat-weight`: the weight k (Voronoi networks; on a roadmap network, the ground
    /// planner of `crate::roadmap_exposure`).
    pub threat_weight: Option<f32>,
    /// `--threat`: radars that popped up, `(lon, lat, radius_m)` (Voronoi networks).
    pub threats: &'a [(f64, f64, f64)],
    /// `--popup-appears`: the scenario pop-ups that may appear (`crate::ruz::cli`; ignored by
    /// [`plan_command`]).
    pub popup_appears: &'a [String],
    /// `--time-limit` and `--fuel-limit`.
    pub limits: skyroute::planner::decision::DecisionLimits,
    /// `--autopilot` and `--altitude`: how `.plan`, `.waypoints` and `.kml` outputs are written.
    pub mission: MissionOutput,
}

/// The route file's record of the pop-ups a plan applied.
pub fn popups_json(popups: &[PopupInput], frame: &crate::frame::LocalFrame) -> serde_json::Value {
    popups
        .iter()
        .map(|p| {
            let c = local(frame, p.lon, p.lat);
            serde_json::json!({
                "name": p.name,
                "source": match p.source {
                    PopupSource::Scenario => "scenario",
                    PopupSource::CommandLine => "--popup",
                },
                "lon": p.lon,
                "lat": p.lat,
                "radius_m": p.radius_m,
                "height_m": p.height_m,
                "probability": p.probability,
                "centre": [c.x, c.y],
            })
        })
        .collect()
}

/// `skyroute plan`.
pub fn plan_command(req: &PlanRequest) -> CliResult {
    let t0 = Instant::now();
    refuse_overwriting_inputs(req.output, &[req.network, req.scenario])?;
    let format = RouteFormat::of(req.output)?;
    let bytes =
        std::fs::read(req.network).map_err(|e| format!("{}: {e}", req.network.display()))?;
    let net = skyroute::Network::from_bytes(&bytes)
        .map_err(|e| format!("{}: {e}", req.network.display()))?;
    if let (Some(w), None) = (req.weather, net.landmark()) {
        return Err(format!(
            "--weather {w}: {} is not a landmark network, so it has no weather",
            req.network.display()
        )
        .into());
    }
    let s = load_scenario(req.scenario, req.hull_repair, req.mode)?;
    if s.planner.mode != scenario::Mode::Voronoi && !req.threats.is_empty() {
        return Err(format!(
            "--threat applies to voronoi networks; {} is a {} network",
            req.network.display(),
            net.mode().name()
        )
        .into());
    }
    if !matches!(
        s.planner.mode,
        scenario::Mode::Voronoi | scenario::Mode::Roadmap
    ) && req.threat_weight.is_some()
    {
        return Err(format!(
            "--threat-weight applies to voronoi and roadmap networks; {} is a {} network",
            req.network.display(),
            net.mode().name()
        )
        .into());
    }
    let paper_rule = req.free_headings != crate::mission::FreeHeadingRule::Cheapest;
    if paper_rule && (s.planner.mode != scenario::Mode::Roadmap || req.threat_weight.is_some()) {
        return Err(format!(
            "--free-headings paper counts a roadmap's clear out-edges: it applies to roadmap \
             networks without --threat-weight; {} is a {} network",
            req.network.display(),
            net.mode().name()
        )
        .into());
    }
    let on = || format!("{} on {}", req.scenario.display(), req.network.display());
    check_binding(&s, &net).map_err(|e| format!("{}: {e}", on()))?;
    let s = with_start(s, req, &net)?;
    let frame = crate::export::network_frame(&net);
    let popups = gather_popups(&s, req.popups, req.scenario_popups);
    check_query(&s, &net, &frame, &popups).map_err(|e| format!("{}: {e}", on()))?;
    check_ends_clear_of_popups(&s, &frame, &popups)
        .map_err(|e| NoRoute(format!("{}: {e}", req.scenario.display())))?;
    for p in &popups {
        println!(
            "  {} (lon {}, lat {}, radius {} m{}) applied",
            p.name,
            p.lon,
            p.lat,
            p.radius_m,
            p.probability
                .map_or(String::new(), |q| format!(", appears with p = {q}"))
        );
    }
    let local_popups: Vec<LocalPopup> = popups.iter().map(|p| p.local(&frame)).collect();
    // `check_binding` has established that the scenario's mode is the network's.
    let mut json = match s.planner.mode {
        scenario::Mode::Landmark => {
            plan_landmark_route(req, &s, &bytes, &frame, &local_popups, t0)?
        }
        scenario::Mode::Roadmap if req.threat_weight.is_some() => {
            plan_ground_exposure_route(req, &s, &net, &frame, &local_popups, t0)?
        }
        scenario::Mode::Roadmap | scenario::Mode::Terrain => {
            plan_mission_route(req, &s, &bytes, &frame, &local_popups, t0)?
        }
        scenario::Mode::Voronoi => plan_voronoi_route(req, &s, &bytes, &frame, &local_popups, t0)?,
    };
    json["popups"] = popups_json(&popups, &frame);
    json["scenario_popups_applied"] = serde_json::json!(req.scenario_popups);
    if let Some(t) = net.terrain() {
        json["altitude_m"] = serde_json::json!(t.altitude_m);
    }
    write_route(req, format, &json, &s)
}

/// Writes a planned route's JSON to `req.output` in `format`, saying for a mission how closely
/// its waypoints follow the route. Errors name the output file.
pub fn write_route(
    req: &PlanRequest,
    format: RouteFormat,
    json: &serde_json::Value,
    s: &scenario::Scenario,
) -> CliResult {
    let at = |e: &dyn std::fmt::Display| format!("{}: {e}", req.output.display());
    let text = route_text(format, json, s, &req.mission).map_err(|e| at(&e))?;
    if format.is_mission() {
        let m = mission_route(json, s).map_err(|e| at(&e))?;
        println!("  {}", mission_summary(&m));
    }
    write_atomically(req.output, text.as_bytes())?;
    Ok(())
}

/// A planning failure as `plan` reports it, prefixed with the scenario: bad input (exit 1) or,
/// when no route exists, [`NoRoute`] (exit 3).
fn planning_error(
    scenario: &Path,
    e: &dyn std::fmt::Display,
    bad_input: bool,
) -> Box<dyn std::error::Error> {
    let message = format!("{}: {e}", scenario.display());
    if bad_input {
        message.into()
    } else {
        Box::new(NoRoute(message))
    }
}

/// `skyroute plan` on a landmark network: the route file's JSON.
fn plan_landmark_route(
    req: &PlanRequest,
    s: &scenario::Scenario,
    bytes: &[u8],
    frame: &crate::frame::LocalFrame,
    popups: &[LocalPopup],
    t0: Instant,
) -> Result<serde_json::Value, Box<dyn std::error::Error>> {
    let on = format!("{} on {}", req.scenario.display(), req.network.display());
    let online = req.start.map(|(lon, lat, heading_deg)| OnlineStart {
        pose: crate::local::local_pose(frame, lon, lat, Some(heading_deg)),
        flown_m: req.flown_m.unwrap_or(0.0) as f32,
        last_overflight: req.last_overflight.clone(),
    });
    // The scenario's goal is the network's unless `--goal` replaced it.
    let online_goal = req.goal.map(|(lon, lat, heading)| skyroute::Goal {
        position: crate::local::local(frame, lon, lat),
        heading: heading.map(|c| crate::local::local_heading(frame, lon, lat, c)),
    });
    let r = match plan_landmark(bytes, s, req.weather, popups, online.as_ref(), online_goal) {
        Ok(r) => r,
        Err(LandmarkPlanError::Plan(e)) => {
            let w = req
                .weather
                .and_then(|name| s.weather.iter().position(|x| x == name))
                .unwrap_or(0);
            // The proof bounds the first leg by the start's `dist_m`, which bounds the range
            // left from the start fix but not from another overflight.
            let proof = match req.last_overflight {
                None => no_route_proof(s, w, frame),
                Some(_) => None,
            };
            let why = match proof {
                Some(proof) => format!("no route can exist: {proof}"),
                None => format!(
                    "straight legs within range could connect the start to the goal, but no \
                     flyable chain of the network does ({e})"
                ),
            };
            let weather = s.weather.get(w).map_or("?", String::as_str);
            return Err(Box::new(NoRoute(format!(
                "{on}: no navigable route from the start to the goal in weather {weather}: {why}"
            ))));
        }
        Err(
            e @ (LandmarkPlanError::RangeSpent(..)
            | LandmarkPlanError::OnlineStartUnconnected(_)
            | LandmarkPlanError::OnlineGoalUnconnected),
        ) => return Err(Box::new(NoRoute(format!("{on}: {e}")))),
        Err(e) => return Err(format!("{on}: {e}").into()),
    };
    if let Some((range, piece)) = &r.online_start {
        println!(
            "  from --start with {:.1} km of range left: a {:.1} km piece to {}",
            range / 1000.0,
            piece.length() / 1000.0,
            r.overflights
                .first()
                .map_or("the goal", |o| o.landmark.as_str())
        );
    }
    for o in &r.overflights {
        println!(
            "  over {} heading {:5.1}°: q {:.2}, range {:.1} km, next leg {:.1} km",
            o.landmark,
            o.heading_deg,
            o.quality,
            o.range_m / 1000.0,
            o.leg_m / 1000.0
        );
    }
    println!(
        "planned {} in weather {}: {:.1} km over {} overflights, {} Hermite pieces, work {} \
         ({} of {} edges leaving overflights not navigable), {:.3} s -> {}",
        s.name,
        r.weather,
        r.summary.length / 1000.0,
        r.overflights.len(),
        r.summary.primitives,
        r.summary.work.total(),
        r.pruned.0,
        r.pruned.1,
        t0.elapsed().as_secs_f64(),
        req.output.display()
    );
    Ok(landmark_route_json(&r, bytes, frame, &s.name))
}

/// `skyroute plan` on a roadmap or terrain network: the route file's JSON.
fn plan_mission_route(
    req: &PlanRequest,
    s: &scenario::Scenario,
    bytes: &[u8],
    frame: &crate::frame::LocalFrame,
    popups: &[LocalPopup],
    t0: Instant,
) -> Result<serde_json::Value, Box<dyn std::error::Error>> {
    let options = MissionOptions {
        connect_radius_m: req.connect_radius_m,
        turn_rule: req.turn_rule,
        free_headings: req.free_headings,
        shortcuts: req.shortcuts.unwrap_or_default(),
    };
    let m = plan_mission_with(bytes, s, frame, popups, &options)
        .map_err(|e| planning_error(req.scenario, &e, e.is_bad_input()))?;
    for (name, heading, count) in &m.fixed_headings {
        match heading.is_nan() {
            false => println!(
                "  {name}: heading {:.0}° (grid) fixed by the paper's rule, {count} clear out-edges",
                skyroute::geometry::compass_deg_from_heading(*heading)
            ),
            true => println!(
                "  {name}: no heading has a clear way in and out within the radius; the default \
                 rule chooses it"
            ),
        }
    }
    for l in &m.legs {
        println!(
            "  {} -> {}: {:.1} m ({:.1} m before post-processing), {} network edges, work {}{}",
            l.from,
            l.to,
            l.summary.length,
            l.planned_length,
            l.summary.network_edges,
            l.summary.work.total(),
            if l.widened {
                "; connected beyond the network's radius to the nearest vertices"
            } else {
                ""
            }
        );
        if l.arc_checks.arcs > 0 {
            println!(
                "    {} turn arcs checked against the elevation grid: {} cells, {:.1} per arc, at \
                 most {} (bound {})",
                l.arc_checks.arcs,
                l.arc_checks.cells,
                l.arc_checks.cells as f64 / l.arc_checks.arcs as f64,
                l.arc_checks.most_cells,
                l.cells_per_turn_bound
            );
        }
        if let Some(note) = crate::mission::exit_note(l, s, popups) {
            println!("    {note}");
        }
    }
    println!(
        "planned {}: {:.1} m over {} legs ({} core queries to choose headings), {:.2} s -> {}",
        s.name,
        m.length,
        m.legs.len(),
        m.queries,
        t0.elapsed().as_secs_f64(),
        req.output.display()
    );
    Ok(crate::route_json::mission_json(&m, frame, &s.name))
}

/// `skyroute plan --threat-weight` on a roadmap network: the ground planner under the exposure
/// cost (`crate::roadmap_exposure`; the onboard roadmap planner does not weigh exposure).
fn plan_ground_exposure_route(
    req: &PlanRequest,
    s: &scenario::Scenario,
    net: &skyroute::Network,
    frame: &crate::frame::LocalFrame,
    popups: &[LocalPopup],
    t0: Instant,
) -> Result<serde_json::Value, Box<dyn std::error::Error>> {
    use crate::roadmap_exposure::{ground_route_json, plan_roadmap_exposure, GroundPlanError};
    // The shortest decimal of the f32 the option was parsed into (0.1, not 0.10000000149).
    let k: f64 = req
        .threat_weight
        .map_or(0.5, |w| w.to_string().parse().unwrap_or(w as f64));
    let m = plan_roadmap_exposure(net, s, frame, popups, k).map_err(
        |e| -> Box<dyn std::error::Error> {
            let message = format!("{}: {e}", req.scenario.display());
            match e {
                GroundPlanError::BadInput(_) => message.into(),
                GroundPlanError::NoRoute(_) => Box::new(NoRoute(message)),
            }
        },
    )?;
    for l in &m.legs {
        println!(
            "  {} -> {}: {:.1} m, {} network edges, exposure {:.1} (three-point {:.1}){}",
            l.from,
            l.to,
            l.length_m,
            l.network_edges,
            l.exposure_flown,
            l.exposure_three_point,
            if l.widened {
                "; connected beyond the network's radius to the nearest vertices"
            } else {
                ""
            }
        );
    }
    println!(
        "planned {} on the ground (roadmap edges, cost k*L + (1 - k)*exposure; not the onboard \
         planner) with k = {k}: {:.1} m, exposure {:.1}, {} threats, {} edges blocked by \
         pop-ups, {:.3} s -> {}",
        s.name,
        m.legs.iter().map(|l| l.length_m).sum::<f64>(),
        m.legs.iter().map(|l| l.exposure_flown).sum::<f64>(),
        m.threats.len(),
        m.blocked_edges,
        t0.elapsed().as_secs_f64(),
        req.output.display()
    );
    Ok(ground_route_json(&m, frame, &s.name))
}

/// `skyroute plan` on a Voronoi network: the route file's JSON.
fn plan_voronoi_route(
    req: &PlanRequest,
    s: &scenario::Scenario,
    bytes: &[u8],
    frame: &crate::frame::LocalFrame,
    popups: &[LocalPopup],
    t0: Instant,
) -> Result<serde_json::Value, Box<dyn std::error::Error>> {
    use crate::voronoi_mission::{plan_voronoi_mission, voronoi_route_json, LocalThreat};
    let threats: Vec<LocalThreat> = req
        .threats
        .iter()
        .enumerate()
        .map(|(i, &(lon, lat, r))| LocalThreat {
            name: format!("--threat {}", i + 1),
            position: local(frame, lon, lat),
            radius: r as f32,
        })
        .collect();
    let m = plan_voronoi_mission(bytes, s, frame, popups, &threats, req.threat_weight)
        .map_err(|e| planning_error(req.scenario, &e, e.is_bad_input()))?;
    for l in &m.legs {
        println!(
            "  {} -> {}: {:.1} m, {} graph edges, {} pieces, exposure {:.1} (coarse, three-point \
             {:.1}), chords within {:.1} m, work {}",
            l.from,
            l.to,
            l.summary.length,
            l.summary.network_edges,
            l.pieces.len(),
            l.flown_exposure,
            l.coarse_exposure,
            l.chord_deviation_m,
            l.summary.work.total()
        );
    }
    let length: f32 = m.legs.iter().map(|l| l.summary.length).sum();
    let exposure: f64 = m.legs.iter().map(|l| l.flown_exposure).sum();
    println!(
        "planned {} with k = {}: {:.1} m, exposure {:.1}, {} threats ({} in flight), {:.3} s -> {}",
        s.name,
        m.threat_weight,
        length,
        exposure,
        m.threats.len(),
        threats.len(),
        t0.elapsed().as_secs_f64(),
        req.output.display()
    );
    Ok(voronoi_route_json(&m, frame, &s.name))
}

/// The scenario with its start and goal replaced by `--start` and `--goal` (after the
/// network's binding to the scenario was checked, so that the new ends are checked like any
/// query's). A landmark start keeps the scenario start's `dist_m`: the range at the mission's
/// start fix.
/// `--flown-m` and `--last-overflight` need `--start` and a landmark network.
fn with_start(
    mut s: scenario::Scenario,
    req: &PlanRequest,
    net: &skyroute::Network,
) -> Result<scenario::Scenario, String> {
    let landmark = match net.mode() {
        skyroute::network::Mode::Landmark => true,
        skyroute::network::Mode::Roadmap
        | skyroute::network::Mode::Terrain
        | skyroute::network::Mode::Voronoi
        | skyroute::network::Mode::Unknown(_) => false,
    };
    let landmark_option = match (req.flown_m.is_some(), req.last_overflight.is_some()) {
        (true, _) => Some("--flown-m"),
        (false, true) => Some("--last-overflight"),
        (false, false) => None,
    };
    if let Some(option) = landmark_option {
        if !landmark {
            return Err(format!(
                "{option} applies to landmark networks (the range flown since the last \
                 overflight); {} is a {} network",
                req.network.display(),
                net.mode().name()
            ));
        }
        if req.start.is_none() {
            return Err(format!(
                "{option} needs --start: it gives the range left where the aircraft is"
            ));
        }
    }
    if let Some((lon, lat, heading_deg)) = req.goal {
        let name = s
            .goal
            .as_ref()
            .map_or_else(|| "goal".to_string(), |e| e.name.clone());
        let altitude_m = s.goal.as_ref().and_then(|e| e.altitude_m);
        s.goal = Some(scenario::Endpoint {
            name,
            lon,
            lat,
            heading_deg,
            dist_m: None,
            altitude_m,
        });
    }
    let Some((lon, lat, heading_deg)) = req.start else {
        return Ok(s);
    };
    let (name, dist_m, altitude_m) = s.start.as_ref().map_or_else(
        || ("start".to_string(), None, None),
        |e| (e.name.clone(), e.dist_m, e.altitude_m),
    );
    s.start = Some(scenario::Endpoint {
        name,
        lon,
        lat,
        heading_deg: Some(heading_deg),
        dist_m: dist_m.filter(|_| landmark),
        altitude_m,
    });
    Ok(s)
}

/// Reads a scenario, repairing self-intersecting no-fly polygons by their hulls when asked (and
/// saying so), and taking it as `mode` instead of its `planner.mode` when given (`--mode`).
pub fn load_scenario(
    path: &Path,
    hull_repair: bool,
    mode: Option<scenario::Mode>,
) -> Result<scenario::Scenario, Box<dyn std::error::Error>> {
    let options = scenario::ParseOptions {
        hull_self_intersecting_no_fly: hull_repair,
    };
    let s = crate::scenario_input::read_scenario(path, &options, mode)?;
    for w in &s.warnings {
        eprintln!("warning: {w}");
    }
    Ok(s)
}
