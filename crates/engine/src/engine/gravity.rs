//! Uniform gravity g along −y in the engine (physics.md §15).
//!
//! A disc's record keeps the straight path p(t) = r0 + v t of body.rs; its true
//! motion adds the fall, r(t) = p(t) − ŷ g t²/2 with velocity v − ŷ g t, on the
//! internal clock. Both discs of a pair fall alike, so their relative motion is the
//! straight one of their paths: pair predictions and collisions run on the paths
//! unchanged (the rules are Galilean invariant). Only what depends on a disc's own
//! height or vertical velocity needs the fall: wall and cell-edge times along y
//! (roots of quadratics, `carom_core::gravity`), a wall's reflection, the positions
//! and velocities handed out, and the clock's restart. These are separate
//! functions, reached only when g ≠ 0 (most through the falling law of motion,
//! engine::motion). A disc resting on the floor does not fall (engine::resting).

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

/// A disc's vertical motion now and its cell row, as the field's and the
/// floor's boundary events need them.
pub(super) struct Vertical {
    /// True height (length).
    pub(super) y: f64,
    /// True vertical velocity (length/time).
    pub(super) u: f64,
    /// The cell row.
    pub(super) row: u32,
    /// The row's lower and upper edges (length).
    pub(super) edges: [f64; 2],
    /// Whether each edge is a cell edge rather than the box's.
    pub(super) inner: [bool; 2],
}

/// Keep the event (time from now `dt`, kind, face) in `out` if it comes before
/// the one there.
#[inline]
pub(super) fn keep(out: &mut (f64, Pending, Face), dt: f64, kind: Pending, face: Face) {
    if dt < out.0 {
        *out = (dt, kind, face);
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
    /// [`Engine::boundary_event_straight`] gives it without one: along x on its straight
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
        let mut out = self.side_event(i, p, v);
        if self.bodies[i].resting() {
            return out;
        }
        let g = self.params.gravity;
        let y = self.vertical(i, p, v);
        // y has walls (checked when the engine is built): the first and last rows'
        // outer edges are the box's.
        let (dt, up) = crossing_time_falling(y.y, y.u, y.edges, y.inner, g);
        keep(&mut out, dt, Pending::Cell, Face::new(1, up));
        let radius = self.species[self.bodies[i].species as usize].radius;
        let (dt, side) = wall_time_falling(y.y, y.u, radius, self.sim_box.size.y, g);
        keep(
            &mut out,
            dt,
            Pending::Wall,
            Face::new(1, side == WallSide::High),
        );
        out
    }

    /// Disc `i`'s earliest event along x, on its straight path (`p` its path
    /// point now, `v` its path velocity): its cell crossing, or a wall hit if
    /// that comes first.
    pub(super) fn side_event(&self, i: usize, p: DVec2, v: DVec2) -> (f64, Pending, Face) {
        let b = &self.bodies[i];
        let c = b.link.coords();
        let grid = self.grids.get(self.grids.class(b.species));
        let radius = self.species[b.species as usize].radius;
        let (dt, up) = grid.crossing_time(0, c[0], p.x, v.x);
        let mut out = (f64::INFINITY, Pending::None, Face::new(0, false));
        keep(&mut out, dt, Pending::Cell, Face::new(0, up));
        if let Boundary::Walls { .. } = self.sim_box.boundary[0] {
            if let Some((dt, side)) = wall_time(p.x, v.x, radius, self.sim_box.size.x) {
                keep(
                    &mut out,
                    dt,
                    Pending::Wall,
                    Face::new(0, side == WallSide::High),
                );
            }
        }
        out
    }

    /// Disc `i`'s true height and vertical velocity now in the field, and its
    /// cell row's edges (`p` its path point now, `v` its path velocity).
    pub(super) fn vertical(&self, i: usize, p: DVec2, v: DVec2) -> Vertical {
        let (g, now) = (self.params.gravity, self.clock);
        let b = &self.bodies[i];
        let grid = self.grids.get(self.grids.class(b.species));
        let row = b.link.coords()[1];
        let last = row + 1 == grid.n[1];
        let lower = row as f64 * grid.width.y;
        let upper = if last {
            grid.size.y
        } else {
            (row + 1) as f64 * grid.width.y
        };
        Vertical {
            y: p.y - 0.5 * g * now * now,
            u: v.y - g * now,
            row,
            edges: [lower, upper],
            inner: [row > 0, !last],
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
