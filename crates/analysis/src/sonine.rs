//! The dilute hard-disc gas beyond the first Sonine polynomial (physics.md §14.5):
//! the factors f_D, f_η, f_λ by which the Chapman–Enskog transport coefficients
//! exceed their first-Sonine values.
//!
//! Each coefficient is the first component of the solution of B a = e₁, where
//! B_pq = [φ_p, φ_q] are the collision brackets of the Sonine functions
//! φ_p = L_p^(1)(c²) c (diffusion of a tracer, p ≥ 0; conduction, p ≥ 1) and
//! φ_p = L_p^(2)(c²) (cc − c²I/2) (shear, p ≥ 0), so the factor to order M is
//! f_M = B₁₁ (B⁻¹)₁₁ and f₁ = 1. The brackets are integrals over the two
//! velocities and the impact parameter, done here by product quadrature in the
//! centre-of-mass and relative velocities; they need no normalisation, since
//! only the ratio f_M enters. The analysis uses the converged values below; the
//! tests derive them again (order 2 gives the closed forms 1 + 1/42, 1 + 1/50,
//! 1 + 1/38).

/// f_D, f_η and f_λ of the dilute hard-disc gas: the exact Chapman–Enskog
/// self-diffusion, shear viscosity and thermal conductivity over their first
/// Sonine approximations.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct SonineFactors {
    pub(super) d: f64,
    pub(super) eta: f64,
    pub(super) lambda: f64,
}

/// The converged factors, to 10⁻⁶: Sonine order 10 plus the geometric rest of
/// the series (each order adds about 0.4 times what the one before added).
pub(super) const SONINE_FACTORS: SonineFactors = SonineFactors {
    d: 1.027094,
    eta: 1.021971,
    lambda: 1.029724,
};

#[cfg(test)]
pub(super) use derivation::*;

/// The derivation of [`SONINE_FACTORS`], run by the tests.
#[cfg(test)]
mod derivation {
    use super::SonineFactors;
    use std::f64::consts::PI;

    /// The collision brackets of the three Sonine families to order `m`, each an
    /// m × m matrix in row order; the source term is the first function.
    pub(crate) struct Brackets {
        m: usize,
        pub(crate) diffusion: Vec<f64>,
        shear: Vec<f64>,
        conduction: Vec<f64>,
    }

    impl Brackets {
        /// Reduced units: velocities c = v/√(2kT/m), so the Maxwellian weight of a
        /// pair is exp(−c₁² − c₂²) = exp(−2G² − g²/2) with G the centre-of-mass and
        /// g the relative velocity; σ = 1. The relative velocity lies along x (the
        /// brackets are rotation invariant); the contact normal k = (cos θ, sin θ)
        /// with θ ∈ (−π/2, π/2) is met at the rate g·k, and the collision gives
        /// c₁' = c₁ − (g·k) k, c₂' = c₂ + (g·k) k.
        pub(crate) fn new(m: usize, nodes: usize) -> Brackets {
            let radial_g = gauss_legendre(nodes, 0.0, 6.0);
            let radial_rel = gauss_legendre(nodes, 0.0, 10.0);
            let angle_g: Vec<(f64, f64)> = (0..nodes)
                .map(|k| (2.0 * PI * k as f64 / nodes as f64, 2.0 * PI / nodes as f64))
                .collect();
            let angle_k = gauss_legendre(nodes, -PI / 2.0, PI / 2.0);
            let mut b = Brackets {
                m,
                diffusion: vec![0.0; m * m],
                shear: vec![0.0; m * m],
                conduction: vec![0.0; m * m],
            };
            let mut funcs = Funcs::new(m);
            for &(gm, wgm) in &radial_g {
                for &(psi, wpsi) in &angle_g {
                    let cm = [gm * psi.cos(), gm * psi.sin()];
                    for &(g, wg) in &radial_rel {
                        let weight_pair =
                            (-2.0 * gm * gm - 0.5 * g * g).exp() * gm * g * wgm * wpsi * wg;
                        let c1 = [cm[0] + 0.5 * g, cm[1]];
                        let c2 = [cm[0] - 0.5 * g, cm[1]];
                        for &(theta, wt) in &angle_k {
                            let (s, c) = theta.sin_cos();
                            let gk = g * c;
                            let w = weight_pair * gk * wt;
                            let c1p = [c1[0] - gk * c, c1[1] - gk * s];
                            let c2p = [c2[0] + gk * c, c2[1] + gk * s];
                            funcs.collision(c1, c2, c1p, c2p);
                            b.add(&funcs, w);
                        }
                    }
                }
            }
            b
        }

        fn add(&mut self, f: &Funcs, w: f64) {
            let m = self.m;
            for p in 0..m {
                for q in 0..=p {
                    let d = f.diffusion[p][0] * f.diffusion[q][0]
                        + f.diffusion[p][1] * f.diffusion[q][1];
                    let s = f.shear[p][0] * f.shear[q][0] + f.shear[p][1] * f.shear[q][1];
                    let c = f.conduction[p][0] * f.conduction[q][0]
                        + f.conduction[p][1] * f.conduction[q][1];
                    self.diffusion[p * m + q] += w * d;
                    self.shear[p * m + q] += w * s;
                    self.conduction[p * m + q] += w * c;
                }
            }
        }

