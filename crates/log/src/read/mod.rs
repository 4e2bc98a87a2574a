//! Reading carom logs: streaming, in file order (which is time order), with memory
//! bounded by one MCAP chunk (a few MiB) plus one message, whatever the file size.
//!
//! [`LogReader`] reads the `carom.run` metadata on opening, checks each carom
//! channel against the format's table and hands out raw or decoded messages
//! (`iter`); `scan` and `indexed` summarise a whole file, by reading it or from its
//! index. A file cut short reads up to its last complete chunk and ends with
//! [`LogEnd::Truncated`] (an error with [`ReadOptions::strict`]); damage that loses
//! messages is a [`ReadError::Corrupt`] error, after everything before it; damage
//! outside the chunks once every message is read is [`LogEnd::Damaged`], a warning
//! (`damage`). [`salvage`] reads around damaged chunks (for `carom repair`).
//! Nothing here panics on bad input.

mod damage;
mod definitions;
mod error;
mod indexed;
mod iter;
mod progress;
mod records;
mod replay;
mod salvage;
mod scan;

pub use error::{LogEnd, ReadError};
pub use indexed::scan_indexed;
pub use iter::{Collisions, Events, Filtered, LogEvent, LogMessage};
pub use progress::ReadProgress;
use records::metadata_name;
pub(crate) use records::parse_record;
pub use salvage::{salvage, LostPart, Salvaged};
pub use scan::{last_checkpoint, last_checkpoint_observed, scan, scan_observed, LogInfo};

use crate::format::N_CHANNELS;
use crate::format::{CollisionBatch, RunMetadata, SummaryMetadata, METADATA_RUN, METADATA_SUMMARY};
use mcap::records::{op, Record};
use mcap::sans_io::{LinearReader, LinearReaderOptions};
use replay::Replay;
use std::collections::{BTreeMap, HashMap};
use std::fs::File;
use std::io::{BufReader, Read, Seek, SeekFrom};
use std::path::Path;

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

impl RawMessage<'_> {
    /// The simulated times (time) of the message's first and last record, read
    /// from the message itself (a snapshot's or checkpoint's time twice; the
    /// MCAP log time, whole nanoseconds, only for a message that cannot be read).
    pub fn simulated_times(&self) -> (f64, f64) {
        scan::simulated_times(self)
    }
}

