//! The equations of motion: one seam through which the event loop moves discs.
//!
//! Between events a disc follows a law of motion chosen once per engine: a
//! straight line r(t) = r0 + v t (physics.md §1, [`Straight`]), a parabola in
//! the field g, r(t) = r0 + v t − ŷ g t²/2 (§15, with an optional vibrating
//! floor §18, [`Falling`]), or a straight line with radii growing as
//! a(t) = a⁰ (s₀ + γ t) (§17, [`Growing`]). A law says how its discs move (their
//! true position and velocity), when a pair meets and when a disc meets a cell
//! edge or a wall, and what a collision's resolution adds to the plain rule.
//! The event loop, prediction and resolution are generic over [`Motion`] and
//! compiled once per law, so that the straight loop is compiled as if fields
//! and growth did not exist (docs/performance.md, "engine").

mod falling;
mod growing;
mod listed;
mod straight;

use super::body::{Aux, Body, Face, Pending};
use super::Engine;
use crate::event::PairCollision;
use carom_core::collision::Resolution;
use carom_core::DVec2;
pub(super) use falling::Falling;
pub(super) use growing::Growing;
pub(super) use listed::Listed;
pub(super) use straight::Straight;

/// A law of motion between events (see the module documentation). Every method
/// is called on the hot path and inlined: a law is a type with no data, its
/// parameters read from the engine.
pub(super) trait Motion {
    /// What a neighbour scan needs of the law at the current time (the field g,
    /// or the radii's scale and rate (s, γ)).
    type Scan: Copy;

    /// Whether discs find their partners in neighbour lists (engine::listed)
    /// rather than in the cell grid.
    const LISTS: bool = false;

    /// The law's [`Motion::Scan`] now.
    fn scan(e: &Engine) -> Self::Scan;

    /// Time from now (≥ 0, or +∞) until discs i (record `bi`, path point now
    /// `ri`, shifted for the image through which j is seen) and j (record `bj`)
    /// meet at contact distance `sigma` (of the reference radii); `dr` is
    /// r_j − r_i now, `now` the internal clock.
    fn pair_time(
        bi: &Body,
        ri: DVec2,
        bj: &Body,
        dr: DVec2,
        sigma: f64,
        now: f64,
        law: Self::Scan,
    ) -> f64;

    /// Disc `i`'s earliest cell crossing or wall hit from now: (time from now,
    /// kind, face). `p` is its path point now, `v` its path velocity.
    fn boundary_event(e: &Engine, i: usize, p: DVec2, v: DVec2) -> (f64, Pending, Face);

    /// The event byte a new prediction files, `new`, given the record's `old`
    /// one: only a field keeps the resting flag (engine::resting).
    #[inline(always)]
    fn file_aux(_old: Aux, new: Aux) -> Aux {
        new
    }

    /// Before a pair collision of discs i and j: whether both rest on the floor
    /// (a resting disc hit by a falling one falls again first; engine::resting).
    #[inline(always)]
    fn pair_on_floor(_e: &mut Engine, _i: usize, _j: usize) -> bool {
        false
    }

    /// What the law adds to the rule's resolution `res` of discs i and j (masses
    /// `m`, velocities before `v`) at separation `dr`.
    #[inline(always)]
    fn pair_extra(
        _e: &Engine,
        _ij: (usize, usize),
        _dr: DVec2,
        _v: (DVec2, DVec2),
        _m: (f64, f64),
        _res: &mut Resolution,
    ) {
    }

    /// After the new velocities of discs i and j are set (`on_floor` as
    /// [`Motion::pair_on_floor`] said): discs that rested and were moved fall.
    #[inline(always)]
    fn after_pair(_e: &mut Engine, _i: usize, _j: usize, _on_floor: bool) {}

    /// Make the velocities of the reported collision `ev`, resolved on the
    /// paths, the discs' true ones.
    #[inline(always)]
    fn report_pair(_e: &Engine, _ev: &mut PairCollision, _on_floor: bool) {}

    /// Whether disc `b` rests on the floor (its path is then its true one).
    #[inline(always)]
    fn resting(_b: &Body) -> bool {
        false
    }

    /// The impulse (along the wall's axis) a wall `high` (or low) gives disc `i`
    /// of mass `m` and normal velocity `vk` with restitution `e_wall`.
    #[inline(always)]
    fn wall_impulse(_e: &Engine, _i: usize, vk: f64, m: f64, e_wall: f64, _high: bool) -> f64 {
        carom_core::boundary::wall_impulse(vk, m, e_wall)
    }

    /// The kinetic energy a wall hit takes (mass `m`, normal velocity `vk`
    /// before and `after`, restitution `e_wall`).
    #[inline(always)]
    fn wall_energy_lost(m: f64, vk: f64, _after: f64, e_wall: f64) -> f64 {
        0.5 * m * (1.0 - e_wall * e_wall) * vk * vk
    }

    /// Whether disc `i`, hit by the wall `face` and leaving at normal velocity
    /// `after`, rests on the floor instead (15.9).
    #[inline(always)]
    fn rests(_e: &Engine, _i: usize, _face: Face, _after: f64) -> bool {
        false
    }

    /// The growth's next instant, a rescale or its end (internal time), for a law
    /// whose radii grow; `None` for the others.
    #[inline(always)]
    fn growth_due(_e: &Engine) -> Option<f64> {
        None
    }

    /// Whether the wall `face` is the vibrating floor (resolved by
    /// [`Engine::hit_floor`]).
    #[inline(always)]
    fn is_floor(_e: &Engine, _face: Face) -> bool {
        false
    }
}

impl Engine {
    /// Disc `i`'s earliest event from now, predicted by the engine's law of
    /// motion (for callers outside the event loop).
    pub(in crate::engine) fn predict_any(&mut self, i: usize) {
        if self.params.gravity != 0.0 || self.params.floor.is_some() {
            self.predict::<Falling>(i);
        } else if self.params.growth.rate != 0.0 {
            self.predict::<Growing>(i);
        } else if self.lists.is_some() {
            self.predict::<Listed>(i);
        } else {
            self.predict::<Straight>(i);
        }
    }
}
