//! The log writer and reader at the carom-io level: small logs written with
//! [`LogWriter`] from a real engine run of a few dozen discs (or by hand, with the
//! `mcap` crate, for files carom would not write) and read back with
//! [`LogReader`], `scan`, `scan_indexed` and `last_checkpoint`. Every expected
//! value comes from what the test wrote (the engine's events and states, its own
//! count of batches and sequence numbers) or from the documented format
//! (docs/log-format.md), never from the reader. (Found missing by mutation
//! testing, docs/testing.md: the reader and writer were exercised only by the
//! root package's whole-engine tests.)

use carom_core::{Boundary, DVec2, Restitution, Species};
use carom_events::{Engine, EngineParams, Event, SystemSpec};
use carom_io::{
    last_checkpoint, scan, scan_indexed, scan_observed, CollisionDetail, CollisionRecord,
    Compression, DriverState, LogCheckpoint, LogEnd, LogEvent, LogMessage, LogOptions, LogReader,
    LogWriter, ReadError, ReadOptions, ReadProgress, RunFacts, RunMetadata, Snapshot, Stop,
    StopReason, SummaryMetadata, Thermo, WriteError, WriterOptions, WriterPosition, CH_CHECKPOINT,
    CH_COLLISIONS, CH_SCENE, CH_SNAPSHOT, CH_THERMO, KIND_PAIR, KIND_WALL, LOG_FORMAT_VERSION,
    METADATA_RUN, METADATA_SUMMARY, NO_DISC, N_CHANNELS, TOPICS,
};
use std::collections::BTreeMap;
use std::io::{Cursor, Read, Seek, SeekFrom};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::Duration;

/// A fresh path in the temporary directory (removed by [`Written`]'s drop).
fn tmp(name: &str) -> PathBuf {
    static N: AtomicU64 = AtomicU64::new(0);
    let k = N.fetch_add(1, Ordering::Relaxed);
    std::env::temp_dir().join(format!(
        "carom-io-log-rw-{}-{k}-{name}.mcap",
        std::process::id()
    ))
}

/// The documented log time of simulated time `t`: round(t · 10⁹) ns.
fn ns(t: f64) -> u64 {
    (t * 1e9).round() as u64
}

/// How a test log is written.
#[derive(Clone)]
struct Plan {
    detail: CollisionDetail,
    every: u64,
    collisions: bool,
    compression: Compression,
    chunk_size: u64,
    batch_size: usize,
    background: bool,
    scene: bool,
    position: WriterPosition,
    t_end: f64,
    /// Flush after every message (each message group ends its chunk).
    flush_each: bool,
    /// Write the start snapshot (a compact log needs velocities before its first
    /// collision: from a snapshot or a checkpoint).
    start_snapshot: bool,
    /// Write a thermo record at the end (just before the final checkpoint, at
    /// the same time).
    final_thermo: bool,
}

impl Default for Plan {
    fn default() -> Self {
        Plan {
            detail: CollisionDetail::Full,
            every: 1,
            collisions: true,
            compression: Compression::Zstd,
            chunk_size: 1 << 20,
            batch_size: 5,
            background: false,
            scene: false,
            position: WriterPosition::default(),
            t_end: 2.0,
            flush_each: false,
            start_snapshot: true,
            final_thermo: true,
        }
    }
}

/// One thing written, in writing order.
#[derive(Debug, Clone)]
enum Item {
    Collision(CollisionRecord),
    Snapshot(Snapshot),
    Thermo(Thermo),
    Checkpoint(Box<LogCheckpoint>),
    /// A `/scene` frame at this time.
    Scene(f64),
}

impl Item {
    fn time(&self) -> f64 {
        match self {
            Item::Collision(c) => c.time,
            Item::Snapshot(s) => s.time,
            Item::Thermo(t) => t.time,
            Item::Checkpoint(c) => c.engine.now,
            Item::Scene(t) => *t,
        }
    }
}

/// A raw message as the writer must have stored it.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Raw {
    channel: usize,
    sequence: u32,
    log_time: u64,
    publish_time: u64,
}

/// What a test log holds, from the writing side.
struct Written {
    path: PathBuf,
    meta: RunMetadata,
    items: Vec<Item>,
    /// Index in `raw` of the message holding each item.
    item_msg: Vec<usize>,
    /// The `/collisions` batches, as the documented batching gives them.
    batches: Vec<Vec<CollisionRecord>>,
    /// Every carom message (scene included), in file order.
    raw: Vec<Raw>,
    /// Number of messages written before each flush (cumulative), in order.
    flushed_after: Vec<usize>,
    summary: SummaryMetadata,
    summary_map: BTreeMap<String, String>,
    pair: u64,
    wall: u64,
    file_bytes: u64,
    options: WriterOptions,
}

impl Drop for Written {
    fn drop(&mut self) {
        let _ = std::fs::remove_file(&self.path);
    }
}

impl Written {
    fn messages(&self, ch: usize) -> u64 {
        self.raw.iter().filter(|r| r.channel == ch).count() as u64
    }
    fn logged(&self) -> Vec<CollisionRecord> {
        self.items
            .iter()
            .filter_map(|i| match i {
                Item::Collision(c) => Some(*c),
                _ => None,
            })
            .collect()
    }
    fn of(&self, ch: usize) -> Vec<Item> {
        self.items
            .iter()
            .filter(|i| {
                matches!(
                    (i, ch),
                    (Item::Snapshot(_), CH_SNAPSHOT)
                        | (Item::Thermo(_), CH_THERMO)
                        | (Item::Checkpoint(_), CH_CHECKPOINT)
                )
            })
            .cloned()
            .collect()
    }
    fn bytes(&self) -> Vec<u8> {
        std::fs::read(&self.path).unwrap()
    }
}

/// The writer side of the test: the engine, the writer and the model of what the
/// file must hold.
struct Recorder {
    w: LogWriter,
    plan: Plan,
    items: Vec<Item>,
    item_msg: Vec<usize>,
    batches: Vec<Vec<CollisionRecord>>,
    pending: Vec<CollisionRecord>,
    pending_seq: Option<u32>,
    raw: Vec<Raw>,
    next_seq: [u32; 4],
    logged: u64,
    ordinal: u64,
    flushed_after: Vec<usize>,
}

impl Recorder {
    /// Close the batch being gathered (the writer does before any message, when
    /// full, and at the end).
    fn close_batch(&mut self) {
        if self.pending.is_empty() {
            return;
        }
        let b = std::mem::take(&mut self.pending);
        let at = self.raw.len();
        for m in self.item_msg.iter_mut().rev().take(b.len()) {
            *m = at;
        }
        self.raw.push(Raw {
            channel: CH_COLLISIONS,
            sequence: self.pending_seq.take().unwrap(),
            log_time: ns(b[0].time),
            publish_time: ns(b[b.len() - 1].time),
        });
        self.batches.push(b);
    }

    fn collision(&mut self, r: impl FnOnce(u64) -> CollisionRecord) {
        let ordinal = self.ordinal;
        self.ordinal += 1;
        if !self.plan.collisions || !ordinal.is_multiple_of(self.plan.every) {
            return;
        }
        let rec = r(ordinal);
        if self.pending.is_empty() {
            self.pending_seq = Some(self.next_seq[CH_COLLISIONS]);
            self.next_seq[CH_COLLISIONS] += 1;
        }
        self.pending.push(rec);
        self.items.push(Item::Collision(rec));
        self.item_msg.push(usize::MAX);
        self.logged += 1;
        if self.pending.len() == self.plan.batch_size {
            self.close_batch();
        }
    }

    fn message(&mut self, ch: usize, t: f64, item: Item) {
        self.close_batch();
        let sequence = self.next_seq[ch];
        self.next_seq[ch] += 1;
        self.item_msg.push(self.raw.len());
        self.raw.push(Raw {
            channel: ch,
            sequence,
            log_time: ns(t),
            publish_time: ns(t),
        });
        self.items.push(item);
    }

    fn after_message(&mut self) {
        if self.plan.flush_each {
            self.w.flush().unwrap();
            self.flushed_after.push(self.raw.len());
        }
    }

    fn snapshot(&mut self, e: &Engine) {
        let s = e.state();
        // The documented snapshot of a state, field by field.
        let expected = Snapshot {
            time: s.time,
            box_size: s.sim_box.size,
            boundary: s.sim_box.boundary.map(|b| match b {
                Boundary::Periodic => 0,
                Boundary::Walls { .. } => 1,
            }),
            species_radius: s.species.iter().map(|sp| sp.radius).collect(),
            species_mass: s.species.iter().map(|sp| sp.mass).collect(),
            species: s.species_of.clone(),
            positions: s.positions.clone(),
            velocities: s.velocities.clone(),
        };
        self.w.write_snapshot(&s).unwrap();
        self.message(CH_SNAPSHOT, s.time, Item::Snapshot(expected));
        self.after_message();
    }

