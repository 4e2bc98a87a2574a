//! What kinetic theory expects of the transport coefficients of hard discs
//! (physics.md §14.4–14.5): Enskog's self-diffusion, shear viscosity and thermal
//! conductivity (Gass 1971), with the dilute gas's Sonine factors f (sonine.rs)
//! on the kinetic parts,
//!
//!   D_E = f_D D₀/χ,  η_E = η₀ [f_η (1 + φχ)²/χ + (8/π) φ²χ],
//!   λ_E = λ₀ [f_λ (1 + 3φχ/2)²/χ + (4/π) φ²χ],
//!   D₀ = √(kT/πm)/(2nσ),  η₀ = √(mkT/π)/(2σ),  λ₀ = (2/σ) √(kT/πm),
//!
//! with χ = g(σ⁺) and φ the packing fraction, k_B = 1; and the amplitude of the
//! VACF's long-time tail in 2D from mode coupling (Ernst, Hauge & van Leeuwen),
//! C(t)/C(0) → 1/[8π n (D + ν) t], ν = η/(nm) the kinematic viscosity.

use super::sonine::SonineFactors;
use std::f64::consts::PI;

/// Enskog's values for a one-species disc fluid.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Enskog {
    pub(super) d: f64,
    pub(super) eta: f64,
    pub(super) lambda: f64,
}

/// Enskog's D, η, λ for discs of diameter `sigma` and mass `m` at number density
/// `n`, temperature `kt`, packing fraction `phi` and contact value `chi`, with
/// the Sonine factors `f` (all 1 for the first Sonine approximation).
pub(super) fn enskog(
    sigma: f64,
    m: f64,
    n: f64,
    kt: f64,
    [phi, chi]: [f64; 2],
    f: SonineFactors,
) -> Enskog {
    let d0 = (kt / (PI * m)).sqrt() / (2.0 * n * sigma);
    let eta0 = (m * kt / PI).sqrt() / (2.0 * sigma);
    let lambda0 = 2.0 / sigma * (kt / (PI * m)).sqrt();
    let pc = phi * chi;
    Enskog {
        d: f.d * d0 / chi,
        eta: eta0 * (f.eta * (1.0 + pc).powi(2) / chi + 8.0 / PI * phi * pc),
        lambda: lambda0 * (f.lambda * (1.0 + 1.5 * pc).powi(2) / chi + 4.0 / PI * phi * pc),
    }
}

/// The contact value χ from the compressibility factor, Z = 1 + 2φχ.
pub(super) fn chi_from_z(z: f64, phi: f64) -> f64 {
    (z - 1.0) / (2.0 * phi)
}

/// The mode-coupling amplitude A of the normalised VACF tail, C(t)/C(0) ≈ A/t,
/// at number density `n` with self-diffusion `d` and shear viscosity `eta` of
/// discs of mass `m`.
pub(super) fn tail_amplitude(n: f64, m: f64, d: f64, eta: f64) -> f64 {
    1.0 / (8.0 * PI * n * (d + eta / (n * m)))
}

#[cfg(test)]
mod tests {
    use super::*;

    const FIRST_SONINE: SonineFactors = SonineFactors {
        d: 1.0,
        eta: 1.0,
        lambda: 1.0,
    };

    /// In the dilute limit (χ = 1, φ → 0) the Enskog values are the Boltzmann
    /// ones, and they obey two identities of the first Sonine approximation in
    /// 2D: D₀ = (kT/m)/ω₀ with ω₀ = 2√π nσ√(kT/m) the collision rate
    /// (physics.md §7), and λ₀ = 4 η₀/m (the Eucken ratio d(d+2)/(2(d−1)) = 4).
    #[test]
    fn dilute_values_obey_the_sonine_identities() {
        let (sigma, m, n, kt) = (1.3, 2.5, 0.01, 0.7);
        let e = enskog(sigma, m, n, kt, [0.0, 1.0], FIRST_SONINE);
        let omega0 = 2.0 * PI.sqrt() * n * sigma * (kt / m).sqrt();
        assert!((e.d - kt / m / omega0).abs() < 1e-14 * e.d);
        assert!((e.lambda - 4.0 * e.eta / m).abs() < 1e-14 * e.lambda);
        // η₀ from its definition with these numbers: √(2.5·0.7/π)/2.6.
        assert!((e.eta - (1.75 / PI).sqrt() / 2.6).abs() < 1e-15);
    }

    /// At φ = 0.2 with χ = 1.5 the brackets are 1/1.5 + 0.4 + 0.04·1.5·(1 + 8/π)
    /// and 1/1.5 + 0.6 + 0.04·1.5·(9/4 + 4/π), and D is divided by χ.
    #[test]
    fn dense_factors() {
        let dilute = enskog(1.0, 1.0, 0.3, 1.0, [0.0, 1.0], FIRST_SONINE);
        let e = enskog(1.0, 1.0, 0.3, 1.0, [0.2, 1.5], FIRST_SONINE);
        assert!((e.d - dilute.d / 1.5).abs() < 1e-15);
        let eta_factor = 1.0 / 1.5 + 0.4 + 0.06 * (1.0 + 8.0 / PI);
        assert!((e.eta / dilute.eta - eta_factor).abs() < 1e-14);
        let lambda_factor = 1.0 / 1.5 + 0.6 + 0.06 * (2.25 + 4.0 / PI);
        assert!((e.lambda / dilute.lambda - lambda_factor).abs() < 1e-14);
    }

    /// The Sonine factors scale D and the kinetic parts (1 + φχ)²/χ and
    /// (1 + 3φχ/2)²/χ only: at φ = 0.2, χ = 1.5 with f = (1.1, 1.2, 1.3),
    /// η/η₀ = 1.2·1.69/1.5 + 0.48/π and λ/λ₀ = 1.3·2.1025/1.5 + 0.24/π.
    #[test]
    fn sonine_factors_scale_the_kinetic_parts() {
        let f = SonineFactors {
            d: 1.1,
            eta: 1.2,
            lambda: 1.3,
        };
        let dilute = enskog(1.0, 1.0, 0.3, 1.0, [0.0, 1.0], FIRST_SONINE);
        let e = enskog(1.0, 1.0, 0.3, 1.0, [0.2, 1.5], f);
        assert!((e.d / dilute.d - 1.1 / 1.5).abs() < 1e-14);
        assert!((e.eta / dilute.eta - (1.2 * 1.69 / 1.5 + 0.48 / PI)).abs() < 1e-14);
        assert!((e.lambda / dilute.lambda - (1.3 * 2.1025 / 1.5 + 0.24 / PI)).abs() < 1e-14);
    }

    #[test]
    fn chi_and_tail_amplitude() {
        // Z = 1 + 2·0.25·χ with χ = 1.8 gives Z = 1.9.
        assert!((chi_from_z(1.9, 0.25) - 1.8).abs() < 1e-15);
        // n = 0.5, m = 2, D = 0.1, η = 0.4: ν = 0.4, A = 1/(8π·0.5·0.5).
        let a = tail_amplitude(0.5, 2.0, 0.1, 0.4);
        assert!((a - 1.0 / (2.0 * PI)).abs() < 1e-15);
    }
}
