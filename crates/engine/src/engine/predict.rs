//! Prediction: each disc's earliest event, and the neighbour scan that finds it.
//!
//! A disc's next event is the earliest of its cell crossing, its wall collision
//! (x + v t = a or L − a) and its pair collisions with the discs of its 3 × 3 block
//! (and of the cells within reach in other size classes' grids), each at the smaller
//! root of |Δr + Δv t| = σ with Δr·Δv < 0 (physics.md §2). The earliest pair is kept
//! as the *pair candidate* even while a crossing or wall comes first: a crossing
//! changes no velocity, so after it only the three newly adjacent cells are scanned,
//! and the candidate (its time recomputed from the unchanged paths) stands for the
//! six seen before unless its partner changed velocity since. Hot comparisons are
//! branch-free (which neighbour wins is a coin toss); contact and boundary times
//! are the law of motion's (engine::motion); on neighbour lists `predict` hands
//! over to engine::listed. See docs/performance.md, "neighbour scan".

use super::body::{Aux, Body, Face, Image, Pending};
use super::motion::Motion;
use super::{time_key, Engine};
use crate::classes::cells_along;
use crate::NO_DISC;
use carom_core::boundary::wall_time;
use carom_core::{Boundary, DVec2, Species, WallSide};

#[inline]
pub(super) fn neighbour(c: u32, o: i32, n: u32, periodic: bool) -> Option<(u32, i32)> {
    let v = c as i32 + o;
    if v < 0 {
        periodic.then(|| ((v + n as i32) as u32, -1))
    } else if v >= n as i32 {
        periodic.then(|| ((v - n as i32) as u32, 1))
    } else {
        Some((v as u32, 0))
    }
}

/// The earliest pair event found so far by a prediction: time from now, partner
/// and the image through which the partner is seen.
pub(super) struct Found {
    pub(super) best: f64,
    pub(super) partner: u32,
    pub(super) image: Image,
}

impl Found {
    /// Nothing found yet: no partner, time +∞.
    pub(super) const NOTHING: Found = Found {
        best: f64::INFINITY,
        partner: NO_DISC,
        image: Image::UNSET,
    };
}

/// Disc `i` as a scan sees it: its record, its radius (length) and its position
/// now (length), shifted to see the scanned cell through the right image.
pub(super) struct Scanner<'a> {
    pub(super) bi: &'a Body,
    pub(super) radius: f64,
    pub(super) ri: DVec2,
}

/// Test disc `j` (record `bj`) against disc i and keep it in `found` if it meets
/// earlier than the best so far, by the law of motion `M` (`law` its state now);
/// `image` is the image through which j's cell is seen.
///
/// Disc i itself needs no test of its own: its relative velocity is exactly zero,
/// so b = 0 and it never meets (whichever image is seen); growing, it is skipped
/// by its zero separation. A full scan of an interior block passes it over
/// ([`Block::scan_own_cell`]); elsewhere it is tested and never wins.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub(super) fn test_pair<M: Motion>(
    me: &Scanner,
    species: &[Species],
    j: u32,
    bj: &Body,
    now: f64,
    law: M::Scan,
    image: Image,
    found: &mut Found,
) {
    let dr = bj.at(now) - me.ri;
    let sigma = me.radius + species[bj.species as usize].radius;
    let dt = M::pair_time(me.bi, me.ri, bj, dr, sigma, now, law);
    count!(PairTests);
    count!(PairApproaching, dr.dot(bj.v - me.bi.v) < 0.0);
    count!(PairMeets, dt.is_finite());
    // Kept without a branch: whether a neighbour beats the best so far is a coin
    // toss for the branch predictor.
    let hit = dt < found.best;
    found.best = std::hint::select_unpredictable(hit, dt, found.best);
    found.partner = std::hint::select_unpredictable(hit, j, found.partner);
    found.image = std::hint::select_unpredictable(hit, image, found.image);
}

/// The neighbour search's view of the engine: disc records (with the cell lists'
/// links), species and the current time; the cells' first discs come from whichever
/// grid is scanned.
struct Block<'a, M: Motion> {
    bodies: &'a [Body],
    species: &'a [Species],
    now: f64,
    /// The law of motion's state now.
    law: M::Scan,
}

