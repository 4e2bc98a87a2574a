//! `carom sweep`: lay out a plan's points, then run the unfinished ones in a local
//! pool with one combined progress display, or submit them to Slurm as a job
//! array; `carom sweep status` tells each point's state from its log; `carom
//! sweep point` is what a Slurm task runs. One sweep at a time per directory
//! (`DIR/sweep.lock`). What the sweep prints goes to standard error; when that
//! cannot be written (a closed pipe, a full disk) it is dropped and the sweep and
//! its points go on — the points write into their own `carom.log`, never into the
//! sweep's streams, so they also outlive a sweep that is killed.

use std::io::IsTerminal;
use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::atomic::{AtomicBool, Ordering};

use carom_run::sweep::slurm::{submit, SlurmOptions};
use carom_run::sweep::{
    cores, jobs_at_once, point_command, point_state, run_point, run_pool, Plan, PointOutcome,
    PointState, PoolEvent, SweepDir, SweepLock,
};
use clap::{Args, Subcommand};
use indicatif::{ProgressBar, ProgressStyle};
use serde_json::json;

use super::CliError;

/// Arguments of `carom sweep`.
// The field docs are `carom sweep --help`'s text (`DIR/<point>/…`), not HTML.
#[allow(rustdoc::invalid_html_tags)]
#[derive(Debug, Args)]
#[command(args_conflicts_with_subcommands = true, subcommand_negates_reqs = true)]
pub struct SweepArgs {
    #[command(subcommand)]
    action: Option<SweepAction>,
    /// The plan: a base configuration, the dotted paths to vary and replicas
    /// (data/sweep.schema.json; example data/sweeps/eos.json).
    #[arg(required = true)]
    plan: Option<PathBuf>,
    /// The sweep's directory: DIR/<point>/run.mcap for each point. Re-running
    /// with the same plan and DIR skips finished points and resumes interrupted
    /// ones.
    #[arg(short, long, value_name = "DIR", required = true)]
    out: Option<PathBuf>,
    /// Points run at once (default: one per core; never more than the cores).
    #[arg(short, long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..))]
    jobs: Option<u32>,
    /// List the points and what each needs, run nothing.
    #[arg(long)]
    dry_run: bool,
    /// Submit the unfinished points to Slurm as a job array instead of running them here.
    #[arg(long)]
    slurm: bool,
    /// Slurm partition (`sbatch --partition`).
    #[arg(long, requires = "slurm", value_name = "NAME")]
    partition: Option<String>,
    /// Time limit per point (`sbatch --time`, e.g. 2:00:00).
    #[arg(long, requires = "slurm", value_name = "TIME")]
    time: Option<String>,
    /// Memory per point (`sbatch --mem`, e.g. 2G).
    #[arg(long, requires = "slurm", value_name = "MEM")]
    mem: Option<String>,
    /// CPUs per point (`sbatch --cpus-per-task`).
    #[arg(long, requires = "slurm", value_name = "N")]
    cpus_per_task: Option<u32>,
    /// One more argument for sbatch, passed as given (repeatable), e.g.
    /// --sbatch-arg=--account=phys.
    #[arg(
        long = "sbatch-arg",
        requires = "slurm",
        value_name = "ARG",
        allow_hyphen_values = true
    )]
    sbatch_args: Vec<String>,
    /// Block until the array has ended, then show the points' states.
    #[arg(long, requires = "slurm")]
    wait: bool,
    /// No progress display.
    #[arg(short, long)]
    quiet: bool,
}

#[derive(Debug, Subcommand)]
enum SweepAction {
    /// Each point's state (pending, running, done, interrupted, failed), read
    /// from its log.
    Status {
        /// The sweep's directory.
        dir: PathBuf,
        /// One JSON object instead of text.
        #[arg(long)]
        json: bool,
    },
    /// Run (or resume) one point of a laid-out sweep: what each Slurm task runs.
    Point {
        /// The sweep's directory.
        dir: PathBuf,
        /// The point's index in DIR/points.json.
        #[arg(long)]
        index: usize,
    },
}

static STOP: AtomicBool = AtomicBool::new(false);

/// Write `line` to standard error, or drop it if standard error cannot be
/// written (closed pipe, full disk): a sweep's messages are never worth its points.
pub(super) use super::output::say_line as say;

fn carom_exe() -> Result<PathBuf, CliError> {
    std::env::current_exe().map_err(|source| CliError::Io {
        context: "cannot find the carom executable to run the points with".into(),
        source,
    })
}

