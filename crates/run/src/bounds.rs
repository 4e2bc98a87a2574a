//! Runs whose cost their parameters fix in advance, refused at the start (a fresh
//! run or a resume alike) when it is beyond any sensible run: the events of one
//! kind scheduled between now and the stop, at most
//! [`MAX_RECORDS`](carom_log::MAX_RECORDS) as for the log's records
//! (`check_log_options`, and `watchdog::check_reachable` for a collision stop).
//!
//! Over the time T to the stop (for a collision stop, the collisions left at the
//! rate expected from the density and temperature, physics.md (7.9)):
//! Andersen redraws ν N T (physics.md §16.1), driving kicks T/Δt (§16.2),
//! velocity rescales of growing discs min(T, time left to the target)/Δt_r
//! (§17), periods of the vibrating floor f T (§18). Each would otherwise keep the
//! engine busy for hours between two collisions or observations; the engine hands
//! back control meanwhile (`carom_engine::Event::Pause`), so a stop is still heard.

use carom_engine::{Engine, Thermostat};
use carom_log::{Stop, MAX_RECORDS};

use super::watchdog::time_to_stop;
use super::RunError;

/// Refuse a run whose parameters schedule more than [`MAX_RECORDS`] events of a
/// kind before its `stop`. `stop_field` names the setting that fixed the stop
/// (`stop.duration`, or a resume's `--until`/`--collisions`).
pub(super) fn check_scheduled(
    engine: &Engine,
    stop: Stop,
    stop_field: &str,
) -> Result<(), RunError> {
    let span = time_to_stop(engine, stop);
    let n = engine.len() as f64;
    let mut kinds: Vec<(&'static str, f64, String, &'static str)> = Vec::new();
    match engine.thermostat() {
        Some(Thermostat::Andersen { rate, .. }) => kinds.push((
            "thermostat.rate",
            rate * n * span,
            format!("Andersen redraws at rate {rate:e} per disc for {n} discs"),
            "a smaller rate",
        )),
        Some(Thermostat::Driven { interval, .. }) => kinds.push((
            "thermostat.interval",
            span / interval,
            format!("driving kicks every {interval:e}"),
            "a longer interval",
        )),
        None => {}
    }
    let g = engine.growth();
    if engine.params().growth.rate != 0.0 && g.rate != 0.0 {
        let dt = engine.params().growth.rescale_interval;
        // Internal times: the end less the next rescale is a duration.
        let growing = (g.end - g.next_rescale) + (engine.next_rescale_time() - engine.now());
        kinds.push((
            "compression.rescale_interval",
            span.min(growing) / dt,
            format!("velocity rescales every {dt:e} while the discs grow"),
            "a longer interval",
        ));
    }
    if let Some(fl) = engine.params().floor {
        let f = fl.omega / std::f64::consts::TAU;
        kinds.push((
            "vibrating_floor.frequency",
            f * span,
            format!("periods of the floor at frequency {f:e}"),
            "a lower frequency",
        ));
    }
    for (field, count, what, remedy) in kinds {
        if count.is_nan() || count > MAX_RECORDS {
            return Err(RunError::Invalid {
                field,
                problem: format!(
                    "{count:.3e} {what} in the {span:.4e} time units to the stop ({stop_field})"
                ),
                allowed: format!(
                    "at most {MAX_RECORDS:e} events of a kind before the stop: {remedy}, or \
                     stop sooner"
                ),
            });
        }
    }
    Ok(())
}
