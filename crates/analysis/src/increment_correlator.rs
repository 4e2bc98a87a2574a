//! Fixed-memory statistics of a series G sampled every Δ (the Helfand moments of
//! physics.md §14) at lags τ = m·2^ℓ·Δ: the mean square increment
//!     ⟨[G(t+τ) − G(t)]²⟩ (Einstein–Helfand),
//! and ⟨J(t) J(t+τ)⟩ of the flux J = ΔG/Δt (Green–Kubo). No mean is subtracted
//! (the fluxes have zero mean by symmetry; a segment's own mean would bias it
//! low by about τ/segment, §14.2). Level ℓ keeps every 2^ℓ-th sample in a ring
//! of p + 1: a new value pairs with m = 1..p−1 back on level 0 and m = p/2..p−1
//! on higher levels, so lags grow geometrically in levels × p memory. Values
//! are decimated, not averaged, so every increment is exact. Sums are kept per
//! time segment, for errors from their spread.

/// Samples kept per level (the lag resolution: p/2 lags per octave).
pub(super) const RING: usize = 16;

/// The sums at one lag.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct LagSums {
    pub(super) count: f64,
    /// Σ ΔG, Σ ΔG².
    pub(super) inc: f64,
    pub(super) inc2: f64,
    /// Pairs of fluxes (one fewer than increments at the start).
    pub(super) flux_count: f64,
    /// Σ J_now·J_then, Σ J_now, Σ J_then.
    pub(super) flux2: f64,
    pub(super) flux_now: f64,
    pub(super) flux_then: f64,
}

impl LagSums {
    /// ⟨ΔG²⟩ at this lag (Var[ΔG], as ⟨ΔG⟩ = 0), or `None` without data.
    pub(super) fn increment_mean_square(&self) -> Option<f64> {
        (self.count > 0.0).then(|| self.inc2 / self.count)
    }

    /// ⟨J(t) J(t+τ)⟩ at this lag (the covariance, as ⟨J⟩ = 0), or `None`
    /// without data.
    pub(super) fn flux_product(&self) -> Option<f64> {
        (self.flux_count > 0.0).then(|| self.flux2 / self.flux_count)
    }
}

/// One lag of the correlator.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Lag {
    pub(super) level: usize,
    pub(super) m: usize,
    /// τ = m·2^ℓ·Δ (time).
    pub(super) tau: f64,
}

/// The correlator of one series.
#[derive(Debug, Clone)]
pub(super) struct IncrementCorrelator {
    dt: f64,
    /// Per level: ring of the last RING + 1 values, and how many were pushed.
    rings: Vec<([f64; RING + 1], u64)>,
    /// sums[level][m][segment].
    sums: Vec<Vec<Vec<LagSums>>>,
    segments: usize,
}

impl IncrementCorrelator {
    /// A correlator of samples `dt` apart, with `levels` levels and `segments`
    /// time segments.
    pub(super) fn new(dt: f64, levels: usize, segments: usize) -> Self {
        IncrementCorrelator {
            dt,
            rings: vec![([0.0; RING + 1], 0); levels],
            sums: vec![vec![vec![LagSums::default(); segments]; RING]; levels],
            segments,
        }
    }

    /// The lags, in increasing τ: level 0 from m = 0 (the flux variance; the
    /// increment is 0 there), higher levels from m = p/2.
    pub(super) fn lags(&self) -> Vec<Lag> {
        (0..self.rings.len())
            .flat_map(|level| {
                let lo = if level == 0 { 0 } else { RING / 2 };
                (lo..RING).map(move |m| Lag {
                    level,
                    m,
                    tau: m as f64 * (1u64 << level) as f64 * self.dt,
                })
            })
            .collect()
    }

    /// The sums at `lag` in `segment`.
    pub(super) fn sums(&self, lag: Lag, segment: usize) -> LagSums {
        self.sums[lag.level][lag.m][segment]
    }

    /// The sums at `lag` over all segments.
    pub(super) fn total(&self, lag: Lag) -> LagSums {
        let mut t = LagSums::default();
        for s in &self.sums[lag.level][lag.m] {
            t.count += s.count;
            t.inc += s.inc;
            t.inc2 += s.inc2;
            t.flux_count += s.flux_count;
            t.flux2 += s.flux2;
            t.flux_now += s.flux_now;
            t.flux_then += s.flux_then;
        }
        t
    }

    /// Number of segments.
    pub(super) fn segments(&self) -> usize {
        self.segments
    }

