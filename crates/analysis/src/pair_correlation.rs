//! The pair correlation g_ab(r) per species pair (physics.md §10), streamed over
//! snapshots: each snapshot's pair distances (minimum image along periodic axes,
//! a cell list, [`super::cell_list`]) go into a histogram of one of
//! [`BLOCKS`] equal time blocks, so memory is independent of the number of
//! snapshots. g is the count over the exact ideal-gas count (10.1):
//! N_a N_b' P_ab(shell), with b' = N_b − δ_ab (unordered pairs: halved when
//! a = b) and P_ab the probability that two independent uniform centres in their
//! reachable regions lie a distance in the shell apart: π(r₂² − r₁²)/A in a
//! periodic box, a deterministic numerical integral of the product of the
//! per-axis densities of the separation (10.2) with walls. Error bars are the
//! standard error of the block means.

use carom_core::{Boundary, SimBox, Species};

use super::cell_list::{pair_reach, CellList};

/// Number of equal time blocks over the window (error bars from their spread).
pub const BLOCKS: usize = 16;
/// Default bin width in units of the smallest contact distance σ_min.
pub const BIN_WIDTH_SIGMA: f64 = 1.0 / 50.0;
/// Default r_max in units of the largest contact distance (also at most half a
/// periodic edge and at most the reachable width of a walled axis).
pub const R_MAX_SIGMA: f64 = 10.0;

/// Accumulates pair-distance histograms per species pair and time block.
#[derive(Debug, Clone)]
pub struct PairCorrelation {
    pub(super) species: Vec<Species>,
    pub(super) sim_box: SimBox,
    pub(super) dr: f64,
    pub(super) r_max: f64,
    pub(super) nbins: usize,
    t0: f64,
    block_time: f64,
    /// counts[block][pair][bin], pair index over a ≤ b.
    counts: Vec<Vec<Vec<u64>>>,
    /// Snapshots per block.
    pub(super) snapshots: Vec<u64>,
    /// Cell list scratch.
    cells: CellList,
}

/// Index of the unordered species pair (a ≤ b) among `ns` species.
pub fn pair_index(a: usize, b: usize, ns: usize) -> usize {
    let (a, b) = if a <= b { (a, b) } else { (b, a) };
    a * ns - a * (a + 1) / 2 + b
}

/// The unordered species pairs (a, b), a ≤ b, in [`pair_index`] order.
pub fn pairs(ns: usize) -> Vec<(usize, usize)> {
    (0..ns).flat_map(|a| (a..ns).map(move |b| (a, b))).collect()
}

impl PairCorrelation {
    /// An accumulator for `species` in `sim_box` over the window [t0, t1].
    pub fn new(species: &[Species], sim_box: &SimBox, t0: f64, t1: f64) -> Self {
        let [sigma_min, _, r_max] = pair_reach(species, sim_box, R_MAX_SIGMA);
        let dr = BIN_WIDTH_SIGMA * sigma_min;
        let nbins = ((r_max / dr).floor() as usize).max(1);
        let r_max = nbins as f64 * dr;
        let ns = species.len();
        let np = ns * (ns + 1) / 2;
        PairCorrelation {
            species: species.to_vec(),
            sim_box: *sim_box,
            dr,
            r_max,
            nbins,
            t0,
            block_time: (t1 - t0) / BLOCKS as f64,
            counts: vec![vec![vec![0; nbins]; np]; BLOCKS],
            snapshots: vec![0; BLOCKS],
            cells: CellList::default(),
        }
    }

    /// Bin centres (length).
    pub fn r(&self) -> Vec<f64> {
        (0..self.nbins)
            .map(|k| (k as f64 + 0.5) * self.dr)
            .collect()
    }

