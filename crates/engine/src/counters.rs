//! Operation counts of the event loop, for profiling (cargo feature `counters`).
//!
//! Where a collision's time goes is a matter of how many of each operation it
//! takes: pair tests (each one a root solve of |Δr + Δv t| = σ, physics.md §2,
//! done for every neighbour since the scan is branch-free), cells walked, full
//! 3 × 3 predictions against the strips of three a crossing scans, which event a
//! prediction files, and the queue's filings, heap pops and lazily dropped
//! entries. The crate's `count!` macro adds to a per-thread tally when
//! the feature is on and expands to nothing when it is off, so the default build
//! is the same machine code (checked by its cachegrind instruction count and final
//! state hash in docs/performance.md, "Where a dense collision's time goes").
//! The tally is per thread: read it on the thread that runs the engine.

use std::cell::Cell;

/// One kind of operation counted.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Count {
    /// Pair tests: one contact-time root solve each (every neighbour scanned).
    PairTests,
    /// Pair tests of an approaching pair, b = Δr·Δv < 0.
    PairApproaching,
    /// Pair tests that found a contact (a finite time).
    PairMeets,
    /// Cells walked by the scans (3 × 3 blocks and strips of three).
    CellsWalked,
    /// Cells walked that were empty.
    CellsEmpty,
    /// Full predictions (the 3 × 3 block): after a collision, a wrap, an
    /// obsolete candidate, or a strip whose candidate's partner moved.
    FullPredictions,
    /// Predictions after a crossing that scanned only the strip of three cells.
    StripPredictions,
    /// Predictions that filed a pair collision as the disc's event.
    FiledPair,
    /// Predictions that filed a cell crossing (or, on lists, a skin exit).
    FiledCell,
    /// Predictions that filed a wall collision (or nothing).
    FiledOther,
    /// Event times filed straight into the current bucket's heap. The three
    /// filings count refilings too (overflow entries brought into the calendar,
    /// rebuilds), not only the predictions' new times.
    QueueIntoHeap,
    /// Event times filed into a calendar slot ahead.
    QueueIntoSlot,
    /// Event times filed into the overflow list beyond the calendar.
    QueueIntoOverflow,
    /// Heap entries popped as obsolete at the head (the disc's time changed).
    QueueHeapStale,
    /// Slot entries poured into the heap as current.
    QueuePouredKept,
    /// Slot entries dropped when poured (obsolete: the disc was refiled).
    QueuePouredDropped,
    /// Buckets the calendar moved on.
    QueueBuckets,
    /// Neighbour-list renewals (skin exits; engine::listed).
    ListUpdates,
}

/// Number of kinds counted.
const KINDS: usize = Count::ListUpdates as usize + 1;

/// Every kind with its name, in order (for printing).
pub const ALL: [(Count, &str); KINDS] = [
    (Count::PairTests, "pair tests (root solves)"),
    (Count::PairApproaching, "  approaching (b < 0)"),
    (Count::PairMeets, "  meeting (finite time)"),
    (Count::CellsWalked, "cells walked"),
    (Count::CellsEmpty, "  empty"),
    (Count::FullPredictions, "full predictions (3 x 3)"),
    (Count::StripPredictions, "strip predictions (3 cells)"),
    (Count::FiledPair, "filed: pair"),
    (Count::FiledCell, "filed: cell crossing / skin exit"),
    (Count::FiledOther, "filed: wall or none"),
    (Count::QueueIntoHeap, "queue: filed into heap"),
    (Count::QueueIntoSlot, "queue: filed into slot"),
    (Count::QueueIntoOverflow, "queue: filed into overflow"),
    (Count::QueueHeapStale, "queue: heap pops (obsolete)"),
    (Count::QueuePouredKept, "queue: poured, kept"),
    (Count::QueuePouredDropped, "queue: poured, dropped"),
    (Count::QueueBuckets, "queue: buckets moved on"),
    (Count::ListUpdates, "list updates (skin exits)"),
];

thread_local! {
    static TALLY: [Cell<u64>; KINDS] = const { [const { Cell::new(0) }; KINDS] };
}

/// Add `n` to the count of `what` (through the crate's `count!` macro).
#[inline]
pub fn add(what: Count, n: u64) {
    TALLY.with(|t| t[what as usize].set(t[what as usize].get() + n));
}

/// The counts so far on this thread, indexed like [`ALL`].
pub fn counts() -> [u64; KINDS] {
    TALLY.with(|t| t.each_ref().map(Cell::get))
}

#[cfg(test)]
mod tests {
    use super::{counts, Count};
    use crate::{Engine, EngineParams, SystemSpec};

    /// Every prediction files exactly one event, which the queue files in one of
    /// its three places (besides a few refilings), and a scan tests at least the discs of the cells it
    /// walks that are not empty: the counts add up as the loop says they must.
    #[test]
    fn the_counts_add_up() {
        let state = SystemSpec::periodic_fluid(400, 0.7, 3).build().unwrap();
        let mut e = Engine::new(state, EngineParams::default()).unwrap();
        e.run_collisions(2000).unwrap();
        let k0 = counts();
        let done = e.run_collisions(20_000).unwrap();
        let k = counts();
        let d = |c: Count| k[c as usize] - k0[c as usize];
        assert_eq!(done, 20_000);
        let predictions = d(Count::FullPredictions) + d(Count::StripPredictions);
        let filed = d(Count::FiledPair) + d(Count::FiledCell) + d(Count::FiledOther);
        assert_eq!(filed, predictions);
        let queued =
            d(Count::QueueIntoHeap) + d(Count::QueueIntoSlot) + d(Count::QueueIntoOverflow);
        // Refilings (overflow entries coming within reach, rebuilds) come on top.
        assert!(queued >= predictions && queued < predictions + predictions / 10);
        // Two full predictions per pair collision, more for obsolete candidates.
        assert!(d(Count::FullPredictions) >= 2 * done);
        assert!(d(Count::PairTests) >= d(Count::CellsWalked) - d(Count::CellsEmpty));
        assert!(d(Count::PairMeets) <= d(Count::PairTests));
    }
}
