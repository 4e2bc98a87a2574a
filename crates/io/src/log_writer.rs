//! Writing a carom log: an MCAP file with the channels of [`crate::schema`].
//!
//! [`LogWriter`] receives plain engine output (collisions, states, checkpoints) and
//! knows nothing about how the engine works.
//!
//! ## Throughput
//! The calling thread only copies each logged collision into a preallocated
//! array of [`CollisionRecord`]s (one 128-byte store, no allocation). When
//! `batch_size` collisions are gathered the whole array is handed to a writer thread
//! (and an empty, recycled one taken back), which encodes it as one CDR
//! `/collisions` message, compresses it into the current MCAP chunk and writes it.
//! Encoding and compression thus run beside the simulation; a bounded queue of
//! [`QUEUE_DEPTH`] messages makes the simulation wait if the writer falls behind,
//! so memory stays bounded. With [`WriterOptions::background`] off, the same work is
//! done inline on the calling thread.
//!
//! A snapshot or checkpoint is encoded on the calling thread into a buffer that
//! is handed over without a copy; once written, the buffer comes back (as the
//! collision arrays do) and the next one is encoded into it. Each fresh buffer of
//! tens of MB (N = 10⁶) cost a page fault per 4 KB. At N = 10⁶, η = 0.5 (41
//! snapshots over 0.5 time units, `carom run` wall time less a run without
//! snapshots) a snapshot took 0.27–0.30 s while the state was gathered twice,
//! copied three times and each copy faulted in afresh; now 0.06–0.10 s, about the
//! writer thread's time to compress its 34 MB.
//!
//! ## Crash safety
//! MCAP chunks are written straight to the file. A flush closes the current chunk
//! and hands every byte to the operating system, after which a reader sees
//! everything written so far even if the process is killed. The writer flushes by
//! itself every `flush_seconds` of wall time (also when no message arrives) and right
//! after every checkpoint.
//!
//! ## Ordering
//! Messages reach the file in the order of the calls. Before any snapshot, thermo
//! or checkpoint message the pending collisions are sent, so the file holds the
//! messages of all channels in time order.

use crate::cdr::CdrWriter;
use crate::checkpoint_codec::{DriverState, LogCheckpoint, CHECKPOINT_MSG};
use crate::options::{Compression, LogOptions};
use crate::schema::*;
use carom_events::{Checkpoint, PairCollision, State, WallCollision};
use mcap::records::{MessageHeader, Metadata};
use std::collections::BTreeMap;
use std::fs::File;
use std::io::BufWriter;
use std::path::{Path, PathBuf};
use std::sync::mpsc::{self, Receiver, RecvTimeoutError, SyncSender};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};
use thiserror::Error;

/// Index of `/collisions` in per-channel arrays.
pub const CH_COLLISIONS: usize = 0;
/// Index of `/snapshot` in per-channel arrays.
pub const CH_SNAPSHOT: usize = 1;
/// Index of `/thermo` in per-channel arrays.
pub const CH_THERMO: usize = 2;
/// Index of `/checkpoint` in per-channel arrays.
pub const CH_CHECKPOINT: usize = 3;
/// Topics in per-channel-array order.
pub const TOPICS: [&str; 4] = [
    TOPIC_COLLISIONS,
    TOPIC_SNAPSHOT,
    TOPIC_THERMO,
    TOPIC_CHECKPOINT,
];

/// Messages that may wait for the writer thread before the caller blocks.
pub const QUEUE_DEPTH: usize = 8;

/// A failure while writing a log. Each names the file.
#[derive(Debug, Error)]
pub enum WriteError {
    /// The file could not be created or written.
    #[error("cannot write log {path}: {source}")]
    Io {
        /// The log file.
        path: PathBuf,
        /// The operating system's error.
        source: std::io::Error,
    },
    /// The MCAP library reported an error.
    #[error("cannot write log {path}: {source}")]
    Mcap {
        /// The log file.
        path: PathBuf,
        /// The MCAP error.
        source: mcap::McapError,
    },
    /// A thermo record could not be serialised.
    #[error("cannot encode /thermo record for {path}: {source}")]
    Json {
        /// The log file.
        path: PathBuf,
        /// The JSON error.
        source: serde_json::Error,
    },
    /// The writer thread could not be started or died.
    #[error("log writer thread for {path}: {problem}")]
    Thread {
        /// The log file.
        path: PathBuf,
        /// What happened.
        problem: String,
    },
    /// A call came after [`LogWriter::finish`] or after an earlier error.
    #[error("log {0} is already finished or failed")]
    Finished(PathBuf),
}

