//! The event loop: the [`Engine`] type, its parameters and its public API.
//!
//! Each disc keeps its state as of its own last update (physics.md §1), a path
//! r(t) = r0 + v t on an internal clock, and owns one pending event, the earliest of
//! its pair collision (|Δr + Δv t| = σ, §2), wall hit and cell crossing (on
//! neighbour lists, `listed`, its skin exit (2.7) instead). A pair
//! prediction remembers the partner's collision counter, so an obsolete one is
//! recomputed at the head of the queue; the earliest true event is always queued, as
//! of any pair the disc updated last scanned the other with both current paths.
//! Files by phase: `step` (the loop, dispatch only), `predict`, `listed` (the
//! neighbour-list path), `resolve`, `clock`,
//! `lookahead`, `checkpoint`; `calendar`, the one calendar of internal events (the
//! caller's scheduled events and the thermostat's); `motion`, the law of motion,
//! chosen once and compiled into the loop (straight; falling: `gravity`, `floor`,
//! `resting`; growing: `growth`). See docs/performance.md, "engine".

mod body;
mod calendar;
mod checkpoint;
mod clock;
mod floor;
mod gravity;
mod growth;
mod listed;
mod lookahead;
mod motion;
mod pause;
mod predict;
mod resolve;
mod resting;
mod step;
mod thermostat;

use crate::cells::Link;
use crate::classes::Grids;
use crate::error::EngineError;
use crate::lists::{Lists, Neighbours};
use crate::memory;
use crate::queue::{EventQueue, Time};
use crate::state::State;
use crate::NO_DISC;
use body::{Aux, Body, Pending};
use calendar::Calendar;
use carom_core::vibrating_wall::Floor;
use carom_core::{DVec2, Restitution, SimBox, Species};
use clock::{origin_limit, reorder_interval};
pub use growth::{Growth, GrowthEnd, GrowthState};
use ordered_float::NotNan;

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
    /// Uniform gravity g along −y (length/time²; physics.md §15): every disc falls,
    /// r(t) = r + v t − ŷ g t²/2. Requires hard walls along y. 0 (the default)
    /// turns it off; allowed: finite, ≥ 0.
    pub gravity: f64,
    /// Growing discs, Lubachevsky–Stillinger compression (physics.md §17); off
    /// (rate 0) by default.
    pub growth: Growth,
    /// A bottom wall that oscillates, h(t) = A (1 − cos ω t) (physics.md §18); none
    /// by default. Requires hard walls along y; not with growing discs.
    pub floor: Option<Floor>,
    /// How discs find their possible partners: cells, neighbour lists, or the
    /// engine's choice (the default; see [`Engine::neighbour_lists`]). Both give the
    /// same events up to rounding.
    pub neighbours: Neighbours,
}