        /// The three factors f_M = B₁₁ (B⁻¹)₁₁ to the full order.
        pub(crate) fn factors(&self) -> SonineFactors {
            self.factors_to(self.m)
        }

        /// The factors from the leading `order` × `order` blocks.
        pub(crate) fn factors_to(&self, order: usize) -> SonineFactors {
            SonineFactors {
                d: factor(&self.diffusion, self.m, order),
                eta: factor(&self.shear, self.m, order),
                lambda: factor(&self.conduction, self.m, order),
            }
        }
    }

    /// The differences the collision makes to each Sonine function: of the tracer's
    /// alone for diffusion, of both discs' sum for shear and conduction. Each is a
    /// vector of two components (the traceless tensor's two independent entries,
    /// (c_x² − c_y²)/2 and c_x c_y, for shear).
    struct Funcs {
        diffusion: Vec<[f64; 2]>,
        shear: Vec<[f64; 2]>,
        conduction: Vec<[f64; 2]>,
        poly1: Vec<f64>,
        poly2: Vec<f64>,
    }

    impl Funcs {
        fn new(m: usize) -> Funcs {
            Funcs {
                diffusion: vec![[0.0; 2]; m],
                shear: vec![[0.0; 2]; m],
                conduction: vec![[0.0; 2]; m],
                poly1: vec![0.0; m + 1],
                poly2: vec![0.0; m + 1],
            }
        }

        fn collision(&mut self, c1: [f64; 2], c2: [f64; 2], c1p: [f64; 2], c2p: [f64; 2]) {
            for v in [&mut self.diffusion, &mut self.shear, &mut self.conduction] {
                v.iter_mut().for_each(|x| *x = [0.0; 2]);
            }
            for (c, sign, tracer) in [
                (c1, 1.0, true),
                (c2, 1.0, false),
                (c1p, -1.0, true),
                (c2p, -1.0, false),
            ] {
                let x = c[0] * c[0] + c[1] * c[1];
                laguerre(1.0, x, &mut self.poly1);
                laguerre(2.0, x, &mut self.poly2);
                let tensor = [0.5 * (c[0] * c[0] - c[1] * c[1]), c[0] * c[1]];
                for p in 0..self.diffusion.len() {
                    let (l1, l1next, l2) = (self.poly1[p], self.poly1[p + 1], self.poly2[p]);
                    if tracer {
                        self.diffusion[p][0] += sign * l1 * c[0];
                        self.diffusion[p][1] += sign * l1 * c[1];
                    }
                    self.shear[p][0] += sign * l2 * tensor[0];
                    self.shear[p][1] += sign * l2 * tensor[1];
                    // Conduction starts at p = 1: L_0 c is the conserved momentum.
                    self.conduction[p][0] += sign * l1next * c[0];
                    self.conduction[p][1] += sign * l1next * c[1];
                }
            }
        }
    }

    /// L_p^(α)(x) for p = 0 .. out.len() − 1, by the three-term recurrence
    /// (p + 1) L_{p+1} = (2p + 1 + α − x) L_p − (p + α) L_{p−1}.
    pub(crate) fn laguerre(alpha: f64, x: f64, out: &mut [f64]) {
        out[0] = 1.0;
        if out.len() > 1 {
            out[1] = 1.0 + alpha - x;
        }
        for p in 1..out.len().saturating_sub(1) {
            let pf = p as f64;
            out[p + 1] =
                ((2.0 * pf + 1.0 + alpha - x) * out[p] - (pf + alpha) * out[p - 1]) / (pf + 1.0);
        }
    }

    /// B₁₁ (B⁻¹)₁₁ of the leading `order` × `order` block of the symmetric matrix
    /// `lower` (m × m, lower triangle filled), by Gaussian elimination of B a = e₁.
    pub(crate) fn factor(lower: &[f64], m: usize, order: usize) -> f64 {
        let mut a: Vec<Vec<f64>> = (0..order)
            .map(|p| (0..order).map(|q| lower[p.max(q) * m + p.min(q)]).collect())
            .collect();
        let mut rhs: Vec<f64> = (0..order).map(|p| if p == 0 { 1.0 } else { 0.0 }).collect();
        // B is positive definite: elimination without pivoting is stable.
        for k in 0..order {
            for r in k + 1..order {
                let f = a[r][k] / a[k][k];
                let pivot_row = a[k].clone();
                for (x, p) in a[r][k..].iter_mut().zip(&pivot_row[k..]) {
                    *x -= f * p;
                }
                rhs[r] -= f * rhs[k];
            }
        }
        let mut x = vec![0.0; order];
        for k in (0..order).rev() {
            let s: f64 = (k + 1..order).map(|c| a[k][c] * x[c]).sum();
            x[k] = (rhs[k] - s) / a[k][k];
        }
        lower[0] * x[0]
    }

    pub(super) use crate::quadrature::gauss_legendre;
}

#[cfg(test)]
#[path = "sonine_tests.rs"]
mod tests;
