//! Free flight and exact contact times of two discs.
//!
//! Between events every disc moves on a straight line (physics.md §1). The contact
//! time of two discs is the smaller root of |Δr + Δv t| = σ, computed in the
//! cancellation-free vector form of physics.md §2. The seed's angular form
//! (seed 000, Eq. 14–17) is kept in [`contact_time_seed`] as a documented reference;
//! property tests show the two agree.

use glam::DVec2;

/// Position after free flight for a time `dt` (physics.md §1): r + v dt.
#[inline]
pub fn advance(r: DVec2, v: DVec2, dt: f64) -> DVec2 {
    r + v * dt
}

/// Time from now until two discs touch, in the vector form of physics.md §2.
///
/// * `dr` = r_j − r_i, the separation of the centres now (length);
/// * `dv` = v_j − v_i, the relative velocity (length/time);
/// * `sigma` = a_i + a_j, the contact distance (length).
///
/// With b = Δr·Δv, c = |Δr|² − σ², D = b² − |Δv|² c the pair meets iff b < 0 and
/// D ≥ 0, after t = c / (−b + √D) (equal to (−b − √D)/|Δv|² without its cancellation).
///
/// Robustness rules (physics.md §2):
/// * receding pairs (b ≥ 0), including zero relative velocity, never meet: `None`;
/// * a miss (D < 0) never meets: `None`;
/// * a pair that rounding left touching or overlapping (c ≤ 0) while approaching
///   collides now: `Some(0.0)` — an event is never scheduled in the past;
/// * the result is never NaN: any NaN input gives `None`.
#[inline]
pub fn contact_time(dr: DVec2, dv: DVec2, sigma: f64) -> Option<f64> {
    let b = dr.dot(dv);
    if b.is_nan() || b >= 0.0 {
        return None;
    }
    let c = dr.length_squared() - sigma * sigma;
    if c <= 0.0 {
        return Some(0.0);
    }
    let d = b * b - dv.length_squared() * c;
    if d.is_nan() || d < 0.0 {
        return None;
    }
    // c > 0 and −b > 0, so the denominator is positive and t is finite and positive.
    Some(c / (d.sqrt() - b))
}

/// [`contact_time`] without branches: the same time when that is `Some(t)`, and
/// +∞ when it is `None` (bit for bit).
///
/// Every quantity is computed for every pair and the result is selected at the
/// end, so the event loop's scan over neighbours has no data-dependent branch:
/// whether a pair approaches (b < 0) is a coin toss that a branch predictor
/// cannot learn. (Measured with `examples/profile` at N = 10⁴, η = 0.5: 5 % more
/// collisions per second than a form that skips the square root for pairs that
/// cannot beat the best time so far, t ≥ c/(−2b), behind a branch; faster also
/// than that pruning behind one combined branch, although every pair now pays
/// for a square root and a division. Testing the neighbours two at a time, with
/// both pairs' square roots and divisions in one `sqrtpd` and one `divpd` and the
/// same trajectory bit for bit, was no faster either: 1.006, median of 6 runs side
/// by side with this form at N = 10⁴, η = 0.5. `perf` puts a third of the scan's
/// samples on the instructions after the square root and the division, but they
/// wait for their latency, not for a free divider.)
#[inline]
pub fn contact_time_or_inf(dr: DVec2, dv: DVec2, sigma: f64) -> f64 {
    let b = dr.dot(dv);
    let c = dr.length_squared() - sigma * sigma;
    let d = b * b - dv.length_squared() * c;
    // For b < 0 and D ≥ 0 the denominator is positive; elsewhere the value is
    // discarded below (it may be ±∞ or NaN there, which never escapes).
    let t = c / (d.max(0.0).sqrt() - b);
    let overlap = c <= 0.0;
    let t = std::hint::select_unpredictable(overlap, 0.0, t);
    let meets = (b < 0.0) & (overlap | (d >= 0.0));
    std::hint::select_unpredictable(meets, t, f64::INFINITY)
}