impl<M: Motion> Block<'_, M> {
    /// Look for the earliest collision (before `found.best`) of the disc `me` with the
    /// discs of the cell whose list starts at `first`, seen through the image with
    /// `image`.
    #[inline(always)]
    fn scan_cell(&self, me: &Scanner, first: u32, image: Image, found: &mut Found) {
        let mut j = first;
        count!(CellsWalked);
        count!(CellsEmpty, first == NO_DISC);
        while j != NO_DISC {
            let bj = &self.bodies[j as usize];
            test_pair::<M>(me, self.species, j, bj, self.now, self.law, image, found);
            j = bj.link.next;
        }
    }

    /// [`Self::scan_cell`] for the scanning disc's own cell, whose list starts at
    /// `first` and holds disc `i` (`me.bi`): the same discs in the same order, so
    /// ties go to the same partner, with disc `i` itself passed over (its test
    /// never meets). Its test would take the contact solve's branch for
    /// overlapping pairs (c ≤ 0), at a random place in every block: skipped, that
    /// branch is almost never taken (docs/performance.md, "the self-test").
    #[inline(always)]
    fn scan_own_cell(&self, me: &Scanner, first: u32, i: u32, found: &mut Found) {
        let mut j = first;
        while j != i && j != NO_DISC {
            let bj = &self.bodies[j as usize];
            test_pair::<M>(
                me,
                self.species,
                j,
                bj,
                self.now,
                self.law,
                Image::SAME,
                found,
            );
            j = bj.link.next;
        }
        if j == i {
            self.scan_cell(me, me.bi.link.next, Image::SAME, found);
        }
    }
}

impl Engine {
    /// Find disc `i`'s earliest event from the current time and queue it: its next
    /// cell crossing or wall collision, or its earliest pair collision with a disc
    /// of its 3 × 3 block of cells (which becomes its pair candidate).
    pub(super) fn predict<M: Motion>(&mut self, i: usize) {
        if M::LISTS {
            return self.predict_listed::<M>(i);
        }
        count!(FullPredictions);
        let now = self.clock;
        let bi = self.bodies[i];
        let ri = bi.at(now);
        let mut found = Found::NOTHING;
        self.scan::<M>(i, ri, [-1, 1], [-1, 1], &mut found);
        if !self.grids.single() {
            self.scan_other_classes::<M>(i, ri, &mut found);
        }
        let boundary = M::boundary_event(self, i, ri, bi.v);
        self.file_event::<M>(i, &found, boundary);
    }

    /// Make disc `i`'s earliest event pending and queue it: the pair candidate
    /// `found`, or the boundary event (time from now, kind, face) if that comes first.
    ///
    /// The record's resting flag (engine::resting) is kept as the law says.
    #[inline(always)]
    pub(super) fn file_event<M: Motion>(
        &mut self,
        i: usize,
        found: &Found,
        (boundary, kind, face): (f64, Pending, Face),
    ) {
        // Without branches (a pair or a boundary event comes first about equally
        // often); with no partner, the count read is of a disc in memory and unused.
        let partner_count = self.bodies[(found.partner as usize).min(self.bodies.len() - 1)].count;
        let pair = found.best < boundary;
        count!(FiledPair, pair);
        count!(
            FiledCell,
            !pair && matches!(kind, Pending::Cell | Pending::Skin)
        );
        count!(
            FiledOther,
            !pair && !matches!(kind, Pending::Cell | Pending::Skin)
        );
        let b = &mut self.bodies[i];
        b.partner = found.partner;
        b.partner_count =
            std::hint::select_unpredictable(found.partner != NO_DISC, partner_count, 0);
        b.pending = std::hint::select_unpredictable(pair, Pending::Pair, kind);
        b.aux = M::file_aux(b.aux, Aux::new(face, found.image));
        self.queue.set(
            self.bodies.as_mut_slice(),
            i as u32,
            time_key(self.clock + found.best.min(boundary)),
        );
    }

