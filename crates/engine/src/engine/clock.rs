//! The engine's clock and the renumbering of its discs.
//!
//! Every per-disc time runs on an internal clock t − epoch, restarted at each
//! renumbering ([`Engine::rebase_clock`]: r0 ← r0 + v t_shift, every stored time
//! − t_shift), so that event times round like times since the last restart, not
//! like the whole run's (contact errors ≈ 4 ulp(t)·|v|). Every 16 N pair
//! collisions the discs are renumbered along the Z (Morton) curve of their cells,
//! so that discs close in space are close in memory; only the internal order
//! changes, never the trajectory. The clock also counts collisions at one instant
//! and reports a runaway (physics.md §4) past the configured limit. See
//! docs/performance.md, "renumbering".

use super::Engine;
use crate::error::EngineError;
use crate::NO_DISC;
use carom_core::DVec2;

/// The limit of [`Engine::origin_limit`] for a box of edges `size` and cells of
/// edges `width` (length).
pub(super) fn origin_limit(size: DVec2, width: DVec2) -> f64 {
    (ORIGIN_LIMIT * size.max_element()).max(ORIGIN_LIMIT_CELLS * width.max_element())
}

/// How far (in box lengths, along either axis) a path origin may lie from the box
/// before the clock is restarted early ([`Engine::keep_origin_near`]); in a fluid it
/// stays within about one box length.
const ORIGIN_LIMIT: f64 = 8.0;

/// The same limit in cell widths (each at least the largest contact distance σ),
/// the larger of the two applying: in a small box, origins 4096 σ out still round
/// to 10⁻¹² σ, and a drifting cluster is not renumbered every few box lengths.
const ORIGIN_LIMIT_CELLS: f64 = 4096.0;

/// Pair collisions between two renumberings of the discs along the Z curve.
pub(super) fn reorder_interval(n: usize) -> u64 {
    (16 * n as u64).max(1 << 16)
}

/// Interleave the bits of a cell's column and row (Z-order / Morton key).
fn morton(c: [u32; 2]) -> u64 {
    fn spread(x: u32) -> u64 {
        let mut x = x as u64;
        x = (x | (x << 16)) & 0x0000_ffff_0000_ffff;
        x = (x | (x << 8)) & 0x00ff_00ff_00ff_00ff;
        x = (x | (x << 4)) & 0x0f0f_0f0f_0f0f_0f0f;
        x = (x | (x << 2)) & 0x3333_3333_3333_3333;
        x = (x | (x << 1)) & 0x5555_5555_5555_5555;
        x
    }
    spread(c[0]) | (spread(c[1]) << 1)
}

impl Engine {
    /// Move the clock to time `t` (≥ now) for an event that is not a collision (a
    /// crossing, a recomputed prediction, a scheduled event): a later time is a new
    /// instant, at which no collision has happened yet.
    #[inline]
    pub(super) fn move_clock(&mut self, t: f64) {
        if t > self.clock {
            self.clock = t;
            self.same_time_collisions = 0;
        }
    }

    /// Move the clock to collision time `t`, counting the collisions at one instant;
    /// more than `max_events_without_time_advance` of them is a runaway.
    #[inline]
    pub(super) fn advance_clock(&mut self, t: f64) -> Result<(), EngineError> {
        // Crossings and stale predictions move the internal clock without being
        // reported, so the reported time catches up here in either case.
        self.reported = self.reported.max(self.epoch + t);
        if t > self.clock {
            self.clock = t;
            self.same_time_collisions = 1;
        } else {
            self.same_time_collisions += 1;
            if self.same_time_collisions > self.params.max_events_without_time_advance {
                return Err(EngineError::Stalled {
                    time: self.reported,
                    events: self.same_time_collisions,
                    limit: self.params.max_events_without_time_advance,
                    dissipative: !self.params.restitution.is_elastic() && self.params.tc == 0.0,
                });
            }
        }
        Ok(())
    }

