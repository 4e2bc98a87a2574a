//! Single-disc dynamics from the snapshots (physics.md §13), in one streaming
//! pass and fixed memory: every snapshot's unwrapped positions u_i and velocities
//! v_i (`Analyzer::motion`) are paired with stored origins ([`super::origins`]),
//! and per pairing key, species and time segment of the origin the sums
//!
//!   Σ 1, Σ |Δu|², Σ |Δu|⁴, Σ v_i(t₀)·v_i(t), Σ J₀(k*|Δu|),   Δu = u_i(t) − u_i(t₀),
//!
//! are accumulated, with the summed exact lags t − t₀. The report turns them into
//! MSD(τ), α₂(τ), D ([`super::msd`]), the snapshot VACF C(τ) and F_s(k*, τ) with
//! τ_α ([`super::self_scattering`]); each value's standard error is the spread of
//! its [`SEGMENTS`] segments (origins grouped by time over [t_eq, t_end]).

use std::collections::BTreeMap;

use carom_core::{SimBox, Species};

use super::dynamics_report::{DynamicsReport, SpeciesDynamics};
use super::msd::{fit_diffusion, overlap_factor, D_WINDOW_COLLISIONS};
use super::origins::{plan, LagKey, Origin, OriginStore};
use super::pair_correlation::mean_se;
use super::self_scattering::{first_peak_k, tau_alpha};

/// Time segments of [t_eq, t_end] whose spread gives the standard errors.
pub const SEGMENTS: usize = 10;

/// Sums over disc-origin pairs of one species.
#[derive(Debug, Clone, Copy, Default)]
struct Sums {
    n: u64,
    dr2: f64,
    dr4: f64,
    vv: f64,
    fs: f64,
}

impl Sums {
    fn add(&mut self, o: &Sums) {
        self.n += o.n;
        self.dr2 += o.dr2;
        self.dr4 += o.dr4;
        self.vv += o.vv;
        self.fs += o.fs;
    }
}

/// The sums of one pairing key, per segment (and species).
#[derive(Debug, Clone)]
struct KeySums {
    pairings: [u64; SEGMENTS],
    lag: [f64; SEGMENTS],
    species: Vec<[Sums; SEGMENTS]>,
}

/// The accumulator behind `Analyzer::motion`.
#[derive(Debug, Clone)]
pub(super) struct Dynamics {
    store: OriginStore,
    capped: bool,
    t_start: f64,
    interval: Option<f64>,
    t_eq: f64,
    t_end: f64,
    sim_box: SimBox,
    sigma_min: f64,
    counts: Vec<usize>,
    /// k*, decided at the first origin (None: walls).
    k_star: Option<Option<f64>>,
    sums: BTreeMap<LagKey, KeySums>,
    origins: u64,
    /// Most origins stored at once.
    max_stored: usize,
    pub(super) ambiguous_gaps: u64,
}

impl Dynamics {
    /// For `species` in `sim_box` over [t_start, t_end] analysed from `t_eq`,
    /// snapshots every `snapshot_interval` (or block of the schedule) when known,
    /// σ_min the smallest diameter.
    pub(super) fn new(
        (species, sim_box): (&[Species], &SimBox),
        [t_start, t_eq, t_end]: [f64; 3],
        snapshot_interval: Option<f64>,
        sigma_min: f64,
    ) -> Self {
        let interval = snapshot_interval.filter(|i| i.is_finite() && *i > 0.0);
        let blocks = interval.map(|i| ((t_end - t_eq) / i).floor().max(0.0) as u64 + 1);
        let n = species.iter().map(|s| s.count).sum();
        let (p, levels, capped) = plan(n, blocks);
        Dynamics {
            store: OriginStore::new(p, levels),
            capped,
            t_start,
            interval,
            t_eq,
            t_end,
            sim_box: *sim_box,
            sigma_min,
            counts: species.iter().map(|s| s.count).collect(),
            k_star: None,
            sums: BTreeMap::new(),
            origins: 0,
            max_stored: 0,
            ambiguous_gaps: 0,
        }
    }

    /// The segment of an origin at `t`.
    fn segment(&self, t: f64) -> usize {
        let w = (self.t_end - self.t_eq) / SEGMENTS as f64;
        (((t - self.t_eq) / w).floor().max(0.0) as usize).min(SEGMENTS - 1)
    }

    /// One snapshot, a block start when `start` (slices already checked to
    /// agree).
    pub(super) fn add(
        &mut self,
        t: f64,
        start: bool,
        species_of: &[u16],
        u: [&[f64]; 2],
        v: [&[f64]; 2],
    ) {
        let tol = 1e-12 * self.t_eq.abs().max(self.t_end - self.t_start);
        if t > self.t_end + tol {
            return;
        }
        let Some((block, j)) = self.store.locate(t, start, self.t_start, self.interval) else {
            return;
        };
        if j == 0 && t >= self.t_eq - tol {
            // k* from the first origin (S(k) does not see the images).
            self.k_star
                .get_or_insert_with(|| first_peak_k(&self.sim_box, self.sigma_min, u[0], u[1]));
            self.origins += 1;
            let segment = self.segment(t);
            self.store.store(Origin {
                time: t,
                block,
                segment,
                ux: u[0].to_vec(),
                uy: u[1].to_vec(),
                vx: v[0].to_vec(),
                vy: v[1].to_vec(),
            });
            self.max_stored = self.max_stored.max(self.store.stored());
        }
        let k = self.k_star.flatten().unwrap_or(0.0);
        let ns = self.counts.len();
        for (key, o) in self.store.pairings(block, j) {
            let e = self.sums.entry(key).or_insert_with(|| KeySums {
                pairings: [0; SEGMENTS],
                lag: [0.0; SEGMENTS],
                species: vec![[Sums::default(); SEGMENTS]; ns],
            });
            e.pairings[o.segment] += 1;
            e.lag[o.segment] += t - o.time;
            for (i, &s) in species_of.iter().enumerate() {
                let (dx, dy) = (u[0][i] - o.ux[i], u[1][i] - o.uy[i]);
                let dr2 = dx * dx + dy * dy;
                let acc = &mut e.species[s as usize][o.segment];
                acc.n += 1;
                acc.dr2 += dr2;
                acc.dr4 += dr2 * dr2;
                acc.vv += o.vx[i] * v[0][i] + o.vy[i] * v[1][i];
                acc.fs += libm::j0(k * dr2.sqrt());
            }
        }
    }

