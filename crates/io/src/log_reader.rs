//! Reading carom logs: streaming, in file order (which is time order), with memory
//! bounded by one MCAP chunk (a few MiB) plus one message, whatever the file size.
//!
//! ```no_run
//! use carom_io::log_reader::{LogReader, LogEvent};
//! # fn main() -> Result<(), carom_io::log_reader::ReadError> {
//! let mut log = LogReader::open("run.mcap".as_ref())?;
//! println!("config: {}", log.run().config);
//! // Every collision, one at a time (no allocation per collision):
//! for c in log.collisions() {
//!     let c = c?;
//!     let _ = (c.time, c.i, c.j, c.vi_after);
//! }
//! if let Some(warning) = log.end().warning() {
//!     eprintln!("warning: {warning}");
//! }
//! // Collisions, snapshots, thermo records and checkpoints interleaved in time order:
//! let mut log = LogReader::open("run.mcap".as_ref())?;
//! for e in log.events() {
//!     match e? {
//!         LogEvent::Collision(c) => { let _ = c; }
//!         LogEvent::Snapshot(s) => { let _ = s.velocities.len(); }
//!         LogEvent::Thermo(t) => { let _ = t.temperature; }
//!         LogEvent::Checkpoint(_) => {}
//!     }
//! }
//! # Ok(()) }
//! ```
//!
//! A file cut short (a killed run) reads up to its last complete chunk; the iterators
//! then end normally and [`LogReader::end`] says [`LogEnd::Truncated`] (with
//! [`ReadOptions::strict`] the cut is an error instead). Damage inside a file that
//! was finished properly is always a [`ReadError::Corrupt`] error, returned after
//! everything before the damage. Nothing here panics on bad input.

use crate::cdr::CdrError;
use crate::checkpoint_codec::LogCheckpoint;
use crate::log_writer::{CH_CHECKPOINT, CH_COLLISIONS, CH_SNAPSHOT, CH_THERMO, TOPICS};
use crate::run_metadata::{MetadataError, RunMetadata, SummaryMetadata};
use crate::schema::*;
use mcap::records::Record;
use mcap::sans_io::{LinearReadEvent, LinearReader, LinearReaderOptions};
use std::collections::{BTreeMap, HashMap};
use std::fs::File;
use std::io::{BufReader, Read, Seek, SeekFrom};
use std::path::Path;
use thiserror::Error;

/// Why a log could not be read. Each variant names the file.
#[derive(Debug, Error)]
pub enum ReadError {
    /// The file could not be opened or read.
    #[error("cannot read log {file}: {source}")]
    Io {
        /// The file.
        file: String,
        /// The operating system's error.
        source: std::io::Error,
    },
    /// The file is not an MCAP file written by carom (no `carom.run` metadata first).
    #[error("{file} is not a carom log: {problem}")]
    NotCarom {
        /// The file.
        file: String,
        /// What gave it away.
        problem: String,
    },
    /// The `carom.run` or `carom.summary` metadata is malformed.
    #[error("{file}: {source}")]
    Metadata {
        /// The file.
        file: String,
        /// The problem.
        source: MetadataError,
    },
    /// The file ends before its end (a killed run), in strict mode.
    #[error("{file} is truncated after {messages} messages: {detail}")]
    Truncated {
        /// The file.
        file: String,
        /// Messages read before the cut.
        messages: u64,
        /// The MCAP reader's message.
        detail: String,
    },
    /// The file is damaged (bad CRC, malformed record, undecodable compression).
    #[error("{file} is corrupted after {messages} messages: {detail}")]
    Corrupt {
        /// The file.
        file: String,
        /// Messages read before the damage.
        messages: u64,
        /// The MCAP reader's message.
        detail: String,
    },
    /// A carom topic uses an unexpected schema or encoding.
    #[error("{file}: topic {topic} has schema `{found}`, expected `{expected}`")]
    WrongSchema {
        /// The file.
        file: String,
        /// The topic.
        topic: &'static str,
        /// Schema name and encodings found.
        found: String,
        /// Schema name and encodings expected.
        expected: String,
    },
    /// A message could not be decoded.
    #[error(
        "{file}: {topic} message #{sequence} (log time {log_time} ns) cannot be decoded: {source}"
    )]
    Decode {
        /// The file.
        file: String,
        /// The topic.
        topic: &'static str,
        /// The message's sequence number.
        sequence: u32,
        /// The message's log time (ns).
        log_time: u64,
        /// The CDR problem.
        source: CdrError,
    },
    /// A `/thermo` message is not valid JSON for [`Thermo`].
    #[error("{file}: /thermo message #{sequence} is not a valid thermo record: {source}")]
    Json {
        /// The file.
        file: String,
        /// The message's sequence number.
        sequence: u32,
        /// The JSON problem.
        source: serde_json::Error,
    },
    /// The whole file was read and a channel the caller asked for never appeared.
    #[error("{file} has no {topic} channel{hint}")]
    MissingChannel {
        /// The file.
        file: String,
        /// The topic.
        topic: &'static str,
        /// Extra context (empty or starting with "; ").
        hint: String,
    },
    /// The file holds no checkpoint to resume from.
    #[error("{file} has no complete /checkpoint message to resume from")]
    NoCheckpoint {
        /// The file.
        file: String,
    },
}

