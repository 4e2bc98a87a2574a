//! Straight lines: r(t) = r0 + v t between events (physics.md §1–§2).
//!
//! A pair meets at the smaller root of |Δr + Δv t| = σ with b = Δr·Δv < 0
//! (physics.md (2.3)); a disc meets a cell edge or a wall where one coordinate
//! of its line reaches it (`Engine::boundary_event_straight`). Collisions are
//! the rule's alone: the trait's defaults.

use super::Motion;
use crate::engine::body::{Body, Face, Pending};
use crate::engine::Engine;
use carom_core::kinematics::contact_time_or_inf;
use carom_core::DVec2;

/// Discs flying straight: no field, no growth.
#[derive(Debug, Clone, Copy)]
pub(in crate::engine) struct Straight;

impl Motion for Straight {
    type Scan = ();

    #[inline(always)]
    fn scan(_e: &Engine) {}

    #[inline(always)]
    fn pair_time(bi: &Body, _ri: DVec2, bj: &Body, dr: DVec2, sigma: f64, _now: f64, _: ()) -> f64 {
        contact_time_or_inf(dr, bj.v - bi.v, sigma)
    }

    #[inline(always)]
    fn boundary_event(e: &Engine, i: usize, p: DVec2, v: DVec2) -> (f64, Pending, Face) {
        e.boundary_event_straight(i, p, v)
    }
}
