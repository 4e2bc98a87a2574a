//! Runs that could never reach their stop: the bound on simulated time without a
//! collision, and the up-front refusal of a collision stop that would write more
//! records than any run may.
//!
//! A run whose discs stop meeting (all moving together, or a gas so dilute that the
//! first collision is ages away) would otherwise write snapshots forever. The
//! driver keeps the time of the last collision and checks it at a scheduled
//! [`Observation::Watchdog`](super::observation::Observation): once no collision
//! has happened for the bound, the run stops with `no_collision` and a finished log.
//! The bound is `stop.max_time_without_collision` when set; otherwise, with a
//! collision stop only, 100 mean free times t_free expected from the density and the
//! temperature at the check (physics.md (7.10)), so a cooling granular gas, whose
//! collisions slow down, is given ever longer.

use carom_core::observables::{degrees_of_freedom, temperature};
use carom_core::rates::{expected_collision_rate, expected_mean_free_time};
use carom_engine::Engine;
use carom_log::{LogOptions, Stop, MAX_RECORDS};

use super::RunError;

/// Mean free times without a collision before a run with a collision stop and no
/// `stop.max_time_without_collision` is stopped (physics.md (7.10)).
pub const MEAN_FREE_TIMES: f64 = 100.0;

/// kT of the engine's state now (energy).
fn kt_now(engine: &Engine) -> f64 {
    let f = degrees_of_freedom(engine.len(), engine.sim_box());
    temperature(engine.kinetic_energy(), f)
}

/// The bound now: the user's, or with a collision stop [`MEAN_FREE_TIMES`] ×
/// t_free at the current temperature; `None` when there is none (a time stop
/// without a user bound, or nothing moving).
pub(super) fn bound(engine: &Engine, user: Option<f64>, stop: Stop) -> Option<f64> {
    let b = match (user, stop) {
        (Some(b), _) => b,
        (None, Stop::Collisions(_)) => {
            MEAN_FREE_TIMES
                * expected_mean_free_time(engine.species(), engine.sim_box(), kt_now(engine))
        }
        (None, Stop::Time(_)) => return None,
    };
    b.is_finite().then_some(b)
}

/// Why a run stopped with `no_collision`, in words for the summary and the user.
pub(super) fn explain(quiet_since: f64, now: f64, bound: f64, user: Option<f64>) -> String {
    let whose = match user {
        Some(_) => "stop.max_time_without_collision".to_string(),
        None => format!(
            "the default of stop.max_time_without_collision, {MEAN_FREE_TIMES} mean free times \
             expected at this density and temperature"
        ),
    };
    format!(
        "no collision since t = {quiet_since} (for {:.6e} time units, the bound {bound:.6e} of \
         {whose}): the discs may no longer meet, and the run might never reach its stop; check the \
         velocities (discs moving together never collide) and the density, or set \
         stop.max_time_without_collision higher",
        now - quiet_since
    )
}

/// The collisions left before the count `target`, kT now and the collision rate
/// expected from the density and the temperature (physics.md (7.9)).
fn collisions_to_come(engine: &Engine, target: u64) -> (f64, f64, f64) {
    let s = engine.stats();
    let left = target.saturating_sub(s.pair_collisions + s.wall_collisions) as f64;
    let kt = kt_now(engine);
    (
        left,
        kt,
        expected_collision_rate(engine.species(), engine.sim_box(), kt),
    )
}

/// The simulated time from now to the stop: exact for a time stop; for a
/// collision stop the collisions left at the rate expected now (physics.md
/// (7.9)), a lower bound when the gas cools.
pub(super) fn time_to_stop(engine: &Engine, stop: Stop) -> f64 {
    match stop {
        Stop::Time(t) => (t - engine.now()).max(0.0),
        Stop::Collisions(target) => {
            let (left, _, rate) = collisions_to_come(engine, target);
            left / rate
        }
    }
}

/// Refuse a collision stop that, at the collision rate expected from the density
/// and temperature (physics.md (7.9), a lower bound on the time when the gas
/// cools), would write more than [`MAX_RECORDS`] snapshots (n + 1 per interval
/// with a `log.snapshot_schedule` of n points), thermo records or checkpoints
/// before reaching its count.
pub(super) fn check_reachable(
    engine: &Engine,
    stop: Stop,
    log: &LogOptions,
) -> Result<(), RunError> {
    let Stop::Collisions(target) = stop else {
        return Ok(());
    };
    let (left, kt, rate) = collisions_to_come(engine, target);
    let time = left / rate;
    // A snapshot schedule writes n + 1 snapshots per snapshot interval.
    let per_snapshot_interval = log.snapshots().map_or(1, |s| s.per_block()) as f64;
    let series = [
        (
            "log.snapshot_interval",
            "snapshots",
            log.snapshot_interval,
            per_snapshot_interval,
        ),
        (
            "log.thermo_interval",
            "thermo records",
            log.thermo_interval,
            1.0,
        ),
        (
            "log.checkpoint_interval",
            "checkpoints",
            log.checkpoint_interval,
            1.0,
        ),
    ];
    for (field, what, interval, per) in series {
        let Some(dt) = interval else { continue };
        let records = time / dt * per;
        if records > MAX_RECORDS {
            return Err(RunError::Invalid {
                field: "stop.collisions",
                problem: format!(
                    "at kT = {kt:.4e} and this density about {rate:.4e} collisions are \
                     expected per unit time (physics.md (7.9)), so {left} collisions take \
                     about {time:.3e} time units: {records:.3e} {what} at {field} = {dt}{}",
                    if per > 1.0 {
                        format!(" ({per} per interval with log.snapshot_schedule)")
                    } else {
                        String::new()
                    }
                ),
                allowed: format!(
                    "at most {MAX_RECORDS:e} records of a kind: fewer collisions, a longer \
                     {field}, stop.duration, or a denser or hotter system"
                ),
            });
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use carom_core::{Boundary, Species};
    use carom_engine::{EngineParams, SystemSpec};
    use carom_log::SchedulePoints;

    #[test]
    fn a_snapshot_schedule_counts_n_plus_one_snapshots_per_interval() {
        let system = SystemSpec::square_box(
            vec![Species::reference(100)],
            0.3,
            [Boundary::Periodic; 2],
            1,
        );
        let engine = Engine::new(system.build().unwrap(), EngineParams::default()).unwrap();
        // A stop about 5·10⁸ time units away at the expected rate: 5·10⁸ snapshots
        // every T = 1 are allowed; with 9 points more per interval, 5·10⁹ are not.
        let rate = expected_collision_rate(engine.species(), engine.sim_box(), kt_now(&engine));
        let stop = Stop::Collisions((5e8 * rate) as u64);
        let plain = LogOptions {
            snapshot_interval: Some(1.0),
            thermo_interval: None,
            checkpoint_interval: None,
            ..LogOptions::default()
        };
        assert!(check_reachable(&engine, stop, &plain).is_ok());
        let scheduled = LogOptions {
            snapshot_schedule: Some(SchedulePoints {
                points: 9,
                first: 0.01,
            }),
            ..plain.clone()
        };
        let e = check_reachable(&engine, stop, &scheduled).unwrap_err();
        let text = e.to_string();
        assert!(text.contains("stop.collisions"), "{text}");
        assert!(
            text.contains("10 per interval with log.snapshot_schedule"),
            "{text}"
        );
        // The same count as snapshots every T/10 without a schedule.
        let tenth = LogOptions {
            snapshot_interval: Some(0.1),
            ..plain
        };
        assert!(check_reachable(&engine, stop, &tenth).is_err());
    }
}
