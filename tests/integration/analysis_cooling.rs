//! `carom analyze` on cooling granular gases, fed straight from the engine:
//! the energy budget, Haff's law and the Sonine coefficient a2 of the homogeneous
//! cooling state (physics.md §8).

use crate::analysis_common::{analyse, analyse_state, fluid};
use crate::stats_common::assert_within;
use carom_analysis::AnalysisOptions;
use carom_core::Restitution;
use carom_engine::{Engine, EngineParams, Velocities};

/// Normal restitution `e` with the TC model's duration `tc`.
fn cooling(e: f64, tc: f64) -> EngineParams {
    EngineParams {
        restitution: Restitution::Normal(e),
        tc,
        ..Default::default()
    }
}

#[test]
fn cooling_granular_gas_closes_its_energy_budget() {
    let spec = fluid(1024, 0.1, 9, Velocities::MaxwellBoltzmann);
    let params = cooling(0.9, 1e-6);
    let r = analyse(spec, params, 40.0, 1.0, AnalysisOptions::default());
    assert!(!r.elastic);
    let inel = r.inelastic.as_ref().unwrap();
    let e = inel.energy.as_ref().unwrap();
    assert!(e.final_ < 0.5 * e.initial, "{e:?}");
    assert!(e.relative_residual.abs() < 1e-9, "{e:?}");
    // (Haff's law itself: `haff_law_holds_from_an_equilibrated_start`.)
    assert!(inel.haff.is_some());
    assert_eq!(r.temperature.series.len(), 41);
    assert!(r.enskog.is_none());
}

/// A cooling granular gas (data/granular-cooling.json's e = 0.9, η = 0.25, at
/// small N): its velocities pooled over snapshots at different temperatures are
/// not Maxwellian, but scaled by each snapshot's thermal speed they are (to the
/// resolution of the tests), and their Sonine a2 is small and negative, near
/// van Noije & Ernst's −0.027 for e = 0.9 (physics.md (8.4)).
#[test]
fn a_cooling_gas_is_tested_in_its_homogeneous_cooling_state() {
    let spec = fluid(1024, 0.25, 4, Velocities::MaxwellBoltzmann);
    let params = cooling(0.9, 1e-5);
    let opts = AnalysisOptions {
        equilibrate: Some(2.0),
        every: Some(2.0),
        ..Default::default()
    };
    let r = analyse(spec, params, 20.0, 0.5, opts);
    let kt = &r.temperature;
    assert!(
        kt.kt_final.unwrap() < 0.4 * kt.kt_initial.unwrap(),
        "{kt:?}"
    );
    let mb = &r.maxwell_boltzmann[0];
    assert!(mb.scaled_to_snapshot_temperature);
    assert!(mb.passed, "{:?} {:?} {:?}", mb.chi_square, mb.ks, mb.ks_vx);
    let a2 = r.inelastic.as_ref().unwrap().sonine.as_ref().unwrap();
    let theory = a2.theory.unwrap();
    assert!((theory + 0.0269).abs() < 1e-3, "{a2:?}");
    // Measured −0.025 ± 0.006 over 10 snapshots (seed 4).
    assert!(
        a2.a2 < 0.0 && (a2.a2 - theory).abs() < 4.0 * a2.std_error,
        "{a2:?}"
    );
    assert!(a2.std_error < 0.01, "{a2:?}");
}

/// a2 of the homogeneous cooling state of smooth inelastic hard spheres in d
/// dimensions, van Noije & Ernst, Granular Matter 1, 57 (1998) (reviewed by Santos &
/// Montanero, Granular Matter 11, 157, 2009):
/// a2 = 16(1 − e)(1 − 2e²) / (9 + 24d − (41 − 8d)e + 30(1 − e)e²). Written here in
/// its d-dimensional form, independently of the analysis's 2D transcription; at
/// d = 3 it must give the classic 3D result 16(1 − e)(1 − 2e²)/(81 − 17e + 30e²(1 − e)).
fn a2_van_noije_ernst(e: f64, d: f64) -> f64 {
    16.0 * (1.0 - e) * (1.0 - 2.0 * e * e)
        / (9.0 + 24.0 * d - (41.0 - 8.0 * d) * e + 30.0 * (1.0 - e) * e * e)
}

