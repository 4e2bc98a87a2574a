//! The [`Analyzer`]: accumulates a run's events in one streaming pass and turns
//! them into a [`Report`]. It sees plain numbers (collision virials, wall
//! impulses, snapshots, kinetic energies), not files: [`super::from_log`] feeds it
//! from an MCAP log, the tests straight from the engine. Sums go into time bins
//! after the equilibration time, so that every observable gets a blocked standard
//! error; kT comes from the thermo records and snapshots, interpolated in time.
//! [`Analyzer::finish`] calls one function per observable (temperature, velocity
//! distribution, pressure, collision rate and Enskog, inelastic).

use carom_core::observables::{degrees_of_freedom, packing_fraction, temperature};
use carom_core::rates::expected_mean_free_time;

use super::atmosphere::Atmosphere;
use super::bond_correlation::BondCorrelation;
use super::bond_order::{BondOrder, MIN_BOND_ORDER_DISCS};
use super::dynamics::Dynamics;
use super::not_computed;
use super::options::{budget_spacing, AnalysisOptions, DECORRELATION_COLLISIONS};
use super::pair_correlation::PairCorrelation;
use super::report::{Report, SpeciesInfo, WindowReport};
use super::stats::StatsError;
use super::structure_factor::StructureFactor;
use super::transport::Transport;
use super::{collision_rate, contact, inelastic, pressure, temperature, velocity, RunDescription};

#[derive(Debug, Clone, Copy, Default)]
pub(super) struct TimeBin {
    pub(super) virial: f64,
    pub(super) wall_impulse: f64,
    pub(super) pairs: u64,
    pub(super) walls: u64,
    /// Pair collisions from [`Analyzer::increment`] (already scaled, fractional).
    pub(super) pairs_weighted: f64,
}

/// Accumulates a run's events and produces a [`Report`].
#[derive(Debug, Clone)]
pub struct Analyzer {
    pub(super) run: RunDescription,
    pub(super) opts: AnalysisOptions,
    pub(super) t_eq: f64,
    pub(super) bin_width: f64,
    pub(super) bins: Vec<TimeBin>,
    /// (time, kT) from every thermo record and snapshot, in time order.
    pub(super) kt_series: Vec<(f64, f64)>,
    /// (time, K, dissipated energy so far when the source reports it).
    pub(super) energy_series: Vec<(f64, f64, Option<f64>)>,
    pub(super) lost_from_collisions: f64,
    pub(super) pair_total: u64,
    pub(super) wall_total: u64,
    pub(super) pairs_from_increments: u64,
    pub(super) speeds: Vec<Vec<f64>>,
    pub(super) vx: Vec<Vec<f64>>,
    pub(super) vy: Vec<Vec<f64>>,
    pub(super) mb_kinetic: f64,
    pub(super) snapshots_used: Vec<f64>,
    /// kT of each snapshot used.
    pub(super) snapshot_kt: Vec<f64>,
    /// Sonine coefficient a2 of each snapshot used (physics.md (8.5)).
    pub(super) snapshot_a2: Vec<f64>,
    pub(super) snapshots_seen: usize,
    /// Whether `opts.every` was chosen here (from the collision rate or the memory
    /// bound) rather than asked for.
    pub(super) every_default: bool,
    /// Whether the memory bound set `opts.every` (spacing the snapshots further
    /// apart than the collision rate asks).
    pub(super) every_from_budget: bool,
    /// The default spacing of an inelastic run, in pair collisions per disc
    /// counted between the snapshots used (its rate changes, so no one time
    /// spacing fits); `None`: the time spacing `opts.every` alone.
    pub(super) every_collisions: Option<f64>,
    /// The engine's running count of pair collisions at the last `/thermo`
    /// record read ([`Analyzer::pair_count`]).
    pub(super) thermo_pairs: Option<u64>,
    /// The pair collisions counted at each snapshot used: (the last `/thermo`
    /// count, [`Analyzer::pairs_counted`]).
    pub(super) snapshot_pairs: Vec<(Option<u64>, f64)>,
    /// Pair-distance histograms per time block (physics.md §10).
    pub(super) pair_correlation: PairCorrelation,
    /// |Ψ6| and local |ψ6| of every snapshot (physics.md §11).
    pub(super) bond_order: BondOrder,
    /// g6(r) per time block.
    pub(super) bond_correlation: BondCorrelation,
    /// S(k) of one snapshot per time block (periodic boxes only).
    pub(super) structure_factor: Option<StructureFactor>,
    /// MSD, snapshot VACF and F_s sums over time origins (physics.md §13).
    pub(super) dynamics: Dynamics,
    /// Transport from the collision log, from the first snapshot analysed on
    /// (physics.md §14); `None` before it, or when the run does not qualify.
    pub(super) transport: Option<Transport>,
    /// Whether the transport replay has been tried (at the first snapshot).
    pub(super) transport_tried: bool,
    /// Pair collisions since it started; a source that gives fewer details
    /// ([`Analyzer::pair_detail`]) gets no transport report.
    pub(super) transport_pairs: u64,
    /// Heights and potential energy in a field (physics.md §15); `None` without one.
    pub(super) atmosphere: Option<Atmosphere>,
}

