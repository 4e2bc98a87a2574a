//! The compact `/collisions` record (log format 2, the default): per collision its
//! time, the discs (or the wall) and the impulse Δp_i given to disc i, as a
//! struct of arrays encoded as CDR with the `ros2msg` schema
//! [`COMPACT_COLLISION_BATCH_MSG`]. The engine applies every collision as
//! v_i' = v_i + Δp_i/m_i, v_j' = v_j − Δp_i/m_j (a wall: v_k' = v_k + Δp_k/m;
//! `carom_core::collision::apply_impulse`), so a reader starting from a snapshot's
//! velocities and adding the impulses in order gets every later velocity bit for
//! bit (the reader's `replay` does; docs/log-format.md, "Compact collisions").
//! The contact normal is stored only when the rule's impulse is not along the
//! line of centres (the centre-of-mass rule): otherwise it is −Δp_i/|Δp_i|.
//! Times are absolute f64 (exact); a wall is coded in `j` ([`wall_code`]).

use super::cdr::{CdrError, CdrReader, CdrWriter};
use super::collisions::{CollisionRecord, KIND_PAIR, KIND_WALL};
use super::{Channel, MESSAGE_ENCODING_CDR, SCHEMA_ENCODING_ROS2MSG, TOPIC_COLLISIONS};
use carom_core::{Axis, DVec2, WallSide};

/// `ros2msg` text of the schema `carom_msgs/msg/CompactCollisionBatch`.
pub const COMPACT_COLLISION_BATCH_MSG: &str = "\
# A batch of consecutive collisions, in time order (struct of arrays): every
# collision of the run (pair + wall) is logged. Units are the run's.
# Velocities are replayed from a /snapshot: pair (i, j): v_i += dp / m_i and
# v_j -= dp / m_j; wall on axis k: v_i[k] += dp[k] / m_i (each component one
# division then one addition, in float64), which gives the engine's velocities
# bit for bit. Masses and radii: the snapshot's species arrays.
uint64 first_ordinal   # 0-based ordinal, among all collisions of the run, of the first entry
uint64 stride          # always 1 (entry k has ordinal first_ordinal + k)
float64[] time         # time of contact (time), absolute
uint32[] i             # disc i (0-based index)
uint32[] j             # disc j; a wall: 4294967292 + 2*axis + side (axis 0 = x, 1 = y; side 0 = low wall, 1 = high wall)
float64[] dpx          # momentum given to disc i, dp_i (mass*length/time); disc j receives -dp_i
float64[] dpy
float64[] nx           # unit contact normal from i to j at contact: empty unless the collision rule's impulse is not along it (centre-of-mass restitution), then one entry per collision (0 for a wall)
float64[] ny
";

/// The `/collisions` channel of a compact log (same topic as the full record's,
/// [`super::CHANNELS`]`[CH_COLLISIONS]`, another schema).
pub const COMPACT_COLLISIONS_CHANNEL: Channel = Channel {
    topic: TOPIC_COLLISIONS,
    schema_name: "carom_msgs/msg/CompactCollisionBatch",
    schema_encoding: SCHEMA_ENCODING_ROS2MSG,
    schema_text: COMPACT_COLLISION_BATCH_MSG,
    message_encoding: MESSAGE_ENCODING_CDR,
};

/// `j` of the first wall code: walls are `WALL_CODE_BASE + 2·axis + side`.
pub const WALL_CODE_BASE: u32 = u32::MAX - 3;

/// The `j` of a collision with the wall of `axis` on `side` in a compact batch.
pub fn wall_code(axis: Axis, side: WallSide) -> u32 {
    WALL_CODE_BASE + 2 * axis.index() as u32 + u32::from(side == WallSide::High)
}

/// The wall (axis, side) a compact `j` codes, or `None` for a disc.
pub fn wall_of(j: u32) -> Option<(Axis, WallSide)> {
    let c = j.checked_sub(WALL_CODE_BASE)?;
    let axis = if c < 2 { Axis::X } else { Axis::Y };
    let side = if c % 2 == 1 {
        WallSide::High
    } else {
        WallSide::Low
    };
    Some((axis, side))
}

