//! The [`Analyzer`]: accumulates a run's events in one streaming pass and turns
//! them into a [`Report`]. It sees plain numbers (collision virials, wall
//! impulses, snapshots, kinetic energies), not files: `from_log` feeds it from
//! an MCAP log, the tests straight from the engine. The thermodynamic sums go
//! into [`Samples`] (time bins after the equilibration time, so that every
//! observable gets a blocked standard error; kT from the thermo records and
//! snapshots, interpolated in time); the snapshots' positions into the structure
//! accumulators (g(r), ψ6, g6, S(k)), their unwrapped positions into the
//! dynamics, the collisions into the transport replay. [`Analyzer::finish`]
//! hands each observable its data and assembles the report from the sections.

use carom_core::observables::{packing_fraction, temperature};
use carom_core::rates::expected_mean_free_time;

use super::atmosphere::Atmosphere;
use super::dynamics::Dynamics;
use super::inelastic::Driven;
use super::not_computed;
use super::options::AnalysisOptions;
use super::report::Report;
use super::report::SpeciesInfo;
use super::run_dynamics::RunDynamics;
use super::samples::Samples;
use super::stats::StatsError;
use super::structure::{smallest_diameter, Structure};
use super::transport::Transport;
use super::{
    collision_rate, floor, inelastic, pressure, temperature, thermostat, velocity, RunDescription,
};

/// Accumulates a run's events and produces a [`Report`].
#[derive(Debug, Clone)]
pub struct Analyzer {
    /// Time bins, kT and energy series, the velocities used.
    pub(crate) samples: Samples,
    /// g(r), ψ6, g6(r) and S(k) per time block (physics.md §10–§11).
    pub(crate) structure: Structure,
    /// MSD, snapshot VACF and F_s sums over time origins (physics.md §13).
    pub(crate) dynamics: Dynamics,
    /// Transport from the collision log, from the first snapshot analysed on
    /// (physics.md §14); `None` before it, or when the run does not qualify.
    pub(crate) transport: Option<Transport>,
    /// Whether the transport replay has been tried (at the first snapshot).
    pub(crate) transport_tried: bool,
    /// Pair collisions since it started; a source that gives fewer details
    /// ([`Analyzer::pair_detail`]) gets no transport report.
    pub(crate) transport_pairs: u64,
    /// Heights and potential energy in a field (physics.md §15); `None` without one.
    pub(crate) atmosphere: Option<Atmosphere>,
}

impl Analyzer {
    /// An analyzer for `run` with options `opts`.
    pub fn new(run: RunDescription, opts: AnalysisOptions) -> Result<Self, StatsError> {
        let samples = Samples::new(run, opts)?;
        let (run, t_eq) = (&samples.run, samples.t_eq);
        let sigma_min = smallest_diameter(&run.species);
        Ok(Analyzer {
            structure: Structure::new(&run.species, &run.sim_box, t_eq, run.t_end),
            dynamics: Dynamics::new(
                (&run.species, &run.sim_box),
                [run.t_start, t_eq, run.t_end],
                run.snapshot_interval,
                sigma_min,
            ),
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
            samples,
        })
    }

    /// The time from which data are used (after `--equilibrate`).
    pub fn equilibrated_from(&self) -> f64 {
        self.samples.t_eq
    }

    /// A logged pair collision at time `t` with virial r_ij·Δp_i (length·momentum)
    /// and dissipated energy (energy).
    pub fn pair(&mut self, t: f64, virial: f64, energy_lost: f64) {
        if self.transport.is_some() {
            self.transport_pairs += 1;
        }
        self.samples.collision(t, false, virial, energy_lost);
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
        self.samples.collision(t, true, impulse, energy_lost);
    }

    /// Running totals between two times, for logs without collisions: the virial
    /// sum (length·momentum), wall impulse (momentum) and pair collisions counted
    /// in [t0, t1] (e.g. differences of consecutive `/thermo` records), spread
    /// over the time bins in proportion to their overlap.
    pub fn increment(&mut self, t0: f64, t1: f64, virial: f64, wall_impulse: f64, pairs: u64) {
        self.samples.increment(t0, t1, virial, wall_impulse, pairs);
    }

    /// The engine's running count of pair collisions (since the run's start) at
    /// a `/thermo` record: with it the snapshots of an inelastic run are spaced by
    /// the collisions between them (see [`AnalysisOptions::every`]).
    pub fn pair_count(&mut self, pairs: u64) {
        self.samples.thermo_pairs = Some(pairs);
    }

