//! The messages of a carom log: topics, schema names, schema texts, and the Rust
//! form of each message with its encoder and decoder.
//!
//! | topic | schema | encoding | content |
//! |---|---|---|---|
//! | `/collisions` | `carom_msgs/msg/CollisionBatch` (`ros2msg`) | `cdr` | [`CollisionBatch`] |
//! | `/snapshot` | `carom_msgs/msg/Snapshot` (`ros2msg`) | `cdr` | [`Snapshot`] |
//! | `/thermo` | `carom.Thermo` (`jsonschema`) | `json` | [`Thermo`] |
//! | `/checkpoint` | `carom_msgs/msg/Checkpoint` (`ros2msg`) | `cdr` | [`crate::checkpoint_codec::LogCheckpoint`] |
//!
//! Message log times are simulated times in nanoseconds, taking one simulated time
//! unit as one second ([`log_time_ns`]). `docs/log-format.md` documents every field.

use crate::cdr::{CdrError, CdrReader, CdrWriter};
use carom_core::{Axis, DVec2, WallSide};
use carom_events::{PairCollision, State, WallCollision};
use serde::{Deserialize, Serialize};

/// Topic of the collision batches.
pub const TOPIC_COLLISIONS: &str = "/collisions";
/// Topic of the snapshots.
pub const TOPIC_SNAPSHOT: &str = "/snapshot";
/// Topic of the thermodynamic records.
pub const TOPIC_THERMO: &str = "/thermo";
/// Topic of the checkpoints.
pub const TOPIC_CHECKPOINT: &str = "/checkpoint";

/// Name of the metadata record written at the start of a run.
pub const METADATA_RUN: &str = "carom.run";
/// Name of the metadata record written at the end of a run.
pub const METADATA_SUMMARY: &str = "carom.summary";

/// Version of the log layout described here; stored in the `carom.run` metadata as
/// `log_format`. Readers reject files with a different major version.
///
/// 1.1: `/checkpoint` format 2 (each disc's pair candidate time; the engine's
/// internal clock and its epoch). The other channels are unchanged; a log 1.0
/// checkpoint cannot be resumed (its reader reports the format).
pub const LOG_FORMAT_VERSION: &str = "1.1";

/// Schema name of [`CollisionBatch`].
pub const SCHEMA_COLLISION_BATCH: &str = "carom_msgs/msg/CollisionBatch";
/// Schema name of [`Snapshot`].
pub const SCHEMA_SNAPSHOT: &str = "carom_msgs/msg/Snapshot";
/// Schema name of the checkpoint message.
pub const SCHEMA_CHECKPOINT: &str = "carom_msgs/msg/Checkpoint";
/// Schema name of [`Thermo`] (a JSON Schema).
pub const SCHEMA_THERMO: &str = "carom.Thermo";

/// `ros2msg` text of [`SCHEMA_COLLISION_BATCH`].
pub const COLLISION_BATCH_MSG: &str = "\
# A batch of consecutive logged collisions, in time order (struct of arrays).
# Every array below has one entry per collision in the batch.
# Units are the run's: length, time, mass; velocities in length/time.
uint64 first_ordinal   # 0-based ordinal, among all collisions of the run (pair + wall), of the first entry
uint64 stride          # ordinal of entry k = first_ordinal + k * stride (the log's collision_every)
float64[] time         # time of contact (time)
uint8[] kind           # 0 = pair collision of discs i and j; 1 = collision of disc i with a wall
uint32[] i             # first disc (0-based index)
uint32[] j             # second disc; 4294967295 for a wall collision
float64[] nx           # unit contact normal, x: from i towards j (pair) or towards the wall (wall)
float64[] ny           # unit contact normal, y
float64[] vix_before   # velocity of i before (length/time)
float64[] viy_before
float64[] vjx_before   # velocity of j before (0 for a wall collision)
float64[] vjy_before
float64[] vix_after    # velocity of i after
float64[] viy_after
float64[] vjx_after    # velocity of j after (0 for a wall collision)
float64[] vjy_after
float64[] energy_lost  # kinetic energy dissipated (energy; 0 when elastic)
float64[] virial       # pair: r_ij . dp_i with r_ij = r_i - r_j at contact (length*momentum); wall: |dp| given to the wall (momentum)
";