/// A compact batch as a struct of arrays ([`COMPACT_COLLISION_BATCH_MSG`]).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct CompactBatch {
    /// Ordinal among all collisions of the run of entry 0.
    pub first_ordinal: u64,
    /// Time of contact (time).
    pub time: Vec<f64>,
    /// Disc i.
    pub i: Vec<u32>,
    /// Disc j or a wall code ([`wall_code`]).
    pub j: Vec<u32>,
    /// Δp_i, x (mass·length/time).
    pub dpx: Vec<f64>,
    /// Δp_i, y.
    pub dpy: Vec<f64>,
    /// Unit contact normal, x (empty when not stored).
    pub nx: Vec<f64>,
    /// Unit contact normal, y (empty when not stored).
    pub ny: Vec<f64>,
}

impl CompactBatch {
    /// Number of collisions in the batch.
    pub fn len(&self) -> usize {
        self.time.len()
    }

    /// True when the batch holds no collision.
    pub fn is_empty(&self) -> bool {
        self.time.is_empty()
    }

    /// Whether the batch stores the contact normals.
    pub fn has_normals(&self) -> bool {
        !self.nx.is_empty()
    }

    /// Empty the batch, keeping its allocations.
    pub fn clear(&mut self) {
        for v in [
            &mut self.time,
            &mut self.dpx,
            &mut self.dpy,
            &mut self.nx,
            &mut self.ny,
        ] {
            v.clear();
        }
        self.i.clear();
        self.j.clear();
    }

    /// Encode `records` (consecutive collisions, every one of the run) as one
    /// compact batch into `w` (reset first); with `normals`, the contact normals
    /// too. A record's `impulse` must be Δp_i as the engine applied it.
    pub fn encode_records(
        records: &[CollisionRecord],
        first_ordinal: u64,
        normals: bool,
        w: &mut CdrWriter,
    ) {
        w.reset();
        w.reserve(4 + 16 + 7 * 8 + records.len() * if normals { 56 } else { 40 });
        w.put(first_ordinal);
        w.put(1u64);
        w.seq_iter(records.iter().map(|r| r.time));
        w.seq_iter(records.iter().map(|r| r.i));
        w.seq_iter(records.iter().map(compact_j));
        w.seq_iter(records.iter().map(|r| r.impulse.x));
        w.seq_iter(records.iter().map(|r| r.impulse.y));
        let normal = |r: &CollisionRecord| match r.kind {
            KIND_PAIR => r.normal,
            _ => DVec2::ZERO,
        };
        if normals {
            w.seq_iter(records.iter().map(|r| normal(r).x));
            w.seq_iter(records.iter().map(|r| normal(r).y));
        } else {
            w.seq_iter(std::iter::empty::<f64>());
            w.seq_iter(std::iter::empty::<f64>());
        }
    }

    /// Encode the batch as CDR into `w` (reset first).
    pub fn encode(&self, w: &mut CdrWriter) {
        w.reset();
        w.put(self.first_ordinal);
        w.put(1u64);
        w.seq(&self.time);
        w.seq(&self.i);
        w.seq(&self.j);
        for a in [&self.dpx, &self.dpy, &self.nx, &self.ny] {
            w.seq(a);
        }
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
        let stride: u64 = r.get("stride")?;
        if stride != 1 {
            return Err(CdrError::Invalid {
                field: "stride",
                problem: format!("{stride} (a compact batch holds every collision: 1)"),
            });
        }
        r.seq_into("time", &mut self.time)?;
        r.seq_into("i", &mut self.i)?;
        r.seq_into("j", &mut self.j)?;
        r.seq_into("dpx", &mut self.dpx)?;
        r.seq_into("dpy", &mut self.dpy)?;
        r.seq_into("nx", &mut self.nx)?;
        r.seq_into("ny", &mut self.ny)?;
        let n = self.time.len();
        let normals = if self.nx.is_empty() { 0 } else { n };
        let lens = [
            ("i", self.i.len(), n),
            ("j", self.j.len(), n),
            ("dpx", self.dpx.len(), n),
            ("dpy", self.dpy.len(), n),
            ("nx", self.nx.len(), normals),
            ("ny", self.ny.len(), normals),
        ];
        if let Some((field, len, want)) = lens.into_iter().find(|&(_, l, w)| l != w) {
            return Err(CdrError::Invalid {
                field,
                problem: format!("{len} entries, expected {want} (`time` has {n})"),
            });
        }
        Ok(())
    }
}

