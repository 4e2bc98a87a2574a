//! Where a [`super::LogReader`]'s raw MCAP records come from: read and
//! decompressed on the calling thread ([`Inline`]), or on a thread of their own
//! that keeps a few batches of records ahead ([`ReadAhead`]), so that decoding
//! and analysis on the calling thread overlap with zstd on the other core. Both
//! hand out the same records in the same order, and the same errors at the same
//! record; memory stays bounded by [`AHEAD`] batches of about [`BATCH_BYTES`].

use mcap::sans_io::{LinearReadEvent, LinearReader};
use std::io::Read;
use std::panic::AssertUnwindSafe;
use std::sync::mpsc::{sync_channel, Receiver};

/// Most bytes handed to the MCAP reader per read call.
const READ_STEP: usize = 1 << 20;
/// Record bytes per batch sent from the reading thread.
const BATCH_BYTES: usize = 1 << 20;
/// Batches the reading thread may hold ready.
const AHEAD: usize = 4;

/// Records read on the calling thread.
pub(super) struct Inline<R> {
    pub(super) source: R,
    pub(super) linear: LinearReader,
    pub(super) bytes_read: u64,
}

impl<R: Read> Inline<R> {
    /// The next record into `out` (replacing its content); its opcode, or `None`
    /// at a clean end. A panic of the mcap crate's reader is an error (see
    /// [`super::parse_record`]).
    pub(super) fn next(&mut self, out: &mut Vec<u8>) -> Result<Option<u8>, String> {
        std::panic::catch_unwind(AssertUnwindSafe(|| self.next_unguarded(out))).unwrap_or_else(
            |_| Err("malformed record: a length beyond the end of its chunk or record".into()),
        )
    }

    fn next_unguarded(&mut self, out: &mut Vec<u8>) -> Result<Option<u8>, String> {
        loop {
            let event = match self.linear.next_event() {
                None => return Ok(None),
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
                    out.clear();
                    out.extend_from_slice(data);
                    return Ok(Some(opcode));
                }
            }
        }
    }
}

/// What the reading thread sends.
enum Batch {
    /// Records back to back in `data`, each (opcode, end offset); the source's
    /// bytes read after the last of them.
    Records {
        data: Vec<u8>,
        records: Vec<(u8, usize)>,
        bytes_read: u64,
    },
    /// The clean end of the file.
    End,
    /// The error the inline reader would have returned at this point.
    Failed(String),
}

/// Records read ahead on a thread of their own.
pub(super) struct ReadAhead {
    rx: Receiver<Batch>,
    data: Vec<u8>,
    records: Vec<(u8, usize)>,
    next: usize,
    pub(super) bytes_read: u64,
    done: Option<Result<(), String>>,
}

impl ReadAhead {
    /// Moves `inline` to a new thread that reads ahead of the caller.
    pub(super) fn spawn<R: Read + Send + 'static>(mut inline: Inline<R>) -> Self {
        let bytes_read = inline.bytes_read;
        let (tx, rx) = sync_channel(AHEAD);
        std::thread::spawn(move || {
            let mut record = Vec::new();
            loop {
                let (mut data, mut records) = (Vec::with_capacity(BATCH_BYTES), Vec::new());
                let last = loop {
                    match inline.next(&mut record) {
                        Ok(Some(opcode)) => {
                            data.extend_from_slice(&record);
                            records.push((opcode, data.len()));
                            if data.len() >= BATCH_BYTES {
                                break None;
                            }
                        }
                        Ok(None) => break Some(Batch::End),
                        Err(e) => break Some(Batch::Failed(e)),
                    }
                };
                let batch = Batch::Records {
                    data,
                    records,
                    bytes_read: inline.bytes_read,
                };
                // A closed channel: the reader was dropped; stop.
                if tx.send(batch).is_err() {
                    return;
                }
                if let Some(last) = last {
                    let _ = tx.send(last);
                    return;
                }
            }
        });
        ReadAhead {
            rx,
            data: Vec::new(),
            records: Vec::new(),
            next: 0,
            bytes_read,
            done: None,
        }
    }

    /// [`Inline::next`], from the batches.
    pub(super) fn next(&mut self, out: &mut Vec<u8>) -> Result<Option<u8>, String> {
        while self.next == self.records.len() {
            if let Some(done) = &self.done {
                return done.clone().map(|()| None);
            }
            match self.rx.recv() {
                Ok(Batch::Records {
                    data,
                    records,
                    bytes_read,
                }) => {
                    (self.data, self.records, self.next) = (data, records, 0);
                    self.bytes_read = bytes_read;
                }
                Ok(Batch::End) => self.done = Some(Ok(())),
                Ok(Batch::Failed(e)) => self.done = Some(Err(e)),
                Err(_) => self.done = Some(Err("the reading thread stopped".into())),
            }
        }
        let start = if self.next == 0 {
            0
        } else {
            self.records[self.next - 1].1
        };
        let (opcode, end) = self.records[self.next];
        self.next += 1;
        out.clear();
        out.extend_from_slice(&self.data[start..end]);
        Ok(Some(opcode))
    }
}

/// The records of a reader: inline, or read ahead (`Moved` only while the
/// inline reader is being handed to its thread).
pub(super) enum RecordSource<R> {
    Inline(Inline<R>),
    ReadAhead(ReadAhead),
    Moved,
}

impl<R: Read> RecordSource<R> {
    /// The next record into `out`; its opcode, or `None` at a clean end.
    pub(super) fn next(&mut self, out: &mut Vec<u8>) -> Result<Option<u8>, String> {
        match self {
            RecordSource::Inline(r) => r.next(out),
            RecordSource::ReadAhead(r) => r.next(out),
            RecordSource::Moved => Err("the reader was moved".into()),
        }
    }

    /// Bytes taken from the source so far.
    pub(super) fn bytes_read(&self) -> u64 {
        match self {
            RecordSource::Inline(r) => r.bytes_read,
            RecordSource::ReadAhead(r) => r.bytes_read,
            RecordSource::Moved => 0,
        }
    }
}
