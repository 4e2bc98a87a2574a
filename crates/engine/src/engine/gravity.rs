//! Uniform gravity g along −y in the engine (physics.md §15).
//!
//! A disc's record keeps the straight path p(t) = r0 + v t of body.rs, and its true
//! motion is that path with the fall added: r(t) = p(t) − ŷ g t²/2, velocity
//! v − ŷ g t, on the internal clock. Both discs of a pair fall alike, so their
//! relative motion is the straight relative motion of their paths: pair
//! predictions and collisions run on the paths unchanged (a collision changes
//! relative velocities only, and the rules are Galilean invariant). Only what
//! depends on a disc's own height or vertical velocity needs the fall: the
//! wall and cell-edge times along y (roots of quadratics, `carom_core::gravity`),
//! a wall's reflection, the positions and velocities handed out, and the
//! restart of the clock. These are separate functions, entered by one test of
//! g ≠ 0, so that the engine without a field does exactly what it did before. A
//! disc resting on the floor does not fall: its record is its straight true path
//! (engine::resting).

use super::body::{Body, Face, Pending};
use super::Engine;
use crate::error::EngineError;
use crate::event::PairCollision;
use carom_core::boundary::wall_time;
use carom_core::gravity::{crossing_time_falling, wall_time_falling};
use carom_core::{Boundary, DVec2, SimBox, WallSide};

impl Body {
    /// True position at internal time `t` in the field `g` (length): the path
    /// p(t) lowered by g t²/2 (physics.md (15.1)); the path itself for a disc
    /// resting on the floor.
    #[inline]
    pub(super) fn falling_at(&self, t: f64, g: f64) -> DVec2 {
        let p = self.at(t);
        if self.resting() {
            return p;
        }
        DVec2::new(p.x, p.y - 0.5 * g * t * t)
    }

    /// True velocity at internal time `t` in the field `g` (length/time): v − ŷ g t;
    /// v for a disc resting on the floor.
    #[inline]
    pub(super) fn falling_velocity(&self, t: f64, g: f64) -> DVec2 {
        if self.resting() {
            return self.v;
        }
        DVec2::new(self.v.x, self.v.y - g * t)
    }
}

/// Whether a field `g` (length/time², along −y) is allowed in `sim_box`: finite,
/// ≥ 0, and with hard walls along y when it is not 0 (a periodic y would let
/// discs fall for ever).
pub(crate) fn check_gravity(g: f64, sim_box: &SimBox) -> Result<(), EngineError> {
    let problem = if !(g.is_finite() && g >= 0.0) {
        format!("g = {g}")
    } else if g > 0.0 && matches!(sim_box.boundary[1], Boundary::Periodic) {
        format!("g = {g} with a periodic y axis")
    } else {
        return Ok(());
    };
    Err(EngineError::BadGravity(problem))
}

impl Engine {
    /// The field g (length/time², along −y; 0 when there is none).
    pub fn gravity(&self) -> f64 {
        self.params.gravity
    }

    /// Total potential energy U = Σ m g y in the field (energy; 0 without one), with
    /// y the height of each centre above the floor.
    pub fn potential_energy(&self) -> f64 {
        let g = self.params.gravity;
        if g == 0.0 {
            return 0.0;
        }
        self.bodies
            .iter()
            .map(|b| self.species[b.species as usize].mass * g * b.falling_at(self.clock, g).y)
            .sum()
    }

    /// Disc `i`'s earliest cell crossing or wall hit from now in the field, as
    /// [`Engine::boundary_event`] gives it without one: along x on its straight
    /// path, along y on its parabola (`carom_core::gravity`), and along y never
    /// while it rests on the floor. `p` is the disc's path point now (not its
    /// position), `v` its path velocity.
    #[cold]
    #[inline(never)]
    pub(super) fn boundary_event_falling(
        &self,
        i: usize,
        p: DVec2,
        v: DVec2,
    ) -> (f64, Pending, Face) {
        if self.params.floor.is_some() {
            return self.boundary_event_floor(i, p, v);
        }
        let (g, now) = (self.params.gravity, self.clock);
        let b = &self.bodies[i];
        let resting = b.resting();
        let c = b.link.coords();
        let grid = self.grids.get(self.grids.class(b.species));
        let radius = self.species[b.species as usize].radius;
        let mut best = f64::INFINITY;
        let (mut kind, mut face) = (Pending::None, Face::new(0, false));
        let mut keep = |dt: f64, k: Pending, f: Face| {
            if dt < best {
                (best, kind, face) = (dt, k, f);
            }
        };
        let (dt, up) = grid.crossing_time(0, c[0], p.x, v.x);
        keep(dt, Pending::Cell, Face::new(0, up));
        if let Boundary::Walls { .. } = self.sim_box.boundary[0] {
            if let Some((dt, side)) = wall_time(p.x, v.x, radius, self.sim_box.size.x) {
                keep(dt, Pending::Wall, Face::new(0, side == WallSide::High));
            }
        }
        if resting {
            return (best, kind, face);
        }
        let y = p.y - 0.5 * g * now * now;
        let u = v.y - g * now;
        let row = c[1];
        let last = row + 1 == grid.n[1];
        let lower = row as f64 * grid.width.y;
        let upper = if last {
            grid.size.y
        } else {
            (row + 1) as f64 * grid.width.y
        };
        // y has walls (checked when the engine is built): the first and last rows'
        // outer edges are the box's.
        let (dt, up) = crossing_time_falling(y, u, [lower, upper], [row > 0, !last], g);
        keep(dt, Pending::Cell, Face::new(1, up));
        let (dt, side) = wall_time_falling(y, u, radius, self.sim_box.size.y, g);
        keep(dt, Pending::Wall, Face::new(1, side == WallSide::High));
        (best, kind, face)
    }

    /// Disc `i`'s earliest event from now, predicted in the field or without one,
    /// as the engine's parameters say (for callers outside the event loop).
    pub(super) fn predict_any(&mut self, i: usize) {
        if self.params.gravity != 0.0 || self.params.floor.is_some() {
            self.predict::<true, false>(i);
        } else if self.params.growth.rate != 0.0 {
            self.predict::<false, true>(i);
        } else {
            self.predict::<false, false>(i);
        }
    }

    /// Make the velocities of the collision `ev`, resolved on the discs' paths, the
    /// discs' true ones at the collision, internal time `now`.
    #[cold]
    #[inline(never)]
    pub(super) fn falling_pair(&self, ev: &mut PairCollision, now: f64) {
        let lift = DVec2::new(0.0, self.params.gravity * now);
        ev.vi_before -= lift;
        ev.vj_before -= lift;
        ev.vi_after -= lift;
        ev.vj_after -= lift;
    }

    /// In the field, ask for an early restart of the clock once it has run for
    /// √(L_y/g), the time to fall half the box: a path velocity v = u + ŷ g t and
    /// origin grow with the clock, and their rounding with them.
    pub(super) fn keep_fall_short(&mut self) {
        let g = self.params.gravity;
        if g > 0.0 && self.clock * self.clock * g > self.sim_box.size.y {
            self.next_reorder = self.next_reorder.min(self.stats.pair_collisions);
        }
    }
}
