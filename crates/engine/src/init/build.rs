//! Building an initial state from a checked request: [`SystemSpec::build`]
//! places the discs by the chosen placement and draws their velocities from one
//! `Pcg64` stream seeded with the seed, so the same request gives the same state
//! bit for bit; velocities whose scale would overflow the engine's arithmetic
//! are refused.

use super::compressed::compressed;
use super::lattice::lattice;
use super::random::{check_explicit, random};
use super::relaxed::relaxed;
use super::spec::{Placement, PlacementProgress, SystemSpec, Velocities};
use super::velocities::{equal_speed, maxwell_boltzmann};
use crate::error::InitError;
use crate::state::State;
use carom_core::DVec2;
use rand::SeedableRng;
use rand_pcg::Pcg64;
use std::ops::ControlFlow;

/// The largest allowed product of the fastest disc's speed and the longest box edge
/// (length²/time). The contact time (physics.md §2) squares products of a
/// separation and a relative velocity, and positions and kinetic energies square
/// or multiply these scales too: kept below 1e150, every such square stays far from
/// the overflow of f64 at 1.8e308 (an infinity there would stop every collision,
/// or put NaN into the event times).
pub const SPEED_TIMES_SIZE_LIMIT: f64 = 1e150;

/// Refuse velocities whose scale would overflow the engine's arithmetic (see
/// [`SPEED_TIMES_SIZE_LIMIT`]); `field` names where they came from. When even a
/// box one diameter across would pass (fastest speed × largest diameter within the
/// limit), the box is what is too large, and the error names `box.size`.
fn check_scales(
    spec: &SystemSpec,
    species_of: &[u16],
    velocities: &[DVec2],
    field: &str,
) -> Result<(), InitError> {
    let fastest = velocities.iter().map(|v| v.length()).fold(0.0, f64::max);
    let edge = spec.sim_box.size.max_element();
    let product = fastest * edge;
    if product.is_nan() || product > SPEED_TIMES_SIZE_LIMIT {
        let box_too_large = fastest * 2.0 * spec.largest_radius() <= SPEED_TIMES_SIZE_LIMIT;
        return Err(InitError::invalid(
            if box_too_large { "box.size" } else { field },
            format!(
                "the fastest disc's speed {fastest:.3e} times the longest box edge {edge:.3e} \
                 is {product:.3e}, beyond what f64 arithmetic on contact times can hold"
            ),
            format!("speed × box edge ≤ {SPEED_TIMES_SIZE_LIMIT:e}"),
        ));
    }
    let energy = crate::state::kinetic_energy(&spec.species, species_of, velocities);
    if !energy.is_finite() {
        return Err(InitError::invalid(
            field,
            "the total kinetic energy overflows f64",
            "masses and speeds whose Σ m v²/2 is finite",
        ));
    }
    Ok(())
}

impl SystemSpec {
    /// Check every field, place the discs and draw velocities.
    pub fn build(&self) -> Result<State, InitError> {
        let state = self.build_observed(&mut |_| ControlFlow::Continue(()))?;
        Ok(state.expect("an observer that never stops"))
    }

    /// [`SystemSpec::build`], reporting the progress of relaxed placement (about a
    /// minute for 10⁶ discs, more near jamming) before every minimization step,
    /// and of compressed placement (as long as the growth law makes it) during
    /// the growth, to `observe`. When `observe` breaks, building stops and
    /// returns `Ok(None)`. Other placements never call it.
    pub fn build_observed(
        &self,
        observe: &mut dyn FnMut(&PlacementProgress) -> ControlFlow<()>,
    ) -> Result<Option<State>, InitError> {
        self.validate()?;
        let n: usize = self.species.iter().map(|s| s.count).sum();
        let mut species_of = Vec::with_capacity(n);
        for (k, s) in self.species.iter().enumerate() {
            species_of.extend(std::iter::repeat_n(k as u16, s.count));
        }
        let mut rng = Pcg64::seed_from_u64(self.seed);
        let positions = match &self.placement {
            Placement::Lattice => lattice(self, &species_of, &mut rng)?,
            Placement::Random => random(self, &species_of, &mut rng)?,
            Placement::Relaxed => match relaxed(self, &species_of, &mut rng, observe)? {
                Some(p) => p,
                None => return Ok(None),
            },
            Placement::Compressed { rate, start } => {
                match compressed(self, &species_of, &mut rng, *rate, *start, observe)? {
                    Some(p) => p,
                    None => return Ok(None),
                }
            }
            Placement::Explicit(p) => {
                check_explicit(self, &species_of, p)?;
                p.iter().map(|&r| self.sim_box.wrap(r)).collect()
            }
        };
        let velocities = match &self.velocities {
            Velocities::MaxwellBoltzmann => maxwell_boltzmann(self, &species_of, &mut rng),
            Velocities::EqualSpeed => equal_speed(self, &species_of, &mut rng),
            Velocities::Explicit(v) => {
                if v.len() != n {
                    return Err(InitError::invalid(
                        "velocities",
                        format!("{} velocities given for {n} discs", v.len()),
                        "exactly one velocity per disc",
                    ));
                }
                if let Some(k) = v.iter().position(|v| !v.is_finite()) {
                    return Err(InitError::invalid(
                        format!("velocities[{k}]"),
                        "velocity is not finite",
                        "finite numbers",
                    ));
                }
                v.clone()
            }
        };
        let field = match &self.velocities {
            Velocities::Explicit(_) => "velocities",
            _ => "temperature",
        };
        check_scales(self, &species_of, &velocities, field)?;
        Ok(Some(State {
            sim_box: self.sim_box,
            species: self.species.clone(),
            species_of,
            images: vec![[0; 2]; positions.len()],
            positions,
            velocities,
            time: 0.0,
        }))
    }
}
