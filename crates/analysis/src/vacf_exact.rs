//! The velocity autocorrelation function, its integral and the mean-square
//! displacement, exactly from the collision log (physics.md §14.1). Between
//! collisions every velocity is constant, so the state at any time t is known
//! without snapshots: v_i(t), and the displacement X_i(t) = X_i(t_i) + v_i (t − t_i)
//! from disc i's last collision t_i. From time origins t₀ (one every τ_max/P,
//! at most P alive) the state is read at lags τ on a log grid, giving per
//! species, exactly at those lags,
//!
//!   C(τ) = ⟨v_i(t₀)·v_i(t₀+τ)⟩,  ∫₀^τ C = ⟨v_i(t₀)·ΔX_i⟩,  MSD(τ) = ⟨|ΔX_i|²⟩,
//!
//! so D(τ) = ½ ∫₀^τ C (2D) needs no quadrature. Sums are kept per time segment
//! (by origin time) for standard errors.

use carom_core::DVec2;

/// One disc of the replayed run: velocity, displacement since the start at its
/// last collision `t`, mass and radius, side by side (one cache line: the
/// collisions visit discs at random).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Replayed {
    pub(super) v: DVec2,
    pub(super) x: DVec2,
    pub(super) t: f64,
    pub(super) mass: f64,
    pub(super) radius: f64,
}

impl Replayed {
    /// The displacement at time `now`.
    pub(super) fn x_at(&self, now: f64) -> DVec2 {
        self.x + self.v * (now - self.t)
    }
}

/// Lag points per decade.
pub(super) const PER_DECADE: usize = 10;

/// Sums at one lag for one species and segment.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct VacfSums {
    /// Disc-origins summed.
    pub(super) count: f64,
    /// Σ v_i(t₀)·v_i(t₀+τ), Σ v_i(t₀)·ΔX_i, Σ |ΔX_i|².
    pub(super) c: f64,
    pub(super) integral: f64,
    pub(super) msd: f64,
}

/// One live origin.
#[derive(Debug, Clone)]
struct Origin {
    t0: f64,
    segment: usize,
    /// Next lag index to read.
    next: usize,
    v0: Vec<DVec2>,
    x0: Vec<DVec2>,
}

/// The exact VACF over a run.
#[derive(Debug, Clone)]
pub(super) struct ExactVacf {
    /// τ_q: 0, then log-spaced from τ_min to τ_max.
    pub(super) lags: Vec<f64>,
    spacing: f64,
    next_origin: f64,
    /// The earliest of `next_origin` and the origins' next readings.
    next: f64,
    origins: Vec<Origin>,
    /// Origins started.
    pub(super) started: u64,
    t_first: f64,
    segment_length: f64,
    /// sums[lag][species][segment].
    pub(super) sums: Vec<Vec<Vec<VacfSums>>>,
}

impl ExactVacf {
    /// Origins from `t_first` on, every `tau_max / max_origins`, read at lags
    /// from `tau_min` to `tau_max`; `species` species, `segments` segments of
    /// `segment_length`.
    pub(super) fn new(
        t_first: f64,
        (tau_min, tau_max): (f64, f64),
        max_origins: usize,
        species: usize,
        (segments, segment_length): (usize, f64),
    ) -> Self {
        let decades = (tau_max / tau_min).log10().max(0.0);
        let points = (decades * PER_DECADE as f64).ceil() as usize;
        let mut lags = vec![0.0];
        lags.extend(
            (0..=points)
                .map(|q| tau_min * (tau_max / tau_min).powf(q as f64 / points.max(1) as f64)),
        );
        ExactVacf {
            sums: vec![vec![vec![VacfSums::default(); segments]; species]; lags.len()],
            lags,
            spacing: tau_max / max_origins as f64,
            next_origin: t_first,
            next: t_first,
            origins: Vec::new(),
            started: 0,
            t_first,
            segment_length,
        }
    }

    /// Time of the next reading (an origin's lag, or a new origin), if any.
    pub(super) fn next_event(&self) -> f64 {
        self.next
    }

    /// The next reading's time, from the origins.
    fn find_next(&self) -> f64 {
        let mut t = self.next_origin;
        for o in &self.origins {
            t = t.min(o.t0 + self.lags[o.next]);
        }
        t
    }

