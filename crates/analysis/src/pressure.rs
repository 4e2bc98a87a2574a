//! Pressure and the compressibility factor Z = βPA/N, per time bin and then
//! averaged with a blocked standard error. In a periodic box Z = 1 + W/(N kT)
//! from the collision virial; with walls Z from the impulse on the walls and the
//! extent each species' centres reach, and A the area they reach (physics.md §5).
//! The formulas are `carom_core::observables`', the same the `/thermo` records use:
//! over the same window the two agree up to the time bins' rounding.

use carom_core::observables::{accessible_area, has_walls, pressure, virial_z, wall_z};

use super::samples::Samples;
use super::series::{blocked, coarse_series, drift};
use super::stats::StatsError;
use super::thermo_report::PressureReport;

/// Z of each time bin, with kT of each bin from `kt_bins`.
pub(super) fn z_per_bin(a: &Samples, kt_bins: &[f64]) -> Vec<f64> {
    let (species, sim_box) = (&a.run.species, &a.run.sim_box);
    let (n, dt, walls) = (a.run.n(), a.bin_width, has_walls(sim_box));
    a.bins
        .iter()
        .zip(kt_bins)
        .map(|(b, &kt)| match walls {
            true => wall_z(species, sim_box, kt, b.wall_impulse, dt),
            false => virial_z(n, kt, b.virial, dt),
        })
        .collect()
}

