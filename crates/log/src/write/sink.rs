//! The file side of a log writer: the MCAP writer itself ([`Sink`]), run inline
//! or on its own thread ([`Backend`]), fed by commands ([`Cmd`]) and handing
//! spent buffers back for reuse ([`Spent`]).

use super::options::{WriteError, WriterOptions};
use crate::format::{
    log_time_ns, seal, CdrWriter, CollisionBatch, CollisionRecord, CompactBatch, CHANNELS,
    CH_COLLISIONS, COMPACT_COLLISIONS_CHANNEL, METADATA_RUN, METADATA_SUMMARY,
};
use crate::format::{CH_SCENE, N_CHANNELS};
use crate::options::CollisionDetail;
use crate::options::Compression;
use mcap::records::{MessageHeader, Metadata};
use std::collections::BTreeMap;
use std::fs::File;
use std::io::BufWriter;
use std::path::{Path, PathBuf};
use std::sync::mpsc::{self, Receiver, RecvTimeoutError, SyncSender};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

/// Messages that may wait for the writer thread before the caller blocks.
pub(super) const QUEUE_DEPTH: usize = 8;

/// A buffer the file side is done with, going back to be filled again.
pub(super) enum Spent {
    /// An emptied array of collision records.
    Records(Vec<CollisionRecord>),
    /// The bytes of a written message.
    Bytes(Vec<u8>),
}

/// Message buffers at least this large (bytes) are given back for reuse: those of
/// snapshots and checkpoints, not of thermo records.
const RECYCLE_BYTES: usize = 1 << 16;

/// Work for the file side.
pub(super) enum Cmd {
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
    /// Flush, then have the operating system write the file to its disk; the
    /// answer goes back once it has.
    Sync(SyncSender<()>),
    Finish,
}

/// `m` as written: a `carom.run` or `carom.summary` record with its checksum
/// (whatever map the caller built or copied; see `format::checksum`), any
/// other record as it is.
fn sealed(mut m: Metadata) -> Metadata {
    if m.name == METADATA_RUN || m.name == METADATA_SUMMARY {
        seal(&mut m.metadata);
    }
    m
}

/// The file side: owns the MCAP writer.
pub(super) struct Sink {
    path: PathBuf,
    mcap: mcap::Writer<BufWriter<File>>,
    /// A second handle on the file, to make its data durable (`Cmd::Sync`).
    durable: File,
    /// MCAP channel id of each channel, once defined.
    channel_ids: [Option<u16>; N_CHANNELS],
    /// `Some(normals)` when `/collisions` holds compact records.
    compact: Option<bool>,
    cdr: CdrWriter,
    pub(super) flush_every: Duration,
    pub(super) last_flush: Instant,
    pub(super) dirty: bool,
}

