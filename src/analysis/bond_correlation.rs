//! The orientational correlation g6(r) = ⟨Re ψ6_i ψ6_j*⟩ over the pairs at
//! distance r (physics.md §11): it decays exponentially, e^{−r/ξ6}, in a liquid
//! and as a power law, r^{−η6} with η6 ≤ 1/4, in the hexatic phase; in a
//! crystal it tends to a constant. Pairs come from the cell list up to
//! [`G6_R_MAX_SIGMA`] σ_max (at most half a periodic edge, at most a walled
//! width), on at most [`G6_SNAPSHOTS`] snapshots evenly spread over the window
//! (pairs out to many σ cost far more than g(r)'s), each into one of 16 time
//! blocks. Both decays are fitted, by least squares in logarithms, to the upper
//! envelope (the largest g6 in each σ_max-wide window, from σ_max to where g6
//! first falls below 3 standard errors) per block;
//! the errors are the spread of the block fits.

use carom_core::{SimBox, Species};
use serde::Serialize;

use super::cell_list::{pair_reach, CellList};
use super::pair_correlation::{mean_se, BLOCKS};

/// Largest r of g6 in units of the largest contact distance.
pub const G6_R_MAX_SIGMA: f64 = 25.0;
/// Bin width of g6 in units of the smallest contact distance.
pub const G6_BIN_WIDTH_SIGMA: f64 = 0.1;
/// Most snapshots that enter g6.
pub const G6_SNAPSHOTS: usize = 64;
/// The decay fits use g6 out to where it first falls below this many standard errors.
pub const SIGNIFICANT: f64 = 3.0;

/// Accumulates Σ Re ψ6_i ψ6_j* and pair counts per bin and time block.
#[derive(Debug, Clone)]
pub struct BondCorrelation {
    sim_box: SimBox,
    sigma_max: f64,
    dr: f64,
    nbins: usize,
    t0: f64,
    block_time: f64,
    spacing: f64,
    last: Option<f64>,
    /// (Σ Re ψψ*, pairs) per block and bin.
    sums: Vec<Vec<(f64, u64)>>,
    snapshots: usize,
    cells: CellList,
}

/// g6(r) and its decay.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BondCorrelationReport {
    /// Bin centres (length).
    pub r: Vec<f64>,
    /// g6 at each bin centre, pooled over the snapshots used (NaN in empty bins).
    pub g6: Vec<f64>,
    /// Standard error of g6 from the spread of the time blocks.
    pub std_error: Vec<f64>,
    /// Snapshots used.
    pub snapshots: usize,
    /// η6 of the power law g6 ∝ r^(−η6) fitted to the envelope, ± its error.
    pub eta6: Option<[f64; 2]>,
    /// ξ6 (length) of the exponential g6 ∝ e^(−r/ξ6) fitted to the envelope, ± its error.
    pub xi6: Option<[f64; 2]>,
    /// The form whose fit has the smaller residual: "power law" or "exponential".
    pub decay: Option<&'static str>,
}

impl BondCorrelation {
    /// An accumulator for `species` in `sim_box` over the window [t0, t1].
    pub fn new(species: &[Species], sim_box: &SimBox, t0: f64, t1: f64) -> Self {
        let [sigma_min, sigma_max, r_max] = pair_reach(species, sim_box, G6_R_MAX_SIGMA);
        let dr = G6_BIN_WIDTH_SIGMA * sigma_min;
        let nbins = ((r_max / dr).floor() as usize).max(1);
        BondCorrelation {
            sim_box: *sim_box,
            sigma_max,
            dr,
            nbins,
            t0,
            block_time: (t1 - t0) / BLOCKS as f64,
            spacing: (t1 - t0) / G6_SNAPSHOTS as f64,
            last: None,
            sums: vec![vec![(0.0, 0); nbins]; BLOCKS],
            snapshots: 0,
            cells: CellList::default(),
        }
    }

    /// Whether a snapshot at `t` is used (after t0, and at least the window over
    /// [`G6_SNAPSHOTS`] after the last one used).
    pub fn wants(&self, t: f64) -> bool {
        t >= self.t0
            && self.block_time > 0.0
            && self
                .last
                .is_none_or(|last| t >= last + self.spacing * (1.0 - 1e-9))
    }

    /// Add one snapshot at `t`: discs at (`x`, `y`) with local order `psi`.
    pub fn add(&mut self, t: f64, x: &[f64], y: &[f64], psi: &[[f64; 2]]) {
        if !self.wants(t) {
            return;
        }
        self.last = Some(t);
        let blk = (((t - self.t0) / self.block_time) as usize).min(BLOCKS - 1);
        let (inv_dr, nbins) = (1.0 / self.dr, self.nbins);
        self.cells
            .build(&self.sim_box, nbins as f64 * self.dr, x, y);
        let local = self.cells.fold_pairs(
            || vec![(0.0, 0u64); nbins],
            |h, i, j, r| {
                let k = ((r * inv_dr) as usize).min(nbins - 1);
                h[k].0 += psi[i][0] * psi[j][0] + psi[i][1] * psi[j][1];
                h[k].1 += 1;
            },
            |a, b| {
                for (u, v) in a.iter_mut().zip(b) {
                    u.0 += v.0;
                    u.1 += v.1;
                }
            },
        );
        for (u, v) in self.sums[blk].iter_mut().zip(local) {
            u.0 += v.0;
            u.1 += v.1;
        }
        self.snapshots += 1;
    }

