//! A fixed-capacity indexed binary min-heap with decrease-key, over item ids `0..N`.
//!
//! Each operation reports the number of levels it sifted through, so the caller can count work:
//! a push, decrease or pop moves through at most `⌊log2 N⌋ + 1` levels (heap invariant, Cormen
//! et al. §6.5), which is what the planner's work bound charges for it.

/// Where an item stands in the heap's life cycle.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ItemState {
    /// Never pushed since the last [`IndexedHeap::clear`].
    Unseen,
    /// In the heap.
    Queued,
    /// Popped: its key is final.
    Done,
}

/// `position` values: 0 unseen, `DONE` popped, otherwise the item's heap index + 1. Zero for
/// "unseen" keeps a new heap all-zero, so a planner in a `static` lands in `.bss`, not in flash.
const UNSEEN: u32 = 0;
const DONE: u32 = u32::MAX;

/// A queued item: its key beside its id, so that comparing two heap entries reads one array.
#[derive(Clone, Copy, Debug)]
struct Slot {
    key: f32,
    id: u32,
}

/// The heap. Memory: 12·N bytes.
#[derive(Debug)]
pub struct IndexedHeap<const N: usize> {
    /// Heap-ordered items with their keys; the first `len` are live.
    slots: [Slot; N],
    /// Position + 1 of each item id in `slots`, or `UNSEEN` / `DONE`.
    position: [u32; N],
    len: usize,
}

impl<const N: usize> Default for IndexedHeap<N> {
    fn default() -> Self {
        Self::new()
    }
}

impl<const N: usize> IndexedHeap<N> {
    /// An empty heap (all items unseen).
    pub const fn new() -> Self {
        Self {
            slots: [Slot { key: 0.0, id: 0 }; N],
            position: [UNSEEN; N],
            len: 0,
        }
    }

    /// Empties the heap and marks the first `n` ids unseen. Work: `n`.
    pub fn clear(&mut self, n: usize) {
        for p in self.position.iter_mut().take(n) {
            *p = UNSEEN;
        }
        self.len = 0;
    }

    /// Number of queued items.
    pub fn len(&self) -> usize {
        self.len
    }

    /// Whether no item is queued.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The state of item `id` (ids out of range read as done, so they are never pushed).
    pub fn state(&self, id: u32) -> ItemState {
        match self.position.get(id as usize) {
            Some(&UNSEEN) => ItemState::Unseen,
            Some(&DONE) | None => ItemState::Done,
            Some(_) => ItemState::Queued,
        }
    }

    /// Inserts `id` with `key`, or lowers its key if it is queued with a larger one. Does nothing
    /// for a done item, an id out of range, or a key that is not lower. Returns the number of
    /// levels sifted (0 when nothing changed).
    pub fn push_or_decrease(&mut self, id: u32, key: f32) -> u32 {
        let Some(&p) = self.position.get(id as usize) else {
            return 0;
        };
        let at = match p {
            DONE => return 0,
            UNSEEN => {
                if self.len >= N {
                    return 0; // cannot happen: each id is queued at most once
                }
                self.len += 1;
                self.len - 1
            }
            p => {
                let at = p as usize - 1;
                if !self.slots.get(at).is_some_and(|s| key < s.key) {
                    return 0;
                }
                at
            }
        };
        self.sift_up(at, Slot { key, id }) + 1
    }

    /// Removes the item with the smallest key and marks it done. Returns it, its key and the
    /// number of levels sifted.
    pub fn pop(&mut self) -> Option<(u32, f32, u32)> {
        if self.len == 0 {
            return None;
        }
        let top = *self.slots.first()?;
        self.len -= 1;
        self.set_position(top.id, DONE);
        let mut levels = 1;
        if let Some(&last) = self.slots.get(self.len).filter(|_| self.len > 0) {
            levels += self.sift_down(last);
        }
        Some((top.id, top.key, levels))
    }

    fn set_position(&mut self, id: u32, position: u32) {
        if let Some(p) = self.position.get_mut(id as usize) {
            *p = position;
        }
    }

    /// Places `x` at the hole `at` (a live index) and moves it up past every parent with a
    /// larger key, each parent moving down into the hole: the moves of swapping `x` upwards,
    /// one write each. Returns the number of levels moved.
    fn sift_up(&mut self, mut at: usize, x: Slot) -> u32 {
        let mut levels = 0;
        // `len ≤ N` always; an inconsistent length leaves the heap as it is, without a panic.
        let Some(live) = self.slots.get_mut(..self.len) else {
            return levels;
        };
        while at > 0 {
            let parent = (at - 1) / 2;
            let Some(&above) = live.get(parent) else {
                break;
            };
            if x.key < above.key {
                if let Some(slot) = live.get_mut(at) {
                    *slot = above;
                }
                if let Some(p) = self.position.get_mut(above.id as usize) {
                    *p = at as u32 + 1;
                }
                at = parent;
                levels += 1;
            } else {
                break;
            }
        }
        if let Some(slot) = live.get_mut(at) {
            *slot = x;
        }
        self.set_position(x.id, at as u32 + 1);
        levels
    }

