//! The carom log: an MCAP file with four channels and two metadata records.
//!
//! `format` is in the middle: the channel table (topics, schemas, encodings),
//! the version constants, the metadata records with the resolved run, and each
//! message's Rust form with its CDR or JSON codec. `write` (the [`LogWriter`](crate::LogWriter))
//! and `read` (the [`LogReader`](crate::LogReader) and whole-file scans) each use the format and
//! never each other, as the `mcap` crate's writer and reader share its
//! `records.rs`. `docs/log-format.md` documents the format for other languages.

pub(crate) mod format;
pub(crate) mod read;
pub(crate) mod write;