/// `carom sweep`.
pub fn sweep(args: SweepArgs) -> Result<ExitCode, CliError> {
    match args.action {
        Some(SweepAction::Status { dir, json }) => return status(&dir, json),
        Some(SweepAction::Point { dir, index }) => return point(&dir, index),
        None => {}
    }
    let (plan, out) = (
        args.plan.expect("required by clap"),
        args.out.expect("required by clap"),
    );
    let plan = Plan::load(&plan)?;
    let out = std::path::absolute(&out).map_err(|source| CliError::Io {
        context: format!("cannot resolve {}", out.display()),
        source,
    })?;
    if args.dry_run {
        // Nothing is written: the points and what each would need now.
        let preview = SweepDir {
            dir: out.clone(),
            plan,
        };
        let mut s = String::new();
        for (i, p) in preview.plan.points.iter().enumerate() {
            let what = if out.join("plan.json").exists() {
                match point_command(&preview, i) {
                    Some(c) => format!("{} {}", point_state(&preview, i).word(), c[0]),
                    None => point_state(&preview, i).word().to_owned(),
                }
            } else {
                "pending run".into()
            };
            s += &format!("{i:4}  {}  ({what})\n", preview.dir.join(&p.name).display());
        }
        s += &format!("{} points\n", preview.plan.points.len());
        super::emit(&s)?;
        return Ok(ExitCode::SUCCESS);
    }
    // Held until the sweep ends: a second sweep into `out` is refused meanwhile.
    let _lock = SweepLock::take(&out)?;
    let sweep = SweepDir::create(&out, plan)?;
    let exe = carom_exe()?;
    if args.slurm {
        let todo: Vec<usize> = (0..sweep.plan.points.len())
            .filter(|&i| point_state(&sweep, i).unfinished())
            .collect();
        if todo.is_empty() {
            say(&format!(
                "every point of {} is finished or running",
                out.display()
            ));
            return Ok(ExitCode::SUCCESS);
        }
        let opts = SlurmOptions {
            partition: args.partition,
            time: args.time,
            mem: args.mem,
            cpus_per_task: args.cpus_per_task,
            extra: args.sbatch_args,
            wait: args.wait,
        };
        let job = submit(&sweep, &exe, &todo, &opts)?;
        say(&format!(
            "submitted job array {job}: {} of {} points ({})",
            todo.len(),
            sweep.plan.points.len(),
            out.join("slurm/sweep.sbatch").display()
        ));
        if !args.wait {
            super::emit(&format!("{job}\n"))?;
            return Ok(ExitCode::SUCCESS);
        }
        return status(&out, false);
    }
    install_stop();
    let (jobs, capped) = jobs_at_once(args.jobs, cores());
    if let Some(note) = capped {
        say(&format!("note: {note}"));
    }
    let n = sweep.plan.points.len();
    let mut display = Display::new(args.quiet, n);
    let report = run_pool(&exe, &sweep, jobs, &STOP, |e| display.event(&sweep, e))?;
    display.finish();
    let count =
        |f: fn(&PointOutcome) -> bool| report.outcomes.iter().flatten().filter(|o| f(o)).count();
    let done = count(|o| {
        matches!(
            o,
            PointOutcome::Done | PointOutcome::Skipped(PointState::Done { .. })
        )
    });
    let failed = count(|o| matches!(o, PointOutcome::Failed(_)));
    let interrupted = n - done - failed;
    say(&format!(
        "sweep {}: {done} of {n} points done, {failed} failed, {interrupted} not finished, in {:.1} s with {jobs} at a time",
        out.display(),
        report.wall_seconds
    ));
    Ok(if STOP.load(Ordering::SeqCst) {
        ExitCode::from(130)
    } else if failed > 0 || interrupted > 0 {
        ExitCode::from(1)
    } else {
        ExitCode::SUCCESS
    })
}

/// `carom sweep status DIR`.
fn status(dir: &std::path::Path, as_json: bool) -> Result<ExitCode, CliError> {
    let sweep = SweepDir::open(dir)?;
    let states: Vec<PointState> = (0..sweep.plan.points.len())
        .map(|i| point_state(&sweep, i))
        .collect();
    if as_json {
        let points: Vec<_> = sweep
            .plan
            .points
            .iter()
            .zip(&states)
            .enumerate()
            .map(|(i, (p, s))| {
                json!({"index": i, "name": p.name, "state": s.word(), "detail": detail(s)})
            })
            .collect();
        super::emit(&format!(
            "{}\n",
            json!({"dir": dir.display().to_string(), "points": points})
        ))?;
    } else {
        let mut s = String::new();
        for (i, (p, st)) in sweep.plan.points.iter().zip(&states).enumerate() {
            s += &format!("{i:4}  {:<11} {}  {}\n", st.word(), p.name, detail(st));
        }
        for w in [
            "done",
            "running",
            "interrupted",
            "failed",
            "mismatch",
            "unreadable",
            "pending",
        ] {
            let k = states.iter().filter(|s| s.word() == w).count();
            if k > 0 {
                s += &format!("{w}: {k}  ");
            }
        }
        s += &format!("(of {})\n", states.len());
        super::emit(&s)?;
    }
    Ok(ExitCode::SUCCESS)
}

