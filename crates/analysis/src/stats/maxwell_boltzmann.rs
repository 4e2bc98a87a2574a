//! The 2D Maxwell–Boltzmann distribution (physics.md §6) and the test of one
//! species' speeds against it: a histogram with a χ² test and a KS test.

use statrs::function::erf::erfc;

use super::{chi_square_histogram, ks_test, ChiSquareTest, Histogram, KsTest, StatsError};

/// The 2D Maxwell–Boltzmann distribution of one species (physics.md §6): each
/// velocity component Gaussian with variance kT/m; the speed has pdf
/// f(v) = (m v/kT) exp(−m v²/(2kT)) and CDF 1 − exp(−m v²/(2kT)).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MaxwellBoltzmann2d {
    /// Particle mass m (mass).
    pub mass: f64,
    /// Temperature kT (energy).
    pub kt: f64,
}

impl MaxwellBoltzmann2d {
    /// The distribution for mass `mass` at temperature `kt` (both > 0).
    pub fn new(mass: f64, kt: f64) -> Result<Self, StatsError> {
        if !(mass.is_finite() && mass > 0.0 && kt.is_finite() && kt > 0.0) {
            return Err(StatsError::InvalidArgument(format!(
                "Maxwell–Boltzmann with m = {mass}, kT = {kt} (need both finite and > 0)"
            )));
        }
        Ok(MaxwellBoltzmann2d { mass, kt })
    }

    /// Speed pdf f(v) = (m v/kT) exp(−m v²/(2kT)) (time/length), 0 for v < 0.
    pub fn speed_pdf(&self, v: f64) -> f64 {
        if v < 0.0 {
            return 0.0;
        }
        let a = self.mass / self.kt;
        a * v * (-0.5 * a * v * v).exp()
    }

    /// Speed CDF 1 − exp(−m v²/(2kT)), 0 for v < 0.
    pub fn speed_cdf(&self, v: f64) -> f64 {
        if v <= 0.0 {
            return 0.0;
        }
        -(-0.5 * self.mass * v * v / self.kt).exp_m1()
    }

    /// Most probable speed √(kT/m) (length/time); also the component standard
    /// deviation.
    pub fn scale(&self) -> f64 {
        (self.kt / self.mass).sqrt()
    }

    /// Mean speed √(π kT/(2m)) (length/time).
    pub fn mean_speed(&self) -> f64 {
        (std::f64::consts::FRAC_PI_2 * self.kt / self.mass).sqrt()
    }

    /// Velocity-component pdf: Gaussian of variance kT/m (time/length).
    pub fn component_pdf(&self, vx: f64) -> f64 {
        let s = self.scale();
        (-0.5 * (vx / s).powi(2)).exp() / (s * (std::f64::consts::TAU).sqrt())
    }

    /// Velocity-component CDF Φ(vx/√(kT/m)) = erfc(−vx/√(2kT/m))/2.
    pub fn component_cdf(&self, vx: f64) -> f64 {
        0.5 * erfc(-vx / (self.scale() * std::f64::consts::SQRT_2))
    }
}

/// A speed distribution checked against Maxwell–Boltzmann (physics.md §6).
#[derive(Debug, Clone, PartialEq)]
pub struct MbTest {
    /// The reference distribution (mass and the kT used).
    pub reference: MaxwellBoltzmann2d,
    /// Speed histogram over [0, 4.5 √(kT/m)).
    pub histogram: Histogram,
    /// χ² of the histogram (with the overflow as a bin).
    pub chi_square: ChiSquareTest,
    /// Kolmogorov–Smirnov test of the speeds (see the Lilliefors caveat on
    /// [`ks_test`] when kT was measured from the same data).
    pub ks: KsTest,
}

