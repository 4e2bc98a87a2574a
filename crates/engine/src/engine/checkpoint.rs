//! The engine's checkpoint: copying its complete state out into a [`Checkpoint`]
//! and rebuilding an engine from one.
//!
//! A resumed run continues bit for bit, so everything that decides the trajectory
//! is copied: each disc's path (origin and velocity, and whether it rests on the
//! floor: bit 16 of its pending word, beside the event's kind and details,
//! refused by a carom that does not know it), collision counter, pair
//! candidate and pending event with its time, the cell lists in their exact order
//! (the order breaks no ties, but it decides which discs a scan meets first), the
//! clock and its epoch, the running totals, the renumbering schedule, the
//! caller's scheduled events and the thermostat's next event. The grids are rebuilt as the engine builds them (one
//! per size class, or one for all in a checkpoint written before size classes), and
//! a checkpoint that is inconsistent in any way is refused with what is wrong.

use super::body::{Aux, Body, Pending};
use super::calendar::{Calendar, Whose};
use super::clock::origin_limit;
use super::listed::{centre_grid, lists_from};
use super::{lookahead, thermostat, Engine, EngineParams};
use crate::cells::Link;
use crate::checkpoint::{Checkpoint, ListsCheckpoint};
use crate::classes::Grids;
use crate::error::EngineError;
use crate::lists::Neighbours;
use crate::memory;
use crate::queue::EventQueue;
use crate::NO_DISC;

impl Engine {
    /// Copy out the complete state (see [`Checkpoint`]).
    pub fn checkpoint(&self) -> Checkpoint {
        let n = self.bodies.len();
        Checkpoint {
            sim_box: self.sim_box,
            species: self.species.clone(),
            species_of: self.bodies.iter().map(|b| b.species).collect(),
            params: self.params,
            now: self.reported,
            epoch: self.epoch,
            clock: self.clock,
            same_time_collisions: self.same_time_collisions,
            stats: self.stats,
            // The engine keeps each path's origin, its position at internal time 0.
            positions: self.bodies.iter().map(|b| b.r0).collect(),
            velocities: self.bodies.iter().map(|b| b.v).collect(),
            times: vec![0.0; n],
            counts: self.bodies.iter().map(|b| b.count).collect(),
            last_collision: self.last_collision.clone(),
            event_times: self.bodies.iter().map(|b| b.event_time).collect(),
            pending: self
                .bodies
                .iter()
                .map(|b| {
                    [
                        b.partner,
                        b.partner_count,
                        b.pending as u32
                            | (b.aux.event_bits() as u32) << 8
                            | (b.resting() as u32) << 16,
                    ]
                })
                .collect(),
            pair_times: self
                .bodies
                .iter()
                .map(|b| {
                    if b.pending == Pending::Pair {
                        b.event_time
                    } else {
                        f64::INFINITY
                    }
                })
                .collect(),
            cell_head: self.grids.heads(),
            cell_next: self.bodies.iter().map(|b| b.link.next).collect(),
            cell_prev: self.grids.prev_links(&self.bodies),
            cell: self.bodies.iter().map(|b| b.link.coords()).collect(),
            scheduled: self.calendar.caller_entries(),
            next_seq: self.calendar.next_seq(),
            labels: self.label.clone(),
            next_reorder: self.next_reorder,
            images: self
                .label
                .iter()
                .map(|&d| self.images[d as usize])
                .collect(),
            thermostat: self
                .thermostat
                .as_ref()
                .map(|r| r.state(self.calendar.thermostat_entry())),
            growth: self.growth,
            floor_origin: self.floor_origin,
            lists: self.lists.as_ref().map(|l| ListsCheckpoint {
                skin: l.skin,
                centres: l.lines.iter().map(|line| line.centre).collect(),
            }),
        }
    }

