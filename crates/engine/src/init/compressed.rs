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
//! The growth reports its packing fraction to the caller's observer after every
//! rescale interval and every few thousand events, and stops when it breaks.

use super::random::random;
use super::spec::{Compressing, PlacementProgress, SystemSpec};
use super::velocities::maxwell_boltzmann;
use crate::engine::{Engine, EngineParams, Growth, GrowthEnd};
use crate::error::InitError;
use crate::state::State;
use crate::MAX_RECORDS;
use carom_core::observables::packing_fraction;
use carom_core::DVec2;
use rand_pcg::Pcg64;
use std::ops::ControlFlow;

/// The jamming bound of compressed placement (Z = βPA/N; physics.md (17.7)).
pub const COMPRESSED_MAX_REDUCED_PRESSURE: f64 = 1e4;

/// Positions of the discs of `spec` by compression from `start` (a packing
/// fraction) at the relative growth rate `rate` (1/time), the progress reported
/// to `observe`; `None` when it stopped them.
pub(super) fn compressed(
    spec: &SystemSpec,
    species_of: &[u16],
    rng: &mut Pcg64,
    rate: f64,
    start: f64,
    observe: &mut dyn FnMut(&PlacementProgress) -> ControlFlow<()>,
) -> Result<Option<Vec<DVec2>>, InitError> {
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
    let kt = if spec.temperature > 0.0 {
        spec.temperature
    } else {
        1.0
    };
    let d_max = 2.0 * spec.largest_radius();
    let m_min = spec
        .species
        .iter()
        .filter(|s| s.count > 0)
        .map(|s| s.mass)
        .fold(f64::INFINITY, f64::min);
    let step = d_max / (kt / m_min).sqrt();
    // The radii grow as s₀ (1 + γ t) up to the scale 1/s₀ (physics.md (17.1)):
    // a growth time (1/s₀ − 1)/γ, with a rescale every step.
    let intervals = ((scale - 1.0) / rate / step).ceil();
    if intervals.is_nan() || intervals > MAX_RECORDS {
        return Err(InitError::invalid(
            format!("{field}.rate"),
            format!(
                "growing the discs from packing fraction {start:e} to {eta:.4} at rate {rate:e} \
                 takes {:.3e} time units: {intervals:.3e} velocity rescales, one every {step:.4e} \
                 (the largest diameter crossed at the thermal speed)",
                (scale - 1.0) / rate
            ),
            format!(
                "at most {MAX_RECORDS:e} rescales: a larger rate, or a \
                 placement.compressed.start_packing_fraction nearer the target"
            ),
        ));
    }
    let mut small = spec.clone();
    for s in &mut small.species {
        s.radius /= scale;
    }
    let positions = random(&small, species_of, rng)?;
    small.temperature = kt;
    let velocities = maxwell_boltzmann(&small, species_of, rng);
    let params = EngineParams {
        growth: Growth {
            rate,
            target_scale: scale,
            kt,
            rescale_interval: step,
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
    let step = params.growth.rescale_interval;
    let mut engine = Engine::new(state, params).map_err(fail)?;
    let max_steps = if intervals < usize::MAX as f64 {
        intervals as usize
    } else {
        usize::MAX
    };
    let mut seen = |engine: &Engine, steps: usize| {
        let s = engine.radius_scale() / scale;
        observe(&PlacementProgress {
            discs: species_of.len(),
            steps,
            max_steps,
            close: 1,
            compressing: Some(Compressing {
                packing_fraction: eta * s * s,
                target: eta,
                reduced_pressure: engine.growth().last_z,
            }),
        })
    };
    let mut steps = 0;
    while engine.growth().ended == GrowthEnd::Growing {
        if seen(&engine, steps).is_break() {
            return Ok(None);
        }
        let until = engine.now() + step;
        let flow = engine
            .run_growing_until(until, &mut |e| seen(e, steps))
            .map_err(fail)?;
        if flow.is_break() {
            return Ok(None);
        }
        steps += 1;
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
    Ok(Some(engine.state().positions))
}
