//! Writing a carom log: an MCAP file with the channels of the log format.
//!
//! [`LogWriter`] receives plain engine output (collisions, states, checkpoints)
//! and knows nothing about how the engine works. The calling thread only copies
//! each logged collision into a preallocated array (no allocation); full arrays,
//! and snapshots and checkpoints encoded into recycled buffers, go to the file
//! side (`sink`), which encodes, compresses and writes them, on a writer thread of
//! its own when the machine has a core to spare. A bounded queue of `QUEUE_DEPTH`
//! messages keeps memory bounded. The file is flushed (the chunk closed, every
//! byte handed to the operating system) every `flush_seconds` of wall time and
//! after every checkpoint, so a killed run loses little; pending collisions are
//! sent before any other message, so the file is in time order.
//! See docs/performance.md, "log writer".

mod options;
mod sink;

pub use options::{WriteError, WriterOptions, WriterPosition, WriterStats};

use crate::format::{encode_scene, CH_SCENE};
use crate::format::{
    log_time_ns, CdrWriter, CollisionRecord, DriverState, LogCheckpoint, Snapshot, Thermo,
    CH_CHECKPOINT, CH_COLLISIONS, CH_SNAPSHOT, CH_THERMO, METADATA_SUMMARY,
};
use carom_engine::{Checkpoint, PairCollision, State, WallCollision};
use mcap::records::Metadata;
use sink::{Backend, Cmd, Sink, Spent, QUEUE_DEPTH};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// Writes a carom log. Create with [`LogWriter::create`], feed it with the
/// `observe_*` and `write_*` methods, end with [`LogWriter::finish`]. Dropping a
/// writer without finishing still ends the file properly (MCAP summary, no
/// `carom.summary` record).
pub struct LogWriter {
    path: PathBuf,
    backend: Backend,
    next_sequence: [u32; 4],
    opts: WriterOptions,
    pending: Vec<CollisionRecord>,
    pending_first: u64,
    cdr: CdrWriter,
    stats: WriterStats,
}

impl std::fmt::Debug for LogWriter {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("LogWriter")
            .field("path", &self.path)
            .field("stats", &self.stats)
            .finish_non_exhaustive()
    }
}

impl LogWriter {
    /// Create `path` (truncating it), write the `carom.run` metadata record,
    /// register the four channels and start the writer thread.
    pub fn create(
        path: &Path,
        mut opts: WriterOptions,
        run_metadata: &BTreeMap<String, String>,
        position: WriterPosition,
    ) -> Result<LogWriter, WriteError> {
        opts.collision_every = opts.collision_every.max(1);
        opts.batch_size = opts.batch_size.max(1);
        let sink = Sink::create(path, &opts, run_metadata)?;
        let backend = Backend::start(sink, opts.background)?;
        Ok(LogWriter {
            path: path.to_path_buf(),
            backend,
            next_sequence: position.next_sequence,
            pending: Vec::with_capacity(opts.batch_size),
            pending_first: 0,
            opts,
            cdr: CdrWriter::new(),
            stats: WriterStats {
                next_ordinal: position.next_ordinal,
                logged_collisions: position.logged_collisions,
                ..WriterStats::default()
            },
        })
    }

    /// The log file.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// What has been sent so far.
    pub fn stats(&self) -> WriterStats {
        self.stats
    }

    /// The options in force.
    pub fn options(&self) -> &WriterOptions {
        &self.opts
    }

    /// An upper estimate (bytes) of how much a file of `file_bytes` bytes on disk
    /// may still grow if a final checkpoint is written and the writer finished now:
    /// the collisions not yet on disk (`QUEUE_DEPTH` full batches waiting for the
    /// writer thread and the one being gathered, each at most 128 bytes per
    /// collision before compression) and the chunk being filled, the final checkpoint (taken as twice the largest
    /// message so far, which is at least the run's first checkpoint), and the
    /// summary section, whose chunk index takes well under 1/512 of the file, plus
    /// 1 MiB for the rest of it. Before the first checkpoint is written this
    /// underestimates; the run writes one at its start.
    pub fn finish_bound(&self, file_bytes: u64) -> u64 {
        let batch = (self.opts.batch_size as u64).saturating_mul(128);
        (QUEUE_DEPTH as u64 + 1)
            .saturating_mul(batch)
            .saturating_add(self.opts.chunk_size)
            .saturating_add(self.stats.largest_message.saturating_mul(2))
            .saturating_add(file_bytes / 512)
            .saturating_add(1 << 20)
    }

