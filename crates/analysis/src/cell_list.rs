//! Every pair of discs closer than a cut-off r_c in one snapshot, in O(N): a cell
//! list with cells at least r_c wide, visited with a half stencil (the own cell
//! and four neighbours) so that each unordered pair is seen once, over positions
//! copied in cell order. Separations are minimum images along periodic axes
//! (r_c ≤ L/2 there): a neighbour across the edge is shifted by ±L. The rows of cells
//! are split into a fixed number of contiguous chunks that run on all cores
//! (rayon) and are merged in chunk order, so floating-point sums are the same on
//! every run (g(r), g6(r); physics.md §10–§11).

use carom_core::{Boundary, SimBox, Species};
use rayon::prelude::*;

/// [σ_min, σ_max], the extreme contact diameters among the species with discs,
/// and r_max, the farthest a pair separation is measured: `r_max_sigma` σ_max at
/// most, half a periodic edge (the minimum image), a walled edge less σ_min.
pub fn pair_reach(species: &[Species], sim_box: &SimBox, r_max_sigma: f64) -> [f64; 3] {
    let radii = || species.iter().filter(|s| s.count > 0).map(|s| s.radius);
    let sigma_min = 2.0 * radii().fold(f64::INFINITY, f64::min);
    let sigma_max = 2.0 * radii().fold(0.0, f64::max);
    let mut r_max = r_max_sigma * sigma_max;
    for (l, b) in [sim_box.size.x, sim_box.size.y]
        .iter()
        .zip(sim_box.boundary)
    {
        r_max = r_max.min(match b {
            Boundary::Periodic => 0.5 * l,
            Boundary::Walls { .. } => l - sigma_min,
        });
    }
    [sigma_min, sigma_max, r_max]
}

/// Chunks of rows (fixed, so the merge order does not depend on the threads).
const CHUNKS: usize = 16;

/// Cells of one snapshot, rebuilt by [`CellList::build`].
#[derive(Debug, Clone, Default)]
pub struct CellList {
    cx: usize,
    cy: usize,
    periodic: [bool; 2],
    size: [f64; 2],
    r2_cut: f64,
    /// Discs sorted by cell; cell c holds `order[starts[c]..starts[c + 1]]`.
    order: Vec<u32>,
    starts: Vec<u32>,
    /// The positions in that order (`xs[k]` is disc `order[k]`'s), so that the
    /// pair loops read memory in sequence.
    xs: Vec<f64>,
    ys: Vec<f64>,
}

impl CellList {
    /// Sort the discs at (`x`, `y`) into cells at least `r_cut` wide.
    pub fn build(&mut self, sim_box: &SimBox, r_cut: f64, x: &[f64], y: &[f64]) {
        let (lx, ly) = (sim_box.size.x, sim_box.size.y);
        let per = sim_box.boundary.map(|b| b.is_periodic());
        // Fewer than 3 cells along a periodic axis would visit a neighbour
        // twice, so such an axis gets a single cell.
        let ncell = |l: f64, p: bool| {
            let n = ((l / r_cut).floor() as usize).max(1);
            if p && n < 3 {
                1
            } else {
                n.min(1 << 12)
            }
        };
        let (cx, cy) = (ncell(lx, per[0]), ncell(ly, per[1]));
        let cell_of =
            |v: f64, l: f64, n: usize| (((v / l) * n as f64).floor().max(0.0) as usize).min(n - 1);
        let cells: Vec<usize> = x
            .iter()
            .zip(y)
            .map(|(&x, &y)| cell_of(y, ly, cy) * cx + cell_of(x, lx, cx))
            .collect();
        self.starts.clear();
        self.starts.resize(cx * cy + 1, 0);
        for &c in &cells {
            self.starts[c + 1] += 1;
        }
        for c in 0..cx * cy {
            self.starts[c + 1] += self.starts[c];
        }
        let mut fill = self.starts.clone();
        self.order.clear();
        self.order.resize(x.len(), 0);
        for (i, &c) in cells.iter().enumerate() {
            self.order[fill[c] as usize] = i as u32;
            fill[c] += 1;
        }
        self.xs.clear();
        self.xs.extend(self.order.iter().map(|&i| x[i as usize]));
        self.ys.clear();
        self.ys.extend(self.order.iter().map(|&i| y[i as usize]));
        (self.cx, self.cy, self.periodic) = (cx, cy, per);
        self.size = [lx, ly];
        self.r2_cut = r_cut * r_cut;
    }

