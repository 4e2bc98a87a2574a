//! Growing discs: straight lines, radii a(t) = a⁰ (s₀ + γ t) (physics.md §17).
//!
//! A pair meets where |Δr + Δv t| = σ⁰ (s₀ + γ t) (17.3), a wall where the
//! growing radius reaches it (17.5); cell edges are those of the straight path
//! (`engine::growth`). At contact a pair leaves at u' = −u + 2g with g = σ⁰ γ
//! (17.4), and a wall returns v' = −v ± 2ȧ (17.6): collisions give energy.

use super::Motion;
use crate::engine::body::{Body, Face, Pending};
use crate::engine::Engine;
use carom_core::collision::{apply_impulse, reduced_mass, Resolution};
use carom_core::growth::{contact_time_growing, growth_impulse};
use carom_core::DVec2;

/// Discs growing in proportion (Lubachevsky–Stillinger).
#[derive(Debug, Clone, Copy)]
pub(in crate::engine) struct Growing;

impl Motion for Growing {
    /// The radii's scale and relative growth rate (s, γ) now.
    type Scan = (f64, f64);

    #[inline(always)]
    fn scan(e: &Engine) -> (f64, f64) {
        e.growth.now(e.clock)
    }

    #[inline(always)]
    fn pair_time(
        bi: &Body,
        _ri: DVec2,
        bj: &Body,
        dr: DVec2,
        sigma: f64,
        _now: f64,
        (s, rate): (f64, f64),
    ) -> f64 {
        // Growing, disc i would meet itself (B = −σg < 0 at C = −σ² ≤ 0): it is
        // the one disc at zero separation.
        let t = contact_time_growing(dr, bj.v - bi.v, sigma * s, sigma * rate);
        if dr == DVec2::ZERO {
            f64::INFINITY
        } else {
            t
        }
    }

    #[inline(always)]
    fn boundary_event(e: &Engine, i: usize, p: DVec2, v: DVec2) -> (f64, Pending, Face) {
        e.boundary_event_growing(i, p, v)
    }

    #[inline(always)]
    fn growth_due(e: &Engine) -> Option<f64> {
        Some(e.growth_due())
    }

    #[inline(always)]
    fn pair_extra(
        e: &Engine,
        (i, j): (usize, usize),
        dr: DVec2,
        (vi, vj): (DVec2, DVec2),
        (mi, mj): (f64, f64),
        res: &mut Resolution,
    ) {
        if e.growth.rate != 0.0 {
            // Growing discs leave at u' = −u + 2g (physics.md (17.4)).
            let sigma0 = e.species[e.bodies[i].species as usize].radius
                + e.species[e.bodies[j].species as usize].radius;
            let g = sigma0 * e.growth.rate;
            res.impulse_i += growth_impulse(dr, reduced_mass(mi, mj), g);
            (res.vi, res.vj) = apply_impulse(vi, vj, mi, mj, res.impulse_i);
            let k = |m: f64, v: DVec2| 0.5 * m * v.length_squared();
            res.energy_lost = k(mi, vi) + k(mj, vj) - k(mi, res.vi) - k(mj, res.vj);
        }
    }

    #[inline(always)]
    fn wall_impulse(e: &Engine, i: usize, vk: f64, m: f64, _e_wall: f64, high: bool) -> f64 {
        e.growing_wall_impulse(i, vk, m, high)
    }

    /// Growing: the wall gives energy (physics.md (17.6)).
    #[inline(always)]
    fn wall_energy_lost(m: f64, vk: f64, after: f64, _e_wall: f64) -> f64 {
        0.5 * m * (vk * vk - after * after)
    }
}