impl Analyzer {
    /// An analyzer for `run` with options `opts`.
    pub fn new(run: RunDescription, opts: AnalysisOptions) -> Result<Self, StatsError> {
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
        let sigma_min = 2.0
            * run
                .species
                .iter()
                .filter(|s| s.count > 0)
                .map(|s| s.radius)
                .fold(f64::INFINITY, f64::min);
        Ok(Analyzer {
            pair_correlation: PairCorrelation::new(&run.species, &run.sim_box, t_eq, run.t_end),
            bond_order: BondOrder::default(),
            bond_correlation: BondCorrelation::new(&run.species, &run.sim_box, t_eq, run.t_end),
            structure_factor: StructureFactor::new(&run.sim_box, sigma_min, t_eq, run.t_end),
            dynamics: Dynamics::new(&run, t_eq, sigma_min),
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
            transport: None,
            transport_tried: false,
            transport_pairs: 0,
            atmosphere: (run.gravity > 0.0).then(|| {
                Atmosphere::new(
                    run.gravity,
                    [run.sim_box.size.x, run.sim_box.size.y],
                    run.species.iter().map(|s| s.mass).collect(),
                    run.species.iter().map(|s| s.radius).collect(),
                )
            }),
            run,
        })
    }

    /// The time from which data are used (after `--equilibrate`).
    pub fn equilibrated_from(&self) -> f64 {
        self.t_eq
    }

    fn bin(&mut self, t: f64) -> Option<&mut TimeBin> {
        if t < self.t_eq || t > self.run.t_end {
            return None;
        }
        let k = (((t - self.t_eq) / self.bin_width) as usize).min(self.bins.len() - 1);
        Some(&mut self.bins[k])
    }

    /// A logged pair collision at time `t` with virial r_ij·Δp_i (length·momentum)
    /// and dissipated energy (energy).
    pub fn pair(&mut self, t: f64, virial: f64, energy_lost: f64) {
        self.pair_total += 1;
        if self.transport.is_some() {
            self.transport_pairs += 1;
        }
        if self.run.totals_from_thermo {
            return;
        }
        let s = self.run.collision_stride as f64;
        self.lost_from_collisions += s * energy_lost;
        if let Some(b) = self.bin(t) {
            b.virial += s * virial;
            b.pairs += 1;
        }
    }

    /// The detail of a logged pair collision of discs `i` and `j` at time `t`, for
    /// the transport coefficients (physics.md §14): the unit contact normal from
    /// i to j and both velocities after. Call it after [`Analyzer::pair`] for every
    /// pair collision when the log holds them.
    pub fn pair_detail(
        &mut self,
        t: f64,
        (i, j): (u32, u32),
        normal: [f64; 2],
        [vi, vj]: [[f64; 2]; 2],
    ) {
        if let Some(tr) = &mut self.transport {
            tr.pair(
                t,
                (i as usize, j as usize),
                normal.into(),
                [vi.into(), vj.into()],
            );
        }
    }

    /// A logged wall collision at time `t` giving the wall momentum `impulse`
    /// (momentum), dissipating `energy_lost` (energy).
    pub fn wall(&mut self, t: f64, impulse: f64, energy_lost: f64) {
        self.wall_total += 1;
        if self.run.totals_from_thermo {
            return;
        }
        let s = self.run.collision_stride as f64;
        self.lost_from_collisions += s * energy_lost;
        if let Some(b) = self.bin(t) {
            b.wall_impulse += s * impulse;
            b.walls += 1;
        }
    }

