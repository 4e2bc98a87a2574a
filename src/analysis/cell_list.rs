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
