//! `carom collect DIR`: analyse every finished point of a sweep (in parallel) and
//! print one table, a row per grid point with its replicas combined (mean ± the
//! standard error from their spread), as text, JSON or CSV; `--plot` draws Z(η)
//! over the published equation of state when the sweep varies the packing
//! fraction. A point whose log is not its own run, cannot be read or fails to
//! analyse is named and left out, and the command then exits with status 1.

use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::atomic::{AtomicUsize, Ordering};

use carom_analysis::AnalysisOptions;
use carom_run::sweep::{
    collect as collect_sweep, cores, jobs_at_once, CollectOptions, Collected, SweepDir,
};
use clap::Args;

use super::sweep::say;
use super::CliError;

/// Arguments of `carom collect`.
#[derive(Debug, Args)]
pub struct CollectArgs {
    /// The sweep's directory (from `carom sweep PLAN --out DIR`).
    pub dir: PathBuf,
    /// Print one JSON object: the grid points with each quantity's mean,
    /// standard error, spread and the runs' own errors, and every replica's values.
    #[arg(long, conflicts_with = "csv")]
    pub json: bool,
    /// Print CSV: the varied paths, the number of replicas, and for each quantity
    /// its mean, standard error, spread and the runs' own errors combined.
    #[arg(long)]
    pub csv: bool,
    /// Write figures (PNG and SVG) into this directory: Z against the packing
    /// fraction with the reference equation of state, when the sweep varies it.
    #[arg(long, value_name = "DIR")]
    pub plot: Option<PathBuf>,
    /// Logs analysed at once (default: one per core; never more than the cores).
    #[arg(short, long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..))]
    pub jobs: Option<u32>,
    /// Ignore everything before this simulated time in every log; default: the
    /// first 10 % of each.
    #[arg(long, value_name = "T")]
    pub equilibrate: Option<f64>,
    /// Skip the structure (g(r), ψ6, S(k)): quicker.
    #[arg(long)]
    pub no_structure: bool,
    /// No progress display.
    #[arg(short, long)]
    pub quiet: bool,
}

/// `carom collect`.
pub fn collect(args: CollectArgs) -> Result<ExitCode, CliError> {
    let sweep = SweepDir::open(&args.dir)?;
    let (jobs, capped) = jobs_at_once(args.jobs, cores());
    if let Some(note) = capped {
        say(&format!("note: {note}"));
    }
    let opts = CollectOptions {
        jobs,
        analysis: AnalysisOptions {
            equilibrate: args.equilibrate,
            structure: !args.no_structure,
            ..AnalysisOptions::default()
        },
    };
    let n = sweep.plan.points.len();
    let seen = AtomicUsize::new(0);
    let quiet = args.quiet;
    let c = collect_sweep(&sweep, &opts, &|name| {
        let k = seen.fetch_add(1, Ordering::SeqCst) + 1;
        if !quiet {
            say(&format!("[{k}/{n}] {name}"));
        }
    })?;
    for (name, why) in c.missing.iter().chain(&c.rejected) {
        say(&format!("left out {name}: {why}"));
    }
    if let Some(dir) = &args.plot {
        let k = super::plot::write_sweep(&c, dir)?;
        say(&format!("wrote {k} figures to {}", dir.display()));
    }
    let text = if args.json {
        serde_json::to_string_pretty(&c).expect("serialises") + "\n"
    } else if args.csv {
        csv(&c)
    } else {
        table(&c)
    };
    super::emit(&text)?;
    Ok(if c.points.is_empty() {
        say(&format!(
            "no finished point to collect in {}",
            args.dir.display()
        ));
        ExitCode::from(1)
    } else if !c.rejected.is_empty() {
        say(&format!(
            "{} finished point{} left out (above): their logs are not theirs, cannot be \
             read, or failed to analyse",
            c.rejected.len(),
            if c.rejected.len() == 1 { "" } else { "s" }
        ));
        ExitCode::from(1)
    } else {
        ExitCode::SUCCESS
    })
}

