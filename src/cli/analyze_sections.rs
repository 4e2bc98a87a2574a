//! The text of the report's first sections: the run and its window, the
//! temperature, and the velocity distribution against Maxwell–Boltzmann. One
//! quantity per line, value ± SE with its reference and verdict
//! ([`super::report_text`]).

use carom_analysis::{Report, SpeciesMb, CORRELATED_SPACING, DECORRELATION_COLLISIONS};

use super::super::report_text::{sig, Text};
use super::super::{AnalyzeArgs, Num};

/// The log, the system and the window analysed.
pub(super) fn run_text(r: &Report, args: &AnalyzeArgs, complete: bool, t: &mut Text) {
    let axis = |p: bool| if p { "periodic" } else { "walls" };
    t.section(&format!(
        "{}{}",
        args.file.display(),
        if complete {
            ""
        } else {
            " (cut short: read up to its last flush)"
        }
    ));
    t.item(
        "system",
        &format!(
            "N = {}, η = {:.4}, box {} × {} ({} × {}), {}",
            r.n,
            r.packing_fraction,
            sig(r.box_size[0], 6),
            sig(r.box_size[1], 6),
            axis(r.periodic[0]),
            axis(r.periodic[1]),
            if r.elastic { "elastic" } else { "inelastic" }
        ),
    );
    let w = &r.window;
    t.item(
        "window",
        &format!(
            "t ∈ [{}, {}] of the log's [{}, {}]",
            Num::computed(w.equilibrate),
            Num(w.t_end),
            Num(w.t_start),
            Num(w.t_end)
        ),
    );
    t.item(
        "snapshots",
        &format!(
            "{} of {} used{}",
            w.snapshot_times.len(),
            w.snapshots_seen,
            match (w.every, w.every_collisions) {
                (Some(e), Some(c)) if w.every_from_budget => format!(
                    ", ≥ {c} pair collisions per disc apart (counted between them) and ≥ {} in \
                     time to keep at most {} velocities in memory (--every to change)",
                    sig(e, 4),
                    w.max_velocities
                ),
                (None, Some(c)) => format!(
                    ", ≥ {c} pair collisions per disc apart, counted between them (the rate \
                     changes as the gas cools; --every to change)"
                ),
                (Some(e), _) if w.every_from_budget => format!(
                    ", ≥ {} apart to keep at most {} velocities in memory (--every to change)",
                    sig(e, 4),
                    w.max_velocities
                ),
                (Some(e), _) if w.every_default => format!(
                    ", ≥ {} apart: {} pair collisions per disc (--every to change)",
                    sig(e, 4),
                    DECORRELATION_COLLISIONS
                ),
                (Some(e), _) => format!(", ≥ {} apart", Num(e)),
                (None, _) => String::new(),
            }
        ),
    );
    let rate = r.collision_rate.per_disc;
    if let Some(c) = w
        .spacing_collisions
        .filter(|&c| c < CORRELATED_SPACING && rate > 0.0)
    {
        let cure = if r.elastic {
            format!(
                "--every {} or more",
                sig(DECORRELATION_COLLISIONS / rate, 4)
            )
        } else {
            "leave out --every: the default spaces them by counted collisions, as the rate \
             changes"
                .to_string()
        };
        t.note(&format!(
            "warning: the snapshots used are only {c:.2} pair collisions per disc apart \
             (counted between them): their velocities are correlated and the \
             Maxwell–Boltzmann tests reject too often ({cure})"
        ));
    }
}

/// Temperature and the Maxwell–Boltzmann tests, one section per species.
pub(super) fn velocity_text(r: &Report, t: &mut Text) {
    let tr = &r.temperature;
    t.section("temperature (physics.md §5)");
    t.item(
        "kT = 2K/f",
        &format!(
            "{}   (f = 2N − {} = {} degrees of freedom)",
            sig(tr.kt, 7),
            tr.conserved_momentum_components,
            tr.dof
        ),
    );
    if r.maxwell_boltzmann.is_empty() && r.maxwell_boltzmann_untested.is_empty() {
        t.section("Maxwell–Boltzmann");
        t.note("not tested: no snapshot in the window");
    }
    for m in &r.maxwell_boltzmann {
        t.section(&format!(
            "Maxwell–Boltzmann, species {} (m = {}, a = {})",
            m.species,
            Num(m.mass),
            Num(m.radius)
        ));
        t.item("speeds", &format!("{}{}", m.samples, thinned(m)));
        t.item(
            "speed χ²",
            &format!(
                "{:.2} / {} dof, p = {}",
                m.chi_square.statistic,
                m.chi_square.dof,
                p_value(m.chi_square.p_value)
            ),
        );
        t.item(
            "speed KS",
            &format!("D = {:.4}, p = {}", m.ks.statistic, p_value(m.ks.p_value)),
        );
        t.item("vx KS", &format!("p = {}", p_value(m.ks_vx.p_value)));
        t.item("vy KS", &format!("p = {}", p_value(m.ks_vy.p_value)));
        t.item(
            "verdict",
            &format!(
                "{}: smallest p {} α/{} = {:.4} (α = {}, Bonferroni over {} tests)",
                if m.passed {
                    "consistent with Maxwell–Boltzmann"
                } else {
                    "NOT Maxwell–Boltzmann"
                },
                if m.passed { "≥" } else { "<" },
                m.tests,
                m.p_threshold,
                carom_analysis::MB_FAMILY_ALPHA,
                m.tests
            ),
        );
        if m.scaled_to_snapshot_temperature {
            t.note("each snapshot's velocities scaled by its own thermal speed √(kT(t)/m)");
        }
    }
    if !r.maxwell_boltzmann.is_empty() {
        t.note(
            "kT is measured from the same snapshots: χ² loses one degree of freedom, KS p is \
             conservative",
        );
    }
    for u in &r.maxwell_boltzmann_untested {
        t.section(&format!("Maxwell–Boltzmann, species {}", u.species));
        t.item("not tested", &format!("{} speeds: {}", u.samples, u.reason));
    }
}

/// A p-value: four significant digits, scientific below 10⁻³.
fn p_value(p: f64) -> String {
    if p >= 1e-3 {
        format!("{p:.3}")
    } else {
        format!("{p:.2e}")
    }
}

/// How a species' snapshots were thinned ("" when all of the window's were used).
fn thinned(m: &SpeciesMb) -> String {
    match m.snapshot_correlation {
        Some(rho) if m.snapshot_step > 1 => format!(
            " from {} (velocities correlate {rho:.3} from one snapshot to the next: {})",
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
        _ => format!(" from {} snapshots", m.snapshots),
    }
}
