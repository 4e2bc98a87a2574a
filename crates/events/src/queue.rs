//! The event queue: one pending event time per disc, in an event calendar.
//!
//! Every disc owns exactly one current event time (`+∞` for none). Times are sorted
//! into buckets of width Δ (bucket b = ⌊(t − t₀)/Δ⌋, a monotone function of t):
//! buckets ahead of the current one are unsorted singly linked lists in a circular
//! calendar of M buckets, events beyond the calendar wait in an overflow list, and
//! only the current bucket is kept sorted, in a small binary heap. Inserting is O(1);
//! popping is O(log k) for k events per bucket (G. Paul, J. Comput. Phys. 221, 615
//! (2007); Smallenburg's EDMD).
//!
//! Deletion is lazy: setting a disc's time files a new entry (time, disc) and leaves
//! the old one where it is; an entry whose time is no longer its disc's current time
//! is dropped when it reaches the front. A change of a disc's time therefore touches
//! no other disc's entry — at large N each such touch was a cache miss. An entry
//! whose time equals its disc's current time always tells the truth ("disc i has an
//! event at t"), so a second entry with the same time (a time set, changed and set
//! back) is harmless: whichever comes first is the disc's current event, and the
//! other is dropped as soon as the time changes. Entries live in a pool with a free
//! list; when stale entries pile up beyond a fixed multiple of N the calendar is
//! rebuilt from the current times.
//!
//! The order is exactly lexicographic in (time, disc index): ties are broken by disc
//! index, and Δ only affects speed, never the order. Keys are
//! [`NotNan<f64>`](ordered_float::NotNan): a NaN cannot enter.

use crate::memory;
use ordered_float::NotNan;

/// Event time in the queue's key type (time unit of the simulation, never NaN).
pub type Time = NotNan<f64>;

const NIL: u32 = u32::MAX;

/// A filed event: the disc and its time when filed.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Item {
    /// Event time (time).
    time: f64,
    /// Disc index.
    disc: u32,
}

/// An entry of a bucket or overflow list.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Node {
    /// Event time (time).
    time: f64,
    /// Disc index.
    disc: u32,
    /// Next node of the list (or of the free list).
    next: u32,
}

const _: () = assert!(std::mem::size_of::<Node>() == 16);

/// An event calendar of per-disc event times.
#[derive(Debug, Clone)]
pub struct EventQueue {
    /// Per-disc current event time (+∞ for none).
    time_of: Vec<f64>,
    /// Pool of list nodes.
    nodes: Vec<Node>,
    /// First free node of the pool.
    free: u32,
    /// Nodes in use (in slots or overflow).
    used: usize,
    /// First node of each calendar slot.
    slot_head: Vec<u32>,
    /// First node of the overflow list.
    overflow_head: u32,
    /// Items of the current bucket, a binary heap on (time, disc).
    heap: Vec<Item>,
    /// The current bucket (absolute number).
    cur: u64,
    /// Time origin of bucket 0.
    t0: f64,
    /// 1/Δ.
    inv_width: f64,
    /// M − 1 for M calendar slots (M a power of two).
    mask: u64,
    /// Discs with a finite time.
    finite: usize,
    /// Nodes (current or stale) in calendar slots.
    in_slots: usize,
}

impl EventQueue {
    /// A queue for `n` discs, every time +∞, buckets of width 1.
    pub fn new(n: usize) -> Self {
        let m = n.max(2).next_power_of_two();
        EventQueue {
            time_of: memory::filled(n, f64::INFINITY),
            nodes: memory::with_capacity(Self::pool_limit_for(n)),
            free: NIL,
            used: 0,
            slot_head: memory::filled(m, NIL),
            overflow_head: NIL,
            heap: Vec::new(),
            cur: 0,
            t0: 0.0,
            inv_width: 1.0,
            mask: m as u64 - 1,
            finite: 0,
            in_slots: 0,
        }
    }