    /// Rebuild an engine from a [`Checkpoint`]; it continues exactly as the engine the
    /// checkpoint was taken from would have. Inconsistent checkpoints are rejected.
    pub fn from_checkpoint(cp: Checkpoint) -> Result<Engine, EngineError> {
        let bad = |m: String| EngineError::BadCheckpoint(m);
        let n = cp.species_of.len();
        for (name, len) in [
            ("positions", cp.positions.len()),
            ("velocities", cp.velocities.len()),
            ("times", cp.times.len()),
            ("counts", cp.counts.len()),
            ("last_collision", cp.last_collision.len()),
            ("event_times", cp.event_times.len()),
            ("pending", cp.pending.len()),
            ("pair_times", cp.pair_times.len()),
            ("cell_next", cp.cell_next.len()),
            ("cell_prev", cp.cell_prev.len()),
            ("cell", cp.cell.len()),
            ("labels", cp.labels.len()),
            // Checkpoints written before carom counted images have none.
            (
                "images",
                if cp.images.is_empty() {
                    n
                } else {
                    cp.images.len()
                },
            ),
        ] {
            if len != n {
                return Err(bad(format!("{name} has {len} entries for {n} discs")));
            }
        }
        if let Some(&s) = cp
            .species_of
            .iter()
            .find(|&&s| s as usize >= cp.species.len())
        {
            return Err(bad(format!("species index {s} out of range")));
        }
        super::gravity::check_gravity(cp.params.gravity, &cp.sim_box)
            .map_err(|e| bad(e.to_string()))?;
        let p = &cp.params;
        super::growth::check_growth(&p.growth, p.restitution, p.tc, p.gravity, &cp.sim_box)
            .map_err(|e| bad(e.to_string()))?;
        super::floor::check_floor(&cp.params, &cp.sim_box, &cp.species)
            .map_err(|e| bad(e.to_string()))?;
        if !cp.floor_origin.is_finite() {
            return Err(bad(format!("floor_origin = {}", cp.floor_origin)));
        }
        let st = &cp.growth;
        if !(st.scale0.is_finite() && st.scale0 > 0.0 && st.rate.is_finite())
            || st.end.is_nan()
            || st.next_rescale.is_nan()
        {
            return Err(bad(format!("growth state {st:?} is not a valid one")));
        }
        for (name, t) in [("now", cp.now), ("epoch", cp.epoch), ("clock", cp.clock)] {
            if !t.is_finite() {
                return Err(bad(format!("{name} is {t}, not a finite time")));
            }
        }
        // A path is a point, a time and a velocity, all finite: anything else would
        // put NaN into the predicted event times.
        for (i, ((p, v), &t)) in cp
            .positions
            .iter()
            .zip(&cp.velocities)
            .zip(&cp.times)
            .enumerate()
        {
            for (name, ok) in [
                ("position", p.is_finite()),
                ("velocity", v.is_finite()),
                ("time", t.is_finite()),
            ] {
                if !ok {
                    return Err(bad(format!(
                        "{name} of disc {i} is not finite (position {p}, velocity {v}, time {t})"
                    )));
                }
            }
            // The path origin p − v t, which the engine stores, must be finite too:
            // finite parts can still overflow (a huge speed times a huge time).
            if !(*p - *v * t).is_finite() {
                return Err(bad(format!(
                    "path of disc {i} overflows: position {p} − velocity {v} × time {t} \
                     is not finite"
                )));
            }
        }
        let mut index_of = vec![NO_DISC; n];
        for (k, &l) in cp.labels.iter().enumerate() {
            if l as usize >= n || index_of[l as usize] != NO_DISC {
                return Err(bad(
                    "labels are not a permutation of the disc indices".into()
                ));
            }
            index_of[l as usize] = k as u32;
        }
        let mut species_of_ext = vec![0u16; n];
        let mut images = vec![[0; 2]; n];
        for (k, &l) in cp.labels.iter().enumerate() {
            species_of_ext[l as usize] = cp.species_of[k];
            images[l as usize] = cp.images.get(k).copied().unwrap_or([0; 2]);
        }
        let bodies: Vec<Body> = memory::collect(
            n,
            (0..n).map(|i| Body {
                // The path origin: the position at internal time 0 (carom writes
                // origins, with times 0, so this is exact for its own checkpoints).
                r0: cp.positions[i] - cp.velocities[i] * cp.times[i],
                v: cp.velocities[i],
                event_time: cp.event_times[i],
                count: cp.counts[i],
                partner: cp.pending[i][0],
                partner_count: cp.pending[i][1],
                // A kind carom does not write is refused below.
                pending: Pending::from_code(cp.pending[i][2] & 0xff).unwrap_or(Pending::None),
                aux: Aux::from_event_bits((cp.pending[i][2] >> 8) as u8)
                    .with_resting(((cp.pending[i][2] >> 16) & 1) == 1),
                species: cp.species_of[i],
                link: Link {
                    cell: cp.cell[i].map(|x| x as u16),
                    next: cp.cell_next[i],
                },
            }),
        );
        // The grids the engine builds for this state (the grids decide when
        // crossings move the clock, so a resumed run must have the grids it was
        // written with to continue bit for bit): one per size class, or one for
        // all in a checkpoint written before carom had size classes.
        let grid_species = super::growth::grid_species(&cp.species, &cp.params.growth);
        let cell_grids = |split| Grids::new(&cp.sim_box, &grid_species, &cp.species_of, split);
        let grids = if let Some(l) = &cp.lists {
            // On lists, the grid of the list centres (engine::listed).
            let sigma = cell_grids(true).largest_sigma();
            centre_grid(&cp.sim_box, cp.species.len(), sigma, l.skin, n)
                .map_err(|e| format!("lists: {e}"))
                .and_then(|centres| restore_grids(&cp, &bodies, centres))
        } else if cp.params.growth.rate != 0.0 {
            // Growing discs: one grid for their final size (engine::growth).
            restore_grids(&cp, &bodies, cell_grids(false))
        } else {
            restore_grids(&cp, &bodies, cell_grids(true))
                .or_else(|e| restore_grids(&cp, &bodies, cell_grids(false)).map_err(|_| e))
        }
        .map_err(bad)?;
        for (i, (&t, p)) in cp.event_times.iter().zip(&cp.pending).enumerate() {
            if t.is_nan() {
                return Err(bad(format!("event time of disc {i} is NaN")));
            }
            if p[0] != NO_DISC && p[0] as usize >= n {
                return Err(bad(format!("pending partner of disc {i} out of range")));
            }
            if Pending::from_code(p[2] & 0xff).is_none() || ((p[2] >> 14) & !0b100) != 0 {
                return Err(bad(format!(
                    "pending kind of disc {i} is not one carom writes"
                )));
            }
            if (p[2] >> 16) == 1 {
                check_resting(&cp, i, &bodies).map_err(bad)?;
            }
            if cp.pair_times[i].is_nan() {
                return Err(bad(format!("pair candidate time of disc {i} is NaN")));
            }
        }

        // The queue files every disc under the event time in its record.
        let mut queue = EventQueue::new(n);
        queue.retune(bodies.as_slice(), cp.clock);
        let mut calendar = Calendar::starting_at(cp.next_seq);
        for &(t, seq, tag) in &cp.scheduled {
            if t.is_nan() {
                return Err(bad("a scheduled time is NaN".into()));
            }
            calendar.insert(t, seq, Whose::Caller(tag));
        }
        let limit = origin_limit(cp.sim_box.size, grids.first.width);
        let thermostat = match &cp.thermostat {
            Some(s) => Some(Box::new(thermostat::Running::from_state(s).map_err(bad)?)),
            None => None,
        };
        if let Some((t, seq)) = cp.thermostat.and_then(|s| s.next) {
            calendar.insert(t, seq, Whose::Thermostat);
        }
        let lists = cp.lists.clone();
        let mut engine = Engine {
            sim_box: cp.sim_box,
            species: cp.species,
            bodies,
            last_collision: memory::collect(n, cp.last_collision),
            queue,
            grids,
            calendar,
            params: cp.params,
            clock: cp.clock,
            epoch: cp.epoch,
            reported: cp.now,
            same_time_collisions: cp.same_time_collisions,
            stats: cp.stats,
            label: cp.labels,
            index_of,
            species_of: species_of_ext,
            images,
            next_reorder: cp.next_reorder,
            look_ahead: lookahead::worthwhile(n),
            tuner: lookahead::Tuner::new(n),
            origin_limit: limit,
            thermostat,
            growth: cp.growth,
            floor_origin: cp.floor_origin,
            quiet_work: 0,
            lists: None,
        };
        if let Some(l) = lists {
            engine.restore_lists(l).map_err(bad)?;
        }
        Ok(engine)
    }

