//! The event queue: one pending event time per disc, in an event calendar.
//!
//! Every disc owns exactly one slot holding the time of its earliest predicted event
//! (`+∞` for none). Times are sorted into buckets of width Δ (bucket
//! b = ⌊(t − t₀)/Δ⌋, a monotone function of t): buckets ahead of the current one are
//! unsorted doubly linked lists in a circular calendar of M buckets, events beyond
//! the calendar wait in an overflow list, and only the current bucket is kept sorted,
//! in a small binary heap. Inserting is O(1); popping is O(log k) for k events per
//! bucket (G. Paul, J. Comput. Phys. 221, 615 (2007); Smallenburg's EDMD).
//!
//! The order is exactly lexicographic in (time, disc index): ties are broken by disc
//! index, and Δ only affects speed, never the order. Keys are
//! [`NotNan<f64>`](ordered_float::NotNan): a NaN cannot enter.

use ordered_float::NotNan;

/// Event time in the queue's key type (time unit of the simulation, never NaN).
pub type Time = NotNan<f64>;

const NEVER: u32 = u32::MAX;
const OVERFLOW: u32 = u32::MAX - 1;
const IN_HEAP: u32 = 1 << 31;
const NIL: u32 = u32::MAX;

/// One disc's entry: its time, where it is, and its bucket-list links — kept in one
/// record so an update touches one cache line of its own.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Entry {
    /// Event time (+∞ for none).
    time: f64,
    /// `NEVER`, `OVERFLOW`, `IN_HEAP | position`, or a bucket slot.
    loc: u32,
    /// Links of the bucket or overflow list.
    prev: u32,
    next: u32,
}

/// An event calendar of per-disc event times.
#[derive(Debug, Clone)]
pub struct EventQueue {
    /// Per-disc entries.
    e: Vec<Entry>,
    /// First disc of each calendar slot.
    slot_head: Vec<u32>,
    /// First disc of the overflow list.
    overflow_head: u32,
    /// Discs of the current bucket, a binary heap on (time, index).
    heap: Vec<u32>,
    /// The current bucket (absolute number).
    cur: u64,
    /// Time origin of bucket 0.
    t0: f64,
    /// 1/Δ.
    inv_width: f64,
    /// M − 1 for M calendar slots (M a power of two).
    mask: u64,
    /// Discs with a finite time, and how many of them sit in calendar slots.
    finite: usize,
    in_slots: usize,
}

