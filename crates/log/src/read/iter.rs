//! Decoding the messages a [`LogReader`] finds, and its iterators: every
//! collision ([`Collisions`]), the messages of one channel ([`Filtered`]) and all
//! events in time order ([`Events`]). The three share one loop ([`Cursor`]):
//! collision batches are decoded into the reader's one reused batch and handed out
//! one record at a time; other messages are decoded whole. Compact batches are
//! replayed into full ones (`replay`), for which every snapshot and checkpoint
//! is decoded too, wanted or not.

use super::{Found, LogEnd, LogReader, ReadError, MESSAGE_HEADER_LEN};
use crate::format::CH_SCENE;
use crate::format::{
    CdrError, CollisionBatch, CollisionRecord, LogCheckpoint, Snapshot, Thermo, CH_CHECKPOINT,
    CH_COLLISIONS, CH_SNAPSHOT, CH_THERMO, TOPICS,
};
use std::io::{Read, Seek};

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

impl<R: Read + Seek> LogReader<R> {
    pub(super) fn decode_error(
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

    /// The next message, decoded (`/scene` frames, which are for viewers, are
    /// skipped).
    pub fn next_message(&mut self) -> Result<Option<LogMessage>, ReadError> {
        loop {
            let Found::Message {
                channel,
                sequence,
                log_time,
                ..
            } = self.advance()?
            else {
                return Ok(None);
            };
            if channel != CH_SCENE {
                return decode_current(self, channel, sequence, log_time).map(Some);
            }
        }
    }

    /// The next `/collisions` batch, decoded into `out` (replayed if compact),
    /// reusing its allocations: `Ok(false)` at the end, `out` then empty. The
    /// fast way to read every collision: other messages are skipped undecoded,
    /// except the snapshots and checkpoints a compact replay needs. A log without
    /// a `/collisions` channel simply ends.
    pub fn next_batch_into(&mut self, out: &mut CollisionBatch) -> Result<bool, ReadError> {
        loop {
            let Found::Message {
                channel,
                sequence,
                log_time,
                ..
            } = self.advance()?
            else {
                out.clear();
                return Ok(false);
            };
            if channel == CH_COLLISIONS {
                return self.decode_batch(sequence, log_time, out).map(|()| true);
            }
            self.sync_replay(channel, sequence, log_time)?;
        }
    }

    /// Decode the current record as a collision batch into `out` (replaying it
    /// if compact).
    fn decode_batch(
        &mut self,
        sequence: u32,
        log_time: u64,
        out: &mut CollisionBatch,
    ) -> Result<(), ReadError> {
        let data = &self.record[MESSAGE_HEADER_LEN.min(self.record.len())..];
        let r = match &mut self.replay {
            Some(replay) => replay.expand(data, out),
            None => out.decode_into(data),
        };
        r.map_err(|e| self.decode_error(CH_COLLISIONS, sequence, log_time, e))
    }

    /// Decode the current record as a collision batch into the reader's own batch
    /// (replaying it if compact).
    fn decode_batch_in_place(&mut self, sequence: u32, log_time: u64) -> Result<(), ReadError> {
        let mut batch = std::mem::take(&mut self.batch);
        let r = self.decode_batch(sequence, log_time, &mut batch);
        self.batch = batch;
        r
    }

    /// Give the replay of compact records the velocities of the current record, a
    /// snapshot or a checkpoint that no one asked for.
    fn sync_replay(
        &mut self,
        channel: usize,
        sequence: u32,
        log_time: u64,
    ) -> Result<(), ReadError> {
        if self.replay.is_none() || !(channel == CH_SNAPSHOT || channel == CH_CHECKPOINT) {
            return Ok(());
        }
        decode_current(self, channel, sequence, log_time).map(|_| ())
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
        Collisions(Cursor::new(self, Wanted::Collisions))
    }

    /// Every snapshot in order. Ends with [`ReadError::MissingChannel`] if the file
    /// has no `/snapshot` channel.
    pub fn snapshots(&mut self) -> Filtered<'_, R> {
        Filtered(Cursor::new(self, Wanted::Channel(CH_SNAPSHOT)))
    }

    /// Every thermo record in order.
    pub fn thermo(&mut self) -> Filtered<'_, R> {
        Filtered(Cursor::new(self, Wanted::Channel(CH_THERMO)))
    }

    /// Every checkpoint in order.
    pub fn checkpoints(&mut self) -> Filtered<'_, R> {
        Filtered(Cursor::new(self, Wanted::Channel(CH_CHECKPOINT)))
    }

    /// Collisions one by one, interleaved with the other messages, in time order.
    pub fn events(&mut self) -> Events<'_, R> {
        Events(Cursor::new(self, Wanted::Events))
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
            match &mut reader.replay {
                Some(replay) => replay.expand(data, &mut b),
                None => b.decode_into(data),
            }
            .map(|_| LogMessage::Collisions(b))
        }
        CH_SNAPSHOT => Snapshot::decode(data).map(|s| {
            if let Some(replay) = &mut reader.replay {
                replay.sync_snapshot(&s);
            }
            LogMessage::Snapshot(s)
        }),
        CH_THERMO => {
            return Thermo::decode(data)
                .map(LogMessage::Thermo)
                .map_err(|source| ReadError::Json {
                    file: reader.label.clone(),
                    sequence,
                    source,
                })
        }
        _ => LogCheckpoint::decode(data).map(|c| {
            if let Some(replay) = &mut reader.replay {
                replay.sync_checkpoint(&c);
            }
            LogMessage::Checkpoint(Box::new(c))
        }),
    };
    r.map_err(|e| reader.decode_error(channel, sequence, log_time, e))
}

