//! Straight lines on neighbour lists: the law of [`super::Straight`], with the
//! partners found in each disc's list and a skin exit in place of cell
//! crossings (engine::listed, physics.md (2.7)).

use super::{Motion, Straight};
use crate::engine::body::{Body, Face, Pending};
use crate::engine::Engine;
use carom_core::DVec2;

/// Discs flying straight, on neighbour lists.
#[derive(Debug, Clone, Copy)]
pub(in crate::engine) struct Listed;

impl Motion for Listed {
    type Scan = ();

    const LISTS: bool = true;

    #[inline(always)]
    fn scan(_e: &Engine) {}

    #[inline(always)]
    fn pair_time(bi: &Body, ri: DVec2, bj: &Body, dr: DVec2, sigma: f64, now: f64, _: ()) -> f64 {
        Straight::pair_time(bi, ri, bj, dr, sigma, now, ())
    }

    #[inline(always)]
    fn boundary_event(e: &Engine, i: usize, p: DVec2, v: DVec2) -> (f64, Pending, Face) {
        e.boundary_event_listed(i, p, v)
    }
}
