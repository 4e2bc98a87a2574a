//! Growing discs (Lubachevsky–Stillinger compression): contact times, wall times
//! and the collision rule when every radius grows linearly in time (physics.md §17).
//!
//! All radii scale together, a_i(t) = a_i⁰ (s + γ t), so a pair's contact distance
//! is σ + g t with g = γ σ_ij⁰. Two discs touch when
//! h(t) = |Δr + Δv t|² − (σ + g t)² = A t² + 2 B t + C = 0 with A = |Δv|² − g²,
//! B = Δr·Δv − σ g, C = |Δr|² − σ² (17.2); they meet when h goes from positive to
//! negative, and the root is taken in the cancellation-free forms of (17.3). At
//! contact the normal relative velocity u is reflected in the frame of the growing
//! contact surface, u − g → −(u − g): the pair separates faster than it grows
//! (17.4). The same rules as for fixed sizes: never in the past, never NaN.

use glam::DVec2;

/// Time from now until two growing discs touch (time ≥ 0, or +∞), physics.md (17.3).
///
/// * `dr` = r_j − r_i now, `dv` = v_j − v_i (length, length/time);
/// * `sigma` = a_i + a_j now (length), `g` = its growth rate dσ/dt ≥ 0 (length/time).
///
/// With A, B, C of the module documentation and D = B² − A C:
/// * approaching (B < 0): touching or overlapping by rounding (C ≤ 0) collides now;
///   else C / (−B + √D) when D ≥ 0, a miss (+∞) when D < 0;
/// * not approaching (B ≥ 0): when the discs grow faster than they can recede
///   (A < 0) they meet at the later root (−B − √D)/A (after leaving an overlap by
///   rounding; the top of h, −B/A, when rounding gives D < 0); otherwise never.
///
/// With g = 0 this is the fixed-size contact time of physics.md §2.
#[inline]
pub fn contact_time_growing(dr: DVec2, dv: DVec2, sigma: f64, g: f64) -> f64 {
    let a = dv.length_squared() - g * g;
    let b = dr.dot(dv) - sigma * g;
    let c = dr.length_squared() - sigma * sigma;
    let d = b * b - a * c;
    if b < 0.0 {
        if c <= 0.0 {
            0.0
        } else if d >= 0.0 {
            // −B > 0 and √D ≥ 0: a positive denominator.
            c / (d.sqrt() - b)
        } else {
            f64::INFINITY
        }
    } else if a < 0.0 {
        // −B − √D ≤ 0 and A < 0: t ≥ 0, no cancellation.
        (-b - d.max(0.0).sqrt()) / a
    } else {
        // B ≥ 0 with A ≥ 0, or NaN.
        f64::INFINITY
    }
}

/// Time from now (≥ 0, or +∞) until a disc of radius `a` growing at `da` (length/
/// time) at coordinate `x` with velocity `v` along a walled axis of length `l`
/// touches a wall, and whether that is the high wall: the centre meets a(t) at the
/// low side when (x − a) + (v − ȧ) t = 0 and l − a(t) at the high side when
/// (l − a − x) − (v + ȧ) t = 0 (physics.md (17.5)). A disc that rounding left
/// beyond a wall it approaches hits it now.
#[inline]
pub fn wall_time_growing(x: f64, v: f64, a: f64, da: f64, l: f64) -> (f64, bool) {
    let low = if v - da < 0.0 {
        ((a - x) / (v - da)).max(0.0)
    } else {
        f64::INFINITY
    };
    let high = if v + da > 0.0 {
        ((l - a - x) / (v + da)).max(0.0)
    } else {
        f64::INFINITY
    };
    if high < low {
        (high, true)
    } else {
        (low, false)
    }
}

/// The extra momentum given to disc i (mass·length/time) beyond the elastic
/// impulse so that a pair in contact along `n` (from i to j, any length) with
/// reduced mass `mu` separates at u' = −u + 2g, physics.md (17.4): −2 μ g n/|n|.
#[inline]
pub fn growth_impulse(n: DVec2, mu: f64, g: f64) -> DVec2 {
    n * (-2.0 * mu * g / n.length())
}

