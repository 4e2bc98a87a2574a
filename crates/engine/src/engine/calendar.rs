//! The calendar of instants that are not the discs' own events.
//!
//! Two kinds of entry share one heap ordered by (time, sequence number): the
//! caller's scheduled events, whose tags are the caller's alone (any u64), and the
//! engine's own: the thermostat's next event (physics.md §16) and the end of a
//! `run_until`. Both take their
//! sequence number from one counter, so entries at the same time come out in the
//! order they were made, whoever made them. The growth's instants (rescales and
//! end, §17) are on the internal clock and stay in the growth's state; this file
//! decides for all three which comes first: an entry of the heap at or before a
//! growth instant goes first, and any of them before a disc event at the same
//! time. A pause (`engine::pause`) is an [`crate::Event`] of its own, no entry.

use super::motion::Motion;
use super::{time_key, Engine, Time};
use std::cmp::Reverse;
use std::collections::BinaryHeap;

/// Whose instant an entry of the calendar is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub(super) enum Whose {
    /// The caller's, with its tag.
    Caller(u64),
    /// The thermostat's next event.
    Thermostat,
    /// The end of [`Engine::run_until`]: reported as a pause, removed when the
    /// call returns (never in a checkpoint).
    Stop,
}

/// The entries: (time as the caller reports it, sequence number, whose). The
/// sequence numbers are unique, so `Whose` never decides the order.
#[derive(Debug, Clone, Default)]
pub(super) struct Calendar {
    heap: BinaryHeap<Reverse<(Time, u64, Whose)>>,
    /// Sequence number of the next entry.
    next_seq: u64,
}

/// An instant due before the discs' earliest event.
pub(super) enum Due {
    /// The growth's instant (internal time).
    Growth(f64),
    /// The calendar's earliest entry: its time (the caller's), its internal time
    /// and whose it is.
    Entry {
        ts: f64,
        internal: f64,
        whose: Whose,
    },
}

impl Calendar {
    /// A calendar whose next entry gets sequence number `next_seq`.
    pub(super) fn starting_at(next_seq: u64) -> Calendar {
        Calendar {
            heap: BinaryHeap::new(),
            next_seq,
        }
    }

    /// Add an entry at `time` (finite), numbered from the counter.
    pub(super) fn push(&mut self, time: f64, whose: Whose) {
        self.insert(time, self.next_seq, whose);
        self.next_seq += 1;
    }

    /// Add an entry with its own sequence number `seq` (from a checkpoint).
    pub(super) fn insert(&mut self, time: f64, seq: u64, whose: Whose) {
        self.heap.push(Reverse((time_key(time), seq, whose)));
    }

    /// The earliest entry: (time, whose).
    #[inline(always)]
    pub(super) fn peek(&self) -> Option<(f64, Whose)> {
        self.heap.peek().map(|r| (r.0 .0.into_inner(), r.0 .2))
    }

    /// Remove the earliest entry.
    pub(super) fn pop(&mut self) {
        self.heap.pop();
    }

    /// Remove `whose` entries (the thermostat's, a stop), if any.
    pub(super) fn drop(&mut self, whose: Whose) {
        self.heap.retain(|r| r.0 .2 != whose);
    }

    /// Whether an entry of `whose` is waiting.
    pub(super) fn holds(&self, whose: Whose) -> bool {
        self.heap.iter().any(|r| r.0 .2 == whose)
    }

    /// The caller's entries as (time, sequence number, tag), in the order they come.
    pub(super) fn caller_entries(&self) -> Vec<(f64, u64, u64)> {
        let mut v: Vec<(f64, u64, u64)> = self
            .heap
            .iter()
            .filter_map(|r| match r.0 .2 {
                Whose::Caller(tag) => Some((r.0 .0.into_inner(), r.0 .1, tag)),
                Whose::Thermostat | Whose::Stop => None,
            })
            .collect();
        v.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        v
    }

    /// The thermostat's entry as (time, sequence number), if there is one.
    pub(super) fn thermostat_entry(&self) -> Option<(f64, u64)> {
        self.heap
            .iter()
            .find(|r| r.0 .2 == Whose::Thermostat)
            .map(|r| (r.0 .0.into_inner(), r.0 .1))
    }

    /// Sequence number the next entry will get.
    pub(super) fn next_seq(&self) -> u64 {
        self.next_seq
    }
}

impl Engine {
    /// What comes before the discs' earliest event at internal time `t`, if
    /// anything: a growth instant (after any calendar entry at its time), or the
    /// calendar's earliest entry (at or before `t`).
    #[inline(always)]
    pub(super) fn calendar_due<M: Motion>(&self, t: f64) -> Option<Due> {
        let first = self.calendar.peek();
        if let Some(due) = M::growth_due(self) {
            let entry_first = first.is_some_and(|(ts, _)| self.internal_time(ts) <= due);
            if due <= t && !entry_first {
                return Some(Due::Growth(due));
            }
        }
        let (ts, whose) = first?;
        let internal = self.internal_time(ts);
        (internal <= t).then_some(Due::Entry {
            ts,
            internal,
            whose,
        })
    }

    /// A calendar time (the caller's) on the internal clock: never before now
    /// (rounding of the difference).
    #[inline(always)]
    fn internal_time(&self, ts: f64) -> f64 {
        (ts - self.epoch).max(self.clock)
    }
}