    fn thermo(&mut self, e: &Engine, pair: u64, wall: u64) {
        let t = e.now();
        let th = Thermo {
            time: t,
            kinetic_energy: e.kinetic_energy(),
            temperature: e.kinetic_energy() / 59.0,
            collisions: pair + wall,
            pair_collisions: pair,
            wall_collisions: wall,
            energy_lost: 0.0,
            virial_sum: pair as f64 / 3.0,
            wall_impulse: wall as f64 / 7.0,
            pressure: (t > 0.0).then_some(1.0 / 3.0 + t),
            z: (t > 0.0).then_some(1.25),
            collision_rate: (t > 0.0).then_some(pair as f64 / t),
        };
        self.w.write_thermo(&th).unwrap();
        self.message(CH_THERMO, t, Item::Thermo(th));
        self.after_message();
    }

    fn checkpoint(&mut self, e: &Engine) {
        let cp = e.checkpoint();
        self.close_batch();
        let mut next_sequence = self.next_seq;
        next_sequence[CH_CHECKPOINT] += 1;
        let expected = LogCheckpoint {
            driver: DriverState {
                run_start_time: 0.0,
                logged_collisions: self.logged,
                next_sequence,
            },
            engine: cp.clone(),
        };
        self.w.write_checkpoint(cp, 0.0).unwrap();
        let t = expected.engine.now;
        self.message(CH_CHECKPOINT, t, Item::Checkpoint(Box::new(expected)));
        // A checkpoint always flushes.
        self.flushed_after.push(self.raw.len());
    }

    fn scene(&mut self, frame: u64, e: &Engine) {
        let s = e.state();
        self.w.write_scene(frame, &s).unwrap();
        self.close_batch();
        self.item_msg.push(self.raw.len());
        self.raw.push(Raw {
            channel: CH_SCENE,
            sequence: frame as u32,
            log_time: ns(s.time),
            publish_time: ns(s.time),
        });
        self.items.push(Item::Scene(s.time));
        self.after_message();
    }
}

const TAG_SNAPSHOT: u64 = 1;
const TAG_THERMO: u64 = 2;
const TAG_SCENE: u64 = 3;
/// Snapshots every third of a time unit and thermo every seventh: times whose
/// nanoseconds are not exact, so that a time read from the MCAP header differs
/// from the message's own.
const SNAPSHOT_EVERY: f64 = 1.0 / 3.0;
const THERMO_EVERY: f64 = 2.0 / 7.0;
const SCENE_EVERY: f64 = 0.5;

/// Run 30 discs of two species (walls on x, periodic on y) and log them as
/// `plan` says: a checkpoint (and snapshot) at the start, snapshots, thermo and
/// scene frames on schedule (from `SCENE_EVERY` on), an extra thermo right after the first logged
/// collision (so that one batch holds exactly one collision), a thermo and a
/// checkpoint at the end, and the summary.
fn write_log(name: &str, plan: Plan) -> Written {
    let path = tmp(name);
    let species = vec![Species::new(20, 0.5, 1.0), Species::new(10, 0.7, 2.5)];
    let state = SystemSpec::square_box(
        species,
        0.3,
        [Boundary::Walls { restitution: 1.0 }, Boundary::Periodic],
        11,
    )
    .build()
    .unwrap();
    let params = EngineParams::default();
    let log = LogOptions {
        collisions: plan.collisions,
        collision_every: plan.every,
        collision_detail: plan.detail,
        snapshot_interval: Some(SNAPSHOT_EVERY),
        thermo_interval: Some(THERMO_EVERY),
        checkpoint_interval: None,
        scene_interval: plan.scene.then_some(SCENE_EVERY),
        compression: plan.compression,
        flush_seconds: 3600.0,
    };
    let facts = RunFacts::new(&state.species, &state.sim_box, &params, &log);
    let meta = RunMetadata {
        log_format: LOG_FORMAT_VERSION.into(),
        carom_version: "0.0.0-test".into(),
        config: "{\"test\": true}".into(),
        seed: 11,
        start_time: "2026-11-26T00:00:00.000Z".into(),
        n_discs: 30,
        stop: Stop::Time(plan.t_end),
        max_time_without_collision: Some(4.5),
        log: log.clone(),
        resumed_from: None,
        resumed_at: None,
        run_facts: Some(facts),
    };
    let mut options = WriterOptions::from_log_options(&log);
    options.collision_detail = plan.detail;
    options.chunk_size = plan.chunk_size;
    options.batch_size = plan.batch_size;
    options.background = plan.background;
    let mut engine = Engine::new(state, params).unwrap();
    let w = LogWriter::create(&path, options.clone(), &meta.to_map(), plan.position).unwrap();
    let mut rec = Recorder {
        w,
        plan: plan.clone(),
        items: Vec::new(),
        item_msg: Vec::new(),
        batches: Vec::new(),
        pending: Vec::new(),
        pending_seq: None,
        raw: Vec::new(),
        next_seq: plan.position.next_sequence,
        logged: plan.position.logged_collisions,
        ordinal: plan.position.next_ordinal,
        flushed_after: Vec::new(),
    };
    rec.checkpoint(&engine);
    if plan.start_snapshot {
        rec.snapshot(&engine);
    }
    rec.thermo(&engine, 0, 0);
    let mut k = [1u64; 4];
    engine.schedule(SNAPSHOT_EVERY, TAG_SNAPSHOT).unwrap();
    engine.schedule(THERMO_EVERY, TAG_THERMO).unwrap();
    if plan.scene {
        engine.schedule(SCENE_EVERY, TAG_SCENE).unwrap();
    }
    let (mut pair, mut wall) = (0u64, 0u64);
    let mut extra_thermo = true;
    loop {
        let ev = engine.next_event().unwrap().unwrap();
        if ev.time() > plan.t_end {
            break;
        }
        match ev {
            Event::Pair(c) => {
                pair += 1;
                rec.w.observe_pair(&c).unwrap();
                rec.collision(|o| CollisionRecord::from_pair(&c, o));
            }
            Event::Wall(c) => {
                wall += 1;
                rec.w.observe_wall(&c).unwrap();
                rec.collision(|o| CollisionRecord::from_wall(&c, o));
            }
            Event::Scheduled { time, tag } => {
                let kk = &mut k[tag as usize];
                *kk += 1;
                let kk = *kk as f64;
                match tag {
                    TAG_SNAPSHOT => {
                        engine.schedule(kk * SNAPSHOT_EVERY, tag).unwrap();
                        rec.snapshot(&engine);
                    }
                    TAG_THERMO => {
                        engine.schedule(kk * THERMO_EVERY, tag).unwrap();
                        rec.thermo(&engine, pair, wall);
                    }
                    _ => {
                        engine.schedule(kk * SCENE_EVERY, tag).unwrap();
                        rec.scene(kk as u64 - 1, &engine);
                    }
                }
                let _ = time;
            }
        }
        if extra_thermo && rec.pending.len() == 1 {
            extra_thermo = false;
            rec.thermo(&engine, pair, wall);
        }
    }
    if plan.final_thermo {
        rec.thermo(&engine, pair, wall);
    }
    rec.checkpoint(&engine);
    let summary = SummaryMetadata {
        end_time: "2026-11-26T00:00:01.000Z".into(),
        stop_reason: StopReason::Time,
        error: None,
        sim_time: engine.now(),
        pair_collisions: pair,
        wall_collisions: wall,
        logged_collisions: rec.logged,
        kinetic_energy: engine.kinetic_energy(),
        energy_lost: 0.0,
        virial_sum: 0.125,
        wall_seconds: 0.5,
        collisions_per_second: 1234.5,
    };
    let summary_map = summary.to_map();
    let stats = rec.w.stats();
    assert_eq!(stats.logged_collisions, rec.logged);
    assert_eq!(stats.next_ordinal, rec.ordinal);
    for (ch, topic) in TOPICS.iter().enumerate() {
        let sent = rec.raw.iter().filter(|r| r.channel == ch).count() as u64;
        assert_eq!(stats.messages[ch], sent, "{topic}");
    }
    let file_bytes = rec.w.finish(&summary_map).unwrap();
    assert_eq!(file_bytes, std::fs::metadata(&path).unwrap().len());
    rec.close_batch();
    Written {
        path,
        meta,
        items: rec.items,
        item_msg: rec.item_msg,
        batches: rec.batches,
        raw: rec.raw,
        flushed_after: rec.flushed_after,
        summary,
        summary_map,
        pair,
        wall,
        file_bytes,
        options,
    }
}

