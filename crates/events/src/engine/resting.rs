//! Discs resting on the floor in a field (physics.md §15, (15.9)–(15.10)).
//!
//! A disc that leaves the static floor with an upward velocity u whose apex
//! a + u²/(2g) rounds to a (u = 0 above all: a disc put at rest on the floor) would
//! hit it again at once for ever. It *rests* instead: the floor takes its whole
//! vertical momentum, its record holds the straight path (x0 + v_x t, a) with
//! v_y = 0 and no fall (the flag in [`super::body::Aux`]), and it slides at
//! constant v_x, meeting side walls and crossing cells along x only. It leaves the
//! floor only in a pair collision: a resting disc hit by a falling one is first
//! turned back into a falling path at the floor (so that the pair's relative
//! motion is straight again and the collision resolves as any other), and one
//! not sent up is met by the floor at once, bounced or laid to rest again. Two
//! resting discs fly straight relative to each other, as do two falling ones; a
//! resting and a falling disc accelerate apart by g, and their contact time is
//! the quartic (15.10) (`carom_core::gravity::contact_time_one_falling`).

use super::body::Body;
use super::Engine;
use carom_core::gravity::{contact_time_one_falling, rebound_rests};
use carom_core::DVec2;

impl Body {
    /// Whether the disc rests on the floor (its path is straight, no fall).
    #[inline(always)]
    pub(super) fn resting(&self) -> bool {
        self.aux.resting()
    }
}

/// Time from now (≥ 0, or +∞) until discs i (record `bi`, path point now `ri`,
/// shifted for the image through which j is seen) and j (record `bj`) at contact
/// distance `sigma` meet when exactly one of them rests: from the paths, the true
/// relative position and velocity now (a falling path runs ahead by ŷ g t²/2 in
/// position and ŷ g t in velocity, engine::gravity) and the relative acceleration
/// ±g ŷ (+g when i falls), into (15.10). `g` the field, `now` the internal clock.
#[cold]
#[inline(never)]
pub(super) fn contact_time_resting(
    bi: &Body,
    ri: DVec2,
    bj: &Body,
    sigma: f64,
    g: f64,
    now: f64,
) -> f64 {
    let s = if bi.resting() { -1.0 } else { 1.0 };
    let dr = bj.at(now) - ri + DVec2::new(0.0, s * 0.5 * g * now * now);
    let dv = bj.v - bi.v + DVec2::new(0.0, s * g * now);
    contact_time_one_falling(dr, dv, sigma, s * g)
}

impl Engine {
    /// Whether disc `i`, hit by the static floor now and leaving it at upward
    /// velocity `u` (length/time), comes to rest (15.9): in a field, without a
    /// vibrating floor.
    pub(super) fn rests_on_floor(&self, i: usize, u: f64) -> bool {
        let g = self.params.gravity;
        let radius = self.species[self.bodies[i].species as usize].radius;
        g > 0.0 && self.params.floor.is_none() && rebound_rests(radius, u, g)
    }

    /// Lay disc `i` to rest on the floor, whose velocity already has v_y = 0: its
    /// height is set to its radius a (from within rounding of it) and its path
    /// stops falling.
    pub(super) fn lay_to_rest(&mut self, i: usize) {
        let radius = self.species[self.bodies[i].species as usize].radius;
        let b = &mut self.bodies[i];
        debug_assert_eq!(b.v.y, 0.0);
        b.r0.y = radius;
        b.aux = b.aux.with_resting(true);
    }

    /// Let resting disc `i` fall again from where it is now, with its velocity
    /// now: the falling path through the same point, with its height (as the
    /// engine computes it) at most a, never a rounding error above the floor, so
    /// that a disc not moving up is met by the floor now and one moving up comes
    /// back after 2u/g (15.4). The caller bumps its collision counter.
    pub(super) fn lift_off(&mut self, i: usize) {
        let (g, now) = (self.params.gravity, self.clock);
        let radius = self.species[self.bodies[i].species as usize].radius;
        let b = &mut self.bodies[i];
        b.v.y += g * now;
        b.r0.y = radius - b.v.y * now + 0.5 * g * now * now;
        b.aux = b.aux.with_resting(false);
        // Rounding may leave it above a by a few ulps: lower the origin by ulps.
        for _ in 0..64 {
            if b.falling_at(now, g).y <= radius {
                break;
            }
            b.r0.y = b.r0.y.next_down();
        }
    }

    /// Before a pair collision of discs `i` and `j` in a field: a resting disc
    /// hit by a falling one falls again ([`Engine::lift_off`]), so that both
    /// paths fall and the collision resolves on them as any other. Returns
    /// whether both rest (their paths are then the straight true ones).
    pub(super) fn pair_on_floor(&mut self, i: usize, j: usize) -> bool {
        match (self.bodies[i].resting(), self.bodies[j].resting()) {
            (true, true) => true,
            (true, false) => {
                self.lift_off(i);
                false
            }
            (false, true) => {
                self.lift_off(j);
                false
            }
            (false, false) => false,
        }
    }

    /// After a collision of two resting discs: disc `i` falls again if the
    /// collision gave it a vertical velocity (discs of different radii touch
    /// off the horizontal).
    pub(super) fn leave_floor_if_moved(&mut self, i: usize) {
        if self.bodies[i].v.y != 0.0 {
            self.lift_off(i);
        }
    }
}
