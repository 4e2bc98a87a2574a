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

use super::cdr::{CdrError, CdrReader, CdrWriter};
use super::snapshot::boundary_code;
use carom_core::vibrating_wall::Floor;
use carom_core::{Boundary, DVec2, Restitution, SimBox, Species};
use carom_engine::{
    Checkpoint, EngineParams, GrowthEnd, GrowthState, Stats, Thermostat, ThermostatState,
    ThermostatStats,
};

/// `ros2msg` text of the schema `carom_msgs/msg/Checkpoint`.
pub const CHECKPOINT_MSG: &str = "\
# The complete state of a carom run, from which it resumes bit-identically.
# Per-disc arrays have one entry per disc; units are the run's.
uint32 format_version             # 5 (4: without growth at the end; 3: nor gravity and the thermostat; 2: nor the images)
# --- run driver ---
float64 run_start_time            # simulated time at which the run started (time)
uint64 logged_collisions          # collisions written to /collisions so far
uint32[4] next_sequence           # next MCAP sequence number of /collisions, /snapshot, /thermo, /checkpoint
# --- box and species ---
float64 box_x                     # box edge lengths (length)
float64 box_y
uint8 boundary_x                  # 0 = periodic, 1 = hard walls
uint8 boundary_y
float64 wall_restitution_x        # wall restitution (1 when periodic)
float64 wall_restitution_y
uint64[] species_count
float64[] species_radius          # (length)
float64[] species_mass            # (mass)
uint16[] species                  # per disc: species index
# --- dynamics ---
uint8 restitution_kind            # 0 = elastic, 1 = centre-of-mass R, 2 = normal e
float64 restitution               # R or e (1 when elastic)
float64 tc                        # TC-model duration (time)
uint64 max_events_without_time_advance
# --- clock and running totals ---
float64 now                       # current time (time)
float64 epoch                     # time of the internal clock's zero (time)
float64 clock                     # internal clock now (time since epoch); per-disc times below are on it
uint64 same_time_collisions
uint64 pair_collisions
uint64 wall_collisions
uint64 cell_crossings
uint64 stale_events
float64 virial_sum                # sum r_ij . dp_i (length*momentum)
float64[4] wall_impulse           # momentum given to walls x-low, x-high, y-low, y-high
float64 energy_lost               # (energy)
# --- per-disc delayed states ---
float64[] x                       # position at time t on the disc's straight path (length)
float64[] y
float64[] vx                      # velocity (length/time)
float64[] vy
float64[] t                       # time of that position (time); carom writes 0: x, y are the path's origin
uint32[] collision_count
float64[] last_collision          # time of last collision, pair or wall (-inf if none or TC off)
float64[] event_time              # time of the pending event (+inf if none)
float64[] pair_time               # time of the pair candidate where it is the pending event, else +inf (not needed to resume)
uint32[] pending_partner          # the pair candidate's partner (4294967295 = none)
uint32[] pending_partner_count    # the partner's collision_count when the candidate was found
uint32[] pending_kind             # the pending event: kind and details (engine-internal)
# --- neighbour grid (engine-internal) ---
uint32[] cell_head                # first disc per cell (4294967295 = none)
uint32[] cell_next
uint32[] cell_prev
uint32[] cell_column
uint32[] cell_row
# --- events scheduled by the caller ---
float64[] scheduled_time
uint64[] scheduled_seq
uint64[] scheduled_tag
uint64 next_seq
# --- internal disc order ---
uint32[] labels                   # per internal slot: the disc's external index (the per-disc arrays above are in internal order)
uint64 next_reorder               # pair-collision count at which the engine next renumbers its discs
# --- periodic images (format_version 3 on) ---
int32[] image_x                   # net periodic edges crossed since the run began, per disc in internal order:
int32[] image_y                   #   the unwrapped position now is x + vx * (clock - t) + image_x * box_x
# --- uniform gravity (format_version 4 on) ---
float64 gravity                   # g along -y (length/time^2; 0: none); then x, y, vx, vy are a path: the
                                  #   position at clock is (x + vx c, y + vy c - g c^2/2), velocity (vx, vy - g c), c = clock - t
