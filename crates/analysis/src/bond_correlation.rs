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

    /// Whether a snapshot at `t` is used (after t0, at least the window over
    /// [`G6_SNAPSHOTS`] after the last one used, and no more than
    /// [`G6_SNAPSHOTS`] in all: with one at t0 the spacing alone would admit a
    /// 65th at t1).
    pub fn wants(&self, t: f64) -> bool {
        self.snapshots < G6_SNAPSHOTS
            && t >= self.t0
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
    /// exact exponential, pick the right form, and the right form's residual
    /// is 0 (to rounding).
    #[test]
    fn fits_recover_exact_decays() {
        let r: Vec<f64> = (0..400).map(|k| 0.05 * (k as f64 + 0.5)).collect();
        let power: Vec<f64> = r.iter().map(|r| 0.9 * r.powf(-0.2)).collect();
        let (eta, _, rp, re) = decay_fits(&r, &power, 1.0, f64::INFINITY).unwrap();
        assert!(
            (eta - 0.2).abs() < 1e-9 && rp < 1e-20 && rp < re,
            "{eta} {rp} {re}"
        );
        let expo: Vec<f64> = r.iter().map(|r| 0.9 * (-r / 3.0).exp()).collect();
        let (_, xi, rp, re) = decay_fits(&r, &expo, 1.0, f64::INFINITY).unwrap();
        assert!(
            (xi - 3.0).abs() < 1e-9 && re < 1e-20 && re < rp,
            "{xi} {rp} {re}"
        );
    }

    /// The least-squares line y = a + b x through (x, y) by the normal
    /// equations in raw sums (not the centred form of `decay_fits`): (b, RSS).
    fn normal_equations(x: &[f64], y: &[f64]) -> (f64, f64) {
        let n = x.len() as f64;
        let (sx, sy) = (x.iter().sum::<f64>(), y.iter().sum::<f64>());
        let sxx: f64 = x.iter().map(|x| x * x).sum();
        let sxy: f64 = x.iter().zip(y).map(|(x, y)| x * y).sum();
        let b = (n * sxy - sx * sy) / (n * sxx - sx * sx);
        let a = (sy - b * sx) / n;
        let rss = x.iter().zip(y).map(|(x, y)| (y - a - b * x).powi(2)).sum();
        (b, rss)
    }

    /// The envelope is the largest positive g6 in each window [m w, (m+1) w),
    /// from r = w (inclusive) to r_stop (exclusive), the first of equal maxima;
    /// NaN, zero and negative values never enter. Here (w = 1.5, r_stop = 9)
    /// it is the points 1.5, 3.6, 5.0 and 6.2 of f = 0.9 r^−0.4, every other
    /// point lying below f or outside: η = 0.4 with residual 0, and the
    /// exponential's fit is the least-squares line through (r, ln f(r)).
    #[test]
    fn the_envelope_is_the_largest_value_of_each_window() {
        let f = |r: f64| 0.9 * r.powf(-0.4);
        let pts = [
            (1.0, 5.0), // below w
            (1.5, f(1.5)),
            (2.0, 0.5 * f(2.0)),
            (2.9, f64::NAN),
            (3.0, 0.7 * f(3.0)), // window 2's first point, not its largest
            (3.6, f(3.6)),
            (4.2, -0.3),
            (4.5, 0.0), // window 3
            (5.0, f(5.0)),
            (5.9, 0.8 * f(5.9)),
            (6.2, f(6.2)), // window 4
            (7.0, f(6.2)), // a tie: the first stays
            (8.0, -0.1),   // window 5 has no positive value
            (9.0, 5.0),    // r_stop
            (9.5, 5.0),
        ];
        let (r, g): (Vec<f64>, Vec<f64>) = pts.iter().copied().unzip();
        let (eta, xi, rp, re) = decay_fits(&r, &g, 1.5, 9.0).unwrap();
        assert!(
            (eta - 0.4).abs() < 1e-12 && rp < 1e-25,
            "η {eta}, residual {rp}"
        );
        let env = [1.5, 3.6, 5.0, 6.2];
        let ln_f: Vec<f64> = env.iter().map(|&r| f(r).ln()).collect();
        let (b, rss) = normal_equations(&env, &ln_f);
        assert!((xi + 1.0 / b).abs() < 1e-9 * xi, "ξ {xi} vs {}", -1.0 / b);
        assert!((re - rss).abs() < 1e-9 * rss, "residual {re} vs {rss}");
        assert!(rss > 1e-4);
    }

    /// Three envelope points make a fit; two do not.
    #[test]
    fn a_fit_needs_three_envelope_points() {
        let f = |r: f64| 0.7 * (-r / 2.2).exp();
        let r = [1.2, 2.5, 3.9];
        let g: Vec<f64> = r.iter().map(|&r| f(r)).collect();
        let (_, xi, _, re) = decay_fits(&r, &g, 1.2, f64::INFINITY).unwrap();
        assert!(
            (xi - 2.2).abs() < 1e-12 && re < 1e-25,
            "ξ {xi}, residual {re}"
        );
        assert_eq!(decay_fits(&r[..2], &g[..2], 1.2, f64::INFINITY), None);
    }

    /// Unequal species (σ_min = 0.6, σ_max = 1.0: bins 0.06 wide) in a
    /// periodic 9 × 7 box: r_max = min(25, 9/2, 7/2) = 3.5, so 58 bins, pairs
    /// up to 58 · 0.06 = 3.48; the window [2, 10] has blocks 0.5 long and
    /// snapshots at least 8/64 = 0.125 apart.
    fn two_species() -> BondCorrelation {
        let sp = [Species::new(3, 0.3, 2.0), Species::new(2, 0.5, 0.5)];
        BondCorrelation::new(&sp, &SimBox::periodic(9.0, 7.0), 2.0, 10.0)
    }

    /// ψ = m e^{iα} as (Re, Im).
    fn psi(m: f64, alpha: f64) -> [f64; 2] {
        [m * alpha.cos(), m * alpha.sin()]
    }

    /// Two discs 1.23 apart through the periodic edge (x = 0.2 and 8.97): one
    /// pair in bin ⌊1.23/0.06⌋ = 20 with Re ψ_0 ψ_1* = m_0 m_1 cos(α_0 − α_1):
    /// 0.8 · 0.5 cos(0.3 − 1.1) at t = 2 (block 0) and 0.9 · 0.7 cos(−0.4 − 2)
    /// at t = 5.3 (block ⌊3.3/0.5⌋ = 6); g6 pools them, (a + b)/2, and its
    /// standard error over the two blocks is |a − b|/2. A snapshot before t0
    /// or 0.05 after the last is skipped; at t = 10 (block 16 → the last) the
    /// discs are 3.49 apart, beyond the last bin, and make no pair.
    #[test]
    fn a_pair_adds_re_psi_psi_star_to_its_distance_bin() {
        let mut bc = two_species();
        assert!((bc.dr - 0.06).abs() < 1e-15 && bc.nbins == 58);
        let (x, y) = ([0.2, 9.0 - (1.23 - 0.2)], [3.0, 3.0]);
        let (a, b) = (0.4 * (-0.8f64).cos(), 0.63 * (-2.4f64).cos());
        bc.add(1.9, &x, &y, &[psi(1.0, 0.0); 2]);
        bc.add(2.0, &x, &y, &[psi(0.8, 0.3), psi(0.5, 1.1)]);
        bc.add(2.05, &x, &y, &[psi(1.0, 0.0); 2]);
        bc.add(5.3, &x, &y, &[psi(0.9, -0.4), psi(0.7, 2.0)]);
        bc.add(10.0, &[0.2, 3.69], &y, &[psi(1.0, 0.0); 2]);
        let close = |u: f64, v: f64| (u - v).abs() < 1e-14;
        for (blk, want) in [(0, a), (6, b)] {
            let s = &bc.sums[blk];
            assert!(
                close(s[20].0, want) && s[20].1 == 1,
                "block {blk}: {:?}",
                s[20]
            );
            assert_eq!(s.iter().map(|v| v.1).sum::<u64>(), 1);
        }
        assert!(bc.sums[15].iter().all(|v| *v == (0.0, 0)));
        let rep = bc.report().unwrap();
        assert_eq!(rep.snapshots, 3);
        for (k, &r) in rep.r.iter().enumerate() {
            assert!(close(r, (k as f64 + 0.5) * 0.06), "r[{k}] = {r}");
        }
        assert_eq!(rep.r.len(), 58);
        assert!(
            close(rep.g6[20], (a + b) / 2.0),
            "{} vs {}",
            rep.g6[20],
            (a + b) / 2.0
        );
        assert!(close(rep.std_error[20], (a - b).abs() / 2.0));
        assert_eq!(rep.g6.iter().filter(|g| !g.is_nan()).count(), 1);
        assert_eq!((rep.eta6, rep.xi6, rep.decay), (None, None, None));
    }

    /// A pair just inside the cut-off whose r/dr rounds up to the number of
    /// bins goes into the last bin: σ = 0.6 in a periodic 8 × 8 box, r_max = 4,
    /// ⌊4/0.06⌋ = 66 bins, cut-off 66 · 0.06 = 3.96, and the double just below
    /// it times 1/0.06 rounds to 66.
    #[test]
    fn a_pair_at_the_cut_off_goes_into_the_last_bin() {
        let sp = [Species::new(2, 0.3, 1.5)];
        let mut bc = BondCorrelation::new(&sp, &SimBox::periodic(8.0, 8.0), 0.0, 1.0);
        assert_eq!(bc.nbins, 66);
        let r = f64::from_bits((66.0 * bc.dr).to_bits() - 1);
        assert!(r * r < (66.0 * bc.dr).powi(2) && (r * (1.0 / bc.dr)) as usize == 66);
        bc.add(
            0.0,
            &[0.0, r],
            &[1.0, 1.0],
            &[psi(0.6, 0.2), psi(0.5, -0.7)],
        );
        let want = 0.3 * 0.9f64.cos();
        let last = bc.sums[0][65];
        assert!((last.0 - want).abs() < 1e-15 && last.1 == 1, "{last:?}");
    }

    /// Snapshots are used from t0 on, each at least window/64 after the last
    /// used (to a relative 10⁻⁹), 64 at most: 641 snapshots evenly over
    /// [0.5, 24.18] are every 10th 65 times (k = 0, 10, …, 640), the last, at
    /// t1, refused; in an empty window none is used.
    #[test]
    fn snapshots_are_used_at_least_a_64th_of_the_window_apart() {
        let (t0, t1) = (0.5, 24.18);
        let s = (t1 - t0) / 64.0;
        let mut bc = BondCorrelation::new(
            &[Species::reference(2)],
            &SimBox::periodic(9.0, 9.0),
            t0,
            t1,
        );
        assert!(!bc.wants(0.49) && bc.wants(t0));
        bc.add(3.0, &[1.0, 2.0], &[1.0, 1.0], &[psi(1.0, 0.0); 2]);
        assert!(!bc.wants(3.0 + s * (1.0 - 1e-8)) && bc.wants(3.0 + s * (1.0 - 1e-10)));
        assert!(bc.wants(3.0 + s) && bc.wants(t1));
        let mut bc = BondCorrelation::new(
            &[Species::reference(2)],
            &SimBox::periodic(9.0, 9.0),
            t0,
            t1,
        );
        for k in 0..=640 {
            let t = t0 + k as f64 * (t1 - t0) / 640.0;
            assert_eq!(bc.wants(t), k % 10 == 0 && k < 640, "k = {k}");
            bc.add(t, &[1.0, 2.0], &[1.0, 1.0], &[psi(1.0, 0.0); 2]);
        }
        assert_eq!(bc.snapshots, 64);
        let empty = BondCorrelation::new(
            &[Species::reference(2)],
            &SimBox::periodic(9.0, 9.0),
            t0,
            t0,
        );
        assert!(!empty.wants(t0) && !empty.wants(t0 + 1.0) && empty.report().is_none());
    }

    /// σ_min = 0.6, σ_max = 1.3 in a periodic 40 × 40 box: 333 bins 0.06 wide
    /// to r_max = 20, envelope windows 1.3 wide. Every bin has 2 pairs a
    /// block with g6 = A_b f(r), A_b = 1.5 in the even blocks and 0.5 in the
    /// odd ones (standard error 0.5 f/√15 < f/3), up to r = 11; then g6
    /// ends, as empty bins or as bins lost in noise (3 f and −f: mean f,
    /// standard error 2 f/√15 > f/3); beyond r = 12, a constant 0.9 A_b that
    /// must not enter. The fits see only [1.3, 11): every block and the
    /// pooled g6 give f's exponent or length exactly, with 0 spread.
    fn fitted(f: impl Fn(f64) -> f64, empty: bool) -> BondCorrelationReport {
        let sp = [Species::new(5, 0.3, 2.0), Species::new(5, 0.65, 1.0)];
        let mut bc = BondCorrelation::new(&sp, &SimBox::periodic(40.0, 40.0), 0.0, 1.6);
        assert_eq!(bc.nbins, 333);
        for (b, blk) in bc.sums.iter_mut().enumerate() {
            let even = b % 2 == 0;
            let amp = if even { 1.5 } else { 0.5 };
            for (k, v) in blk.iter_mut().enumerate() {
                let r = (k as f64 + 0.5) * 0.06;
                let g = match r {
                    r if r < 11.0 => amp * f(r),
                    r if r < 12.0 => f(r) * if even { 3.0 } else { -1.0 },
                    _ => 0.9 * amp,
                };
                *v = if empty && (11.0..12.0).contains(&r) {
                    (0.0, 0)
                } else {
                    (2.0 * g, 2)
                };
            }
        }
        bc.snapshots = 16;
        bc.report().unwrap()
    }

    #[test]
    fn the_decay_fits_stop_where_g6_ends() {
        for empty in [true, false] {
            let rep = fitted(|r| 0.8 * r.powf(-0.25), empty);
            let [eta, se] = rep.eta6.unwrap();
            assert!(
                (eta - 0.25).abs() < 1e-9 && se < 1e-9,
                "empty {empty}: η {eta} ± {se}"
            );
            assert_eq!(rep.decay, Some("power law"));
            let rep = fitted(|r| 0.8 * (-r / 2.5).exp(), empty);
            let [xi, se] = rep.xi6.unwrap();
            assert!(
                (xi - 2.5).abs() < 1e-9 && se < 1e-9,
                "empty {empty}: ξ {xi} ± {se}"
            );
            assert_eq!(rep.decay, Some("exponential"));
        }
    }
}