    /// The next sample of G, taken in time segment `segment`.
    pub(super) fn push(&mut self, g: f64, segment: usize) {
        let segment = segment.min(self.segments - 1);
        for level in 0..self.rings.len() {
            let h = (1u64 << level) as f64 * self.dt;
            let (ring, pushed) = &mut self.rings[level];
            let n = *pushed as usize;
            // ring[(n - k) % (RING + 1)] holds the value k pushes back.
            let back = |k: usize| ring[(n + RING + 1 - k) % (RING + 1)];
            if n >= 1 {
                let j_now = (g - back(1)) / h;
                let lo = if level == 0 { 0 } else { RING / 2 };
                for m in lo.max(1)..RING.min(n + 1) {
                    let inc = g - back(m);
                    let s = &mut self.sums[level][m][segment];
                    s.count += 1.0;
                    s.inc += inc;
                    s.inc2 += inc * inc;
                    if n > m {
                        let j_then = (back(m) - back(m + 1)) / h;
                        s.flux_count += 1.0;
                        s.flux2 += j_now * j_then;
                        s.flux_now += j_now;
                        s.flux_then += j_then;
                    }
                }
                if level == 0 {
                    let s = &mut self.sums[0][0][segment];
                    s.count += 1.0;
                    s.flux_count += 1.0;
                    s.flux2 += j_now * j_now;
                    s.flux_now += j_now;
                    s.flux_then += j_now;
                }
            }
            ring[n % (RING + 1)] = g;
            *pushed += 1;
            // Values 0, 2, 4, … of this level go on to the next.
            if *pushed % 2 == 0 {
                break;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The lags: level 0 at m·Δ for m = 0..p−1, then m·2^ℓ·Δ for m = p/2..p−1,
    /// strictly increasing.
    #[test]
    fn lags_grow_geometrically_without_overlap() {
        let c = IncrementCorrelator::new(0.5, 3, 1);
        let taus: Vec<f64> = c.lags().iter().map(|l| l.tau).collect();
        assert_eq!(taus.len(), RING + 2 * (RING / 2));
        assert_eq!(taus[0], 0.0);
        assert_eq!(taus[RING - 1], (RING - 1) as f64 * 0.5);
        // Level 1 starts at (p/2)·2·Δ = p·Δ.
        assert_eq!(taus[RING], RING as f64 * 0.5);
        assert_eq!(*taus.last().unwrap(), (RING - 1) as f64 * 4.0 * 0.5);
        assert!(taus.windows(2).all(|w| w[1] > w[0]));
    }

    /// G = a·n² sampled at n = 0..99 (Δ = 1): the increment over m at origin n
    /// is a(2nm + m²); its sums over all origins with n + m ≤ 99 are worked here
    /// directly and must match, on level 0 and on level 1 (decimated: every
    /// second sample, n even).
    #[test]
    fn increments_of_a_parabola_match_direct_sums() {
        let a = 0.3;
        let mut c = IncrementCorrelator::new(1.0, 2, 1);
        for n in 0..100 {
            c.push(a * (n * n) as f64, 0);
        }
        let g = |n: usize| a * (n * n) as f64;
        for lag in c.lags() {
            if lag.m == 0 {
                continue;
            }
            let step = 1usize << lag.level;
            let span = lag.m * step;
            let (mut count, mut s1, mut s2) = (0.0, 0.0, 0.0);
            let mut n = 0;
            while n + span < 100 {
                let d = g(n + span) - g(n);
                count += 1.0;
                s1 += d;
                s2 += d * d;
                n += step;
            }
            let t = c.total(lag);
            assert_eq!(t.count, count, "{lag:?}");
            assert!((t.inc - s1).abs() <= 1e-9 * s1.abs(), "{lag:?}");
            assert!((t.inc2 - s2).abs() <= 1e-9 * s2.abs(), "{lag:?}");
        }
    }

    /// A series whose flux alternates +1, −1 (G = 0, 1, 0, 1, …, Δ = 1): the flux
    /// product at lag m is (−1)^m, 1 at m = 0; the increment over an even lag is
    /// 0, over an odd one ±1 (mean square 1).
    #[test]
    fn flux_of_an_alternating_series() {
        let mut c = IncrementCorrelator::new(1.0, 1, 1);
        for n in 0..1000 {
            c.push((n % 2) as f64, 0);
        }
        for lag in c.lags() {
            let t = c.total(lag);
            let cov = t.flux_product().unwrap();
            let want = if lag.m % 2 == 0 { 1.0 } else { -1.0 };
            assert!((cov - want).abs() < 1e-12, "lag {}: {cov}", lag.m);
            if lag.m > 0 {
                let var = t.increment_mean_square().unwrap();
                let want = if lag.m % 2 == 0 { 0.0 } else { 1.0 };
                assert!((var - want).abs() < 1e-12, "lag {}: {var}", lag.m);
            }
        }
    }

    /// Samples land in the segment they are given; the last segment takes any
    /// index beyond it.
    #[test]
    fn sums_go_to_their_segment() {
        let mut c = IncrementCorrelator::new(1.0, 1, 2);
        for n in 0..10 {
            c.push(n as f64, if n < 5 { 0 } else { 7 });
        }
        let lag = c.lags()[1];
        // Lag 1: pairs end at n = 1..9; n = 1..4 in segment 0, 5..9 in 1.
        assert_eq!(c.sums(lag, 0).count, 4.0);
        assert_eq!(c.sums(lag, 1).count, 5.0);
        assert_eq!(c.sums(lag, 1).inc, 5.0);
    }
}
