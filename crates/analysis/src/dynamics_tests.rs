//! Tests of the dynamics accumulator: discs in free flight through periodic wraps
//! (every quantity known in closed form) and a Gaussian random walk of known D.

use super::*;
use crate::RunDescription;
use carom_core::{Restitution, Species};
use rand::SeedableRng;
use rand_distr::{Distribution, StandardNormal};
use rand_pcg::Pcg64;

/// A periodic 10 × 10 run over [0, t_end] with snapshots every `interval`.
fn run(species: Vec<Species>, t_end: f64, interval: f64) -> RunDescription {
    RunDescription {
        species,
        sim_box: SimBox::periodic(10.0, 10.0),
        restitution: Restitution::Elastic,
        collision_stride: 1,
        totals_from_thermo: false,
        t_start: 0.0,
        t_end,
        pair_rate: None,
        snapshot_interval: Some(interval),
        snapshot_schedule: None,
        gravity: 0.0,
    }
}

fn close(a: f64, b: f64, rel: f64) -> bool {
    (a - b).abs() <= rel * b.abs().max(1e-300)
}

/// Five discs (species 0: three, species 1: two) in free flight, fast enough to
/// cross the 10 × 10 box many times in 20; snapshots at every block start b =
/// 0 … 20 (T = 1) and at b + 1/4. Each snapshot gives the wrapped position r =
/// (u₀ + v t) mod L and image n = ⌊(u₀ + v t)/L⌋, fed as r + nL. Then exactly
/// Δu = vτ: MSD_s(τ) = ⟨|v|²⟩_s τ², α₂ = ⟨|v|⁴⟩/(2⟨|v|²⟩²) − 1 at every τ > 0,
/// C(τ) = ⟨|v|²⟩_s, F_s = ⟨J₀(k*|v|τ)⟩_s. The lags: level 0 m = 0 … 15 with
/// j = 0, 1 (m + j/4; 32), and 21 blocks need level 1 (2⁰·16 < 21) at m = 2q,
/// q = 8 … 15, of which 16, 18, 20 fit: 35 lags.
#[test]
fn free_flight_through_wraps_is_ballistic() {
    let species = vec![Species::new(3, 0.5, 1.0), Species::new(2, 0.5, 4.0)];
    let r = run(species, 20.0, 1.0);
    let mut d = Dynamics::new(
        (&r.species, &r.sim_box),
        [r.t_start, 0.0, r.t_end],
        r.snapshot_interval,
        1.0,
    );
    let species_of = [0u16, 1, 0, 1, 0];
    let u0 = [(1.0, 2.0), (5.5, 7.25), (9.0, 0.5), (3.3, 3.3), (0.1, 8.8)];
    let v = [
        (3.1, -1.7),
        (-0.4, 2.2),
        (0.0, -5.3),
        (1.5, 1.5),
        (-2.6, 0.9),
    ];
    let l = 10.0;
    let mut times: Vec<f64> = (0..=20).flat_map(|b| [b as f64, b as f64 + 0.25]).collect();
    times.pop(); // 20.25 is after the end.
    let mut wrapped_somewhere = false;
    for &t in &times {
        let (mut ux, mut uy) = (vec![], vec![]);
        for (p, w) in u0.iter().zip(&v) {
            let (x, y) = (p.0 + w.0 * t, p.1 + w.1 * t);
            let (nx, ny) = ((x / l).floor(), (y / l).floor());
            wrapped_somewhere |= nx != 0.0 || ny != 0.0;
            ux.push(x - nx * l + nx * l);
            uy.push(y - ny * l + ny * l);
        }
        let vx: Vec<f64> = v.iter().map(|w| w.0).collect();
        let vy: Vec<f64> = v.iter().map(|w| w.1).collect();
        d.add(t, t.fract() == 0.0, &species_of, [&ux, &uy], [&vx, &vy]);
    }
    assert!(wrapped_somewhere);
    let rep = d.report(f64::NAN).unwrap();
    assert_eq!(rep.origins, 21);
    assert_eq!((rep.origins_per_level, rep.levels), (16, 2));
    let k = rep.k_star.unwrap();
    let mut want_lags: Vec<f64> = (0..16)
        .flat_map(|m| [m as f64, m as f64 + 0.25])
        .chain([16.0, 18.0, 20.0])
        .collect();
    want_lags.sort_by(f64::total_cmp);
    for s in &rep.species {
        let members: Vec<usize> = (0..5)
            .filter(|&i| species_of[i] as usize == s.species)
            .collect();
        let v2 = |i: usize| v[i].0 * v[i].0 + v[i].1 * v[i].1;
        let mean = |f: &dyn Fn(usize) -> f64| {
            members.iter().map(|&i| f(i)).sum::<f64>() / members.len() as f64
        };
        let (m2, m4) = (mean(&v2), mean(&|i| v2(i) * v2(i)));
        assert_eq!(s.lag.len(), want_lags.len());
        for (i, &tau) in s.lag.iter().enumerate() {
            assert!(close(tau, want_lags[i], 1e-12), "{tau} vs {}", want_lags[i]);
            assert!(close(s.vacf[i], m2, 1e-12));
            assert!(close(s.vacf_normalised[i], 1.0, 1e-12));
            if tau == 0.0 {
                assert_eq!(s.msd[i], 0.0);
                assert_eq!(s.fs[i], 1.0);
                continue;
            }
            assert!(close(s.msd[i], m2 * tau * tau, 1e-9), "MSD at {tau}");
            let a2 = m4 / (2.0 * m2 * m2) - 1.0;
            assert!((s.alpha2[i] - a2).abs() < 1e-8, "α₂ at {tau}");
            let fs = mean(&|j| libm::j0(k * v2(j).sqrt() * tau));
            assert!((s.fs[i] - fs).abs() < 1e-9, "F_s at {tau}");
        }
        // Samples: the species' discs times the pairings of the key; lag 0 has
        // one per origin (21).
        assert_eq!(s.samples[0], 21 * members.len() as u64);
    }
}

