//! Every pair of discs closer than a cut-off r_c in one snapshot, in O(N): a cell
//! list with cells at least r_c wide, visited with a half stencil (the own cell
//! and four neighbours) so that each unordered pair is seen once. Separations
//! are minimum images along periodic axes (r_c ≤ L/2 there). The rows of cells
//! are split into a fixed number of contiguous chunks that run on all cores
//! (rayon) and are merged in chunk order, so floating-point sums are the same on
//! every run (g(r), g6(r); physics.md §10–§11).

use carom_core::SimBox;
use rayon::prelude::*;

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
        (self.cx, self.cy, self.periodic) = (cx, cy, per);
        self.size = [lx, ly];
        self.r2_cut = r_cut * r_cut;
    }

    /// Fold `visit(acc, i, j, r)` over every unordered pair i ≠ j at distance
    /// r < r_cut (positions as given to [`CellList::build`]): each chunk of rows
    /// folds into its own `zero()`, and the chunks are merged in order.
    pub fn fold_pairs<A, Z, V, M>(&self, x: &[f64], y: &[f64], zero: Z, visit: V, merge: M) -> A
    where
        A: Send,
        Z: Fn() -> A + Sync,
        V: Fn(&mut A, usize, usize, f64) + Sync,
        M: Fn(&mut A, A),
    {
        let (cx, cy, per) = (self.cx, self.cy, self.periodic);
        let [lx, ly] = self.size;
        let (hx, hy) = (0.5 * lx, 0.5 * ly);
        let image = |d: f64, l: f64, h: f64, p: bool| {
            if !p {
                d
            } else if d > h {
                d - l
            } else if d < -h {
                d + l
            } else {
                d
            }
        };
        let pair = |acc: &mut A, i: usize, j: usize| {
            let dx = image(x[j] - x[i], lx, hx, per[0]);
            let dy = image(y[j] - y[i], ly, hy, per[1]);
            let r2 = dx * dx + dy * dy;
            if r2 < self.r2_cut {
                visit(acc, i, j, r2.sqrt());
            }
        };
        const HALF: [(i64, i64); 4] = [(1, 0), (-1, 1), (0, 1), (1, 1)];
        let wrap = |k: i64, nc: usize, p: bool| -> Option<usize> {
            if p {
                Some(k.rem_euclid(nc as i64) as usize)
            } else {
                (0..nc as i64).contains(&k).then_some(k as usize)
            }
        };
        let cell = |c: usize| &self.order[self.starts[c] as usize..self.starts[c + 1] as usize];
        let row = |acc: &mut A, gy: usize| {
            for gx in 0..cx {
                let own = cell(gy * cx + gx);
                for (a, &i) in own.iter().enumerate() {
                    for &j in &own[a + 1..] {
                        pair(acc, i as usize, j as usize);
                    }
                }
                for &(ox, oy) in &HALF {
                    // An axis with one cell has no neighbours along it, a walled
                    // axis none beyond its ends.
                    if (ox != 0 && cx == 1) || (oy != 0 && cy == 1) {
                        continue;
                    }
                    let (Some(nx), Some(ny)) = (
                        wrap(gx as i64 + ox, cx, per[0]),
                        wrap(gy as i64 + oy, cy, per[1]),
                    ) else {
                        continue;
                    };
                    for &i in own {
                        for &j in cell(ny * cx + nx) {
                            pair(acc, i as usize, j as usize);
                        }
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