/// `ros2msg` text of [`SCHEMA_SNAPSHOT`].
pub const SNAPSHOT_MSG: &str = "\
# The exact state of every disc at one time (struct of arrays, one entry per disc).
float64 time              # simulated time of the state (time)
float64 box_x             # box edge lengths (length); the box is [0, box_x) x [0, box_y)
float64 box_y
uint8 boundary_x          # 0 = periodic, 1 = hard walls
uint8 boundary_y
float64[] species_radius  # per species: radius (length)
float64[] species_mass    # per species: mass (mass)
uint16[] species          # per disc: species index
float64[] x               # per disc: centre position (length), inside the box
float64[] y
float64[] vx              # per disc: velocity (length/time)
float64[] vy
";

/// JSON Schema of [`SCHEMA_THERMO`].
pub const THERMO_JSON_SCHEMA: &str = r#"{
  "$schema": "https://json-schema.org/draft/2020-12/schema",
  "title": "carom.Thermo",
  "description": "Thermodynamics of a carom run at one simulated time. Running quantities average over the run so far (from run_start_time).",
  "type": "object",
  "properties": {
    "time": {"type": "number", "description": "simulated time (time)"},
    "kinetic_energy": {"type": "number", "description": "K = sum m v^2 / 2 (energy)"},
    "temperature": {"type": "number", "description": "kT = 2K/f with f = 2N - (periodic axes) (energy)"},
    "collisions": {"type": "integer", "description": "pair + wall collisions since the start of the run"},
    "pair_collisions": {"type": "integer", "description": "pair collisions since the start of the run"},
    "wall_collisions": {"type": "integer", "description": "wall collisions since the start of the run"},
    "energy_lost": {"type": "number", "description": "kinetic energy dissipated since the start of the run (energy)"},
    "virial_sum": {"type": "number", "description": "sum over pair collisions of r_ij . dp_i since the start of the run (length*momentum)"},
    "wall_impulse": {"type": "number", "description": "momentum given to all walls since the start of the run (momentum)"},
    "pressure": {"type": "number", "description": "running pressure estimate P (energy/length^2) over the run so far (t = time - run start); periodic box: P A = N kT + W with W = virial_sum/(2 t); walls: wall impulse per unit time per unit accessible wall length, averaged over the walled axes; absent while t = 0 or kT = 0"},
    "z": {"type": "number", "description": "running compressibility factor beta P A / N (periodic: 1 + W/(N kT)); with walls A is the area reachable by disc centres, (L_x - 2a)(L_y - 2a) on walled axes with a the largest radius; absent like pressure"},
    "collision_rate": {"type": "number", "description": "pair collisions per disc per unit time over the run so far, 2 N_pair / (N t) (1/time); absent while t = 0"}
  },
  "required": ["time", "kinetic_energy", "temperature", "collisions", "pair_collisions", "wall_collisions", "energy_lost", "virial_sum", "wall_impulse"]
}"#;

/// Encoding of the JSON Schema `carom.Thermo`.
pub const SCHEMA_ENCODING_JSONSCHEMA: &str = "jsonschema";
/// Encoding of the `ros2msg` schemas.
pub const SCHEMA_ENCODING_ROS2MSG: &str = "ros2msg";
/// Message encoding of CDR channels.
pub const MESSAGE_ENCODING_CDR: &str = "cdr";
/// Message encoding of JSON channels.
pub const MESSAGE_ENCODING_JSON: &str = "json";

/// `kind` of a pair collision in [`CollisionBatch`].
pub const KIND_PAIR: u8 = 0;
/// `kind` of a wall collision in [`CollisionBatch`].
pub const KIND_WALL: u8 = 1;
/// `j` of a wall collision in [`CollisionBatch`].
pub const NO_DISC: u32 = u32::MAX;

/// MCAP log time of simulated time `t`: nanoseconds, one simulated time unit taken
/// as one second; negative times map to 0 and times beyond ~584 years saturate.
pub fn log_time_ns(t: f64) -> u64 {
    let ns = t * 1e9;
    if ns.is_nan() || ns <= 0.0 {
        0
    } else if ns >= u64::MAX as f64 {
        u64::MAX
    } else {
        ns.round() as u64
    }
}

