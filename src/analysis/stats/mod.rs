//! Statistics for checking a simulation against theory, independent of the engine:
//! histograms, χ² and Kolmogorov–Smirnov goodness-of-fit tests, block averaging
//! for correlated series, and the 2D Maxwell–Boltzmann distribution
//! (physics.md §5–§6).
//!
//! Special functions (regularised incomplete gamma for χ² p-values, erfc for the
//! Gaussian CDF, χ² quantiles) come from `statrs`; only the Kolmogorov series,
//! which `statrs` does not provide, is summed here.

use statrs::distribution::{ChiSquared, ContinuousCDF};
use statrs::function::erf::erfc;
use thiserror::Error;

/// Why a statistic could not be computed.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum StatsError {
    /// Too few data for the requested statistic.
    #[error("not enough data: {0}")]
    NotEnoughData(String),
    /// An argument is outside its allowed range.
    #[error("invalid argument: {0}")]
    InvalidArgument(String),
}

// ---------------------------------------------------------------------------
// Histogram
// ---------------------------------------------------------------------------

/// A histogram of equal-width bins over [lo, hi), with the counts that fall below
/// `lo` and at or above `hi` kept separately (same units as the data).
#[derive(Debug, Clone, PartialEq)]
pub struct Histogram {
    /// Lower edge of the first bin.
    pub lo: f64,
    /// Upper edge of the last bin.
    pub hi: f64,
    /// Counts per bin.
    pub counts: Vec<u64>,
    /// Values below `lo`.
    pub underflow: u64,
    /// Values at or above `hi`.
    pub overflow: u64,
}

impl Histogram {
    /// An empty histogram of `bins` equal bins over [lo, hi). Requires finite
    /// lo < hi and bins ≥ 1.
    pub fn new(lo: f64, hi: f64, bins: usize) -> Result<Self, StatsError> {
        if !(lo.is_finite() && hi.is_finite() && lo < hi) || bins == 0 {
            return Err(StatsError::InvalidArgument(format!(
                "histogram range [{lo}, {hi}) with {bins} bins (need finite lo < hi, bins ≥ 1)"
            )));
        }
        Ok(Histogram {
            lo,
            hi,
            counts: vec![0; bins],
            underflow: 0,
            overflow: 0,
        })
    }

    /// A histogram of `values` over [lo, hi) with `bins` bins.
    pub fn from_values(
        values: impl IntoIterator<Item = f64>,
        lo: f64,
        hi: f64,
        bins: usize,
    ) -> Result<Self, StatsError> {
        let mut h = Histogram::new(lo, hi, bins)?;
        for x in values {
            h.add(x);
        }
        Ok(h)
    }

    /// Count one value (NaN counts as overflow).
    pub fn add(&mut self, x: f64) {
        if x < self.lo {
            self.underflow += 1;
        } else if x >= self.hi || x.is_nan() {
            self.overflow += 1;
        } else {
            let k = ((x - self.lo) / self.width()) as usize;
            // Rounding can put x just below hi into bin `bins`.
            let k = k.min(self.counts.len() - 1);
            self.counts[k] += 1;
        }
    }

    /// Number of bins.
    pub fn bins(&self) -> usize {
        self.counts.len()
    }

    /// Bin width (units of the data).
    pub fn width(&self) -> f64 {
        (self.hi - self.lo) / self.counts.len() as f64
    }

    /// The bins + 1 bin edges.
    pub fn edges(&self) -> Vec<f64> {
        (0..=self.bins())
            .map(|k| self.lo + k as f64 * self.width())
            .collect()
    }

    /// Bin centres.
    pub fn centres(&self) -> Vec<f64> {
        (0..self.bins())
            .map(|k| self.lo + (k as f64 + 0.5) * self.width())
            .collect()
    }

    /// All values counted, including underflow and overflow.
    pub fn total(&self) -> u64 {
        self.counts.iter().sum::<u64>() + self.underflow + self.overflow
    }

    /// Estimated probability density per bin: count / (total × width)
    /// (1/units of the data), comparable with a pdf.
    pub fn density(&self) -> Vec<f64> {
        let norm = self.total() as f64 * self.width();
        self.counts
            .iter()
            .map(|&c| if norm > 0.0 { c as f64 / norm } else { 0.0 })
            .collect()
    }

