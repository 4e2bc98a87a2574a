//! The current bucket's binary heap, ordered by (time, disc).
//!
//! Only the bucket being emptied is sorted: a binary min-heap on the pair
//! (t, i), compared lexicographically, so events at equal times leave in order of
//! disc index and the order never depends on Δ. A poured slot is ordered at once
//! by Floyd's construction, O(k) for k entries; push and pop are O(log k).

use super::EventQueue;

/// An event of the heap or the overflow list: the disc and its time.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Item {
    /// Event time (time).
    pub(super) time: f64,
    /// Disc index.
    pub(super) disc: u32,
}

impl EventQueue {
    /// Restore the heap order of the whole heap array (Floyd's construction).
    pub(super) fn heapify(&mut self) {
        for pos in (0..self.heap.len() / 2).rev() {
            let item = self.heap[pos];
            self.sift_down(pos, item);
        }
    }

    /// Put `item` at `pos` or below, moving smaller children up.
    #[inline]
    pub(super) fn sift_down(&mut self, mut pos: usize, item: Item) {
        let len = self.heap.len();
        loop {
            let mut child = 2 * pos + 1;
            if child >= len {
                break;
            }
            if child + 1 < len && Self::less(&self.heap[child + 1], &self.heap[child]) {
                child += 1;
            }
            if !Self::less(&self.heap[child], &item) {
                break;
            }
            self.heap[pos] = self.heap[child];
            pos = child;
        }
        self.heap[pos] = item;
    }

    #[inline]
    pub(super) fn less(a: &Item, b: &Item) -> bool {
        a.time < b.time || (a.time == b.time && a.disc < b.disc)
    }

    pub(super) fn heap_push(&mut self, item: Item) {
        self.heap.push(item);
        let mut pos = self.heap.len() - 1;
        while pos > 0 {
            let parent = (pos - 1) / 2;
            if !Self::less(&item, &self.heap[parent]) {
                break;
            }
            self.heap[pos] = self.heap[parent];
            pos = parent;
        }
        self.heap[pos] = item;
    }

    pub(super) fn heap_pop(&mut self) {
        let last = self.heap.pop().expect("heap is not empty");
        if !self.heap.is_empty() {
            self.sift_down(0, last);
        }
    }
}