fn detail(s: &PointState) -> String {
    match s {
        PointState::Done {
            stop_reason,
            sim_time,
        } => format!("{} at t = {sim_time}", stop_reason.as_str()),
        PointState::Interrupted { detail, .. } => detail.clone(),
        PointState::Failed { error } => error.clone(),
        PointState::Mismatch { detail } | PointState::Unreadable { detail } => {
            format!("{detail} (not collected; the next sweep moves it aside and runs the point)")
        }
        PointState::Pending | PointState::Running => String::new(),
    }
}

/// `carom sweep point DIR --index I` (a Slurm task).
fn point(dir: &std::path::Path, index: usize) -> Result<ExitCode, CliError> {
    let sweep = SweepDir::open(dir)?;
    let n = sweep.plan.points.len();
    if index >= n {
        return Err(CliError::Usage(format!(
            "--index {index}: {} has {n} points (allowed: 0 to {})",
            dir.display(),
            n.saturating_sub(1)
        )));
    }
    let name = &sweep.plan.points[index].name;
    let outcome = run_point(&carom_exe()?, &sweep, index)?;
    say(&format!("point {index} ({name}): {outcome:?}"));
    Ok(match outcome {
        PointOutcome::Done | PointOutcome::Skipped(_) => ExitCode::SUCCESS,
        PointOutcome::Interrupted => ExitCode::from(130),
        PointOutcome::Failed(_) => ExitCode::from(1),
    })
}

/// Ctrl-C, SIGTERM, SIGHUP: start nothing more, stop the running points cleanly.
fn install_stop() {
    let r = ctrlc::set_handler(|| {
        if !STOP.swap(true, Ordering::SeqCst) {
            say("\ninterrupt: stopping the running points cleanly (re-run the sweep to resume them)");
        }
    });
    if let Err(e) = r {
        say(&format!(
            "warning: cannot handle Ctrl-C ({e}); an interrupt will cut the points' logs short"
        ));
    }
}

/// The combined progress: a bar over all points (finished ones count 1, running
/// ones their fraction) on a terminal, plain lines otherwise.
struct Display {
    bar: Option<ProgressBar>,
    quiet: bool,
    n: usize,
    ended: usize,
    failed: usize,
    last_plain: Option<std::time::Instant>,
}

impl Display {
    fn new(quiet: bool, n: usize) -> Self {
        let bar = (!quiet && std::io::stderr().is_terminal()).then(|| {
            let b = ProgressBar::new(1000 * n as u64);
            b.set_style(
                ProgressStyle::with_template(
                    "{spinner} [{elapsed_precise}] {bar:30} {percent:>3}% {msg} (ETA {eta})",
                )
                .expect("valid template"),
            );
            b
        });
        Display {
            bar,
            quiet,
            n,
            ended: 0,
            failed: 0,
            last_plain: None,
        }
    }

    fn say(&self, line: &str) {
        if self.quiet {
            return;
        }
        match &self.bar {
            Some(b) => b.suspend(|| say(line)),
            None => say(line),
        }
    }

    fn event(&mut self, sweep: &SweepDir, e: PoolEvent) {
        let name = |i: usize| sweep.plan.points[i].name.clone();
        match e {
            PoolEvent::Started(i) => self.say(&format!("started  {}", name(i))),
            // Said even with --quiet: a file was moved.
            PoolEvent::SetAside(i, note) => {
                let line = format!("warning: {}: {note}", name(i));
                match &self.bar {
                    Some(b) => b.suspend(|| say(&line)),
                    None => say(&line),
                }
            }
            PoolEvent::Ended(i, o) => {
                self.ended += 1;
                match &o {
                    PointOutcome::Done => self.say(&format!("done     {}", name(i))),
                    PointOutcome::Skipped(s) => {
                        self.say(&format!("skipped  {} ({})", name(i), s.word()))
                    }
                    PointOutcome::Interrupted => {
                        self.say(&format!("stopped  {} (resumes on the next sweep)", name(i)))
                    }
                    PointOutcome::Failed(why) => {
                        self.failed += 1;
                        self.say(&format!(
                            "FAILED   {}: {why} (see {})",
                            name(i),
                            sweep.output_path(i).display()
                        ))
                    }
                }
            }
            PoolEvent::Tick(running) => {
                let part: f64 = running.iter().map(|r| r.1).sum();
                let msg = format!(
                    "{}/{} points ended, {} running, {} failed",
                    self.ended,
                    self.n,
                    running.len(),
                    self.failed
                );
                if let Some(b) = &self.bar {
                    b.set_position((1000.0 * (self.ended as f64 + part)) as u64);
                    b.set_message(msg);
                } else if !self.quiet
                    && self
                        .last_plain
                        .is_none_or(|t| t.elapsed() >= super::PLAIN_EVERY)
                {
                    say(&format!(
                        "{:5.1}% {msg}",
                        100.0 * (self.ended as f64 + part) / self.n as f64
                    ));
                    self.last_plain = Some(std::time::Instant::now());
                }
            }
        }
    }

    fn finish(&self) {
        if let Some(b) = &self.bar {
            b.finish_and_clear();
        }
    }
}
