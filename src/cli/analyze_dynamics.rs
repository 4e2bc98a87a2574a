//! The text lines of the single-disc dynamics from the snapshots (physics.md §13),
//! one quantity per line: how the origins and errors were made, and per species
//! D from the snapshot MSD fit with its window in time and in t_c and N (the
//! headline D when the run has no exact collision replay, otherwise a check with
//! the headline in the transport section), the largest α₂, the snapshot VACF at
//! the first lag and τ_α; and a warning when snapshot gaps could not be unwrapped
//! with certainty.

use carom_analysis::Report;

use super::transport::pm;
use super::Num;

/// Append the dynamics lines of `r` to `s` (nothing without origins).
pub(super) fn dynamics_text(r: &Report, s: &mut String) {
    use std::fmt::Write;
    let Some(d) = &r.dynamics else {
        return;
    };
    let replay = r.transport.is_some();
    let _ = writeln!(s, "dynamics (snapshot MSD, physics.md §13)");
    let _ = writeln!(
        s,
        "  {:<18}{} ({} per level on {} levels{})",
        "time origins",
        d.origins,
        d.origins_per_level,
        d.levels,
        if d.origins_capped {
            ", capped: long lags may be missing"
        } else {
            ""
        },
    );
    let _ = writeln!(
        s,
        "  {:<18}spread of {} time segments; D's adds the weighted − unweighted fit",
        "errors", d.segments
    );
    if let Some(k) = d.k_star {
        let _ = writeln!(s, "  {:<18}{:.4}  (first peak of S(k))", "k*", Num(k));
    }
    let several = d.species.len() > 1;
    for sp in &d.species {
        let tag = if several {
            format!(" {}", sp.species)
        } else {
            String::new()
        };
        if several {
            let _ = writeln!(s, "  species {} ({} discs)", sp.species, sp.count);
        }
        match &sp.diffusion {
            Some(f) => {
                let role = if replay {
                    "check; headline D: transport"
                } else {
                    "headline"
                };
                let _ = writeln!(
                    s,
                    "  {:<18}{}  ({role})",
                    format!("D{tag}"),
                    pm(f.d, f.std_error)
                );
                let tc = d
                    .collision_time
                    .map(|tc| format!(" = [{:.1}, {:.1}] t_c", f.t_a / tc, f.t_b / tc))
                    .unwrap_or_default();
                let _ = writeln!(
                    s,
                    "  {:<18}MSD = 4Dτ + c over τ ∈ [{:.4}, {:.4}]{tc}, N = {}",
                    "  D window",
                    Num(f.t_a),
                    Num(f.t_b),
                    r.n
                );
                let _ = writeln!(
                    s,
                    "  {:<18}unweighted fit {:.5}, statistical SE {:.5}",
                    "  D fit",
                    Num(f.d_unweighted),
                    Num(f.statistical_std_error)
                );
            }
            None => {
                let _ = writeln!(
                    s,
                    "  {:<18}too few lags in the fit window",
                    format!("D{tag}")
                );
            }
        }
        let last = sp.lag.len().saturating_sub(1);
        let alpha2 = sp
            .alpha2
            .iter()
            .copied()
            .filter(|a| a.is_finite())
            .fold(f64::NAN, f64::max);
        let _ = writeln!(
            s,
            "  {:<18}{:.5} at τ = {:.4}",
            "MSD",
            Num(sp.msd[last]),
            Num(sp.lag[last])
        );
        let _ = writeln!(s, "  {:<18}{:.4}", "largest α₂", Num(alpha2));
        let _ = writeln!(
            s,
            "  {:<18}{:.4} at τ = {:.4}",
            "C(τ)/C(0)",
            Num(sp.vacf_normalised.get(1).copied().unwrap_or(f64::NAN)),
            Num(sp.lag.get(1).copied().unwrap_or(f64::NAN)),
        );
        let early = sp.fs.get(1).is_some_and(|f| *f <= (-1.0f64).exp());
        let tau = match (sp.tau_alpha, sp.fs.is_empty(), early) {
            (_, true, _) => None,
            (Some(t), _, _) => Some(format!("{:.4}  (F_s(k*, τ_α) = 1/e)", Num(t))),
            (None, _, true) => Some(format!(
                "< {:.4}  (F_s below 1/e at the first lag)",
                Num(sp.lag[1])
            )),
            (None, _, false) => Some(format!(
                "> {:.4}  (F_s above 1/e at every lag)",
                Num(sp.lag[last])
            )),
        };
        if let Some(t) = tau {
            let _ = writeln!(s, "  {:<18}{t}", "τ_α");
        }
    }
    if d.ambiguous_gaps > 0 {
        let _ = writeln!(
            s,
            "  warning: {} snapshot gaps too long to unwrap with certainty (log without",
            d.ambiguous_gaps
        );
        let _ = writeln!(
            s,
            "  images): MSD, D and F_s over them may be off by box lengths"
        );
    }
}
