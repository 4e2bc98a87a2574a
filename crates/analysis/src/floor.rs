//! Runs on a vibrating floor (physics.md §18): the floor's amplitude, frequency
//! and shaking parameter Γ = A ω²/g, and the energy flows over the analysis
//! window from the engine's totals in the log's checkpoints: the work W the floor
//! did and the energy E_lost the collisions dissipated between the first
//! checkpoint in the window and the last, as mean powers W/Δt and E_lost/Δt. In a
//! steady state they are equal; their difference is Δ(K + U)/Δt. A driven bed is
//! not in equilibrium nor a cooling state: the analyzer leaves out the energy
//! budget, Haff's law and the cooling state's a2, and compares the barometric fit
//! with no known value (its n(y) and fitted β_g are still reported).

use carom_core::vibrating_wall::Floor;
use serde::Serialize;

/// The floor and the energy it puts in.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FloorReport {
    /// Amplitude A (length): the floor moves between 0 and 2A.
    pub amplitude: f64,
    /// Frequency f = ω/2π (1/time).
    pub frequency: f64,
    /// Γ = A ω²/g, the floor's peak acceleration in units of g (`null` without a field).
    pub shaking_parameter: Option<f64>,
    /// The checkpoints whose totals are compared: the first at or after the
    /// analysis window's start, and the last (time).
    pub window: [f64; 2],
    /// Work the floor did on the discs between them (energy).
    pub floor_work: f64,
    /// Energy dissipated in collisions between them (energy).
    pub energy_lost: f64,
    /// Mean power in from the floor over the window (energy/time).
    pub power_in: f64,
    /// Mean dissipated power over the window (energy/time).
    pub power_out: f64,
}

/// The floor report of a run with floor `floor` in a field `g`, from the
/// engine's totals (time, floor work, energy lost) at its checkpoints, over the
/// first checkpoint at or after `from` to the last; `None` over less than two
/// checkpoints.
pub(super) fn report(
    floor: &Floor,
    g: f64,
    totals: &[(f64, f64, f64)],
    from: f64,
) -> Option<FloorReport> {
    let a = totals.iter().find(|c| c.0 >= from)?;
    let b = totals.last().expect("one found above");
    let span = b.0 - a.0;
    if span <= 0.0 {
        return None;
    }
    Some(FloorReport {
        amplitude: floor.amplitude,
        frequency: floor.omega / (2.0 * std::f64::consts::PI),
        shaking_parameter: (g > 0.0).then(|| floor.amplitude * floor.omega.powi(2) / g),
        window: [a.0, b.0],
        floor_work: b.1 - a.1,
        energy_lost: b.2 - a.2,
        power_in: (b.1 - a.1) / span,
        power_out: (b.2 - a.2) / span,
    })
}
