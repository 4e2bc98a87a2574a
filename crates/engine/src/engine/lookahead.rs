//! Fetching ahead: start loading the memory the next events will read.
//!
//! At large N the engine's state far outgrows the caches and each event reads
//! records at random places, so nearly every read is a main-memory round trip. The
//! calendar knows which discs have events in the next buckets (about two
//! collisions per bucket), so loads are started early, in stages, each reading
//! only what the previous stage (one bucket earlier) started to load: four
//! buckets ahead the disc records (by the queue), three the labels, two the
//! partner's record and the rows of cell heads of the disc's 3 × 3 block, one the
//! first disc of each cell of that block and the partner's rows, and the current
//! bucket the partner's first discs. Only hints are issued: nothing read changes
//! the trajectory. Whether it pays is timed ([`Tuner`]). See docs/performance.md,
//! "look-ahead".

use super::body::{Body, Pending};
use super::Engine;
use crate::cells::CellGrid;
use crate::lists::Lists;
use crate::memory::prefetch_at;
use crate::NO_DISC;

mod tuner;
pub(super) use tuner::Tuner;

/// The first guess of whether fetching ahead pays for N discs: only once the state
/// (about 160 bytes per disc) outgrows the cache the process gets; below that the
/// loads hit the cache anyway and the extra work only costs time. From 20 000
/// discs on a [`Tuner`] times both settings and keeps the faster (see
/// docs/performance.md, "look-ahead").
pub(super) fn worthwhile(n: usize) -> bool {
    n >= 170_000
}

impl Engine {
    /// A window of the look-ahead tuner ended: choose the setting for the next one.
    #[cold]
    #[inline(never)]
    pub(super) fn tune_look_ahead(&mut self) {
        self.look_ahead = self
            .tuner
            .next_window(std::time::Instant::now(), self.look_ahead);
    }

    /// Start loading what the events of the next buckets will read (see the module
    /// docs). Called when the queue moves on to another bucket. Kept out of line, so
    /// that profiles show its share (inlining it made no measurable difference).
    #[inline(never)]
    pub(super) fn look_ahead(&self) {
        if let Some(lists) = self.lists.as_deref() {
            return self.look_ahead_listed(lists);
        }
        let grids = &self.grids;
        // Each disc's blocks lie in the grid of its size class (the only one for
        // equal discs); the scans of other classes' grids are not fetched ahead.
        let grid_of = |b: &Body| grids.get(grids.class(b.species));
        let bodies = self.bodies.as_slice();
        let last = self.bodies.len() - 1;
        // The first disc of a cell, or (for an empty cell) the last disc: a needless
        // but harmless load, cheaper than a branch on emptiness (chosen with
        // `select_unpredictable`: whether a cell is empty is a coin toss).
        let fetch_first = |head: u32| {
            let h = std::hint::select_unpredictable(head == NO_DISC, last, head as usize);
            prefetch_at(&self.bodies, h);
        };
        // Stale entries (about 4 in 10: every collision leaves the partner's old
        // entry behind) are skipped already here: their loads would only compete
        // with the useful ones for the processor's miss buffers.
        for d in self.queue.filed_ahead(bodies, 3) {
            prefetch_at(&self.label, d as usize);
        }
        for d in self.queue.filed_ahead(bodies, 2) {
            let b = &self.bodies[d as usize];
            if b.pending == Pending::Pair {
                let p = b.partner as usize;
                prefetch_at(&self.bodies, p);
                prefetch_at(&self.label, p);
            }
            let grid = grid_of(b);
            for_rows(grid, event_cell(grid, b), |k| prefetch_at(&grid.head, k));
        }
        for d in self.queue.filed_ahead(bodies, 1) {
            let b = &self.bodies[d as usize];
            let grid = grid_of(b);
            for_block(grid, event_cell(grid, b), fetch_first);
            if b.pending == Pending::Pair {
                let p = b.partner as usize;
                let grid = grid_of(&self.bodies[p]);
                for_rows(grid, self.bodies[p].link.coords(), |k| {
                    prefetch_at(&grid.head, k)
                });
            }
        }
        for d in self.queue.in_current_bucket(bodies) {
            let b = &self.bodies[d as usize];
            if b.pending == Pending::Pair {
                let p = b.partner as usize;
                let grid = grid_of(&self.bodies[p]);
                for_block(grid, self.bodies[p].link.coords(), fetch_first);
            }
        }
    }
}

