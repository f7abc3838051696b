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
    use super::*;

    #[test]
    fn pops_in_key_order_with_decrease_key() {
        let mut h = IndexedHeap::<64>::new();
        h.clear(64);
        let mut x = 12345u32;
        let mut keys = [0f32; 64];
        for id in 0..64u32 {
            x = x.wrapping_mul(1664525).wrapping_add(1013904223);
            keys[id as usize] = (x >> 8) as f32;
            h.push_or_decrease(id, keys[id as usize]);
        }
        for id in (0..64u32).step_by(3) {
            keys[id as usize] *= 0.5;
            h.push_or_decrease(id, keys[id as usize]);
        }
        let mut last = f32::NEG_INFINITY;
        let mut n = 0;
        while let Some((id, k, levels)) = h.pop() {
            assert_eq!(k, keys[id as usize]);
            assert!(k >= last);
            assert!(levels as u64 <= heap_levels(64));
            assert_eq!(h.state(id), ItemState::Done);
            last = k;
            n += 1;
        }
        assert_eq!(n, 64);
    }
}
