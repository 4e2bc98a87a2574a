//! The structure factor S(k) = |ρ_k|²/N, ρ_k = Σ_j e^{−i k·r_j}, on the wave
//! vectors of a periodic box, k = 2π (n/L_x, m/L_y), 0 < |k| ≤ k_max =
//! min([`SK_K_MAX_SIGMA`]/σ_min, [`SK_MAX_MODES`]·2π/L_max),
//! radially averaged in shells 2π/min(L) wide centred on multiples of it
//! (physics.md §11); ρ_k from the non-uniform FFT ([`super::nufft`]), and since
//! ρ_{−k} = ρ_k* half of the k-plane is averaged. The largest S
//! among the vectors gives the translational order ψ_T = max_k |ρ_k|/N (a Bragg
//! peak of weight N ψ_T² in a crystal; of order N^(−1/2) in a fluid). It runs on
//! at most [`SK_SNAPSHOTS`] snapshots, one per time block (errors from their
//! spread).

use carom_core::SimBox;
use serde::Serialize;

use super::nufft::density_modes;
use super::pair_correlation::{mean_se, BLOCKS};

/// Shells below this many 1/σ_min are not searched for the first peak of S(k):
/// a liquid's first peak lies near 2π/σ, and the few vectors of a small-k shell
/// can scatter above a gas's weak peak.
pub const K_STAR_MIN_SIGMA: f64 = std::f64::consts::PI;

/// Largest |k| in units of 1/σ_min (the first peak of a dense fluid is near 7).
pub const SK_K_MAX_SIGMA: f64 = 10.0;
/// Most modes per axis and sign: bounds the FFT grid at 2048² points (64 MiB),
/// so k_max shrinks to 511·2π/L in boxes wider than about 320 σ_min.
pub const SK_MAX_MODES: usize = 511;
/// Most snapshots that enter S(k): one per time block.
pub const SK_SNAPSHOTS: usize = BLOCKS;

/// S(k) of one snapshot, shell by shell, and its largest value with the vector.
#[derive(Debug, Clone, PartialEq)]
pub struct SnapshotSk {
    /// Σ S over the vectors in each shell.
    pub sums: Vec<f64>,
    /// Vectors in each shell (the half plane).
    pub counts: Vec<u64>,
    /// (largest S, its k_x, its k_y).
    pub peak: (f64, f64, f64),
    /// Discs.
    pub n: usize,
}

/// k-shells of the box: width dk, count, and the largest |k|. Shell s holds
/// the vectors with round(|k|/dk) = s, so that the vectors along the axes lie
/// at the centres of theirs, not on a boundary.
pub(super) fn shells(sim_box: &SimBox, sigma_min: f64) -> (f64, usize, f64) {
    let tp = 2.0 * std::f64::consts::PI;
    let dk = tp / sim_box.size.x.min(sim_box.size.y);
    let k_max = (SK_K_MAX_SIGMA / sigma_min)
        .min(SK_MAX_MODES as f64 * tp / sim_box.size.x.max(sim_box.size.y));
    (dk, (k_max / dk).round() as usize + 1, k_max)
}

/// The shell of a vector of length `k`.
fn shell_of(k: f64, dk: f64, nshell: usize) -> usize {
    ((k / dk).round() as usize).min(nshell - 1)
}

/// S(k) of the discs at (`x`, `y`) in the periodic `sim_box`.
pub fn snapshot_sk(sim_box: &SimBox, sigma_min: f64, x: &[f64], y: &[f64]) -> SnapshotSk {
    let two_pi = 2.0 * std::f64::consts::PI;
    let (lx, ly) = (sim_box.size.x, sim_box.size.y);
    let (dkx, dky) = (two_pi / lx, two_pi / ly);
    let (dk, nshell, k_max) = shells(sim_box, sigma_min);
    let n_max = (k_max / dkx).floor() as usize;
    let m_max = (k_max / dky).floor() as usize;
    let angle = |v: &[f64], l: f64| -> Vec<f64> {
        v.iter()
            .map(|&v| (two_pi * (v / l)).rem_euclid(two_pi))
            .collect()
    };
    let modes = density_modes(&angle(x, lx), &angle(y, ly), n_max, m_max);
    let n = x.len() as f64;
    let mut out = SnapshotSk {
        sums: vec![0.0; nshell],
        counts: vec![0; nshell],
        peak: (0.0, 0.0, 0.0),
        n: x.len(),
    };
    for nx in 0..=n_max as i64 {
        for my in -(m_max as i64)..=m_max as i64 {
            let (kx, ky) = (nx as f64 * dkx, my as f64 * dky);
            let k = kx.hypot(ky);
            // Half plane: n > 0, or n = 0 with m > 0.
            if (nx == 0 && my <= 0) || k > k_max {
                continue;
            }
            let s = modes.get(nx, my).norm_sqr() / n;
            let shell = shell_of(k, dk, nshell);
            out.sums[shell] += s;
            out.counts[shell] += 1;
            if s > out.peak.0 {
                out.peak = (s, kx, ky);
            }
        }
    }
    out
}