# --- thermostat (format_version 4 on; its next event is the scheduled event of tag 18446744073709551614) ---
uint8 thermostat_kind             # 0 = none, 1 = Andersen, 2 = driven
float64 thermostat_a              # Andersen: kT (energy); driven: xi2 (length^2/time^3); 0 for none
float64 thermostat_b              # Andersen: rate per disc (1/time); driven: interval (time); 0 for none
uint64[2] thermostat_rng          # the Pcg64Mcg generator's 128-bit state: high, low 64 bits
uint64 thermostat_events          # thermostat events so far
float64 thermostat_energy_added   # kinetic energy the thermostat added so far (energy)
float64 thermostat_origin         # time the thermostat was set: driving kick k comes at origin + k * interval (time)
# --- growing discs, compression (format_version 5 on; physics.md section 16) ---
float64 growth_rate               # configured relative growth rate (1/time; 0: none); radii are a0 * scale, a0 the species radii
float64 growth_target_scale       # scale at which growth stops
float64 growth_kt                 # kT the velocities are rescaled to (energy)
float64 growth_rescale_interval   # time between rescales (time)
float64 growth_max_reduced_pressure # jamming bound on Z
float64 growth_scale0             # engine-internal: scale at clock 0
float64 growth_rate_now           # engine-internal: rate now (0 once ended)
float64 growth_end                # engine-internal: clock time of the target scale (+inf once ended)
float64 growth_next_rescale       # engine-internal: clock time of the next rescale (+inf once ended)
float64 growth_virial_mark        # engine-internal: virial sum at the last rescale
uint8 growth_ended                # 0 growing (or none), 1 target reached, 2 jammed
float64 growth_last_z             # Z over the last interval between rescales
# --- vibrating floor (format_version 5 on; physics.md section 18) ---
float64 floor_amplitude           # A (length; 0: no floor): the floor is at A (1 - cos(omega t')), t' = time - floor_origin
float64 floor_omega               # angular frequency omega = 2 pi f (1/time; 0: no floor)
float64 floor_origin              # time the floor was set, its phase origin (time)
float64 floor_work                # kinetic energy the floor gave the discs so far (energy)
";