/// The pressure report from the bins' Z and kT; `None` when some bin has no
/// finite Z (no temperature known).
pub(super) fn report(
    a: &Samples,
    z_bins: &[f64],
    kt_bins: &[f64],
) -> Result<Option<PressureReport>, StatsError> {
    if !z_bins.iter().all(|z| z.is_finite()) {
        return Ok(None);
    }
    let (n, dt) = (a.run.n(), a.bin_width);
    let nf = n as f64;
    let area = accessible_area(&a.run.species, &a.run.sim_box);
    let est = blocked(z_bins)?;
    let kt_mean = kt_bins.iter().sum::<f64>() / kt_bins.len() as f64;
    Ok(Some(PressureReport {
        estimator: if has_walls(&a.run.sim_box) {
            "wall impulse: βPA/N = J/(2t kT Σ_walled axes k Σ_s N_s/ℓ_k(a_s)), J the impulse \
             on the walls, ℓ_k(a_s) the extent species s's centres reach, A = N/Σ_s(N_s/A_s) \
             (physics.md §5)"
        } else {
            "collision virial: βPA/N = 1 + W/(N kT), W = Σ r_ij·Δp_i/(2t), \
             kT = 2K/f (physics.md §5)"
        },
        z: est.mean,
        z_std_error: est.std_error,
        beta_p: est.mean * nf / area,
        beta_p_std_error: est.std_error * nf / area,
        p: pressure(est.mean, n, kt_mean, area),
        area,
        blocks: est.blocks,
        block_time: est.block_len as f64 * dt,
        converged: est.converged,
        series: coarse_series(z_bins, a.t_eq, dt, 64),
        drift: drift(z_bins),
    }))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::description::RunDescription;
    use crate::AnalysisOptions;
    use crate::Analyzer;
    use carom_core::{SimBox, Species};

    /// 16 bins over [2, 10], 0.5 wide.
    fn analyzer(run: RunDescription) -> Analyzer {
        let opts = AnalysisOptions {
            equilibrate: Some(2.0),
            time_bins: 16,
            ..Default::default()
        };
        Analyzer::new(run, opts).unwrap()
    }

    /// Periodic, N = 4: Z = 1 + (Σ r·Δp/(2Δt))/(N kT) per bin, Δt = 0.5: bin 0
    /// (virial 3, kT 1.5) 1 + 3/6 = 1.5; bin 4 (virial 1 + 2, kT 0.5) 1 + 3/2 = 2.5;
    /// the others 1.
    #[test]
    fn a_periodic_bin_has_z_from_its_collision_virial() {
        let run = RunDescription {
            species: vec![Species::new(4, 0.3, 2.0)],
            sim_box: SimBox::periodic(10.0, 8.0),
            ..RunDescription::for_tests()
        };
        let mut a = analyzer(run);
        for (t, w) in [(2.1, 3.0), (4.3, 1.0), (4.4, 2.0)] {
            a.pair(t, w, 0.0);
        }
        let kt: Vec<f64> = (0..16).map(|k| if k == 4 { 0.5 } else { 1.5 }).collect();
        let z = z_per_bin(&a.samples, &kt);
        let want: Vec<f64> = (0..16)
            .map(|k| match k {
                0 => 1.5,
                4 => 2.5,
                _ => 1.0,
            })
            .collect();
        assert_eq!(z, want);
    }

    /// Walls on both axes of an 11 × 9 box, 2 discs of radius 0.5 (centres reach
    /// 10 × 8) and 1 of radius 1 (9 × 7): Z = J/(2Δt kT Σ_k Σ_s N_s/ℓ_k(a_s)) with
    /// Σ = 2/10 + 1/9 + 2/8 + 1/7; bin 1 has J = 2.7 at kT 2, the others none.
    #[test]
    fn a_walled_bin_has_z_from_its_wall_impulse() {
        let run = RunDescription {
            species: vec![Species::new(2, 0.5, 2.0), Species::new(1, 1.0, 0.5)],
            sim_box: SimBox::walled(11.0, 9.0, 1.0),
            ..RunDescription::for_tests()
        };
        let mut a = analyzer(run);
        a.wall(2.7, 1.2, 0.0);
        a.wall(2.8, 1.5, 0.0);
        let z = z_per_bin(&a.samples, &[2.0; 16]);
        let sum = 2.0 / 10.0 + 1.0 / 9.0 + 2.0 / 8.0 + 1.0 / 7.0;
        let z1 = 2.7 / (2.0 * 0.5 * 2.0 * sum);
        assert_eq!(z.len(), 16);
        for (k, z) in z.iter().enumerate() {
            let want = if k == 1 { z1 } else { 0.0 };
            assert!((z - want).abs() < 1e-14, "bin {k}: {z} against {want}");
        }
    }

    /// N = 5 in a periodic 10 × 8 box (A = 80): Z the mean of the bins, βP = Z N/A
    /// (and its error the same multiple of Z's), P = Z N ⟨kT⟩/A with ⟨kT⟩ = (8·1 +
    /// 8·2)/16 = 1.5; the blocks tile the window [2, 10]. A bin without a finite Z
    /// (no temperature) gives no report.
    #[test]
    fn the_report_averages_z_and_converts_it_to_the_pressure() {
        let run = RunDescription {
            species: vec![Species::new(5, 0.3, 2.0)],
            sim_box: SimBox::periodic(10.0, 8.0),
            ..RunDescription::for_tests()
        };
        let a = analyzer(run);
        let z: Vec<f64> = (0..16)
            .map(|k| 2.0 + 0.1 * ((k * k) % 7) as f64 - 0.05 * (k % 3) as f64)
            .collect();
        let kt: Vec<f64> = (0..16).map(|k| if k < 8 { 1.0 } else { 2.0 }).collect();
        let r = report(&a.samples, &z, &kt).unwrap().unwrap();
        let z_mean = z.iter().sum::<f64>() / 16.0;
        assert!((r.z - z_mean).abs() < 1e-14);
        assert_eq!(r.area, 80.0);
        assert!((r.beta_p - z_mean * 5.0 / 80.0).abs() < 1e-14);
        assert!(r.z_std_error > 0.0);
        assert!((r.beta_p_std_error - r.z_std_error * 5.0 / 80.0).abs() < 1e-15);
        assert!((r.p - z_mean * 5.0 * 1.5 / 80.0).abs() < 1e-14);
        assert!((r.blocks as f64 * r.block_time - 8.0).abs() < 1e-12);
        let mut z_nan = z.clone();
        z_nan[3] = f64::NAN;
        assert!(report(&a.samples, &z_nan, &kt).unwrap().is_none());
    }
}
