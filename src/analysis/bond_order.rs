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
use super::report::DriftReport;
use super::series::{blocked, drift, subsample, MAX_SERIES};

/// z⁶ for the unit complex number z = (dx + i dy)/r.
pub fn sixfold(dx: f64, dy: f64) -> [f64; 2] {
    let r2 = dx * dx + dy * dy;
    let (a, b) = (dx * dx - dy * dy, 2.0 * dx * dy); // z² r²
    let (c, d) = (a * a - b * b, 2.0 * a * b); // z⁴ r⁴
    let s = 1.0 / (r2 * r2 * r2);
    [(a * c - b * d) * s, (a * d + b * c) * s]
}

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
}

impl BondOrder {
    /// Add one snapshot at time `t`; returns the local ψ6 of its discs (for g6).
    pub fn add(&mut self, t: f64, sim_box: &SimBox, x: &[f64], y: &[f64]) -> Vec<[f64; 2]> {
        let psi = local_psi6(sim_box, x, y);
        let g = global_psi6(&psi);
        let local = psi.iter().map(|p| p[0].hypot(p[1])).sum::<f64>() / psi.len().max(1) as f64;
        self.series.push((t, g[0].hypot(g[1]), local));
        self.n = x.len();
        psi
    }

    /// The report; `None` without at least two snapshots.
    pub fn report(&self) -> Option<BondOrderReport> {
        if self.series.len() < 2 {
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
        })
    }
}

#[cfg(test)]
mod tests {
    use super::super::test_lattice::triangular;
    use super::*;

    #[test]
    fn sixfold_is_the_sixth_power_of_the_bond_direction() {
        for th in [0.0, 0.3, 1.0, 2.5, -2.0, 3.1] {
            let z = sixfold(2.0 * f64::cos(th), 2.0 * f64::sin(th));
            assert!((z[0] - (6.0 * th).cos()).abs() < 1e-14);
            assert!((z[1] - (6.0 * th).sin()).abs() < 1e-14);
        }
    }

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
}
