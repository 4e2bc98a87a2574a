//! The two MCAP metadata records of a carom log: `carom.run` (written first: what
//! was run) and `carom.summary` (written last: how it ended). MCAP metadata are maps
//! of strings to strings; this module is their typed form. Each map carries its
//! checksum (`crc32`, log format 2.3 on; see `checksum`): `to_map` seals it,
//! and readers verify it before `from_map` (which ignores the key).

use super::checksum::seal;
use super::facts::RunFacts;
use super::number::{f64_from_json, f64_from_text, f64_to_json, f64_to_text};
use super::{LOG_FORMAT_VERSION, READABLE_MAJOR_VERSIONS};
use crate::options::{CollisionDetail, Compression, LogOptions, Stop};
use crate::schedule::SchedulePoints;
use serde_json::{json, Value};
use std::collections::BTreeMap;
use std::time::{SystemTime, UNIX_EPOCH};
use thiserror::Error;

/// A metadata record that is missing a key or holds a bad value.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
#[error("metadata `{record}`: key `{key}`: {problem}")]
pub struct MetadataError {
    /// Record name (`carom.run` or `carom.summary`).
    pub record: &'static str,
    /// The key.
    pub key: &'static str,
    /// What was wrong.
    pub problem: String,
}

/// The `carom.run` record: what was run.
#[derive(Debug, Clone, PartialEq)]
pub struct RunMetadata {
    /// `log_format`: layout version of the log (see [`LOG_FORMAT_VERSION`]).
    pub log_format: String,
    /// `carom_version`: version of the carom that wrote the log.
    pub carom_version: String,
    /// `config`: the user's configuration, verbatim JSON text.
    pub config: String,
    /// `seed`: seed of the initial state.
    pub seed: u64,
    /// `start_time`: wall-clock start of the writing process, RFC 3339 UTC.
    pub start_time: String,
    /// `n_discs`: number of discs N.
    pub n_discs: u64,
    /// `stop`: when the run ends, JSON `{"time": t}` or `{"collisions": n}`.
    pub stop: Stop,
    /// `max_time_without_collision`: the user's bound on simulated time without a
    /// collision (time); absent: the default (see `stop.max_time_without_collision`
    /// in the configuration).
    pub max_time_without_collision: Option<f64>,
    /// `log_options`: what is logged, JSON (see `log_options_to_json`).
    pub log: LogOptions,
    /// `resumed_from`: for a resumed log, the file it was resumed from.
    pub resumed_from: Option<String>,
    /// `resumed_at`: for a resumed log, the simulated time of the checkpoint it
    /// continued from (time).
    pub resumed_at: Option<f64>,
    /// `run_facts`: the resolved run, JSON (see [`RunFacts`]); `None` in logs of
    /// format ≤ 1.1, which do not store it.
    pub run_facts: Option<RunFacts>,
}

fn get<'a>(
    m: &'a BTreeMap<String, String>,
    record: &'static str,
    key: &'static str,
) -> Result<&'a str, MetadataError> {
    m.get(key).map(String::as_str).ok_or(MetadataError {
        record,
        key,
        problem: "missing".into(),
    })
}

fn parse<T: std::str::FromStr>(
    m: &BTreeMap<String, String>,
    record: &'static str,
    key: &'static str,
) -> Result<T, MetadataError> {
    let s = get(m, record, key)?;
    s.parse().map_err(|_| MetadataError {
        record,
        key,
        problem: format!("cannot parse {s:?}"),
    })
}

/// A float metadata value (see `number`: decimals, `NaN`, `Infinity`, `-Infinity`).
fn parse_f64(
    m: &BTreeMap<String, String>,
    record: &'static str,
    key: &'static str,
) -> Result<f64, MetadataError> {
    let s = get(m, record, key)?;
    f64_from_text(s).ok_or_else(|| MetadataError {
        record,
        key,
        problem: format!("cannot parse {s:?}"),
    })
}

/// An optional float metadata value.
fn parse_opt_f64(
    m: &BTreeMap<String, String>,
    record: &'static str,
    key: &'static str,
) -> Result<Option<f64>, MetadataError> {
    match m.get(key) {
        Some(_) => parse_f64(m, record, key).map(Some),
        None => Ok(None),
    }
}