    /// The report; `None` without snapshots.
    pub fn report(&self) -> Option<BondCorrelationReport> {
        if self.snapshots == 0 {
            return None;
        }
        let ratio = |s: &[(f64, u64)]| -> Vec<f64> {
            s.iter()
                .map(|&(w, c)| if c > 0 { w / c as f64 } else { f64::NAN })
                .collect()
        };
        let used: Vec<&Vec<(f64, u64)>> = self
            .sums
            .iter()
            .filter(|b| b.iter().any(|v| v.1 > 0))
            .collect();
        let blocks: Vec<Vec<f64>> = used.iter().map(|b| ratio(b)).collect();
        let pooled: Vec<(f64, u64)> = (0..self.nbins)
            .map(|k| {
                used.iter()
                    .fold((0.0, 0), |a, b| (a.0 + b[k].0, a.1 + b[k].1))
            })
            .collect();
        let g6 = ratio(&pooled);
        let std_error: Vec<f64> = (0..self.nbins)
            .map(|k| {
                let col: Vec<f64> = blocks
                    .iter()
                    .map(|b| b[k])
                    .filter(|v| v.is_finite())
                    .collect();
                mean_se(&col).1
            })
            .collect();
        let r: Vec<f64> = (0..self.nbins)
            .map(|k| (k as f64 + 0.5) * self.dr)
            .collect();
        // The fits stop where g6 is first lost in its noise (< 3 SE), so that the
        // envelope of noise does not pose as a slow decay.
        let w = self.sigma_max;
        let r_stop = r
            .iter()
            .zip(g6.iter().zip(&std_error))
            .find(|&(&r, (&g, &e))| r >= w && (g.is_nan() || g <= SIGNIFICANT * e))
            .map_or(f64::INFINITY, |p| *p.0);
        let fits: Vec<(f64, f64, f64, f64)> = blocks
            .iter()
            .filter_map(|b| decay_fits(&r, b, w, r_stop))
            .collect();
        let pooled_fit = decay_fits(&r, &g6, w, r_stop);
        let with_error = |f: fn(&(f64, f64, f64, f64)) -> f64| {
            pooled_fit.as_ref().map(|p| {
                let v: Vec<f64> = fits.iter().map(f).collect();
                [f(p), mean_se(&v).1]
            })
        };
        Some(BondCorrelationReport {
            eta6: with_error(|f| f.0),
            xi6: with_error(|f| f.1),
            decay: pooled_fit.map(|f| {
                if f.2 <= f.3 {
                    "power law"
                } else {
                    "exponential"
                }
            }),
            r,
            g6,
            std_error,
            snapshots: self.snapshots,
        })
    }
}

/// The upper envelope of g6 (largest value in each `width`-wide window from
/// r = width to `r_stop`, positive values only) and the least-squares fits
/// ln g6 = c − η6 ln r and ln g6 = c − r/ξ6 to it: (η6, ξ6, residual of the
/// power law, residual of the exponential); `None` with fewer than 3 points.
pub fn decay_fits(r: &[f64], g6: &[f64], width: f64, r_stop: f64) -> Option<(f64, f64, f64, f64)> {
    let mut env: Vec<(f64, f64)> = Vec::new();
    for (&r, &g) in r.iter().zip(g6) {
        if r < width || r >= r_stop || g.is_nan() || g <= 0.0 {
            continue;
        }
        let w = (r / width).floor();
        match env.last_mut() {
            Some(last) if (last.0 / width).floor() == w => {
                if g > last.1 {
                    *last = (r, g);
                }
            }
            _ => env.push((r, g)),
        }
    }
    if env.len() < 3 {
        return None;
    }
    let ln_g: Vec<f64> = env.iter().map(|p| p.1.ln()).collect();
    let line = |u: &[f64]| -> (f64, f64) {
        let n = u.len() as f64;
        let (mu, mv) = (u.iter().sum::<f64>() / n, ln_g.iter().sum::<f64>() / n);
        let sxy: f64 = u.iter().zip(&ln_g).map(|(a, b)| (a - mu) * (b - mv)).sum();
        let sxx: f64 = u.iter().map(|a| (a - mu).powi(2)).sum();
        let slope = sxy / sxx;
        let rss = u
            .iter()
            .zip(&ln_g)
            .map(|(a, b)| (b - mv - slope * (a - mu)).powi(2))
            .sum();
        (slope, rss)
    };
    let ln_r: Vec<f64> = env.iter().map(|p| p.0.ln()).collect();
    let lin_r: Vec<f64> = env.iter().map(|p| p.0).collect();
    let (s_pow, rss_pow) = line(&ln_r);
    let (s_exp, rss_exp) = line(&lin_r);
    Some((-s_pow, -1.0 / s_exp, rss_pow, rss_exp))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The fits recover the exponent of an exact power law and the length of an
    /// exact exponential, and pick the right form.
    #[test]
    fn fits_recover_exact_decays() {
        let r: Vec<f64> = (0..400).map(|k| 0.05 * (k as f64 + 0.5)).collect();
        let power: Vec<f64> = r.iter().map(|r| 0.9 * r.powf(-0.2)).collect();
        let (eta, _, rp, re) = decay_fits(&r, &power, 1.0, f64::INFINITY).unwrap();
        assert!((eta - 0.2).abs() < 1e-9 && rp < re, "{eta} {rp} {re}");
        let expo: Vec<f64> = r.iter().map(|r| 0.9 * (-r / 3.0).exp()).collect();
        let (_, xi, rp, re) = decay_fits(&r, &expo, 1.0, f64::INFINITY).unwrap();
        assert!((xi - 3.0).abs() < 1e-9 && re < rp, "{xi} {rp} {re}");
    }
}
