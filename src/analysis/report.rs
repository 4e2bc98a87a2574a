//! What `carom analyze` measures, computed in one streaming pass over a run's
//! events: temperature, the velocity distribution of each species against
//! Maxwell–Boltzmann, pressure and compressibility factor with a block-averaged
//! standard error, the collision rate and the Enskog consistency check, and for
//! inelastic runs the temperature against time and the energy budget
//! (physics.md §5–§8).
//!
//! The [`Analyzer`] sees plain numbers (collision virials, snapshots, kinetic
//! energies), not files: the CLI feeds it from an MCAP log, the tests feed it
//! straight from the engine. [`Report`] serialises to the JSON that
//! `carom analyze --json` prints; every field is documented below.

use carom_core::{Restitution, SimBox, Species};
use serde::Serialize;

use super::stats::{block_average, blocking, mb_speed_test, Histogram, KsTest, StatsError};

/// Which run is analysed: what the log's metadata and first snapshot say.
#[derive(Debug, Clone, PartialEq)]
pub struct RunDescription {
    /// The species (count, radius, mass).
    pub species: Vec<Species>,
    /// The box.
    pub sim_box: SimBox,
    /// The pair collision rule.
    pub restitution: Restitution,
    /// Logged collisions are every `collision_stride`-th collision (1 = all); sums
    /// over logged collisions are multiplied by it.
    pub collision_stride: u64,
    /// The virial, wall impulse and collision counts come from running totals over
    /// every collision ([`Analyzer::increment`], from the `/thermo` records), and
    /// logged collisions are only counted: for logs without collisions, and for
    /// logs of every k-th collision (k > 1), whose sums would only estimate them.
    pub totals_from_thermo: bool,
    /// Simulated time of the start of the log (time).
    pub t_start: f64,
    /// Simulated time of the end of the log (time).
    pub t_end: f64,
    /// The pair collision rate ω (pair collisions per disc per unit time) known
    /// before the events are read, e.g. from the log's first and last `/thermo`
    /// records; it sets the default spacing of the snapshots used for the velocity
    /// distribution (see [`AnalysisOptions::every`]). `None`: unknown.
    pub pair_rate: Option<f64>,
    /// Time between the log's snapshots (time), from its configuration; `None`:
    /// unknown. With it the default spacing is widened only when the snapshots
    /// would otherwise hold more than [`AnalysisOptions::max_velocities`]
    /// velocities; without it, whenever a window full of snapshots could.
    pub snapshot_interval: Option<f64>,
}

/// Pair collisions per disc between the snapshots that the Maxwell–Boltzmann
/// tests use by default. A disc's speed stays correlated with itself over about
/// one collision, and correlated samples make both tests reject too often: in
/// elastic runs of 10⁴ discs (η = 0.5, three seeds, and η = 0.7, two seeds, 20–60
/// time units) χ² over 39 degrees of freedom was 230–470 with snapshots 0.2–0.35
/// collisions per disc apart, 66–106 at 1, 38–64 at 2 and 26–47 from 4 on; the
/// KS tests failed likewise below 2.
pub const DECORRELATION_COLLISIONS: f64 = 5.0;

/// Velocities (one per disc and snapshot used) that the Maxwell–Boltzmann tests keep
/// in memory by default: 32 bytes each (speed and components, and a sorted copy
/// of one of them for a KS test), so about 640 MB. When the default spacing would
/// use more, the snapshots are spaced further apart (see
/// [`AnalysisOptions::max_velocities`]). 2·10⁷ velocities resolve a difference of
/// 3·10⁻⁴ between the measured and the Maxwell–Boltzmann distribution functions
/// (the KS test's critical distance 1.36/√n at p = 0.05).
pub const MAX_VELOCITIES: usize = 20_000_000;

/// Snapshots closer than this many pair collisions per disc hold correlated
/// velocities (see [`DECORRELATION_COLLISIONS`]): `carom analyze` warns.
pub const CORRELATED_SPACING: f64 = 4.0;

impl RunDescription {
    /// Number of discs N.
    pub fn n(&self) -> usize {
        self.species.iter().map(|s| s.count).sum()
    }

    /// Degrees of freedom f = 2N − (periodic axes) (physics.md §5).
    pub fn dof(&self) -> usize {
        (2 * self.n()).saturating_sub(self.sim_box.conserved_momentum_components())
    }

    /// Packing fraction η = Σ N_s π a_s² / (L_x L_y).
    pub fn packing_fraction(&self) -> f64 {
        self.species
            .iter()
            .map(|s| s.count as f64 * s.disc_area())
            .sum::<f64>()
            / self.sim_box.area()
    }

    /// True for a box with hard walls on at least one axis.
    pub fn has_walls(&self) -> bool {
        self.sim_box.conserved_momentum_components() < 2
    }

    /// Number-weighted mean radius (length): the radius used for the area that disc
    /// centres can reach next to walls (exact for one species).
    fn mean_radius(&self) -> f64 {
        self.species
            .iter()
            .map(|s| s.count as f64 * s.radius)
            .sum::<f64>()
            / self.n().max(1) as f64
    }

    /// Area reachable by disc centres, Π (L − 2a) over walled axes and L over
    /// periodic ones (length², physics.md §5).
    pub fn accessible_area(&self) -> f64 {
        let a = self.mean_radius();
        (0..2).map(|k| self.accessible_length(k, a)).product()
    }

    fn accessible_length(&self, k: usize, a: f64) -> f64 {
        let l = self.sim_box.size[k];
        if self.sim_box.boundary[k].is_periodic() {
            l
        } else {
            l - 2.0 * a
        }
    }

    /// Total length of wall that disc centres touch: for each walled axis, two
    /// walls as long as the reachable extent of the other axis (length).
    pub fn accessible_wall_length(&self) -> f64 {
        let a = self.mean_radius();
        (0..2)
            .filter(|&k| !self.sim_box.boundary[k].is_periodic())
            .map(|k| 2.0 * self.accessible_length(1 - k, a))
            .sum()
    }
}

