//! Compressed placement: random positions at a low packing fraction, then the
//! discs grown in the event-driven engine until they have the requested radii
//! (Lubachevsky–Stillinger compression, physics.md §17).
//!
//! The discs start with every radius a_i scaled by s₀ = √(η_start/η), placed at
//! random (`init::random`) with Maxwell–Boltzmann velocities at the requested kT
//! (1 if it is 0), and grow as a_i s₀ (1 + γ t) until the scale 1/s₀, the radii
//! asked for. Velocities are scaled back to kT every d_max/√(kT/m_min) (the largest
//! final diameter crossed at the thermal speed of the lightest disc). A slow
//! compression (γ d_max ≪ √(kT/m)) equilibrates on the way: monodisperse discs
//! crystallise above η ≈ 0.72; a fast one gives a disordered packing. A compression
//! that jams first (Z above 10⁴) is refused, with the packing fraction it reached.

use super::random::random;
use super::spec::SystemSpec;
use super::velocities::maxwell_boltzmann;
use crate::engine::{Engine, EngineParams, Growth, GrowthEnd};
use crate::error::InitError;
use crate::state::State;
use carom_core::observables::packing_fraction;
use carom_core::DVec2;
use rand_pcg::Pcg64;

/// The jamming bound of compressed placement (Z = βPA/N; physics.md (17.7)).
pub const COMPRESSED_MAX_REDUCED_PRESSURE: f64 = 1e4;

/// Positions of the discs of `spec` by compression from `start` (a packing
/// fraction) at the relative growth rate `rate` (1/time).
pub(super) fn compressed(
    spec: &SystemSpec,
    species_of: &[u16],
    rng: &mut Pcg64,
    rate: f64,
    start: f64,
) -> Result<Vec<DVec2>, InitError> {
    let field = "placement.compressed";
    let eta = packing_fraction(&spec.species, &spec.sim_box);
    if !(rate.is_finite() && rate > 0.0) {
        return Err(InitError::invalid(
            format!("{field}.rate"),
            format!("value {rate}"),
            "a finite relative growth rate > 0 (1/time)",
        ));
    }
    if !(start > 0.0 && start <= eta) {
        return Err(InitError::invalid(
            format!("{field}.start_packing_fraction"),
            format!("value {start} with the box's packing fraction {eta}"),
            "0 < start ≤ the packing fraction of the species in the box (random placement \
             reaches about 0.4)",
        ));
    }
    let scale = (eta / start).sqrt();
    let mut small = spec.clone();
    for s in &mut small.species {
        s.radius /= scale;
    }
    let positions = random(&small, species_of, rng)?;
    let kt = if spec.temperature > 0.0 {
        spec.temperature
    } else {
        1.0
    };
    small.temperature = kt;
    let velocities = maxwell_boltzmann(&small, species_of, rng);
    let d_max = 2.0 * spec.largest_radius();
    let m_min = spec
        .species
        .iter()
        .filter(|s| s.count > 0)
        .map(|s| s.mass)
        .fold(f64::INFINITY, f64::min);
    let params = EngineParams {
        growth: Growth {
            rate,
            target_scale: scale,
            kt,
            rescale_interval: d_max / (kt / m_min).sqrt(),
            max_reduced_pressure: COMPRESSED_MAX_REDUCED_PRESSURE,
        },
        ..EngineParams::default()
    };
    let state = State {
        sim_box: spec.sim_box,
        species: small.species.clone(),
        species_of: species_of.to_vec(),
        images: vec![[0; 2]; positions.len()],
        positions,
        velocities,
        time: 0.0,
    };
    let fail = |e: crate::EngineError| {
        InitError::invalid(field, e.to_string(), "a compression the engine can run")
    };
    let mut engine = Engine::new(state, params).map_err(fail)?;
    let step = params.growth.rescale_interval;
    while engine.growth().ended == GrowthEnd::Growing {
        let until = engine.now() + step;
        engine.run_growing_until(until).map_err(fail)?;
    }
    if engine.growth().ended == GrowthEnd::Jammed {
        let s = engine.radius_scale() / scale;
        return Err(InitError::invalid(
            field,
            format!(
                "the discs jammed at packing fraction {:.4} (Z > {COMPRESSED_MAX_REDUCED_PRESSURE:e}) \
                 before reaching {eta:.4}",
                eta * s * s
            ),
            "a packing fraction below jamming, or a slower compression (smaller rate)",
        ));
    }
    Ok(engine.state().positions)
}
