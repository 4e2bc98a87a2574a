//! The text of an inelastic run's sections (physics.md §8): the energy budget
//! E0 − dissipated − E, Haff's law twice (the self-consistency check with the
//! measured collision rate, and the prediction from Enskog's ω_E with the
//! measured a2), the Sonine coefficient a2 against the second Sonine
//! approximation (van Noije & Ernst's first-order formula shown as the
//! approximation it is), and kT against time. One quantity per line
//! ([`super::super::report_text`]).

use carom_analysis::{InelasticReport, Report, ENSKOG_COOLING_TOLERANCE};

use super::super::report_text::{pm, sig, sigmas, Text};

/// The inelastic sections of `r` (nothing for an elastic run).
pub(super) fn inelastic_text(r: &Report, t: &mut Text) {
    let Some(i) = &r.inelastic else {
        return;
    };
    energy_text(i, t);
    haff_text(i, t);
    sonine_text(i, t);
    t.section("temperature vs time");
    let series = &r.temperature.series;
    let step = (series.len() / 10).max(1);
    for p in series.iter().step_by(step) {
        t.item(
            &format!("t = {}", sig(p[0], 5)),
            &format!("kT = {}", sig(p[1], 6)),
        );
    }
}

fn energy_text(i: &InelasticReport, t: &mut Text) {
    let Some(e) = &i.energy else {
        return;
    };
    t.section("energy budget (physics.md §8)");
    t.item("E0", &sig(e.initial, 9));
    t.item("E", &sig(e.final_, 9));
    t.item(
        "dissipated",
        &format!("{}   ({})", sig(e.dissipated, 9), e.dissipated_source),
    );
    t.item(
        "E0 − dissipated − E",
        &format!("{:.3e} (relative {:.3e})", e.residual, e.relative_residual),
    );
}

fn haff_text(i: &InelasticReport, t: &mut Text) {
    let Some(h) = &i.haff else {
        return;
    };
    t.section("Haff's law kT(t) = kT0/(1 + t/t0)² (physics.md §8)");
    t.note(&format!("{}:", h.check));
    t.item(
        "t0",
        &format!(
            "{}   (ω(T0) = {}, a2 = {})",
            sig(h.t0, 5),
            sig(h.collision_frequency_initial, 4),
            sig(h.a2, 3)
        ),
    );
    t.item(
        "final kT",
        &format!(
            "measured {}, predicted {} (ratio {:.4})",
            sig(h.kt_final_measured, 5),
            sig(h.kt_final_predicted, 5),
            h.ratio
        ),
    );
    let Some(e) = &h.enskog else {
        return;
    };
    t.section(&format!(
        "cooling rate from Enskog's ω_E and the measured a2, t ∈ [{}, {}] (physics.md §8)",
        sig(e.window[0], 4),
        sig(e.window[1], 4)
    ));
    t.item(
        "ω_E at the start",
        &format!(
            "{} = 2σ n g(σ) √(π kT/m), Henderson's g(σ) = {}",
            sig(e.omega_start, 4),
            sig(e.g_contact, 4)
        ),
    );
    t.item(
        "d(1/√kT)/dt",
        &format!(
            "measured {}, predicted {} (1 − e²)(1 + 3a2/16) ω_E/(4√kT), a2 = {}",
            sig(e.slope_measured, 4),
            sig(e.slope_predicted, 4),
            sig(e.a2, 3)
        ),
    );
    t.item(
        "kT at the end",
        &format!(
            "measured {}, predicted {}",
            sig(e.kt_end_measured, 5),
            sig(e.kt_end_predicted, 5)
        ),
    );
    t.item(
        "verdict",
        &format!(
            "{} (measured/predicted cooling rate {:.3}; tolerance ± {})",
            if e.agrees {
                "cools as Enskog's theory predicts"
            } else if e.ratio < 1.0 {
                "cools MORE SLOWLY than Enskog's theory predicts (clusters, or velocity \
                 correlations Enskog neglects)"
            } else {
                "cools FASTER than Enskog's theory predicts"
            },
            e.ratio,
            ENSKOG_COOLING_TOLERANCE
        ),
    );
}

fn sonine_text(i: &InelasticReport, t: &mut Text) {
    let Some(a) = &i.sonine else {
        return;
    };
    t.section("Sonine coefficient a2 = ⟨(mv²)²⟩/(2⟨mv²⟩²) − 1 (physics.md §8)");
    t.item(
        "a2",
        &format!(
            "{}   over {} snapshots{}",
            pm(a.a2, a.std_error),
            a.snapshots,
            if a.std_error_blocked {
                " (blocked error)"
            } else {
                ""
            }
        ),
    );
    if let Some(th) = a.theory_second_order {
        t.item(
            "second Sonine order",
            &format!("{} ({} apart)", sig(th, 3), sigmas(a.a2 - th, a.std_error)),
        );
    }
    if let Some(th) = a.theory {
        t.item(
            "van Noije–Ernst",
            &format!(
                "{} ({} apart; first Sonine approximation, 10–20 % off for discs)",
                sig(th, 3),
                sigmas(a.a2 - th, a.std_error)
            ),
        );
    }
}
