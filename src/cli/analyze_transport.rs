//! The transport lines of `carom analyze`'s text report (physics.md §14), one
//! quantity per line, `name  value ± SE  (reference …)  verdict`: N, t_c, the lag
//! window in time and in t_c beside the documented [10, 100] t_c, how the errors
//! are made and whether the replayed velocities matched the snapshots; then the
//! headline D (from the MSD of the exact collision replay), η and λ (Einstein–
//! Helfand) beside Enskog's values, each marked "unreliable" with the reasons
//! when its window is short or its running value has not levelled off (§14.6);
//! the other routes (D from the VACF integral, Green–Kubo) as checks with their
//! difference in standard errors; the VACF tail amplitude against mode coupling;
//! and the 2D caveat. Only formatting here: every number comes from
//! [`TransportReport`].

use std::fmt::Write;

use carom_analysis::{Estimate, HelfandReport, Reliability, TransportReport};

use super::sigmas;
use crate::cli::Num;

/// Decimals that show two significant digits of `se` (2 to 6 when it is not
/// finite or positive).
fn decimals(se: f64) -> usize {
    if se.is_finite() && se > 0.0 {
        (1.0 - se.log10().floor()).clamp(0.0, 8.0) as usize
    } else {
        4
    }
}

/// "value ± se" to two significant digits of the error.
pub(super) fn pm(value: f64, se: f64) -> String {
    let d = decimals(se);
    format!("{:.d$} ± {:.d$}", Num(value), Num(se))
}

/// "value ± se" of an estimate.
fn est(e: &Estimate) -> String {
    pm(e.value, e.std_error)
}

/// "(Enskog X_E, ratio r)" or "" without Enskog.
fn enskog(value: f64, reference: Option<f64>) -> String {
    match reference {
        Some(e) if e > 0.0 => format!("  (Enskog {:.5}, ratio {:.3})", Num(e), value / e),
        _ => String::new(),
    }
}

/// The verdict and, when unreliable, one indented line per reason.
fn verdict(r: &Reliability) -> (String, String) {
    if r.reliable {
        return ("  reliable".into(), String::new());
    }
    let why: String = r.why.iter().map(|w| format!("      why: {w}\n")).collect();
    ("  UNRELIABLE".into(), why)
}

/// A headline line with its verdict and reasons.
fn headline(s: &mut String, name: &str, e: &Estimate, reference: Option<f64>, r: &Reliability) {
    let (v, why) = verdict(r);
    let _ = writeln!(s, "  {name:<18}{}{}{v}", est(e), enskog(e.value, reference));
    s.push_str(&why);
}

/// A check line: the other route and its difference from the headline route.
fn check(s: &mut String, name: &str, e: &Estimate, diff: &Estimate) {
    let _ = writeln!(
        s,
        "  {name:<18}{}  (check: difference {}, {})",
        est(e),
        est(diff),
        sigmas(diff.value, diff.std_error)
    );
}

/// η or λ: Einstein–Helfand as the headline, Green–Kubo as the check.
fn coefficient(s: &mut String, symbol: &str, h: &HelfandReport, reference: Option<f64>) {
    headline(s, symbol, &h.value_helfand, reference, &h.reliability);
    check(
        s,
        &format!("{symbol} Green–Kubo"),
        &h.value_green_kubo,
        &h.difference,
    );
}

/// Append the transport lines of `t` to `s`.
pub(super) fn transport_text(t: &TransportReport, s: &mut String) {
    let [a, b] = t.window;
    let [ac, bc] = t.window_collision_times;
    let [da, db] = t.documented_window_collision_times;
    let _ = writeln!(s, "transport (exact collision replay, physics.md §14)");
    let _ = writeln!(s, "  {:<18}{} discs", "N", t.n);
    let _ = writeln!(
        s,
        "  {:<18}{:.5}  (kT = {:.5})",
        "t_c",
        Num(t.collision_time),
        Num(t.kt)
    );
    let _ = writeln!(
        s,
        "  {:<18}τ ∈ [{:.4}, {:.4}] = [{ac:.1}, {bc:.1}] t_c  (documented [{da}, {db}] t_c)",
        "window",
        Num(a),
        Num(b)
    );
    let _ = writeln!(
        s,
        "  {:<18}spread of {} time segments × Student's t (§14.6)",
        "errors", t.segments
    );
    let (k, bad) = (t.snapshots_checked, t.snapshots_mismatched);
    let _ = match (k, bad) {
        (0, _) => writeln!(s, "  {:<18}no later snapshot to check against", "replay"),
        (k, 0) => writeln!(s, "  {:<18}velocities matched all {k} snapshots", "replay"),
        (k, m) => writeln!(
            s,
            "  {:<18}WARNING: differs from {m} of {k} snapshots: collisions missing, \
             NONE of the values below hold",
            "replay"
        ),
    };
    let ens = t.enskog.as_ref();
    let several = t.species.len() > 1;
    for p in &t.species {
        let tag = if several {
            format!(" {}", p.species)
        } else {
            String::new()
        };
        headline(
            s,
            &format!("D{tag}"),
            &p.diffusion_msd,
            ens.map(|e| e.diffusion),
            &p.diffusion_reliability,
        );
        check(
            s,
            &format!("D{tag} VACF ∫"),
            &p.diffusion_vacf,
            &p.difference,
        );
    }
    coefficient(s, "η", &t.viscosity, ens.map(|e| e.viscosity));
    match &t.thermal_conductivity {
        Some(l) => coefficient(s, "λ", l, ens.map(|e| e.thermal_conductivity)),
        None => {
            let _ = writeln!(
                s,
                "  {:<18}not computed (several species: heat flux mixes with interdiffusion)",
                "λ"
            );
        }
    }
    for p in &t.species {
        if let Some(m) = &p.tail_amplitude {
            let theory = match p.tail_amplitude_theory {
                Some(th) => format!("  (mode coupling {:.5})", Num(th)),
                None => String::new(),
            };
            let (v, why) = verdict(&p.tail_amplitude_reliability);
            let tag = if several {
                format!(" {}", p.species)
            } else {
                String::new()
            };
            let name = format!("VACF tail A{tag}");
            let _ = writeln!(s, "  {name:<18}{}{theory}{v}", est(m));
            s.push_str(&why);
        }
    }
    let _ = writeln!(
        s,
        "  {:<18}in 2D D, η, λ grow like ln τ: values hold for this window and N = {}",
        "caveat", t.n
    );
}
