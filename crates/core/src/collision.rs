//! Resolution of a pair collision: elastic and the two inelastic models.
//!
//! Conventions (physics.md §3): disc i and disc j touch with normal n along
//! r_j − r_i, pointing from i to j; g = v_i − v_j; u = g·n̂ > 0 when the pair
//! approaches. Masses in the user's mass unit, velocities in length/time.
//!
//! `n` need not have unit length: every formula uses u n̂ = (g·n) n/|n|² (seed
//! 004's form, which divides by d² instead of normalising), so kinetic energy is
//! conserved algebraically whatever the rounding of |n|; the engine passes the
//! contact vector r_j − r_i itself. The ratio (g·n)/|n|² is evaluated with
//! compensated products and sums ([`normal_ratio`]) so that it is rounded about
//! once and without bias: a biased ratio drifts the energy of a long elastic run
//! linearly. See docs/performance.md, "Resolution".

use glam::DVec2;

/// Which collision rule resolves a pair collision (physics.md §3–4).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Restitution {
    /// Perfectly elastic: kinetic energy is conserved (physics.md §3).
    Elastic,
    /// The seed's centre-of-mass restitution R ∈ [0, 1] (seed 000, Eq. 22–27,
    /// physics.md §4a): resolve elastically, then scale both velocities about the
    /// centre-of-mass velocity by R. Normal and tangential relative velocity shrink.
    CentreOfMass(f64),
    /// Normal restitution e ∈ [0, 1] (physics.md §4b): only the normal relative
    /// velocity changes, u' = −e u. The convention of granular-gas theory.
    Normal(f64),
}

impl Restitution {
    /// The coefficient (R or e), 1 for [`Restitution::Elastic`].
    pub fn coefficient(&self) -> f64 {
        match *self {
            Restitution::Elastic => 1.0,
            Restitution::CentreOfMass(r) => r,
            Restitution::Normal(e) => e,
        }
    }

    /// True when the rule conserves kinetic energy exactly (coefficient 1).
    pub fn is_elastic(&self) -> bool {
        self.coefficient() == 1.0
    }
}

/// The outcome of a pair collision.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Resolution {
    /// Velocity of disc i after the collision (length/time).
    pub vi: DVec2,
    /// Velocity of disc j after the collision (length/time).
    pub vj: DVec2,
    /// Kinetic energy dissipated, from the model's closed form (energy; 0 when elastic).
    pub energy_lost: f64,
    /// Momentum given to disc i, Δp_i (mass·length/time); disc j receives −Δp_i,
    /// and the velocities are exactly [`apply_impulse`] of it.
    pub impulse_i: DVec2,
}

/// Elastic collision of unequal masses in vector form (physics.md §3, seed 004):
/// v_i' = v_i − (2 m_j/(m_i+m_j)) u n,  v_j' = v_j + (2 m_i/(m_i+m_j)) u n.
///
/// `n` is the line of centres from i to j at contact (any length). Returns (v_i', v_j').
#[inline]
pub fn elastic(vi: DVec2, vj: DVec2, mi: f64, mj: f64, n: DVec2) -> (DVec2, DVec2) {
    normal_restitution(vi, vj, mi, mj, n, 1.0)
}

/// Normal restitution (physics.md §4b):
/// v_i' = v_i − (1+e) (m_j/(m_i+m_j)) u n,  v_j' = v_j + (1+e) (m_i/(m_i+m_j)) u n.
/// With e = 1 this is exactly [`elastic`]. `n` is the line of centres from i to j
/// (any length; u n is evaluated as (g·n) n/|n|²). Returns (v_i', v_j'), applied
/// from the impulse [`normal_impulse`] by [`apply_impulse`].
#[inline]
pub fn normal_restitution(
    vi: DVec2,
    vj: DVec2,
    mi: f64,
    mj: f64,
    n: DVec2,
    e: f64,
) -> (DVec2, DVec2) {
    apply_impulse(vi, vj, mi, mj, normal_impulse(vi, vj, mi, mj, n, e))
}

/// The momentum Δp_i given to disc i by normal restitution e (physics.md §4b):
/// Δp_i = −(1+e) μ (g·n) n/|n|², μ = m_i m_j/(m_i+m_j); disc j receives −Δp_i.
/// Along −n: a reader recovers the unit normal as −Δp_i/|Δp_i|. The scalar is
/// evaluated as ((1+e)(g·n)/|n|²/(m_i+m_j)) m_i m_j: rounded per collision, not
/// through a fixed rounded μ, whose constant error would bias the energy of every
/// elastic collision the same way (unequal masses; see the module docs), and with
/// masses that are powers of two the velocities equal those of
/// v_i − (2 m_j/(m_i+m_j)) u n bit for bit.
#[inline]
pub fn normal_impulse(vi: DVec2, vj: DVec2, mi: f64, mj: f64, n: DVec2, e: f64) -> DVec2 {
    let k = (1.0 + e) * normal_ratio(vi - vj, n) / (mi + mj);
    n * -(k * mi * mj)
}