/// A collision read back equals the one written: exactly, but for what the record
/// does not store (a full record's pair impulse reads as zero) or derives (a
/// compact record's pair normal and virial, to rounding).
fn check_collision(got: &CollisionRecord, want: &CollisionRecord, compact: bool, at: usize) {
    let (g, w) = (&got.collision, &want.collision);
    let same = |a: f64, b: f64| a.to_bits() == b.to_bits();
    let same2 = |a: DVec2, b: DVec2| same(a.x, b.x) && same(a.y, b.y);
    assert_eq!(got.ordinal, want.ordinal, "ordinal #{at}");
    assert_eq!(got.kind, want.kind, "kind #{at}");
    assert!(same(g.time, w.time), "time #{at}");
    assert_eq!((g.i, g.j), (w.i, w.j), "discs #{at}");
    assert!(same2(g.vi_before, w.vi_before), "vi_before #{at}");
    assert!(same2(g.vj_before, w.vj_before), "vj_before #{at}");
    assert!(same2(g.vi_after, w.vi_after), "vi_after #{at}");
    assert!(same2(g.vj_after, w.vj_after), "vj_after #{at}");
    assert!(same(g.energy_lost, w.energy_lost), "energy_lost #{at}");
    if compact && want.kind == KIND_PAIR {
        assert!((g.normal - w.normal).length() < 1e-12, "normal #{at}");
        assert!(
            (g.virial - w.virial).abs() <= 1e-12 * w.virial.abs().max(1.0),
            "virial #{at}: {} {}",
            g.virial,
            w.virial
        );
        assert!(same2(g.impulse, w.impulse), "impulse #{at}");
    } else {
        assert!(same2(g.normal, w.normal), "normal #{at}");
        assert!(same(g.virial, w.virial), "virial #{at}");
        if want.kind == KIND_PAIR {
            assert_eq!(
                g.impulse,
                DVec2::ZERO,
                "a full record stores no pair impulse"
            );
        } else {
            // Derived from the normal and |Δp| (the sign of a zero is not kept).
            assert_eq!(g.impulse, w.impulse, "impulse #{at}");
        }
    }
}

fn check_message(got: &LogMessage, want: &Item, compact: bool) {
    match (got, want) {
        (LogMessage::Snapshot(g), Item::Snapshot(w)) => assert_eq!(g, w),
        (LogMessage::Thermo(g), Item::Thermo(w)) => assert_eq!(g, w),
        (LogMessage::Checkpoint(g), Item::Checkpoint(w)) => assert_eq!(g, w),
        (LogMessage::Collisions(b), Item::Collision(_)) => {
            let _ = (b, compact);
            panic!("a batch where a single collision was expected")
        }
        (g, w) => panic!("read {g:?}, wrote {w:?}"),
    }
}

/// `events()` of `r` give the written items (but scene frames) in order; returns
/// how many were read.
fn check_events<R: Read + Seek>(r: &mut LogReader<R>, w: &Written, compact: bool) -> usize {
    let want: Vec<&Item> = w
        .items
        .iter()
        .filter(|i| !matches!(i, Item::Scene(_)))
        .collect();
    let mut n = 0;
    for e in r.events() {
        let e = e.unwrap();
        assert!(n < want.len(), "more events than written");
        let t = e.time();
        assert_eq!(t.to_bits(), want[n].time().to_bits(), "event #{n}'s time");
        match (&e, want[n]) {
            (LogEvent::Collision(g), Item::Collision(c)) => check_collision(g, c, compact, n),
            (LogEvent::Snapshot(g), Item::Snapshot(s)) => assert_eq!(g, s, "#{n}"),
            (LogEvent::Thermo(g), Item::Thermo(s)) => assert_eq!(g, s, "#{n}"),
            (LogEvent::Checkpoint(g), Item::Checkpoint(s)) => assert_eq!(g, s, "#{n}"),
            (g, s) => panic!("event #{n}: read {g:?}, wrote {s:?}"),
        }
        n += 1;
    }
    n
}

fn open(path: &Path) -> LogReader {
    LogReader::open(path).unwrap()
}

fn reader(bytes: Vec<u8>, strict: bool) -> Result<LogReader<Cursor<Vec<u8>>>, ReadError> {
    LogReader::new(
        Cursor::new(bytes),
        "in-memory".into(),
        ReadOptions {
            strict,
            record_length_limit: None,
        },
    )
}

/// The records of an MCAP file: (opcode, start, total length) from the magic on,
/// up to and including the footer (or the last whole record of a cut file).
fn records(bytes: &[u8]) -> Vec<(u8, usize, usize)> {
    let mut out = Vec::new();
    let mut p = 8;
    while p + 9 <= bytes.len() {
        let op = bytes[p];
        let len = u64::from_le_bytes(bytes[p + 1..p + 9].try_into().unwrap()) as usize;
        if p + 9 + len > bytes.len() {
            break;
        }
        out.push((op, p, 9 + len));
        if op == 0x02 {
            break;
        }
        p += 9 + len;
    }
    out
}

const OP_CHUNK: u8 = 0x06;
const OP_METADATA: u8 = 0x0C;
const OP_DATA_END: u8 = 0x0F;
const OP_CHUNK_INDEX: u8 = 0x08;
const OP_METADATA_INDEX: u8 = 0x0D;

fn chunks(bytes: &[u8]) -> Vec<(usize, usize)> {
    records(bytes)
        .into_iter()
        .filter(|r| r.0 == OP_CHUNK)
        .map(|r| (r.1, r.2))
        .collect()
}

// ---------------------------------------------------------------------------
// Round trips
// ---------------------------------------------------------------------------

/// Everything of a full-record log reads back: each iterator, raw messages with
/// their sequences and times, the metadata, the counts.
#[test]
fn a_full_record_log_reads_back_exactly_what_was_written() {
    let w = write_log("full", Plan::default());
    let logged = w.logged();
    assert!(
        w.pair > 20 && w.wall > 5,
        "{} pair, {} wall",
        w.pair,
        w.wall
    );
    assert!(w.batches.iter().any(|b| b.len() == 1));
    assert!(w.batches.iter().any(|b| b.len() == w.options.batch_size));
    assert_eq!(logged.len() as u64, w.pair + w.wall);

    // Raw messages: channel, sequence, times, in file order; the reader's counters.
    let mut r = open(&w.path);
    assert_eq!(r.label(), w.path.display().to_string());
    assert!(format!("{r:?}").contains(&w.path.display().to_string()));
    assert_eq!(r.run(), &w.meta);
    assert_eq!(r.run_map(), &w.meta.to_map());
    assert_eq!(r.end(), &LogEnd::Reading);
    assert_eq!(r.summary().unwrap(), None);
    let mut k = 0;
    while let Some(m) = r.next_raw().unwrap() {
        let got = Raw {
            channel: m.channel,
            sequence: m.sequence,
            log_time: m.log_time,
            publish_time: m.publish_time,
        };
        assert_eq!(got, w.raw[k], "raw message #{k}");
        k += 1;
        assert_eq!(r.messages_read(), k as u64);
    }
    assert_eq!(k, w.raw.len());
    assert_eq!(r.end(), &LogEnd::Complete);
    assert_eq!(r.end().warning(), None);
    assert_eq!(r.summary().unwrap(), Some(w.summary.clone()));
    assert_eq!(r.channels_seen(), [true, true, true, true, false]);
    assert!(!r.compact_collisions());
    // At the end, nothing more (and no error).
    assert!(r.next_raw().unwrap().is_none());
    assert!(r.next_message().unwrap().is_none());

    // Every collision, one at a time.
    let mut r = open(&w.path);
    let mut n = 0;
    for c in r.collisions() {
        let c = c.unwrap();
        assert!(n < logged.len(), "more collisions than written");
        check_collision(&c, &logged[n], false, n);
        n += 1;
    }
    assert_eq!(n, logged.len());
    assert_eq!(r.messages_read(), w.raw.len() as u64);

    // Each other channel on its own.
    for (ch, it) in [(CH_SNAPSHOT, 0), (CH_THERMO, 1), (CH_CHECKPOINT, 2)] {
        let want = w.of(ch);
        assert!(want.len() >= 2, "{}", TOPICS[ch]);
        let mut r = open(&w.path);
        let iter = match it {
            0 => r.snapshots(),
            1 => r.thermo(),
            _ => r.checkpoints(),
        };
        let mut n = 0;
        for m in iter {
            let m = m.unwrap();
            assert!(n < want.len(), "{}: more than written", TOPICS[ch]);
            check_message(&m, &want[n], false);
            n += 1;
        }
        assert_eq!(n, want.len(), "{}", TOPICS[ch]);
    }

    // All events in time order.
    let mut r = open(&w.path);
    assert_eq!(check_events(&mut r, &w, false), w.items.len());

    // Whole messages: the batches as batched.
    let mut r = open(&w.path);
    let (mut b, mut others) = (0, 0);
    let others_want: Vec<Item> = w
        .items
        .iter()
        .filter(|i| !matches!(i, Item::Collision(_)))
        .cloned()
        .collect();
    while let Some(m) = r.next_message().unwrap() {
        match m {
            LogMessage::Collisions(batch) => {
                assert!(b < w.batches.len());
                let want = &w.batches[b];
                assert_eq!(batch.len(), want.len(), "batch #{b}");
                for (e, c) in want.iter().enumerate() {
                    check_collision(&batch.get(e), c, false, e);
                }
                b += 1;
            }
            m => {
                check_message(&m, &others_want[others], false);
                others += 1;
            }
        }
    }
    assert_eq!((b, others), (w.batches.len(), others_want.len()));
}