    /// Fold `visit(acc, i, j, r)` over every unordered pair i ≠ j at distance
    /// r < r_cut (of the positions last given to [`CellList::build`]): each chunk of rows
    /// folds into its own `zero()`, and the chunks are merged in order.
    pub fn fold_pairs<A, Z, V, M>(&self, zero: Z, visit: V, merge: M) -> A
    where
        A: Send,
        Z: Fn() -> A + Sync,
        V: Fn(&mut A, usize, usize, f64) + Sync,
        M: Fn(&mut A, A),
    {
        let (cx, cy, per) = (self.cx, self.cy, self.periodic);
        let [lx, ly] = self.size;
        // A periodic axis of one cell needs the minimum image for every pair
        // along it; with 3 or more cells (never 2) a pair closer than r_cut lies
        // in the same or adjacent cells, and crossing the edge is a shift by ±L.
        let image = [per[0] && cx == 1, per[1] && cy == 1];
        let min_image = |d: f64, l: f64, on: bool| {
            if on && d > 0.5 * l {
                d - l
            } else if on && d < -0.5 * l {
                d + l
            } else {
                d
            }
        };
        let (xs, ys, order, r2_cut) = (&self.xs[..], &self.ys[..], &self.order[..], self.r2_cut);
        // Disc at place `a` against the places `nb` (coordinates shifted by
        // (sx, sy)).
        let against = |acc: &mut A, a: usize, nb: std::ops::Range<usize>, sx: f64, sy: f64| {
            let (xa, ya, i) = (xs[a], ys[a], order[a] as usize);
            let others = xs[nb.clone()].iter().zip(&ys[nb.clone()]).zip(&order[nb]);
            for ((&xj, &yj), &j) in others {
                let dx = min_image((xj - xa) + sx, lx, image[0]);
                let dy = min_image((yj - ya) + sy, ly, image[1]);
                let r2 = dx * dx + dy * dy;
                if r2 < r2_cut {
                    visit(acc, i, j as usize, r2.sqrt());
                }
            }
        };
        const HALF: [(i64, i64); 4] = [(1, 0), (-1, 1), (0, 1), (1, 1)];
        // The neighbour's index along an axis and the shift of its coordinates.
        let wrap = |k: i64, nc: usize, p: bool, l: f64| -> Option<(usize, f64)> {
            let n = nc as i64;
            match (p, k) {
                (true, k) if k < 0 => Some(((k + n) as usize, -l)),
                (true, k) if k >= n => Some(((k - n) as usize, l)),
                (_, k) => (0..n).contains(&k).then_some((k as usize, 0.0)),
            }
        };
        let cell = |c: usize| self.starts[c] as usize..self.starts[c + 1] as usize;
        let row = |acc: &mut A, gy: usize| {
            for gx in 0..cx {
                let own = cell(gy * cx + gx);
                for a in own.clone() {
                    against(acc, a, a + 1..own.end, 0.0, 0.0);
                }
                for &(ox, oy) in &HALF {
                    if (ox != 0 && cx == 1) || (oy != 0 && cy == 1) {
                        continue;
                    }
                    let (Some((nx, sx)), Some((ny, sy))) = (
                        wrap(gx as i64 + ox, cx, per[0], lx),
                        wrap(gy as i64 + oy, cy, per[1], ly),
                    ) else {
                        continue;
                    };
                    let nb = cell(ny * cx + nx);
                    for a in own.clone() {
                        against(acc, a, nb.clone(), sx, sy);
                    }
                }
            }
        };
        let per_chunk = cy.div_ceil(CHUNKS);
        let chunks: Vec<A> = (0..cy.div_ceil(per_chunk))
            .into_par_iter()
            .map(|c| {
                let mut acc = zero();
                for gy in c * per_chunk..((c + 1) * per_chunk).min(cy) {
                    row(&mut acc, gy);
                }
                acc
            })
            .collect();
        let mut total = zero();
        for c in chunks {
            merge(&mut total, c);
        }
        total
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use carom_core::DVec2;
    use rand::{RngExt, SeedableRng};
    use rand_pcg::Pcg64;

    /// A box with `per[k]` telling whether axis k is periodic (else elastic walls).
    fn boxed(lx: f64, ly: f64, per: [bool; 2]) -> SimBox {
        let b = |p: bool| {
            if p {
                Boundary::Periodic
            } else {
                Boundary::Walls { restitution: 1.0 }
            }
        };
        SimBox {
            size: DVec2::new(lx, ly),
            boundary: [b(per[0]), b(per[1])],
        }
    }

    /// Every pair the cell list visits, as (i < j, r), sorted; each chunk
    /// collects its own list and the merge appends them.
    fn visited(cl: &CellList) -> Vec<(usize, usize, f64)> {
        let mut v = cl.fold_pairs(
            Vec::new,
            |acc: &mut Vec<(usize, usize, f64)>, i, j, r| acc.push((i.min(j), i.max(j), r)),
            |a, b| a.extend(b),
        );
        v.sort_by_key(|a| (a.0, a.1));
        v
    }

    /// The O(N²) reference: every pair i < j whose minimum-image separation
    /// (d − L round(d/L) along a periodic axis, d along a walled one) is
    /// shorter than r_c.
    fn brute(sb: &SimBox, r_cut: f64, x: &[f64], y: &[f64]) -> Vec<(usize, usize, f64)> {
        let mut v = Vec::new();
        for i in 0..x.len() {
            for j in i + 1..x.len() {
                let d = sb.minimum_image(DVec2::new(x[j] - x[i], y[j] - y[i]));
                let r2 = d.x * d.x + d.y * d.y;
                if r2 < r_cut * r_cut {
                    v.push((i, j, r2.sqrt()));
                }
            }
        }
        v
    }

    /// The cell list's pairs against the brute force: the same pairs (each
    /// once), at the same distance to rounding.
    fn check(sb: &SimBox, r_cut: f64, x: &[f64], y: &[f64]) -> usize {
        let mut cl = CellList::default();
        cl.build(sb, r_cut, x, y);
        let (got, want) = (visited(&cl), brute(sb, r_cut, x, y));
        let ij = |v: &[(usize, usize, f64)]| v.iter().map(|p| (p.0, p.1)).collect::<Vec<_>>();
        assert_eq!(
            ij(&got),
            ij(&want),
            "{:?} r_c {r_cut}: {} cells x {} cells",
            sb,
            cl.cx,
            cl.cy
        );
        for (g, w) in got.iter().zip(&want) {
            assert!((g.2 - w.2).abs() <= 1e-12 * w.2, "{g:?} vs {w:?}");
        }
        want.len()
    }

    /// Random discs in the box, plus discs on the cell edges (x = k L/n, the
    /// box's edge 0, the largest double below L, and L itself: the last cell's
    /// closed edge, the same point as 0 along a periodic axis).
    fn discs(sb: &SimBox, r_cut: f64, n: usize, rng: &mut Pcg64) -> (Vec<f64>, Vec<f64>) {
        let (lx, ly) = (sb.size.x, sb.size.y);
        let mut x: Vec<f64> = (0..n).map(|_| rng.random_range(0.0..lx)).collect();
        let mut y: Vec<f64> = (0..n).map(|_| rng.random_range(0.0..ly)).collect();
        let (nx, ny) = ((lx / r_cut).floor(), (ly / r_cut).floor());
        let below = |l: f64| f64::from_bits(l.to_bits() - 1);
        for k in 0..nx as usize {
            x.push(k as f64 * lx / nx);
            y.push(rng.random_range(0.0..ly));
        }
        for k in 0..ny as usize {
            x.push(rng.random_range(0.0..lx));
            y.push(k as f64 * ly / ny);
        }
        x.extend([0.0, below(lx), below(lx), 0.0, 0.5 * lx, lx, lx, 0.3 * lx]);
        y.extend([below(ly), 0.0, below(ly), 0.0, below(ly), ly, 0.5 * ly, ly]);
        (x, y)
    }

    /// The cell list finds exactly the brute force's pairs in periodic, walled
    /// and mixed boxes, square and not, with 1, 2 (one cell then), 3 and many
    /// cells per side, r_c at L/2, more rows than chunks (42 rows: 3 a chunk),
    /// and a walled box with r_c > L/2 (one cell, no minimum image).
    #[test]
    fn cell_list_finds_exactly_the_brute_force_pairs() {
        let mut rng = Pcg64::seed_from_u64(5);
        let mut found = 0;
        for (lx, ly, r_cut) in [
            (10.0, 7.0, 3.4),   // 2 x 2 cells' worth: 1 x 1 on periodic axes
            (10.0, 7.0, 3.3),   // 3 x 2
            (7.0, 10.0, 3.3),   // 2 x 3
            (10.0, 7.0, 3.5),   // r_c = L_y/2
            (12.6, 9.1, 1.3),   // 9 x 7
            (10.0, 61.0, 1.45), // 6 x 42: more rows than chunks
            (61.0, 10.0, 1.45), // 42 x 6
            (5.0, 40.0, 2.4),   // 2 x 16
            (30.0, 4.0, 3.7),   // 8 x 1: a channel
        ] {
            for per in [[true, true], [false, false], [true, false], [false, true]] {
                let sb = boxed(lx, ly, per);
                let (x, y) = discs(&sb, r_cut, 160, &mut rng);
                found += check(&sb, r_cut, &x, &y);
            }
        }
        // A walled box with r_c > L/2: pairs farther apart than L/2 are not
        // wrapped (a minimum image would bring 9.4 down to 0.6).
        let sb = boxed(10.0, 7.0, [false, false]);
        let (x, y) = discs(&sb, 6.2, 60, &mut rng);
        found += check(&sb, 6.2, &x, &y);
        let (x, y) = (vec![0.3, 9.7, 0.3], vec![3.0, 3.0, 6.5]);
        assert_eq!(check(&sb, 6.2, &x, &y), 1, "only 0.3–0.3 at 3.5");
        assert!(found > 10_000, "{found} pairs");
    }

    /// A pair exactly r_c apart is not a pair (r < r_c): 3 apart along a wall,
    /// and 7.5 − 0.5 − 10 = −3 through a periodic edge of 3 cells 10/3 wide.
    #[test]
    fn a_pair_exactly_at_the_cut_off_is_left_out() {
        let (x, y) = (vec![1.0, 4.0, 0.5, 7.5], vec![5.0, 5.0, 1.0, 1.0]);
        for per in [[false, false], [true, true]] {
            let mut cl = CellList::default();
            cl.build(&boxed(10.0, 10.0, per), 3.0, &x, &y);
            assert_eq!(cl.cx, 3);
            let pairs = visited(&cl);
            assert!(pairs.iter().all(|p| p.2 < 3.0), "{per:?}: {pairs:?}");
        }
        // and 3 − 2⁻⁵⁰ apart it is one.
        let below = f64::from_bits(3f64.to_bits() - 1);
        let mut cl = CellList::default();
        cl.build(
            &boxed(10.0, 10.0, [false, false]),
            3.0,
            &[1.0, 1.0 + below],
            &[5.0; 2],
        );
        assert_eq!(visited(&cl), vec![(0, 1, below)]);
    }

    /// Cells as narrow as r_c allows, ⌊L/r_c⌋ per side (so the cost is O(N)),
    /// at most 4096, and a single one along a periodic axis with fewer than 3.
    #[test]
    fn cells_are_as_many_as_fit_at_least_r_c_wide() {
        for (lx, ly, r_cut, per, want) in [
            (10.0, 7.0, 3.3, [true, true], (3, 1)),
            (10.0, 7.0, 3.3, [false, false], (3, 2)),
            (7.0, 10.0, 3.4, [true, false], (1, 2)),
            (100.0, 55.0, 1.25, [true, true], (80, 44)),
            (100.0, 55.0, 1.25, [false, true], (80, 44)),
            (1.0, 1e-4, 2e-4, [false, false], (4096, 1)),
        ] {
            let mut cl = CellList::default();
            cl.build(&boxed(lx, ly, per), r_cut, &[0.5], &[0.5]);
            assert_eq!((cl.cx, cl.cy), want, "{lx} x {ly}, r_c {r_cut}, {per:?}");
        }
    }

    /// σ_min, σ_max over the species that have discs (an empty one of radius
    /// 0.1 or 2 counts for neither), and r_max = min(r_max_sigma σ_max, L/2
    /// on a periodic axis, L − σ_min on a walled one).
    #[test]
    fn pair_reach_takes_the_extreme_diameters_and_the_box_limits() {
        let sp = [
            Species::new(3, 0.3, 2.0),
            Species::new(0, 0.1, 1.0),
            Species::new(2, 0.45, 0.5),
            Species::new(0, 2.0, 1.0),
        ];
        let close = |a: [f64; 3], b: [f64; 3]| a.iter().zip(&b).all(|(u, v)| (u - v).abs() < 1e-12);
        for (sb, r_max_sigma, want) in [
            // 25 · 0.9 = 22.5 against 9/2 and 7/2
            (boxed(9.0, 7.0, [true, true]), 25.0, [0.6, 0.9, 3.5]),
            // against 9 − 0.6 and 7 − 0.6
            (boxed(9.0, 7.0, [false, false]), 25.0, [0.6, 0.9, 6.4]),
            // 9/2 against 7 − 0.6
            (boxed(9.0, 7.0, [true, false]), 25.0, [0.6, 0.9, 4.5]),
            // 4 · 0.9 = 3.6 against 9 − 0.6 and 9/2
            (boxed(9.0, 9.0, [false, true]), 4.0, [0.6, 0.9, 3.6]),
            // 9 − 0.6 against 30/2
            (boxed(9.0, 30.0, [false, true]), 25.0, [0.6, 0.9, 8.4]),
        ] {
            let got = pair_reach(&sp, &sb, r_max_sigma);
            assert!(close(got, want), "{:?}: {got:?} vs {want:?}", sb.boundary);
        }
    }
}
