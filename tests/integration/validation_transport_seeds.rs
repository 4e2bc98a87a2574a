//! The standard errors of the transport coefficients against the spread of
//! independent runs (physics.md §14.6): 16 seeds of the default run (10⁴ discs,
//! φ = 0.5, 50 time units, `carom run` then `carom analyze --json
//! --no-structure`); for each of D (MSD of the exact replay), η and λ
//! (Einstein–Helfand) the seeds' standard deviation must be within a factor 1.5
//! of the mean quoted standard error. With 16 seeds the SD itself is known to
//! ±18 %, so a correct error passes with room to spare. Ignored (about a minute
//! in release); run with
//!
//! ```sh
//! cargo test --release --test integration validation_transport_seeds:: -- --ignored --nocapture
//! ```

use crate::cli_common::*;

use serde_json::Value;

/// (value, quoted SE) of each coefficient for one seed.
fn one_seed(seed: u64) -> [(f64, f64); 3] {
    let dir = scratch(&format!("seeds-{seed}"));
    let s = format!("seed={seed}");
    ok(&carom(
        &dir,
        &["run", "--quiet", "--out", "r.mcap", "--set", &s],
    ));
    let r = json_of(&carom(
        &dir,
        &["analyze", "r.mcap", "--quiet", "--json", "--no-structure"],
    ));
    let t = &r["transport"];
    let pair = |e: &Value| {
        (
            e["value"].as_f64().unwrap(),
            e["std_error"].as_f64().unwrap(),
        )
    };
    [
        pair(&t["species"][0]["diffusion_msd"]),
        pair(&t["viscosity"]["value_helfand"]),
        pair(&t["thermal_conductivity"]["value_helfand"]),
    ]
}

#[test]
#[ignore = "16 default runs and their analyses (about a minute in release)"]
fn quoted_errors_match_the_spread_of_seeds() {
    let runs: Vec<[(f64, f64); 3]> = (1..=16).map(|s| one_seed(1000 + s)).collect();
    let mut failures = Vec::new();
    for (k, name) in ["D", "η", "λ"].iter().enumerate() {
        let v: Vec<f64> = runs.iter().map(|r| r[k].0).collect();
        let se: Vec<f64> = runs.iter().map(|r| r[k].1).collect();
        let n = v.len() as f64;
        let mean = v.iter().sum::<f64>() / n;
        let sd = (v.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0)).sqrt();
        let quoted = se.iter().sum::<f64>() / n;
        let ratio = sd / quoted;
        println!(
            "{name}: mean {mean:.5}, SD over {} seeds {sd:.5}, mean quoted SE {quoted:.5}, \
             SD/SE {ratio:.2}; values {v:.4?}",
            v.len()
        );
        if !(1.0 / 1.5..=1.5).contains(&ratio) {
            failures.push(format!("{name}: SD/SE = {ratio:.2}"));
        }
    }
    assert!(failures.is_empty(), "{failures:?}");
}