    /// Add the pair distances of one snapshot at time `t` (ignored outside the
    /// window). `species_of`, `x`, `y` have one entry per disc.
    pub fn add(&mut self, t: f64, species_of: &[u16], x: &[f64], y: &[f64]) {
        if t < self.t0 || self.block_time.is_nan() || self.block_time <= 0.0 {
            return;
        }
        let blk = (((t - self.t0) / self.block_time) as usize).min(BLOCKS - 1);
        self.cells.build(&self.sim_box, self.r_max, x, y);
        let ns = self.species.len();
        let (inv_dr, nbins) = (1.0 / self.dr, self.nbins);
        let np = self.counts[blk].len();
        // Integer counts: the same sum in any order.
        let local = self.cells.fold_pairs(
            || vec![vec![0u64; nbins]; np],
            |hist, i, j, r| {
                let k = ((r * inv_dr) as usize).min(nbins - 1);
                hist[pair_index(species_of[i] as usize, species_of[j] as usize, ns)][k] += 1;
            },
            |a, b| {
                for (x, y) in a.iter_mut().zip(&b) {
                    for (u, v) in x.iter_mut().zip(y) {
                        *u += v;
                    }
                }
            },
        );
        for (x, y) in self.counts[blk].iter_mut().zip(&local) {
            for (u, v) in x.iter_mut().zip(y) {
                *u += v;
            }
        }
        self.snapshots[blk] += 1;
    }

    /// Expected count of unordered (a, b) pairs per snapshot in each bin for an
    /// ideal gas (10.1).
    pub fn ideal_counts(&self, a: usize, b: usize) -> Vec<f64> {
        let (na, nb) = (self.species[a].count as f64, self.species[b].count as f64);
        let pairs = if a == b {
            0.5 * na * (na - 1.0)
        } else {
            na * nb
        };
        (0..self.nbins)
            .map(|k| {
                let (r1, r2) = (k as f64 * self.dr, (k + 1) as f64 * self.dr);
                pairs * self.shell_probability(a, b, r1, r2)
            })
            .collect()
    }

    /// Probability that independent uniform centres of species a and b in their
    /// reachable regions lie between r1 and r2 apart (10.2).
    pub fn shell_probability(&self, a: usize, b: usize, r1: f64, r2: f64) -> f64 {
        let sb = &self.sim_box;
        if sb.boundary.iter().all(|b| b.is_periodic()) {
            return std::f64::consts::PI * (r2 * r2 - r1 * r1) / (sb.size.x * sb.size.y);
        }
        let (ra, rb) = (self.species[a].radius, self.species[b].radius);
        let density = |l: f64, bd: Boundary| -> Box<dyn Fn(f64) -> f64> {
            match bd {
                Boundary::Periodic => Box::new(move |_| 1.0 / l),
                Boundary::Walls { .. } => {
                    let (wa, wb) = ((l - 2.0 * ra).max(0.0), (l - 2.0 * rb).max(0.0));
                    Box::new(move |d: f64| separation_density(d.abs(), wa, wb))
                }
            }
        };
        let fx = density(sb.size.x, sb.boundary[0]);
        let fy = density(sb.size.y, sb.boundary[1]);
        // Gauss–Legendre (4 points) in r, midpoint rule in θ over a quarter turn
        // (both densities are even).
        const GL: [(f64, f64); 4] = [
            (-0.861_136_311_594_052_6, 0.347_854_845_137_453_85),
            (-0.339_981_043_584_856_3, 0.652_145_154_862_546_1),
            (0.339_981_043_584_856_3, 0.652_145_154_862_546_1),
            (0.861_136_311_594_052_6, 0.347_854_845_137_453_85),
        ];
        const NT: usize = 512;
        let (mid, half) = (0.5 * (r1 + r2), 0.5 * (r2 - r1));
        let mut total = 0.0;
        for (xi, w) in GL {
            let r = mid + half * xi;
            let mut ang = 0.0;
            for k in 0..NT {
                let th = (k as f64 + 0.5) * std::f64::consts::FRAC_PI_2 / NT as f64;
                ang += fx(r * th.cos()) * fy(r * th.sin());
            }
            total += w * half * r * 4.0 * ang * std::f64::consts::FRAC_PI_2 / NT as f64;
        }
        total
    }