/// One logged collision, as decoded from a [`CollisionBatch`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CollisionRecord {
    /// 0-based ordinal among all collisions (pair + wall) of the run.
    pub ordinal: u64,
    /// Time of contact (time).
    pub time: f64,
    /// [`KIND_PAIR`] or [`KIND_WALL`].
    pub kind: u8,
    /// First disc.
    pub i: u32,
    /// Second disc ([`NO_DISC`] for a wall collision).
    pub j: u32,
    /// Unit contact normal: from i towards j, or from i towards the wall.
    pub normal: DVec2,
    /// Velocity of i before (length/time).
    pub vi_before: DVec2,
    /// Velocity of j before (length/time; zero for a wall).
    pub vj_before: DVec2,
    /// Velocity of i after (length/time).
    pub vi_after: DVec2,
    /// Velocity of j after (length/time; zero for a wall).
    pub vj_after: DVec2,
    /// Kinetic energy dissipated (energy).
    pub energy_lost: f64,
    /// Pair: r_ij·Δp_i (length·momentum); wall: |Δp| given to the wall (momentum).
    pub virial: f64,
}

impl CollisionRecord {
    /// The record of pair collision `c` with run ordinal `ordinal`.
    #[inline]
    pub fn from_pair(c: &PairCollision, ordinal: u64) -> Self {
        CollisionRecord {
            ordinal,
            time: c.time,
            kind: KIND_PAIR,
            i: c.i,
            j: c.j,
            normal: c.normal,
            vi_before: c.vi_before,
            vj_before: c.vj_before,
            vi_after: c.vi_after,
            vj_after: c.vj_after,
            energy_lost: c.energy_lost,
            virial: c.virial,
        }
    }

    /// The record of wall collision `c` with run ordinal `ordinal`; the normal
    /// points from the disc to the wall, `j` is [`NO_DISC`], `virial` holds the
    /// impulse given to the wall.
    #[inline]
    pub fn from_wall(c: &WallCollision, ordinal: u64) -> Self {
        let sign = match c.side {
            WallSide::Low => -1.0,
            WallSide::High => 1.0,
        };
        let normal = match c.axis {
            Axis::X => DVec2::new(sign, 0.0),
            Axis::Y => DVec2::new(0.0, sign),
        };
        CollisionRecord {
            ordinal,
            time: c.time,
            kind: KIND_WALL,
            i: c.i,
            j: NO_DISC,
            normal,
            vi_before: c.v_before,
            vj_before: DVec2::ZERO,
            vi_after: c.v_after,
            vj_after: DVec2::ZERO,
            energy_lost: c.energy_lost,
            virial: c.impulse,
        }
    }

    /// True for a wall collision.
    pub fn is_wall(&self) -> bool {
        self.kind == KIND_WALL
    }

    /// The collision as the engine reported it (pair collisions only).
    pub fn as_pair(&self) -> Option<PairCollision> {
        (self.kind == KIND_PAIR).then_some(PairCollision {
            time: self.time,
            i: self.i,
            j: self.j,
            normal: self.normal,
            vi_before: self.vi_before,
            vj_before: self.vj_before,
            vi_after: self.vi_after,
            vj_after: self.vj_after,
            energy_lost: self.energy_lost,
            virial: self.virial,
        })
    }

    /// The collision as the engine reported it (wall collisions only).
    pub fn as_wall(&self) -> Option<WallCollision> {
        if self.kind != KIND_WALL {
            return None;
        }
        let (axis, k) = if self.normal.x != 0.0 {
            (Axis::X, 0)
        } else {
            (Axis::Y, 1)
        };
        let side = if self.normal[k] > 0.0 {
            WallSide::High
        } else {
            WallSide::Low
        };
        Some(WallCollision {
            time: self.time,
            i: self.i,
            axis,
            side,
            v_before: self.vi_before,
            v_after: self.vi_after,
            impulse: self.virial,
            energy_lost: self.energy_lost,
        })
    }
}

/// A batch of consecutive logged collisions as a struct of arrays
/// ([`SCHEMA_COLLISION_BATCH`]); every `Vec` has [`CollisionBatch::len`] entries.
/// The writer reuses one batch (no allocation per collision once it has grown).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct CollisionBatch {
    /// Ordinal among all collisions of the run of entry 0.
    pub first_ordinal: u64,
    /// Ordinal step between entries (the log's `collision_every`).
    pub stride: u64,
    /// Time of contact (time).
    pub time: Vec<f64>,
    /// [`KIND_PAIR`] or [`KIND_WALL`].
    pub kind: Vec<u8>,
    /// First disc.
    pub i: Vec<u32>,
    /// Second disc or [`NO_DISC`].
    pub j: Vec<u32>,
    /// Contact normal x.
    pub nx: Vec<f64>,
    /// Contact normal y.
    pub ny: Vec<f64>,
    /// Velocity of i before, x (length/time).
    pub vix_before: Vec<f64>,
    /// Velocity of i before, y.
    pub viy_before: Vec<f64>,
    /// Velocity of j before, x.
    pub vjx_before: Vec<f64>,
    /// Velocity of j before, y.
    pub vjy_before: Vec<f64>,
    /// Velocity of i after, x.
    pub vix_after: Vec<f64>,
    /// Velocity of i after, y.
    pub viy_after: Vec<f64>,
    /// Velocity of j after, x.
    pub vjx_after: Vec<f64>,
    /// Velocity of j after, y.
    pub vjy_after: Vec<f64>,
    /// Energy dissipated (energy).
    pub energy_lost: Vec<f64>,
    /// Pair virial r_ij·Δp_i or wall impulse |Δp|.
    pub virial: Vec<f64>,
}

