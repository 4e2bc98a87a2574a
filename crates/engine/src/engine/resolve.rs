//! Resolving the events that change a disc: pair collisions, wall hits and cell
//! crossings.
//!
//! A pair collision applies the configured rule (physics.md §3–4) to the contact
//! vector r_j − r_i, or the elastic rule when either disc collided less than t_c
//! ago (the TC model, §4); its virial r_ij·Δp_i (§5) goes to the running totals. A
//! wall gives Δp_k = −(1+e) m v_k, so v_k ← v_k + Δp_k/m (= −e v_k up to
//! rounding). A velocity change moves the path's origin so that r0 + v t still passes through the disc's position now, and
//! bumps the disc's collision counter, which makes its partners' predictions
//! obsolete. A crossing moves the disc into the next cell (wrapping by a box length
//! on a periodic axis) and predicts again. Every velocity change is applied from an
//! impulse Δp as v + Δp/m (carom_core::collision::apply_impulse), the arithmetic
//! a reader of the log repeats to replay velocities bit for bit. See
//! docs/performance.md, "resolution".

use super::body::{origin_after, Face, Image};
use super::motion::Motion;
use super::Engine;
use crate::event::{PairCollision, WallCollision};
use carom_core::collision::{apply_impulse, apply_wall_impulse, reduced_mass, resolve};
use carom_core::{Axis, Boundary, DVec2, Restitution, WallSide};

/// Whether discs i and j, whose paths (origin, velocity) were `paths` before a
/// collision at internal time `now`, approach at `now` once given velocities
/// (v_i, v_j), as the neighbour scans will see them: b = Δr·Δv < 0 (physics.md §2)
/// from i's side (j's image at r_j + shift) or from j's, with the positions
/// ([`Body::at`]) of the updated paths.
#[inline(always)]
fn approaching(
    paths: [(DVec2, DVec2); 2],
    shift: DVec2,
    now: f64,
    (vi, vj): (DVec2, DVec2),
) -> bool {
    let ri = origin_after(paths[0], vi, now) + vi * now;
    let rj = origin_after(paths[1], vj, now) + vj * now;
    (rj - (ri - shift)).dot(vj - vi) < 0.0 || (ri - (rj + shift)).dot(vi - vj) < 0.0
}

/// The total impulse Δp_i and the velocities (v_i', v_j') = [`apply_impulse`] of
/// it to the velocities before, `before`, after an extra impulse along the
/// contact vector `n` is added to the rule's impulse `dp`: the smallest of a
/// doubling sequence (starting at a velocity change of about one ulp of the
/// speeds) with which the pair no longer [`approaching`]. Momentum is kept (j
/// receives −Δp_i), and the velocities stay exactly those a reader of the log
/// gets by applying the logged Δp_i; the kinetic energy changes by the
/// rounding-level work of the extra impulse, about ε m v² relative to the pair.
/// `None` if no finite impulse does it (the collision is then left as the rule
/// made it).
#[cold]
#[inline(never)]
fn push_apart(
    paths: [(DVec2, DVec2); 2],
    shift: DVec2,
    now: f64,
    n: DVec2,
    before: (DVec2, DVec2),
    dp: DVec2,
    (mi, mj): (f64, f64),
) -> Option<(DVec2, DVec2, DVec2)> {
    let (vi, vj) = apply_impulse(before.0, before.1, mi, mj, dp);
    let speed = vi.abs().max_element().max(vj.abs().max_element());
    let mu = reduced_mass(mi, mj);
    let mut k = (f64::EPSILON * speed / n.length_squared()).max(f64::MIN_POSITIVE);
    while k.is_finite() {
        let total = dp - n * (k * mu);
        let pushed = apply_impulse(before.0, before.1, mi, mj, total);
        if !approaching(paths, shift, now, pushed) {
            return Some((total, pushed.0, pushed.1));
        }
        k *= 2.0;
    }
    None
}

impl Engine {
    #[inline]
    fn mass(&self, i: usize) -> f64 {
        self.species[self.bodies[i].species as usize].mass
    }

    /// Whether disc `i` collided (with a disc or a wall) less than t_c before `now`
    /// (internal time), so that its next collision is elastic under the TC model
    /// (physics.md §4); always false with the model off.
    #[inline]
    pub(super) fn within_tc(&self, i: usize, now: f64) -> bool {
        let tc = self.params.tc;
        tc > 0.0 && now - self.last_collision[i] < tc
    }