impl EventQueue {
    /// A queue for `n` discs, every slot empty (time +∞), buckets of width 1.
    pub fn new(n: usize) -> Self {
        let m = n.max(2).next_power_of_two();
        EventQueue {
            e: vec![
                Entry {
                    time: f64::INFINITY,
                    loc: NEVER,
                    prev: NIL,
                    next: NIL,
                };
                n
            ],
            slot_head: vec![NIL; m],
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

    /// Re-tune the bucket width to the current times: Δ = 4 ⟨t − now⟩ / N over the
    /// finite times, so a bucket holds a few events and the calendar spans a few
    /// mean event intervals. Changes speed only, never the order.
    pub fn retune(&mut self, now: f64) {
        let (mut sum, mut k) = (0.0, 0usize);
        for t in self.e.iter().map(|e| e.time) {
            if t.is_finite() {
                sum += t - now;
                k += 1;
            }
        }
        let n = self.e.len().max(1);
        let width = if k > 0 && sum > 0.0 {
            4.0 * sum / k as f64 / n as f64
        } else {
            1.0
        };
        let times: Vec<f64> = self.e.iter().map(|e| e.time).collect();
        *self = EventQueue::new(times.len());
        self.t0 = now;
        self.inv_width = 1.0 / width;
        for (i, &t) in times.iter().enumerate() {
            self.e[i].time = t;
            if t.is_finite() {
                self.insert(i as u32);
            }
        }
    }

    /// The earliest event: (time, disc). With all slots empty the time is +∞.
    #[inline]
    pub fn peek(&mut self) -> (Time, u32) {
        loop {
            if let Some(&top) = self.heap.first() {
                return (
                    NotNan::new(self.e[top as usize].time).expect("no NaN in queue"),
                    top,
                );
            }
            if self.finite == 0 {
                return (NotNan::new(f64::INFINITY).expect("∞ is not NaN"), 0);
            }
            self.advance();
        }
    }

    /// The time currently stored for disc `i`.
    #[inline]
    pub fn get(&self, i: u32) -> Time {
        NotNan::new(self.e[i as usize].time).expect("no NaN in queue")
    }

    /// Set the event time of disc `i`.
    #[inline]
    pub fn set(&mut self, i: u32, t: Time) {
        self.remove(i);
        self.e[i as usize].time = t.into_inner();
        if t.is_finite() {
            self.insert(i);
        }
    }

    /// Bytes of heap memory used (for the memory report).
    pub fn heap_bytes(&self) -> usize {
        self.e.capacity() * std::mem::size_of::<Entry>()
            + self.slot_head.capacity() * 4
            + self.heap.capacity() * 4
    }

    #[inline]
    fn bucket(&self, t: f64) -> u64 {
        // Saturating float-to-int cast; monotone in t.
        ((t - self.t0) * self.inv_width) as u64
    }

    #[inline]
    fn insert(&mut self, i: u32) {
        self.finite += 1;
        let b = self.bucket(self.e[i as usize].time);
        if b <= self.cur {
            self.heap_push(i);
        } else if b - self.cur <= self.mask {
            let s = (b & self.mask) as u32;
            self.link(i, s);
            self.in_slots += 1;
        } else {
            let h = self.overflow_head;
            self.e[i as usize].prev = NIL;
            self.e[i as usize].next = h;
            if h != NIL {
                self.e[h as usize].prev = i;
            }
            self.overflow_head = i;
            self.e[i as usize].loc = OVERFLOW;
        }
    }

    #[inline]
    fn link(&mut self, i: u32, s: u32) {
        let h = self.slot_head[s as usize];
        self.e[i as usize].prev = NIL;
        self.e[i as usize].next = h;
        if h != NIL {
            self.e[h as usize].prev = i;
        }
        self.slot_head[s as usize] = i;
        self.e[i as usize].loc = s;
    }

    #[inline]
    fn remove(&mut self, i: u32) {
        let l = self.e[i as usize].loc;
        if l == NEVER {
            return;
        }
        self.finite -= 1;
        if l & IN_HEAP != 0 && l != OVERFLOW {
            self.heap_remove((l & !IN_HEAP) as usize);
        } else {
            let (p, n) = (self.e[i as usize].prev, self.e[i as usize].next);
            if p != NIL {
                self.e[p as usize].next = n;
            } else if l == OVERFLOW {
                self.overflow_head = n;
            } else {
                self.slot_head[l as usize] = n;
            }
            if n != NIL {
                self.e[n as usize].prev = p;
            }
            if l != OVERFLOW {
                self.in_slots -= 1;
            }
        }
        self.e[i as usize].loc = NEVER;
    }

    /// Move to the next bucket: pour its slot into the heap; at every full turn of
    /// the calendar, bring overflow events that are now within reach into slots.
    fn advance(&mut self) {
        if self.in_slots == 0 {
            // Only overflow events are left: jump straight to the earliest of them.
            let mut b = u64::MAX;
            let mut k = self.overflow_head;
            while k != NIL {
                b = b.min(self.bucket(self.e[k as usize].time));
                k = self.e[k as usize].next;
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
        while k != NIL {
            let nx = self.e[k as usize].next;
            self.in_slots -= 1;
            self.heap_push(k);
            k = nx;
        }
    }

    fn redistribute_overflow(&mut self) {
        let mut k = self.overflow_head;
        self.overflow_head = NIL;
        while k != NIL {
            let nx = self.e[k as usize].next;
            self.e[k as usize].loc = NEVER;
            self.finite -= 1;
            self.insert(k);
            k = nx;
        }
    }

    #[inline]
    fn less(&self, a: u32, b: u32) -> bool {
        let (ta, tb) = (self.e[a as usize].time, self.e[b as usize].time);
        ta < tb || (ta == tb && a < b)
    }

    #[inline]
    fn place(&mut self, pos: usize, i: u32) {
        self.heap[pos] = i;
        self.e[i as usize].loc = IN_HEAP | pos as u32;
    }

    fn heap_push(&mut self, i: u32) {
        self.heap.push(i);
        self.sift_up(self.heap.len() - 1, i);
    }

    fn heap_remove(&mut self, pos: usize) {
        let last = self.heap.pop().expect("heap holds the removed disc");
        if pos < self.heap.len() {
            let removed = self.heap[pos];
            if self.less(last, removed) {
                self.sift_up(pos, last);
            } else {
                self.sift_down(pos, last);
            }
        }
    }

    fn sift_up(&mut self, mut pos: usize, i: u32) {
        while pos > 0 {
            let parent = (pos - 1) / 2;
            let p = self.heap[parent];
            if !self.less(i, p) {
                break;
            }
            self.place(pos, p);
            pos = parent;
        }
        self.place(pos, i);
    }

    fn sift_down(&mut self, mut pos: usize, i: u32) {
        let len = self.heap.len();
        loop {
            let mut child = 2 * pos + 1;
            if child >= len {
                break;
            }
            if child + 1 < len && self.less(self.heap[child + 1], self.heap[child]) {
                child += 1;
            }
            let c = self.heap[child];
            if !self.less(c, i) {
                break;
            }
            self.place(pos, c);
            pos = child;
        }
        self.place(pos, i);
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