impl Sink {
    /// Create `path` (truncating it), write the `carom.run` metadata record and
    /// register the channels of [`CHANNELS`] but `/scene`, which is defined
    /// before its first message (runs without scene frames do not show it);
    /// `/collisions` with the compact schema unless the options ask for the full
    /// record.
    pub(super) fn create(
        path: &Path,
        opts: &WriterOptions,
        run_metadata: &BTreeMap<String, String>,
    ) -> Result<Sink, WriteError> {
        let file = File::create(path).map_err(|source| WriteError::Io {
            path: path.to_path_buf(),
            source,
        })?;
        let durable = file.try_clone().map_err(|source| WriteError::Io {
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
            // Build each chunk in memory and write it whole when it closes: with
            // seeking, the crate writes a placeholder chunk header (length 2⁶⁴−1)
            // into the file and fixes it up at the end of the chunk, so a killed
            // run's file ended in a record strict readers (`@mcap/core`) refuse.
            // The finished file's bytes are the same either way.
            .disable_seeking(true)
            .library(format!("carom-log {}", env!("CARGO_PKG_VERSION")))
            .create(BufWriter::with_capacity(1 << 20, file))
            .map_err(mcap_err)?;
        mcap.write_metadata(&sealed(Metadata {
            name: METADATA_RUN.into(),
            metadata: run_metadata.clone(),
        }))
        .map_err(mcap_err)?;
        let compact = (opts.collision_detail == CollisionDetail::Compact
            && opts.collision_every == 1)
            .then_some(opts.collision_normals);
        let mut sink = Sink {
            path: path.to_path_buf(),
            mcap,
            durable,
            channel_ids: [None; N_CHANNELS],
            compact,
            cdr: CdrWriter::new(),
            flush_every: opts.flush_every,
            last_flush: Instant::now(),
            dirty: true,
        };
        for ch in (0..N_CHANNELS).filter(|&ch| ch != CH_SCENE) {
            sink.channel_id(ch)?;
        }
        Ok(sink)
    }

    /// The MCAP channel id of channel `ch`, defining it (schema and channel
    /// records) first if it is not yet.
    fn channel_id(&mut self, ch: usize) -> Result<u16, WriteError> {
        if let Some(id) = self.channel_ids[ch] {
            return Ok(id);
        }
        let c = match self.compact {
            Some(_) if ch == CH_COLLISIONS => &COMPACT_COLLISIONS_CHANNEL,
            _ => &CHANNELS[ch],
        };
        let sid = self
            .mcap
            .add_schema(c.schema_name, c.schema_encoding, c.schema_text.as_bytes())
            .map_err(|e| self.err(e))?;
        let id = self
            .mcap
            .add_channel(sid, c.topic, c.message_encoding, &BTreeMap::new())
            .map_err(|e| self.err(e))?;
        self.channel_ids[ch] = Some(id);
        Ok(id)
    }

    fn err(&self, source: mcap::McapError) -> WriteError {
        WriteError::from_mcap(&self.path, source)
    }

    /// Handle one command; an emptied record buffer, and a written message's
    /// buffer, are handed to `recycle`.
    pub(super) fn handle(
        &mut self,
        cmd: Cmd,
        recycle: &mut dyn FnMut(Spent),
    ) -> Result<(), WriteError> {
        match cmd {
            Cmd::Batch {
                sequence,
                first_ordinal,
                stride,
                mut records,
            } => {
                if !records.is_empty() {
                    match self.compact {
                        Some(normals) => CompactBatch::encode_records(
                            &records,
                            first_ordinal,
                            normals,
                            &mut self.cdr,
                        ),
                        None => CollisionBatch::encode_records(
                            &records,
                            first_ordinal,
                            stride,
                            &mut self.cdr,
                        ),
                    }
                    let header = MessageHeader {
                        channel_id: self.channel_id(CH_COLLISIONS)?,
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
                    channel_id: self.channel_id(ch)?,
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
                let r = self.mcap.write_metadata(&sealed(m));
                r.map_err(|e| self.err(e))?;
                self.dirty = true;
            }
            Cmd::Flush => self.flush()?,
            Cmd::Sync(done) => {
                self.sync()?;
                let _ = done.send(());
            }
            Cmd::Finish => {}
        }
        if self.dirty && self.last_flush.elapsed() >= self.flush_every {
            self.flush()?;
        }
        Ok(())
    }

    /// Flush, and wait until the file's data are on its disk.
    pub(super) fn sync(&mut self) -> Result<(), WriteError> {
        self.flush()?;
        self.durable.sync_data().map_err(|source| WriteError::Io {
            path: self.path.clone(),
            source,
        })
    }

    pub(super) fn flush(&mut self) -> Result<(), WriteError> {
        let r = self.mcap.flush();
        r.map_err(|e| self.err(e))?;
        self.last_flush = Instant::now();
        self.dirty = false;
        Ok(())
    }

    /// Write the summary section and close the file; returns its size in bytes.
    pub(super) fn finish(mut self) -> Result<u64, WriteError> {
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
pub(super) enum Backend {
    Inline(Box<Sink>),
    Thread {
        tx: SyncSender<Cmd>,
        recycled: Receiver<Vec<CollisionRecord>>,
        recycled_bytes: Receiver<Vec<u8>>,
        handle: JoinHandle<Result<u64, WriteError>>,
    },
    Done,
}

impl Backend {
    /// Run `sink` on a writer thread of its own, or inline on the caller's.
    pub(super) fn start(sink: Sink, background: bool) -> Result<Backend, WriteError> {
        if !background {
            return Ok(Backend::Inline(Box::new(sink)));
        }
        let path = sink.path.clone();
        let (tx, rx) = mpsc::sync_channel(QUEUE_DEPTH);
        let (rtx, recycled) = mpsc::channel();
        let (btx, recycled_bytes) = mpsc::channel();
        let handle = std::thread::Builder::new()
            .name("carom-log-writer".into())
            .spawn(move || sink.serve(rx, rtx, btx))
            .map_err(|e| WriteError::Thread {
                path,
                problem: format!("cannot start: {e}"),
            })?;
        Ok(Backend::Thread {
            tx,
            recycled,
            recycled_bytes,
            handle,
        })
    }
}
