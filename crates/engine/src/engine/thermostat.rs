//! The thermostat's events: Andersen redraws and driving kicks (physics.md §16).
//!
//! A thermostat event is an entry of the engine's calendar (engine::calendar),
//! so it costs nothing while no thermostat is set: the event loop looks at whose
//! an entry is only when one is due. At the event
//! the clock stands at its time; each disc changed is brought there on its path,
//! given its new velocity (the path origin moves so that r0 + v t still passes
//! through its position now), its collision counter is bumped (its partners'
//! predictions become obsolete, as after a collision) and its next event is
//! predicted again. Andersen: v ~ N(0, kT/m) per component for one uniformly
//! chosen disc, next event after an exponential wait of mean 1/(N ν). Driven:
//! Δv_k ~ N(0, ξ² Δt) per component for every disc, minus their mass-weighted
//! mean, next kick Δt later. Random numbers come from the engine's own `Pcg64Mcg`,
//! seeded once and stored in the checkpoint.

use super::calendar::Whose;
use super::Engine;
use crate::error::EngineError;
use crate::thermostat::{Thermostat, ThermostatState, ThermostatStats};
use carom_core::DVec2;
use rand::{RngExt, SeedableRng};
use rand_distr::{Exp1, StandardNormal};
use rand_pcg::Pcg64Mcg;

/// Mixed into the run's seed so that the thermostat's stream is not the one the
/// initial state was drawn from.
const STREAM: u64 = 0x7468_6572_6d6f_7374; // "thermost"

/// A thermostat at work: its parameters, generator and totals.
#[derive(Debug, Clone)]
pub(super) struct Running {
    thermostat: Thermostat,
    rng: Pcg64Mcg,
    stats: ThermostatStats,
    /// The time it was set (time).
    origin: f64,
}

impl Running {
    /// The state a checkpoint stores, with the next event `next` (time,
    /// sequence number) from the calendar.
    pub(super) fn state(&self, next: Option<(f64, u64)>) -> ThermostatState {
        ThermostatState {
            thermostat: self.thermostat,
            rng: self.rng.state(),
            stats: self.stats,
            origin: self.origin,
            next,
        }
    }

    /// The thermostat of a checkpoint's `state`.
    pub(super) fn from_state(s: &ThermostatState) -> Result<Running, String> {
        s.thermostat.validate()?;
        let next = s.next.map_or(0.0, |n| n.0);
        for (name, x) in [
            ("energy added", s.stats.energy_added),
            ("origin", s.origin),
            ("next event time", next),
        ] {
            if !x.is_finite() {
                return Err(format!("thermostat {name} is {x}, not finite"));
            }
        }
        Ok(Running {
            thermostat: s.thermostat,
            rng: Pcg64Mcg::new(s.rng),
            stats: s.stats,
            origin: s.origin,
        })
    }
}

/// A standard normal pair (two independent N(0, 1) draws).
fn normal2(rng: &mut Pcg64Mcg) -> DVec2 {
    let x: f64 = rng.sample(StandardNormal);
    let y: f64 = rng.sample(StandardNormal);
    DVec2::new(x, y)
}

impl Engine {
    /// Set the thermostat (or none), its generator seeded from `seed`, its totals
    /// at 0; it replaces any thermostat set before. The first Andersen event comes
    /// after an exponential wait, the first driving kick one interval from now.
    /// A thermostat with a parameter that is not finite and > 0 is refused.
    pub fn set_thermostat(
        &mut self,
        thermostat: Option<Thermostat>,
        seed: u64,
    ) -> Result<(), EngineError> {
        if let Some(t) = &thermostat {
            t.validate().map_err(EngineError::BadThermostat)?;
            if self.growth.rate != 0.0 {
                return Err(EngineError::BadThermostat(
                    "a thermostat while the discs grow: the compression rescales the \
                     velocities itself; set the thermostat once growth has ended"
                        .into(),
                ));
            }
        }
        self.calendar.drop(Whose::Thermostat);
        self.thermostat = thermostat.map(|thermostat| {
            Box::new(Running {
                thermostat,
                rng: Pcg64Mcg::seed_from_u64(seed ^ STREAM),
                stats: ThermostatStats::default(),
                origin: self.reported,
            })
        });
        if self.thermostat.is_some() {
            self.schedule_thermostat();
        }
        Ok(())
    }

    /// The thermostat, if one is set.
    pub fn thermostat(&self) -> Option<Thermostat> {
        self.thermostat.as_ref().map(|r| r.thermostat)
    }

