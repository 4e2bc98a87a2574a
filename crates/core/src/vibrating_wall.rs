//! A floor that oscillates: its height, its velocity, the time at which a disc
//! (falling or flying straight) first touches it, and the bounce (physics.md §18).
//!
//! The floor's height is h(t) = A (1 − cos ω t) = 2A sin²(ω t/2) (18.1), t the time
//! since it was set, so it starts at rest at 0 and stays in [0, 2A]. A disc of
//! radius a touches it when f(t) = y(t) − a − h(t) reaches 0 (18.2). There is no
//! closed form, so the root is found by conservative advancement (18.3): with
//! M = g + A ω² ≥ |f''|, from a point with f > 0 no root lies closer than the
//! positive root δ of f + f' δ − M δ²/2 = 0, so stepping by δ never steps over one
//! and converges on the first root from the safe side (like Newton's method for a
//! crossing). The bounce reverses the velocity relative to the floor (18.4).

/// The floor's motion: amplitude A (length) and angular frequency ω (1/time).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Floor {
    /// Amplitude A (length): the floor moves between 0 and 2A.
    pub amplitude: f64,
    /// Angular frequency ω = 2π f (1/time).
    pub omega: f64,
}

/// What the search for a disc's next floor contact found.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum FloorContact {
    /// The disc touches the floor after this time (≥ 0) from now.
    At(f64),
    /// No contact up to this time (> 0) from now, where the search stopped at its
    /// step limit: look again from there.
    NotBefore(f64),
    /// No contact before the horizon.
    Beyond,
}

/// Steps of the root search before it hands back [`FloorContact::NotBefore`].
pub const MAX_STEPS: usize = 64;

impl Floor {
    /// Height h(t) = 2A sin²(ω t/2) (length) at time `t` since the floor was set
    /// (physics.md (18.1); the sine form keeps relative precision near 0).
    #[inline]
    pub fn height(&self, t: f64) -> f64 {
        let s = (0.5 * self.omega * t).sin();
        2.0 * self.amplitude * s * s
    }

    /// Velocity h'(t) = A ω sin ω t (length/time) at time `t` since it was set.
    #[inline]
    pub fn velocity(&self, t: f64) -> f64 {
        self.amplitude * self.omega * (self.omega * t).sin()
    }

    /// The bound M = g + A ω² ≥ |f''| (length/time²) on the curvature of the gap
    /// between the floor and a disc falling in the field `g` (physics.md (18.3)).
    #[inline]
    pub fn curvature_bound(&self, g: f64) -> f64 {
        g + self.amplitude * self.omega * self.omega
    }

    /// The first time from now at which a disc of radius `a` at height `y` with
    /// upward velocity `u`, in the field `g` (≥ 0), touches the floor, whose phase
    /// (time since it was set) is `phase` now; searched up to `horizon` (time from
    /// now; the disc's next other event), by conservative advancement
    /// (physics.md (18.3)). Never NaN, never negative.
    ///
    /// A disc within rounding of the floor and approaching it (or at rest on it)
    /// touches it now; one within rounding and leaving is first carried to where
    /// the gap's lower bound peaks, f'/M later.
    pub fn contact_time(
        &self,
        y: f64,
        u: f64,
        a: f64,
        g: f64,
        phase: f64,
        horizon: f64,
    ) -> FloorContact {
        let m = self.curvature_bound(g);
        let gap = |t: f64| {
            let fall = u * t - 0.5 * g * t * t;
            let f = y + fall - a - self.height(phase + t);
            // What rounding can hide in f (length).
            let tol = 4.0 * f64::EPSILON * (y.abs() + fall.abs() + a + 2.0 * self.amplitude);
            (f, u - g * t - self.velocity(phase + t), tol)
        };
        let (mut t, (mut f, mut fp, mut tol)) = (0.0, gap(0.0));
        if !(f.is_finite() && fp.is_finite()) {
            return FloorContact::Beyond;
        }
        if f <= tol && fp > 0.0 {
            // Leaving: the gap is at least f + f' s − M s²/2, rising until s = f'/M.
            t = fp / m;
            (f, fp, tol) = gap(t);
        }
        for _ in 0..MAX_STEPS {
            if t >= horizon {
                return FloorContact::Beyond;
            }
            if f <= tol {
                return FloorContact::At(t);
            }
            // Positive root of f + f' δ − M δ²/2 = 0, in the form without
            // cancellation for the sign of f' (√D ≥ |f'|).
            let root = (fp * fp + 2.0 * m * f).sqrt();
            let step = if fp >= 0.0 {
                (fp + root) / m
            } else {
                2.0 * f / (root - fp)
            };
            let next = t + step;
            if next <= t || next.is_nan() {
                // The step is below the clock's resolution: touching to rounding.
                return if t >= horizon {
                    FloorContact::Beyond
                } else {
                    FloorContact::At(t)
                };
            }
            t = next;
            (f, fp, tol) = gap(t);
        }
        if t >= horizon {
            FloorContact::Beyond
        } else {
            FloorContact::NotBefore(t)
        }
    }
}

