//! JSON for routes and primitives, shared by `plan` and `export`.

use crate::frame::LocalFrame;
use crate::mission::Mission;
use serde_json::{json, Value};
use skyroute::geometry::hermite::HermiteSegment;
use skyroute::planner::Work;
use skyroute::{Primitive, Turn};

/// A primitive as JSON: `line` {start, end} or `arc` {centre, radius, start_angle, sweep, turn},
/// metres and radians in the local frame.
pub fn primitive_json(p: &Primitive) -> Value {
    match p {
        Primitive::Line(s) => {
            json!({"type": "line", "start": [s.start.x, s.start.y], "end": [s.end.x, s.end.y]})
        }
        Primitive::Arc(a) => json!({
            "type": "arc",
            "centre": [a.centre.x, a.centre.y],
            "radius": a.radius,
            "start_angle": a.start_angle,
            "sweep": a.sweep,
            "turn": if a.turn() == Turn::Left { "left" } else { "right" },
        }),
    }
}

/// A quintic Hermite piece as JSON: its two line elements (position, metres; velocity, m/s, in
/// the local frame), its parameter range and length, enough to rebuild it with
/// [`skyroute::geometry::hermite::HermiteSegment::new`] and sample it.
pub fn hermite_piece_json(seg: &HermiteSegment) -> Value {
    let (a, b) = (seg.start(), seg.end());
    json!({
        "from": {"position": [a.position.x, a.position.y], "velocity": [a.velocity.x, a.velocity.y]},
        "to": {"position": [b.position.x, b.position.y], "velocity": [b.velocity.x, b.velocity.y]},
        "t_max": seg.t_max(),
        "length": seg.length(),
    })
}

/// Work counters as JSON.
pub fn work_json(w: &Work) -> Value {
    json!({
        "total": w.total(),
        "vertex_scans": w.vertex_scans,
        "dubins_solves": w.dubins_solves,
        "collision_tests": w.collision_tests,
        "heap_steps": w.heap_steps,
        "relaxations": w.relaxations,
        "cells_visited": w.cells_visited,
        "threat_steps": w.threat_steps,
    })
}

/// Points every `step` metres along the primitives (and at each primitive's end), lon/lat.
pub fn sampled_lon_lat(primitives: &[Primitive], frame: &LocalFrame, step: f32) -> Vec<[f64; 2]> {
    let mut out = Vec::new();
    for p in primitives {
        let n = (p.length() / step).ceil().max(1.0) as usize;
        let first = if out.is_empty() { 0 } else { 1 };
        for i in first..=n {
            let q = p.pose_at(p.length() * i as f32 / n as f32).position;
            let (lon, lat) = frame.to_geo(q.x as f64, q.y as f64);
            out.push([lon, lat]);
        }
    }
    out
}

/// The route file written by `skyroute plan`.
pub fn mission_json(m: &Mission, frame: &LocalFrame, scenario_name: &str) -> Value {
    let all: Vec<Primitive> = m
        .legs
        .iter()
        .flat_map(|l| l.primitives.iter().copied())
        .collect();
    let (lat0, lon0) = frame.origin();
    json!({
        "scenario": scenario_name,
        "frame": {"origin_lat_deg": lat0, "origin_lon_deg": lon0, "method": "transverse Mercator on WGS-84 centred on the origin (prep/src/frame.rs)"},
        "length_m": m.length,
        "queries": m.queries,
        "work_all_queries": work_json(&m.work),
        "legs": m.legs.iter().map(|l| json!({
            "from": l.from,
            "to": l.to,
            "length_m": l.summary.length,
            "planned_length_m": l.planned_length,
            "network_edges": l.summary.network_edges,
            "arrival_heading_rad": l.summary.arrival_heading,
            "work": work_json(&l.summary.work),
            "exit": l.summary.exit.map(|e| json!({
                "region": match e.violated {
                    skyroute::planner::Violation::Obstacle(i) => json!({"obstacle": i}),
                    skyroute::planner::Violation::Popup(id) => json!({"popup": id}),
                },
                "regions": e.regions,
                "length_m": e.length,
            })),
            "primitives": l.primitives.iter().map(primitive_json).collect::<Vec<_>>(),
        })).collect::<Vec<_>>(),
        "geometry": {"type": "LineString", "coordinates": sampled_lon_lat(&all, frame, 5.0)},
    })
}
