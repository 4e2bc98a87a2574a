//! `carom run` and `carom resume`: progress on a terminal (indicatif) or plain
//! periodic lines otherwise, and Ctrl-C (SIGINT), SIGTERM and SIGHUP as a clean
//! stop: batch schedulers send SIGTERM at the end of a job's time, and a closed
//! terminal sends SIGHUP.

use std::cell::RefCell;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::OnceLock;
use std::time::{Duration, Instant};

use carom_config::{load_config, ConfigError};
use carom_engine::{Engine, Placement, PlacementProgress};
use carom_log::{ReadProgress, Stop, StopReason};
use carom_run::{Control, Observer, Progress, ResumeOptions, ResumePass, RunError, RunSummary};

use super::output::say;
use super::reading::ReadDisplay;
use super::run_display::Display;
use super::{CliError, Num, ResumeArgs, RunArgs};

/// Raised by Ctrl-C, SIGTERM or SIGHUP; the run stops at its next event and
/// finishes the log.
static STOP: AtomicBool = AtomicBool::new(false);

/// A repeat of the stop signal within this time is the same request: GNU `timeout`
/// sends SIGTERM to the child and then to its process group microseconds apart.
const REPEAT_WINDOW: Duration = Duration::from_secs(1);

/// What a stop signal asks for, given when the first one came (`None`: this is it).
#[derive(Debug, PartialEq)]
enum OnSignal {
    /// Stop at the next event and finish the log.
    Stop,
    /// The same request again (within [`REPEAT_WINDOW`]): nothing more to do.
    Repeat,
    /// A second, deliberate interrupt: exit at once.
    Abort,
}

fn on_signal(first: Option<Instant>, now: Instant) -> OnSignal {
    match first {
        None => OnSignal::Stop,
        Some(t) if now.duration_since(t) < REPEAT_WINDOW => OnSignal::Repeat,
        Some(_) => OnSignal::Abort,
    }
}

/// From this many discs a run says that it is placing them (it takes seconds).
const LARGE_PLACEMENT: usize = 1_000_000;

/// Install the handler of Ctrl-C, SIGTERM and SIGHUP: the first signal asks the
/// run to stop cleanly, a second one more than [`REPEAT_WINDOW`] later exits at
/// once.
fn install_ctrlc() {
    static FIRST: OnceLock<Instant> = OnceLock::new();
    let r = ctrlc::set_handler(|| {
        let now = Instant::now();
        match on_signal(FIRST.get().copied(), now) {
            OnSignal::Repeat => {}
            OnSignal::Abort => {
                say!("\ninterrupted again: exiting without finishing the log");
                std::process::exit(130);
            }
            OnSignal::Stop => {
                let _ = FIRST.set(now);
                STOP.store(true, Ordering::SeqCst);
                say!(
                    "\ninterrupt: stopping at the next event and finishing the log, or at once \
                     if the discs are still being placed (interrupt again to abort)"
                );
            }
        }
    });
    if let Err(e) = r {
        say!(
            "warning: cannot handle Ctrl-C, SIGTERM or SIGHUP ({e}); a signal will cut the log short"
        );
    }
}

fn default_out(config: Option<&Path>) -> PathBuf {
    match config.and_then(|c| c.file_stem()) {
        Some(stem) => {
            let mut name = stem.to_os_string();
            name.push(".mcap");
            PathBuf::from(name)
        }
        None => PathBuf::from("carom.mcap"),
    }
}

/// Map a run error whose cause is the configuration to a [`ConfigError`] naming
/// the configuration's field, and one whose cause is an option (such as a
/// `resume --until` before the log's end) to a usage error: both exit with 2.
fn run_error(e: RunError, config_json: Option<&str>) -> CliError {
    match e {
        RunError::Init(init) => CliError::Config(match config_json {
            Some(json) => ConfigError::from_init_in(init, json),
            None => ConfigError::from_init(init),
        }),
        e @ RunError::Invalid { .. } => CliError::Usage(e.to_string()),
        other => CliError::Run(other),
    }
}

