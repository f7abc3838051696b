//! `skyroute render`: a picture of a network, and optionally a planned route, a scenario's
//! endpoints and pop-up threats, as SVG (written by hand) or PNG (the same SVG rasterised with
//! resvg).
//!
//! The map is drawn in the network's local frame with grid north up and the same scale on both
//! axes. Layers, bottom to top: a metric grid at round distances (fine and coarse); the
//! longitude/latitude graticule (meridians and parallels at a round spacing, dashed;
//! `graticule`); the clearance band around every obstacle; obstacles (grey); for a terrain
//! network, the cells blocked at its altitude (grey); the network's edges (thin, light; a
//! landmark network's are its Hermite chains); pop-ups (red); the route, one colour per leg,
//! with a white casing and arrowheads every so often in the direction of flight; a landmark
//! network's landmarks (purple triangles); start, waypoints and goal with heading ticks where
//! the heading is fixed. Over everything, unclipped but moved inside the map
//! (`draw::clamp_label`): the graticule's labels in degrees and minutes at the map's bottom and
//! right edges, the landmarks' names (from the scenario, else `L1`, `L2`, …), the endpoints'
//! names and the pop-ups' labels. For a terrain network with a route, a strip under the map
//! plots the terrain elevation under the (first) route against distance flown, with the
//! route's altitude and the altitude less the safety height (`profile_layer`). A panel on the
//! right holds the title, a legend with an entry for every kind of mark drawn, the legs with
//! their lengths, the route's smallest distance to any obstacle or pop-up (in red when it is
//! below the network's clearance) and a scale bar. A route flying a decision among pop-up
//! bypass alternatives (`plan --popup-appears`) is drawn thin and dark over the nominal route
//! and every alternative, with their legend in the panel (`decision_layer`).

mod decision_layer;
mod draw;
mod graticule;
mod landmark_layer;
mod mark_layer;
mod network_layer;
mod obstacle_layer;
mod panel;
mod picture;
mod png;
mod profile_layer;
mod route_file;
mod route_layer;
mod svg;
#[cfg(test)]
mod tests;
mod threat_layer;

pub(crate) use panel::primitive_obstacle_distance;
pub use picture::{
    scenario_marks, AlternativeMark, DecisionMark, DecisionPopup, EndpointMark, LandmarkMark,
    Picture, PopupMark, Route, RouteLeg, ThreatMark,
};
pub use png::svg_to_png;
pub use route_file::{
    parse_route, piece_from_json, primitive_from_json, read_route, route_from_json,
};
pub use svg::render_svg;
pub use threat_layer::exposure_density;

use crate::export::{network_frame, read_network};
use crate::scenario;
use skyroute::Network;
use std::path::{Path, PathBuf};

/// What `skyroute render` is asked to draw.
#[derive(Clone, Debug, Default)]
pub struct RenderRequest {
    /// The network image.
    pub network: PathBuf,
    /// `--mode`: the mode to take the scenario as.
    pub mode: Option<scenario::Mode>,
    /// Route files from `skyroute plan` (`--route`, repeatable): one is drawn a colour per leg,
    /// several a colour per route.
    pub routes: Vec<PathBuf>,
    /// A scenario for the start, waypoints, goal and pop-ups.
    pub scenario: Option<PathBuf>,
    /// Extra pop-ups, `(lon, lat, radius_m)`.
    pub popups: Vec<(f64, f64, f64)>,
    /// The picture: SVG, or PNG when the name ends in `.png`.
    pub output: PathBuf,
    /// Also a PNG here.
    pub png: Option<PathBuf>,
    /// Width of the map, pixels.
    pub map_width_px: f64,
    /// Leave out the network's edges.
    pub no_edges: bool,
    /// Draw only this part of the frame, `(min_x, min_y, max_x, max_y)` metres.
    pub area: Option<(f64, f64, f64, f64)>,
}

fn is_png(p: &Path) -> bool {
    has_extension(p, "png")
}