/// Choices of `carom analyze`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AnalysisOptions {
    /// Ignore everything before this simulated time (time). `None`: the first 10 %
    /// of the log's time span.
    pub equilibrate: Option<f64>,
    /// Use snapshots at least this far apart for the velocity distribution (time).
    /// `None`: [`DECORRELATION_COLLISIONS`] collision times apart when
    /// [`RunDescription::pair_rate`] is known, otherwise every snapshot after
    /// `equilibrate`; either way spaced further apart when that would keep more
    /// than `max_velocities` velocities.
    pub every: Option<f64>,
    /// The most velocities (discs × snapshots used) that the default spacing keeps
    /// in memory; an `every` asked for is used as it is. Default
    /// [`MAX_VELOCITIES`].
    pub max_velocities: usize,
    /// Bins of the speed histograms (before merging for χ²).
    pub speed_bins: usize,
    /// Time bins for the pressure and collision-rate series (a power of two suits
    /// the blocking analysis).
    pub time_bins: usize,
}

impl Default for AnalysisOptions {
    fn default() -> Self {
        AnalysisOptions {
            equilibrate: None,
            every: None,
            max_velocities: MAX_VELOCITIES,
            speed_bins: 40,
            time_bins: 1024,
        }
    }
}

/// p-value below which a Maxwell–Boltzmann test counts as failed (either test).
pub const MB_P_THRESHOLD: f64 = 1e-3;

/// The largest correlation of a species' velocities between the snapshots its
/// Maxwell–Boltzmann tests use. The default spacing ([`DECORRELATION_COLLISIONS`])
/// is set by the collision rate of all discs, but a heavy disc keeps its velocity
/// over about M/m collisions with light ones: in a run with 100 discs of mass 10⁶
/// among 10⁴ of mass 1 the heavy discs' velocities hardly changed over the whole
/// run, and 31 snapshots of the same 100 velocities failed both tests (χ² = 797 over
/// 29 degrees of freedom). A species whose velocities correlate more than this from
/// one snapshot to the next is tested on every k-th snapshot only, with k the
/// smallest for which the correlation, decaying as ρ^k, falls to this. (Only with
/// the default spacing: a spacing asked for, [`AnalysisOptions::every`], is used as
/// it is, the correlation still reported.)
pub const MAX_SNAPSHOT_CORRELATION: f64 = 0.05;

/// The correlation of a species' velocities between consecutive snapshots: `vx`,
/// `vy` hold `per` discs' components per snapshot, snapshot after snapshot, each
/// disc at the same place in every snapshot. Components are taken relative to
/// their mean over all snapshots. `None` with fewer than two snapshots or no
/// variation.
fn snapshot_correlation(vx: &[f64], vy: &[f64], per: usize) -> Option<f64> {
    let snapshots = vx.len().checked_div(per)?;
    if snapshots < 2 {
        return None;
    }
    let (mut cross, mut before, mut after) = (0.0, 0.0, 0.0);
    for v in [vx, vy] {
        let mean = v.iter().sum::<f64>() / v.len() as f64;
        for (a, b) in v.iter().zip(&v[per..]) {
            let (a, b) = (a - mean, b - mean);
            cross += a * b;
            before += a * a;
            after += b * b;
        }
    }
    let rho = cross / (before * after).sqrt();
    rho.is_finite().then_some(rho)
}

/// Every how many snapshots a species whose velocities correlate `rho` between
/// consecutive snapshots is tested ([`MAX_SNAPSHOT_CORRELATION`]); `usize::MAX`
/// (the first snapshot only) when they hardly change.
fn snapshot_step(rho: Option<f64>) -> usize {
    match rho {
        Some(r) if r > MAX_SNAPSHOT_CORRELATION => {
            let k = (MAX_SNAPSHOT_CORRELATION.ln() / r.min(1.0).ln()).ceil();
            if k.is_finite() && k < 1e9 {
                k as usize
            } else {
                usize::MAX
            }
        }
        _ => 1,
    }
}

/// The values of every `step`-th snapshot of `v` (`per` values per snapshot).
fn every_nth_snapshot(v: &[f64], per: usize, step: usize) -> Vec<f64> {
    v.chunks(per.max(1))
        .step_by(step)
        .flatten()
        .copied()
        .collect()
}

#[derive(Debug, Clone, Copy, Default)]
struct TimeBin {
    virial: f64,
    wall_impulse: f64,
    pairs: u64,
    walls: u64,
    /// Pair collisions from [`Analyzer::increment`] (already scaled, fractional).
    pairs_weighted: f64,
}

/// The spacing (time) of snapshots in a window of length `window` that keeps at
/// most `max_velocities` velocities of `n` discs, or `None` if snapshots
/// `spacing` apart (`None`: any distance apart) keep no more than that. With room
/// for fewer than two snapshots, the spacing is the whole window, which keeps one
/// (or two, at its very ends).
fn budget_spacing(
    n: usize,
    max_velocities: usize,
    window: f64,
    spacing: Option<f64>,
) -> Option<f64> {
    // Snapshots at least `s` apart in a window of length `window` number at most
    // ⌊window/s⌋ + 1.
    let room = max_velocities / n.max(1);
    if let Some(s) = spacing.filter(|s| *s > 0.0) {
        let snapshots = (window / s).floor() + 1.0;
        if snapshots <= room as f64 {
            return None;
        }
    }
    Some(match room {
        0 | 1 => window,
        m => window / (m - 1) as f64,
    })
}

