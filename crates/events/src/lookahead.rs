//! Fetching ahead: start loading the memory the next events will read.
//!
//! At large N the engine's state is far bigger than the processor's caches and
//! events land at random places, so nearly every record, cell-list entry and row of
//! cell heads an event reads is a cache miss, and each miss holds up the processor
//! for a main-memory round trip. The calendar knows which discs have events in the
//! next buckets (about two collisions per bucket), so the loads are started early, in
//! stages: a stage reads only what the previous stage, one bucket earlier, started
//! to load, and starts loading what the next one will read.
//!
//! - four buckets ahead (done by the queue when it moves on): each entry's disc
//!   record, whose event time tells whether the entry is still current, and which
//!   holds the disc's cell, list link and pair candidate;
//! - three buckets ahead (entries already stale skipped from here on): each disc's
//!   label;
//! - two buckets ahead: the partner's record and label, for a pair event, and the
//!   rows of cell heads of the disc's 3 × 3 block;
//! - one bucket ahead: the records of the first disc of each cell of that block,
//!   and the rows of cell heads of the partner's block;
//! - the current bucket: the first discs of the partner's block.
//!
//! For a cell crossing the block is the one around the cell being entered, which
//! holds the three cells the crossing scans. Only hints are issued here: nothing
//! read changes what the engine computes, and stale entries cost only a wasted load.
//!
//! What it costs (η = 0.5, `examples/profile`, CPU time per collision): forced on at
//! N = 10⁴, where it is not needed, it adds about 0.17 µs to 0.48 µs; calling it a
//! second time at once, with everything it reads already in L1, adds 0.10 µs, so
//! about 0.1 µs is its own work and the rest waiting for memory. At N = 10⁶ a
//! collision still reads about 18 cache lines that miss the last-level cache
//! (cachegrind, which ignores prefetches): 7.7 in `predict`'s scans, 5.4 in the
//! look-ahead's own reads, 2.0 filing into calendar slots, 1.9 in `next_event`,
//! 1.3 in the rest. (Measured before the stale entries were skipped three buckets
//! ahead and before the empty-cell choice lost its branch, which took the
//! look-ahead from 16 to 9 mispredicted branches per collision under cachegrind's
//! branch simulation.)
//!
//! All stages run at once, when the queue moves on. Spreading them over the
//! events of a bucket instead (one stage per event, the current bucket's first, so
//! that fewer loads are asked for at once) was slower: median 0.85 of 4
//! alternating pairs at N = 10⁶, and 0.76 in one run with the farthest stage first.
//!
//! Measured with the two builds running side by side, one on each core (which
//! cancels most of the shared machine's drift: two runs of one build agree within
//! ±3 %), at N = 10⁶, η = 0.5, medians of 6–8 runs: leaving out the current
//! bucket's stage (the partner's block) costs 12 % (0.88); issuing the stages
//! nearest first instead of farthest first, 6 % (0.94); fetching for a crossing
//! only the strip of three cells its scan reads, instead of the whole block around
//! the cell it enters, 10 % (0.90: the disc's next events read the rest). Hints
//! into L2 only for the stages two or more buckets ahead (1.01) and the second
//! disc of each cell of the current bucket's blocks (0.99) made no measurable
//! difference.
//!
//! A calendar slot names only its first seven discs; a crowded bucket's further
//! entries (7 % of the events at N = 10⁶, η = 0.5) sit in a chunk and are not
//! fetched ahead. Following the chunk as well (its line fetched a bucket before it
//! is read) gave 1.02–1.04 at N = 10⁶ (medians of 8–10 side-by-side runs, two
//! variants) and was not kept; doing it in the queue's own advance, which runs at
//! every N, cost N = 10⁴ (0.93, 8 runs).
//!
//! At N = 10⁶ what it loads counts more than what it computes: leaving out
//! needless loads (the stale entries) gave +14 %, adding loads of the second disc
//! of each cell cost 5 %, and the cheaper branches made no measurable difference
//! there. `perf` then finds the look-ahead waiting on its own reads of lines it
//! asked for a bucket earlier (the cell heads in `for_block`, the partner's cell),
//! as if some requests were still queued or had been dropped when they were due.
//!
//! Halving the cell-list records to 8 bytes (singly linked lists, see
//! [`crate::cells`]) took the lines missing the last-level cache from 18.1 to 15.7
//! per collision (cachegrind, 32 MB LL, a 5·10⁵-collision run less an empty one)
//! and gave about +5 % at N = 10⁶ (12 alternating pairs). What remains is mostly
//! the records of the discs a scan reads (5.9 lines per collision, of which the
//! look-ahead prefetches the first disc of each cell), the event discs' own records
//! and the queue's event times. Reading the scans from a separate array of
//! 32-byte paths (r − v t, v) instead cut the first item to 4.2 lines but added
//! 1.2 lines of path writes per collision and was no faster.
//! Moving the 8-byte link into the disc's own record (room made by storing the
//! path's origin in place of a position and a last-update time) took them from
//! 25.9 to 20.9 per collision (cachegrind, 8 MB LL, fetching ahead forced on, as
//! below) and gave +10 % at N = 10⁶ and +4 % at 10⁴ (medians of 6 alternating
//! pairs). With the link there, fetching the second disc of each cell (its number
//! is in the first disc's record) was still slower: −6 % at N = 10⁶ (median of 8
//! alternating pairs). Measured again at η = 0.7, where a cell holds 0.89 discs
//! on average and second discs are commoner (the event disc's block, seconds
//! fetched in the current bucket from the first discs fetched a bucket earlier):
//! 0.984 ± 0.013 at η = 0.7 and 0.960 ± 0.015 at η = 0.5 (geometric means of 150
//! pairs of 10⁵-collision windows alternating in one process).
//!
//! The test machine's 32 MB last-level cache is shared: a pointer chase
//! (`examples/memlat`) finds 16–22 ns per random load up to 4 MB, 35–55 ns at 5–6 MB
//! and 105–200 ns from 7 MB on, so a process gets only about 4–6 MB of it.
//! Simulated with an 8 MB last-level cache, a collision at N = 10⁶ misses it 25.9
//! times (3689 instructions); with every prefetch turned into a plain load, about
//! 8.5 of its misses are still not covered by the look-ahead.
//!
//! That last figure did not hold up when measured again with the event times in
//! the records (N = 3·10⁵, 1 MB simulated last-level cache, fetching ahead forced
//! on, a 2·10⁵-collision run less an empty one). Counting every disc a scan reads
//! first in a cell against the look-ahead's own list shows 97 % of them named by
//! it at most 8 events before (a second disc in a cell is rare: 0.19 per
//! collision against 14 first discs). With the first discs fetched ahead through
//! an ordinary read of the record, and the other hints turned into one-byte reads,
//! the look-ahead reads 18.3 missing lines per collision and everything else only
//! 1.4, of which the first discs of cells 0.33. (With the first discs read through
//! the same one-byte read as the other hints, cachegrind counted most of them
//! missing again in the scan, 6.4 per collision; that build is the odd one out
//! and is not understood.) What is left at N = 10⁶ is therefore the cost of
//! fetching about 20 lines per collision and the look-ahead's own 650
//! instructions, not lines it fails to name: covering the rest (the partner of a
//! crossing's candidate, and no label for a crossing, which never reports) gave
//! medians of 1.04, 1.00 and 0.995 (η = 0.7) in three sets of 6–8 side-by-side
//! runs. Buckets half and one and a half times as wide (fetching ahead over less
//! and more time) gave 0.92 and 0.87 (6 runs each).
//!
//! Nor does fetching fewer lines help much. Each of the following gave the same
//! trajectory; medians of 8 side-by-side runs at N = 10⁶, η = 0.5, with per-run
//! ratios spread over about ±10 %:
//! - A build that reports internal indices and never reads or fetches the labels
//!   (2 lines per collision fewer) ran at 0.98: an upper bound for keeping the
//!   label in the record.
//! - Calendar entries tagged with the disc's filing count mod 256, checked against
//!   a 1-byte-per-disc array, so that stale entries' records are not fetched four
//!   buckets ahead: 0.94, and 0.93 with the counts of the event discs fetched ahead
//!   too (mean 1.00). Filing now reads that array at a random place.
//! - Stages three and two deferred to the event after the queue moves on, to halve
//!   the burst of loads: 0.94.
//! - The partner's chain one bucket earlier (its record three buckets ahead, its
//!   rows two, its first discs one, so that no stage runs for the current bucket):
//!   0.92 (per-run ratios 0.84–1.00). Loads asked for earlier are not the cure.
//! - The partner's rows and first discs left out for a pair prediction already
//!   obsolete (the partner's counter, in the record fetched a bucket earlier, has
//!   moved on; 0.18 such events per collision at η = 0.5, 0.32 at η = 0.7, each
//!   recomputed from the disc's own block): 0.994 ± 0.014 at η = 0.7 (geometric
//!   mean of 150 pairs of 10⁵-collision windows alternating in one process, so
//!   that both settings see the same state and nearly the same machine).
//!
//! `perf` at N = 10⁶ (cpu-clock) puts 21 % of the time in the look-ahead and 8 %
//! in filing, and most of their samples on prefetch instructions: the label
//! hints of stage three, the first row hint of stage two, and the calendar slot
//! hint in `EventQueue::file` (73 % of filing's samples). A prefetch waits when no
//! miss buffer is free. So the time at N = 10⁶ goes into keeping many loads in
//! flight, and removing a few of them only moves the wait to the next one.

