//! Pearson's χ² goodness-of-fit test, with adjacent bins merged until each expects
//! at least [`MIN_EXPECTED`] counts and one degree of freedom per fitted parameter
//! (physics.md §6). p-values from `statrs`' regularised incomplete gamma.

use statrs::distribution::{ChiSquared, ContinuousCDF};

use super::{Histogram, StatsError};

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

#[cfg(test)]
mod tests {
    use super::*;

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

    /// |a − b| ≤ 1e-12 (1 + |b|).
    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() <= 1e-12 * (1.0 + b.abs())
    }

    #[test]
    fn chi_square_with_two_degrees_of_freedom_has_p_exp_minus_half() {
        // O = 3, 12, 9 against E = 8 each: X² = (25 + 16 + 1)/8 = 5.25, dof 2, and
        // for 2 degrees of freedom the survival function is exp(−X²/2).
        let t = chi_square_test(&[3.0, 12.0, 9.0], &[8.0; 3], 0).unwrap();
        assert_eq!((t.bins, t.dof), (3, 2));
        assert!(close(t.statistic, 5.25), "{t:?}");
        assert!(close(t.p_value, (-2.625f64).exp()), "{t:?}");
        // Expected counts need not be equal: O = 7, 1, 12 against E = 4, 6, 10
        // (each ≥ 5 except the first, merged into the second: 8 against 10):
        // X² = 4/10 + 4/10 = 0.8, one bin fewer, dof 1 (2 bins − 1).
        let t = chi_square_test(&[7.0, 1.0, 12.0], &[4.0, 6.0, 10.0], 0).unwrap();
        assert_eq!((t.bins, t.dof), (2, 1));
        assert!(close(t.statistic, 0.8), "{t:?}");
    }

    #[test]
    fn a_short_remainder_joins_the_last_bin_even_if_one_side_is_zero() {
        // E = 6, 6, 2 and O = 8, 6, 0: the remainder (O 0, E 2) joins the second
        // bin, (6, 8): X² = 4/6 + 4/8 = 7/6 (without it, 4/6).
        let t = chi_square_test(&[8.0, 6.0, 0.0], &[6.0, 6.0, 2.0], 0).unwrap();
        assert_eq!((t.bins, t.dof), (2, 1));
        assert!(close(t.statistic, 7.0 / 6.0), "{t:?}");
        // Counts where nothing is expected (E = 0, O = 3) are not lost either:
        // last bin (7, 6), X² = 1/6 + 1/6 = 1/3 (without them, 1/6 + 4/6).
        let t = chi_square_test(&[5.0, 4.0, 3.0], &[6.0, 6.0, 0.0], 0).unwrap();
        assert!(close(t.statistic, 1.0 / 3.0), "{t:?}");
        // A leading bin expecting 0 is allowed and merged into the next: E = 0,
        // 6, 6 and O = 0, 5, 7 → bins (5, 6), (7, 6), X² = 2/6.
        let t = chi_square_test(&[0.0, 5.0, 7.0], &[0.0, 6.0, 6.0], 0).unwrap();
        assert_eq!(t.bins, 2);
        assert!(close(t.statistic, 1.0 / 3.0), "{t:?}");
    }

    #[test]
    fn invalid_expected_counts_and_too_few_bins_are_refused() {
        let o = [5.0, 5.0, 5.0];
        for bad in [-1.0, f64::INFINITY, f64::NAN] {
            let e = [6.0, bad, 6.0];
            assert!(
                matches!(
                    chi_square_test(&o, &e, 0),
                    Err(StatsError::InvalidArgument(_))
                ),
                "{bad}"
            );
        }
        assert!(chi_square_test(&o, &[6.0, 6.0], 0).is_err());
        // Two merged bins leave one degree of freedom, none with a fitted
        // parameter; three bins with one fitted parameter leave one again.
        let e = [6.0, 6.0, 6.0];
        let not_enough =
            |r: Result<ChiSquareTest, StatsError>| matches!(r, Err(StatsError::NotEnoughData(_)));
        assert_eq!(chi_square_test(&o[..2], &e[..2], 0).unwrap().dof, 1);
        assert!(not_enough(chi_square_test(&o[..2], &e[..2], 1)));
        assert!(not_enough(chi_square_test(&o[..1], &e[..1], 0)));
        assert_eq!(chi_square_test(&o, &e, 1).unwrap().dof, 1);
        assert!(not_enough(chi_square_test(&o, &e, 2)));
    }

    #[test]
    fn a_good_fit_of_many_counts_keeps_its_precision() {
        // O = 10⁸ ± 3 against E = 10⁸ (equal totals): X² = 2·9/10⁸ = 1.8e-7, each
        // term exact to rounding. The algebraically equal (for equal totals)
        // Σ (O + E)(O − E)/E = Σ O²/E − N would lose it to cancellation (terms
        // ±6.0000001 summing to 1.8e-7).
        let t = chi_square_test(&[1e8 + 3.0, 1e8 - 3.0], &[1e8, 1e8], 0).unwrap();
        assert!((t.statistic / 1.8e-7 - 1.0).abs() < 1e-12, "{t:?}");
    }
}