    /// Expected counts per bin under a distribution with CDF `cdf`, for the same
    /// total: N [F(e_{k+1}) − F(e_k)], followed by the expected underflow N F(lo)
    /// and overflow N [1 − F(hi)].
    pub fn expected_counts(&self, cdf: impl Fn(f64) -> f64) -> (Vec<f64>, f64, f64) {
        let n = self.total() as f64;
        let f: Vec<f64> = self.edges().into_iter().map(&cdf).collect();
        let inner = f.windows(2).map(|w| n * (w[1] - w[0])).collect();
        (inner, n * f[0], n * (1.0 - f[self.bins()]))
    }
}

// ---------------------------------------------------------------------------
// χ² goodness of fit
// ---------------------------------------------------------------------------

/// Result of Pearson's χ² goodness-of-fit test.
#[derive(Debug, Clone, PartialEq)]
pub struct ChiSquareTest {
    /// χ² = Σ (O − E)² / E over the merged bins.
    pub statistic: f64,
    /// Degrees of freedom: merged bins − 1 − fitted parameters (physics.md §6).
    pub dof: usize,
    /// P(χ²_dof ≥ statistic): the probability of a fit at least this bad if the
    /// hypothesis holds (regularised upper incomplete gamma Q(dof/2, χ²/2)).
    pub p_value: f64,
    /// Number of bins after merging (each with ≥ `min_expected` expected counts).
    pub bins: usize,
}

/// Minimum expected count per bin for the χ² approximation (physics.md §6).
pub const MIN_EXPECTED: f64 = 5.0;

/// Pearson's χ² test of observed counts against expected counts (same order,
/// same total). Adjacent bins are merged, from the left, until each merged bin
/// expects at least [`MIN_EXPECTED`] counts; a short remainder at the end joins the
/// last merged bin. `fitted_params` is the number of parameters estimated from the
/// same data (1 when the temperature is measured from the sample), each costing
/// one degree of freedom: dof = merged bins − 1 − fitted_params (physics.md §6).
pub fn chi_square_test(
    observed: &[f64],
    expected: &[f64],
    fitted_params: usize,
) -> Result<ChiSquareTest, StatsError> {
    if observed.len() != expected.len() {
        return Err(StatsError::InvalidArgument(format!(
            "{} observed and {} expected bins",
            observed.len(),
            expected.len()
        )));
    }
    if expected.iter().any(|e| !e.is_finite() || *e < 0.0) {
        return Err(StatsError::InvalidArgument(
            "expected counts must be finite and ≥ 0".into(),
        ));
    }
    let mut merged: Vec<(f64, f64)> = Vec::new();
    let (mut o_acc, mut e_acc) = (0.0, 0.0);
    for (&o, &e) in observed.iter().zip(expected) {
        o_acc += o;
        e_acc += e;
        if e_acc >= MIN_EXPECTED {
            merged.push((o_acc, e_acc));
            o_acc = 0.0;
            e_acc = 0.0;
        }
    }
    if e_acc > 0.0 || o_acc > 0.0 {
        match merged.last_mut() {
            Some(last) => {
                last.0 += o_acc;
                last.1 += e_acc;
            }
            None => merged.push((o_acc, e_acc)),
        }
    }
    let bins = merged.len();
    if bins < 2 + fitted_params {
        return Err(StatsError::NotEnoughData(format!(
            "{bins} bins with ≥ {MIN_EXPECTED} expected counts leave no degree of freedom \
             ({fitted_params} fitted parameters)"
        )));
    }
    let statistic: f64 = merged
        .iter()
        .map(|&(o, e)| if e > 0.0 { (o - e) * (o - e) / e } else { 0.0 })
        .sum();
    let dof = bins - 1 - fitted_params;
    let p_value = ChiSquared::new(dof as f64)
        .map_err(|e| StatsError::InvalidArgument(e.to_string()))?
        .sf(statistic);
    Ok(ChiSquareTest {
        statistic,
        dof,
        p_value,
        bins,
    })
}

/// χ² test of a histogram against a continuous distribution given by its CDF,
/// including the underflow and overflow as bins (so the probabilities sum to 1).
pub fn chi_square_histogram(
    h: &Histogram,
    cdf: impl Fn(f64) -> f64,
    fitted_params: usize,
) -> Result<ChiSquareTest, StatsError> {
    let (inner, under, over) = h.expected_counts(cdf);
    let mut observed = vec![h.underflow as f64];
    observed.extend(h.counts.iter().map(|&c| c as f64));
    observed.push(h.overflow as f64);
    let mut expected = vec![under];
    expected.extend(inner);
    expected.push(over);
    chi_square_test(&observed, &expected, fitted_params)
}