/// S(k) and ψ_T over the snapshots.
#[derive(Debug, Clone)]
pub struct StructureFactor {
    sim_box: SimBox,
    sigma_min: f64,
    t0: f64,
    block_time: f64,
    /// One snapshot's S(k) per time block (the first in the block).
    per_block: Vec<Option<SnapshotSk>>,
}

/// The radially averaged S(k) and the translational order.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StructureFactorReport {
    /// Shell centres (1/length); shells without vectors are left out.
    pub k: Vec<f64>,
    /// S averaged over the vectors of each shell and the snapshots.
    pub s: Vec<f64>,
    /// Standard error of S from the spread of the snapshots.
    pub std_error: Vec<f64>,
    /// Wave vectors in each shell (half plane).
    pub vectors: Vec<u64>,
    /// Snapshots used (one per time block).
    pub snapshots: usize,
    /// Position of the first peak (the largest S at k ≥ π/σ_min, physics.md
    /// §11), 1/length; `null` when no shell reaches k = π/σ_min (a box too small).
    pub peak_k: Option<f64>,
    /// Its height.
    pub peak_s: Option<f64>,
    /// The standard error of its height.
    pub peak_std_error: Option<f64>,
    /// ψ_T = max_k |ρ_k|/N, mean over the snapshots.
    pub translational: f64,
    /// Its standard error.
    pub translational_std_error: f64,
    /// The vector of the largest S in the last snapshot used (1/length).
    pub translational_k: [f64; 2],
}

impl StructureFactor {
    /// An accumulator over [t0, t1]; `None` unless the box is periodic.
    pub fn new(sim_box: &SimBox, sigma_min: f64, t0: f64, t1: f64) -> Option<Self> {
        (sim_box.boundary.iter().all(|b| b.is_periodic()) && sigma_min > 0.0).then(|| {
            StructureFactor {
                sim_box: *sim_box,
                sigma_min,
                t0,
                block_time: (t1 - t0) / BLOCKS as f64,
                per_block: vec![None; BLOCKS],
            }
        })
    }

    /// Add a snapshot at `t` if it is the first of its time block.
    pub fn add(&mut self, t: f64, x: &[f64], y: &[f64]) {
        if t < self.t0 || self.block_time.is_nan() || self.block_time <= 0.0 || x.is_empty() {
            return;
        }
        let blk = (((t - self.t0) / self.block_time) as usize).min(BLOCKS - 1);
        if self.per_block[blk].is_none() {
            self.per_block[blk] = Some(snapshot_sk(&self.sim_box, self.sigma_min, x, y));
        }
    }

