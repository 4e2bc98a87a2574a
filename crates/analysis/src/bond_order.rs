//! Bond-orientational order (physics.md §11). The local order of disc j is
//! ψ6_j = Σ_k ℓ_jk e^{6iθ_jk} / Σ_k ℓ_jk over its Delaunay neighbours k
//! ([`super::neighbours`]), θ_jk the angle of the bond r_k − r_j and ℓ_jk the
//! length of the Voronoi edge the two cells share (Mickel et al., J. Chem.
//! Phys. 138, 044501 (2013): a neighbour across a vanishing edge, which a small
//! displacement adds or removes, then weighs nothing, so ψ6 is continuous in
//! the positions; a disc on the hull of a walled box, with an unbounded cell,
//! weighs its bonds equally); the global
//! order is Ψ6 = (1/N) Σ_j ψ6_j. Per snapshot the accumulator keeps |Ψ6| and
//! the mean local |ψ6_j| (a series of two numbers per snapshot, as the report's
//! snapshot times); the susceptibility is χ6 = N (⟨|Ψ6|²⟩ − ⟨|Ψ6|⟩²), with
//! errors from 16 time blocks. e^{6iθ} is computed as ((Δx + iΔy)/r)⁶, without
//! trigonometry.

use carom_core::SimBox;
use serde::Serialize;

use super::neighbours::{delaunay_neighbours, Neighbours};
use super::pair_correlation::mean_se;
use super::psi6_estimators::{local_psi6_equal, local_psi6_nearest, six_neighbour_fraction};
use super::sixfold::sixfold;

/// Fewer discs than this get no bond order, g6 or χ6: a disc with its six
/// neighbours is seven, and below that ψ6 measures the box, not an order.
pub const MIN_BOND_ORDER_DISCS: usize = 7;
use super::series::{blocked, drift, subsample, MAX_SERIES};
use super::thermo_report::DriftReport;

/// ψ6 of every disc from its neighbour list (0 for a disc without neighbours).
pub fn local_psi6_from(nb: &Neighbours) -> Vec<[f64; 2]> {
    (0..nb.start.len() - 1)
        .map(|i| {
            let bonds = nb.of(i);
            let equal = bonds.iter().any(|b| b.2.is_nan() || b.2 < 0.0);
            let (mut s, mut total) = ([0.0, 0.0], 0.0);
            for &(_, [dx, dy], facet) in bonds {
                let w = if equal { 1.0 } else { facet };
                let z = sixfold(dx, dy);
                s[0] += w * z[0];
                s[1] += w * z[1];
                total += w;
            }
            if total > 0.0 {
                [s[0] / total, s[1] / total]
            } else {
                [0.0, 0.0]
            }
        })
        .collect()
}

/// ψ6 of every disc at (`x`, `y`) in `sim_box` (Delaunay neighbours).
pub fn local_psi6(sim_box: &SimBox, x: &[f64], y: &[f64]) -> Vec<[f64; 2]> {
    local_psi6_from(&delaunay_neighbours(sim_box, x, y))
}

/// The global order Ψ6 = mean of the local ψ6.
pub fn global_psi6(psi: &[[f64; 2]]) -> [f64; 2] {
    let n = psi.len().max(1) as f64;
    let s = psi
        .iter()
        .fold([0.0, 0.0], |s, p| [s[0] + p[0], s[1] + p[1]]);
    [s[0] / n, s[1] / n]
}

/// Per-snapshot |Ψ6| and mean local |ψ6|.
#[derive(Debug, Clone, Default)]
pub struct BondOrder {
    /// (t, |Ψ6|, mean_j |ψ6_j|) of every snapshot added.
    series: Vec<(f64, f64, f64)>,
    n: usize,
    /// |Ψ6| equal-weight Delaunay, |Ψ6| six nearest, six-neighbour fraction
    /// ([`super::psi6_estimators`]) of every snapshot added.
    others: Vec<[f64; 3]>,
}

