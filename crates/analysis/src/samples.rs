//! The data an [`Analyzer`](super::Analyzer) accumulates for the thermodynamic
//! observables, as plain fields: sums per time bin (virial, wall impulse, pair
//! collisions) after the equilibration time, the kT and energy series, and the
//! velocities of the snapshots used for the Maxwell–Boltzmann tests. Temperature,
//! pressure, collision rate, velocity distribution and the inelastic checks each
//! read these and return their report section; none of them sees the Analyzer.
//! Per bin: Z = βPA/N from the virial or the wall impulse (physics.md §5) and
//! ω = 2 N_pair/(N Δt) (§7); kT = 2K/f, interpolated in time (§5).

use carom_core::observables::{degrees_of_freedom, temperature};

use super::description::RunDescription;
use super::options::{budget_spacing, AnalysisOptions, DECORRELATION_COLLISIONS};
use super::report::WindowReport;
use super::stats::StatsError;

/// Sums of one time bin.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct TimeBin {
    pub(crate) virial: f64,
    pub(crate) wall_impulse: f64,
    pub(crate) pairs: u64,
    pub(crate) walls: u64,
    /// Pair collisions from [`Samples::increment`] (already scaled, fractional).
    pub(crate) pairs_weighted: f64,
}

/// What the thermodynamic observables are computed from.
#[derive(Debug, Clone)]
pub(crate) struct Samples {
    pub(crate) run: RunDescription,
    pub(crate) opts: AnalysisOptions,
    pub(crate) t_eq: f64,
    pub(crate) bin_width: f64,
    pub(crate) bins: Vec<TimeBin>,
    /// (time, kT) from every thermo record and snapshot, in time order.
    pub(crate) kt_series: Vec<(f64, f64)>,
    /// (time, K, dissipated energy so far when the source reports it).
    pub(crate) energy_series: Vec<(f64, f64, Option<f64>)>,
    pub(crate) lost_from_collisions: f64,
    pub(crate) pair_total: u64,
    pub(crate) wall_total: u64,
    pub(crate) pairs_from_increments: u64,
    pub(crate) speeds: Vec<Vec<f64>>,
    pub(crate) vx: Vec<Vec<f64>>,
    pub(crate) vy: Vec<Vec<f64>>,
    pub(crate) mb_kinetic: f64,
    pub(crate) snapshots_used: Vec<f64>,
    /// kT of each snapshot used.
    pub(crate) snapshot_kt: Vec<f64>,
    /// Sonine coefficient a2 of each snapshot used (physics.md (8.5)).
    pub(crate) snapshot_a2: Vec<f64>,
    pub(crate) snapshots_seen: usize,
    /// Whether `opts.every` was chosen here (from the collision rate or the memory
    /// bound) rather than asked for.
    pub(crate) every_default: bool,
    /// Whether the memory bound set `opts.every` (spacing the snapshots further
    /// apart than the collision rate asks).
    pub(crate) every_from_budget: bool,
    /// The default spacing of an inelastic run, in pair collisions per disc
    /// counted between the snapshots used (its rate changes, so no one time
    /// spacing fits); `None`: the time spacing `opts.every` alone.
    pub(crate) every_collisions: Option<f64>,
    /// The engine's running count of pair collisions at the last `/thermo`
    /// record read (`Analyzer::pair_count`).
    pub(crate) thermo_pairs: Option<u64>,
    /// The pair collisions counted at each snapshot used: (the last `/thermo`
    /// count, [`Samples::pairs_counted`]).
    pub(crate) snapshot_pairs: Vec<(Option<u64>, f64)>,
}