    /// The report; `None` without snapshots.
    pub fn report(&self) -> Option<StructureFactorReport> {
        let used: Vec<&SnapshotSk> = self.per_block.iter().flatten().collect();
        let last = used.last()?;
        let (dk, nshell, _) = shells(&self.sim_box, self.sigma_min);
        let (mut k, mut s, mut std_error, mut vectors) = (vec![], vec![], vec![], vec![]);
        let mut uncut = 0;
        for sh in 0..nshell {
            let c = last.counts[sh];
            if c == 0 {
                continue;
            }
            let per: Vec<f64> = used.iter().map(|u| u.sums[sh] / c as f64).collect();
            let (m, se) = mean_se(&per);
            k.push(sh as f64 * dk);
            s.push(m);
            std_error.push(se);
            vectors.push(c);
            if sh + 1 < nshell {
                uncut = k.len();
            }
        }
        let peak = first_peak(&k[..uncut], &s[..uncut], self.sigma_min);
        let psi_t: Vec<f64> = used
            .iter()
            .map(|u| (u.peak.0 / u.n as f64).sqrt())
            .collect();
        let (translational, translational_std_error) = mean_se(&psi_t);
        Some(StructureFactorReport {
            peak_k: peak.map(|p| k[p]),
            peak_s: peak.map(|p| s[p]),
            peak_std_error: peak.map(|p| std_error[p]),
            k,
            s,
            std_error,
            vectors,
            snapshots: used.len(),
            translational,
            translational_std_error,
            translational_k: [last.peak.1, last.peak.2],
        })
    }
}

/// The first peak of S(k), the one rule for it: the index of the shell with the
/// largest S among those at k ≥ [`K_STAR_MIN_SIGMA`]/σ_min (`k` increasing, the
/// last shell, cut by k_max, already left out); `None` when no shell is that far
/// out. Below π/σ, S(k) measures long-wavelength density fluctuations (the
/// compressibility, a granular gas's clusters), not the shell of neighbours.
pub fn first_peak(k: &[f64], s: &[f64], sigma_min: f64) -> Option<usize> {
    (0..k.len())
        .filter(|&i| k[i] >= K_STAR_MIN_SIGMA / sigma_min)
        .max_by(|&a, &b| s[a].total_cmp(&s[b]))
}

#[cfg(test)]
mod tests {
    use super::super::test_lattice::triangular;
    use super::*;
    use rand::{RngExt, SeedableRng};
    use rand_pcg::Pcg64;

    /// The row recurrence and the half plane give the shell sums of a plain
    /// double loop over every vector with sin and cos.
    #[test]
    fn shell_sums_match_the_direct_double_sum() {
        let mut rng = Pcg64::seed_from_u64(5);
        let sb = SimBox::periodic(9.0, 7.0);
        let x: Vec<f64> = (0..40).map(|_| rng.random_range(0.0..9.0)).collect();
        let y: Vec<f64> = (0..40).map(|_| rng.random_range(0.0..7.0)).collect();
        let got = snapshot_sk(&sb, 1.0, &x, &y);
        let (dk, nshell, k_max) = shells(&sb, 1.0);
        let mut sums = vec![0.0; nshell];
        let tp = 2.0 * std::f64::consts::PI;
        for n in -20i64..=20 {
            for m in -20i64..=20 {
                let (kx, ky) = (n as f64 * (tp / 9.0), m as f64 * (tp / 7.0));
                let k = kx.hypot(ky);
                if k == 0.0 || k > k_max {
                    continue;
                }
                let (mut c, mut s) = (0.0, 0.0);
                for j in 0..40 {
                    c += (kx * x[j] + ky * y[j]).cos();
                    s += (kx * x[j] + ky * y[j]).sin();
                }
                // Both halves of the plane: each shell's sum counted twice.
                sums[shell_of(k, dk, nshell)] += 0.5 * (c * c + s * s) / 40.0;
            }
        }
        for (a, b) in got.sums.iter().zip(&sums) {
            assert!((a - b).abs() < 1e-9 * b.max(1.0), "{a} vs {b}");
        }
    }

    /// Uniform random points have S(k) = 1 at every k: the shell means lie
    /// within their errors of 1 (mean squared deviation ≈ 1 SE²).
    #[test]
    fn an_ideal_gas_has_s_one() {
        let mut rng = Pcg64::seed_from_u64(9);
        let sb = SimBox::periodic(20.0, 20.0);
        let mut sf = StructureFactor::new(&sb, 1.0, 0.0, 1.0).unwrap();
        for t in 0..BLOCKS {
            let x: Vec<f64> = (0..300).map(|_| rng.random_range(0.0..20.0)).collect();
            let y: Vec<f64> = (0..300).map(|_| rng.random_range(0.0..20.0)).collect();
            sf.add((t as f64 + 0.5) / BLOCKS as f64, &x, &y);
        }
        let r = sf.report().unwrap();
        assert_eq!(r.snapshots, BLOCKS);
        let z2: f64 =
            r.s.iter()
                .zip(&r.std_error)
                .map(|(s, e)| ((s - 1.0) / e).powi(2))
                .sum::<f64>()
                / r.s.len() as f64;
        assert!((0.6..1.6).contains(&z2), "mean squared deviation {z2}");
        assert!(r.translational < 0.2, "{}", r.translational);
    }