/// The other estimators of the same snapshots, for comparison (physics.md §11,
/// eqs. 11.7–11.8): each ⟨·⟩ over the snapshots with its blocked standard error.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct OtherEstimatorsReport {
    /// ⟨|Ψ6|⟩ with every Delaunay bond weighing the same.
    pub delaunay_equal: f64,
    /// Its blocked standard error.
    pub delaunay_equal_std_error: f64,
    /// ⟨|Ψ6|⟩ over each disc's six nearest neighbours.
    pub six_nearest: f64,
    /// Its blocked standard error.
    pub six_nearest_std_error: f64,
    /// ⟨fraction of the discs with exactly six Delaunay neighbours⟩.
    pub six_neighbour_fraction: f64,
    /// Its blocked standard error.
    pub six_neighbour_fraction_std_error: f64,
}

/// Bond-orientational order of the snapshots (physics.md §11).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BondOrderReport {
    /// How neighbours are found: "delaunay".
    pub neighbours: &'static str,
    /// Snapshots used (all after the equilibration time).
    pub snapshots: usize,
    /// ⟨|Ψ6|⟩ over the snapshots, Ψ6 = (1/N) Σ_j ψ6_j.
    pub global: f64,
    /// Its blocked standard error.
    pub global_std_error: f64,
    /// ⟨(1/N) Σ_j |ψ6_j|⟩: local order, large in a crystal and a dense liquid alike.
    pub local: f64,
    /// Its blocked standard error.
    pub local_std_error: f64,
    /// χ6 = N (⟨|Ψ6|²⟩ − ⟨|Ψ6|⟩²), from 16 time blocks.
    pub susceptibility: f64,
    /// Standard error of χ6 (spread of the block values).
    pub susceptibility_std_error: f64,
    /// (t, |Ψ6|), at most 2000 points.
    pub series: Vec<[f64; 2]>,
    /// |Ψ6| of the window's first half against its second; `null` when too short.
    pub drift: Option<DriftReport>,
    /// The equal-weight Delaunay and six-nearest-neighbour |Ψ6| and the
    /// six-neighbour fraction of the same snapshots.
    pub other_estimators: OtherEstimatorsReport,
}

impl BondOrder {
    /// Add one snapshot at time `t`; returns the local ψ6 of its discs (for g6).
    pub fn add(&mut self, t: f64, sim_box: &SimBox, x: &[f64], y: &[f64]) -> Vec<[f64; 2]> {
        let nb = delaunay_neighbours(sim_box, x, y);
        let psi = local_psi6_from(&nb);
        let g = global_psi6(&psi);
        let local = psi.iter().map(|p| p[0].hypot(p[1])).sum::<f64>() / psi.len().max(1) as f64;
        self.series.push((t, g[0].hypot(g[1]), local));
        self.n = x.len();
        let abs = |p: [f64; 2]| p[0].hypot(p[1]);
        self.others.push([
            abs(global_psi6(&local_psi6_equal(&nb))),
            abs(global_psi6(&local_psi6_nearest(sim_box, x, y, &nb, 6))),
            six_neighbour_fraction(&nb),
        ]);
        psi
    }

