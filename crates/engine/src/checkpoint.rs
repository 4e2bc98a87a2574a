//! The complete internal state of an [`Engine`](crate::Engine), from which a run
//! resumes bit-identically: per-disc delayed states, collision counters, pending
//! events and their times, the cell lists in their exact order, running totals and
//! the caller's scheduled events. Plain data: the io crate decides how to store it;
//! the engine copies itself out and back in `engine/checkpoint.rs`.

use crate::engine::{EngineParams, GrowthState, Stats};
use crate::thermostat::ThermostatState;
use carom_core::{DVec2, SimBox, Species};

/// Everything an [`Engine`](crate::Engine) holds, as plain arrays (one entry per disc unless noted).
#[derive(Debug, Clone, PartialEq)]
pub struct Checkpoint {
    /// The box.
    pub sim_box: SimBox,
    /// The species.
    pub species: Vec<Species>,
    /// Species index of each disc, in the engine's internal order (see `labels`).
    pub species_of: Vec<u16>,
    /// Dynamics parameters.
    pub params: EngineParams,
    /// Current simulation time, as reported to the caller (time).
    pub now: f64,
    /// Time of the internal clock's zero (time).
    pub epoch: f64,
    /// The internal clock now (time since `epoch`). Every per-disc time below
    /// (`times`, `event_times`, `pair_times`, `last_collision`) is on this clock;
    /// `scheduled` times are the caller's.
    pub clock: f64,
    /// Collisions processed at the current instant, `clock` (for the runaway
    /// guard; 0 if the clock last moved for another kind of event). Checkpoints
    /// written before this counted the collisions after the first, so such a
    /// checkpoint taken in the middle of a burst allows one more.
    pub same_time_collisions: u64,
    /// Running totals.
    pub stats: Stats,
    /// Position of each disc at time `times[i]` on its current straight path
    /// (length). carom writes each path's origin, the position at internal time 0
    /// (with `times` all 0), which may lie outside the box; any point of the path
    /// with its time reads back the same path.
    pub positions: Vec<DVec2>,
    /// Velocities (length/time).
    pub velocities: Vec<DVec2>,
    /// The time at which each disc is at `positions[i]` (time; 0 in checkpoints
    /// carom writes).
    pub times: Vec<f64>,
    /// Collision counters.
    pub counts: Vec<u32>,
    /// Time of each disc's last collision, pair or wall (time); −∞ if none, and never
    /// updated when the TC model is off (t_c = 0), which is the only reader.
    pub last_collision: Vec<f64>,
    /// Time of each disc's pending event (+∞ if none; time).
    pub event_times: Vec<f64>,
    /// Pair candidate and pending event of each disc: [candidate's partner
    /// ([`NO_DISC`](crate::NO_DISC) for none), partner's counter when found,
    /// pending kind | aux << 8]. Kinds: 0
    /// none, 1 the pair candidate, 2 wall, 3 cell crossing, 4 a floor search to
    /// resume, 5 a skin exit (on neighbour lists). aux bits 0–1: wall 2·axis +
    /// side (1 = high) or crossing 2·axis + (1 if upwards); bits 2–5: the candidate's
    /// image shift code (sx+1) + 3 (sy+1). Bit 16: the disc rests on the floor in a
    /// field (physics.md (15.9); its path is then straight, not falling).
    pub pending: Vec<[u32; 3]>,
    /// Time of each disc's pair candidate where it is the pending event (time; +∞
    /// otherwise). Not needed to resume: the engine keeps only the pending event's
    /// time and computes a candidate's time again when a crossing needs it, so on
    /// reading this is only checked for NaN. (Checkpoints written before that
    /// stored the candidate's time also when a crossing or wall came first.)
    pub pair_times: Vec<f64>,

    /// First disc of each cell ([`NO_DISC`](crate::NO_DISC) for none), one entry
    /// per cell.
    pub cell_head: Vec<u32>,
    /// Next disc in the same cell.
    pub cell_next: Vec<u32>,
    /// Previous disc in the same cell.
    pub cell_prev: Vec<u32>,
    /// Cell (column, row) of each disc.
    pub cell: Vec<[u32; 2]>,
    /// Caller-scheduled events still pending: (time, sequence number, tag), in
    /// the order they come. The thermostat's next event is in `thermostat`.
    pub scheduled: Vec<(f64, u64, u64)>,
    /// Sequence number the next scheduled event (the caller's or the
    /// thermostat's) will get.
    pub next_seq: u64,
    /// External (user) index of each internal slot: the per-disc arrays above are in
    /// the engine's internal (space-filling-curve) order.
    pub labels: Vec<u32>,
    /// Pair-collision count at which the engine next renumbers its discs.
    pub next_reorder: u64,
    /// Net periodic edges each disc crossed since the run began, per axis (see
    /// [`State::images`](crate::State::images)); in internal order like the other
    /// per-disc arrays. Empty in checkpoints written before carom counted them: the
    /// count then restarts at 0.
    pub images: Vec<[i32; 2]>,
    /// The thermostat with its generator, totals and next event, if one is set.
    pub thermostat: Option<ThermostatState>,
    /// The growth of the radii (physics.md §17; [`GrowthState::NONE`] without
    /// growth, and in checkpoints written before carom had it).
    pub growth: GrowthState,
    /// Time (as reported) at which the vibrating floor was set, its phase origin
    /// (physics.md §18; 0 without a floor, and in checkpoints written before carom
    /// had it).
    pub floor_origin: f64,
    /// The neighbour lists, when the run is on them (`None` on the cell path, and
    /// in checkpoints written before carom had lists: such a run resumes on cells).
    pub lists: Option<ListsCheckpoint>,
}

/// What a [`Checkpoint`] keeps of the neighbour lists: the skin and each disc's
/// list centre. The lists themselves are a function of the centres and are
/// rebuilt on resume; the cell lists of the [`Checkpoint`] are then those of the
/// grid of list centres.
#[derive(Debug, Clone, PartialEq)]
pub struct ListsCheckpoint {
    /// The skin s (length): a disc's list is renewed when it has moved s from its
    /// list centre.
    pub skin: f64,
    /// Each disc's list centre, its position (in the box) at its last list update
    /// (length), in the engine's internal order like the other per-disc arrays.
    pub centres: Vec<DVec2>,
}