fn report(summary: &RunSummary) -> ExitCode {
    say!(
        "{}: stopped ({}) at t = {}, {} pair + {} wall collisions ({} logged), \
         {:.3e} collisions/s over {:.1} s, {:.1} MB",
        summary.log.display(),
        summary.stop_reason.as_str(),
        Num(summary.sim_time),
        summary.pair_collisions,
        summary.wall_collisions,
        summary.logged_collisions,
        summary.collisions_per_second,
        summary.wall_seconds,
        summary.file_bytes as f64 / 1e6
    );
    if let Some(u) = summary.potential_energy {
        say!(
            "  energy in the field: K = {}, U = Σ m g y = {}, K + U = {}",
            Num(summary.kinetic_energy),
            Num(u),
            Num(summary.kinetic_energy + u)
        );
    }
    match summary.stop_reason {
        StopReason::Interrupted => {
            say!(
                "interrupted: the log is finished; continue with `carom resume {}`",
                summary.log.display()
            );
            ExitCode::from(130)
        }
        StopReason::DiskFull if summary.detail.is_some() => {
            say!(
                "stopped early: {}; continue with `carom resume {} --ignore-disk-estimate`",
                summary.detail.as_deref().unwrap_or_default(),
                summary.log.display()
            );
            ExitCode::FAILURE
        }
        StopReason::DiskFull => {
            say!(
                "stopped early: the disk of {log} was nearly full (room was kept to finish \
                 the log, which is complete); free some space, or continue on another disk \
                 with `carom resume {log} --out OTHER_DISK/{name}`",
                log = summary.log.display(),
                name = summary
                    .log
                    .file_name()
                    .map_or("run.mcap".into(), |n| n.to_string_lossy()),
            );
            ExitCode::FAILURE
        }
        StopReason::NoCollision => {
            say!(
                "stopped early: {}; the log is finished",
                summary
                    .detail
                    .as_deref()
                    .unwrap_or("no collision within the bound")
            );
            ExitCode::FAILURE
        }
        StopReason::Error => ExitCode::FAILURE,
        _ => ExitCode::SUCCESS,
    }
}

/// `carom run`.
pub fn run(args: RunArgs) -> Result<ExitCode, CliError> {
    if let Some(file) = args.resume {
        return resume(ResumeArgs {
            file,
            out: args.out,
            until: None,
            collisions: None,
            force: args.force,
            quiet: args.quiet,
            ignore_disk_estimate: args.ignore_disk_estimate,
            live: args.live,
        });
    }
    let spec = load_config(args.config.as_deref(), &args.set)?;
    // Before placement allocates anything of the size of N.
    carom_run::check_memory(&spec)?;
    if args.dry_run {
        super::emit(&format!("{}\n", spec.config_json))?;
        return Ok(ExitCode::SUCCESS);
    }
    let out = args
        .out
        .unwrap_or_else(|| default_out(args.config.as_deref()));
    if out.exists() && !args.force {
        return Err(CliError::Usage(format!(
            "{} exists; use --force to overwrite it or --out to choose another file",
            out.display()
        )));
    }
    let mut live = args.live.start()?;
    install_ctrlc();
    let display = RefCell::new(Display::new(args.quiet, &out));
    let n: usize = spec.system.species.iter().map(|s| s.count).sum();
    if n >= LARGE_PLACEMENT
        && !matches!(
            spec.system.placement,
            Placement::Relaxed | Placement::Compressed { .. }
        )
        && !display.borrow().quiet()
    {
        // Relaxed placement shows its own progress; the others take seconds here.
        display.borrow().say(&format!("placing {n} discs…"));
    }
    let mut progress = |p: &Progress| display.borrow_mut().update(p);
    let mut placing = |p: &PlacementProgress| display.borrow_mut().placing(p);
    let mut started = |e: &Engine| display.borrow().started(e);
    let control = Control {
        placing: Some(&mut placing),
        started: Some(&mut started),
        ignore_disk_estimate: args.ignore_disk_estimate,
        observer: live.as_mut().map(|l| l as &mut dyn Observer),
        ..Control::new(&STOP, &mut progress)
    };
    let summary = carom_run::run(&spec, &out, control);
    display.borrow().finish();
    drop(live);
    if summary.is_err() {
        // A run that failed before its log held a byte leaves no empty file behind
        // to block the next attempt (which would need --force).
        if std::fs::metadata(&out).is_ok_and(|m| m.is_file() && m.len() == 0) {
            let _ = std::fs::remove_file(&out);
        }
    }
    Ok(report(
        &summary.map_err(|e| run_error(e, Some(&spec.config_json)))?,
    ))
}