impl WriteError {
    /// The error for an MCAP failure while writing `path`. The MCAP library wraps
    /// the operating system's errors in a message of its own ("I/O error from
    /// writing, or reading a compression stream") that hides the cause; those are
    /// unwrapped, so that a full disk says "No space left on device".
    pub fn from_mcap(path: &Path, source: mcap::McapError) -> WriteError {
        match source {
            mcap::McapError::Io(source) => WriteError::Io {
                path: path.to_path_buf(),
                source,
            },
            source => WriteError::Mcap {
                path: path.to_path_buf(),
                source,
            },
        }
    }
}

/// How a log is written (the writer's view of [`LogOptions`] plus tuning knobs).
#[derive(Debug, Clone, PartialEq)]
pub struct WriterOptions {
    /// Log collisions at all.
    pub collisions: bool,
    /// Log the collisions whose ordinal is a multiple of this (≥ 1).
    pub collision_every: u64,
    /// Chunk compression.
    pub compression: Compression,
    /// Compression level: zstd 1 to 22, or negative for zstd's fast levels (−1 to
    /// −7 and below: less CPU, slightly larger files); lz4 0 to 12; 0 means the
    /// library's default.
    pub compression_level: i32,
    /// Target uncompressed chunk size (bytes).
    pub chunk_size: u64,
    /// Collisions per `/collisions` message.
    pub batch_size: usize,
    /// Wall-clock time between forced flushes.
    pub flush_every: Duration,
    /// Encode, compress and write on a separate thread instead of inline (default:
    /// when the machine has more than one core).
    pub background: bool,
}

/// zstd level used by default: −1, zstd's first fast level. Collision data are
/// mostly float mantissas that do not compress: level −1 writes 103 bytes per
/// collision against 97 at level 1 and 92 at level 3, but needs about 60 % of level
/// 1's CPU time and 35 % of level 3's, which keeps a run at N = 10⁴, η = 0.5 above
/// 75 % of the bare engine's speed even when no core is free for the writer thread
/// (`benches/logging.rs`; `docs/log-format.md`, "Throughput").
pub const DEFAULT_ZSTD_LEVEL: i32 = -1;
/// Collisions per `/collisions` message by default.
pub const DEFAULT_BATCH_SIZE: usize = 4096;
/// Target uncompressed chunk size by default (bytes).
pub const DEFAULT_CHUNK_SIZE: u64 = 1 << 20;

impl WriterOptions {
    /// The writer options for the user's log options (defaults for the rest).
    pub fn from_log_options(o: &LogOptions) -> Self {
        WriterOptions {
            collisions: o.collisions,
            collision_every: o.collision_every.max(1),
            compression: o.compression,
            compression_level: match o.compression {
                Compression::Zstd => DEFAULT_ZSTD_LEVEL,
                _ => 0,
            },
            chunk_size: DEFAULT_CHUNK_SIZE,
            batch_size: DEFAULT_BATCH_SIZE,
            flush_every: Duration::from_secs_f64(if o.flush_seconds.is_finite() {
                o.flush_seconds.clamp(0.0, 1e9)
            } else {
                1e9
            }),
            background: std::thread::available_parallelism().is_ok_and(|n| n.get() > 1),
        }
    }
}

impl Default for WriterOptions {
    fn default() -> Self {
        Self::from_log_options(&LogOptions::default())
    }
}

