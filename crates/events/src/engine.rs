//! The event loop.
//!
//! Each disc keeps its state as of its own last update ("delayed states",
//! physics.md §1), stored as its straight path r(t) = r0 + v t on the internal
//! clock rather than as a position and a last-update time (see the `Body` record
//! in the source; the two are the same line), and owns exactly one pending event:
//! the earliest of its next pair collision, wall collision and cell crossing, found
//! by scanning the 3 × 3 block of cells around it (and, in a mixture of very
//! different sizes with a grid per size class, the cells of the other classes'
//! grids within reach: [`crate::classes`]). An event moves only the discs it
//! touches: a velocity change moves the path's origin so that the path passes
//! through the disc's position at that instant.
//!
//! A pending pair event remembers the partner's collision counter at prediction
//! time; every velocity change (and every periodic wrap) bumps a disc's counter, so
//! a prediction made obsolete by the partner's other collisions is recognised when it
//! reaches the head of the queue and is simply recomputed. The earliest true event is
//! always in the queue: of the two discs of any pair, the one updated last scanned the
//! other with both current trajectories.
//!
//! Recomputing obsolete predictions at once instead, when the scan after a collision
//! meets a neighbour whose candidate is the disc that just changed, was measured and
//! is slower: most obsolete candidates are overtaken by another event of their own
//! disc before they come up, so it made 0.62 extra predictions per collision in place
//! of 0.19 recomputations at the head of the queue (`examples/profile`, η = 0.5;
//! N = 10⁴ 28 % slower, median of four alternating pairs).
//!
//! Each disc also keeps its *pair candidate* — the partner of the earliest pair
//! collision its last scan found — even while a cell crossing or wall comes first.
//! A crossing changes no velocity, so after it only the three newly adjacent cells
//! need a scan: a disc of the six cells seen before either meets no earlier than the
//! candidate (as that scan found, unless its velocity changed since), or changed
//! velocity since and then scanned this disc itself. The candidate's time is not
//! stored (its disc's record holds only the pending event's time): the crossing
//! computes it again from the two paths, which have not changed if the partner's
//! counter has not. A candidate made obsolete by its partner's collisions no longer
//! tells when the six cells' discs can meet, so then the whole block is scanned. A
//! crossing through a periodic edge moves the disc by a box length and changes image
//! shifts: it rescans the whole block too.
//!
//! Keeping the pending event's time in the disc's record rather than in an array of
//! the queue's (the queue reads it through [`EventTimes`]) saves a cache line per
//! disc an event touches at large N: `examples/profile`, η = 0.5, both builds side
//! by side on the two cores, medians of 6: 1.04 at N = 10⁶ (per-run ratios
//! 1.03–1.18) and 1.08 at N = 10⁴; 8 fewer bytes per disc. Obsolete predictions
//! recomputed at the head of the queue fell from 0.191 to 0.176 per collision, as
//! a crossing now replaces an obsolete candidate at once.

use crate::cells::{Link, NONE};
use crate::classes::{cells_along, Grids};
use crate::error::EngineError;
use crate::event::{Event, PairCollision, WallCollision};
use crate::lookahead;
use crate::memory;
use crate::queue::{EventQueue, EventTimes, Time};
use crate::state::State;
use carom_core::boundary::{wall_reflect, wall_time};
use carom_core::collision::resolve;
use carom_core::kinematics::contact_time_or_inf;
use carom_core::{Axis, Boundary, DVec2, Restitution, SimBox, Species, WallSide};
use ordered_float::NotNan;
use std::cmp::Reverse;
use std::collections::BinaryHeap;

/// Parameters of the dynamics.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EngineParams {
    /// Collision rule for pairs (physics.md §3–4).
    pub restitution: Restitution,
    /// TC model duration t_c (time; physics.md §4): a collision is elastic when either
    /// disc collided less than t_c ago; a wall collision counts as a collision of its
    /// disc and is elastic likewise. 0 disables it.
    pub tc: f64,
    /// Collisions allowed at one instant before the engine reports a runaway
    /// (inelastic collapse) instead of hanging.
    pub max_events_without_time_advance: u64,
}

impl Default for EngineParams {
    fn default() -> Self {
        EngineParams {
            restitution: Restitution::Elastic,
            tc: 0.0,
            max_events_without_time_advance: 100_000,
        }
    }
}

/// Running totals since the start of the run.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Stats {
    /// Pair collisions resolved.
    pub pair_collisions: u64,
    /// Wall collisions resolved.
    pub wall_collisions: u64,
    /// Cell crossings processed (internal events).
    pub cell_crossings: u64,
    /// Predictions found obsolete at the head of the queue and recomputed.
    pub stale_events: u64,
    /// Σ r_ij·Δp_i over pair collisions (physics.md §5; length·momentum).
    pub virial_sum: f64,
    /// Σ |Δp| given to each wall, indexed [axis][0 = low, 1 = high] (momentum).
    pub wall_impulse: [[f64; 2]; 2],
    /// Kinetic energy dissipated in pair and wall collisions (energy).
    pub energy_lost: f64,
}