impl CollisionBatch {
    /// An empty batch with room for `capacity` collisions.
    pub fn with_capacity(capacity: usize) -> Self {
        let f = || Vec::with_capacity(capacity);
        CollisionBatch {
            first_ordinal: 0,
            stride: 1,
            time: f(),
            kind: Vec::with_capacity(capacity),
            i: Vec::with_capacity(capacity),
            j: Vec::with_capacity(capacity),
            nx: f(),
            ny: f(),
            vix_before: f(),
            viy_before: f(),
            vjx_before: f(),
            vjy_before: f(),
            vix_after: f(),
            viy_after: f(),
            vjx_after: f(),
            vjy_after: f(),
            energy_lost: f(),
            virial: f(),
        }
    }

    /// Number of collisions in the batch.
    pub fn len(&self) -> usize {
        self.time.len()
    }

    /// True when the batch holds no collision.
    pub fn is_empty(&self) -> bool {
        self.time.is_empty()
    }

    /// Empty the batch, keeping its allocations.
    pub fn clear(&mut self) {
        self.time.clear();
        self.kind.clear();
        self.i.clear();
        self.j.clear();
        self.nx.clear();
        self.ny.clear();
        self.vix_before.clear();
        self.viy_before.clear();
        self.vjx_before.clear();
        self.vjy_before.clear();
        self.vix_after.clear();
        self.viy_after.clear();
        self.vjx_after.clear();
        self.vjy_after.clear();
        self.energy_lost.clear();
        self.virial.clear();
    }

    #[allow(clippy::too_many_arguments)]
    #[inline]
    fn push_raw(
        &mut self,
        time: f64,
        kind: u8,
        i: u32,
        j: u32,
        n: DVec2,
        vib: DVec2,
        vjb: DVec2,
        via: DVec2,
        vja: DVec2,
        energy_lost: f64,
        virial: f64,
    ) {
        self.time.push(time);
        self.kind.push(kind);
        self.i.push(i);
        self.j.push(j);
        self.nx.push(n.x);
        self.ny.push(n.y);
        self.vix_before.push(vib.x);
        self.viy_before.push(vib.y);
        self.vjx_before.push(vjb.x);
        self.vjy_before.push(vjb.y);
        self.vix_after.push(via.x);
        self.viy_after.push(via.y);
        self.vjx_after.push(vja.x);
        self.vjy_after.push(vja.y);
        self.energy_lost.push(energy_lost);
        self.virial.push(virial);
    }

    /// Append a record (its `ordinal` is not stored).
    #[inline]
    pub fn push(&mut self, r: &CollisionRecord) {
        self.push_raw(
            r.time,
            r.kind,
            r.i,
            r.j,
            r.normal,
            r.vi_before,
            r.vj_before,
            r.vi_after,
            r.vj_after,
            r.energy_lost,
            r.virial,
        );
    }

    /// Append a pair collision.
    #[inline]
    pub fn push_pair(&mut self, c: &PairCollision) {
        self.push(&CollisionRecord::from_pair(c, 0));
    }

    /// Append a wall collision; the normal points from the disc to the wall.
    #[inline]
    pub fn push_wall(&mut self, c: &WallCollision) {
        self.push(&CollisionRecord::from_wall(c, 0));
    }

    /// Entry `k` as a record.
    pub fn get(&self, k: usize) -> CollisionRecord {
        let v = |x: &[f64], y: &[f64]| DVec2::new(x[k], y[k]);
        CollisionRecord {
            ordinal: self
                .first_ordinal
                .wrapping_add((k as u64).wrapping_mul(self.stride)),
            time: self.time[k],
            kind: self.kind[k],
            i: self.i[k],
            j: self.j[k],
            normal: v(&self.nx, &self.ny),
            vi_before: v(&self.vix_before, &self.viy_before),
            vj_before: v(&self.vjx_before, &self.vjy_before),
            vi_after: v(&self.vix_after, &self.viy_after),
            vj_after: v(&self.vjx_after, &self.vjy_after),
            energy_lost: self.energy_lost[k],
            virial: self.virial[k],
        }
    }

