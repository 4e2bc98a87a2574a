//! The first time a polynomial of degree ≤ 4 comes down through zero, isolated
//! exactly (physics.md §15, resting discs).
//!
//! The contact condition of a disc resting on the floor and a falling one,
//! |Δr + Δv t + ½ a t² ŷ|² = σ², is a quartic p(t) = Σ c_k t^k in the time t
//! (relative acceleration a = ±g). Its roots are isolated without a formula and
//! without a tolerance: the real roots of p' (found the same way, down to a linear
//! polynomial) cut [0, B] into pieces on which p is monotone, B the Fujiwara bound
//! of the roots, and on each piece where p changes sign the root is bisected over
//! the floating-point numbers themselves (the bits of non-negative doubles are
//! ordered as their values) until its bracket holds two adjacent doubles: at most
//! 64 halvings, to the rounding of p. Rules as for the contact time (2.3): the
//! answer is never negative and never NaN; a pair overlapping by rounding (p(0) ≤ 0)
//! that approaches (p'(0) < 0) meets now.

/// A polynomial Σ c_k t^k of degree ≤ 4, its coefficients `c` (c[k] of t^k).
#[derive(Debug, Clone, Copy, PartialEq)]
struct Poly {
    c: [f64; 5],
    degree: usize,
}

impl Poly {
    fn new(c: [f64; 5]) -> Poly {
        let degree = (0..5).rev().find(|&k| c[k] != 0.0).unwrap_or(0);
        Poly { c, degree }
    }

    /// p(t) by Horner's rule.
    fn at(&self, t: f64) -> f64 {
        self.c[..=self.degree]
            .iter()
            .rev()
            .fold(0.0, |acc, &c| acc * t + c)
    }

    /// The sign of p(t) as −1, 0 or 1; where p(t) overflows (t far beyond the
    /// roots), the leading term's.
    fn sign(&self, t: f64) -> i32 {
        let v = self.at(t);
        let v = if v.is_finite() {
            v
        } else {
            self.c[self.degree]
        };
        (v > 0.0) as i32 - (v < 0.0) as i32
    }

    fn derivative(&self) -> Poly {
        let mut d = [0.0; 5];
        for k in 1..=self.degree {
            d[k - 1] = k as f64 * self.c[k];
        }
        Poly::new(d)
    }

    /// Fujiwara's bound on the magnitude of the roots: 2 max_k |c_{n−k}/c_n|^{1/k}
    /// (the last term halved); `f64::MAX` when it overflows.
    fn root_bound(&self) -> f64 {
        let n = self.degree;
        let lead = self.c[n];
        let mut b: f64 = 0.0;
        for k in 1..=n {
            let mut r = (self.c[n - k] / lead).abs();
            if k == n {
                r *= 0.5;
            }
            b = b.max(r.powf(1.0 / k as f64));
        }
        let b = 2.0 * b;
        if b.is_finite() {
            b
        } else {
            f64::MAX
        }
    }

    /// The points in (lo, hi) where p changes sign, increasing, into `out`
    /// (returns how many; at most the degree). Both ends ≥ 0.
    fn sign_changes(&self, lo: f64, hi: f64, out: &mut [f64; 4]) -> usize {
        if self.degree == 0 {
            return 0;
        }
        // p is monotone between consecutive turning points, the sign changes of p'.
        let mut turns = [0.0; 4];
        let m = self.derivative().sign_changes(lo, hi, &mut turns);
        let mut count = 0;
        let mut left = lo;
        // The pieces' right ends: the turning points, then hi.
        let mut ends = [hi; 5];
        ends[..m].copy_from_slice(&turns[..m]);
        for (k, &right) in ends[..=m].iter().enumerate() {
            let (sl, sr) = (self.sign(left), self.sign(right));
            if sl != 0 && sr != 0 && sl != sr {
                out[count] = bisect(|t| self.sign(t), left, right, sl);
                count += 1;
            } else if sr == 0 && right < hi && sl != 0 {
                // p vanishes exactly at a turning point: a sign change there only if
                // p has the other sign beyond it, which the next piece shows.
                if self.sign(ends[k + 1]) == -sl {
                    out[count] = right;
                    count += 1;
                }
            }
            left = right;
        }
        count
    }
}

