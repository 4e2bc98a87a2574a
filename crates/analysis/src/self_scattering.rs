//! The self intermediate scattering function (physics.md §13): in 2D the
//! isotropic average of cos(k·Δu) over the directions of k is the Bessel function
//! J₀(k|Δu|), so
//!
//!   F_s(k, τ) = ⟨J₀(k |u_i(t₀ + τ) − u_i(t₀)|)⟩,
//!
//! evaluated at k*, the first peak of S(k) of the first origin (periodic boxes;
//! [`super::structure_factor`]'s shells on the box's wave vectors, searched from
//! π/σ_min up). The α-time
//! τ_α solves F_s(k*, τ_α) = 1/e, linearly interpolated in ln τ between the
//! bracketing lags. J₀ is `libm`'s (the FreeBSD msun implementation).

use carom_core::SimBox;

use super::structure_factor::{first_peak, shells, snapshot_sk};

/// k* (1/length): the first peak of S(k) ([`first_peak`], physics.md §11) of the
/// discs at (`x`, `y`) (any images) in the periodic `sim_box`; `None` for walls
/// or when no shell reaches
/// [`K_STAR_MIN_SIGMA`](super::structure_factor::K_STAR_MIN_SIGMA)/σ_min.
pub fn first_peak_k(sim_box: &SimBox, sigma_min: f64, x: &[f64], y: &[f64]) -> Option<f64> {
    if !sim_box.boundary.iter().all(|b| b.is_periodic())
        || x.is_empty()
        || sigma_min.is_nan()
        || sigma_min <= 0.0
    {
        return None;
    }
    let sk = snapshot_sk(sim_box, sigma_min, x, y);
    let (dk, _, _) = shells(sim_box, sigma_min);
    // Shells with vectors, short of the last (cut by k_max: few vectors, noisy).
    let (k, s): (Vec<f64>, Vec<f64>) = (1..sk.sums.len().saturating_sub(1))
        .filter(|&sh| sk.counts[sh] > 0)
        .map(|sh| (sh as f64 * dk, sk.sums[sh] / sk.counts[sh] as f64))
        .unzip();
    first_peak(&k, &s, sigma_min).map(|p| k[p])
}

/// τ_α: the first lag where `fs` falls to 1/e, linear in ln τ between the two
/// bracketing positive lags (`lag` increasing); `None` if it never does, or does
/// already at the first positive lag (τ_α shorter than the lags, unbracketed).
pub fn tau_alpha(lag: &[f64], fs: &[f64]) -> Option<f64> {
    let target = (-1.0f64).exp();
    let pts: Vec<(f64, f64)> = lag
        .iter()
        .zip(fs)
        .filter(|(t, f)| **t > 0.0 && f.is_finite())
        .map(|(&t, &f)| (t, f))
        .collect();
    if pts.first().is_some_and(|p| p.1 <= target) {
        return None;
    }
    pts.windows(2).find_map(|w| {
        let ((t0, f0), (t1, f1)) = (w[0], w[1]);
        (f0 > target && f1 <= target).then(|| {
            let w = (f0 - target) / (f0 - f1);
            (t0.ln() + w * (t1.ln() - t0.ln())).exp()
        })
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    /// F_s falling from 1 through 0.5 at τ = 1 to 0.25 at τ = 4: 1/e is crossed
    /// between them at ln τ = ln 4·(0.5 − 1/e)/(0.5 − 0.25); lag 0 is skipped;
    /// no crossing, or a first positive lag already below, gives None.
    #[test]
    fn tau_alpha_interpolates_in_ln_tau() {
        let e = (-1.0f64).exp();
        let got = tau_alpha(&[0.0, 1.0, 4.0, 9.0], &[1.0, 0.5, 0.25, 0.1]).unwrap();
        let want = (4f64.ln() * (0.5 - e) / 0.25).exp();
        assert!((got - want).abs() < 1e-12, "{got} vs {want}");
        assert_eq!(tau_alpha(&[0.0, 1.0, 2.0], &[1.0, 0.9, 0.5]), None);
        assert_eq!(tau_alpha(&[0.0, 2.0, 3.0], &[1.0, 0.2, 0.1]), None);
    }

    /// A triangular lattice of spacing 1 has its first Bragg shell at 4π/√3;
    /// walls give no k*.
    #[test]
    fn the_first_peak_of_a_lattice_is_its_bragg_shell() {
        let (sb, x, y) = super::super::test_lattice::triangular(16, 18, 1.0);
        let k = first_peak_k(&sb, 1.0, &x, &y).unwrap();
        let (dk, _, _) = shells(&sb, 1.0);
        let g0 = 4.0 * PI / 3f64.sqrt();
        assert!((k - g0).abs() <= 0.5 * dk, "{k} vs {g0}");
        let walled = SimBox::walled(10.0, 10.0, 1.0);
        assert_eq!(first_peak_k(&walled, 1.0, &x, &y), None);
    }
}