    /// The records of the batch in order.
    pub fn iter(&self) -> impl ExactSizeIterator<Item = CollisionRecord> + '_ {
        (0..self.len()).map(move |k| self.get(k))
    }

    /// Uncompressed encoded size in bytes (header included).
    pub fn encoded_len(&self) -> usize {
        // 4 header + 16 scalars + 16 length prefixes + payload + at most 7 pad per f64 array.
        4 + 16 + 16 * 4 + self.len() * (8 * 13 + 1 + 4 + 4) + 16 * 8
    }

    /// Encode as CDR into `w` (which is reset first).
    pub fn encode(&self, w: &mut CdrWriter) {
        w.reset();
        w.reserve(self.encoded_len());
        w.put(self.first_ordinal);
        w.put(self.stride);
        w.seq(&self.time);
        w.seq(&self.kind);
        w.seq(&self.i);
        w.seq(&self.j);
        for a in [
            &self.nx,
            &self.ny,
            &self.vix_before,
            &self.viy_before,
            &self.vjx_before,
            &self.vjy_before,
            &self.vix_after,
            &self.viy_after,
            &self.vjx_after,
            &self.vjy_after,
            &self.energy_lost,
            &self.virial,
        ] {
            w.seq(a);
        }
    }

    /// Encode records (given as an array of structs, e.g. gathered by the writer's
    /// hot loop) as one CDR batch into `w` (which is reset first): the same bytes as
    /// pushing them into a batch and calling [`CollisionBatch::encode`]. The
    /// records' own `ordinal` fields are not stored; `first_ordinal` and `stride`
    /// describe them.
    pub fn encode_records(
        records: &[CollisionRecord],
        first_ordinal: u64,
        stride: u64,
        w: &mut CdrWriter,
    ) {
        w.reset();
        w.reserve(4 + 16 + 16 * 8 + records.len() * 113);
        w.put(first_ordinal);
        w.put(stride);
        w.seq_iter(records.iter().map(|r| r.time));
        w.seq_iter(records.iter().map(|r| r.kind));
        w.seq_iter(records.iter().map(|r| r.i));
        w.seq_iter(records.iter().map(|r| r.j));
        w.seq_iter(records.iter().map(|r| r.normal.x));
        w.seq_iter(records.iter().map(|r| r.normal.y));
        w.seq_iter(records.iter().map(|r| r.vi_before.x));
        w.seq_iter(records.iter().map(|r| r.vi_before.y));
        w.seq_iter(records.iter().map(|r| r.vj_before.x));
        w.seq_iter(records.iter().map(|r| r.vj_before.y));
        w.seq_iter(records.iter().map(|r| r.vi_after.x));
        w.seq_iter(records.iter().map(|r| r.vi_after.y));
        w.seq_iter(records.iter().map(|r| r.vj_after.x));
        w.seq_iter(records.iter().map(|r| r.vj_after.y));
        w.seq_iter(records.iter().map(|r| r.energy_lost));
        w.seq_iter(records.iter().map(|r| r.virial));
    }

    /// Decode from CDR into `self`, reusing its allocations. On error `self` is
    /// left empty.
    pub fn decode_into(&mut self, data: &[u8]) -> Result<(), CdrError> {
        let r = self.decode_inner(data);
        if r.is_err() {
            self.clear();
        }
        r
    }

    fn decode_inner(&mut self, data: &[u8]) -> Result<(), CdrError> {
        let mut r = CdrReader::new(data)?;
        self.first_ordinal = r.get("first_ordinal")?;
        self.stride = r.get("stride")?;
        r.seq_into("time", &mut self.time)?;
        r.seq_into("kind", &mut self.kind)?;
        r.seq_into("i", &mut self.i)?;
        r.seq_into("j", &mut self.j)?;
        r.seq_into("nx", &mut self.nx)?;
        r.seq_into("ny", &mut self.ny)?;
        r.seq_into("vix_before", &mut self.vix_before)?;
        r.seq_into("viy_before", &mut self.viy_before)?;
        r.seq_into("vjx_before", &mut self.vjx_before)?;
        r.seq_into("vjy_before", &mut self.vjy_before)?;
        r.seq_into("vix_after", &mut self.vix_after)?;
        r.seq_into("viy_after", &mut self.viy_after)?;
        r.seq_into("vjx_after", &mut self.vjx_after)?;
        r.seq_into("vjy_after", &mut self.vjy_after)?;
        r.seq_into("energy_lost", &mut self.energy_lost)?;
        r.seq_into("virial", &mut self.virial)?;
        let n = self.time.len();
        let lens = [
            ("kind", self.kind.len()),
            ("i", self.i.len()),
            ("j", self.j.len()),
            ("nx", self.nx.len()),
            ("ny", self.ny.len()),
            ("vix_before", self.vix_before.len()),
            ("viy_before", self.viy_before.len()),
            ("vjx_before", self.vjx_before.len()),
            ("vjy_before", self.vjy_before.len()),
            ("vix_after", self.vix_after.len()),
            ("viy_after", self.viy_after.len()),
            ("vjx_after", self.vjx_after.len()),
            ("vjy_after", self.vjy_after.len()),
            ("energy_lost", self.energy_lost.len()),
            ("virial", self.virial.len()),
        ];
        if let Some((field, len)) = lens.into_iter().find(|&(_, l)| l != n) {
            return Err(CdrError::Invalid {
                field,
                problem: format!("{len} entries, but `time` has {n}"),
            });
        }
        if let Some(&k) = self.kind.iter().find(|&&k| k > KIND_WALL) {
            return Err(CdrError::Invalid {
                field: "kind",
                problem: format!("unknown collision kind {k} (allowed: 0 = pair, 1 = wall)"),
            });
        }
        Ok(())
    }
}