    /// Places `x` at the root's hole and moves it down while a child has a smaller key (the
    /// smaller child, the left one on a tie), each such child moving up into the hole: the
    /// moves of swapping `x` downwards, one write each. Returns the number of levels moved.
    fn sift_down(&mut self, x: Slot) -> u32 {
        let mut levels = 0;
        let mut at = 0;
        let Some(live) = self.slots.get_mut(..self.len) else {
            return levels;
        };
        loop {
            let (l, r) = (2 * at + 1, 2 * at + 2);
            let (mut smallest, mut key) = (at, x.key);
            if let Some(s) = live.get(l) {
                if s.key < key {
                    (smallest, key) = (l, s.key);
                }
            }
            if let Some(s) = live.get(r) {
                if s.key < key {
                    smallest = r;
                }
            }
            if smallest == at {
                break;
            }
            let Some(&below) = live.get(smallest) else {
                break;
            };
            if let Some(slot) = live.get_mut(at) {
                *slot = below;
            }
            if let Some(p) = self.position.get_mut(below.id as usize) {
                *p = at as u32 + 1;
            }
            at = smallest;
            levels += 1;
        }
        if let Some(slot) = live.get_mut(at) {
            *slot = x;
        }
        self.set_position(x.id, at as u32 + 1);
        levels
    }
}

/// `⌊log2 n⌋ + 1` for n ≥ 1 (1 for n = 0): the most levels one heap operation moves through.
pub const fn heap_levels(n: u64) -> u64 {
    if n == 0 {
        1
    } else {
        64 - n.leading_zeros() as u64
    }
}

#[cfg(test)]
mod tests {
    // The heap against a textbook binary heap written here (Cormen et al. §6: MIN-HEAP-INSERT,
    // HEAP-DECREASE-KEY and EXTRACT-MIN by swapping), driven by the same random operations:
    // every pop returns the same item and key, every operation reports the same number of
    // levels (the work the planner charges), and every id's state matches, including done
    // items, ids out of range, keys that are not lower, equal keys and partial clears. In the
    // crate rather than in host-tests so that `cargo mutants --file src/planner/heap.rs` runs
    // it against each mutant in seconds (docs/RELIABILITY.md).

    extern crate std;

    use super::*;
    use std::collections::HashSet;
    use std::vec::Vec;
    use std::{println, vec};

    /// SplitMix64 (Steele, Lea & Flood 2014): the tests' random numbers, seeded.
    struct Rng(u64);

    impl Rng {
        fn next_u64(&mut self) -> u64 {
            self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
            let mut z = self.0;
            z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
            z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
            z ^ (z >> 31)
        }
        /// Uniform integer in [0, n).
        fn below(&mut self, n: u64) -> u64 {
            self.next_u64() % n
        }
        /// Uniform in [lo, hi), f32 (24 bits).
        fn range_f32(&mut self, lo: f32, hi: f32) -> f32 {
            lo + (hi - lo) * ((self.next_u64() >> 40) as f32 / (1u64 << 24) as f32)
        }
    }

    const N: usize = 40;

    /// The reference: a vector heap of (key, id) moved by swaps, and each id's state.
    struct Textbook {
        heap: Vec<(f32, u32)>,
        state: Vec<ItemState>,
    }

    impl Textbook {
        fn new() -> Self {
            Textbook {
                heap: Vec::new(),
                state: vec![ItemState::Unseen; N],
            }
        }

        fn clear(&mut self, n: usize) {
            self.heap.clear();
            for s in self.state.iter_mut().take(n) {
                *s = ItemState::Unseen;
            }
        }

        fn state(&self, id: u32) -> ItemState {
            self.state
                .get(id as usize)
                .copied()
                .unwrap_or(ItemState::Done)
        }

        /// Swaps `at` up while its key is below its parent's; the number of swaps.
        fn bubble_up(&mut self, mut at: usize) -> u32 {
            let mut swaps = 0;
            while at > 0 && self.heap[at].0 < self.heap[(at - 1) / 2].0 {
                self.heap.swap(at, (at - 1) / 2);
                at = (at - 1) / 2;
                swaps += 1;
            }
            swaps
        }

        /// The levels the planner's heap reports: 0 if nothing changed, else 1 + the swaps.
        fn push_or_decrease(&mut self, id: u32, key: f32) -> u32 {
            match self.state(id) {
                ItemState::Done => 0,
                ItemState::Unseen => {
                    self.state[id as usize] = ItemState::Queued;
                    self.heap.push((key, id));
                    1 + self.bubble_up(self.heap.len() - 1)
                }
                ItemState::Queued => {
                    let at = self.heap.iter().position(|&(_, i)| i == id).unwrap();
                    if key < self.heap[at].0 {
                        self.heap[at].0 = key;
                        1 + self.bubble_up(at)
                    } else {
                        0
                    }
                }
            }
        }

