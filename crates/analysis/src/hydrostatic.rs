//! The density profile of a dense atmosphere (physics.md §15, (15.7)): a column of
//! hard discs in hydrostatic balance with its equation of state. Near the floor
//! the gas is not ideal (Z > 1) and the barometric exponential (15.6) is the wrong
//! model there: the pressure p = n kT Z(η) must carry the weight above,
//!
//! ```text
//! dp/dy = −m g n   ⇒   dn/dy = −β_g n / (Z + η dZ/dη),   β_g = m g/kT,
//! ```
//!
//! with Henderson's Z(η) (7.6) in the local-density approximation. The floor
//! density n(a) is fixed by the number of discs, N = L_x ∫ n dy. The estimator
//! (15.8) applied to this profile's mean height gives the β_g that an equilibrium
//! column of this density would show: the known value to judge the fit by.

use carom_core::gravity::barometric_beta;

use super::eos_reference::henderson_z;

/// Integration steps over the column.
const STEPS: usize = 4000;

/// (∫ n dy, ∫ (y − a) n dy) over the column of height `span` above a, starting from
/// n(a) = `n0`, for discs of radius `a` and β_g = `beta` (RK4 in y).
fn column(n0: f64, beta: f64, a: f64, span: f64) -> (f64, f64) {
    let area = std::f64::consts::PI * a * a;
    let slope = |n: f64| {
        let eta = n * area;
        let h = 1e-6 * eta.max(1e-6);
        let dz = (henderson_z(eta + h) - henderson_z(eta - h)) / (2.0 * h);
        -beta * n / (henderson_z(eta) + eta * dz)
    };
    let dy = span / STEPS as f64;
    let (mut n, mut count, mut moment) = (n0, 0.0, 0.0);
    for k in 0..STEPS {
        let y = k as f64 * dy;
        let k1 = slope(n);
        let k2 = slope(n + 0.5 * dy * k1);
        let k3 = slope(n + 0.5 * dy * k2);
        let k4 = slope(n + dy * k3);
        let next = n + dy * (k1 + 2.0 * k2 + 2.0 * k3 + k4) / 6.0;
        // Trapezoid for the integrals.
        count += 0.5 * dy * (n + next);
        moment += 0.5 * dy * (y * n + (y + dy) * next);
        n = next;
    }
    (count, moment)
}

/// The β_g that (15.8) gives for the hydrostatic profile of `count` discs of
/// radius `a` per unit length of floor (N/L_x) in a column of height `span`
/// (centres in [a, a + span]) at β_g = m g/kT = `beta`; NaN when the column
/// would need a floor density above η = 0.85.
pub fn hydrostatic_beta(beta: f64, count: f64, a: f64, span: f64) -> f64 {
    let area = std::f64::consts::PI * a * a;
    let (mut lo, mut hi) = (count / span, 0.85 / area);
    if column(hi, beta, a, span).0 < count {
        return f64::NAN;
    }
    for _ in 0..100 {
        let mid = (lo * hi).sqrt();
        if column(mid, beta, a, span).0 < count {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let (c, m) = column((lo * hi).sqrt(), beta, a, span);
    barometric_beta(m / c, span)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A dilute column is ideal: Z → 1 and the profile is the exponential, whose
    /// fitted β_g is β_g itself; a dense one is flatter near the floor (Z > 1
    /// resists the weight), so its fitted β_g is smaller, the more so the denser.
    #[test]
    fn dilute_columns_are_barometric_and_dense_ones_flatter() {
        let (beta, a, span) = (0.05, 0.5, 99.0);
        let dilute = hydrostatic_beta(beta, 0.001, a, span);
        assert!((dilute / beta - 1.0).abs() < 1e-3, "{dilute}");
        let (b4, b8) = (
            hydrostatic_beta(beta, 4.0, a, span),
            hydrostatic_beta(beta, 8.0, a, span),
        );
        assert!(b8 < b4 && b4 < beta * 0.99, "{b4} {b8}");
        // A column that cannot hold its discs below η = 0.85.
        assert!(hydrostatic_beta(beta, 1e3, a, span).is_nan());
    }
}
