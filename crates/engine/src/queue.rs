//! The event queue: one pending event time per disc, in an event calendar.
//!
//! Every disc owns exactly one current event time (`+∞` for none), which the queue
//! reads and writes through [`EventTimes`] (the engine keeps it in the disc's own
//! record). Times are sorted into buckets of width Δ, bucket b = ⌊(t − t₀)/Δ⌋ (a
//! monotone function of t): buckets ahead are unsorted 32-byte slots of a circular
//! calendar (up to seven discs each, then a chain of chunks), events beyond it wait
//! in an overflow list, and only the current bucket is sorted, in a small binary
//! heap. Inserting is O(1), popping O(log k) for k events per bucket (G. Paul,
//! J. Comput. Phys. 221, 615 (2007)). Deletion is lazy: an entry is kept when its
//! bucket is poured only if its disc's current time still falls there. The order
//! is exactly lexicographic in (time, disc index); Δ only affects speed. The
//! slots are in `slot`, the heap in `heap`, the look-ahead hints in `ahead`. See
//! docs/performance.md, "queue".

mod ahead;
mod heap;
mod slot;

use crate::memory;
use heap::Item;
use ordered_float::NotNan;
pub use slot::SLOT_DISCS;
use slot::{Slot, NO_CHUNK};

/// Event time in the queue's key type (time unit of the simulation, never NaN).
pub type Time = NotNan<f64>;

/// Where the queue finds each disc's current event time (time; +∞ for none).
///
/// The queue files a disc under the time stored when [`EventQueue::set`] is called
/// and later recognises its entries as current by reading the time again, so a
/// stored time must change only through [`EventQueue::set`] (or be followed by
/// [`EventQueue::retune`], which refiles every disc).
pub trait EventTimes {
    /// The stored event time of disc `i`.
    fn time(&self, i: u32) -> f64;
    /// Store `t` as disc `i`'s event time.
    fn store(&mut self, i: u32, t: f64);
    /// Start loading disc `i`'s time (a hint; `i` may be out of range).
    fn prefetch(&self, i: u32);
}

/// Plain arrays of times (for tests and simple callers).
impl EventTimes for [f64] {
    #[inline]
    fn time(&self, i: u32) -> f64 {
        self[i as usize]
    }
    #[inline]
    fn store(&mut self, i: u32, t: f64) {
        self[i as usize] = t;
    }
    #[inline]
    fn prefetch(&self, i: u32) {
        memory::prefetch_at(self, i as usize);
    }
}

/// An event calendar of per-disc event times (kept by the caller, see
/// [`EventTimes`]).
#[derive(Debug, Clone)]
pub struct EventQueue {
    /// Number of discs.
    n: usize,
    /// The calendar: slot `b mod M` holds the discs filed in bucket b.
    slots: Vec<Slot>,
    /// Pool of chunks for crowded slots.
    chunks: Vec<Slot>,
    /// First free chunk of the pool.
    free: u32,
    /// Chunks in use.
    chunks_used: usize,
    /// Events beyond the calendar's span.
    overflow: Vec<Item>,
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
    /// Entries (current or stale) in calendar slots, their chunks and `pending`.
    in_slots: usize,
    /// Entries on their way into calendar slots: (slot, disc). Filing into a slot
    /// far ahead is a cache miss at large N; the slot is fetched when the entry is
    /// made and written a few events later: when this buffer is full, or when the
    /// slot's bucket is poured.
    pending: [(u32, u32); PENDING],
    /// Entries in `pending`.
    pending_len: usize,
    /// Whether the queue moved to another bucket since [`EventQueue::moved_on`] was
    /// last asked.
    moved: bool,
}

/// Capacity of the buffer of entries on their way into slots.
const PENDING: usize = 16;

impl EventQueue {
    /// An empty queue for `n` discs, buckets of width 1: every disc's stored time
    /// must be +∞, or be filed by [`retune`](Self::retune) before the first
    /// [`peek`](Self::peek).
    pub fn new(n: usize) -> Self {
        let m = n.max(2).next_power_of_two();
        EventQueue {
            n,
            slots: memory::filled(m, Slot::EMPTY),
            chunks: memory::with_capacity(Self::chunk_limit_for(n)),
            free: NO_CHUNK,
            chunks_used: 0,
            overflow: Vec::new(),
            heap: Vec::new(),
            cur: 0,
            t0: 0.0,
            inv_width: 1.0,
            mask: m as u64 - 1,
            finite: 0,
            in_slots: 0,
            pending: [(0, 0); PENDING],
            pending_len: 0,
            moved: true,
        }
    }

