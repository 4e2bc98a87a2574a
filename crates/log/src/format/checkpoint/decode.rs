//! Decoding a `/checkpoint` message, field by field in the order of the schema
//! ([`super::CHECKPOINT_MSG`]), reading older format versions too.

use super::calendar::{decode_thermostat, split_scheduled};
use super::lists::decode_neighbours;
use super::{DriverState, LogCheckpoint, CHECKPOINT_FORMAT_VERSION};
use crate::format::cdr::{CdrError, CdrReader};
use carom_core::vibrating_wall::Floor;
use carom_core::{Boundary, DVec2, Restitution, SimBox, Species};
use carom_engine::{Checkpoint, EngineParams, GrowthEnd, GrowthState, Stats};

impl LogCheckpoint {
    /// Decode from CDR. Checks the layout and the lengths of paired arrays; the
    /// engine's own [`carom_engine::Engine::from_checkpoint`] checks the rest.
    pub fn decode(data: &[u8]) -> Result<Self, CdrError> {
        let mut r = CdrReader::new(data)?;
        let version: u32 = r.get("format_version")?;
        // Version 5 is version 6 without the neighbour search, 4 also without
        // growth, 3 also without gravity and the thermostat, 2 also without the
        // images.
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
        let mut thermostat = if version >= 4 {
            decode_thermostat(&mut r)?
        } else {
            None
        };
        let (scheduled, next) = split_scheduled(scheduled, thermostat.is_some());
        if let Some(t) = &mut thermostat {
            t.next = next;
        }
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
        let mut lists = None;
        if version >= 6 {
            (params.neighbours, lists) = decode_neighbours(&mut r, species_of.len())?;
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
                lists,
            },
        })
    }
}