/// Boundary code in snapshots and checkpoints: 0 periodic, 1 walls.
pub fn boundary_code(b: &carom_core::Boundary) -> u8 {
    match b {
        carom_core::Boundary::Periodic => 0,
        carom_core::Boundary::Walls { .. } => 1,
    }
}

/// The state of every disc at one time ([`SCHEMA_SNAPSHOT`]).
#[derive(Debug, Clone, PartialEq)]
pub struct Snapshot {
    /// Simulated time (time).
    pub time: f64,
    /// Box edge lengths (length).
    pub box_size: DVec2,
    /// Boundary codes of the x and y axes (0 periodic, 1 walls).
    pub boundary: [u8; 2],
    /// Radius of each species (length).
    pub species_radius: Vec<f64>,
    /// Mass of each species (mass).
    pub species_mass: Vec<f64>,
    /// Species index of each disc.
    pub species: Vec<u16>,
    /// Centre positions (length).
    pub positions: Vec<DVec2>,
    /// Velocities (length/time).
    pub velocities: Vec<DVec2>,
}

/// The CDR form of a snapshot (`SNAPSHOT_MSG`): (time, box size, boundary codes),
/// each species' (radius, mass), then each disc's species, x, y, vx and vy.
fn encode_snapshot<'a>(
    w: &mut CdrWriter,
    (time, box_size, boundary): (f64, DVec2, [u8; 2]),
    (radius, mass): (
        impl ExactSizeIterator<Item = &'a f64>,
        impl ExactSizeIterator<Item = &'a f64>,
    ),
    species: &[u16],
    positions: &[DVec2],
    velocities: &[DVec2],
) {
    w.reset();
    w.reserve(64 + positions.len() * 34 + radius.len() * 16);
    w.put(time);
    w.put(box_size.x);
    w.put(box_size.y);
    w.put(boundary[0]);
    w.put(boundary[1]);
    w.seq_iter(radius.copied());
    w.seq_iter(mass.copied());
    w.seq(species);
    w.seq_iter(positions.iter().map(|p| p.x));
    w.seq_iter(positions.iter().map(|p| p.y));
    w.seq_iter(velocities.iter().map(|p| p.x));
    w.seq_iter(velocities.iter().map(|p| p.y));
}

impl Snapshot {
    /// The snapshot of an engine state.
    pub fn from_state(s: &State) -> Self {
        Snapshot {
            time: s.time,
            box_size: s.sim_box.size,
            boundary: [
                boundary_code(&s.sim_box.boundary[0]),
                boundary_code(&s.sim_box.boundary[1]),
            ],
            species_radius: s.species.iter().map(|sp| sp.radius).collect(),
            species_mass: s.species.iter().map(|sp| sp.mass).collect(),
            species: s.species_of.clone(),
            positions: s.positions.clone(),
            velocities: s.velocities.clone(),
        }
    }

    /// Number of discs.
    pub fn len(&self) -> usize {
        self.positions.len()
    }