use crate::cells::{CellGrid, NONE};
use crate::engine::{Body, Engine, KIND_CELL, KIND_PAIR};
use crate::memory::prefetch_at;

/// The first guess of whether fetching ahead pays for N discs: only once the state
/// (about 160 bytes per disc) outgrows the cache the process gets; below that the
/// loads hit the cache anyway and the extra work only costs time. Measured with
/// `examples/profile` at η = 0.5 on the 2-core test machine on a quiet day, in
/// collisions per second of CPU time, without → with:
/// N = 10⁴ 2.09 → 1.50 M; 10⁵ 1.67 → 1.41 M; 1.5·10⁵ 1.40 → 1.33 M;
/// 2·10⁵ 1.05 → 1.31 M; 3·10⁵ 0.97 → 1.27 M; 10⁶ 0.77 → 1.10 M.
/// On a day when other tenants held most of the shared L3 (`examples/memlat`: 4–6 MB
/// left) the crossover was near 3·10⁴ instead, and 10⁵ ran at 0.62 without against
/// 1.17 M/s with (medians of 8 alternating pairs). So from [`TUNED_FROM`] discs on,
/// a [`Tuner`] times both settings and keeps the faster.
pub(crate) fn worthwhile(n: usize) -> bool {
    n >= 170_000
}

