//! The `carom` command line: `run`, `resume`, `analyze`, `info`, `repair`,
//! `render`, `export`, `sweep` and `collect`.
//!
//! Exit status: 0 on success; 1 when a run or a read fails; 2 for a bad command
//! line or configuration (the message names the field); 130 when a run was
//! interrupted with Ctrl-C, SIGTERM or SIGHUP (its log is finished and readable).

mod analyze;
mod collect;
mod export;
mod info;
mod live;
mod output;
mod plot;
mod reading;
mod render;
mod repair;
mod report_text;
mod run;
mod run_display;
mod sweep;

use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Duration;

use carom_config::ConfigError;
use clap::{Args, Parser, Subcommand};
use thiserror::Error;

/// Exact event-driven molecular dynamics of hard discs.
#[derive(Debug, Parser)]
#[command(name = "carom", version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Run a simulation and write its MCAP log.
    ///
    /// Without CONFIG runs the built-in default: 10⁴ discs at packing fraction 0.5
    /// for 50 time units (a few seconds), logged to ./carom.mcap.
    Run(RunArgs),
    /// Continue a log from its last checkpoint (a killed run, or a finished one with
    /// a later stop).
    Resume(ResumeArgs),
    /// Analyse a log: temperature, Maxwell–Boltzmann tests, pressure and Z with
    /// standard errors, collision rate and the Enskog check, cooling.
    Analyze(AnalyzeArgs),
    /// Describe a log: configuration, channels, message counts, time span, and
    /// whether it is complete (from a finished log's index; --verify reads every
    /// message).
    Info(InfoArgs),
    /// Write a complete, indexed log from one cut short (a killed run) holding
    /// every message up to the cut, without simulating again; the input is left
    /// as it is.
    Repair(RepairArgs),
    /// Draw a snapshot of a log as PNG or SVG (discs to scale, coloured by species
    /// or speed, the box drawn), or a range of snapshots as an animated GIF.
    Render(render::RenderArgs),
    /// Export a log's snapshots to HOOMD's GSD or extended XYZ (OVITO, freud,
    /// HOOMD-blue), one frame per snapshot.
    Export(export::ExportArgs),
    /// Run many points from one plan (a base configuration, the paths to vary,
    /// replicas): locally, one per core, or as a Slurm job array; `carom sweep
    /// status DIR` shows where each point stands.
    Sweep(sweep::SweepArgs),
    /// Analyse every finished log of a sweep and write one table (replicas
    /// combined), and for a sweep over packing fraction a figure of Z(η).
    Collect(collect::CollectArgs),
}

/// Arguments of `carom run`.
#[derive(Debug, Args)]
pub struct RunArgs {
    /// JSON configuration (see data/config.schema.json); omitted: the built-in
    /// default.
    pub config: Option<PathBuf>,
    /// Log file to write; default: CONFIG's name with .mcap in the current
    /// directory, or carom.mcap.
    #[arg(short, long, value_name = "FILE")]
    pub out: Option<PathBuf>,
    /// Override a configuration field by its dotted path, e.g.
    /// --set species.0.count=500 --set collision.coefficient=0.9 (repeatable;
    /// the value is JSON if it parses, else a string).
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub set: Vec<String>,
    /// Overwrite the log file if it exists.
    #[arg(short, long)]
    pub force: bool,
    /// Instead of a new run, continue this log (same as `carom resume FILE`).
    #[arg(long, value_name = "FILE", conflicts_with_all = ["config", "set", "dry_run"])]
    pub resume: Option<PathBuf>,
    /// Print the resolved configuration and exit without running.
    #[arg(long)]
    pub dry_run: bool,
    /// No progress display.
    #[arg(short, long)]
    pub quiet: bool,
    /// Run on when the log, projected from its growth so far, would need more
    /// than 10 times the room on its disk (by default the run then stops at once,
    /// with a finished log); it still stops when the disk is nearly full.
    #[arg(long)]
    pub ignore_disk_estimate: bool,
    #[command(flatten)]
    pub live: live::LiveArgs,
}

/// Arguments of `carom resume`.
#[derive(Debug, Args)]
pub struct ResumeArgs {
    /// The log to continue.
    pub file: PathBuf,
    /// Where to write the continued log; default: replace FILE (safely: the new log
    /// is written beside it and renamed over it when finished).
    #[arg(short, long, value_name = "FILE")]
    pub out: Option<PathBuf>,
    /// Run until this simulated time instead of the log's own stop.
    #[arg(
        long,
        value_name = "T",
        conflicts_with = "collisions",
        allow_negative_numbers = true
    )]
    pub until: Option<f64>,
    /// Run until this many collisions in total instead of the log's own stop.
    #[arg(long, value_name = "N", value_parser = parse_count)]
    pub collisions: Option<u64>,
    /// Overwrite the --out file if it exists (continuing FILE in place needs no
    /// --force).
    #[arg(short, long)]
    pub force: bool,
    /// No progress display.
    #[arg(short, long)]
    pub quiet: bool,
    /// As for `carom run`: run on when the log would need more than 10 times the
    /// room on its disk.
    #[arg(long)]
    pub ignore_disk_estimate: bool,
    #[command(flatten)]
    pub live: live::LiveArgs,
}

