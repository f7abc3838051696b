//! The writer's landmark section: the record, the landmarks, the rosettes, the chain offsets,
//! the chains as index lists and each distinct line element once.

use super::{count, push, EdgeSpec, LandmarkSpec, NetworkSpec, WriteError};
use crate::geometry::hermite::LineElement;
use crate::geometry::DubinsWord;
use crate::network::format::*;
use std::vec::Vec;

/// Landmark mode: writes the landmark record, the landmarks, the rosettes, the chain offsets
/// and the chains' line elements.
pub(super) fn write_landmark_section(
    body: &mut Vec<u8>,
    l: &LandmarkSpec,
    chains: &[&[LineElement]],
) -> Result<(), WriteError> {
    let chain_index_count = count(chains.iter().map(|c| c.len()).sum(), "line elements")?;
    // Each distinct element once (bit for bit), the chains as lists of indices into them.
    let mut distinct: Vec<LineElement> = Vec::new();
    let mut index_of: std::collections::HashMap<[u32; 4], u16> = std::collections::HashMap::new();
    let mut indices: Vec<u16> = Vec::with_capacity(chain_index_count as usize);
    for el in chains.iter().flat_map(|c| c.iter()) {
        let key = [
            el.position.x.to_bits(),
            el.position.y.to_bits(),
            el.velocity.x.to_bits(),
            el.velocity.y.to_bits(),
        ];
        let i = match index_of.get(&key) {
            Some(&i) => i,
            None => {
                let i = u16::try_from(distinct.len())
                    .ok()
                    .filter(|&i| u32::from(i) < MAX_LINE_ELEMENTS)
                    .ok_or(WriteError::TooLarge(
                        "distinct line elements (16-bit indices: at most 65536)",
                    ))?;
                distinct.push(*el);
                index_of.insert(key, i);
                i
            }
        };
        indices.push(i);
    }
    push(
        body,
        &LandmarkRecord {
            landmark_count: count(l.landmarks.len(), "landmarks")?,
            directions: l.directions,
            weather_count: l.weather_count,
            v_nominal: l.v_nominal,
            v_min: l.limits.v_min,
            v_max: l.limits.v_max,
            a_long_min: l.limits.a_long_min,
            a_long_max: l.limits.a_long_max,
            a_lat_max: l.limits.a_lat_max,
            start_vertex: l.start_vertex.unwrap_or(LandmarkRecord::ABSENT),
            goal_vertex: l.goal_vertex.unwrap_or(LandmarkRecord::ABSENT),
            start_range_m: l.start_range_m,
            element_count: distinct.len() as u32,
            chain_index_count,
        },
    );
    for site in &l.landmarks {
        push(
            body,
            &LandmarkSiteRecord {
                x: site.position.x,
                y: site.position.y,
                d_max: site.d_max_m,
            },
        );
    }
    for q in &l.qualities {
        push(body, &F32Record(*q));
    }
    let mut at = 0u32;
    push(body, &U32Record(0));
    for c in chains {
        at += c.len() as u32;
        push(body, &U32Record(at));
    }
    for i in indices {
        push(body, &U16Record(i));
    }
    for el in &distinct {
        push(
            body,
            &ElementRecord {
                x: el.position.x,
                y: el.position.y,
                vx: el.velocity.x,
                vy: el.velocity.y,
            },
        );
    }
    Ok(())
}

/// Landmark mode: the tables agree with the vertices and edges.
pub(super) fn check_landmark(
    spec: &NetworkSpec,
    l: &LandmarkSpec,
    edges: &[EdgeSpec],
) -> Result<(), WriteError> {
    let bad = |what| Err(WriteError::BadLandmark(what));
    let overflights = l.landmarks.len() as u64 * l.directions as u64;
    let endpoints = l.start_vertex.is_some() as u64 + l.goal_vertex.is_some() as u64;
    if overflights + endpoints != spec.vertices.len() as u64 {
        return bad("vertex count is not landmarks x directions plus the endpoints");
    }
    if l.qualities.len() as u64 != overflights * l.weather_count as u64 {
        return bad("quality count is not landmarks x weathers x directions");
    }
    if l.chains.len() != spec.edges.len() {
        return bad("one chain per edge needed");
    }
    if edges
        .iter()
        .any(|e| e.word != DubinsWord::Lsl || e.lengths[1] != 0.0 || e.lengths[2] != 0.0)
    {
        return bad("an edge is not a Hermite chain (EdgeSpec::chain)");
    }
    if l.chains.iter().any(|c| c.len() < 2) {
        return bad("a chain has fewer than 2 line elements");
    }
    Ok(())
}
