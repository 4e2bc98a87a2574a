//! The `/checkpoint` message: the engine's complete [`Checkpoint`] plus the run
//! driver's own state ([`DriverState`]), encoded as CDR. The wire layout (field
//! order, types, units, codes) is described in one place, the schema text
//! [`CHECKPOINT_MSG`], which every log stores and `docs/log-format.md` shows
//! verbatim; [`LogCheckpoint::encode`] and [`LogCheckpoint::decode`] follow it
//! field by field. Fields the schema marks "engine-internal" are copied as the
//! engine hands them over; `carom_engine::Checkpoint` says what they mean.
//!
//! Every `f64` is stored bit for bit (±∞ included), so an engine restored from a
//! decoded checkpoint continues bit-identically. The engine draws random numbers
//! while building the initial state and, with a thermostat, from the thermostat's
//! own generator, whose state is stored.

mod calendar;
mod decode;
mod lists;
mod schema;

use super::cdr::CdrWriter;
use super::snapshot::boundary_code;
use calendar::encode_thermostat;
pub(crate) use calendar::scheduled_entries;
use carom_core::vibrating_wall::Floor;
use carom_core::{Boundary, Restitution};
use carom_engine::Checkpoint;
use lists::encode_neighbours;
pub(crate) use lists::neighbours_named;
pub use schema::{CHECKPOINT_FORMAT_VERSION, CHECKPOINT_MSG};

/// The run driver's state at a checkpoint (what it needs, beyond the engine, to
/// continue the log exactly as the uninterrupted run would have).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct DriverState {
    /// Simulated time at which the run started (time).
    pub run_start_time: f64,
    /// Collisions written to `/collisions` so far.
    pub logged_collisions: u64,
    /// Next MCAP sequence number of `/collisions`, `/snapshot`, `/thermo`, `/checkpoint`.
    pub next_sequence: [u32; 4],
}

/// A decoded `/checkpoint` message.
#[derive(Debug, Clone, PartialEq)]
pub struct LogCheckpoint {
    /// The run driver's state.
    pub driver: DriverState,
    /// The engine's complete state.
    pub engine: Checkpoint,
}

fn wall_e(b: &Boundary) -> f64 {
    match *b {
        Boundary::Periodic => 1.0,
        Boundary::Walls { restitution } => restitution,
    }
}

impl LogCheckpoint {
    /// Encode as CDR into `w` (which is reset first).
    pub fn encode(&self, w: &mut CdrWriter) {
        self.encode_with(w, &scheduled_entries(&self.engine));
    }

    /// [`LogCheckpoint::encode`] with the scheduled arrays' entries `scheduled`
    /// (tests write the order of older formats with it).
    fn encode_with(&self, w: &mut CdrWriter, scheduled: &[(f64, u64, u64)]) {
        let c = &self.engine;
        let d = &self.driver;
        let n = c.species_of.len();
        w.reset();
        w.reserve(512 + n * 140 + c.cell_head.len() * 4 + scheduled.len() * 24);
        w.put(CHECKPOINT_FORMAT_VERSION);
        w.put(d.run_start_time);
        w.put(d.logged_collisions);
        w.array(&d.next_sequence);
        w.put(c.sim_box.size.x);
        w.put(c.sim_box.size.y);
        w.put(boundary_code(&c.sim_box.boundary[0]));
        w.put(boundary_code(&c.sim_box.boundary[1]));
        w.put(wall_e(&c.sim_box.boundary[0]));
        w.put(wall_e(&c.sim_box.boundary[1]));
        w.seq_iter(c.species.iter().map(|s| s.count as u64));
        w.seq_iter(c.species.iter().map(|s| s.radius));
        w.seq_iter(c.species.iter().map(|s| s.mass));
        w.seq(&c.species_of);
        let (kind, coef) = match c.params.restitution {
            Restitution::Elastic => (0u8, 1.0),
            Restitution::CentreOfMass(r) => (1, r),
            Restitution::Normal(e) => (2, e),
        };
        w.put(kind);
        w.put(coef);
        w.put(c.params.tc);
        w.put(c.params.max_events_without_time_advance);
        w.put(c.now);
        w.put(c.epoch);
        w.put(c.clock);
        w.put(c.same_time_collisions);
        let s = &c.stats;
        w.put(s.pair_collisions);
        w.put(s.wall_collisions);
        w.put(s.cell_crossings);
        w.put(s.stale_events);
        w.put(s.virial_sum);
        w.array(&[
            s.wall_impulse[0][0],
            s.wall_impulse[0][1],
            s.wall_impulse[1][0],
            s.wall_impulse[1][1],
        ]);
        w.put(s.energy_lost);
        w.seq_iter(c.positions.iter().map(|p| p.x));
        w.seq_iter(c.positions.iter().map(|p| p.y));
        w.seq_iter(c.velocities.iter().map(|p| p.x));
        w.seq_iter(c.velocities.iter().map(|p| p.y));
        w.seq(&c.times);
        w.seq(&c.counts);
        w.seq(&c.last_collision);
        w.seq(&c.event_times);
        w.seq(&c.pair_times);
        w.seq_iter(c.pending.iter().map(|p| p[0]));
        w.seq_iter(c.pending.iter().map(|p| p[1]));
        w.seq_iter(c.pending.iter().map(|p| p[2]));
        w.seq(&c.cell_head);
        w.seq(&c.cell_next);
        w.seq(&c.cell_prev);
        w.seq_iter(c.cell.iter().map(|p| p[0]));
        w.seq_iter(c.cell.iter().map(|p| p[1]));
        w.seq_iter(scheduled.iter().map(|s| s.0));
        w.seq_iter(scheduled.iter().map(|s| s.1));
        w.seq_iter(scheduled.iter().map(|s| s.2));
        w.put(c.next_seq);
        w.seq(&c.labels);
        w.put(c.next_reorder);
        w.seq_iter(c.images.iter().map(|m| m[0]));
        w.seq_iter(c.images.iter().map(|m| m[1]));
        w.put(c.params.gravity);
        encode_thermostat(w, &c.thermostat);
        let (g, st) = (&c.params.growth, &c.growth);
        for x in [
            g.rate,
            g.target_scale,
            g.kt,
            g.rescale_interval,
            g.max_reduced_pressure,
            st.scale0,
            st.rate,
            st.end,
            st.next_rescale,
            st.virial_mark,
        ] {
            w.put(x);
        }
        w.put(st.ended as u8);
        w.put(st.last_z);
        let fl = c.params.floor.unwrap_or(Floor {
            amplitude: 0.0,
            omega: 0.0,
        });
        w.put(fl.amplitude);
        w.put(fl.omega);
        w.put(c.floor_origin);
        w.put(s.floor_work);
        encode_neighbours(w, c.params.neighbours, c.lists.as_ref());
    }
}

#[cfg(test)]
mod tests;
