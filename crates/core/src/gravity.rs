//! Free fall in a uniform field g along −y: heights and the exact times at which a
//! falling disc reaches a wall or a cell edge (physics.md §15).
//!
//! Between events a disc's height follows y(t) = y + u t − g t²/2 (§15.1). The time
//! at which it next rises through a line H above it, or comes down through a line h
//! below it, is a root of that quadratic, taken in the cancellation-free form of
//! §15.2 (the same device as the contact time of §2): never negative, never NaN,
//! and the right root even when rounding has put the disc a hair beyond the line —
//! a disc just below a floor it bounced from rises, so its next floor time is the
//! descending root, ≈ 2u/g, never the ascending one at ≈ 0. Relative motion of two
//! falling discs stays straight, so their contact times need nothing from here; a
//! disc resting on the floor (15.9) does not fall, and its contact with a falling
//! one is the quartic (15.10), solved by [`crate::roots::first_descent`].

use crate::boundary::WallSide;
use crate::roots::first_descent;
use glam::DVec2;

/// Height (length) after a time `t` of free fall from height `y` with upward
/// velocity `u` (length/time) in the field `g` (length/time²), physics.md (15.1):
/// y + u t − g t²/2.
#[inline]
pub fn fall_height(y: f64, u: f64, g: f64, t: f64) -> f64 {
    y + u * t - 0.5 * g * t * t
}

/// Time (≥ 0, or +∞) until a disc with upward velocity `u` in the field `g > 0`
/// rises through the line `h` above it (length; ≤ 0 when rounding left it beyond),
/// on its way up (physics.md (15.3)): t = 2h / (u + √(u² − 2 g h)), +∞ when it is
/// not rising (u ≤ 0) or turns below the line (u² < 2 g h); 0 when it is already
/// beyond and rising.
#[inline]
pub fn rise_time(h: f64, u: f64, g: f64) -> f64 {
    // Not rising (u ≤ 0, or NaN): never.
    if u.is_nan() || u <= 0.0 {
        return f64::INFINITY;
    }
    let d = u * u - 2.0 * g * h;
    if d.is_nan() || d < 0.0 {
        return f64::INFINITY;
    }
    // u + √d > 0: no cancellation, no division by zero.
    (2.0 * h / (u + d.sqrt())).max(0.0)
}

/// Time (≥ 0, finite for g > 0) until a disc with upward velocity `u` in the field
/// `g > 0` comes down through the line `h` below it (length; ≤ 0 when rounding left
/// it beyond), on its way down: the descending root of h + u t − g t²/2 = 0
/// (physics.md (15.4)), 2h / (√(u² + 2 g h) − u) when falling (u < 0),
/// (u + √(u² + 2 g h))/g when rising or at the apex. When rounding left the disc
/// below a line it never rises above again (u² + 2 g h < 0), the apex time u/g.
#[inline]
pub fn fall_time(h: f64, u: f64, g: f64) -> f64 {
    let s = (u * u + 2.0 * g * h).max(0.0).sqrt();
    if u < 0.0 {
        // s − u ≥ −u > 0: no cancellation; h ≤ 0 (beyond, falling) gives now.
        (2.0 * h / (s - u)).max(0.0)
    } else {
        // Rising or at the apex (or NaN, which ends at 0 below).
        let t = (u + s) / g;
        if t.is_nan() {
            0.0
        } else {
            t
        }
    }
}

/// The next wall hit along y of a disc of radius `a` at height `y` with upward
/// velocity `u` between hard walls at 0 and `l`, in the field `g > 0`: (time from
/// now, side). The floor (centre at a) is always reached, by [`fall_time`]; the
/// ceiling (centre at l − a) first when the disc rises that far, by [`rise_time`].
#[inline]
pub fn wall_time_falling(y: f64, u: f64, a: f64, l: f64, g: f64) -> (f64, WallSide) {
    let up = rise_time(l - a - y, u, g);
    let down = fall_time(y - a, u, g);
    if up < down {
        (up, WallSide::High)
    } else {
        (down, WallSide::Low)
    }
}