    /// The writer thread's error after it stopped (or a generic one).
    fn thread_failure(&mut self) -> WriteError {
        match std::mem::replace(&mut self.backend, Backend::Done) {
            Backend::Thread { tx, handle, .. } => {
                drop(tx);
                match handle.join() {
                    Ok(Err(e)) => e,
                    Ok(Ok(_)) => WriteError::Finished(self.path.clone()),
                    Err(_) => WriteError::Thread {
                        path: self.path.clone(),
                        problem: "panicked".into(),
                    },
                }
            }
            _ => WriteError::Finished(self.path.clone()),
        }
    }

    fn send(&mut self, cmd: Cmd) -> Result<(), WriteError> {
        match &mut self.backend {
            Backend::Inline(sink) => {
                let (pending, cdr) = (&mut self.pending, &mut self.cdr);
                let sent = sink.handle(cmd, &mut |spent| match spent {
                    // Inline: hand the (cleared) buffer straight back.
                    Spent::Records(mut v) => std::mem::swap(pending, &mut v),
                    Spent::Bytes(v) => cdr.reuse(v),
                });
                self.stop_on_error(sent)
            }
            Backend::Thread { tx, .. } => {
                if tx.send(cmd).is_err() {
                    return Err(self.thread_failure());
                }
                Ok(())
            }
            Backend::Done => Err(WriteError::Finished(self.path.clone())),
        }
    }

    fn take_sequence(&mut self, ch: usize) -> u32 {
        let s = self.next_sequence[ch];
        self.next_sequence[ch] = s.wrapping_add(1);
        self.stats.messages[ch] += 1;
        s
    }

    #[inline]
    fn observe(&mut self, record: impl FnOnce(u64) -> CollisionRecord) -> Result<(), WriteError> {
        let ordinal = self.stats.next_ordinal;
        self.stats.next_ordinal += 1;
        if self.opts.collisions && ordinal.is_multiple_of(self.opts.collision_every) {
            if self.pending.is_empty() {
                self.pending_first = ordinal;
            }
            self.pending.push(record(ordinal));
            if self.pending.len() >= self.opts.batch_size {
                self.write_batch()?;
            }
        }
        Ok(())
    }

    /// Account for one pair collision (logged if its ordinal is a multiple of
    /// `collision_every`). Allocation-free.
    #[inline]
    pub fn observe_pair(&mut self, c: &PairCollision) -> Result<(), WriteError> {
        self.observe(|o| CollisionRecord::from_pair(c, o))
    }

    /// Account for one wall collision (logged like [`LogWriter::observe_pair`]).
    #[inline]
    pub fn observe_wall(&mut self, c: &WallCollision) -> Result<(), WriteError> {
        self.observe(|o| CollisionRecord::from_wall(c, o))
    }

    /// Send the pending collisions (if any) as one `/collisions` message.
    pub fn write_batch(&mut self) -> Result<(), WriteError> {
        if self.pending.is_empty() {
            return Ok(());
        }
        let fresh = match &self.backend {
            Backend::Thread { recycled, .. } => recycled
                .try_recv()
                .unwrap_or_else(|_| Vec::with_capacity(self.opts.batch_size)),
            _ => Vec::new(),
        };
        let records = std::mem::replace(&mut self.pending, fresh);
        self.stats.logged_collisions += records.len() as u64;
        let sequence = self.take_sequence(CH_COLLISIONS);
        self.send(Cmd::Batch {
            sequence,
            first_ordinal: self.pending_first,
            stride: self.opts.collision_every,
            records,
        })?;
        if self.pending.capacity() < self.opts.batch_size {
            self.pending.reserve(self.opts.batch_size);
        }
        Ok(())
    }

    /// Take back the message buffers the writer thread is done with, to encode
    /// the next large message into (the largest is kept, the rest freed). Called
    /// before every message, so that the buffers coming back never pile up.
    fn reclaim_bytes(&mut self) {
        if let Backend::Thread { recycled_bytes, .. } = &self.backend {
            while let Ok(b) = recycled_bytes.try_recv() {
                self.cdr.reuse(b);
            }
        }
    }

    fn send_message(&mut self, ch: usize, t: f64, data: Vec<u8>) -> Result<(), WriteError> {
        self.write_batch()?;
        self.reclaim_bytes();
        self.stats.largest_message = self.stats.largest_message.max(data.len() as u64);
        let sequence = self.take_sequence(ch);
        let t = log_time_ns(t);
        self.send(Cmd::Message {
            ch,
            sequence,
            log_time: t,
            publish_time: t,
            data,
        })
    }