    /// Ask for a renumbering at the next event, and with it a restart of the
    /// internal clock ([`Engine::rebase_clock`]), if disc `i`'s path origin has
    /// moved more than `ORIGIN_LIMIT` box lengths (or `ORIGIN_LIMIT_CELLS` cell
    /// widths, whichever is more) from the box. Positions are
    /// computed as r0 + v t, so their rounding is that of |r0|: it stays that of
    /// the box's own coordinates only while |r0| does. The renumbering every 16 N
    /// pair collisions keeps |r0| ≈ L + |v| t small in a fluid, but a cooled
    /// granular cluster drifting with the rounding residue of its momentum (speeds of
    /// 10⁻¹⁷ at t ≈ 10²³, few collisions) moved 4·10⁶ box lengths on one clock, and
    /// its contacts were off by 10⁻⁹ (`crates/engine/tests/engine_reference.rs`, random dynamics).
    /// Called where an origin changes: a velocity change, a wrap across a periodic
    /// edge.
    #[inline]
    pub(super) fn keep_origin_near<const K: usize>(&mut self, discs: [usize; K]) {
        // One comparison for all the discs of an event (a pair: two).
        let far = discs
            .iter()
            .map(|&i| self.bodies[i].r0.abs().max_element())
            .fold(0.0, f64::max);
        if far > self.origin_limit {
            self.next_reorder = self.next_reorder.min(self.stats.pair_collisions);
        }
    }

    /// Resolve the pair collision of discs i and j (j seen through the image with
    /// `image`) at the current time with the configured rule, or
    /// elastically under the TC model, and predict both discs' next events.
    pub(super) fn collide<M: Motion>(&mut self, i: usize, j: usize, image: Image) -> PairCollision {
        let now = self.clock;
        // In a field, a resting disc hit by a falling one falls again first; two
        // resting discs collide on their straight paths (engine::resting).
        let on_floor = M::pair_on_floor(self, i, j);
        let shift = image.shift(self.sim_box.size);
        let dr = self.bodies[j].at(now) + shift - self.bodies[i].at(now);
        // The unnormalised contact vector goes to the collision rule (see
        // carom_core::collision: energy is then conserved without rounding bias).
        let (vi, vj) = (self.bodies[i].v, self.bodies[j].v);
        let (mi, mj) = (self.mass(i), self.mass(j));
        let tc = self.params.tc;
        let rule = if self.within_tc(i, now) || self.within_tc(j, now) {
            Restitution::Elastic
        } else {
            self.params.restitution
        };
        let mut res = resolve(vi, vj, mi, mj, dr, rule);
        M::pair_extra(self, (i, j), dr, (vi, vj), (mi, mj), &mut res);
        // A rule leaves the pair separating at −e u (physics.md §4), but when that
        // is below what the velocities' rounding resolves (e = 0, R = 0, or an
        // elastic collision of a pair that met at such a speed, as under the TC
        // model) the rounded velocities may leave it approaching. In contact, it
        // would then collide again at once, and as the resolution cannot change the
        // velocities again, forever: under the TC model (restitution 0, t_c = 10⁻³,
        // N = 400, η = 0.3) a stall at t ≈ 0.5 that no collapse caused. So a pair
        // that still approaches as the scans will see it is pushed apart. Not for an
        // inelastic rule without the TC model: there the pair meets again at once,
        // and the run stops with the runaway error, as a collapse must be reported.
        // It changes no other collision (docs/performance.md, "resolution").
        let paths = [(self.bodies[i].r0, vi), (self.bodies[j].r0, vj)];
        let separated = if (tc > 0.0 || self.params.restitution.is_elastic())
            && approaching(paths, shift, now, (res.vi, res.vj))
        {
            push_apart(paths, shift, now, dr, (vi, vj), res.impulse_i, (mi, mj))
        } else {
            None
        };
        if let Some((dp, a, b)) = separated {
            (res.impulse_i, res.vi, res.vj) = (dp, a, b);
        }
        // r_ij = r_i − r_j = −dr.
        let virial = -dr.dot(res.impulse_i);
        self.bodies[i].set_velocity(res.vi, now);
        self.bodies[j].set_velocity(res.vj, now);
        M::after_pair(self, i, j, on_floor);
        self.keep_origin_near([i, j]);
        self.bodies[i].count = self.bodies[i].count.wrapping_add(1);
        self.bodies[j].count = self.bodies[j].count.wrapping_add(1);
        if tc > 0.0 {
            // Read only by the TC model; skipping the write saves two cache misses
            // per collision at large N.
            self.last_collision[i] = now;
            self.last_collision[j] = now;
        }
        self.stats.pair_collisions += 1;
        self.stats.virial_sum += virial;
        self.stats.energy_lost += res.energy_lost;
        self.predict::<M>(i);
        self.predict::<M>(j);
        let mut ev = PairCollision {
            time: self.reported,
            i: self.label[i],
            j: self.label[j],
            normal: dr / dr.length(),
            vi_before: vi,
            vj_before: vj,
            vi_after: res.vi,
            vj_after: res.vj,
            energy_lost: res.energy_lost,
            virial,
            impulse: res.impulse_i,
        };
        M::report_pair(self, &mut ev, on_floor);
        ev
    }

