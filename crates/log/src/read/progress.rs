//! How far a reader has got through its file, for progress displays.

use super::{LogEnd, LogReader};
use std::io::{Read, Seek};

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

impl<R: Read + Seek> LogReader<R> {
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
}