    /// The report; `None` without at least two snapshots or with fewer than
    /// [`MIN_BOND_ORDER_DISCS`] discs.
    pub fn report(&self) -> Option<BondOrderReport> {
        if self.series.len() < 2 || self.n < MIN_BOND_ORDER_DISCS {
            return None;
        }
        let abs: Vec<f64> = self.series.iter().map(|s| s.1).collect();
        let local: Vec<f64> = self.series.iter().map(|s| s.2).collect();
        let estimate = |x: &[f64]| match blocked(x) {
            Ok(b) => (b.mean, b.std_error),
            Err(_) => mean_se(x),
        };
        let (global, global_std_error) = estimate(&abs);
        let (local_mean, local_std_error) = estimate(&local);
        let chi = |x: &[f64]| {
            let m = x.iter().sum::<f64>() / x.len() as f64;
            let m2 = x.iter().map(|v| v * v).sum::<f64>() / x.len() as f64;
            self.n as f64 * (m2 - m * m)
        };
        let blocks = 16.min(abs.len() / 2).max(1);
        let len = abs.len() / blocks;
        let per_block: Vec<f64> = (0..blocks)
            .map(|k| chi(&abs[k * len..(k + 1) * len]))
            .collect();
        let (_, susceptibility_std_error) = mean_se(&per_block);
        let other = |k: usize| estimate(&self.others.iter().map(|o| o[k]).collect::<Vec<f64>>());
        let (delaunay_equal, delaunay_equal_std_error) = other(0);
        let (six_nearest, six_nearest_std_error) = other(1);
        let (six_neighbour_fraction, six_neighbour_fraction_std_error) = other(2);
        let t_abs: Vec<(f64, f64)> = self.series.iter().map(|s| (s.0, s.1)).collect();
        Some(BondOrderReport {
            neighbours: "delaunay",
            snapshots: self.series.len(),
            global,
            global_std_error,
            local: local_mean,
            local_std_error,
            susceptibility: chi(&abs),
            susceptibility_std_error,
            series: subsample(&t_abs, MAX_SERIES),
            drift: drift(&abs),
            other_estimators: OtherEstimatorsReport {
                delaunay_equal,
                delaunay_equal_std_error,
                six_nearest,
                six_nearest_std_error,
                six_neighbour_fraction,
                six_neighbour_fraction_std_error,
            },
        })
    }
}

#[cfg(test)]
mod tests {
    use super::super::test_lattice::triangular;
    use super::*;
    use std::f64::consts::{PI, SQRT_2};

    /// A perfect triangular lattice: six neighbours each at distance a, every
    /// ψ6 = e^{6iφ} of the lattice's orientation (here φ = 0: ψ6 = 1), |Ψ6| = 1.
    #[test]
    fn the_triangular_lattice_has_perfect_order() {
        let (sb, x, y) = triangular(12, 14, 1.1);
        let nb = delaunay_neighbours(&sb, &x, &y);
        for i in 0..x.len() {
            assert_eq!(nb.of(i).len(), 6, "disc {i}");
            for &(_, [dx, dy], _) in nb.of(i) {
                assert!((dx.hypot(dy) - 1.1).abs() < 1e-12);
            }
        }
        let psi = local_psi6_from(&nb);
        for p in &psi {
            assert!((p[0] - 1.0).abs() < 1e-12 && p[1].abs() < 1e-12, "{p:?}");
        }
        let mut bo = BondOrder::default();
        bo.add(0.0, &sb, &x, &y);
        bo.add(1.0, &sb, &x, &y);
        let r = bo.report().unwrap();
        assert!((r.global - 1.0).abs() < 1e-12 && (r.local - 1.0).abs() < 1e-12);
        assert!(r.susceptibility.abs() < 1e-9);
    }

    /// Hand-built neighbour lists, with bonds whose e^{6iθ} is exact: θ = 0 → 1,
    /// 45° → e^{3πi/2} = −i, 90° → e^{3πi} = −1, 135° → e^{9πi/2} = i.
    /// Disc 0: facets 1 and 3 on the bonds at 0 and 45°: (1 − 3i)/4.
    /// Disc 1: a hull bond (NaN facet) makes all three weigh equally:
    /// (1 + i − 1)/3 = i/3. Disc 2: a vanishing edge (facet 0) weighs nothing
    /// beside facet 2 at 135°: ψ6 = i. Disc 3: no neighbours, ψ6 = 0.
    #[test]
    fn local_order_weighs_bonds_by_their_voronoi_edges() {
        let nb = Neighbours {
            start: vec![0, 2, 5, 7, 7],
            list: vec![
                (1, [2.0, 0.0], 1.0),
                (2, [0.5, 0.5], 3.0),
                (0, [2.0, 0.0], f64::NAN),
                (2, [-1.0, 1.0], 5.0),
                (3, [0.0, 1.5], 2.0),
                (0, [3.0, 0.0], 0.0),
                (1, [-0.7, 0.7], 2.0),
            ],
        };
        let psi = local_psi6_from(&nb);
        let expected = [[0.25, -0.75], [0.0, 1.0 / 3.0], [0.0, 1.0], [0.0, 0.0]];
        assert_eq!(psi.len(), 4);
        for (p, e) in psi.iter().zip(expected) {
            assert!(
                (p[0] - e[0]).abs() < 1e-14 && (p[1] - e[1]).abs() < 1e-14,
                "{p:?} vs {e:?}"
            );
        }
    }