/// Format version written in `format_version`.
pub const CHECKPOINT_FORMAT_VERSION: u32 = 5;

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
        let c = &self.engine;
        let d = &self.driver;
        let n = c.species_of.len();
        w.reset();
        w.reserve(512 + n * 124 + c.cell_head.len() * 4 + c.scheduled.len() * 24);
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
        w.seq_iter(c.scheduled.iter().map(|s| s.0));
        w.seq_iter(c.scheduled.iter().map(|s| s.1));
        w.seq_iter(c.scheduled.iter().map(|s| s.2));
        w.put(c.next_seq);
        w.seq(&c.labels);
        w.put(c.next_reorder);
        w.seq_iter(c.images.iter().map(|m| m[0]));
        w.seq_iter(c.images.iter().map(|m| m[1]));
        w.put(c.params.gravity);
        let t = c.thermostat.unwrap_or(ThermostatState {
            thermostat: Thermostat::Andersen { kt: 0.0, rate: 0.0 },
            rng: 0,
            stats: ThermostatStats::default(),
            origin: 0.0,
        });
        let (kind, a, b) = match (c.thermostat.is_some(), t.thermostat) {
            (false, _) => (0u8, 0.0, 0.0),
            (true, Thermostat::Andersen { kt, rate }) => (1, kt, rate),
            (true, Thermostat::Driven { xi2, interval }) => (2, xi2, interval),
        };
        w.put(kind);
        w.put(a);
        w.put(b);
        w.array(&[(t.rng >> 64) as u64, t.rng as u64]);
        w.put(t.stats.events);
        w.put(t.stats.energy_added);
        w.put(t.origin);
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
    }

    /// Decode from CDR. Checks the layout and the lengths of paired arrays; the
    /// engine's own [`carom_engine::Engine::from_checkpoint`] checks the rest.
    pub fn decode(data: &[u8]) -> Result<Self, CdrError> {
        let mut r = CdrReader::new(data)?;
        let version: u32 = r.get("format_version")?;
        // Version 4 is version 5 without growth, 3 also without gravity and the
        // thermostat, 2 also without the images.
        if !(2..=CHECKPOINT_FORMAT_VERSION).contains(&version) {
            return Err(CdrError::Invalid {
                field: "format_version",
                problem: format!(
                    "checkpoint format {version} is not supported (this carom reads 2 to {CHECKPOINT_FORMAT_VERSION})"
                ),
            });
        }
        let driver = DriverState {
            run_start_time: r.get("run_start_time")?,
            logged_collisions: r.get("logged_collisions")?,
            next_sequence: r.fixed("next_sequence")?,
        };
        let size = DVec2::new(r.get("box_x")?, r.get("box_y")?);
        let bcode: [u8; 2] = [r.get("boundary_x")?, r.get("boundary_y")?];
        let we: [f64; 2] = [r.get("wall_restitution_x")?, r.get("wall_restitution_y")?];
        let mut boundary = [Boundary::Periodic; 2];
        for k in 0..2 {
            boundary[k] = match bcode[k] {
                0 => Boundary::Periodic,
                1 => Boundary::Walls { restitution: we[k] },
                b => {
                    return Err(CdrError::Invalid {
                        field: "boundary",
                        problem: format!("unknown boundary code {b} (allowed: 0, 1)"),
                    })
                }
            };
        }
        let counts: Vec<u64> = r.seq("species_count")?;
        let radii: Vec<f64> = r.seq("species_radius")?;
        let masses: Vec<f64> = r.seq("species_mass")?;
        if radii.len() != counts.len() || masses.len() != counts.len() {
            return Err(CdrError::Invalid {
                field: "species_radius",
                problem: "species arrays differ in length".into(),
            });
        }
        let species = counts
            .iter()
            .zip(&radii)
            .zip(&masses)
            .map(|((&count, &radius), &mass)| Species {
                count: count as usize,
                radius,
                mass,
            })
            .collect();
        let species_of: Vec<u16> = r.seq("species")?;
        let kind: u8 = r.get("restitution_kind")?;
        let coef: f64 = r.get("restitution")?;
        let restitution = match kind {
            0 => Restitution::Elastic,
            1 => Restitution::CentreOfMass(coef),
            2 => Restitution::Normal(coef),
            k => {
                return Err(CdrError::Invalid {
                    field: "restitution_kind",
                    problem: format!("unknown restitution kind {k} (allowed: 0, 1, 2)"),
                })
            }
        };
        let mut params = EngineParams {
            restitution,
            tc: r.get("tc")?,
            max_events_without_time_advance: r.get("max_events_without_time_advance")?,
            ..EngineParams::default()
        };
        let now = r.get("now")?;
        let epoch = r.get("epoch")?;
        let clock = r.get("clock")?;
        let same_time_collisions = r.get("same_time_collisions")?;
        let pair_collisions = r.get("pair_collisions")?;
        let wall_collisions = r.get("wall_collisions")?;
        let cell_crossings = r.get("cell_crossings")?;
        let stale_events = r.get("stale_events")?;
        let virial_sum = r.get("virial_sum")?;
        let wi: [f64; 4] = r.fixed("wall_impulse")?;
        let energy_lost = r.get("energy_lost")?;
        let stats = Stats {
            pair_collisions,
            wall_collisions,
            cell_crossings,
            stale_events,
            virial_sum,
            wall_impulse: [[wi[0], wi[1]], [wi[2], wi[3]]],
            energy_lost,
            floor_work: 0.0,
        };
        let pair = |a: Vec<f64>, b: Vec<f64>, field: &'static str| {
            if a.len() != b.len() {
                return Err(CdrError::Invalid {
                    field,
                    problem: format!("{} entries for {} discs", b.len(), a.len()),
                });
            }
            Ok(a.iter()
                .zip(&b)
                .map(|(&x, &y)| DVec2::new(x, y))
                .collect::<Vec<_>>())
        };
        let x = r.seq("x")?;
        let y = r.seq("y")?;
        let positions = pair(x, y, "y")?;
        let vx = r.seq("vx")?;
        let vy = r.seq("vy")?;
        let velocities = pair(vx, vy, "vy")?;
        let times = r.seq("t")?;
        let counts = r.seq("collision_count")?;
        let last_collision = r.seq("last_collision")?;
        let event_times = r.seq("event_time")?;
        let pair_times = r.seq("pair_time")?;
        let p0: Vec<u32> = r.seq("pending_partner")?;
        let p1: Vec<u32> = r.seq("pending_partner_count")?;
        let p2: Vec<u32> = r.seq("pending_kind")?;
        if p1.len() != p0.len() || p2.len() != p0.len() {
            return Err(CdrError::Invalid {
                field: "pending_kind",
                problem: "pending-event arrays differ in length".into(),
            });
        }
        let pending = (0..p0.len()).map(|k| [p0[k], p1[k], p2[k]]).collect();
        let cell_head = r.seq("cell_head")?;
        let cell_next = r.seq("cell_next")?;
        let cell_prev = r.seq("cell_prev")?;
        let col: Vec<u32> = r.seq("cell_column")?;
        let row: Vec<u32> = r.seq("cell_row")?;
        if col.len() != row.len() {
            return Err(CdrError::Invalid {
                field: "cell_row",
                problem: format!("{} entries for {} columns", row.len(), col.len()),
            });
        }
        let cell = col.iter().zip(&row).map(|(&a, &b)| [a, b]).collect();
        let st: Vec<f64> = r.seq("scheduled_time")?;
        let ss: Vec<u64> = r.seq("scheduled_seq")?;
        let sg: Vec<u64> = r.seq("scheduled_tag")?;
        if ss.len() != st.len() || sg.len() != st.len() {
            return Err(CdrError::Invalid {
                field: "scheduled_tag",
                problem: "scheduled-event arrays differ in length".into(),
            });
        }
        let scheduled = (0..st.len()).map(|k| (st[k], ss[k], sg[k])).collect();
        let next_seq = r.get("next_seq")?;
        let labels = r.seq("labels")?;
        let next_reorder = r.get("next_reorder")?;
        let images = if version >= 3 {
            let x: Vec<i32> = r.seq("image_x")?;
            let y: Vec<i32> = r.seq("image_y")?;
            if x.len() != y.len() {
                return Err(CdrError::Invalid {
                    field: "image_y",
                    problem: format!("{} entries, but `image_x` has {}", y.len(), x.len()),
                });
            }
            x.into_iter().zip(y).map(|(a, b)| [a, b]).collect()
        } else {
            Vec::new()
        };
        if version >= 4 {
            params.gravity = r.get("gravity")?;
        }
        let thermostat = if version >= 4 {
            decode_thermostat(&mut r)?
        } else {
            None
        };
        let mut stats = stats;
        let mut floor_origin = 0.0;
        let mut growth = GrowthState::NONE;
        if version >= 5 {
            let g = &mut params.growth;
            g.rate = r.get("growth_rate")?;
            g.target_scale = r.get("growth_target_scale")?;
            g.kt = r.get("growth_kt")?;
            g.rescale_interval = r.get("growth_rescale_interval")?;
            g.max_reduced_pressure = r.get("growth_max_reduced_pressure")?;
            growth.scale0 = r.get("growth_scale0")?;
            growth.rate = r.get("growth_rate_now")?;
            growth.end = r.get("growth_end")?;
            growth.next_rescale = r.get("growth_next_rescale")?;
            growth.virial_mark = r.get("growth_virial_mark")?;
            let ended: u8 = r.get("growth_ended")?;
            growth.ended = match ended {
                0 => GrowthEnd::Growing,
                1 => GrowthEnd::Target,
                2 => GrowthEnd::Jammed,
                _ => {
                    return Err(CdrError::Invalid {
                        field: "growth_ended",
                        problem: format!("{ended} is not 0, 1 or 2"),
                    })
                }
            };
            growth.last_z = r.get("growth_last_z")?;
            let amplitude: f64 = r.get("floor_amplitude")?;
            let omega: f64 = r.get("floor_omega")?;
            if amplitude != 0.0 || omega != 0.0 {
                params.floor = Some(Floor { amplitude, omega });
            }
            floor_origin = r.get("floor_origin")?;
            stats.floor_work = r.get("floor_work")?;
        }
        Ok(LogCheckpoint {
            driver,
            engine: Checkpoint {
                sim_box: SimBox { size, boundary },
                species,
                species_of,
                params,
                now,
                epoch,
                clock,
                same_time_collisions,
                stats,
                positions,
                velocities,
                times,
                counts,
                last_collision,
                event_times,
                pair_times,
                pending,
                cell_head,
                cell_next,
                cell_prev,
                cell,
                scheduled,
                next_seq,
                labels,
                next_reorder,
                images,
                thermostat,
                growth,
                floor_origin,
            },
        })
    }
}

