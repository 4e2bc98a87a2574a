//! The text of the report's equilibrium sections: the run and its window, the
//! temperature, the velocity distribution against Maxwell–Boltzmann, the pressure
//! with the collision rate and Enskog's check, the pair correlation with the
//! contact theorem, and the structure (ψ6, g6, S(k)). One quantity per line,
//! value ± SE with its reference and verdict ([`super::report_text`]).

use carom_analysis::{Report, SpeciesMb, CORRELATED_SPACING, DECORRELATION_COLLISIONS};

use super::super::report_text::{pm, sig, sigmas, Text};
use super::super::{AnalyzeArgs, Num};

/// Whether the run cools freely: inelastic, with nothing putting energy in.
pub(super) fn cooling(r: &Report) -> bool {
    !r.elastic && r.thermostat.is_none() && r.floor.is_none()
}

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
                t.item(
                    "drift",
                    &format!(
                        "first half {}, second half {} ({:.1} SE apart)",
                        pm(d.first_half, d.first_half_std_error),
                        pm(d.second_half, d.second_half_std_error),
                        d.difference_std_errors
                    ),
                );
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
        t.item(
            "drift",
            &format!(
                "first half {}, second half {} ({:.1} SE apart){}",
                pm(d.first_half, d.first_half_std_error),
                pm(d.second_half, d.second_half_std_error),
                d.difference_std_errors,
                if cooling(r) {
                    ": the gas is cooling"
                } else {
                    ": equilibrate longer"
                }
            ),
        );
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
            t.item(
                "drift",
                &format!(
                    "first half {}, second half {} ({:.1} SE apart): the order is still \
                     changing{}",
                    pm(d.first_half, d.first_half_std_error),
                    pm(d.second_half, d.second_half_std_error),
                    d.difference_std_errors,
                    if cooling(r) {
                        " (a cooling gas never settles)"
                    } else {
                        "; equilibrate longer"
                    }
                ),
            );
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
