//! The single-disc dynamics of `carom analyze` (physics.md §13) fed straight from
//! the engine: in a dilute gas, over lags much shorter than the mean free time,
//! discs fly freely, so the MSD is ⟨v²⟩τ² and F_s(k, τ) is the free-particle
//! Gaussian exp(−k² kT τ²/(2m)) (the Maxwell average of J₀(k v τ) in 2D).

mod analysis_common;

use analysis_common::fluid;
use carom::analysis::{AnalysisOptions, Analyzer, RunDescription};
use carom::events::{Engine, EngineParams, Event, Velocities};

#[test]
fn a_dilute_gas_is_ballistic_at_short_lags() {
    // 1000 discs at η = 0.05: ω ≈ 0.2 per disc per unit time, so a lag τ ≤ 0.3
    // has ωτ ≤ 0.07: few discs collide within it.
    let state = fluid(1000, 0.05, 11, Velocities::MaxwellBoltzmann)
        .build()
        .unwrap();
    let params = EngineParams::default();
    let (dt, t_end) = (0.05, 25.0);
    let run = RunDescription {
        species: state.species.clone(),
        sim_box: state.sim_box,
        restitution: params.restitution,
        collision_stride: 1,
        totals_from_thermo: false,
        t_start: 0.0,
        t_end,
        pair_rate: None,
        snapshot_interval: Some(dt),
    };
    let mut a = Analyzer::new(run, AnalysisOptions::default()).unwrap();
    let mut engine = Engine::new(state, params).unwrap();
    let steps = (t_end / dt).round() as u64;
    for k in 0..=steps {
        engine.schedule(k as f64 * dt, k).unwrap();
    }
    while let Some(ev) = engine.next_event().unwrap() {
        match ev {
            Event::Pair(p) => a.pair(p.time, p.virial, p.energy_lost),
            Event::Wall(w) => a.wall(w.time, w.impulse, w.energy_lost),
            Event::Scheduled { time, tag } => {
                let s = engine.state();
                let l = s.sim_box.size;
                let (vx, vy): (Vec<f64>, Vec<f64>) =
                    s.velocities.iter().map(|v| (v.x, v.y)).unzip();
                // Unwrapped u = r + n L (physics.md (12.1)).
                let (ux, uy): (Vec<f64>, Vec<f64>) = s
                    .positions
                    .iter()
                    .zip(&s.images)
                    .map(|(p, n)| (p.x + n[0] as f64 * l.x, p.y + n[1] as f64 * l.y))
                    .unzip();
                a.thermo(time, s.kinetic_energy(), Some(0.0));
                a.snapshot(time, &s.species_of, &vx, &vy).unwrap();
                a.motion(time, &s.species_of, [&ux, &uy], [&vx, &vy])
                    .unwrap();
                if tag == steps {
                    break;
                }
            }
        }
    }
    let r = a.finish().unwrap();
    let d = r.dynamics.expect("dynamics");
    let s = &d.species[0];
    let k = d.k_star.unwrap();
    // ⟨v²⟩ = C(0) exactly (the lag-0 pairing); kT/m = C(0)/2 in 2D.
    assert_eq!(s.lag[0], 0.0);
    let v2 = s.vacf[0];
    assert!((v2 - 2.0).abs() < 0.05, "⟨v²⟩ = {v2}");
    let short: Vec<usize> = (1..s.lag.len()).filter(|&i| s.lag[i] <= 0.3).collect();
    assert!(short.len() >= 5);
    let mut tested_decay = false;
    for i in short {
        let tau = s.lag[i];
        let ballistic = v2 * tau * tau;
        assert!(
            (s.msd[i] / ballistic - 1.0).abs() < 0.03,
            "MSD({tau}) = {} vs ⟨v²⟩τ² = {ballistic}",
            s.msd[i]
        );
        let gauss = (-k * k * 0.5 * v2 * tau * tau / 2.0).exp();
        assert!(
            (s.fs[i] - gauss).abs() < 0.02,
            "F_s({k}, {tau}) = {} ± {} vs {gauss}",
            s.fs[i],
            s.fs_std_error[i]
        );
        eprintln!(
            "τ = {tau:.3}: MSD/⟨v²⟩τ² = {:.4}, F_s = {:.4} ± {:.4} vs {gauss:.4}",
            s.msd[i] / ballistic,
            s.fs[i],
            s.fs_std_error[i]
        );
        tested_decay |= gauss < 0.8;
        // Free flight does not change the velocity: C(τ)/C(0) ≈ 1 − O(ωτ).
        assert!(s.vacf_normalised[i] > 0.85, "{}", s.vacf_normalised[i]);
    }
    // k* ≥ π/σ and τ up to 0.3 reach where F_s has decayed.
    assert!(tested_decay, "k* = {k}");
    assert_eq!(d.ambiguous_gaps, 0);
}
