//! Whole-file passes over a log: what it holds ([`scan`]: channels, counts, time
//! spans, how it ends, without decoding collisions) and its last complete
//! checkpoint ([`last_checkpoint`], what a resume starts from).

use super::{LogEnd, LogReader, RawMessage, ReadError, ReadProgress};
use crate::format::{
    CdrReader, LogCheckpoint, RunMetadata, SummaryMetadata, Thermo, CH_CHECKPOINT, CH_COLLISIONS,
    CH_SNAPSHOT, CH_THERMO,
};
use crate::format::{CH_SCENE, N_CHANNELS};
use std::path::Path;

/// What a scan of a whole log found (for `carom info`).
#[derive(Debug, Clone, PartialEq)]
pub struct LogInfo {
    /// The `carom.run` metadata.
    pub run: RunMetadata,
    /// The `carom.summary` metadata (complete runs only).
    pub summary: Option<SummaryMetadata>,
    /// How the file ends.
    pub end: LogEnd,
    /// Whether each channel is defined (see [`crate::TOPICS`]).
    pub channels: [bool; N_CHANNELS],
    /// Messages per channel.
    pub messages: [u64; N_CHANNELS],
    /// Collisions in `/collisions`.
    pub logged_collisions: u64,
    /// Simulated time of the first and last message per channel (time); `None` if no message.
    pub time_span: [Option<(f64, f64)>; N_CHANNELS],
    /// Simulated time of the last checkpoint (time).
    pub last_checkpoint_time: Option<f64>,
    /// (time, pair collisions, wall collisions) of the first and the last `/thermo`
    /// record (counts since the run's start); `None` without thermo records.
    pub thermo_counts: Option<[(f64, u64, u64); 2]>,
    /// File size (bytes).
    pub file_bytes: u64,
}

/// Scan a whole log without decoding the collision payloads: channels, message
/// counts, time spans, how it ends. Corruption is an error; a cut is reported in
/// [`LogInfo::end`].
pub fn scan(path: &Path) -> Result<LogInfo, ReadError> {
    scan_observed(path, &mut |_| {})
}

/// [`scan`], calling `observe` with the reader's [`ReadProgress`] each time it has
/// read more of the file (about once per MiB) and once at the end.
pub fn scan_observed(
    path: &Path,
    observe: &mut dyn FnMut(ReadProgress),
) -> Result<LogInfo, ReadError> {
    let file_bytes = std::fs::metadata(path)
        .map_err(|source| ReadError::Io {
            file: path.display().to_string(),
            source,
        })?
        .len();
    let mut r = LogReader::open(path)?;
    let mut messages = [0u64; N_CHANNELS];
    let mut span: [Option<(f64, f64)>; N_CHANNELS] = [None; N_CHANNELS];
    let mut logged = 0u64;
    let mut last_cp = None;
    let mut thermo: Option<[(f64, u64, u64); 2]> = None;
    let mut seen = 0;
    loop {
        if let Some(p) = r.progress_since(&mut seen) {
            observe(p);
        }
        let Some(m) = r.next_raw()? else { break };
        messages[m.channel] += 1;
        let (t0, t1) = simulated_times(&m);
        let s = &mut span[m.channel];
        *s = Some(match *s {
            None => (t0, t1),
            Some((a, b)) => (a.min(t0), b.max(t1)),
        });
        if m.channel == CH_COLLISIONS {
            logged += batch_times(m.data).map_or(0, |(n, ..)| n as u64);
        }
        if m.channel == CH_CHECKPOINT {
            last_cp = Some(t0);
        }
        if m.channel == CH_THERMO {
            if let Ok(t) = Thermo::decode(m.data) {
                let now = (t.time, t.pair_collisions, t.wall_collisions);
                thermo = Some([thermo.map_or(now, |[first, _]| first), now]);
            }
        }
    }
    observe(r.progress());
    Ok(LogInfo {
        run: r.run.clone(),
        summary: r.summary()?,
        end: r.end.clone(),
        channels: r.seen,
        messages,
        logged_collisions: logged,
        time_span: span,
        last_checkpoint_time: last_cp,
        thermo_counts: thermo,
        file_bytes,
    })
}