/// The thermostat fields at the end of a checkpoint of format 4 on.
fn decode_thermostat(r: &mut CdrReader) -> Result<Option<ThermostatState>, CdrError> {
    let kind: u8 = r.get("thermostat_kind")?;
    let a: f64 = r.get("thermostat_a")?;
    let b: f64 = r.get("thermostat_b")?;
    let rng: [u64; 2] = r.fixed("thermostat_rng")?;
    let events = r.get("thermostat_events")?;
    let energy_added = r.get("thermostat_energy_added")?;
    let origin = r.get("thermostat_origin")?;
    let thermostat = match kind {
        0 => return Ok(None),
        1 => Thermostat::Andersen { kt: a, rate: b },
        2 => Thermostat::Driven {
            xi2: a,
            interval: b,
        },
        k => {
            return Err(CdrError::Invalid {
                field: "thermostat_kind",
                problem: format!("unknown thermostat kind {k} (allowed: 0, 1, 2)"),
            })
        }
    };
    Ok(Some(ThermostatState {
        thermostat,
        rng: (rng[0] as u128) << 64 | rng[1] as u128,
        stats: ThermostatStats {
            events,
            energy_added,
        },
        origin,
    }))
}

#[cfg(test)]
mod tests {
    use super::*;
    use carom_engine::{box_size_for, Engine, Placement, SystemSpec, Velocities};

