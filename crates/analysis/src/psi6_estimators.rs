//! Two textbook ψ6 estimators beside the Voronoi-weighted one of
//! `bond_order.rs` (physics.md §11, eqs. 11.7–11.8), kept for comparison:
//! the plain Delaunay estimator ψ6_j = (1/n_j) Σ_k e^{6iθ_jk} over the n_j
//! Delaunay neighbours (each bond weighs the same, so a neighbour across a
//! vanishing Voronoi edge — four nearly co-circular discs — counts in full and
//! ψ6 jumps when a small move flips the diagonal), and the k-nearest-neighbour
//! estimator ψ6_j = (1/k) Σ_{k nearest} e^{6iθ_jk} (k = 6; it jumps when the
//! sixth and seventh neighbours swap). The k nearest neighbours are found on the
//! Delaunay graph: the m-th nearest neighbour of j is a Delaunay neighbour of j or
//! of one of its m − 1 nearer ones (Dickerson, Drysdale & Sack, Int. J. Comput.
//! Geom. Appl. 2, 221 (1992)), so a best-first walk from j is exact.

use carom_core::SimBox;

/// A neighbour's image: (disc, periodic image shifts) and its separation.
type Image = ((u32, i64, i64), [f64; 2]);

use super::neighbours::Neighbours;
use super::sixfold::sixfold;

/// ψ6 of every disc with every Delaunay bond weighing the same (eq. 11.7; 0 for a
/// disc without neighbours).
pub fn local_psi6_equal(nb: &Neighbours) -> Vec<[f64; 2]> {
    (0..nb.start.len() - 1)
        .map(|i| mean_sixfold(nb.of(i).iter().map(|b| b.1)))
        .collect()
}

/// ψ6 of every disc over its `k` nearest neighbours (eq. 11.8), found on the
/// Delaunay graph `nb` of the discs at (`x`, `y`) in `sim_box`; images of one disc
/// across a periodic edge count as distinct neighbours. Ties at the k-th distance
/// are broken by the order the walk meets them. A disc with fewer than `k` discs
/// in reach (a tiny box) averages over those it has.
pub fn local_psi6_nearest(
    sim_box: &SimBox,
    x: &[f64],
    y: &[f64],
    nb: &Neighbours,
    k: usize,
) -> Vec<[f64; 2]> {
    let (lx, ly) = (sim_box.size.x, sim_box.size.y);
    let periodic = sim_box.boundary.map(|b| b.is_periodic());
    // A point of the walk: disc, displacement from i, and the whole boxes between
    // that displacement and the disc's stored position (its image's identity).
    let image = |i: usize, j: u32, d: [f64; 2]| -> (u32, i64, i64) {
        let w = |p: bool, xi: f64, xj: f64, di: f64, l: f64| {
            if p {
                ((xi + di - xj) / l).round() as i64
            } else {
                0
            }
        };
        (
            j,
            w(periodic[0], x[i], x[j as usize], d[0], lx),
            w(periodic[1], y[i], y[j as usize], d[1], ly),
        )
    };
    (0..x.len())
        .map(|i| {
            let own = (i as u32, 0, 0);
            let mut chosen: Vec<Image> = Vec::with_capacity(k);
            let mut candidates: Vec<Image> = Vec::new();
            let add = |from: [f64; 2],
                       bonds: &[(u32, [f64; 2], f64)],
                       chosen: &[Image],
                       candidates: &mut Vec<Image>| {
                for &(j, d, _) in bonds {
                    let d = [from[0] + d[0], from[1] + d[1]];
                    let id = image(i, j, d);
                    let known = |c: &Image| c.0 == id;
                    if id != own && !chosen.iter().any(known) && !candidates.iter().any(known) {
                        candidates.push((id, d));
                    }
                }
            };
            add([0.0, 0.0], nb.of(i), &chosen, &mut candidates);
            while chosen.len() < k && !candidates.is_empty() {
                let r2 = |c: &Image| c.1[0] * c.1[0] + c.1[1] * c.1[1];
                let best = (0..candidates.len())
                    .min_by(|&a, &b| r2(&candidates[a]).total_cmp(&r2(&candidates[b])))
                    .unwrap();
                let next = candidates.remove(best);
                chosen.push(next);
                add(next.1, nb.of(next.0 .0 as usize), &chosen, &mut candidates);
            }
            mean_sixfold(chosen.iter().map(|c| c.1))
        })
        .collect()
}

/// Fraction of the discs with exactly six Delaunay neighbours.
pub fn six_neighbour_fraction(nb: &Neighbours) -> f64 {
    let n = nb.start.len() - 1;
    let six = (0..n).filter(|&i| nb.of(i).len() == 6).count();
    six as f64 / n.max(1) as f64
}

/// (1/n) Σ e^{6iθ} over the bond vectors `bonds` (0 without bonds).
fn mean_sixfold(bonds: impl Iterator<Item = [f64; 2]>) -> [f64; 2] {
    let (mut s, mut n) = ([0.0, 0.0], 0usize);
    for [dx, dy] in bonds {
        let z = sixfold(dx, dy);
        s = [s[0] + z[0], s[1] + z[1]];
        n += 1;
    }
    if n == 0 {
        [0.0, 0.0]
    } else {
        [s[0] / n as f64, s[1] / n as f64]
    }
}

#[cfg(test)]
#[path = "psi6_estimators_tests.rs"]
mod tests;