    /// What the thermostat has done since it was set (zeros without one).
    pub fn thermostat_stats(&self) -> ThermostatStats {
        self.thermostat
            .as_ref()
            .map_or(ThermostatStats::default(), |r| r.stats)
    }

    /// The time of the thermostat's next event (time): after an exponential wait
    /// of mean 1/(N ν) for Andersen; for driving the next multiple of the interval
    /// from the time it was set, origin + (k + 1) Δt after k kicks (not summed,
    /// so that rounding does not accumulate).
    fn thermostat_next(&mut self) -> f64 {
        let n = self.len() as f64;
        let now = self.reported;
        let r = self.thermostat.as_mut().expect("a thermostat is set");
        match r.thermostat {
            Thermostat::Andersen { rate, .. } => {
                let e: f64 = r.rng.sample(Exp1);
                now + e / (n * rate)
            }
            Thermostat::Driven { interval, .. } => {
                (r.origin + (r.stats.events + 1) as f64 * interval).max(now)
            }
        }
    }

    /// The thermostat's event due now (the clock stands at its time): change the
    /// velocities, predict again, and schedule the next event. Returns whether a
    /// pause is due (`engine::pause`).
    #[cold]
    #[inline(never)]
    pub(super) fn thermostat_event(&mut self) -> Result<bool, EngineError> {
        let mut r = self
            .thermostat
            .take()
            .expect("the thermostat's calendar entry goes with the thermostat");
        let n = self.len();
        // In a field a disc's stored path velocity runs ahead of its true velocity
        // by ŷ g t (engine/gravity.rs); the thermostat acts on true velocities.
        let lift = DVec2::new(0.0, self.params.gravity * self.clock);
        if n > 0 {
            match r.thermostat {
                Thermostat::Andersen { kt, .. } => {
                    let k = r.rng.random_range(0..n as u32) as usize;
                    let i = self.index_of[k] as usize;
                    let m = self.species[self.bodies[i].species as usize].mass;
                    let v = normal2(&mut r.rng) * (kt / m).sqrt();
                    r.stats.energy_added += self.replace_velocity(i, v, lift);
                    self.predict_any(i);
                }
                Thermostat::Driven { xi2, interval } => {
                    let s = (xi2 * interval).sqrt();
                    let kicks: Vec<DVec2> = (0..n).map(|_| normal2(&mut r.rng) * s).collect();
                    let mass = |k: usize| {
                        let i = self.index_of[k] as usize;
                        self.species[self.bodies[i].species as usize].mass
                    };
                    let total_mass: f64 = (0..n).map(mass).sum();
                    let mean = (0..n).map(|k| kicks[k] * mass(k)).sum::<DVec2>() / total_mass;
                    // Every velocity first, then every prediction: each prediction
                    // then sees the other discs' new paths.
                    for (k, dv) in kicks.iter().enumerate() {
                        let i = self.index_of[k] as usize;
                        let v = self.true_velocity(&self.bodies[i]) + (*dv - mean);
                        r.stats.energy_added += self.replace_velocity(i, v, lift);
                    }
                    for i in 0..n {
                        self.predict_any(i);
                    }
                }
            }
        }
        let touched = match r.thermostat {
            Thermostat::Andersen { .. } => 1,
            Thermostat::Driven { .. } => n,
        };
        r.stats.events += 1;
        self.thermostat = Some(r);
        self.schedule_thermostat();
        Ok(self.quiet_work(touched.max(1)))
    }

    /// Schedule the thermostat's next event, one wait from now (none if the wait
    /// is infinite: a rate so small that N ν rounds to 0).
    fn schedule_thermostat(&mut self) {
        let t = self.thermostat_next();
        if t.is_finite() {
            self.calendar.push(t, Whose::Thermostat);
        }
    }

    /// Give disc `i` (internal index) the true velocity `v` now (its path velocity
    /// `v + lift` in a field), keeping its position, and
    /// make its partners' predictions obsolete; returns the kinetic energy change.
    fn replace_velocity(&mut self, i: usize, v: DVec2, lift: DVec2) -> f64 {
        if self.bodies[i].resting() {
            // Kicked off the floor: a falling path again (engine::resting).
            self.lift_off(i);
        }
        let now = self.clock;
        let m = self.species[self.bodies[i].species as usize].mass;
        let b = &mut self.bodies[i];
        let de = 0.5 * m * (v.length_squared() - (b.v - lift).length_squared());
        b.set_velocity(v + lift, now);
        b.count = b.count.wrapping_add(1);
        self.keep_origin_near([i]);
        de
    }
}