    /// True when there are no discs.
    pub fn is_empty(&self) -> bool {
        self.positions.is_empty()
    }

    /// Mass of disc `k` (mass).
    pub fn mass(&self, k: usize) -> f64 {
        self.species_mass[self.species[k] as usize]
    }

    /// Encode as CDR into `w` (which is reset first).
    pub fn encode(&self, w: &mut CdrWriter) {
        encode_snapshot(
            w,
            (self.time, self.box_size, self.boundary),
            (self.species_radius.iter(), self.species_mass.iter()),
            &self.species,
            &self.positions,
            &self.velocities,
        );
    }

    /// Encode the snapshot of `state` into `w` (reset first): the same bytes as
    /// [`Snapshot::from_state`] followed by [`Snapshot::encode`], without copying
    /// the state's arrays first.
    pub fn encode_state(state: &State, w: &mut CdrWriter) {
        let b = &state.sim_box.boundary;
        encode_snapshot(
            w,
            (
                state.time,
                state.sim_box.size,
                [boundary_code(&b[0]), boundary_code(&b[1])],
            ),
            (
                state.species.iter().map(|sp| &sp.radius),
                state.species.iter().map(|sp| &sp.mass),
            ),
            &state.species_of,
            &state.positions,
            &state.velocities,
        );
    }

    /// Decode from CDR, checking that the arrays are consistent.
    pub fn decode(data: &[u8]) -> Result<Self, CdrError> {
        let mut r = CdrReader::new(data)?;
        let time = r.get("time")?;
        let bx = r.get("box_x")?;
        let by = r.get("box_y")?;
        let boundary = [r.get("boundary_x")?, r.get("boundary_y")?];
        let species_radius: Vec<f64> = r.seq("species_radius")?;
        let species_mass: Vec<f64> = r.seq("species_mass")?;
        let species: Vec<u16> = r.seq("species")?;
        let x: Vec<f64> = r.seq("x")?;
        let y: Vec<f64> = r.seq("y")?;
        let vx: Vec<f64> = r.seq("vx")?;
        let vy: Vec<f64> = r.seq("vy")?;
        let n = species.len();
        for (field, len) in [
            ("x", x.len()),
            ("y", y.len()),
            ("vx", vx.len()),
            ("vy", vy.len()),
        ] {
            if len != n {
                return Err(CdrError::Invalid {
                    field,
                    problem: format!("{len} entries, but `species` has {n}"),
                });
            }
        }
        if species_mass.len() != species_radius.len() {
            return Err(CdrError::Invalid {
                field: "species_mass",
                problem: format!(
                    "{} entries, but `species_radius` has {}",
                    species_mass.len(),
                    species_radius.len()
                ),
            });
        }
        if let Some(&s) = species
            .iter()
            .find(|&&s| s as usize >= species_radius.len())
        {
            return Err(CdrError::Invalid {
                field: "species",
                problem: format!(
                    "species index {s} but only {} species",
                    species_radius.len()
                ),
            });
        }
        Ok(Snapshot {
            time,
            box_size: DVec2::new(bx, by),
            boundary,
            species_radius,
            species_mass,
            species,
            positions: x.iter().zip(&y).map(|(&a, &b)| DVec2::new(a, b)).collect(),
            velocities: vx
                .iter()
                .zip(&vy)
                .map(|(&a, &b)| DVec2::new(a, b))
                .collect(),
        })
    }
}

/// A `/thermo` record (JSON, schema [`THERMO_JSON_SCHEMA`]). Running quantities
/// average over the run so far, from its start time.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Thermo {
    /// Simulated time (time).
    pub time: f64,
    /// K = Σ m v²/2 (energy).
    pub kinetic_energy: f64,
    /// kT = 2K/f, f = 2N − (periodic axes) (energy; physics.md §5).
    pub temperature: f64,
    /// Pair + wall collisions since the start of the run.
    pub collisions: u64,
    /// Pair collisions since the start of the run.
    pub pair_collisions: u64,
    /// Wall collisions since the start of the run.
    pub wall_collisions: u64,
    /// Kinetic energy dissipated since the start (energy).
    pub energy_lost: f64,
    /// Σ r_ij·Δp_i over pair collisions since the start (length·momentum).
    pub virial_sum: f64,
    /// Momentum given to all walls since the start (momentum).
    pub wall_impulse: f64,
    /// Running pressure estimate P (energy/length²), see [`THERMO_JSON_SCHEMA`];
    /// absent (`None`) while no simulated time has passed or kT = 0.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pressure: Option<f64>,
    /// Running compressibility factor βPA/N (dimensionless); absent like `pressure`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub z: Option<f64>,
    /// Pair collisions per disc per unit time, 2 N_pair/(N t) (1/time); absent
    /// while no simulated time has passed.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub collision_rate: Option<f64>,
}

