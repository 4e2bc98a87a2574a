//! `carom analyze --plot DIR`: figures of a [`Report`] as PNG and SVG (plotters;
//! text in DejaVu Sans, embedded, so no system fonts are needed).
//!
//! Files: `speed_species{k}`, `components_species{k}`, `temperature`, `pressure`
//! and `density_profile` ([`thermo`]); `pair_correlation`, `bond_order`, `g6` and
//! `structure_factor` ([`structure`]); `msd`, `vacf` and `self_scattering`
//! ([`dynamics`]); `vacf_exact`, `msd_exact`, `helfand_viscosity` and
//! `helfand_conductivity` ([`transport`]). Distances are in σ (the diameter of
//! species 0) and, when kT is constant, lags in τ₀ = σ√(m/kT) ([`Units`]).
//! A figure that would show nothing is not drawn: [`write_all`] names it with
//! the reason ([`skip`] holds the rules). Axes, ticks, legends and error bands
//! are shared ([`axes`]).

use std::path::Path;

use carom_analysis::Report;
use plotters::prelude::*;

use super::CliError;

#[path = "plot_axes.rs"]
mod axes;
#[path = "plot_dynamics.rs"]
mod dynamics;
#[path = "plot_skip.rs"]
mod skip;
#[path = "plot_structure.rs"]
mod structure;
#[path = "plot_sweep.rs"]
mod sweep;
#[path = "plot_thermo.rs"]
mod thermo;
#[path = "plot_transport.rs"]
mod transport;

#[cfg(test)]
#[path = "plot_tests.rs"]
mod tests;

const SIZE: (u32, u32) = (900, 600);

pub(super) type DrawResult<DB> =
    Result<(), DrawingAreaErrorKind<<DB as DrawingBackend>::ErrorType>>;

/// A figure that could not be drawn or written: the error says which file and why (the operating system's reason for a write).
fn plot_err<E: std::error::Error + Send + Sync + 'static>(
    path: &Path,
    e: DrawingAreaErrorKind<E>,
) -> CliError {
    let reason = crate::render::drawing_error_reason(&e);
    CliError::Plot(format!("cannot write {}: {reason}", path.display()))
}

/// Draw one figure with `draw` into `dir/name.png` and `dir/name.svg`, each
/// under the lock a run takes on its log (a file another process writes is
/// refused and left as it is). A failed file is removed once its backend is
/// dropped (dropping presents it again).
macro_rules! both {
    ($dir:expr, $name:expr, $draw:expr) => {{
        let png = $dir.join(format!("{}.png", $name));
        let lock = super::render::OutLock::take(&png)?;
        let drawn = {
            let root = BitMapBackend::new(&png, SIZE).into_drawing_area();
            root.fill(&WHITE)
                .and_then(|()| $draw(&root))
                .and_then(|()| root.present())
                .map_err(|e| plot_err(&png, e))
        };
        drawn.inspect_err(|_| remove(&png))?;
        lock.keep();
        let svg = $dir.join(format!("{}.svg", $name));
        let lock = super::render::OutLock::take(&svg)?;
        let drawn = {
            let root = SVGBackend::new(&svg, SIZE).into_drawing_area();
            root.fill(&WHITE)
                .and_then(|()| $draw(&root))
                .and_then(|()| root.present())
                .map_err(|e| plot_err(&svg, e))
        };
        drawn.inspect_err(|_| remove(&svg))?;
        lock.keep();
    }};
}

/// Remove a figure that could not be written.
fn remove(path: &Path) {
    let _ = std::fs::remove_file(path);
}

/// The reduced units of the figures: σ, the diameter of species 0, and, when
/// kT is constant (an elastic run), τ₀ = σ√(m/kT) with species 0's mass
/// (the time unit of physics.md's Enskog relation); distances are shown as r/σ
/// and lags as τ/τ₀.
pub(super) struct Units {
    /// σ (length).
    pub sigma: f64,
    /// τ₀ (time), if kT is constant.
    pub tau0: Option<f64>,
    /// Whether the run has several species (σ is then named as species 0's).
    pub mixture: bool,
}