fn has_extension(p: &Path, ext: &str) -> bool {
    p.extension().is_some_and(|e| e.eq_ignore_ascii_case(ext))
}

/// Refuses outputs whose names do not say what they hold: `-o` must end in `.svg` or `.png`,
/// `--png` in `.png`, and the two must differ. A tool built without its `png` feature refuses
/// a PNG output here, before it draws anything.
fn check_output_names(req: &RenderRequest) -> Result<(), String> {
    if !cfg!(feature = "png") {
        if let Some(p) = req
            .png
            .as_deref()
            .or(Some(req.output.as_path()).filter(|o| is_png(o)))
        {
            return Err(format!("{}: {}", p.display(), png::WITHOUT_PNG));
        }
    }
    if !(is_png(&req.output) || has_extension(&req.output, "svg")) {
        return Err(format!(
            "{}: render writes SVG or PNG; name the output .svg or .png",
            req.output.display()
        ));
    }
    if let Some(p) = &req.png {
        if !is_png(p) {
            return Err(format!("{}: --png writes PNG; name it .png", p.display()));
        }
        if p == &req.output {
            return Err(format!(
                "{}: given as both -o and --png; choose two paths",
                p.display()
            ));
        }
    }
    Ok(())
}

/// Reads a route file and checks that it was planned in `net`'s frame; errors name the file.
fn read_route_on(path: &Path, net: &Network, net_path: &Path) -> Result<Route, String> {
    let r = read_route(path)?;
    let (lat, lon) = net.origin_deg();
    if (r.origin_deg.0 - lat).abs() > 1e-9 || (r.origin_deg.1 - lon).abs() > 1e-9 {
        return Err(format!(
            "{}: the route's frame origin ({}, {}) is not the network's ({lat}, {lon}): was it \
             planned on {}?",
            path.display(),
            r.origin_deg.0,
            r.origin_deg.1,
            net_path.display()
        ));
    }
    Ok(r)
}

/// A landmark network's landmarks, named as in the scenario when one is given: the
/// scenario's landmark at the same index if it lies within a metre of the network's (the
/// builder keeps the scenario's order), else `L` and the landmark's number from 1.
fn landmark_marks(
    net: &Network,
    s: Option<&scenario::Scenario>,
    frame: &crate::frame::LocalFrame,
) -> Vec<LandmarkMark> {
    let count = net.landmark().map_or(0, |l| l.landmark_count);
    (0..count)
        .filter_map(|i| {
            let (p, _) = net.landmark_site(i)?;
            let position = (p.x as f64, p.y as f64);
            let named = s.and_then(|s| s.landmarks.get(i as usize)).filter(|l| {
                let (x, y) = frame.to_local(l.lon, l.lat);
                (x - position.0).hypot(y - position.1) < 1.0
            });
            Some(LandmarkMark {
                name: named.map_or_else(|| format!("L{}", i + 1), |l| l.name.clone()),
                position,
            })
        })
        .collect()
}

