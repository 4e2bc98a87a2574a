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
use super::{lookahead, thermostat, Engine};
use crate::cells::Link;
use crate::checkpoint::Checkpoint;
use crate::classes::Grids;
use crate::error::EngineError;
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
        let grids = if cp.params.growth.rate != 0.0 {
            // Growing discs: one grid for their final size (engine::growth).
            restore_grids(&cp, &bodies, false)
        } else {
            restore_grids(&cp, &bodies, true)
                .or_else(|e| restore_grids(&cp, &bodies, false).map_err(|_| e))
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
        Ok(Engine {
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
        })
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

/// The cell grids of checkpoint `cp` (one per size class if `split`, else one for
/// all), with the stored cell lists threaded through `bodies`, or what is wrong.
fn restore_grids(cp: &Checkpoint, bodies: &[Body], split: bool) -> Result<Grids, String> {
    let grid_species = super::growth::grid_species(&cp.species, &cp.params.growth);
    let mut grids = Grids::new(&cp.sim_box, &grid_species, &cp.species_of, split);
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
mod tests {
    use crate::*;
    use carom_core::{Boundary, DVec2, SimBox, Species};

    /// Small discs (diameter 1, mass 1) and `large` discs of radius `radius` and
    /// mass `mass` at packing fraction `eta` in a channel (periodic in x, walls in
    /// y, aspect 1.5), placed by `placement`, with a grid per size class where
    /// that is faster if `split`.
    fn channel(
        (small, large): (usize, usize),
        (radius, mass): (f64, f64),
        eta: f64,
        (seed, placement): (u64, Placement),
        split: bool,
    ) -> Engine {
        let species = vec![
            Species::reference(small),
            Species {
                count: large,
                radius,
                mass,
            },
        ];
        let size = box_size_for(&species, eta, 1.5);
        let sim_box = SimBox {
            size,
            boundary: [Boundary::Periodic, Boundary::Walls { restitution: 1.0 }],
        };
        let spec = SystemSpec {
            species,
            sim_box,
            temperature: 1.0,
            seed,
            placement,
            velocities: Velocities::MaxwellBoltzmann,
        };
        Engine::with_grids(spec.build().unwrap(), EngineParams::default(), split).unwrap()
    }

    /// 150 + 50 discs of radii 0.5 and 0.7 in a channel (one grid).
    fn channel_mixture() -> Engine {
        channel((150, 50), (0.7, 4.0), 0.45, (7, Placement::Lattice), true)
    }

    /// 400 small discs and 6 of 6 times their diameter in a channel: a grid per
    /// size class (or one for all, when not `split`).
    fn asymmetric_channel(split: bool) -> Engine {
        channel((400, 6), (3.0, 36.0), 0.35, (8, Placement::Relaxed), split)
    }

    fn trajectory(e: &mut Engine, n: usize) -> Vec<Event> {
        (0..n).map(|_| e.next_event().unwrap().unwrap()).collect()
    }

    #[test]
    fn resumed_engine_continues_bit_identically() {
        let mut a = channel_mixture();
        // Stop 5 000 collisions short of a renumbering (every 65 536 pair collisions
        // here), so that the compared stretch crosses one.
        a.run_collisions(60_000).unwrap();
        let before = a.stats().pair_collisions;
        a.schedule(a.now() + 3.0, 1).unwrap();
        let mut b = Engine::from_checkpoint(a.checkpoint()).unwrap();
        let ta = trajectory(&mut a, 20_000);
        let tb = trajectory(&mut b, 20_000);
        assert!(ta
            .iter()
            .any(|e| matches!(e, Event::Scheduled { tag: 1, .. })));
        assert_eq!(ta, tb);
        assert!(before < 65_536 && a.stats().pair_collisions > 65_536);
        let (sa, sb) = (a.state(), b.state());
        let bits = |v: &[DVec2]| {
            v.iter()
                .flat_map(|p| [p.x.to_bits(), p.y.to_bits()])
                .collect::<Vec<_>>()
        };
        assert_eq!(bits(&sa.positions), bits(&sb.positions));
        assert_eq!(bits(&sa.velocities), bits(&sb.velocities));
    }

    /// Run the asymmetric channel (a grid per size class if `split`) for 10⁴
    /// events, resume a copy from its checkpoint, and check that both have `grids`
    /// grids, follow the same next 2·10⁴ events and end with equal checkpoints.
    fn resumes_bit_identically(split: bool, grids: usize) -> Engine {
        let mut a = asymmetric_channel(split);
        assert_eq!(a.grid_count(), grids);
        a.run_collisions(10_000).unwrap();
        let mut b = Engine::from_checkpoint(a.checkpoint()).unwrap();
        assert_eq!(b.grid_count(), grids);
        assert_eq!(trajectory(&mut a, 20_000), trajectory(&mut b, 20_000));
        assert_eq!(a.checkpoint(), b.checkpoint());
        a
    }

    #[test]
    fn a_grid_per_size_class_resumes_bit_identically() {
        resumes_bit_identically(true, 2);
    }

    #[test]
    fn a_checkpoint_with_one_grid_for_all_sizes_resumes_with_one() {
        // As written before carom had size classes.
        let a = resumes_bit_identically(false, 1);
        // Lists that fit neither layout are refused, naming the cells needed.
        let mut cp = a.checkpoint();
        cp.cell_head.push(NO_DISC);
        let Err(EngineError::BadCheckpoint(m)) = Engine::from_checkpoint(cp) else {
            panic!("accepted a checkpoint with a cell too many");
        };
        assert!(m.contains("cells stored"), "{m}");
    }

    #[test]
    fn any_point_of_a_path_restores_it() {
        // carom writes each path's origin with time 0; a checkpoint naming another
        // point of the same line (the position at time t, as older checkpoints
        // stored it) must restore the same paths, to rounding.
        let mut a = channel_mixture();
        a.run_collisions(5_000).unwrap();
        let cp = a.checkpoint();
        assert!(cp.times.iter().all(|&t| t == 0.0));
        let mut moved = cp.clone();
        for (k, (p, v)) in moved.positions.iter_mut().zip(&cp.velocities).enumerate() {
            let t = cp.clock - 0.25 * (k % 4) as f64;
            *p += *v * t;
            moved.times[k] = t;
        }
        let b = Engine::from_checkpoint(moved).unwrap();
        let (sa, sb) = (a.state(), b.state());
        for (i, (pa, pb)) in sa.positions.iter().zip(&sb.positions).enumerate() {
            let d = a.sim_box().minimum_image(*pb - *pa).length();
            assert!(d < 1e-12, "disc {i}: restored {d} away from its path");
        }
        assert_eq!(sa.velocities, sb.velocities);
        // The same position named at another time is another path: the disc is
        // then displaced by v Δt (which shows the times are not ignored).
        let mut off = cp.clone();
        off.times[0] = 0.5;
        let c = Engine::from_checkpoint(off).unwrap();
        let ext = cp.labels[0] as usize;
        let d = a
            .sim_box()
            .minimum_image(c.state().positions[ext] - sa.positions[ext])
            .length();
        let expected = 0.5 * cp.velocities[0].length();
        assert!((d - expected).abs() < 1e-9, "{d} vs {expected}");
    }

    #[test]
    fn inconsistent_checkpoint_is_rejected() {
        let a = channel_mixture();
        let mut cp = a.checkpoint();
        cp.times.pop();
        assert!(matches!(
            Engine::from_checkpoint(cp),
            Err(EngineError::BadCheckpoint(_))
        ));
        let mut cp = a.checkpoint();
        cp.cell_next[3] = 1_000_000;
        assert!(matches!(
            Engine::from_checkpoint(cp),
            Err(EngineError::BadCheckpoint(_))
        ));
        // A list that loops back on itself (the event loop would never leave it).
        let mut cp = a.checkpoint();
        let first = cp.cell_head.iter().position(|&h| h != NO_DISC).unwrap();
        let d = cp.cell_head[first];
        cp.cell_next[d as usize] = d;
        let err = Engine::from_checkpoint(cp).unwrap_err().to_string();
        assert!(err.contains(&format!("disc {d} is listed twice")), "{err}");
        // Back links that do not match the forward links.
        let mut cp = a.checkpoint();
        cp.cell_prev[d as usize] = (d + 1) % cp.cell_prev.len() as u32;
        let err = Engine::from_checkpoint(cp).unwrap_err().to_string();
        assert!(err.contains("back links"), "{err}");
        // A path that is not finite: each of its three parts is named.
        let mut cp = a.checkpoint();
        cp.positions[2].x = f64::NAN;
        let err = Engine::from_checkpoint(cp).unwrap_err().to_string();
        assert!(err.contains("position of disc 2 is not finite"), "{err}");
        let mut cp = a.checkpoint();
        cp.velocities[4].y = f64::INFINITY;
        let err = Engine::from_checkpoint(cp).unwrap_err().to_string();
        assert!(err.contains("velocity of disc 4 is not finite"), "{err}");
        let mut cp = a.checkpoint();
        cp.times[1] = f64::NEG_INFINITY;
        let err = Engine::from_checkpoint(cp).unwrap_err().to_string();
        assert!(err.contains("time of disc 1 is not finite"), "{err}");
        // Finite parts whose path origin p − v t overflows.
        let mut cp = a.checkpoint();
        cp.velocities[3] = DVec2::new(1e300, 0.0);
        cp.times[3] = 1e300;
        let err = Engine::from_checkpoint(cp).unwrap_err().to_string();
        assert!(err.contains("path of disc 3 overflows"), "{err}");
    }
}
