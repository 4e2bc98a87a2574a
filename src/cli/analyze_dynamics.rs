//! The text lines of the single-disc dynamics (physics.md §13): per species D
//! with its window and N, the largest α₂, the snapshot VACF at the first lag and
//! τ_α, and a warning when snapshot gaps could not be unwrapped with certainty.

use carom::analysis::Report;

use super::Num;

/// Append the dynamics lines of `r` to `s` (nothing without origins).
pub(super) fn dynamics_text(r: &Report, s: &mut String) {
    use std::fmt::Write;
    let Some(d) = &r.dynamics else {
        return;
    };
    let _ = writeln!(
        s,
        "dynamics  {} time origins ({} per level on {} levels{}), errors from {} time segments; k* = {} (first peak of S(k))",
        d.origins,
        d.origins_per_level,
        d.levels,
        if d.origins_capped { ", lowered to fit the memory cap: long lags may be missing" } else { "" },
        d.segments,
        d.k_star.map_or("n/a (walls)".to_owned(), |k| format!("{:.4}", Num(k))),
    );
    for sp in &d.species {
        let last = sp.lag.len().saturating_sub(1);
        let diffusion = match &sp.diffusion {
            Some(f) => format!(
                "D = {:.5} ± {:.5} from MSD = 4Dτ + c over τ in [{:.4}, {:.4}] with N = {} (in 2D D grows like ln τ: it depends on the window and N)",
                Num(f.d), Num(f.std_error), Num(f.t_a), Num(f.t_b), r.n
            ),
            None => "D: too few lags in the fit window".to_owned(),
        };
        let alpha2 = sp
            .alpha2
            .iter()
            .copied()
            .filter(|a| a.is_finite())
            .fold(f64::NAN, f64::max);
        let early = sp.fs.get(1).is_some_and(|f| *f <= (-1.0f64).exp());
        let tau = match (sp.tau_alpha, sp.fs.is_empty(), early) {
            (_, true, _) => String::new(),
            (Some(t), _, _) => format!("; F_s(k*, τ) = 1/e at τ_α = {:.4}", Num(t)),
            (None, _, true) => format!(
                "; F_s(k*, τ) is below 1/e already at τ = {:.4}: τ_α is shorter than the snapshot spacing",
                Num(sp.lag[1])
            ),
            (None, _, false) => format!(
                "; F_s(k*, τ) stays above 1/e to τ = {:.4}",
                Num(sp.lag[last])
            ),
        };
        let _ = writeln!(
            s,
            "  species {} ({} discs): {diffusion}; MSD({:.4}) = {:.5}; largest α₂ = {:.4}; C(τ)/C(0) at τ = {:.4}: {:.4}{tau}",
            sp.species,
            sp.count,
            Num(sp.lag[last]),
            Num(sp.msd[last]),
            Num(alpha2),
            Num(sp.lag.get(1).copied().unwrap_or(f64::NAN)),
            Num(sp.vacf_normalised.get(1).copied().unwrap_or(f64::NAN)),
        );
    }
    if d.ambiguous_gaps > 0 {
        let _ = writeln!(
            s,
            "  warning: {} snapshot gaps too long to unwrap with certainty (a log without images); \
             the MSD, D and F_s at lags spanning them may be off by box lengths",
            d.ambiguous_gaps
        );
    }
}