/// Arguments of `carom analyze`.
#[derive(Debug, Args)]
pub struct AnalyzeArgs {
    /// The log to analyse.
    pub file: PathBuf,
    /// Print one JSON object instead of text: the report's fields (what the text
    /// shows, in the run's units) with `file` and `log_complete`.
    #[arg(long)]
    pub json: bool,
    /// Write figures (PNG and SVG) into this directory.
    #[arg(long, value_name = "DIR")]
    pub plot: Option<PathBuf>,
    /// Ignore everything before this simulated time; default: the first 10 % of
    /// the log.
    #[arg(long, value_name = "T", allow_negative_numbers = true)]
    pub equilibrate: Option<f64>,
    /// Use snapshots at least this far apart (simulated time) for the velocity
    /// distribution; default: 5 pair collisions per disc, from the log's collision
    /// rate (every snapshot after --equilibrate if the log has no collision counts),
    /// or for an inelastic run counted between the snapshots.
    /// Closer snapshots hold correlated velocities: the tests then reject too often.
    #[arg(long, value_name = "DT", allow_negative_numbers = true)]
    pub every: Option<f64>,
    /// Bins of each species' speed histogram over [0, 4.5 √(kT/m)) and of its
    /// v_x, v_y histograms; for the χ² test, bins expecting fewer than 5 counts are
    /// merged. At least 4: the χ² test fits kT and needs a degree of freedom left.
    #[arg(long, value_name = "N", default_value_t = 40,
          value_parser = clap::value_parser!(u32).range(4..))]
    pub bins: u32,
    /// Skip the structure (g(r), ψ6, g6, S(k)): a quicker pass over the
    /// collisions, velocities, dynamics and transport.
    #[arg(long)]
    pub no_structure: bool,
    /// No progress display.
    #[arg(short, long)]
    pub quiet: bool,
}

/// Arguments of `carom info`.
#[derive(Debug, Args)]
pub struct InfoArgs {
    /// The log to describe.
    pub file: PathBuf,
    /// Print one JSON object instead of text.
    #[arg(long)]
    pub json: bool,
    /// Read and check every message, also of a finished log (whose index alone
    /// otherwise tells what it holds).
    #[arg(long)]
    pub verify: bool,
    /// No progress display.
    #[arg(short, long)]
    pub quiet: bool,
}

/// A count given on the command line, in the forms the configuration accepts: a
/// non-negative integer, also written as an integral number such as `1e9` (up to
/// 2⁵³, where such numbers stop being exact).
fn parse_count(text: &str) -> Result<u64, String> {
    if let Ok(n) = text.parse::<u64>() {
        return Ok(n);
    }
    match text.parse::<f64>() {
        Ok(x) if x.fract() == 0.0 && (0.0..=9_007_199_254_740_992.0).contains(&x) => Ok(x as u64),
        _ => Err(
            "not a whole number ≥ 0 (allowed: an integer such as 5000000, \
                  or written with an exponent such as 5e6)"
                .to_owned(),
        ),
    }
}

/// Arguments of `carom repair`.
#[derive(Debug, Args)]
pub struct RepairArgs {
    /// The log to repair (it is only read).
    pub file: PathBuf,
    /// Where to write the repaired log; default: FILE.repaired.mcap beside FILE
    /// (for FILE.mcap). Must not be FILE.
    #[arg(short, long, value_name = "FILE")]
    pub out: Option<PathBuf>,
    /// Overwrite the --out file if it exists.
    #[arg(short, long)]
    pub force: bool,
}

/// Interval of the plain progress lines written when standard error is not a
/// terminal.
pub(crate) const PLAIN_EVERY: Duration = Duration::from_secs(5);