    /// Disc `i`'s events after it crossed into the next cell along axis `k` (upwards
    /// if `up`) without wrapping: only the three newly adjacent cells are scanned,
    /// and the pair candidate is kept unless one of their discs meets earlier (see
    /// the module documentation).
    ///
    /// The candidate's time is not stored (the record has no room beside the
    /// pending event's time): when its partner has not changed velocity since, it is
    /// computed again, from the two paths as they are now; when the partner has, the
    /// candidate no longer says when the discs of the six cells seen before can
    /// meet, and the whole block is scanned again instead.
    pub(super) fn predict_after_crossing<M: Motion>(&mut self, i: usize, k: usize, up: bool) {
        let now = self.clock;
        let bi = self.bodies[i];
        let ri = bi.at(now);
        let mut candidate = Found::NOTHING;
        if bi.partner != NO_DISC {
            let bp = &self.bodies[bi.partner as usize];
            if bp.count != bi.partner_count {
                self.predict::<M>(i);
                return;
            }
            // Seeing the partner's image at r_j + s L is seeing i at r_i − s L.
            let image = bi.aux.image();
            let me = Scanner {
                bi: &bi,
                radius: self.species[bi.species as usize].radius,
                ri: ri - image.shift(self.sim_box.size),
            };
            test_pair::<M>(
                &me,
                &self.species,
                bi.partner,
                bp,
                now,
                M::scan(self),
                image,
                &mut candidate,
            );
        }
        count!(StripPredictions);
        let o = if up { 1 } else { -1 };
        let (xs, ys) = if k == 0 {
            ([o, o], [-1, 1])
        } else {
            ([-1, 1], [o, o])
        };
        // The strip's discs replace the candidate only when one meets earlier.
        self.scan::<M>(i, ri, xs, ys, &mut candidate);
        if !self.grids.single() {
            self.scan_other_classes::<M>(i, ri, &mut candidate);
        }
        let boundary = M::boundary_event(self, i, ri, bi.v);
        self.file_event::<M>(i, &candidate, boundary);
    }

    /// Look for disc `i`'s earliest pair collision (before `found.best`, time from
    /// now) with the discs of the cells at offsets `xs[0]..=xs[1]` along x and
    /// `ys[0]..=ys[1]` along y from its cell: the whole 3 × 3 block, or the strip of
    /// three cells a crossing brings next to it, in the grid of its size class. `ri`
    /// is its position now.
    ///
    /// Each cell is walked behind a branch on its emptiness (see
    /// docs/performance.md, "neighbour scan").
    #[inline(always)]
    fn scan<M: Motion>(&self, i: usize, ri: DVec2, xs: [i32; 2], ys: [i32; 2], found: &mut Found) {
        let grid = self.grids.get(self.grids.class(self.bodies[i].species));
        let block = self.block::<M>();
        let bi = &self.bodies[i];
        let radius = self.species[bi.species as usize].radius;
        let c = bi.link.coords();
        let [nx, ny] = grid.n;
        let head = grid.head.as_slice();
        if c[0] >= 1 && c[0] + 1 < nx && c[1] >= 1 && c[1] + 1 < ny {
            // Interior cell (almost all of them): no image shifts, and each row of
            // the block is consecutive cells.
            let me = Scanner { bi, radius, ri };
            let nx = nx as usize;
            let first = (c[1] as i32 + ys[0]) as usize * nx + (c[0] as i32 + xs[0]) as usize;
            if xs == [-1, 1] && ys == [-1, 1] {
                let heads = [
                    head[first],
                    head[first + 1],
                    head[first + 2],
                    head[first + nx],
                    head[first + nx + 1],
                    head[first + nx + 2],
                    head[first + 2 * nx],
                    head[first + 2 * nx + 1],
                    head[first + 2 * nx + 2],
                ];
                // The middle cell is disc i's own.
                for h in &heads[..4] {
                    block.scan_cell(&me, *h, Image::SAME, found);
                }
                block.scan_own_cell(&me, heads[4], i as u32, found);
                for h in &heads[5..] {
                    block.scan_cell(&me, *h, Image::SAME, found);
                }
            } else {
                // A strip: a column (x crossing) or a row (y crossing) of three.
                let stride = if xs[0] == xs[1] { nx } else { 1 };
                let heads = [head[first], head[first + stride], head[first + 2 * stride]];
                for h in heads {
                    block.scan_cell(&me, h, Image::SAME, found);
                }
            }
        } else {
            let size = self.sim_box.size;
            // The (up to) three columns: index, image shift along x, shift sign.
            let mut col_list = [(0usize, 0.0f64, 0i32); 3];
            let mut ncols = 0;
            for ox in xs[0]..=xs[1] {
                if let Some((cx, sx)) = neighbour(c[0], ox, nx, grid.periodic[0]) {
                    col_list[ncols] = (cx as usize, sx as f64 * size.x, sx);
                    ncols += 1;
                }
            }
            for oy in ys[0]..=ys[1] {
                let Some((cy, sy)) = neighbour(c[1], oy, ny, grid.periodic[1]) else {
                    continue;
                };
                let row = cy as usize * nx as usize;
                let shift_y = sy as f64 * size.y;
                for &(cx, shift_x, sx) in &col_list[..ncols] {
                    // Seeing j's image at r_j + s L is seeing i at r_i − s L.
                    let me = Scanner {
                        bi,
                        radius,
                        ri: DVec2::new(ri.x - shift_x, ri.y - shift_y),
                    };
                    block.scan_cell(&me, head[row + cx], Image::new(sx, sy), found);
                }
            }
        }
    }

