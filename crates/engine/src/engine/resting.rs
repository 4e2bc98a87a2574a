//! Discs resting on the floor in a field (physics.md §15, (15.9)–(15.10)).
//!
//! A disc leaving the static floor with an upward velocity u whose apex
//! a + u²/(2g) rounds to a (u = 0 above all) would hit it again at once for ever. It
//! *rests* instead: the floor takes its vertical momentum, its record holds the
//! straight path (x0 + v_x t, a) with v_y = 0 and no fall (the flag in
//! [`super::body::Aux`]), and it slides along x, meeting side walls and crossing
//! cells along x only. Only a pair collision lifts it: it is first turned back into
//! a falling path at the floor, so the pair's relative motion is straight and
//! resolves as any other; if not sent up, the floor meets it at once. A resting and
//! a falling disc accelerate apart by g: their contact time is the quartic (15.10)
//! (`carom_core::gravity::contact_time_one_falling`).

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

#[cfg(test)]
mod tests {
    use crate::{Engine, EngineError, EngineParams, Event, State};
    use carom_core::{Boundary, DVec2, SimBox, Species};

    /// Discs of radius 0.5 and mass 1 at `positions` with `velocities` in a box
    /// `lx` × 10 with walls along y (restitution `wall_e`) and along x (elastic) or
    /// periodic x.
    fn discs(lx: f64, periodic_x: bool, wall_e: f64, pv: &[([f64; 2], [f64; 2])]) -> State {
        let n = pv.len();
        State {
            sim_box: SimBox {
                size: DVec2::new(lx, 10.0),
                boundary: [
                    if periodic_x {
                        Boundary::Periodic
                    } else {
                        Boundary::Walls { restitution: 1.0 }
                    },
                    Boundary::Walls {
                        restitution: wall_e,
                    },
                ],
            },
            species: vec![Species::reference(n)],
            species_of: vec![0; n],
            positions: pv.iter().map(|p| DVec2::from(p.0)).collect(),
            velocities: pv.iter().map(|p| DVec2::from(p.1)).collect(),
            images: Vec::new(),
            time: 0.0,
        }
    }

    fn field(g: f64) -> EngineParams {
        EngineParams {
            gravity: g,
            ..EngineParams::default()
        }
    }

    /// K + U + the energy the walls took (energy).
    fn books(e: &Engine) -> f64 {
        e.kinetic_energy() + e.potential_energy() + e.stats().energy_lost
    }

    /// The disc at rest on the floor (centre at a = 0.5, v = 0, g = 1):
    /// one floor hit with no impulse at t = 0 lays it to rest; then nothing happens
    /// and time runs to the stop, the disc exactly where it was.
    #[test]
    fn a_disc_put_at_rest_on_the_floor_rests_there_while_time_runs() {
        let mut e = Engine::new(
            discs(10.0, false, 1.0, &[([5.0, 0.5], [0.0, 0.0])]),
            field(1.0),
        )
        .unwrap();
        match e.next_event().unwrap() {
            Some(Event::Wall(w)) => {
                assert_eq!((w.time, w.impulse, w.v_after), (0.0, 0.0, DVec2::ZERO));
            }
            other => panic!("expected the floor hit that lays it to rest: {other:?}"),
        }
        assert!(e.bodies[0].resting());
        assert_eq!(e.next_event().unwrap(), None, "a resting disc has no event");
        assert_eq!(e.run_until(1e3).unwrap(), 0);
        assert_eq!(e.now(), 1e3);
        assert_eq!(e.position(0), DVec2::new(5.0, 0.5));
        assert_eq!(e.velocity(0), DVec2::ZERO);
        assert_eq!(e.kinetic_energy() + e.potential_energy(), 0.5);
    }

    /// Sliding at 1 along the floor of a periodic box 10 wide: at every time x is
    /// x0 + t wrapped, y stays a exactly and K + U = 1/2 + 1/2; between side walls
    /// it is reflected at x = 0.5 and 9.5.
    #[test]
    fn a_disc_sliding_on_the_floor_moves_at_constant_speed() {
        for periodic in [true, false] {
            let mut e = Engine::new(
                discs(10.0, periodic, 1.0, &[([5.0, 0.5], [1.0, 0.0])]),
                field(1.0),
            )
            .unwrap();
            for k in 1..=40 {
                let t = 2.35 * k as f64;
                e.run_until(t).unwrap();
                let x = 5.0 + t;
                let expected = if periodic {
                    x.rem_euclid(10.0)
                } else {
                    // Unfolded along 0.5..9.5 (a travel of 9 each way).
                    let s = (x - 0.5).rem_euclid(18.0);
                    0.5 + if s <= 9.0 { s } else { 18.0 - s }
                };
                let p = e.position(0);
                assert!(
                    (p.x - expected).abs() < 1e-12,
                    "t {t}: x {} vs {expected}",
                    p.x
                );
                assert_eq!(p.y, 0.5, "t {t}");
                assert_eq!(e.velocity(0).y, 0.0);
                assert_eq!(e.velocity(0).x.abs(), 1.0);
                assert_eq!(e.kinetic_energy() + e.potential_energy(), 1.0);
            }
        }
    }

