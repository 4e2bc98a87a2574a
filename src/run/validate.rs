//! The checks of a run's log options and stop against the current time, made
//! before a fresh run places its discs and before a resume goes on.
//!
//! The configuration front end checks the same options when a configuration is
//! read; a single validator in the io crate is to replace this one.

use carom_io::MAX_RECORDS;
use carom_io::{LogOptions, Stop};

use super::RunError;

fn check_interval(field: &'static str, v: Option<f64>) -> Result<(), RunError> {
    match v {
        Some(x) if !(x.is_finite() && x > 0.0) => Err(RunError::Invalid {
            field,
            problem: format!("interval {x} is not a positive finite number"),
            allowed: "finite numbers > 0, or null for none",
        }),
        _ => Ok(()),
    }
}

pub(super) fn validate(log: &LogOptions, stop: &Stop, now: f64) -> Result<(), RunError> {
    for (field, v) in log.intervals() {
        check_interval(field, v)?;
    }
    if log.collision_every == 0 {
        return Err(RunError::Invalid {
            field: "log.collision_every",
            problem: "0 collisions between logged ones".into(),
            allowed: "integers ≥ 1",
        });
    }
    if log.flush_seconds.is_nan() || log.flush_seconds < 0.0 {
        return Err(RunError::Invalid {
            field: "log.flush_seconds",
            problem: format!("{} is not ≥ 0", log.flush_seconds),
            allowed: "numbers ≥ 0",
        });
    }
    if let Stop::Time(t) = *stop {
        if !t.is_finite() || t < now {
            return Err(RunError::Invalid {
                field: "stop.time",
                problem: format!("stop time {t} is not a finite time ≥ the current time {now}"),
                allowed: "finite times ≥ the start time",
            });
        }
        // A stop time mistyped by some orders of magnitude (`resume --until 1e12`)
        // would otherwise fill the disk with records, as a mistyped interval would
        // (the configuration checks those against stop.duration).
        let smallest = log
            .intervals()
            .into_iter()
            .filter_map(|(name, x)| Some((name, x?)))
            .min_by(|a, b| a.1.total_cmp(&b.1));
        if let Some((name, x)) = smallest {
            let records = (t - now) / x;
            if records > MAX_RECORDS {
                return Err(RunError::Invalid {
                    field: "stop.time",
                    problem: format!(
                        "stop time {t} would write {records:.1e} records {x} apart \
                         ({name}) after the current time {now}, more than {MAX_RECORDS:.0e}; \
                         the latest stop time is {}",
                        now + MAX_RECORDS * x
                    ),
                    allowed: "stop times at most 10⁹ log intervals after the current time",
                });
            }
        }
    }
    Ok(())
}