/// The next crossing of a cell edge along y of a disc at height `y` with upward
/// velocity `u`, in a cell spanning [`lower`, `upper`) of which an edge that is a
/// wall is never crossed (`open` = [lower open, upper open]): (time from now, up),
/// +∞ when neither edge is ever crossed. Rising to the upper edge comes first when
/// it happens at all; otherwise the disc turns at its apex and falls through the
/// lower one.
#[inline]
pub fn crossing_time_falling(
    y: f64,
    u: f64,
    [lower, upper]: [f64; 2],
    open: [bool; 2],
    g: f64,
) -> (f64, bool) {
    let up = if open[1] {
        rise_time(upper - y, u, g)
    } else {
        f64::INFINITY
    };
    if up < f64::INFINITY {
        return (up, true);
    }
    let down = if open[0] {
        fall_time(y - lower, u, g)
    } else {
        f64::INFINITY
    };
    (down, false)
}

/// Whether a disc of radius `a` that leaves a static floor with upward velocity
/// `u` (length/time) in the field `g > 0` comes to rest on it (physics.md (15.9)):
/// when its apex a + u²/(2g) rounds to a, its height never differs from the
/// floor's as a number, and the bounce (of period 2u/g, ≲ 10⁻⁸ √(a/g)) would only
/// repeat at once for ever. True for u = 0; a NaN never rests.
#[inline]
pub fn rebound_rests(a: f64, u: f64, g: f64) -> bool {
    a + u * u / (2.0 * g) == a
}

/// Time (≥ 0, or +∞) until two discs at contact distance `sigma` meet when one
/// rests on the floor and the other falls: j seen from i at `dr` = r_j − r_i with
/// relative velocity `dv` = v_j − v_i (true ones, now) and relative acceleration
/// `accel` ŷ (−g when j falls, +g when i does). The first approaching root of
/// physics.md (15.10),
/// |dr + dv t + ½ accel t² ŷ|² − σ² = c0 + 2 (dr·dv) t + (|dv|² + accel dr_y) t²
///                                   + accel dv_y t³ + accel²/4 t⁴ = 0,
/// by [`first_descent`]: never in the past, never NaN; a pair that rounding left
/// overlapping meets now if it approaches, and a pair touching now and separating
/// is met again only when it comes back.
pub fn contact_time_one_falling(dr: DVec2, dv: DVec2, sigma: f64, accel: f64) -> f64 {
    first_descent([
        dr.length_squared() - sigma * sigma,
        2.0 * dr.dot(dv),
        dv.length_squared() + accel * dr.y,
        accel * dv.y,
        0.25 * accel * accel,
    ])
}

