//! `carom analyze`: read a log into an [`Analyzer`] and print its [`Report`] as
//! text or JSON. The time span and collision rate, which the analysis needs
//! first, come from a finished log's index, or from a scan of a log cut short; then
//! every message is read in one streaming pass.
//!
//! The JSON object is the [`Report`] (see its field documentation) with two more
//! fields: `file` (the log) and `log_complete` (false for a log cut short).

use std::process::ExitCode;

use carom::analysis::report::{
    AnalysisOptions, Analyzer, Report, RunDescription, CORRELATED_SPACING, DECORRELATION_COLLISIONS,
};
use carom::core::{Boundary, DVec2, Restitution, SimBox, Species};
use carom::io::{
    scan_indexed, scan_observed, Config, LogEnd, LogInfo, LogMessage, LogReader, Snapshot,
    KIND_PAIR,
};

use super::reading::ReadDisplay;
use super::{AnalyzeArgs, CliError, Num};

/// The run's species, box and collision rule: from the configuration stored in the
/// log, or failing that from the first snapshot (then assumed elastic).
fn describe(
    config: &str,
    first: Option<&Snapshot>,
    display: &mut ReadDisplay,
) -> Result<(Vec<Species>, SimBox, Restitution), CliError> {
    match Config::from_json_str(config).and_then(|c| c.to_run_spec()) {
        Ok(spec) => Ok((
            spec.system.species,
            spec.system.sim_box,
            spec.params.restitution,
        )),
        Err(e) => {
            let s = first.ok_or_else(|| {
                CliError::Usage(format!(
                    "the log's configuration cannot be read ({e}) and it has no snapshot"
                ))
            })?;
            display.warn(&format!("warning: the log's configuration cannot be read ({e}); using its first snapshot and assuming elastic collisions"));
            let mut counts = vec![0usize; s.species_radius.len()];
            for &k in &s.species {
                *counts.get_mut(k as usize).ok_or_else(|| {
                    CliError::Usage(format!(
                        "the first snapshot names species {k} but lists {} species",
                        s.species_radius.len()
                    ))
                })? += 1;
            }
            let species = counts
                .iter()
                .zip(s.species_radius.iter().zip(&s.species_mass))
                .map(|(&count, (&radius, &mass))| Species {
                    count,
                    radius,
                    mass,
                })
                .collect();
            let b = |code: u8| {
                if code == 0 {
                    Boundary::Periodic
                } else {
                    Boundary::Walls { restitution: 1.0 }
                }
            };
            Ok((
                species,
                SimBox {
                    size: s.box_size,
                    boundary: [b(s.boundary[0]), b(s.boundary[1])],
                },
                Restitution::Elastic,
            ))
        }
    }
}

/// The pair collision rate ω (pair collisions per disc per unit time) over the
/// log, from its first and last `/thermo` records, or else from its summary
/// (counts since the run's start at `t_start`); `None` if neither tells.
fn pair_rate(info: &LogInfo, n: usize, t_start: f64) -> Option<f64> {
    let from_thermo = info.thermo_counts.and_then(|[(t0, p0, _), (t1, p1, _)]| {
        (t1 > t0 && p1 > p0).then(|| 2.0 * (p1 - p0) as f64 / (n as f64 * (t1 - t0)))
    });
    let from_summary = info.summary.as_ref().and_then(|s| {
        (s.sim_time > t_start && s.pair_collisions > 0)
            .then(|| 2.0 * s.pair_collisions as f64 / (n as f64 * (s.sim_time - t_start)))
    });
    from_thermo
        .or(from_summary)
        .filter(|w| w.is_finite() && *w > 0.0)
}

/// Read the log and compute the report, showing how far reading has got.
/// Returns the report with whether the log is complete.
pub fn read_report(args: &AnalyzeArgs) -> Result<(Report, bool), CliError> {
    let mut display = ReadDisplay::new(args.quiet, &args.file.display().to_string());
    let report = read_report_shown(args, &mut display);
    display.finish();
    report
}