/// The velocities after disc i receives the momentum `dp` (Δp_i) and disc j
/// receives −Δp_i: (v_i + Δp_i/m_i, v_j − Δp_i/m_j), componentwise in exactly this
/// order of operations (one division and one addition per component). The engine
/// changes velocities only through this function (and [`apply_wall_impulse`]), so
/// that a reader of the log repeating it gets every velocity bit for bit.
#[inline]
pub fn apply_impulse(vi: DVec2, vj: DVec2, mi: f64, mj: f64, dp: DVec2) -> (DVec2, DVec2) {
    (vi + dp / mi, vj - dp / mj)
}

/// The velocity component after a wall gives the momentum `dp` (Δp along the
/// wall's axis) to a disc of mass `m`: v + Δp/m (see [`apply_impulse`]).
#[inline]
pub fn apply_wall_impulse(v: f64, m: f64, dp: f64) -> f64 {
    v + dp / m
}

/// The ratio (g·n)/|n|² (time⁻¹ for a relative velocity g and a contact vector n),
/// so that (g·n) n/|n|² is the normal part of g, computed to about twice the
/// working precision and then rounded: both dot products are evaluated exactly as
/// a sum of a value and its error (the error-free transformations TwoProduct, with
/// a fused multiply-add, and TwoSum; Ogita, Rump & Oishi, SIAM J. Sci. Comput. 26,
/// 1955 (2005)), and the quotient is corrected by its remainder. A rounding error
/// here changes the kinetic energy of the collision to first order, so it must not
/// be biased (see the module docs). (On a baseline x86-64 build `mul_add` calls a
/// library routine that picks the fma instruction at run time, about 20
/// instructions per collision; Dekker's product with Veltkamp's splitting, which
/// needs no fma, gave the same trajectory and was no faster: 0.996, median of 8
/// runs side by side at N = 10⁴.)
#[inline]
pub fn normal_ratio(g: DVec2, n: DVec2) -> f64 {
    let (d, d_err) = dot_compensated(g, n);
    let (s, s_err) = dot_compensated(n, n);
    let q = d / s;
    // (d + d_err) − q (s + s_err): d − q s is exact (one fma), then the low parts.
    let rem = (-q).mul_add(s, d) + (d_err - q * s_err);
    q + rem / s
}

/// a·b as an unevaluated sum (value, error) accurate to about twice the working
/// precision: the products split exactly by TwoProduct, the sum by TwoSum.
#[inline]
fn dot_compensated(a: DVec2, b: DVec2) -> (f64, f64) {
    let (p, p_err) = two_product(a.x, b.x);
    let (q, q_err) = two_product(a.y, b.y);
    let (s, s_err) = two_sum(p, q);
    (s, p_err + q_err + s_err)
}

/// a b as (rounded product, its exact rounding error), by one fused multiply-add
/// (TwoProduct).
#[inline]
fn two_product(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    (p, a.mul_add(b, -p))
}

/// a + b as (rounded sum, its exact rounding error) (Knuth's TwoSum).
#[inline]
fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let b_part = s - a;
    (s, (a - (s - b_part)) + (b - b_part))
}

/// The seed's centre-of-mass restitution (seed 000 Eq. 22–27, physics.md §4a):
/// elastic resolution, then v'' = (v' − v_cm) R + v_cm with
/// v_cm = (m_i v_i + m_j v_j)/(m_i + m_j). `n` as in [`elastic`]. Returns (v_i'', v_j''),
/// applied from the impulse [`centre_of_mass_impulse`] by [`apply_impulse`].
#[inline]
pub fn centre_of_mass_restitution(
    vi: DVec2,
    vj: DVec2,
    mi: f64,
    mj: f64,
    n: DVec2,
    r: f64,
) -> (DVec2, DVec2) {
    apply_impulse(vi, vj, mi, mj, centre_of_mass_impulse(vi, vj, mi, mj, n, r))
}