        fn pop(&mut self) -> Option<(u32, f32, u32)> {
            if self.heap.is_empty() {
                return None;
            }
            let (key, id) = self.heap.swap_remove(0);
            self.state[id as usize] = ItemState::Done;
            let mut levels = 1;
            let mut at = 0;
            loop {
                let (l, r) = (2 * at + 1, 2 * at + 2);
                let mut smallest = at;
                if l < self.heap.len() && self.heap[l].0 < self.heap[smallest].0 {
                    smallest = l;
                }
                if r < self.heap.len() && self.heap[r].0 < self.heap[smallest].0 {
                    smallest = r;
                }
                if smallest == at {
                    break;
                }
                self.heap.swap(at, smallest);
                at = smallest;
                levels += 1;
            }
            Some((id, key, levels))
        }
    }

    /// A new key, below `below` if given: with `ties`, a whole number under 30 (so equal keys are
    /// frequent and the tie rule, the left child first, is compared too); otherwise one not used
    /// before.
    fn fresh_key(
        rng: &mut Rng,
        used: &mut HashSet<u32>,
        below: Option<f32>,
        ties: bool,
    ) -> Option<f32> {
        let top = below.unwrap_or(if ties { 30.0 } else { 1000.0 });
        for _ in 0..100 {
            let mut key = rng.range_f32(0.0, top);
            if ties {
                key = key.floor();
                if key < top {
                    return Some(key);
                }
            } else if used.insert(key.to_bits()) {
                return Some(key);
            }
        }
        None
    }

    #[test]
    fn the_indexed_heap_pops_and_counts_levels_as_a_textbook_heap() {
        let mut rng = Rng(61);
        let (mut pops, mut decreases, mut refused) = (0u64, 0u64, 0u64);
        for case in 0..400 {
            let ties = case % 2 == 1;
            let mut heap = IndexedHeap::<N>::new();
            let mut reference = Textbook::new();
            let mut used = HashSet::new();
            heap.clear(N);
            // `clear(n)` promises nothing for ids from n on (the planner clears every id it
            // uses): after a partial clear only the first n ids are used, and three out of range.
            let mut in_play = N;
            for _ in 0..300 {
                match rng.below(10) {
                    0..=4 => {
                        // Push, decrease, or a call that must change nothing: a done item, an id
                        // out of range, a key that is not lower.
                        let pick = rng.below(in_play as u64 + 3) as usize;
                        let id = if pick < in_play {
                            pick
                        } else {
                            N + pick - in_play
                        } as u32;
                        let lower = reference.state(id) == ItemState::Queued && rng.below(3) > 0;
                        let current = reference
                            .heap
                            .iter()
                            .find(|&&(_, i)| i == id)
                            .map(|&(k, _)| k);
                        let key = if lower {
                            fresh_key(&mut rng, &mut used, current, ties)
                        } else if let (Some(k), true) = (current, rng.below(2) == 0) {
                            Some(k) // the same key: not lower
                        } else {
                            fresh_key(&mut rng, &mut used, None, ties)
                        };
                        let Some(key) = key else { continue };
                        let expected = reference.push_or_decrease(id, key);
                        let got = heap.push_or_decrease(id, key);
                        assert_eq!(got, expected, "push_or_decrease({id}, {key})");
                        decreases += (lower && expected > 0) as u64;
                        refused += (expected == 0) as u64;
                    }
                    5..=8 => {
                        let expected = reference.pop();
                        assert_eq!(heap.pop(), expected);
                        pops += expected.is_some() as u64;
                    }
                    _ => {
                        if rng.below(8) == 0 {
                            let n = rng.below(N as u64 + 1) as usize;
                            reference.clear(n);
                            heap.clear(n);
                            in_play = n;
                        }
                    }
                }
                assert_eq!(heap.len(), reference.heap.len());
                assert_eq!(heap.is_empty(), reference.heap.is_empty());
                for id in (0..in_play as u32).chain(N as u32..N as u32 + 3) {
                    assert_eq!(heap.state(id), reference.state(id), "id {id}");
                }
            }
            while let Some(expected) = reference.pop() {
                assert_eq!(heap.pop(), Some(expected));
                pops += 1;
            }
            assert_eq!(heap.pop(), None);
            assert!(heap.is_empty());
        }
        println!("{pops} pops, {decreases} decreases, {refused} calls that changed nothing");
        assert!(pops > 1000 && decreases > 100 && refused > 100);
    }

    /// Pushing ids in falling key order sifts each new item to the root: the i-th push (from 0)
    /// moves through ⌊log2(i + 1)⌋ + 1 levels, which `heap_levels` gives for a heap of i + 1 items
    /// and is the planner's charge per heap operation.
    #[test]
    fn heap_levels_is_the_depth_of_a_complete_heap_plus_one() {
        assert_eq!(heap_levels(0), 1);
        for n in 1..=4096u64 {
            assert_eq!(
                heap_levels(n),
                (n as f64).log2().floor() as u64 + 1,
                "n = {n}"
            );
        }
        assert_eq!(heap_levels(u64::MAX), 64);
        let mut heap = IndexedHeap::<N>::new();
        heap.clear(N);
        for id in 0..N as u32 {
            let levels = heap.push_or_decrease(id, 1000.0 - id as f32);
            assert_eq!(levels as u64, heap_levels(id as u64 + 1), "push {id}");
        }
    }
}