    /// Resolve disc `i`'s collision with the wall `face` at the current time (the
    /// wall's restitution, or elastic under the TC model) and predict its next event.
    pub(super) fn hit_wall<M: Motion>(&mut self, i: usize, face: Face) -> WallCollision {
        let k = face.axis();
        if M::is_floor(self, face) {
            return self.hit_floor(i);
        }
        let side = if face.high() {
            WallSide::High
        } else {
            WallSide::Low
        };
        let wall_e = match self.sim_box.boundary[k] {
            Boundary::Walls { restitution } => restitution,
            Boundary::Periodic => unreachable!("wall event on a periodic axis"),
        };
        // The TC model covers wall collisions as well (physics.md §4: a collision is
        // elastic if the disc collided less than t_c ago), as in Luding & McNamara:
        // without it, discs wedged between inelastic walls collapse under the TC
        // model just as they would without it (`crates/engine/tests/inelastic.rs`).
        let now = self.clock;
        let e = if self.within_tc(i, now) { 1.0 } else { wall_e };
        if self.params.tc > 0.0 {
            self.last_collision[i] = now;
        }
        let m = self.mass(i);
        let path_v = self.bodies[i].v;
        let mut path_after = path_v;
        // In a field the path velocity's y is the true one plus g t (engine::gravity):
        // the wall reverses the true normal velocity. (A disc resting on the floor
        // meets only the side walls, k = 0, and its path is its true one.)
        let g = self.params.gravity;
        let was_resting = M::resting(&self.bodies[i]);
        let lift = if k == 1 { g * now } else { 0.0 };
        let vk = path_v[k] - lift;
        // Applied as v_k + Δp/m, the arithmetic a reader of the log repeats.
        let mut dp = M::wall_impulse(self, i, vk, m, e, face.high());
        path_after[k] = apply_wall_impulse(vk, m, dp);
        // A floor bounce whose apex rounds to the floor rests instead (15.9): the
        // floor takes the whole vertical momentum (engine::resting).
        let rests = M::rests(self, i, face, path_after[k]);
        if rests {
            dp = -m * vk;
            path_after[k] = 0.0;
        } else if lift != 0.0 {
            path_after[k] += lift;
        }
        self.bodies[i].set_velocity(path_after, now);
        if rests {
            self.lay_to_rest(i);
        }
        self.keep_origin_near([i]);
        self.keep_fall_short();
        self.bodies[i].count = self.bodies[i].count.wrapping_add(1);
        let impulse = dp.abs();
        let energy_lost = if rests {
            0.5 * m * vk * vk
        } else {
            M::wall_energy_lost(m, vk, path_after[k], e)
        };
        let (mut before, mut after) = (path_v, path_after);
        if g != 0.0 {
            if !was_resting {
                before.y -= g * now;
            }
            if !(was_resting || rests) {
                after.y -= g * now;
            }
        }
        self.stats.wall_collisions += 1;
        self.stats.wall_impulse[k][face.high() as usize] += impulse;
        self.stats.energy_lost += energy_lost;
        self.predict::<M>(i);
        WallCollision {
            time: self.reported,
            i: self.label[i],
            axis: if k == 0 { Axis::X } else { Axis::Y },
            side,
            v_before: before,
            v_after: after,
            impulse,
            energy_lost,
        }
    }

    /// Move disc `i` across its cell's `face` into the next cell (through the
    /// periodic edge if there is no next cell) and predict its next event.
    pub(super) fn cross<M: Motion>(&mut self, i: usize, face: Face) {
        let k = face.axis();
        let up = face.high();
        let mut c = self.bodies[i].link.coords();
        let grid = self.grids.get_mut(self.grids.class(self.bodies[i].species));
        let n = grid.n[k];
        grid.remove(&mut self.bodies, i as u32);
        let mut wrapped = true;
        if up {
            if c[k] + 1 == n {
                // Leaving through the periodic edge at L: re-enter at 0.
                c[k] = 0;
                self.bodies[i].r0[k] -= self.sim_box.size[k];
            } else {
                c[k] += 1;
                wrapped = false;
            }
        } else if c[k] == 0 {
            c[k] = n - 1;
            self.bodies[i].r0[k] += self.sim_box.size[k];
        } else {
            c[k] -= 1;
            wrapped = false;
        }
        grid.insert(&mut self.bodies, i as u32, c);
        self.stats.cell_crossings += 1;
        if wrapped {
            self.images[self.label[i] as usize][k] += if up { 1 } else { -1 };
            self.keep_origin_near([i]);
            // The position moved by one box length: partners' image shifts change.
            self.bodies[i].count = self.bodies[i].count.wrapping_add(1);
            self.predict::<M>(i);
        } else {
            self.predict_after_crossing::<M>(i, k, up);
        }
    }
}