/// The momentum Δp_i given to disc i by the centre-of-mass rule with R
/// (physics.md §4a): m_i (v_i'' − v_i) = −μ [(1 − R) g + 2R (g·n) n/|n|²], with
/// g = v_i − v_j and μ the reduced mass; the elastic impulse when R = 1. Not along
/// n unless R = 1 or g ∥ n, so a log of this rule stores the normal as well.
#[inline]
pub fn centre_of_mass_impulse(vi: DVec2, vj: DVec2, mi: f64, mj: f64, n: DVec2, r: f64) -> DVec2 {
    if r == 1.0 {
        return normal_impulse(vi, vj, mi, mj, n, 1.0);
    }
    let g = vi - vj;
    let w = (g * (1.0 - r) + n * (2.0 * r * normal_ratio(g, n))) / (mi + mj);
    w * -(mi * mj)
}

/// Resolve a pair collision with the chosen rule (physics.md §3–4).
///
/// `n` is the line of centres from i to j at contact (any length). The energy lost is the model's
/// closed form: (1 − e²) μ u²/2 for normal restitution, (1 − R²) μ |g|²/2 for the
/// centre-of-mass model, with μ = m_i m_j/(m_i + m_j).
#[inline(always)]
pub fn resolve(vi: DVec2, vj: DVec2, mi: f64, mj: f64, n: DVec2, rule: Restitution) -> Resolution {
    let (impulse_i, energy_lost) = match rule {
        Restitution::Elastic => (normal_impulse(vi, vj, mi, mj, n, 1.0), 0.0),
        Restitution::Normal(e) => {
            let un = (vi - vj).dot(n);
            let u2 = un * un / n.length_squared();
            (
                normal_impulse(vi, vj, mi, mj, n, e),
                0.5 * (1.0 - e * e) * reduced_mass(mi, mj) * u2,
            )
        }
        Restitution::CentreOfMass(r) => {
            let g2 = (vi - vj).length_squared();
            (
                centre_of_mass_impulse(vi, vj, mi, mj, n, r),
                0.5 * (1.0 - r * r) * reduced_mass(mi, mj) * g2,
            )
        }
    };
    let (vi2, vj2) = apply_impulse(vi, vj, mi, mj, impulse_i);
    Resolution {
        vi: vi2,
        vj: vj2,
        energy_lost,
        impulse_i,
    }
}

/// Reduced mass μ = m_i m_j/(m_i + m_j) (mass).
#[inline]
pub fn reduced_mass(mi: f64, mj: f64) -> f64 {
    mi * mj / (mi + mj)
}

