//! Collecting a sweep: every finished point's log analysed (in parallel, `jobs`
//! at a time, as `carom analyze` would), the results that matter across state
//! points picked from each report, and the replicas of a grid point combined: the
//! mean x̄ of the k replicas, their spread s (sample standard deviation), and the
//! standard error s/√k (k ≥ 2; one replica keeps its run's own error). The runs'
//! own errors combined, √(Σ σ_r²)/k, are kept beside it: the two should agree
//! when the runs' error bars are honest. Only a point's own log is analysed:
//! one whose configuration is not the point's (a `mismatch`, see
//! [`super::status`]), one that cannot be read, or one whose analysis fails is
//! left out and listed in [`Collected::rejected`] (the command then fails).

use std::collections::BTreeMap;

use rayon::prelude::*;
use serde::Serialize;
use serde_json::Value;

use carom_analysis::{analyze_log_with, AnalysisOptions, ReadObserver};
use carom_config::derive_facts_for_old_log;
use carom_log::ReadProgress;

use super::{point_state, PointState, SweepDir, SweepError};

/// The results taken from each report: name, JSON pointer of the value, of its
/// standard error (empty: none).
pub const QUANTITIES: [(&str, &str, &str); 12] = [
    ("packing_fraction", "/packing_fraction", ""),
    ("kT", "/temperature/kt", ""),
    ("Z", "/pressure/z", "/pressure/z_std_error"),
    ("beta_P", "/pressure/beta_p", "/pressure/beta_p_std_error"),
    (
        "collision_rate",
        "/collision_rate/per_disc",
        "/collision_rate/std_error",
    ),
    ("mb_min_p", "", ""),
    (
        "Z_contact",
        "/pair_correlation/contact_theorem/z_structure",
        "/pair_correlation/contact_theorem/z_structure_std_error",
    ),
    ("psi6", "/bond_order/global", "/bond_order/global_std_error"),
    (
        "D",
        "/transport/species/0/diffusion_msd/value",
        "/transport/species/0/diffusion_msd/std_error",
    ),
    (
        "viscosity",
        "/transport/viscosity/value_helfand/value",
        "/transport/viscosity/value_helfand/std_error",
    ),
    (
        "thermal_conductivity",
        "/transport/thermal_conductivity/value_helfand/value",
        "/transport/thermal_conductivity/value_helfand/std_error",
    ),
    ("mb_passed", "", ""),
];

/// Options of [`collect`].
#[derive(Debug, Clone)]
pub struct CollectOptions {
    /// Logs analysed at once (at most the cores, [`super::cores`]).
    pub jobs: usize,
    /// The analysis options (equilibration, structure on or off).
    pub analysis: AnalysisOptions,
}

/// One quantity over the replicas of a grid point.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct Combined {
    /// Mean over the replicas.
    pub value: f64,
    /// Standard error of the mean: spread/√k for k ≥ 2, else the run's own.
    pub std_error: Option<f64>,
    /// Sample standard deviation of the replicas (k ≥ 2).
    pub spread: Option<f64>,
    /// The runs' own standard errors combined, √(Σ σ_r²)/k.
    pub run_std_error: Option<f64>,
    /// Replicas that had this quantity.
    pub n: usize,
}

/// A grid point's collected results.
#[derive(Debug, Clone, Serialize)]
pub struct CollectedPoint {
    /// The varied paths' values.
    pub values: BTreeMap<String, Value>,
    /// Its replicas' point names.
    pub runs: Vec<String>,
    /// Its replicas' seeds.
    pub seeds: Vec<u64>,
    /// Each quantity combined over the replicas (absent: no replica had it).
    pub results: BTreeMap<String, Combined>,
    /// Each replica's own values (value, standard error), by quantity.
    pub replicas: Vec<BTreeMap<String, (f64, Option<f64>)>>,
}