/// Everything the event loop touches for one disc, in one 64-byte cache line: its
/// straight path (origin and velocity), collision counter, pair candidate, pending
/// event and its time, species, and its place in the cell lists. At large N every
/// event lands at a random place in memory, so keeping these together saves a cache
/// miss per lookup (measured: see benches/engine.rs), and a scan walking a cell's
/// list reads nothing but the records it tests.
///
/// The path is stored as its origin `r0`, the position the disc would have had at
/// internal time 0 on its current velocity: its position at time t is
/// `r0 + v t` (physics.md §1, with the last-update time folded into the origin).
/// That saves the 8-byte last-update time that made room for the cell link. Its
/// rounding is that of positions of the size of |r0| + |v t|, the same order as
/// the rounding of event times (≈ ulp(t)·|v|) that the clock's restarts at each
/// renumbering keep small.
#[derive(Debug, Clone, Copy, PartialEq)]
#[repr(C, align(64))]
pub(crate) struct Body {
    /// Path origin: the position at internal time 0 on the current velocity
    /// (length; may lie outside the box).
    pub r0: DVec2,
    /// Velocity (length/time).
    pub v: DVec2,
    /// Time of the pending event, the queue's key (time; +∞ if none; changed only
    /// through [`EventQueue::set`]). For a pair event it is the pair candidate's
    /// time; when a crossing or wall comes first the candidate's time is not kept
    /// (see [`Engine::predict_after_crossing`]).
    pub event_time: f64,
    /// Collision counter: bumped on every velocity change and periodic wrap.
    pub count: u32,
    /// Partner of the pair candidate ([`NONE`] if none).
    pub partner: u32,
    /// Partner's collision counter when the candidate was found.
    pub partner_count: u32,
    /// Which event is pending: one of the `KIND_*` constants (pair = the candidate).
    pub kind: u8,
    /// Bits 0–1: the boundary event — wall: 2·axis + side; cell: 2·axis + (dir > 0).
    /// Bits 2–5: the candidate's image shift code (sx+1) + 3 (sy+1).
    pub aux: u8,
    /// Species index.
    pub species: u16,
    /// Cell and next disc of the cell's list (see [`crate::cells`]).
    pub link: Link,
}

impl Body {
    /// Position at internal time `t` (length), not wrapped into the box.
    #[inline(always)]
    pub fn at(&self, t: f64) -> DVec2 {
        self.r0 + self.v * t
    }

    /// Set the velocity to `v` at internal time `now`, keeping the position there:
    /// the path origin moves by (v_old − v) now.
    #[inline]
    pub fn set_velocity(&mut self, v: DVec2, now: f64) {
        self.r0 = origin_after((self.r0, self.v), v, now);
        self.v = v;
    }
}

/// The origin (length) of a path (origin, velocity) = `path` once its velocity is
/// set to `v` at internal time `now` ([`Body::set_velocity`]).
#[inline(always)]
fn origin_after((r0, v0): (DVec2, DVec2), v: DVec2, now: f64) -> DVec2 {
    r0 + (v0 - v) * now
}

/// The queue reads each disc's event time from its record, which the event reads
/// anyway: a separate array of times cost a cache miss per disc an event touches at
/// large N.
impl EventTimes for [Body] {
    #[inline(always)]
    fn time(&self, i: u32) -> f64 {
        self[i as usize].event_time
    }
    #[inline(always)]
    fn store(&mut self, i: u32, t: f64) {
        self[i as usize].event_time = t;
    }
    #[inline(always)]
    fn prefetch(&self, i: u32) {
        memory::prefetch_at(self, i as usize);
    }
}

impl crate::cells::Member for Body {
    #[inline(always)]
    fn link(&self) -> &Link {
        &self.link
    }
    #[inline(always)]
    fn link_mut(&mut self) -> &mut Link {
        &mut self.link
    }
}

pub(crate) const KIND_NONE: u8 = 0;
pub(crate) const KIND_PAIR: u8 = 1;
pub(crate) const KIND_WALL: u8 = 2;
pub(crate) const KIND_CELL: u8 = 3;

const _: () = assert!(
    std::mem::size_of::<Body>() == 64,
    "Body must fill one cache line"
);

/// The exact event-driven engine for hard discs.
#[derive(Debug, Clone)]
pub struct Engine {
    pub(crate) sim_box: SimBox,
    pub(crate) species: Vec<Species>,
    pub(crate) bodies: Vec<Body>,
    pub(crate) last_collision: Vec<f64>,
    pub(crate) queue: EventQueue,
    /// The cell grids, one per size class (see [`crate::classes`]).
    pub(crate) grids: Grids,
    pub(crate) scheduled: BinaryHeap<Reverse<(Time, u64, u64)>>,
    pub(crate) next_seq: u64,
    pub(crate) params: EngineParams,
    /// The internal clock (time since `epoch`): every per-disc time, event time and
    /// the queue run on it, so that their rounding stays that of times since the
    /// last renumbering rather than of the whole run (see [`Engine::rebase_clock`]).
    pub(crate) clock: f64,
    /// Time of the internal clock's zero (time).
    pub(crate) epoch: f64,
    /// The current time as reported to the caller (time): `epoch + clock` rounded, or
    /// a scheduled event's own time; never decreasing.
    pub(crate) reported: f64,
    /// Collisions so far at the instant `clock` (0 when the clock last moved for
    /// another kind of event).
    pub(crate) same_time_collisions: u64,
    pub(crate) stats: Stats,
    /// External (user) index of each internal slot. (Kept instead beside each
    /// disc's event time in the queue, when the queue held the times, in 16-byte
    /// entries: +6 % at N = 10⁶ (+3 % with the release profile's fat LTO) but −3 %
    /// at 10⁴ with fat LTO, where the event times then spread over twice the memory
    /// (+1.2 misses of a 512 KiB L2 per collision, cachegrind); in packed 12-byte
    /// entries: 1.00 at 10⁶ and 0.98 at 10⁴. Medians of 6–20 runs of both builds
    /// side by side on the two cores.)
    pub(crate) label: Vec<u32>,
    /// Internal slot of each external index.
    pub(crate) index_of: Vec<u32>,
    /// Species of each disc in external order.
    pub(crate) species_of: Vec<u16>,
    /// Pair-collision count at which discs are next renumbered along the Z curve.
    pub(crate) next_reorder: u64,
    /// Whether to fetch the next events' memory ahead (see [`crate::lookahead`]).
    pub(crate) look_ahead: bool,
    /// Times fetching ahead on and off and keeps the faster.
    pub(crate) tuner: lookahead::Tuner,
    /// The largest |r0| component before the clock is restarted early (length;
    /// [`Engine::keep_origin_near`]; derived from the box and the grid).
    pub(crate) origin_limit: f64,
}