/// `stop` as JSON.
pub fn stop_to_json(s: &Stop) -> Value {
    match *s {
        Stop::Time(t) => json!({ "time": f64_to_json(t) }),
        Stop::Collisions(n) => json!({ "collisions": n }),
    }
}

/// `stop` from JSON.
pub fn stop_from_json(v: &Value) -> Option<Stop> {
    if let Some(t) = v.get("time").and_then(f64_from_json) {
        return Some(Stop::Time(t));
    }
    v.get("collisions")
        .and_then(Value::as_u64)
        .map(Stop::Collisions)
}

fn compression_name(c: Compression) -> &'static str {
    match c {
        Compression::Zstd => "zstd",
        Compression::Lz4 => "lz4",
        Compression::None => "none",
    }
}

/// Log options as JSON: `{"collisions", "collision_every", "collision_detail",
/// "snapshot_interval", "thermo_interval", "checkpoint_interval", "scene_interval",
/// "compression", "flush_seconds"}` (intervals `null` when off; `collision_detail`
/// the record the log holds, [`LogOptions::collision_record`]), and
/// `"snapshot_schedule": {"points", "first"}` only when there is one (logs
/// without one, and logs older than the schedule, lack the key).
pub fn log_options_to_json(o: &LogOptions) -> Value {
    let mut v = json!({
        "collisions": o.collisions,
        "collision_every": o.collision_every,
        "collision_detail": o.collision_record().name(),
        "snapshot_interval": o.snapshot_interval.map(f64_to_json),
        "thermo_interval": o.thermo_interval.map(f64_to_json),
        "checkpoint_interval": o.checkpoint_interval.map(f64_to_json),
        "scene_interval": o.scene_interval.map(f64_to_json),
        "compression": compression_name(o.compression),
        "flush_seconds": f64_to_json(o.flush_seconds),
    });
    if let Some(p) = &o.snapshot_schedule {
        v["snapshot_schedule"] = json!({ "points": p.points, "first": f64_to_json(p.first) });
    }
    v
}

/// Log options from JSON; missing keys take their defaults, except
/// `collision_detail`, which is `"full"` when missing (logs of format 1).
pub fn log_options_from_json(v: &Value) -> Option<LogOptions> {
    let d = LogOptions::default();
    let interval = |k: &str, def: Option<f64>| match v.get(k) {
        None => Some(def),
        Some(Value::Null) => Some(None),
        Some(x) => f64_from_json(x).map(Some),
    };
    Some(LogOptions {
        collisions: v
            .get("collisions")
            .map_or(Some(d.collisions), Value::as_bool)?,
        collision_every: v
            .get("collision_every")
            .map_or(Some(d.collision_every), Value::as_u64)?,
        collision_detail: match v.get("collision_detail").and_then(Value::as_str) {
            None => CollisionDetail::Full,
            Some(name) => CollisionDetail::from_name(name)?,
        },
        snapshot_interval: interval("snapshot_interval", d.snapshot_interval)?,
        snapshot_schedule: match v.get("snapshot_schedule") {
            None | Some(Value::Null) => None,
            Some(s) => Some(SchedulePoints {
                points: s.get("points")?.as_u64()?,
                first: f64_from_json(s.get("first")?)?,
            }),
        },
        thermo_interval: interval("thermo_interval", d.thermo_interval)?,
        checkpoint_interval: interval("checkpoint_interval", d.checkpoint_interval)?,
        scene_interval: interval("scene_interval", d.scene_interval)?,
        compression: match v.get("compression").and_then(Value::as_str) {
            None => d.compression,
            Some("zstd") => Compression::Zstd,
            Some("lz4") => Compression::Lz4,
            Some("none") => Compression::None,
            Some(_) => return None,
        },
        flush_seconds: v
            .get("flush_seconds")
            .map_or(Some(d.flush_seconds), f64_from_json)?,
    })
}

