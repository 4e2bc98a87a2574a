//! Validation of uniform gravity (physics.md §15), engine only (no log), both
//! `#[ignore]`d (about a minute each; results in docs/validation.md):
//!
//! 1. Barometric law: 300 discs in a 5000 × 120 box (periodic x, walls y),
//!    g = 0.1, dilute (η ≈ 0.005 at the floor): the maximum-likelihood β_g of the
//!    heights (15.8), from 20 blocks of snapshots, against m g/kT with kT = 2⟨K⟩/f.
//!    Pass: within 3 standard errors.
//! 2. Hydrostatic balance: 800 discs in a 40-wide column (g = 0.13 at kT = 1, η
//!    from ≈ 0.5 at the floor to 0 at the top): in 1σ bins at least 3σ above the
//!    floor and 2σ below the ceiling, n(y) kT(y) Z(η(y)) (kT(y) = ⟨m v²⟩/2 of the
//!    bin's discs, Henderson's Z, (7.1) with (7.6)) against the ceiling's measured
//!    pressure (its wall impulse per length and time: the column touches it) plus the
//!    weight above, m g N_above(y)/L_x (15.7), time averaged. Pass: each bin with η > 0.02
//!    within 3 SE + 3 % (Henderson's Z is within about 1 % of Kolafa–Rottner up to
//!    η = 0.6; the local-density approximation ignores gradients over σ).
//!
//! Both start from a lattice filling the box; falling releases potential energy, so
//! the state is equilibrated, its velocities scaled back to kT = 1 and equilibrated
//! again, twice, before measuring.

use carom_core::gravity::barometric_beta;
use carom_core::observables::degrees_of_freedom;
use carom_core::rates::henderson_contact_value;
use carom_core::{Boundary, DVec2, SimBox, Species};
use carom_engine::{Engine, EngineParams, Placement, State, SystemSpec, Velocities};

/// A column of `n` discs (σ = 1, m = 1) in an `lx` × `ly` box, periodic x, walls
/// y, in the field `g`: run for `settle`, brought back to kT = 1, twice, then run
/// for `settle` once more (see the module doc).
fn settled(n: usize, lx: f64, ly: f64, g: f64, settle: f64) -> Engine {
    let spec = SystemSpec {
        species: vec![Species::reference(n)],
        sim_box: SimBox {
            size: DVec2::new(lx, ly),
            boundary: [Boundary::Periodic, Boundary::Walls { restitution: 1.0 }],
        },
        temperature: 1.0,
        seed: 17,
        placement: Placement::Lattice,
        velocities: Velocities::MaxwellBoltzmann,
    };
    let params = EngineParams {
        gravity: g,
        ..EngineParams::default()
    };
    let mut state: State = spec.build().unwrap();
    for _ in 0..2 {
        let mut e = Engine::new(state, params).unwrap();
        e.run_until(settle).unwrap();
        state = e.state();
        let kt = 2.0 * state.kinetic_energy() / degrees_of_freedom(n, &state.sim_box) as f64;
        for v in state.velocities.iter_mut() {
            *v /= kt.sqrt();
        }
        state.time = 0.0;
    }
    let mut e = Engine::new(state, params).unwrap();
    e.run_until(settle).unwrap();
    e
}

/// Mean and standard error of `x`.
fn mean_se(x: &[f64]) -> (f64, f64) {
    let n = x.len() as f64;
    let m = x.iter().sum::<f64>() / n;
    let var = x.iter().map(|v| (v - m) * (v - m)).sum::<f64>() / (n - 1.0);
    (m, (var / n).sqrt())
}

#[test]
#[ignore = "about a minute; run with --ignored, results in docs/validation.md"]
fn a_dilute_atmosphere_follows_the_barometric_law() {
    let (n, lx, ly, g) = (300, 5000.0, 120.0, 0.1);
    let mut e = settled(n, lx, ly, g, 4000.0);
    let f = degrees_of_freedom(n, e.sim_box()) as f64;
    let (blocks, per_block, dt) = (20, 100, 10.0);
    let (mut betas, mut kts) = (Vec::new(), Vec::new());
    let mut t = e.now();
    for _ in 0..blocks {
        let (mut sum_y, mut count, mut sum_k) = (0.0, 0usize, 0.0);
        for _ in 0..per_block {
            t += dt;
            e.run_until(t).unwrap();
            let s = e.state();
            sum_y += s.positions.iter().map(|p| p.y - 0.5).sum::<f64>();
            count += n;
            sum_k += s.kinetic_energy();
        }
        betas.push(barometric_beta(sum_y / count as f64, ly - 1.0));
        kts.push(2.0 * sum_k / per_block as f64 / f);
    }
    let (beta, se) = mean_se(&betas);
    let (kt, kt_se) = mean_se(&kts);
    let expected = g / kt;
    let z = (beta - expected) / se;
    println!(
        "barometric: N = {n}, {lx} × {ly}, g = {g}: β_g fitted {beta:.5} ± {se:.5}, \
         m g/kT = {expected:.5} (kT = {kt:.4} ± {kt_se:.4}); deviation {z:+.2} SE, \
         relative {:+.2} %; floor η ≈ {:.4}",
        100.0 * (beta / expected - 1.0),
        n as f64 * expected / lx * std::f64::consts::PI / 4.0
    );
    assert!(z.abs() < 3.0, "β_g off by {z:.2} SE");
}

