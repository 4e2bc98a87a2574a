//! The records that say what a log holds, as the reader meets them: `carom.run`
//! first (the run; its checksum), each channel's definition (checked against the
//! format's table), and `carom.summary` (how the run ended; left out, with a
//! warning, when its checksum fails).

use super::replay::Replay;
use super::{parse_record, LogEnd, LogReader, ReadError};
use crate::format::{
    verify, Checksum, MetadataError, RunMetadata, SummaryMetadata, CHANNELS, CHECKSUM_KEY,
    CH_COLLISIONS, COMPACT_COLLISIONS_CHANNEL, METADATA_RUN, METADATA_SUMMARY, TOPICS,
};
use mcap::records::{Channel, Record};
use std::collections::BTreeMap;
use std::io::{Read, Seek};

impl<R: Read + Seek> LogReader<R> {
    /// Read records up to the `carom.run` metadata, which carom writes first.
    pub(super) fn read_run_metadata(&mut self) -> Result<(), ReadError> {
        loop {
            match self.next_record() {
                Ok(true) => {}
                Ok(false) => return Err(self.not_carom("the file ends before any carom metadata")),
                Err(detail) => {
                    return Err(self.not_carom(format!(
                        "not a readable MCAP file up to its `{METADATA_RUN}` record ({detail})"
                    )))
                }
            }
            match parse_record(self.opcode, &self.record) {
                Ok(Record::Header(_)) => continue,
                Ok(Record::Metadata(m)) if m.name == METADATA_RUN => {
                    let error = |source| ReadError::Metadata {
                        file: self.label.clone(),
                        source,
                    };
                    let check = verify(&m.metadata);
                    let parsed = RunMetadata::from_map(&m.metadata);
                    // (A log of another major format is named as such first: its
                    // records need not follow this version's checksum rule.)
                    if let (Some(problem), false) = (
                        check.problem(),
                        matches!(&parsed, Err(e) if e.key == "log_format"),
                    ) {
                        return Err(error(MetadataError {
                            record: METADATA_RUN,
                            key: CHECKSUM_KEY,
                            problem,
                        }));
                    }
                    self.run = parsed.map_err(error)?;
                    self.run_sealed = check == Checksum::Holds;
                    self.run_map = m.metadata;
                    return Ok(());
                }
                Ok(other) => {
                    return Err(self.not_carom(format!(
                        "expected the `{METADATA_RUN}` metadata record first, found a record with opcode {:#04x}",
                        other.opcode()
                    )))
                }
                Err(e) => {
                    return Err(self.not_carom(format!(
                        "malformed record where the `{METADATA_RUN}` record belongs: {e}"
                    )))
                }
            }
        }
    }

    /// Keep the `carom.summary` record `metadata`, or, when its checksum fails or
    /// it does not parse, say why it is left out (a warning at the end, not an
    /// error: the messages are all there).
    pub(super) fn take_summary(&mut self, metadata: BTreeMap<String, String>) {
        let check = verify(&metadata);
        match (check.problem(), SummaryMetadata::from_map(&metadata)) {
            (Some(problem), _) => {
                self.summary_damage = Some(format!(
                    "{METADATA_SUMMARY}: {problem}; its values are not used"
                ))
            }
            (None, Ok(_)) => self.summary = Some(metadata),
            (None, Err(e)) => {
                self.summary_damage =
                    Some(format!("the {METADATA_SUMMARY} record is unreadable: {e}"))
            }
        }
    }

    /// Record the MCAP channel `c`: one of carom's topics must have the schema
    /// and encodings of the format's table (the compact `/collisions` schema
    /// switches on the replay of velocities); another tool's channel is ignored.
    pub(super) fn define_channel(&mut self, c: &Channel) -> Result<(), ReadError> {
        let ours = TOPICS.iter().position(|&t| t == c.topic);
        if let Some(k) = ours {
            let (sname, senc) = self.schemas.get(&c.schema_id).cloned().unwrap_or_default();
            let compact = k == CH_COLLISIONS && sname == COMPACT_COLLISIONS_CHANNEL.schema_name;
            let want = if compact {
                &COMPACT_COLLISIONS_CHANNEL
            } else {
                &CHANNELS[k]
            };
            if compact && self.replay.is_none() {
                self.replay = Some(Box::new(Replay::new(self.run.run_facts.as_ref())));
            }
            if sname != want.schema_name
                || senc != want.schema_encoding
                || c.message_encoding != want.message_encoding
            {
                self.end = LogEnd::Failed;
                return Err(ReadError::WrongSchema {
                    file: self.label.clone(),
                    topic: TOPICS[k],
                    found: format!("{sname} ({senc}, messages {})", c.message_encoding),
                    expected: format!(
                        "{} ({}, messages {})",
                        want.schema_name, want.schema_encoding, want.message_encoding
                    ),
                });
            }
            self.seen[k] = true;
        }
        self.channels.insert(c.id, ours);
        Ok(())
    }
}