/// How reading ended.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum LogEnd {
    /// Not at the end yet.
    Reading,
    /// The file ended properly (MCAP footer and end magic).
    Complete,
    /// The file stops early (a killed run): everything before `detail` was read.
    Truncated {
        /// What the MCAP reader found at the cut.
        detail: String,
    },
    /// Reading stopped at an error (see the error returned).
    Failed,
}

impl LogEnd {
    /// A warning for the user when the file was cut short.
    pub fn warning(&self) -> Option<String> {
        match self {
            LogEnd::Truncated { detail } => Some(format!(
                "the log is truncated (the run was killed or is still being written); \
                 read everything up to the last flush ({detail})"
            )),
            _ => None,
        }
    }
}

/// Reading options.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct ReadOptions {
    /// Report a truncated file as [`ReadError::Truncated`] instead of ending quietly
    /// with [`LogEnd::Truncated`].
    pub strict: bool,
    /// Largest record or decompressed chunk accepted (bytes); `None` = a bound derived
    /// from the file size (64 × the size, at least 64 MiB, at most 16 GiB).
    pub record_length_limit: Option<usize>,
}

/// A raw carom message: which of the four channels, and its bytes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct RawMessage<'a> {
    /// Channel index: 0 `/collisions`, 1 `/snapshot`, 2 `/thermo`, 3 `/checkpoint`.
    pub channel: usize,
    /// MCAP sequence number.
    pub sequence: u32,
    /// MCAP log time (ns; simulated time × 10⁹).
    pub log_time: u64,
    /// MCAP publish time (ns).
    pub publish_time: u64,
    /// The encoded message.
    pub data: &'a [u8],
}

/// A decoded message.
#[derive(Debug, Clone, PartialEq)]
pub enum LogMessage {
    /// A batch of collisions.
    Collisions(Box<CollisionBatch>),
    /// A snapshot.
    Snapshot(Snapshot),
    /// A thermo record.
    Thermo(Thermo),
    /// A checkpoint.
    Checkpoint(Box<LogCheckpoint>),
}

/// One event of the log in time order: collisions one by one, and the other messages.
#[derive(Debug, Clone, PartialEq)]
pub enum LogEvent {
    /// One collision.
    Collision(CollisionRecord),
    /// A snapshot.
    Snapshot(Snapshot),
    /// A thermo record.
    Thermo(Thermo),
    /// A checkpoint.
    Checkpoint(Box<LogCheckpoint>),
}

impl LogEvent {
    /// Simulated time of the event (time).
    pub fn time(&self) -> f64 {
        match self {
            LogEvent::Collision(c) => c.time,
            LogEvent::Snapshot(s) => s.time,
            LogEvent::Thermo(t) => t.time,
            LogEvent::Checkpoint(c) => c.engine.now,
        }
    }
}

enum Found {
    Message {
        channel: usize,
        sequence: u32,
        log_time: u64,
        publish_time: u64,
    },
    End,
}

/// Message header length inside a Message record (channel, sequence, two times).
const MESSAGE_HEADER_LEN: usize = 2 + 4 + 8 + 8;
/// Most bytes handed to the MCAP reader per read call.
const READ_STEP: usize = 1 << 20;

/// The longest record (bytes, compressed or not) accepted in a file of `len`
/// bytes: a length read from a damaged file must not ask for an absurd allocation,
/// and a chunk compresses physical data well under 64-fold.
fn record_length_limit(len: u64) -> usize {
    len.saturating_mul(64).clamp(64 << 20, 16 << 30) as usize
}

/// A streaming reader of one carom log.
pub struct LogReader<R: Read + Seek = BufReader<File>> {
    source: R,
    label: String,
    linear: LinearReader,
    record: Vec<u8>,
    opcode: u8,
    /// channel id → our channel index (None: a channel carom does not know).
    channels: HashMap<u16, Option<usize>>,
    /// schema id → (name, encoding).
    schemas: HashMap<u16, (String, String)>,
    seen: [bool; 4],
    run: RunMetadata,
    run_map: BTreeMap<String, String>,
    summary: Option<BTreeMap<String, String>>,
    has_end_magic: bool,
    in_summary_section: bool,
    strict: bool,
    end: LogEnd,
    messages: u64,
    batch: CollisionBatch,
    /// Bytes taken from the source so far.
    bytes_read: u64,
    /// The source's length (bytes).
    source_bytes: u64,
}

impl<R: Read + Seek> std::fmt::Debug for LogReader<R> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("LogReader")
            .field("file", &self.label)
            .field("messages", &self.messages)
            .field("end", &self.end)
            .finish_non_exhaustive()
    }
}