#[test]
#[ignore = "about a minute; run with --ignored, results in docs/validation.md"]
fn a_dense_column_is_in_hydrostatic_balance_with_the_equation_of_state() {
    let (n, lx, ly, g) = (800, 40.0, 60.0, 0.13);
    let mut e = settled(n, lx, ly, g, 1000.0);
    let f = degrees_of_freedom(n, e.sim_box()) as f64;
    let bins = ly as usize;
    let (blocks, per_block, dt) = (20, 100, 1.0);
    // Per block: the mean number of centres per 1σ bin, and Σ m v²/2 per bin.
    let mut counts = vec![vec![0.0; bins]; blocks];
    let mut kinetic = vec![vec![0.0; bins]; blocks];
    let mut kts = Vec::new();
    // Per block: the ceiling's pressure, its momentum per unit length and time.
    let mut ceiling = Vec::new();
    let mut t = e.now();
    for b in 0..blocks {
        let mut sum_k = 0.0;
        let (t0, j0) = (t, e.stats().wall_impulse[1][1]);
        for _ in 0..per_block {
            t += dt;
            e.run_until(t).unwrap();
            let s = e.state();
            for (p, v) in s.positions.iter().zip(&s.velocities) {
                let k = (p.y.floor() as usize).min(bins - 1);
                counts[b][k] += 1.0 / per_block as f64;
                kinetic[b][k] += 0.5 * v.length_squared() / per_block as f64;
            }
            sum_k += s.kinetic_energy();
        }
        kts.push(2.0 * sum_k / per_block as f64 / f);
        ceiling.push((e.stats().wall_impulse[1][1] - j0) / (lx * (t - t0)));
    }
    let (kt, _) = mean_se(&kts);
    let (p_top, p_top_se) = mean_se(&ceiling);
    let area = std::f64::consts::PI * 0.25;
    let mut checked = 0;
    // Not the layers at the floor and under the ceiling (walls order them).
    for k in 3..bins - 2 {
        // Per block: P from the EOS at the bin's density, and the weight above
        // the bin's middle (half the bin's own discs).
        let (mut p_eos, mut p_w) = (Vec::new(), Vec::new());
        for ((c, kin), &top) in counts.iter().zip(&kinetic).zip(&ceiling) {
            let density = c[k] / lx;
            let eta = density * area;
            let z = 1.0 + 2.0 * eta * henderson_contact_value(eta);
            // The bin's own kT = ⟨m v²⟩/2 (two components per disc).
            let kt_bin = if c[k] > 0.0 { kin[k] / c[k] } else { 0.0 };
            p_eos.push(density * kt_bin * z);
            let above: f64 = c[k + 1..].iter().sum::<f64>() + 0.5 * c[k];
            p_w.push(g * above / lx + top);
        }
        let (pe, se_e) = mean_se(&p_eos);
        let (pw, se_w) = mean_se(&p_w);
        let density = counts.iter().map(|c| c[k]).sum::<f64>() / blocks as f64 / lx;
        let eta_bin = density * area;
        let se = (se_e * se_e + se_w * se_w).sqrt();
        println!(
            "y = {k}–{}: η = {eta_bin:.4}, n kT Z = {pe:.5} ± {se_e:.5}, m g N_above/L_x = \
             {pw:.5} ± {se_w:.5}, relative {:+.2} % ({:+.2} SE)",
            k + 1,
            100.0 * (pe / pw - 1.0),
            (pe - pw) / se
        );
        if eta_bin > 0.02 {
            assert!(
                (pe - pw).abs() < 3.0 * se + 0.03 * pw,
                "bin {k}: EOS pressure {pe} against the weight {pw}"
            );
            checked += 1;
        }
    }
    println!(
        "kT = {kt:.4}; ceiling pressure {p_top:.5} ± {p_top_se:.5}; {checked} bins with η > 0.02 checked"
    );
    assert!(checked >= 10, "only {checked} bins dense enough");
}