/// The a2 and the Haff time the report uses, at e = 0.5, 0.8 and 0.9, against the
/// d-dimensional van Noije–Ernst formula at d = 2 and 1/t0 = (1 − e²)(1 + 3a2/16)ω0/4
/// (physics.md §8), to rounding. (A sign slip in the a2 formula, 1 − 2e² → 1 + 2e²,
/// moves a2(0.9) from −0.0269 to +0.114.)
#[test]
fn the_reported_a2_and_haff_time_follow_van_noije_ernst() {
    for e in [0.3, 0.9] {
        let three_d =
            16.0 * (1.0 - e) * (1.0 - 2.0 * e * e) / (81.0 - 17.0 * e + 30.0 * e * e * (1.0 - e));
        assert!((a2_van_noije_ernst(e, 3.0) - three_d).abs() < 1e-15);
    }
    assert!((a2_van_noije_ernst(0.9, 2.0) + 0.0269).abs() < 1e-4);
    for (k, e) in [0.5, 0.8, 0.9].into_iter().enumerate() {
        let params = cooling(e, 1e-6);
        let spec = fluid(256, 0.1, 30 + k as u64, Velocities::MaxwellBoltzmann);
        // Every snapshot: the default spacing (5 collisions per disc, counted)
        // leaves one in this short window, and a2 needs two.
        let opts = AnalysisOptions {
            every: Some(0.5),
            ..Default::default()
        };
        let r = analyse(spec, params, 4.0, 0.5, opts);
        let inel = r.inelastic.as_ref().unwrap();
        let want = a2_van_noije_ernst(e, 2.0);
        let h = inel.haff.as_ref().unwrap();
        let theory = inel.sonine.as_ref().unwrap().theory.unwrap();
        for (what, got) in [("Haff a2", h.a2), ("Sonine theory", theory)] {
            assert!(
                (got - want).abs() <= 1e-15,
                "e = {e}: {what} {got} vs {want}"
            );
        }
        let inv_t0 =
            (1.0 - e * e) * (1.0 + 3.0 * want / 16.0) * h.collision_frequency_initial / 4.0;
        assert!((h.t0 * inv_t0 - 1.0).abs() < 1e-14, "e = {e}: {h:?}");
    }
}

/// Haff's law (physics.md (8.2)–(8.4)) as `carom analyze` reports it: N = 1024 at
/// η = 0.1, e = 0.9, 16 seeds, each melted elastically first (20 collisions per
/// disc: from the lattice, the collision rate starts low and the report's constant
/// ω biased the ratio by −1.5 % at t = 10 over 8 seeds), cooled to t = 40. The mean of
/// the reported kT_final/kT_Haff is 1 within k = 4 standard errors of the seeds'
/// spread: measured 1.0056 ± 0.0032 (one run's SD ≈ 1.3 %, so the single run's
/// 1.0235 that issue 39 quotes was noise plus the lattice start). A sign slip in
/// a2 (1 − 2e² → 1 + 2e²) speeds the predicted cooling by 2.7 %: measured
/// 1.0324 ± 0.0032, 10 SE.
#[test]
fn haff_law_holds_from_an_equilibrated_start() {
    let params = cooling(0.9, 1e-6);
    let ratios: Vec<f64> = (1..=16)
        .map(|seed| {
            let spec = fluid(1024, 0.1, seed, Velocities::MaxwellBoltzmann);
            let mut e = Engine::new(spec.build().unwrap(), EngineParams::default()).unwrap();
            e.run_collisions(20 * 1024).unwrap();
            let mut state = e.state();
            state.time = 0.0;
            let r = analyse_state(state, params, 40.0, 1.0, AnalysisOptions::default(), None);
            r.inelastic.unwrap().haff.unwrap().ratio
        })
        .collect();
    let n = ratios.len() as f64;
    let mean = ratios.iter().sum::<f64>() / n;
    let var = ratios.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0);
    let se = (var / n).sqrt();
    eprintln!("Haff ratio over {n} seeds: {mean} ± {se}");
    assert_within(
        "Haff kT_final/kT_Haff, mean of 16 seeds",
        mean,
        se,
        1.0,
        0.0,
        4.0,
    );
}

/// Mean and standard error of the mean of independent values.
fn mean_se(x: &[f64]) -> (f64, f64) {
    let n = x.len() as f64;
    let m = x.iter().sum::<f64>() / n;
    let var = x.iter().map(|v| (v - m).powi(2)).sum::<f64>() / (n - 1.0);
    (m, (var / n).sqrt())
}

/// a2 = ⟨v⁴⟩/(2⟨v²⟩²) − 1 of equal-mass discs (physics.md (8.5)).
fn a2_of(state: &carom_engine::State) -> f64 {
    let n = state.velocities.len() as f64;
    let (s2, s4) = state.velocities.iter().fold((0.0, 0.0), |(a, b), v| {
        let x = v.length_squared();
        (a + x, b + x * x)
    });
    (s4 / n) / (2.0 * (s2 / n).powi(2)) - 1.0
}

