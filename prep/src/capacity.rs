//! The planner capacities a network needs onboard, and the RAM a planner of those capacities
//! takes: what an integrator sizes `Planner<V, E, P, R>` with (`skyroute info`, the firmware
//! fixture).

use skyroute::network::Mode;
use skyroute::planner::MAX_LINKS;
use skyroute::{Network, Planner};

/// Pop-up slots of the firmware example's planner.
pub const FIRMWARE_POPUPS: usize = 4;
/// Route primitives (or landmark route edges) the firmware example's planner holds.
pub const FIRMWARE_ROUTE: usize = 128;

/// The smallest capacities a planner needs to load a network.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Needs {
    /// `V`: the search states: the vertices, or for a terrain network its directed edges plus
    /// [`MAX_LINKS`] start links (`Planner::load` refuses fewer with `TooManySearchStates`).
    pub states: usize,
    /// `E`: the edges.
    pub edges: usize,
}

/// What `network` needs of a planner.
pub fn needs(network: &Network) -> Needs {
    let (v, e) = (
        network.vertex_count() as usize,
        network.edge_count() as usize,
    );
    let states = match network.mode() {
        Mode::Terrain => e + MAX_LINKS,
        // The onboard graph is rebuilt when threats pop up: room for the most it can have.
        Mode::Voronoi => v.max(skyroute::planner::VORONOI_GRAPH_VERTICES),
        Mode::Roadmap | Mode::Landmark | Mode::Unknown(_) => v,
    };
    Needs { states, edges: e }
}

/// The search states a terrain query under the paper's turn rule
/// ([`TurnRule::Paper`](skyroute::TurnRule::Paper)) may need, whatever its start links:
/// `|E| + T + 2·Ks + 1 + Ks·max_out` with `Ks` = [`MAX_LINKS`], `T = Σ_v indeg(v)·outdeg(v)`
/// and `max_out` the largest out-degree (`planner/terrain`'s state layout); `None` for other
/// modes.
pub fn paper_turn_states(network: &Network) -> Option<usize> {
    match network.mode() {
        Mode::Terrain => {}
        Mode::Roadmap | Mode::Landmark | Mode::Voronoi | Mode::Unknown(_) => return None,
    }
    let mut transitions = 0usize;
    for e in 0..network.edge_count() {
        let (_, target) = network.edge_cost_target(e)?;
        transitions += network.out_edges(target).len();
    }
    let max_out = (0..network.vertex_count())
        .map(|v| network.out_edges(v).len())
        .max()
        .unwrap_or(0);
    Some(network.edge_count() as usize + transitions + 2 * MAX_LINKS + 1 + MAX_LINKS * max_out)
}

/// The bytes of a `Planner<V = v, E = e, P, R>`, from the sizes of three instances (a planner
/// grows linearly in `V` and `E`): exact up to alignment padding.
pub fn planner_bytes<const P: usize, const R: usize>(v: usize, e: usize) -> usize {
    use std::mem::size_of;
    const K: usize = 1024;
    let base = size_of::<Planner<'_, 0, 0, P, R>>();
    let per_vertex = size_of::<Planner<'_, K, 0, P, R>>() - base;
    let per_edge = size_of::<Planner<'_, 0, K, P, R>>() - base;
    base + (per_vertex * v).div_ceil(K) + (per_edge * e).div_ceil(K)
}

/// `n` with a little headroom, as the firmware example sizes its planner: +1/16, rounded up
/// to a multiple of `step`.
pub fn with_headroom(n: usize, step: usize) -> usize {
    (n + n / 16 + 1).div_ceil(step) * step
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn planner_bytes_matches_size_of_for_known_capacities() {
        assert_eq!(
            planner_bytes::<4, 128>(1536, 19712),
            std::mem::size_of::<Planner<'_, 1536, 19712, 4, 128>>()
        );
        assert_eq!(
            planner_bytes::<4, 128>(0, 0),
            std::mem::size_of::<Planner<'_, 0, 0, 4, 128>>()
        );
    }

    #[test]
    fn headroom_rounds_up_past_a_sixteenth() {
        assert_eq!(with_headroom(1445, 64), 1536);
        assert_eq!(with_headroom(0, 64), 64);
    }
}
