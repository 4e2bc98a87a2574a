//! `carom analyze`: analyse a log (`carom_analysis::analyze_log_with`, with a progress
//! display) and print its [`Report`] as text or JSON.
//!
//! The JSON object is the [`Report`] (see its field documentation) with two more
//! fields: `file` (the log) and `log_complete` (false for a log cut short).

use std::process::ExitCode;

use carom_analysis::{analyze_log_with, AnalysisOptions, ReadObserver, Report};
use carom_config::derive_facts_for_old_log;
use carom_log::ReadProgress;

#[path = "analyze_dynamics.rs"]
mod dynamics;

use super::output::say;
use super::reading::ReadDisplay;
use super::{AnalyzeArgs, CliError, Num};

#[path = "analyze_transport.rs"]
mod transport;

#[path = "analyze_driven.rs"]
mod driven;

#[path = "analyze_sections.rs"]
mod sections;

#[path = "analyze_pressure.rs"]
mod pressure;

#[path = "analyze_structure.rs"]
mod structure;

#[path = "analyze_inelastic.rs"]
mod inelastic;

use super::report_text::{self, sigmas, Text};
use pressure::pressure_text;
use sections::{run_text, velocity_text};
use structure::{pair_correlation_text, structure_text};

/// Whether the run cools freely: inelastic, with nothing putting energy in.
fn cooling(r: &Report) -> bool {
    !r.elastic && r.thermostat.is_none() && r.floor.is_none()
}

/// The "drift" line of a drifting observable: both halves with their errors, how
/// many standard errors apart, then `tail`.
fn drift_line(d: &carom_analysis::DriftReport, tail: &str) -> String {
    format!(
        "first half {}, second half {} ({:.1} SE apart){tail}",
        report_text::pm(d.first_half, d.first_half_std_error),
        report_text::pm(d.second_half, d.second_half_std_error),
        d.difference_std_errors
    )
}

impl ReadObserver for ReadDisplay {
    fn pass(&mut self, what: &'static str) {
        ReadDisplay::pass(self, what);
    }
    fn progress(&mut self, p: ReadProgress) {
        self.update(p);
    }
    fn warn(&mut self, line: &str) {
        ReadDisplay::warn(self, line);
    }
}

/// Read the log and compute the report, showing how far reading has got.
/// Returns the report with whether the log is complete.
pub fn read_report(args: &AnalyzeArgs) -> Result<(Report, bool), CliError> {
    let mut display = ReadDisplay::new(args.quiet, &args.file.display().to_string());
    let opts = AnalysisOptions {
        equilibrate: args.equilibrate,
        every: args.every,
        speed_bins: args.bins as usize,
        structure: !args.no_structure,
        ..AnalysisOptions::default()
    };
    // An old log's facts from its configuration (carom-config).
    let report = analyze_log_with(&args.file, opts, &derive_facts_for_old_log, &mut display);
    display.finish();
    Ok(report?)
}

/// `carom analyze`.
pub fn analyze(args: AnalyzeArgs) -> Result<ExitCode, CliError> {
    let (report, complete) = read_report(&args)?;
    if let Some(dir) = &args.plot {
        let written = super::plot::write_all(&report, dir)?;
        say!("wrote {} figures to {}", written.figures, dir.display());
        for (name, why) in &written.skipped {
            say!("skipped {name}: {why}");
        }
    }
    if args.json {
        let v = report.to_json(&args.file.display().to_string(), complete);
        super::emit(&format!("{v}\n"))?;
    } else {
        super::emit(&text(&report, &args, complete))?;
    }
    Ok(ExitCode::SUCCESS)
}

/// The human-readable report ([`report_text`]'s layout: sections, one quantity
/// per line, at most 100 columns).
pub fn text(r: &Report, args: &AnalyzeArgs, complete: bool) -> String {
    let mut t = Text::default();
    run_text(r, args, complete, &mut t);
    if let Some(c) = &r.compression {
        driven::compression_text(c, &mut t);
    }
    velocity_text(r, &mut t);
    pressure_text(r, &mut t);
    pair_correlation_text(r, &mut t);
    structure_text(r, &mut t);
    if let Some(g) = &r.gravity {
        driven::gravity_text(g, &mut t);
    }
    if let Some(th) = &r.thermostat {
        driven::thermostat_text(th, &mut t);
    }
    if let Some(f) = &r.floor {
        driven::floor_text(f, &mut t);
    }
    let mut s = t.finish();
    s.push('\n');
    let before = s.len();
    dynamics::dynamics_text(r, &mut s);
    if let Some(t) = &r.transport {
        if s.len() > before {
            s.push('\n');
        }
        transport::transport_text(t, &mut s);
    }
    let mut i = Text::default();
    inelastic::inelastic_text(r, &mut i);
    let i = i.finish();
    if !i.is_empty() {
        s.push('\n');
        s += &i;
    }
    if !r.not_computed.is_empty() {
        let mut t = Text::default();
        t.section("not computed (the reason for each)");
        for n in &r.not_computed {
            t.item(n.quantity, &n.why);
        }
        s.push('\n');
        s += &t.finish();
    }
    report_text::fit(&s)
}