    /// The report, with `collision_rate` pair collisions per disc per unit time
    /// (sets the D window's start); `None` without origins.
    pub(super) fn report(&self, collision_rate: f64) -> Option<DynamicsReport> {
        if self.origins == 0 {
            return None;
        }
        let mut keys: Vec<(f64, &KeySums)> = self
            .sums
            .values()
            .map(|k| {
                let n: u64 = k.pairings.iter().sum();
                (k.lag.iter().sum::<f64>() / n as f64, k)
            })
            .collect();
        keys.sort_by(|a, b| a.0.total_cmp(&b.0));
        let t_a = (collision_rate.is_finite() && collision_rate > 0.0)
            .then(|| D_WINDOW_COLLISIONS / collision_rate);
        let k_star = self.k_star.flatten();
        let w = (self.t_end - self.t_eq) / SEGMENTS as f64;
        let species = (0..self.counts.len())
            .filter(|&s| self.counts[s] > 0)
            .map(|s| species_report(s, self.counts[s], &keys, k_star.is_some(), t_a, w))
            .collect();
        Some(DynamicsReport {
            species,
            origins: self.origins,
            origins_per_level: self.store.per_level(),
            levels: self.store.level_count(),
            origins_capped: self.capped,
            max_stored: self.max_stored,
            segments: SEGMENTS,
            collision_time: t_a.map(|t| t / D_WINDOW_COLLISIONS),
            k_star,
            ambiguous_gaps: self.ambiguous_gaps,
        })
    }
}

/// Standard error at lag `tau` from the finite per-segment values (NaN with
/// fewer than 2), widened for segments of width `w` by [`overlap_factor`].
fn segment_se(values: &[f64], tau: f64, w: f64) -> f64 {
    let v: Vec<f64> = values.iter().copied().filter(|x| x.is_finite()).collect();
    mean_se(&v).1 * overlap_factor(tau, w)
}

/// One species' curves over the keys sorted by lag; `w` the segments' width.
fn species_report(
    s: usize,
    count: usize,
    keys: &[(f64, &KeySums)],
    with_fs: bool,
    t_a: Option<f64>,
    w: f64,
) -> SpeciesDynamics {
    let mut r = SpeciesDynamics {
        species: s,
        count,
        lag: vec![],
        samples: vec![],
        msd: vec![],
        msd_std_error: vec![],
        alpha2: vec![],
        vacf: vec![],
        vacf_std_error: vec![],
        vacf_normalised: vec![],
        fs: vec![],
        fs_std_error: vec![],
        tau_alpha: None,
        diffusion: None,
    };
    let mut msd_segments: Vec<Vec<f64>> = vec![Vec::new(); SEGMENTS];
    for (lag, k) in keys {
        let seg = &k.species[s];
        let mut total = Sums::default();
        seg.iter().for_each(|x| total.add(x));
        if total.n == 0 {
            continue;
        }
        let per = |f: &dyn Fn(&Sums) -> f64| -> Vec<f64> {
            seg.iter()
                .map(|x| if x.n > 0 { f(x) / x.n as f64 } else { f64::NAN })
                .collect()
        };
        let n = total.n as f64;
        let msd = total.dr2 / n;
        let m = per(&|x| x.dr2);
        r.lag.push(*lag);
        r.samples.push(total.n);
        r.msd.push(msd);
        r.msd_std_error.push(segment_se(&m, *lag, w));
        r.alpha2.push(total.dr4 / n / (2.0 * msd * msd) - 1.0);
        r.vacf.push(total.vv / n);
        r.vacf_std_error.push(segment_se(&per(&|x| x.vv), *lag, w));
        if with_fs {
            r.fs.push(total.fs / n);
            r.fs_std_error.push(segment_se(&per(&|x| x.fs), *lag, w));
        }
        for (out, v) in msd_segments.iter_mut().zip(m) {
            out.push(v);
        }
    }
    let c0 = match r.lag.first() {
        Some(&0.0) => r.vacf[0],
        _ => f64::NAN,
    };
    r.vacf_normalised = r.vacf.iter().map(|c| c / c0).collect();
    r.tau_alpha = tau_alpha(&r.lag, &r.fs);
    r.diffusion = fit_diffusion(&r.lag, &r.msd, &r.msd_std_error, &msd_segments, t_a, w);
    r
}

#[cfg(test)]
#[path = "dynamics_tests.rs"]
mod tests;