impl RunMetadata {
    /// The record as an MCAP metadata map, sealed with its checksum.
    pub fn to_map(&self) -> BTreeMap<String, String> {
        let mut m = BTreeMap::new();
        m.insert("log_format".into(), self.log_format.clone());
        m.insert("carom_version".into(), self.carom_version.clone());
        m.insert("config".into(), self.config.clone());
        m.insert("seed".into(), self.seed.to_string());
        m.insert("start_time".into(), self.start_time.clone());
        m.insert("n_discs".into(), self.n_discs.to_string());
        m.insert("stop".into(), stop_to_json(&self.stop).to_string());
        if let Some(t) = self.max_time_without_collision {
            m.insert("max_time_without_collision".into(), f64_to_text(t));
        }
        m.insert(
            "log_options".into(),
            log_options_to_json(&self.log).to_string(),
        );
        if let Some(r) = &self.resumed_from {
            m.insert("resumed_from".into(), r.clone());
        }
        if let Some(t) = self.resumed_at {
            m.insert("resumed_at".into(), f64_to_text(t));
        }
        if let Some(f) = &self.run_facts {
            m.insert("run_facts".into(), f.to_json().to_string());
        }
        seal(&mut m);
        m
    }

    /// Parse the record; a log of another major format version is rejected.
    pub fn from_map(m: &BTreeMap<String, String>) -> Result<Self, MetadataError> {
        const R: &str = "carom.run";
        let log_format = get(m, R, "log_format")?.to_string();
        let major = log_format.split('.').next().unwrap_or_default();
        if !READABLE_MAJOR_VERSIONS.contains(&major) {
            return Err(MetadataError {
                record: R,
                key: "log_format",
                problem: format!(
                    "log format {log_format} is not supported (this carom reads {} and writes {LOG_FORMAT_VERSION})",
                    READABLE_MAJOR_VERSIONS.map(|v| format!("{v}.x")).join(" and ")
                ),
            });
        }
        let json_of = |key: &'static str| -> Result<Value, MetadataError> {
            serde_json::from_str(get(m, R, key)?).map_err(|e| MetadataError {
                record: R,
                key,
                problem: format!("not JSON: {e}"),
            })
        };
        let stop = stop_from_json(&json_of("stop")?).ok_or(MetadataError {
            record: R,
            key: "stop",
            problem: "expected {\"time\": t} or {\"collisions\": n}".into(),
        })?;
        let log = log_options_from_json(&json_of("log_options")?).ok_or(MetadataError {
            record: R,
            key: "log_options",
            problem: "a field has the wrong type".into(),
        })?;
        Ok(RunMetadata {
            log_format,
            carom_version: get(m, R, "carom_version")?.to_string(),
            config: get(m, R, "config")?.to_string(),
            seed: parse(m, R, "seed")?,
            start_time: get(m, R, "start_time")?.to_string(),
            n_discs: parse(m, R, "n_discs")?,
            stop,
            max_time_without_collision: parse_opt_f64(m, R, "max_time_without_collision")?,
            log,
            resumed_from: m.get("resumed_from").cloned(),
            resumed_at: parse_opt_f64(m, R, "resumed_at")?,
            run_facts: match m.get("run_facts") {
                Some(_) => Some(RunFacts::from_json(&json_of("run_facts")?).map_err(
                    |problem| MetadataError {
                        record: R,
                        key: "run_facts",
                        problem,
                    },
                )?),
                None => None,
            },
        })
    }
}

/// Why a run ended (`stop_reason` in `carom.summary`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StopReason {
    /// The stop time was reached (`time`).
    Time,
    /// The collision budget was reached (`collisions`).
    Collisions,
    /// The caller's stop flag was raised, e.g. Ctrl-C (`interrupted`).
    Interrupted,
    /// Nothing could ever happen again: all discs at rest (`exhausted`).
    Exhausted,
    /// The engine failed (`error`); `error` in the summary says how.
    Error,
    /// The log's disk was about to fill up (`disk_full`): the run stopped while
    /// there was still room for a final checkpoint and the summary, so the log is
    /// finished and a resume loses nothing.
    DiskFull,
    /// No collision happened within `max_time_without_collision`
    /// (`no_collision`): the run could never reach its stop; its log is finished.
    NoCollision,
}