/// Systems of at least this many discs have fetching ahead chosen by timing
/// ([`Tuner`]); smaller ones (under 3.2 MB of state, which any cache this engine
/// runs on holds) never fetch ahead.
pub(crate) const TUNED_FROM: usize = 20_000;

/// Events per timed window (about 0.05 s at N = 10⁶).
const WINDOW: u64 = 1 << 16;

/// Windows kept with the chosen setting after a first trial, before both are timed
/// again; doubled each time the same setting wins again, up to [`MAX_KEEP`]. (At
/// N = 10⁶ the setting that loses is 2× slower, so two trial windows in 64 would
/// cost 3 %; after a few trials two in 516 cost 0.4 %.)
const KEEP: u32 = 60;

/// The longest run of kept windows (about 25 s at N = 10⁶).
const MAX_KEEP: u32 = 512;

/// Chooses whether to fetch ahead by timing it: four windows of [`WINDOW`] events
/// (on, off, off, on), then the faster setting for a while, and again. Each setting
/// is judged by the shorter of its two windows, so a one-off pause in one window (the
/// caller writing a checkpoint, the process descheduled) does not decide the trial;
/// the engine's own renumbering is not charged to any window
/// ([`Tuner::exclude`]). The setting only changes speed, never the trajectory, so
/// the choice may depend on the clock. Wall-clock windows of equal event counts are
/// compared; all four see the same machine within a fifth of a second.
#[derive(Debug, Clone)]
pub(crate) struct Tuner {
    /// Events left in the current window; `u64::MAX` when not tuning.
    pub(crate) left: u64,
    phase: Phase,
    /// Start of the current window.
    started: Option<std::time::Instant>,
    /// The shorter window (s) so far of this trial, [with, without] fetching ahead.
    best: [f64; 2],
    /// Windows to keep the winner of the next trial for.
    keep: u32,
    /// The winner of the last trial.
    last_winner: Option<bool>,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Phase {
    /// The first window: not timed (caches and calendar settle).
    Warm,
    /// Trial window k (0–3) of the settings on, off, off, on.
    Trial(u8),
    /// Keeping the chosen setting for this many more windows.
    Keep(u32),
}

/// The setting of each trial window: on, off, off, on (a drift in speed during the
/// trial weighs on both settings alike).
const TRIAL: [bool; 4] = [true, false, false, true];

impl Tuner {
    /// A tuner for `n` discs: active from [`TUNED_FROM`] discs on.
    pub(crate) fn new(n: usize) -> Tuner {
        Tuner {
            left: if n >= TUNED_FROM { WINDOW } else { u64::MAX },
            phase: Phase::Warm,
            started: None,
            best: [f64::INFINITY; 2],
            keep: KEEP,
            last_winner: None,
        }
    }

    /// A tuner that never changes the setting (the caller chose it).
    pub(crate) fn off() -> Tuner {
        Tuner {
            left: u64::MAX,
            ..Tuner::new(0)
        }
    }

