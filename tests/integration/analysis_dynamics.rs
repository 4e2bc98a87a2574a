//! The single-disc dynamics of `carom analyze` (physics.md §13) fed straight from
//! the engine: in a dilute gas, over lags much shorter than the mean free time,
//! discs fly freely, so the MSD is ⟨v²⟩τ² and F_s(k, τ) is the free-particle
//! Gaussian exp(−k² kT τ²/(2m)) (the Maxwell average of J₀(k v τ) in 2D).

use crate::analysis_common::fluid;
use carom_analysis::{AnalysisOptions, Analyzer, RunDescription};
use carom_engine::{Engine, EngineParams, Event, Velocities};

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
        snapshot_schedule: None,
        gravity: 0.0,
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
            Event::Pause { .. } => {}
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

/// Unwrapped position of disc i of [`free_flight_log`] at t.
fn unwrapped(i: usize, t: f64) -> (f64, f64) {
    (1.0 + 2.5 * i as f64 + V[i].0 * t, 5.0 + V[i].1 * t)
}

/// A log of four discs in free flight through a periodic 10 × 10 box, snapshots
/// (wrapped positions and images) every `gap` over [0, 12] (`snapshot_interval`
/// = `gap`).
fn free_flight_log(name: &str, gap: f64) -> std::path::PathBuf {
    use carom_core::{DVec2, SimBox, Species};
    use carom_engine::State;
    use carom_log::{
        LogOptions, LogWriter, RunFacts, RunMetadata, Stop, StopReason, SummaryMetadata, Thermo,
        WriterOptions, WriterPosition,
    };
    let path =
        std::env::temp_dir().join(format!("carom-dynamics-{}-{name}.mcap", std::process::id()));
    let species = Species::new(4, 0.5, 1.0);
    let sim_box = SimBox::periodic(10.0, 10.0);
    let log = LogOptions {
        collisions: false,
        snapshot_interval: Some(gap),
        thermo_interval: Some(gap),
        checkpoint_interval: None,
        scene_interval: None,
        ..LogOptions::default()
    };
    let meta = RunMetadata {
        log_format: carom_log::LOG_FORMAT_VERSION.into(),
        carom_version: "0.0.0-test".into(),
        config: "not json".into(),
        seed: 1,
        start_time: String::new(),
        n_discs: 4,
        stop: Stop::Time(12.0),
        max_time_without_collision: None,
        log: log.clone(),
        resumed_from: None,
        resumed_at: None,
        run_facts: Some(RunFacts::new(
            &[species],
            &sim_box,
            &EngineParams::default(),
            &log,
        )),
    };
    let options = WriterOptions::from_log_options(&log);
    let mut w =
        LogWriter::create(&path, options, &meta.to_map(), WriterPosition::default()).unwrap();
    let kinetic: f64 = V.iter().map(|v| 0.5 * (v.0 * v.0 + v.1 * v.1)).sum();
    let steps = (12.0 / gap).round() as usize;
    for k in 0..=steps {
        let t = k as f64 * gap;
        w.write_thermo(&Thermo {
            time: t,
            kinetic_energy: kinetic,
            temperature: 0.0,
            collisions: 0,
            pair_collisions: 0,
            wall_collisions: 0,
            energy_lost: 0.0,
            virial_sum: 0.0,
            wall_impulse: 0.0,
            pressure: None,
            z: None,
            collision_rate: None,
            ..Default::default()
        })
        .unwrap();
        w.write_snapshot(&State {
            sim_box,
            species: vec![species],
            species_of: vec![0; 4],
            positions: (0..4)
                .map(|i| {
                    let (x, y) = unwrapped(i, t);
                    DVec2::new(x.rem_euclid(10.0), y.rem_euclid(10.0))
                })
                .collect(),
            velocities: V.iter().map(|v| DVec2::new(v.0, v.1)).collect(),
            images: (0..4)
                .map(|i| {
                    let (x, y) = unwrapped(i, t);
                    [(x / 10.0).floor() as i32, (y / 10.0).floor() as i32]
                })
                .collect(),
            time: t,
        })
        .unwrap();
    }
    let summary = SummaryMetadata {
        end_time: String::new(),
        stop_reason: StopReason::Time,
        error: None,
        sim_time: 12.0,
        pair_collisions: 0,
        wall_collisions: 0,
        logged_collisions: 0,
        kinetic_energy: kinetic,
        energy_lost: 0.0,
        virial_sum: 0.0,
        wall_seconds: 1.0,
        collisions_per_second: 1.0,
        potential_energy: None,
    };
    w.finish(&summary.to_map()).unwrap();
    path
}

/// Velocities of the four discs of [`free_flight_log`]: max speed bound
/// √(2K/m) = √(9 + 1 + 4 + 5) = √19 ≈ 4.36.
const V: [(f64, f64); 4] = [(3.0, 0.0), (0.0, -1.0), (-1.2, 1.6), (1.5, -1.5)];

/// Snapshots 3 apart, longer than the box's half-width over the largest speed
/// (√(2K/m) = √19 ≈ 4.36: 13 > L/2 = 5, physics.md (12.2)), so only the images
/// can unwrap them: the MSD read from the file is ⟨v²⟩τ² = (9 + 1 + 4 + 4.5)/4 τ²
/// = 4.625 τ² exactly (disc 0 crosses the box 3.6 times), no gap is counted as
/// ambiguous, and the lags are the multiples of 3 up to 12.
#[test]
fn a_log_is_unwrapped_through_its_images() {
    use carom_analysis::analyze_log;
    struct Quiet;
    impl carom_analysis::ReadObserver for Quiet {
        fn pass(&mut self, _: &'static str) {}
        fn progress(&mut self, _: carom_log::ReadProgress) {}
        fn warn(&mut self, _: &str) {}
    }
    let opts = AnalysisOptions {
        equilibrate: Some(0.0),
        ..Default::default()
    };
    let path = free_flight_log("images", 3.0);
    let got = analyze_log(&path, opts, &mut Quiet);
    let _ = std::fs::remove_file(&path);
    let d = got.unwrap().0.dynamics.unwrap();
    assert_eq!(d.ambiguous_gaps, 0);
    let s = &d.species[0];
    assert_eq!(s.lag, vec![0.0, 3.0, 6.0, 9.0, 12.0]);
    for (tau, msd) in s.lag.iter().zip(&s.msd) {
        let want = 4.625 * tau * tau;
        assert!(
            (msd - want).abs() <= 1e-9 * want.max(1.0),
            "MSD({tau}) = {msd} vs {want}"
        );
    }
}