impl Thermo {
    /// Decode a `/thermo` message (JSON).
    pub fn decode(data: &[u8]) -> Result<Thermo, serde_json::Error> {
        serde_json::from_slice(data)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample_batch() -> CollisionBatch {
        let mut b = CollisionBatch::with_capacity(4);
        b.first_ordinal = 10;
        b.stride = 2;
        b.push_pair(&PairCollision {
            time: 1.25,
            i: 3,
            j: 9,
            normal: DVec2::new(0.6, 0.8),
            vi_before: DVec2::new(1.0, 2.0),
            vj_before: DVec2::new(-1.0, 0.5),
            vi_after: DVec2::new(0.1, 0.2),
            vj_after: DVec2::new(0.3, 0.4),
            energy_lost: 0.0,
            virial: -0.7,
        });
        b.push_wall(&WallCollision {
            time: 1.5,
            i: 4,
            axis: Axis::Y,
            side: WallSide::Low,
            v_before: DVec2::new(0.5, -1.0),
            v_after: DVec2::new(0.5, 0.9),
            impulse: 1.9,
            energy_lost: 0.05,
        });
        b
    }

    #[test]
    fn collision_batch_round_trips() {
        let b = sample_batch();
        let mut w = CdrWriter::new();
        b.encode(&mut w);
        assert!(w.bytes().len() <= b.encoded_len());
        let mut d = CollisionBatch::default();
        d.decode_into(w.bytes()).unwrap();
        assert_eq!(d, b);
        let recs: Vec<_> = b.iter().collect();
        let mut w2 = CdrWriter::new();
        CollisionBatch::encode_records(&recs, b.first_ordinal, b.stride, &mut w2);
        assert_eq!(w.bytes(), w2.bytes());
        let recs: Vec<_> = d.iter().collect();
        assert_eq!(recs[1].ordinal, 12);
        let wall = recs[1].as_wall().unwrap();
        assert_eq!((wall.axis, wall.side), (Axis::Y, WallSide::Low));
        assert_eq!(wall.impulse, 1.9);
        assert!(recs[0].as_wall().is_none());
        assert_eq!(recs[0].as_pair().unwrap().j, 9);
    }

    #[test]
    fn inconsistent_batch_is_an_error() {
        let mut b = sample_batch();
        b.ny.pop();
        let mut w = CdrWriter::new();
        b.encode(&mut w);
        let mut d = CollisionBatch::default();
        assert!(matches!(
            d.decode_into(w.bytes()),
            Err(CdrError::Invalid { field: "ny", .. })
        ));
        assert!(d.is_empty());
    }

    #[test]
    fn a_state_encodes_as_its_snapshot() {
        use carom_core::{Boundary, SimBox, Species};
        let state = State {
            sim_box: SimBox {
                size: DVec2::new(7.5, 4.0),
                boundary: [Boundary::Periodic, Boundary::Walls { restitution: 0.9 }],
            },
            species: vec![Species::reference(2), Species::new(1, 0.7, 2.5)],
            species_of: vec![0, 0, 1],
            positions: vec![
                DVec2::new(1.0, 1.0),
                DVec2::new(3.0, 2.0),
                DVec2::new(5.5, 2.5),
            ],
            velocities: vec![
                DVec2::new(0.1, -0.2),
                DVec2::new(-1.5, 0.25),
                DVec2::new(0.0, 3.0),
            ],
            time: 2.75,
        };
        let (mut a, mut b) = (CdrWriter::new(), CdrWriter::new());
        Snapshot::from_state(&state).encode(&mut a);
        // Into a writer that held an earlier, longer message.
        b.reuse(vec![0xAB; 4096]);
        Snapshot::encode_state(&state, &mut b);
        assert_eq!(a.bytes(), b.bytes());
        assert_eq!(
            Snapshot::decode(b.bytes()).unwrap(),
            Snapshot::from_state(&state)
        );
    }

    #[test]
    fn log_time_saturates() {
        assert_eq!(log_time_ns(-1.0), 0);
        assert_eq!(log_time_ns(f64::NAN), 0);
        assert_eq!(log_time_ns(1.5), 1_500_000_000);
        assert_eq!(log_time_ns(1e30), u64::MAX);
    }
}