/// Time from now until a disc at `d` from a fixed point (d = r − c, length),
/// moving with velocity `v`, is `s` from it: the positive root of |d + v t| = s
/// (physics.md (2.7)), the instant a disc leaves its neighbour-list skin.
///
/// With β = d·v, γ = |d|² − s² and D = β² − |v|² γ, for γ < 0 (inside) the root is
/// (−β + √D)/|v|² when β < 0 and −γ/(β + √D) when β ≥ 0, each without
/// cancellation. A disc at or beyond the circle (γ ≥ 0, by rounding) leaves now,
/// 0; a disc at rest never, +∞. Never NaN for finite input.
#[inline]
pub fn exit_time(d: DVec2, v: DVec2, s: f64) -> f64 {
    let beta = d.dot(v);
    let gamma = d.length_squared() - s * s;
    let vv = v.length_squared();
    let root = (beta * beta - vv * gamma).max(0.0).sqrt();
    let t = if beta < 0.0 {
        (root - beta) / vv
    } else {
        -gamma / (beta + root)
    };
    if gamma >= 0.0 {
        0.0
    } else if vv == 0.0 {
        f64::INFINITY
    } else {
        t
    }
}

/// Absolute angular tolerance (radians) of the seed form at its degenerate
/// boundaries: 4π machine epsilons, a bound on the rounding of a difference of two
/// `atan2` angles (each within an ulp of π) passed through `sin_cos`.
pub const SEED_ANGLE_TOLERANCE: f64 = 4.0 * std::f64::consts::PI * f64::EPSILON;