    /// A thermodynamic record: kinetic energy K (energy) at time `t`, and the
    /// energy dissipated since the start when known.
    pub fn thermo(&mut self, t: f64, kinetic_energy: f64, energy_lost: Option<f64>) {
        self.samples.thermo(t, kinetic_energy, energy_lost);
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
        self.samples
            .check_snapshot(t, species_of, [vx, vy], ["vx", "vy"])?;
        let s = &mut self.samples;
        s.snapshots_seen += 1;
        let masses: Vec<f64> = s.run.species.iter().map(|s| s.mass).collect();
        let k: f64 = species_of
            .iter()
            .zip(vx.iter().zip(vy))
            .map(|(&s, (&x, &y))| 0.5 * masses[s as usize] * (x * x + y * y))
            .sum();
        let kt = temperature(k, s.dof());
        s.push_kt(t, kt);
        if s.energy_series.last().is_none_or(|e| e.0 != t) {
            s.energy_series.push((t, k, None));
        }
        // A snapshot at the start of the window counts despite rounding of the
        // window's start (a tolerance relative to the run's own times, which may be
        // in any unit).
        let span = s.run.t_end - s.run.t_start;
        if t < s.t_eq - 1e-12 * s.t_eq.abs().max(span) {
            return Ok(());
        }
        self.transport_snapshot(t, species_of, vx, vy, kt);
        let s = &mut self.samples;
        // Spaced by the collisions counted, any snapshot far enough from the last
        // one used is as independent as a block start.
        let counted = (s.thermo_pairs, s.pairs_counted());
        match (s.every_collisions, s.snapshot_pairs.last()) {
            (Some(c), Some(&last)) => {
                if s.collisions_between(last, counted) < c * (1.0 - 1e-9) {
                    return Ok(());
                }
            }
            (Some(_), None) => {}
            (None, _) => {
                if !s.block_start(t) {
                    return Ok(());
                }
            }
        }
        if let (Some(&last), Some(every)) = (s.snapshots_used.last(), s.opts.every) {
            if t < last + every * (1.0 - 1e-9) {
                return Ok(());
            }
        }
        s.snapshots_used.push(t);
        s.snapshot_pairs.push(counted);
        s.snapshot_kt.push(kt);
        s.snapshot_a2
            .push(inelastic::sonine_a2(&masses, species_of, vx, vy));
        s.mb_kinetic += k;
        let (ux, uy) = velocity::centre_of_mass_velocity(&masses, species_of, vx, vy);
        for (&sp, (&x, &y)) in species_of.iter().zip(vx.iter().zip(vy)) {
            let (sp, x, y) = (sp as usize, x - ux, y - uy);
            s.speeds[sp].push(x.hypot(y));
            s.vx[sp].push(x);
            s.vy[sp].push(y);
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
        self.samples
            .check_snapshot(t, species_of, [x, y], ["x", "y"])?;
        let s = &self.samples;
        let span = s.run.t_end - s.run.t_start;
        if t < s.t_eq - 1e-12 * s.t_eq.abs().max(span) || !s.block_start(t) {
            return Ok(());
        }
        if let Some(a) = &mut self.atmosphere {
            a.add(t, species_of, y);
        }
        if !self.samples.opts.structure {
            return Ok(());
        }
        let t = t.max(self.samples.t_eq);
        self.structure.add(t, species_of, x, y);
        Ok(())
    }

    /// A snapshot's unwrapped positions (`ux`, `uy`, length; continuous in time,
    /// physics.md §12) and velocities (length/time) of every disc, with species
    /// indices, for the MSD, D, snapshot VACF and F_s (physics.md §13). Snapshots
    /// come in time order; block starts after the equilibration time become time
    /// origins.
    ///
    /// Errors when the slices differ in length or a species index is not one of
    /// the run's species.
    pub fn motion(
        &mut self,
        t: f64,
        species_of: &[u16],
        [ux, uy]: [&[f64]; 2],
        [vx, vy]: [&[f64]; 2],
    ) -> Result<(), StatsError> {
        self.samples
            .check_snapshot(t, species_of, [ux, uy], ["ux", "uy"])?;
        self.samples
            .check_snapshot(t, species_of, [vx, vy], ["vx", "vy"])?;
        let start = self.samples.block_start(t);
        self.dynamics.add(t, start, species_of, [ux, uy], [vx, vy]);
        Ok(())
    }

    /// The number of snapshot gaps that could not be unwrapped with certainty
    /// ([`super::Unwrapper::ambiguous_gaps`]), for the report's warning.
    pub fn ambiguous_gaps(&mut self, gaps: u64) {
        self.dynamics.ambiguous_gaps = gaps;
    }

    /// The transport replay starts at the first snapshot analysed and checks
    /// itself against the later ones.
    fn transport_snapshot(&mut self, t: f64, species_of: &[u16], vx: &[f64], vy: &[f64], kt: f64) {
        if let Some(tr) = &mut self.transport {
            tr.check(t, (vx, vy));
        } else if !self.transport_tried {
            self.transport_tried = true;
            let t_c = match self.samples.run.pair_rate {
                Some(omega) if omega > 0.0 => 1.0 / omega,
                _ => expected_mean_free_time(
                    &self.samples.run.species,
                    &self.samples.run.sim_box,
                    kt,
                ),
            };
            self.transport = Transport::start(&self.samples.run, t, species_of, (vx, vy), t_c);
        }
    }

    /// Compute everything for a run with neither thermostat, compression nor
    /// vibrating floor: [`Analyzer::finish_with`] and the default [`RunDynamics`].
    pub fn finish(self) -> Result<Report, StatsError> {
        self.finish_with(RunDynamics::default())
    }

    /// Compute everything: each observable its section from its data (and from
    /// the sections it reads, passed in), `run`'s thermostat, compression and
    /// floor included; the report assembled once from the sections.
    pub fn finish_with(mut self, run_dynamics: RunDynamics) -> Result<Report, StatsError> {
        let RunDynamics {
            thermostat,
            compression,
            floor,
        } = run_dynamics;
        let s = &mut self.samples;
        s.kt_series.sort_by(|a, b| a.0.total_cmp(&b.0));
        s.energy_series.sort_by(|a, b| a.0.total_cmp(&b.0));
        let (species, sim_box) = (&s.run.species, &s.run.sim_box);
        let elastic = s.run.restitution.is_elastic()
            && sim_box.boundary.iter().all(
                |b| !matches!(b, carom_core::Boundary::Walls { restitution } if *restitution < 1.0),
            );
        let periodic = sim_box.boundary.iter().all(|b| b.is_periodic());
        let phi = packing_fraction(species, sim_box);
        let kt_used = temperature::snapshot_kt(s);
        let temperature = temperature::report(s, kt_used);
        // A cooling gas is tested in its homogeneous cooling state: each
        // snapshot's velocities scaled to the mean kT of the snapshots used.
        if !elastic {
            if let Some(kt) = kt_used {
                inelastic::scale_to(s, kt);
            }
        }
        let (maxwell_boltzmann, maxwell_boltzmann_untested) =
            velocity::maxwell_boltzmann(s, kt_used, !elastic)?;
        let s = &self.samples;
        let run = &s.run;
        let kt_bins = s.kt_per_bin();
        let z_bins = pressure::z_per_bin(s, &kt_bins);
        let omega_bins = collision_rate::omega_per_bin(s);
        let pressure = pressure::report(s, &z_bins, &kt_bins)?;
        let collision_rate = collision_rate::report(s, &omega_bins, elastic)?;
        let bins = [&z_bins[..], &omega_bins[..], &kt_bins[..]];
        let enskog = collision_rate::enskog(s, elastic, pressure.as_ref(), bins)?;
        let thermostat = thermostat.map(|(t, restitution)| {
            thermostat::report(&t, restitution, run, &temperature, collision_rate.per_disc)
        });
        // A thermostat or a floor puts energy in; a floor's bed is no cooling state.
        let driven = match (&thermostat, &floor) {
            (_, Some(_)) => Some(Driven { a2_theory: None }),
            (Some(t), None) => Some(Driven {
                a2_theory: t.a2_theory,
            }),
            (None, None) => None,
        };
        let inelastic = (!elastic).then(|| inelastic::report(s, driven));
        let structure = self
            .structure
            .report(elastic && periodic, pressure.as_ref());
        // The replay misses a thermostat's velocity changes.
        let transport = match thermostat {
            Some(_) => None,
            None => self.transport.take().and_then(|tr| {
                (tr.pairs() == self.transport_pairs)
                    .then(|| tr.report(run.t_end, pressure.as_ref().map(|p| p.z), phi))
                    .flatten()
            }),
        };
        let gravity = self.atmosphere.as_ref().and_then(|a| {
            let kinetic: Vec<(f64, f64)> = s.energy_series.iter().map(|e| (e.0, e.1)).collect();
            a.report(&kinetic, kt_used, floor.is_none())
        });
        let floor = floor.and_then(|f| floor::report(&f.floor, f.gravity, &f.totals, s.t_eq));
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
            packing_fraction: phi,
            box_size: [run.sim_box.size.x, run.sim_box.size.y],
            periodic: run.sim_box.boundary.map(|b| b.is_periodic()),
            elastic,
            window: s.window(collision_rate.per_disc),
            dynamics: self.dynamics.report(collision_rate.per_disc),
            temperature,
            maxwell_boltzmann,
            maxwell_boltzmann_untested,
            pressure,
            collision_rate,
            enskog,
            inelastic,
            pair_correlation: structure.pair_correlation,
            bond_order: structure.bond_order,
            orientational_correlation: structure.orientational_correlation,
            structure_factor: structure.structure_factor,
            transport,
            gravity,
            thermostat,
            compression,
            floor,
            not_computed: Vec::new(),
        };
        // What is absent, with its reason, read off the assembled sections.
        report.not_computed = not_computed::explain(&report);
        Ok(report)
    }
}

#[cfg(test)]
#[path = "analyzer_tests.rs"]
mod tests;

#[cfg(test)]
#[path = "analyzer_finish_tests.rs"]
mod finish_tests;
