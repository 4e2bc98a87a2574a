//! Gauss–Legendre quadrature: the n nodes and weights that integrate polynomials
//! of degree up to 2n − 1 exactly on [a, b], the nodes found by Newton's method
//! on the Legendre polynomial P_n (three-term recurrence). Used for the
//! collision integrals of the Sonine expansions (physics.md §8, §14.5).

use std::f64::consts::PI;

/// Gauss–Legendre nodes and weights on [a, b] (Newton's method on P_n).
pub(super) fn gauss_legendre(n: usize, a: f64, b: f64) -> Vec<(f64, f64)> {
    let (mid, half) = (0.5 * (a + b), 0.5 * (b - a));
    (0..n)
        .map(|i| {
            let mut x = (PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
            let mut dp = 0.0;
            for _ in 0..100 {
                let (mut p0, mut p1) = (1.0, x);
                for k in 2..=n {
                    let kf = k as f64;
                    let p2 = ((2.0 * kf - 1.0) * x * p1 - (kf - 1.0) * p0) / kf;
                    p0 = p1;
                    p1 = p2;
                }
                dp = n as f64 * (x * p1 - p0) / (x * x - 1.0);
                let step = p1 / dp;
                x -= step;
                if step.abs() < 1e-16 {
                    break;
                }
            }
            (mid + half * x, half * 2.0 / ((1.0 - x * x) * dp * dp))
        })
        .collect()
}