/// The seed's angular contact time (seed 000, Eq. 14–17), kept as a reference.
///
/// Disc 1 at `r1` with velocity `v1` and radius `a1`, disc 2 likewise. With
/// d = |r2 − r1|, γ_xy = atan2 of r2 − r1 (Eq. 16), γ_v = atan2 of v1 − v2 (Eq. 7) the
/// discs touch after
/// t = [d cos(γ_xy − γ_v) − √((a1+a2)² − (d sin(γ_xy − γ_v))²)] / |v1 − v2|  (Eq. 17),
/// defined only when |d sin(γ_xy − γ_v)| ≤ a1 + a2 (Eq. 14) and cos(γ_xy − γ_v) > 0
/// (the discs approach). `atan2` replaces the printed arctan of a ratio, which loses
/// the quadrant. The same rules as [`contact_time`] apply: overlapping and
/// approaching collides now, misses and receding pairs never.
///
/// The angle difference carries an absolute rounding error of a few ulps of 2π, so
/// the two degenerate boundaries are resolved with a documented angular tolerance
/// δγ = [`SEED_ANGLE_TOLERANCE`] (radians): motion within δγ of exactly sideways
/// (cos(γ_xy − γ_v) ≤ δγ, i.e. b ≈ 0) never meets, and an impact parameter
/// |d sin(γ_xy − γ_v)| within d δγ of σ is a grazing contact (Eq. 14 at equality).
pub fn contact_time_seed(
    r1: DVec2,
    v1: DVec2,
    a1: f64,
    r2: DVec2,
    v2: DVec2,
    a2: f64,
) -> Option<f64> {
    let sep = r2 - r1;
    let g = v1 - v2;
    let speed = g.length();
    if speed == 0.0 || !speed.is_finite() {
        return None;
    }
    let d = sep.length();
    let gamma_xy = sep.y.atan2(sep.x);
    let gamma_v = g.y.atan2(g.x);
    let (s, c) = (gamma_xy - gamma_v).sin_cos();
    if c <= SEED_ANGLE_TOLERANCE {
        return None; // receding or moving sideways
    }
    let sigma = a1 + a2;
    let h = d * s;
    if h.abs() > sigma + d * SEED_ANGLE_TOLERANCE {
        return None; // miss (Eq. 14 undefined)
    }
    let t = (d * c - (sigma * sigma - h * h).max(0.0).sqrt()) / speed;
    Some(t.max(0.0))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_disc_leaves_its_skin_where_its_line_crosses_the_circle() {
        // From the centre at speed 2 along x: |t v| = 0.3 at t = 0.15.
        assert_eq!(exit_time(DVec2::ZERO, DVec2::new(2.0, 0.0), 0.3), 0.15);
        // Across a chord: from (0, 0.1) heading −x then +x, the circle x² + 0.01 = 0.09
        // is reached at |x| = √0.08 either way.
        for vx in [-1.0, 1.0] {
            let t = exit_time(DVec2::new(0.0, 0.1), DVec2::new(vx, 0.0), 0.3);
            assert!((t - 0.08f64.sqrt()).abs() < 1e-15, "{t}");
        }
        // Moving inward from near the edge (β < 0): through the centre to the far side.
        let t = exit_time(DVec2::new(0.29, 0.0), DVec2::new(-1.0, 0.0), 0.3);
        assert!((t - 0.59).abs() < 1e-15, "{t}");
        // On or beyond the circle: now; at rest: never.
        assert_eq!(
            exit_time(DVec2::new(0.3, 0.0), DVec2::new(-1.0, 0.0), 0.3),
            0.0
        );
        assert_eq!(
            exit_time(DVec2::new(0.0, 0.31), DVec2::new(1.0, 0.0), 0.3),
            0.0
        );
        assert_eq!(
            exit_time(DVec2::new(0.1, 0.0), DVec2::ZERO, 0.3),
            f64::INFINITY
        );
        // The root lies on the circle, for random-looking directions and starts.
        for k in 0..200 {
            let a = k as f64 * 0.7;
            let d = DVec2::new(0.2 * (1.3 * a).cos(), 0.2 * (0.9 * a).sin());
            let v = DVec2::new(a.cos(), a.sin()) * (0.5 + k as f64 * 0.01);
            let t = exit_time(d, v, 0.3);
            assert!(
                t > 0.0 && ((d + v * t).length() - 0.3).abs() < 1e-15,
                "{k}: {t}"
            );
        }
    }

    #[test]
    fn head_on_pair_meets_when_gap_closes() {
        // Centres 3 apart, contact distance 1, closing speed 2: gap 2 closes at t = 1.
        let t = contact_time(DVec2::new(3.0, 0.0), DVec2::new(-2.0, 0.0), 1.0).unwrap();
        assert_eq!(t, 1.0);
    }

    #[test]
    fn receding_and_still_pairs_never_meet() {
        assert_eq!(
            contact_time(DVec2::new(3.0, 0.0), DVec2::new(2.0, 0.0), 1.0),
            None
        );
        assert_eq!(contact_time(DVec2::new(3.0, 0.0), DVec2::ZERO, 1.0), None);
    }

    #[test]
    fn overlapping_approaching_pair_collides_now() {
        let t = contact_time(DVec2::new(0.9, 0.0), DVec2::new(-1.0, 0.0), 1.0);
        assert_eq!(t, Some(0.0));
    }

    #[test]
    fn nan_never_comes_out() {
        assert_eq!(
            contact_time(DVec2::new(f64::NAN, 0.0), DVec2::new(-1.0, 0.0), 1.0),
            None
        );
        assert_eq!(
            contact_time(DVec2::new(2.0, 0.0), DVec2::new(f64::NAN, 0.0), 1.0),
            None
        );
    }

    #[test]
    fn branch_free_contact_time_is_the_contact_time() {
        // A deterministic sweep over geometries (overlaps, misses, grazing and
        // receding pairs, zero relative velocity): bit for bit the same time, +∞
        // for no contact.
        let mut k = 0u64;
        let mut next = || {
            k = k
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (k >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut met = 0;
        for n in 0..200_000 {
            let dr = DVec2::new(4.0 * next() - 2.0, 4.0 * next() - 2.0);
            let mut dv = DVec2::new(4.0 * next() - 2.0, 4.0 * next() - 2.0);
            if n % 97 == 0 {
                dv = DVec2::ZERO;
            }
            let expect = contact_time(dr, dv, 1.0).unwrap_or(f64::INFINITY);
            let got = contact_time_or_inf(dr, dv, 1.0);
            assert_eq!(got.to_bits(), expect.to_bits(), "{dr} {dv}");
            met += got.is_finite() as u32;
        }
        assert!(met > 10_000, "the sweep must contain meeting pairs: {met}");
        // Grazing exactly (D = 0), overlapping, receding and NaN.
        let graze = contact_time_or_inf(DVec2::new(3.0, 1.0), DVec2::new(-1.0, 0.0), 1.0);
        assert_eq!(graze, 3.0);
        let overlap = contact_time_or_inf(DVec2::new(0.9, 0.0), DVec2::new(-1.0, 0.0), 1.0);
        assert_eq!(overlap, 0.0);
        let away = contact_time_or_inf(DVec2::new(0.9, 0.0), DVec2::new(1.0, 0.0), 1.0);
        assert_eq!(away, f64::INFINITY);
        let nan = contact_time_or_inf(DVec2::new(f64::NAN, 0.0), DVec2::new(-1.0, 0.0), 1.0);
        assert_eq!(nan, f64::INFINITY);
    }

    #[test]
    fn offset_pair_misses_beyond_contact_distance() {
        // Impact parameter 1.5 > σ = 1: a miss.
        assert_eq!(
            contact_time(DVec2::new(5.0, 1.5), DVec2::new(-1.0, 0.0), 1.0),
            None
        );
    }
}