/// Accumulates a run's events and produces a [`Report`].
#[derive(Debug, Clone)]
pub struct Analyzer {
    run: RunDescription,
    opts: AnalysisOptions,
    t_eq: f64,
    bin_width: f64,
    bins: Vec<TimeBin>,
    /// (time, kT) from every thermo record and snapshot, in time order.
    kt_series: Vec<(f64, f64)>,
    /// (time, K, dissipated energy so far when the source reports it).
    energy_series: Vec<(f64, f64, Option<f64>)>,
    lost_from_collisions: f64,
    pair_total: u64,
    wall_total: u64,
    pairs_from_increments: u64,
    speeds: Vec<Vec<f64>>,
    vx: Vec<Vec<f64>>,
    vy: Vec<Vec<f64>>,
    mb_kinetic: f64,
    snapshots_used: Vec<f64>,
    snapshots_seen: usize,
    /// Whether `opts.every` was chosen here (from the collision rate or the memory
    /// bound) rather than asked for.
    every_default: bool,
    /// Whether the memory bound set `opts.every` (spacing the snapshots further
    /// apart than the collision rate asks).
    every_from_budget: bool,
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
        let (every_default, every_from_budget) = match opts.every {
            Some(_) => (false, false),
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
        Ok(Analyzer {
            every_default,
            every_from_budget,
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
            snapshots_seen: 0,
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

    /// A thermodynamic record: kinetic energy K (energy) at time `t`, and the
    /// energy dissipated since the start when known.
    pub fn thermo(&mut self, t: f64, kinetic_energy: f64, energy_lost: Option<f64>) {
        let kt = 2.0 * kinetic_energy / self.run.dof().max(1) as f64;
        self.push_kt(t, kt);
        match self.energy_series.last_mut() {
            Some(last) if last.0 == t => *last = (t, kinetic_energy, energy_lost.or(last.2)),
            _ => self.energy_series.push((t, kinetic_energy, energy_lost)),
        }
    }

    /// A snapshot at time `t`: species index and velocity components of every disc
    /// (length/time). Used for the temperature series, and for the velocity
    /// distribution when it is after `equilibrate` and at least `every` after the
    /// last snapshot used.
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
        if species_of.len() != vx.len() || vx.len() != vy.len() {
            return Err(StatsError::InvalidArgument(format!(
                "snapshot at t = {t}: {} species indices, {} vx, {} vy",
                species_of.len(),
                vx.len(),
                vy.len()
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
        self.snapshots_seen += 1;
        let masses: Vec<f64> = self.run.species.iter().map(|s| s.mass).collect();
        let k: f64 = species_of
            .iter()
            .zip(vx.iter().zip(vy))
            .map(|(&s, (&x, &y))| 0.5 * masses[s as usize] * (x * x + y * y))
            .sum();
        let kt = 2.0 * k / self.run.dof().max(1) as f64;
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
        if let (Some(&last), Some(every)) = (self.snapshots_used.last(), self.opts.every) {
            if t < last + every * (1.0 - 1e-9) {
                return Ok(());
            }
        }
        self.snapshots_used.push(t);
        self.mb_kinetic += k;
        for (&s, (&x, &y)) in species_of.iter().zip(vx.iter().zip(vy)) {
            let s = s as usize;
            self.speeds[s].push(x.hypot(y));
            self.vx[s].push(x);
            self.vy[s].push(y);
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
    fn kt_at(&self, t: f64) -> Option<f64> {
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

    /// Compute everything.
    pub fn finish(mut self) -> Result<Report, StatsError> {
        self.kt_series.sort_by(|a, b| a.0.total_cmp(&b.0));
        self.energy_series.sort_by(|a, b| a.0.total_cmp(&b.0));
        let run = &self.run;
        let n = run.n();
        let nf = n as f64;
        let f = run.dof();
        let elastic = run.restitution.is_elastic()
            && run.sim_box.boundary.iter().all(
                |b| !matches!(b, carom_core::Boundary::Walls { restitution } if *restitution < 1.0),
            );

        // ---- temperature
        let kt_used = if self.snapshots_used.is_empty() {
            None
        } else {
            Some(2.0 * self.mb_kinetic / (self.snapshots_used.len() as f64 * f.max(1) as f64))
        };
        let temperature = TemperatureReport {
            kt: kt_used
                .or_else(|| self.kt_at(self.t_eq))
                .unwrap_or(f64::NAN),
            kt_initial: self.kt_series.first().map(|p| p.1),
            kt_final: self.kt_series.last().map(|p| p.1),
            dof: f,
            conserved_momentum_components: run.sim_box.conserved_momentum_components(),
            convention: "kT = 2K/f, f = 2N − (number of periodic axes) (physics.md §5)",
            series: subsample(&self.kt_series, MAX_SERIES),
        };

        // ---- Maxwell–Boltzmann per species
        let mut maxwell_boltzmann = Vec::new();
        let mut maxwell_boltzmann_untested = Vec::new();
        if let Some(kt) = kt_used {
            for (s, sp) in run.species.iter().enumerate() {
                if self.speeds[s].len() < 2 {
                    continue;
                }
                // Discs of this species per snapshot. With the default spacing its
                // samples are thinned to snapshots far enough apart for its own
                // velocities to decorrelate; a spacing asked for is used as it is.
                let per = self.speeds[s].len() / self.snapshots_used.len().max(1);
                let correlation = snapshot_correlation(&self.vx[s], &self.vy[s], per);
                let step = if self.every_default {
                    snapshot_step(correlation)
                } else {
                    1
                };
                if step > 1 {
                    for v in [&mut self.speeds[s], &mut self.vx[s], &mut self.vy[s]] {
                        *v = every_nth_snapshot(v, per, step);
                    }
                }
                let snapshots = self.speeds[s].len() / per.max(1);
                // Discs at rest (placed so with explicit velocities) have no
                // distribution to test.
                if kt <= 0.0 {
                    maxwell_boltzmann_untested.push(SpeciesUntested {
                        species: s,
                        samples: self.speeds[s].len(),
                        reason: format!("no thermal motion (kT = {kt})"),
                    });
                    continue;
                }
                // A species with too few speeds for the χ² test (a handful of
                // discs in a short window) is reported as untested; the other
                // species and the rest of the analysis go on.
                let t =
                    match mb_speed_test(&self.speeds[s], sp.mass, kt, self.opts.speed_bins, true) {
                        Err(StatsError::NotEnoughData(why)) => {
                            maxwell_boltzmann_untested.push(SpeciesUntested {
                                species: s,
                                samples: self.speeds[s].len(),
                                reason: why,
                            });
                            continue;
                        }
                        r => r?,
                    };
                let mb = t.reference;
                let comp_hist = |v: &[f64]| {
                    let l = 4.5 * mb.scale();
                    Histogram::from_values(v.iter().copied(), -l, l, self.opts.speed_bins)
                };
                let ks_x = super::stats::ks_test(&self.vx[s], |v| mb.component_cdf(v))?;
                let ks_y = super::stats::ks_test(&self.vy[s], |v| mb.component_cdf(v))?;
                let passed =
                    t.chi_square.p_value >= MB_P_THRESHOLD && t.ks.p_value >= MB_P_THRESHOLD;
                maxwell_boltzmann.push(SpeciesMb {
                    species: s,
                    mass: sp.mass,
                    radius: sp.radius,
                    samples: self.speeds[s].len(),
                    snapshots,
                    snapshot_correlation: correlation,
                    snapshot_step: step.min(self.snapshots_used.len()),
                    kt,
                    speed_histogram: HistogramReport::new(&t.histogram, |v| mb.speed_pdf(v)),
                    vx_histogram: HistogramReport::new(&comp_hist(&self.vx[s])?, |v| {
                        mb.component_pdf(v)
                    }),
                    vy_histogram: HistogramReport::new(&comp_hist(&self.vy[s])?, |v| {
                        mb.component_pdf(v)
                    }),
                    chi_square: ChiSquareReport {
                        statistic: t.chi_square.statistic,
                        dof: t.chi_square.dof,
                        p_value: t.chi_square.p_value,
                        bins: t.chi_square.bins,
                    },
                    ks: KsReport::from(&t.ks),
                    ks_vx: KsReport::from(&ks_x),
                    ks_vy: KsReport::from(&ks_y),
                    passed,
                });
            }
        }

        // ---- pressure, collision rate, Enskog check (per time bin, then blocked)
        let dt = self.bin_width;
        let walls = run.has_walls();
        let area = if walls {
            run.accessible_area()
        } else {
            run.sim_box.area()
        };
        let wall_len = run.accessible_wall_length();
        let stride = run.collision_stride as f64;
        let mut z_bins = Vec::with_capacity(self.bins.len());
        let mut omega_bins = Vec::with_capacity(self.bins.len());
        let mut kt_bins = Vec::with_capacity(self.bins.len());
        for (k, b) in self.bins.iter().enumerate() {
            let t_mid = self.t_eq + (k as f64 + 0.5) * dt;
            let kt = self.kt_at(t_mid).unwrap_or(f64::NAN);
            let z = if walls {
                // βPA/N with P = wall impulse / (time × wall length), A reachable.
                b.wall_impulse / (dt * wall_len) * area / (nf * kt)
            } else {
                // βPA/N = 1 + W/(N kT), W = Σ r·Δp / (2 t)  (physics.md §5).
                1.0 + b.virial / (2.0 * dt) / (nf * kt)
            };
            z_bins.push(z);
            omega_bins.push(2.0 * (stride * b.pairs as f64 + b.pairs_weighted) / (nf * dt));
            kt_bins.push(kt);
        }
        let pressure = if z_bins.iter().all(|z| z.is_finite()) {
            let est = blocked(&z_bins)?;
            let bp = est.mean * nf / area;
            let kt_mean = kt_bins.iter().sum::<f64>() / kt_bins.len() as f64;
            Some(PressureReport {
                estimator: if walls {
                    "wall impulse: βPA/N with P = Σ|Δp_wall|/(t × wall length) and A, wall \
                     length reachable by centres (physics.md §5)"
                } else {
                    "collision virial: βPA/N = 1 + W/(N kT), W = Σ r_ij·Δp_i/(2t), \
                     kT = 2K/f (physics.md §5)"
                },
                z: est.mean,
                z_std_error: est.std_error,
                beta_p: bp,
                beta_p_std_error: est.std_error * nf / area,
                p: bp * kt_mean,
                area,
                blocks: est.blocks,
                block_time: est.block_len as f64 * dt,
                converged: est.converged,
                series: coarse_series(&z_bins, self.t_eq, dt, 64),
            })
        } else {
            None
        };
        let omega_est = blocked(&omega_bins)?;
        let collision_rate = CollisionRateReport {
            per_disc: omega_est.mean,
            std_error: omega_est.std_error,
            logged_pair_collisions: self.pair_total,
            logged_wall_collisions: self.wall_total,
            collision_stride: run.collision_stride,
            window: [self.t_eq, run.t_end],
        };
        let monodisperse = run.species.iter().filter(|s| s.count > 0).count() == 1;
        let enskog = if let (true, Some(pr)) = (monodisperse && !walls && elastic, &pressure) {
            let sp = run
                .species
                .iter()
                .find(|s| s.count > 0)
                .expect("monodisperse");
            let sigma = 2.0 * sp.radius;
            let c = std::f64::consts::PI.sqrt() / 4.0;
            let d: Vec<f64> = (0..z_bins.len())
                .map(|k| {
                    (z_bins[k] - 1.0) - c * omega_bins[k] * sigma * (sp.mass / kt_bins[k]).sqrt()
                })
                .collect();
            let rhs: Vec<f64> = (0..z_bins.len())
                .map(|k| c * omega_bins[k] * sigma * (sp.mass / kt_bins[k]).sqrt())
                .collect();
            let d_est = blocked(&d)?;
            let rhs_est = blocked(&rhs)?;
            let z = pr.z;
            Some(EnskogReport {
                z_minus_1: z - 1.0,
                rate_term: rhs_est.mean,
                rate_term_std_error: rhs_est.std_error,
                difference: d_est.mean,
                difference_std_error: d_est.std_error,
                relation: "Z − 1 = (√π/4) ω τ0, τ0 = σ √(m/kT) (physics.md §7)",
            })
        } else {
            None
        };

        // ---- inelastic runs: temperature against time, energy budget, Haff's law
        let inelastic = if elastic {
            None
        } else {
            Some(self.inelastic_report())
        };

        Ok(Report {
            n,
            species: run
                .species
                .iter()
                .map(|s| SpeciesInfo {
                    count: s.count,
                    radius: s.radius,
                    mass: s.mass,
                })
                .collect(),
            packing_fraction: run.packing_fraction(),
            box_size: [run.sim_box.size.x, run.sim_box.size.y],
            periodic: [
                run.sim_box.boundary[0].is_periodic(),
                run.sim_box.boundary[1].is_periodic(),
            ],
            elastic,
            window: WindowReport {
                t_start: run.t_start,
                t_end: run.t_end,
                equilibrate: self.t_eq,
                every: self.opts.every,
                every_default: self.every_default,
                every_from_budget: self.every_from_budget,
                max_velocities: self.opts.max_velocities,
                spacing_collisions: self
                    .snapshots_used
                    .windows(2)
                    .map(|w| w[1] - w[0])
                    .reduce(f64::min)
                    .map(|gap| gap * collision_rate.per_disc),
                snapshots_seen: self.snapshots_seen,
                snapshot_times: self.snapshots_used.clone(),
            },
            temperature,
            maxwell_boltzmann,
            maxwell_boltzmann_untested,
            pressure,
            collision_rate,
            enskog,
            inelastic,
        })
    }

    fn inelastic_report(&self) -> InelasticReport {
        let first = self.energy_series.first().copied();
        let last = self.energy_series.last().copied();
        let (e0, e1) = (first.map(|e| e.1), last.map(|e| e.1));
        // Dissipated energy between the first and last record: exact when the
        // source reports running totals, else the sum over logged collisions.
        let lost = match (first, last) {
            (Some((_, _, Some(a))), Some((_, _, Some(b)))) => Some(b - a),
            _ => None,
        };
        let lost_source = if lost.is_some() {
            "running total of the thermo records"
        } else {
            "sum over logged collisions × stride"
        };
        let lost = lost.unwrap_or(self.lost_from_collisions);
        let budget = match (e0, e1) {
            (Some(e0), Some(e1)) => Some(EnergyBudget {
                initial: e0,
                final_: e1,
                dissipated: lost,
                dissipated_source: lost_source,
                residual: e0 - lost - e1,
                relative_residual: (e0 - lost - e1) / e0,
            }),
            _ => None,
        };
        let haff = match self.run.restitution {
            Restitution::Normal(e) if e < 1.0 => self.haff(e),
            _ => None,
        };
        InelasticReport {
            energy: budget,
            haff,
        }
    }

    /// Haff's law (physics.md §8) with the collision frequency measured over the
    /// run: in homogeneous cooling ω ∝ √T, so c = ω/√T = (2 N_pair/N) / ∫ √kT dt.
    fn haff(&self, e: f64) -> Option<HaffReport> {
        let s = &self.kt_series;
        if s.len() < 3 {
            return None;
        }
        let (t0, kt0) = s[0];
        let integral: f64 = s
            .windows(2)
            .map(|w| 0.5 * (w[1].0 - w[0].0) * (w[0].1.max(0.0).sqrt() + w[1].1.max(0.0).sqrt()))
            .sum();
        let logged = if self.run.totals_from_thermo {
            0.0
        } else {
            self.pair_total as f64 * self.run.collision_stride as f64
        };
        let pairs = logged + self.pairs_from_increments as f64;
        if integral <= 0.0 || pairs == 0.0 {
            return None;
        }
        let c = 2.0 * pairs / self.run.n() as f64 / integral;
        let a2 =
            16.0 * (1.0 - e) * (1.0 - 2.0 * e * e) / (57.0 - 25.0 * e + 30.0 * e * e * (1.0 - e));
        let omega0 = c * kt0.sqrt();
        let inv_t0 = (1.0 - e * e) * (1.0 + 3.0 * a2 / 16.0) * omega0 / 4.0;
        let (t_last, kt_last) = s[s.len() - 1];
        let predicted = kt0 / (1.0 + (t_last - t0) * inv_t0).powi(2);
        Some(HaffReport {
            a2,
            collision_frequency_initial: omega0,
            t0: 1.0 / inv_t0,
            kt_final_predicted: predicted,
            kt_final_measured: kt_last,
            ratio: kt_last / predicted,
        })
    }
}

/// A blocked estimate: the automatic blocking analysis when it converges, else 16
/// equal blocks.
struct Blocked {
    mean: f64,
    std_error: f64,
    blocks: usize,
    block_len: usize,
    converged: bool,
}

fn blocked(x: &[f64]) -> Result<Blocked, StatsError> {
    let b = blocking(x)?;
    if b.converged {
        let lv = b.levels[b.chosen];
        return Ok(Blocked {
            mean: b.mean,
            std_error: b.std_error,
            blocks: lv.blocks,
            block_len: lv.block_len,
            converged: true,
        });
    }
    let e = block_average(x, 16)?;
    Ok(Blocked {
        mean: b.mean,
        std_error: e.std_error,
        blocks: e.blocks,
        block_len: e.block_len,
        converged: false,
    })
}

/// Most points in a time series of the report.
const MAX_SERIES: usize = 2000;

/// At most `max` points of `s`, evenly spaced in index, always keeping the last.
fn subsample(s: &[(f64, f64)], max: usize) -> Vec<[f64; 2]> {
    let step = s.len().div_ceil(max).max(1);
    let mut out: Vec<[f64; 2]> = s.iter().step_by(step).map(|&(t, v)| [t, v]).collect();
    if let Some(&(t, v)) = s.last() {
        if out.last().is_some_and(|p| p[0] != t) {
            out.push([t, v]);
        }
    }
    out
}

/// Averages of `x` over `parts` consecutive groups, with their mid times.
fn coarse_series(x: &[f64], t0: f64, dt: f64, parts: usize) -> Vec<[f64; 2]> {
    let len = (x.len() / parts).max(1);
    x.chunks(len)
        .enumerate()
        .map(|(k, c)| {
            let t = t0 + (k * len) as f64 * dt + 0.5 * c.len() as f64 * dt;
            [t, c.iter().sum::<f64>() / c.len() as f64]
        })
        .collect()
}

// ---------------------------------------------------------------------------
// The report (the JSON of `carom analyze --json`)
// ---------------------------------------------------------------------------

/// Everything `carom analyze` reports. Serialised as one JSON object; units are
/// the run's (length, time, mass; energies as kT).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Report {
    /// Number of discs N.
    pub n: usize,
    /// The species.
    pub species: Vec<SpeciesInfo>,
    /// Packing fraction η = Σ N_s π a_s² / (L_x L_y).
    pub packing_fraction: f64,
    /// Box edge lengths [L_x, L_y] (length).
    pub box_size: [f64; 2],
    /// Whether the x and y axes are periodic (else hard walls).
    pub periodic: [bool; 2],
    /// True when pair and wall collisions conserve energy.
    pub elastic: bool,
    /// Which part of the log was used.
    pub window: WindowReport,
    /// Temperature and its degrees-of-freedom convention.
    pub temperature: TemperatureReport,
    /// Velocity distribution against Maxwell–Boltzmann, one entry per species with
    /// enough samples for the tests (the others are in
    /// `maxwell_boltzmann_untested`).
    pub maxwell_boltzmann: Vec<SpeciesMb>,
    /// Species with speeds but too few for the Maxwell–Boltzmann tests.
    pub maxwell_boltzmann_untested: Vec<SpeciesUntested>,
    /// Pressure and compressibility factor; `null` when no temperature is known.
    pub pressure: Option<PressureReport>,
    /// Pair collisions per disc per unit time.
    pub collision_rate: CollisionRateReport,
    /// Enskog consistency check (periodic, monodisperse, elastic runs only).
    pub enskog: Option<EnskogReport>,
    /// Inelastic runs only: cooling and energy budget.
    pub inelastic: Option<InelasticReport>,
}

/// One species of the run.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SpeciesInfo {
    /// Number of discs.
    pub count: usize,
    /// Radius (length).
    pub radius: f64,
    /// Mass (mass).
    pub mass: f64,
}

/// The part of the log analysed.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct WindowReport {
    /// First simulated time in the log (time).
    pub t_start: f64,
    /// Last simulated time in the log (time).
    pub t_end: f64,
    /// Data before this time are ignored (time).
    pub equilibrate: f64,
    /// Minimum spacing of the snapshots used for the velocity distribution (time);
    /// `null`: every snapshot.
    pub every: Option<f64>,
    /// Whether `every` is the default rather than asked for: [`DECORRELATION_COLLISIONS`]
    /// collision times from the log's collision rate, or more when that would keep
    /// more than `max_velocities` velocities.
    pub every_default: bool,
    /// Whether the default `every` was widened to keep at most `max_velocities`
    /// velocities in memory.
    pub every_from_budget: bool,
    /// The most velocities (discs × snapshots) the default spacing keeps.
    pub max_velocities: usize,
    /// The smallest spacing of the snapshots used, in pair collisions per disc (ω
    /// times the spacing, with the measured ω); `null` with fewer than two. Below
    /// about 4, the velocities of consecutive snapshots are correlated and the
    /// Maxwell–Boltzmann tests reject too often.
    pub spacing_collisions: Option<f64>,
    /// Snapshots in the log.
    pub snapshots_seen: usize,
    /// Times of the snapshots used for the velocity distribution.
    pub snapshot_times: Vec<f64>,
}

/// Temperature (physics.md §5).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TemperatureReport {
    /// kT = 2K/f averaged over the snapshots used (energy); if none, at the start of
    /// the window.
    pub kt: f64,
    /// kT at the first record of the log.
    pub kt_initial: Option<f64>,
    /// kT at the last record of the log.
    pub kt_final: Option<f64>,
    /// Degrees of freedom f.
    pub dof: usize,
    /// Momentum components conserved (periodic axes), subtracted from 2N.
    pub conserved_momentum_components: usize,
    /// The convention in words.
    pub convention: &'static str,
    /// [time, kT] from the thermo records and snapshots of the whole log (at most
    /// 2000 points, evenly subsampled).
    pub series: Vec<[f64; 2]>,
}

/// A histogram with the theoretical density at the bin centres.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct HistogramReport {
    /// Bin edges (bins + 1 values).
    pub edges: Vec<f64>,
    /// Counts per bin.
    pub counts: Vec<u64>,
    /// Values outside the edges (below, above).
    pub outside: [u64; 2],
    /// Estimated density per bin, count / (total × width).
    pub density: Vec<f64>,
    /// Maxwell–Boltzmann density at the bin centres.
    pub theory: Vec<f64>,
}

impl HistogramReport {
    fn new(h: &Histogram, pdf: impl Fn(f64) -> f64) -> Self {
        HistogramReport {
            edges: h.edges(),
            counts: h.counts.clone(),
            outside: [h.underflow, h.overflow],
            density: h.density(),
            theory: h.centres().into_iter().map(pdf).collect(),
        }
    }
}

/// χ² test result (physics.md §6).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ChiSquareReport {
    /// χ² statistic.
    pub statistic: f64,
    /// Degrees of freedom: merged bins − 1 − 1 (kT measured from the data).
    pub dof: usize,
    /// p-value.
    pub p_value: f64,
    /// Bins after merging to ≥ 5 expected counts.
    pub bins: usize,
}

/// Kolmogorov–Smirnov test result. The temperature is measured from the same
/// data, so the p-value is conservative (Lilliefors).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct KsReport {
    /// D statistic.
    pub statistic: f64,
    /// Sample size.
    pub n: usize,
    /// p-value (asymptotic Kolmogorov with Stephens' correction).
    pub p_value: f64,
}

impl From<&KsTest> for KsReport {
    fn from(k: &KsTest) -> Self {
        KsReport {
            statistic: k.statistic,
            n: k.n,
            p_value: k.p_value,
        }
    }
}

/// A species whose velocities could not be tested against Maxwell–Boltzmann.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SpeciesUntested {
    /// Species index.
    pub species: usize,
    /// Speeds in the window (discs × snapshots).
    pub samples: usize,
    /// Why the tests could not be made.
    pub reason: String,
}

/// One species' velocities against the 2D Maxwell–Boltzmann distribution
/// (physics.md §6).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SpeciesMb {
    /// Species index.
    pub species: usize,
    /// Mass (mass).
    pub mass: f64,
    /// Radius (length).
    pub radius: f64,
    /// Speeds used (discs × snapshots).
    pub samples: usize,
    /// Snapshots used for this species.
    pub snapshots: usize,
    /// Correlation of this species' velocities between consecutive snapshots of
    /// the window (before thinning; `None` with fewer than two).
    pub snapshot_correlation: Option<f64>,
    /// Every how many of the window's snapshots this species was tested on: 1, or
    /// more when its velocities correlate more than [`MAX_SNAPSHOT_CORRELATION`]
    /// from one to the next (a heavy species).
    pub snapshot_step: usize,
    /// kT of the reference distribution (energy), measured from the same snapshots.
    pub kt: f64,
    /// Speed histogram over [0, 4.5 √(kT/m)) with the MB speed pdf.
    pub speed_histogram: HistogramReport,
    /// v_x histogram over ±4.5 √(kT/m) with the Gaussian pdf.
    pub vx_histogram: HistogramReport,
    /// v_y histogram.
    pub vy_histogram: HistogramReport,
    /// χ² of the speed histogram.
    pub chi_square: ChiSquareReport,
    /// KS test of the speeds.
    pub ks: KsReport,
    /// KS test of v_x against the Gaussian.
    pub ks_vx: KsReport,
    /// KS test of v_y against the Gaussian.
    pub ks_vy: KsReport,
    /// Both speed tests have p ≥ 10⁻³.
    pub passed: bool,
}