/// The quantities at least one grid point has, in [`carom_run::sweep::QUANTITIES`]'s order.
fn present(c: &Collected) -> Vec<&'static str> {
    carom_run::sweep::QUANTITIES
        .iter()
        .map(|q| q.0)
        .filter(|q| c.points.iter().any(|p| p.results.contains_key(*q)))
        .collect()
}

fn value_text(v: &serde_json::Value) -> String {
    match v {
        serde_json::Value::String(s) => s.clone(),
        other => other.to_string(),
    }
}

/// The four CSV columns of each quantity, as (suffix, value): the mean over
/// replicas, its standard error, the replicas' spread and the runs' own errors
/// combined. The header and every row are built from this one list, so they
/// cannot disagree in width.
const CSV_COLUMNS: [(&str, CsvCell); 4] = [
    ("", |r| Some(r.value)),
    ("_std_error", |r| r.std_error),
    ("_spread", |r| r.spread),
    ("_run_std_error", |r| r.run_std_error),
];

/// How a CSV cell reads its number from a quantity's combined result.
type CsvCell = fn(&carom_run::sweep::Combined) -> Option<f64>;

/// One CSV field (RFC 4180): quoted when it holds a comma, a quote or a line break.
fn csv_field(x: &str) -> String {
    if x.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", x.replace('"', "\"\""))
    } else {
        x.to_string()
    }
}

/// CSV: axes, replicas, then value, std_error, spread and the runs' own
/// combined error per quantity; an empty field where a point lacks a value.
fn csv(c: &Collected) -> String {
    let qs = present(c);
    let mut head: Vec<String> = c.axes.clone();
    head.push("replicas".into());
    for q in &qs {
        head.extend(CSV_COLUMNS.iter().map(|(suffix, _)| format!("{q}{suffix}")));
    }
    let line = |cells: Vec<String>| {
        let cells: Vec<String> = cells.iter().map(|x| csv_field(x)).collect();
        cells.join(",") + "\n"
    };
    let mut s = line(head);
    for p in &c.points {
        let mut row: Vec<String> = c.axes.iter().map(|a| value_text(&p.values[a])).collect();
        row.push(p.runs.len().to_string());
        for q in &qs {
            let r = p.results.get(*q);
            row.extend(
                CSV_COLUMNS
                    .iter()
                    .map(|(_, get)| r.and_then(get).map(|x| x.to_string()).unwrap_or_default()),
            );
        }
        s += &line(row);
    }
    s
}

/// The table for people: value ± standard error, aligned.
fn table(c: &Collected) -> String {
    let qs = present(c);
    let mut rows: Vec<Vec<String>> = Vec::new();
    let mut head: Vec<String> = c.axes.clone();
    head.push("runs".into());
    head.extend(qs.iter().map(|q| q.to_string()));
    rows.push(head);
    for p in &c.points {
        let mut row: Vec<String> = c.axes.iter().map(|a| value_text(&p.values[a])).collect();
        row.push(p.runs.len().to_string());
        for q in &qs {
            row.push(match p.results.get(*q) {
                Some(r) => match r.std_error {
                    Some(e) if e > 0.0 => format!("{:.5} ± {:.5}", r.value, e),
                    _ => format!("{:.5}", r.value),
                },
                None => "–".into(),
            });
        }
        rows.push(row);
    }
    let widths: Vec<usize> = (0..rows[0].len())
        .map(|k| rows.iter().map(|r| r[k].chars().count()).max().unwrap_or(0))
        .collect();
    let mut s = String::new();
    for r in &rows {
        let cells: Vec<String> = r
            .iter()
            .zip(&widths)
            .map(|(x, w)| format!("{x:<w$}"))
            .collect();
        s += cells.join("  ").trim_end();
        s += "\n";
    }
    s += "(± the standard error of the mean over replicas, from their spread; a single run's own error otherwise)\n";
    s
}
