//! Resolution of a pair collision: elastic and the two inelastic models.
//!
//! Conventions (physics.md §3): disc i and disc j touch with normal n along
//! r_j − r_i, pointing from i to j; g = v_i − v_j; u = g·n̂ > 0 when the pair
//! approaches. Masses in the user's mass unit, velocities in length/time.
//!
//! `n` need not have unit length: every formula uses u n̂ = (g·n) n/|n|² (the form of
//! seed 004, which divides by d² instead of normalising). Kinetic energy is then
//! conserved algebraically whatever the rounding of |n|, whereas normalising first
//! leaves |n̂|² − 1 biased by rounding, and an elastic collision changes the energy
//! by exactly u²(|n̂|² − 1) μ-weighted: a systematic drift over 10⁷ collisions.
//! The engine therefore passes the contact vector r_j − r_i itself.

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
    /// Momentum given to disc i, Δp_i = m_i (v_i' − v_i) (mass·length/time);
    /// disc j receives −Δp_i.
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
/// (any length; u n is evaluated as (g·n) n/|n|²). Returns (v_i', v_j').
#[inline]
pub fn normal_restitution(
    vi: DVec2,
    vj: DVec2,
    mi: f64,
    mj: f64,
    n: DVec2,
    e: f64,
) -> (DVec2, DVec2) {
    let k = (1.0 + e) * (vi - vj).dot(n) / (n.length_squared() * (mi + mj));
    (vi - n * (k * mj), vj + n * (k * mi))
}

/// The seed's centre-of-mass restitution (seed 000 Eq. 22–27, physics.md §4a):
/// elastic resolution, then v'' = (v' − v_cm) R + v_cm with
/// v_cm = (m_i v_i + m_j v_j)/(m_i + m_j). `n` as in [`elastic`]. Returns (v_i'', v_j'').
#[inline]
pub fn centre_of_mass_restitution(
    vi: DVec2,
    vj: DVec2,
    mi: f64,
    mj: f64,
    n: DVec2,
    r: f64,
) -> (DVec2, DVec2) {
    let (ei, ej) = elastic(vi, vj, mi, mj, n);
    if r == 1.0 {
        return (ei, ej);
    }
    let vcm = (vi * mi + vj * mj) / (mi + mj);
    ((ei - vcm) * r + vcm, (ej - vcm) * r + vcm)
}

/// Resolve a pair collision with the chosen rule (physics.md §3–4).
///
/// `n` is the line of centres from i to j at contact (any length). The energy lost is the model's
/// closed form: (1 − e²) μ u²/2 for normal restitution, (1 − R²) μ |g|²/2 for the
/// centre-of-mass model, with μ = m_i m_j/(m_i + m_j).
#[inline]
pub fn resolve(vi: DVec2, vj: DVec2, mi: f64, mj: f64, n: DVec2, rule: Restitution) -> Resolution {
    let (vi2, vj2, energy_lost) = match rule {
        Restitution::Elastic => {
            let (a, b) = elastic(vi, vj, mi, mj, n);
            (a, b, 0.0)
        }
        Restitution::Normal(e) => {
            let (a, b) = normal_restitution(vi, vj, mi, mj, n, e);
            let un = (vi - vj).dot(n);
            let u2 = un * un / n.length_squared();
            (a, b, 0.5 * (1.0 - e * e) * reduced_mass(mi, mj) * u2)
        }
        Restitution::CentreOfMass(r) => {
            let (a, b) = centre_of_mass_restitution(vi, vj, mi, mj, n, r);
            let g2 = (vi - vj).length_squared();
            (a, b, 0.5 * (1.0 - r * r) * reduced_mass(mi, mj) * g2)
        }
    };
    Resolution {
        vi: vi2,
        vj: vj2,
        energy_lost,
        impulse_i: (vi2 - vi) * mi,
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
