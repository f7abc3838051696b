//! JSON for routes and primitives, shared by `plan` and `export`.

use crate::frame::LocalFrame;
use crate::mission::Mission;
use serde_json::{json, Value};
use skyroute::geometry::hermite::HermiteSegment;
use skyroute::geometry::vertical::{VerticalLimits, VerticalProfile};
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

/// A primitive's altitude on a three-dimensional roadmap: the profile of the path it belongs
/// to (`from_m` → `to_m` over `path_length_m`, rebuilt with
/// [`skyroute::geometry::vertical::VerticalProfile::new`] and the route's `vertical` limits)
/// and the distance along that path at which it starts (`offset_m`); with its altitudes at its
/// two ends for reading.
pub fn primitive_altitude_json(p: &Primitive, profile: &VerticalProfile, offset: f32) -> Value {
    json!({
        "from_m": profile.from,
        "to_m": profile.to,
        "path_length_m": profile.length,
        "offset_m": offset,
        "start_m": profile.altitude_at(offset),
        "end_m": profile.altitude_at(offset + p.length()),
    })
}

/// A three-dimensional roadmap's vertical limits as JSON.
pub fn vertical_limits_json(l: &VerticalLimits) -> Value {
    json!({
        "airspeed_mps": l.airspeed,
        "climb_rate_mps": l.climb_rate,
        "vertical_accel_mps2": l.vertical_accel,
    })
}

/// Points every `step` metres along the primitives (and at each primitive's end) as
/// `[lon, lat, altitude]`, each primitive flown with its profile and offset (`vertical`, one
/// per primitive).
pub fn sampled_lon_lat_alt(
    primitives: &[Primitive],
    vertical: &[(VerticalProfile, f32)],
    frame: &LocalFrame,
    step: f32,
) -> Vec<[f64; 3]> {
    let mut out = Vec::new();
    for (p, (profile, offset)) in primitives.iter().zip(vertical) {
        let n = (p.length() / step).ceil().max(1.0) as usize;
        let first = if out.is_empty() { 0 } else { 1 };
        for i in first..=n {
            let s = p.length() * i as f32 / n as f32;
            let q = p.pose_at(s).position;
            let (lon, lat) = frame.to_geo(q.x as f64, q.y as f64);
            out.push([lon, lat, profile.altitude_at(offset + s) as f64]);
        }
    }
    out
}

/// A leg's primitives as JSON, each with its altitude on a three-dimensional roadmap.
fn leg_primitives_json(l: &crate::mission::Leg) -> Vec<Value> {
    l.primitives
        .iter()
        .enumerate()
        .map(|(k, p)| {
            let mut v = primitive_json(p);
            if let (Some((profile, offset)), Some(o)) = (l.vertical.get(k), v.as_object_mut()) {
                o.insert(
                    "altitude".into(),
                    primitive_altitude_json(p, profile, *offset),
                );
            }
            v
        })
        .collect()
}

/// The route file written by `skyroute plan`.
pub fn mission_json(m: &Mission, frame: &LocalFrame, scenario_name: &str) -> Value {
    let all: Vec<Primitive> = m
        .legs
        .iter()
        .flat_map(|l| l.primitives.iter().copied())
        .collect();
    let vertical: Vec<(VerticalProfile, f32)> = m
        .legs
        .iter()
        .flat_map(|l| l.vertical.iter().copied())
        .collect();
    let geometry = match m.vertical_limits.is_some() && vertical.len() == all.len() {
        true => {
            json!({"type": "LineString", "coordinates": sampled_lon_lat_alt(&all, &vertical, frame, 5.0)})
        }
        false => json!({"type": "LineString", "coordinates": sampled_lon_lat(&all, frame, 5.0)}),
    };
    let (lat0, lon0) = frame.origin();
    let mut route = json!({
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
            "primitives": leg_primitives_json(l),
        })).collect::<Vec<_>>(),
        "geometry": geometry,
    });
    if let (Some(limits), Some(o)) = (&m.vertical_limits, route.as_object_mut()) {
        o.insert("vertical".into(), vertical_limits_json(limits));
    }
    route
}