/// The barometric β_g = m g/kT (1/length) whose law n ∝ exp(−β_g (y − a)),
/// truncated to centres in [a, a + `span`], has mean height `mean` above a
/// (length): the maximum-likelihood fit of physics.md (15.8),
/// mean = 1/β − D e^{−βD}/(1 − e^{−βD}) with D = `span`, solved by bisection on
/// ln β. 0 for a uniform profile (mean ≥ D/2), +∞ for mean ≤ 0; NaN for NaN input.
pub fn barometric_beta(mean: f64, span: f64) -> f64 {
    if mean.is_nan() || span.is_nan() {
        return f64::NAN;
    }
    if mean <= 0.0 {
        return f64::INFINITY;
    }
    if mean >= 0.5 * span {
        return 0.0;
    }
    // The truncated mean, decreasing in β from D/2 (β → 0) to 1/β (β D ≫ 1).
    let truncated = |b: f64| {
        let x = b * span;
        if x < 1e-6 {
            span * (0.5 - x / 12.0)
        } else {
            1.0 / b - span / x.exp_m1()
        }
    };
    let (mut lo, mut hi) = ((1e-12 / span).ln(), (1e12 / mean).ln());
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if truncated(mid.exp()) > mean {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    (0.5 * (lo + hi)).exp()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// β = 0.1 on a span of 30: the truncated mean is 10 − 30/(e³ − 1) = 8.4281…,
    /// and the fit gives β back; a very tall span gives 1/mean.
    #[test]
    fn the_barometric_fit_inverts_the_truncated_mean() {
        let mean = 10.0 - 30.0 / 3f64.exp_m1();
        assert!((barometric_beta(mean, 30.0) - 0.1).abs() < 1e-12);
        assert!((barometric_beta(5.0, 1e6) - 0.2).abs() < 1e-12);
        assert_eq!(barometric_beta(20.0, 30.0), 0.0);
        assert_eq!(barometric_beta(0.0, 30.0), f64::INFINITY);
    }

    /// Dropped from rest at height 2 with g = 1: it falls 2 in t = 2 (2 = t²/2).
    #[test]
    fn a_dropped_disc_falls_by_g_t_squared_over_two() {
        assert_eq!(fall_time(2.0, 0.0, 1.0), 2.0);
        assert_eq!(fall_height(2.0, 0.0, 1.0, 2.0), 0.0);
        // Thrown up at 3 from the line with g = 2: back after 2u/g = 3.
        assert_eq!(fall_time(0.0, 3.0, 2.0), 3.0);
        // Thrown down at −1 from height 1.5 with g = 1: 1.5 = t + t²/2, t = 1.
        assert_eq!(fall_time(1.5, -1.0, 1.0), 1.0);
    }

    /// Rising at 2 with g = 1: it reaches 1.5 at t = 1 (2 − 1/2), the apex 2 at
    /// t = 2, and never 2.5.
    #[test]
    fn a_rising_disc_reaches_lines_below_its_apex() {
        assert_eq!(rise_time(1.5, 2.0, 1.0), 1.0);
        assert_eq!(rise_time(2.0, 2.0, 1.0), 2.0);
        assert_eq!(rise_time(2.5, 2.0, 1.0), f64::INFINITY);
        assert_eq!(rise_time(0.5, -1.0, 1.0), f64::INFINITY);
        assert_eq!(rise_time(0.5, 0.0, 1.0), f64::INFINITY);
    }

    /// A disc that rounding left 10⁻¹⁶ below the floor it just bounced from, rising
    /// at 1: its next floor hit is the descending root ≈ 2u/g = 2, not now.
    #[test]
    fn a_disc_just_below_the_floor_after_a_bounce_comes_back_after_2u_over_g() {
        let t = fall_time(-1e-16, 1.0, 1.0);
        assert!((t - 2.0).abs() < 1e-15, "{t}");
        // Falling and below: now.
        assert_eq!(fall_time(-1e-16, -1.0, 1.0), 0.0);
        // Rising above the ceiling line by rounding: now.
        assert_eq!(rise_time(-1e-16, 1.0, 1.0), 0.0);
        // Below a line and never rising above it: the apex.
        assert_eq!(fall_time(-1.0, 1.0, 1.0), 1.0);
    }

    /// Skimming: a disc 10⁻³⁰⁰ above the floor rising at 10⁻¹⁰ comes back after
    /// 2 × 10⁻¹⁰; nothing is NaN or negative at the extremes.
    #[test]
    fn extreme_inputs_give_no_nan_and_nothing_in_the_past() {
        assert!((fall_time(1e-300, 1e-10, 1.0) - 2e-10).abs() < 1e-25);
        for h in [0.0, -0.0, 1e-300, -1e-300, 1.0, -1.0, 1e300] {
            for u in [0.0, -0.0, 1e-300, -1e-300, 1.0, -1.0, 1e150, -1e150] {
                for g in [1e-300, 1.0, 1e300] {
                    let (f, r) = (fall_time(h, u, g), rise_time(h, u, g));
                    assert!(f >= 0.0 && r >= 0.0, "h {h} u {u} g {g}: {f} {r}");
                }
            }
        }
    }

    /// A disc at rest (u = 0) rests; one leaving at 10⁻⁹ rounds its apex
    /// 0.5 + 5·10⁻¹⁹ to 0.5 and rests; at 10⁻⁶ (apex 5·10⁻¹³ above) it bounces.
    #[test]
    fn a_rebound_whose_apex_rounds_to_the_floor_rests() {
        assert!(rebound_rests(0.5, 0.0, 1.0));
        assert!(rebound_rests(0.5, -0.0, 1.0));
        assert!(rebound_rests(0.5, 1e-9, 1.0));
        assert!(!rebound_rests(0.5, 1e-6, 1.0));
        assert!(!rebound_rests(0.5, f64::NAN, 1.0));
        assert!(!rebound_rests(0.5, 1e200, 1.0));
    }

    /// j dropped from rest with its centre at (0.3, 3) onto i resting at the origin
    /// (σ = 1, g = 1): they touch when (3 − t²/2)² + 0.09 = 1, t = √(2 (3 − √0.91)).
    /// Seen from j (accel +g) the same time. The brute-force check: |Δr(t)| − σ
    /// stepped by 10⁻⁶ changes sign within one step of it.
    #[test]
    fn a_disc_dropped_onto_a_resting_one_meets_it_at_the_root_of_the_quartic() {
        let (dr, sigma, g) = (DVec2::new(0.3, 3.0), 1.0, 1.0);
        let exact = (2.0 * (3.0 - 0.91f64.sqrt())).sqrt();
        let t = contact_time_one_falling(dr, DVec2::ZERO, sigma, -g);
        assert!((t - exact).abs() < 1e-14, "{t} vs {exact}");
        let t_j = contact_time_one_falling(-dr, DVec2::ZERO, sigma, g);
        assert!((t_j - exact).abs() < 1e-14, "{t_j}");
        let gap = |t: f64| (dr + DVec2::new(0.0, -0.5 * g * t * t)).length() - sigma;
        let step = 1e-6;
        let first = (0..)
            .map(|k| k as f64 * step)
            .find(|&t| gap(t) <= 0.0)
            .unwrap();
        assert!(
            first >= t && first - t <= step,
            "brute force {first}, root {t}"
        );
    }

    /// Thrown up past the resting disc, side by side: j at (1.5, 0) rising at 2
    /// with i resting at the origin (σ = 1) never touches (always 1.5 apart in x);
    /// j leaving i upwards after a collision (touching, dr = (0, 1), rising at 1)
    /// comes back down onto it after 2u/g = 2, not at once; overlapping by rounding
    /// and approaching: now.
    #[test]
    fn separating_pairs_come_back_and_misses_never_meet() {
        let t = contact_time_one_falling(DVec2::new(1.5, 0.0), DVec2::new(0.0, 2.0), 1.0, -1.0);
        assert_eq!(t, f64::INFINITY);
        let t = contact_time_one_falling(DVec2::new(0.0, 1.0), DVec2::new(0.0, 1.0), 1.0, -1.0);
        assert!((t - 2.0).abs() < 1e-14, "{t}");
        let t = contact_time_one_falling(
            DVec2::new(0.0, 1.0 - 1e-16),
            DVec2::new(0.0, -1.0),
            1.0,
            -1.0,
        );
        assert_eq!(t, 0.0);
        for accel in [-1e300, -1.0, -1e-300, 1e-300, 1.0, 1e300] {
            for v in [0.0, 1e-300, 1.0, 1e150] {
                let t =
                    contact_time_one_falling(DVec2::new(0.5, 2.0), DVec2::new(v, -v), 1.0, accel);
                assert!(t >= 0.0, "accel {accel} v {v}: {t}");
            }
        }
    }

    /// Between walls at 0 and 10 (radius 0.5), g = 1: from 5 rising at 1 the floor
    /// comes first (apex 5.5); rising at 4 the ceiling (9.5 − 5 = 4.5 = 4t − t²/2,
    /// t = 4 − √7).
    #[test]
    fn the_ceiling_only_when_the_apex_reaches_it() {
        let (t, side) = wall_time_falling(5.0, 1.0, 0.5, 10.0, 1.0);
        assert_eq!(side, WallSide::Low);
        assert!((t - (1.0 + 10f64.sqrt())).abs() < 1e-14, "{t}");
        let (t, side) = wall_time_falling(5.0, 4.0, 0.5, 10.0, 1.0);
        assert_eq!(side, WallSide::High);
        assert!((t - (4.0 - 7f64.sqrt())).abs() < 1e-14, "{t}");
    }

    /// A cell [1, 2) entered at 1.5 rising at 0.5 with g = 1: the apex 1.625 is
    /// inside, so it falls out of the bottom when 0.5 = −0.5 t + t²/2, t = (1 + √5)/2;
    /// with the bottom a wall it never crosses.
    #[test]
    fn a_cell_crossing_at_the_top_of_a_parabola_goes_down() {
        let (t, up) = crossing_time_falling(1.5, 0.5, [1.0, 2.0], [true, true], 1.0);
        assert!(!up);
        assert!((t - (1.0 + 5f64.sqrt()) / 2.0).abs() < 1e-15, "{t}");
        let (t, _) = crossing_time_falling(1.5, 0.5, [1.0, 2.0], [false, true], 1.0);
        assert_eq!(t, f64::INFINITY);
        // Rising at 1.5: up through 2 at 0.5 = 1.5 t − t²/2, t = 1.5 − √1.25.
        let (t, up) = crossing_time_falling(1.5, 1.5, [1.0, 2.0], [true, true], 1.0);
        assert!(up);
        assert!((t - (1.5 - 1.25f64.sqrt())).abs() < 1e-15, "{t}");
    }
}