impl StopReason {
    /// The name stored in the summary.
    pub fn as_str(&self) -> &'static str {
        match self {
            StopReason::Time => "time",
            StopReason::Collisions => "collisions",
            StopReason::Interrupted => "interrupted",
            StopReason::Exhausted => "exhausted",
            StopReason::Error => "error",
            StopReason::DiskFull => "disk_full",
            StopReason::NoCollision => "no_collision",
        }
    }

    fn parse(s: &str) -> Option<Self> {
        Some(match s {
            "time" => StopReason::Time,
            "collisions" => StopReason::Collisions,
            "interrupted" => StopReason::Interrupted,
            "exhausted" => StopReason::Exhausted,
            "error" => StopReason::Error,
            "disk_full" => StopReason::DiskFull,
            "no_collision" => StopReason::NoCollision,
            _ => return None,
        })
    }
}

/// The `carom.summary` record: how the run ended. Totals count the whole run,
/// including the part before a resume; wall-clock figures count this process only.
#[derive(Debug, Clone, PartialEq)]
pub struct SummaryMetadata {
    /// `end_time`: wall-clock end, RFC 3339 UTC.
    pub end_time: String,
    /// `stop_reason`.
    pub stop_reason: StopReason,
    /// `error`: the engine's error message when `stop_reason` is `error`; why no
    /// collision came when it is `no_collision`.
    pub error: Option<String>,
    /// `sim_time`: simulated time at the end (time).
    pub sim_time: f64,
    /// `pair_collisions`.
    pub pair_collisions: u64,
    /// `wall_collisions`.
    pub wall_collisions: u64,
    /// `logged_collisions`: collisions in `/collisions`.
    pub logged_collisions: u64,
    /// `kinetic_energy` at the end (energy).
    pub kinetic_energy: f64,
    /// `energy_lost` over the run (energy).
    pub energy_lost: f64,
    /// `virial_sum` over the run (length·momentum).
    pub virial_sum: f64,
    /// `wall_seconds`: wall-clock duration of this process's part (s).
    pub wall_seconds: f64,
    /// `collisions_per_second`: collisions of this part per wall-clock second.
    pub collisions_per_second: f64,
    /// `potential_energy` U = Σ m g y at the end (energy), only in runs in a field
    /// (log format 2.2 on; `None` otherwise and in older logs).
    pub potential_energy: Option<f64>,
}

impl SummaryMetadata {
    /// The record as an MCAP metadata map (floats in shortest round-trip form,
    /// non-finite ones as `NaN`, `Infinity`, `-Infinity`), sealed with its checksum.
    pub fn to_map(&self) -> BTreeMap<String, String> {
        let mut m = BTreeMap::new();
        let f = f64_to_text;
        m.insert("end_time".into(), self.end_time.clone());
        m.insert("stop_reason".into(), self.stop_reason.as_str().into());
        if let Some(e) = &self.error {
            m.insert("error".into(), e.clone());
        }
        m.insert("sim_time".into(), f(self.sim_time));
        m.insert("pair_collisions".into(), self.pair_collisions.to_string());
        m.insert("wall_collisions".into(), self.wall_collisions.to_string());
        m.insert(
            "logged_collisions".into(),
            self.logged_collisions.to_string(),
        );
        m.insert("kinetic_energy".into(), f(self.kinetic_energy));
        m.insert("energy_lost".into(), f(self.energy_lost));
        m.insert("virial_sum".into(), f(self.virial_sum));
        m.insert("wall_seconds".into(), f(self.wall_seconds));
        m.insert(
            "collisions_per_second".into(),
            f(self.collisions_per_second),
        );
        if let Some(u) = self.potential_energy {
            m.insert("potential_energy".into(), f(u));
        }
        seal(&mut m);
        m
    }

    /// Parse the record.
    pub fn from_map(m: &BTreeMap<String, String>) -> Result<Self, MetadataError> {
        const R: &str = "carom.summary";
        let reason = get(m, R, "stop_reason")?;
        Ok(SummaryMetadata {
            end_time: get(m, R, "end_time")?.to_string(),
            stop_reason: StopReason::parse(reason).ok_or(MetadataError {
                record: R,
                key: "stop_reason",
                problem: format!("unknown reason {reason:?}"),
            })?,
            error: m.get("error").cloned(),
            sim_time: parse_f64(m, R, "sim_time")?,
            pair_collisions: parse(m, R, "pair_collisions")?,
            wall_collisions: parse(m, R, "wall_collisions")?,
            logged_collisions: parse(m, R, "logged_collisions")?,
            kinetic_energy: parse_f64(m, R, "kinetic_energy")?,
            energy_lost: parse_f64(m, R, "energy_lost")?,
            virial_sum: parse_f64(m, R, "virial_sum")?,
            wall_seconds: parse_f64(m, R, "wall_seconds")?,
            collisions_per_second: parse_f64(m, R, "collisions_per_second")?,
            potential_energy: parse_opt_f64(m, R, "potential_energy")?,
        })
    }
}

