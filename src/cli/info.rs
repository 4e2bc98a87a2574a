//! `carom info`: what a log holds: from a finished log's index, or from a scan of
//! every message (which does not decode collisions) for a log cut short, a log
//! whose index, footer or `carom.summary` record is damaged, or with `--verify`.
//! A damaged summary (its checksum fails) is not shown: the counts from the last
//! `/thermo` record stand in for it.

use std::process::ExitCode;

use carom_log::CH_SCENE;
use carom_log::{scan_indexed, scan_observed, LogEnd, LogInfo, Stop, METADATA_SUMMARY, TOPICS};
use std::fmt::Write;
use std::io::Write as _;

use serde_json::{json, Value};

use super::reading::ReadDisplay;
use super::{CliError, InfoArgs, Num};

fn stop_json(s: &Stop) -> Value {
    match s {
        Stop::Time(t) => json!({ "time": t }),
        Stop::Collisions(n) => json!({ "collisions": n }),
    }
}

/// Whether the log's `carom.summary` record is there but damaged (the reader
/// names it in the damage it reports, and then leaves it out).
fn summary_damaged(i: &LogInfo) -> bool {
    i.summary.is_none()
        && matches!(&i.end, LogEnd::Damaged { detail } if detail.contains(METADATA_SUMMARY))
}

fn end_text(e: &LogEnd) -> (bool, String) {
    match e {
        LogEnd::Complete => (true, "complete".into()),
        LogEnd::Truncated { detail } => (false, format!("cut off ({detail})")),
        LogEnd::Damaged { detail } => (
            false,
            format!("damaged outside its chunks, every message read ({detail})"),
        ),
        LogEnd::Reading | LogEnd::Failed => (false, "unreadable end".into()),
    }
}

/// The scan as one JSON object: `file`, `bytes`, `complete`, `end`, `run`
/// (version, start time, seed, N, stop, resumed_from/at, config with the resolved
/// `log.collision_detail`), `channels`
/// (topic → defined, messages, time span), `logged_collisions`,
/// `last_checkpoint_time`, `summary` (null for a cut-off log). `carom info --json`
/// adds `verified`: whether every message was read (a log cut short, or
/// `--verify`) rather than the file's index.
pub fn info_json(path: &str, i: &LogInfo) -> Value {
    let (complete, end) = end_text(&i.end);
    let mut config: Value =
        serde_json::from_str(&i.run.config).unwrap_or(Value::String(i.run.config.clone()));
    // The resolved record, which a configuration that left it out does not say.
    if let Some(c) = config.as_object_mut() {
        let log = c.entry("log").or_insert_with(|| json!({}));
        if let Some(log) = log.as_object_mut() {
            log.entry("collision_detail")
                .or_insert_with(|| json!(i.run.log.collision_detail.name()));
        }
    }
    let channels: serde_json::Map<String, Value> = TOPICS
        .iter()
        .enumerate()
        .map(|(k, t)| {
            (
                t.to_string(),
                json!({
                    "defined": i.channels[k],
                    "messages": i.messages[k],
                    "time_span": i.time_span[k].map(|(a, b)| [a, b]),
                }),
            )
        })
        .collect();
    let summary = i.summary.as_ref().map(|s| {
        json!({
            "stop_reason": s.stop_reason.as_str(),
            "error": s.error,
            "end_time": s.end_time,
            "sim_time": s.sim_time,
            "pair_collisions": s.pair_collisions,
            "wall_collisions": s.wall_collisions,
            "logged_collisions": s.logged_collisions,
            "kinetic_energy": s.kinetic_energy,
            "energy_lost": s.energy_lost,
            "wall_seconds": s.wall_seconds,
            "collisions_per_second": s.collisions_per_second,
            "potential_energy": s.potential_energy,
        })
    });
    json!({
        "file": path,
        "bytes": i.file_bytes,
        "complete": complete,
        "end": end,
        "run": {
            "log_format": i.run.log_format,
            "carom_version": i.run.carom_version,
            "start_time": i.run.start_time,
            "seed": i.run.seed,
            "n_discs": i.run.n_discs,
            "stop": stop_json(&i.run.stop),
            "resumed_from": i.run.resumed_from,
            "resumed_at": i.run.resumed_at,
            "config": config,
        },
        "channels": channels,
        "logged_collisions": i.logged_collisions,
        "last_checkpoint_time": i.last_checkpoint_time,
        "summary": summary,
    })
}