/// A wall's impulse (mass·length/time, along the axis) on a disc of mass `m` with
/// normal velocity `v` whose radius grows at `da`: the velocity relative to the
/// moving contact point, v ∓ ȧ, is reversed, so v' = −v + 2ȧ at the low wall and
/// −v − 2ȧ at the high wall (physics.md (17.6)); Δp = m (v' − v).
#[inline]
pub fn growing_wall_impulse(v: f64, m: f64, da: f64, high: bool) -> f64 {
    let away = if high { -da } else { da };
    (2.0 * (away - v)) * m
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kinematics::contact_time_or_inf;

    /// Two discs of contact distance 1 at rest, 3 apart, the distance growing at 1:
    /// 1 + t = 3 at t = 2. Closing at 1 as well: |3 − t| = 1 + t at t = 1.
    #[test]
    fn hand_worked_growing_contacts() {
        let dr = DVec2::new(3.0, 0.0);
        assert_eq!(contact_time_growing(dr, DVec2::ZERO, 1.0, 1.0), 2.0);
        assert_eq!(
            contact_time_growing(dr, DVec2::new(-1.0, 0.0), 1.0, 1.0),
            1.0
        );
        // Receding at 2 while growing at 1: |3 + 2t| = 1 + t has no root t ≥ 0.
        assert_eq!(
            contact_time_growing(dr, DVec2::new(2.0, 0.0), 1.0, 1.0),
            f64::INFINITY
        );
        // Receding at 1/2 while growing at 1: 3 + t/2 = 1 + t at t = 4.
        assert_eq!(
            contact_time_growing(dr, DVec2::new(0.5, 0.0), 1.0, 1.0),
            4.0
        );
        // Side by side: Δr = (0, 2), moving across at 1, σ = 1 growing at 1/2:
        // 4 + t² = (1 + t/2)², 3 t²/4 − t + 3 = 0 has no real root, but the
        // discs grow slower than they part, so they never meet.
        let t = contact_time_growing(DVec2::new(0.0, 2.0), DVec2::new(1.0, 0.0), 1.0, 0.5);
        assert_eq!(t, f64::INFINITY);
    }

    /// Pairs at contact (σ = 1, Δr = (1, 0)): separating faster than the contact
    /// distance grows, they part (+∞); separating slower, their surfaces close in at
    /// once and they collide now (0).
    #[test]
    fn a_pair_at_contact_parts_or_collides_now() {
        let dr = DVec2::new(1.0, 0.0);
        // u = 3 > g = 1 (as the contact rule leaves u' = −u + 2g from u = −1).
        let t = contact_time_growing(dr, DVec2::new(3.0, 0.0), 1.0, 1.0);
        assert_eq!(t, f64::INFINITY);
        // u = 2 < g = 3: B = −1 < 0 at C = 0.
        assert_eq!(
            contact_time_growing(dr, DVec2::new(2.0, 0.0), 1.0, 3.0),
            0.0
        );
        // u = 1/2 < g = 1 with a sideways 2.
        assert_eq!(
            contact_time_growing(dr, DVec2::new(0.5, 2.0), 1.0, 1.0),
            0.0
        );
        // u = 4 > g = 3 with a sideways 3: A = 16 > 0, B = 1 > 0.
        let t = contact_time_growing(dr, DVec2::new(4.0, 3.0), 1.0, 3.0);
        assert_eq!(t, f64::INFINITY);
        // A hair inside contact (C < 0, rounding), u = 6 < g = 7: now.
        let inside = DVec2::new(1.0 - 1e-15, 0.0);
        assert_eq!(
            contact_time_growing(inside, DVec2::new(6.0, 0.0), 1.0, 7.0),
            0.0
        );
        // The same hair inside, parting at u = 6 > g = 5 with A = 36 − 25 > 0: never.
        let t = contact_time_growing(inside, DVec2::new(6.0, 0.0), 1.0, 5.0);
        assert_eq!(t, f64::INFINITY);
        // (At contact B > 0 needs |Δv| ≥ u > g, so A > 0: the later root (17.3) is
        // for pairs apart, below.)
    }

    /// With g > |Δv| the discs always meet: a disc passing sideways at 1 at
    /// distance 3 with σ = 1 growing at 2: |Δr + Δv t|² = 9 + t² = (1 + 2t)²,
    /// 3t² + 4t − 8 = 0, t = (−2 + √28)/3. B = −2 < 0 here; with the pair
    /// receding at 1 instead (B = 3 − 2 > 0, A = 1 − 4 < 0): (3 + t) = 1 + 2t, t = 2.
    #[test]
    fn faster_growth_than_relative_speed_always_meets() {
        let t = contact_time_growing(DVec2::new(3.0, 0.0), DVec2::new(0.0, 1.0), 1.0, 2.0);
        let exact = (-2.0 + 28f64.sqrt()) / 3.0;
        assert!(
            (t - exact).abs() < 4.0 * f64::EPSILON * exact,
            "{t} {exact}"
        );
        let t = contact_time_growing(DVec2::new(3.0, 0.0), DVec2::new(1.0, 0.0), 1.0, 2.0);
        assert_eq!(t, 2.0);
    }

    /// Without growth, the fixed-size contact time, bit for bit (a sweep).
    #[test]
    fn no_growth_is_the_fixed_size_contact_time() {
        let mut k = 7u64;
        let mut next = || {
            k = k
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (k >> 11) as f64 / (1u64 << 53) as f64
        };
        for _ in 0..100_000 {
            let dr = DVec2::new(4.0 * next() - 2.0, 4.0 * next() - 2.0);
            let dv = DVec2::new(4.0 * next() - 2.0, 4.0 * next() - 2.0);
            let want = contact_time_or_inf(dr, dv, 1.0);
            let got = contact_time_growing(dr, dv, 1.0, 0.0);
            assert_eq!(got.to_bits(), want.to_bits(), "{dr} {dv}");
        }
    }

    /// Never NaN, never negative, over random geometries with growth, including
    /// overlaps and zero velocities.
    #[test]
    fn never_nan_never_negative() {
        let mut k = 11u64;
        let mut next = || {
            k = k
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (k >> 11) as f64 / (1u64 << 53) as f64
        };
        for n in 0..100_000 {
            let dr = DVec2::new(4.0 * next() - 2.0, 4.0 * next() - 2.0);
            let dv = if n % 13 == 0 {
                DVec2::ZERO
            } else {
                DVec2::new(4.0 * next() - 2.0, 4.0 * next() - 2.0)
            };
            let t = contact_time_growing(dr, dv, 1.0, 3.0 * next());
            assert!(t >= 0.0, "{dr} {dv} {t}");
        }
        let nan = contact_time_growing(DVec2::new(f64::NAN, 0.0), DVec2::X, 1.0, 1.0);
        assert_eq!(nan, f64::INFINITY);
    }

    /// A disc of radius 1/2 at rest at x = 2 in a box of length 10, growing at 1/2:
    /// 1/2 + t/2 = 2 at t = 3 (low wall); moving up at 1: 1/2 + t/2 = 10 − 2 − t at
    /// t = 5 (high wall, 7.5/1.5).
    #[test]
    fn hand_worked_wall_times() {
        assert_eq!(wall_time_growing(2.0, 0.0, 0.5, 0.5, 10.0), (3.0, false));
        assert_eq!(wall_time_growing(2.0, 1.0, 0.5, 0.5, 10.0), (5.0, true));
        assert_eq!(wall_time_growing(2.0, 0.0, 0.5, 0.0, 10.0).0, f64::INFINITY);
    }

    /// The contact rule: head on at u = −1 (closing at 1) with g = 1/2 leaves at
    /// u' = 1 + 1 = 2 (equal masses 1, μ = 1/2: Δp_i = −(1 + 1/2)·... along x).
    #[test]
    fn the_pair_leaves_at_minus_u_plus_twice_g() {
        use crate::collision::{apply_impulse, resolve};
        use crate::Restitution;
        let (vi, vj) = (DVec2::new(0.5, 0.0), DVec2::new(-0.5, 0.0));
        let n = DVec2::new(1.0, 0.0);
        let el = resolve(vi, vj, 1.0, 1.0, n, Restitution::Elastic);
        let dp = el.impulse_i + growth_impulse(n, 0.5, 0.5);
        let (a, b) = apply_impulse(vi, vj, 1.0, 1.0, dp);
        assert_eq!((b - a).dot(n), 2.0);
        // A wall: v = −1 at the low wall growing at 1/4 leaves at 1 + 1/2.
        let dp = growing_wall_impulse(-1.0, 2.0, 0.25, false);
        assert_eq!(-1.0 + dp / 2.0, 1.5);
        let dp = growing_wall_impulse(1.0, 2.0, 0.25, true);
        assert_eq!(1.0 + dp / 2.0, -1.5);
    }
}