    /// The neighbour search's view of the engine now (see [`Block`]).
    #[inline(always)]
    fn block<M: Motion>(&self) -> Block<'_, M> {
        Block {
            bodies: &self.bodies,
            species: &self.species,
            now: self.clock,
            law: M::scan(self),
        }
    }

    /// Look for disc `i`'s earliest pair collision (before `found.best`, time from
    /// now) with the discs of the other size classes: in each other class's grid,
    /// every cell meeting disc i's own cell widened by its reach into that class
    /// (see [`crate::classes`]). `ri` is its position now.
    ///
    /// Never with growing discs, which share one grid (engine::growth).
    fn scan_other_classes<M: Motion>(&self, i: usize, ri: DVec2, found: &mut Found) {
        let block = self.block::<M>();
        let bi = &self.bodies[i];
        let radius = self.species[bi.species as usize].radius;
        let own_class = self.grids.class(bi.species);
        let own = self.grids.get(own_class);
        let c = bi.link.coords();
        let size = self.sim_box.size;
        for (class, grid) in self.grids.iter().enumerate() {
            let class = class as u8;
            if class == own_class {
                continue;
            }
            let reach = self.grids.reach(radius, class);
            let span = |k: usize| {
                let lo = c[k] as f64 * own.width[k] - reach;
                let hi = (c[k] + 1) as f64 * own.width[k] + reach;
                cells_along(grid, k, lo, hi)
            };
            let nx = grid.n[0] as usize;
            for (cy, sy) in span(1) {
                for (cx, sx) in span(0) {
                    // Seeing j's image at r_j + s L is seeing i at r_i − s L.
                    let me = Scanner {
                        bi,
                        radius,
                        ri: DVec2::new(ri.x - sx as f64 * size.x, ri.y - sy as f64 * size.y),
                    };
                    let first = grid.head[cy as usize * nx + cx as usize];
                    block.scan_cell(&me, first, Image::new(sx, sy), found);
                }
            }
        }
    }

    /// Disc `i`'s earliest cell crossing or wall collision from now: (time from now,
    /// kind, face), in the grid of its size class. `ri` is its position
    /// now, `v` its velocity.
    #[inline(always)]
    pub(super) fn boundary_event_straight(
        &self,
        i: usize,
        ri: DVec2,
        v: DVec2,
    ) -> (f64, Pending, Face) {
        let mut best = f64::INFINITY;
        let (mut kind, mut face) = (Pending::None, Face::new(0, false));
        let c = self.bodies[i].link.coords();
        let grid = self.grids.get(self.grids.class(self.bodies[i].species));
        for k in 0..2 {
            // Without branches: which axis is crossed first is a coin toss.
            let (dt, up) = grid.crossing_time(k, c[k], ri[k], v[k]);
            let hit = dt < best;
            best = std::hint::select_unpredictable(hit, dt, best);
            kind = std::hint::select_unpredictable(hit, Pending::Cell, kind);
            face = std::hint::select_unpredictable(hit, Face::new(k, up), face);
            self.earlier_wall(i, k, ri[k], v[k], (&mut best, &mut kind, &mut face));
        }
        (best, kind, face)
    }

    /// Make disc `i`'s hit of a wall normal to axis `k` (coordinate `x` now,
    /// velocity `v` along it) the boundary event `(best, kind, face)` if the axis
    /// is walled and the hit comes first (2.6).
    #[inline(always)]
    pub(super) fn earlier_wall(
        &self,
        i: usize,
        k: usize,
        x: f64,
        v: f64,
        (best, kind, face): (&mut f64, &mut Pending, &mut Face),
    ) {
        if let Boundary::Walls { .. } = self.sim_box.boundary[k] {
            let radius = self.species[self.bodies[i].species as usize].radius;
            if let Some((dt, side)) = wall_time(x, v, radius, self.sim_box.size[k]) {
                if dt < *best {
                    *best = dt;
                    *kind = Pending::Wall;
                    *face = Face::new(k, side == WallSide::High);
                }
            }
        }
    }
}
