//! The transport lines of `carom analyze`'s text report (physics.md §14): N, the
//! collision time t_c and the lag window [τ_a, τ_b]; per species D from the MSD,
//! [MSD(τ_b) − MSD(τ_a)]/[4(τ_b − τ_a)], and from the VACF integral, the mean of
//! D(τ) = ½ ∫₀^τ C over the window, with their difference in standard errors; η
//! and λ by Einstein–Helfand and Green–Kubo likewise, beside Enskog's values and
//! the ratio to them; whether the replayed velocities matched the snapshots; the
//! VACF's tail amplitude A in C(τ)/C(0) ≈ A/τ, measured and from mode coupling,
//! 1/[8π n (D + ν)]. In 2D all three coefficients grow like ln τ, so the lines
//! end with that caveat. Only formatting here: every number comes from
//! [`TransportReport`].

use std::fmt::Write;

use carom::analysis::{Estimate, HelfandReport, TransportReport};

use super::sigmas;
use crate::cli::Num;

/// "x ± se" with five digits after the point (or in exponent form far from 1).
fn est(e: &Estimate) -> String {
    format!("{:.5} ± {:.5}", Num(e.value), Num(e.std_error))
}

/// The value beside Enskog's: "Enskog X_E = …, X/X_E = …" (from the Helfand value
/// for η and λ, the MSD value for D), or "" without Enskog.
fn beside_enskog(symbol: &str, value: f64, enskog: Option<f64>) -> String {
    match enskog {
        Some(e) if e > 0.0 => format!(
            "; Enskog {symbol}_E = {:.5}, {symbol}/{symbol}_E = {:.4}",
            Num(e),
            value / e
        ),
        _ => String::new(),
    }
}

/// One coefficient by both routes, with Enskog's value.
fn coefficient(s: &mut String, symbol: &str, h: &HelfandReport, enskog: Option<f64>) {
    let _ = writeln!(
        s,
        "  {} {symbol}: Einstein–Helfand {}, Green–Kubo {}; difference {} ({}){}",
        h.quantity,
        est(&h.value_helfand),
        est(&h.value_green_kubo),
        est(&h.difference),
        sigmas(h.difference.value, h.difference.std_error),
        beside_enskog(symbol, h.value_helfand.value, enskog)
    );
}

/// Append the transport lines of `t` to `s`.
pub(super) fn transport_text(t: &TransportReport, s: &mut String) {
    let [a, b] = t.window;
    let tc = t.collision_time;
    let _ = writeln!(
        s,
        "transport  N = {}, t_c = {:.5}, kT = {:.5}; window τ ∈ [{:.5}, {:.5}] = [{:.1}, {:.1}] t_c; \
         errors from {} time segments (physics.md §14)",
        t.n,
        Num(tc),
        Num(t.kt),
        Num(a),
        Num(b),
        a / tc,
        b / tc,
        t.segments
    );
    let (k, bad) = (t.snapshots_checked, t.snapshots_mismatched);
    let _ = match (k, bad) {
        (0, _) => writeln!(
            s,
            "  warning: no later snapshot to check the replayed velocities against"
        ),
        (k, 0) => writeln!(s, "  replayed velocities matched all {k} snapshots"),
        (k, m) => writeln!(
            s,
            "  WARNING: replayed velocities differ from {m} of {k} snapshots: collisions are \
             missing from the log, NONE of the transport values below hold"
        ),
    };
    let enskog = t.enskog.as_ref();
    for p in &t.species {
        let _ = writeln!(
            s,
            "  species {}: D from the MSD {}, from the VACF integral {}; difference {} ({}){}",
            p.species,
            est(&p.diffusion_msd),
            est(&p.diffusion_vacf),
            est(&p.difference),
            sigmas(p.difference.value, p.difference.std_error),
            beside_enskog("D", p.diffusion_msd.value, enskog.map(|e| e.diffusion))
        );
    }
    coefficient(s, "η", &t.viscosity, enskog.map(|e| e.viscosity));
    match &t.thermal_conductivity {
        Some(l) => coefficient(s, "λ", l, enskog.map(|e| e.thermal_conductivity)),
        None => {
            let _ = writeln!(
                s,
                "  thermal conductivity λ: not computed (several species: the heat flux mixes with interdiffusion)"
            );
        }
    }
    for p in &t.species {
        if let Some(m) = &p.tail_amplitude {
            let _ = writeln!(
                s,
                "  species {}: VACF tail C(τ)/C(0) ≈ A/τ, A = τ C(τ)/C(0) over τ ≥ τ_a = {}{}",
                p.species,
                est(m),
                match p.tail_amplitude_theory {
                    Some(th) => format!(", mode coupling 1/[8π n (D + ν)] = {:.5}", Num(th)),
                    None => String::new(),
                }
            );
        }
    }
    let _ = writeln!(
        s,
        "  caveat: in 2D D, η and λ grow like ln τ (the long-time tails), so these values hold \
         for this window and N = {} only",
        t.n
    );
}