    /// Ψ6 is the plain mean: (1 + 3.5 + 1.5, 2 − 4 + 0.5)/3 = (2, −0.5); no discs give 0.
    #[test]
    fn global_order_is_the_mean_of_the_local_ones() {
        let g = global_psi6(&[[1.0, 2.0], [3.5, -4.0], [1.5, 0.5]]);
        assert_eq!(g, [2.0, -0.5]);
        assert_eq!(global_psi6(&[]), [0.0, 0.0]);
    }

    /// A parallelogram patch of a triangular lattice rotated by α in a walled box:
    /// every Delaunay bond, inside or along the hull (equal weights there), lies along
    /// a lattice direction α + k·60°, so every ψ6 = e^{6iα}, and |Ψ6| = mean |ψ6| = 1.
    #[test]
    fn a_rotated_lattice_has_every_psi6_turned_by_six_alpha() {
        let (alpha, a) = (0.1_f64, 0.9);
        let (u, v) = (
            [a * alpha.cos(), a * alpha.sin()],
            [a * (alpha + PI / 3.0).cos(), a * (alpha + PI / 3.0).sin()],
        );
        let (mut x, mut y) = (Vec::new(), Vec::new());
        for i in 0..7 {
            for j in 0..6 {
                x.push(8.0 + i as f64 * u[0] + j as f64 * v[0]);
                y.push(1.0 + i as f64 * u[1] + j as f64 * v[1]);
            }
        }
        let sb = SimBox::walled(20.0, 12.0, 1.0);
        let e = [(6.0 * alpha).cos(), (6.0 * alpha).sin()];
        let psi = local_psi6(&sb, &x, &y);
        assert_eq!(psi.len(), 42);
        for p in &psi {
            assert!(
                (p[0] - e[0]).abs() < 1e-12 && (p[1] - e[1]).abs() < 1e-12,
                "{p:?}"
            );
        }
        let mut bo = BondOrder::default();
        let back = bo.add(2.5, &sb, &x, &y);
        assert_eq!(back, psi);
        assert_eq!(bo.n, 42);
        let (t, g, local) = bo.series[0];
        assert_eq!(t, 2.5);
        assert!((g - 1.0).abs() < 1e-12 && (local - 1.0).abs() < 1e-12);
    }

