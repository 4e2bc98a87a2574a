//! The minimizer of relaxed placement: random positions made free of overlaps by
//! minimizing a soft overlap energy.
//!
//! Each overlapping pair, with its radii inflated by [`INFLATE`], gets the harmonic
//! energy U = ½ δ² (δ the overlap of the inflated discs, length), and so does a
//! disc reaching into a wall. U is minimized with FIRE (E. Bitzek et al., Phys.
//! Rev. Lett. 97, 170201 (2006)) until every pair of the real discs is at least
//! [`MARGIN`] times its contact distance apart. Below the mixture's jamming density
//! (about 0.84 in 2D) U reaches zero and the minimization ends; above it the forces
//! balance while overlaps remain (jammed), which is reported. The result is an
//! instantaneous quench, not an equilibrium state. Every step is a fixed sequence
//! of f64 operations, so a seed gives the same placement bit for bit. See
//! docs/performance.md, "initial states".

use crate::cells::CellGrid;
use carom_core::{DVec2, SimBox};
use std::ops::ControlFlow;

/// Factor on the radii while minimizing (dimensionless): the inflated discs are
/// pushed apart, so the real ones end with gaps.
pub(super) const INFLATE: f64 = 1.0 + 2e-3;

/// The minimization stops once every pair of discs is at least this factor times
/// its contact distance a_i + a_j apart, and every disc at least this factor times
/// its radius from a wall (dimensionless).
pub(super) const MARGIN: f64 = 1.0 + 1e-3;

/// FIRE parameters (Bitzek et al. 2006, in the time unit of a unit mass on a unit
/// spring): first and largest step, steps of positive power before the step grows,
/// its growth and cut factors, and the mixing coefficient's start and decay.
const DT_START: f64 = 0.05;
const DT_MAX: f64 = 0.5;
const N_MIN: u32 = 5;
const F_INC: f64 = 1.1;
const F_DEC: f64 = 0.5;
const ALPHA_START: f64 = 0.1;
const F_ALPHA: f64 = 0.99;

/// Below this root-mean-square force per disc, in units of the largest radius
/// (force = length for unit springs), discs that still overlap are held in place
/// by their neighbours: the inflated discs are jammed, and minimizing further
/// cannot separate them.
const JAMMED_FORCE: f64 = 1e-10;

/// Why relaxation stopped without a state free of overlaps.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Why {
    /// The discs are jammed: the forces balance while overlaps remain.
    Jammed,
    /// The most steps allowed were taken.
    OutOfSteps,
    /// The observer asked to stop.
    Stopped,
}

/// How relaxation stopped without a state free of overlaps.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct NotRelaxed {
    /// Minimization steps taken.
    pub steps: usize,
    /// Pairs and wall contacts still closer than [`MARGIN`] allows at the end.
    pub close: usize,
    /// Why it stopped.
    pub why: Why,
}