/// A compact log replays into the full records: velocities bit for bit, the
/// rest derived; scene frames are skipped by the decoding iterators and kept by
/// the raw ones.
#[test]
fn a_compact_log_with_scene_frames_replays_every_collision() {
    let w = write_log(
        "compact",
        Plan {
            detail: CollisionDetail::Compact,
            scene: true,
            compression: Compression::Lz4,
            batch_size: 9,
            ..Plan::default()
        },
    );
    let logged = w.logged();
    assert!(w.messages(CH_SCENE) >= 3);

    let mut r = open(&w.path);
    let mut n = 0;
    for c in r.collisions() {
        let c = c.unwrap();
        assert!(n < logged.len(), "more collisions than written");
        check_collision(&c, &logged[n], true, n);
        n += 1;
    }
    assert_eq!(n, logged.len());
    assert!(r.compact_collisions());
    assert_eq!(r.channels_seen(), [true; N_CHANNELS]);

    let mut r = open(&w.path);
    let scenes = w.messages(CH_SCENE) as usize;
    assert_eq!(check_events(&mut r, &w, true), w.items.len() - scenes);

    // Raw: the scene frames too, numbered by frame.
    let mut r = open(&w.path);
    let mut k = 0;
    while let Some(m) = r.next_raw().unwrap() {
        let got = Raw {
            channel: m.channel,
            sequence: m.sequence,
            log_time: m.log_time,
            publish_time: m.publish_time,
        };
        assert_eq!(got, w.raw[k], "raw message #{k}");
        k += 1;
    }
    assert_eq!(k, w.raw.len());

    // Whole messages skip the scene.
    let mut r = open(&w.path);
    let (mut b, mut others) = (0, 0);
    let others_want: Vec<Item> = w
        .items
        .iter()
        .filter(|i| !matches!(i, Item::Collision(_) | Item::Scene(_)))
        .cloned()
        .collect();
    while let Some(m) = r.next_message().unwrap() {
        match m {
            LogMessage::Collisions(batch) => {
                let want = &w.batches[b];
                assert_eq!(batch.len(), want.len(), "batch #{b}");
                for (e, c) in want.iter().enumerate() {
                    check_collision(&batch.get(e), c, true, e);
                }
                b += 1;
            }
            m => {
                check_message(&m, &others_want[others], true);
                others += 1;
            }
        }
    }
    assert_eq!((b, others), (w.batches.len(), others_want.len()));

    // The snapshots alone, in a compact log with scene frames.
    let want = w.of(CH_SNAPSHOT);
    let mut r = open(&w.path);
    let got: Vec<LogMessage> = r.snapshots().map(Result::unwrap).collect();
    assert_eq!(got.len(), want.len());
    for (g, s) in got.iter().zip(&want) {
        check_message(g, s, true);
    }
}

/// A compact log whose first velocities come from its start checkpoint only (no
/// snapshot before the first collisions) replays from the checkpoint.
#[test]
fn a_compact_log_replays_from_a_checkpoint_without_a_snapshot() {
    let w = write_log(
        "compact-cp",
        Plan {
            detail: CollisionDetail::Compact,
            start_snapshot: false,
            compression: Compression::None,
            t_end: 0.3,
            ..Plan::default()
        },
    );
    let logged = w.logged();
    assert!(!logged.is_empty());
    assert_eq!(w.messages(CH_SNAPSHOT), 0);
    let mut r = open(&w.path);
    let mut n = 0;
    for c in r.collisions() {
        let c = c.unwrap();
        assert!(n < logged.len());
        check_collision(&c, &logged[n], true, n);
        n += 1;
    }
    assert_eq!(n, logged.len());
}

/// Every k-th collision: full records (compact needs every collision, whatever
/// the options ask), ordinals multiples of k, on a writer thread; the writer's
/// position carries over (ordinals, logged count, sequence numbers).
#[test]
fn every_kth_collision_from_a_resumed_position_on_a_writer_thread() {
    let position = WriterPosition {
        next_ordinal: 300,
        logged_collisions: 100,
        next_sequence: [5, 6, 7, 8],
    };
    let w = write_log(
        "every3",
        Plan {
            detail: CollisionDetail::Compact,
            every: 3,
            background: true,
            position,
            batch_size: 4,
            ..Plan::default()
        },
    );
    let logged = w.logged();
    assert!(logged.len() > 5);
    assert!(logged
        .iter()
        .all(|c| c.ordinal % 3 == 0 && c.ordinal >= 300));
    assert_eq!(logged[0].ordinal, 300);
    let mut r = open(&w.path);
    let mut k = 0;
    while let Some(m) = r.next_raw().unwrap() {
        assert_eq!(m.sequence, w.raw[k].sequence, "#{k}");
        assert_eq!(m.channel, w.raw[k].channel, "#{k}");
        k += 1;
    }
    let mut r = open(&w.path);
    assert_eq!(check_events(&mut r, &w, false), w.items.len());
    assert!(!r.compact_collisions());
    let (cp, _, _) = last_checkpoint(&w.path).unwrap();
    assert_eq!(cp.driver.logged_collisions, 100 + logged.len() as u64);
    assert_eq!(w.summary.logged_collisions, 100 + logged.len() as u64);
}

/// Without collisions: no `/collisions` message, the four channels still
/// defined, ordinals still counted.
#[test]
fn a_log_without_collisions_still_defines_its_channels() {
    let w = write_log(
        "nocoll",
        Plan {
            collisions: false,
            ..Plan::default()
        },
    );
    assert!(w.logged().is_empty());
    let mut r = open(&w.path);
    assert_eq!(r.collisions().count(), 0);
    assert_eq!(r.channels_seen(), [true, true, true, true, false]);
    let info = scan(&w.path).unwrap();
    assert_eq!(info.messages[CH_COLLISIONS], 0);
    assert_eq!(info.logged_collisions, 0);
    assert_eq!(info.time_span[CH_COLLISIONS], None);
    assert_eq!(info.channels, [true, true, true, true, false]);
}

// ---------------------------------------------------------------------------
// Summaries: scan, scan_indexed, last_checkpoint
// ---------------------------------------------------------------------------

fn check_info(w: &Written, info: &carom_io::LogInfo, scene: bool) {
    assert_eq!(info.run, w.meta);
    assert_eq!(info.summary.as_ref(), Some(&w.summary));
    assert_eq!(info.end, LogEnd::Complete);
    assert_eq!(info.channels, [true, true, true, true, scene]);
    for (ch, topic) in TOPICS.iter().enumerate() {
        assert_eq!(info.messages[ch], w.messages(ch), "{topic}");
    }
    assert_eq!(info.logged_collisions, w.logged().len() as u64);
    assert_eq!(info.file_bytes, w.file_bytes);
    // Time spans from the messages themselves (exact), scene from its log times.
    let span = |f: &dyn Fn(&Item) -> bool| {
        let t: Vec<f64> = w.items.iter().filter(|i| f(i)).map(Item::time).collect();
        (!t.is_empty()).then(|| (t[0], t[t.len() - 1]))
    };
    let exact = |a: Option<(f64, f64)>, b: Option<(f64, f64)>| {
        a.map(|(x, y)| (x.to_bits(), y.to_bits())) == b.map(|(x, y)| (x.to_bits(), y.to_bits()))
    };
    assert!(exact(
        info.time_span[CH_COLLISIONS],
        span(&|i| matches!(i, Item::Collision(_)))
    ));
    assert!(exact(
        info.time_span[CH_SNAPSHOT],
        span(&|i| matches!(i, Item::Snapshot(_)))
    ));
    assert!(exact(
        info.time_span[CH_THERMO],
        span(&|i| matches!(i, Item::Thermo(_)))
    ));
    assert!(exact(
        info.time_span[CH_CHECKPOINT],
        span(&|i| matches!(i, Item::Checkpoint(_)))
    ));
    match span(&|i| matches!(i, Item::Scene(_))) {
        Some((a, b)) => {
            let (x, y) = info.time_span[CH_SCENE].unwrap();
            assert!((x - a).abs() < 1e-9 && (y - b).abs() < 1e-9, "{x} {y}");
        }
        None => assert_eq!(info.time_span[CH_SCENE], None),
    }
    let last_cp = w.of(CH_CHECKPOINT).last().unwrap().time();
    assert_eq!(info.last_checkpoint_time, Some(last_cp));
    let thermo = w.of(CH_THERMO);
    let counts = |i: &Item| match i {
        Item::Thermo(t) => (t.time, t.pair_collisions, t.wall_collisions),
        _ => unreachable!(),
    };
    assert_eq!(
        info.thermo_counts,
        Some([counts(&thermo[0]), counts(thermo.last().unwrap())])
    );
    if let Some(Item::Thermo(t)) = w.items.iter().rev().nth(1) {
        // The final thermo: the run's counts.
        let [_, (_, p, wl)] = info.thermo_counts.unwrap();
        assert_eq!((p, wl), (w.pair, w.wall));
        assert_eq!((t.pair_collisions, t.wall_collisions), (p, wl));
    }
}

/// `scan` and `scan_indexed` agree with each other and with what was written,
/// over several chunks; each channel's span is that of its own messages (the
/// last snapshot at 5/3 and the first scene frame at 1/2, whose nanoseconds
/// are and are not exact, the run ending after its last thermo record).
#[test]
fn scan_and_the_index_agree_with_what_was_written() {
    for scene in [false, true] {
        let w = write_log(
            "scan",
            Plan {
                detail: CollisionDetail::Compact,
                scene,
                t_end: 1.9,
                final_thermo: scene,
                chunk_size: 8 << 10,
                compression: Compression::None,
                ..Plan::default()
            },
        );
        assert!(chunks(&w.bytes()).len() > 2);
        let info = scan(&w.path).unwrap();
        check_info(&w, &info, scene);
        let indexed = scan_indexed(&w.path).unwrap().expect("an index");
        check_info(&w, &indexed, scene);
        assert_eq!(info, indexed);
    }
}

