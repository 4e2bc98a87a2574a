use super::*;
use std::f64::consts::PI;

/// n-point Gauss–Legendre integrates polynomials up to degree 2n − 1 exactly:
/// ∫₋₁³ x^k dx = (3^{k+1} − (−1)^{k+1})/(k + 1).
#[test]
fn gauss_legendre_is_exact_for_polynomials() {
    for n in [1, 2, 5, 12] {
        let q = gauss_legendre(n, -1.0, 3.0);
        for k in 0..2 * n {
            let sum: f64 = q.iter().map(|&(x, w)| w * x.powi(k as i32)).sum();
            let exact = (3f64.powi(k as i32 + 1) - (-1f64).powi(k as i32 + 1)) / (k as f64 + 1.0);
            assert!(
                (sum - exact).abs() < 1e-12 * exact.abs().max(1.0),
                "n {n} k {k}"
            );
        }
    }
}

/// L₂^(α)(x) = x²/2 − (α + 2)x + (α + 1)(α + 2)/2, and the L_p^(α) are orthogonal
/// with weight x^α e^{−x} on [0, ∞).
#[test]
fn laguerre_polynomials() {
    let mut l = [0.0; 6];
    for (alpha, x) in [(1.0, 0.7), (2.0, 3.1)] {
        laguerre(alpha, x, &mut l);
        assert!(
            (l[2] - (x * x / 2.0 - (alpha + 2.0) * x + (alpha + 1.0) * (alpha + 2.0) / 2.0)).abs()
                < 1e-13
        );
    }
    let q = gauss_legendre(120, 0.0, 80.0);
    for alpha in [1.0, 2.0] {
        let mut gram = [[0.0; 6]; 6];
        for &(x, w) in &q {
            laguerre(alpha, x, &mut l);
            let weight = w * x.powf(alpha) * (-x).exp();
            for (row, lp) in gram.iter_mut().zip(l) {
                for (g, lr) in row.iter_mut().zip(l) {
                    *g += weight * lp * lr;
                }
            }
        }
        for (p, row) in gram.iter().enumerate() {
            for (r, g) in row.iter().enumerate() {
                if p != r {
                    assert!(g.abs() < 1e-9 * row[p], "α {alpha}: {p},{r}");
                }
            }
        }
    }
}

/// The first diffusion bracket is the tracer's momentum relaxation rate: with the
/// normalised Maxwellian e^{−c²}/π per disc, ν = ½ ∫∫ f₁f₂ (rate) |Δc₁|² / ⟨c²⟩
/// with ⟨c²⟩ = 1, which in the first Sonine approximation is the collision rate
/// ω₀ = 2√π nσ √(kT/m) = √(2π) in these units (D₀ = (kT/m)/ω₀, physics.md §14.4).
/// The brackets leave out the 2π of the relative velocity's direction.
#[test]
fn the_first_diffusion_bracket_is_the_collision_rate() {
    let b = Brackets::new(1, 24);
    let nu = 2.0 * PI * 0.5 * b.diffusion[0] / (PI * PI);
    assert!((nu - (2.0 * PI).sqrt()).abs() < 1e-10, "ν = {nu}");
}

/// Higher orders can only raise the coefficients (the Sonine solution is a
/// variational minimum of the inverse); order 2 gives the closed forms
/// 1 + 1/42, 1 + 1/50, 1 + 1/38; each order adds less than the one before; the
/// quadrature has converged; and order 10 plus the geometric rest of the series
/// gives [`SONINE_FACTORS`] to 10⁻⁶.
#[test]
fn factors_rise_converge_and_give_the_constants() {
    const ORDER: usize = 10;
    let b = Brackets::new(ORDER, 32);
    let at = |m: usize| {
        let f = b.factors_to(m);
        [f.d, f.eta, f.lambda]
    };
    assert!(at(1).iter().all(|f| (f - 1.0).abs() < 1e-15));
    let second = at(2);
    for (f, exact) in second
        .iter()
        .zip([1.0 + 1.0 / 42.0, 1.02, 1.0 + 1.0 / 38.0])
    {
        assert!((f - exact).abs() < 1e-12, "{f} vs {exact}");
    }
    let fine = Brackets::new(ORDER, 40).factors();
    let constants = [SONINE_FACTORS.d, SONINE_FACTORS.eta, SONINE_FACTORS.lambda];
    for k in 0..3 {
        let steps: Vec<f64> = (2..=ORDER).map(|m| at(m)[k] - at(m - 1)[k]).collect();
        eprintln!("family {k}: f_10 = {:.9}, steps {steps:?}", at(ORDER)[k]);
        assert!(steps.iter().all(|&s| s > -1e-12), "{steps:?}");
        assert!(steps.windows(2).all(|w| w[1] < w[0]), "{steps:?}");
        let ratio = steps[steps.len() - 1] / steps[steps.len() - 2];
        assert!(ratio < 0.5, "{steps:?}");
        let limit = at(ORDER)[k] + steps[steps.len() - 1] * ratio / (1.0 - ratio);
        assert!(
            (limit - constants[k]).abs() < 1e-6,
            "{limit} vs {}",
            constants[k]
        );
        let f = [fine.d, fine.eta, fine.lambda][k];
        assert!(
            (f - at(ORDER)[k]).abs() < 1e-9,
            "nodes: {f} vs {}",
            at(ORDER)[k]
        );
    }
}
