//! Shared helpers of the carom-log log tests (`log_*.rs`): small logs written with
//! [`LogWriter`] from a real engine run of a few dozen discs, with a model of what
//! the file must hold (the engine's events and states, the test's own count of
//! batches and sequence numbers), and readers of raw MCAP records. (Found missing
//! by mutation testing, docs/testing.md: the reader and writer were exercised only
//! by the root package's whole-engine tests.)
#![allow(dead_code, unused_imports)]

pub use carom_core::{Boundary, DVec2, Restitution, Species};
pub use carom_engine::{Engine, EngineParams, Event, SystemSpec};
pub use carom_log::{
    last_checkpoint, scan, scan_indexed, scan_observed, CollisionDetail, CollisionRecord,
    Compression, DriverState, LogCheckpoint, LogEnd, LogEvent, LogMessage, LogOptions, LogReader,
    LogWriter, ReadError, ReadOptions, ReadProgress, RunFacts, RunMetadata, Snapshot, Stop,
    StopReason, SummaryMetadata, Thermo, WriteError, WriterOptions, WriterPosition, CH_CHECKPOINT,
    CH_COLLISIONS, CH_SCENE, CH_SNAPSHOT, CH_THERMO, KIND_PAIR, KIND_WALL, LOG_FORMAT_VERSION,
    METADATA_RUN, METADATA_SUMMARY, NO_DISC, N_CHANNELS, TOPICS,
};
pub use std::collections::BTreeMap;
pub use std::io::{Cursor, Read, Seek, SeekFrom};
pub use std::path::{Path, PathBuf};
pub use std::sync::atomic::{AtomicU64, Ordering};
pub use std::time::Duration;

/// A fresh path in the temporary directory (removed by [`Written`]'s drop).
pub fn tmp(name: &str) -> PathBuf {
    static N: AtomicU64 = AtomicU64::new(0);
    let k = N.fetch_add(1, Ordering::Relaxed);
    std::env::temp_dir().join(format!(
        "carom-log-log-rw-{}-{k}-{name}.mcap",
        std::process::id()
    ))
}

/// The documented log time of simulated time `t`: round(t · 10⁹) ns.
pub fn ns(t: f64) -> u64 {
    (t * 1e9).round() as u64
}

