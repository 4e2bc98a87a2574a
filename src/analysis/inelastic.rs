//! Inelastic runs: the energy budget E(t_end) = E(t_start) − dissipated, and
//! Haff's law of homogeneous cooling T(t) = T0/(1 + t/t0)² with
//! 1/t0 = (1 − e²)(1 + 3a2/16) ω(T0)/4 (physics.md §8), ω(T0) from the measured
//! collision rate scaled as √T. The temperature against time is the temperature
//! report's series. The velocities of a cooling gas are tested in its
//! homogeneous cooling state, each snapshot scaled by its own thermal speed
//! √(kT(t)/m), and their Sonine coefficient a2 = ⟨v⁴⟩/(2⟨v²⟩²) − 1 (mass-weighted,
//! physics.md (8.5)) is compared with van Noije & Ernst's (8.4).

use carom_core::Restitution;

use super::analyzer::Analyzer;
use super::report::{EnergyBudget, HaffReport, InelasticReport, SonineReport};
use super::series::blocked;

/// a2 of the homogeneous cooling state of 2D hard discs with normal restitution
/// `e` (van Noije & Ernst 1998; physics.md (8.4)).
pub(super) fn a2_theory(e: f64) -> f64 {
    16.0 * (1.0 - e) * (1.0 - 2.0 * e * e) / (57.0 - 25.0 * e + 30.0 * e * e * (1.0 - e))
}

/// a2 = ⟨(m v²)²⟩/(2⟨m v²⟩²) − 1 of one snapshot (physics.md (8.5); 0 for a 2D
/// Maxwellian of any temperature); NaN without motion.
pub(super) fn sonine_a2(masses: &[f64], species_of: &[u16], vx: &[f64], vy: &[f64]) -> f64 {
    let (mut s2, mut s4) = (0.0, 0.0);
    for (&s, (&x, &y)) in species_of.iter().zip(vx.iter().zip(vy)) {
        let e = masses[s as usize] * (x * x + y * y);
        s2 += e;
        s4 += e * e;
    }
    let n = vx.len() as f64;
    (s4 / n) / (2.0 * (s2 / n).powi(2)) - 1.0
}

/// Scale each snapshot's velocities by √(kt/kT(t)), kT(t) that snapshot's
/// temperature: the homogeneous cooling state at the common temperature `kt`.
pub(super) fn scale_to(a: &mut Analyzer, kt: f64) {
    let snapshots = a.snapshots_used.len();
    for s in 0..a.speeds.len() {
        let per = a.speeds[s].len() / snapshots.max(1);
        if per == 0 {
            continue;
        }
        for v in [&mut a.speeds[s], &mut a.vx[s], &mut a.vy[s]] {
            for (chunk, &kt_k) in v.chunks_mut(per).zip(&a.snapshot_kt) {
                let f = (kt / kt_k).sqrt();
                if f.is_finite() {
                    chunk.iter_mut().for_each(|x| *x *= f);
                }
            }
        }
    }
}

/// The measured a2 over the snapshots used, with a blocked standard error (the
/// plain error of the mean with fewer than 16 snapshots); `None` with fewer than 2.
fn sonine(a: &Analyzer) -> Option<SonineReport> {
    let x: Vec<f64> = a
        .snapshot_a2
        .iter()
        .copied()
        .filter(|v| v.is_finite())
        .collect();
    if x.len() < 2 {
        return None;
    }
    let (mean, se, is_blocked) = match blocked(&x) {
        Ok(b) => (b.mean, b.std_error, true),
        Err(_) => {
            let n = x.len() as f64;
            let m = x.iter().sum::<f64>() / n;
            let var = x.iter().map(|v| (v - m).powi(2)).sum::<f64>() / (n - 1.0);
            (m, (var / n).sqrt(), false)
        }
    };
    Some(SonineReport {
        a2: mean,
        std_error: se,
        std_error_blocked: is_blocked,
        snapshots: x.len(),
        theory: match a.run.restitution {
            Restitution::Normal(e) if e < 1.0 => Some(a2_theory(e)),
            _ => None,
        },
    })
}

pub(super) fn report(a: &Analyzer) -> InelasticReport {
    let first = a.energy_series.first().copied();
    let last = a.energy_series.last().copied();
    let (e0, e1) = (first.map(|e| e.1), last.map(|e| e.1));
    // Dissipated energy between the first and last record: exact when the
    // source reports running totals, else the sum over logged collisions.
    let lost = match (first, last) {
        (Some((_, _, Some(a))), Some((_, _, Some(b)))) => Some(b - a),
        _ => None,
    };
    let lost_source = if lost.is_some() {
        "running total of the thermo records"
    } else {
        "sum over logged collisions × stride"
    };
    let lost = lost.unwrap_or(a.lost_from_collisions);
    let budget = match (e0, e1) {
        (Some(e0), Some(e1)) => Some(EnergyBudget {
            initial: e0,
            final_: e1,
            dissipated: lost,
            dissipated_source: lost_source,
            residual: e0 - lost - e1,
            relative_residual: (e0 - lost - e1) / e0,
        }),
        _ => None,
    };
    let haff = match a.run.restitution {
        Restitution::Normal(e) if e < 1.0 => haff(a, e),
        _ => None,
    };
    InelasticReport {
        energy: budget,
        haff,
        sonine: sonine(a),
    }
}

/// Haff's law (physics.md §8) with the collision frequency measured over the
/// run: in homogeneous cooling ω ∝ √T, so c = ω/√T = (2 N_pair/N) / ∫ √kT dt.
fn haff(a: &Analyzer, e: f64) -> Option<HaffReport> {
    let s = &a.kt_series;
    if s.len() < 3 {
        return None;
    }
    let (t0, kt0) = s[0];
    let integral: f64 = s
        .windows(2)
        .map(|w| 0.5 * (w[1].0 - w[0].0) * (w[0].1.max(0.0).sqrt() + w[1].1.max(0.0).sqrt()))
        .sum();
    let logged = if a.run.totals_from_thermo {
        0.0
    } else {
        a.pair_total as f64 * a.run.collision_stride as f64
    };
    let pairs = logged + a.pairs_from_increments as f64;
    if integral <= 0.0 || pairs == 0.0 {
        return None;
    }
    let c = 2.0 * pairs / a.run.n() as f64 / integral;
    let a2 = a2_theory(e);
    let omega0 = c * kt0.sqrt();
    let inv_t0 = (1.0 - e * e) * (1.0 + 3.0 * a2 / 16.0) * omega0 / 4.0;
    let (t_last, kt_last) = s[s.len() - 1];
    let predicted = kt0 / (1.0 + (t_last - t0) * inv_t0).powi(2);
    Some(HaffReport {
        a2,
        collision_frequency_initial: omega0,
        t0: 1.0 / inv_t0,
        kt_final_predicted: predicted,
        kt_final_measured: kt_last,
        ratio: kt_last / predicted,
    })
}