    /// Running totals between two times, for logs without collisions: the virial
    /// sum (length·momentum), wall impulse (momentum) and pair collisions counted
    /// in [t0, t1] (e.g. differences of consecutive `/thermo` records), spread
    /// over the time bins in proportion to their overlap.
    pub fn increment(&mut self, t0: f64, t1: f64, virial: f64, wall_impulse: f64, pairs: u64) {
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

    /// The engine's running count of pair collisions (since the run's start) at
    /// a `/thermo` record: with it the snapshots of an inelastic run are spaced by
    /// the collisions between them (see [`AnalysisOptions::every`]).
    pub fn pair_count(&mut self, pairs: u64) {
        self.thermo_pairs = Some(pairs);
    }

    /// Pair collisions counted so far: the logged ones × stride (unless the
    /// totals come from `/thermo`) plus those of [`Analyzer::increment`].
    pub(super) fn pairs_counted(&self) -> f64 {
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
    fn collisions_between(&self, a: (Option<u64>, f64), b: (Option<u64>, f64)) -> f64 {
        let pairs = match (a.0, b.0) {
            (Some(x), Some(y)) if y > x => (y - x) as f64,
            _ => b.1 - a.1,
        };
        2.0 * pairs / self.run.n().max(1) as f64
    }

    /// A thermodynamic record: kinetic energy K (energy) at time `t`, and the
    /// energy dissipated since the start when known.
    pub fn thermo(&mut self, t: f64, kinetic_energy: f64, energy_lost: Option<f64>) {
        let kt = temperature(kinetic_energy, self.dof());
        self.push_kt(t, kt);
        match self.energy_series.last_mut() {
            Some(last) if last.0 == t => *last = (t, kinetic_energy, energy_lost.or(last.2)),
            _ => self.energy_series.push((t, kinetic_energy, energy_lost)),
        }
    }

    /// A snapshot at time `t`: species index and velocity components of every disc
    /// (length/time). Used for the temperature series, and for the velocity
    /// distribution when it is after `equilibrate`, at least `every` after the
    /// last snapshot used, and starts a block of the snapshot schedule
    /// (`Analyzer::block_start`).
    ///
    /// Errors when the three slices differ in length or a species index is not one
    /// of the run's species.
    pub fn snapshot(
        &mut self,
        t: f64,
        species_of: &[u16],
        vx: &[f64],
        vy: &[f64],
    ) -> Result<(), StatsError> {
        self.check_snapshot(t, species_of, [vx, vy], ["vx", "vy"])?;
        self.snapshots_seen += 1;
        let masses: Vec<f64> = self.run.species.iter().map(|s| s.mass).collect();
        let k: f64 = species_of
            .iter()
            .zip(vx.iter().zip(vy))
            .map(|(&s, (&x, &y))| 0.5 * masses[s as usize] * (x * x + y * y))
            .sum();
        let kt = temperature(k, self.dof());
        self.push_kt(t, kt);
        if self.energy_series.last().is_none_or(|e| e.0 != t) {
            self.energy_series.push((t, k, None));
        }
        // A snapshot at the start of the window counts despite rounding of the
        // window's start (a tolerance relative to the run's own times, which may be
        // in any unit).
        let span = self.run.t_end - self.run.t_start;
        if t < self.t_eq - 1e-12 * self.t_eq.abs().max(span) {
            return Ok(());
        }
        self.transport_snapshot(t, species_of, vx, vy, kt);
        // Spaced by the collisions counted, any snapshot far enough from the last
        // one used is as independent as a block start.
        let counted = (self.thermo_pairs, self.pairs_counted());
        match (self.every_collisions, self.snapshot_pairs.last()) {
            (Some(c), Some(&last)) => {
                if self.collisions_between(last, counted) < c * (1.0 - 1e-9) {
                    return Ok(());
                }
            }
            (Some(_), None) => {}
            (None, _) => {
                if !self.block_start(t) {
                    return Ok(());
                }
            }
        }
        if let (Some(&last), Some(every)) = (self.snapshots_used.last(), self.opts.every) {
            if t < last + every * (1.0 - 1e-9) {
                return Ok(());
            }
        }
        self.snapshots_used.push(t);
        self.snapshot_pairs.push(counted);
        self.snapshot_kt.push(kt);
        self.snapshot_a2
            .push(inelastic::sonine_a2(&masses, species_of, vx, vy));
        self.mb_kinetic += k;
        let (ux, uy) = velocity::centre_of_mass_velocity(&masses, species_of, vx, vy);
        for (&s, (&x, &y)) in species_of.iter().zip(vx.iter().zip(vy)) {
            let (s, x, y) = (s as usize, x - ux, y - uy);
            self.speeds[s].push(x.hypot(y));
            self.vx[s].push(x);
            self.vy[s].push(y);
        }
        Ok(())
    }

    /// The positions of a snapshot at time `t` (species index and centre of every
    /// disc, length), used when `t` is after the equilibration time and starts a
    /// block of the snapshot schedule (independent of `every`): pair distances
    /// into g(r) and ψ6 from every such snapshot, g6(r) and S(k) from some
    /// (physics.md §10–§11).
    ///
    /// Errors when the slices differ in length or a species index is not one of
    /// the run's species.
    pub fn positions(
        &mut self,
        t: f64,
        species_of: &[u16],
        x: &[f64],
        y: &[f64],
    ) -> Result<(), StatsError> {
        self.check_snapshot(t, species_of, [x, y], ["x", "y"])?;
        let span = self.run.t_end - self.run.t_start;
        if t < self.t_eq - 1e-12 * self.t_eq.abs().max(span) || !self.block_start(t) {
            return Ok(());
        }
        if let Some(a) = &mut self.atmosphere {
            a.add(t, species_of, y);
        }
        if !self.opts.structure {
            return Ok(());
        }
        let t = t.max(self.t_eq);
        // g(r) runs on all cores; the triangulation behind ψ6 is serial, so it
        // runs beside g(r) rather than after it.
        let (pair_correlation, bond_order) = (&mut self.pair_correlation, &mut self.bond_order);
        let sim_box = &self.run.sim_box;
        let ((), psi) = rayon::join(
            || pair_correlation.add(t, species_of, x, y),
            || bond_order.add(t, sim_box, x, y),
        );
        self.bond_correlation.add(t, x, y, &psi);
        if let Some(sf) = &mut self.structure_factor {
            sf.add(t, x, y);
        }
        Ok(())
    }

    /// Whether the snapshot at time `t` starts a block of the log's
    /// `log.snapshot_schedule` (always true without one). Snapshots inside a
    /// block, closely spaced for dynamics, add correlated samples rather than
    /// information to the structure and velocity tests, which use block starts only.
    pub(super) fn block_start(&self, t: f64) -> bool {
        self.run
            .snapshot_schedule
            .is_none_or(|s| s.is_block_start(self.run.t_start, t))
    }

    /// The transport replay starts at the first snapshot analysed and checks
    /// itself against the later ones.
    fn transport_snapshot(&mut self, t: f64, species_of: &[u16], vx: &[f64], vy: &[f64], kt: f64) {
        if let Some(tr) = &mut self.transport {
            tr.check(t, (vx, vy));
        } else if !self.transport_tried {
            self.transport_tried = true;
            let t_c = match self.run.pair_rate {
                Some(omega) if omega > 0.0 => 1.0 / omega,
                _ => expected_mean_free_time(&self.run.species, &self.run.sim_box, kt),
            };
            self.transport = Transport::start(&self.run, t, species_of, (vx, vy), t_c);
        }
    }

    /// A snapshot's per-disc slices must agree in length, and its species indices
    /// must be the run's.
    pub(super) fn check_snapshot(
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
    fn push_kt(&mut self, t: f64, kt: f64) {
        match self.kt_series.last_mut() {
            Some(last) if last.0 == t => last.1 = kt,
            _ => self.kt_series.push((t, kt)),
        }
    }

    /// kT at time `t`, linearly interpolated in the recorded series.
    pub(super) fn kt_at(&self, t: f64) -> Option<f64> {
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
    pub(super) fn dof(&self) -> usize {
        degrees_of_freedom(self.run.n(), &self.run.sim_box)
    }

    /// kT at the middle of each time bin.
    fn kt_per_bin(&self) -> Vec<f64> {
        (0..self.bins.len())
            .map(|k| {
                let t_mid = self.t_eq + (k as f64 + 0.5) * self.bin_width;
                self.kt_at(t_mid).unwrap_or(f64::NAN)
            })
            .collect()
    }

    /// Compute everything: one function per observable.
    pub fn finish(mut self) -> Result<Report, StatsError> {
        self.kt_series.sort_by(|a, b| a.0.total_cmp(&b.0));
        self.energy_series.sort_by(|a, b| a.0.total_cmp(&b.0));
        let elastic = self.run.restitution.is_elastic()
            && self.run.sim_box.boundary.iter().all(
                |b| !matches!(b, carom_core::Boundary::Walls { restitution } if *restitution < 1.0),
            );
        let kt_used = temperature::snapshot_kt(&self);
        let temperature = temperature::report(&self, kt_used);
        // A cooling gas is tested in its homogeneous cooling state: each
        // snapshot's velocities scaled to the mean kT of the snapshots used.
        if !elastic {
            if let Some(kt) = kt_used {
                inelastic::scale_to(&mut self, kt);
            }
        }
        let (maxwell_boltzmann, maxwell_boltzmann_untested) =
            velocity::maxwell_boltzmann(&mut self, kt_used, !elastic)?;
        let kt_bins = self.kt_per_bin();
        let z_bins = pressure::z_per_bin(&self, &kt_bins);
        let omega_bins = collision_rate::omega_per_bin(&self);
        let pressure = pressure::report(&self, &z_bins, &kt_bins)?;
        let collision_rate = collision_rate::report(&self, &omega_bins, elastic)?;
        let bins = [&z_bins[..], &omega_bins[..], &kt_bins[..]];
        let enskog = collision_rate::enskog(&self, elastic, pressure.as_ref(), bins)?;
        let inelastic = (!elastic).then(|| inelastic::report(&self));
        let periodic = self.run.sim_box.boundary.iter().all(|b| b.is_periodic());
        let pair_correlation = contact::report(
            &self.pair_correlation,
            elastic && periodic,
            pressure.as_ref(),
        );
        let phi = packing_fraction(&self.run.species, &self.run.sim_box);
        let transport = self.transport.take().and_then(|tr| {
            (tr.pairs() == self.transport_pairs)
                .then(|| tr.report(self.run.t_end, pressure.as_ref().map(|p| p.z), phi))
                .flatten()
        });
        let gravity = self.atmosphere.as_ref().and_then(|a| {
            let kinetic: Vec<(f64, f64)> = self.energy_series.iter().map(|e| (e.0, e.1)).collect();
            a.report(&kinetic, kt_used)
        });
        let run = &self.run;
        let mut report = Report {
            n: run.n(),
            species: run
                .species
                .iter()
                .map(|s| SpeciesInfo {
                    count: s.count,
                    radius: s.radius,
                    mass: s.mass,
                })
                .collect(),
            packing_fraction: packing_fraction(&run.species, &run.sim_box),
            box_size: [run.sim_box.size.x, run.sim_box.size.y],
            periodic: run.sim_box.boundary.map(|b| b.is_periodic()),
            elastic,
            window: self.window(collision_rate.per_disc),
            dynamics: self.dynamics.report(collision_rate.per_disc),
            temperature,
            maxwell_boltzmann,
            maxwell_boltzmann_untested,
            pressure,
            collision_rate,
            enskog,
            inelastic,
            pair_correlation,
            bond_order: self.bond_order.report(),
            orientational_correlation: self
                .bond_correlation
                .report()
                .filter(|_| run.n() >= MIN_BOND_ORDER_DISCS),
            structure_factor: self
                .structure_factor
                .as_ref()
                .and_then(StructureFactor::report),
            transport,
            gravity,
            thermostat: None,
            compression: None,
            floor: None,
            not_computed: Vec::new(),
        };
        report.not_computed = not_computed::explain(&report);
        Ok(report)
    }

    /// The window analysed, with the spacing of the snapshots used in collisions
    /// per disc: counted between them for an inelastic run (whose rate changes),
    /// else at the measured rate `omega`.
    fn window(&self, omega: f64) -> WindowReport {
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

#[cfg(test)]
#[path = "analyzer_tests.rs"]
mod tests;