    /// A square lattice (a = 1.25, 6 × 5 sites filling a periodic box): every cell is
    /// the square of side a, so the four axis bonds weigh a each, and a diagonal the
    /// triangulation adds between four cocircular discs crosses a Voronoi edge of
    /// length 0 (both triangles share the circumcentre; multiples of 1/8, exact) and
    /// weighs nothing. Then ψ4 = (1 + 1 + 1 + 1)/4 = 1 and ψ6 = (1 − 1 + 1 − 1)/4 = 0
    /// (e^{6i·90°} = −1) for every disc, whichever diagonals were drawn (±i each).
    #[test]
    fn a_square_lattice_has_no_sixfold_order() {
        let a = 1.25;
        let sb = SimBox::periodic(6.0 * a, 5.0 * a);
        let (mut x, mut y) = (Vec::new(), Vec::new());
        for r in 0..5 {
            for c in 0..6 {
                x.push((c as f64 + 0.5) * a);
                y.push((r as f64 + 0.5) * a);
            }
        }
        let nb = delaunay_neighbours(&sb, &x, &y);
        let mut diagonals = 0;
        for i in 0..x.len() {
            let (mut psi4, mut total) = ([0.0, 0.0], 0.0);
            for &(_, [dx, dy], facet) in nb.of(i) {
                if (dx.hypot(dy) - a).abs() < 1e-12 {
                    assert_eq!(facet, a);
                } else {
                    assert!((dx.hypot(dy) - a * SQRT_2).abs() < 1e-12);
                    assert_eq!(facet, 0.0);
                    diagonals += 1;
                }
                let th = dy.atan2(dx);
                psi4 = [
                    psi4[0] + facet * (4.0 * th).cos(),
                    psi4[1] + facet * (4.0 * th).sin(),
                ];
                total += facet;
            }
            assert!((psi4[0] / total - 1.0).abs() < 1e-12 && (psi4[1] / total).abs() < 1e-12);
        }
        // One diagonal per cell, seen from each end (a cell on the box's edge may
        // be cut one way at the disc and the other way at its ghost: a degenerate
        // choice that the zero weight makes harmless).
        assert!(
            diagonals > x.len() && diagonals <= 2 * x.len(),
            "{diagonals}"
        );
        for p in local_psi6(&sb, &x, &y) {
            assert!(p[0].abs() < 1e-12 && p[1].abs() < 1e-12, "{p:?}");
        }
    }

    /// No report without two snapshots.
    #[test]
    fn one_snapshot_gives_no_report() {
        let (sb, x, y) = triangular(6, 6, 1.3);
        let mut bo = BondOrder::default();
        assert_eq!(bo.report(), None);
        bo.add(0.0, &sb, &x, &y);
        assert_eq!(bo.report(), None);
    }

    /// Four snapshots of N = 50 discs, |Ψ6| = 0.1, 0.3, 0.2, 0.6, local 0.5, 0.7,
    /// 0.6, 0.8 (too short to block: plain mean and SE). ⟨|Ψ6|⟩ = 0.3, SE
    /// √(Σ(x − 0.3)²/3/4) = √(0.14/12); local 0.65, SE √(0.05/12).
    /// χ6 = 50 (⟨|Ψ6|²⟩ − 0.3²) = 50 (0.5/4 − 0.09) = 1.75; per block (min(16, 4/2)
    /// = 2 blocks of 2): 50 (0.05 − 0.04) = 0.5 and 50 (0.2 − 0.16) = 2, SE of two
    /// values |2 − 0.5|/2 = 0.75.
    #[test]
    fn the_report_has_the_susceptibility_from_the_spread_of_the_order() {
        let abs = [0.1, 0.3, 0.2, 0.6];
        let local = [0.5, 0.7, 0.6, 0.8];
        let bo = BondOrder {
            series: (0..4).map(|k| (1.5 * k as f64, abs[k], local[k])).collect(),
            n: 50,
            others: vec![[0.0; 3]; 4],
        };
        let r = bo.report().unwrap();
        let close = |a: f64, b: f64| (a - b).abs() < 1e-12;
        assert_eq!((r.neighbours, r.snapshots), ("delaunay", 4));
        assert!(close(r.global, 0.3) && close(r.global_std_error, (0.14_f64 / 12.0).sqrt()));
        assert!(close(r.local, 0.65) && close(r.local_std_error, (0.05_f64 / 12.0).sqrt()));
        assert!(close(r.susceptibility, 1.75), "{}", r.susceptibility);
        assert!(close(r.susceptibility_std_error, 0.75));
        assert_eq!(
            r.series,
            vec![[0.0, 0.1], [1.5, 0.3], [3.0, 0.2], [4.5, 0.6]]
        );
        // Halves of two values, plain errors: 0.2 ± 0.1 and 0.4 ± 0.2, 0.89 SE
        // apart: checked, not drifting.
        let d = r.drift.expect("a drift check of two halves of two");
        assert!(
            close(d.first_half, 0.2) && close(d.second_half, 0.4),
            "{d:?}"
        );
        assert!(!d.drifting, "{d:?}");
    }
}