/// a2 of the homogeneous cooling state, measured by the engine, against the
/// second Sonine approximation the report uses (`theory_second_order`, a
/// Boltzmann result: judged in a very dilute gas, η = 0.005, N = 200, L ≈ 178σ).
/// The box must be small against the critical size of the shear instability,
/// L_c = 2π/k_c with ν k_c² = ζ/2 and the dilute viscosity, which grows like the
/// mean free path: at η = 0.005, L_c ≈ 1240σ (e = 0.9), 900σ (0.8), 620σ (0.5).
/// Nearer L_c the long-wavelength flows raise a2: at e = 0.5 and η = 0.02 (L_c ≈
/// 156σ) it measured 0.0711 ± 0.0011, 0.0768 ± 0.0006 and 0.0802 ± 0.0006 at
/// L/L_c = 0.40, 0.57 and 0.81 (N = 100, 200, 400), and 0.0708 ± 0.0008 here
/// (L/L_c = 0.29; docs/validation.md, "a2 of the cooling state"). Each seed is
/// melted elastically (20 collisions per disc), cooled 10 collisions per disc into
/// the cooling state, then sampled 20 times, every 5 collisions per disc, its
/// velocities rescaled to kT = 1 after every sample (the cooling state is scale
/// free; the TC time stays negligible). Every block must lose at least half the
/// energy a homogeneous gas loses, K'/K < exp(−(1 − e²)c/4) for c collisions per
/// disc: longer runs of a small box leave the cooling state (after ≈ 400
/// collisions per disc at e = 0.8 one seed kept a few discs colliding, nearly
/// elastically under the TC rule, while the rest streamed freely). A snapshot of N
/// discs of fixed total energy has a2 = −1/N in equilibrium (physics.md §6): the
/// elastic control must give it, and the cooling values are corrected by it.
/// Pass: within 3 SE (over the seeds) + half the step from the first to the second
/// Sonine order (the truncation error of the reference: the independent DSMC values
/// of the issue, −0.0299 ± 0.0003, −0.0264 ± 0.0002 and ≈ 0.071 at e = 0.9, 0.8,
/// 0.5, lie within it). Run: `cargo test --release --test integration analysis_cooling:: --
/// --ignored a2_of_the_cooling_state --nocapture` (two threads, ≈ 20 min).
#[test]
#[ignore]
fn a2_of_the_cooling_state_follows_the_second_sonine_approximation() {
    const N: usize = 200;
    const ETA: f64 = 0.005;
    const SAMPLES: usize = 20;
    let one_seed = |e: f64, seed: u64| -> f64 {
        let spec = fluid(N, ETA, 100 + seed, Velocities::MaxwellBoltzmann);
        let mut eng = Engine::new(spec.build().unwrap(), EngineParams::default()).unwrap();
        eng.run_collisions(10 * N as u64).unwrap();
        let params = if e < 1.0 {
            cooling(e, 1e-5)
        } else {
            EngineParams::default()
        };
        let mut eng = Engine::new(eng.state(), params).unwrap();
        eng.run_collisions(5 * N as u64).unwrap();
        let kinetic = |s: &carom_engine::State| -> f64 {
            s.velocities.iter().map(|v| v.length_squared()).sum()
        };
        // 5 collisions per disc: K falls by exp(−(1 − e²)·5/2) in the cooling state.
        let slowest = (-(1.0 - e * e) * 5.0 / 4.0).exp();
        let mut k_last = kinetic(&eng.state());
        let mut sum = 0.0;
        for _ in 0..SAMPLES {
            eng.run_collisions(5 * N as u64 / 2).unwrap();
            let mut state = eng.state();
            sum += a2_of(&state);
            let k = kinetic(&state);
            assert!(
                e == 1.0 || k < slowest * k_last,
                "e = {e}, seed {seed}: left the cooling state (K'/K = {})",
                k / k_last
            );
            let f = (N as f64 / k).sqrt();
            state.velocities.iter_mut().for_each(|v| *v *= f);
            k_last = N as f64;
            eng = Engine::new(state, params).unwrap();
        }
        sum / SAMPLES as f64
    };
    // The seeds of one case, shared out over two threads.
    let samples = |e: f64, seeds: u64| -> Vec<f64> {
        std::thread::scope(|s| {
            let half = [1, 2].map(|k| {
                let one_seed = &one_seed;
                s.spawn(move || {
                    (1..=seeds)
                        .filter(|seed| seed % 2 == k % 2)
                        .map(|seed| one_seed(e, seed))
                        .collect::<Vec<_>>()
                })
            });
            half.into_iter().flat_map(|h| h.join().unwrap()).collect()
        })
    };
    let (control, se) = mean_se(&samples(1.0, 400));
    eprintln!(
        "e = 1: a2 = {control:.5} ± {se:.5} (−1/N = {:.5})",
        -1.0 / N as f64
    );
    assert_within(
        "elastic a2 at N = 200",
        control,
        se,
        -1.0 / N as f64,
        0.0,
        3.0,
    );
    // The second Sonine order (physics.md (8.8)) and the DSMC values.
    let mut failed = Vec::new();
    for (e, second, dsmc) in [
        (0.9, -0.02967, "−0.0299 ± 0.0003"),
        (0.8, -0.02551, "−0.0264 ± 0.0002"),
        (0.5, 0.06545, "≈ 0.070–0.072"),
    ] {
        let (a2, se) = mean_se(&samples(e, 1600));
        let corrected = a2 + 1.0 / N as f64;
        let first = a2_van_noije_ernst(e, 2.0);
        let truncation = (second - first).abs() / 2.0;
        let pass = (corrected - second).abs() <= 3.0 * se + truncation;
        eprintln!(
            "e = {e}: a2 + 1/N = {corrected:.5} ± {se:.5}; second Sonine {second} ± \
             {truncation:.4}, first Sonine {first:.5}, DSMC {dsmc}: {}",
            if pass { "pass" } else { "FAIL" }
        );
        if !pass {
            failed.push(e);
        }
    }
    assert!(
        failed.is_empty(),
        "a2 off the second Sonine order at e = {failed:?}"
    );
}
