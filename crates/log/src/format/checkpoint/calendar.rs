//! How the engine's calendar is stored in `/checkpoint`: the caller's scheduled
//! events and the thermostat (its parameters, generator, totals and next event).
//!
//! The thermostat's next event is the last entry of the `scheduled_*` arrays,
//! with tag [`THERMOSTAT_ENTRY_TAG`] (time +∞ when there is none), whenever a
//! thermostat is set; every other entry is the caller's, whatever its tag. Logs
//! before format 2.5 stored it with that tag among the caller's in time order, a
//! tag the engine then kept for itself: in both, the thermostat's is the last
//! entry with that tag, so one rule reads both and resumes either bit for bit.
//! A run without a thermostat stores exactly the caller's entries, as before.

use crate::format::cdr::{CdrError, CdrReader, CdrWriter};
use carom_engine::{Checkpoint, Thermostat, ThermostatState, ThermostatStats};

/// The tag that marks the thermostat's next event in the scheduled arrays
/// (u64::MAX − 1, the thermostat's reserved tag before format 2.5).
pub(crate) const THERMOSTAT_ENTRY_TAG: u64 = u64::MAX - 1;

/// The entries of the scheduled arrays: (time, sequence number, tag).
type Entry = (f64, u64, u64);

/// The scheduled arrays' entries of `c`: the caller's, then the thermostat's
/// next event if a thermostat is set.
pub(crate) fn scheduled_entries(c: &Checkpoint) -> Vec<Entry> {
    let mut v = c.scheduled.clone();
    if let Some(t) = &c.thermostat {
        let (time, seq) = t.next.unwrap_or((f64::INFINITY, 0));
        v.push((time, seq, THERMOSTAT_ENTRY_TAG));
    }
    v
}

/// The caller's entries and the thermostat's next event (`None` when there is
/// no thermostat or its wait is infinite) of the stored `entries`.
pub(super) fn split_scheduled(
    mut entries: Vec<Entry>,
    thermostat: bool,
) -> (Vec<Entry>, Option<(f64, u64)>) {
    if !thermostat {
        return (entries, None);
    }
    let Some(k) = entries.iter().rposition(|e| e.2 == THERMOSTAT_ENTRY_TAG) else {
        return (entries, None);
    };
    let (time, seq, _) = entries.remove(k);
    (entries, time.is_finite().then_some((time, seq)))
}

/// Write the thermostat's fields (format 4 on; zeros without one).
pub(super) fn encode_thermostat(w: &mut CdrWriter, thermostat: &Option<ThermostatState>) {
    let (kind, a, b) = match thermostat.map(|t| t.thermostat) {
        None => (0u8, 0.0, 0.0),
        Some(Thermostat::Andersen { kt, rate }) => (1, kt, rate),
        Some(Thermostat::Driven { xi2, interval }) => (2, xi2, interval),
    };
    let (rng, stats, origin) = thermostat.map_or((0, ThermostatStats::default(), 0.0), |t| {
        (t.rng, t.stats, t.origin)
    });
    w.put(kind);
    w.put(a);
    w.put(b);
    w.array(&[(rng >> 64) as u64, rng as u64]);
    w.put(stats.events);
    w.put(stats.energy_added);
    w.put(origin);
}

/// The thermostat fields at the end of a checkpoint of format 4 on, without its
/// next event (see [`split_scheduled`]).
pub(super) fn decode_thermostat(r: &mut CdrReader) -> Result<Option<ThermostatState>, CdrError> {
    let kind: u8 = r.get("thermostat_kind")?;
    let a: f64 = r.get("thermostat_a")?;
    let b: f64 = r.get("thermostat_b")?;
    let rng: [u64; 2] = r.fixed("thermostat_rng")?;
    let events = r.get("thermostat_events")?;
    let energy_added = r.get("thermostat_energy_added")?;
    let origin = r.get("thermostat_origin")?;
    let thermostat = match kind {
        0 => return Ok(None),
        1 => Thermostat::Andersen { kt: a, rate: b },
        2 => Thermostat::Driven {
            xi2: a,
            interval: b,
        },
        k => {
            return Err(CdrError::Invalid {
                field: "thermostat_kind",
                problem: format!("unknown thermostat kind {k} (allowed: 0, 1, 2)"),
            })
        }
    };
    Ok(Some(ThermostatState {
        thermostat,
        rng: (rng[0] as u128) << 64 | rng[1] as u128,
        stats: ThermostatStats {
            events,
            energy_added,
        },
        origin,
        next: None,
    }))
}
