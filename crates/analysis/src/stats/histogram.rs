//! Histograms of equal-width bins with under- and overflow counts: the speed and
//! velocity-component histograms of the Maxwell–Boltzmann tests.

use super::StatsError;

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

#[cfg(test)]
mod tests {
    use super::*;

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
    fn bins_edges_and_centres_off_the_origin() {
        // [−1.5, 2.5) in 8 bins: width 4/8 = 0.5, edges −1.5 + 0.5 k, centres
        // −1.25 + 0.5 k (all exact in binary). Bin of x: ⌊(x + 1.5)/0.5⌋:
        // −1.5 (on the lower edge) → 0, −1.4 → 0, 0.2 → ⌊3.4⌋ = 3 (twice),
        // 1.0 → 5, 2.4 → ⌊7.8⌋ = 7; −2 and −1.6 below; 2.5 (on the upper edge),
        // 3 and NaN above.
        let xs = [
            -2.0,
            -1.6,
            -1.5,
            -1.4,
            0.2,
            0.2,
            1.0,
            2.4,
            2.5,
            3.0,
            f64::NAN,
        ];
        let h = Histogram::from_values(xs, -1.5, 2.5, 8).unwrap();
        assert_eq!(h.counts, vec![2, 0, 0, 2, 0, 1, 0, 1]);
        assert_eq!((h.underflow, h.overflow, h.total()), (2, 3, 11));
        assert_eq!((h.bins(), h.width()), (8, 0.5));
        let edges: Vec<f64> = (0..=8).map(|k| -1.5 + 0.5 * k as f64).collect();
        assert_eq!(h.edges(), edges);
        let centres: Vec<f64> = (0..8).map(|k| -1.25 + 0.5 * k as f64).collect();
        assert_eq!(h.centres(), centres);
        // Density count/(total · width) = count/5.5.
        let want = [2.0, 0.0, 0.0, 2.0, 0.0, 1.0, 0.0, 1.0].map(|c| c / 5.5);
        for (d, w) in h.density().iter().zip(want) {
            assert!((d - w).abs() < 1e-15, "{:?}", h.density());
        }
        assert_eq!(h.density().len(), 8);
        // An empty histogram has density 0, not 0/0.
        let empty = Histogram::new(-1.5, 2.5, 8).unwrap();
        assert_eq!(empty.density(), vec![0.0; 8]);
    }

    #[test]
    fn a_value_just_below_the_top_is_in_the_last_bin() {
        // [−1, 1) in 2 bins: x = 1 − 2⁻⁵³ (the largest double below 1) gives
        // x + 1 = 2 − 2⁻⁵³, which rounds (to even) to 2, and 2/1 = bin 2, one past
        // the last: it must still count in bin 1, not overflow.
        let x = 1.0 - f64::EPSILON / 2.0;
        assert!(x < 1.0);
        let h = Histogram::from_values([x], -1.0, 1.0, 2).unwrap();
        assert_eq!((h.counts.clone(), h.overflow), (vec![0, 1], 0));
    }

    #[test]
    fn expected_counts_of_a_uniform_distribution_by_hand() {
        // Uniform on [−2.5, 4.5), F(x) = (x + 2.5)/7, against [−1.5, 2.5) in 8
        // bins of 0.5, with N = 10 values counted: each bin expects 10·0.5/7 =
        // 5/7, the underflow 10 F(−1.5) = 10/7, the overflow 10 (1 − F(2.5)) =
        // 10·2/7 = 20/7; together 10.
        let xs = [-2.0, -1.5, -1.4, 0.2, 0.2, 1.0, 2.4, 2.5, 3.0, 4.0];
        let h = Histogram::from_values(xs, -1.5, 2.5, 8).unwrap();
        let (inner, under, over) = h.expected_counts(|x| ((x + 2.5) / 7.0).clamp(0.0, 1.0));
        assert_eq!(inner.len(), 8);
        for e in &inner {
            assert!((e - 5.0 / 7.0).abs() < 1e-12, "{inner:?}");
        }
        assert!((under - 10.0 / 7.0).abs() < 1e-12, "{under}");
        assert!((over - 20.0 / 7.0).abs() < 1e-12, "{over}");
    }
}