    /// Put an engine rebuilt from a checkpoint back on its neighbour lists
    /// (engine::listed): the lists and the grid of centres from the stored
    /// centres, after checking that lists can be used and that every disc is
    /// within its skin of its centre.
    fn restore_lists(&mut self, l: ListsCheckpoint) -> Result<(), String> {
        let n = self.len();
        if l.centres.len() != n {
            return Err(format!("lists: {} centres for {n} discs", l.centres.len()));
        }
        let params = EngineParams {
            neighbours: Neighbours::Lists,
            ..self.params
        };
        super::listed::choose(
            &params,
            &self.sim_box,
            &self.species,
            &self.species_of,
            &self.grids,
        )
        .map_err(|e| format!("lists: {e}"))?;
        for (i, (b, c)) in self.bodies.iter().zip(&l.centres).enumerate() {
            let d = (b.at(self.clock) - *c).length();
            // (A NaN distance is beyond it too.)
            if d.is_nan() || d > l.skin * (1.0 + 1e-9) {
                return Err(format!(
                    "lists: disc {i} is {d} from its list centre {c}, beyond the skin {}",
                    l.skin
                ));
            }
            if b.link.coords() != self.grids.first.coords_of(*c) {
                return Err(format!(
                    "lists: disc {i} is listed in cell {:?}, its centre {c} lies in {:?}",
                    b.link.coords(),
                    self.grids.first.coords_of(*c)
                ));
            }
        }
        let grids = self.grids.clone();
        let lists = lists_from(&grids, &self.bodies, &l.centres, l.skin, self.sim_box.size)
            .map_err(|e| format!("lists: {e}"))?;
        self.take_lists(grids, lists);
        Ok(())
    }
}