/// Pressure and compressibility factor with one standard error (physics.md §5).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PressureReport {
    /// How P was measured.
    pub estimator: &'static str,
    /// Z = βPA/N.
    pub z: f64,
    /// One standard error of Z (blocking analysis over time bins).
    pub z_std_error: f64,
    /// βP (1/length²).
    pub beta_p: f64,
    /// Standard error of βP.
    pub beta_p_std_error: f64,
    /// P = βP × kT (energy/length²), with kT averaged over the window.
    pub p: f64,
    /// Area A used (length²): the box, or the area reachable by centres with walls.
    pub area: f64,
    /// Independent blocks the error is estimated from.
    pub blocks: usize,
    /// Duration of one block (time).
    pub block_time: f64,
    /// False when the blocking analysis found no plateau (error from 16 blocks;
    /// the run may be too short for its correlation time).
    pub converged: bool,
    /// Z against time: [time, Z] averaged over ~64 consecutive intervals.
    pub series: Vec<[f64; 2]>,
}

/// Pair collision rate (physics.md §7).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CollisionRateReport {
    /// ω = 2 N_pair / (N t): pair collisions per disc per unit time (1/time).
    pub per_disc: f64,
    /// One standard error of ω.
    pub std_error: f64,
    /// Logged pair collisions in the whole log.
    pub logged_pair_collisions: u64,
    /// Logged wall collisions in the whole log.
    pub logged_wall_collisions: u64,
    /// Every k-th collision is logged; counts are scaled by it.
    pub collision_stride: u64,
    /// [start, end] of the window the rate is measured over (time).
    pub window: [f64; 2],
}