impl LogReader<BufReader<File>> {
    /// Open a log file and read its `carom.run` metadata.
    pub fn open(path: &Path) -> Result<Self, ReadError> {
        Self::open_with(path, ReadOptions::default())
    }

    /// [`LogReader::open`] with options.
    pub fn open_with(path: &Path, opts: ReadOptions) -> Result<Self, ReadError> {
        let label = path.display().to_string();
        // A directory opens like a file on Linux and then fails to read with
        // "Invalid argument": say what it is instead.
        let file = File::open(path)
            .and_then(|f| match f.metadata()?.is_dir() {
                true => Err(std::io::Error::new(
                    std::io::ErrorKind::IsADirectory,
                    "a directory, not a log file",
                )),
                false => Ok(f),
            })
            .map_err(|source| ReadError::Io {
                file: label.clone(),
                source,
            })?;
        Self::new(BufReader::with_capacity(1 << 20, file), label, opts)
    }
}

impl<R: Read + Seek> LogReader<R> {
    /// Read a log from any seekable source; `label` names it in errors.
    pub fn new(mut source: R, label: String, opts: ReadOptions) -> Result<Self, ReadError> {
        let io = |source| ReadError::Io {
            file: label.clone(),
            source,
        };
        let len = source.seek(SeekFrom::End(0)).map_err(io)?;
        let mut has_end_magic = false;
        if len >= 16 {
            source.seek(SeekFrom::End(-8)).map_err(io)?;
            let mut tail = [0u8; 8];
            source.read_exact(&mut tail).map_err(io)?;
            has_end_magic = tail == mcap::MAGIC;
        }
        source.seek(SeekFrom::Start(0)).map_err(io)?;
        let limit = opts
            .record_length_limit
            .unwrap_or_else(|| record_length_limit(len));
        let linear = LinearReader::new_with_options(
            LinearReaderOptions::default()
                .with_prevalidate_chunk_crcs(true)
                .with_validate_chunk_crcs(true)
                .with_validate_data_section_crc(true)
                .with_validate_summary_section_crc(true)
                .with_record_length_limit(limit),
        );
        let mut r = LogReader {
            source,
            label,
            linear,
            record: Vec::new(),
            opcode: 0,
            channels: HashMap::new(),
            schemas: HashMap::new(),
            seen: [false; 4],
            run: RunMetadata {
                log_format: String::new(),
                carom_version: String::new(),
                config: String::new(),
                seed: 0,
                start_time: String::new(),
                n_discs: 0,
                stop: crate::options::Stop::Collisions(0),
                log: Default::default(),
                resumed_from: None,
                resumed_at: None,
            },
            run_map: BTreeMap::new(),
            summary: None,
            has_end_magic,
            in_summary_section: false,
            strict: opts.strict,
            end: LogEnd::Reading,
            messages: 0,
            batch: CollisionBatch::default(),
            bytes_read: 0,
            source_bytes: len,
        };
        r.read_run_metadata()?;
        Ok(r)
    }

    fn not_carom(&self, problem: impl Into<String>) -> ReadError {
        ReadError::NotCarom {
            file: self.label.clone(),
            problem: problem.into(),
        }
    }

    /// Read records up to the `carom.run` metadata, which carom writes first.
    fn read_run_metadata(&mut self) -> Result<(), ReadError> {
        loop {
            match self.next_record() {
                Ok(true) => {}
                Ok(false) => return Err(self.not_carom("the file ends before any carom metadata")),
                Err(detail) => {
                    return Err(self.not_carom(format!("not a readable MCAP file ({detail})")))
                }
            }
            match mcap::parse_record(self.opcode, &self.record) {
                Ok(Record::Header(_)) => continue,
                Ok(Record::Metadata(m)) if m.name == METADATA_RUN => {
                    self.run = RunMetadata::from_map(&m.metadata).map_err(|source| {
                        ReadError::Metadata {
                            file: self.label.clone(),
                            source,
                        }
                    })?;
                    self.run_map = m.metadata;
                    return Ok(());
                }
                Ok(other) => {
                    return Err(self.not_carom(format!(
                        "expected the `{METADATA_RUN}` metadata record first, found a record with opcode {:#04x}",
                        other.opcode()
                    )))
                }
                Err(e) => return Err(self.not_carom(format!("malformed first record: {e}"))),
            }
        }
    }

    /// Pull the next raw record into `self.record`. Ok(false) at a clean end.
    fn next_record(&mut self) -> Result<bool, String> {
        loop {
            let event = match self.linear.next_event() {
                None => return Ok(false),
                Some(Err(e)) => return Err(e.to_string()),
                Some(Ok(e)) => e,
            };
            match event {
                LinearReadEvent::ReadRequest(need) => {
                    let step = need.clamp(1, READ_STEP);
                    let buf = self.linear.insert(step);
                    let n = loop {
                        match self.source.read(buf) {
                            Ok(n) => break n,
                            Err(e) if e.kind() == std::io::ErrorKind::Interrupted => continue,
                            Err(e) => return Err(format!("I/O error: {e}")),
                        }
                    };
                    self.linear.notify_read(n);
                    self.bytes_read += n as u64;
                }
                LinearReadEvent::Record { data, opcode } => {
                    self.record.clear();
                    self.record.extend_from_slice(data);
                    self.opcode = opcode;
                    return Ok(true);
                }
            }
        }
    }