/// `carom resume`.
pub fn resume(args: ResumeArgs) -> Result<ExitCode, CliError> {
    let stop = match (args.until, args.collisions) {
        (Some(t), None) => {
            if !t.is_finite() {
                return Err(CliError::Usage(format!("--until {t}: not a finite time")));
            }
            Some(Stop::Time(t))
        }
        (None, Some(n)) => Some(Stop::Collisions(n)),
        _ => None,
    };
    let out = args.out.unwrap_or_else(|| args.file.clone());
    if !args.force && out.exists() && !carom_run::same_file(&out, &args.file) {
        return Err(CliError::Usage(format!(
            "{} exists; use --force to overwrite it, choose another --out, or leave \
             --out away to continue {} in place",
            out.display(),
            args.file.display()
        )));
    }
    let mut live = args.live.start()?;
    install_ctrlc();
    let display = Display::new(args.quiet, &out);
    // Reading the input (the whole log, then most of it again to copy it) comes
    // first, with a display of its own that ends when the run's begins.
    let reads = RefCell::new(Some(ReadDisplay::new(
        args.quiet,
        &args.file.display().to_string(),
    )));
    let end_reads = || {
        if let Some(mut r) = reads.borrow_mut().take() {
            r.finish();
        }
    };
    let mut pass_now = None;
    let mut reading = |pass: ResumePass, p: ReadProgress| {
        if let Some(r) = reads.borrow_mut().as_mut() {
            if pass_now != Some(pass) {
                r.pass(pass.as_str());
                pass_now = Some(pass);
            }
            r.update(p);
        }
    };
    let display = RefCell::new(display);
    let mut started = |e: &Engine| {
        end_reads();
        display.borrow().started(e)
    };
    let mut progress = |p: &Progress| {
        end_reads();
        display.borrow_mut().update(p)
    };
    let summary = carom_run::resume(
        &args.file,
        &out,
        &ResumeOptions { stop },
        Control {
            reading: Some(&mut reading),
            started: Some(&mut started),
            ignore_disk_estimate: args.ignore_disk_estimate,
            observer: live.as_mut().map(|l| l as &mut dyn Observer),
            ..Control::new(&STOP, &mut progress)
        },
    );
    drop(live);
    end_reads();
    display.borrow().finish();
    // A resume builds no initial state, from no configuration.
    Ok(report(&summary.map_err(|e| run_error(e, None))?))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn progress(fraction: f64, log_bytes: u64) -> Progress {
        Progress {
            sim_time: 50.0 * fraction,
            collisions: 0,
            collisions_per_second: 0.0,
            wall_seconds: 1.0,
            fraction,
            stop: Stop::Time(50.0),
            log_bytes,
        }
    }

    #[test]
    fn the_log_is_projected_to_the_stop_once_its_rate_says_something() {
        // 1 % of the run or 64 MB written: the size so far over the fraction done.
        assert_eq!(progress(0.5, 100).projected_log_bytes(), Some(200.0));
        assert_eq!(progress(0.01, 1000).projected_log_bytes(), Some(1e5));
        let big = 64 << 20;
        assert_eq!(
            progress(0.001, big).projected_log_bytes(),
            Some(big as f64 * 1000.0)
        );
        // Too early: the first snapshot and checkpoint would dominate.
        assert_eq!(progress(0.005, 1 << 20).projected_log_bytes(), None);
        assert_eq!(progress(0.0, big).projected_log_bytes(), None);
    }

    #[test]
    fn a_signal_repeated_within_a_second_is_the_same_stop() {
        let t0 = Instant::now();
        assert_eq!(on_signal(None, t0), OnSignal::Stop);
        let soon = t0 + Duration::from_micros(20);
        assert_eq!(on_signal(Some(t0), soon), OnSignal::Repeat);
        let later = t0 + Duration::from_millis(1500);
        assert_eq!(on_signal(Some(t0), later), OnSignal::Abort);
    }
}