    /// Re-tune the bucket width to the current times: Δ = 2 ⟨t − now⟩ / N over the
    /// finite times, so a bucket holds about two current events and the calendar
    /// spans at least two mean event intervals; refile every current time and drop
    /// stale entries. Changes speed only, never the order. (Factor 2 measured best
    /// with `examples/profile` at N = 10⁴ and 10⁶; 4 and 1 were slower.)
    pub fn retune(&mut self, now: f64) {
        let (mut sum, mut k) = (0.0, 0usize);
        for &t in &self.time_of {
            if t.is_finite() {
                sum += t - now;
                k += 1;
            }
        }
        let n = self.time_of.len().max(1);
        let width = if k > 0 && sum > 0.0 {
            2.0 * sum / k as f64 / n as f64
        } else {
            1.0
        };
        self.nodes.clear();
        // The heap can be large right after construction (every first prediction
        // lands in bucket 0 before the width is tuned); give that memory back.
        self.heap = Vec::new();
        self.free = NIL;
        self.used = 0;
        self.slot_head.fill(NIL);
        self.overflow_head = NIL;
        self.cur = 0;
        self.t0 = now;
        self.inv_width = 1.0 / width;
        self.finite = 0;
        self.in_slots = 0;
        for i in 0..self.time_of.len() {
            if self.time_of[i].is_finite() {
                self.finite += 1;
                self.file(i as u32);
            }
        }
    }

    /// Renumber the discs: disc k takes the time of old disc `perm[k]`; then
    /// [`retune`](Self::retune) at `now`. Keeps the queue's allocations.
    pub fn renumber(&mut self, perm: &[usize], now: f64) {
        let old = self.time_of.clone();
        for (t, &o) in self.time_of.iter_mut().zip(perm) {
            *t = old[o];
        }
        self.retune(now);
    }

    /// Move the time origin: every stored time t becomes t − `shift` (+∞ stays),
    /// and the calendar is rebuilt at the new time 0. Subtracting one number is
    /// monotone, so the order is kept (two times may round to one, and then go by
    /// disc index).
    pub fn shift_origin(&mut self, shift: f64) {
        for t in self.time_of.iter_mut() {
            *t -= shift;
        }
        self.retune(0.0);
    }

    /// The earliest event: (time, disc). With every time +∞ the time is +∞.
    #[inline]
    pub fn peek(&mut self) -> (Time, u32) {
        loop {
            if let Some(&top) = self.heap.first() {
                if self.time_of[top.disc as usize] == top.time {
                    return (NotNan::new(top.time).expect("no NaN in queue"), top.disc);
                }
                self.heap_pop();
                continue;
            }
            if self.finite == 0 {
                return (NotNan::new(f64::INFINITY).expect("∞ is not NaN"), 0);
            }
            self.advance();
        }
    }

    /// Discs likely to have the events after the earliest: the two children of the
    /// head of the current bucket's heap ([`NIL`] where there are none). A hint for
    /// fetching their records early; it says nothing certain about the order.
    #[inline]
    pub fn upcoming(&self) -> [u32; 2] {
        let at = |k: usize| self.heap.get(k).map_or(NIL, |item| item.disc);
        [at(1), at(2)]
    }

    /// The time currently stored for disc `i`.
    #[inline]
    pub fn get(&self, i: u32) -> Time {
        NotNan::new(self.time_of[i as usize]).expect("no NaN in queue")
    }

    /// Set the event time of disc `i`.
    #[inline]
    pub fn set(&mut self, i: u32, t: Time) {
        let old = std::mem::replace(&mut self.time_of[i as usize], t.into_inner());
        let was_finite = old.is_finite();
        match (was_finite, t.is_finite()) {
            (false, true) => self.finite += 1,
            (true, false) => self.finite -= 1,
            _ => {}
        }
        if t.is_finite() {
            self.file(i);
        }
        if self.used >= self.pool_limit() {
            // Stale entries have piled up (times changed many times within the
            // calendar's span): start afresh from the current times.
            self.retune(self.t0 + self.cur as f64 / self.inv_width);
        }
    }

    /// Bytes of heap memory used (for the memory report).
    pub fn heap_bytes(&self) -> usize {
        self.time_of.capacity() * 8
            + self.nodes.capacity() * std::mem::size_of::<Node>()
            + self.slot_head.capacity() * 4
            + self.heap.capacity() * std::mem::size_of::<Item>()
    }