    /// Turn a low-level failure into the end of reading.
    fn fail(&mut self, detail: String) -> Result<Found, ReadError> {
        if !self.has_end_magic && !self.strict {
            self.end = LogEnd::Truncated { detail };
            return Ok(Found::End);
        }
        self.end = LogEnd::Failed;
        if self.has_end_magic {
            Err(ReadError::Corrupt {
                file: self.label.clone(),
                messages: self.messages,
                detail,
            })
        } else {
            Err(ReadError::Truncated {
                file: self.label.clone(),
                messages: self.messages,
                detail,
            })
        }
    }

    fn advance(&mut self) -> Result<Found, ReadError> {
        if self.end != LogEnd::Reading {
            return Ok(Found::End);
        }
        loop {
            match self.next_record() {
                Ok(true) => {}
                Ok(false) => {
                    self.end = LogEnd::Complete;
                    return Ok(Found::End);
                }
                Err(detail) => return self.fail(detail),
            }
            if self.in_summary_section {
                // Summary records repeat what the data section said; only check them.
                if let Err(e) = mcap::parse_record(self.opcode, &self.record) {
                    return self.fail(format!("malformed summary record: {e}"));
                }
                continue;
            }
            let rec = match mcap::parse_record(self.opcode, &self.record) {
                Ok(r) => r,
                Err(e) => return self.fail(format!("malformed record: {e}")),
            };
            match rec {
                Record::Schema { header, .. } => {
                    self.schemas
                        .insert(header.id, (header.name, header.encoding));
                }
                Record::Channel(c) => {
                    let ours = TOPICS.iter().position(|&t| t == c.topic);
                    if let Some(k) = ours {
                        let (sname, senc) =
                            self.schemas.get(&c.schema_id).cloned().unwrap_or_default();
                        let expected = match k {
                            CH_COLLISIONS => (SCHEMA_COLLISION_BATCH, SCHEMA_ENCODING_ROS2MSG),
                            CH_SNAPSHOT => (SCHEMA_SNAPSHOT, SCHEMA_ENCODING_ROS2MSG),
                            CH_THERMO => (SCHEMA_THERMO, SCHEMA_ENCODING_JSONSCHEMA),
                            _ => (SCHEMA_CHECKPOINT, SCHEMA_ENCODING_ROS2MSG),
                        };
                        let menc = if k == CH_THERMO {
                            MESSAGE_ENCODING_JSON
                        } else {
                            MESSAGE_ENCODING_CDR
                        };
                        if sname != expected.0 || senc != expected.1 || c.message_encoding != menc {
                            self.end = LogEnd::Failed;
                            return Err(ReadError::WrongSchema {
                                file: self.label.clone(),
                                topic: TOPICS[k],
                                found: format!("{sname} ({senc}, messages {})", c.message_encoding),
                                expected: format!(
                                    "{} ({}, messages {menc})",
                                    expected.0, expected.1
                                ),
                            });
                        }
                        self.seen[k] = true;
                    }
                    self.channels.insert(c.id, ours);
                }
                Record::Message { header, .. } => match self.channels.get(&header.channel_id) {
                    Some(&Some(channel)) => {
                        self.messages += 1;
                        return Ok(Found::Message {
                            channel,
                            sequence: header.sequence,
                            log_time: header.log_time,
                            publish_time: header.publish_time,
                        });
                    }
                    Some(None) => {}
                    None => {
                        return self.fail(format!(
                            "message on channel {} which was never defined",
                            header.channel_id
                        ))
                    }
                },
                Record::Metadata(m) if m.name == METADATA_SUMMARY => {
                    self.summary = Some(m.metadata);
                }
                Record::DataEnd(_) => self.in_summary_section = true,
                _ => {}
            }
        }
    }