    /// Handles every reading due at or before `t` (before a collision at `t`),
    /// with the run's state `discs` and the species of each disc. Origins start only up to `t_stop`; each lives
    /// τ_max, so at most P + 1 are alive.
    pub(super) fn advance(&mut self, t: f64, t_stop: f64, discs: &[Replayed], species: &[u16]) {
        let lags = &self.lags;
        while self.next <= t {
            let now = self.next;
            let Some(k) = self.origins.iter().position(|o| o.t0 + lags[o.next] <= now) else {
                // A new origin (readings due at the same time came first).
                let x0 = discs.iter().map(|d| d.x_at(now)).collect();
                self.origins.push(Origin {
                    t0: now,
                    segment: ((now - self.t_first) / self.segment_length) as usize,
                    next: 0,
                    v0: discs.iter().map(|d| d.v).collect(),
                    x0,
                });
                self.started += 1;
                self.next_origin = self.t_first + self.started as f64 * self.spacing;
                if self.next_origin > t_stop {
                    self.next_origin = f64::INFINITY;
                }
                self.next = self.find_next();
                continue;
            };
            let o = &mut self.origins[k];
            let q = o.next;
            let segment = o.segment.min(self.sums[q][0].len() - 1);
            for (i, d) in discs.iter().enumerate() {
                let s = &mut self.sums[q][species[i] as usize][segment];
                let dx = d.x_at(now) - o.x0[i];
                s.count += 1.0;
                s.c += o.v0[i].dot(d.v);
                s.integral += o.v0[i].dot(dx);
                s.msd += dx.length_squared();
            }
            o.next += 1;
            if o.next == lags.len() {
                self.origins.swap_remove(k);
            }
            self.next = self.find_next();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn disc(v: DVec2, x: DVec2, t: f64) -> Replayed {
        Replayed {
            v,
            x,
            t,
            mass: 1.0,
            radius: 0.5,
        }
    }

    /// Two discs of two species flying freely with constant velocities: from
    /// every origin C(τ) = |v|², ∫₀^τ C = |v|² τ and MSD = |v|² τ², exactly at
    /// each lag. Origins every τ_max/P = 2.5 from 0 up to t_stop = 12: five of
    /// them, each read at every lag by t = 25.
    #[test]
    fn free_flight_gives_constant_c_linear_integral_and_ballistic_msd() {
        let v = [DVec2::new(1.0, 2.0), DVec2::new(-3.0, 0.5)];
        let x = [DVec2::new(0.3, -0.2), DVec2::new(4.0, 1.0)];
        let t_last = [0.0, -1.0];
        let discs: Vec<Replayed> = (0..2).map(|i| disc(v[i], x[i], t_last[i])).collect();
        let mut c = ExactVacf::new(0.0, (0.1, 10.0), 4, 2, (1, 100.0));
        assert_eq!(c.lags.len(), 1 + 21);
        assert!((c.lags[21] - 10.0).abs() < 1e-12);
        c.advance(25.0, 12.0, &discs, &[0, 1]);
        assert_eq!(c.started, 5);
        for (q, &tau) in c.lags.iter().enumerate() {
            for (s, v) in v.iter().enumerate() {
                let sums = c.sums[q][s][0];
                let v2 = v.length_squared();
                assert_eq!(sums.count, 5.0);
                assert!((sums.c - 5.0 * v2).abs() < 1e-12 * v2, "{q} {s}");
                let want = 5.0 * v2 * tau;
                assert!(
                    (sums.integral - want).abs() <= 1e-12 * (1.0 + want),
                    "{q} {s}"
                );
                let want = 5.0 * v2 * tau * tau;
                assert!((sums.msd - want).abs() <= 1e-11 * (1.0 + want), "{q} {s}");
            }
        }
    }

    /// A velocity that changes between two readings: from the origin at 0 with
    /// v = (1, 0), the disc turns to (0, 2) at t = 0.5 (as a collision would
    /// leave it); at lag τ ≥ 0.5, C = v(0)·v(τ) = 0, ∫C = 0.5, and
    /// MSD = 0.5² + (2(τ − 0.5))².
    #[test]
    fn a_turn_between_readings() {
        let mut c = ExactVacf::new(0.0, (0.1, 1.0), 1, 1, (1, 10.0));
        let mut d = [disc(DVec2::new(1.0, 0.0), DVec2::ZERO, 0.0)];
        c.advance(0.5, 0.0, &d, &[0]);
        d[0] = disc(DVec2::new(0.0, 2.0), d[0].x_at(0.5), 0.5);
        c.advance(2.0, 0.0, &d, &[0]);
        for (q, &tau) in c.lags.iter().enumerate() {
            let s = c.sums[q][0][0];
            assert_eq!(s.count, 1.0, "{q}");
            if tau > 0.5 {
                assert_eq!(s.c, 0.0);
                assert!((s.integral - 0.5).abs() < 1e-15);
                let want = 0.25 + (2.0 * (tau - 0.5)).powi(2);
                assert!((s.msd - want).abs() < 1e-14, "{q}");
            } else if tau < 0.5 {
                assert_eq!(s.c, 1.0);
                assert!((s.integral - tau).abs() < 1e-15);
            }
        }
    }
}