/// 300 walkers with independent Gaussian steps of variance 2D per component per
/// unit time (D = 0.5): MSD = 4Dτ exactly in expectation, so the fitted D is
/// within 3 of its standard errors of 0.5 (the error widened for overlapping
/// segments, physics.md §13), and the error is neither zero nor larger than a
/// tenth of D. 401 blocks (T = 1) give 6 levels (2⁴·16 = 256 <
/// 401 ≤ 512).
#[test]
fn a_random_walk_has_its_diffusion_coefficient() {
    let dc: f64 = 0.5;
    let n = 300;
    let r = run(vec![Species::new(n, 0.5, 1.0)], 400.0, 1.0);
    let mut d = Dynamics::new(
        (&r.species, &r.sim_box),
        [r.t_start, 0.0, r.t_end],
        r.snapshot_interval,
        1.0,
    );
    let mut rng = Pcg64::seed_from_u64(36);
    let (mut ux, mut uy) = (vec![5.0; n], vec![5.0; n]);
    let zero = vec![0.0; n];
    let species_of = vec![0u16; n];
    let step = (2.0 * dc).sqrt();
    for b in 0..=400 {
        if b > 0 {
            for i in 0..n {
                let (gx, gy): (f64, f64) = (
                    StandardNormal.sample(&mut rng),
                    StandardNormal.sample(&mut rng),
                );
                ux[i] += step * gx;
                uy[i] += step * gy;
            }
        }
        d.add(b as f64, true, &species_of, [&ux, &uy], [&zero, &zero]);
    }
    let rep = d.report(f64::NAN).unwrap();
    assert_eq!(rep.levels, 6);
    let f = rep.species[0].diffusion.clone().unwrap();
    eprintln!("D = {} ± {} over [{}, {}]", f.d, f.std_error, f.t_a, f.t_b);
    assert!(f.std_error > 0.0 && f.std_error < 0.1 * dc, "{f:?}");
    assert!((f.d - dc).abs() < 3.0 * f.std_error, "{f:?}");
    assert!(f.points >= 5 && f.segments >= 3, "{f:?}");
}
