//! Validation of the transport analysis (issue 36) with the engine's own runs,
//! analysed as `carom analyze` would, in its own section of docs/validation.md:
//!
//! 10. Low density (ignored, about 3 min): φ = 0.01, 0.05, 0.1, 0.2, N = 4096,
//!     4000 collision times per disc. Over the window [10 t_c, 100 t_c]: η and λ
//!     against Enskog with the dilute gas's Sonine factors (physics.md (14.8))
//!     within 3 SE, the reference given a 5 % allowance for the 2D tail and ring
//!     collisions (not a measured error); D against Enskog with f_D plus the
//!     tail's ln t growth (physics.md (14.9)), whose onset gives the allowance;
//!     and on the same data D from the MSD = D from the VACF integral,
//!     Helfand = Green–Kubo for η and λ, each within 3 SE of the difference.
//! 11. The VACF's long-time tail (ignored, about 5 min): φ = 0.3, N = 40 000;
//!     the measured amplitude of C(τ)/C(0) ≈ A/τ over lags ≥ 10 t_c against mode
//!     coupling A = 1/[8π n (D + ν)] (physics.md (14.6)), with D and ν measured
//!     (the reference's error from theirs), within 3 SE.
//!
//! ```sh
//! CAROM_VALIDATION_DOCS=docs/validation.md cargo test --test integration validation_transport:: \
//!     -- --include-ignored --nocapture --test-threads=1
//! ```

use std::time::Instant;

use crate::analysis_common;
use crate::validation_common::{fmt_se, Check, Fragment, Row};
use carom_analysis::{AnalysisOptions, Analyzer, Report, RunDescription};
use carom_engine::{Engine, EngineParams, SystemSpec};

/// A run's analysis and what it cost.
struct Measured {
    report: Report,
    collisions: u64,
    seconds: f64,
}

/// `n` discs at packing fraction `phi`, 50 collisions per disc to equilibrate,
/// then `per_disc` collisions per disc with a snapshot every 10.
fn measure(n: usize, phi: f64, seed: u64, per_disc: f64) -> Measured {
    let wall = Instant::now();
    let params = EngineParams::default();
    let mut e = Engine::new(
        SystemSpec::periodic_fluid(n, phi, seed).build().unwrap(),
        params,
    )
    .unwrap();
    let pairs = |per_disc: f64| (per_disc * n as f64 / 2.0).round() as u64;
    e.run_collisions(pairs(50.0)).expect("equilibration");
    let t_eq = e.now();
    let t_c = t_eq / (2.0 * e.stats().pair_collisions as f64 / n as f64);
    let dt = 10.0 * t_c;
    let snapshots = (per_disc / 10.0).round() as u64;
    let t_end = t_eq + snapshots as f64 * dt;
    let s = e.state();
    let run = RunDescription {
        species: s.species.clone(),
        sim_box: s.sim_box,
        restitution: params.restitution,
        collision_stride: 1,
        totals_from_thermo: false,
        t_start: t_eq,
        t_end,
        pair_rate: Some(1.0 / t_c),
        snapshot_interval: Some(dt),
        snapshot_schedule: None,
        gravity: 0.0,
    };
    let opts = AnalysisOptions {
        equilibrate: Some(t_eq),
        ..Default::default()
    };
    let mut a = Analyzer::new(run, opts).unwrap();
    let before = e.stats().pair_collisions;
    analysis_common::feed(&mut e, &mut a, t_eq, dt, snapshots);
    Measured {
        report: a.finish().unwrap(),
        collisions: e.stats().pair_collisions - before,
        seconds: wall.elapsed().as_secs_f64(),
    }
}