/// `scan_observed` reports progress that only grows, ending at the file's size.
#[test]
fn scan_reports_progress_up_to_the_whole_file() {
    let w = write_log(
        "progress",
        Plan {
            compression: Compression::None,
            ..Plan::default()
        },
    );
    let mut seen: Vec<ReadProgress> = Vec::new();
    scan_observed(&w.path, &mut |p| seen.push(p)).unwrap();
    assert!(seen.len() >= 2, "{seen:?}");
    assert!(seen.windows(2).all(|p| p[0].bytes_read <= p[1].bytes_read));
    assert!(seen.iter().all(|p| p.file_bytes == w.file_bytes));
    assert!(seen[0].bytes_read > 0 && seen[0].bytes_read < w.file_bytes);
    assert_eq!(seen.last().unwrap().bytes_read, w.file_bytes);
    assert_eq!(seen.last().unwrap().fraction(), 1.0);

    // The reader's own progress: some of the file after opening, all at the end.
    let mut r = open(&w.path);
    let p = r.progress();
    assert!(p.bytes_read > 0 && p.bytes_read < w.file_bytes, "{p:?}");
    let mut shown = 0;
    assert_eq!(r.progress_since(&mut shown), Some(p));
    assert_eq!(shown, p.bytes_read);
    assert_eq!(r.progress_since(&mut shown), None);
    while r.next_raw().unwrap().is_some() {}
    assert_eq!(r.progress().bytes_read, w.file_bytes);
    assert_eq!(
        r.progress_since(&mut shown).map(|p| p.bytes_read),
        Some(w.file_bytes)
    );
}

#[test]
fn the_fraction_read_is_bytes_over_size_at_most_one() {
    let f = |bytes_read, file_bytes| {
        ReadProgress {
            bytes_read,
            file_bytes,
        }
        .fraction()
    };
    assert_eq!(f(0, 0), 1.0);
    assert_eq!(f(1, 4), 0.25);
    assert_eq!(f(3, 4), 0.75);
    assert_eq!(f(0, 4), 0.0);
    assert_eq!(f(5, 4), 1.0);
}

/// The last checkpoint and the number of messages up to it.
#[test]
fn the_last_checkpoint_is_the_one_written_last() {
    let w = write_log(
        "lastcp",
        Plan {
            scene: true,
            ..Plan::default()
        },
    );
    let (cp, prefix, run) = last_checkpoint(&w.path).unwrap();
    match w.of(CH_CHECKPOINT).last().unwrap() {
        Item::Checkpoint(want) => assert_eq!(&cp, want.as_ref()),
        _ => unreachable!(),
    }
    let at = w
        .raw
        .iter()
        .rposition(|r| r.channel == CH_CHECKPOINT)
        .unwrap();
    assert_eq!(prefix, at as u64 + 1);
    assert_eq!(run, w.meta);
}

// ---------------------------------------------------------------------------
// Cut and damaged files
// ---------------------------------------------------------------------------

/// A log flushed after every message group, several chunks.
fn chunked(name: &str, compression: Compression) -> Written {
    write_log(
        name,
        Plan {
            compression,
            flush_each: true,
            t_end: 1.0,
            ..Plan::default()
        },
    )
}

/// Messages in the chunks before chunk `k` (0-based): each flush closes one.
fn messages_before_chunk(w: &Written, k: usize) -> usize {
    if k == 0 {
        0
    } else {
        w.flushed_after[k - 1]
    }
}

/// A file cut short reads up to its last complete chunk: quietly
/// (`LogEnd::Truncated`) by default, as an error in strict mode.
#[test]
fn a_cut_file_reads_to_its_last_whole_chunk_or_fails_in_strict_mode() {
    let w = chunked("cut", Compression::Zstd);
    let bytes = w.bytes();
    let ch = chunks(&bytes);
    assert_eq!(ch.len(), w.flushed_after.len());
    for k in [1, 3] {
        // Cut in the middle of chunk k.
        let (start, len) = ch[k];
        let cut = bytes[..start + len / 2].to_vec();
        let before = messages_before_chunk(&w, k);
        // Lenient: everything before, then the end.
        let mut r = reader(cut.clone(), false).unwrap();
        let mut n = 0;
        while let Some(m) = r.next_raw().unwrap() {
            assert_eq!(m.sequence, w.raw[n].sequence);
            assert_eq!(m.channel, w.raw[n].channel);
            n += 1;
        }
        assert_eq!(n, before, "cut in chunk {k}");
        let LogEnd::Truncated { detail } = r.end().clone() else {
            panic!("{:?}", r.end())
        };
        let warning = r.end().warning().unwrap();
        assert!(warning.contains("truncated") && warning.contains(&detail));
        // The same through the decoding iterators: every event of those messages.
        let mut r = reader(cut.clone(), false).unwrap();
        let want = w
            .items
            .iter()
            .zip(&w.item_msg)
            .filter(|(i, &m)| m < before && !matches!(i, Item::Scene(_)))
            .count();
        let mut got = 0;
        for e in r.events() {
            e.unwrap();
            got += 1;
        }
        assert_eq!(got, want, "events before the cut in chunk {k}");
        // Strict: the same messages, then an error saying how many.
        let mut r = reader(cut.clone(), true).unwrap();
        let mut n = 0;
        let e = loop {
            match r.next_raw() {
                Ok(Some(_)) => n += 1,
                Ok(None) => panic!("a strict reader read to the end of a cut file"),
                Err(e) => break e,
            }
        };
        assert_eq!(n, before);
        assert!(
            matches!(e, ReadError::Truncated { messages, .. } if messages == before as u64),
            "{e:?}"
        );
        assert_eq!(r.end(), &LogEnd::Failed);
        // Nothing more after the end or the error.
        assert!(r.next_raw().unwrap().is_none());
    }
}

/// A cut before any chunk: no channel at all. Asking for one says it is missing
/// and why; all events are simply none.
#[test]
fn a_file_cut_before_its_channels_says_which_channel_is_missing() {
    let w = chunked("cut0", Compression::None);
    let bytes = w.bytes();
    let first = chunks(&bytes)[0].0;
    let cut = bytes[..first + 20].to_vec();
    let mut r = reader(cut.clone(), false).unwrap();
    assert_eq!(r.run(), &w.meta);
    assert_eq!(r.events().count(), 0);
    assert!(matches!(r.end(), LogEnd::Truncated { .. }));
    assert_eq!(r.channels_seen(), [false; N_CHANNELS]);
    for (name, topic) in [
        ("collisions", "/collisions"),
        ("snapshots", "/snapshot"),
        ("thermo", "/thermo"),
        ("checkpoints", "/checkpoint"),
    ] {
        let mut r = reader(cut.clone(), false).unwrap();
        let mut items: Vec<Result<(), ReadError>> = match name {
            "collisions" => r.collisions().map(|e| e.map(|_| ())).collect(),
            "snapshots" => r.snapshots().map(|e| e.map(|_| ())).collect(),
            "thermo" => r.thermo().map(|e| e.map(|_| ())).collect(),
            _ => r.checkpoints().map(|e| e.map(|_| ())).collect(),
        };
        assert_eq!(items.len(), 1, "{name}");
        match items.pop().unwrap() {
            Err(ReadError::MissingChannel { topic: t, hint, .. }) => {
                assert_eq!(t, topic);
                assert!(hint.contains("truncated"), "{hint}");
            }
            e => panic!("{name}: {e:?}"),
        }
    }
}

/// A file with only some channels (written by another program): asking for a
/// channel it lacks is an error naming it, with no hint of truncation.
#[test]
fn a_missing_channel_in_a_whole_file_is_named() {
    let meta = write_log(
        "meta",
        Plan {
            t_end: 0.1,
            ..Plan::default()
        },
    )
    .meta
    .to_map();
    // Only /snapshot.
    let bytes = foreign(&meta, &[("/snapshot", SNAP_SCHEMA, "ros2msg", "cdr")]);
    let mut r = reader(bytes.clone(), false).unwrap();
    let got: Vec<_> = r.collisions().collect();
    assert_eq!(got.len(), 1);
    match &got[0] {
        Err(ReadError::MissingChannel { topic, hint, .. }) => {
            assert_eq!(*topic, "/collisions");
            assert_eq!(hint, "");
        }
        e => panic!("{e:?}"),
    }
    let mut r = reader(bytes.clone(), false).unwrap();
    assert_eq!(r.snapshots().count(), 0);
    let mut r = reader(bytes.clone(), false).unwrap();
    assert_eq!(r.events().count(), 0);
    // Only /collisions.
    let bytes = foreign(
        &meta,
        &[(
            "/collisions",
            "carom_msgs/msg/CollisionBatch",
            "ros2msg",
            "cdr",
        )],
    );
    let mut r = reader(bytes.clone(), false).unwrap();
    let got: Vec<_> = r.snapshots().collect();
    assert_eq!(got.len(), 1);
    assert!(
        matches!(
            &got[0],
            Err(ReadError::MissingChannel {
                topic: "/snapshot",
                ..
            })
        ),
        "{got:?}"
    );
    let mut r = reader(bytes.clone(), false).unwrap();
    assert_eq!(r.collisions().count(), 0);
    let mut r = reader(bytes, false).unwrap();
    assert_eq!(r.events().count(), 0);
}