fn read_report_shown(
    args: &AnalyzeArgs,
    display: &mut ReadDisplay,
) -> Result<(Report, bool), CliError> {
    // A finished log's index tells the time span and collision counts at once; a
    // log cut short is scanned. (Either way the pass below reads and checks every
    // message.)
    let info = match scan_indexed(&args.file)? {
        Some(info) => info,
        None => {
            display.pass("scanning");
            scan_observed(&args.file, &mut |p| display.update(p))?
        }
    };
    if let Some(w) = info.end.warning() {
        display.warn(&format!("warning: {w}"));
    }
    let complete = info.end == LogEnd::Complete;
    let (mut t_start, mut t_end) = (f64::INFINITY, f64::NEG_INFINITY);
    for (a, b) in info.time_span.iter().flatten() {
        t_start = t_start.min(*a);
        t_end = t_end.max(*b);
    }
    if t_end.is_nan() || t_start.is_nan() || t_end <= t_start {
        return Err(CliError::Usage(format!(
            "{} holds no data spanning any simulated time",
            args.file.display()
        )));
    }
    let mut reader = LogReader::open(&args.file)?;
    let collisions_logged = info.run.log.collisions && info.channels[0];
    // Every k-th collision (k > 1) gives only an estimate of the sums that the
    // /thermo records hold exactly.
    let totals_from_thermo = !collisions_logged
        || (info.run.log.collision_every > 1 && info.run.log.thermo_interval.is_some());
    // The first snapshot is only needed when the configuration is unreadable.
    let first_snapshot = if Config::from_json_str(&info.run.config).is_err() {
        let mut r = LogReader::open(&args.file)?;
        r.snapshots().find_map(|m| match m {
            Ok(LogMessage::Snapshot(s)) => Some(s),
            _ => None,
        })
    } else {
        None
    };
    let (species, sim_box, restitution) =
        describe(&info.run.config, first_snapshot.as_ref(), display)?;
    let n: usize = species.iter().map(|s| s.count).sum();
    let run = RunDescription {
        pair_rate: pair_rate(&info, n, t_start),
        snapshot_interval: info.run.log.snapshot_interval,
        species,
        sim_box,
        restitution,
        collision_stride: info.run.log.collision_every.max(1),
        totals_from_thermo,
        t_start,
        t_end,
    };
    let opts = AnalysisOptions {
        equilibrate: args.equilibrate,
        every: args.every,
        speed_bins: args.bins as usize,
        ..AnalysisOptions::default()
    };
    if let Some(t) = args.equilibrate {
        if !t.is_finite() || t >= t_end {
            return Err(CliError::Usage(format!(
                "--equilibrate {t}: must be before the end of the log at t = {t_end}"
            )));
        }
    }
    if let Some(dt) = args.every {
        if !(dt.is_finite() && dt >= 0.0) {
            return Err(CliError::Usage(format!(
                "--every {dt}: must be a finite time ≥ 0"
            )));
        }
    }
    let mut a = Analyzer::new(run, opts)?;
    let mut previous_thermo: Option<(f64, f64, f64, u64)> = None;
    let (mut vx, mut vy) = (Vec::new(), Vec::new());
    display.pass("reading");
    let mut shown = 0;
    loop {
        if let Some(p) = reader.progress_since(&mut shown) {
            display.update(p);
        }
        let Some(m) = next(&mut reader)? else { break };
        match m {
            LogMessage::Collisions(b) => {
                for k in 0..b.time.len() {
                    if b.kind[k] == KIND_PAIR {
                        a.pair(b.time[k], b.virial[k], b.energy_lost[k]);
                    } else {
                        a.wall(b.time[k], b.virial[k], b.energy_lost[k]);
                    }
                }
            }
            LogMessage::Snapshot(s) => {
                vx.clear();
                vy.clear();
                vx.extend(s.velocities.iter().map(|v: &DVec2| v.x));
                vy.extend(s.velocities.iter().map(|v: &DVec2| v.y));
                a.snapshot(s.time, &s.species, &vx, &vy)?;
            }
            LogMessage::Thermo(t) => {
                a.thermo(t.time, t.kinetic_energy, Some(t.energy_lost));
                if totals_from_thermo {
                    if let Some((t0, v0, w0, p0)) = previous_thermo {
                        if t.pair_collisions >= p0 {
                            a.increment(
                                t0,
                                t.time,
                                t.virial_sum - v0,
                                t.wall_impulse - w0,
                                t.pair_collisions - p0,
                            );
                        }
                    }
                    previous_thermo =
                        Some((t.time, t.virial_sum, t.wall_impulse, t.pair_collisions));
                }
            }
            LogMessage::Checkpoint(_) => {}
        }
    }
    Ok((a.finish()?, complete))
}