/// The first double in (lo, hi] at which `sign` no longer equals `from`, for a
/// `sign` that changes once on [lo, hi] (monotone) with `sign(lo) = from`:
/// bisection over the bits of the doubles, ≤ 64 halvings.
fn bisect(sign: impl Fn(f64) -> i32, lo: f64, hi: f64, from: i32) -> f64 {
    let (mut a, mut b) = (lo.to_bits(), hi.to_bits());
    while b - a > 1 {
        let mid = a + (b - a) / 2;
        if sign(f64::from_bits(mid)) == from {
            a = mid;
        } else {
            b = mid;
        }
    }
    f64::from_bits(b)
}

/// The earliest time t ≥ 0 at which p(t) = `c[0]` + `c[1]` t + … + `c[4]` t⁴
/// comes down to 0 (p > 0 just before, ≤ 0 at t: the first such double), or the
/// time at which p starts to decrease while it is ≤ 0 (0 when p(0) ≤ 0 and p
/// decreases from 0 on, e.g. p'(0) = `c[1]` < 0); +∞ when neither happens (and for
/// any NaN or infinite coefficient). A tangency (a double root) counts.
///
/// For a contact condition p(t) = |Δr(t)|² − σ² this is the first touching while
/// approaching: a pair touching now and separating (p(0) ≈ 0, p'(0) > 0) is not
/// met again at once, but when it comes back; a pair that rounding left
/// overlapping meets as soon as it approaches.
pub fn first_descent(c: [f64; 5]) -> f64 {
    if c.iter().any(|x| !x.is_finite()) {
        return f64::INFINITY;
    }
    let p = Poly::new(c);
    if p.degree == 0 {
        // A constant: the pair neither approaches nor recedes.
        return f64::INFINITY;
    }
    // Doubled against the rounding of the bound itself.
    let hi = (2.0 * p.root_bound()).clamp(f64::MIN_POSITIVE, f64::MAX);
    let dp = p.derivative();
    let mut turns = [0.0; 4];
    let m = dp.sign_changes(0.0, hi, &mut turns);
    let mut left = 0.0;
    for right in turns[..m].iter().copied().chain([hi]) {
        if p.sign(left) > 0 {
            if p.sign(right) <= 0 {
                return bisect(|t| p.sign(t), left, right, 1);
            }
        } else {
            // Touching or overlapping (by rounding) at `left`: met there if p
            // decreases on this piece (p' keeps one sign inside it).
            let inside = f64::from_bits(left.to_bits() / 2 + right.to_bits() / 2);
            if dp.sign(inside) < 0 {
                return left;
            }
        }
        left = right;
    }
    f64::INFINITY
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Whether `t` is the simple root `root` of the polynomial `c` to the rounding
    /// of p: within Horner's error bound 2n ε Σ|c_k| t^k (n = 4) divided by |p'|
    /// there, plus an ulp.
    fn near(c: [f64; 5], t: f64, root: f64) -> bool {
        let p = Poly::new(c);
        let size: f64 = (0..5).map(|k| c[k].abs() * root.abs().powi(k as i32)).sum();
        let slope = p.derivative().at(root).abs();
        (t - root).abs() <= 8.0 * f64::EPSILON * size / slope + f64::EPSILON * root.abs()
    }

    /// (t − 1)(t − 2)(t − 3)(t − 4) = t⁴ − 10t³ + 35t² − 50t + 24 comes down through
    /// 0 at 1 (and at 3); all four roots are found to the rounding of p.
    #[test]
    fn the_first_descent_of_a_quartic_with_four_known_roots() {
        let c = [24.0, -50.0, 35.0, -10.0, 1.0];
        assert!(near(c, first_descent(c), 1.0), "{}", first_descent(c));
        let mut r = [0.0; 4];
        let n = Poly::new(c).sign_changes(0.0, 100.0, &mut r);
        assert_eq!(n, 4);
        for (t, root) in r.iter().zip([1.0, 2.0, 3.0, 4.0]) {
            assert!(near(c, *t, root), "{t} vs {root}");
        }
        // −p: rises through 1, comes down through 2.
        assert!(near(c, first_descent(c.map(|x| -x)), 2.0));
        // Overlapping by rounding and approaching: now; receding: when it returns.
        assert_eq!(first_descent([-1e-16, -1.0, 1.0, 0.0, 0.0]), 0.0);
        assert_eq!(first_descent([-1e-16, 1.0, -1.0, 0.0, 0.0]), 1.0);
    }

    /// Roots that are not doubles: (t² − 2)(t² − 3) has √2 and √3 > 0; the first
    /// descent is the double next to √2, within one ulp.
    #[test]
    fn an_irrational_root_is_found_to_the_last_bit() {
        let c = [6.0, 0.0, -5.0, 0.0, 1.0];
        let t = first_descent(c);
        let s = 2f64.sqrt();
        assert!(near(c, t, s), "{t} vs {s}");
        // A touching pair separating (p(0) = 0, p'(0) > 0) that comes back: the
        // drop of a ball (height t − t²/2 above contact): p = t(2 − t)·… > 0 on
        // (0, 2), back at 2.
        let back = [0.0, 2.0, -1.0, 0.0, 0.0];
        assert_eq!(first_descent(back), 2.0);
    }

    /// A double root (tangency, a grazing contact) counts as a meeting; a near miss
    /// does not; a quartic with no real root never meets; NaN never escapes.
    #[test]
    fn grazing_missing_and_bad_input() {
        // (t − 1)²(t + 1)(t + 2) = t⁴ + t³ − 3t² − t + 2: touches 0 at 1. Near a
        // double root p ≈ 6 (t − 1)² is below its rounding (≈ 10⁻¹⁵) within
        // 1.3·10⁻⁸ of it: that is where the touching can be put.
        let t = first_descent([2.0, -1.0, -3.0, 1.0, 1.0]);
        assert!((t - 1.0).abs() < 2e-8, "{t}");
        // Touching now with no normal velocity, pressed together (p''(0) < 0): now.
        assert_eq!(first_descent([0.0, 0.0, -1.0, 0.0, 0.25]), 0.0);
        // (t − 1)² + 10⁻⁶ (times t² + 1): never 0.
        assert_eq!(
            first_descent([1.000001, -2.0, 2.000001, -2.0, 1.0]),
            f64::INFINITY
        );
        assert_eq!(first_descent([1.0, 0.0, 1.0, 0.0, 1.0]), f64::INFINITY);
        assert_eq!(first_descent([f64::NAN, 0.0, 1.0, 0.0, 1.0]), f64::INFINITY);
        // Degree 1 and 0: 3 − t comes down at 3; a positive constant never.
        assert_eq!(first_descent([3.0, -1.0, 0.0, 0.0, 0.0]), 3.0);
        assert_eq!(first_descent([3.0, 0.0, 0.0, 0.0, 0.0]), f64::INFINITY);
    }

    /// Roots spread over many decades: (t − 10⁻⁹)(t − 10⁶)(t² + 1), and a leading
    /// coefficient of 10⁻³⁰⁰ (a field that barely acts).
    #[test]
    fn roots_far_apart_and_tiny_leading_terms() {
        let (a, b) = (1e-9, 1e6);
        // (t² − (a+b) t + ab)(t² + 1)
        let c = [a * b, -(a + b), 1.0 + a * b, -(a + b), 1.0];
        let t = first_descent(c);
        assert!(near(c, t, a), "{t}");
        let c = [1.0, -1.0, 0.0, 0.0, 1e-300];
        assert!(near(c, first_descent(c), 1.0), "{}", first_descent(c));
    }
}
