//! The text of the report's structure sections: the pair correlation g(r) with
//! its contact values and the contact theorem (physics.md §10), and the bond order
//! (ψ6, g6) and static structure factor S(k). Value ± SE with its reference and
//! verdict ([`super::report_text`]).

use carom_analysis::Report;

use super::super::report_text::{pm, sig, Text};
use super::{cooling, drift_line};

/// g(r), its contact values and the contact theorem.
pub(super) fn pair_correlation_text(r: &Report, t: &mut Text) {
    let Some(pc) = &r.pair_correlation else {
        return;
    };
    t.section("pair correlation g(r) (physics.md §10)");
    t.item(
        "g(r)",
        &format!(
            "to r = {} in bins of {}, from {} snapshots in {} time blocks",
            sig(pc.r_max, 4),
            sig(pc.bin_width, 4),
            pc.snapshots,
            pc.blocks
        ),
    );
    for p in &pc.pairs {
        let name = format!("g{}{}(σ⁺)", p.a, p.b);
        match (&p.contact, &p.contact_missing) {
            (Some(c), _) => t.item(
                &name,
                &match (c.std_error, &c.no_error) {
                    (Some(se), _) => format!(
                        "{}   at σ = {} (fit of ln g over {} bins)",
                        pm(c.value, se),
                        sig(p.sigma, 6),
                        c.fit_bins
                    ),
                    (None, why) => format!(
                        "{} at σ = {}; error not computed: {}",
                        sig(c.value, 4),
                        sig(p.sigma, 6),
                        why.as_deref().unwrap_or("")
                    ),
                },
            ),
            (None, why) => t.item(
                &name,
                &format!("not computed: {}", why.as_deref().unwrap_or("no fit")),
            ),
        }
    }
    if let Some(c) = &pc.contact_theorem {
        t.section("contact theorem Z = 1 + (π/2) n Σ x_a x_b σ_ab² g_ab(σ_ab⁺) (physics.md §10)");
        t.item("Z from g(σ⁺)", &pm(c.z_structure, c.z_structure_std_error));
        t.item("Z from the virial", &pm(c.z_virial, c.z_virial_std_error));
        t.item(
            "difference",
            &format!(
                "{:.5} ({:+.1}σ)",
                c.z_structure - c.z_virial,
                c.difference_std_errors
            ),
        );
    }
}

/// Bond order ψ6, g6(r) and S(k) (physics.md §11).
pub(super) fn structure_text(r: &Report, t: &mut Text) {
    if let Some(b) = &r.bond_order {
        t.section(&format!(
            "bond order ψ6 (physics.md §11; {} snapshots)",
            b.snapshots
        ));
        t.item(
            "|Ψ6|",
            &format!(
                "{}   (Delaunay neighbours weighted by Voronoi edges)",
                pm(b.global, b.global_std_error)
            ),
        );
        t.item("local ⟨|ψ6|⟩", &pm(b.local, b.local_std_error));
        t.item(
            "χ6",
            &format!(
                "{}   (N(⟨|Ψ6|²⟩ − ⟨|Ψ6|⟩²))",
                pm(b.susceptibility, b.susceptibility_std_error)
            ),
        );
        let o = &b.other_estimators;
        t.item(
            "|Ψ6| equal weights",
            &pm(o.delaunay_equal, o.delaunay_equal_std_error),
        );
        t.item(
            "|Ψ6| six nearest",
            &pm(o.six_nearest, o.six_nearest_std_error),
        );
        t.item(
            "six neighbours",
            &format!(
                "{} of the discs",
                pm(o.six_neighbour_fraction, o.six_neighbour_fraction_std_error)
            ),
        );
        if let Some(d) = b.drift.as_ref().filter(|d| d.drifting) {
            let tail = if cooling(r) {
                ": the order is still changing (a cooling gas never settles)"
            } else {
                ": the order is still changing; equilibrate longer"
            };
            t.item("drift", &drift_line(d, tail));
        }
    }
    if let Some(g) = &r.orientational_correlation {
        let fit = |v: Option<[f64; 2]>| match v {
            Some([x, e]) => pm(x, e),
            None => "no fit".to_string(),
        };
        t.section(&format!(
            "orientational correlation g6(r) (physics.md §11; {} snapshots)",
            g.snapshots
        ));
        t.item("power law η6", &fit(g.eta6));
        t.item("exponential ξ6", &fit(g.xi6));
        t.item(
            "decay",
            &match (g.decay, g.eta6) {
                (Some("power law"), Some([eta, _])) if eta <= 0.25 => {
                    "power law fits better; η6 ≤ 1/4: quasi-long-range order (hexatic or \
                     crystal)"
                        .to_string()
                }
                (Some(form), _) => format!("{form} fits better"),
                (None, _) => "no fit: g6 is within 3 SE of 0 after fewer than 3 envelope \
                              points (short-ranged order)"
                    .to_string(),
            },
        );
    }
    if let Some(f) = &r.structure_factor {
        t.section(&format!(
            "structure factor S(k) (physics.md §11; {} snapshots)",
            f.snapshots
        ));
        match (f.peak_s, f.peak_k, f.peak_std_error) {
            (Some(s), Some(k), se) => t.item(
                "first peak",
                &format!(
                    "S = {} at k = {} (kσ = {})",
                    pm(s, se.unwrap_or(f64::NAN)),
                    sig(k, 4),
                    sig(k * sigma_min(r), 4)
                ),
            ),
            _ => t.item(
                "first peak",
                "not computed: no shell reaches k = π/σ (the box's wave vectors)",
            ),
        }
        if let (Some(s), Some(e), Some(k)) = (f.s.first(), f.std_error.first(), f.k.first()) {
            t.item(
                "S at the smallest k",
                &format!("{} at k = {}", pm(*s, *e), sig(*k, 4)),
            );
        }
        t.item(
            "ψ_T = max |ρ_k|/N",
            &format!(
                "{} at k = ({}, {})",
                pm(f.translational, f.translational_std_error),
                sig(f.translational_k[0], 4),
                sig(f.translational_k[1], 4)
            ),
        );
    }
}

/// The smallest contact distance σ_min = 2 a_min of the species present.
fn sigma_min(r: &Report) -> f64 {
    r.species
        .iter()
        .filter(|s| s.count > 0)
        .map(|s| 2.0 * s.radius)
        .fold(f64::INFINITY, f64::min)
}