/// The limit of [`Engine::origin_limit`] for a box of edges `size` and cells of
/// edges `width` (length).
pub(crate) fn origin_limit(size: DVec2, width: DVec2) -> f64 {
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
/// (Every 4 N instead of 16 N made no measurable difference at N = 10⁶: 1.02,
/// median of 6 runs side by side with the 16 N build.)
fn reorder_interval(n: usize) -> u64 {
    (16 * n as u64).max(1 << 16)
}

/// Whether discs i and j, whose paths (origin, velocity) were `paths` before a
/// collision at internal time `now`, approach at `now` once given velocities
/// (v_i, v_j), as the neighbour scans will see them: b = Δr·Δv < 0 (physics.md §2)
/// from i's side (j's image at r_j + shift) or from j's, with the positions
/// ([`Body::at`]) of the updated paths.
#[inline(always)]
fn approaching(
    paths: [(DVec2, DVec2); 2],
    shift: DVec2,
    now: f64,
    (vi, vj): (DVec2, DVec2),
) -> bool {
    let ri = origin_after(paths[0], vi, now) + vi * now;
    let rj = origin_after(paths[1], vj, now) + vj * now;
    (rj - (ri - shift)).dot(vj - vi) < 0.0 || (ri - (rj + shift)).dot(vi - vj) < 0.0
}

/// The velocities (v_i', v_j') after an extra impulse along the contact vector `n`,
/// the smallest of a doubling sequence (starting at a relative velocity change of
/// about one ulp of the speeds) with which the pair no longer [`approaching`].
/// Momentum is kept (the two changes are m_j/M and m_i/M of one relative change);
/// the kinetic energy changes by the rounding-level work of that impulse, about
/// ε m v² relative to the pair. `None` if no finite impulse does it (the
/// collision is then left as the rule made it).
#[cold]
#[inline(never)]
fn push_apart(
    paths: [(DVec2, DVec2); 2],
    shift: DVec2,
    now: f64,
    n: DVec2,
    (vi, vj): (DVec2, DVec2),
    (mi, mj): (f64, f64),
) -> Option<(DVec2, DVec2)> {
    let speed = vi.abs().max_element().max(vj.abs().max_element());
    let (wi, wj) = (mj / (mi + mj), mi / (mi + mj));
    let mut k = (f64::EPSILON * speed / n.length_squared()).max(f64::MIN_POSITIVE);
    while k.is_finite() {
        let pushed = (vi - n * (k * wi), vj + n * (k * wj));
        if !approaching(paths, shift, now, pushed) {
            return Some(pushed);
        }
        k *= 2.0;
    }
    None
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

#[inline]
fn neighbour(c: u32, o: i32, n: u32, periodic: bool) -> Option<(u32, i32)> {
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
/// and the partner's image shift code.
struct Found {
    best: f64,
    partner: u32,
    code: u8,
}

impl Found {
    /// Nothing found yet: no partner, time +∞.
    const NOTHING: Found = Found {
        best: f64::INFINITY,
        partner: NONE,
        code: 0,
    };
}

/// Disc `i` as a scan sees it: its record, its radius (length) and its position
/// now (length), shifted to see the scanned cell through the right image.
struct Scanner<'a> {
    bi: &'a Body,
    radius: f64,
    ri: DVec2,
}

/// Test disc `j` (record `bj`) against disc i and keep it in `found` if it meets
/// earlier than the best so far; `code` is the image shift code of j's cell.
///
/// Disc i itself needs no test of its own: its relative velocity is exactly zero,
/// so b = 0 and it never meets (whichever image is seen).
#[inline(always)]
fn test_pair(
    me: &Scanner,
    species: &[Species],
    j: u32,
    bj: &Body,
    now: f64,
    code: u8,
    found: &mut Found,
) {
    let bi = me.bi;
    let dr = bj.at(now) - me.ri;
    let sigma = me.radius + species[bj.species as usize].radius;
    let dt = contact_time_or_inf(dr, bj.v - bi.v, sigma);
    // Kept without a branch: whether a neighbour beats the best so far is a coin
    // toss for the branch predictor.
    let hit = dt < found.best;
    found.best = std::hint::select_unpredictable(hit, dt, found.best);
    found.partner = std::hint::select_unpredictable(hit, j, found.partner);
    found.code = std::hint::select_unpredictable(hit, code, found.code);
}

/// The neighbour search's view of the engine: disc records (with the cell lists'
/// links), species and the current time; the cells' first discs come from whichever
/// grid is scanned.
struct Block<'a> {
    bodies: &'a [Body],
    species: &'a [Species],
    now: f64,
}

impl Block<'_> {
    /// Look for the earliest collision (before `found.best`) of the disc `me` with the
    /// discs of the cell whose list starts at `first`, seen through the image with
    /// shift code `code`.
    #[inline(always)]
    fn scan_cell(&self, me: &Scanner, first: u32, code: u8, found: &mut Found) {
        let mut j = first;
        while j != NONE {
            let bj = &self.bodies[j as usize];
            test_pair(me, self.species, j, bj, self.now, code, found);
            j = bj.link.next;
        }
    }
}

/// The largest radius among the species that have discs (length; 0 for none): it
/// sets the width of the cells, so a species listed with no discs must not.
pub(crate) fn largest_radius(species: &[Species], species_of: &[u16]) -> f64 {
    let mut present = vec![false; species.len()];
    for &s in species_of {
        present[s as usize] = true;
    }
    species
        .iter()
        .zip(present)
        .filter(|(_, p)| *p)
        .map(|(s, _)| s.radius)
        .fold(0.0, f64::max)
}

#[inline]
fn time_key(t: f64) -> Time {
    NotNan::new(t).expect("event times are never NaN: inputs are validated finite")
}

impl Engine {
    /// An engine starting from `state` with dynamics `params`.
    ///
    /// The state must come from [`crate::SystemSpec::build`] or satisfy the same
    /// rules (finite values, discs inside the box, no overlap).
    pub fn new(state: State, params: EngineParams) -> Result<Engine, EngineError> {
        Self::with_grids(state, params, true)
    }