impl Units {
    pub(super) fn of(r: &Report) -> Units {
        let s0 = r.species.first();
        let sigma = s0.map_or(1.0, |s| 2.0 * s.radius);
        let kt = r.temperature.kt;
        let tau0 = s0
            .filter(|_| r.elastic && r.inelastic.is_none() && kt > 0.0)
            .map(|s| sigma * (s.mass / kt).sqrt());
        Units {
            sigma,
            tau0,
            mixture: r.species.len() > 1,
        }
    }

    /// The distance axis "r/σ" (σ named for a mixture).
    pub(super) fn r_desc(&self) -> String {
        if self.mixture {
            format!(
                "distance r/σ (σ = {} the diameter of species 0)",
                self.sigma
            )
        } else {
            format!("distance r/σ (σ = {} the disc diameter)", self.sigma)
        }
    }

    /// The factor taking a lag to the figures' time unit, and that axis's text.
    pub(super) fn lag(&self) -> (f64, String) {
        match self.tau0 {
            Some(t) => (1.0 / t, format!("lag τ/τ₀ (τ₀ = σ√(m/kT) = {t:.4})")),
            None => (1.0, "lag τ (time)".to_owned()),
        }
    }
}

/// What [`write_all`] did: the number of figures written (each as PNG and
/// SVG) and the figures not drawn, each with its one-line reason.
#[derive(Debug, Default)]
pub struct Written {
    pub figures: usize,
    pub skipped: Vec<(&'static str, String)>,
}

impl Written {
    /// The figures of report sections that were not computed, with the report's
    /// reason (`not_computed`), so that a missing figure is never silent.
    fn not_computed(&mut self, report: &Report) {
        const FIGURES: [(&str, &str); 4] = [
            ("pair_correlation", "pair_correlation"),
            ("bond_order", "bond_order"),
            ("orientational_correlation", "g6"),
            ("structure_factor", "structure_factor"),
        ];
        for n in &report.not_computed {
            if let Some((_, figure)) = FIGURES.iter().find(|(q, _)| *q == n.quantity) {
                self.skipped.push((figure, n.why.clone()));
            }
        }
    }

