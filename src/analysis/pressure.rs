//! Pressure and the compressibility factor Z = βPA/N, per time bin and then
//! averaged with a blocked standard error. In a periodic box Z = 1 + W/(N kT)
//! from the collision virial; with walls Z from the impulse on the walls and the
//! extent each species' centres reach, and A the area they reach (physics.md §5).
//! The formulas are `carom_core::observables`', the same the `/thermo` records use:
//! over the same window the two agree up to the time bins' rounding.

use carom_core::observables::{accessible_area, has_walls, pressure, virial_z, wall_z};

use super::analyzer::Analyzer;
use super::report::PressureReport;
use super::series::{blocked, coarse_series, drift};
use super::stats::StatsError;

/// Z of each time bin, with kT of each bin from `kt_bins`.
pub(super) fn z_per_bin(a: &Analyzer, kt_bins: &[f64]) -> Vec<f64> {
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
    a: &Analyzer,
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