    /// [`Engine::new`] with a cell grid per size class where that is estimated to
    /// be faster (`split`), or one grid for all discs (as carom had before size
    /// classes; for tests of old checkpoints).
    pub(crate) fn with_grids(
        state: State,
        params: EngineParams,
        split: bool,
    ) -> Result<Engine, EngineError> {
        let n = state.len();
        let mut grids = Grids::new(&state.sim_box, &state.species, &state.species_of, split);
        let mut bodies: Vec<Body> = memory::collect(
            n,
            (0..n).map(|i| Body {
                r0: state.sim_box.wrap(state.positions[i]),
                v: state.velocities[i],
                event_time: f64::INFINITY,
                count: 0,
                partner: NONE,
                partner_count: 0,
                kind: KIND_NONE,
                aux: 0,
                species: state.species_of[i],
                link: Link::UNLINKED,
            }),
        );
        for i in 0..n {
            let grid = grids.get_mut(grids.class(bodies[i].species));
            let c = grid.coords_of(bodies[i].r0);
            grid.insert(&mut bodies, i as u32, c);
        }
        let limit = origin_limit(state.sim_box.size, grids.first.width);
        let mut engine = Engine {
            sim_box: state.sim_box,
            species: state.species,
            species_of: state.species_of,
            label: (0..n as u32).collect(),
            index_of: (0..n as u32).collect(),
            next_reorder: reorder_interval(n),
            look_ahead: lookahead::worthwhile(n),
            tuner: lookahead::Tuner::new(n),
            origin_limit: limit,
            bodies,
            last_collision: memory::filled(n, f64::NEG_INFINITY),
            queue: EventQueue::new(n),
            grids,
            scheduled: BinaryHeap::new(),
            next_seq: 0,
            params,
            clock: 0.0,
            epoch: state.time,
            reported: state.time,
            same_time_collisions: 0,
            stats: Stats::default(),
        };
        engine.reorder();
        for i in 0..n {
            engine.predict(i);
        }
        engine.queue.retune(engine.bodies.as_slice(), engine.clock);
        Ok(engine)
    }

    /// The current simulation time (time).
    pub fn now(&self) -> f64 {
        self.reported
    }

    /// Number of discs N.
    pub fn len(&self) -> usize {
        self.bodies.len()
    }

    /// True when there are no discs.
    pub fn is_empty(&self) -> bool {
        self.bodies.is_empty()
    }

    /// The box.
    pub fn sim_box(&self) -> &SimBox {
        &self.sim_box
    }

    /// The species.
    pub fn species(&self) -> &[Species] {
        &self.species
    }

    /// Species index of each disc.
    pub fn species_of(&self) -> &[u16] {
        &self.species_of
    }

    /// The dynamics parameters.
    pub fn params(&self) -> &EngineParams {
        &self.params
    }

    /// Running totals since the start.
    pub fn stats(&self) -> &Stats {
        &self.stats
    }

    /// Turn fetching ahead on or off for good (a speed setting that never changes
    /// the trajectory). By default it is off below 20 000 discs, and from there on
    /// chosen by timing both settings from time to time, starting on from 170 000
    /// discs (see [`crate::lookahead`]).
    pub fn set_look_ahead(&mut self, on: bool) {
        self.look_ahead = on;
        self.tuner = lookahead::Tuner::off();
    }

    /// Whether fetching ahead is on (see [`Engine::set_look_ahead`]).
    pub fn look_ahead_enabled(&self) -> bool {
        self.look_ahead
    }

    /// Cells per axis of the neighbour grid (of the smallest discs, when a mixture
    /// has a grid per size class: see [`crate::classes`]).
    pub fn cells(&self) -> [u32; 2] {
        self.grids.first.n
    }

    /// Number of cell grids: one per size class (see [`crate::classes`]).
    pub fn grid_count(&self) -> usize {
        self.grids.len()
    }

    /// Position of disc `i` at the current time (length), inside the box.
    pub fn position(&self, i: usize) -> DVec2 {
        let b = &self.bodies[self.index_of[i] as usize];
        self.sim_box.wrap(b.at(self.clock))
    }

    /// Velocity of disc `i` (length/time).
    pub fn velocity(&self, i: usize) -> DVec2 {
        self.bodies[self.index_of[i] as usize].v
    }

    /// Total kinetic energy K = Σ m v²/2 (energy).
    pub fn kinetic_energy(&self) -> f64 {
        self.bodies
            .iter()
            .map(|b| 0.5 * self.species[b.species as usize].mass * b.v.length_squared())
            .sum()
    }

    /// The exact state of every disc at the current time. Reading it does not
    /// disturb the trajectory.
    pub fn state(&self) -> State {
        let mut s = State {
            sim_box: self.sim_box,
            species: Vec::new(),
            species_of: Vec::new(),
            positions: Vec::new(),
            velocities: Vec::new(),
            time: self.reported,
        };
        self.state_into(&mut s);
        s
    }

    /// [`Engine::state`] written into `out`, reusing its allocations (for callers
    /// that take many snapshots). The records are read once each, in storage order,
    /// and the positions and velocities written at the discs' own indices: at
    /// large N, reading the records by disc index instead (two random reads per
    /// disc) took most of a snapshot's time.
    pub fn state_into(&self, out: &mut State) {
        let n = self.len();
        out.sim_box = self.sim_box;
        out.species.clone_from(&self.species);
        out.species_of.clone_from(&self.species_of);
        out.positions.resize(n, DVec2::ZERO);
        out.velocities.resize(n, DVec2::ZERO);
        out.time = self.reported;
        for (b, &i) in self.bodies.iter().zip(&self.label) {
            out.positions[i as usize] = self.sim_box.wrap(b.at(self.clock));
            out.velocities[i as usize] = b.v;
        }
    }

    /// Heap bytes held by the engine (for the memory report).
    pub fn heap_bytes(&self) -> usize {
        self.bodies.capacity() * std::mem::size_of::<Body>()
            + self.last_collision.capacity() * 8
            + self.species_of.capacity() * 2
            + (self.label.capacity() + self.index_of.capacity()) * 4
            + self.queue.heap_bytes()
            + self.grids.heap_bytes()
    }