/// Move the discs of radii `radii` (length) from positions `pos` (length, inside
/// the box) until no two are closer than [`MARGIN`] times their contact distance
/// and none is closer to a wall than [`MARGIN`] times its radius, in at most
/// `max_steps` FIRE steps. Periodic axes must be longer than 2·[`INFLATE`] times
/// the largest contact distance (so that a pair meets through one image only).
/// `observe` is called with (steps taken, pairs and wall contacts still too close)
/// before every step, and stops the minimization when it breaks.
pub(crate) fn relax(
    sim_box: &SimBox,
    radii: &[f64],
    pos: Vec<DVec2>,
    max_steps: usize,
    observe: &mut dyn FnMut(usize, usize) -> ControlFlow<()>,
) -> Result<Vec<DVec2>, NotRelaxed> {
    let n = pos.len();
    let a_max = radii.iter().copied().fold(0.0, f64::max);
    let grid = CellGrid::new(sim_box, 2.0 * a_max * INFLATE, n);
    let cells = grid.head.len();
    // Half box edges on periodic axes (∞ on walled ones), for nearest images.
    let half = DVec2::new(
        if grid.periodic[0] {
            0.5 * sim_box.size.x
        } else {
            f64::INFINITY
        },
        if grid.periodic[1] {
            0.5 * sim_box.size.y
        } else {
            f64::INFINITY
        },
    );
    // Each cell's distinct neighbours (itself included), walls dropped: on a
    // periodic axis of fewer than three cells the 3 × 3 block repeats cells.
    let blocks: Vec<Vec<usize>> = (0..cells)
        .map(|k| {
            let w = grid.n[0] as usize;
            let mut b: Vec<usize> = grid.cells_near([(k % w) as u32, (k / w) as u32]).collect();
            b.sort_unstable();
            b.dedup();
            b
        })
        .collect();
    // The discs in cell order (counting sort at every step): disc `id[k]` is at
    // `pos[k]` with velocity `vel[k]`; cell c holds places start[c]..start[c + 1].
    let mut id: Vec<u32> = (0..n as u32).collect();
    let mut pos = pos;
    let mut vel = vec![DVec2::ZERO; n];
    let mut rad: Vec<f64> = radii.to_vec();
    let mut force = vec![DVec2::ZERO; n];
    let mut cell = vec![0usize; n];
    let mut start = vec![0usize; cells + 1];
    let mut scratch: Vec<(u32, DVec2, DVec2, f64)> = Vec::with_capacity(n);
    let (mut dt, mut alpha, mut positive) = (DT_START, ALPHA_START, 0u32);
    let mut close = 0;
    let mut why = Why::OutOfSteps;
    let mut steps = 0;
    while steps <= max_steps {
        // Sort into cells (stable, so equal inputs give equal orders).
        start.fill(0);
        for (c, r) in cell.iter_mut().zip(&pos) {
            *c = grid.index(grid.coords_of(*r));
            start[*c + 1] += 1;
        }
        for c in 0..cells {
            start[c + 1] += start[c];
        }
        scratch.clear();
        scratch.resize(n, (0, DVec2::ZERO, DVec2::ZERO, 0.0));
        let mut fill = start.clone();
        for k in 0..n {
            let to = &mut fill[cell[k]];
            scratch[*to] = (id[k], pos[k], vel[k], rad[k]);
            *to += 1;
        }
        for (k, &(i, r, v, a)) in scratch.iter().enumerate() {
            (id[k], pos[k], vel[k], rad[k]) = (i, r, v, a);
        }
        force.fill(DVec2::ZERO);
        close = 0;
        for (c, block) in blocks.iter().enumerate() {
            for k in start[c]..start[c + 1] {
                for &c2 in block {
                    for m in start[c2].max(k + 1)..start[c2 + 1] {
                        let d = nearest_image(pos[m] - pos[k], half, sim_box.size);
                        let sigma = rad[k] + rad[m];
                        let r2 = d.length_squared();
                        close += usize::from(r2 < (MARGIN * sigma) * (MARGIN * sigma));
                        let s = INFLATE * sigma;
                        if r2 < s * s {
                            let r = r2.sqrt();
                            // Coincident centres (never drawn in practice): along x.
                            let e = if r > 0.0 { d / r } else { DVec2::X };
                            let f = e * (s - r);
                            force[k] -= f;
                            force[m] += f;
                        }
                    }
                }
            }
        }
        for k in 0..n {
            for a in 0..2 {
                if grid.periodic[a] {
                    continue;
                }
                let (x, l, r) = (pos[k][a], sim_box.size[a], rad[k]);
                close += usize::from(x < MARGIN * r) + usize::from(x > l - MARGIN * r);
                let s = INFLATE * r;
                force[k][a] += (s - x).max(0.0) - (x - (l - s)).max(0.0);
            }
        }
        if close == 0 {
            let mut out = vec![DVec2::ZERO; n];
            for (k, &i) in id.iter().enumerate() {
                out[i as usize] = pos[k];
            }
            return Ok(out);
        }
        let f2: f64 = force.iter().map(|f| f.length_squared()).sum();
        if f2 < n as f64 * (JAMMED_FORCE * a_max).powi(2) {
            why = Why::Jammed;
            break;
        }
        if steps == max_steps {
            break;
        }
        if observe(steps, close).is_break() {
            why = Why::Stopped;
            break;
        }
        steps += 1;
        // FIRE: mix the velocity towards the force while the power is positive,
        // stop dead and cut the step when it turns negative.
        let power: f64 = vel.iter().zip(&force).map(|(v, f)| v.dot(*f)).sum();
        if power >= 0.0 {
            let v_norm = vel.iter().map(|v| v.length_squared()).sum::<f64>().sqrt();
            let mix = alpha * v_norm / f2.sqrt();
            for (v, f) in vel.iter_mut().zip(&force) {
                *v = *v * (1.0 - alpha) + *f * mix;
            }
            positive += 1;
            if positive > N_MIN {
                dt = (dt * F_INC).min(DT_MAX);
                alpha *= F_ALPHA;
            }
        } else {
            vel.fill(DVec2::ZERO);
            positive = 0;
            dt *= F_DEC;
            alpha = ALPHA_START;
        }
        // Semi-implicit Euler step of unit masses.
        for ((r, v), f) in pos.iter_mut().zip(vel.iter_mut()).zip(&force) {
            *v += *f * dt;
            *r = sim_box.wrap(*r + *v * dt);
            for a in 0..2 {
                if !grid.periodic[a] {
                    r[a] = r[a].clamp(0.0, sim_box.size[a]);
                }
            }
        }
    }
    Err(NotRelaxed { steps, close, why })
}

/// The nearest periodic image of the separation `d` of two positions inside the
/// box (so |d| < L per axis): one edge `size` subtracted or added where |d| exceeds
/// `half` (half the edge on a periodic axis, ∞ on a walled one). The same image as
/// [`SimBox::minimum_image`] without its division and rounding call.
#[inline]
fn nearest_image(mut d: DVec2, half: DVec2, size: DVec2) -> DVec2 {
    for k in 0..2 {
        if d[k] > half[k] {
            d[k] -= size[k];
        } else if d[k] < -half[k] {
            d[k] += size[k];
        }
    }
    d
}