/// Counters of what a writer has been given.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct WriterStats {
    /// Ordinal of the next collision (collisions seen, logged or not, plus the
    /// starting ordinal).
    pub next_ordinal: u64,
    /// Collisions sent to `/collisions` over the run (including before a resume).
    pub logged_collisions: u64,
    /// Messages sent per channel by this writer (see [`TOPICS`]).
    pub messages: [u64; 4],
    /// Encoded size of the largest snapshot, thermo or checkpoint message sent so
    /// far (bytes, before compression).
    pub largest_message: u64,
}

/// Where a writer starts counting (a fresh run starts at zero; a resumed run at the
/// checkpoint's counters).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct WriterPosition {
    /// Ordinal of the next collision the writer will observe.
    pub next_ordinal: u64,
    /// Collisions already logged.
    pub logged_collisions: u64,
    /// Next sequence number per channel.
    pub next_sequence: [u32; 4],
}

/// A buffer the file side is done with, going back to be filled again.
enum Spent {
    /// An emptied array of collision records.
    Records(Vec<CollisionRecord>),
    /// The bytes of a written message.
    Bytes(Vec<u8>),
}

/// Message buffers at least this large (bytes) are given back for reuse: those of
/// snapshots and checkpoints, not of thermo records.
const RECYCLE_BYTES: usize = 1 << 16;

/// Work for the file side.
enum Cmd {
    Batch {
        sequence: u32,
        first_ordinal: u64,
        stride: u64,
        records: Vec<CollisionRecord>,
    },
    Message {
        ch: usize,
        sequence: u32,
        log_time: u64,
        publish_time: u64,
        data: Vec<u8>,
    },
    Metadata(Metadata),
    Flush,
    Finish,
}

/// The file side: owns the MCAP writer.
struct Sink {
    path: PathBuf,
    mcap: mcap::Writer<BufWriter<File>>,
    channel_ids: [u16; 4],
    cdr: CdrWriter,
    flush_every: Duration,
    last_flush: Instant,
    dirty: bool,
}

impl Sink {
    fn err(&self, source: mcap::McapError) -> WriteError {
        WriteError::from_mcap(&self.path, source)
    }

    /// Handle one command; an emptied record buffer, and a written message's
    /// buffer, are handed to `recycle`.
    fn handle(&mut self, cmd: Cmd, recycle: &mut dyn FnMut(Spent)) -> Result<(), WriteError> {
        match cmd {
            Cmd::Batch {
                sequence,
                first_ordinal,
                stride,
                mut records,
            } => {
                if !records.is_empty() {
                    CollisionBatch::encode_records(&records, first_ordinal, stride, &mut self.cdr);
                    let header = MessageHeader {
                        channel_id: self.channel_ids[CH_COLLISIONS],
                        sequence,
                        log_time: log_time_ns(records[0].time),
                        publish_time: log_time_ns(records[records.len() - 1].time),
                    };
                    let r = self.mcap.write_to_known_channel(&header, self.cdr.bytes());
                    r.map_err(|e| self.err(e))?;
                    self.dirty = true;
                }
                records.clear();
                recycle(Spent::Records(records));
            }
            Cmd::Message {
                ch,
                sequence,
                log_time,
                publish_time,
                data,
            } => {
                let header = MessageHeader {
                    channel_id: self.channel_ids[ch],
                    sequence,
                    log_time,
                    publish_time,
                };
                let r = self.mcap.write_to_known_channel(&header, &data);
                r.map_err(|e| self.err(e))?;
                self.dirty = true;
                if data.capacity() >= RECYCLE_BYTES {
                    recycle(Spent::Bytes(data));
                }
            }
            Cmd::Metadata(m) => {
                let r = self.mcap.write_metadata(&m);
                r.map_err(|e| self.err(e))?;
                self.dirty = true;
            }
            Cmd::Flush => self.flush()?,
            Cmd::Finish => {}
        }
        if self.dirty && self.last_flush.elapsed() >= self.flush_every {
            self.flush()?;
        }
        Ok(())
    }

    fn flush(&mut self) -> Result<(), WriteError> {
        let r = self.mcap.flush();
        r.map_err(|e| self.err(e))?;
        self.last_flush = Instant::now();
        self.dirty = false;
        Ok(())
    }