    /// Ask for an [`Event::Scheduled`] with `tag` at time `time` (≥ now). Events at the
    /// same time are delivered in the order they were scheduled, before any collision
    /// at that time.
    pub fn schedule(&mut self, time: f64, tag: u64) -> Result<(), EngineError> {
        if time.is_nan() || time < self.reported || time.is_infinite() {
            return Err(EngineError::ScheduleInPast {
                time,
                now: self.reported,
            });
        }
        self.scheduled
            .push(Reverse((time_key(time), self.next_seq, tag)));
        self.next_seq += 1;
        Ok(())
    }

    /// Process events until the next observable one and return it; `None` when
    /// nothing will ever happen again (all discs at rest and nothing scheduled).
    ///
    /// Cell crossings are not observable, so in a system whose discs move but never
    /// collide again (a lone disc in a periodic box) this call returns only at the
    /// next scheduled event: schedule a stop ([`Engine::schedule`], or use
    /// [`Engine::run_until`]) rather than waiting for collisions that never come.
    pub fn next_event(&mut self) -> Result<Option<Event>, EngineError> {
        loop {
            self.tuner.left -= 1;
            if self.tuner.left == 0 {
                self.tune_look_ahead();
            }
            if self.stats.pair_collisions >= self.next_reorder {
                // The renumbering is not the look-ahead's doing: leave its time out
                // of the tuner's window.
                let started = self.tuner.active().then(std::time::Instant::now);
                self.reorder();
                if let Some(t) = started {
                    self.tuner.exclude(t.elapsed());
                }
                self.next_reorder += reorder_interval(self.len());
            }
            let (t, who) = self.queue.peek(self.bodies.as_slice());
            // Start fetching the records (and cell coordinates) of the likely next
            // events while this one is processed: at large N each is a cache miss.
            // A prefetch hint only; nothing depends on it. (`examples/profile`,
            // η = 0.5: a plain read of the record gave +2 % at N = 10⁴ and +6 % at
            // 10⁶; the prefetch instruction, which does not hold up the processor
            // until the line arrives, with the cell coordinates, another +2.5 % at
            // 10⁴ (2.01 → 2.06 M/s, three alternating runs each) and +2 % at 10⁶.
            // Reading the partners' records as well was slower.)
            for d in self.queue.upcoming() {
                if let Some(b) = self.bodies.get(d as usize) {
                    memory::prefetch(b);
                }
            }
            if self.look_ahead && self.queue.moved_on() {
                self.look_ahead();
            }
            if let Some(&Reverse((ts, _, tag))) = self.scheduled.peek() {
                // Scheduled times are the caller's; on the internal clock, never
                // before now (rounding of the difference).
                let ts = ts.into_inner();
                let internal = (ts - self.epoch).max(self.clock);
                if internal <= t.into_inner() {
                    self.scheduled.pop();
                    self.move_clock(internal);
                    self.reported = self.reported.max(ts);
                    return Ok(Some(Event::Scheduled {
                        time: self.reported,
                        tag,
                    }));
                }
            }
            let t = t.into_inner();
            if t == f64::INFINITY {
                return Ok(None);
            }
            debug_assert!(t >= self.clock, "event in the past: {t} < {}", self.clock);
            let i = who as usize;
            let b = &self.bodies[i];
            let (kind, aux) = (b.kind, b.aux);
            match kind {
                KIND_PAIR => {
                    let j = b.partner as usize;
                    if self.bodies[j].count != b.partner_count {
                        self.move_clock(t);
                        self.stats.stale_events += 1;
                        self.predict(i);
                        continue;
                    }
                    self.advance_clock(t)?;
                    return Ok(Some(Event::Pair(self.collide(i, j, aux >> 2))));
                }
                KIND_WALL => {
                    self.advance_clock(t)?;
                    return Ok(Some(Event::Wall(self.hit_wall(i, aux & 3))));
                }
                KIND_CELL => {
                    self.move_clock(t);
                    self.cross(i, aux & 3);
                }
                _ => unreachable!("a disc with no event has time +∞"),
            }
        }
    }

    /// Run until time `t_end` (≥ now): the engine stops with every disc's state known
    /// at exactly `t_end`. Returns the number of collisions (pair + wall) processed.
    pub fn run_until(&mut self, t_end: f64) -> Result<u64, EngineError> {
        const STOP_TAG: u64 = u64::MAX;
        self.schedule(t_end, STOP_TAG)?;
        let mut collisions = 0;
        while let Some(ev) = self.next_event()? {
            match ev {
                Event::Scheduled { tag: STOP_TAG, .. } => break,
                Event::Scheduled { .. } => {}
                _ => collisions += 1,
            }
        }
        Ok(collisions)
    }

    /// Run `n` collisions (pair + wall), skipping scheduled events. Stops early if
    /// nothing will ever happen again; returns the number processed. (Like
    /// [`Engine::next_event`], it does not return while discs that never collide
    /// again keep crossing cells.)
    pub fn run_collisions(&mut self, n: u64) -> Result<u64, EngineError> {
        let mut done = 0;
        while done < n {
            match self.next_event()? {
                Some(Event::Scheduled { .. }) => {}
                Some(_) => done += 1,
                None => break,
            }
        }
        Ok(done)
    }

    /// A window of the look-ahead tuner ended: choose the setting for the next one.
    #[cold]
    #[inline(never)]
    fn tune_look_ahead(&mut self) {
        self.look_ahead = self
            .tuner
            .next_window(std::time::Instant::now(), self.look_ahead);
    }

    /// Move the clock to time `t` (≥ now) for an event that is not a collision (a
    /// crossing, a recomputed prediction, a scheduled event): a later time is a new
    /// instant, at which no collision has happened yet.
    #[inline]
    fn move_clock(&mut self, t: f64) {
        if t > self.clock {
            self.clock = t;
            self.same_time_collisions = 0;
        }
    }