/// Damage inside a finished file is a `Corrupt` error after everything before
/// it, strict or not; `last_checkpoint` still finds the checkpoint before it.
#[test]
fn damage_in_a_finished_file_is_an_error_after_everything_before_it() {
    for compression in [Compression::None, Compression::Zstd] {
        let w = chunked("damage", compression);
        let bytes = w.bytes();
        let ch = chunks(&bytes);
        let k = ch.len() - 2;
        let before = messages_before_chunk(&w, k);
        let (start, len) = ch[k];
        let mut bad = bytes.clone();
        bad[start + len - 3] ^= 0x5a;
        for strict in [false, true] {
            let mut r = reader(bad.clone(), strict).unwrap();
            let mut n = 0;
            let e = loop {
                match r.next_raw() {
                    Ok(Some(m)) => {
                        assert_eq!(m.sequence, w.raw[n].sequence);
                        n += 1
                    }
                    Ok(None) => panic!("damage read to the end ({compression:?})"),
                    Err(e) => break e,
                }
            };
            assert_eq!(n, before);
            assert!(
                matches!(e, ReadError::Corrupt { messages, .. } if messages == before as u64),
                "{e:?}"
            );
            assert_eq!(r.end(), &LogEnd::Failed);
            assert_eq!(r.end().warning(), None);
        }
        // The events before the damage are what was written.
        let mut r = reader(bad.clone(), false).unwrap();
        let mut n = 0;
        let mut failed = false;
        for e in r.events() {
            match e {
                Ok(_) => n += 1,
                Err(e) => {
                    assert!(matches!(e, ReadError::Corrupt { .. }), "{e:?}");
                    failed = true;
                }
            }
        }
        assert!(failed);
        assert!(n > 0);
        // The last checkpoint before the damage.
        let path = tmp("damaged");
        std::fs::write(&path, &bad).unwrap();
        let (cp, prefix, _) = last_checkpoint(&path).unwrap();
        let at = w.raw[..before]
            .iter()
            .rposition(|r| r.channel == CH_CHECKPOINT)
            .unwrap();
        assert_eq!(prefix, at as u64 + 1);
        let cps = w.of(CH_CHECKPOINT);
        let nth = w.raw[..=at]
            .iter()
            .filter(|r| r.channel == CH_CHECKPOINT)
            .count();
        match &cps[nth - 1] {
            Item::Checkpoint(want) => assert_eq!(&cp, want.as_ref()),
            _ => unreachable!(),
        }
        // Damage in the first chunk, before any checkpoint: the damage is the error.
        let mut bad0 = bytes.clone();
        bad0[ch[0].0 + ch[0].1 - 3] ^= 0x5a;
        std::fs::write(&path, &bad0).unwrap();
        let e = last_checkpoint(&path).unwrap_err();
        assert!(matches!(e, ReadError::Corrupt { .. }), "{e:?}");
        std::fs::remove_file(&path).unwrap();
    }
}

/// Damage in the summary section (the index at the end, which repeats what the
/// data section said) is found after every message, and said to be there.
#[test]
fn damage_in_the_summary_section_comes_after_every_message() {
    let w = write_log(
        "summary-damage",
        Plan {
            t_end: 0.5,
            ..Plan::default()
        },
    );
    let mut bytes = w.bytes();
    let recs = records(&bytes);
    let footer = *recs.last().unwrap();
    // Summary CRC 0 (= not computed): the damage is found by parsing the record.
    let crc_at = footer.1 + 9 + 16;
    bytes[crc_at..crc_at + 4].copy_from_slice(&[0; 4]);
    // The statistics record's per-channel counts claim more bytes than it has.
    let stats = recs.iter().find(|r| r.0 == 0x0B).unwrap();
    let map_len_at = stats.1 + 9 + 42;
    bytes[map_len_at..map_len_at + 4].copy_from_slice(&u32::MAX.to_le_bytes());
    let mut r = reader(bytes, false).unwrap();
    let mut n = 0;
    let e = loop {
        match r.next_raw() {
            Ok(Some(_)) => n += 1,
            Ok(None) => panic!("damaged summary read to the end"),
            Err(e) => break e,
        }
    };
    assert_eq!(n, w.raw.len());
    match e {
        ReadError::Corrupt {
            messages, detail, ..
        } => {
            assert_eq!(messages, w.raw.len() as u64);
            assert!(detail.starts_with("malformed summary record"), "{detail}");
        }
        e => panic!("{e:?}"),
    }
    // The summary metadata record came before the damage.
    assert_eq!(r.summary().unwrap(), Some(w.summary.clone()));
}

/// Reading hands every byte it takes to the MCAP reader; an I/O error is an error,
/// an interrupted read is retried.
#[test]
fn io_errors_end_reading_and_interrupted_reads_are_retried() {
    let w = write_log(
        "io",
        Plan {
            compression: Compression::None,
            t_end: 0.5,
            ..Plan::default()
        },
    );
    let bytes = w.bytes();
    for kind in [std::io::ErrorKind::Interrupted, std::io::ErrorKind::Other] {
        let fail = std::rc::Rc::new(std::cell::Cell::new(None));
        let src = Flaky {
            inner: Cursor::new(bytes.clone()),
            fail: fail.clone(),
        };
        let mut r = LogReader::new(src, "flaky".into(), ReadOptions::default()).unwrap();
        fail.set(Some(kind));
        let mut n = 0;
        let mut err = None;
        loop {
            match r.next_raw() {
                Ok(Some(_)) => n += 1,
                Ok(None) => break,
                Err(e) => {
                    err = Some(e);
                    break;
                }
            }
        }
        if kind == std::io::ErrorKind::Interrupted {
            assert!(err.is_none(), "{err:?}");
            assert_eq!(n, w.raw.len());
            assert_eq!(r.end(), &LogEnd::Complete);
        } else {
            let e = err.expect("an I/O error ends reading");
            assert!(
                matches!(&e, ReadError::Corrupt { detail, .. } if detail.contains("I/O")),
                "{e:?}"
            );
            assert!(n < w.raw.len());
        }
    }
}

/// A source that fails its next read once, with the error kind set.
struct Flaky {
    inner: Cursor<Vec<u8>>,
    fail: std::rc::Rc<std::cell::Cell<Option<std::io::ErrorKind>>>,
}

impl Read for Flaky {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        if let Some(kind) = self.fail.take() {
            return Err(std::io::Error::new(kind, "injected"));
        }
        self.inner.read(buf)
    }
}

impl Seek for Flaky {
    fn seek(&mut self, to: SeekFrom) -> std::io::Result<u64> {
        self.inner.seek(to)
    }
}

/// A record or decompressed chunk longer than the limit is refused (an error in a
/// finished file), and one within it is read.
#[test]
fn records_longer_than_the_limit_are_refused() {
    let w = write_log(
        "limit",
        Plan {
            compression: Compression::Zstd,
            t_end: 0.5,
            ..Plan::default()
        },
    );
    let bytes = w.bytes();
    let longest = records(&bytes).iter().map(|r| r.2).max().unwrap();
    let read = |limit| {
        let mut r = LogReader::new(
            Cursor::new(bytes.clone()),
            "limit".into(),
            ReadOptions {
                strict: false,
                record_length_limit: Some(limit),
            },
        )?;
        let mut n = 0;
        while r.next_raw()?.is_some() {
            n += 1;
        }
        Ok::<_, ReadError>(n)
    };
    assert_eq!(read(1 << 24).unwrap(), w.raw.len());
    // The chunk (decompressed: at least its compressed length) is longer than 600
    // bytes; the run metadata record is shorter than the longest record.
    assert!(longest > 2000);
    let e = read(longest / 2).unwrap_err();
    assert!(
        matches!(e, ReadError::Corrupt { .. } | ReadError::NotCarom { .. }),
        "{e:?}"
    );
}

// ---------------------------------------------------------------------------
// Files carom would not write
// ---------------------------------------------------------------------------

const SNAP_SCHEMA: &str = "carom_msgs/msg/Snapshot";

/// An MCAP file with `meta` as its `carom.run` record and the channels
/// (topic, schema name, schema encoding, message encoding), without messages.
fn foreign(meta: &BTreeMap<String, String>, channels: &[(&str, &str, &str, &str)]) -> Vec<u8> {
    foreign_bytes(meta, channels)
}

