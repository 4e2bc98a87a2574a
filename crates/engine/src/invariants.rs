//! The invariant checker used by the tests (and available to callers):
//! no overlap beyond a tolerance, energy conserved in elastic runs, momentum
//! conserved along periodic axes, time never decreasing.

use crate::engine::Engine;
use carom_core::DVec2;
use thiserror::Error;

/// A broken invariant.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum Violation {
    /// Two discs overlap by more than the tolerance.
    #[error("discs {i} and {j} overlap by {overlap:e} of the contact distance at t = {time}")]
    Overlap {
        /// First disc.
        i: usize,
        /// Second disc.
        j: usize,
        /// (σ − d)/σ.
        overlap: f64,
        /// Time (time).
        time: f64,
    },
    /// Kinetic energy drifted in an elastic run.
    #[error("kinetic energy drifted by {relative:e} (relative) at t = {time}")]
    Energy {
        /// |E − E0|/E0.
        relative: f64,
        /// Time (time).
        time: f64,
    },
    /// Momentum changed along a periodic axis.
    #[error("momentum changed by {change:e} along axis {axis} at t = {time}")]
    Momentum {
        /// Axis index.
        axis: usize,
        /// |ΔP| relative to Σ m|v|.
        change: f64,
        /// Time (time).
        time: f64,
    },
    /// A disc is below the vibrating floor (physics.md §18).
    #[error("disc {i} is {depth:e} below the vibrating floor at t = {time}")]
    BelowFloor {
        /// The disc.
        i: usize,
        /// How far its edge is below the floor (length).
        depth: f64,
        /// Time (time).
        time: f64,
    },
    /// The clock went backwards.
    #[error("time went backwards from {before} to {after}")]
    Time {
        /// Previous time.
        before: f64,
        /// New time.
        after: f64,
    },
}

/// Tolerances and reference values for [`InvariantChecker::check`].
#[derive(Debug, Clone)]
pub struct InvariantChecker {
    /// Largest allowed overlap, relative to the contact distance (default 1e-10).
    pub overlap_tolerance: f64,
    /// Largest allowed relative energy drift in elastic runs (default 1e-12).
    pub energy_tolerance: f64,
    /// Largest allowed momentum change relative to Σ m|v|, now or at the start,
    /// whichever is larger (default 1e-12).
    pub momentum_tolerance: f64,
    e0: f64,
    p0: DVec2,
    /// Σ m|v| at the start (momentum): the floor of the momentum check's scale.
    scale0: f64,
    last_time: f64,
    /// Largest relative overlap seen so far.
    pub max_overlap: f64,
    /// Largest relative energy drift seen so far.
    pub max_energy_drift: f64,
}

impl InvariantChecker {
    /// Record the reference energy, momentum and time of `engine` now.
    pub fn new(engine: &Engine) -> Self {
        let (p0, scale0) = momentum(engine);
        InvariantChecker {
            overlap_tolerance: 1e-10,
            energy_tolerance: 1e-12,
            momentum_tolerance: 1e-12,
            e0: engine.kinetic_energy(),
            p0,
            scale0,
            last_time: engine.now(),
            max_overlap: 0.0,
            max_energy_drift: 0.0,
        }
    }

    /// Check the time, energy and momentum invariants (O(N)).
    pub fn check_conservation(&mut self, engine: &Engine) -> Result<(), Violation> {
        let t = engine.now();
        if t < self.last_time {
            return Err(Violation::Time {
                before: self.last_time,
                after: t,
            });
        }
        self.last_time = t;
        // A vibrating floor gives and takes energy: no elastic check then.
        let elastic = engine.params().restitution.is_elastic()
            && engine.params().floor.is_none()
            && engine.sim_box().boundary.iter().all(|b| match b {
                carom_core::Boundary::Periodic => true,
                carom_core::Boundary::Walls { restitution } => *restitution == 1.0,
            });
        if elastic && self.e0 > 0.0 {
            let rel = (engine.kinetic_energy() - self.e0).abs() / self.e0;
            self.max_energy_drift = self.max_energy_drift.max(rel);
            if rel > self.energy_tolerance {
                return Err(Violation::Energy {
                    relative: rel,
                    time: t,
                });
            }
        }
        // Relative to the larger of Σ m|v| now and at the start: the rounding of
        // every collision is of the size of the momenta it moved, so in a gas that
        // cools (lossy walls or pairs) the error accumulated while it was hot stays
        // of the size of the initial momenta while the current ones shrink.
        let (p, scale) = momentum(engine);
        let scale = scale.max(self.scale0);
        for axis in 0..2 {
            if engine.sim_box().boundary[axis].is_periodic() && scale > 0.0 {
                let change = (p[axis] - self.p0[axis]).abs() / scale;
                if change > self.momentum_tolerance {
                    return Err(Violation::Momentum {
                        axis,
                        change,
                        time: t,
                    });
                }
            }
        }
        Ok(())
    }