/// Test speeds of discs of one species (mass `mass`) against the 2D MB speed
/// distribution at `kt`: a histogram of `bins` bins over [0, 4.5 √(kT/m)) with a χ²
/// test and a KS test. `kt_fitted` says whether kT was measured from these data
/// (one fewer χ² degree of freedom, physics.md §6).
pub fn mb_speed_test(
    speeds: &[f64],
    mass: f64,
    kt: f64,
    bins: usize,
    kt_fitted: bool,
) -> Result<MbTest, StatsError> {
    let mb = MaxwellBoltzmann2d::new(mass, kt)?;
    let histogram = Histogram::from_values(speeds.iter().copied(), 0.0, 4.5 * mb.scale(), bins)?;
    let chi_square = chi_square_histogram(&histogram, |v| mb.speed_cdf(v), kt_fitted as usize)?;
    let ks = ks_test(speeds, |v| mb.speed_cdf(v))?;
    Ok(MbTest {
        reference: mb,
        histogram,
        chi_square,
        ks,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;
    use rand_distr::{Distribution, Normal};
    use rand_pcg::Pcg64;

    fn mb_speeds(n: usize, mass: f64, kt: f64, seed: u64) -> Vec<f64> {
        let mut rng = Pcg64::seed_from_u64(seed);
        let g = Normal::new(0.0, (kt / mass).sqrt()).unwrap();
        (0..n)
            .map(|_| g.sample(&mut rng).hypot(g.sample(&mut rng)))
            .collect()
    }

    #[test]
    fn mb_speed_cdf_is_the_integral_of_the_pdf() {
        let mb = MaxwellBoltzmann2d::new(2.0, 1.5).unwrap();
        // Trapezoid integral of the pdf up to v against the CDF.
        let v_end = 2.0;
        let steps = 20_000;
        let h = v_end / steps as f64;
        let integral: f64 = (0..steps)
            .map(|k| 0.5 * h * (mb.speed_pdf(k as f64 * h) + mb.speed_pdf((k + 1) as f64 * h)))
            .sum();
        assert!((integral - mb.speed_cdf(v_end)).abs() < 1e-7);
        assert_eq!(mb.speed_cdf(0.0), 0.0);
        assert!((mb.speed_cdf(100.0) - 1.0).abs() < 1e-15);
        assert!((mb.component_cdf(0.0) - 0.5).abs() < 1e-15);
        // Φ(1) = 0.841344746 at one standard deviation √(kT/m).
        assert!((mb.component_cdf(mb.scale()) - 0.841_344_746).abs() < 1e-8);
        assert!(MaxwellBoltzmann2d::new(0.0, 1.0).is_err());
    }

    #[test]
    fn mb_samples_pass_and_wrong_temperature_fails() {
        for (mass, seed) in [(1.0, 1), (3.0, 2)] {
            let v = mb_speeds(20_000, mass, 1.0, seed);
            let ok = mb_speed_test(&v, mass, 1.0, 40, false).unwrap();
            assert!(ok.chi_square.p_value > 1e-3, "{:?}", ok.chi_square);
            assert!(ok.ks.p_value > 1e-3, "{:?}", ok.ks);
            assert!(ok.chi_square.dof >= 20);
            // The same speeds against a temperature 5 % too high.
            let bad = mb_speed_test(&v, mass, 1.05, 40, false).unwrap();
            assert!(bad.chi_square.p_value < 1e-4, "{:?}", bad.chi_square);
            assert!(bad.ks.p_value < 1e-4, "{:?}", bad.ks);
            // Against the wrong mass (species mixed up).
            let bad = mb_speed_test(&v, 2.0 * mass, 1.0, 40, false).unwrap();
            assert!(bad.ks.p_value < 1e-10);
        }
    }

    #[test]
    fn equal_speeds_fail_the_mb_test() {
        let v = vec![2f64.sqrt(); 1000];
        let t = mb_speed_test(&v, 1.0, 1.0, 30, true).unwrap();
        assert!(t.chi_square.p_value < 1e-10);
        assert!(t.ks.p_value < 1e-10);
    }

    #[test]
    fn mb_chi_square_p_values_are_uniform_under_the_null() {
        // 200 samples of 2000 speeds: about 10 % should have p < 0.1 (sd 0.021).
        let mut below = 0;
        for seed in 0..200 {
            let v = mb_speeds(2000, 1.0, 1.0, 100 + seed);
            let t = mb_speed_test(&v, 1.0, 1.0, 25, false).unwrap();
            below += (t.chi_square.p_value < 0.1) as usize;
        }
        let f = below as f64 / 200.0;
        assert!((f - 0.1).abs() < 0.065, "{f}");
    }

    /// |a − b| ≤ 1e-14 (1 + |b|).
    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() <= 1e-14 * (1.0 + b.abs())
    }

    #[test]
    fn mb_formulas_at_unequal_mass_and_temperature() {
        // m = 3, kT = 2: m/kT = 1.5. At v = 3 (physics.md 6.2–6.3):
        // f = 1.5·3 exp(−1.5·9/2) = 4.5 e^−6.75, F = 1 − e^−6.75.
        let mb = MaxwellBoltzmann2d::new(3.0, 2.0).unwrap();
        assert!(close(mb.speed_pdf(3.0), 4.5 * (-6.75f64).exp()));
        assert!(close(mb.speed_cdf(3.0), 1.0 - (-6.75f64).exp()));
        // And at v = 0.4: f = 0.6 e^−0.12, F = 1 − e^−0.12.
        assert!(close(mb.speed_pdf(0.4), 0.6 * (-0.12f64).exp()));
        assert!(close(mb.speed_cdf(0.4), 1.0 - (-0.12f64).exp()));
        // No negative speeds.
        assert_eq!((mb.speed_pdf(-1.0), mb.speed_cdf(-1.0)), (0.0, 0.0));
        // Scale √(kT/m) = √(2/3), mean speed √(π kT/(2m)) = √(π/3).
        assert!(close(mb.scale(), (2.0f64 / 3.0).sqrt()));
        assert!(close(mb.mean_speed(), (std::f64::consts::PI / 3.0).sqrt()));
        // Component pdf (6.1) √(m/(2π kT)) exp(−m v²/(2kT)) at v = 0.5:
        // √(3/(4π)) e^−0.1875; symmetric.
        let want = (3.0 / (4.0 * std::f64::consts::PI)).sqrt() * (-0.1875f64).exp();
        assert!(close(mb.component_pdf(0.5), want));
        assert!(close(mb.component_pdf(-0.5), want));
        // Component CDF at ±one and two standard deviations: Φ(1) =
        // 0.8413447460685429, Φ(−2) = 0.02275013194817921 (tables; statrs' erfc
        // is good to ~1e-11 here).
        let s = mb.scale();
        assert!((mb.component_cdf(s) - 0.841_344_746_068_542_9).abs() < 1e-10);
        assert!((mb.component_cdf(-2.0 * s) - 0.022_750_131_948_179_21).abs() < 1e-10);
    }

    #[test]
    fn mb_mean_speed_is_the_first_moment_of_the_pdf() {
        // ⟨v⟩ = ∫ v f(v) dv (midpoint rule up to 12 √(kT/m), the tail beyond
        // being e^−72 small), m = 0.7, kT = 2.3.
        let mb = MaxwellBoltzmann2d::new(0.7, 2.3).unwrap();
        let (end, steps) = (12.0 * mb.scale(), 40_000);
        let h = end / steps as f64;
        let mean: f64 = (0..steps)
            .map(|k| {
                let v = (k as f64 + 0.5) * h;
                v * mb.speed_pdf(v) * h
            })
            .sum();
        assert!((mean / mb.mean_speed() - 1.0).abs() < 1e-8, "{mean}");
    }

    #[test]
    fn mb_speed_test_histogram_spans_four_and_a_half_scales() {
        // m = 3, kT = 2: the histogram is over [0, 4.5 √(2/3)) in 10 bins; the
        // speeds 0.1 and 1.0 fall in bins ⌊0.1/0.367⌋ = 0 and ⌊1.0/0.367⌋ = 2,
        // 4 above.
        let speeds: Vec<f64> = [0.1, 1.0, 4.0].repeat(10);
        let t = mb_speed_test(&speeds, 3.0, 2.0, 10, false).unwrap();
        let hi = 4.5 * (2.0f64 / 3.0).sqrt();
        assert!(close(t.histogram.hi, hi), "{}", t.histogram.hi);
        assert_eq!(t.histogram.bins(), 10);
        assert_eq!((t.histogram.counts[0], t.histogram.counts[2]), (10, 10));
        assert_eq!(t.histogram.overflow, 10);
        assert_eq!(t.reference, MaxwellBoltzmann2d { mass: 3.0, kt: 2.0 });
    }
}