fn foreign_bytes(
    meta: &BTreeMap<String, String>,
    channels: &[(&str, &str, &str, &str)],
) -> Vec<u8> {
    let mut buf = Cursor::new(Vec::new());
    {
        let mut w = mcap::WriteOptions::new().create(&mut buf).unwrap();
        w.write_metadata(&mcap::records::Metadata {
            name: METADATA_RUN.into(),
            metadata: meta.clone(),
        })
        .unwrap();
        for (topic, schema, enc, msg) in channels {
            let sid = w.add_schema(schema, enc, b"").unwrap();
            w.add_channel(sid, topic, msg, &BTreeMap::new()).unwrap();
        }
        w.finish().unwrap();
    }
    buf.into_inner()
}

/// A carom topic with another schema, schema encoding or message encoding is
/// refused, each on its own.
#[test]
fn a_carom_topic_with_another_schema_or_encoding_is_refused() {
    let meta = write_log(
        "meta2",
        Plan {
            t_end: 0.1,
            ..Plan::default()
        },
    )
    .meta
    .to_map();
    let good = ("/snapshot", SNAP_SCHEMA, "ros2msg", "cdr");
    let mut r = reader(foreign_bytes(&meta, &[good]), false).unwrap();
    assert!(r.next_raw().unwrap().is_none());
    assert_eq!(r.channels_seen(), [false, true, false, false, false]);
    for bad in [
        ("/snapshot", "other/Snapshot", "ros2msg", "cdr"),
        ("/snapshot", SNAP_SCHEMA, "jsonschema", "cdr"),
        ("/snapshot", SNAP_SCHEMA, "ros2msg", "json"),
    ] {
        let mut r = reader(foreign_bytes(&meta, &[bad]), false).unwrap();
        let e = r.next_raw().unwrap_err();
        assert!(
            matches!(
                e,
                ReadError::WrongSchema {
                    topic: "/snapshot",
                    ..
                }
            ),
            "{bad:?}: {e:?}"
        );
        assert_eq!(r.end(), &LogEnd::Failed);
    }
}

/// The first record must be the `carom.run` metadata.
#[test]
fn a_file_without_carom_run_metadata_first_is_not_a_carom_log() {
    let meta = write_log(
        "meta3",
        Plan {
            t_end: 0.1,
            ..Plan::default()
        },
    )
    .meta
    .to_map();
    let mut buf = Cursor::new(Vec::new());
    {
        let mut w = mcap::WriteOptions::new().create(&mut buf).unwrap();
        w.write_metadata(&mcap::records::Metadata {
            name: "other.run".into(),
            metadata: meta.clone(),
        })
        .unwrap();
        w.finish().unwrap();
    }
    let e = reader(buf.into_inner(), false).unwrap_err();
    assert!(matches!(e, ReadError::NotCarom { .. }), "{e:?}");
    let e = reader(b"not an mcap file at all".to_vec(), false).unwrap_err();
    assert!(matches!(e, ReadError::NotCarom { .. }), "{e:?}");
    // An MCAP file that ends before any record.
    let e = reader(mcap::MAGIC.to_vec(), false).unwrap_err();
    assert!(matches!(e, ReadError::NotCarom { .. }), "{e:?}");
}

/// Only the metadata record named `carom.summary` is the summary, wherever
/// another one comes.
#[test]
fn only_the_carom_summary_record_is_the_summary() {
    let path = tmp("summary-last");
    let w = write_log(
        "meta4",
        Plan {
            t_end: 0.1,
            ..Plan::default()
        },
    );
    let mut writer = LogWriter::create(
        &path,
        WriterOptions {
            background: false,
            ..WriterOptions::default()
        },
        &w.meta.to_map(),
        WriterPosition::default(),
    )
    .unwrap();
    writer
        .write_metadata(METADATA_SUMMARY, &w.summary_map)
        .unwrap();
    let mut other = BTreeMap::new();
    other.insert("note".to_string(), "after the summary".to_string());
    writer.write_metadata("notes", &other).unwrap();
    let size = writer.close().unwrap();
    assert_eq!(size, std::fs::metadata(&path).unwrap().len());
    let mut r = open(&path);
    while r.next_raw().unwrap().is_some() {}
    assert_eq!(r.summary().unwrap(), Some(w.summary.clone()));
    std::fs::remove_file(&path).unwrap();
}

/// The index of a damaged summary section is not used: `scan_indexed` says
/// `None` (for the full scan to find the damage) rather than fail or panic.
#[test]
fn a_damaged_index_is_left_to_the_full_scan() {
    let w = write_log(
        "index",
        Plan {
            chunk_size: 16 << 10,
            ..Plan::default()
        },
    );
    let bytes = w.bytes();
    let recs = records(&bytes);
    // The footer's summary CRC set to 0 (= not computed), so the summary reader
    // takes the edited section.
    let footer = recs.last().unwrap();
    assert_eq!(footer.0, 0x02);
    let crc_at = footer.1 + 9 + 16;
    let path = tmp("index-damaged");
    let edit = |f: &dyn Fn(&mut Vec<u8>)| {
        let mut b = bytes.clone();
        b[crc_at..crc_at + 4].copy_from_slice(&[0; 4]);
        f(&mut b);
        std::fs::write(&path, &b).unwrap();
        scan_indexed(&path)
    };
    // Unedited (but for the CRC): the index is used.
    assert!(edit(&|_| {}).unwrap().is_some());
    // The index of the carom.summary record (name after offset and length).
    let mi = recs
        .iter()
        .find(|r| {
            r.0 == OP_METADATA_INDEX
                && bytes[r.1 + 9 + 20..r.1 + r.2].starts_with(METADATA_SUMMARY.as_bytes())
        })
        .unwrap();
    let ci = recs.iter().find(|r| r.0 == OP_CHUNK_INDEX).unwrap();
    let put = |b: &mut Vec<u8>, at: usize, v: u64| b[at..at + 8].copy_from_slice(&v.to_le_bytes());
    // The summary metadata's length too short to hold a record.
    let len_at = mi.1 + 9 + 8;
    for short in [0, 5, 8] {
        assert_eq!(edit(&|b| put(b, len_at, short)).unwrap(), None, "{short}");
    }
    // Its offset beyond the end of the file.
    let off_at = mi.1 + 9;
    assert_eq!(
        edit(&|b| put(b, off_at, bytes.len() as u64 + 10)).unwrap(),
        None
    );
    // A chunk that starts beyond the end of the file.
    let cstart_at = ci.1 + 9 + 16;
    assert_eq!(
        edit(&|b| put(b, cstart_at, bytes.len() as u64 + 10)).unwrap(),
        None
    );
    // A cut file has no index.
    std::fs::write(&path, &bytes[..bytes.len() - 100]).unwrap();
    assert_eq!(scan_indexed(&path).unwrap(), None);
    std::fs::remove_file(&path).unwrap();
    assert!(recs.iter().any(|r| r.0 == OP_DATA_END));
    assert!(recs.iter().any(|r| r.0 == OP_METADATA));
}

// ---------------------------------------------------------------------------
// The writer
// ---------------------------------------------------------------------------

fn small_meta() -> BTreeMap<String, String> {
    RunMetadata {
        log_format: LOG_FORMAT_VERSION.into(),
        carom_version: "0.0.0-test".into(),
        config: "{}".into(),
        seed: 1,
        start_time: "2026-11-26T00:00:00.000Z".into(),
        n_discs: 2,
        stop: Stop::Collisions(10),
        max_time_without_collision: None,
        log: LogOptions::default(),
        resumed_from: None,
        resumed_at: None,
        run_facts: None,
    }
    .to_map()
}

fn thermo_at(t: f64) -> Thermo {
    Thermo {
        time: t,
        kinetic_energy: 1.5,
        temperature: 0.75,
        collisions: 3,
        pair_collisions: 2,
        wall_collisions: 1,
        energy_lost: 0.0,
        virial_sum: 0.5,
        wall_impulse: 0.25,
        pressure: None,
        z: None,
        collision_rate: None,
    }
}

/// The thermo records a copy of the file taken now holds (none if it cannot be
/// read at all).
fn thermo_on_disk(path: &Path) -> usize {
    let bytes = std::fs::read(path).unwrap();
    let Ok(mut r) = reader(bytes, false) else {
        return 0;
    };
    r.thermo().filter(Result::is_ok).count()
}

fn inline(flush_every: Duration) -> WriterOptions {
    WriterOptions {
        background: false,
        flush_every,
        ..WriterOptions::default()
    }
}

/// A killed run loses at most what came after the last flush: an explicit flush
/// puts everything so far on disk, and nothing is flushed before `flush_every`.
#[test]
fn a_crash_loses_at_most_what_came_after_the_last_flush() {
    let path = tmp("flush");
    let hour = Duration::from_secs(3600);
    let mut w = LogWriter::create(&path, inline(hour), &small_meta(), Default::default()).unwrap();
    assert_eq!(w.path(), path.as_path());
    w.write_thermo(&thermo_at(0.5)).unwrap();
    w.maybe_flush().unwrap();
    assert_eq!(thermo_on_disk(&path), 0, "flushed before flush_every");
    w.flush().unwrap();
    assert_eq!(thermo_on_disk(&path), 1);
    w.write_thermo(&thermo_at(1.5)).unwrap();
    w.write_thermo(&thermo_at(2.5)).unwrap();
    w.maybe_flush().unwrap();
    assert_eq!(thermo_on_disk(&path), 1, "flushed before flush_every");
    w.flush().unwrap();
    assert_eq!(thermo_on_disk(&path), 3);
    drop(w);
    std::fs::remove_file(&path).unwrap();
}

