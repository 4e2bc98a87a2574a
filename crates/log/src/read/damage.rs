//! What a failure while reading means: the end of the file reached after every
//! message (damage outside the chunks: [`LogEnd::Damaged`], a warning), a file cut
//! short ([`LogEnd::Truncated`]), or damage that loses messages (an error).

use super::{Found, LogReader};
use crate::read::{LogEnd, ReadError};
use mcap::records::op;
use std::io::{Read, Seek};

/// How the mcap crate's error for a failed data-section CRC begins.
const DATA_CRC_FAILED: &str = "Data section CRC failed";

impl<R: Read + Seek> LogReader<R> {
    /// Whether every message has been read by the time of a failure, `data_crc`
    /// saying whether it is the data section's CRC that failed (which the MCAP
    /// reader checks at the data-end record, after the last chunk).
    ///
    /// A failed data-section CRC alone proves nothing about where the damage is:
    /// it covers the records outside the chunks too, the run's configuration
    /// among them. In a log whose `carom.run` checksum held (format 2.3 on), with
    /// every chunk's CRC held (else reading would have stopped there) and no
    /// record of a kind carom does not write, the damage lies in the framing of
    /// records read without harm (or in `carom.summary`, whose checksum then
    /// fails): every message counts. Older logs fail as before.
    ///
    /// Any other failure comes after the data section once the `carom.summary`
    /// record, written after the last chunk, or a data-end record whose CRC held
    /// has been read (a data-end record misread out of damaged bytes fails its
    /// CRC), or, in a 2.3 log as above, any data-end record.
    fn all_messages_read(&self, data_crc: bool) -> bool {
        let framing_clean = self.run_sealed && self.foreign.is_none();
        if data_crc {
            return framing_clean;
        }
        self.summary.is_some()
            || self.summary_damage.is_some()
            || self.data_end_verified
            || (self.in_summary_section && framing_clean)
    }

    /// Whether the record just read, which does not parse, may be skipped: a
    /// metadata or message-index record (carom writes nothing else outside the
    /// chunks after `carom.run`).
    pub(super) fn damage_tolerable(&self) -> bool {
        self.opcode == op::METADATA || self.opcode == op::MESSAGE_INDEX
    }

    /// Turn a low-level failure into the end of reading: [`LogEnd::Damaged`], a
    /// warning, when every message has been read (see
    /// [`LogReader::all_messages_read`]), else truncated or an error.
    pub(super) fn fail(&mut self, detail: String) -> Result<Found, ReadError> {
        // (A file that simply ends there was cut while being finished: truncated.)
        let cut = self.cut && !self.has_end_magic;
        let data_crc = detail.starts_with(DATA_CRC_FAILED);
        if !cut && self.all_messages_read(data_crc) {
            let detail = [
                self.summary_damage.clone(),
                self.odd_metadata.clone(),
                Some(detail),
            ]
            .into_iter()
            .flatten()
            .collect::<Vec<_>>()
            .join("; ");
            self.end = LogEnd::Damaged { detail };
            return Ok(Found::End);
        }
        let detail = match &self.foreign {
            Some(f) => format!("{detail} (after {f})"),
            None => detail,
        };
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
}