    /// A perfect triangular lattice: a Bragg peak of height N at a reciprocal
    /// vector of length 4π/(√3 a), ψ_T = 1, and S = 0 at the vectors between.
    #[test]
    fn a_crystal_has_bragg_peaks_and_translational_order_one() {
        let (sb, x, y) = triangular(16, 18, 1.0);
        let one = snapshot_sk(&sb, 1.0, &x, &y);
        let n = x.len() as f64;
        assert!((one.peak.0 - n).abs() < 1e-6 * n, "{:?}", one.peak);
        let g = one.peak.1.hypot(one.peak.2);
        let g0 = 4.0 * std::f64::consts::PI / 3f64.sqrt();
        assert!((g - g0).abs() < 1e-9, "{g} vs {g0}");
        // The shells below the first Bragg shell hold only S = 0.
        let (dk, _, _) = shells(&sb, 1.0);
        for sh in 0..shell_of(g0, dk, one.sums.len()) {
            assert!(one.sums[sh] < 1e-9 * n, "shell {sh}: {}", one.sums[sh]);
        }
        let mut sf = StructureFactor::new(&sb, 1.0, 0.0, 1.0).unwrap();
        sf.add(0.0, &x, &y);
        sf.add(0.5, &x, &y);
        let r = sf.report().unwrap();
        assert!((r.translational - 1.0).abs() < 1e-9);
    }

    const TP: f64 = 2.0 * std::f64::consts::PI;

    /// A box 4π × 8π: Δk_x = 1/2 and Δk_y = 1/4 exactly (k = (n/2, m/4)), shells
    /// 2π/4π = 1/2 wide; with σ_min = 1.25, k_max = min(10/1.25, 511·2π/8π) = 8.
    fn exact_box() -> SimBox {
        SimBox::periodic(2.0 * TP, 4.0 * TP)
    }

    /// S(k) of two discs r_1, r_2: |e^{−ik·r_1} + e^{−ik·r_2}|²/2 = 1 + cos(k·d),
    /// d = r_2 − r_1.
    fn two_disc_s(kx: f64, ky: f64, d: (f64, f64)) -> f64 {
        1.0 + (kx * d.0 + ky * d.1).cos()
    }

    /// Shell sums, counts and the peak of two discs in `exact_box` at k_max = 8,
    /// from the whole k-plane: every vector 0 < |k| ≤ 8 (k = (n/2, m/4)) counts ½
    /// towards shell round(2|k|), since k and −k give the same S. The peak is
    /// the largest 1 + cos(k·d) over the half plane (n > 0, or n = 0 < m).
    fn two_disc_expected(d: (f64, f64)) -> (Vec<f64>, Vec<f64>, (f64, f64, f64)) {
        let (mut sums, mut counts) = (vec![0.0; 17], vec![0.0; 17]);
        let mut best = (f64::NEG_INFINITY, 0.0, 0.0);
        let mut second = f64::NEG_INFINITY;
        for n in -20i64..=20 {
            for m in -40i64..=40 {
                let (kx, ky) = (n as f64 * 0.5, m as f64 * 0.25);
                let k = kx.hypot(ky);
                if k == 0.0 || k > 8.0 {
                    continue;
                }
                let s = two_disc_s(kx, ky, d);
                let sh = (2.0 * k).round() as usize;
                sums[sh] += 0.5 * s;
                counts[sh] += 0.5;
                if n > 0 || (n == 0 && m > 0) {
                    if s > best.0 {
                        second = best.0;
                        best = (s, kx, ky);
                    } else if s > second {
                        second = s;
                    }
                }
            }
        }
        // The largest stands out of the next, beyond the NUFFT's rounding.
        assert!(best.0 - second > 1e-6, "{best:?} vs {second}");
        (sums, counts, best)
    }