/// Enskog consistency check Z − 1 = (√π/4) ω τ0 (physics.md §7).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct EnskogReport {
    /// Z − 1 from the pressure.
    pub z_minus_1: f64,
    /// (√π/4) ω τ0 from the collision rate.
    pub rate_term: f64,
    /// Its standard error.
    pub rate_term_std_error: f64,
    /// (Z − 1) − (√π/4) ω τ0, blocked per time bin (correlations included); 0
    /// within a few standard errors when pressure and rate agree.
    pub difference: f64,
    /// One standard error of the difference.
    pub difference_std_error: f64,
    /// The relation in words.
    pub relation: &'static str,
}

/// Inelastic runs: energy budget and Haff's law (physics.md §8); the temperature
/// against time is [`TemperatureReport::series`].
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct InelasticReport {
    /// Energy at the first and last record against the energy dissipated between.
    pub energy: Option<EnergyBudget>,
    /// Haff's law check (normal restitution only).
    pub haff: Option<HaffReport>,
}

/// E(t_end) = E(t_start) − dissipated (physics.md §8).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct EnergyBudget {
    /// Kinetic energy at the first record (energy).
    pub initial: f64,
    /// Kinetic energy at the last record (energy).
    #[serde(rename = "final")]
    pub final_: f64,
    /// Energy dissipated in between (energy).
    pub dissipated: f64,
    /// Where `dissipated` comes from.
    pub dissipated_source: &'static str,
    /// initial − dissipated − final (energy); 0 up to rounding when exact.
    pub residual: f64,
    /// residual / initial.
    pub relative_residual: f64,
}