/// The compact `j` of a record: disc j, or the wall's code.
fn compact_j(r: &CollisionRecord) -> u32 {
    if r.kind != KIND_WALL {
        return r.j;
    }
    let k = if r.normal.x != 0.0 { 0 } else { 1 };
    let axis = if k == 0 { Axis::X } else { Axis::Y };
    let side = if r.normal[k] > 0.0 {
        WallSide::High
    } else {
        WallSide::Low
    };
    wall_code(axis, side)
}

#[cfg(test)]
mod tests {
    use super::*;
    use carom_engine::{PairCollision, WallCollision};

    #[test]
    fn wall_codes_round_trip_and_are_not_discs() {
        for axis in [Axis::X, Axis::Y] {
            for side in [WallSide::Low, WallSide::High] {
                assert_eq!(wall_of(wall_code(axis, side)), Some((axis, side)));
            }
        }
        assert_eq!(wall_of(WALL_CODE_BASE - 1), None);
        assert_eq!(wall_code(Axis::Y, WallSide::High), u32::MAX);
    }

    #[test]
    fn compact_batch_round_trips_with_and_without_normals() {
        let pair = PairCollision {
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
            impulse: DVec2::new(-0.9, -1.8),
        };
        let wall = WallCollision {
            time: 1.5,
            i: 4,
            axis: Axis::Y,
            side: WallSide::High,
            v_before: DVec2::new(0.5, 1.0),
            v_after: DVec2::new(0.5, -0.9),
            impulse: 1.9,
            energy_lost: 0.05,
        };
        let recs = [
            CollisionRecord::from_pair(&pair, 7),
            CollisionRecord::from_wall(&wall, 8),
        ];
        for normals in [false, true] {
            let mut w = CdrWriter::new();
            CompactBatch::encode_records(&recs, 7, normals, &mut w);
            let mut b = CompactBatch::default();
            b.decode_into(w.bytes()).unwrap();
            assert_eq!(b.first_ordinal, 7);
            assert_eq!(b.time, [1.25, 1.5]);
            assert_eq!(b.i, [3, 4]);
            assert_eq!(b.j, [9, wall_code(Axis::Y, WallSide::High)]);
            assert_eq!(b.dpx, [-0.9, 0.0]);
            assert_eq!(b.dpy, [-1.8, -1.9]);
            assert_eq!(b.has_normals(), normals);
            if normals {
                assert_eq!(
                    (b.nx.as_slice(), b.ny.as_slice()),
                    (&[0.6, 0.0][..], &[0.8, 0.0][..])
                );
            }
            let mut again = CdrWriter::new();
            b.encode(&mut again);
            assert_eq!(again.bytes(), w.bytes());
        }
    }

    #[test]
    fn inconsistent_compact_batch_is_an_error() {
        let mut b = CompactBatch {
            time: vec![1.0, 2.0],
            i: vec![0, 1],
            j: vec![1, 2],
            dpx: vec![0.5, 0.5],
            dpy: vec![0.5],
            ..CompactBatch::default()
        };
        let mut w = CdrWriter::new();
        b.encode(&mut w);
        let mut d = CompactBatch::default();
        assert!(matches!(
            d.decode_into(w.bytes()),
            Err(CdrError::Invalid { field: "dpy", .. })
        ));
        assert!(d.is_empty());
        b.dpy.push(0.5);
        b.nx = vec![1.0];
        b.ny = vec![0.0];
        b.encode(&mut w);
        assert!(matches!(
            d.decode_into(w.bytes()),
            Err(CdrError::Invalid { field: "nx", .. })
        ));
    }
}
