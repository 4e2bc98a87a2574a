//! The observations a run schedules at exact times: the k-th snapshot, thermo
//! record, checkpoint and scene frame (due at start + k·interval; the k-th
//! snapshot at carom-log's `SnapshotSchedule::time`, the same without a
//! `log.snapshot_schedule`), the two phases
//! of a stop, the watchdog's check for a run without collisions
//! (`watchdog.rs`), and a frame for the caller's [`Observer`](crate::Observer). The engine carries a scheduled observation as an opaque `u64` tag
//! (`Engine::schedule`), and checkpoints store those tags, so the encoding below
//! is part of the log format: the kind in the top byte, the index k below. It is
//! written and read here only.

/// Bits below the kind: the index k.
const SHIFT: u32 = 56;
const INDEX: u64 = (1 << SHIFT) - 1;
const SNAPSHOT: u64 = 1;
const THERMO: u64 = 2;
const CHECKPOINT: u64 = 3;
const STOP: u64 = 4;
const SCENE: u64 = 5;
const WATCHDOG: u64 = 6;
const LIVE: u64 = 7;
/// The index of a stop's second phase.
const STOP_FINAL: u64 = 1;

/// One observation scheduled in the engine.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Observation {
    /// The k-th `/snapshot`.
    Snapshot(u64),
    /// The k-th `/thermo` record.
    Thermo(u64),
    /// The k-th `/checkpoint`.
    Checkpoint(u64),
    /// The k-th `/scene` frame.
    Scene(u64),
    /// The stop time is reached: the stop is scheduled again at the same time as
    /// [`Observation::FinalStop`], so that every observation due then comes first.
    Stop,
    /// The run stops.
    FinalStop,
    /// Check that a collision happened within the bound (`watchdog.rs`).
    Watchdog,
    /// A frame for the caller's [`Observer`](crate::Observer) (a live viewer).
    Live,
}

impl Observation {
    /// The engine's tag for this observation (indices beyond 2⁵⁶ wrap).
    pub(super) fn encode(self) -> u64 {
        let (kind, k) = match self {
            Observation::Snapshot(k) => (SNAPSHOT, k),
            Observation::Thermo(k) => (THERMO, k),
            Observation::Checkpoint(k) => (CHECKPOINT, k),
            Observation::Scene(k) => (SCENE, k),
            Observation::Stop => (STOP, 0),
            Observation::FinalStop => (STOP, STOP_FINAL),
            Observation::Watchdog => (WATCHDOG, 0),
            Observation::Live => (LIVE, 0),
        };
        kind << SHIFT | (k & INDEX)
    }

    /// The observation a tag stands for; `None` for a tag of no known kind.
    pub(super) fn decode(tag: u64) -> Option<Self> {
        let k = tag & INDEX;
        Some(match tag >> SHIFT {
            SNAPSHOT => Observation::Snapshot(k),
            THERMO => Observation::Thermo(k),
            CHECKPOINT => Observation::Checkpoint(k),
            SCENE => Observation::Scene(k),
            STOP if k == STOP_FINAL => Observation::FinalStop,
            STOP => Observation::Stop,
            WATCHDOG => Observation::Watchdog,
            LIVE => Observation::Live,
            _ => return None,
        })
    }

    /// Whether this is either phase of a stop.
    pub(super) fn is_stop(self) -> bool {
        matches!(self, Observation::Stop | Observation::FinalStop)
    }
}

#[cfg(test)]
mod tests {
    use super::Observation::{self, *};

    #[test]
    fn tags_keep_the_encoding_that_checkpoints_store() {
        let cases = [
            (Snapshot(0), 1 << 56),
            (Thermo(7), 2 << 56 | 7),
            (Checkpoint(3), 3 << 56 | 3),
            (Scene(2), 5 << 56 | 2),
            (Stop, 4 << 56),
            (FinalStop, 4 << 56 | 1),
            (Watchdog, 6 << 56),
            (Live, 7 << 56),
        ];
        for (o, tag) in cases {
            assert_eq!(o.encode(), tag, "{o:?}");
            assert_eq!(Observation::decode(tag), Some(o));
        }
        assert_eq!(Observation::decode(0), None);
        assert_eq!(Observation::decode(8 << 56), None);
        // Any other index of a stop is its first phase, as before.
        assert_eq!(Observation::decode(4 << 56 | 9), Some(Stop));
        assert!(Stop.is_stop() && FinalStop.is_stop() && !Thermo(0).is_stop());
    }
}
