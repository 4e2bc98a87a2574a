//! a2 of the homogeneous cooling state of hard discs with normal restitution e
//! in the second Sonine approximation (physics.md §8, (8.8)). With c =
//! v/√(2kT/m) and f = φ(c)[1 + a2 S2(c²) + a3 S3(c²)], the cooling state gives
//! for every moment
//!     μ_p = (p/d) μ2 ⟨c^p⟩,   μ_p = −∫ c^p I(f, f) dc
//! (Brilliantov & Pöschel, PRE 61, 5573 (2000); EPL 74, 424 (2006)), linear in
//! a2 and a3: p = 4 with a3 = 0 is van Noije & Ernst's first approximation
//! (recovered to 10⁻¹² in the tests), p = 4 and 6 together the second. The
//! collisional moments are done by product quadrature (Gauss–Legendre in the
//! speeds and the normal's angle, trapezoid in the centre-of-mass direction);
//! g(σ) and every constant factor cancel.

use std::f64::consts::PI;

use super::quadrature::gauss_legendre;

/// Gauss–Legendre nodes per dimension: a2 converged to 10⁻¹⁰ (the tests compare
/// with twice as many).
const NODES: usize = 32;

/// a2 of the first Sonine approximation (linear in a2; van Noije & Ernst's
/// formula) and of the second (a2 and a3, linear in both), at normal
/// restitution `e`, by quadrature.
pub(super) fn a2_sonine(e: f64) -> [f64; 2] {
    let m = Moments::new(e, NODES);
    [m.first_order(), m.second_order()[0]]
}

/// The collisional moments μ_p = μ_p⁰ + μ_p² a2 + μ_p³ a3 (p = 2, 4, 6), linear
/// in the Sonine coefficients, up to a common factor.
pub(super) struct Moments {
    /// mu[i][k]: p = 2(i + 1); k = 0 (Maxwellian), 1 (a2), 2 (a3).
    mu: [[f64; 3]; 3],
}

/// ⟨c^p⟩ = c[i][0] + c[i][1] a2 + c[i][2] a3 for p = 2(i + 1) in 2D: with
/// x = c² exponential under φ, ⟨x^n⟩ = n!, ⟨x^n S_k(x)⟩ from the polynomials.
const C_MOMENTS: [[f64; 3]; 3] = [[1.0, 0.0, 0.0], [2.0, 2.0, 0.0], [6.0, 18.0, -6.0]];

/// The dimension d.
const D: f64 = 2.0;

impl Moments {
    /// By quadrature with `nodes` points per dimension.
    pub(super) fn new(e: f64, nodes: usize) -> Moments {
        let radial_g = gauss_legendre(nodes, 0.0, 6.0);
        let radial_rel = gauss_legendre(nodes, 0.0, 10.0);
        let angle_k = gauss_legendre(nodes, -PI / 2.0, PI / 2.0);
        let psi: Vec<f64> = (0..nodes)
            .map(|k| 2.0 * PI * k as f64 / nodes as f64)
            .collect();
        let mut mu = [[0.0; 3]; 3];
        let h = 0.5 * (1.0 + e);
        for &(gm, wgm) in &radial_g {
            for &p in &psi {
                let cm = [gm * p.cos(), gm * p.sin()];
                for &(g, wg) in &radial_rel {
                    // φ(c1)φ(c2) ∝ exp(−2G² − g²/2); the measure G dG dψ g dg.
                    let w_pair = (-2.0 * gm * gm - 0.5 * g * g).exp() * gm * g * wgm * wg;
                    let c1 = [cm[0] + 0.5 * g, cm[1]];
                    let c2 = [cm[0] - 0.5 * g, cm[1]];
                    let (x1, x2) = (sq(c1), sq(c2));
                    let weights = [1.0, s2(x1) + s2(x2), s3(x1) + s3(x2)];
                    for &(theta, wt) in &angle_k {
                        let (s, c) = theta.sin_cos();
                        let gk = g * c;
                        // c1' = c1 − ((1 + e)/2)(g·k) k, c2' = c2 + ((1 + e)/2)(g·k) k.
                        let d = [h * gk * c, h * gk * s];
                        let y1 = sq([c1[0] - d[0], c1[1] - d[1]]);
                        let y2 = sq([c2[0] + d[0], c2[1] + d[1]]);
                        let w = w_pair * gk * wt;
                        // μ_p = −∫ Δ(c^p): the loss of c^p per collision.
                        let mut before = [x1 + x2, 0.0, 0.0];
                        let mut after = [y1 + y2, 0.0, 0.0];
                        before[1] = x1 * x1 + x2 * x2;
                        after[1] = y1 * y1 + y2 * y2;
                        before[2] = x1.powi(3) + x2.powi(3);
                        after[2] = y1.powi(3) + y2.powi(3);
                        for i in 0..3 {
                            let loss = w * (before[i] - after[i]);
                            for k in 0..3 {
                                mu[i][k] += loss * weights[k];
                            }
                        }
                    }
                }
            }
        }
        Moments { mu }
    }