// ---------------------------------------------------------------------------
// Kolmogorov–Smirnov
// ---------------------------------------------------------------------------

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
        // better than 1e-20.
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

// ---------------------------------------------------------------------------
// Block averaging
// ---------------------------------------------------------------------------

/// A mean with one standard error estimated from block averages.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BlockEstimate {
    /// Mean of the series (of the data used).
    pub mean: f64,
    /// One standard error of the mean.
    pub std_error: f64,
    /// Number of blocks the error is estimated from.
    pub blocks: usize,
    /// Samples per block.
    pub block_len: usize,
}

/// Mean and standard error of a correlated series by splitting it into `blocks`
/// consecutive blocks of equal length (a remainder at the end is dropped), treating
/// the block means as independent: SE = s_blocks / √blocks, with s the sample
/// standard deviation of the block means (physics.md §5). Valid when a block is
/// much longer than the correlation time. Requires ≥ 2 blocks of ≥ 1 sample.
pub fn block_average(series: &[f64], blocks: usize) -> Result<BlockEstimate, StatsError> {
    if blocks < 2 {
        return Err(StatsError::InvalidArgument(format!(
            "{blocks} blocks (need ≥ 2)"
        )));
    }
    let block_len = series.len() / blocks;
    if block_len == 0 {
        return Err(StatsError::NotEnoughData(format!(
            "{} samples for {blocks} blocks",
            series.len()
        )));
    }
    let means: Vec<f64> = series
        .chunks_exact(block_len)
        .take(blocks)
        .map(|c| c.iter().sum::<f64>() / block_len as f64)
        .collect();
    let (mean, var) = mean_and_variance(&means);
    Ok(BlockEstimate {
        mean,
        std_error: (var / blocks as f64).sqrt(),
        blocks,
        block_len,
    })
}

/// Sample mean and unbiased variance (n − 1).
fn mean_and_variance(x: &[f64]) -> (f64, f64) {
    let n = x.len() as f64;
    let mean = x.iter().sum::<f64>() / n;
    let var = if x.len() > 1 {
        x.iter().map(|v| (v - mean) * (v - mean)).sum::<f64>() / (n - 1.0)
    } else {
        0.0
    };
    (mean, var)
}

/// One level of a blocking analysis: the data averaged in pairs `level` times.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BlockingLevel {
    /// Original samples per block (2^level).
    pub block_len: usize,
    /// Number of blocks at this level.
    pub blocks: usize,
    /// Standard error of the mean if the blocks were independent.
    pub std_error: f64,
    /// Uncertainty of that standard error, SE / √(2 (blocks − 1)).
    pub std_error_error: f64,
}

/// A blocking analysis: the standard error at each level and the level chosen.
#[derive(Debug, Clone, PartialEq)]
pub struct Blocking {
    /// Mean of the series.
    pub mean: f64,
    /// One standard error of the mean, read at level `chosen`.
    pub std_error: f64,
    /// The levels, finest first.
    pub levels: Vec<BlockingLevel>,
    /// Index into `levels` of the level used.
    pub chosen: usize,
    /// False when no level passed the decorrelation test and the coarsest usable
    /// level was taken: the series is too short for its correlation time.
    pub converged: bool,
}