    /// Renumber the discs along the Z (Morton) curve of their cells, so that discs
    /// close in space are close in memory and in the queue. Only the internal order
    /// changes: events and states keep the user's numbering, and no arithmetic on
    /// the trajectory depends on the order (ties are broken by internal index, which
    /// this renumbering makes a deterministic function of the history).
    pub(super) fn reorder(&mut self) {
        self.rebase_clock();
        let n = self.len();
        // Along the curve of the smallest discs' cells (their own cell for those).
        let first = &self.grids.first;
        let mut keys: Vec<(u64, u32)> = (0..n)
            .map(|i| {
                let b = &self.bodies[i];
                let c = if self.grids.class(b.species) == 0 {
                    b.link.coords()
                } else {
                    first.coords_of(b.r0)
                };
                (morton(c), i as u32)
            })
            .collect();
        keys.sort_unstable();
        let perm: Vec<usize> = keys.iter().map(|k| k.1 as usize).collect();
        let mut inv = vec![0u32; n];
        for (k, &old) in perm.iter().enumerate() {
            inv[old] = k as u32;
        }
        /// Reorder `v` in place (through a temporary copy), so that the array keeps
        /// its allocation and with it its huge pages.
        fn permute<T: Copy>(v: &mut [T], perm: &[usize]) {
            let old = v.to_vec();
            for (slot, &o) in v.iter_mut().zip(perm) {
                *slot = old[o];
            }
        }
        permute(&mut self.bodies, &perm);
        permute(&mut self.last_collision, &perm);
        permute(&mut self.label, &perm);
        if let Some(lists) = self.lists.as_mut() {
            // The lists move with their discs and name them by their new indices.
            permute(&mut lists.lines, &perm);
            for line in lists.lines.iter_mut() {
                line.renumber(&inv);
            }
        }
        for b in self.bodies.iter_mut() {
            if b.partner != NO_DISC {
                b.partner = inv[b.partner as usize];
            }
        }
        self.queue.retune(self.bodies.as_slice(), self.clock);
        for (k, &l) in self.label.iter().enumerate() {
            self.index_of[l as usize] = k as u32;
        }
        for grid in self.grids.iter_mut() {
            grid.head.fill(NO_DISC);
        }
        for k in (0..n).rev() {
            let c = self.bodies[k].link.coords();
            let grid = self.grids.get_mut(self.grids.class(self.bodies[k].species));
            grid.insert(&mut self.bodies, k as u32, c);
        }
    }

    /// Move the internal clock's zero to now: every disc is brought to the current
    /// time, and every stored time (pending events, last collisions) is shifted by
    /// the same amount. Called at each renumbering, which refiles the queue.
    ///
    /// Event times are rounded to the precision of the times they are stored as, so
    /// with one clock for a whole run the contact distance at a collision would be
    /// off by about 4 ulp(t)·|v| — 1e-11 σ after 10⁹ collisions at N = 10⁴, and past
    /// the invariant checker's 1e-10 beyond 10¹⁰. On a clock restarted every 16 N
    /// collisions the error stays that of times of order 10 mean free times, however
    /// long the run. The shift is monotone, so no two events change order (at most
    /// two become equal in time, and ties go by disc index as always). The reported
    /// time `epoch + clock` is only a label and is kept non-decreasing.
    fn rebase_clock(&mut self) {
        let shift = self.clock;
        if shift == 0.0 {
            return;
        }
        // The queue is refiled from the shifted times by the renumbering that
        // follows.
        let g = self.params.gravity;
        for b in self.bodies.iter_mut() {
            b.r0 = b.at(shift);
            if g != 0.0 && !b.resting() {
                // The new origin and velocity are the true ones now (engine::gravity;
                // a resting disc's path is its true one, engine::resting).
                b.r0.y -= 0.5 * g * shift * shift;
                b.v.y -= g * shift;
            }
            b.event_time -= shift;
        }
        for t in self.last_collision.iter_mut() {
            *t -= shift;
        }
        self.growth.rebase(shift);
        self.epoch += shift;
        self.clock = 0.0;
    }
}
