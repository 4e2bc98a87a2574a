//! The text of the report's pressure section: the pressure from the collisional
//! virial, the collision rate, and Enskog's relation between them (physics.md §5),
//! value ± SE with its reference and verdict ([`super::report_text`]).

use carom_analysis::Report;

use super::super::report_text::{pm, sig, sigmas, Text};
use super::{cooling, drift_line};

/// Pressure, collision rate and Enskog's relation between them.
pub(super) fn pressure_text(r: &Report, t: &mut Text) {
    t.section("pressure (physics.md §5)");
    match &r.pressure {
        Some(p) => {
            let state = match (p.converged, p.drift.as_ref().is_some_and(|d| d.drifting)) {
                (_, true) => "  DRIFTING (below)",
                (true, false) => "",
                (false, false) if cooling(r) => "  blocking did not converge",
                (false, false) => "  blocking did not converge: run longer",
            };
            t.item("Z = βPA/N", &format!("{}{state}", pm(p.z, p.z_std_error)));
            t.item("βP", &pm(p.beta_p, p.beta_p_std_error));
            t.item("P", &format!("{}   (A = {})", sig(p.p, 7), sig(p.area, 7)));
            t.item("estimator", p.estimator);
            t.item(
                "error",
                &format!(
                    "from {} blocks of {} in time",
                    p.blocks,
                    sig(p.block_time, 4)
                ),
            );
            if let Some(d) = p.drift.as_ref().filter(|d| d.drifting) {
                t.item("drift", &drift_line(d, ""));
                let w = &r.window;
                if cooling(r) {
                    t.note(
                        "a freely cooling gas never reaches a steady state: this Z is an average \
                         over the cooling, and no equilibration time removes the drift (Z(t) in \
                         the figures)",
                    );
                } else {
                    t.note(&format!(
                        "not in a steady state: the mean and its error mean little; equilibrate \
                         longer (e.g. --equilibrate {}) or run longer",
                        sig(0.5 * (w.equilibrate + w.t_end), 4)
                    ));
                }
            }
        }
        None => t.note("not available: no temperature in the log"),
    }
    let c = &r.collision_rate;
    t.section("collision rate (physics.md §7)");
    match (&c.start, &c.end) {
        (Some(a), Some(b)) if cooling(r) => {
            for (name, p) in [("ω at the start", a), ("ω at the end", b)] {
                t.item(
                    name,
                    &format!(
                        "{} pair collisions per disc per unit time over t ∈ [{}, {}], kT = {}",
                        pm(p.per_disc, p.std_error),
                        sig(p.window[0], 4),
                        sig(p.window[1], 4),
                        sig(p.kt, 4)
                    ),
                );
            }
            t.note("a cooling gas's ω falls as √T: no one mean describes it (JSON: per_disc)");
        }
        _ => t.item(
            "ω",
            &format!(
                "{} pair collisions per disc per unit time",
                pm(c.per_disc, c.std_error)
            ),
        ),
    }
    t.item(
        "counted from",
        &if c.counted_from == "thermo" {
            "the running collision counts of /thermo (the log does not hold every collision)"
                .to_string()
        } else {
            format!(
                "{} pair and {} wall collisions in the log{}",
                c.logged_pair_collisions,
                c.logged_wall_collisions,
                if c.collision_stride > 1 {
                    format!(", every {}th logged", c.collision_stride)
                } else {
                    String::new()
                }
            )
        },
    );
    if let Some(d) = c.drift.as_ref().filter(|d| d.drifting) {
        let tail = if cooling(r) {
            ": the gas is cooling"
        } else {
            ": equilibrate longer"
        };
        t.item("drift", &drift_line(d, tail));
    }
    if let Some(e) = &r.enskog {
        t.section("Enskog's relation Z − 1 = (√π/4) ω τ0 (physics.md §7)");
        t.item("Z − 1", &sig(e.z_minus_1, 6));
        t.item("(√π/4) ω τ0", &pm(e.rate_term, e.rate_term_std_error));
        t.item(
            "difference",
            &format!(
                "{} ({})",
                pm(e.difference, e.difference_std_error),
                sigmas(e.difference, e.difference_std_error)
            ),
        );
    }
}