    /// Re-tune the bucket width to the current times: Δ = 2 ⟨t − now⟩ / N over the
    /// finite times, so the calendar spans at least two mean event intervals (the
    /// buckets next to the current one hold about five events each, about two
    /// collisions' worth, as most events are due soon); refile every current time and drop
    /// stale entries. Changes speed only, never the order (factor 2: see
    /// docs/performance.md, "queue").
    pub fn retune<T: EventTimes + ?Sized>(&mut self, times: &T, now: f64) {
        let (mut sum, mut k) = (0.0, 0usize);
        for i in 0..self.n as u32 {
            let t = times.time(i);
            if t.is_finite() {
                sum += t - now;
                k += 1;
            }
        }
        let n = self.n.max(1);
        let width = if k > 0 && sum > 0.0 {
            2.0 * sum / k as f64 / n as f64
        } else {
            1.0
        };
        self.slots.fill(Slot::EMPTY);
        self.chunks.clear();
        self.free = NO_CHUNK;
        self.chunks_used = 0;
        self.overflow.clear();
        // The heap can be large right after construction (every first prediction
        // lands in bucket 0 before the width is tuned); give that memory back.
        self.heap = Vec::new();
        self.cur = 0;
        self.t0 = now;
        self.inv_width = 1.0 / width;
        self.finite = 0;
        self.in_slots = 0;
        self.pending_len = 0;
        self.moved = true;
        for i in 0..self.n as u32 {
            let t = times.time(i);
            if t.is_finite() {
                self.finite += 1;
                self.file(i, t);
            }
        }
    }

    /// The earliest event: (time, disc). With every time +∞ the time is +∞.
    #[inline(always)]
    pub fn peek<T: EventTimes + ?Sized>(&mut self, times: &T) -> (Time, u32) {
        loop {
            if let Some(&top) = self.heap.first() {
                if times.time(top.disc) == top.time {
                    return (NotNan::new(top.time).expect("no NaN in queue"), top.disc);
                }
                count!(QueueHeapStale);
                self.heap_pop();
                continue;
            }
            if self.finite == 0 {
                return (NotNan::new(f64::INFINITY).expect("∞ is not NaN"), 0);
            }
            self.advance(times);
        }
    }

    /// Set the event time of disc `i` to `t`: stored in `times` and filed.
    #[inline]
    pub fn set<T: EventTimes + ?Sized>(&mut self, times: &mut T, i: u32, t: Time) {
        let t = t.into_inner();
        let was_finite = times.time(i).is_finite();
        times.store(i, t);
        match (was_finite, t.is_finite()) {
            (false, true) => self.finite += 1,
            (true, false) => self.finite -= 1,
            _ => {}
        }
        if t.is_finite() {
            self.file(i, t);
            if self.chunks_used >= self.chunk_limit()
                || self.overflow.len() >= self.overflow_limit()
            {
                self.rebuild(times);
            }
        }
    }

    /// Stale entries have piled up (times changed many times within the calendar's
    /// span): start afresh from the current times.
    fn rebuild<T: EventTimes + ?Sized>(&mut self, times: &T) {
        self.retune(times, self.t0 + self.cur as f64 / self.inv_width);
    }

    /// Bytes of heap memory used (for the memory report).
    pub fn heap_bytes(&self) -> usize {
        (self.slots.capacity() + self.chunks.capacity()) * std::mem::size_of::<Slot>()
            + (self.overflow.capacity() + self.heap.capacity()) * std::mem::size_of::<Item>()
    }

    #[inline]
    fn bucket(&self, t: f64) -> u64 {
        // Saturating float-to-int cast; monotone in t (+∞ maps to u64::MAX).
        ((t - self.t0) * self.inv_width) as u64
    }

    /// File disc `i` under its current time `time`: into the heap, a calendar slot
    /// or overflow.
    #[inline]
    fn file(&mut self, i: u32, time: f64) {
        let b = self.bucket(time);
        if b <= self.cur {
            count!(QueueIntoHeap);
            self.heap_push(Item { time, disc: i });
        } else if b - self.cur <= self.mask {
            count!(QueueIntoSlot);
            let s = (b & self.mask) as usize;
            memory::prefetch(&self.slots[s]);
            self.pending[self.pending_len] = (s as u32, i);
            self.pending_len += 1;
            self.in_slots += 1;
            if self.pending_len == PENDING {
                self.flush();
            }
        } else {
            count!(QueueIntoOverflow);
            self.overflow.push(Item { time, disc: i });
        }
    }