/// With `flush_every` = 0 every message is on disk at once; otherwise, inline,
/// `maybe_flush` flushes once the time has passed, and a writer thread by itself.
#[test]
fn flushes_follow_flush_every() {
    let path = tmp("flush0");
    let mut w = LogWriter::create(
        &path,
        inline(Duration::ZERO),
        &small_meta(),
        Default::default(),
    )
    .unwrap();
    w.write_thermo(&thermo_at(0.5)).unwrap();
    assert_eq!(thermo_on_disk(&path), 1);
    drop(w);

    let step = Duration::from_millis(150);
    let mut w = LogWriter::create(&path, inline(step), &small_meta(), Default::default()).unwrap();
    w.write_thermo(&thermo_at(0.5)).unwrap();
    std::thread::sleep(step + Duration::from_millis(50));
    w.maybe_flush().unwrap();
    assert_eq!(thermo_on_disk(&path), 1);
    drop(w);

    let mut w = LogWriter::create(
        &path,
        WriterOptions {
            background: true,
            flush_every: Duration::from_millis(50),
            ..WriterOptions::default()
        },
        &small_meta(),
        Default::default(),
    )
    .unwrap();
    w.write_thermo(&thermo_at(0.5)).unwrap();
    let mut on_disk = 0;
    for _ in 0..100 {
        std::thread::sleep(Duration::from_millis(20));
        on_disk = thermo_on_disk(&path);
        if on_disk == 1 {
            break;
        }
    }
    assert_eq!(on_disk, 1, "the writer thread flushes by itself");
    drop(w);
    std::fs::remove_file(&path).unwrap();
}

/// Dropping a writer without finishing still ends the file properly, without a
/// summary; on a writer thread too, by the time the drop returns (here with
/// messages still queued for the thread when the writer is dropped).
#[test]
fn a_dropped_writer_leaves_a_finished_file() {
    // 256 KiB of text that compresses, but not to nothing.
    let mut x = 1u64;
    let big: Vec<u8> = (0..256 << 10)
        .map(|_| {
            x = x
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            b"0123456789abcdef"[(x >> 60) as usize]
        })
        .collect();
    for background in [false, true] {
        let path = tmp("drop");
        let mut w = LogWriter::create(
            &path,
            WriterOptions {
                background,
                ..WriterOptions::default()
            },
            &small_meta(),
            Default::default(),
        )
        .unwrap();
        for k in 0..12 {
            w.copy_message(CH_THERMO, k, 1000 * k as u64, 1000 * k as u64, &big)
                .unwrap();
        }
        drop(w);
        // The file as it is the moment the drop returns.
        let bytes = std::fs::read(&path).unwrap();
        let mut r = reader(bytes, false).unwrap();
        let mut n = 0;
        while let Some(m) = r.next_raw().unwrap() {
            assert_eq!((m.sequence, m.data.len()), (n, big.len()));
            n += 1;
        }
        assert_eq!(n, 12);
        assert_eq!(r.end(), &LogEnd::Complete);
        assert_eq!(r.summary().unwrap(), None);
        std::fs::remove_file(&path).unwrap();
    }
}

/// Options in force, stats, the debug form, and what `finish` returns.
#[test]
fn the_writer_reports_its_options_and_what_it_sent() {
    for background in [false, true] {
        let path = tmp("stats");
        let opts = WriterOptions {
            collision_every: 0,
            batch_size: 0,
            background,
            ..WriterOptions::default()
        };
        let position = WriterPosition {
            next_ordinal: 7,
            logged_collisions: 3,
            next_sequence: [1, 2, 3, 4],
        };
        let mut w = LogWriter::create(&path, opts.clone(), &small_meta(), position).unwrap();
        assert_eq!(
            w.options(),
            &WriterOptions {
                collision_every: 1,
                batch_size: 1,
                ..opts
            }
        );
        assert!(format!("{w:?}").contains("LogWriter"));
        let s = w.stats();
        assert_eq!((s.next_ordinal, s.logged_collisions), (7, 3));
        assert_eq!(s.messages, [0; N_CHANNELS]);
        let th = thermo_at(0.25);
        w.write_thermo(&th).unwrap();
        w.write_thermo(&th).unwrap();
        let s = w.stats();
        assert_eq!(s.messages, [0, 0, 2, 0, 0]);
        assert_eq!(
            s.largest_message,
            serde_json::to_vec(&th).unwrap().len() as u64
        );
        // A copied message: same channel, sequence, times and bytes.
        let data = serde_json::to_vec(&thermo_at(0.75)).unwrap();
        w.copy_message(CH_THERMO, 41, 750_000_000, 750_000_001, &data)
            .unwrap();
        assert_eq!(w.stats().messages, [0, 0, 3, 0, 0]);
        let size = w.close().unwrap();
        assert_eq!(size, std::fs::metadata(&path).unwrap().len());
        let mut r = open(&path);
        let mut seen = Vec::new();
        while let Some(m) = r.next_raw().unwrap() {
            seen.push((
                m.channel,
                m.sequence,
                m.log_time,
                m.publish_time,
                m.data.to_vec(),
            ));
        }
        assert_eq!(seen.len(), 3);
        assert_eq!(
            (seen[0].0, seen[0].1, seen[0].2),
            (CH_THERMO, 3, 250_000_000)
        );
        assert_eq!(seen[1].1, 4);
        assert_eq!(seen[2], (CH_THERMO, 41, 750_000_000, 750_000_001, data));
        // Once closed, writing fails.
        let e = w.write_thermo(&th).unwrap_err();
        assert!(matches!(e, WriteError::Finished(_)), "{e:?}");
        assert!(matches!(w.close(), Err(WriteError::Finished(_))));
        std::fs::remove_file(&path).unwrap();
    }
}

/// A write error is the operating system's error (a full disk says so).
#[test]
fn a_full_disk_is_reported_as_such() {
    let full = Path::new("/dev/full");
    if !full.exists() {
        return;
    }
    for background in [false, true] {
        let e = LogWriter::create(
            full,
            WriterOptions {
                background,
                ..WriterOptions::default()
            },
            &small_meta(),
            Default::default(),
        )
        .unwrap_err();
        assert!(
            matches!(&e, WriteError::Io { source, .. } if source.kind() == std::io::ErrorKind::StorageFull),
            "{e:?}"
        );
    }
}

/// The documented defaults and the mapping of the user's log options.
#[test]
fn writer_options_follow_the_log_options() {
    let d = WriterOptions::default();
    assert_eq!(d.compression, Compression::Zstd);
    assert_eq!(
        d.compression_level, -1,
        "docs/performance.md: zstd level −1"
    );
    assert_eq!(d.chunk_size, 1 << 20, "docs/log-format.md: 1 MiB chunks");
    assert_eq!(d.batch_size, 4096, "docs/log-format.md: batches of 4096");
    assert_eq!(d.flush_every, Duration::from_secs(1));
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    assert_eq!(d.background, cores > 1);
    let o = |f: &dyn Fn(&mut LogOptions)| {
        let mut l = LogOptions::default();
        f(&mut l);
        WriterOptions::from_log_options(&l)
    };
    let w = o(&|l| {
        l.collisions = false;
        l.collision_every = 0;
        l.compression = Compression::Lz4;
        l.flush_seconds = 2.5;
    });
    assert!(!w.collisions);
    assert_eq!(w.collision_every, 1);
    assert_eq!(w.compression, Compression::Lz4);
    assert_eq!(w.compression_level, 0);
    assert_eq!(w.flush_every, Duration::from_secs_f64(2.5));
    let w = o(&|l| {
        l.collision_every = 4;
        l.compression = Compression::None;
        l.flush_seconds = -1.0;
    });
    assert_eq!(w.collision_every, 4);
    assert_eq!(w.collision_detail, CollisionDetail::Full);
    assert_eq!(w.compression_level, 0);
    assert_eq!(w.flush_every, Duration::ZERO);
    for never in [f64::INFINITY, f64::NAN] {
        assert_eq!(
            o(&|l| l.flush_seconds = never).flush_every,
            Duration::from_secs(1_000_000_000)
        );
    }
    assert!(WriterOptions::needs_normals(Restitution::CentreOfMass(0.5)));
    assert!(!WriterOptions::needs_normals(Restitution::CentreOfMass(
        1.0
    )));
    assert!(!WriterOptions::needs_normals(Restitution::Elastic));
    assert!(!WriterOptions::needs_normals(Restitution::Normal(0.5)));
}

#[test]
fn the_log_end_warns_only_when_cut() {
    let t = LogEnd::Truncated {
        detail: "cut here".into(),
    };
    let w = t.warning().unwrap();
    assert!(w.contains("truncated") && w.contains("cut here"), "{w}");
    for e in [LogEnd::Reading, LogEnd::Complete, LogEnd::Failed] {
        assert_eq!(e.warning(), None);
    }
    let _ = (KIND_WALL, NO_DISC);
}