    /// The shell parameters worked by hand in a non-square box, with k_max set
    /// by σ_min and by the mode cap, and the shell of a vector.
    #[test]
    fn shells_follow_the_box_and_the_smallest_diameter() {
        // 9 × 7, σ_min = 0.8: Δk = 2π/7; k_max = min(10/0.8 = 12.5, 511·2π/9 ≈ 357);
        // k_max/Δk = 87.5/2π = 13.93 → 14 shells after shell 0.
        let (dk, nshell, k_max) = shells(&SimBox::periodic(9.0, 7.0), 0.8);
        assert!((dk - TP / 7.0).abs() < 1e-15, "{dk}");
        assert_eq!(nshell, 15);
        assert!((k_max - 12.5).abs() < 1e-14, "{k_max}");
        // 300 × 400, σ_min = 0.01: Δk = 2π/300; k_max = min(1000, 511·2π/400)
        // = 511π/200; k_max/Δk = 511·300/400 = 383.25 → 383 → 384 shells.
        let (dk, nshell, k_max) = shells(&SimBox::periodic(300.0, 400.0), 0.01);
        assert!((dk - TP / 300.0).abs() < 1e-17, "{dk}");
        assert_eq!(nshell, 384);
        let cap = 511.0 * std::f64::consts::PI / 200.0;
        assert!((k_max - cap).abs() < 1e-13, "{k_max} vs {cap}");
        // Exact box: Δk = 1/2, k_max = 8, 8/(1/2) + 1 = 17 shells.
        assert_eq!(shells(&exact_box(), 1.25), (0.5, 17, 8.0));
        // Shell s holds round(k/Δk) = s: 1.24/0.5 = 2.48 → 2, 1.26/0.5 = 2.52 → 3,
        // 0.2/0.5 = 0.4 → 0, k_max = 8 → 16.
        assert_eq!(shell_of(1.24, 0.5, 17), 2);
        assert_eq!(shell_of(1.26, 0.5, 17), 3);
        assert_eq!(shell_of(0.2, 0.5, 17), 0);
        assert_eq!(shell_of(8.0, 0.5, 17), 16);
    }

    /// Two discs at d = (2.3, 4.1): S = 1 + cos(k·d) on every vector, the shells
    /// counted over the half plane including the two vectors exactly at k_max
    /// ((8, 0) and (0, 8), both in shell 16), and the peak vector.
    #[test]
    fn two_discs_give_one_plus_cos_on_every_vector() {
        let d = (2.3, 4.1);
        let (x, y) = ([0.7, 0.7 + d.0], [1.9, 1.9 + d.1]);
        let got = snapshot_sk(&exact_box(), 1.25, &x, &y);
        let (sums, counts, best) = two_disc_expected(d);
        assert_eq!(got.n, 2);
        // Shell 0 holds no vector (the shortest, (0, 1/4), rounds to 1); shell 1
        // (|k| in [1/4, 3/4)) holds (0, 1/4), (0, 1/2), (1/2, 0), (1/2, ±1/4),
        // (1/2, ±1/2): 7.
        assert_eq!((got.counts[0], got.counts[1]), (0, 7));
        assert_eq!(got.counts.len(), 17);
        for sh in 0..17 {
            assert_eq!(got.counts[sh] as f64, counts[sh], "shell {sh}");
            assert!((got.sums[sh] - sums[sh]).abs() < 1e-9, "shell {sh}");
        }
        // The two vectors at |k| = k_max count: without them shell 16 has 2 fewer.
        assert!(counts[16] >= 2.0);
        assert!(
            (got.peak.0 - best.0).abs() < 1e-9,
            "{:?} vs {best:?}",
            got.peak
        );
        assert_eq!((got.peak.1, got.peak.2), (best.1, best.2));
    }

    /// One disc: S = |e^{−ik·r}|² = 1 at every vector, wherever the disc is
    /// (also outside the box, by a period).
    #[test]
    fn one_disc_has_s_one_at_every_vector() {
        for (x, y) in [(0.0, 0.0), (3.3, 20.1), (3.3 - 2.0 * TP, 20.1 + 4.0 * TP)] {
            let got = snapshot_sk(&exact_box(), 1.25, &[x], &[y]);
            for sh in 0..17 {
                let c = got.counts[sh] as f64;
                assert!((got.sums[sh] - c).abs() < 1e-9 * c.max(1.0), "shell {sh}");
            }
            assert!((got.peak.0 - 1.0).abs() < 1e-9);
        }
    }