    /// Dropped from 2 above the floor (g = 1) on a floor of restitution 1/2: it
    /// lands at t = 2 at speed 2 and its bounces of 2 u_k/g with u_k = 2^{1−k}
    /// add up to 4: it comes to rest at t = 6 (its last bounce, of apex below the
    /// rounding of a, lasts ≈ 10⁻⁸), with K + U + the energy lost at the floor
    /// kept. With restitution 0 it rests at once at t = 2.
    #[test]
    fn an_inelastic_floor_lays_a_bouncing_disc_to_rest_when_its_bounces_end() {
        for (wall_e, rest_at) in [(0.5, 6.0), (0.0, 2.0)] {
            let mut e = Engine::new(
                discs(10.0, false, wall_e, &[([5.0, 2.5], [0.0, 0.0])]),
                field(1.0),
            )
            .unwrap();
            let start = books(&e);
            let mut last = 0.0;
            while let Some(ev) = e.next_event().unwrap() {
                match ev {
                    Event::Wall(w) => last = w.time,
                    other => panic!("{other:?}"),
                }
            }
            assert!(e.bodies[0].resting());
            assert!((last - rest_at).abs() < 1e-7, "rests at {last}");
            assert_eq!(e.position(0).y, 0.5);
            assert!(
                (books(&e) - start).abs() < 1e-14,
                "{} vs {start}",
                books(&e)
            );
            e.run_until(100.0).unwrap();
            assert_eq!(e.position(0), DVec2::new(5.0, 0.5));
        }
    }

    /// j dropped from rest with its centre at (5.3, 3.5) onto i resting at
    /// (5, 0.5) (σ = 1, g = 1): they touch when (3 − t²/2)² + 0.3² = 1,
    /// t = √(2 (3 − √0.91)); a brute-force walk of the true positions in steps of
    /// 10⁻⁶ finds the first overlap within one step after it. Then, over 10⁴
    /// collisions, K + U stays the same to rounding and no pair overlaps.
    #[test]
    fn a_disc_dropped_onto_a_resting_one_meets_it_at_the_quartic_root() {
        let mut e = Engine::new(
            discs(
                10.0,
                false,
                1.0,
                &[([5.0, 0.5], [0.0, 0.0]), ([5.3, 3.5], [0.0, 0.0])],
            ),
            field(1.0),
        )
        .unwrap();
        let start = e.kinetic_energy() + e.potential_energy();
        let hit = loop {
            match e.next_event().unwrap().unwrap() {
                Event::Pair(p) => break p,
                Event::Wall(w) => assert_eq!(w.time, 0.0, "only i's laying to rest: {w:?}"),
                other => panic!("{other:?}"),
            }
        };
        let exact = (2.0 * (3.0 - 0.91f64.sqrt())).sqrt();
        assert!((hit.time - exact).abs() < 1e-13, "{} vs {exact}", hit.time);
        let gap = |t: f64| (DVec2::new(0.3, 3.0 - 0.5 * t * t)).length() - 1.0;
        let step = 1e-6;
        let first = (0..)
            .map(|k| k as f64 * step)
            .find(|&t| gap(t) <= 0.0)
            .unwrap();
        assert!(
            first >= hit.time && first - hit.time <= step,
            "brute force {first}"
        );
        let mut collisions = 0;
        while collisions < 10_000 {
            match e.next_event().unwrap().unwrap() {
                Event::Pair(_) | Event::Wall(_) => collisions += 1,
                Event::Scheduled { .. } | Event::Pause { .. } => {}
            }
            let d = (e.position(1) - e.position(0)).length();
            assert!(d > 1.0 - 1e-12, "overlap {d} at {}", e.now());
        }
        let end = e.kinetic_energy() + e.potential_energy();
        assert!((end - start).abs() < 1e-11 * start, "{end} vs {start}");
        assert!(e.now() > 100.0, "time advances: {}", e.now());
    }

    /// Resting discs side by side with a bouncing one between them and a gas of
    /// falling discs above: a checkpoint taken with discs resting continues bit
    /// for bit; its resting bit (16 of the pending word) marks them, and a
    /// checkpoint whose resting disc is off the floor is refused.
    #[test]
    fn a_checkpoint_keeps_the_discs_that_rest() {
        let mut pv = vec![
            ([1.0, 0.5], [0.0, 0.0]),
            ([2.5, 0.5], [0.3, 0.0]),
            ([6.0, 0.5], [-0.2, 0.0]),
            ([9.0, 0.5], [0.0, 0.0]),
            ([4.2, 4.0], [0.0, 0.0]),
        ];
        for k in 0..8 {
            let x = 1.0 + 2.5 * (k % 4) as f64;
            pv.push(([x, 6.0 + 1.5 * (k / 4) as f64], [0.4 - 0.1 * k as f64, 0.5]));
        }
        let mut a = Engine::new(discs(10.0, true, 1.0, &pv), field(1.0)).unwrap();
        let start = a.kinetic_energy() + a.potential_energy();
        // The first checkpoint after 50 collisions with a disc resting.
        a.run_collisions(50).unwrap();
        while !a.bodies.iter().any(|b| b.resting()) {
            a.run_collisions(1).unwrap();
        }
        let cp = a.checkpoint();
        assert!(
            cp.pending.iter().any(|p| p[2] >> 16 == 1),
            "some disc rests"
        );
        let mut b = Engine::from_checkpoint(cp.clone()).unwrap();
        for _ in 0..3000 {
            assert_eq!(a.next_event().unwrap(), b.next_event().unwrap());
        }
        assert_eq!(a.checkpoint(), b.checkpoint());
        let end = a.kinetic_energy() + a.potential_energy();
        assert!((end - start).abs() < 1e-11 * start, "{end} vs {start}");
        let k = cp.pending.iter().position(|p| p[2] >> 16 == 1).unwrap();
        let mut off = cp.clone();
        off.positions[k].y += 1.0;
        match Engine::from_checkpoint(off) {
            Err(EngineError::BadCheckpoint(m)) => assert!(m.contains("resting"), "{m}"),
            other => panic!("a resting disc off the floor was restored: {other:?}"),
        }
        let mut unknown = cp;
        unknown.pending[k][2] |= 1 << 17;
        assert!(Engine::from_checkpoint(unknown).is_err());
    }
}