/// Blocking analysis (Flyvbjerg & Petersen 1989): repeatedly average neighbouring
/// pairs and estimate the standard error of the mean at each level; it rises with
/// the block length and levels off once blocks are longer than the correlation
/// time. The level is chosen automatically with Jonsson's (2018, PRE 98, 043304)
/// test: the first level j whose remaining lag-1 autocorrelations are consistent
/// with zero, M_j = Σ_{i≥j} n_i (γ_i/σ_i²)² below the 99 % quantile of χ²(d − j).
/// The mean is over the whole series; levels use its first 2^d samples for the
/// largest d with at least 4 blocks at the coarsest level. Requires ≥ 16 samples.
pub fn blocking(series: &[f64]) -> Result<Blocking, StatsError> {
    if series.len() < 16 {
        return Err(StatsError::NotEnoughData(format!(
            "{} samples for a blocking analysis (need ≥ 16)",
            series.len()
        )));
    }
    let (mean_all, _) = mean_and_variance(series);
    // d levels with n_i = 2^(d0 − i) samples, keeping ≥ 4 blocks at the last.
    let d0 = usize::BITS as usize - 1 - series.len().leading_zeros() as usize;
    let levels_n = d0 - 1;
    let mut x: Vec<f64> = series[..1 << d0].to_vec();
    let (mu, _) = mean_and_variance(&x);
    let mut levels = Vec::with_capacity(levels_n);
    let mut m_terms = Vec::with_capacity(levels_n);
    for i in 0..levels_n {
        let n = x.len();
        let nf = n as f64;
        let var0 = x.iter().map(|v| (v - mu) * (v - mu)).sum::<f64>() / nf;
        let gamma = x.windows(2).map(|w| (w[0] - mu) * (w[1] - mu)).sum::<f64>() / nf;
        let se = (var0 / (nf - 1.0)).sqrt();
        levels.push(BlockingLevel {
            block_len: 1 << i,
            blocks: n,
            std_error: se,
            std_error_error: se / (2.0 * (nf - 1.0)).sqrt(),
        });
        m_terms.push(if var0 > 0.0 {
            nf * (gamma / var0).powi(2)
        } else {
            0.0
        });
        x = x.chunks_exact(2).map(|p| 0.5 * (p[0] + p[1])).collect();
    }
    let mut chosen = levels_n - 1;
    let mut converged = false;
    let mut tail: f64 = m_terms.iter().sum();
    for (j, m_j) in m_terms.iter().enumerate() {
        let q = ChiSquared::new((levels_n - j) as f64)
            .map_err(|e| StatsError::InvalidArgument(e.to_string()))?
            .inverse_cdf(0.99);
        if tail < q {
            chosen = j;
            converged = true;
            break;
        }
        tail -= m_j;
    }
    Ok(Blocking {
        mean: mean_all,
        std_error: levels[chosen].std_error,
        levels,
        chosen,
        converged,
    })
}