/// What [`LogReader::advance`] found.
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
///
/// ```no_run
/// use carom_log::{LogEvent, LogReader};
/// # fn main() -> Result<(), carom_log::ReadError> {
/// let mut log = LogReader::open("run.mcap".as_ref())?;
/// for e in log.events() {
///     if let LogEvent::Collision(c) = e? {
///         let _ = (c.time, c.i, c.j, c.vi_after);
///     }
/// }
/// # Ok(()) }
/// ```
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
    seen: [bool; N_CHANNELS],
    run: RunMetadata,
    run_map: BTreeMap<String, String>,
    summary: Option<BTreeMap<String, String>>,
    /// Why the `carom.summary` record, when reached, could not be read.
    summary_damage: Option<String>,
    /// Whether `carom.run` carries a checksum, which held (format 2.3 on).
    run_sealed: bool,
    /// A record in the data section of a kind carom does not write (damaged
    /// framing can make one up), if any: what it was.
    foreign: Option<String>,
    /// A metadata record of a name carom does not write (a damaged name?).
    odd_metadata: Option<String>,
    /// Whether the data-end record was read with a data-section CRC that held.
    data_end_verified: bool,
    /// Whether the last low-level failure was the file ending inside a record.
    cut: bool,
    has_end_magic: bool,
    in_summary_section: bool,
    strict: bool,
    end: LogEnd,
    messages: u64,
    batch: CollisionBatch,
    /// The replay of compact `/collisions` records (`Some` once the channel is
    /// found to hold them): batches decode through it into `batch`.
    replay: Option<Box<Replay>>,
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
            seen: [false; N_CHANNELS],
            run: RunMetadata {
                log_format: String::new(),
                carom_version: String::new(),
                config: String::new(),
                seed: 0,
                start_time: String::new(),
                n_discs: 0,
                stop: crate::options::Stop::Collisions(0),
                max_time_without_collision: None,
                log: Default::default(),
                resumed_from: None,
                resumed_at: None,
                run_facts: None,
            },
            run_map: BTreeMap::new(),
            summary: None,
            summary_damage: None,
            run_sealed: false,
            foreign: None,
            odd_metadata: None,
            data_end_verified: false,
            cut: false,
            has_end_magic,
            in_summary_section: false,
            strict: opts.strict,
            end: LogEnd::Reading,
            messages: 0,
            batch: CollisionBatch::default(),
            replay: None,
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

    fn advance(&mut self) -> Result<Found, ReadError> {
        if self.end != LogEnd::Reading {
            return Ok(Found::End);
        }
        loop {
            match self.next_record() {
                Ok(true) => {}
                Ok(false) => {
                    self.end = match self.summary_damage.take() {
                        Some(detail) => LogEnd::Damaged { detail },
                        None => LogEnd::Complete,
                    };
                    return Ok(Found::End);
                }
                Err(detail) => return self.fail(detail),
            }
            if self.in_summary_section {
                // Summary records repeat what the data section said; only check them.
                if let Err(e) = parse_record(self.opcode, &self.record) {
                    return self.fail(format!("malformed summary record: {e}"));
                }
                continue;
            }
            let rec = match parse_record(self.opcode, &self.record) {
                Ok(r) => r,
                // In a 2.3 log, a metadata or message-index record (outside the
                // chunks) whose body is damaged but whose length held: reading
                // goes on at the next record, and the data section's CRC decides
                // (see `all_messages_read`).
                Err(e) if self.run_sealed && self.damage_tolerable() => {
                    let what = format!("a malformed record of opcode {:#04x} ({e})", self.opcode);
                    if self.opcode == op::METADATA
                        && metadata_name(&self.record) == Some(METADATA_SUMMARY)
                    {
                        self.summary_damage = Some(format!(
                            "{METADATA_SUMMARY}: malformed ({e}); its values are not used"
                        ));
                    } else {
                        self.odd_metadata.get_or_insert(what);
                    }
                    continue;
                }
                Err(e) => return self.fail(format!("malformed record: {e}")),
            };
            match rec {
                Record::Schema { header, .. } => {
                    self.schemas
                        .insert(header.id, (header.name, header.encoding));
                }
                Record::Channel(c) => self.define_channel(&c)?,
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
                Record::Metadata(m) if m.name == METADATA_SUMMARY => self.take_summary(m.metadata),
                Record::Metadata(m) if m.name != METADATA_RUN => {
                    // Another tool's record, or one of ours with a damaged name:
                    // said only if the file turns out damaged.
                    self.odd_metadata = Some(format!(
                        "a metadata record named {:?}, which carom does not write (a {METADATA_SUMMARY} record with a damaged name?)",
                        m.name
                    ));
                }
                Record::DataEnd(d) => {
                    self.in_summary_section = true;
                    // (The MCAP reader has checked a non-zero CRC.)
                    self.data_end_verified = d.data_section_crc != 0;
                }
                Record::Header(_)
                | Record::Metadata(_)
                | Record::MessageIndex(_)
                | Record::Chunk { .. } => {}
                // carom writes no such record: damaged bytes (a chunk whose opcode
                // was hit would otherwise be skipped, and its messages lost unseen).
                Record::Unknown { opcode, .. } => {
                    return self.fail(format!(
                        "a record of unknown opcode {opcode:#04x} in the data section"
                    ))
                }
                // Records carom does not write in the data section (attachments,
                // index records): another writer's, or misread out of damage.
                other => {
                    self.foreign.get_or_insert_with(|| {
                        format!(
                            "a record of opcode {:#04x}, which carom does not write in the data section",
                            other.opcode()
                        )
                    });
                }
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

    /// Whether `/collisions` holds compact records (replayed into full ones by
    /// the decoding iterators), as far as read so far.
    pub fn compact_collisions(&self) -> bool {
        self.replay.is_some()
    }

    /// Whether each channel (see [`TOPICS`](crate::TOPICS)) has been defined so far.
    pub fn channels_seen(&self) -> [bool; N_CHANNELS] {
        self.seen
    }

    /// The file's label (its path).
    pub fn label(&self) -> &str {
        &self.label
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// 64 × the file's size, at least 64 MiB, at most 16 GiB.
    #[test]
    fn the_record_length_limit_follows_the_file_size_within_bounds() {
        assert_eq!(record_length_limit(0), 64 << 20);
        assert_eq!(record_length_limit(1 << 20), 64 << 20);
        assert_eq!(record_length_limit(3 << 20), 192 << 20);
        assert_eq!(record_length_limit(1 << 30), 16 << 30);
        assert_eq!(record_length_limit(u64::MAX), 16 << 30);
    }
}