/// The next message; a truncated tail ends the stream (the scan already warned).
fn next(r: &mut LogReader) -> Result<Option<LogMessage>, carom::io::ReadError> {
    r.next_message()
}

/// `carom analyze`.
pub fn analyze(args: AnalyzeArgs) -> Result<ExitCode, CliError> {
    let (report, complete) = read_report(&args)?;
    if let Some(dir) = &args.plot {
        let written = super::plot::write_all(&report, dir)?;
        eprintln!("wrote {} figures to {}", written, dir.display());
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

fn sigmas(x: f64, se: f64) -> String {
    if se > 0.0 {
        format!("{:.1}σ", x / se)
    } else {
        "–".into()
    }
}

/// The human-readable report.
pub fn text(r: &Report, args: &AnalyzeArgs, complete: bool) -> String {
    use std::fmt::Write;
    let mut s = String::new();
    let axis = |p: bool| if p { "periodic" } else { "walls" };
    let _ = writeln!(
        s,
        "{}{}",
        args.file.display(),
        if complete { "" } else { " (truncated)" }
    );
    let _ = writeln!(
        s,
        "  N = {}, η = {:.4}, box {:.4} × {:.4} ({} × {}), {}",
        r.n,
        r.packing_fraction,
        Num(r.box_size[0]),
        Num(r.box_size[1]),
        axis(r.periodic[0]),
        axis(r.periodic[1]),
        if r.elastic { "elastic" } else { "inelastic" }
    );
    let w = &r.window;
    let _ = writeln!(
        s,
        "  log t ∈ [{}, {}], analysed from t = {} ({} of {} snapshots used{})",
        Num(w.t_start),
        Num(w.t_end),
        Num::computed(w.equilibrate),
        w.snapshot_times.len(),
        w.snapshots_seen,
        match w.every {
            Some(e) if w.every_from_budget => format!(
                ", ≥ {:.4} apart so as to keep at most {} velocities in memory ({} discs); \
                 --every to change",
                Num(e),
                w.max_velocities,
                r.n
            ),
            Some(e) if w.every_default => format!(
                ", ≥ {:.4} apart: the default, {} pair collisions per disc; --every to change",
                Num(e),
                DECORRELATION_COLLISIONS
            ),
            Some(e) => format!(", ≥ {} apart", Num(e)),
            None => String::new(),
        }
    );
    let rate = r.collision_rate.per_disc;
    if let Some(c) = w
        .spacing_collisions
        .filter(|&c| c < CORRELATED_SPACING && rate > 0.0)
    {
        let _ = writeln!(
            s,
            "  warning: snapshots used only {c:.2} pair collisions per disc apart: velocities \
             that close are correlated, and the Maxwell–Boltzmann tests below reject too often \
             (use --every {:.4} or more)",
            Num(DECORRELATION_COLLISIONS / rate)
        );
    }
    let t = &r.temperature;
    let _ = writeln!(
        s,
        "temperature  kT = {:.6}   (f = {} = 2N − {}; {})",
        Num(t.kt),
        t.dof,
        t.conserved_momentum_components,
        t.convention
    );
    if r.maxwell_boltzmann.is_empty() && r.maxwell_boltzmann_untested.is_empty() {
        let _ = writeln!(s, "Maxwell–Boltzmann  no snapshots in the window");
    } else {
        let _ = writeln!(
            s,
            "Maxwell–Boltzmann  (kT measured from the same snapshots: χ² loses one dof, KS p is conservative)"
        );
    }
    for m in &r.maxwell_boltzmann {
        let _ = writeln!(
            s,
            "  species {} (m = {}, a = {}): {} speeds{}; χ² = {:.2} / {} dof, p = {:.3e}; KS D = {:.4}, p = {:.3e}; vx KS p = {:.3e}, vy KS p = {:.3e}  → {}",
            m.species,
            Num(m.mass),
            Num(m.radius),
            m.samples,
            thinned(m),
            m.chi_square.statistic,
            m.chi_square.dof,
            m.chi_square.p_value,
            m.ks.statistic,
            m.ks.p_value,
            m.ks_vx.p_value,
            m.ks_vy.p_value,
            if m.passed { "consistent with MB" } else { "NOT Maxwell–Boltzmann" }
        );
    }
    for u in &r.maxwell_boltzmann_untested {
        let _ = writeln!(
            s,
            "  species {}: not tested ({} speeds: {})",
            u.species, u.samples, u.reason
        );
    }
    match &r.pressure {
        Some(p) => {
            let _ = writeln!(
                s,
                "pressure  Z = βPA/N = {:.5} ± {:.5}   βP = {:.6} ± {:.6}   P = {:.6}   (A = {:.4}; {} blocks of {:.4}{})",
                p.z,
                p.z_std_error,
                Num(p.beta_p),
                Num(p.beta_p_std_error),
                Num(p.p),
                Num(p.area),
                p.blocks,
                Num(p.block_time),
                if p.converged { "" } else { "; blocking did not converge: run longer" }
            );
            let _ = writeln!(s, "  estimator: {}", p.estimator);
        }
        None => {
            let _ = writeln!(s, "pressure  not available (no temperature in the log)");
        }
    }
    let c = &r.collision_rate;
    let _ = writeln!(
        s,
        "collision rate  ω = {:.5} ± {:.5} pair collisions per disc per unit time ({} pair, {} wall collisions logged, every {})",
        Num(c.per_disc), Num(c.std_error), c.logged_pair_collisions, c.logged_wall_collisions, c.collision_stride
    );
    if let Some(e) = &r.enskog {
        let _ = writeln!(
            s,
            "Enskog check  Z − 1 = {:.5}, (√π/4) ω τ0 = {:.5} ± {:.5}; difference {:.5} ± {:.5} ({})",
            e.z_minus_1,
            e.rate_term,
            e.rate_term_std_error,
            e.difference,
            e.difference_std_error,
            sigmas(e.difference, e.difference_std_error)
        );
    }
    if let Some(i) = &r.inelastic {
        if let Some(e) = &i.energy {
            let _ = writeln!(
                s,
                "energy budget  E0 = {:.6}, E = {:.6}, dissipated = {:.6} ({}), E0 − dissipated − E = {:.3e} (relative {:.3e})",
                Num(e.initial), Num(e.final_), Num(e.dissipated), e.dissipated_source, e.residual, e.relative_residual
            );
        }
        if let Some(h) = &i.haff {
            let _ = writeln!(
                s,
                "Haff's law  t0 = {:.4}, a2 = {:.4}; final kT measured {:.5}, predicted {:.5} (ratio {:.4})",
                Num(h.t0), h.a2, Num(h.kt_final_measured), Num(h.kt_final_predicted), h.ratio
            );
        }
        let series = &r.temperature.series;
        let step = (series.len() / 10).max(1);
        let _ = writeln!(s, "temperature vs time:");
        for p in series.iter().step_by(step) {
            let _ = writeln!(s, "  t = {:10.4}  kT = {:.6}", p[0], p[1]);
        }
    }
    s
}

/// How a species' snapshots were thinned, for the text report ("" when all of the
/// window's snapshots were used).
fn thinned(m: &carom::analysis::report::SpeciesMb) -> String {
    match m.snapshot_correlation {
        Some(rho) if m.snapshot_step > 1 => format!(
            " from {} (its velocities correlate {rho:.3} from one snapshot to the next: {})",
            if m.snapshots == 1 {
                "1 snapshot".to_owned()
            } else {
                format!("{} snapshots", m.snapshots)
            },
            if m.snapshots == 1 {
                "only the first used".to_owned()
            } else {
                format!("one in {} used", m.snapshot_step)
            }
        ),
        _ => String::new(),
    }
}