/// Whether disc `i` (internal slot; record `bodies[i]`) of checkpoint `cp`, marked
/// resting on the floor, can be: a field without a vibrating floor, and a path
/// along the floor (height its radius, no vertical velocity; engine::resting).
fn check_resting(cp: &Checkpoint, i: usize, bodies: &[Body]) -> Result<(), String> {
    let b = &bodies[i];
    let radius = cp.species[b.species as usize].radius;
    if cp.params.gravity > 0.0 && cp.params.floor.is_none() && b.r0.y == radius && b.v.y == 0.0 {
        Ok(())
    } else {
        Err(format!(
            "disc {i} is marked resting on the floor with gravity {} (a vibrating floor: \
             {}), height {} for radius {radius}, vertical velocity {} (allowed: g > 0, no \
             vibrating floor, height = radius, vertical velocity 0)",
            cp.params.gravity,
            cp.params.floor.is_some(),
            b.r0.y,
            b.v.y
        ))
    }
}

/// The cell grids `grids` (empty) of checkpoint `cp`, with the stored cell lists
/// threaded through `bodies`, or what is wrong.
fn restore_grids(cp: &Checkpoint, bodies: &[Body], mut grids: Grids) -> Result<Grids, String> {
    let cells: usize = grids.iter().map(|g| g.head.len()).sum();
    if cp.cell_head.len() != cells {
        return Err(format!(
            "{} cells stored, the box needs {cells} (a checkpoint of a dilute system, or \
             of one with a species of no discs, written before carom capped the \
             cells at {} per disc)",
            cp.cell_head.len(),
            crate::cells::CELLS_PER_DISC
        ));
    }
    // Disc indices in the lists are checked by `check_lists_of` below; the cells
    // must exist before they are stored (as u16).
    for (i, c) in cp.cell.iter().enumerate() {
        let grid = grids.get(grids.class(cp.species_of[i]));
        if c[0] >= grid.n[0] || c[1] >= grid.n[1] {
            return Err("cell lists refer to cells that do not exist".into());
        }
    }
    // Copied into the engine's own arrays (allocated for huge pages).
    let mut stored = cp.cell_head.as_slice();
    for grid in grids.iter_mut() {
        let (mine, rest) = stored.split_at(grid.head.len());
        grid.head.copy_from_slice(mine);
        stored = rest;
    }
    for (class, grid) in grids.iter().enumerate() {
        grid.check_lists_of(bodies, |i| grids.class(cp.species_of[i]) as usize == class)
            .map_err(|e| format!("cell lists: {e}"))?;
    }
    // The lists are singly linked; the stored back links are only checked.
    if grids.prev_links(bodies) != cp.cell_prev {
        return Err("cell lists: back links do not match the lists".into());
    }
    Ok(grids)
}

#[cfg(test)]
#[path = "checkpoint_tests.rs"]
mod tests;
