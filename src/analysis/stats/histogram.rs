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
}