/// `carom info`.
pub fn info(args: InfoArgs) -> Result<ExitCode, CliError> {
    // A finished log's index says it all at once; a log cut short, or --verify,
    // reads every message.
    let indexed = if args.verify {
        None
    } else {
        scan_indexed(&args.file)?
    };
    let verified = indexed.is_none();
    let i = match indexed {
        Some(i) => i,
        None => {
            let mut display = ReadDisplay::new(args.quiet, &args.file.display().to_string());
            display.pass("scanning");
            let i = scan_observed(&args.file, &mut |p| display.update(p));
            display.finish();
            i?
        }
    };
    let path = args.file.display().to_string();
    if let Some(w) = i.end.warning() {
        let _ = writeln!(std::io::stderr(), "warning: {w}");
    }
    // --verify checks every CRC and the footer: anything but an intact end fails.
    let status = if args.verify && i.end != LogEnd::Complete {
        ExitCode::FAILURE
    } else {
        ExitCode::SUCCESS
    };
    if args.json {
        let mut v = info_json(&path, &i);
        v["verified"] = Value::Bool(verified);
        v["summary_damaged"] = Value::Bool(summary_damaged(&i));
        super::emit(&format!("{v}\n"))?;
        return Ok(status);
    }
    let mut s = String::new();
    let (_, end) = end_text(&i.end);
    let _ = writeln!(
        s,
        "{path}: {:.2} MB, {end}{}",
        i.file_bytes as f64 / 1e6,
        if verified {
            ""
        } else {
            " (from its index; --verify reads every message)"
        }
    );
    let _ = writeln!(
        s,
        "  written by carom {} (log format {}), started {}",
        i.run.carom_version, i.run.log_format, i.run.start_time
    );
    let _ = writeln!(
        s,
        "  N = {}, seed {}, stop at {}",
        i.run.n_discs,
        i.run.seed,
        stop_json(&i.run.stop)
    );
    if let (Some(f), Some(t)) = (&i.run.resumed_from, i.run.resumed_at) {
        let _ = writeln!(s, "  resumed from {f} at t = {}", Num(t));
    }
    let _ = writeln!(s, "  channels:");
    for (k, t) in TOPICS.iter().enumerate() {
        if k == CH_SCENE && !i.channels[k] {
            continue; // optional, and off unless asked for
        }
        let span = match i.time_span[k] {
            Some((a, b)) => format!("t ∈ [{}, {}]", Num(a), Num(b)),
            None => "no messages".into(),
        };
        let _ = writeln!(
            s,
            "    {t:<12} {:>10} messages  {span}{}",
            i.messages[k],
            if i.channels[k] { "" } else { "  (not defined)" }
        );
    }
    let _ = writeln!(s, "  logged collisions: {}", i.logged_collisions);
    if let Some(t) = i.last_checkpoint_time {
        let _ = writeln!(s, "  last checkpoint at t = {}", Num(t));
    }
    let _ = match &i.summary {
        Some(sm) => writeln!(s,
            "  summary: stopped ({}{}) at t = {}, {} pair + {} wall collisions, {:.3e} collisions/s, E = {}, dissipated {}",
            sm.stop_reason.as_str(),
            sm.error.as_deref().map(|e| format!(": {e}")).unwrap_or_default(),
            Num(sm.sim_time),
            sm.pair_collisions,
            sm.wall_collisions,
            sm.collisions_per_second,
            Num(sm.kinetic_energy),
            Num(sm.energy_lost)
        ).and_then(|_| match sm.potential_energy {
            Some(u) => writeln!(s,
                "  energy in the field: K = {}, U = Σ m g y = {}, K + U = {}",
                Num(sm.kinetic_energy), Num(u), Num(sm.kinetic_energy + u)),
            None => Ok(()),
        }),
        None if summary_damaged(&i) => writeln!(
            s,
            "  summary: DAMAGED (the {METADATA_SUMMARY} record: see the warning); its values are not shown{}",
            match i.thermo_counts {
                Some([_, (t, pair, wall)]) => format!(
                    "; the last /thermo record says t = {}, {pair} pair + {wall} wall collisions",
                    Num(t)
                ),
                None => String::new(),
            }
        ),
        None => match (&i.end, i.last_checkpoint_time) {
            (LogEnd::Damaged { .. }, _) => writeln!(s, "  summary: none readable"),
            (_, Some(_)) => writeln!(s, "  summary: none (the run did not finish; `carom resume` continues it)"),
            (_, None) => writeln!(s, "  summary: none (the run did not finish, and no checkpoint to resume from)"),
        },
    };
    let _ = writeln!(
        s,
        "  collision record (log.collision_detail): {}",
        i.run.log.collision_detail.name()
    );
    let _ = writeln!(s, "  configuration:");
    for line in i.run.config.lines() {
        let _ = writeln!(s, "    {line}");
    }
    super::emit(&s)?;
    Ok(status)
}
