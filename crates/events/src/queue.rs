//! The event queue: one pending event time per disc, in a tournament tree.
//!
//! Every disc owns exactly one slot holding the time of its earliest predicted event
//! (`+∞` for none). The tree stores, at every internal node, the earlier of its two
//! children, so the root is the next event of the whole system. Changing a disc's
//! time walks from its leaf towards the root and stops as soon as a node is
//! unchanged. Keys are [`NotNan<f64>`](ordered_float::NotNan): a NaN can never enter.
//!
//! Ties are broken deterministically by disc index: the left subtree holds the
//! smaller indices and wins equal times.

use ordered_float::NotNan;

/// Event time in the queue's key type (time unit of the simulation, never NaN).
pub type Time = NotNan<f64>;

/// A tournament tree of per-disc event times.
#[derive(Debug, Clone)]
pub struct EventQueue {
    /// Number of leaves, a power of two ≥ the number of discs.
    leaves: usize,
    /// Node times; node 1 is the root, leaf k is at `leaves + k`.
    time: Vec<Time>,
    /// Disc index winning each node.
    who: Vec<u32>,
}

const NEVER: f64 = f64::INFINITY;

impl EventQueue {
    /// A queue for `n` discs, every slot empty (time +∞).
    pub fn new(n: usize) -> Self {
        let leaves = n.max(1).next_power_of_two();
        let inf = NotNan::new(NEVER).expect("infinity is not NaN");
        let mut who = vec![0u32; 2 * leaves];
        for k in 0..leaves {
            who[leaves + k] = k as u32;
        }
        // Internal nodes start as the leftmost leaf below them.
        for node in (1..leaves).rev() {
            who[node] = who[2 * node];
        }
        EventQueue {
            leaves,
            time: vec![inf; 2 * leaves],
            who,
        }
    }

    /// The earliest event: (time, disc). With all slots empty the time is +∞.
    #[inline]
    pub fn peek(&self) -> (Time, u32) {
        (self.time[1], self.who[1])
    }

    /// The time currently stored for disc `i`.
    #[inline]
    pub fn get(&self, i: u32) -> Time {
        self.time[self.leaves + i as usize]
    }

    /// Set the event time of disc `i` and restore the tree above it.
    #[inline]
    pub fn set(&mut self, i: u32, t: Time) {
        let mut node = self.leaves + i as usize;
        self.time[node] = t;
        while node > 1 {
            let parent = node >> 1;
            let left = parent << 1;
            let (lt, rt) = (self.time[left], self.time[left + 1]);
            // Left wins ties: it holds the smaller disc indices.
            let win = if rt < lt { left + 1 } else { left };
            let (wt, ww) = (self.time[win], self.who[win]);
            if self.time[parent] == wt && self.who[parent] == ww {
                // The parent holds what it held before, so nothing above it changes.
                break;
            }
            self.time[parent] = wt;
            self.who[parent] = ww;
            node = parent;
        }
    }

    /// Bytes of heap memory used (for the memory report).
    pub fn heap_bytes(&self) -> usize {
        self.time.capacity() * std::mem::size_of::<Time>()
            + self.who.capacity() * std::mem::size_of::<u32>()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn t(x: f64) -> Time {
        NotNan::new(x).unwrap()
    }

    #[test]
    fn ties_go_to_the_smaller_index() {
        let mut q = EventQueue::new(5);
        q.set(3, t(1.0));
        q.set(1, t(1.0));
        q.set(4, t(1.0));
        assert_eq!(q.peek(), (t(1.0), 1));
        q.set(1, t(2.0));
        assert_eq!(q.peek(), (t(1.0), 3));
    }

    proptest! {
        /// After any sequence of updates the root is the (time, index) minimum.
        #[test]
        fn root_is_lexicographic_minimum(n in 1usize..40, ops in proptest::collection::vec((0usize..40, 0u8..6), 1..200)) {
            let mut q = EventQueue::new(n);
            let mut model = vec![f64::INFINITY; n];
            for (i, v) in ops {
                let i = i % n;
                let v = if v == 5 { f64::INFINITY } else { v as f64 };
                q.set(i as u32, t(v));
                model[i] = v;
                let (bt, bi) = model.iter().enumerate()
                    .fold((f64::INFINITY, 0usize), |acc, (k, &x)| if x < acc.0 { (x, k) } else { acc });
                let (qt, qi) = q.peek();
                prop_assert_eq!(qt.into_inner(), bt);
                if bt.is_finite() { prop_assert_eq!(qi as usize, bi); }
            }
        }
    }
}
