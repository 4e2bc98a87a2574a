//! `carom run` and `carom resume`: progress on a terminal (indicatif) or plain
//! periodic lines otherwise, and Ctrl-C (SIGINT), SIGTERM and SIGHUP as a clean
//! stop: batch schedulers send SIGTERM at the end of a job's time, and a closed
//! terminal sends SIGHUP.

use std::cell::RefCell;
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Instant;

use carom::events::PlacementProgress;
use carom::io::config::{self, ConfigError};
use carom::io::run_metadata::StopReason;
use carom::io::Stop;
use carom::run::{Control, Progress, ResumeOptions, RunError, RunSummary};
use indicatif::{ProgressBar, ProgressStyle};

use super::{CliError, Num, ResumeArgs, RunArgs, PLAIN_EVERY};

/// Raised by Ctrl-C, SIGTERM or SIGHUP; the run stops at its next event and
/// finishes the log.
static STOP: AtomicBool = AtomicBool::new(false);

/// Install the handler of Ctrl-C, SIGTERM and SIGHUP: the first signal asks the
/// run to stop cleanly, a second one exits at once.
fn install_ctrlc() {
    let r = ctrlc::set_handler(|| {
        if STOP.swap(true, Ordering::SeqCst) {
            eprintln!("\ninterrupted again: exiting without finishing the log");
            std::process::exit(130);
        }
        eprintln!(
            "\ninterrupt: stopping at the next event and finishing the log, or at once if the \
             discs are still being placed (interrupt again to abort)"
        );
    });
    if let Err(e) = r {
        eprintln!(
            "warning: cannot handle Ctrl-C, SIGTERM or SIGHUP ({e}); a signal will cut the log short"
        );
    }
}

/// Progress display: an indicatif bar on a terminal, a plain line every
/// `PLAIN_EVERY` otherwise, nothing with `--quiet`. Relaxed placement, before the
/// run, gets a spinner of its own (its length is not known in advance).
struct Display {
    bar: Option<ProgressBar>,
    plain: bool,
    last_plain: Option<Instant>,
    /// The placement spinner (terminal only) and when placement started.
    placing: Option<(Option<ProgressBar>, Instant)>,
}

fn stop_text(s: &Stop) -> String {
    match s {
        Stop::Time(t) => format!("t = {}", Num(*t)),
        Stop::Collisions(n) => format!("{n} collisions"),
    }
}

impl Display {
    fn new(quiet: bool) -> Self {
        if quiet {
            return Display {
                bar: None,
                plain: false,
                last_plain: None,
                placing: None,
            };
        }
        if std::io::stderr().is_terminal() {
            let bar = ProgressBar::new(1000);
            bar.set_style(
                ProgressStyle::with_template(
                    "{spinner} [{elapsed_precise}] {bar:30} {percent:>3}% {msg} (ETA {eta})",
                )
                .expect("valid template"),
            );
            Display {
                bar: Some(bar),
                plain: false,
                last_plain: None,
                placing: None,
            }
        } else {
            Display {
                bar: None,
                plain: true,
                last_plain: None,
                placing: None,
            }
        }
    }

    fn update(&mut self, p: &Progress) {
        let msg = format!(
            "t = {:.4} / {}, {} collisions, {:.3e} coll/s",
            Num(p.sim_time),
            stop_text(&p.stop),
            p.collisions,
            p.collisions_per_second
        );
        if let Some(bar) = &self.bar {
            bar.set_position((p.fraction.clamp(0.0, 1.0) * 1000.0) as u64);
            bar.set_message(msg);
        } else if self.plain {
            let due = self.last_plain.is_none_or(|t| t.elapsed() >= PLAIN_EVERY);
            if due || p.fraction >= 1.0 {
                eprintln!(
                    "[{:7.1} s] {:5.1}% {msg}",
                    p.wall_seconds,
                    100.0 * p.fraction.clamp(0.0, 1.0)
                );
                self.last_plain = Some(Instant::now());
            }
        }
    }

