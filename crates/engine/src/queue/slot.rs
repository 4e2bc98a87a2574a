//! Calendar slots: the unsorted buckets ahead of the current one.
//!
//! Slot b mod M holds the discs filed in bucket b = ⌊(t − t₀)/Δ⌋: up to seven disc
//! indices in one 32-byte slot (half a cache line), then a chain of chunks of the
//! same shape from a pool allocated once (a free list recycles them). Filing is
//! O(1); a slot's entries are sorted only when its bucket becomes the current one.

use super::EventQueue;
use crate::NO_DISC;

/// "No chunk" at the end of a slot's chain or of the free list.
pub(super) const NO_CHUNK: u32 = u32::MAX;

/// Discs held in one slot or chunk.
pub const SLOT_DISCS: usize = 7;

/// A calendar slot, or a chunk of a slot's chain: up to [`SLOT_DISCS`] disc indices
/// (filled from the front, [`NO_DISC`] after the last) and the next chunk.
#[derive(Debug, Clone, Copy, PartialEq)]
#[repr(C, align(32))]
pub(super) struct Slot {
    /// Discs filed in this bucket (current or stale entries).
    pub(super) disc: [u32; SLOT_DISCS],
    /// Next chunk of the chain (or of the free list), or [`NO_CHUNK`].
    pub(super) more: u32,
}

const _: () = assert!(std::mem::size_of::<Slot>() == 32);

impl Slot {
    pub(super) const EMPTY: Slot = Slot {
        disc: [NO_DISC; SLOT_DISCS],
        more: NO_CHUNK,
    };

    /// Put `d` in the first free place; false if the slot is full.
    #[inline]
    fn add(&mut self, d: u32) -> bool {
        let k = self.len();
        if k < SLOT_DISCS {
            self.disc[k] = d;
        }
        k < SLOT_DISCS
    }

    /// Number of discs held (counted without a branch per entry: they fill the
    /// slot from the front).
    #[inline]
    pub(super) fn len(&self) -> usize {
        self.disc.iter().map(|&x| (x != NO_DISC) as usize).sum()
    }
}

impl EventQueue {
    /// Put disc `d` into calendar slot `s`, or into its chain of chunks.
    #[inline]
    pub(super) fn add_to_slot(&mut self, s: usize, d: u32) {
        if self.slots[s].add(d) {
            return;
        }
        let c = self.slots[s].more;
        if c != NO_CHUNK && self.chunks[c as usize].add(d) {
            return;
        }
        let mut chunk = Slot::EMPTY;
        chunk.disc[0] = d;
        chunk.more = c;
        self.slots[s].more = self.chunk(chunk);
    }

    /// Chunks the pool may hold before the calendar is rebuilt; allocated at this
    /// size once and never grown. A rebuild files at most N entries, which need at
    /// most N/7 + 1 chunks, so a rebuild never fills the pool again.
    pub(super) fn chunk_limit_for(n: usize) -> usize {
        n / 4 + 64
    }

    pub(super) fn chunk_limit(&self) -> usize {
        Self::chunk_limit_for(self.n)
    }

    /// A chunk holding `chunk`, from the free list or the pool's end.
    #[inline]
    pub(super) fn chunk(&mut self, chunk: Slot) -> u32 {
        self.chunks_used += 1;
        let k = self.free;
        if k != NO_CHUNK {
            self.free = self.chunks[k as usize].more;
            self.chunks[k as usize] = chunk;
            k
        } else {
            self.chunks.push(chunk);
            (self.chunks.len() - 1) as u32
        }
    }
}
