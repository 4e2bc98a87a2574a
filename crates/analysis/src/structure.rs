//! The structure of a set of snapshots (physics.md §10–§11): the pair
//! correlation g_ab(r) with its contact values, the bond order ψ6_j =
//! Σ_k ℓ_jk e^{6iθ_jk}/Σ_k ℓ_jk with |Ψ6| and χ6, g6(r), and S(k) with the
//! translational order. One accumulator per observable, each binning its
//! snapshots into time blocks over the window [t0, t1] for its errors; the
//! [`Analyzer`](super::Analyzer) feeds it a log's snapshots, `frames.rs` plain
//! arrays, so both give the same sections from the same code.

use carom_core::{SimBox, Species};
use serde::Serialize;

use super::bond_correlation::{BondCorrelation, BondCorrelationReport};
use super::bond_order::{BondOrder, BondOrderReport, MIN_BOND_ORDER_DISCS};
use super::contact::{self, PairCorrelationReport};
use super::pair_correlation::PairCorrelation;
use super::structure_factor::{StructureFactor, StructureFactorReport};
use super::thermo_report::PressureReport;

/// The structure sections of a report.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StructureReport {
    /// g_ab(r), contact values and the contact theorem (physics.md §10).
    pub pair_correlation: Option<PairCorrelationReport>,
    /// ψ6, |Ψ6| and χ6 (physics.md §11).
    pub bond_order: Option<BondOrderReport>,
    /// g6(r) and its decay.
    pub orientational_correlation: Option<BondCorrelationReport>,
    /// S(k) and the translational order (periodic boxes only).
    pub structure_factor: Option<StructureFactorReport>,
}

/// The structure accumulators over one window.
#[derive(Debug, Clone)]
pub(crate) struct Structure {
    pub(crate) pair_correlation: PairCorrelation,
    bond_order: BondOrder,
    bond_correlation: BondCorrelation,
    structure_factor: Option<StructureFactor>,
    sim_box: SimBox,
    n: usize,
}

/// The smallest diameter σ_min = 2 min a_s over the species present.
pub(crate) fn smallest_diameter(species: &[Species]) -> f64 {
    2.0 * species
        .iter()
        .filter(|s| s.count > 0)
        .map(|s| s.radius)
        .fold(f64::INFINITY, f64::min)
}

impl Structure {
    /// Empty accumulators for `species` in `sim_box` over the window [t0, t1].
    pub(crate) fn new(species: &[Species], sim_box: &SimBox, t0: f64, t1: f64) -> Self {
        let sigma_min = smallest_diameter(species);
        Structure {
            pair_correlation: PairCorrelation::new(species, sim_box, t0, t1),
            bond_order: BondOrder::default(),
            bond_correlation: BondCorrelation::new(species, sim_box, t0, t1),
            structure_factor: StructureFactor::new(sim_box, sigma_min, t0, t1),
            sim_box: *sim_box,
            n: species.iter().map(|s| s.count).sum(),
        }
    }

    /// The positions (in the box) of a snapshot at time `t` in the window.
    pub(crate) fn add(&mut self, t: f64, species_of: &[u16], x: &[f64], y: &[f64]) {
        // g(r) runs on all cores; the triangulation behind ψ6 is serial, so it
        // runs beside g(r) rather than after it.
        let (pair_correlation, bond_order) = (&mut self.pair_correlation, &mut self.bond_order);
        let sim_box = &self.sim_box;
        let ((), psi) = rayon::join(
            || pair_correlation.add(t, species_of, x, y),
            || bond_order.add(t, sim_box, x, y),
        );
        self.bond_correlation.add(t, x, y, &psi);
        if let Some(sf) = &mut self.structure_factor {
            sf.add(t, x, y);
        }
    }

    /// The sections; the contact theorem needs `elastic_periodic` and a pressure.
    pub(crate) fn report(
        &self,
        elastic_periodic: bool,
        pressure: Option<&PressureReport>,
    ) -> StructureReport {
        StructureReport {
            pair_correlation: contact::report(&self.pair_correlation, elastic_periodic, pressure),
            bond_order: self.bond_order.report(),
            orientational_correlation: self
                .bond_correlation
                .report()
                .filter(|_| self.n >= MIN_BOND_ORDER_DISCS),
            structure_factor: self
                .structure_factor
                .as_ref()
                .and_then(StructureFactor::report),
        }
    }
}