    /// Whether windows are being timed.
    pub(crate) fn active(&self) -> bool {
        self.left != u64::MAX
    }

    /// Leave `pause` (wall-clock time spent on something other than events, such as
    /// a renumbering of the discs) out of the current window.
    pub(crate) fn exclude(&mut self, pause: std::time::Duration) {
        if let Some(t) = self.started.as_mut() {
            *t += pause;
        }
    }

    /// The window just ended at `now` with setting `current`: the setting for the
    /// next one.
    pub(crate) fn next_window(&mut self, now: std::time::Instant, current: bool) -> bool {
        let seconds = self
            .started
            .map_or(0.0, |t| now.saturating_duration_since(t).as_secs_f64());
        self.started = Some(now);
        self.left = WINDOW;
        self.step(seconds, current)
    }

    /// The window just ended took `seconds` with setting `current`: the next
    /// setting.
    fn step(&mut self, seconds: f64, current: bool) -> bool {
        let (phase, on) = match self.phase {
            Phase::Warm | Phase::Keep(0) => {
                self.best = [f64::INFINITY; 2];
                (Phase::Trial(0), TRIAL[0])
            }
            Phase::Trial(k) => {
                let slot = &mut self.best[usize::from(!TRIAL[k as usize])];
                *slot = slot.min(seconds);
                if (k as usize) + 1 < TRIAL.len() {
                    (Phase::Trial(k + 1), TRIAL[k as usize + 1])
                } else {
                    let winner = self.best[0] < self.best[1];
                    self.keep = if self.last_winner == Some(winner) {
                        (2 * self.keep).min(MAX_KEEP)
                    } else {
                        KEEP
                    };
                    self.last_winner = Some(winner);
                    (Phase::Keep(self.keep), winner)
                }
            }
            Phase::Keep(k) => (Phase::Keep(k - 1), current),
        };
        self.phase = phase;
        on
    }
}

impl Engine {
    /// Start loading what the events of the next buckets will read (see the module
    /// docs). Called when the queue moves on to another bucket. Kept out of line, so
    /// that profiles show its share (inlining it made no measurable difference).
    #[inline(never)]
    pub(crate) fn look_ahead(&self) {
        let grids = &self.grids;
        // Each disc's blocks lie in the grid of its size class (the only one for
        // equal discs); the scans of other classes' grids are not fetched ahead.
        let grid_of = |b: &Body| grids.get(grids.class(b.species));
        let bodies = self.bodies.as_slice();
        let last = self.bodies.len() - 1;
        // The first disc of a cell, or (for an empty cell) the last disc: a needless
        // but harmless load, cheaper than a branch on emptiness. (Chosen with
        // `select_unpredictable`: `min` compiled to a branch, and whether a cell is
        // empty is a coin toss; cachegrind at N = 10⁴, look-ahead forced on: 7 fewer
        // mispredicted branches per collision, 1.38 → 1.66 M/s median of 9.)
        let fetch_first = |head: u32| {
            let h = std::hint::select_unpredictable(head == NONE, last, head as usize);
            prefetch_at(&self.bodies, h);
        };
        // Stale entries (about 4 in 10: every collision leaves the partner's old
        // entry behind) are skipped already here: their loads would only
        // compete with the useful ones for the processor's miss buffers (N = 10⁶:
        // 1.06 → 1.16 M/s, median of 7 alternating runs). Now that the records
        // come a bucket earlier and only labels are fetched here, skipping still
        // pays: labels of every entry without the check, 0.94 (8 side by side).
        for d in self.queue.filed_ahead(bodies, 3) {
            prefetch_at(&self.label, d as usize);
        }
        for d in self.queue.filed_ahead(bodies, 2) {
            let b = &self.bodies[d as usize];
            if b.kind == KIND_PAIR {
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
            if b.kind == KIND_PAIR {
                let p = b.partner as usize;
                let grid = grid_of(&self.bodies[p]);
                for_rows(grid, self.bodies[p].link.coords(), |k| {
                    prefetch_at(&grid.head, k)
                });
            }
        }
        for d in self.queue.in_current_bucket(bodies) {
            let b = &self.bodies[d as usize];
            if b.kind == KIND_PAIR {
                let p = b.partner as usize;
                let grid = grid_of(&self.bodies[p]);
                for_block(grid, self.bodies[p].link.coords(), fetch_first);
            }
        }
    }
}

/// The cell around which the disc with record `b` will search at its pending event:
/// its own, or for a crossing the cell it enters (wrapped on a periodic axis).
#[inline]
fn event_cell(grid: &CellGrid, b: &Body) -> [u32; 2] {
    let mut c = b.link.coords();
    if b.kind == KIND_CELL {
        let k = ((b.aux & 3) / 2) as usize;
        let n = grid.n[k];
        c[k] = if b.aux & 1 == 1 {
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

/// Call `f` with the head (first disc or `NONE`) of each cell of the 3 × 3 block
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
/// middle alone misses the second line of the one row in eight that straddles two;
/// naming both gave +2.7 % at N = 10⁶ in one comparison of five alternating runs,
/// within the noise of later ones).
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

#[cfg(test)]
mod tests {
    use super::*;

    /// Feed `tuner` windows lasting `on(k)` s with fetching ahead and `off` s
    /// without (k counts the windows); the settings it chose for each of `windows`
    /// windows.
    fn run_with(
        tuner: &mut Tuner,
        on: impl Fn(usize) -> f64,
        off: f64,
        windows: usize,
    ) -> Vec<bool> {
        let mut setting = false;
        let mut chosen = Vec::new();
        for k in 0..windows {
            let seconds = if setting { on(k) } else { off };
            setting = tuner.step(seconds, setting);
            chosen.push(setting);
        }
        chosen
    }

    fn run(tuner: &mut Tuner, on: f64, off: f64, windows: usize) -> Vec<bool> {
        run_with(tuner, |_| on, off, windows)
    }

    #[test]
    fn keeps_the_faster_setting_and_tries_both_again() {
        // Warm, then the four trial windows and KEEP + 1 windows of the winner, and
        // again.
        let period = KEEP as usize + 5;
        let faster_on = run(&mut Tuner::new(TUNED_FROM), 0.1, 0.2, 3 * period);
        assert_eq!(&faster_on[..4], &TRIAL);
        assert!(faster_on[4..period].iter().all(|&s| s));
        assert_eq!(&faster_on[period..period + 4], &TRIAL);
        // The same winner again: kept twice as long before the next trial.
        assert!(faster_on[period + 4..period + 5 + 2 * KEEP as usize]
            .iter()
            .all(|&s| s));
        let faster_off = run(&mut Tuner::new(TUNED_FROM), 0.3, 0.2, 2 * period);
        assert_eq!(&faster_off[..4], &TRIAL);
        assert!(faster_off[4..period].iter().all(|&s| !s));
        assert_eq!(&faster_off[period..period + 4], &TRIAL);
        assert!(faster_off[period + 4..].iter().all(|&s| !s));
    }

    #[test]
    fn one_slow_window_does_not_decide_a_trial() {
        // Fetching ahead is twice as fast, but the first window with it on takes
        // ten times as long (a pause that had nothing to do with the setting).
        let mut tuner = Tuner::new(TUNED_FROM);
        let chosen = run_with(&mut tuner, |k| if k == 1 { 2.0 } else { 0.1 }, 0.2, 10);
        assert_eq!(tuner.last_winner, Some(true));
        assert!(chosen[4..].iter().all(|&s| s));
    }

    #[test]
    fn an_excluded_pause_is_not_charged_to_the_window() {
        let mut tuner = Tuner::new(TUNED_FROM);
        let t0 = std::time::Instant::now();
        tuner.next_window(t0, false);
        tuner.exclude(std::time::Duration::from_secs(5));
        // The window ends 5.01 s after it began, 5 s of which were excluded.
        tuner.next_window(t0 + std::time::Duration::from_millis(5010), true);
        assert!((tuner.best[0] - 0.01).abs() < 1e-9, "{:?}", tuner.best);
    }

    #[test]
    fn a_change_of_winner_shortens_the_keep_again() {
        let mut tuner = Tuner::new(TUNED_FROM);
        run(&mut tuner, 0.1, 0.2, 3 * KEEP as usize);
        assert!(tuner.keep > KEEP);
        // Off is now faster: at the first trial it wins, the keep starts over.
        let mut windows = 0;
        while tuner.last_winner != Some(false) {
            run(&mut tuner, 0.3, 0.2, 1);
            windows += 1;
            assert!(windows <= MAX_KEEP as usize + 5, "no trial within a keep");
        }
        assert_eq!(tuner.keep, KEEP);
    }

    #[test]
    fn small_systems_and_chosen_settings_are_not_tuned() {
        assert!(!Tuner::new(TUNED_FROM - 1).active());
        assert!(!Tuner::off().active());
        assert_eq!(Tuner::new(TUNED_FROM).left, WINDOW);
        assert!(Tuner::new(TUNED_FROM).active());
    }
}