impl Samples {
    /// Empty samples of `run` with options `opts`: the window, the time bins and
    /// the spacing of the snapshots used (`opts.every`, defaulted here).
    pub(crate) fn new(run: RunDescription, opts: AnalysisOptions) -> Result<Samples, StatsError> {
        if run.t_start.is_nan() || run.t_end.is_nan() || run.t_end <= run.t_start {
            return Err(StatsError::NotEnoughData(format!(
                "the log spans no time ({} to {})",
                run.t_start, run.t_end
            )));
        }
        let t_eq = opts
            .equilibrate
            .unwrap_or(run.t_start + 0.1 * (run.t_end - run.t_start))
            .max(run.t_start);
        if t_eq >= run.t_end {
            return Err(StatsError::InvalidArgument(format!(
                "--equilibrate {t_eq} is not before the end of the log at {}",
                run.t_end
            )));
        }
        let nbins = opts.time_bins.max(16);
        let ns = run.species.len();
        let mut opts = opts;
        let mut every_collisions = None;
        let (every_default, every_from_budget) = match opts.every {
            Some(_) => (false, false),
            None if !run.restitution.is_elastic() => {
                // Snapshots DECORRELATION_COLLISIONS apart by count number at most
                // the log's collisions per disc over that, plus one; a schedule's
                // snapshots are closer than its interval.
                every_collisions = Some(DECORRELATION_COLLISIONS);
                let room = (opts.max_velocities / run.n().max(1)) as f64;
                let by_count = run
                    .pair_rate
                    .map(|w| w * (run.t_end - run.t_start) / DECORRELATION_COLLISIONS + 1.0);
                let interval = run
                    .snapshot_interval
                    .filter(|_| run.snapshot_schedule.is_none());
                opts.every = match by_count {
                    Some(k) if k <= room => None,
                    _ => budget_spacing(run.n(), opts.max_velocities, run.t_end - t_eq, interval),
                };
                (true, opts.every.is_some())
            }
            None => {
                let decorrelated = run
                    .pair_rate
                    .filter(|w| *w > 0.0 && w.is_finite())
                    .map(|w| DECORRELATION_COLLISIONS / w);
                let budget = budget_spacing(
                    run.n(),
                    opts.max_velocities,
                    run.t_end - t_eq,
                    match (decorrelated, run.snapshot_interval) {
                        (Some(d), Some(i)) => Some(d.max(i)),
                        (d, i) => d.or(i),
                    },
                );
                opts.every = match (decorrelated, budget) {
                    (Some(d), Some(b)) => Some(d.max(b)),
                    (d, b) => d.or(b),
                };
                (
                    opts.every.is_some(),
                    budget.is_some_and(|b| decorrelated.is_none_or(|d| b > d)),
                )
            }
        };
        Ok(Samples {
            every_default,
            every_from_budget,
            every_collisions,
            thermo_pairs: None,
            snapshot_pairs: Vec::new(),
            bin_width: (run.t_end - t_eq) / nbins as f64,
            bins: vec![TimeBin::default(); nbins],
            t_eq,
            opts,
            kt_series: Vec::new(),
            energy_series: Vec::new(),
            lost_from_collisions: 0.0,
            pair_total: 0,
            wall_total: 0,
            pairs_from_increments: 0,
            speeds: vec![Vec::new(); ns],
            vx: vec![Vec::new(); ns],
            vy: vec![Vec::new(); ns],
            mb_kinetic: 0.0,
            snapshots_used: Vec::new(),
            snapshot_kt: Vec::new(),
            snapshot_a2: Vec::new(),
            snapshots_seen: 0,
            run,
        })
    }

    fn bin(&mut self, t: f64) -> Option<&mut TimeBin> {
        if t < self.t_eq || t > self.run.t_end {
            return None;
        }
        let k = (((t - self.t_eq) / self.bin_width) as usize).min(self.bins.len() - 1);
        Some(&mut self.bins[k])
    }

    /// A logged pair (`wall` false) or wall collision at time `t`: its virial or
    /// wall impulse and its dissipated energy, scaled by the collision stride.
    pub(crate) fn collision(
        &mut self,
        t: f64,
        wall: bool,
        virial_or_impulse: f64,
        energy_lost: f64,
    ) {
        if wall {
            self.wall_total += 1;
        } else {
            self.pair_total += 1;
        }
        if self.run.totals_from_thermo {
            return;
        }
        let s = self.run.collision_stride as f64;
        self.lost_from_collisions += s * energy_lost;
        if let Some(b) = self.bin(t) {
            if wall {
                b.wall_impulse += s * virial_or_impulse;
                b.walls += 1;
            } else {
                b.virial += s * virial_or_impulse;
                b.pairs += 1;
            }
        }
    }

    /// Running totals between two times, for logs without collisions: the virial
    /// sum (length·momentum), wall impulse (momentum) and pair collisions counted
    /// in [t0, t1] (e.g. differences of consecutive `/thermo` records), spread
    /// over the time bins in proportion to their overlap.
    pub(crate) fn increment(
        &mut self,
        t0: f64,
        t1: f64,
        virial: f64,
        wall_impulse: f64,
        pairs: u64,
    ) {
        if t0.is_nan() || t1.is_nan() || t1 <= t0 {
            return;
        }
        self.pairs_from_increments += pairs;
        let (lo, hi) = (t0.max(self.t_eq), t1.min(self.run.t_end));
        if hi <= lo {
            return;
        }
        let first = ((lo - self.t_eq) / self.bin_width) as usize;
        let last = (((hi - self.t_eq) / self.bin_width) as usize).min(self.bins.len() - 1);
        for k in first..=last {
            let b0 = self.t_eq + k as f64 * self.bin_width;
            let overlap = (hi.min(b0 + self.bin_width) - lo.max(b0)).max(0.0);
            let w = overlap / (t1 - t0);
            let bin = &mut self.bins[k];
            bin.virial += w * virial;
            bin.wall_impulse += w * wall_impulse;
            bin.pairs_weighted += w * pairs as f64;
        }
    }

    /// Pair collisions counted so far: the logged ones × stride (unless the
    /// totals come from `/thermo`) plus those of [`Samples::increment`].
    pub(crate) fn pairs_counted(&self) -> f64 {
        let logged = if self.run.totals_from_thermo {
            0.0
        } else {
            self.pair_total as f64 * self.run.collision_stride as f64
        };
        logged + self.pairs_from_increments as f64
    }