/// How a test log is written.
#[derive(Clone)]
pub struct Plan {
    pub detail: CollisionDetail,
    pub every: u64,
    pub collisions: bool,
    pub compression: Compression,
    pub chunk_size: u64,
    pub batch_size: usize,
    pub background: bool,
    pub scene: bool,
    pub position: WriterPosition,
    pub t_end: f64,
    /// Flush after every message (each message group ends its chunk).
    pub flush_each: bool,
    /// Write the start snapshot (a compact log needs velocities before its first
    /// collision: from a snapshot or a checkpoint).
    pub start_snapshot: bool,
    /// Write a thermo record at the end (just before the final checkpoint, at
    /// the same time).
    pub final_thermo: bool,
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
pub enum Item {
    Collision(CollisionRecord),
    Snapshot(Snapshot),
    Thermo(Thermo),
    Checkpoint(Box<LogCheckpoint>),
    /// A `/scene` frame at this time.
    Scene(f64),
}

impl Item {
    pub fn time(&self) -> f64 {
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
pub struct Raw {
    pub channel: usize,
    pub sequence: u32,
    pub log_time: u64,
    pub publish_time: u64,
}

impl Raw {
    /// The header fields of a message as read.
    pub fn of(m: &carom_log::RawMessage<'_>) -> Raw {
        Raw {
            channel: m.channel,
            sequence: m.sequence,
            log_time: m.log_time,
            publish_time: m.publish_time,
        }
    }
}

/// What a test log holds, from the writing side.
pub struct Written {
    pub path: PathBuf,
    pub meta: RunMetadata,
    pub items: Vec<Item>,
    /// Index in `raw` of the message holding each item.
    pub item_msg: Vec<usize>,
    /// The `/collisions` batches, as the documented batching gives them.
    pub batches: Vec<Vec<CollisionRecord>>,
    /// Every carom message (scene included), in file order.
    pub raw: Vec<Raw>,
    /// Number of messages written before each flush (cumulative), in order.
    pub flushed_after: Vec<usize>,
    pub summary: SummaryMetadata,
    pub summary_map: BTreeMap<String, String>,
    pub pair: u64,
    pub wall: u64,
    pub file_bytes: u64,
    pub options: WriterOptions,
}

impl Drop for Written {
    fn drop(&mut self) {
        let _ = std::fs::remove_file(&self.path);
    }
}

impl Written {
    pub fn messages(&self, ch: usize) -> u64 {
        self.raw.iter().filter(|r| r.channel == ch).count() as u64
    }
    pub fn logged(&self) -> Vec<CollisionRecord> {
        self.items
            .iter()
            .filter_map(|i| match i {
                Item::Collision(c) => Some(*c),
                _ => None,
            })
            .collect()
    }
    pub fn of(&self, ch: usize) -> Vec<Item> {
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
    pub fn bytes(&self) -> Vec<u8> {
        std::fs::read(&self.path).unwrap()
    }
}

/// The writer side of the test: the engine, the writer and the model of what the
/// file must hold.
pub struct Recorder {
    pub w: LogWriter,
    pub plan: Plan,
    pub items: Vec<Item>,
    pub item_msg: Vec<usize>,
    pub batches: Vec<Vec<CollisionRecord>>,
    pub pending: Vec<CollisionRecord>,
    pub pending_seq: Option<u32>,
    pub raw: Vec<Raw>,
    pub next_seq: [u32; 4],
    pub logged: u64,
    pub ordinal: u64,
    pub flushed_after: Vec<usize>,
}

impl Recorder {
    /// Close the batch being gathered (the writer does before any message, when
    /// full, and at the end).
    pub fn close_batch(&mut self) {
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

    pub fn collision(&mut self, r: impl FnOnce(u64) -> CollisionRecord) {
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

    pub fn message(&mut self, ch: usize, t: f64, item: Item) {
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

    pub fn after_message(&mut self) {
        if self.plan.flush_each {
            self.w.flush().unwrap();
            self.flushed_after.push(self.raw.len());
        }
    }

    pub fn snapshot(&mut self, e: &Engine) {
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
            images: s.images.clone(),
        };
        self.w.write_snapshot(&s).unwrap();
        self.message(CH_SNAPSHOT, s.time, Item::Snapshot(expected));
        self.after_message();
    }

    pub fn thermo(&mut self, e: &Engine, pair: u64, wall: u64) {
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
            ..Default::default()
        };
        self.w.write_thermo(&th).unwrap();
        self.message(CH_THERMO, t, Item::Thermo(th));
        self.after_message();
    }

    pub fn checkpoint(&mut self, e: &Engine) {
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

    pub fn scene(&mut self, frame: u64, e: &Engine) {
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

pub const TAG_SNAPSHOT: u64 = 1;
pub const TAG_THERMO: u64 = 2;
pub const TAG_SCENE: u64 = 3;
/// Snapshots every third of a time unit and thermo every seventh: times whose
/// nanoseconds are not exact, so that a time read from the MCAP header differs
/// from the message's own.
pub const SNAPSHOT_EVERY: f64 = 1.0 / 3.0;
pub const THERMO_EVERY: f64 = 2.0 / 7.0;
pub const SCENE_EVERY: f64 = 0.5;

/// Run 30 discs of two species (walls on x, periodic on y) and log them as
/// `plan` says: a checkpoint (and snapshot) at the start, snapshots, thermo and
/// scene frames on schedule (from `SCENE_EVERY` on), an extra thermo right after the first logged
/// collision (so that one batch holds exactly one collision), a thermo and a
/// checkpoint at the end, and the summary.
pub fn write_log(name: &str, plan: Plan) -> Written {
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
        snapshot_schedule: None,
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
            Event::Pause { .. } => {}
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
        potential_energy: None,
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
pub fn check_collision(got: &CollisionRecord, want: &CollisionRecord, compact: bool, at: usize) {
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

pub fn check_message(got: &LogMessage, want: &Item, compact: bool) {
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
pub fn check_events<R: Read + Seek>(r: &mut LogReader<R>, w: &Written, compact: bool) -> usize {
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

pub fn open(path: &Path) -> LogReader {
    LogReader::open(path).unwrap()
}

pub fn reader(bytes: Vec<u8>, strict: bool) -> Result<LogReader<Cursor<Vec<u8>>>, ReadError> {
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
pub fn records(bytes: &[u8]) -> Vec<(u8, usize, usize)> {
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

pub const OP_CHUNK: u8 = 0x06;
pub const OP_METADATA: u8 = 0x0C;
pub const OP_DATA_END: u8 = 0x0F;
pub const OP_CHUNK_INDEX: u8 = 0x08;
pub const OP_METADATA_INDEX: u8 = 0x0D;

pub fn chunks(bytes: &[u8]) -> Vec<(usize, usize)> {
    records(bytes)
        .into_iter()
        .filter(|r| r.0 == OP_CHUNK)
        .map(|r| (r.1, r.2))
        .collect()
}