    /// Write the summary section and close the file; returns its size in bytes.
    fn finish(mut self) -> Result<u64, WriteError> {
        let r = self.mcap.finish();
        r.map_err(|e| self.err(e))?;
        let path = self.path.clone();
        let io = |source| WriteError::Io {
            path: path.clone(),
            source,
        };
        let mut buf = self.mcap.into_inner();
        use std::io::Write;
        buf.flush().map_err(io)?;
        let file = buf.into_inner().map_err(|e| io(e.into_error()))?;
        Ok(file.metadata().map_err(io)?.len())
    }

    /// The writer thread's loop.
    fn serve(
        mut self,
        rx: Receiver<Cmd>,
        records: mpsc::Sender<Vec<CollisionRecord>>,
        bytes: mpsc::Sender<Vec<u8>>,
    ) -> Result<u64, WriteError> {
        let mut give_back = |spent: Spent| {
            let _ = match spent {
                Spent::Records(v) => records.send(v).is_ok(),
                Spent::Bytes(v) => bytes.send(v).is_ok(),
            };
        };
        loop {
            let wait = if self.dirty {
                self.flush_every.saturating_sub(self.last_flush.elapsed())
            } else {
                Duration::from_secs(3600)
            };
            match rx.recv_timeout(wait) {
                Ok(Cmd::Finish) | Err(RecvTimeoutError::Disconnected) => return self.finish(),
                Ok(cmd) => self.handle(cmd, &mut give_back)?,
                Err(RecvTimeoutError::Timeout) => {
                    if self.dirty {
                        self.flush()?;
                    }
                }
            }
        }
    }
}