    /// Write the pending entries into their slots.
    fn flush(&mut self) {
        for k in 0..std::mem::take(&mut self.pending_len) {
            let (s, d) = self.pending[k];
            self.add_to_slot(s as usize, d);
        }
    }

    /// Entries the overflow list may hold before the calendar is rebuilt.
    fn overflow_limit(&self) -> usize {
        2 * self.n + 64
    }

    /// Move to the next bucket: pour its slot into the heap; at every full turn of
    /// the calendar, bring overflow events that are now within reach into slots.
    fn advance<T: EventTimes + ?Sized>(&mut self, times: &T) {
        self.moved = true;
        if self.in_slots == 0 {
            // Only overflow entries are left: the events have spread out beyond the
            // calendar since Δ was tuned (a cooling gas): tune it anew, which files
            // the earliest events in the current bucket.
            self.rebuild(times);
            return;
        }
        self.cur = self.cur.saturating_add(1);
        count!(QueueBuckets);
        if self.cur & self.mask == 0 {
            self.redistribute_overflow(times);
            if 2 * self.overflow.len() > self.finite {
                // More than half the events lie beyond a turn of the calendar, which
                // a tuned Δ never leaves (a turn spans at least twice the mean time
                // ahead; Markov's inequality): the events have spread out.
                self.rebuild(times);
                return;
            }
        }
        // The times of the discs four buckets ahead are read when the engine looks
        // ahead ([`EventQueue::filed_ahead`], from three buckets ahead) and when
        // their bucket is poured: start loading them now.
        for &d in self.ahead(4) {
            times.prefetch(d);
        }
        let s = (self.cur & self.mask) as usize;
        // Entries still on their way into this slot go in now (the others wait, so
        // that their slots have time to arrive in the cache).
        let mut k = 0;
        while k < self.pending_len {
            if self.pending[k].0 as usize == s {
                self.add_to_slot(s, self.pending[k].1);
                self.pending_len -= 1;
                self.pending[k] = self.pending[self.pending_len];
            } else {
                k += 1;
            }
        }
        let slot = std::mem::replace(&mut self.slots[s], Slot::EMPTY);
        let before = self.heap.len();
        self.pour(times, &slot);
        let mut c = slot.more;
        while c != NO_CHUNK {
            let chunk = self.chunks[c as usize];
            self.pour(times, &chunk);
            self.chunks[c as usize].more = self.free;
            self.free = c;
            self.chunks_used -= 1;
            c = chunk.more;
        }
        if self.heap.len() > before {
            self.heapify();
        }
        if self.chunks_used >= self.chunk_limit() {
            self.rebuild(times);
        }
    }

    /// Append the current entries of `slot` (filed in the current bucket) to the
    /// heap array, unordered.
    #[inline]
    fn pour<T: EventTimes + ?Sized>(&mut self, times: &T, slot: &Slot) {
        let len = slot.len();
        self.in_slots -= len;
        for &d in &slot.disc[..len] {
            let time = times.time(d);
            // Stale entries are dropped here rather than sorted first, without a
            // branch (whether an entry is stale is a coin toss): every entry is
            // appended, and a stale one is cut off again.
            let keep = self.bucket(time) == self.cur;
            count!(QueuePouredKept, keep);
            count!(QueuePouredDropped, !keep);
            self.heap.push(Item { time, disc: d });
            let len = self.heap.len() - 1 + keep as usize;
            self.heap.truncate(len);
        }
    }

    /// Drop stale overflow entries and move those now within the calendar's reach
    /// into their slots.
    fn redistribute_overflow<T: EventTimes + ?Sized>(&mut self, times: &T) {
        let mut k = 0;
        while k < self.overflow.len() {
            let item = self.overflow[k];
            if times.time(item.disc) != item.time {
                self.overflow.swap_remove(k);
                continue;
            }
            let b = self.bucket(item.time);
            if b <= self.cur || b - self.cur <= self.mask {
                self.overflow.swap_remove(k);
                self.file(item.disc, item.time);
                continue;
            }
            k += 1;
        }
    }
}

#[cfg(test)]
mod tests;