    /// Equation p = 2(i + 1), linearised: μ_p − (p/d) μ2 ⟨c^p⟩ = r + u a2 + v a3 = 0.
    fn equation(&self, i: usize) -> [f64; 3] {
        let p = 2.0 * (i + 1) as f64;
        let (m, c) = (&self.mu, &C_MOMENTS);
        let q = p / D;
        [
            m[i][0] - q * m[0][0] * c[i][0],
            m[i][1] - q * (m[0][0] * c[i][1] + m[0][1] * c[i][0]),
            m[i][2] - q * (m[0][0] * c[i][2] + m[0][2] * c[i][0]),
        ]
    }

    /// a2 from p = 4 with a3 = 0.
    pub(super) fn first_order(&self) -> f64 {
        let [r, u, _] = self.equation(1);
        -r / u
    }

    /// (a2, a3) from p = 4 and p = 6.
    pub(super) fn second_order(&self) -> [f64; 2] {
        let [r4, u4, v4] = self.equation(1);
        let [r6, u6, v6] = self.equation(2);
        let det = u4 * v6 - v4 * u6;
        [(-r4 * v6 + v4 * r6) / det, (-u4 * r6 + r4 * u6) / det]
    }
}

fn sq(c: [f64; 2]) -> f64 {
    c[0] * c[0] + c[1] * c[1]
}

/// S2(x) = L₂⁽⁰⁾(x) = (x² − 4x + 2)/2.
fn s2(x: f64) -> f64 {
    0.5 * (x * x - 4.0 * x + 2.0)
}

/// S3(x) = L₃⁽⁰⁾(x) = (−x³ + 9x² − 18x + 6)/6.
fn s3(x: f64) -> f64 {
    (-x * x * x + 9.0 * x * x - 18.0 * x + 6.0) / 6.0
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::inelastic::a2_theory;

    /// ⟨c^p⟩ under φ(1 + a2 S2 + a3 S3) with x = c² ~ Exp(1): ⟨x^n⟩ = n!, so
    /// ⟨x² S2⟩ = (24 − 4·6 + 2·2)/2 = 2, ⟨x³ S2⟩ = (120 − 96 + 12)/2 = 18,
    /// ⟨x³ S3⟩ = (−720 + 9·120 − 18·24 + 6·6)/6 = −6, ⟨x² S3⟩ = (−120 + 216 − 108 + 12)/6 = 0.
    #[test]
    fn the_velocity_moments_follow_from_the_exponential_moments() {
        let fact = |n: i32| (1..=n).product::<i32>() as f64;
        let avg = |n: i32, k: usize| -> f64 {
            // ⟨x^n S_k(x)⟩ from the polynomial coefficients.
            let coeffs: &[f64] = match k {
                0 => &[1.0],
                1 => &[1.0, -2.0, 0.5],
                _ => &[1.0, -3.0, 1.5, -1.0 / 6.0],
            };
            coeffs
                .iter()
                .enumerate()
                .map(|(j, a)| a * fact(n + j as i32))
                .sum()
        };
        for (i, row) in C_MOMENTS.iter().enumerate() {
            for (k, c) in row.iter().enumerate() {
                let want = avg(i as i32 + 1, k);
                assert!((c - want).abs() < 1e-12, "{i} {k}: {want}");
            }
        }
        // The polynomials are the ones coded.
        for x in [0.3, 1.7, 4.0] {
            assert!((s2(x) - (1.0 - 2.0 * x + 0.5 * x * x)).abs() < 1e-14);
            assert!((s3(x) - (1.0 - 3.0 * x + 1.5 * x * x - x * x * x / 6.0)).abs() < 1e-13);
        }
    }

    /// The first Sonine approximation by quadrature is van Noije & Ernst's closed
    /// form at d = 2; the elastic gas has a2 = a3 = 0; twice the nodes change
    /// nothing.
    #[test]
    fn the_first_order_is_van_noije_and_ernst() {
        for e in [0.2, 0.5, 0.8, 0.9, 0.95] {
            let m = Moments::new(e, NODES);
            let got = m.first_order();
            assert!((got - a2_theory(e)).abs() < 1e-12, "e = {e}: {got}");
            let fine = Moments::new(e, 2 * NODES);
            let (a, b) = (m.second_order(), fine.second_order());
            assert!((a[0] - b[0]).abs() < 1e-10 && (a[1] - b[1]).abs() < 1e-10);
        }
        for e in [0.5, 0.8, 0.9] {
            let [a2, a3] = Moments::new(e, NODES).second_order();
            eprintln!("e = {e}: first {} second a2 {a2} a3 {a3}", a2_theory(e));
        }
        let elastic = Moments::new(1.0, NODES).second_order();
        assert!(elastic[0].abs() < 1e-12 && elastic[1].abs() < 1e-12);
    }
}