#[test]
#[ignore = "long validation (about 2 min): run with --include-ignored"]
fn case10_transport_at_low_density_against_enskog() {
    let mut frag = Fragment::new("10-transport-enskog", "10. Transport at low density");
    for (phi, seed) in [(0.01, 99), (0.05, 100), (0.1, 101), (0.2, 102)] {
        let m = measure(4096, phi, seed, 4000.0);
        let t = m.report.transport.as_ref().expect("a transport report");
        assert_eq!(t.snapshots_mismatched, 0);
        let e = t.enskog.as_ref().expect("Enskog's values");
        let s = &t.species[0];
        let l = t.thermal_conductivity.as_ref().expect("λ");
        let label = format!("φ = {phi}");
        let vs_enskog = |q: &str, v: f64, se: f64, r: f64| {
            Row::new(format!("{q}, {label}"), v, se)
                .reference(r, 0.05 * r)
                .check(Check::Sigma(3.0))
        };
        // D over the window against Enskog (with f_D) plus the growth the 2D tail
        // gives D(t), (kT/m) A ln(t/t₀) (physics.md (14.9)), averaged over the
        // window uniformly in t as the MSD secant averages D(t); the tail's onset
        // t₀ is put between t_c and 10 t_c, the reference is the middle of that
        // range and its half-width the allowance (a model's range, not a
        // measured error).
        let a_theory = s
            .tail_amplitude_theory
            .expect("the mode-coupling amplitude");
        let [ta, tb] = t.window;
        let mean_ln = (tb * tb.ln() - ta * ta.ln()) / (tb - ta) - 1.0 - t.collision_time.ln();
        let growth = |onset: f64| s.vacf_zero / 2.0 * a_theory * (mean_ln - onset.ln());
        let (early, late) = (growth(1.0), growth(10.0));
        frag.row(
            Row::new(
                format!("D (MSD) vs Enskog + tail, {label}"),
                s.diffusion_msd.value,
                s.diffusion_msd.std_error,
            )
            .reference(e.diffusion + 0.5 * (early + late), 0.5 * (early - late))
            .check(Check::Sigma(3.0)),
        );
        frag.row(
            Row::new(
                format!("D (MSD) / D_Enskog, {label}"),
                s.diffusion_msd.value / e.diffusion,
                s.diffusion_msd.std_error / e.diffusion,
            )
            .reference(1.0, 0.0),
        );
        frag.row(vs_enskog(
            "η (Helfand) vs Enskog",
            t.viscosity.value_helfand.value,
            t.viscosity.value_helfand.std_error,
            e.viscosity,
        ));
        frag.row(vs_enskog(
            "λ (Helfand) vs Enskog",
            l.value_helfand.value,
            l.value_helfand.std_error,
            e.thermal_conductivity,
        ));
        let same = |q: &str, d: &carom_analysis::Estimate| {
            Row::new(format!("{q}, {label}"), d.value, d.std_error)
                .reference(0.0, 0.0)
                .check(Check::Sigma(3.0))
        };
        frag.row(same("D(MSD) − D(VACF)", &s.difference));
        frag.row(same("η Helfand − Green–Kubo", &t.viscosity.difference));
        frag.row(same("λ Helfand − Green–Kubo", &l.difference));
        frag.note(format!(
            "{label}, N = {}: {} pair collisions after 50 per disc of equilibration ({:.0} s); \
             t_c = {:.4}, window [{:.3}, {:.3}]; χ = {:.4} from Z; D(MSD) = {}, D(VACF) = {} \
             (Enskog {:.4}); η Helfand {}, Green–Kubo {} (Enskog {:.4}); λ Helfand {}, \
             Green–Kubo {} (Enskog {:.4}); tail amplitude {} against mode coupling {:.4}.",
            t.n,
            m.collisions,
            m.seconds,
            t.collision_time,
            t.window[0],
            t.window[1],
            e.chi,
            fmt_se(s.diffusion_msd.value, s.diffusion_msd.std_error),
            fmt_se(s.diffusion_vacf.value, s.diffusion_vacf.std_error),
            e.diffusion,
            fmt_se(
                t.viscosity.value_helfand.value,
                t.viscosity.value_helfand.std_error
            ),
            fmt_se(
                t.viscosity.value_green_kubo.value,
                t.viscosity.value_green_kubo.std_error
            ),
            e.viscosity,
            fmt_se(l.value_helfand.value, l.value_helfand.std_error),
            fmt_se(l.value_green_kubo.value, l.value_green_kubo.std_error),
            e.thermal_conductivity,
            s.tail_amplitude
                .map_or("n/a".into(), |a| fmt_se(a.value, a.std_error)),
            s.tail_amplitude_theory.unwrap_or(f64::NAN),
        ));
    }
    frag.finish();
}

#[test]
#[ignore = "long validation (about 5 min): run with --include-ignored"]
fn case11_vacf_tail_against_mode_coupling() {
    let mut frag = Fragment::new("11-vacf-tail", "11. The VACF's long-time tail");
    let m = measure(40_000, 0.3, 111, 2000.0);
    let t = m.report.transport.as_ref().expect("a transport report");
    assert_eq!(t.snapshots_mismatched, 0);
    let s = &t.species[0];
    let a = s.tail_amplitude.expect("a tail amplitude");
    let theory = s
        .tail_amplitude_theory
        .expect("the mode-coupling amplitude");
    let theory_se = s.tail_amplitude_theory_std_error.unwrap_or(0.0);
    frag.row(
        Row::new(
            "tail amplitude A, φ = 0.3, N = 40 000",
            a.value,
            a.std_error,
        )
        .reference(theory, theory_se)
        .check(Check::Sigma(3.0)),
    );
    let window: Vec<String> = s
        .lags
        .iter()
        .zip(&s.vacf)
        .filter(|(&tau, _)| tau >= t.window[0])
        .map(|(&tau, &c)| format!("{:.3}: {:.5}", tau / t.collision_time, c * tau))
        .collect();
    frag.note(format!(
        "N = {}, {} pair collisions ({:.0} s), t_c = {:.4}; D = {}, η = {}; \
         τ C(τ)/C(0) at τ/t_c = {}.",
        t.n,
        m.collisions,
        m.seconds,
        t.collision_time,
        fmt_se(s.diffusion_vacf.value, s.diffusion_vacf.std_error),
        fmt_se(
            t.viscosity.value_helfand.value,
            t.viscosity.value_helfand.std_error
        ),
        window.join(", ")
    ));
    frag.finish();
}