impl Default for EngineParams {
    fn default() -> Self {
        EngineParams {
            restitution: Restitution::Elastic,
            tc: 0.0,
            max_events_without_time_advance: 100_000,
            gravity: 0.0,
            growth: Growth::default(),
            floor: None,
            neighbours: Neighbours::Auto,
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
    /// Cell crossings processed (internal events); on neighbour lists, list
    /// renewals (a disc leaving its skin, physics.md (2.7)).
    pub cell_crossings: u64,
    /// Predictions found obsolete at the head of the queue and recomputed.
    pub stale_events: u64,
    /// Σ r_ij·Δp_i over pair collisions (physics.md §5; length·momentum).
    pub virial_sum: f64,
    /// Σ |Δp| given to each wall, indexed [axis][0 = low, 1 = high] (momentum).
    pub wall_impulse: [[f64; 2]; 2],
    /// Kinetic energy dissipated in pair and wall collisions (energy).
    pub energy_lost: f64,
    /// Kinetic energy the vibrating floor gave the discs, Σ m (v'² − v²)/2 over
    /// floor hits (energy; physics.md (18.5)); its hits' dissipation is in it, not
    /// in `energy_lost`.
    pub floor_work: f64,
}

/// One disc now, as [`Engine::discs_now`] gives it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DiscNow {
    /// The disc's index (its place in the configuration's order).
    pub index: usize,
    /// Centre position, wrapped into the box (length).
    pub position: DVec2,
    /// Velocity (length/time).
    pub velocity: DVec2,
    /// Periodic image: the unwrapped position is `position + image · box size`.
    pub image: [i32; 2],
}

/// The exact event-driven engine for hard discs.
///
/// ```
/// use carom_engine::{Engine, EngineParams, SystemSpec};
///
/// // 100 discs of diameter 1 at packing fraction 0.3 in a periodic box.
/// let state = SystemSpec::periodic_fluid(100, 0.3, 7).build().unwrap();
/// let mut engine = Engine::new(state, EngineParams::default()).unwrap();
/// let energy = engine.kinetic_energy();
/// let collisions = engine.run_until(2.0).unwrap();
/// assert!(collisions > 0);
/// assert!((engine.kinetic_energy() - energy).abs() < 1e-9 * energy);
/// ```
#[derive(Debug, Clone)]
pub struct Engine {
    sim_box: SimBox,
    species: Vec<Species>,
    bodies: Vec<Body>,
    last_collision: Vec<f64>,
    queue: EventQueue,
    /// The cell grids, one per size class.
    grids: Grids,
    /// The caller's scheduled events and the thermostat's (engine::calendar).
    calendar: Calendar,
    params: EngineParams,
    /// The internal clock (time since `epoch`): every per-disc time, event time and
    /// the queue run on it, so that their rounding stays that of times since the
    /// last renumbering rather than of the whole run (see [`Engine::rebase_clock`]).
    clock: f64,
    /// Time of the internal clock's zero (time).
    epoch: f64,
    /// The current time as reported to the caller (time): `epoch + clock` rounded, or
    /// a scheduled event's own time; never decreasing.
    reported: f64,
    /// Collisions so far at the instant `clock` (0 when the clock last moved for
    /// another kind of event).
    same_time_collisions: u64,
    stats: Stats,
    /// External (user) index of each internal slot.
    label: Vec<u32>,
    /// Internal slot of each external index.
    index_of: Vec<u32>,
    /// Species of each disc in external order.
    species_of: Vec<u16>,
    /// Periodic edges crossed by each disc, net, in external order (+1 leaving at L,
    /// −1 leaving at 0, per axis): its unwrapped position is its path plus
    /// `images` box lengths. Touched only when a disc wraps.
    images: Vec<[i32; 2]>,
    /// Pair-collision count at which discs are next renumbered along the Z curve.
    next_reorder: u64,
    /// Whether to fetch the next events' memory ahead (see `engine::lookahead`).
    look_ahead: bool,
    /// Times fetching ahead on and off and keeps the faster.
    tuner: lookahead::Tuner,
    /// The largest |r0| component before the clock is restarted early (length;
    /// [`Engine::keep_origin_near`]; derived from the box and the grid).
    origin_limit: f64,
    /// The thermostat, if one is set (`engine::thermostat`).
    thermostat: Option<Box<thermostat::Running>>,
    /// The growth of the radii (engine::growth; [`GrowthState::NONE`] without).
    growth: GrowthState,
    /// Time (as reported) at which the vibrating floor was set, its phase origin.
    floor_origin: f64,
    /// Disc updates of unobservable work so far (`engine::pause`).
    quiet_work: u64,
    /// The neighbour lists, when the engine runs on them (engine::listed); `None`
    /// on the cell path.
    lists: Option<Box<Lists>>,
}

#[inline]
fn time_key(t: f64) -> Time {
    NotNan::new(t).expect("event times are never NaN: inputs are validated finite")
}

/// The image of a disc at `path` (its position on its path) shown at `wrapped`
/// (the same point wrapped into the box) that had crossed the periodic edges
/// `images` times: `images` plus the box lengths the wrapping took off, so that
/// `wrapped + image · L` is the unwrapped position.
#[inline]
fn image_shift(sim_box: &SimBox, path: DVec2, wrapped: DVec2, images: [i32; 2]) -> [i32; 2] {
    if path == wrapped {
        // Nearly always: the engine keeps every disc inside the box.
        return images;
    }
    let k = ((path - wrapped) / sim_box.size).round();
    [images[0] + k.x as i32, images[1] + k.y as i32]
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
    fn with_grids(state: State, params: EngineParams, split: bool) -> Result<Engine, EngineError> {
        gravity::check_gravity(params.gravity, &state.sim_box)?;
        let p = &params;
        growth::check_growth(&p.growth, p.restitution, p.tc, p.gravity, &state.sim_box)?;
        floor::check_floor(&params, &state.sim_box, &state.species)?;
        let n = state.len();
        // Growing discs share one grid, for their final size (engine::growth).
        let split = split && params.growth.rate == 0.0;
        let grid_species = growth::grid_species(&state.species, &params.growth);
        let mut grids = Grids::new(&state.sim_box, &grid_species, &state.species_of, split);
        let images = (0..n)
            .map(|i| {
                let given = state.images.get(i).copied().unwrap_or([0; 2]);
                let p = state.positions[i];
                image_shift(&state.sim_box, p, state.sim_box.wrap(p), given)
            })
            .collect();
        let mut bodies: Vec<Body> = memory::collect(
            n,
            (0..n).map(|i| Body {
                r0: state.sim_box.wrap(state.positions[i]),
                v: state.velocities[i],
                event_time: f64::INFINITY,
                count: 0,
                partner: NO_DISC,
                partner_count: 0,
                pending: Pending::None,
                aux: Aux::EMPTY,
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
            images,
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
            calendar: Calendar::default(),
            params,
            clock: 0.0,
            epoch: state.time,
            reported: state.time,
            same_time_collisions: 0,
            stats: Stats::default(),
            thermostat: None,
            growth: GrowthState::start(&params.growth),
            floor_origin: state.time,
            quiet_work: 0,
            lists: None,
        };
        engine.start_lists()?;
        engine.reorder();
        for i in 0..n {
            engine.predict_any(i);
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

    /// The species. With growing discs (physics.md §17) their radii are the
    /// reference radii a⁰: the radii now are a⁰ times [`Engine::radius_scale`], as
    /// [`Engine::state`] gives them.
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
    /// discs (see `engine::lookahead`).
    pub fn set_look_ahead(&mut self, on: bool) {
        self.look_ahead = on;
        self.tuner = lookahead::Tuner::off();
    }

    /// Whether fetching ahead is on (see [`Engine::set_look_ahead`]).
    pub fn look_ahead_enabled(&self) -> bool {
        self.look_ahead
    }

    /// Cells per axis of the neighbour grid (of the smallest discs, when a mixture
    /// has a grid per size class).
    pub fn cells(&self) -> [u32; 2] {
        self.grids.first.n
    }

    /// Whether the engine runs on neighbour lists (with a skin, physics.md §2)
    /// rather than on the cell grid. [`Neighbours::Auto`] chooses lists for equal
    /// discs flying straight, without a field, growth or vibrating floor, at
    /// packing fractions from [`LISTS_FROM_PACKING`](crate::LISTS_FROM_PACKING),
    /// in a box at least three list cells wide on each periodic axis; the choice
    /// is made once, from the configuration, never by timing. A list that
    /// overflows sends the run back to cells for good.
    pub fn neighbour_lists(&self) -> bool {
        self.lists.is_some()
    }

    /// Number of cell grids: one per size class.
    pub fn grid_count(&self) -> usize {
        self.grids.len()
    }

    /// Position of disc `i` at the current time (length), inside the box.
    pub fn position(&self, i: usize) -> DVec2 {
        let b = &self.bodies[self.index_of[i] as usize];
        self.sim_box.wrap(self.true_position(b))
    }

    /// Velocity of disc `i` (length/time).
    pub fn velocity(&self, i: usize) -> DVec2 {
        self.true_velocity(&self.bodies[self.index_of[i] as usize])
    }

    /// A disc's position now (length): on its path, lowered by the fall in a field
    /// (engine::gravity).
    #[inline]
    fn true_position(&self, b: &Body) -> DVec2 {
        let g = self.params.gravity;
        if g == 0.0 {
            b.at(self.clock)
        } else {
            b.falling_at(self.clock, g)
        }
    }

    /// A disc's velocity now (length/time): its path's, less g t in a field.
    #[inline]
    fn true_velocity(&self, b: &Body) -> DVec2 {
        let g = self.params.gravity;
        if g == 0.0 {
            b.v
        } else {
            b.falling_velocity(self.clock, g)
        }
    }

    /// Total kinetic energy K = Σ m v²/2 (energy).
    pub fn kinetic_energy(&self) -> f64 {
        self.bodies
            .iter()
            .map(|b| {
                0.5 * self.species[b.species as usize].mass * self.true_velocity(b).length_squared()
            })
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
            images: Vec::new(),
            time: self.reported,
        };
        self.state_into(&mut s);
        s
    }

    /// [`Engine::state`] written into `out`, reusing its allocations (for callers
    /// that take many snapshots).
    pub fn state_into(&self, out: &mut State) {
        let n = self.len();
        out.sim_box = self.sim_box;
        out.species = self.species_now();
        out.species_of.clone_from(&self.species_of);
        out.positions.resize(n, DVec2::ZERO);
        out.velocities.resize(n, DVec2::ZERO);
        out.images.resize(n, [0; 2]);
        out.time = self.reported;
        for d in self.discs_now() {
            out.positions[d.index] = d.position;
            out.velocities[d.index] = d.velocity;
            out.images[d.index] = d.image;
        }
    }

    /// The species as they are now: their radii grown by the compression's scale
    /// (engine::growth), otherwise as built.
    pub fn species_now(&self) -> Vec<Species> {
        let mut species = self.species.clone();
        if self.params.growth.rate != 0.0 {
            let s = self.radius_scale();
            for sp in &mut species {
                sp.radius *= s;
            }
        }
        species
    }

    /// Every disc now, as [`Engine::state`] reports it (the rule is defined here
    /// once): its position wrapped into the box, its velocity and its periodic
    /// image. The discs come in storage order, not by index, each with its
    /// index: a caller writes them into its own columns at `index`. Reading the
    /// records once each in storage order and writing at the discs' indices is
    /// the fast way at large N; reading the records by disc index instead (two
    /// random reads per disc) took most of a snapshot's time.
    pub fn discs_now(&self) -> impl Iterator<Item = DiscNow> + '_ {
        self.bodies.iter().zip(&self.label).map(|(b, &i)| {
            let (p, index) = (self.true_position(b), i as usize);
            let position = self.sim_box.wrap(p);
            DiscNow {
                index,
                position,
                velocity: self.true_velocity(b),
                image: image_shift(&self.sim_box, p, position, self.images[index]),
            }
        })
    }

    /// Heap bytes held by the engine (for the memory report).
    pub fn heap_bytes(&self) -> usize {
        self.bodies.capacity() * std::mem::size_of::<Body>()
            + self.last_collision.capacity() * 8
            + self.species_of.capacity() * 2
            + (self.label.capacity() + self.index_of.capacity()) * 4
            + self.queue.heap_bytes()
            + self.grids.heap_bytes()
            + self.lists.as_ref().map_or(0, |l| l.heap_bytes())
    }
}

#[cfg(test)]
mod tests {
    use super::image_shift;
    use carom_core::{DVec2, SimBox};

    /// A point on a disc's path at (23, −1) in a 10 × 4 box shows at (3, 3): the
    /// wrap took off 2 box lengths in x and added 1 in y, so images (1, −2) become
    /// (1 + 2, −2 − 1). A point the wrap did not move keeps its images.
    #[test]
    fn the_image_adds_the_box_lengths_the_wrap_took_off() {
        let b = SimBox::periodic(10.0, 4.0);
        let path = DVec2::new(23.0, -1.0);
        assert_eq!(b.wrap(path), DVec2::new(3.0, 3.0));
        assert_eq!(image_shift(&b, path, b.wrap(path), [1, -2]), [3, -3]);
        let inside = DVec2::new(9.5, 0.25);
        assert_eq!(image_shift(&b, inside, b.wrap(inside), [7, -5]), [7, -5]);
    }
}
