//! Relaxed placement: random positions at the requested density, one in each cell
//! of a grid of about N cells (so the density is even on large scales), with the
//! overlaps then removed by minimizing a soft overlap energy (`relax`): disordered
//! states of any mixture up to just below jamming. A placement that jams or runs
//! out of steps is refused with what the minimizer reached; the caller may watch
//! the minimization and stop it ([`PlacementProgress`]).

use super::random::shuffle;
use super::relax::{relax, Why, INFLATE};
use super::spec::{PlacementProgress, SystemSpec};
use crate::error::InitError;
use carom_core::observables::packing_fraction;
use carom_core::DVec2;
use rand::RngExt;
use rand_pcg::Pcg64;
use std::ops::ControlFlow;

/// Most minimization steps of relaxed placement (see docs/performance.md,
/// "initial states").
const RELAX_STEPS: usize = 100_000;

/// Relaxed placement (see `init::relax`); `None` when `observe` stopped it.
pub(super) fn relaxed(
    spec: &SystemSpec,
    species_of: &[u16],
    rng: &mut Pcg64,
    observe: &mut dyn FnMut(&PlacementProgress) -> ControlFlow<()>,
) -> Result<Option<Vec<DVec2>>, InitError> {
    let radius = |i: usize| spec.species[species_of[i] as usize].radius;
    let reach = 4.0 * spec.largest_radius() * INFLATE;
    for (k, name) in ["x", "y"].iter().enumerate() {
        let l = spec.sim_box.size[k];
        if spec.sim_box.boundary[k].is_periodic() && l <= reach {
            return Err(InitError::invalid(
                format!("box.size.{name}"),
                format!("periodic edge {l} is too short for relaxed placement"),
                format!("periodic edges longer than {reach:.6} (twice the largest contact distance, with a margin), or \"lattice\" placement"),
            ));
        }
    }
    let radii: Vec<f64> = (0..species_of.len()).map(radius).collect();
    // One disc per cell of a grid of about N cells, at a uniformly random place in
    // it (a jittered grid; the cells left over are chosen at random), so that the
    // discs are spread evenly on scales beyond a few diameters. From uniformly
    // random positions, with only the overlaps removed, the state was uneven on
    // large scales and started a collective flow: for 4000 discs of the 1 : 1.4
    // mixture at η = 0.78 the flow averaged over 4 × 4 blocks held 1.5 % of the
    // kinetic energy at t = 1, four times its equilibrium share, and still 1.5
    // times at t = 8, and the speeds failed Maxwell–Boltzmann over t ∈ [1, 10]
    // (p ≈ 1e-5 to 1e-10). From the jittered grid the flow is at its
    // equilibrium share from the start.
    let n = radii.len();
    let size = spec.sim_box.size;
    let nx = ((n as f64 * size.x / size.y).sqrt().round() as usize).clamp(1, n);
    let ny = n.div_ceil(nx);
    let mut cells: Vec<usize> = (0..nx * ny).collect();
    shuffle(&mut cells, rng);
    cells.truncate(n);
    cells.sort_unstable();
    // Shuffle which disc takes which cell, so the species mix.
    shuffle(&mut cells, rng);
    let cell = DVec2::new(size.x / nx as f64, size.y / ny as f64);
    let start: Vec<DVec2> = cells
        .iter()
        .map(|&c| {
            let corner = DVec2::new((c % nx) as f64, (c / nx) as f64) * cell;
            let r = corner + DVec2::new(rng.random::<f64>(), rng.random::<f64>()) * cell;
            // Inside the box although rounding may put a coordinate at L.
            DVec2::new(
                r.x.min(size.x * (1.0 - f64::EPSILON)),
                r.y.min(size.y * (1.0 - f64::EPSILON)),
            )
        })
        .collect();
    let mut report = |steps, close| {
        observe(&PlacementProgress {
            discs: n,
            steps,
            max_steps: RELAX_STEPS,
            close,
            compressing: None,
        })
    };
    let relaxed = relax(&spec.sim_box, &radii, start, RELAX_STEPS, &mut report);
    let e = match relaxed {
        Ok(p) => return Ok(Some(p)),
        Err(e) => e,
    };
    let eta = packing_fraction(&spec.species, &spec.sim_box);
    let why = match e.why {
        Why::Stopped => return Ok(None),
        Why::Jammed => format!(
            "the discs jammed with {} pairs or wall contacts still overlapping",
            e.close
        ),
        Why::OutOfSteps => format!(
            "{} pairs or wall contacts still too close after {} minimization steps",
            e.close, e.steps
        ),
    };
    Err(InitError::invalid(
        "packing_fraction",
        format!("{eta:.4} is too dense for relaxed placement in this box: {why}"),
        "η below the jamming density of the mixture (about 0.84 for discs; \
             0.83 works for an equimolar 1 : 1.4 mixture), or \"lattice\" placement",
    ))
}
