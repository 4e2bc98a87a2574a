//! Inelastic collapse with and without the TC model (case 5 of the validation suite).
//! The suite's tolerances, references and the command that runs it: `super`.

use super::{engine, mono, periodic_spec};
use crate::validation_common::{Check, Fragment, Row};
use carom_core::Restitution;
use carom_engine::{Engine, EngineError, EngineParams, Velocities};

// ===========================================================================
// Case 5: inelastic collapse
// ===========================================================================

/// Dense e = 0.5 system: melt elastically, switch to normal restitution 0.5 with
/// TC duration `tc`, run up to `max` collisions.
fn collapse_run(n: usize, tc: f64, max: u64) -> (Result<u64, EngineError>, Engine, f64) {
    let spec = periodic_spec(mono(n), 0.6, 3, Velocities::MaxwellBoltzmann);
    let mut e = engine(&spec, EngineParams::default());
    e.run_collisions(10 * n as u64).expect("melt");
    let params = EngineParams {
        restitution: Restitution::Normal(0.5),
        tc,
        ..EngineParams::default()
    };
    let mut e = Engine::new(e.state(), params).expect("engine");
    let e0 = e.kinetic_energy();
    let r = e.run_collisions(max);
    (r, e, e0)
}

#[test]
fn case5_inelastic_collapse() {
    let mut frag = Fragment::new("5-collapse", "5 Inelastic collapse (e = 0.5, η = 0.6)");
    let n = 1000;
    let max = 2_000_000;
    let (without, e_without, _) = collapse_run(n, 0.0, max);
    let stalled = match &without {
        Err(EngineError::Stalled {
            time,
            events,
            limit,
            ..
        }) => {
            frag.note(format!(
                "Without TC: EngineError::Stalled after {} collisions at t = {time} \
                 ({events} events at one instant, limit {limit}): \"{}\"",
                e_without.stats().pair_collisions,
                without.as_ref().unwrap_err()
            ));
            true
        }
        other => {
            frag.note(format!(
                "Without TC: {other:?} (expected EngineError::Stalled)"
            ));
            false
        }
    };
    frag.row(
        Row::new(
            "without TC: stops with EngineError::Stalled (1 = yes)",
            stalled as u8 as f64,
            0.0,
        )
        .check(Check::AtLeast(1.0)),
    );
    let msg_ok = without.as_ref().err().is_some_and(|e| {
        e.to_string().contains("inelastic collapse") && e.to_string().contains("tc")
    });
    frag.row(
        Row::new(
            "without TC: message names the collapse and the TC cure (1 = yes)",
            msg_ok as u8 as f64,
            0.0,
        )
        .check(Check::AtLeast(1.0)),
    );
    // TC duration: 10⁻⁴ of the initial mean free time 1/ω ≈ 0.08 τ0 at η = 0.6.
    let tc = 1e-5;
    let (with, e_with, e0) = collapse_run(n, tc, max);
    let done = with.as_ref().copied().unwrap_or(0);
    frag.row(
        Row::new(
            format!("with TC (t_c = {tc}): collisions completed of {max}"),
            done as f64,
            0.0,
        )
        .check(Check::AtLeast(max as f64)),
    );
    let resid = (e0 - e_with.stats().energy_lost - e_with.kinetic_energy()) / e0;
    frag.row(Row::new("with TC: (E0 − Σ losses − E)/E0", resid, 0.0).check(Check::AtMost(1e-9)));
    frag.note(format!(
        "N = {n} at η = 0.6, melted elastically, then normal restitution e = 0.5. With TC the \
         run reaches t = {:.3} with T/T0 = {:.3e} (result {:?}).",
        e_with.now(),
        e_with.kinetic_energy() / e0,
        with.as_ref().map_err(|e| e.to_string())
    ));
    frag.finish();
}