/// Reads the inputs, draws, writes the picture(s). Returns the files written. Errors name the
/// file concerned.
pub fn render(req: &RenderRequest) -> Result<Vec<PathBuf>, Box<dyn std::error::Error>> {
    check_output_names(req)?;
    let bytes = read_network(&req.network)?;
    let net = Network::from_bytes(&bytes).map_err(|e| format!("{}: {e}", req.network.display()))?;
    let frame = network_frame(&net);
    let routes = req
        .routes
        .iter()
        .map(|path| read_route_on(path, &net, &req.network))
        .collect::<Result<Vec<_>, _>>()?;
    let s = req
        .scenario
        .as_deref()
        .map(|p| {
            crate::scenario_input::read_scenario(p, &scenario::ParseOptions::default(), req.mode)
        })
        .transpose()?;
    if let Some(s) = &s {
        // Drawn over a network it does not match, a scenario's zones would be missing from
        // the picture and from its clearance figures.
        crate::provenance::check_binding(s, &net)
            .map_err(|e| format!("{} on {}: {e}", s.path.display(), req.network.display()))?;
    }
    let (endpoints, mut popups) = s
        .as_ref()
        .map(|s| scenario_marks(s, &frame))
        .unwrap_or_default();
    // Routes that were all planned without the scenario's pop-ups (`--no-scenario-popups`)
    // are drawn without them.
    if !routes.is_empty()
        && routes
            .iter()
            .all(|r| r.scenario_popups_applied == Some(false))
    {
        popups.clear();
    }
    // The pop-ups the routes were planned round, unless the scenario already drew them (the
    // route file holds the centre in f32, the scenario in f64: equal within a metre).
    let same = |a: (f64, f64), b: (f64, f64)| (a.0 - b.0).hypot(a.1 - b.1) < 1.0;
    for p in routes.iter().flat_map(|r| r.popups.iter()) {
        if !popups
            .iter()
            .any(|q| same(q.centre, p.centre) && (q.radius - p.radius).abs() < 1e-3)
        {
            popups.push(p.clone());
        }
    }
    // The pop-ups a route's decision weighed are labelled with their appearance probability.
    for p in routes
        .iter()
        .filter_map(|r| r.decision.as_ref())
        .flat_map(|d| &d.popups)
    {
        // A route file names a scenario's pop-up `pop-up "U1"`, the scenario `U1`.
        let quoted = format!("pop-up {:?}", p.name);
        for q in popups
            .iter_mut()
            .filter(|q| q.name == p.name || q.name == quoted)
        {
            q.name = format!("{}, P_A {}", p.name, p.probability);
        }
    }
    let mut threats: Vec<ThreatMark> = (0..net.threat_count())
        .filter_map(|i| net.threat(i))
        .map(|(c, r)| ThreatMark {
            centre: (c.x as f64, c.y as f64),
            radius: r as f64,
            popped: false,
        })
        .collect();
    for t in routes.iter().flat_map(|r| r.threats.iter()) {
        if t.popped && !threats.iter().any(|q| same(q.centre, t.centre)) {
            threats.push(t.clone());
        }
    }
    popups.extend(
        req.popups
            .iter()
            .enumerate()
            .map(|(i, &(lon, lat, r))| PopupMark {
                name: format!("--popup #{}", i + 1),
                centre: frame.to_local(lon, lat),
                radius: r,
            }),
    );
    let title = s
        .as_ref()
        .map(|s| s.name.clone())
        .or_else(|| {
            routes
                .first()
                .map(|r| r.scenario.clone())
                .filter(|n| !n.is_empty())
        })
        .unwrap_or_else(|| req.network.display().to_string());
    let landmarks = landmark_marks(&net, s.as_ref(), &frame);
    let pic = Picture {
        title,
        landmarks,
        network: Some(net),
        edges: !req.no_edges,
        routes,
        threats,
        endpoints,
        popups,
        map_width_px: if req.map_width_px > 0.0 {
            req.map_width_px
        } else {
            1200.0
        },
        area: req.area,
    };
    let svg = render_svg(&pic);
    let mut written = Vec::new();
    let mut png = None;
    let mut write_png = |path: &Path| -> Result<(), String> {
        if png.is_none() {
            png = Some(svg_to_png(&svg).map_err(|e| format!("{}: {e}", path.display()))?);
        }
        crate::output::write_atomically(path, png.as_deref().unwrap_or_default())
    };
    let mut inputs = vec![req.network.as_path()];
    inputs.extend(req.routes.iter().map(PathBuf::as_path));
    inputs.extend(req.scenario.as_deref());
    for out in std::iter::once(&req.output).chain(req.png.iter()) {
        crate::output::refuse_overwriting_inputs(out, &inputs)?;
    }
    if is_png(&req.output) {
        write_png(&req.output)?;
    } else {
        crate::output::write_atomically(&req.output, svg.as_bytes())?;
    }
    written.push(req.output.clone());
    if let Some(p) = &req.png {
        write_png(p)?;
        written.push(p.clone());
    }
    Ok(written)
}