/// Haff's law T(t) = T0/(1 + t/t0)² with 1/t0 = (1 − e²)(1 + 3a2/16) ω(T0)/4
/// (physics.md §8), ω(T0) from the measured collision rate scaled as √T.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct HaffReport {
    /// a2 (van Noije & Ernst) for the run's e.
    pub a2: f64,
    /// ω(T0) (1/time).
    pub collision_frequency_initial: f64,
    /// t0 (time).
    pub t0: f64,
    /// Haff's kT at the last record.
    pub kt_final_predicted: f64,
    /// Measured kT at the last record.
    pub kt_final_measured: f64,
    /// measured / predicted (1 in homogeneous cooling; clustering makes it differ).
    pub ratio: f64,
}

#[cfg(test)]
mod tests {
    use super::*;

    fn run() -> RunDescription {
        RunDescription {
            species: vec![Species::reference(2)],
            sim_box: SimBox::periodic(10.0, 10.0),
            restitution: Restitution::Elastic,
            collision_stride: 1,
            totals_from_thermo: false,
            t_start: 0.0,
            t_end: 10.0,
            pair_rate: None,
            snapshot_interval: None,
        }
    }

    #[test]
    fn the_memory_bound_spaces_snapshots_only_when_they_would_exceed_it() {
        // 100 discs, room for 10 snapshots, a window of 9.
        let b = |spacing| budget_spacing(100, 1000, 9.0, spacing);
        // Snapshots 1 apart: 10 of them fit; 0.5 apart: 19 would not.
        assert_eq!(b(Some(1.0)), None);
        assert_eq!(b(Some(0.5)), Some(1.0));
        // Spacing unknown: assume a window full of snapshots.
        assert_eq!(b(None), Some(1.0));
        assert_eq!(b(Some(0.0)), Some(1.0));
        // Room for one snapshot or none: the whole window apart.
        assert_eq!(budget_spacing(100, 150, 9.0, Some(0.5)), Some(9.0));
        assert_eq!(budget_spacing(100, 50, 9.0, None), Some(9.0));
        // Room for two: the window's two ends.
        assert_eq!(budget_spacing(100, 200, 9.0, Some(0.5)), Some(9.0));
        assert_eq!(budget_spacing(100, 300, 9.0, Some(0.5)), Some(4.5));
    }

