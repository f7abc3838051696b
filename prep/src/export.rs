//! `skyroute export`: a network image as JSON, for tools that do not read the binary format.
//!
//! The file is one object:
//!
//! ```text
//! {
//!   "format": "skyroute-network-json", "format_version": 1, "network_format_version": 1,
//!   "frame": {"origin_lat_deg", "origin_lon_deg", "method"},
//!   "turn_radius_m", "clearance_m",
//!   "vertices":  [{"id", "x", "y", "heading_rad", "heading_compass_deg", "lon", "lat"}],
//!   "edges":     [{"id", "from", "to", "cost", "word", "lengths", "primitives": [...]}
//!               | {"id", "from", "to", "cost", "word": "hermite_chain", "length", "pieces": [...]}],
//!   "obstacles": [{"id", "kind": "polygon", "points": [[x, y], ...]}
//!               | {"id", "kind": "circle", "centre": [x, y], "radius"}]
//! }
//! ```
//!
//! Positions are metres in the network's local frame (`x` east, `y` north of the origin, see
//! `prep/src/frame.rs`), the same frame as the route files of `skyroute plan`. `heading_rad` is
//! the network's heading (counter-clockwise from the frame's `x` axis); `heading_compass_deg` the
//! same direction as a compass heading (clockwise from *true* north, corrected for the
//! projection's meridian convergence at the vertex). `lon`/`lat` are WGS-84 degrees. Edge
//! primitives are written by [`crate::route_json::primitive_json`] and fly the edge from the
//! `from` vertex's pose to the `to` vertex's pose. A landmark network's edges are chains of
//! quintic Hermite pieces, written by [`crate::route_json::hermite_piece_json`]. `provenance`
//! lists the digests of what the network was built from (`prep/src/provenance.rs`). Numbers are
//! the network's f32 values, written exactly (as f64).

use crate::frame::LocalFrame;
use crate::route_json::{hermite_piece_json, primitive_json};
use serde_json::{json, Value};
use skyroute::geometry::compass_deg_from_heading;
use skyroute::geometry::predicates::PolygonView;
use skyroute::network::format::FORMAT_VERSION;
use skyroute::network::Obstacle;
use skyroute::Network;
use std::path::Path;

/// Version of this JSON layout (independent of the binary format's version).
pub const JSON_FORMAT_VERSION: u32 = 1;

/// Reads and validates a network image; errors name the file
/// (`/tmp/x.bin: network truncated: needs 820058 bytes, 5000 present`).
pub fn read_network(path: &Path) -> Result<Vec<u8>, String> {
    let bytes = std::fs::read(path).map_err(|e| format!("{}: {e}", path.display()))?;
    Network::from_bytes(&bytes).map_err(|e| format!("{}: {e}", path.display()))?;
    Ok(bytes)
}

/// The local frame a network is expressed in.
pub fn network_frame(net: &Network) -> LocalFrame {
    let (lat, lon) = net.origin_deg();
    LocalFrame::new(lat, lon)
}

/// The network as JSON (see the module documentation for the layout).
pub fn network_json(net: &Network) -> Value {
    let frame = network_frame(net);
    let (lat0, lon0) = frame.origin();
    let vertices: Vec<Value> = (0..net.vertex_count())
        .filter_map(|i| net.vertex(i).map(|p| (i, p)))
        .map(|(i, p)| {
            let (x, y) = (p.position.x as f64, p.position.y as f64);
            let (lon, lat) = frame.to_geo(x, y);
            let grid_compass = compass_deg_from_heading(p.heading) as f64;
            json!({
                "id": i,
                "x": p.position.x,
                "y": p.position.y,
                "heading_rad": p.heading,
                "heading_compass_deg": frame.heading_to_geo(x, y, grid_compass),
                "lon": lon,
                "lat": lat,
            })
        })
        .collect();
    let edges: Vec<Value> = (0..net.edge_count())
        .filter_map(|i| edge_json(net, i))
        .collect();
    let obstacles: Vec<Value> = (0..net.obstacle_count())
        .filter_map(|i| net.obstacle(i).map(|(o, _)| (i, o)))
        .map(|(i, o)| match o {
            Obstacle::Polygon(poly) => {
                let points: Vec<[f32; 2]> = (0..poly.vertex_count())
                    .filter_map(|k| poly.vertex(k))
                    .map(|v| [v.x, v.y])
                    .collect();
                json!({"id": i, "kind": "polygon", "points": points})
            }
            Obstacle::Circle { centre, radius } => {
                json!({"id": i, "kind": "circle", "centre": [centre.x, centre.y], "radius": radius})
            }
        })
        .collect();
    json!({
        "format": "skyroute-network-json",
        "format_version": JSON_FORMAT_VERSION,
        "network_format_version": FORMAT_VERSION,
        "frame": {
            "origin_lat_deg": lat0,
            "origin_lon_deg": lon0,
            "method": "transverse Mercator on WGS-84 centred on the origin (prep/src/frame.rs)",
        },
        "turn_radius_m": net.turn_radius(),
        "clearance_m": net.clearance(),
        "vertices": vertices,
        "edges": edges,
        "obstacles": obstacles,
        "provenance": (0..net.provenance_count())
            .filter_map(|i| net.provenance(i))
            .map(|r| json!({"kind": r.kind, "digest": format!("{:016x}", r.digest)}))
            .collect::<Vec<_>>(),
    })
}

/// Edge `i` as JSON: a Dubins word (or a terrain line) with its primitives, or a landmark
/// network's Hermite chain with its pieces. `None` only past the edge count.
fn edge_json(net: &Network, i: u32) -> Option<Value> {
    let r = net.edge_record(i)?;
    if let (Some(e), Some(path)) = (net.edge(i), net.edge_path(i)) {
        return Some(json!({
            "id": i,
            "from": e.source,
            "to": e.target,
            "cost": e.cost,
            "word": e.word.name(),
            "lengths": e.lengths,
            "primitives": path.primitives().iter().flatten().map(primitive_json).collect::<Vec<_>>(),
        }));
    }
    let pieces: Vec<Value> = (0..net.chain_piece_count(i))
        .filter_map(|k| net.chain_piece(i, k))
        .map(|seg| hermite_piece_json(&seg))
        .collect();
    Some(json!({
        "id": i,
        "from": net.edge_source(i)?,
        "to": r.target,
        "cost": r.cost,
        "word": "hermite_chain",
        "length": net.edge_length(i).unwrap_or(0.0),
        "pieces": pieces,
    }))
}

/// Reads the network image `input` and writes it as JSON to `output` (indented when `pretty`).
/// Returns the numbers of vertices, edges and obstacles. Errors name the file concerned.
pub fn export_file(input: &Path, output: &Path, pretty: bool) -> Result<(u32, u32, u32), String> {
    if !output
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("json"))
    {
        return Err(format!(
            "{}: export writes JSON; name the output .json",
            output.display()
        ));
    }
    crate::output::refuse_overwriting_inputs(output, &[input])?;
    let bytes = read_network(input)?;
    let net = Network::from_bytes(&bytes).map_err(|e| format!("{}: {e}", input.display()))?;
    let json = network_json(&net);
    let mut text = if pretty {
        serde_json::to_string_pretty(&json)
    } else {
        serde_json::to_string(&json)
    }
    .map_err(|e| format!("{}: {e}", output.display()))?;
    text.push('\n');
    crate::output::write_atomically(output, text.as_bytes())?;
    Ok((net.vertex_count(), net.edge_count(), net.obstacle_count()))
}
