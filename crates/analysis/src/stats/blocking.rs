//! Means of correlated series with honest standard errors: block averages, and the
//! blocking analysis (Flyvbjerg–Petersen) that doubles the block length until the
//! error estimate reaches a plateau.

use statrs::distribution::{ChiSquared, ContinuousCDF};

use super::StatsError;

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
    /// level was taken. For finite data this cannot happen: the coarsest level
    /// has 4 blocks and |γ| ≤ σ², so its term M ≤ 4 < χ²₀.₉₉(1) = 6.63 always
    /// passes; only NaN (overflowing squares) leaves it false. A series too short
    /// for its correlation time shows instead as a `chosen` level with few blocks
    /// (and a large `std_error_error`).
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

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;
    use rand_distr::{Distribution, Normal};
    use rand_pcg::Pcg64;

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

    /// |a − b| ≤ 1e-12 (1 + |b|).
    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() <= 1e-12 * (1.0 + b.abs())
    }

    #[test]
    fn block_average_of_a_short_series_by_hand() {
        // 7 samples in 3 blocks: block length ⌊7/3⌋ = 2, the last sample (100)
        // dropped. Block means 2, 4, 9: mean 5, deviations −3, −1, 4, unbiased
        // variance (9 + 1 + 16)/2 = 13, SE = √(13/3).
        let x = [1.0, 3.0, 2.0, 6.0, 7.0, 11.0, 100.0];
        let b = block_average(&x, 3).unwrap();
        assert_eq!((b.blocks, b.block_len), (3, 2));
        assert!(close(b.mean, 5.0), "{b:?}");
        assert!(close(b.std_error, (13.0f64 / 3.0).sqrt()), "{b:?}");
        // Two blocks (the fewest allowed) of 3: means 2 and 8, mean 5, variance
        // (9 + 9)/1 = 18, SE = √(18/2) = 3.
        let b = block_average(&x, 2).unwrap();
        assert_eq!((b.blocks, b.block_len), (2, 3));
        assert!(close(b.mean, 5.0) && close(b.std_error, 3.0), "{b:?}");
        // Exactly one sample per block is enough: 7 blocks of 1.
        assert_eq!(block_average(&x, 7).unwrap().block_len, 1);
        assert!(block_average(&x, 8).is_err());
        // Shifting the data by c shifts the mean and leaves the error unchanged.
        // With c = 2⁵¹ every sum, block mean and deviation above is still an
        // exact double, so the SE must be √(13/3) to rounding, not Σv² − n·mean²
        // with its cancellation (products ~2⁵³, spaced by 2).
        let c = 2f64.powi(51);
        let shifted: Vec<f64> = x.iter().map(|v| v + c).collect();
        let b = block_average(&shifted, 3).unwrap();
        assert_eq!(b.mean, c + 5.0);
        assert!(close(b.std_error, (13.0f64 / 3.0).sqrt()), "{b:?}");
    }

    /// 99 % quantiles of χ²(k), k = 1…4 (standard tables).
    const CHI2_99: [f64; 4] = [6.635, 9.210, 11.345, 13.277];

    #[test]
    fn blocking_a_ramp_matches_its_closed_form() {
        // x_k = 2.5 + 0.75 k, k = 0…36: the levels use the first 2⁵ = 32 samples
        // (4 levels, n = 32, 16, 8, 4 blocks); the mean is over all 37, 2.5 +
        // 0.75·18 = 16. The block means of level i are again a ramp, of step
        // s = 0.75·2^i and n points, so (with the population variance and lag-1
        // autocovariance of a centred ramp z_j = s (j − (n−1)/2):
        // Σ z² = s² n (n² − 1)/12, Σ z_j z_{j+1} = s² (n² − 1)(n − 3)/12)
        //   σ² = s² (n² − 1)/12, SE = √(σ²/(n − 1)) = s √((n + 1)/12),
        //   γ/σ² = (n − 3)/n, M-term n (γ/σ²)² = (n − 3)²/n.
        let x: Vec<f64> = (0..37).map(|k| 2.5 + 0.75 * k as f64).collect();
        let b = blocking(&x).unwrap();
        assert!(close(b.mean, 16.0), "{}", b.mean);
        assert_eq!(b.levels.len(), 4);
        let mut m = Vec::new();
        for (i, level) in b.levels.iter().enumerate() {
            let n = 32 >> i;
            let (nf, s) = (n as f64, 0.75 * (1 << i) as f64);
            assert_eq!((level.block_len, level.blocks), (1 << i, n), "{level:?}");
            let se = s * ((nf + 1.0) / 12.0).sqrt();
            assert!(close(level.std_error, se), "{i}: {level:?} vs {se}");
            let see = se / (2.0 * (nf - 1.0)).sqrt();
            assert!(close(level.std_error_error, see), "{i}: {level:?}");
            m.push((nf - 3.0).powi(2) / nf);
        }
        // M-terms 26.28, 10.56, 3.125, 0.25: M_0 = 40.2 ≥ 13.28 (χ²₄), M_1 =
        // 13.94 ≥ 11.35 (χ²₃), M_2 = 3.375 < 9.21 (χ²₂): level 2 is chosen.
        let tails: Vec<f64> = (0..4).map(|j| m[j..].iter().sum()).collect();
        assert!(tails[0] >= CHI2_99[3] && tails[1] >= CHI2_99[2] && tails[2] < CHI2_99[1]);
        assert_eq!(b.chosen, 2);
        assert!(b.converged);
        assert!(close(b.std_error, 3.0 * 0.75f64.sqrt()), "{}", b.std_error);
    }

    #[test]
    fn blocking_anticorrelated_pairs_by_hand() {
        // Pairs (p + 4, p − 4) around p = 1, 3, 2, 6, 4, 0, 5, 3 (16 samples, the
        // fewest allowed; 3 levels). μ = 3, δp = p − 3 = −2, 0, −1, 3, 1, −3, 2, 0
        // (Σδp² = 28, Σδp_k δp_{k+1} = −9).
        // Level 0: σ² = (2·28 + 16·16)/16 = 19.5; Σ lag-1 products = within pairs
        //   Σ(δp² − 16) = −100, across pairs −9 + 4(δp_0 − δp_7) − 7·16 = −129,
        //   γ = −229/16; SE = √(19.5/15) = √1.3.
        // Level 1 (the p): σ² = 28/8 = 3.5, γ = −9/8, SE = √(3.5/7) = √0.5.
        // Level 2: 2, 4, 2, 4: σ² = 1, γ = −3/4, SE = √(1/3).
        let p = [1.0, 3.0, 2.0, 6.0, 4.0, 0.0, 5.0, 3.0];
        let x: Vec<f64> = p.iter().flat_map(|&q| [q + 4.0, q - 4.0]).collect();
        let b = blocking(&x).unwrap();
        assert!(close(b.mean, 3.0));
        let want_se = [1.3f64.sqrt(), 0.5f64.sqrt(), (1.0f64 / 3.0).sqrt()];
        assert_eq!(b.levels.len(), 3);
        for (level, se) in b.levels.iter().zip(want_se) {
            assert!(close(level.std_error, se), "{level:?} vs {se}");
        }
        // M-terms 16 (229/16/19.5)² = 8.62, 8 (1.125/3.5)² = 0.83, 4 (3/4)² =
        // 2.25: M_0 = 11.70 ≥ 11.345 (χ²₃) but M_1 = 3.08 < 9.21 (χ²₂): level 1.
        let m = [
            16.0 * (229.0f64 / 16.0 / 19.5).powi(2),
            8.0 * (1.125f64 / 3.5).powi(2),
            2.25,
        ];
        assert!(m.iter().sum::<f64>() >= CHI2_99[2] && m[1] + m[2] < CHI2_99[1]);
        assert_eq!(b.chosen, 1);
        assert!(b.converged);
        assert!(close(b.std_error, 0.5f64.sqrt()));
        assert!(blocking(&x[..15]).is_err());
    }

    #[test]
    fn a_constant_series_has_no_error_and_level_0() {
        // Every variance is 0: no correlation to test (the M-terms are 0, not
        // 0/0), so level 0 passes and the standard error is 0.
        let b = blocking(&[2.5; 20]).unwrap();
        assert_eq!(b.mean, 2.5);
        assert_eq!((b.chosen, b.converged, b.std_error), (0, true, 0.0));
        assert!(b.levels.iter().all(|l| l.std_error == 0.0));
    }

    #[test]
    fn without_a_passing_level_the_coarsest_is_taken_unconverged() {
        // The last level (4 blocks) always passes for finite data: M = 4 (γ/σ²)²
        // ≤ 4 < 6.635 by Cauchy–Schwarz. Only NaN M-terms fail every level: here
        // the squares of deviations ~1e201 overflow, σ² = ∞ and γ/σ² = ∞/∞ at
        // every level. Then the coarsest level (index 2 of 3) is reported.
        let x: Vec<f64> = (0..16).map(|k| 1e200 * k as f64).collect();
        let b = blocking(&x).unwrap();
        assert_eq!(b.levels.len(), 3);
        assert_eq!((b.chosen, b.converged), (2, false));
        assert_eq!(b.std_error, b.levels[2].std_error);
    }
}
