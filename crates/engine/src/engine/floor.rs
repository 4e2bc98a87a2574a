//! The vibrating floor in the engine (physics.md §18).
//!
//! The bottom wall moves as h(t') = A (1 − cos ω t'), t' the time since it was set
//! (`floor_origin`, in reported time, so the phase survives the clock's restarts
//! and a checkpoint). An engine with a floor runs the event loop compiled for a
//! field (`engine::motion::Falling`, engine::gravity), with g = 0 when there is none: the plain loop
//! never sees the floor. For a disc in a cell row the floor's band can reach
//! (lower edge below 2A + a), the floor contact is searched by conservative
//! advancement (`carom_core::vibrating_wall`) up to the disc's other boundary
//! events; a search that stops at its step limit leaves a [`Pending::Recheck`]
//! event there. A hit reverses the velocity relative to the floor,
//! v' = w − e (v − w), and the kinetic energy it gives goes to `Stats::floor_work`.

use super::body::{Face, Pending};
use super::gravity::{keep, Vertical};
use super::Engine;
use crate::error::EngineError;
use crate::event::WallCollision;
use carom_core::collision::apply_wall_impulse;
use carom_core::gravity::{crossing_time_falling, rise_time};
use carom_core::vibrating_wall::{bounce, FloorContact};
use carom_core::{Axis, Boundary, DVec2, SimBox, Species, WallSide};

/// Whether the floor of `params` (if any) is allowed in `sim_box` with the
/// `species`: amplitude and angular frequency finite and > 0, hard walls along y,
/// the top of the floor's travel 2A plus the largest diameter within half the box
/// height, and no growing discs.
pub(crate) fn check_floor(
    params: &super::EngineParams,
    sim_box: &SimBox,
    species: &[Species],
) -> Result<(), EngineError> {
    let Some(fl) = params.floor else {
        return Ok(());
    };
    let bad = |m: String| Err(EngineError::BadFloor(m));
    let (a, w) = (fl.amplitude, fl.omega);
    if !(a.is_finite() && a > 0.0) {
        return bad(format!("amplitude = {a} (allowed: finite, > 0)"));
    }
    if !(w.is_finite() && w > 0.0) {
        return bad(format!(
            "frequency = {} (allowed: finite, > 0)",
            w / std::f64::consts::TAU
        ));
    }
    if !(a * w * w).is_finite() {
        return bad(format!(
            "amplitude × (2π frequency)² = {} overflows",
            a * w * w
        ));
    }
    if matches!(sim_box.boundary[1], Boundary::Periodic) {
        return bad("the y axis is periodic (allowed: hard walls along y)".into());
    }
    let diameter = species.iter().map(|s| 2.0 * s.radius).fold(0.0, f64::max);
    let half = 0.5 * sim_box.size.y;
    if 2.0 * a + diameter > half {
        return bad(format!(
            "2 × amplitude + the largest diameter = {} exceeds half the box height {half} \
             (allowed: at most half the box height)",
            2.0 * a + diameter
        ));
    }
    if params.growth.rate != 0.0 {
        return bad("with compression (growing discs) (allowed: one or the other)".into());
    }
    Ok(())
}

impl Engine {
    /// The floor's phase t' now (time since it was set), on the internal clock's
    /// time `t`.
    #[inline]
    fn floor_phase(&self, t: f64) -> f64 {
        (self.epoch - self.floor_origin) + t
    }

    /// The floor's height (length) now, 0 without one.
    pub fn floor_height(&self) -> f64 {
        self.params
            .floor
            .map_or(0.0, |fl| fl.height(self.floor_phase(self.clock)))
    }

    /// Disc `i`'s earliest cell crossing, wall hit or floor contact from now, with
    /// the vibrating floor: as [`Engine::boundary_event_falling`] (g may be 0), the
    /// floor's contact searched up to the earliest of the others. `p` is the disc's
    /// path point now, `v` its path velocity.
    #[cold]
    #[inline(never)]
    pub(super) fn boundary_event_floor(
        &self,
        i: usize,
        p: DVec2,
        v: DVec2,
    ) -> (f64, Pending, Face) {
        let fl = self.params.floor.expect("called with a floor");
        let g = self.params.gravity;
        let b = &self.bodies[i];
        let grid = self.grids.get(self.grids.class(b.species));
        let radius = self.species[b.species as usize].radius;
        let mut out = self.side_event(i, p, v);
        let Vertical {
            y,
            u,
            row,
            edges,
            inner,
        } = self.vertical(i, p, v);
        let (dt, up) = if g > 0.0 {
            crossing_time_falling(y, u, edges, inner, g)
        } else {
            grid.crossing_time(1, row, y, u)
        };
        keep(&mut out, dt, Pending::Cell, Face::new(1, up));
        keep(
            &mut out,
            rise_time(self.sim_box.size.y - radius - y, u, g),
            Pending::Wall,
            Face::new(1, true),
        );
        if edges[0] < 2.0 * fl.amplitude + radius {
            let phase = self.floor_phase(self.clock);
            match fl.contact_time(y, u, radius, g, phase, out.0) {
                FloorContact::At(dt) => keep(&mut out, dt, Pending::Wall, Face::new(1, false)),
                FloorContact::NotBefore(dt) => {
                    keep(&mut out, dt, Pending::Recheck, Face::new(1, false))
                }
                FloorContact::Beyond => {}
            }
        }
        out
    }

    /// Resolve disc `i`'s hit on the vibrating floor now: v' = w − e (v − w) with w
    /// the floor's velocity (physics.md (18.4); e the wall restitution, or 1 under
    /// the TC model), applied as an impulse like any wall's; the energy given goes
    /// to `floor_work`. A disc not approaching the floor keeps its velocity.
    #[cold]
    #[inline(never)]
    pub(super) fn hit_floor(&mut self, i: usize) -> WallCollision {
        let fl = self.params.floor.expect("called with a floor");
        let now = self.clock;
        let wall_e = match self.sim_box.boundary[1] {
            Boundary::Walls { restitution } => restitution,
            Boundary::Periodic => unreachable!("a floor on a periodic axis"),
        };
        let e = if self.within_tc(i, now) { 1.0 } else { wall_e };
        if self.params.tc > 0.0 {
            self.last_collision[i] = now;
        }
        let m = self.species[self.bodies[i].species as usize].mass;
        let lift = self.params.gravity * now;
        let path_v = self.bodies[i].v;
        let vy = path_v.y - lift;
        let w = fl.velocity(self.floor_phase(now));
        let dp = m * (bounce(vy, w, e) - vy);
        // Applied as v + Δp/m, the arithmetic a reader of the log repeats.
        let after = apply_wall_impulse(vy, m, dp);
        let mut path_after = path_v;
        path_after.y = after + lift;
        self.bodies[i].set_velocity(path_after, now);
        self.keep_origin_near([i]);
        self.keep_fall_short();
        self.bodies[i].count = self.bodies[i].count.wrapping_add(1);
        let work = 0.5 * m * (after * after - vy * vy);
        self.stats.wall_collisions += 1;
        self.stats.wall_impulse[1][0] += dp.abs();
        self.stats.floor_work += work;
        self.predict::<super::motion::Falling>(i);
        WallCollision {
            time: self.reported,
            i: self.label[i],
            axis: Axis::Y,
            side: WallSide::Low,
            v_before: DVec2::new(path_v.x, vy),
            v_after: DVec2::new(path_v.x, after),
            impulse: dp.abs(),
            energy_lost: -work,
        }
    }
}
