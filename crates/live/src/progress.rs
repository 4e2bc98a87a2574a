//! The live `/progress` record: where the run is (simulated time, collisions),
//! how fast it goes (collisions per wall second) and how long it still needs
//! (ETA = wall time so far × (1 − f)/f, f the fraction done by the stop
//! criterion), as JSON with the JSON Schema [`PROGRESS_JSON_SCHEMA`] (every
//! property typed, as Foxglove's readers want).

use carom_run::Progress;
use serde::Serialize;

/// JSON Schema `carom.Progress` of the `/progress` records.
pub(crate) const PROGRESS_JSON_SCHEMA: &str = r#"{
  "$schema": "https://json-schema.org/draft/2020-12/schema",
  "title": "carom.Progress",
  "description": "Progress of a carom run while it runs (carom run --live), about every frame.",
  "type": "object",
  "properties": {
    "time": {"type": "number", "description": "simulated time (time)"},
    "collisions": {"type": "integer", "description": "pair + wall collisions since the start of the run, including before a resume"},
    "collisions_per_second": {"type": "number", "description": "collisions of this process per wall-clock second so far"},
    "wall_seconds": {"type": "number", "description": "wall-clock seconds since this process started the run"},
    "fraction": {"type": "number", "description": "fraction of the run done (0 to 1), from the stop criterion"},
    "eta_seconds": {"type": "number", "description": "wall-clock seconds still needed at the rate so far, wall_seconds (1 - fraction) / fraction; absent while fraction = 0"}
  },
  "required": ["time", "collisions", "collisions_per_second", "wall_seconds", "fraction"]
}"#;

/// A `/progress` record.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub(crate) struct ProgressRecord {
    time: f64,
    collisions: u64,
    collisions_per_second: f64,
    wall_seconds: f64,
    fraction: f64,
    #[serde(skip_serializing_if = "Option::is_none")]
    eta_seconds: Option<f64>,
}

impl ProgressRecord {
    /// The record of the run's progress `p`.
    pub(crate) fn of(p: &Progress) -> Self {
        let f = p.fraction;
        ProgressRecord {
            time: p.sim_time,
            collisions: p.collisions,
            collisions_per_second: p.collisions_per_second,
            wall_seconds: p.wall_seconds,
            fraction: f,
            eta_seconds: (f > 0.0).then(|| p.wall_seconds * (1.0 - f) / f),
        }
    }

    /// The record as JSON.
    pub(crate) fn to_json(self) -> Vec<u8> {
        serde_json::to_vec(&self).expect("a record of finite numbers serializes")
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use carom_log::Stop;

    #[test]
    fn the_eta_is_the_time_so_far_scaled_by_what_is_left() {
        let p = Progress {
            sim_time: 3.5,
            collisions: 1000,
            collisions_per_second: 250.0,
            wall_seconds: 4.0,
            fraction: 0.25,
            stop: Stop::Time(14.0),
            log_bytes: 0,
        };
        let r: serde_json::Value =
            serde_json::from_slice(&ProgressRecord::of(&p).to_json()).unwrap();
        assert_eq!(r["eta_seconds"], 12.0);
        assert_eq!(r["collisions"], 1000);
        let start = ProgressRecord::of(&Progress { fraction: 0.0, ..p });
        assert_eq!(start.eta_seconds, None);
        // Every property of a record is in the schema, typed.
        let schema: serde_json::Value = serde_json::from_str(PROGRESS_JSON_SCHEMA).unwrap();
        for (k, _) in r.as_object().unwrap() {
            assert!(schema["properties"][k]["type"].is_string(), "{k}");
        }
    }
}
