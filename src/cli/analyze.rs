//! `carom analyze`: analyse a log (`carom::analysis::analyze_log`, with a progress
//! display) and print its [`Report`] as text or JSON.
//!
//! The JSON object is the [`Report`] (see its field documentation) with two more
//! fields: `file` (the log) and `log_complete` (false for a log cut short).

use std::process::ExitCode;

use carom::analysis::{
    analyze_log, AnalysisOptions, ReadObserver, Report, CONTACT_FIT_SIGMA, CORRELATED_SPACING,
    DECORRELATION_COLLISIONS,
};
use carom::io::ReadProgress;

#[path = "analyze_dynamics.rs"]
mod dynamics;

use super::reading::ReadDisplay;
use super::{AnalyzeArgs, CliError, Num};

#[path = "analyze_transport.rs"]
mod transport;

#[path = "analyze_compression.rs"]
mod compression;

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
    if let Some(c) = &r.compression {
        compression::compression_text(c, &mut s);
    }
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
            "Maxwell–Boltzmann  (kT measured from the same snapshots: χ² loses one dof, KS p is conservative; \
             verdict: Bonferroni over the {} tests made (speed χ², speed KS, vx KS, vy KS per species), \
             a species is rejected when its smallest p < α/{} = {:.2e}, α = {})",
            r.maxwell_boltzmann.first().map_or(0, |m| m.tests),
            r.maxwell_boltzmann.first().map_or(0, |m| m.tests),
            r.maxwell_boltzmann.first().map_or(0.0, |m| m.p_threshold),
            carom::analysis::MB_FAMILY_ALPHA
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
            match (m.passed, m.scaled_to_snapshot_temperature) {
                (true, false) => "consistent with MB",
                (true, true) => "consistent with MB (each snapshot scaled by its thermal speed √(kT(t)/m))",
                (false, false) => "NOT Maxwell–Boltzmann",
                (false, true) => "NOT Maxwell–Boltzmann (each snapshot scaled by its thermal speed √(kT(t)/m))",
            }
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
                match (p.converged, p.drift.as_ref().is_some_and(|d| d.drifting)) {
                    (_, true) => "; DRIFTING, see below",
                    (true, false) => "",
                    (false, false) => "; blocking did not converge: run longer",
                }
            );
            let _ = writeln!(s, "  estimator: {}", p.estimator);
            if let Some(d) = p.drift.as_ref().filter(|d| d.drifting) {
                let w = &r.window;
                let _ = writeln!(
                    s,
                    "  drifting: first half Z = {:.5} ± {:.5}, second half {:.5} ± {:.5} ({:.1} standard errors apart): \
                     not in a steady state, the mean and its error mean little; equilibrate longer with \
                     --equilibrate T (e.g. {:.4}) or run longer",
                    d.first_half,
                    d.first_half_std_error,
                    d.second_half,
                    d.second_half_std_error,
                    d.difference_std_errors,
                    Num(0.5 * (w.equilibrate + w.t_end))
                );
            }
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
    if let Some(d) = c.drift.as_ref().filter(|d| d.drifting) {
        let _ = writeln!(
            s,
            "  drifting: first half ω = {:.5} ± {:.5}, second half {:.5} ± {:.5} ({:.1} standard errors apart); \
             equilibrate longer with --equilibrate T",
            Num(d.first_half),
            Num(d.first_half_std_error),
            Num(d.second_half),
            Num(d.second_half_std_error),
            d.difference_std_errors
        );
    }
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
    if let Some(pc) = &r.pair_correlation {
        let _ = writeln!(
            s,
            "pair correlation  g(r) to r = {:.4} in bins of {:.4} from {} snapshots in {} time blocks (physics.md §10)",
            pc.r_max, pc.bin_width, pc.snapshots, pc.blocks
        );
        for p in &pc.pairs {
            match &p.contact {
                Some(c) => {
                    let _ = writeln!(
                        s,
                        "  species {}–{}: contact value g(σ⁺) = {:.4} ± {:.4} at σ = {:.4} (fit of ln g over {} bins)",
                        p.a, p.b, Num(c.value), Num(c.std_error), p.sigma, c.fit_bins
                    );
                }
                None => {
                    let _ = writeln!(
                        s,
                        "  species {}–{}: no contact value (no bin within [σ, {} σ])",
                        p.a,
                        p.b,
                        1.0 + CONTACT_FIT_SIGMA
                    );
                }
            }
        }
        if let Some(c) = &pc.contact_theorem {
            let _ = writeln!(
                s,
                "contact theorem  Z = 1 + (π/2) n Σ x_a x_b σ_ab² g_ab(σ_ab⁺) = {:.5} ± {:.5}, virial Z = {:.5} ± {:.5}; difference {:.5} ({:.1} standard errors)",
                Num(c.z_structure), Num(c.z_structure_std_error), Num(c.z_virial), Num(c.z_virial_std_error), c.difference, c.difference_std_errors
            );
        }
    }
    structure_text(r, &mut s);
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
        if let Some(a) = &i.sonine {
            let _ = writeln!(
                s,
                "Sonine coefficient  a2 = ⟨(mv²)²⟩/(2⟨mv²⟩²) − 1 = {:.4} ± {:.4} over {} snapshots{}",
                a.a2,
                a.std_error,
                a.snapshots,
                match a.theory {
                    Some(th) => format!(
                        "; van Noije–Ernst {th:.4} ({} apart)",
                        sigmas(a.a2 - th, a.std_error)
                    ),
                    None => String::new(),
                }
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
/// The lines of bond order, g6(r) and S(k) (physics.md §11).
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

fn structure_text(r: &Report, s: &mut String) {
    use std::fmt::Write;
    if let Some(b) = &r.bond_order {
        let _ = writeln!(
            s,
            "bond order  |Ψ6| = {:.4} ± {:.4}, local ⟨|ψ6|⟩ = {:.4} ± {:.4}, susceptibility χ6 = N(⟨|Ψ6|²⟩ − ⟨|Ψ6|⟩²) = {:.4} ± {:.4} ({} snapshots, Delaunay neighbours weighted by Voronoi edges)",
            Num(b.global), Num(b.global_std_error), Num(b.local), Num(b.local_std_error),
            Num(b.susceptibility), Num(b.susceptibility_std_error), b.snapshots
        );
        let o = &b.other_estimators;
        let _ = writeln!(
            s,
            "  other estimators  |Ψ6| equal-weight Delaunay = {:.4} ± {:.4}, six nearest neighbours = {:.4} ± {:.4}; discs with six Delaunay neighbours {:.4} ± {:.4}",
            Num(o.delaunay_equal), Num(o.delaunay_equal_std_error), Num(o.six_nearest),
            Num(o.six_nearest_std_error), Num(o.six_neighbour_fraction), Num(o.six_neighbour_fraction_std_error)
        );
        if let Some(d) = b.drift.as_ref().filter(|d| d.drifting) {
            let _ = writeln!(
                s,
                "  drifting: first half |Ψ6| = {:.4} ± {:.4}, second half {:.4} ± {:.4} ({:.1} standard errors apart); \
                 the order is still changing: equilibrate longer with --equilibrate T",
                Num(d.first_half), Num(d.first_half_std_error), Num(d.second_half),
                Num(d.second_half_std_error), d.difference_std_errors
            );
        }
    }
    if let Some(g) = &r.orientational_correlation {
        let fit = |v: Option<[f64; 2]>| match v {
            Some([x, e]) => format!("{:.4} ± {:.4}", Num(x), Num(e)),
            None => "n/a".to_string(),
        };
        let _ = writeln!(
            s,
            "orientational correlation  g6(r) to r = {:.4} from {} snapshots: power law η6 = {}, exponential ξ6 = {}; {}{}",
            Num(g.r.last().copied().unwrap_or(f64::NAN) + 0.5 * (g.r.get(1).copied().unwrap_or(0.0) - g.r.first().copied().unwrap_or(0.0))),
            g.snapshots,
            fit(g.eta6),
            fit(g.xi6),
            match g.decay {
                Some(form) => format!("{form} fits better"),
                None => "no decay fit: g6 is within 3 SE of 0 after fewer than 3 envelope points (short-ranged order)".to_string(),
            },
            match (g.decay, g.eta6) {
                (Some("power law"), Some([eta, _])) if eta <= 0.25 => " (η6 ≤ 1/4: quasi-long-range order, as in the hexatic phase, or a crystal)",
                _ => "",
            }
        );
    }
    if let Some(f) = &r.structure_factor {
        let _ = writeln!(
            s,
            "structure factor  first peak S = {:.4} at k = {:.4}; S at the smallest k = {:.4} ± {:.4} (k = {:.4}); \
             translational order ψ_T = max_k |ρ_k|/N = {:.4} ± {:.4} at k = ({:.4}, {:.4}) ({} snapshots)",
            Num(f.peak_s), Num(f.peak_k),
            Num(f.s.first().copied().unwrap_or(f64::NAN)), Num(f.std_error.first().copied().unwrap_or(f64::NAN)),
            Num(f.k.first().copied().unwrap_or(f64::NAN)),
            Num(f.translational), Num(f.translational_std_error),
            Num(f.translational_k[0]), Num(f.translational_k[1]), f.snapshots
        );
    }
}

fn thinned(m: &carom::analysis::SpeciesMb) -> String {
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