// ---------------------------------------------------------------------------
// Maxwell–Boltzmann in 2D
// ---------------------------------------------------------------------------

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
    use rand_distr::{Distribution, Normal, Uniform};
    use rand_pcg::Pcg64;

    #[test]
    fn histogram_bins_values_and_normalises() {
        let h =
            Histogram::from_values([-1.0, 0.0, 0.5, 0.99, 1.0, 2.5, 3.0, f64::NAN], 0.0, 3.0, 3)
                .unwrap();
        assert_eq!(h.counts, vec![3, 1, 1]);
        assert_eq!((h.underflow, h.overflow), (1, 2));
        assert_eq!(h.total(), 8);
        assert_eq!(h.edges(), vec![0.0, 1.0, 2.0, 3.0]);
        let area: f64 = h.density().iter().sum::<f64>() * h.width();
        assert!((area - 5.0 / 8.0).abs() < 1e-12);
        assert!(Histogram::new(1.0, 1.0, 3).is_err());
        assert!(Histogram::new(0.0, 1.0, 0).is_err());
    }

    #[test]
    fn chi_square_fair_die_matches_textbook() {
        // 60 rolls of a die: 5, 8, 9, 8, 10, 20 against 10 each.
        // χ² = (25 + 4 + 1 + 4 + 0 + 100)/10 = 13.4 with 5 dof, p ≈ 0.0199.
        let o = [5.0, 8.0, 9.0, 8.0, 10.0, 20.0];
        let e = [10.0; 6];
        let t = chi_square_test(&o, &e, 0).unwrap();
        assert!((t.statistic - 13.4).abs() < 1e-12);
        assert_eq!(t.dof, 5);
        assert!((t.p_value - 0.0199).abs() < 5e-4, "p = {}", t.p_value);
        // Tabulated critical values: χ²_{0.05}(5) = 11.0705, χ²_{0.01}(10) = 23.2093.
        let p = ChiSquared::new(5.0).unwrap().sf(11.0705);
        assert!((p - 0.05).abs() < 1e-5);
        let p = ChiSquared::new(10.0).unwrap().sf(23.2093);
        assert!((p - 0.01).abs() < 1e-5);
        // A fitted parameter costs a degree of freedom.
        assert_eq!(chi_square_test(&o, &e, 1).unwrap().dof, 4);
    }

    #[test]
    fn chi_square_merges_sparse_bins() {
        // Expected 1, 2, 3, 10, 10, 2, 2: merged to [6, 10, 14] → 3 bins, dof 2.
        let e = [1.0, 2.0, 3.0, 10.0, 10.0, 2.0, 2.0];
        let o = [0.0, 3.0, 3.0, 9.0, 11.0, 1.0, 3.0];
        let t = chi_square_test(&o, &e, 0).unwrap();
        assert_eq!(t.bins, 3);
        assert_eq!(t.dof, 2);
        let want = 0.0 / 6.0 + 1.0 / 10.0 + 1.0 / 14.0;
        assert!((t.statistic - want).abs() < 1e-12);
        // Too few expected counts for any degree of freedom.
        assert!(chi_square_test(&[1.0, 2.0], &[2.0, 1.0], 0).is_err());
        assert!(chi_square_test(&[1.0], &[2.0, 1.0], 0).is_err());
    }

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

    /// AR(1) series x_t = φ x_{t−1} + ε_t with unit-variance noise, stationary
    /// start. Var(x) = 1/(1 − φ²); the standard error of the mean of n values tends
    /// to √(Var(x) (1 + φ)/(1 − φ) / n).
    fn ar1(n: usize, phi: f64, seed: u64) -> Vec<f64> {
        let mut rng = Pcg64::seed_from_u64(seed);
        let g = Normal::new(0.0, 1.0).unwrap();
        let mut x = g.sample(&mut rng) / (1.0 - phi * phi).sqrt();
        (0..n)
            .map(|_| {
                x = phi * x + g.sample(&mut rng);
                x
            })
            .collect()
    }

    fn ar1_std_error(n: usize, phi: f64) -> f64 {
        (1.0 / (1.0 - phi * phi) * (1.0 + phi) / (1.0 - phi) / n as f64).sqrt()
    }

    #[test]
    fn block_average_recovers_ar1_standard_error() {
        let (n, phi) = (1 << 15, 0.9);
        let want = ar1_std_error(n, phi);
        let reps = 60;
        let mut se_sum = 0.0;
        let mut means = Vec::new();
        for seed in 0..reps {
            let x = ar1(n, phi, seed);
            let b = block_average(&x, 32).unwrap();
            assert_eq!(b.block_len, 1024);
            se_sum += b.std_error;
            means.push(b.mean);
        }
        // The average estimated SE (estimator noise ~13 % each, /√60) agrees
        // with the analytic value (block length ≫ correlation time ~10 steps
        // biases it low by ~1 %).
        let se_avg = se_sum / reps as f64;
        assert!((se_avg / want - 1.0).abs() < 0.06, "{se_avg} vs {want}");
        // And the scatter of the means across independent series is that SE
        // (sd of the sample sd ~9 % with 60 series).
        let (_, var) = mean_and_variance(&means);
        assert!(
            (var.sqrt() / want - 1.0).abs() < 0.3,
            "{} vs {want}",
            var.sqrt()
        );
        // The naive SE (independent samples) is far too small.
        let x = ar1(n, phi, 999);
        let (_, v) = mean_and_variance(&x);
        assert!((v / n as f64).sqrt() < 0.3 * want);
        assert!(block_average(&x, 1).is_err());
        assert!(block_average(&x[..3], 4).is_err());
    }

    #[test]
    fn blocking_analysis_finds_the_plateau() {
        let (n, phi) = (1 << 16, 0.9);
        let want = ar1_std_error(n, phi);
        let mut ratios = Vec::new();
        for seed in 0..20 {
            let x = ar1(n, phi, 1000 + seed);
            let b = blocking(&x).unwrap();
            assert!(b.converged);
            // The chosen level has blocks longer than the correlation time.
            assert!(b.levels[b.chosen].block_len >= 8, "{}", b.chosen);
            // The standard error rises from level 0 to the plateau.
            assert!(b.levels[0].std_error < 0.3 * b.std_error);
            ratios.push(b.std_error / want);
        }
        let mean_ratio = ratios.iter().sum::<f64>() / ratios.len() as f64;
        assert!((mean_ratio - 1.0).abs() < 0.08, "{ratios:?}");
        // Uncorrelated data: level 0 is chosen and SE = σ/√n.
        let mut rng = Pcg64::seed_from_u64(5);
        let g = Normal::new(3.0, 2.0).unwrap();
        let x: Vec<f64> = (0..4096).map(|_| g.sample(&mut rng)).collect();
        let b = blocking(&x).unwrap();
        assert!(b.chosen <= 1, "{}", b.chosen);
        assert!((b.std_error / (2.0 / 64.0) - 1.0).abs() < 0.1);
        assert!((b.mean - 3.0).abs() < 4.0 * b.std_error);
        assert!(blocking(&x[..10]).is_err());
    }
}