    /// Check every pair of discs for overlap at the current time (O(N) with a cell
    /// grid) and record the largest overlap seen.
    pub fn check_overlaps(&mut self, engine: &Engine) -> Result<(), Violation> {
        let worst = max_overlap(engine);
        if let Some((i, j, ov)) = worst {
            self.max_overlap = self.max_overlap.max(ov);
            if ov > self.overlap_tolerance {
                return Err(Violation::Overlap {
                    i,
                    j,
                    overlap: ov,
                    time: engine.now(),
                });
            }
        }
        Ok(())
    }

    /// With a vibrating floor, check that no disc's edge is below it by more than
    /// the overlap tolerance times its diameter.
    pub fn check_floor(&mut self, engine: &Engine) -> Result<(), Violation> {
        if engine.params().floor.is_none() {
            return Ok(());
        }
        let h = engine.floor_height();
        for i in 0..engine.len() {
            let a = engine.species()[engine.species_of()[i] as usize].radius;
            let depth = h - (engine.position(i).y - a);
            if depth > self.overlap_tolerance * 2.0 * a {
                return Err(Violation::BelowFloor {
                    i,
                    depth,
                    time: engine.now(),
                });
            }
        }
        Ok(())
    }

    /// All checks.
    pub fn check(&mut self, engine: &Engine) -> Result<(), Violation> {
        self.check_conservation(engine)?;
        self.check_floor(engine)?;
        self.check_overlaps(engine)
    }
}

fn momentum(engine: &Engine) -> (DVec2, f64) {
    let mut p = DVec2::ZERO;
    let mut scale = 0.0;
    for i in 0..engine.len() {
        let m = engine.species()[engine.species_of()[i] as usize].mass;
        let v = engine.velocity(i);
        p += v * m;
        scale += m * v.length();
    }
    (p, scale)
}

/// The pair with the largest relative overlap (σ − d)/σ > 0 at the current time, if
/// any pair overlaps at all.
pub fn max_overlap(engine: &Engine) -> Option<(usize, usize, f64)> {
    let sim_box = engine.sim_box();
    let n = engine.len();
    // The radii now: the species' scaled by the growth (physics.md §17; 1 without).
    let scale = engine.radius_scale();
    let radius = |i: usize| engine.species()[engine.species_of()[i] as usize].radius * scale;
    // Cells as wide as the largest contact distance among the discs present.
    let a_max = (0..n).map(radius).fold(0.0, f64::max);
    let mut grid = crate::cells::CellGrid::new(sim_box, 2.0 * a_max, n);
    let mut links = vec![crate::cells::Link::UNLINKED; n];
    let pos: Vec<DVec2> = (0..n).map(|i| engine.position(i)).collect();
    for (i, r) in pos.iter().enumerate() {
        grid.insert(&mut links, i as u32, grid.coords_of(*r));
    }
    let mut worst: Option<(usize, usize, f64)> = None;
    for i in 0..n {
        for j in grid
            .discs_near(&links, links[i].coords())
            .map(|j| j as usize)
        {
            if j > i {
                let sigma = radius(i) + radius(j);
                let d = sim_box.minimum_image(pos[j] - pos[i]).length();
                let ov = (sigma - d) / sigma;
                if ov > 0.0 && worst.is_none_or(|w| ov > w.2) {
                    worst = Some((i, j, ov));
                }
            }
        }
    }
    worst
}
