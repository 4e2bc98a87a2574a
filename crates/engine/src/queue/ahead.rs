//! Look-ahead hints: which discs the queue will hand out soon.
//!
//! The engine fetches the records (and neighbours) of discs whose events are near
//! before it needs them, which hides memory latency at large N. These read the
//! queue but never change what it hands out: the children of the current bucket's
//! heap head, the current bucket's discs, and the first discs filed in the bucket
//! k places ahead, b + k with b = ⌊(t − t₀)/Δ⌋. See docs/performance.md, "queue".

use super::{EventQueue, EventTimes, SLOT_DISCS};
use crate::NO_DISC;

impl EventQueue {
    /// Discs likely to have the events after the earliest: the two children of the
    /// head of the current bucket's heap ([`NO_DISC`] where there are none). A hint for
    /// fetching their records early; it says nothing certain about the order.
    #[inline]
    pub fn upcoming(&self) -> [u32; 2] {
        let at = |k: usize| self.heap.get(k).map_or(NO_DISC, |item| item.disc);
        [at(1), at(2)]
    }

    /// Whether the queue has moved on to another bucket since the last call (a hint
    /// for when to look [`ahead`](Self::ahead) again).
    #[inline]
    pub fn moved_on(&mut self) -> bool {
        std::mem::take(&mut self.moved)
    }

    /// Discs with events in the current bucket (stale items left out), in no
    /// particular order. A hint for fetching their neighbours early.
    #[inline]
    pub fn in_current_bucket<'a, T: EventTimes + ?Sized>(
        &'a self,
        times: &'a T,
    ) -> impl Iterator<Item = u32> + 'a {
        self.heap
            .iter()
            .filter(|item| times.time(item.disc) == item.time)
            .map(|item| item.disc)
    }

    /// Discs filed in the bucket `k` ≥ 1 places after the current one (the first
    /// [`SLOT_DISCS`] of them, [`NO_DISC`] after the last; some may be stale). A hint
    /// for fetching their records before they are needed.
    #[inline]
    pub fn ahead(&self, k: u64) -> &[u32; SLOT_DISCS] {
        // Wrapping: near the end of the bucket numbers the slot named is any slot,
        // which is harmless for a hint.
        &self.slots[(self.cur.wrapping_add(k) & self.mask) as usize].disc
    }

    /// The discs of [`ahead(k)`](Self::ahead) whose current time is still in that
    /// bucket (stale entries left out; this reads their times).
    #[inline]
    pub fn filed_ahead<'a, T: EventTimes + ?Sized>(
        &'a self,
        times: &'a T,
        k: u64,
    ) -> impl Iterator<Item = u32> + 'a {
        self.ahead(k)
            .iter()
            .take_while(|&&d| d != NO_DISC)
            .copied()
            .filter(move |&d| self.bucket(times.time(d)) == self.cur.wrapping_add(k))
    }
}