    /// Show how far relaxed placement has got; `p.close == 0` means it is done.
    fn placing(&mut self, p: &PlacementProgress) {
        if self.bar.is_none() && !self.plain {
            return;
        }
        let terminal = self.bar.is_some();
        let (spinner, start) = self.placing.get_or_insert_with(|| {
            let spinner = terminal.then(|| {
                let s = ProgressBar::new_spinner();
                s.set_style(
                    ProgressStyle::with_template("{spinner} [{elapsed_precise}] {msg}")
                        .expect("valid template"),
                );
                s
            });
            (spinner, Instant::now())
        });
        if let Some(s) = spinner {
            if p.close == 0 {
                s.finish_and_clear();
            } else {
                // Short enough for one line of an 80-column terminal.
                s.set_message(format!(
                    "placing {} discs (relaxed): step {}, {} pairs too close",
                    p.discs, p.steps, p.close
                ));
                s.tick();
            }
            return;
        }
        let due = self.last_plain.is_none_or(|t| t.elapsed() >= PLAIN_EVERY);
        if due || p.close == 0 {
            let seconds = start.elapsed().as_secs_f64();
            if p.close == 0 {
                eprintln!(
                    "[{seconds:7.1} s] placed {} discs (relaxed placement) in {} minimization \
                     steps",
                    p.discs, p.steps
                );
            } else {
                eprintln!(
                    "[{seconds:7.1} s] placing {} discs (relaxed placement): step {} of at most \
                     {}, {} pairs or wall contacts still too close",
                    p.discs, p.steps, p.max_steps, p.close
                );
            }
            self.last_plain = Some(Instant::now());
        }
    }

    fn finish(&self) {
        if let Some((Some(s), _)) = &self.placing {
            s.finish_and_clear();
        }
        if let Some(bar) = &self.bar {
            bar.finish_and_clear();
        }
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
fn run_error(e: RunError) -> CliError {
    match e {
        RunError::Init(init) => CliError::Config(ConfigError::from_init(init)),
        e @ RunError::Invalid { .. } => CliError::Usage(e.to_string()),
        other => CliError::Run(other),
    }
}

fn report(summary: &RunSummary) -> ExitCode {
    eprintln!(
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
    match summary.stop_reason {
        StopReason::Interrupted => {
            eprintln!(
                "interrupted: the log is finished; continue with `carom resume {}`",
                summary.log.display()
            );
            ExitCode::from(130)
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
        });
    }
    let spec = config::load(args.config.as_deref(), &args.set)?;
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
    install_ctrlc();
    let display = RefCell::new(Display::new(args.quiet));
    let mut progress = |p: &Progress| display.borrow_mut().update(p);
    let mut placing = |p: &PlacementProgress| display.borrow_mut().placing(p);
    let control = Control {
        placing: Some(&mut placing),
        ..Control::new(&STOP, &mut progress)
    };
    let summary = carom::run::run(&spec, &out, control);
    display.borrow().finish();
    Ok(report(&summary.map_err(run_error)?))
}

/// Whether paths `a` and `b` name the same existing file.
fn same_file(a: &Path, b: &Path) -> bool {
    match (std::fs::canonicalize(a), std::fs::canonicalize(b)) {
        (Ok(a), Ok(b)) => a == b,
        _ => a == b,
    }
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
    if !args.force && out.exists() && !same_file(&out, &args.file) {
        return Err(CliError::Usage(format!(
            "{} exists; use --force to overwrite it, choose another --out, or leave \
             --out away to continue {} in place",
            out.display(),
            args.file.display()
        )));
    }
    install_ctrlc();
    let mut display = Display::new(args.quiet);
    let mut progress = |p: &Progress| display.update(p);
    let summary = carom::run::resume(
        &args.file,
        &out,
        &ResumeOptions { stop },
        Control::new(&STOP, &mut progress),
    );
    display.finish();
    Ok(report(&summary.map_err(run_error)?))
}