    #[inline]
    fn bucket(&self, t: f64) -> u64 {
        // Saturating float-to-int cast; monotone in t.
        ((t - self.t0) * self.inv_width) as u64
    }

    /// File disc `i`'s current time: into the heap, a calendar slot or overflow.
    #[inline]
    fn file(&mut self, i: u32) {
        let item = Item {
            time: self.time_of[i as usize],
            disc: i,
        };
        let b = self.bucket(item.time);
        if b <= self.cur {
            self.heap_push(item);
        } else if b - self.cur <= self.mask {
            let s = (b & self.mask) as usize;
            self.slot_head[s] = self.node(item, self.slot_head[s]);
            self.in_slots += 1;
        } else {
            self.overflow_head = self.node(item, self.overflow_head);
        }
    }

    /// Nodes the pool may hold before stale entries are collected: one current entry
    /// per disc and as many again stale (about 0.3–0.4 N are seen at η = 0.5). The
    /// pool is allocated at this size once and never grows.
    fn pool_limit_for(n: usize) -> usize {
        2 * n + 64
    }

    fn pool_limit(&self) -> usize {
        Self::pool_limit_for(self.time_of.len())
    }

    /// A node holding `item` in front of `next`, from the free list or the pool's end.
    #[inline]
    fn node(&mut self, item: Item, next: u32) -> u32 {
        self.used += 1;
        let node = Node {
            time: item.time,
            disc: item.disc,
            next,
        };
        let k = self.free;
        if k != NIL {
            self.free = self.nodes[k as usize].next;
            self.nodes[k as usize] = node;
            k
        } else {
            self.nodes.push(node);
            (self.nodes.len() - 1) as u32
        }
    }

    /// Return node `k` to the free list: its item and its successor.
    #[inline]
    fn release(&mut self, k: u32) -> (Item, u32) {
        let Node { time, disc, next } = self.nodes[k as usize];
        let item = Item { time, disc };
        self.nodes[k as usize].next = self.free;
        self.free = k;
        self.used -= 1;
        (item, next)
    }

    /// Whether `item` still holds its disc's current time.
    #[inline]
    fn is_current(&self, item: &Item) -> bool {
        self.time_of[item.disc as usize] == item.time
    }

    /// Move to the next bucket: pour its slot into the heap; at every full turn of
    /// the calendar, bring overflow events that are now within reach into slots.
    fn advance(&mut self) {
        if self.in_slots == 0 {
            // Only overflow entries are left: jump straight to the earliest of them.
            let mut b = u64::MAX;
            let mut k = self.overflow_head;
            while k != NIL {
                let Node { time, disc, next } = self.nodes[k as usize];
                if self.is_current(&Item { time, disc }) {
                    b = b.min(self.bucket(time));
                }
                k = next;
            }
            self.cur = b.max(self.cur + 1);
            self.redistribute_overflow();
        } else {
            self.cur += 1;
            if self.cur & self.mask == 0 {
                self.redistribute_overflow();
            }
        }
        let s = (self.cur & self.mask) as usize;
        let mut k = self.slot_head[s];
        self.slot_head[s] = NIL;
        let before = self.heap.len();
        while k != NIL {
            let (item, next) = self.release(k);
            self.in_slots -= 1;
            // Stale entries are dropped here rather than sorted first, without a
            // branch (whether an entry is stale is a coin toss): every entry is
            // appended, and a stale one is cut off again.
            let keep = self.is_current(&item);
            self.heap.push(item);
            let len = self.heap.len() - 1 + keep as usize;
            self.heap.truncate(len);
            k = next;
        }
        if self.heap.len() > before {
            self.heapify();
        }
    }

    /// Restore the heap order of the whole heap array (Floyd's construction).
    fn heapify(&mut self) {
        for pos in (0..self.heap.len() / 2).rev() {
            let item = self.heap[pos];
            self.sift_down(pos, item);
        }
    }

