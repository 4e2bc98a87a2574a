//! The one-sample Kolmogorov–Smirnov test, with p-values from the asymptotic
//! Kolmogorov distribution and Stephens' small-n correction (physics.md §6). The
//! Kolmogorov series, which `statrs` does not provide, is summed here.

use super::StatsError;

/// Result of the one-sample Kolmogorov–Smirnov test.
#[derive(Debug, Clone, PartialEq)]
pub struct KsTest {
    /// D = sup_x |F_n(x) − F(x)| (dimensionless).
    pub statistic: f64,
    /// Sample size n.
    pub n: usize,
    /// Approximate P(D_n ≥ statistic) under the hypothesis, from the asymptotic
    /// Kolmogorov distribution with Stephens' small-n correction
    /// ([`kolmogorov_p_value`]).
    pub p_value: f64,
}

/// One-sample Kolmogorov–Smirnov test of `samples` against a fully specified
/// continuous distribution with CDF `cdf`. Sorts a copy of the samples.
///
/// Caveat (Lilliefors): the p-value assumes the distribution was fixed before
/// looking at the data. When a parameter (the temperature) is estimated from the
/// same sample, D is stochastically smaller and this p-value is conservative
/// (too large): a small p-value still rejects, but a large one is weaker evidence
/// than it looks. The effect does not shrink with N when every disc of a snapshot
/// is tested against the kT = 2K/f of the same velocities: the sample's second
/// moment is then fitted exactly. The samples must also be independent: velocities
/// of one disc in snapshots less than a few collision times apart are correlated,
/// which makes the test reject too often (physics.md §6).
pub fn ks_test(samples: &[f64], cdf: impl Fn(f64) -> f64) -> Result<KsTest, StatsError> {
    let n = samples.len();
    if n == 0 {
        return Err(StatsError::NotEnoughData("KS test of no samples".into()));
    }
    if samples.iter().any(|x| x.is_nan()) {
        return Err(StatsError::InvalidArgument("NaN sample".into()));
    }
    let mut x = samples.to_vec();
    // Equal under total_cmp means equal bits, so an unstable sort gives the same
    // order as a stable one, and faster (the sort dominated `carom analyze` on
    // 10⁷ speeds).
    x.sort_unstable_by(f64::total_cmp);
    let nf = n as f64;
    let d = x
        .iter()
        .enumerate()
        .map(|(i, &xi)| {
            let f = cdf(xi);
            ((i + 1) as f64 / nf - f).max(f - i as f64 / nf)
        })
        .fold(0.0, f64::max);
    Ok(KsTest {
        statistic: d,
        n,
        p_value: kolmogorov_p_value(d, n),
    })
}

/// Survival function of the Kolmogorov distribution,
/// Q_KS(λ) = 2 Σ_{j≥1} (−1)^{j−1} exp(−2 j² λ²), evaluated at Stephens' (1970)
/// corrected argument λ = (√n + 0.12 + 0.11/√n) D: the approximate probability
/// that the KS statistic of n samples from the hypothesised distribution is ≥ D.
/// Accurate to about 0.01 in p for n ≥ 5 and better for large n.
pub fn kolmogorov_p_value(d: f64, n: usize) -> f64 {
    if n == 0 || d <= 0.0 {
        return 1.0;
    }
    let sn = (n as f64).sqrt();
    kolmogorov_survival((sn + 0.12 + 0.11 / sn) * d)
}