    /// Move the clock to collision time `t`, counting the collisions at one instant;
    /// more than `max_events_without_time_advance` of them is a runaway.
    #[inline]
    fn advance_clock(&mut self, t: f64) -> Result<(), EngineError> {
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
    /// close in space are close in memory and in the queue. (The Hilbert curve, with
    /// fewer jumps between distant cells, gave the same trajectory and 0.98 of the
    /// speed at N = 10⁶, median of 6 side-by-side runs: each neighbour's record is
    /// its own cache line either way. Nor did the label array on huge pages help:
    /// 0.96, 6 runs.) Only the internal order
    /// changes: events and states keep the user's numbering, and no arithmetic on
    /// the trajectory depends on the order (ties are broken by internal index, which
    /// this renumbering makes a deterministic function of the history).
    pub(crate) fn reorder(&mut self) {
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
        for b in self.bodies.iter_mut() {
            if b.partner != NONE {
                b.partner = inv[b.partner as usize];
            }
        }
        self.queue.retune(self.bodies.as_slice(), self.clock);
        for (k, &l) in self.label.iter().enumerate() {
            self.index_of[l as usize] = k as u32;
        }
        for grid in self.grids.iter_mut() {
            grid.head.fill(NONE);
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
        for b in self.bodies.iter_mut() {
            b.r0 = b.at(shift);
            b.event_time -= shift;
        }
        for t in self.last_collision.iter_mut() {
            *t -= shift;
        }
        self.epoch += shift;
        self.clock = 0.0;
    }

    #[inline]
    fn mass(&self, i: usize) -> f64 {
        self.species[self.bodies[i].species as usize].mass
    }

    #[inline]
    fn shift_of(&self, code: u8) -> DVec2 {
        let sx = (code % 3) as f64 - 1.0;
        let sy = (code / 3) as f64 - 1.0;
        DVec2::new(sx * self.sim_box.size.x, sy * self.sim_box.size.y)
    }

    /// Whether disc `i` collided (with a disc or a wall) less than t_c before `now`
    /// (internal time), so that its next collision is elastic under the TC model
    /// (physics.md §4); always false with the model off.
    #[inline]
    fn within_tc(&self, i: usize, now: f64) -> bool {
        let tc = self.params.tc;
        tc > 0.0 && now - self.last_collision[i] < tc
    }

    /// Ask for a renumbering at the next event, and with it a restart of the
    /// internal clock ([`Engine::rebase_clock`]), if disc `i`'s path origin has
    /// moved more than [`ORIGIN_LIMIT`] box lengths (or [`ORIGIN_LIMIT_CELLS`] cell
    /// widths, whichever is more) from the box. Positions are
    /// computed as r0 + v t, so their rounding is that of |r0|: it stays that of
    /// the box's own coordinates only while |r0| does. The renumbering every 16 N
    /// pair collisions keeps |r0| ≈ L + |v| t small in a fluid, but a cooled
    /// granular cluster drifting with the rounding residue of its momentum (speeds of
    /// 10⁻¹⁷ at t ≈ 10²³, few collisions) moved 4·10⁶ box lengths on one clock, and
    /// its contacts were off by 10⁻⁹ (`tests/engine_reference.rs`, random dynamics).
    /// Called where an origin changes: a velocity change, a wrap across a periodic
    /// edge.
    #[inline]
    fn keep_origin_near<const K: usize>(&mut self, discs: [usize; K]) {
        // One comparison for all the discs of an event (a pair: two).
        let far = discs
            .iter()
            .map(|&i| self.bodies[i].r0.abs().max_element())
            .fold(0.0, f64::max);
        if far > self.origin_limit {
            self.next_reorder = self.next_reorder.min(self.stats.pair_collisions);
        }
    }

    /// Resolve the pair collision of discs i and j (j seen through the image with
    /// shift code `shift_code`) at the current time with the configured rule, or
    /// elastically under the TC model, and predict both discs' next events.
    fn collide(&mut self, i: usize, j: usize, shift_code: u8) -> PairCollision {
        let now = self.clock;
        let shift = self.shift_of(shift_code);
        let dr = self.bodies[j].at(now) + shift - self.bodies[i].at(now);
        // The unnormalised contact vector goes to the collision rule (see
        // carom_core::collision: energy is then conserved without rounding bias).
        let (vi, vj) = (self.bodies[i].v, self.bodies[j].v);
        let (mi, mj) = (self.mass(i), self.mass(j));
        let tc = self.params.tc;
        let rule = if self.within_tc(i, now) || self.within_tc(j, now) {
            Restitution::Elastic
        } else {
            self.params.restitution
        };
        let mut res = resolve(vi, vj, mi, mj, dr, rule);
        // A rule leaves the pair separating at −e u (physics.md §4), but when that
        // is below what the velocities' rounding resolves (e = 0, R = 0, or an
        // elastic collision of a pair that met at such a speed, as under the TC
        // model) the rounded velocities may leave it approaching. In contact, it
        // would then collide again at once, and as the resolution cannot change the
        // velocities again, forever: under the TC model (restitution 0, t_c = 10⁻³,
        // N = 400, η = 0.3) a stall at t ≈ 0.5 that no collapse caused. So a pair
        // that still approaches as the scans will see it is pushed apart. Not for an
        // inelastic rule without the TC model: there the pair meets again at once,
        // and the run stops with the runaway error, as a collapse must be reported.
        // Costs about 55 instructions per collision (cachegrind, N = 10⁴:
        // 2938 → 2993) and changes no other collision (the same trajectories at
        // N = 10⁴, η = 0.5 and 0.7, and at N = 10⁶).
        let paths = [(self.bodies[i].r0, vi), (self.bodies[j].r0, vj)];
        let separated = if (tc > 0.0 || self.params.restitution.is_elastic())
            && approaching(paths, shift, now, (res.vi, res.vj))
        {
            push_apart(paths, shift, now, dr, (res.vi, res.vj), (mi, mj))
        } else {
            None
        };
        if let Some((a, b)) = separated {
            res.impulse_i += (a - res.vi) * mi;
            (res.vi, res.vj) = (a, b);
        }
        // r_ij = r_i − r_j = −dr.
        let virial = -dr.dot(res.impulse_i);
        self.bodies[i].set_velocity(res.vi, now);
        self.bodies[j].set_velocity(res.vj, now);
        self.keep_origin_near([i, j]);
        self.bodies[i].count = self.bodies[i].count.wrapping_add(1);
        self.bodies[j].count = self.bodies[j].count.wrapping_add(1);
        if tc > 0.0 {
            // Read only by the TC model; skipping the write saves two cache misses
            // per collision at large N.
            self.last_collision[i] = now;
            self.last_collision[j] = now;
        }
        self.stats.pair_collisions += 1;
        self.stats.virial_sum += virial;
        self.stats.energy_lost += res.energy_lost;
        self.predict(i);
        self.predict(j);
        PairCollision {
            time: self.reported,
            i: self.label[i],
            j: self.label[j],
            normal: dr / dr.length(),
            vi_before: vi,
            vj_before: vj,
            vi_after: res.vi,
            vj_after: res.vj,
            energy_lost: res.energy_lost,
            virial,
        }
    }

    fn hit_wall(&mut self, i: usize, aux: u8) -> WallCollision {
        let k = (aux / 2) as usize;
        let side = if aux % 2 == 1 {
            WallSide::High
        } else {
            WallSide::Low
        };
        let wall_e = match self.sim_box.boundary[k] {
            Boundary::Walls { restitution } => restitution,
            Boundary::Periodic => unreachable!("wall event on a periodic axis"),
        };
        // The TC model covers wall collisions as well (physics.md §4: a collision is
        // elastic if the disc collided less than t_c ago), as in Luding & McNamara:
        // without it, discs wedged between inelastic walls collapse under the TC
        // model just as they would without it (`tests/inelastic.rs`).
        let now = self.clock;
        let e = if self.within_tc(i, now) { 1.0 } else { wall_e };
        if self.params.tc > 0.0 {
            self.last_collision[i] = now;
        }
        let m = self.mass(i);
        let before = self.bodies[i].v;
        let mut after = before;
        after[k] = wall_reflect(before[k], e);
        self.bodies[i].set_velocity(after, now);
        self.keep_origin_near([i]);
        self.bodies[i].count = self.bodies[i].count.wrapping_add(1);
        let impulse = m * (before[k] - after[k]).abs();
        let energy_lost = 0.5 * m * (1.0 - e * e) * before[k] * before[k];
        self.stats.wall_collisions += 1;
        self.stats.wall_impulse[k][(aux % 2) as usize] += impulse;
        self.stats.energy_lost += energy_lost;
        self.predict(i);
        WallCollision {
            time: self.reported,
            i: self.label[i],
            axis: if k == 0 { Axis::X } else { Axis::Y },
            side,
            v_before: before,
            v_after: after,
            impulse,
            energy_lost,
        }
    }

    fn cross(&mut self, i: usize, aux: u8) {
        let k = (aux / 2) as usize;
        let up = aux % 2 == 1;
        let mut c = self.bodies[i].link.coords();
        let grid = self.grids.get_mut(self.grids.class(self.bodies[i].species));
        let n = grid.n[k];
        grid.remove(&mut self.bodies, i as u32);
        let mut wrapped = true;
        if up {
            if c[k] + 1 == n {
                // Leaving through the periodic edge at L: re-enter at 0.
                c[k] = 0;
                self.bodies[i].r0[k] -= self.sim_box.size[k];
            } else {
                c[k] += 1;
                wrapped = false;
            }
        } else if c[k] == 0 {
            c[k] = n - 1;
            self.bodies[i].r0[k] += self.sim_box.size[k];
        } else {
            c[k] -= 1;
            wrapped = false;
        }
        grid.insert(&mut self.bodies, i as u32, c);
        self.stats.cell_crossings += 1;
        if wrapped {
            self.keep_origin_near([i]);
            // The position moved by one box length: partners' image shifts change.
            self.bodies[i].count = self.bodies[i].count.wrapping_add(1);
            self.predict(i);
        } else {
            self.predict_after_crossing(i, k, up);
        }
    }

    /// Find disc `i`'s earliest event from the current time and queue it: its next
    /// cell crossing or wall collision, or its earliest pair collision with a disc
    /// of its 3 × 3 block of cells (which becomes its pair candidate).
    fn predict(&mut self, i: usize) {
        let now = self.clock;
        let bi = self.bodies[i];
        let ri = bi.at(now);
        let mut found = Found::NOTHING;
        self.scan(i, ri, [-1, 1], [-1, 1], &mut found);
        if !self.grids.single() {
            self.scan_other_classes(i, ri, &mut found);
        }
        let boundary = self.boundary_event(i, ri, bi.v);
        self.file_event(i, &found, boundary);
    }

    /// Make disc `i`'s earliest event pending and queue it: the pair candidate
    /// `found`, or the boundary event (time from now, kind, aux) if that comes first.
    #[inline(always)]
    fn file_event(&mut self, i: usize, found: &Found, (boundary, kind, aux): (f64, u8, u8)) {
        // Without branches (a pair or a boundary event comes first about equally
        // often); with no partner, the count read is of a disc in memory and unused.
        let partner_count = self.bodies[(found.partner as usize).min(self.bodies.len() - 1)].count;
        let pair = found.best < boundary;
        let b = &mut self.bodies[i];
        b.partner = found.partner;
        b.partner_count = std::hint::select_unpredictable(found.partner != NONE, partner_count, 0);
        b.kind = std::hint::select_unpredictable(pair, KIND_PAIR, kind);
        b.aux = aux | found.code << 2;
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
    fn predict_after_crossing(&mut self, i: usize, k: usize, up: bool) {
        let now = self.clock;
        let bi = self.bodies[i];
        let ri = bi.at(now);
        let mut candidate = Found::NOTHING;
        if bi.partner != NONE {
            let bp = &self.bodies[bi.partner as usize];
            if bp.count != bi.partner_count {
                self.predict(i);
                return;
            }
            // Seeing the partner's image at r_j + s L is seeing i at r_i − s L.
            let code = bi.aux >> 2;
            let me = Scanner {
                bi: &bi,
                radius: self.species[bi.species as usize].radius,
                ri: ri - self.shift_of(code),
            };
            test_pair(
                &me,
                &self.species,
                bi.partner,
                bp,
                now,
                code,
                &mut candidate,
            );
        }
        let o = if up { 1 } else { -1 };
        let (xs, ys) = if k == 0 {
            ([o, o], [-1, 1])
        } else {
            ([-1, 1], [o, o])
        };
        // The strip's discs replace the candidate only when one meets earlier.
        self.scan(i, ri, xs, ys, &mut candidate);
        if !self.grids.single() {
            self.scan_other_classes(i, ri, &mut candidate);
        }
        let boundary = self.boundary_event(i, ri, bi.v);
        self.file_event(i, &candidate, boundary);
    }

    /// Look for disc `i`'s earliest pair collision (before `found.best`, time from
    /// now) with the discs of the cells at offsets `xs[0]..=xs[1]` along x and
    /// `ys[0]..=ys[1]` along y from its cell: the whole 3 × 3 block, or the strip of
    /// three cells a crossing brings next to it, in the grid of its size class. `ri`
    /// is its position now.
    ///
    /// Each cell is walked behind a branch on its emptiness (about half the cells
    /// are empty at η = 0.5). Testing the first disc of every cell without that
    /// branch instead (disc i against itself for an empty cell, which never meets)
    /// and the rest of the lists after was much slower: 0.87 at N = 10⁶ and 0.68
    /// at 10⁴ (`examples/profile`, η = 0.5, medians of 6 side-by-side runs; the
    /// same trajectory). Two more forms, measured at N = 10⁴ as geometric means of
    /// 150 pairs of 10⁵-collision windows alternating in one process: the
    /// non-empty heads packed first without a branch and then walked (one
    /// mispredicted loop exit in place of a coin toss per cell) gave 1.037 ± 0.010
    /// at η = 0.5 and 1.008 ± 0.011 at η = 0.7 for the block alone, and 1.016 ±
    /// 0.009 and 0.985 ± 0.007 with the strips too, too little and too mixed to
    /// keep; every disc of the block (first, second and further discs of each
    /// cell) gathered into a buffer before any test, 0.953 ± 0.008 and 0.943 ±
    /// 0.009.
    #[inline(always)]
    fn scan(&self, i: usize, ri: DVec2, xs: [i32; 2], ys: [i32; 2], found: &mut Found) {
        let grid = self.grids.get(self.grids.class(self.bodies[i].species));
        let block = self.block();
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
                for h in heads {
                    block.scan_cell(&me, h, 4, found);
                }
            } else {
                // A strip: a column (x crossing) or a row (y crossing) of three.
                let stride = if xs[0] == xs[1] { nx } else { 1 };
                let heads = [head[first], head[first + stride], head[first + 2 * stride]];
                for h in heads {
                    block.scan_cell(&me, h, 4, found);
                }
            }
        } else {
            let size = self.sim_box.size;
            // The (up to) three columns: index, image shift along x, shift sign + 1.
            let mut col_list = [(0usize, 0.0f64, 0i32); 3];
            let mut ncols = 0;
            for ox in xs[0]..=xs[1] {
                if let Some((cx, sx)) = neighbour(c[0], ox, nx, grid.periodic[0]) {
                    col_list[ncols] = (cx as usize, sx as f64 * size.x, sx + 1);
                    ncols += 1;
                }
            }
            for oy in ys[0]..=ys[1] {
                let Some((cy, sy)) = neighbour(c[1], oy, ny, grid.periodic[1]) else {
                    continue;
                };
                let row = cy as usize * nx as usize;
                let shift_y = sy as f64 * size.y;
                for &(cx, shift_x, cxs) in &col_list[..ncols] {
                    // Seeing j's image at r_j + s L is seeing i at r_i − s L.
                    let me = Scanner {
                        bi,
                        radius,
                        ri: DVec2::new(ri.x - shift_x, ri.y - shift_y),
                    };
                    let code = (cxs + 3 * (sy + 1)) as u8;
                    block.scan_cell(&me, head[row + cx], code, found);
                }
            }
        }
    }

    /// The neighbour search's view of the engine now (see [`Block`]).
    #[inline(always)]
    fn block(&self) -> Block<'_> {
        Block {
            bodies: &self.bodies,
            species: &self.species,
            now: self.clock,
        }
    }

