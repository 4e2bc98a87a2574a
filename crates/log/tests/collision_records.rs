//! A logged collision knows what it was: a wall collision, written into the pair
//! form of the `/collisions` record, reads back as the same wall collision (axis,
//! side, velocities, impulse, energy) for each of the four walls, with its normal
//! pointing at the wall and its impulse away from it; a pair collision reads back
//! as itself and never as a wall; a batch numbers its entries by its stride (1
//! when new).
//! (Found missing by mutation testing, docs/testing.md: these were exercised
//! only through the whole CLI.)

use carom_core::collision::resolve;
use carom_core::{Axis, DVec2, Restitution, WallSide};
use carom_engine::{PairCollision, WallCollision};
use carom_log::{CollisionBatch, CollisionRecord, KIND_PAIR, KIND_WALL, NO_DISC};

fn wall(axis: Axis, side: WallSide) -> WallCollision {
    let out = if side == WallSide::High { 1.0 } else { -1.0 };
    let mut v_before = DVec2::new(0.25, -0.75);
    v_before[axis.index()] = 1.5 * out;
    let mut v_after = v_before;
    v_after[axis.index()] = -1.25 * out;
    WallCollision {
        time: 2.5,
        i: 6,
        axis,
        side,
        v_before,
        v_after,
        impulse: 2.75,
        energy_lost: 0.34375,
    }
}

/// A pair collision as the engine reports it: resolved elastically along the
/// line of centres.
fn pair() -> PairCollision {
    let (vi, vj) = (DVec2::new(1.5, 0.25), DVec2::new(-0.5, 0.75));
    let n = DVec2::new(0.8, -0.6);
    let r = resolve(vi, vj, 1.0, 2.0, n, Restitution::Elastic);
    PairCollision {
        time: 3.75,
        i: 2,
        j: 8,
        normal: n,
        vi_before: vi,
        vj_before: vj,
        vi_after: r.vi,
        vj_after: r.vj,
        energy_lost: r.energy_lost,
        virial: -n.dot(r.impulse_i),
        impulse: r.impulse_i,
    }
}

#[test]
fn each_wall_collision_reads_back_as_itself() {
    for axis in [Axis::X, Axis::Y] {
        for side in [WallSide::Low, WallSide::High] {
            let c = wall(axis, side);
            let r = CollisionRecord::from_wall(&c, 5);
            assert!(r.is_wall() && r.kind == KIND_WALL);
            assert_eq!(r.j, NO_DISC);
            assert_eq!(r.as_pair(), None);
            assert_eq!(r.as_wall(), Some(c), "{axis:?} {side:?}");
            // The normal points from the disc to the wall; the disc's impulse away.
            let out = if side == WallSide::High { 1.0 } else { -1.0 };
            assert_eq!(r.normal[axis.index()], out);
            assert_eq!(r.impulse, -r.normal * c.impulse);
            assert_eq!(r.impulse, c.impulse_vector());
            // Through a batch, which does not store the impulse, the same.
            let mut b = CollisionBatch::with_capacity(1);
            b.push_wall(&c);
            assert_eq!(b.get(0).impulse, c.impulse_vector());
            assert_eq!(b.get(0).as_wall(), Some(c));
        }
    }
}

#[test]
fn a_pair_collision_is_never_a_wall() {
    let c = pair();
    let r = CollisionRecord::from_pair(&c, 5);
    assert!(!r.is_wall() && r.kind == KIND_PAIR);
    assert_eq!(r.as_wall(), None);
    assert_eq!(r.as_pair(), Some(c));
    assert_eq!(r.ordinal, 5);
}

#[test]
fn batch_entries_are_numbered_by_the_stride() {
    // A new batch holds consecutive collisions from ordinal 0.
    let mut b = CollisionBatch::with_capacity(3);
    b.push_pair(&pair());
    b.push_pair(&pair());
    assert_eq!(b.get(1).ordinal, 1);
    b.clear();
    b.first_ordinal = 100;
    b.stride = 7;
    for _ in 0..3 {
        b.push_pair(&pair());
    }
    assert_eq!(b.len(), 3);
    assert!(!b.is_empty());
    let ordinals: Vec<u64> = b.iter().map(|r| r.ordinal).collect();
    assert_eq!(ordinals, [100, 107, 114]);
    // The full record does not store a pair's impulse: zero, never made up.
    assert_eq!(b.get(1).impulse, DVec2::ZERO);
    b.clear();
    assert!(b.is_empty());
}