/// Why a command failed.
#[derive(Debug, Error)]
pub enum CliError {
    /// The configuration or a `--set` is wrong (exit status 2).
    #[error("configuration: {0}")]
    Config(#[from] ConfigError),
    /// A command-line value is wrong (exit status 2).
    #[error("{0}")]
    Usage(String),
    /// A run failed.
    #[error("{0}")]
    Run(#[from] carom_run::RunError),
    /// A log could not be read.
    #[error("{0}")]
    Read(#[from] carom_log::ReadError),
    /// A log could not be analysed.
    #[error("{0}")]
    Analysis(carom_analysis::AnalysisError),
    /// Writing output failed.
    #[error("{context}: {source}")]
    Io {
        /// What was being written.
        context: String,
        /// The operating system's error.
        source: std::io::Error,
    },
    /// Drawing a figure failed.
    #[error("plot: {0}")]
    Plot(String),
    /// Pictures or exported frames could not be made (no snapshots, a write).
    #[error("{0}")]
    Frames(String),
    /// A sweep could not be laid out, run or collected.
    #[error("sweep: {0}")]
    Sweep(#[from] carom_run::sweep::SweepError),
}

impl From<crate::frames::FrameError> for CliError {
    fn from(e: crate::frames::FrameError) -> Self {
        use crate::frames::FrameError;
        match e {
            FrameError::Read(e) => CliError::Read(e),
            FrameError::Unusable(why) => CliError::Usage(why),
            e => CliError::Frames(e.to_string()),
        }
    }
}

impl From<carom_analysis::AnalysisError> for CliError {
    fn from(e: carom_analysis::AnalysisError) -> Self {
        use carom_analysis::AnalysisError;
        match e {
            AnalysisError::Read(e) => CliError::Read(e),
            AnalysisError::Unusable(why) => CliError::Usage(why),
            e => CliError::Analysis(e),
        }
    }
}

impl CliError {
    fn exit_code(&self) -> u8 {
        match self {
            CliError::Config(_) | CliError::Usage(_) => 2,
            CliError::Sweep(
                carom_run::sweep::SweepError::Plan { .. }
                | carom_run::sweep::SweepError::Point { .. },
            ) => 2,
            // Interrupted before the log existed: the shell's code for SIGINT, as
            // for a run interrupted later (with its log finished).
            CliError::Run(carom_run::RunError::InterruptedPlacing { .. }) => 130,
            _ => 1,
        }
    }
}

pub(crate) use output::emit;

/// A number for people to read: as Rust prints it (the shortest text that reads
/// back exactly) between 10⁻⁴ and 10¹⁵ in magnitude, in scientific notation
/// outside (so t = 5.55e-142 rather than 141 zeros). A precision (`{:.4}`) counts
/// digits after the point in either notation.
pub(crate) struct Num(pub f64);

impl Num {
    /// `x` rounded to 12 significant digits, for a time the program computed rather
    /// than read: 0.1 × 127 prints as 12.7, not 12.700000000000001. Times read from
    /// a log or the command line are printed whole instead.
    pub(crate) fn computed(x: f64) -> Num {
        Num(format!("{x:.11e}").parse().unwrap_or(x))
    }
}

impl std::fmt::Display for Num {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let (x, a) = (self.0, self.0.abs());
        let plain = a == 0.0 || !a.is_finite() || (1e-4..1e15).contains(&a);
        match (plain, f.precision()) {
            (true, None) => write!(f, "{x}"),
            (true, Some(p)) => write!(f, "{x:.p$}"),
            (false, None) => write!(f, "{x:e}"),
            (false, Some(p)) => write!(f, "{x:.p$e}"),
        }
    }
}

/// Ignore SIGXFSZ: past a file size limit (`ulimit -f`) a write then fails with
/// EFBIG, which carom reports naming the file and the system's reason, instead of
/// the signal killing the process without a word (exit status 153).
fn ignore_file_size_signal() {
    #[cfg(unix)]
    // SAFETY: `signal` with SIG_IGN installs no handler code, only the kernel's
    // disposition "ignore"; it is called first thing in `main`, before any thread
    // is started, and nothing in carom relies on SIGXFSZ's default action.
    unsafe {
        libc::signal(libc::SIGXFSZ, libc::SIG_IGN);
    }
}

/// Parse the command line, run the command, report errors; the process's exit
/// status.
pub fn main() -> ExitCode {
    ignore_file_size_signal();
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Run(a) => run::run(a),
        Command::Resume(a) => run::resume(a),
        Command::Analyze(a) => analyze::analyze(a),
        Command::Info(a) => info::info(a),
        Command::Repair(a) => repair::repair(a),
        Command::Render(a) => render::render(a),
        Command::Export(a) => export::export(a),
        Command::Sweep(a) => sweep::sweep(a),
        Command::Collect(a) => collect::collect(a),
    };
    match result {
        Ok(code) => code,
        Err(e) => {
            output::say!("error: {}", output::compact_numbers(&e.to_string()));
            ExitCode::from(e.exit_code())
        }
    }
}

#[cfg(test)]
mod tests {
    use super::Num;

    #[test]
    fn numbers_print_plainly_in_range_and_computed_times_without_rounding_noise() {
        assert_eq!(Num(12.5).to_string(), "12.5");
        assert_eq!(Num(5.55e-142).to_string(), "5.55e-142");
        assert_eq!(format!("{:.2}", Num(2.0 / 3.0)), "0.67");
        let noisy = 0.1 * 127.0;
        assert_eq!(Num(noisy).to_string(), "12.700000000000001");
        assert_eq!(Num::computed(noisy).to_string(), "12.7");
        // Twelve significant digits survive; values already short stay as they are.
        assert_eq!(Num::computed(12.3456789012).to_string(), "12.3456789012");
        assert_eq!(Num::computed(0.0).to_string(), "0");
        assert_eq!(Num::computed(1e300).to_string(), "1e300");
    }

    #[test]
    fn counts_are_read_as_the_configuration_reads_them() {
        use super::parse_count;
        assert_eq!(parse_count("1000"), Ok(1000));
        assert_eq!(parse_count("1e3"), Ok(1000));
        assert_eq!(parse_count("2.5E6"), Ok(2_500_000));
        assert_eq!(parse_count("18446744073709551615"), Ok(u64::MAX));
        for bad in ["-1", "1.5", "1e300", "NaN", "inf", "ten", ""] {
            assert!(parse_count(bad).is_err(), "{bad}");
        }
    }
}