/// The current wall-clock time as RFC 3339 UTC with millisecond precision, e.g.
/// `2024-05-01T12:34:56.789Z`.
pub fn now_rfc3339() -> String {
    let d = SystemTime::now()
        .duration_since(UNIX_EPOCH)
        .unwrap_or_default();
    rfc3339(d.as_secs(), d.subsec_millis())
}

/// Seconds since the Unix epoch as RFC 3339 UTC.
pub fn rfc3339(secs: u64, millis: u32) -> String {
    let days = (secs / 86_400) as i64;
    let rem = secs % 86_400;
    // Howard Hinnant's civil_from_days.
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let day = doy - (153 * mp + 2) / 5 + 1;
    let month = if mp < 10 { mp + 3 } else { mp - 9 };
    let year = yoe + era * 400 + i64::from(month <= 2);
    format!(
        "{year:04}-{month:02}-{day:02}T{:02}:{:02}:{:02}.{millis:03}Z",
        rem / 3600,
        rem % 3600 / 60,
        rem % 60
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rfc3339_known_dates() {
        assert_eq!(rfc3339(0, 0), "1970-01-01T00:00:00.000Z");
        assert_eq!(rfc3339(951_782_400, 5), "2000-02-29T00:00:00.005Z");
        assert_eq!(rfc3339(1_700_000_000, 0), "2023-11-14T22:13:20.000Z");
    }

    /// Day by day from 1970 to 2500 against a calendar counted forward by hand
    /// (the Gregorian leap rule: every 4th year, not every 100th, every 400th).
    #[test]
    fn rfc3339_counts_every_day_of_the_gregorian_calendar() {
        let (mut y, mut m, mut d) = (1970i64, 1i64, 1i64);
        let leap = |y: i64| (y % 4 == 0 && y % 100 != 0) || y % 400 == 0;
        for day in 0..(530 * 366) as u64 {
            if y == 2500 {
                break;
            }
            let expected = format!("{y:04}-{m:02}-{d:02}T23:59:59.999Z");
            assert_eq!(rfc3339(day * 86_400 + 86_399, 999), expected, "day {day}");
            let len = match m {
                2 if leap(y) => 29,
                2 => 28,
                4 | 6 | 9 | 11 => 30,
                _ => 31,
            };
            d += 1;
            if d > len {
                (d, m) = (1, m + 1);
            }
            if m > 12 {
                (m, y) = (1, y + 1);
            }
        }
        assert_eq!(y, 2500);
    }

    #[test]
    fn now_is_read_from_the_clock() {
        let secs = || SystemTime::now().duration_since(UNIX_EPOCH).unwrap();
        let before = secs();
        let now = now_rfc3339();
        let after = secs();
        // The fixed-width format sorts like the time it names.
        assert!(
            rfc3339(before.as_secs(), before.subsec_millis()) <= now,
            "{now}"
        );
        assert!(
            now <= rfc3339(after.as_secs(), after.subsec_millis()),
            "{now}"
        );
    }

    #[test]
    fn summary_metadata_round_trips() {
        let mut s = SummaryMetadata {
            end_time: rfc3339(1_700_000_000, 250),
            stop_reason: StopReason::NoCollision,
            error: Some("no pair can meet".into()),
            sim_time: 12.5,
            pair_collisions: 1_000_001,
            wall_collisions: 17,
            logged_collisions: 500_000,
            kinetic_energy: 99.75,
            energy_lost: 0.1 + 0.2,
            virial_sum: -3.0e-7,
            wall_seconds: 1.0 / 3.0,
            collisions_per_second: 2.5e6,
            potential_energy: Some(-2.5),
        };
        assert_eq!(SummaryMetadata::from_map(&s.to_map()).unwrap(), s);
        s.error = None;
        s.stop_reason = StopReason::Time;
        let m = s.to_map();
        assert!(!m.contains_key("error"));
        assert_eq!(SummaryMetadata::from_map(&m).unwrap(), s);
    }

    #[test]
    fn stop_reasons_round_trip_under_distinct_names() {
        let all = [
            StopReason::Time,
            StopReason::Collisions,
            StopReason::Interrupted,
            StopReason::Exhausted,
            StopReason::Error,
            StopReason::DiskFull,
            StopReason::NoCollision,
        ];
        for r in all {
            assert_eq!(StopReason::parse(r.as_str()), Some(r));
        }
        let names: std::collections::BTreeSet<_> = all.iter().map(|r| r.as_str()).collect();
        assert_eq!(names.len(), all.len());
        assert_eq!(StopReason::parse("disk full"), None);
    }

    #[test]
    fn run_metadata_round_trips() {
        let m = RunMetadata {
            log_format: LOG_FORMAT_VERSION.into(),
            carom_version: "0.1.0".into(),
            config: "{\"a\": 1}".into(),
            seed: 42,
            start_time: now_rfc3339(),
            n_discs: 100,
            stop: Stop::Time(12.5),
            max_time_without_collision: Some(0.25),
            log: LogOptions {
                snapshot_interval: None,
                compression: Compression::Lz4,
                ..LogOptions::default()
            },
            resumed_from: Some("a.mcap".into()),
            resumed_at: Some(0.1),
            run_facts: Some(RunFacts::new(
                &[carom_core::Species::new(100, 0.5, 1.0)],
                &carom_core::SimBox::walled(12.0, 15.0, 1.0),
                &carom_engine::EngineParams::default(),
                &LogOptions::default(),
            )),
        };
        assert_eq!(RunMetadata::from_map(&m.to_map()).unwrap(), m);
        // A log of format 1.1 has no `run_facts`: it reads, without facts.
        let mut old = m.to_map();
        old.remove("run_facts");
        old.insert("log_format".into(), "1.1".into());
        let read = RunMetadata::from_map(&old).unwrap();
        assert_eq!(read.run_facts, None);
        assert_eq!(read.log_format, "1.1");
        let mut bad = m.to_map();
        bad.insert("run_facts".into(), "{\"n_discs\": 1}".into());
        assert_eq!(RunMetadata::from_map(&bad).unwrap_err().key, "run_facts");
        // Format 1.x logs hold the full collision record (no `collision_detail`).
        let mut log = serde_json::from_str::<Value>(&old["log_options"]).unwrap();
        log.as_object_mut().unwrap().remove("collision_detail");
        old.insert("log_options".into(), log.to_string());
        let read = RunMetadata::from_map(&old).unwrap();
        assert_eq!(read.log.collision_detail, CollisionDetail::Full);
        assert_eq!(m.log.collision_record(), CollisionDetail::Compact);
        let mut bad = m.to_map();
        bad.insert("log_format".into(), "3.0".into());
        let err = RunMetadata::from_map(&bad).unwrap_err();
        assert_eq!(err.key, "log_format");
        assert!(err.problem.contains("1.x and 2.x"), "{}", err.problem);
        bad.remove("log_format");
        assert_eq!(RunMetadata::from_map(&bad).unwrap_err().problem, "missing");
    }

    #[test]
    fn a_snapshot_schedule_is_stored_only_when_set() {
        let plain = LogOptions::default();
        let json = log_options_to_json(&plain);
        assert!(json.get("snapshot_schedule").is_none(), "{json}");
        assert_eq!(log_options_from_json(&json), Some(plain.clone()));
        let sched = LogOptions {
            snapshot_schedule: Some(SchedulePoints {
                points: 20,
                first: 0.01,
            }),
            ..plain
        };
        let json = log_options_to_json(&sched);
        assert_eq!(json["snapshot_schedule"]["points"], 20);
        assert_eq!(json["snapshot_schedule"]["first"], 0.01);
        assert_eq!(log_options_from_json(&json), Some(sched));
        // A schedule without its number of points is no log's.
        let bad = serde_json::json!({"snapshot_schedule": {"first": 0.01}});
        assert_eq!(log_options_from_json(&bad), None);
    }
}
