//! Terrain search states under each [`TurnRule`]: where they lie in the planner's state arrays,
//! what a state stands for ([`Arrived`]), and the expansion of a state (the module doc of
//! `planner/terrain` gives the rules and the costs).
//!
//! Layout, with `Ks` the query's start links and straights numbered as the network's edges
//! (`0..|E|`) and then the start links (`|E| + k`):
//!
//! * [`TurnRule::SharedEqually`]: state `e < |E|` is edge `e`, state `|E| + k` start link `k`.
//! * [`TurnRule::Paper`]: `via[p]` for `p ≤ |E| + Ks` is the offset table `O[p]` =
//!   `Σ_{q<p} outdeg(end of straight q)` (no states there); start link `k` is state
//!   `|E| + Ks + 1 + k`; the pair (straight `p`, the `j`-th out-edge of its end) is state
//!   `|E| + 2·Ks + 1 + O[p] + j`. A pair state is decoded by a binary search of the table.

use super::fillet::{Fillet, ON_NODE_M};
use crate::geometry::{DubinsPath, Vec2};
use crate::planner::heap::ItemState;
use crate::planner::search::Arrival;
use crate::planner::{Meter, PlanError, Planner, TurnRule};

#[cfg(all(test, feature = "std"))]
mod tests;

/// `via` of a start-link state: no previous state.
pub(super) const NO_PREVIOUS: u32 = u32::MAX;

/// Where a query's states lie ([`TurnRule`] and counts; the module doc gives the layout).
#[derive(Clone, Copy, Debug)]
pub(super) struct Layout {
    /// The turn rule of the query.
    rule: TurnRule,
    /// Network edges, |E|.
    edges: u32,
    /// The query's start links, Ks.
    links: u32,
}

impl Layout {
    /// Straights: the edges, then the start links.
    fn straights(&self) -> u32 {
        self.edges + self.links
    }

    /// The state of start link `k`.
    fn link_state(&self, k: u32) -> u32 {
        match self.rule {
            TurnRule::SharedEqually => self.edges + k,
            TurnRule::Paper => self.straights() + 1 + k,
        }
    }

    /// The start link whose state `s` is, if it is one.
    pub(super) fn link_of(&self, s: u32) -> Option<u32> {
        let first = self.link_state(0);
        (s >= first && s - first < self.links).then(|| s - first)
    }

    /// The paper's rule: the first pair state.
    fn pair_base(&self) -> u32 {
        self.straights() + 1 + self.links
    }
}

impl TurnRule {
    /// For a turn of cut `cut` at the start of a next straight of length `length`: the share
    /// `sₒ` of the straight it takes and the key point `kₒ` (the module doc), or `None` if the
    /// turn does not fit that straight. The equal split gives the turn half and counts the
    /// straight whole (`ℓ/2`, `ℓ`); the paper's rule gives it the cut itself, leaving `ℓ − c`
    /// to the far end, and counts up to the cut (`c`, `c`).
    fn start_share(self, cut: f32, length: f32) -> Option<(f32, f32)> {
        match self {
            TurnRule::SharedEqually => (cut <= 0.5 * length).then_some((0.5 * length, length)),
            TurnRule::Paper => (cut <= length).then_some((cut, cut)),
        }
    }

    /// The most a turn may cut of a goal link's straight of length `length` (which has no
    /// turn at the goal).
    fn goal_room(self, length: f32) -> f32 {
        match self {
            TurnRule::SharedEqually => 0.5 * length,
            TurnRule::Paper => length,
        }
    }
}

/// A state: "arrived at `node`, the end of straight `straight`, with `start_share` of the
/// straight's start given to the turn there".
#[derive(Clone, Copy, Debug)]
pub(super) struct Arrived {
    /// The straight: an edge index, or `|E| + k` for start link `k`.
    pub(super) straight: u32,
    /// Its end node.
    pub(super) node: u32,
    /// The end node's position.
    pub(super) position: Vec2,
    /// The straight's unit direction.
    pub(super) direction: Vec2,
    /// The straight's length `ℓ`.
    pub(super) length: f32,
    /// `s`: the equal split's `ℓ/2`, the paper's rule's cut at the start, 0 for a start link.
    pub(super) start_share: f32,
    /// `k`: the state's key counts the straight up to this far from its start (the equal
    /// split's `ℓ`; the paper's rule's cut at the start, 0 for a start link).
    pub(super) key_point: f32,
    /// The straight's start node (`None` for a start link).
    pub(super) from: Option<u32>,
}