    /// Write a `/snapshot` of `state` (after the pending collisions).
    pub fn write_snapshot(&mut self, state: &State) -> Result<(), WriteError> {
        self.reclaim_bytes();
        Snapshot::encode_state(state, &mut self.cdr);
        let data = self.cdr.take_bytes();
        self.send_message(CH_SNAPSHOT, state.time, data)
    }

    /// Write `/scene` frame number `frame` of `state` (after the pending
    /// collisions). Its MCAP sequence number is `frame` (mod 2³²), so a resumed
    /// run, whose checkpoint carries the next frame's number, continues it.
    pub fn write_scene(&mut self, frame: u64, state: &State) -> Result<(), WriteError> {
        self.write_batch()?;
        self.reclaim_bytes();
        encode_scene(state, &mut self.cdr);
        let data = self.cdr.take_bytes();
        self.stats.largest_message = self.stats.largest_message.max(data.len() as u64);
        self.stats.messages[CH_SCENE] += 1;
        let t = log_time_ns(state.time);
        self.send(Cmd::Message {
            ch: CH_SCENE,
            sequence: frame as u32,
            log_time: t,
            publish_time: t,
            data,
        })
    }

    /// Write a `/thermo` record (after the pending collisions).
    pub fn write_thermo(&mut self, thermo: &Thermo) -> Result<(), WriteError> {
        let json = serde_json::to_vec(thermo).map_err(|source| WriteError::Json {
            path: self.path.clone(),
            source,
        })?;
        self.send_message(CH_THERMO, thermo.time, json)
    }

    /// Write a `/checkpoint` of `engine` (after the pending collisions) and flush the
    /// file. The driver state stored with it carries this writer's counters, so a run
    /// resumed from it continues the log exactly.
    pub fn write_checkpoint(
        &mut self,
        engine: Checkpoint,
        run_start_time: f64,
    ) -> Result<(), WriteError> {
        self.write_batch()?;
        let mut next_sequence = self.next_sequence;
        next_sequence[CH_CHECKPOINT] = next_sequence[CH_CHECKPOINT].wrapping_add(1);
        let t = engine.now;
        let lc = LogCheckpoint {
            driver: DriverState {
                run_start_time,
                logged_collisions: self.stats.logged_collisions,
                next_sequence,
            },
            engine,
        };
        self.reclaim_bytes();
        lc.encode(&mut self.cdr);
        let data = self.cdr.take_bytes();
        self.send_message(CH_CHECKPOINT, t, data)?;
        self.flush()
    }

    /// Write a metadata record (after the pending collisions; closes the chunk).
    pub fn write_metadata(
        &mut self,
        name: &str,
        metadata: &BTreeMap<String, String>,
    ) -> Result<(), WriteError> {
        self.write_batch()?;
        self.send(Cmd::Metadata(Metadata {
            name: name.into(),
            metadata: metadata.clone(),
        }))
    }

    /// Copy a message from another carom log verbatim (same channel, sequence,
    /// times and bytes). Used by resume to carry a log's prefix into a new file.
    pub fn copy_message(
        &mut self,
        ch: usize,
        sequence: u32,
        log_time: u64,
        publish_time: u64,
        data: &[u8],
    ) -> Result<(), WriteError> {
        self.write_batch()?;
        self.stats.messages[ch] += 1;
        // Into a buffer the writer thread gave back: a copied prefix of any length
        // holds only the few buffers in flight.
        self.reclaim_bytes();
        let mut buf = self.cdr.take_bytes();
        buf.clear();
        buf.extend_from_slice(data);
        self.send(Cmd::Message {
            ch,
            sequence,
            log_time,
            publish_time,
            data: buf,
        })
    }

    /// Ask for a flush: close the current chunk and hand everything written so far
    /// to the operating system (the pending collisions are sent first). With the
    /// writer thread the flush happens in order after the messages already sent.
    pub fn flush(&mut self) -> Result<(), WriteError> {
        self.write_batch()?;
        self.send(Cmd::Flush)
    }