    #[test]
    fn checkpoint_round_trips_bit_for_bit() {
        let species = vec![Species::reference(40), Species::new(10, 0.8, 3.0)];
        let size = box_size_for(&species, 0.4, 1.0);
        let spec = SystemSpec {
            species,
            sim_box: SimBox {
                size,
                boundary: [Boundary::Periodic, Boundary::Walls { restitution: 0.9 }],
            },
            temperature: 1.0,
            seed: 3,
            placement: Placement::Lattice,
            velocities: Velocities::MaxwellBoltzmann,
        };
        let params = EngineParams {
            restitution: Restitution::Normal(0.95),
            tc: 1e-4,
            max_events_without_time_advance: 1000,
            ..EngineParams::default()
        };
        let mut e = Engine::new(spec.build().unwrap(), params).unwrap();
        e.run_collisions(500).unwrap();
        e.schedule(e.now() + 1.0, 42).unwrap();
        let lc = LogCheckpoint {
            driver: DriverState {
                run_start_time: 0.0,
                logged_collisions: 250,
                next_sequence: [1, 2, 3, 4],
            },
            engine: e.checkpoint(),
        };
        let mut w = CdrWriter::new();
        lc.encode(&mut w);
        let back = LogCheckpoint::decode(w.bytes()).unwrap();
        // PartialEq on f64 would accept -0.0 == 0.0; compare the encodings too.
        assert_eq!(back, lc);
        let mut w2 = CdrWriter::new();
        back.encode(&mut w2);
        assert_eq!(w.bytes(), w2.bytes());
        // Truncations are clean errors.
        for cut in [0, 3, 4, 10, 100, w.bytes().len() - 1] {
            assert!(LogCheckpoint::decode(&w.bytes()[..cut]).is_err());
        }
    }

    /// A shaken bed's checkpoint (gravity, vibrating floor) round-trips with the
    /// floor, its phase origin and its work, and resumes into the same engine.
    #[test]
    fn a_checkpoint_with_a_vibrating_floor_round_trips() {
        let species = vec![Species::reference(60)];
        let spec = SystemSpec {
            species,
            sim_box: SimBox {
                size: DVec2::new(12.0, 30.0),
                boundary: [Boundary::Periodic, Boundary::Walls { restitution: 0.9 }],
            },
            temperature: 1.0,
            seed: 4,
            placement: Placement::Random,
            velocities: Velocities::MaxwellBoltzmann,
        };
        let params = EngineParams {
            restitution: Restitution::Normal(0.9),
            tc: 1e-4,
            gravity: 1.0,
            floor: Some(Floor {
                amplitude: 0.4,
                omega: 3.0,
            }),
            ..EngineParams::default()
        };
        let mut e = Engine::new(spec.build().unwrap(), params).unwrap();
        e.run_collisions(3_000).unwrap();
        assert!(e.stats().floor_work != 0.0);
        let lc = LogCheckpoint {
            driver: DriverState {
                run_start_time: 0.0,
                logged_collisions: 3_000,
                next_sequence: [1, 2, 3, 4],
            },
            engine: e.checkpoint(),
        };
        let mut w = CdrWriter::new();
        lc.encode(&mut w);
        let back = LogCheckpoint::decode(w.bytes()).unwrap();
        assert_eq!(back, lc);
        let mut b = Engine::from_checkpoint(back.engine).unwrap();
        for _ in 0..2_000 {
            assert_eq!(e.next_event().unwrap(), b.next_event().unwrap());
        }
    }
}