/// Which messages an iterator yields.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Wanted {
    /// Collisions one by one.
    Collisions,
    /// The messages of one channel, whole.
    Channel(usize),
    /// Collisions one by one and the other messages whole.
    Events,
}

impl Wanted {
    fn takes(self, channel: usize) -> bool {
        match self {
            Wanted::Collisions => channel == CH_COLLISIONS,
            Wanted::Channel(k) => channel == k,
            Wanted::Events => channel != CH_SCENE,
        }
    }

    /// The channel whose absence from the file ends the iteration with an error.
    fn required(self) -> Option<usize> {
        match self {
            Wanted::Collisions => Some(CH_COLLISIONS),
            Wanted::Channel(k) => Some(k),
            Wanted::Events => None,
        }
    }

    /// True when collision batches are handed out one record at a time.
    fn unbatches(self) -> bool {
        self != Wanted::Channel(CH_COLLISIONS) && self.takes(CH_COLLISIONS)
    }
}

/// What the loop found next.
enum Step {
    Collision(CollisionRecord),
    Message(LogMessage),
}

/// The one reading loop behind the iterators.
#[derive(Debug)]
struct Cursor<'a, R: Read + Seek> {
    reader: &'a mut LogReader<R>,
    wanted: Wanted,
    /// Next record of the reader's batch to hand out.
    k: usize,
    done: bool,
}

impl<'a, R: Read + Seek> Cursor<'a, R> {
    fn new(reader: &'a mut LogReader<R>, wanted: Wanted) -> Self {
        Cursor {
            reader,
            wanted,
            k: 0,
            done: false,
        }
    }

    /// The next wanted step; after an error, `None` for ever.
    fn step(&mut self) -> Option<Result<Step, ReadError>> {
        loop {
            if self.done {
                return None;
            }
            if self.k < self.reader.batch.len() {
                self.k += 1;
                return Some(Ok(Step::Collision(self.reader.batch.get(self.k - 1))));
            }
            let (channel, sequence, log_time) = match self.reader.advance() {
                Err(e) => {
                    self.done = true;
                    return Some(Err(e));
                }
                Ok(Found::End) => {
                    self.done = true;
                    self.reader.batch.clear();
                    let missing = self.wanted.required().and_then(|k| self.reader.missing(k));
                    return missing.map(Err);
                }
                Ok(Found::Message {
                    channel,
                    sequence,
                    log_time,
                    ..
                }) => (channel, sequence, log_time),
            };
            if !self.wanted.takes(channel) {
                // Snapshots and checkpoints feed the replay of compact collisions.
                let synced = if self.wanted.takes(CH_COLLISIONS) {
                    self.reader.sync_replay(channel, sequence, log_time)
                } else {
                    Ok(())
                };
                if let Err(e) = synced {
                    self.done = true;
                    return Some(Err(e));
                }
                continue;
            }
            self.k = 0;
            let r = if channel == CH_COLLISIONS && self.wanted.unbatches() {
                match self.reader.decode_batch_in_place(sequence, log_time) {
                    Ok(()) => continue,
                    Err(e) => Err(e),
                }
            } else {
                self.reader.batch.clear();
                decode_current(self.reader, channel, sequence, log_time).map(Step::Message)
            };
            self.done = r.is_err();
            return Some(r);
        }
    }

    /// The next step that `pick` turns into an item (others are skipped).
    fn next_picked<T>(&mut self, pick: fn(Step) -> Option<T>) -> Option<Result<T, ReadError>> {
        loop {
            match self.step()? {
                Ok(step) => {
                    if let Some(item) = pick(step) {
                        return Some(Ok(item));
                    }
                }
                Err(e) => return Some(Err(e)),
            }
        }
    }
}

/// Iterator over collisions (see [`LogReader::collisions`]).
#[derive(Debug)]
pub struct Collisions<'a, R: Read + Seek>(Cursor<'a, R>);

impl<R: Read + Seek> Iterator for Collisions<'_, R> {
    type Item = Result<CollisionRecord, ReadError>;

    fn next(&mut self) -> Option<Self::Item> {
        self.0.next_picked(|step| match step {
            Step::Collision(c) => Some(c),
            Step::Message(_) => None,
        })
    }
}

/// Iterator over the messages of one channel (see [`LogReader::snapshots`]).
#[derive(Debug)]
pub struct Filtered<'a, R: Read + Seek>(Cursor<'a, R>);

impl<R: Read + Seek> Iterator for Filtered<'_, R> {
    type Item = Result<LogMessage, ReadError>;

    fn next(&mut self) -> Option<Self::Item> {
        self.0.next_picked(|step| match step {
            Step::Message(m) => Some(m),
            Step::Collision(_) => None,
        })
    }
}

/// Iterator over all events in time order (see [`LogReader::events`]).
#[derive(Debug)]
pub struct Events<'a, R: Read + Seek>(Cursor<'a, R>);

impl<R: Read + Seek> Iterator for Events<'_, R> {
    type Item = Result<LogEvent, ReadError>;

    fn next(&mut self) -> Option<Self::Item> {
        // Batches come one record at a time (`Wanted::unbatches`), never whole.
        self.0.next_picked(|step| match step {
            Step::Collision(c) => Some(LogEvent::Collision(c)),
            Step::Message(LogMessage::Snapshot(s)) => Some(LogEvent::Snapshot(s)),
            Step::Message(LogMessage::Thermo(t)) => Some(LogEvent::Thermo(t)),
            Step::Message(LogMessage::Checkpoint(c)) => Some(LogEvent::Checkpoint(c)),
            Step::Message(LogMessage::Collisions(_)) => None,
        })
    }
}