    /// The next carom message in file order, undecoded; `Ok(None)` at the end (see
    /// [`LogReader::end`]). Messages on topics carom does not know are skipped.
    pub fn next_raw(&mut self) -> Result<Option<RawMessage<'_>>, ReadError> {
        match self.advance()? {
            Found::End => Ok(None),
            Found::Message {
                channel,
                sequence,
                log_time,
                publish_time,
            } => Ok(Some(RawMessage {
                channel,
                sequence,
                log_time,
                publish_time,
                data: &self.record[MESSAGE_HEADER_LEN.min(self.record.len())..],
            })),
        }
    }

    fn decode_error(
        &self,
        channel: usize,
        sequence: u32,
        log_time: u64,
        source: CdrError,
    ) -> ReadError {
        ReadError::Decode {
            file: self.label.clone(),
            topic: TOPICS[channel],
            sequence,
            log_time,
            source,
        }
    }

    /// The next message, decoded.
    pub fn next_message(&mut self) -> Result<Option<LogMessage>, ReadError> {
        let Found::Message {
            channel,
            sequence,
            log_time,
            ..
        } = self.advance()?
        else {
            return Ok(None);
        };
        decode_current(self, channel, sequence, log_time).map(Some)
    }

    /// Decode the current record as a collision batch into the reader's own batch.
    fn decode_batch_in_place(&mut self, sequence: u32, log_time: u64) -> Result<(), ReadError> {
        let data = &self.record[MESSAGE_HEADER_LEN.min(self.record.len())..];
        if let Err(e) = self.batch.decode_into(data) {
            return Err(self.decode_error(CH_COLLISIONS, sequence, log_time, e));
        }
        Ok(())
    }

    /// The `carom.run` metadata.
    pub fn run(&self) -> &RunMetadata {
        &self.run
    }

    /// The `carom.run` metadata as stored (string map).
    pub fn run_map(&self) -> &BTreeMap<String, String> {
        &self.run_map
    }

    /// The `carom.summary` metadata, once reading has reached it (only complete
    /// runs have one).
    pub fn summary(&self) -> Result<Option<SummaryMetadata>, ReadError> {
        self.summary
            .as_ref()
            .map(|m| {
                SummaryMetadata::from_map(m).map_err(|source| ReadError::Metadata {
                    file: self.label.clone(),
                    source,
                })
            })
            .transpose()
    }

    /// How reading ended so far.
    pub fn end(&self) -> &LogEnd {
        &self.end
    }

    /// Carom messages read so far.
    pub fn messages_read(&self) -> u64 {
        self.messages
    }

    /// How far through the file reading has got: bytes taken from it so far (in
    /// steps of a record or a chunk, at most 1 MiB) and its length. Once reading
    /// has ended (see [`LogReader::end`]) the whole file counts as read: the index
    /// records at its end are not needed.
    pub fn progress(&self) -> ReadProgress {
        ReadProgress {
            bytes_read: if self.end == LogEnd::Reading {
                self.bytes_read.min(self.source_bytes)
            } else {
                self.source_bytes
            },
            file_bytes: self.source_bytes,
        }
    }

    /// [`LogReader::progress`] if the reader has read more of the file since
    /// `shown` bytes (which is then updated): for displays that show progress
    /// only when it has moved (about once per MiB), whatever the number of
    /// messages read in between.
    pub fn progress_since(&self, shown: &mut u64) -> Option<ReadProgress> {
        let p = self.progress();
        (p.bytes_read != *shown).then(|| {
            *shown = p.bytes_read;
            p
        })
    }

    /// Whether each channel (see [`TOPICS`]) has been defined so far.
    pub fn channels_seen(&self) -> [bool; 4] {
        self.seen
    }

    /// The file's label (its path).
    pub fn label(&self) -> &str {
        &self.label
    }

    fn missing(&self, ch: usize) -> Option<ReadError> {
        (!self.seen[ch]).then(|| ReadError::MissingChannel {
            file: self.label.clone(),
            topic: TOPICS[ch],
            hint: match &self.end {
                LogEnd::Truncated { .. } => {
                    "; the file is truncated before the channel was written".into()
                }
                _ => String::new(),
            },
        })
    }

    /// Every logged collision in order, one at a time (batches are decoded into one
    /// reused buffer). Ends with [`ReadError::MissingChannel`] if the file has no
    /// `/collisions` channel.
    pub fn collisions(&mut self) -> Collisions<'_, R> {
        Collisions {
            reader: self,
            k: 0,
            done: false,
        }
    }

    /// Every snapshot in order. Ends with [`ReadError::MissingChannel`] if the file
    /// has no `/snapshot` channel.
    pub fn snapshots(&mut self) -> Filtered<'_, R> {
        Filtered {
            reader: self,
            channel: CH_SNAPSHOT,
            done: false,
        }
    }

    /// Every thermo record in order.
    pub fn thermo(&mut self) -> Filtered<'_, R> {
        Filtered {
            reader: self,
            channel: CH_THERMO,
            done: false,
        }
    }

    /// Every checkpoint in order.
    pub fn checkpoints(&mut self) -> Filtered<'_, R> {
        Filtered {
            reader: self,
            channel: CH_CHECKPOINT,
            done: false,
        }
    }

    /// Collisions one by one, interleaved with the other messages, in time order.
    pub fn events(&mut self) -> Events<'_, R> {
        Events {
            reader: self,
            k: 0,
            done: false,
        }
    }
}

/// Iterator over collisions (see [`LogReader::collisions`]).
#[derive(Debug)]
pub struct Collisions<'a, R: Read + Seek> {
    reader: &'a mut LogReader<R>,
    k: usize,
    done: bool,
}