/// Where the file side lives.
enum Backend {
    Inline(Box<Sink>),
    Thread {
        tx: SyncSender<Cmd>,
        recycled: Receiver<Vec<CollisionRecord>>,
        recycled_bytes: Receiver<Vec<u8>>,
        handle: JoinHandle<Result<u64, WriteError>>,
    },
    Done,
}

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
        let file = File::create(path).map_err(|source| WriteError::Io {
            path: path.to_path_buf(),
            source,
        })?;
        let compression = match opts.compression {
            Compression::Zstd => Some(mcap::Compression::Zstd),
            Compression::Lz4 => Some(mcap::Compression::Lz4),
            Compression::None => None,
        };
        let mcap_err = |source| WriteError::from_mcap(path, source);
        let mut mcap = mcap::WriteOptions::new()
            .compression(compression)
            // The mcap crate takes the level as u32 and hands it to zstd as i32
            // (`as` casts), so a negative (fast) zstd level passes through its
            // two's-complement bit pattern.
            .compression_level(opts.compression_level as u32)
            .compression_threads(0)
            .chunk_size(Some(opts.chunk_size))
            .library(format!("carom-io {}", env!("CARGO_PKG_VERSION")))
            .create(BufWriter::with_capacity(1 << 20, file))
            .map_err(mcap_err)?;
        mcap.write_metadata(&Metadata {
            name: METADATA_RUN.into(),
            metadata: run_metadata.clone(),
        })
        .map_err(mcap_err)?;
        let schemas: [(&str, &str, &str); 4] = [
            (
                SCHEMA_COLLISION_BATCH,
                SCHEMA_ENCODING_ROS2MSG,
                COLLISION_BATCH_MSG,
            ),
            (SCHEMA_SNAPSHOT, SCHEMA_ENCODING_ROS2MSG, SNAPSHOT_MSG),
            (
                SCHEMA_THERMO,
                SCHEMA_ENCODING_JSONSCHEMA,
                THERMO_JSON_SCHEMA,
            ),
            (SCHEMA_CHECKPOINT, SCHEMA_ENCODING_ROS2MSG, CHECKPOINT_MSG),
        ];
        let mut channel_ids = [0u16; 4];
        for (k, (name, enc, text)) in schemas.iter().enumerate() {
            let sid = mcap
                .add_schema(name, enc, text.as_bytes())
                .map_err(mcap_err)?;
            let menc = if k == CH_THERMO {
                MESSAGE_ENCODING_JSON
            } else {
                MESSAGE_ENCODING_CDR
            };
            channel_ids[k] = mcap
                .add_channel(sid, TOPICS[k], menc, &BTreeMap::new())
                .map_err(mcap_err)?;
        }
        let sink = Sink {
            path: path.to_path_buf(),
            mcap,
            channel_ids,
            cdr: CdrWriter::new(),
            flush_every: opts.flush_every,
            last_flush: Instant::now(),
            dirty: true,
        };
        let backend = if opts.background {
            let (tx, rx) = mpsc::sync_channel(QUEUE_DEPTH);
            let (rtx, recycled) = mpsc::channel();
            let (btx, recycled_bytes) = mpsc::channel();
            let handle = std::thread::Builder::new()
                .name("carom-log-writer".into())
                .spawn(move || sink.serve(rx, rtx, btx))
                .map_err(|e| WriteError::Thread {
                    path: path.to_path_buf(),
                    problem: format!("cannot start: {e}"),
                })?;
            Backend::Thread {
                tx,
                recycled,
                recycled_bytes,
                handle,
            }
        } else {
            Backend::Inline(Box::new(sink))
        };
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
    /// the collisions not yet on disk ([`QUEUE_DEPTH`] full batches waiting for the
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
                sink.handle(cmd, &mut |spent| match spent {
                    // Inline: hand the (cleared) buffer straight back.
                    Spent::Records(mut v) => std::mem::swap(pending, &mut v),
                    Spent::Bytes(v) => cdr.reuse(v),
                })
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
    /// the next large message into.
    fn reclaim_bytes(&mut self) {
        if let Backend::Thread { recycled_bytes, .. } = &self.backend {
            while let Ok(b) = recycled_bytes.try_recv() {
                self.cdr.reuse(b);
            }
        }
    }

    fn send_message(&mut self, ch: usize, t: f64, data: Vec<u8>) -> Result<(), WriteError> {
        self.write_batch()?;
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
        self.send(Cmd::Message {
            ch,
            sequence,
            log_time,
            publish_time,
            data: data.to_vec(),
        })
    }

    /// Ask for a flush: close the current chunk and hand everything written so far
    /// to the operating system (the pending collisions are sent first). With the
    /// writer thread the flush happens in order after the messages already sent.
    pub fn flush(&mut self) -> Result<(), WriteError> {
        self.write_batch()?;
        self.send(Cmd::Flush)
    }

    /// With the inline backend, flush if `flush_every` of wall time has passed since
    /// the last flush (the writer thread does this by itself).
    #[inline]
    pub fn maybe_flush(&mut self) -> Result<(), WriteError> {
        if let Backend::Inline(sink) = &mut self.backend {
            if sink.dirty && sink.last_flush.elapsed() >= sink.flush_every {
                sink.flush()?;
            }
        }
        Ok(())
    }

    /// Send the pending collisions and the `carom.summary` metadata record, write
    /// the MCAP summary section, close the file and wait for the writer thread.
    /// Returns the file size in bytes.
    pub fn finish(&mut self, summary: &BTreeMap<String, String>) -> Result<u64, WriteError> {
        self.write_metadata(METADATA_SUMMARY, summary)?;
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

    #[test]
    fn mcap_io_errors_show_the_operating_systems_reason() {
        let io = std::io::Error::from(std::io::ErrorKind::StorageFull);
        let text = io.to_string();
        let e = WriteError::from_mcap(Path::new("run.mcap"), mcap::McapError::Io(io));
        assert!(matches!(e, WriteError::Io { .. }), "{e:?}");
        assert_eq!(e.to_string(), format!("cannot write log run.mcap: {text}"));
        // Other MCAP errors keep the library's own message.
        let e = WriteError::from_mcap(Path::new("run.mcap"), mcap::McapError::TooManyChannels);
        assert!(matches!(e, WriteError::Mcap { .. }), "{e:?}");
    }
}