impl Arrived {
    /// The most the turn at the end may cut: `ℓ − s` (for a start link on the node, of length
    /// 0, [`ON_NODE_M`]).
    pub(super) fn room(&self) -> f32 {
        let room = self.length - self.start_share;
        match self.from {
            Some(_) => room,
            None => room.max(ON_NODE_M),
        }
    }

    /// What the state's key leaves out of the straight: `ℓ − k`.
    fn uncounted(&self) -> f32 {
        self.length - self.key_point
    }
}

/// A straight's end node, its position, unit direction and length.
#[derive(Clone, Copy, Debug)]
struct Straight {
    to: u32,
    position: Vec2,
    direction: Vec2,
    length: f32,
}

/// The direction a goal link leaves its node in: its own, or — for a free-heading goal on the
/// node (a straight of length 0) — the direction the route arrives in, so that arriving at the
/// node is arriving at the goal, with no turn.
pub(super) fn goal_direction(at: &Arrived, link: &DubinsPath) -> Vec2 {
    let on_node = link.lengths[0] == 0.0 && link.lengths[2] == 0.0 && link.lengths[1] <= ON_NODE_M;
    if on_node {
        at.direction
    } else {
        Vec2::from_angle(link.start.heading)
    }
}

impl<'n, const V: usize, const E: usize, const P: usize, const R: usize> Planner<'n, V, E, P, R> {
    /// The layout of this query's states.
    pub(super) fn terrain_layout(&self) -> Layout {
        Layout {
            rule: self.config().turn_rule,
            edges: self.network.edge_count(),
            links: self.start_links.len() as u32,
        }
    }

    /// The number of states of this query; under the paper's rule, writes the offset table
    /// first (one vertex scan per straight). Refuses a query whose states exceed `V`.
    pub(in crate::planner) fn prepare_edge_states(
        &mut self,
        meter: &mut Meter,
    ) -> Result<usize, PlanError> {
        let layout = self.terrain_layout();
        let states = match layout.rule {
            TurnRule::SharedEqually => layout.straights() as u64,
            TurnRule::Paper => {
                let mut offset = 0u64;
                for p in 0..=layout.straights() {
                    meter.work.vertex_scans += 1;
                    if let Some(slot) = self.via.get_mut(p as usize) {
                        *slot = u32::try_from(offset).unwrap_or(u32::MAX);
                    }
                    if p < layout.straights() {
                        let end = self.straight_end(layout, p)?;
                        offset += self.network.out_edges(end).len() as u64;
                    }
                }
                layout.pair_base() as u64 + offset
            }
        };
        if states > V as u64 {
            return Err(PlanError::TooManySearchStates {
                needed: u32::try_from(states).unwrap_or(u32::MAX),
                capacity: u32::try_from(V).unwrap_or(u32::MAX),
            });
        }
        Ok(states as usize)
    }

    /// The end node of straight `p`.
    fn straight_end(&self, layout: Layout, p: u32) -> Result<u32, PlanError> {
        if p < layout.edges {
            let (_, target) = self
                .network
                .edge_cost_target(p)
                .ok_or(PlanError::Internal)?;
            Ok(target)
        } else {
            let link = self
                .start_links
                .get((p - layout.edges) as usize)
                .ok_or(PlanError::Internal)?;
            Ok(link.vertex)
        }
    }

    /// Edge `e` leaving node `source` as a straight.
    fn edge_straight(&self, source: u32, e: u32) -> Result<Straight, PlanError> {
        let (_, to) = self
            .network
            .edge_cost_target(e)
            .ok_or(PlanError::Internal)?;
        let a = self.network.vertex(source).ok_or(PlanError::Internal)?;
        let b = self.network.vertex(to).ok_or(PlanError::Internal)?;
        let length = a.position.distance(b.position);
        Ok(Straight {
            to,
            position: b.position,
            direction: (b.position - a.position) * (1.0 / length),
            length,
        })
    }