    /// Pair collisions per disc, 2ΔN_pair/N, between two counts of
    /// `snapshot_pairs`: the `/thermo` running counts when both have one, else
    /// the collisions counted.
    pub(crate) fn collisions_between(&self, a: (Option<u64>, f64), b: (Option<u64>, f64)) -> f64 {
        let pairs = match (a.0, b.0) {
            (Some(x), Some(y)) if y > x => (y - x) as f64,
            _ => b.1 - a.1,
        };
        2.0 * pairs / self.run.n().max(1) as f64
    }

    /// A thermodynamic record: kinetic energy K (energy) at time `t`, and the
    /// energy dissipated since the start when known.
    pub(crate) fn thermo(&mut self, t: f64, kinetic_energy: f64, energy_lost: Option<f64>) {
        let kt = temperature(kinetic_energy, self.dof());
        self.push_kt(t, kt);
        match self.energy_series.last_mut() {
            Some(last) if last.0 == t => *last = (t, kinetic_energy, energy_lost.or(last.2)),
            _ => self.energy_series.push((t, kinetic_energy, energy_lost)),
        }
    }

    /// Whether the snapshot at time `t` starts a block of the log's
    /// `log.snapshot_schedule` (always true without one). Snapshots inside a
    /// block, closely spaced for dynamics, add correlated samples rather than
    /// information to the structure and velocity tests, which use block starts only.
    pub(crate) fn block_start(&self, t: f64) -> bool {
        self.run
            .snapshot_schedule
            .is_none_or(|s| s.is_block_start(self.run.t_start, t))
    }

    /// A snapshot's per-disc slices must agree in length, and its species indices
    /// must be the run's.
    pub(crate) fn check_snapshot(
        &self,
        t: f64,
        species_of: &[u16],
        [a, b]: [&[f64]; 2],
        [na, nb]: [&str; 2],
    ) -> Result<(), StatsError> {
        if species_of.len() != a.len() || a.len() != b.len() {
            return Err(StatsError::InvalidArgument(format!(
                "snapshot at t = {t}: {} species indices, {} {na}, {} {nb}",
                species_of.len(),
                a.len(),
                b.len()
            )));
        }
        if let Some(&bad) = species_of
            .iter()
            .find(|&&s| s as usize >= self.run.species.len())
        {
            return Err(StatsError::InvalidArgument(format!(
                "snapshot at t = {t}: species index {bad}, but the run has {} species",
                self.run.species.len()
            )));
        }
        Ok(())
    }

    /// Record kT at `t`, once per time (a thermo record and a snapshot at the
    /// same time give one point).
    pub(crate) fn push_kt(&mut self, t: f64, kt: f64) {
        match self.kt_series.last_mut() {
            Some(last) if last.0 == t => last.1 = kt,
            _ => self.kt_series.push((t, kt)),
        }
    }

    /// kT at time `t`, linearly interpolated in the recorded series.
    pub(crate) fn kt_at(&self, t: f64) -> Option<f64> {
        let s = &self.kt_series;
        let first = s.first()?;
        if t <= first.0 {
            return Some(first.1);
        }
        let k = s.partition_point(|p| p.0 <= t);
        if k >= s.len() {
            return Some(s[s.len() - 1].1);
        }
        let (a, b) = (s[k - 1], s[k]);
        let w = if b.0 > a.0 {
            (t - a.0) / (b.0 - a.0)
        } else {
            1.0
        };
        Some(a.1 + w * (b.1 - a.1))
    }

    /// Degrees of freedom f of the run (physics.md §5).
    pub(crate) fn dof(&self) -> usize {
        degrees_of_freedom(self.run.n(), &self.run.sim_box)
    }

    /// kT at the middle of each time bin.
    pub(crate) fn kt_per_bin(&self) -> Vec<f64> {
        (0..self.bins.len())
            .map(|k| {
                let t_mid = self.t_eq + (k as f64 + 0.5) * self.bin_width;
                self.kt_at(t_mid).unwrap_or(f64::NAN)
            })
            .collect()
    }

    /// The window analysed, with the spacing of the snapshots used in collisions
    /// per disc: counted between them for an inelastic run (whose rate changes),
    /// else at the measured rate `omega`.
    pub(crate) fn window(&self, omega: f64) -> WindowReport {
        let spacing_collisions = if self.run.restitution.is_elastic() {
            self.snapshots_used
                .windows(2)
                .map(|w| w[1] - w[0])
                .reduce(f64::min)
                .map(|gap| gap * omega)
        } else {
            self.snapshot_pairs
                .windows(2)
                .map(|w| self.collisions_between(w[0], w[1]))
                .reduce(f64::min)
        };
        WindowReport {
            t_start: self.run.t_start,
            t_end: self.run.t_end,
            equilibrate: self.t_eq,
            every: self.opts.every,
            every_default: self.every_default,
            every_from_budget: self.every_from_budget,
            every_collisions: self.every_collisions,
            max_velocities: self.opts.max_velocities,
            spacing_collisions,
            snapshots_seen: self.snapshots_seen,
            snapshot_times: self.snapshots_used.clone(),
        }
    }
}