    #[test]
    fn snapshot_thinning_follows_the_correlation() {
        // Two discs, three snapshots: the same velocities each time, then reversed.
        let same = [1.0, -1.0, 1.0, -1.0, 1.0, -1.0];
        let zeros = [0.0; 6];
        let rho = snapshot_correlation(&same, &zeros, 2).unwrap();
        assert!((rho - 1.0).abs() < 1e-12, "{rho}");
        let flip = [1.0, -1.0, -1.0, 1.0, 1.0, -1.0];
        let rho = snapshot_correlation(&flip, &zeros, 2).unwrap();
        assert!((rho + 1.0).abs() < 1e-12, "{rho}");
        assert_eq!(snapshot_correlation(&same[..2], &zeros[..2], 2), None);
        assert_eq!(snapshot_correlation(&zeros, &zeros, 2), None);
        // ρ^k ≤ 0.05: k = 1 below it, ⌈ln 0.05 / ln ρ⌉ above, the first only at 1.
        assert_eq!(snapshot_step(None), 1);
        assert_eq!(snapshot_step(Some(-0.9)), 1);
        assert_eq!(snapshot_step(Some(0.05)), 1);
        assert_eq!(snapshot_step(Some(0.5)), 5);
        assert_eq!(snapshot_step(Some(0.9)), 29);
        assert_eq!(snapshot_step(Some(1.0)), usize::MAX);
        assert_eq!(
            every_nth_snapshot(&[1.0, 2.0, 3.0, 4.0, 5.0, 6.0], 2, 2),
            vec![1.0, 2.0, 5.0, 6.0]
        );
        assert_eq!(every_nth_snapshot(&flip, 2, usize::MAX), vec![1.0, -1.0]);
    }