/// A disc's upward velocity after bouncing with restitution `e` off a floor moving
/// up at `w` (length/time), from `v` (physics.md (18.4)): w − e (v − w) when it
/// approaches (v < w), unchanged otherwise.
#[inline]
pub fn bounce(v: f64, w: f64, e: f64) -> f64 {
    if v < w {
        w - e * (v - w)
    } else {
        v
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    /// The first root of the gap, found independently: the first sign change on a
    /// grid of 10⁶ points up to `end`, then bisection to the last bit.
    fn reference(fl: &Floor, y: f64, u: f64, a: f64, g: f64, phase: f64, end: f64) -> f64 {
        let f = |t: f64| y + u * t - 0.5 * g * t * t - a - fl.height(phase + t);
        let n = 1_000_000;
        let mut lo = 0.0;
        for k in 1..=n {
            let t = end * k as f64 / n as f64;
            if f(t) <= 0.0 {
                let mut hi = t;
                for _ in 0..200 {
                    let mid = 0.5 * (lo + hi);
                    if f(mid) > 0.0 {
                        lo = mid;
                    } else {
                        hi = mid;
                    }
                }
                return hi;
            }
            lo = t;
        }
        f64::INFINITY
    }

    /// Without a field, a disc at rest at height a + A is reached when the floor
    /// rises through A, at ω t = π/2.
    #[test]
    fn the_floor_reaches_a_resting_disc_at_a_quarter_period() {
        let fl = Floor {
            amplitude: 0.25,
            omega: 2.0 * PI,
        };
        let FloorContact::At(t) = fl.contact_time(0.5 + 0.25, 0.0, 0.5, 0.0, 0.0, 10.0) else {
            panic!("no contact");
        };
        assert!((t - 0.25).abs() < 1e-14, "{t}");
        assert_eq!(fl.height(0.5), 0.5);
        assert!((fl.velocity(0.25) - 0.5 * PI).abs() < 1e-15);
    }

    /// A disc dropped from rest at height 2 + a with g = 1 on a floor of
    /// amplitude 10⁻¹² falls for t = 2 as on a fixed floor (to 10⁻¹¹).
    #[test]
    fn a_tiny_amplitude_is_a_fixed_floor() {
        let fl = Floor {
            amplitude: 1e-12,
            omega: 3.0,
        };
        let FloorContact::At(t) = fl.contact_time(2.5, 0.0, 0.5, 1.0, 0.0, 10.0) else {
            panic!("no contact");
        };
        assert!((t - 2.0).abs() < 1e-11, "{t}");
    }

    /// Falling and thrown discs, on floors of several phases, with and without a
    /// field: the time agrees with the independent grid-and-bisection root to
    /// 10⁻¹², or both say there is none before the horizon.
    #[test]
    fn contact_times_agree_with_bisection() {
        let fl = Floor {
            amplitude: 0.5,
            omega: 2.0 * PI * 1.3,
        };
        for &(y, u, g, phase) in &[
            (2.0, 0.0, 1.0, 0.0),
            (2.0, -1.0, 1.0, 0.3),
            (1.5, 2.0, 9.81, 0.77),
            (1.2, -0.1, 0.0, 0.1),
            (1.7, 0.5, 2.0, 0.6),
            (3.0, 0.3, 0.0, 0.0),
        ] {
            let want = reference(&fl, y, u, 0.5, g, phase, 5.0);
            let mut t0 = 0.0;
            let got = loop {
                // Look again where the search stopped, as the engine does.
                let (yy, uu) = (y + u * t0 - 0.5 * g * t0 * t0, u - g * t0);
                match fl.contact_time(yy, uu, 0.5, g, phase + t0, 5.0 - t0) {
                    FloorContact::At(t) => break t0 + t,
                    FloorContact::NotBefore(t) => t0 += t,
                    FloorContact::Beyond => break f64::INFINITY,
                }
            };
            if want.is_finite() {
                assert!(
                    (got - want).abs() < 1e-12,
                    "{y} {u} {g} {phase}: {got} vs {want}"
                );
            } else {
                assert_eq!(got, f64::INFINITY, "{y} {u} {g} {phase}");
            }
        }
    }

    /// A disc just above the floor and leaving is carried on, not hit now; one
    /// within rounding and approaching is hit now; nothing is NaN or negative.
    #[test]
    fn near_the_floor_it_leaves_or_touches_now() {
        let fl = Floor {
            amplitude: 0.1,
            omega: 5.0,
        };
        // On the floor at rest at phase 0, thrown up at 1 with g = 1: back after
        // about 2 (the floor moves by at most 0.2).
        match fl.contact_time(0.5, 1.0, 0.5, 1.0, 0.0, 100.0) {
            FloorContact::At(t) | FloorContact::NotBefore(t) => assert!(t > 1.0, "{t}"),
            FloorContact::Beyond => panic!("beyond"),
        }
        assert_eq!(
            fl.contact_time(0.5 - 1e-17, -1.0, 0.5, 1.0, 0.0, 100.0),
            FloorContact::At(0.0)
        );
        for y in [0.5, 0.6, 1e3] {
            for u in [-1e3, -1.0, 0.0, 1.0, 1e3] {
                for g in [0.0, 1.0] {
                    match fl.contact_time(y, u, 0.5, g, 1.7, 50.0) {
                        FloorContact::At(t) | FloorContact::NotBefore(t) => {
                            assert!(t >= 0.0, "{y} {u} {g}: {t}")
                        }
                        FloorContact::Beyond => {}
                    }
                }
            }
        }
    }

    /// In the floor's frame the relative velocity is reversed and scaled by e: a
    /// disc at −1 on a floor rising at 2 leaves at 2 + 0.5 × 3 = 3.5 with e = 0.5;
    /// a disc outrunning the floor is left alone.
    #[test]
    fn the_bounce_reverses_the_velocity_relative_to_the_floor() {
        assert_eq!(bounce(-1.0, 2.0, 0.5), 3.5);
        assert_eq!(bounce(-1.0, 0.0, 1.0), 1.0);
        assert_eq!(bounce(3.0, 2.0, 1.0), 3.0);
    }
}
