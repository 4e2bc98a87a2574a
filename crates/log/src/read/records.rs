//! Pulling records out of the MCAP byte stream: the reader's one source of raw
//! records, and the parse of a record with the mcap crate's panics turned into
//! errors (a damaged length must give an error, never a panic).

use super::{LogReader, READ_STEP};
use mcap::records::Record;
use mcap::sans_io::LinearReadEvent;
use std::io::{Read, Seek};
use std::panic::AssertUnwindSafe;

/// `mcap::parse_record`, with its panics as errors. The mcap crate (0.26) trusts
/// some lengths inside records and chunks (an attachment's data length, a record
/// longer than what is left of its chunk) and panics on a damaged one; carom's
/// promise is an error for any damaged log. Found by `fuzz/log_reader`; the inputs
/// are kept in `crates/log/tests/fuzz_regressions/`.
pub(crate) fn parse_record(opcode: u8, data: &[u8]) -> Result<Record<'_>, String> {
    match std::panic::catch_unwind(move || mcap::parse_record(opcode, data)) {
        Ok(Ok(record)) => Ok(record),
        Ok(Err(e)) => Err(e.to_string()),
        Err(_) => Err("malformed record: a length beyond the end of its record".into()),
    }
}

/// The name of a metadata record whose body may be damaged past its name
/// (the body starts with the name: u32 length, then its bytes).
pub(super) fn metadata_name(body: &[u8]) -> Option<&str> {
    let len = u32::from_le_bytes(body.get(..4)?.try_into().ok()?) as usize;
    std::str::from_utf8(body.get(4..4usize.checked_add(len)?)?).ok()
}

impl<R: Read + Seek> LogReader<R> {
    /// Pull the next raw record into `self.record`. Ok(false) at a clean end.
    /// A panic of the mcap crate's reader is an error (see [`parse_record`]).
    pub(super) fn next_record(&mut self) -> Result<bool, String> {
        std::panic::catch_unwind(AssertUnwindSafe(|| self.next_record_unguarded())).unwrap_or_else(
            |_| Err("malformed record: a length beyond the end of its chunk or record".into()),
        )
    }

    fn next_record_unguarded(&mut self) -> Result<bool, String> {
        loop {
            let event = match self.linear.next_event() {
                None => return Ok(false),
                Some(Err(e)) => {
                    self.cut = matches!(e, mcap::McapError::UnexpectedEof);
                    return Err(e.to_string());
                }
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
}
