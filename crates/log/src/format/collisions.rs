//! The `/collisions` channel: one record per logged collision, and the batch
//! (struct of arrays) it travels in, encoded as CDR with the `ros2msg` schema
//! [`COLLISION_BATCH_MSG`]. The kind codes [`KIND_PAIR`] and [`KIND_WALL`] and
//! the wall marker [`NO_DISC`] are defined here and nowhere else.

use super::cdr::{CdrError, CdrReader, CdrWriter};
use carom_core::{Axis, DVec2, WallSide};
use carom_engine::{PairCollision, WallCollision};

/// `ros2msg` text of the schema `carom_msgs/msg/CollisionBatch`.
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

/// `kind` of a pair collision in [`CollisionBatch`].
pub const KIND_PAIR: u8 = 0;
/// `kind` of a wall collision in [`CollisionBatch`].
pub const KIND_WALL: u8 = 1;
/// `j` of a wall collision in [`CollisionBatch`] is the engine's "no disc",
/// [`NO_DISC`] (u32::MAX).
pub use carom_engine::NO_DISC;

/// One logged collision, as decoded from a [`CollisionBatch`]: its ordinal, its
/// kind, and the collision in the engine's pair form, which it reads through
/// (`record.time`, `record.vi_before`, …). A wall collision fills that form as
/// the log stores it: `j` is [`NO_DISC`], the normal points from the disc to the
/// wall, the second disc's velocities are zero, `virial` holds |Δp| given to
/// the wall (momentum) and `impulse` the Δp the disc received. The full record
/// does not store a pair's impulse: decoded from it, a pair's `impulse` is zero
/// (which no real collision gives; a compact record's replay fills it).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CollisionRecord {
    /// 0-based ordinal among all collisions (pair + wall) of the run.
    pub ordinal: u64,
    /// [`KIND_PAIR`] or [`KIND_WALL`].
    pub kind: u8,
    /// The collision's time, discs, normal, velocities, energy lost and virial.
    pub collision: PairCollision,
}

impl std::ops::Deref for CollisionRecord {
    type Target = PairCollision;

    fn deref(&self) -> &PairCollision {
        &self.collision
    }
}

impl CollisionRecord {
    /// The record of pair collision `c` with run ordinal `ordinal`.
    #[inline]
    pub fn from_pair(c: &PairCollision, ordinal: u64) -> Self {
        CollisionRecord {
            ordinal,
            kind: KIND_PAIR,
            collision: *c,
        }
    }

    /// The record of wall collision `c` with run ordinal `ordinal` (see the type's
    /// documentation for how a wall fills the pair form).
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
            kind: KIND_WALL,
            collision: PairCollision {
                time: c.time,
                i: c.i,
                j: NO_DISC,
                normal,
                vi_before: c.v_before,
                vj_before: DVec2::ZERO,
                vi_after: c.v_after,
                vj_after: DVec2::ZERO,
                energy_lost: c.energy_lost,
                virial: c.impulse,
                impulse: c.impulse_vector(),
            },
        }
    }

    /// True for a wall collision.
    pub fn is_wall(&self) -> bool {
        self.kind == KIND_WALL
    }

    /// The collision as the engine reported it (pair collisions only).
    pub fn as_pair(&self) -> Option<PairCollision> {
        (self.kind == KIND_PAIR).then_some(self.collision)
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
/// ([`COLLISION_BATCH_MSG`]); every `Vec` has [`CollisionBatch::len`] entries.
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
    /// Δp_i, x, when known (a replayed compact batch); empty otherwise. Not part
    /// of the encoded full record.
    pub impulse_x: Vec<f64>,
    /// Δp_i, y, like `impulse_x`.
    pub impulse_y: Vec<f64>,
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
            impulse_x: Vec::new(),
            impulse_y: Vec::new(),
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
        self.impulse_x.clear();
        self.impulse_y.clear();
    }

    /// Append one collision from its fields (the one place a full batch grows;
    /// the replay of compact records uses it too).
    #[allow(clippy::too_many_arguments)]
    #[inline]
    pub(crate) fn push_raw(
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
            kind: self.kind[k],
            collision: PairCollision {
                time: self.time[k],
                i: self.i[k],
                j: self.j[k],
                normal: v(&self.nx, &self.ny),
                vi_before: v(&self.vix_before, &self.viy_before),
                vj_before: v(&self.vjx_before, &self.vjy_before),
                vi_after: v(&self.vix_after, &self.viy_after),
                vj_after: v(&self.vjx_after, &self.vjy_after),
                energy_lost: self.energy_lost[k],
                virial: self.virial[k],
                impulse: if k < self.impulse_x.len() {
                    v(&self.impulse_x, &self.impulse_y)
                } else if self.kind[k] == KIND_WALL {
                    // Away from the wall the normal points to.
                    v(&self.nx, &self.ny) * -self.virial[k]
                } else {
                    DVec2::ZERO
                },
            },
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
        self.impulse_x.clear();
        self.impulse_y.clear();
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
            impulse: DVec2::ZERO,
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
        let wall = d.get(1);
        assert_eq!(wall.impulse, DVec2::new(0.0, 1.9));
        assert_eq!(d.get(0).impulse, DVec2::ZERO);
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
}