    /// g per block for pair (a, b) (`None` for blocks without snapshots), and the
    /// pooled g over all snapshots.
    pub fn g(&self, a: usize, b: usize) -> (Vec<Option<Vec<f64>>>, Vec<f64>) {
        let p = pair_index(a, b, self.species.len());
        let ideal = self.ideal_counts(a, b);
        let norm = |c: &[u64], s: u64| -> Vec<f64> {
            c.iter()
                .zip(&ideal)
                .map(|(&c, &i)| {
                    if i > 0.0 {
                        c as f64 / (s as f64 * i)
                    } else {
                        f64::NAN
                    }
                })
                .collect()
        };
        let blocks = (0..BLOCKS)
            .map(|k| (self.snapshots[k] > 0).then(|| norm(&self.counts[k][p], self.snapshots[k])))
            .collect();
        let total: Vec<u64> = (0..self.nbins)
            .map(|j| (0..BLOCKS).map(|k| self.counts[k][p][j]).sum())
            .collect();
        let s: u64 = self.snapshots.iter().sum();
        (blocks, norm(&total, s.max(1)))
    }

    /// Snapshots added.
    pub fn snapshot_count(&self) -> u64 {
        self.snapshots.iter().sum()
    }
}

/// Density of the separation d ≥ 0 along one walled axis of two independent
/// uniform coordinates on centred intervals of widths `wa`, `wb` (the
/// convolution of two boxes: a trapezoid), counted for +d and −d together
/// halved, i.e. the density at d.
fn separation_density(d: f64, wa: f64, wb: f64) -> f64 {
    if wa <= 0.0 || wb <= 0.0 {
        return 0.0;
    }
    let flat = 0.5 * (wa - wb).abs();
    let v = if d <= flat {
        wa.min(wb)
    } else {
        (0.5 * (wa + wb) - d).max(0.0)
    };
    v / (wa * wb)
}