impl<R: Read + Seek> Iterator for Collisions<'_, R> {
    type Item = Result<CollisionRecord, ReadError>;

    fn next(&mut self) -> Option<Self::Item> {
        loop {
            if self.done {
                return None;
            }
            if self.k < self.reader.batch.len() {
                self.k += 1;
                return Some(Ok(self.reader.batch.get(self.k - 1)));
            }
            match self.reader.advance() {
                Err(e) => {
                    self.done = true;
                    return Some(Err(e));
                }
                Ok(Found::End) => {
                    self.done = true;
                    self.reader.batch.clear();
                    return self.reader.missing(CH_COLLISIONS).map(Err);
                }
                Ok(Found::Message {
                    channel: CH_COLLISIONS,
                    sequence,
                    log_time,
                    ..
                }) => {
                    self.k = 0;
                    if let Err(e) = self.reader.decode_batch_in_place(sequence, log_time) {
                        self.done = true;
                        return Some(Err(e));
                    }
                }
                Ok(_) => {}
            }
        }
    }
}

/// Iterator over the messages of one channel (see [`LogReader::snapshots`]).
#[derive(Debug)]
pub struct Filtered<'a, R: Read + Seek> {
    reader: &'a mut LogReader<R>,
    channel: usize,
    done: bool,
}

impl<R: Read + Seek> Iterator for Filtered<'_, R> {
    type Item = Result<LogMessage, ReadError>;

    fn next(&mut self) -> Option<Self::Item> {
        loop {
            if self.done {
                return None;
            }
            let found = match self.reader.advance() {
                Err(e) => {
                    self.done = true;
                    return Some(Err(e));
                }
                Ok(Found::End) => {
                    self.done = true;
                    return self.reader.missing(self.channel).map(Err);
                }
                Ok(Found::Message {
                    channel,
                    sequence,
                    log_time,
                    ..
                }) if channel == self.channel => (sequence, log_time),
                Ok(_) => continue,
            };
            let r = decode_current(self.reader, self.channel, found.0, found.1);
            if r.is_err() {
                self.done = true;
            }
            return Some(r);
        }
    }
}

fn decode_current<R: Read + Seek>(
    reader: &mut LogReader<R>,
    channel: usize,
    sequence: u32,
    log_time: u64,
) -> Result<LogMessage, ReadError> {
    let data = &reader.record[MESSAGE_HEADER_LEN.min(reader.record.len())..];
    let r = match channel {
        CH_COLLISIONS => {
            let mut b = Box::<CollisionBatch>::default();
            b.decode_into(data).map(|_| LogMessage::Collisions(b))
        }
        CH_SNAPSHOT => Snapshot::decode(data).map(LogMessage::Snapshot),
        CH_THERMO => {
            return serde_json::from_slice(data)
                .map(LogMessage::Thermo)
                .map_err(|source| ReadError::Json {
                    file: reader.label.clone(),
                    sequence,
                    source,
                })
        }
        _ => LogCheckpoint::decode(data).map(|c| LogMessage::Checkpoint(Box::new(c))),
    };
    r.map_err(|e| reader.decode_error(channel, sequence, log_time, e))
}

/// Iterator over all events in time order (see [`LogReader::events`]).
#[derive(Debug)]
pub struct Events<'a, R: Read + Seek> {
    reader: &'a mut LogReader<R>,
    k: usize,
    done: bool,
}

impl<R: Read + Seek> Iterator for Events<'_, R> {
    type Item = Result<LogEvent, ReadError>;

    fn next(&mut self) -> Option<Self::Item> {
        loop {
            if self.done {
                return None;
            }
            if self.k < self.reader.batch.len() {
                self.k += 1;
                return Some(Ok(LogEvent::Collision(self.reader.batch.get(self.k - 1))));
            }
            let (channel, sequence, log_time) = match self.reader.advance() {
                Err(e) => {
                    self.done = true;
                    return Some(Err(e));
                }
                Ok(Found::End) => {
                    self.done = true;
                    self.reader.batch.clear();
                    return None;
                }
                Ok(Found::Message {
                    channel,
                    sequence,
                    log_time,
                    ..
                }) => (channel, sequence, log_time),
            };
            if channel == CH_COLLISIONS {
                self.k = 0;
                if let Err(e) = self.reader.decode_batch_in_place(sequence, log_time) {
                    self.done = true;
                    return Some(Err(e));
                }
                continue;
            }
            self.reader.batch.clear();
            self.k = 0;
            let r = decode_current(self.reader, channel, sequence, log_time).map(|m| match m {
                LogMessage::Snapshot(s) => LogEvent::Snapshot(s),
                LogMessage::Thermo(t) => LogEvent::Thermo(t),
                LogMessage::Checkpoint(c) => LogEvent::Checkpoint(c),
                LogMessage::Collisions(_) => unreachable!("handled above"),
            });
            if r.is_err() {
                self.done = true;
            }
            return Some(r);
        }
    }
}

/// How far a reader has got through its file (see [`LogReader::progress`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ReadProgress {
    /// Bytes read from the file so far.
    pub bytes_read: u64,
    /// The file's length (bytes).
    pub file_bytes: u64,
}