/// The simulated times (time) of the first and the last record of message `m`,
/// read from the message itself. MCAP's log and publish times are whole
/// nanoseconds of simulated time (one time unit as one second): they cannot tell
/// apart the times of a run in seconds at the scale of molecules (10⁻¹² s), and
/// saturate beyond 1.8·10¹⁰. They are used only for a message that cannot be read.
pub(super) fn simulated_times(m: &RawMessage) -> (f64, f64) {
    let exact = match m.channel {
        CH_COLLISIONS => batch_times(m.data).map(|(_, first, last)| (first, last)),
        CH_SNAPSHOT => CdrReader::new(m.data)
            .and_then(|mut r| r.get::<f64>("time"))
            .ok()
            .map(|t| (t, t)),
        CH_THERMO => Thermo::decode(m.data).ok().map(|t| (t.time, t.time)),
        // `/scene`: its log time (whole nanoseconds) is close enough for a span.
        CH_SCENE => None,
        _ => LogCheckpoint::decode(m.data)
            .ok()
            .map(|c| (c.engine.now, c.engine.now)),
    };
    exact.unwrap_or((m.log_time as f64 * 1e-9, m.publish_time as f64 * 1e-9))
}

/// A `/collisions` batch's number of collisions and the times (time) of its first
/// and last, read without decoding the rest; `None` for an empty or unreadable
/// batch.
fn batch_times(data: &[u8]) -> Option<(usize, f64, f64)> {
    let mut r = CdrReader::new(data).ok()?;
    r.skip::<u64>("first_ordinal, stride", 2).ok()?;
    let n = r.get::<u32>("time").ok()? as usize;
    let first = r.get::<f64>("time").ok()?;
    if n > 1 {
        r.skip::<f64>("time", n - 2).ok()?;
        return Some((n, first, r.get::<f64>("time").ok()?));
    }
    (n == 1).then_some((1, first, first))
}

/// The last complete checkpoint of a log (possibly truncated) and how many carom
/// messages precede it, counting the checkpoint itself (the prefix a resumed log
/// copies). Streams the whole file, keeping only the latest checkpoint's bytes.
pub fn last_checkpoint(path: &Path) -> Result<(LogCheckpoint, u64, RunMetadata), ReadError> {
    last_checkpoint_observed(path, &mut |_| {})
}

/// [`last_checkpoint`], calling `observe` with the reader's [`ReadProgress`] each
/// time it has read more of the file (about once per MiB) and once at the end: the
/// whole log is read, which takes a minute for a log of 10⁶ discs.
pub fn last_checkpoint_observed(
    path: &Path,
    observe: &mut dyn FnMut(ReadProgress),
) -> Result<(LogCheckpoint, u64, RunMetadata), ReadError> {
    let mut r = LogReader::open(path)?;
    let mut best: Option<(Vec<u8>, u64, u32, u64)> = None;
    let mut count = 0u64;
    let mut seen = 0;
    loop {
        if let Some(p) = r.progress_since(&mut seen) {
            observe(p);
        }
        let m = match r.next_raw() {
            Ok(Some(m)) => m,
            Ok(None) => break,
            // A corrupted tail still leaves the checkpoints before it usable.
            Err(ReadError::Corrupt { .. }) if best.is_some() => break,
            Err(e) => return Err(e),
        };
        count += 1;
        if m.channel == CH_CHECKPOINT {
            let (seq, t) = (m.sequence, m.log_time);
            let buf = match best.take() {
                Some((mut b, ..)) => {
                    b.clear();
                    b.extend_from_slice(m.data);
                    b
                }
                None => m.data.to_vec(),
            };
            best = Some((buf, count, seq, t));
        }
    }
    observe(r.progress());
    let Some((bytes, prefix, seq, t)) = best else {
        return Err(ReadError::NoCheckpoint {
            file: r.label.clone(),
        });
    };
    let cp = LogCheckpoint::decode(&bytes).map_err(|e| r.decode_error(CH_CHECKPOINT, seq, t, e))?;
    Ok((cp, prefix, r.run.clone()))
}