/// Mean and standard error of the mean of `x` (NaN error for fewer than 2).
pub(super) fn mean_se(x: &[f64]) -> (f64, f64) {
    let n = x.len() as f64;
    let m = x.iter().sum::<f64>() / n;
    if x.len() < 2 {
        return (m, f64::NAN);
    }
    let v = x.iter().map(|v| (v - m).powi(2)).sum::<f64>() / (n - 1.0);
    (m, (v / n).sqrt())
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{RngExt, SeedableRng};
    use rand_pcg::Pcg64;

    fn uniform(n: usize, lo: [f64; 2], hi: [f64; 2], rng: &mut Pcg64) -> (Vec<f64>, Vec<f64>) {
        let x = (0..n).map(|_| rng.random_range(lo[0]..hi[0])).collect();
        let y = (0..n).map(|_| rng.random_range(lo[1]..hi[1])).collect();
        (x, y)
    }

    /// Uniformly random positions (an ideal gas) give g ≈ 1 within errors at
    /// every r: periodic, and in a closed box where the normalisation is the
    /// numerical integral.
    #[test]
    fn ideal_gas_has_g_one_within_errors() {
        for walls in [false, true] {
            let sb = if walls {
                SimBox::walled(12.0, 9.0, 1.0)
            } else {
                SimBox::periodic(12.0, 9.0)
            };
            let sp = vec![Species::reference(200)];
            let mut pc = PairCorrelation::new(&sp, &sb, 0.0, 1.0);
            let mut rng = Pcg64::seed_from_u64(7);
            let (lo, hi) = if walls {
                ([0.5; 2], [11.5, 8.5])
            } else {
                ([0.0; 2], [12.0, 9.0])
            };
            for s in 0..320 {
                let (x, y) = uniform(200, lo, hi, &mut rng);
                pc.add(s as f64 / 320.0, &[0; 200], &x, &y);
            }
            let (blocks, pooled) = pc.g(0, 0);
            let blocks: Vec<Vec<f64>> = blocks.into_iter().flatten().collect();
            assert_eq!(blocks.len(), BLOCKS);
            // The squared deviations in standard errors average to 1 (15/13 for
            // a t distribution with 15 degrees of freedom); a bias of the
            // normalisation, or wrong error bars, moves them away.
            let mut z2 = 0.0;
            for k in 0..pc.nbins {
                let col: Vec<f64> = blocks.iter().map(|b| b[k]).collect();
                let (m, se) = mean_se(&col);
                assert!((m - pooled[k]).abs() < 1e-9);
                z2 += ((m - 1.0) / se).powi(2);
            }
            let z2 = z2 / pc.nbins as f64;
            assert!(
                (0.8..1.5).contains(&z2),
                "walls {walls}: mean squared deviation {z2} SE²"
            );
            // and on average over r it is 1 to 1 %.
            let mean = pooled.iter().sum::<f64>() / pooled.len() as f64;
            assert!((mean - 1.0).abs() < 0.01, "walls {walls}: mean g {mean}");
        }
    }

    /// The numerical shell probability with walls matches the closed form for
    /// equal widths, ∫ r [2πWH − 4r(W+H) + 2r²] dr/(W²H²).
    #[test]
    fn walled_normalisation_matches_closed_form() {
        let sb = SimBox::walled(7.0, 5.0, 1.0);
        let sp = vec![Species::reference(10)];
        let pc = PairCorrelation::new(&sp, &sb, 0.0, 1.0);
        let (w, h) = (6.0, 4.0);
        let f = |r: f64| {
            std::f64::consts::PI * w * h * r * r - 4.0 / 3.0 * (w + h) * r.powi(3) + 0.5 * r.powi(4)
        };
        for (r1, r2) in [(0.0, 0.1), (1.0, 1.02), (3.0, 3.5)] {
            let exact = (f(r2) - f(r1)) / (w * w * h * h);
            let num = pc.shell_probability(0, 0, r1, r2);
            assert!(
                (num / exact - 1.0).abs() < 1e-5,
                "{r1}..{r2}: {num} vs {exact}"
            );
        }
    }

    /// The cell list counts exactly the pairs a brute-force O(N²) loop counts,
    /// for boxes with 1 to 5 cells per axis, periodic and walled.
    #[test]
    fn cell_list_counts_every_pair_once() {
        let mut rng = Pcg64::seed_from_u64(3);
        for (lx, ly) in [(12.0, 9.0), (25.0, 31.0), (41.0, 52.0), (20.0, 55.0)] {
            for sb in [SimBox::periodic(lx, ly), SimBox::walled(lx, ly, 1.0)] {
                let sp = vec![Species::reference(150), Species::scaled(90, 1.4)];
                let mut pc = PairCorrelation::new(&sp, &sb, 0.0, 1.0);
                let (x, y) = uniform(240, [0.7; 2], [lx - 0.7, ly - 0.7], &mut rng);
                let s: Vec<u16> = (0..240).map(|i| (i >= 150) as u16).collect();
                pc.add(0.5, &s, &x, &y);
                let mut brute = vec![vec![0u64; pc.nbins]; 3];
                for i in 0..240 {
                    for j in i + 1..240 {
                        let mut d = [x[j] - x[i], y[j] - y[i]];
                        for (k, l) in [lx, ly].iter().enumerate() {
                            if sb.boundary[k].is_periodic() {
                                d[k] -= l * (d[k] / l).round();
                            }
                        }
                        let r = d[0].hypot(d[1]);
                        if r < pc.r_max {
                            let b = ((r / pc.dr) as usize).min(pc.nbins - 1);
                            brute[pair_index(s[i] as usize, s[j] as usize, 2)][b] += 1;
                        }
                    }
                }
                let blk = pc
                    .counts
                    .iter()
                    .position(|c| c[0].iter().any(|&v| v > 0))
                    .unwrap();
                assert_eq!(pc.counts[blk], brute, "{lx} x {ly} {:?}", sb.boundary);
            }
        }
    }

    #[test]
    fn pair_indices_are_a_bijection() {
        let ns = 4;
        let ps = pairs(ns);
        for (k, &(a, b)) in ps.iter().enumerate() {
            assert_eq!(pair_index(a, b, ns), k);
            assert_eq!(pair_index(b, a, ns), k);
        }
        assert_eq!(ps.len(), 10);
    }

    /// Species of unequal size and number in a periodic 9 × 7 box (σ_min = 0.6,
    /// bins 0.012 wide, r_max = 3.5 → 291 bins), over the window [2, 10]
    /// (blocks 0.5 long).
    fn two_species() -> PairCorrelation {
        let sp = [Species::new(3, 0.3, 2.0), Species::new(2, 0.45, 0.5)];
        PairCorrelation::new(&sp, &SimBox::periodic(9.0, 7.0), 2.0, 10.0)
    }

    /// The middle of bin k (bins 0.012 wide).
    fn mid(k: usize) -> f64 {
        (k as f64 + 0.5) * 0.012
    }

    /// A snapshot goes into block ⌊(t − t0)/(window/16)⌋ (the window's end into
    /// the last), one before the window or in an empty window nowhere; a pair is
    /// counted in the bin of its minimum-image distance.
    #[test]
    fn snapshots_fall_in_their_time_block_and_pairs_in_their_distance_bin() {
        let mut pc = two_species();
        assert!((pc.dr - 0.012).abs() < 1e-15 && pc.nbins == 291);
        // Two A discs at x = 0.2 and 9.2 − r: r apart through the periodic edge.
        let place = |k: usize| (vec![0.2, 9.0 - (mid(k) - 0.2)], vec![3.0, 3.0]);
        let shots = [(1.9, 10), (2.0, 20), (5.3, 57), (10.0, 70)];
        for (t, k) in shots {
            let (x, y) = place(k);
            pc.add(t, &[0, 0], &x, &y);
        }
        // 1.9 < t0: ignored; 2 → block 0; (5.3 − 2)/0.5 = 6.6 → 6; 10 → 16 → 15.
        let mut want = [0; BLOCKS];
        (want[0], want[6], want[15]) = (1, 1, 1);
        assert_eq!(pc.snapshots, want);
        assert_eq!(pc.snapshot_count(), 3);
        for (blk, k) in [(0, 20), (6, 57), (15, 70)] {
            let mut bins = vec![0; pc.nbins];
            bins[k] = 1;
            assert_eq!(pc.counts[blk][0], bins, "block {blk}");
            assert!(pc.counts[blk][1..].iter().flatten().all(|&c| c == 0));
        }
        // A window of no length takes nothing.
        let sp = [Species::new(2, 0.3, 2.0)];
        let mut empty = PairCorrelation::new(&sp, &SimBox::periodic(9.0, 7.0), 3.0, 3.0);
        let (x, y) = place(20);
        empty.add(3.0, &[0, 0], &x, &y);
        assert_eq!(empty.snapshot_count(), 0);
        assert!(empty.counts.iter().flatten().flatten().all(|&c| c == 0));
        // Bin centres (k + 1/2) dr.
        let r = pc.r();
        assert_eq!(r.len(), 291);
        assert!((r[0] - 0.006).abs() < 1e-15 && (r[57] - mid(57)).abs() < 1e-14);
    }

    /// A pair closer than r_max by one rounding counts in the last bin, even
    /// where r/dr rounds up to the number of bins (radius 0.55 in a periodic
    /// 6 × 6 box: dr = 0.022, 136 bins, r_max = 2.992).
    #[test]
    fn a_pair_just_inside_r_max_counts_in_the_last_bin() {
        let sp = [Species::new(2, 0.55, 1.0)];
        let mut pc = PairCorrelation::new(&sp, &SimBox::periodic(6.0, 6.0), 0.0, 1.0);
        assert_eq!(pc.nbins, 136);
        let mut d = pc.r_max;
        while d * d >= pc.r_max * pc.r_max {
            d = f64::from_bits(d.to_bits() - 1);
        }
        assert!(
            d * (1.0 / pc.dr) >= 136.0,
            "this distance's bin index rounds up"
        );
        pc.add(0.5, &[0, 0], &[0.0, d], &[1.0, 1.0]);
        let mut want = vec![0; 136];
        want[135] = 1;
        assert_eq!(pc.counts[8][0], want);
    }

    /// Periodic box: P = π(r₂² − r₁²)/A (10.1) and the ideal count per bin is
    /// M_ab P with M_aa = N_a(N_a − 1)/2 and M_ab = N_a N_b; g per block is the
    /// block's count per snapshot over it, the pooled g all counts over all
    /// snapshots, and a block without snapshots has none.
    #[test]
    fn g_is_the_count_per_snapshot_over_the_ideal_gas_count() {
        let mut pc = two_species();
        let area = 63.0;
        let p = |r1: f64, r2: f64| std::f64::consts::PI * (r2 * r2 - r1 * r1) / area;
        assert!((pc.shell_probability(0, 1, 0.3, 1.1) / p(0.3, 1.1) - 1.0).abs() < 1e-14);
        for (a, b, m) in [(0, 0, 3.0), (0, 1, 6.0), (1, 1, 1.0)] {
            let ideal = pc.ideal_counts(a, b);
            assert_eq!(ideal.len(), 291);
            for k in [0, 1, 52, 290] {
                let want = m * p(k as f64 * 0.012, (k + 1) as f64 * 0.012);
                assert!((ideal[k] / want - 1.0).abs() < 1e-12, "{a}{b} bin {k}");
            }
        }
        // Block 0 (t = 2.2): the A–A pair in bin 52; block 3 (t = 3.6 and 3.9):
        // once in bin 52, once in bin 60. The third A disc is beyond r_max of
        // both; B–B 3.2 apart (bin 266) in every snapshot.
        let shot = |pc: &mut PairCorrelation, t: f64, k: usize| {
            let x = [1.0, 1.0 + mid(k), 6.0, 6.0, 6.0];
            let y = [1.0, 1.0, 3.5, 1.0, 4.2];
            pc.add(t, &[0, 0, 0, 1, 1], &x, &y);
        };
        shot(&mut pc, 2.2, 52);
        shot(&mut pc, 3.6, 52);
        shot(&mut pc, 3.9, 60);
        let ideal = pc.ideal_counts(0, 0);
        let (blocks, pooled) = pc.g(0, 0);
        assert_eq!(blocks.len(), BLOCKS);
        assert!(blocks
            .iter()
            .enumerate()
            .all(|(k, b)| b.is_some() == (k == 0 || k == 3)));
        let (b0, b3) = (blocks[0].as_ref().unwrap(), blocks[3].as_ref().unwrap());
        let close = |u: f64, v: f64| (u / v - 1.0).abs() < 1e-12;
        assert!(close(b0[52], 1.0 / ideal[52]) && b0[60] == 0.0);
        assert!(close(b3[52], 1.0 / (2.0 * ideal[52])) && close(b3[60], 1.0 / (2.0 * ideal[60])));
        assert!(close(pooled[52], 2.0 / (3.0 * ideal[52])));
        assert!(close(pooled[60], 1.0 / (3.0 * ideal[60])));
        let (_, bb) = pc.g(1, 1);
        assert!(close(bb[266], 3.0 / (3.0 * pc.ideal_counts(1, 1)[266])));
    }

    /// The separation density of two uniform intervals (widths 5 and 2) is the
    /// trapezoid min(W_a, W_b, (W_a + W_b)/2 − |d|)⁺/(W_a W_b): 2/10 up to
    /// |d| = 1.5, then falling to 0 at 3.5; it integrates to 1 over all d; an
    /// interval of width ≤ 0 holds no centre.
    #[test]
    fn the_separation_density_is_the_trapezoid_of_two_intervals() {
        for (wa, wb) in [(5.0, 2.0), (2.0, 5.0)] {
            for (d, want) in [(0.0, 0.2), (1.4, 0.2), (2.5, 0.1), (3.0, 0.05), (3.6, 0.0)] {
                let v = separation_density(d, wa, wb);
                assert!((v - want).abs() < 1e-15, "{wa} {wb} {d}: {v}");
            }
            // Midpoint rule over [0, 4] (exact on each linear piece, kinks at
            // 1.5 and 3.5 on cell edges), both signs of d.
            let n = 4000;
            let total: f64 = (0..n)
                .map(|i| 2.0 * separation_density((i as f64 + 0.5) * 4.0 / n as f64, wa, wb))
                .sum::<f64>()
                * 4.0
                / n as f64;
            assert!((total - 1.0).abs() < 1e-12, "{total}");
        }
        for (wa, wb) in [(0.0, 2.0), (2.0, 0.0), (-1.0, 2.0), (2.0, -1.0)] {
            assert_eq!(separation_density(0.1, wa, wb), 0.0);
        }
    }

    /// With walls the shell probability (10.2) for a thin shell r ≤ the flat
    /// part of both trapezoids is π(r₂² − r₁²) times the flat density of each
    /// axis, 1/max(W_a, W_b) (1/L along a periodic axis); beyond it, a direct
    /// polar integral of the trapezoids written as min(…)⁺ agrees (over bins
    /// of the usual width: 4 points in r do not resolve a kink of f inside one).
    #[test]
    fn the_walled_shell_probability_uses_each_species_reach() {
        // Radii 0.3 and 1.2 in 9 × 7: W = 8.4, 6.6 along x (flat to 0.9) and
        // 6.4, 4.6 along y (flat to 0.9).
        let sp = [Species::new(4, 0.3, 1.0), Species::new(3, 1.2, 3.0)];
        let walled = PairCorrelation::new(&sp, &SimBox::walled(9.0, 7.0, 1.0), 0.0, 1.0);
        let mut channel = SimBox::walled(9.0, 7.0, 1.0);
        channel.boundary[0] = Boundary::Periodic;
        let channel = PairCorrelation::new(&sp, &channel, 0.0, 1.0);
        let ring = std::f64::consts::PI * (0.6f64.powi(2) - 0.2f64.powi(2));
        let close = |u: f64, v: f64, tol: f64| (u / v - 1.0).abs() < tol;
        let w = walled.shell_probability(0, 1, 0.2, 0.6);
        assert!(close(w, ring / (8.4 * 6.4), 1e-12), "{w}");
        let c = channel.shell_probability(1, 0, 0.2, 0.6);
        assert!(close(c, ring / (9.0 * 6.4), 1e-12), "{c}");
        // Same species: W = 6.6 and 4.6 (equal widths: no flat part).
        let trap = |d: f64, wa: f64, wb: f64| {
            (wa.min(wb).min(0.5 * (wa + wb) - d.abs())).max(0.0) / (wa * wb)
        };
        let direct = |r1: f64, r2: f64, wx: [f64; 2], wy: [f64; 2]| {
            // Midpoint rule, 10 radii × 4000 angles over the full turn.
            let (nr, nt) = (10, 4000);
            let (dr, dt) = ((r2 - r1) / nr as f64, std::f64::consts::TAU / nt as f64);
            let mut s = 0.0;
            for i in 0..nr {
                let r = r1 + (i as f64 + 0.5) * dr;
                for j in 0..nt {
                    let th = (j as f64 + 0.5) * dt;
                    s += r * trap(r * th.cos(), wx[0], wx[1]) * trap(r * th.sin(), wy[0], wy[1]);
                }
            }
            s * dr * dt
        };
        for (a, b, wx, wy) in [
            (0, 1, [8.4, 6.6], [6.4, 4.6]),
            (1, 1, [6.6, 6.6], [4.6, 4.6]),
            (1, 0, [6.6, 8.4], [4.6, 6.4]),
        ] {
            for (r1, r2) in [(0.95, 0.962), (2.0, 2.012), (4.4, 4.412)] {
                let (num, want) = (
                    walled.shell_probability(a, b, r1, r2),
                    direct(r1, r2, wx, wy),
                );
                assert!(close(num, want, 1e-4), "{a}{b} {r1}..{r2}: {num} vs {want}");
            }
        }
    }

    /// Mean and standard error of the mean: 1, 2, 4, 9 have mean 4, sample
    /// variance (9 + 4 + 0 + 25)/3 and SE √(38/3/4); one value has no error.
    #[test]
    fn mean_and_standard_error_of_the_mean() {
        let (m, se) = mean_se(&[1.0, 2.0, 4.0, 9.0]);
        assert!((m - 4.0).abs() < 1e-15 && (se - (38.0f64 / 12.0).sqrt()).abs() < 1e-15);
        let (m, se) = mean_se(&[2.5]);
        assert!(m == 2.5 && se.is_nan());
        let (m, se) = mean_se(&[3.0, 3.0]);
        assert!(m == 3.0 && se == 0.0);
    }
}