    /// Straight `p` arrived along, with the start share and key point `shares` gives for its
    /// length.
    fn arrived_on(
        &self,
        layout: Layout,
        p: u32,
        shares: impl FnOnce(f32) -> (f32, f32),
    ) -> Result<Arrived, PlanError> {
        if p < layout.edges {
            let from = self.network.edge_source(p).ok_or(PlanError::Internal)?;
            let st = self.edge_straight(from, p)?;
            if !(st.length > 0.0) {
                return Err(PlanError::Internal);
            }
            let (start_share, key_point) = shares(st.length);
            Ok(Arrived {
                straight: p,
                node: st.to,
                position: st.position,
                direction: st.direction,
                length: st.length,
                start_share,
                key_point,
                from: Some(from),
            })
        } else {
            let link = self
                .start_links
                .get((p - layout.edges) as usize)
                .ok_or(PlanError::Internal)?;
            let position = self
                .network
                .vertex(link.vertex)
                .ok_or(PlanError::Internal)?
                .position;
            let (start_share, key_point) = shares(link.path.lengths[1]);
            Ok(Arrived {
                straight: p,
                node: link.vertex,
                position,
                direction: Vec2::from_angle(link.path.end().heading),
                length: link.path.lengths[1],
                start_share,
                key_point,
                from: None,
            })
        }
    }

    /// Where search state `s` stands; adds the table reads of a decoding (paper's rule) to
    /// `reads`.
    pub(super) fn arrived(&self, s: u32, reads: &mut u64) -> Result<Arrived, PlanError> {
        let layout = self.terrain_layout();
        if let Some(k) = layout.link_of(s) {
            // No turn at its start: share 0; the equal split counts it whole.
            let key_point = |l| match layout.rule {
                TurnRule::SharedEqually => l,
                TurnRule::Paper => 0.0,
            };
            return self.arrived_on(layout, layout.edges + k, |l| (0.0, key_point(l)));
        }
        match layout.rule {
            TurnRule::SharedEqually => self.arrived_on(layout, s, |l| (0.5 * l, l)),
            TurnRule::Paper => {
                let x = s
                    .checked_sub(layout.pair_base())
                    .ok_or(PlanError::Internal)?;
                // The last straight p with O[p] ≤ x: O[0] = 0 ≤ x, and O[|E| + Ks] > x for a
                // state below the count.
                let (mut lo, mut hi) = (0u32, layout.straights());
                while hi - lo > 1 {
                    *reads += 1;
                    let mid = lo + (hi - lo) / 2;
                    if *self.via.get(mid as usize).ok_or(PlanError::Internal)? <= x {
                        lo = mid;
                    } else {
                        hi = mid;
                    }
                }
                let first = *self.via.get(lo as usize).ok_or(PlanError::Internal)?;
                let before = self.arrived_on(layout, lo, |_| (0.0, 0.0))?;
                let e = self.network.out_edges(before.node).start + (x - first);
                let at = self.arrived_on(layout, e, |_| (0.0, 0.0))?;
                let r = self.network.turn_radius();
                let cut = Fillet::new(before.direction, at.direction, r).cut;
                Ok(Arrived {
                    start_share: cut,
                    key_point: cut,
                    ..at
                })
            }
        }
    }

    /// The state of taking out-edge `e` (the `slot`-th of its node) after `at`.
    fn next_state(&self, layout: Layout, at: &Arrived, e: u32, slot: u32) -> Option<u32> {
        match layout.rule {
            TurnRule::SharedEqually => Some(e),
            TurnRule::Paper => {
                let first = *self.via.get(at.straight as usize)?;
                Some(layout.pair_base() + first + slot)
            }
        }
    }

