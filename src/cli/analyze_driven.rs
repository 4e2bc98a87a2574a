//! The text of the report's sections for runs that are not a plain closed box:
//! a compression (physics.md §17), a field with its barometric and hydrostatic
//! profiles (§15), a thermostat (§16) and a vibrating floor (§18). Only
//! formatting: every number comes from the report; layout as in
//! [`super::super::report_text`].

use carom_analysis::{CompressionReport, FloorReport, GravityReport, ThermostatReport};

use super::super::report_text::{pm, sig, sigmas, Text};

/// How the discs grew, just after the window that it explains.
pub(super) fn compression_text(c: &CompressionReport, t: &mut Text) {
    t.section("compression (Lubachevsky–Stillinger, physics.md §17)");
    t.item(
        "η",
        &format!(
            "{:.4} → {:.4} (radii × {})",
            c.start_packing_fraction,
            c.final_packing_fraction,
            sig(c.final_radius_scale, 7)
        ),
    );
    let how = match c.ended {
        "target" => format!("reached the target η = {:.4}", c.target_packing_fraction),
        "jammed" => format!(
            "jammed: Z of the last interval above the bound {} (target η = {:.4} not reached)",
            c.max_reduced_pressure, c.target_packing_fraction
        ),
        _ => "still growing at the end of the log".to_owned(),
    };
    let when = c
        .end_time
        .map_or(String::new(), |t| format!(" at t = {}", sig(t, 6)));
    t.item("growth", &format!("{how}{when}"));
    t.item("last Z", &sig(c.last_z, 5));
    t.item(
        "rescales",
        &format!(
            "{} logged (γ = {}, every {})",
            c.rescales, c.rate, c.rescale_interval
        ),
    );
    t.note("the analysis below uses the radii after growth and only the time after it");
}

/// Potential energy, energy conservation in the field, and the density profile
/// against the barometric (ideal gas) and hydrostatic (equation of state) laws.
pub(super) fn gravity_text(g: &GravityReport, t: &mut Text) {
    t.section(&format!("gravity g = {} along −y (physics.md §15)", g.g));
    t.item(
        "U = Σ m g y",
        &format!(
            "{} (mean of {} snapshots)",
            sig(g.potential_energy, 7),
            g.snapshots
        ),
    );
    if let (Some(a), Some(b)) = (g.total_energy_first, g.total_energy_last) {
        t.item(
            "K + U",
            &format!(
                "{} at the first snapshot, {} at the last (relative change {:.1e})",
                sig(a, 10),
                sig(b, 10),
                (b - a) / a.abs()
            ),
        );
    }
    for b in &g.barometric {
        t.section(&format!(
            "density profile n(y), species {} (physics.md (15.7)–(15.8))",
            b.species
        ));
        let fitted = match b.beta_std_error {
            Some(se) => pm(b.beta, se),
            None => format!("{} (no error estimate)", sig(b.beta, 5)),
        };
        t.item("fitted m g/kT", &fitted);
        let apart = |known: f64| {
            b.beta_std_error
                .map_or("–".to_string(), |e| sigmas(b.beta - known, e))
        };
        if let Some(why) = b.not_applicable {
            t.item("reference", &format!("none: {why}"));
        } else {
            if let Some(h) = b.beta_hydrostatic {
                t.item(
                    "hydrostatic (EOS)",
                    &format!("{} ({})  the reference", sig(h, 5), apart(h)),
                );
            }
            t.item(
                "ideal gas m g/kT",
                &format!(
                    "{} ({}){}",
                    sig(b.beta_expected, 5),
                    apart(b.beta_expected),
                    if b.beta_hydrostatic.is_some() {
                        "  not the reference: the gas is not ideal near the floor"
                    } else {
                        ""
                    }
                ),
            );
        }
        t.item(
            "n at the floor",
            &format!("{} (the fitted law at y = a)", sig(b.floor_density, 5)),
        );
    }
}

/// The thermostat's target against the measured temperature (physics.md §16);
/// it replaces the energy budget, which a thermostat does not close.
pub(super) fn thermostat_text(th: &ThermostatReport, t: &mut Text) {
    let opt = |x: Option<f64>| x.map_or("–".to_owned(), |v| sig(v, 5));
    match (th.target_kt, th.granular_temperature) {
        (Some(target), _) => {
            t.section("thermostat: Andersen (physics.md §16.1)");
            t.item("rate", &format!("{} per disc", opt(th.rate)));
            t.item(
                "kT = 2K/(2N)",
                &format!(
                    "{} against the target {} (relative difference {:+.1e})",
                    sig(th.kt_all_components, 6),
                    sig(target, 6),
                    th.relative_difference.unwrap_or(0.0)
                ),
            );
        }
        (None, Some(tg)) => {
            t.section("thermostat: driven by random kicks (physics.md §16.2)");
            t.item(
                "kicks",
                &format!("ξ² = {}, every {}", opt(th.xi2), opt(th.interval)),
            );
            t.item("T = K/N", &sig(tg, 6));
            t.item(
                "steady T predicted",
                &format!(
                    "{} (Enskog–Henderson rate), {} (measured rate)",
                    opt(th.predicted_temperature),
                    opt(th.predicted_temperature_from_rate)
                ),
            );
        }
        _ => return,
    }
    t.note("energy is not conserved: the thermostat puts it in and takes it out");
}

/// The vibrating floor and the power balance of its bed (physics.md §18).
pub(super) fn floor_text(f: &FloorReport, t: &mut Text) {
    t.section("vibrating floor (physics.md §18)");
    t.item(
        "floor",
        &format!(
            "A = {}, f = {}{}",
            sig(f.amplitude, 6),
            sig(f.frequency, 6),
            f.shaking_parameter
                .map(|g| format!(", Γ = Aω²/g = {g:.3}"))
                .unwrap_or_default()
        ),
    );
    t.item(
        "window",
        &format!("t ∈ [{}, {}]", sig(f.window[0], 6), sig(f.window[1], 6)),
    );
    t.item(
        "power in",
        &format!(
            "{} (floor work {})",
            sig(f.power_in, 6),
            sig(f.floor_work, 6)
        ),
    );
    t.item(
        "power dissipated",
        &format!(
            "{} (energy lost {})",
            sig(f.power_out, 6),
            sig(f.energy_lost, 6)
        ),
    );
    t.item(
        "balance",
        &format!(
            "in / out = {:.3}: a steady state has 1",
            f.power_in / f.power_out
        ),
    );
}