    /// Snapshots enter by time block, [2, 6] in 16 blocks of 1/4: the first of
    /// each block only, none before t0 or without discs, the one at t1 in the
    /// last block; the report averages S per shell over them.
    #[test]
    fn the_report_averages_the_first_snapshot_of_each_block() {
        let sb = exact_box();
        let mut sf = StructureFactor::new(&sb, 1.25, 2.0, 6.0).unwrap();
        let pair = |d: (f64, f64)| ([0.7, 0.7 + d.0], [1.9, 1.9 + d.1]);
        let (da, db, dc, dd) = ((0.4, 0.3), (2.3, 4.1), (1.1, 13.7), (5.2, 0.6));
        let (a, b, c, e) = (pair(da), pair(db), pair(dc), pair(dd));
        sf.add(1.9, &a.0, &a.1); // before t0
        sf.add(2.0, &b.0, &b.1); // t0: block 0
        sf.add(2.1, &a.0, &a.1); // block 0 again
        sf.add(2.3, &[], &[]); // block 1, no discs
        sf.add(2.3, &c.0, &c.1); // block 1
        sf.add(6.0, &e.0, &e.1); // t1: block 15
        sf.add(7.0, &a.0, &a.1); // after t1: block 15 again
        let r = sf.report().unwrap();
        assert_eq!(r.snapshots, 3);
        let exp: Vec<_> = [db, dc, dd].map(two_disc_expected).into();
        let counts = &exp[0].1;
        // Shell 0 is empty, so the shells reported are 1..=16 at k = s/2.
        let ks: Vec<f64> = (1..17).map(|s| s as f64 * 0.5).collect();
        assert_eq!(r.k, ks);
        let mut top = (0, f64::NEG_INFINITY);
        for (sh, &count) in counts.iter().enumerate().skip(1) {
            let i = sh - 1;
            assert_eq!(r.vectors[i] as f64, count);
            // Per snapshot the shell mean is its sum over its count.
            let per: Vec<f64> = exp.iter().map(|e| e.0[sh] / count).collect();
            let mean = per.iter().sum::<f64>() / 3.0;
            let var = per.iter().map(|p| (p - mean).powi(2)).sum::<f64>() / 2.0;
            assert!(
                (r.s[i] - mean).abs() < 1e-9,
                "shell {sh}: {} vs {mean}",
                r.s[i]
            );
            assert!((r.std_error[i] - (var / 3.0).sqrt()).abs() < 1e-9);
            // The first peak: k ≥ π/σ_min (σ_min = 1.25), short of the last
            // shell (16, cut by k_max).
            let k = sh as f64 * 0.5;
            if k >= K_STAR_MIN_SIGMA / 1.25 && sh < 16 && mean > top.1 {
                top = (sh, mean);
            }
        }
        assert!(top.0 >= 6, "{top:?}");
        assert_eq!(r.peak_k, Some(top.0 as f64 * 0.5));
        assert!((r.peak_s.unwrap() - top.1).abs() < 1e-9);
        // ψ_T = √(S_max/N) per snapshot, N = 2; its vector from the last (dd).
        let psi: Vec<f64> = exp.iter().map(|e| (e.2 .0 / 2.0).sqrt()).collect();
        let mean = psi.iter().sum::<f64>() / 3.0;
        assert!((r.translational - mean).abs() < 1e-9);
        assert_eq!(r.translational_k, [exp[2].2 .1, exp[2].2 .2]);
    }

    /// A window of no length (t0 = t1) or an undefined one (t1 NaN) takes no
    /// snapshot.
    #[test]
    fn a_window_without_length_takes_no_snapshot() {
        for t1 in [3.0, f64::NAN] {
            let mut sf = StructureFactor::new(&exact_box(), 1.25, 3.0, t1).unwrap();
            sf.add(3.0, &[1.0, 2.0], &[1.0, 5.0]);
            sf.add(3.5, &[1.0, 2.0], &[1.0, 5.0]);
            assert!(sf.report().is_none(), "t1 = {t1}");
        }
    }
}