    /// Put `item` at `pos` or below, moving smaller children up.
    #[inline]
    fn sift_down(&mut self, mut pos: usize, item: Item) {
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

    fn redistribute_overflow(&mut self) {
        let mut k = self.overflow_head;
        self.overflow_head = NIL;
        while k != NIL {
            let (item, next) = self.release(k);
            if self.is_current(&item) {
                self.file(item.disc);
            }
            k = next;
        }
    }

    #[inline]
    fn less(a: &Item, b: &Item) -> bool {
        a.time < b.time || (a.time == b.time && a.disc < b.disc)
    }

    fn heap_push(&mut self, item: Item) {
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

    fn heap_pop(&mut self) {
        let last = self.heap.pop().expect("heap is not empty");
        if !self.heap.is_empty() {
            self.sift_down(0, last);
        }
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

    #[test]
    fn far_future_events_come_back_from_overflow() {
        let mut q = EventQueue::new(4);
        q.set(0, t(0.5));
        q.retune(0.0);
        q.set(1, t(1e6));
        q.set(2, t(3e3));
        q.set(0, t(f64::INFINITY));
        assert_eq!(q.peek(), (t(3e3), 2));
        q.set(2, t(f64::INFINITY));
        assert_eq!(q.peek(), (t(1e6), 1));
        q.set(1, t(f64::INFINITY));
        assert!(q.peek().0.is_infinite());
    }

    #[test]
    fn a_time_set_back_is_found_and_stale_copies_are_dropped() {
        let mut q = EventQueue::new(3);
        q.set(0, t(5.0));
        q.set(1, t(6.0));
        q.retune(0.0);
        // Disc 0 moves away and back: two entries with time 5 exist, both true.
        q.set(0, t(9.0));
        q.set(0, t(5.0));
        assert_eq!(q.peek(), (t(5.0), 0));
        q.set(0, t(7.0));
        // Both old entries are stale now; the next event is disc 1's.
        assert_eq!(q.peek(), (t(6.0), 1));
        q.set(1, t(f64::INFINITY));
        assert_eq!(q.peek(), (t(7.0), 0));
        q.set(0, t(f64::INFINITY));
        assert!(q.peek().0.is_infinite());
    }

    #[test]
    fn piled_up_stale_entries_are_collected() {
        let n = 10;
        let mut q = EventQueue::new(n);
        for i in 0..n {
            q.set(i as u32, t(100.0 + i as f64));
        }
        q.retune(0.0);
        // Many changes of far-future times leave stale entries behind; the pool
        // must stay bounded and the order exact.
        for k in 0..100_000u32 {
            let i = k % n as u32;
            q.set(i, t(50.0 + (k % 977) as f64 * 0.1 + i as f64 * 1e-3));
            assert!(q.used <= q.pool_limit());
        }
        let (t0, i0) = q.peek();
        let best = (0..n as u32).map(|i| (q.get(i), i)).min().unwrap();
        assert_eq!((t0, i0), best);
    }

    proptest! {
        /// Popping in a simulation-like pattern (the head moves to a later time, others
        /// change anywhere ahead of the head) always yields the (time, index) minimum.
        #[test]
        fn head_is_lexicographic_minimum(
            n in 1usize..40,
            width in 0.01f64..10.0,
            ops in proptest::collection::vec((0usize..40, 0u32..2000, any::<bool>()), 1..300),
        ) {
            let mut q = EventQueue::new(n);
            let mut model = vec![f64::INFINITY; n];
            for (k, m) in model.iter_mut().enumerate() {
                *m = k as f64 * 0.37;
                q.set(k as u32, t(*m));
            }
            q.retune(0.0);
            let mut now = 0.0;
            for (i, dt, pop) in ops {
                let (qt, qi) = q.peek();
                let (bt, bi) = model.iter().enumerate()
                    .fold((f64::INFINITY, 0usize), |acc, (k, &x)| if x < acc.0 { (x, k) } else { acc });
                prop_assert_eq!(qt.into_inner(), bt);
                if bt.is_finite() { prop_assert_eq!(qi as usize, bi); now = bt; }
                let target = if pop && bt.is_finite() { bi } else { i % n };
                let v = if dt == 1999 { f64::INFINITY } else { now + (dt / 7) as f64 * width };
                q.set(target as u32, t(v));
                model[target] = v;
            }
        }
    }
}
