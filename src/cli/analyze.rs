//! `carom analyze`: analyse a log (`carom::analysis::analyze_log`, with a progress
//! display) and print its [`Report`] as text or JSON.
//!
//! The JSON object is the [`Report`] (see its field documentation) with two more
//! fields: `file` (the log) and `log_complete` (false for a log cut short).

use std::process::ExitCode;

use carom::analysis::{analyze_log, AnalysisOptions, ReadObserver, Report};
use carom::io::ReadProgress;

#[path = "analyze_dynamics.rs"]
mod dynamics;

use super::reading::ReadDisplay;
use super::{AnalyzeArgs, CliError, Num};

#[path = "analyze_transport.rs"]
mod transport;

#[path = "analyze_compression.rs"]
mod compression;

#[path = "analyze_sections.rs"]
mod sections;

#[path = "analyze_inelastic.rs"]
mod inelastic;

use super::report_text::{self, sigmas, Text};
use sections::{pair_correlation_text, pressure_text, run_text, structure_text, velocity_text};

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
    let report = analyze_log(&args.file, opts, &mut display);
    display.finish();
    Ok(report?)
}

/// `carom analyze`.
pub fn analyze(args: AnalyzeArgs) -> Result<ExitCode, CliError> {
    let (report, complete) = read_report(&args)?;
    if let Some(dir) = &args.plot {
        let written = super::plot::write_all(&report, dir)?;
        eprintln!("wrote {} figures to {}", written.figures, dir.display());
        for (name, why) in &written.skipped {
            eprintln!("skipped {name}: {why}");
        }
    }
    if args.json {
        let mut v = serde_json::to_value(&report).expect("a Report serialises");
        if let Some(o) = v.as_object_mut() {
            o.insert(
                "file".into(),
                serde_json::Value::String(args.file.display().to_string()),
            );
            o.insert("log_complete".into(), serde_json::Value::Bool(complete));
        }
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
        compression::compression_text(c, t.raw());
    }
    velocity_text(r, &mut t);
    pressure_text(r, &mut t);
    pair_correlation_text(r, &mut t);
    structure_text(r, &mut t);
    let mut s = t.finish();
    s.push('\n');
    use std::fmt::Write;
    dynamics::dynamics_text(r, &mut s);
    if let Some(t) = &r.transport {
        transport::transport_text(t, &mut s);
    }
    if let Some(g) = &r.gravity {
        gravity_text(g, &mut s);
    }
    if let Some(t) = &r.thermostat {
        thermostat_text(t, &mut s);
    }
    if let Some(f) = &r.floor {
        let gamma = f
            .shaking_parameter
            .map(|g| format!(", Γ = Aω²/g = {g:.3}"))
            .unwrap_or_default();
        let _ = writeln!(
            s,
            "floor       vibrating, A = {}, f = {}{gamma}: from t = {} to {}, power in {:.6} (floor work {:.6}), dissipated {:.6} (energy lost {:.6}); steady when equal",
            Num(f.amplitude),
            Num(f.frequency),
            Num(f.window[0]),
            Num(f.window[1]),
            f.power_in,
            f.floor_work,
            f.power_out,
            f.energy_lost
        );
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

/// The thermostat's target against the measured temperature (physics.md §16);
/// it replaces the energy budget, which a thermostat does not close.
fn thermostat_text(t: &carom::analysis::ThermostatReport, s: &mut String) {
    use std::fmt::Write;
    let opt = |x: Option<f64>| x.map_or("–".to_owned(), |v| format!("{:.5}", Num(v)));
    match (t.target_kt, t.granular_temperature) {
        (Some(target), _) => {
            let _ = writeln!(
                s,
                "thermostat  Andersen, rate {} per disc: kT = 2K/(2N) = {:.5} against the target {:.5} (relative difference {:+.2e}); energy is not conserved",
                opt(t.rate), Num(t.kt_all_components), Num(target), t.relative_difference.unwrap_or(f64::NAN)
            );
        }
        (None, Some(tg)) => {
            let _ = writeln!(
                s,
                "thermostat  driven, ξ² = {}, kicks every {}: granular T = K/N = {:.5}; steady T from the energy balance {} (Enskog–Henderson rate), {} (measured rate); energy is not conserved",
                opt(t.xi2), opt(t.interval), Num(tg), opt(t.predicted_temperature), opt(t.predicted_temperature_from_rate)
            );
        }
        _ => {}
    }
}

/// The lines of a run in a field (physics.md §15): potential and total energy, and
/// the barometric fit per species.
fn gravity_text(g: &carom::analysis::GravityReport, s: &mut String) {
    use std::fmt::Write;
    let total = match (g.total_energy_first, g.total_energy_last) {
        (Some(a), Some(b)) => format!(
            "; K + U = {:.6} at the first snapshot, {:.6} at the last (relative change {:.3e})",
            Num(a),
            Num(b),
            (b - a) / a.abs()
        ),
        _ => String::new(),
    };
    let _ = writeln!(
        s,
        "gravity  g = {}, potential energy U = Σ m g y = {:.6} (mean of {} snapshots){total}",
        g.g,
        Num(g.potential_energy),
        g.snapshots
    );
    for b in &g.barometric {
        let se = b
            .beta_std_error
            .map_or("?".to_owned(), |e| format!("{e:.5}"));
        let apart = |known: f64| {
            b.beta_std_error.map_or(String::new(), |e| {
                format!(" ({} apart)", sigmas(b.beta - known, e))
            })
        };
        let _ = writeln!(
            s,
            "barometric law  species {}: fitted m g/kT = {:.5} ± {se} (15.8)",
            b.species,
            Num(b.beta)
        );
        if let Some(why) = b.not_applicable {
            let _ = writeln!(s, "  no known value: {why}");
        } else {
            let _ = writeln!(
                s,
                "  ideal gas m g/kT = {:.5}{} (dilute law)",
                Num(b.beta_expected),
                apart(b.beta_expected)
            );
            if let Some(h) = b.beta_hydrostatic {
                let _ = writeln!(s, "  hydrostatic (15.7) = {:.5}{} (EOS)", Num(h), apart(h));
            }
        }
        let _ = writeln!(
            s,
            "  n(a) = {:.5} (the fitted law at the floor)",
            Num(b.floor_density)
        );
    }
}
