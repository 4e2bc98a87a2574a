//! Falling in the field g along −y, with an optional vibrating floor
//! (physics.md §15, §18).
//!
//! The record keeps the straight path p(t) = r0 + v t and the true motion is
//! r(t) = p(t) − ŷ g t²/2, v(t) = v − ŷ g t (`engine::gravity`). Both discs of
//! a pair fall alike, so a pair meets on its straight relative path, except
//! when exactly one of them rests on the floor: then at the root of the quartic
//! (15.10) (`engine::resting`). Cell edges and walls along y are met on the
//! parabola; the floor, if it vibrates, by conservative advancement
//! (`engine::floor`). A wall reverses the true normal velocity, and a floor
//! bounce whose apex rounds to the floor rests instead (15.9).

use super::Motion;
use crate::engine::body::{Aux, Body, Face, Pending};
use crate::engine::resting::contact_time_resting;
use crate::engine::Engine;
use crate::event::PairCollision;
use carom_core::kinematics::contact_time_or_inf;
use carom_core::DVec2;

/// Discs falling in a field (g may be 0 with a vibrating floor).
#[derive(Debug, Clone, Copy)]
pub(in crate::engine) struct Falling;

impl Motion for Falling {
    /// The field g (length/time²).
    type Scan = f64;

    #[inline(always)]
    fn scan(e: &Engine) -> f64 {
        e.params.gravity
    }

    #[inline(always)]
    fn pair_time(bi: &Body, ri: DVec2, bj: &Body, dr: DVec2, sigma: f64, now: f64, g: f64) -> f64 {
        if bi.resting() != bj.resting() {
            contact_time_resting(bi, ri, bj, sigma, g, now)
        } else {
            contact_time_or_inf(dr, bj.v - bi.v, sigma)
        }
    }

    #[inline(always)]
    fn boundary_event(e: &Engine, i: usize, p: DVec2, v: DVec2) -> (f64, Pending, Face) {
        e.boundary_event_falling(i, p, v)
    }

    #[inline(always)]
    fn file_aux(old: Aux, new: Aux) -> Aux {
        new.with_resting(old.resting())
    }

    #[inline(always)]
    fn pair_on_floor(e: &mut Engine, i: usize, j: usize) -> bool {
        e.pair_on_floor(i, j)
    }

    #[inline(always)]
    fn after_pair(e: &mut Engine, i: usize, j: usize, on_floor: bool) {
        if on_floor {
            e.leave_floor_if_moved(i);
            e.leave_floor_if_moved(j);
        }
    }

    #[inline(always)]
    fn report_pair(e: &Engine, ev: &mut PairCollision, on_floor: bool) {
        if !on_floor {
            e.falling_pair(ev, e.clock);
        }
    }

    #[inline(always)]
    fn resting(b: &Body) -> bool {
        b.resting()
    }

    #[inline(always)]
    fn rests(e: &Engine, i: usize, face: Face, after: f64) -> bool {
        face.axis() == 1 && !face.high() && e.rests_on_floor(i, after)
    }

    #[inline(always)]
    fn is_floor(e: &Engine, face: Face) -> bool {
        face.axis() == 1 && !face.high() && e.params.floor.is_some()
    }
}