impl Engine {
    /// [`Engine::look_ahead`] on neighbour lists (engine::listed): two buckets
    /// ahead the disc's list line and its partner's record, one ahead the records
    /// of its list's members, which its prediction will test.
    fn look_ahead_listed(&self, lists: &Lists) {
        let bodies = self.bodies.as_slice();
        for d in self.queue.filed_ahead(bodies, 3) {
            prefetch_at(&self.label, d as usize);
        }
        for d in self.queue.filed_ahead(bodies, 2) {
            let b = &self.bodies[d as usize];
            prefetch_at(&lists.lines, d as usize);
            if b.pending == Pending::Pair {
                let p = b.partner as usize;
                prefetch_at(&self.bodies, p);
                prefetch_at(&self.label, p);
                prefetch_at(&lists.lines, p);
            }
        }
        for d in self.queue.filed_ahead(bodies, 1) {
            for (j, _) in lists.lines[d as usize].members() {
                prefetch_at(&self.bodies, j as usize);
            }
        }
        for d in self.queue.in_current_bucket(bodies) {
            let b = &self.bodies[d as usize];
            if b.pending == Pending::Pair {
                for (j, _) in lists.lines[b.partner as usize].members() {
                    prefetch_at(&self.bodies, j as usize);
                }
            }
        }
    }
}

/// The cell around which the disc with record `b` will search at its pending event:
/// its own, or for a crossing the cell it enters (wrapped on a periodic axis).
#[inline]
fn event_cell(grid: &CellGrid, b: &Body) -> [u32; 2] {
    let mut c = b.link.coords();
    if b.pending == Pending::Cell {
        let face = b.aux.face();
        let k = face.axis();
        let n = grid.n[k];
        c[k] = if face.high() {
            if c[k] + 1 == n {
                0
            } else {
                c[k] + 1
            }
        } else if c[k] == 0 {
            n - 1
        } else {
            c[k] - 1
        };
    }
    c
}

/// Call `f` with the head (first disc or [`NO_DISC`]) of each cell of the 3 × 3 block
/// around `c`, wrapped around the box on both axes (beyond a wall that is a
/// needless but harmless cell).
#[inline(always)]
fn for_block(grid: &CellGrid, c: [u32; 2], mut f: impl FnMut(u32)) {
    let [nx, ny] = grid.n;
    let w = nx as usize;
    if c[0] >= 1 && c[0] + 1 < nx && c[1] >= 1 && c[1] + 1 < ny {
        // Interior (almost every cell): rows of three consecutive cells, read
        // from one slice (one bounds check for the nine heads).
        let first = (c[1] as usize - 1) * w + c[0] as usize - 1;
        let block = &grid.head[first..first + 2 * w + 3];
        for row in [0, w, 2 * w] {
            f(block[row]);
            f(block[row + 1]);
            f(block[row + 2]);
        }
        return;
    }
    // c ± 1 wrapped, without a division.
    let around = |c: u32, n: u32| {
        let below = if c == 0 { n - 1 } else { c - 1 };
        let above = if c + 1 == n { 0 } else { c + 1 };
        [below, c, above]
    };
    let cols = around(c[0], nx);
    for cy in around(c[1], ny) {
        let row = cy as usize * w;
        for cx in cols {
            f(grid.head[row + cx as usize]);
        }
    }
}

/// Call `f` with the linear index of the first and the last cell of each row of the
/// 3 × 3 block around `c` (wrapped around the box): the three cells of a row are
/// consecutive in memory, so their ends name every cache line the row touches (the
/// middle alone misses the second line of the one row in eight that straddles two).
#[inline(always)]
fn for_rows(grid: &CellGrid, c: [u32; 2], mut f: impl FnMut(usize)) {
    let [nx, ny] = grid.n;
    let below = if c[1] == 0 { ny - 1 } else { c[1] - 1 };
    let above = if c[1] + 1 == ny { 0 } else { c[1] + 1 };
    let left = if c[0] == 0 { nx - 1 } else { c[0] - 1 };
    let right = if c[0] + 1 == nx { 0 } else { c[0] + 1 };
    for cy in [below, c[1], above] {
        let row = cy as usize * nx as usize;
        f(row + left as usize);
        f(row + right as usize);
    }
}