    /// A heavy species whose velocities do not change between snapshots is tested on
    /// one snapshot, not on the same velocities counted again and again (which fails
    /// the tests however Maxwellian they are); the light species keeps every
    /// snapshot. A spacing asked for is used as it is, and then the heavy species
    /// fails.
    #[test]
    fn a_species_with_frozen_velocities_is_tested_once_per_disc() {
        use rand::SeedableRng;
        use rand_distr::{Distribution, StandardNormal};
        let (light, heavy, snapshots) = (2000, 400, 20);
        let mut r = run();
        r.species = vec![Species::reference(light), Species::new(heavy, 0.5, 100.0)];
        r.sim_box = SimBox::periodic(100.0, 100.0);
        let mut rng = rand_pcg::Pcg64::seed_from_u64(7);
        let mut gauss = |m: f64| {
            let g: f64 = StandardNormal.sample(&mut rng);
            g / m.sqrt()
        };
        let species: Vec<u16> = (0..light + heavy).map(|k| u16::from(k >= light)).collect();
        let frozen: Vec<(f64, f64)> = (0..heavy).map(|_| (gauss(100.0), gauss(100.0))).collect();
        let taken: Vec<(Vec<f64>, Vec<f64>)> = (0..snapshots)
            .map(|_| {
                let (mut vx, mut vy) = (Vec::new(), Vec::new());
                for _ in 0..light {
                    vx.push(gauss(1.0));
                    vy.push(gauss(1.0));
                }
                for &(x, y) in &frozen {
                    vx.push(x);
                    vy.push(y);
                }
                (vx, vy)
            })
            .collect();
        let analyse = |every: Option<f64>| {
            // Without `every` the default spacing; no collision rate is known, so
            // it keeps every snapshot.
            let opts = AnalysisOptions {
                equilibrate: Some(0.0),
                every,
                ..Default::default()
            };
            let mut a = Analyzer::new(r.clone(), opts).unwrap();
            for (k, (vx, vy)) in taken.iter().enumerate() {
                a.snapshot(k as f64 * 0.5, &species, vx, vy).unwrap();
            }
            a.finish().unwrap().maxwell_boltzmann
        };
        let report = analyse(None);
        let [l, h] = &report[..] else {
            panic!("two species tested");
        };
        assert_eq!(
            (l.snapshot_step, l.snapshots, l.samples),
            (1, snapshots, light * snapshots)
        );
        assert!(l.snapshot_correlation.unwrap().abs() < 0.05);
        assert_eq!((h.snapshots, h.samples), (1, heavy));
        assert_eq!(h.snapshot_step, snapshots);
        assert!(h.snapshot_correlation.unwrap() > 0.999);
        assert!(l.passed && h.passed, "{l:?}\n{h:?}");
        let asked = analyse(Some(0.0));
        let h = &asked[1];
        assert_eq!((h.snapshot_step, h.snapshots), (1, snapshots));
        assert!(h.snapshot_correlation.unwrap() > 0.999);
        assert!(!h.passed, "{h:?}");
    }

    #[test]
    fn inconsistent_snapshots_are_errors_not_panics() {
        let mut a = Analyzer::new(run(), AnalysisOptions::default()).unwrap();
        assert!(a.snapshot(1.0, &[0, 1], &[1.0, 1.0], &[0.0, 0.0]).is_err());
        assert!(a.snapshot(1.0, &[0], &[1.0, 1.0], &[0.0, 0.0]).is_err());
        assert!(a.snapshot(1.0, &[0, 0], &[1.0, -1.0], &[0.0, 0.0]).is_ok());
        let mut r = run();
        r.t_end = 0.0;
        assert!(Analyzer::new(r, AnalysisOptions::default()).is_err());
        let opts = AnalysisOptions {
            equilibrate: Some(20.0),
            ..Default::default()
        };
        assert!(Analyzer::new(run(), opts).is_err());
    }

    #[test]
    fn increments_spread_over_time_bins_keep_their_total() {
        let mut a = Analyzer::new(
            run(),
            AnalysisOptions {
                equilibrate: Some(0.0),
                time_bins: 16,
                ..Default::default()
            },
        )
        .unwrap();
        a.increment(0.3, 7.1, 68.0, 0.0, 34);
        let v: f64 = a.bins.iter().map(|b| b.virial).sum();
        let p: f64 = a.bins.iter().map(|b| b.pairs_weighted).sum();
        assert!((v - 68.0).abs() < 1e-9 && (p - 34.0).abs() < 1e-9);
        // Bin 0 ([0, 0.625)) holds the overlap 0.325 of 6.8.
        assert!((a.bins[0].virial - 68.0 * 0.325 / 6.8).abs() < 1e-9);
    }
}