    /// Flush and wait until everything written so far is on the disk (`fsync`):
    /// a crash after this returns loses none of it. Blocks the caller, so it is
    /// for rare moments, as before a new log replaces an older one.
    pub fn sync(&mut self) -> Result<(), WriteError> {
        self.write_batch()?;
        match &mut self.backend {
            Backend::Inline(sink) => {
                let synced = sink.sync();
                self.stop_on_error(synced)
            }
            Backend::Thread { tx, .. } => {
                let (done, answer) = std::sync::mpsc::sync_channel(1);
                if tx.send(Cmd::Sync(done)).is_err() || answer.recv().is_err() {
                    return Err(self.thread_failure());
                }
                Ok(())
            }
            Backend::Done => Err(WriteError::Finished(self.path.clone())),
        }
    }

    /// With the inline backend, flush if `flush_every` of wall time has passed since
    /// the last flush (the writer thread does this by itself).
    #[inline]
    pub fn maybe_flush(&mut self) -> Result<(), WriteError> {
        if let Backend::Inline(sink) = &mut self.backend {
            if sink.dirty && sink.last_flush.elapsed() >= sink.flush_every {
                let flushed = sink.flush();
                return self.stop_on_error(flushed);
            }
        }
        Ok(())
    }

    /// After the inline backend's first error the writer is finished, as it is when
    /// the writer thread stops on one: every later call says so.
    fn stop_on_error(&mut self, r: Result<(), WriteError>) -> Result<(), WriteError> {
        if r.is_err() {
            self.backend = Backend::Done;
        }
        r
    }

    /// Send the pending collisions and the `carom.summary` metadata record, write
    /// the MCAP summary section, close the file and wait for the writer thread.
    /// Returns the file size in bytes.
    pub fn finish(&mut self, summary: &BTreeMap<String, String>) -> Result<u64, WriteError> {
        self.write_metadata(METADATA_SUMMARY, summary)?;
        self.close()
    }

    /// Send the pending collisions, write the MCAP summary section, close the file
    /// and wait for the writer thread, without a `carom.summary` record (as for a
    /// run that did not end: `carom repair` of a cut log). Returns the file size.
    pub fn close(&mut self) -> Result<u64, WriteError> {
        self.write_batch()?;
        match std::mem::replace(&mut self.backend, Backend::Done) {
            Backend::Inline(sink) => sink.finish(),
            Backend::Thread { tx, handle, .. } => {
                let _ = tx.send(Cmd::Finish);
                drop(tx);
                handle.join().map_err(|_| WriteError::Thread {
                    path: self.path.clone(),
                    problem: "panicked".into(),
                })?
            }
            Backend::Done => Err(WriteError::Finished(self.path.clone())),
        }
    }
}

impl Drop for LogWriter {
    fn drop(&mut self) {
        // End the file properly (the writer thread finishes it when its queue closes).
        match std::mem::replace(&mut self.backend, Backend::Done) {
            Backend::Inline(sink) => {
                let _ = sink.finish();
            }
            Backend::Thread { tx, handle, .. } => {
                drop(tx);
                let _ = handle.join();
            }
            Backend::Done => {}
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The bound adds up its documented parts: the queued and gathered batches
    /// (128 bytes a collision), the chunk, twice the largest message, 1/512 of the
    /// file for the chunk index, and 1 MiB.
    #[test]
    fn the_finish_bound_adds_up_what_may_still_be_written() {
        let path = std::env::temp_dir().join(format!(
            "carom-log-finish-bound-{}.mcap",
            std::process::id()
        ));
        let opts = WriterOptions {
            batch_size: 10,
            chunk_size: 1000,
            background: false,
            ..WriterOptions::default()
        };
        let mut w =
            LogWriter::create(&path, opts, &BTreeMap::new(), WriterPosition::default()).unwrap();
        assert_eq!(QUEUE_DEPTH, 8);
        let batches = 9 * 10 * 128;
        assert_eq!(w.finish_bound(0), batches + 1000 + (1 << 20));
        assert_eq!(
            w.finish_bound(512 * 7 + 100),
            batches + 1000 + 7 + (1 << 20)
        );
        let thermo = Thermo {
            time: 0.5,
            kinetic_energy: 1.0,
            temperature: 1.0,
            collisions: 0,
            pair_collisions: 0,
            wall_collisions: 0,
            energy_lost: 0.0,
            virial_sum: 0.0,
            wall_impulse: 0.0,
            pressure: None,
            z: None,
            collision_rate: None,
            ..Default::default()
        };
        let json = serde_json::to_vec(&thermo).unwrap().len() as u64;
        w.write_thermo(&thermo).unwrap();
        assert_eq!(w.finish_bound(0), batches + 1000 + 2 * json + (1 << 20));
        drop(w);
        std::fs::remove_file(&path).unwrap();
    }
}
