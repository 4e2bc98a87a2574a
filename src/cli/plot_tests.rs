//! Tests of the figures at the data level: each figure is drawn to SVG and
//! its text (tick labels, legend entries) and elements read back.

use carom_analysis::{DiffusionFit, DynamicsReport, SpeciesDynamics};
use plotters::prelude::*;

use super::dynamics::{draw_fs, draw_msd, draw_vacf};
use super::Units;

/// The legend entry of every band of one standard error.
const SE: &str = "± one standard error";

/// σ = 1 and τ₀ = 2: lags shown halved.
fn units() -> Units {
    Units {
        sigma: 1.0,
        tau0: Some(2.0),
        mixture: false,
    }
}

/// Two species, one with a D fit and τ_α, one with neither and a VACF that
/// crosses zero (NaN errors where one segment had data).
fn report() -> DynamicsReport {
    let lag = vec![0.0, 1.0, 2.0, 4.0, 8.0];
    let sp = |species: usize, fit: bool| SpeciesDynamics {
        species,
        count: 10,
        lag: lag.clone(),
        samples: vec![10; 5],
        msd: vec![0.0, 1.0, 3.0, 7.0, 15.0],
        msd_std_error: vec![f64::NAN, 0.1, 0.2, 0.3, f64::NAN],
        alpha2: vec![f64::NAN, 0.1, 0.1, 0.05, 0.0],
        vacf: vec![2.0, 1.0, 0.1, -0.02, 0.01],
        vacf_std_error: vec![0.0; 5],
        vacf_normalised: vec![1.0, 0.5, 0.05, -0.01, 0.005],
        fs: vec![1.0, 0.8, 0.5, 0.2, 0.05],
        fs_std_error: vec![0.0; 5],
        tau_alpha: fit.then_some(2.9),
        diffusion: fit.then_some(DiffusionFit {
            d: 0.5,
            std_error: 0.01,
            statistical_std_error: 0.008,
            d_unweighted: 0.49,
            intercept: -1.0,
            t_a: 2.0,
            t_b: 4.0,
            points: 2,
            segments: 10,
        }),
    };
    DynamicsReport {
        species: vec![sp(0, true), sp(1, false)],
        origins: 9,
        origins_per_level: 16,
        levels: 1,
        max_stored: 9,
        origins_capped: false,
        segments: 10,
        k_star: Some(6.0),
        ambiguous_gaps: 0,
        collision_time: Some(0.5),
    }
}

/// The SVG text of one figure drawn by `$draw`.
macro_rules! svg {
    ($draw:expr, $d:expr) => {{
        let mut svg = String::new();
        {
            let root = SVGBackend::with_string(&mut svg, (900, 600)).into_drawing_area();
            $draw(&root, $d, &units()).unwrap();
            root.present().unwrap();
        }
        svg
    }};
}

/// Each figure draws with its guides and labels in its legend.
#[test]
fn the_dynamics_figures_carry_their_guides() {
    crate::render::register_font();
    let d = report();
    let figures = [
        (
            svg!(|root, d, u| draw_msd(root, d, u, false), &d),
            &[
                "slope 1",
                "D = 0.5000",
                "species 1",
                SE,
                "fit 4Dτ + c",
                "fit window",
            ][..],
            true,
        ),
        (svg!(draw_vacf, &d), &["τ⁻¹", "species 0", SE][..], true),
        (
            svg!(draw_fs, &d),
            &["1/e", "τ_α = 2.9000", "no τ_α", SE, "τ_α of species 0"][..],
            false,
        ),
    ];
    for (svg, labels, log_log) in figures {
        for l in labels {
            assert!(svg.contains(l), "{l} missing");
        }
        // The band of one standard error is drawn (a filled polygon).
        assert!(svg.contains("<polygon"), "no band");
        // Log axes: tick labels powers of ten (on log–log axes all of them).
        let ticks: Vec<&str> = svg
            .split("</text>")
            .filter_map(|t| t.rsplit('>').next())
            .map(str::trim)
            .filter(|t| !t.is_empty() && t.chars().all(|c| "0123456789×⁰¹²³⁴⁵⁶⁷⁸⁹⁻.-".contains(c)))
            .collect();
        assert!(ticks.iter().any(|t| t.starts_with("10")), "{ticks:?}");
        assert!(
            !log_log || ticks.iter().all(|t| !t.contains('.')),
            "{ticks:?}"
        );
    }
}

/// F_s that is below 1/e at the first lag is skipped with its reason; one
/// that decays over the lags is drawn.
#[test]
fn a_self_scattering_decayed_before_the_first_lag_is_skipped() {
    let mut d = report();
    assert_eq!(super::skip::self_scattering(&d), None);
    for s in &mut d.species {
        s.fs = vec![1.0, 0.01, 0.0, 0.0, 0.0];
    }
    let why = super::skip::self_scattering(&d).expect("skipped");
    assert!(why.contains("shorter than the snapshot spacing"), "{why}");
}