impl ReadProgress {
    /// The fraction of the file read, in [0, 1] (1 for an empty file).
    pub fn fraction(&self) -> f64 {
        if self.file_bytes == 0 {
            1.0
        } else {
            (self.bytes_read as f64 / self.file_bytes as f64).min(1.0)
        }
    }
}

/// What a scan of a whole log found (for `carom info`).
#[derive(Debug, Clone, PartialEq)]
pub struct LogInfo {
    /// The `carom.run` metadata.
    pub run: RunMetadata,
    /// The `carom.summary` metadata (complete runs only).
    pub summary: Option<SummaryMetadata>,
    /// How the file ends.
    pub end: LogEnd,
    /// Whether each channel is defined (see [`TOPICS`]).
    pub channels: [bool; 4],
    /// Messages per channel.
    pub messages: [u64; 4],
    /// Collisions in `/collisions`.
    pub logged_collisions: u64,
    /// Simulated time of the first and last message per channel (time); `None` if no message.
    pub time_span: [Option<(f64, f64)>; 4],
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
    let mut messages = [0u64; 4];
    let mut span: [Option<(f64, f64)>; 4] = [None; 4];
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
fn simulated_times(m: &RawMessage) -> (f64, f64) {
    let exact = match m.channel {
        CH_COLLISIONS => batch_times(m.data).map(|(_, first, last)| (first, last)),
        CH_SNAPSHOT => crate::cdr::CdrReader::new(m.data)
            .and_then(|mut r| r.get::<f64>("time"))
            .ok()
            .map(|t| (t, t)),
        CH_THERMO => Thermo::decode(m.data).ok().map(|t| (t.time, t.time)),
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
    let mut r = crate::cdr::CdrReader::new(data).ok()?;
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

/// [`scan`]'s findings for a log that was finished properly, read from its index
/// (the MCAP summary section) and the few chunks that hold each channel's first and
/// last messages, instead of from the whole file: what `carom analyze` needs before
/// its own pass over every message. Message counts come from the index's
/// statistics, logged collisions from the `carom.summary` metadata, and times and
/// thermo counts from the messages themselves, so the result equals [`scan`]'s for
/// an intact file. Nothing else in the file is read or checked: damage elsewhere is
/// found only by a later full read. `Ok(None)` when the file has no usable index (a
/// run cut short; then use [`scan`]).
pub fn scan_indexed(path: &Path) -> Result<Option<LogInfo>, ReadError> {
    use mcap::sans_io::indexed_reader::ReadOrder;
    use mcap::sans_io::indexed_reader::{IndexedReadEvent, IndexedReader, IndexedReaderOptions};
    use mcap::sans_io::summary_reader::{SummaryReadEvent, SummaryReader, SummaryReaderOptions};

    let label = path.display().to_string();
    let io = |source| ReadError::Io {
        file: label.clone(),
        source,
    };
    let head = LogReader::open(path)?;
    let mut file = File::open(path).map_err(io)?;
    let file_bytes = file.metadata().map_err(io)?.len();
    if !head.has_end_magic {
        return Ok(None);
    }
    // Knowing the file's size, the summary reader never asks for more bytes than
    // are left (a damaged length cannot make it allocate gigabytes).
    let mut summary_reader = SummaryReader::new_with_options(
        SummaryReaderOptions::default()
            .with_file_size(file_bytes)
            .with_record_length_limit(record_length_limit(file_bytes)),
    );
    while let Some(event) = summary_reader.next_event() {
        let Ok(event) = event else { return Ok(None) };
        match event {
            SummaryReadEvent::ReadRequest(need) => {
                let n = file.read(summary_reader.insert(need)).map_err(io)?;
                summary_reader.notify_read(n);
            }
            SummaryReadEvent::SeekRequest(to) => {
                summary_reader.notify_seeked(file.seek(to).map_err(io)?);
            }
        }
    }
    let Some(summary) = summary_reader.finish() else {
        return Ok(None);
    };
    let Some(stats) = &summary.stats else {
        return Ok(None);
    };
    // Our channel index of each MCAP channel id.
    let ours: HashMap<u16, usize> = summary
        .channels
        .iter()
        .filter_map(|(&id, c)| TOPICS.iter().position(|&t| t == c.topic).map(|k| (id, k)))
        .collect();
    let mut channels = [false; 4];
    let mut messages = [0u64; 4];
    for (&id, &k) in &ours {
        channels[k] = true;
        messages[k] += stats.channel_message_counts.get(&id).copied().unwrap_or(0);
    }
    // The carom.summary metadata (logged collisions, and the summary itself).
    let Some(index) = summary
        .metadata_indexes
        .iter()
        .find(|m| m.name == METADATA_SUMMARY)
    else {
        return Ok(None);
    };
    // (An index pointing outside the file is damage: left to the full scan, as is
    // any other inconsistency below.)
    if index.length < 9 || index.offset.saturating_add(index.length) > file_bytes {
        return Ok(None);
    }
    let mut record = vec![0u8; index.length as usize];
    file.seek(SeekFrom::Start(index.offset)).map_err(io)?;
    file.read_exact(&mut record).map_err(io)?;
    // A record is its opcode, its length (u64) and its body.
    let Ok(Record::Metadata(m)) = mcap::parse_record(record[0], &record[9..]) else {
        return Ok(None);
    };
    let Ok(carom_summary) = SummaryMetadata::from_map(&m.metadata) else {
        return Ok(None);
    };
    // The chunks (in file order) that hold each channel's first and last message.
    let mut chunks = summary.chunk_indexes.clone();
    chunks.sort_by_key(|c| c.chunk_start_offset);
    if chunks.iter().any(|c| c.message_index_offsets.is_empty()) {
        return Ok(None);
    }
    let ours = &ours;
    let holding = |k: usize| {
        move |c: &&mcap::records::ChunkIndex| {
            c.message_index_offsets
                .keys()
                .any(|id| ours.get(id) == Some(&k))
        }
    };
    let mut ends: [Option<(RawOwned, RawOwned)>; 4] = Default::default();
    for (k, end) in ends.iter_mut().enumerate() {
        let (Some(first), Some(last)) = (
            chunks.iter().find(holding(k)),
            chunks.iter().rfind(holding(k)),
        ) else {
            continue;
        };
        let mut pick = |chunk: &mcap::records::ChunkIndex,
                        want_last: bool|
         -> Result<Option<RawOwned>, ReadError> {
            let one = mcap::Summary {
                chunk_indexes: vec![chunk.clone()],
                channels: summary.channels.clone(),
                schemas: summary.schemas.clone(),
                ..Default::default()
            };
            let Ok(mut reader) = IndexedReader::new_with_options(
                &one,
                IndexedReaderOptions::new()
                    .with_order(ReadOrder::File)
                    .with_record_length_limit(record_length_limit(file_bytes)),
            ) else {
                return Ok(None);
            };
            let mut found: Option<RawOwned> = None;
            let mut buf = Vec::new();
            while let Some(event) = reader.next_event() {
                let Ok(event) = event else { return Ok(None) };
                match event {
                    IndexedReadEvent::ReadChunkRequest { offset, length } => {
                        if offset.saturating_add(length as u64) > file_bytes {
                            return Ok(None);
                        }
                        file.seek(SeekFrom::Start(offset)).map_err(io)?;
                        buf.resize(length, 0);
                        file.read_exact(&mut buf).map_err(io)?;
                        if reader.insert_chunk_record_data(offset, &buf).is_err() {
                            return Ok(None);
                        }
                    }
                    IndexedReadEvent::Message { header, data } => {
                        if ours.get(&header.channel_id) == Some(&k) {
                            found = Some(RawOwned {
                                channel: k,
                                log_time: header.log_time,
                                publish_time: header.publish_time,
                                data: data.to_vec(),
                            });
                            if !want_last {
                                break;
                            }
                        }
                    }
                }
            }
            Ok(found)
        };
        let (Some(a), Some(b)) = (pick(first, false)?, pick(last, true)?) else {
            return Ok(None);
        };
        *end = Some((a, b));
    }
    let mut time_span: [Option<(f64, f64)>; 4] = [None; 4];
    for (span, end) in time_span.iter_mut().zip(&ends) {
        if let Some((a, b)) = end {
            let (t0, _) = simulated_times(&a.raw());
            let (_, t1) = simulated_times(&b.raw());
            *span = Some((t0, t1));
        }
    }
    let last_checkpoint_time = ends[CH_CHECKPOINT]
        .as_ref()
        .map(|(_, b)| simulated_times(&b.raw()).0);
    let thermo_counts = match &ends[CH_THERMO] {
        Some((a, b)) => {
            let count = |m: &RawOwned| {
                Thermo::decode(&m.data)
                    .ok()
                    .map(|t| (t.time, t.pair_collisions, t.wall_collisions))
            };
            match (count(a), count(b)) {
                (Some(x), Some(y)) => Some([x, y]),
                _ => return Ok(None),
            }
        }
        None => None,
    };
    Ok(Some(LogInfo {
        run: head.run.clone(),
        summary: Some(carom_summary.clone()),
        end: LogEnd::Complete,
        channels,
        messages,
        logged_collisions: carom_summary.logged_collisions,
        time_span,
        last_checkpoint_time,
        thermo_counts,
        file_bytes,
    }))
}

/// A message copied out of its chunk (see [`scan_indexed`]).
struct RawOwned {
    channel: usize,
    log_time: u64,
    publish_time: u64,
    data: Vec<u8>,
}

impl RawOwned {
    fn raw(&self) -> RawMessage<'_> {
        RawMessage {
            channel: self.channel,
            sequence: 0,
            log_time: self.log_time,
            publish_time: self.publish_time,
            data: &self.data,
        }
    }
}
