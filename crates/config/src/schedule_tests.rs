//! Unit tests of `log.snapshot_schedule` in the configuration: read, resolved,
//! set field by field, and each bad setting named.

use super::tests::err_of;
use super::*;

#[test]
fn a_snapshot_schedule_is_read_and_each_bad_setting_named() {
    let spec = |text: &str, sets: &[&str]| {
        let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
        Config::from_json_with_sets(text, "test", &sets)
            .and_then(|c| c.to_run_spec())
            .unwrap()
    };
    assert_eq!(spec("{}", &[]).log.snapshot_schedule, None);
    let s = spec(
        r#"{"log": {"snapshot_schedule": {"points": 20, "first": 0.01}}}"#,
        &[],
    );
    let want = carom_log::SchedulePoints {
        points: 20,
        first: 0.01,
    };
    assert_eq!(s.log.snapshot_schedule, Some(want));
    // The resolved configuration in the log keeps it; without one it has no key.
    assert!(s.config_json.contains("snapshot_schedule"));
    assert!(!spec("{}", &[]).config_json.contains("snapshot_schedule"));
    // Nested --set builds the object field by field (both fields are required).
    let set = spec(
        "{}",
        &[
            "log.snapshot_schedule.points=20",
            "log.snapshot_schedule.first=0.01",
        ],
    );
    assert_eq!(set.log.snapshot_schedule, Some(want));
    // A missing field is reported on its object, as for species (`species.0`).
    let e = err_of("{}", &["log.snapshot_schedule.points=20"]);
    assert_eq!(e.field(), Some("log.snapshot_schedule"), "{e}");
    assert!(e.to_string().contains("missing field `first`"), "{e}");
    let sched = |body: &str| format!(r#"{{"log": {{"snapshot_schedule": {body}}}}}"#);
    for (text, field, allowed) in [
        (
            r#"{"log": {"snapshot_interval": null, "snapshot_schedule": {"points": 2, "first": 0.01}}}"#
                .to_owned(),
            "log.snapshot_schedule",
            "log.snapshot_interval",
        ),
        (
            sched(r#"{"points": 0, "first": 0.01}"#),
            "log.snapshot_schedule.points",
            "1 ≤ n ≤ 1000",
        ),
        (
            sched(r#"{"points": 1001, "first": 0.01}"#),
            "log.snapshot_schedule.points",
            "1 ≤ n ≤ 1000",
        ),
        (
            sched(r#"{"points": 2.5, "first": 0.01}"#),
            "log.snapshot_schedule.points",
            "integer",
        ),
        // T = 1 (the default interval): first must be in [10⁻⁶, 1).
        (
            sched(r#"{"points": 2, "first": 1}"#),
            "log.snapshot_schedule.first",
            "first < T = 1",
        ),
        (
            sched(r#"{"points": 2, "first": 1e-7}"#),
            "log.snapshot_schedule.first",
            "≤ first",
        ),
        (
            sched(r#"{"points": 2, "first": -0.5}"#),
            "log.snapshot_schedule.first",
            "≤ first",
        ),
        (
            sched(r#"{"points": 2, "first": 0.1, "last": 0.5}"#),
            "log.snapshot_schedule.last",
            "",
        ),
    ] {
        let e = err_of(&text, &[]);
        assert_eq!(e.field(), Some(field), "{text}: {e}");
        assert!(e.to_string().contains(allowed), "{text}: {e}");
    }
}
