//! The collisions of a log as one block of records laid out as numpy's
//! `carom.COLLISION_DTYPE` (aligned: 18 eight-byte words per record), built in
//! Rust with the GIL released and handed to numpy without a copy; Python views
//! the words as the structured dtype. Reading at 10⁷ collisions per second needs
//! this: filling 19 separate columns and then copying each into a structured
//! array in Python cost more than decoding the log (docs/performance.md).
//!
//! The words of a record, in the dtype's field order: `ordinal`, `kind` (one
//! byte, then padding), `time`, `i` and `j` (two u32 in one word), then `nx`,
//! `ny`, the eight velocities (before, after; i then j; x then y),
//! `energy_lost`, `virial`, `impulse_x`, `impulse_y` as the bits of f64s. The
//! values are those of carom-log's [`CollisionBatch::get`] (compact batches
//! replayed by the reader, a full record's impulse by carom-log's rule).

use carom_log::{CollisionBatch, CollisionRecord, LogReader};
use std::fs::File;
use std::io::BufReader;

/// Eight-byte words per record (`COLLISION_DTYPE.itemsize` / 8).
pub const WORDS: usize = 18;

/// A record as its words (see the module's documentation).
#[inline]
fn words(r: &CollisionRecord) -> [u64; WORDS] {
    let mut kind = [0u8; 8];
    kind[0] = r.kind;
    let mut ij = [0u8; 8];
    ij[..4].copy_from_slice(&r.i.to_ne_bytes());
    ij[4..].copy_from_slice(&r.j.to_ne_bytes());
    let f = |x: f64| x.to_bits();
    [
        r.ordinal,
        u64::from_ne_bytes(kind),
        f(r.time),
        u64::from_ne_bytes(ij),
        f(r.normal.x),
        f(r.normal.y),
        f(r.vi_before.x),
        f(r.vi_before.y),
        f(r.vj_before.x),
        f(r.vj_before.y),
        f(r.vi_after.x),
        f(r.vi_after.y),
        f(r.vj_after.x),
        f(r.vj_after.y),
        f(r.energy_lost),
        f(r.virial),
        f(r.impulse.x),
        f(r.impulse.y),
    ]
}

/// Visit every collision of `reader` with t0 ≤ time ≤ t1 as its words, in
/// order (batches after t1 are not read).
fn each_record(
    reader: &mut LogReader<BufReader<File>>,
    t0: f64,
    t1: f64,
    mut visit: impl FnMut(&[u64; WORDS]),
) -> Result<(), carom_log::ReadError> {
    let mut b = CollisionBatch::default();
    while reader.next_batch_into(&mut b)? {
        if b.time.first().is_some_and(|&t| t > t1) {
            break;
        }
        // A batch's times are in order: its records in the window are a run.
        let lo = b.time.partition_point(|&t| t < t0);
        let hi = b.time.partition_point(|&t| t <= t1).max(lo);
        for k in lo..hi {
            visit(&words(&b.get(k)));
        }
    }
    Ok(())
}

/// Every collision of `reader` with t0 ≤ time ≤ t1, [`WORDS`] words each.
pub fn collision_words(
    reader: &mut LogReader<BufReader<File>>,
    t0: f64,
    t1: f64,
) -> Result<Vec<u64>, carom_log::ReadError> {
    let mut out = Vec::new();
    each_record(reader, t0, t1, |w| out.extend_from_slice(w))?;
    Ok(out)
}

/// Every collision of `reader` with t0 ≤ time ≤ t1 written into `out`, which
/// has room for exactly as many (the count of the log's summary): `false`
/// when the log holds another number of them (a damaged summary), `out` then
/// partly written.
pub fn fill_collision_words(
    reader: &mut LogReader<BufReader<File>>,
    t0: f64,
    t1: f64,
    out: &mut [u64],
) -> Result<bool, carom_log::ReadError> {
    let mut slots = out.chunks_exact_mut(WORDS);
    let mut fits = true;
    each_record(reader, t0, t1, |w| match slots.next() {
        Some(slot) => slot.copy_from_slice(w),
        None => fits = false,
    })?;
    Ok(fits && slots.next().is_none())
}