    /// Look for disc `i`'s earliest pair collision (before `found.best`, time from
    /// now) with the discs of the other size classes: in each other class's grid,
    /// every cell meeting disc i's own cell widened by its reach into that class
    /// (see [`crate::classes`]). `ri` is its position now.
    fn scan_other_classes(&self, i: usize, ri: DVec2, found: &mut Found) {
        let block = self.block();
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
                    let code = ((sx + 1) + 3 * (sy + 1)) as u8;
                    let first = grid.head[cy as usize * nx + cx as usize];
                    block.scan_cell(&me, first, code, found);
                }
            }
        }
    }

    /// Disc `i`'s earliest cell crossing or wall collision from now: (time from now,
    /// kind, aux as in [`Body`]), in the grid of its size class. `ri` is its position
    /// now, `v` its velocity.
    #[inline(always)]
    fn boundary_event(&self, i: usize, ri: DVec2, v: DVec2) -> (f64, u8, u8) {
        let mut best = f64::INFINITY;
        let (mut kind, mut aux) = (KIND_NONE, 0u8);
        let c = self.bodies[i].link.coords();
        let grid = self.grids.get(self.grids.class(self.bodies[i].species));
        for k in 0..2 {
            // Without branches: which axis is crossed first is a coin toss.
            let (dt, up) = grid.crossing_time(k, c[k], ri[k], v[k]);
            let hit = dt < best;
            best = std::hint::select_unpredictable(hit, dt, best);
            kind = std::hint::select_unpredictable(hit, KIND_CELL, kind);
            aux = std::hint::select_unpredictable(hit, (2 * k) as u8 + up as u8, aux);
            if let Boundary::Walls { .. } = self.sim_box.boundary[k] {
                let radius = self.species[self.bodies[i].species as usize].radius;
                if let Some((dt, side)) = wall_time(ri[k], v[k], radius, self.sim_box.size[k]) {
                    if dt < best {
                        best = dt;
                        kind = KIND_WALL;
                        aux = (2 * k + (side == WallSide::High) as usize) as u8;
                    }
                }
            }
        }
        (best, kind, aux)
    }
}