    /// Draw the figure `name` unless `why_not` gives a reason not to.
    fn one(
        &mut self,
        name: &'static str,
        why_not: Option<String>,
        draw: impl FnOnce() -> Result<(), CliError>,
    ) -> Result<(), CliError> {
        match why_not {
            Some(reason) => self.skipped.push((name, reason)),
            None => {
                draw()?;
                self.figures += 1;
            }
        }
        Ok(())
    }
}

/// Write every figure of `report` into `dir` (created if needed): those drawn,
/// and those skipped with their reasons.
pub fn write_all(report: &Report, dir: &Path) -> Result<Written, CliError> {
    std::fs::create_dir_all(dir).map_err(|source| CliError::Io {
        context: format!("cannot create {}", dir.display()),
        source,
    })?;
    crate::render::register_font();
    let u = Units::of(report);
    let mut w = Written::default();
    w.not_computed(report);
    for m in &report.maxwell_boltzmann {
        let name = format!("speed_species{}", m.species);
        both!(dir, &name, |root| thermo::draw_speed(root, m));
        let name = format!("components_species{}", m.species);
        both!(dir, &name, |root| thermo::draw_components(root, m));
        w.figures += 2;
    }
    if report.temperature.series.len() >= 2 {
        w.one("temperature", skip::temperature(report), || {
            both!(dir, "temperature", |root| thermo::draw_temperature(
                root, report
            ));
            Ok(())
        })?;
    }
    if let Some(p) = report.pressure.as_ref().filter(|p| p.series.len() >= 2) {
        w.one("pressure", None, || {
            both!(dir, "pressure", |root| thermo::draw_pressure(root, p));
            Ok(())
        })?;
    }
    if let Some(pc) = report
        .pair_correlation
        .as_ref()
        .filter(|p| !p.pairs.is_empty())
    {
        w.one("pair_correlation", skip::few_discs(report), || {
            both!(dir, "pair_correlation", |root| structure::draw_g(
                root, pc, &u
            ));
            Ok(())
        })?;
    }
    if let Some(b) = report.bond_order.as_ref().filter(|b| b.series.len() >= 2) {
        let why = skip::few_discs(report).or_else(|| skip::psi6(b));
        w.one("bond_order", why, || {
            both!(dir, "bond_order", |root| structure::draw_bond_order(
                root, b
            ));
            Ok(())
        })?;
    }
    if let Some(g) = &report.orientational_correlation {
        w.one("g6", skip::few_discs(report), || {
            both!(dir, "g6", |root| structure::draw_g6(root, g, &u));
            Ok(())
        })?;
    }
    if let Some(f) = report.structure_factor.as_ref().filter(|f| f.k.len() >= 2) {
        w.one("structure_factor", skip::few_discs(report), || {
            both!(dir, "structure_factor", |root| structure::draw_sk(
                root, f, &u
            ));
            Ok(())
        })?;
    }
    if let Some(t) = &report.transport {
        w.one("vacf_exact", None, || {
            both!(dir, "vacf_exact", |root| transport::draw_vacf(root, t, &u));
            Ok(())
        })?;
        w.one("msd_exact", None, || {
            both!(dir, "msd_exact", |root| transport::draw_msd(root, t, &u));
            Ok(())
        })?;
        let enskog = t.enskog.as_ref();
        let eta = ("η", "mass/time");
        let visc = enskog.map(|e| e.viscosity);
        w.one("helfand_viscosity", None, || {
            both!(dir, "helfand_viscosity", |root| transport::draw_helfand(
                root,
                &t.viscosity,
                (eta, visc),
                t.window,
                &u
            ));
            Ok(())
        })?;
        if let Some(l) = &t.thermal_conductivity {
            let lambda = ("λ", "1/time, k_B = 1");
            let cond = enskog.map(|e| e.thermal_conductivity);
            w.one("helfand_conductivity", None, || {
                both!(dir, "helfand_conductivity", |root| transport::draw_helfand(
                    root,
                    l,
                    (lambda, cond),
                    t.window,
                    &u
                ));
                Ok(())
            })?;
        }
    }
    if let Some(g) = report.gravity.as_ref().filter(|g| g.heights.len() >= 2) {
        w.one("density_profile", None, || {
            both!(dir, "density_profile", |root| thermo::draw_density_profile(
                root, g
            ));
            Ok(())
        })?;
    }
    if let Some(d) = report.dynamics.as_ref().filter(|d| !d.species.is_empty()) {
        let few = skip::few_discs(report);
        w.one("msd", few.clone(), || {
            both!(dir, "msd", |root| dynamics::draw_msd(
                root,
                d,
                &u,
                report.transport.is_some()
            ));
            Ok(())
        })?;
        w.one("vacf", few.clone(), || {
            both!(dir, "vacf", |root| dynamics::draw_vacf(root, d, &u));
            Ok(())
        })?;
        if d.k_star.is_some() {
            let why = few.or_else(|| skip::self_scattering(d));
            w.one("self_scattering", why, || {
                both!(dir, "self_scattering", |root| dynamics::draw_fs(
                    root, d, &u
                ));
                Ok(())
            })?;
        }
    }
    Ok(w)
}

/// Write the figures of a collected sweep into `dir`: `equation_of_state` when
/// the sweep varies a packing fraction and has pressures. Returns their number.
pub fn write_sweep(c: &carom_run::sweep::Collected, dir: &Path) -> Result<usize, CliError> {
    let Some(eta) = c.axes.iter().find(|a| a.ends_with("packing_fraction")) else {
        return Ok(0);
    };
    let series = sweep::eos_series(c, eta);
    if series.is_empty() {
        return Ok(0);
    }
    std::fs::create_dir_all(dir).map_err(|source| CliError::Io {
        context: format!("cannot create {}", dir.display()),
        source,
    })?;
    crate::render::register_font();
    both!(dir, "equation_of_state", |root| sweep::draw_eos(
        root, &series
    ));
    Ok(1)
}

pub(super) fn range(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = values
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
            (a.min(v), b.max(v))
        });
    if hi.is_nan() || lo.is_nan() || hi <= lo {
        let c = if lo.is_finite() { lo } else { 0.0 };
        return (c - 1.0, c + 1.0);
    }
    let pad = 0.05 * (hi - lo);
    (lo - pad, hi + pad)
}

/// The largest of `values`, times 1.1 (a density axis's top), at least 10⁻¹².
pub(super) fn top(values: impl Iterator<Item = f64>) -> f64 {
    (values.fold(0.0, f64::max) * 1.1).max(1e-12)
}