/// Q_KS(λ) = 2 Σ_{j≥1} (−1)^{j−1} exp(−2 j² λ²), the asymptotic probability
/// P(√n D_n > λ) (dimensionless).
pub fn kolmogorov_survival(lambda: f64) -> f64 {
    if lambda < 0.2 {
        // The alternating series converges slowly here and the value is 1 to
        // within 5e-13 (1 − Q_KS(0.2) ≈ 5.0e-13, 3e-23 at 0.15).
        return 1.0;
    }
    let mut sum = 0.0;
    let mut sign = 1.0;
    for j in 1..=100 {
        let term = (-2.0 * (j * j) as f64 * lambda * lambda).exp();
        sum += sign * term;
        if term < 1e-17 * sum.abs() {
            break;
        }
        sign = -sign;
    }
    (2.0 * sum).clamp(0.0, 1.0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;
    use rand_distr::{Distribution, Uniform};
    use rand_pcg::Pcg64;

    #[test]
    fn kolmogorov_p_values_match_tables() {
        // Asymptotic critical values: Q_KS(1.3581) = 0.05, Q_KS(1.6276) = 0.01,
        // Q_KS(1.2238) = 0.10.
        assert!((kolmogorov_survival(1.3581) - 0.05).abs() < 2e-4);
        assert!((kolmogorov_survival(1.6276) - 0.01).abs() < 1e-4);
        assert!((kolmogorov_survival(1.2238) - 0.10).abs() < 3e-4);
        // Exact small-n critical values (Miller 1956 tables): n = 10, α = 0.05:
        // D = 0.409; n = 20, α = 0.05: 0.294; n = 20, α = 0.01: 0.352.
        assert!((kolmogorov_p_value(0.409, 10) - 0.05).abs() < 3e-3);
        assert!((kolmogorov_p_value(0.294, 20) - 0.05).abs() < 3e-3);
        assert!((kolmogorov_p_value(0.352, 20) - 0.01).abs() < 1e-3);
        assert_eq!(kolmogorov_p_value(0.0, 10), 1.0);
        assert!(kolmogorov_p_value(1.0, 100) < 1e-30);
    }

    #[test]
    fn ks_statistic_of_a_small_sample_by_hand() {
        // Uniform(0,1) CDF, samples 0.1, 0.5, 0.6: D = max(1/3 − 0.1, 0.5 − 1/3,
        // 2/3 − 0.5, 0.6 − 2/3, 1 − 0.6) = 0.4.
        let t = ks_test(&[0.6, 0.1, 0.5], |x| x.clamp(0.0, 1.0)).unwrap();
        assert!((t.statistic - 0.4).abs() < 1e-12);
        assert_eq!(t.n, 3);
        assert!(ks_test(&[], |x| x).is_err());
    }

    #[test]
    fn ks_p_values_are_uniform_under_the_null() {
        // 400 samples of size 50 from U(0,1): the fraction with p < 0.05 should be
        // 0.05 (binomial sd 0.011); with p < 0.2, 0.2 (sd 0.02).
        let mut rng = Pcg64::seed_from_u64(11);
        let u = Uniform::new(0.0, 1.0).unwrap();
        let mut below5 = 0;
        let mut below20 = 0;
        for _ in 0..400 {
            let x: Vec<f64> = (0..50).map(|_| u.sample(&mut rng)).collect();
            let p = ks_test(&x, |v| v.clamp(0.0, 1.0)).unwrap().p_value;
            below5 += (p < 0.05) as usize;
            below20 += (p < 0.2) as usize;
        }
        let f5 = below5 as f64 / 400.0;
        let f20 = below20 as f64 / 400.0;
        assert!((f5 - 0.05).abs() < 0.035, "{f5}");
        assert!((f20 - 0.2).abs() < 0.06, "{f20}");
    }

    /// Q_KS(λ) from the other theta-function form, 1 − (√(2π)/λ) Σ_{j≥1}
    /// exp(−(2j − 1)² π²/(8λ²)), which converges fast where the alternating
    /// series does not (small λ); accurate to ~1e-16 absolute for λ ≤ 3.
    fn q_ks_dual(lambda: f64) -> f64 {
        let pi2 = std::f64::consts::PI.powi(2);
        let s: f64 = (1..20)
            .map(|j| (-((2 * j - 1) as f64).powi(2) * pi2 / (8.0 * lambda * lambda)).exp())
            .sum();
        1.0 - std::f64::consts::TAU.sqrt() / lambda * s
    }

    #[test]
    fn kolmogorov_survival_agrees_with_its_dual_series() {
        // Q_KS(1) = 0.27000 (tables); the two series agree to rounding.
        assert!((kolmogorov_survival(1.0) - 0.27).abs() < 1e-5);
        for lambda in [0.2, 0.3, 0.5, 0.8, 1.0, 1.3581, 2.0, 3.0] {
            let (q, want) = (kolmogorov_survival(lambda), q_ks_dual(lambda));
            assert!((q - want).abs() < 2e-15, "{lambda}: {q} vs {want}");
        }
        // At λ = 0.2 the value is 1 − 5.0e-13, not yet 1.
        assert!(kolmogorov_survival(0.2) < 1.0 - 4e-13);
        // Below 0.2 it is 1 (the dual series: 1 − 3e-23 at 0.15), including at
        // λ = 0 (D = 0), where the alternating series would not converge.
        for lambda in [0.0, 0.01, 0.1, 0.15] {
            assert_eq!(kolmogorov_survival(lambda), 1.0, "{lambda}");
        }
    }

    #[test]
    fn kolmogorov_p_value_uses_stephens_argument() {
        // λ = (√n + 0.12 + 0.11/√n) D: n = 4 → 2.175 D, n = 25 → 5.142 D.
        let p = kolmogorov_p_value(0.5, 4);
        assert!((p - q_ks_dual(2.175 * 0.5)).abs() < 1e-14, "{p}");
        let p = kolmogorov_p_value(0.3, 25);
        assert!((p - q_ks_dual(5.142 * 0.3)).abs() < 1e-14, "{p}");
        // No samples: no evidence against the hypothesis.
        assert_eq!(kolmogorov_p_value(0.3, 0), 1.0);
    }

    #[test]
    fn ks_statistic_from_below_the_empirical_cdf() {
        // Exponential CDF F(x) = 1 − exp(−2x), samples at F = 0.05, 0.85, 0.9
        // (x = −ln(1 − F)/2). Gaps i/3 − F and F − (i−1)/3: 1/3 − 0.05, 0.05;
        // 2/3 − 0.85 < 0, 0.85 − 1/3; 1 − 0.9, 0.9 − 2/3. D = 0.85 − 1/3,
        // attained where the CDF is above the empirical step.
        let x: Vec<f64> = [0.9, 0.05, 0.85]
            .iter()
            .map(|u: &f64| -(1.0 - u).ln() / 2.0)
            .collect();
        let t = ks_test(&x, |v| if v > 0.0 { 1.0 - (-2.0 * v).exp() } else { 0.0 }).unwrap();
        assert!((t.statistic - (0.85 - 1.0 / 3.0)).abs() < 1e-12, "{t:?}");
        assert_eq!(t.n, 3);
        assert!(ks_test(&[0.1, f64::NAN], |v| v).is_err());
    }
}