/// What `carom collect` found.
#[derive(Debug, Clone, Serialize)]
pub struct Collected {
    /// The varied paths, in the plan's order.
    pub axes: Vec<String>,
    /// One entry per grid point with at least one analysed replica.
    pub points: Vec<CollectedPoint>,
    /// Points left out because they have not finished: (name, why).
    pub missing: Vec<(String, String)>,
    /// Points left out although their log is there: it is not the point's run,
    /// cannot be read, or its analysis failed (name, why).
    pub rejected: Vec<(String, String)>,
}

/// One run's quantities: name → (value, its standard error).
type Values = BTreeMap<String, (f64, Option<f64>)>;

struct Quiet;
impl ReadObserver for Quiet {
    fn pass(&mut self, _: &'static str) {}
    fn progress(&mut self, _: ReadProgress) {}
    fn warn(&mut self, _: &str) {}
}

/// Analyse every finished point of `sweep`, calling `done(name)` after each.
pub fn collect(
    sweep: &SweepDir,
    opts: &CollectOptions,
    done: &(dyn Fn(&str) + Sync),
) -> Result<Collected, SweepError> {
    let points = &sweep.plan.points;
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(opts.jobs.clamp(1, super::cores()))
        .build()
        .map_err(|e| SweepError::Directory {
            dir: sweep.dir.clone(),
            problem: format!("cannot start the analysis threads: {e}"),
        })?;
    // Per point: its values, or why it is left out and whether its log was there.
    let analysed: Vec<Result<Values, (String, bool)>> = pool.install(|| {
        (0..points.len())
            .into_par_iter()
            .map(|i| {
                let r = match point_state(sweep, i) {
                    PointState::Done { .. } => analyze_log_with(
                        &sweep.log_path(i),
                        opts.analysis,
                        &derive_facts_for_old_log,
                        &mut Quiet,
                    )
                    .map(|(report, _)| {
                        pick(&serde_json::to_value(report).expect("a Report serialises"))
                    })
                    .map_err(|e| (format!("analysis failed: {e}"), true)),
                    PointState::Mismatch { detail } | PointState::Unreadable { detail } => {
                        Err((detail, true))
                    }
                    s => Err((format!("not finished ({})", s.word()), false)),
                };
                done(&points[i].name);
                r
            })
            .collect()
    });
    let mut out = Collected {
        axes: sweep.plan.axes.iter().map(|a| a.path.clone()).collect(),
        points: Vec::new(),
        missing: Vec::new(),
        rejected: Vec::new(),
    };
    let replicas = sweep.plan.replicas as usize;
    for (g, chunk) in points.chunks(replicas).enumerate() {
        let mut cp = CollectedPoint {
            values: out
                .axes
                .iter()
                .cloned()
                .zip(chunk[0].values.iter().cloned())
                .collect(),
            runs: Vec::new(),
            seeds: Vec::new(),
            results: BTreeMap::new(),
            replicas: Vec::new(),
        };
        for (r, p) in chunk.iter().enumerate() {
            match &analysed[g * replicas + r] {
                Ok(values) => {
                    cp.runs.push(p.name.clone());
                    cp.seeds.push(p.seed);
                    cp.replicas.push(values.clone());
                }
                Err((why, false)) => out.missing.push((p.name.clone(), why.clone())),
                Err((why, true)) => out.rejected.push((p.name.clone(), why.clone())),
            }
        }
        if cp.replicas.is_empty() {
            continue;
        }
        for (q, _, _) in QUANTITIES {
            let xs: Vec<(f64, Option<f64>)> = cp
                .replicas
                .iter()
                .filter_map(|m| m.get(q).copied())
                .collect();
            if let Some(c) = combine(&xs) {
                cp.results.insert(q.to_owned(), c);
            }
        }
        out.points.push(cp);
    }
    Ok(out)
}

/// The quantities of one report (those it has, finite).
fn pick(report: &Value) -> Values {
    let mut m = BTreeMap::new();
    for (q, value, se) in QUANTITIES {
        if value.is_empty() {
            continue;
        }
        if let Some(x) = report.pointer(value).and_then(Value::as_f64) {
            let e = if se.is_empty() {
                None
            } else {
                report.pointer(se).and_then(Value::as_f64)
            };
            if x.is_finite() {
                m.insert(q.to_owned(), (x, e.filter(|e| e.is_finite())));
            }
        }
    }
    if let Some(mb) = report.get("maxwell_boltzmann").and_then(Value::as_array) {
        let ps: Vec<f64> = mb
            .iter()
            .filter_map(|s| s.get("min_p_value").and_then(Value::as_f64))
            .collect();
        if !ps.is_empty() {
            m.insert(
                "mb_min_p".into(),
                (ps.iter().cloned().fold(1.0, f64::min), None),
            );
            let passed = mb
                .iter()
                .all(|s| s.get("passed").and_then(Value::as_bool) == Some(true));
            m.insert("mb_passed".into(), (if passed { 1.0 } else { 0.0 }, None));
        }
    }
    m
}

/// The replicas' values `xs` (value, own standard error) combined.
pub(crate) fn combine(xs: &[(f64, Option<f64>)]) -> Option<Combined> {
    let k = xs.len();
    if k == 0 {
        return None;
    }
    let mean = xs.iter().map(|x| x.0).sum::<f64>() / k as f64;
    let spread = (k >= 2)
        .then(|| (xs.iter().map(|x| (x.0 - mean).powi(2)).sum::<f64>() / (k - 1) as f64).sqrt());
    let run_std_error = xs
        .iter()
        .map(|x| x.1.map(|e| e * e))
        .sum::<Option<f64>>()
        .map(|s| s.sqrt() / k as f64);
    Some(Combined {
        value: mean,
        std_error: match spread {
            Some(s) => Some(s / (k as f64).sqrt()),
            None => run_std_error,
        },
        spread,
        run_std_error,
        n: k,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Hand-worked: 1, 2, 3 → mean 2, s = 1, SE 1/√3; own errors 0.3, 0.4, 1.2 →
    /// √(0.09 + 0.16 + 1.44)/3 = 1.3/3.
    #[test]
    fn replicas_combine_into_mean_spread_and_both_errors() {
        let c = combine(&[(1.0, Some(0.3)), (2.0, Some(0.4)), (3.0, Some(1.2))]).unwrap();
        assert_eq!(c.value, 2.0);
        assert_eq!(c.spread, Some(1.0));
        assert!((c.std_error.unwrap() - 1.0 / 3f64.sqrt()).abs() < 1e-15);
        assert!((c.run_std_error.unwrap() - 1.3 / 3.0).abs() < 1e-15);
        assert_eq!(c.n, 3);
        let one = combine(&[(5.0, Some(0.5))]).unwrap();
        assert_eq!(
            (one.value, one.std_error, one.spread),
            (5.0, Some(0.5), None)
        );
        let no_error = combine(&[(1.0, None), (3.0, Some(1.0))]).unwrap();
        assert_eq!(no_error.run_std_error, None);
        assert_eq!(no_error.std_error, Some(2f64.sqrt() / 2f64.sqrt()));
        assert!(combine(&[]).is_none());
    }

    #[test]
    fn a_report_gives_its_quantities() {
        let r = serde_json::json!({
            "packing_fraction": 0.3,
            "temperature": {"kt": 1.0},
            "pressure": {"z": 2.06, "z_std_error": 0.01, "beta_p": 1.0, "beta_p_std_error": 0.005},
            "maxwell_boltzmann": [{"min_p_value": 0.4, "passed": true},
                                  {"min_p_value": 0.1, "passed": true}],
            "transport": null
        });
        let m = pick(&r);
        assert_eq!(m["Z"], (2.06, Some(0.01)));
        assert_eq!(m["kT"], (1.0, None));
        assert_eq!(m["mb_min_p"], (0.1, None));
        assert_eq!(m["mb_passed"], (1.0, None));
        assert!(!m.contains_key("D"));
    }
}