/// The seed's elastic resolution (seed 000, Eq. 7–13), kept as a reference.
///
/// Ball 1 at `r1` (velocity `v1`, mass `m1`, radius `a1`), ball 2 likewise. The
/// positions may be those at contact or earlier on the approach: the impact angle
/// α = arcsin(d sin(γ_xy − γ_v)/(a1+a2)) (Eq. 14) fixes the geometry, a = tan(γ_v + α)
/// (Eq. 9) and
/// Δv_x,2 = 2[(v_x,1 − v_x,2) + a (v_y,1 − v_y,2)] / [(1 + a²)(1 + m2/m1)] (Eq. 8),
/// then Eq. 10–13 give the new velocities. Angles use atan2 (Eq. 7 and 16 as printed
/// lose the quadrant). The tan form is singular when the line of centres is vertical
/// (a → ∞); [`elastic`] is not. Returns (v1', v2').
#[allow(clippy::too_many_arguments)] // mirrors the seed's variables, ball 1 then ball 2
pub fn elastic_seed(
    r1: DVec2,
    v1: DVec2,
    m1: f64,
    a1: f64,
    r2: DVec2,
    v2: DVec2,
    m2: f64,
    a2: f64,
) -> (DVec2, DVec2) {
    let sep = r2 - r1;
    let g = v1 - v2;
    let d = sep.length();
    let gamma_xy = sep.y.atan2(sep.x);
    let gamma_v = g.y.atan2(g.x);
    let sin_alpha = (d * (gamma_xy - gamma_v).sin() / (a1 + a2)).clamp(-1.0, 1.0);
    let alpha = sin_alpha.asin();
    let a = (gamma_v + alpha).tan();
    let dvx2 = 2.0 * (g.x + a * g.y) / ((1.0 + a * a) * (1.0 + m2 / m1));
    let v2n = DVec2::new(v2.x + dvx2, v2.y + a * dvx2);
    let v1n = DVec2::new(v1.x - m2 / m1 * dvx2, v1.y - a * (m2 / m1) * dvx2);
    (v1n, v2n)
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{RngExt, SeedableRng};
    use rand_distr::{Distribution, StandardNormal};
    use rand_pcg::Pcg64;

    #[test]
    fn equal_masses_head_on_exchange_velocities() {
        let (a, b) = elastic(
            DVec2::new(1.0, 0.0),
            DVec2::new(-1.0, 0.0),
            1.0,
            1.0,
            DVec2::X,
        );
        assert_eq!(a, DVec2::new(-1.0, 0.0));
        assert_eq!(b, DVec2::new(1.0, 0.0));
    }

    /// Σ m |v|²/2 over the given discs as an unevaluated sum (value, error), exact
    /// to about 10⁻³² relative: each square and its product with the mass split
    /// exactly by TwoProduct, the terms added by TwoSum.
    fn kinetic_exact(discs: &[(f64, DVec2)]) -> (f64, f64) {
        let (mut hi, mut lo) = (0.0f64, 0.0f64);
        for &(m, v) in discs {
            for x in [v.x, v.y] {
                let (sq, sq_err) = two_product(x, x);
                let (term, term_err) = two_product(0.5 * m, sq);
                let term_err = term_err + 0.5 * m * sq_err;
                let (sum, sum_err) = two_sum(hi, term);
                lo += sum_err + term_err;
                hi = sum;
            }
        }
        (hi, lo)
    }

    /// Elastic collisions change the kinetic energy by rounding only, with no bias,
    /// even where plain rounding of (g·n)/|n|² is biased: |n|² within a few ulp of a
    /// power of two, as at a contact of discs of diameter 1 or 2 located exactly or,
    /// as the engine locates it, to about 1e-14. The mean of the exact energy change
    /// over many random collisions must lie within 5 standard errors of zero.
    /// Plainly rounded, the cases gave (in standard errors) +46, +9.6 and +55, and
    /// +3.5e-18 per collision in the engine is a drift of +3.5e-13 over 10⁹
    /// collisions at N = 10⁴; the last case, away from a power of two, is a control.
    #[test]
    fn elastic_energy_change_has_no_rounding_bias() {
        // (mass i, mass j, contact distance, relative noise of the contact vector,
        // collisions)
        let cases = [
            (1.0, 1.0, 1.0, 0.0, 400_000),
            (1.0, 1.0, 1.0, 1e-14, 16_000_000),
            (1.0, 4.0, 2.0, 0.0, 400_000),
            (1.0, 1.0, 0.75, 0.0, 400_000),
            // Masses that are not powers of two (data/binary-mixture.json): Δp/m
            // rounds once more per component.
            (1.0, 1.96, 1.2, 1e-14, 4_000_000),
        ];
        let mut rng = Pcg64::seed_from_u64(7);
        let gaussian =
            |rng: &mut Pcg64| DVec2::new(StandardNormal.sample(rng), StandardNormal.sample(rng));
        for (mi, mj, sigma, noise, count) in cases {
            let (mut sum, mut sum_sq) = (0.0f64, 0.0f64);
            for _ in 0..count {
                let (vi, vj) = (gaussian(&mut rng), gaussian(&mut rng));
                // A uniform direction, and a length blurred by up to ± noise.
                let direction = gaussian(&mut rng).normalize();
                let length = sigma * (1.0 + noise * (2.0 * rng.random::<f64>() - 1.0));
                let mut n = direction * length;
                if (vi - vj).dot(n) < 0.0 {
                    n = -n;
                }
                let (a, b) = elastic(vi, vj, mi, mj, n);
                let (k0, k0_err) = kinetic_exact(&[(mi, vi), (mj, vj)]);
                let (k1, k1_err) = kinetic_exact(&[(mi, a), (mj, b)]);
                let change = (k1 - k0) + (k1_err - k0_err);
                sum += change;
                sum_sq += change * change;
            }
            let mean = sum / count as f64;
            let se = ((sum_sq / count as f64 - mean * mean) / count as f64).sqrt();
            assert!(
                mean.abs() <= 5.0 * se,
                "masses {mi}, {mj}, contact distance {sigma}, noise {noise}: mean energy \
                 change {mean:e} per collision, standard error {se:e}"
            );
        }
    }

    #[test]
    fn perfectly_inelastic_normal_leaves_no_normal_relative_velocity() {
        let n = DVec2::new(0.6, 0.8);
        let r = resolve(
            DVec2::new(1.0, 2.0),
            DVec2::new(-0.5, 0.1),
            1.0,
            3.0,
            n,
            Restitution::Normal(0.0),
        );
        assert!((r.vi - r.vj).dot(n).abs() < 1e-15);
    }

    #[test]
    fn centre_of_mass_zero_makes_discs_move_on_together() {
        let r = resolve(
            DVec2::new(1.0, 2.0),
            DVec2::new(-0.5, 0.1),
            1.0,
            3.0,
            DVec2::new(0.6, 0.8),
            Restitution::CentreOfMass(0.0),
        );
        assert!((r.vi - r.vj).length() < 1e-15);
    }
}