    /// Queues the start links' states at their keys: the link's length (the equal split), or
    /// its initial arc (the paper's rule: key point 0).
    #[inline(never)]
    pub(in crate::planner) fn seed_edge_states(
        &mut self,
        meter: &mut Meter,
    ) -> Result<(), PlanError> {
        let layout = self.terrain_layout();
        for k in 0..self.start_links.len() {
            let s = layout.link_state(k as u32);
            let Some(key) = self.start_links.get(k).map(|link| match layout.rule {
                TurnRule::SharedEqually => link.path.length(),
                TurnRule::Paper => link.path.lengths[0] + link.path.lengths[2],
            }) else {
                return Err(PlanError::Internal);
            };
            let (Some(d), Some(via)) =
                (self.dist.get_mut(s as usize), self.via.get_mut(s as usize))
            else {
                return Err(PlanError::Internal);
            };
            *d = key;
            *via = NO_PREVIOUS;
            meter.work.heap_steps += self.heap.push_or_decrease(s, key) as u64;
        }
        Ok(())
    }

    /// Expands state `s` (popped at key `ds`): offers the goal links leaving its node, turn
    /// checked, to `best`, and relaxes the transitions to the node's usable out-edges whose
    /// turn fits and is clear (the turn is checked only for a transition that would improve
    /// its target). Returns `false`: an edge-state search has no target state.
    #[inline(never)]
    pub(in crate::planner) fn expand_edge_state(
        &mut self,
        s: u32,
        ds: f32,
        best: &mut Option<(f32, Arrival)>,
        meter: &mut Meter,
    ) -> Result<bool, PlanError> {
        let r = self.network.turn_radius();
        let layout = self.terrain_layout();
        let at = self.arrived(s, &mut meter.work.vertex_scans)?;
        let room = at.room();
        meter.work.vertex_scans += 1;
        for k in 0..self.goal_links.len() {
            meter.work.relaxations += 1;
            let link = *self.goal_links.get(k).ok_or(PlanError::Internal)?;
            if link.vertex != at.node {
                continue;
            }
            let out = goal_direction(&at, &link.path);
            let fillet = Fillet::new(at.direction, out, r);
            let on_goal = out == at.direction;
            if fillet.cut > room
                || (!on_goal && fillet.cut > layout.rule.goal_room(link.path.lengths[1]))
            {
                continue;
            }
            let total = ds + at.uncounted() + link.path.length() + fillet.saving(r);
            if best.is_none_or(|(b, _)| total < b) && self.fillet_is_clear(&at, &fillet, meter) {
                *best = Some((total, Arrival::FromState { state: s, link: k }));
            }
        }
        let out_edges = self.network.out_edges(at.node);
        for e in out_edges.clone() {
            meter.work.relaxations += 1;
            if !self.is_edge_usable_from(at.node, e) {
                continue;
            }
            let next = self.edge_straight(at.node, e)?;
            if Some(next.to) == at.from || !(next.length > 0.0) {
                continue;
            }
            let fillet = Fillet::new(at.direction, next.direction, r);
            let Some((_, key_point)) = layout.rule.start_share(fillet.cut, next.length) else {
                continue;
            };
            if fillet.cut > room {
                continue;
            }
            // The step `(ℓᵢ − kᵢ) + kₒ + r·θ − 2c`, never negative (the module doc).
            let candidate = ds + at.uncounted() + key_point + fillet.saving(r);
            let t = self
                .next_state(layout, &at, e, e - out_edges.start)
                .ok_or(PlanError::Internal)?;
            let state = self.heap.state(t);
            let improves = state == ItemState::Unseen
                || (state == ItemState::Queued
                    && self.dist.get(t as usize).is_some_and(|d| candidate < *d));
            if !improves || !self.fillet_is_clear(&at, &fillet, meter) {
                continue;
            }
            let (Some(dt), Some(via)) =
                (self.dist.get_mut(t as usize), self.via.get_mut(t as usize))
            else {
                return Err(PlanError::Internal);
            };
            *dt = candidate;
            *via = s;
            meter.work.heap_steps += self.heap.push_or_decrease(t, candidate) as u64;
        }
        Ok(false)
    }
}
