//! A run with gravity through the whole tool chain: configuration → run → log →
//! resume → analyze. A log cut in the middle and resumed holds the uninterrupted
//! run's messages byte for byte (g is in the checkpoint), and `analyze` reports the
//! potential energy, K + U conserved between the first and last snapshot, n(y) and
//! the barometric fit (physics.md §15).

use crate::mcap_common::tmp;
use carom_analysis::{analyze_log, AnalysisOptions, ReadObserver};
use carom_config::Config;
use carom_log::{LogEnd, LogReader, ReadProgress};
use carom_run::{resume, run, Control, ResumeOptions};
use std::path::Path;

struct Quiet;
impl ReadObserver for Quiet {
    fn pass(&mut self, _: &'static str) {}
    fn progress(&mut self, _: ReadProgress) {}
    fn warn(&mut self, _: &str) {}
}

fn raw(path: &Path) -> Vec<(usize, u32, u64, Vec<u8>)> {
    let mut r = LogReader::open(path).unwrap();
    let mut v = Vec::new();
    while let Some(m) = r.next_raw().unwrap() {
        v.push((m.channel, m.sequence, m.log_time, m.data.to_vec()));
    }
    assert_eq!(*r.end(), LogEnd::Complete);
    v
}

/// 60 discs in a 200 × 60 channel with g = 0.1 (scale height ≈ 12 once settled,
/// η ≈ 0.02 at the floor).
const CONFIG: &str = r#"{
    "species": [{"count": 60}],
    "box": {"size": [200, 60], "boundary": {"x": "periodic", "y": "walls"}},
    "gravity": 0.1,
    "placement": "random",
    "seed": 4,
    "stop": {"duration": 300},
    "log": {"snapshot_interval": 1, "thermo_interval": 1, "checkpoint_interval": 20}
}"#;

#[test]
fn a_run_with_gravity_resumes_byte_for_byte_and_analyze_fits_its_atmosphere() {
    let spec = Config::from_json_str(CONFIG)
        .unwrap()
        .to_run_spec()
        .unwrap();
    let full = tmp("gravity-full.mcap");
    run(&spec, &full, Control::default()).unwrap();
    let expected = raw(&full);
    let bytes = std::fs::read(&full).unwrap();
    let cut = tmp("gravity-cut.mcap");
    std::fs::write(&cut, &bytes[..bytes.len() / 2]).unwrap();
    let out = tmp("gravity-resumed.mcap");
    resume(&cut, &out, &ResumeOptions::default(), Control::default()).unwrap();
    let got = raw(&out);
    assert_eq!(got.len(), expected.len());
    for (k, (a, b)) in got.iter().zip(&expected).enumerate() {
        assert!(a == b, "message {k} differs after the resume");
    }

    let opts = AnalysisOptions {
        equilibrate: Some(100.0),
        ..AnalysisOptions::default()
    };
    let (report, complete) = analyze_log(&full, opts, &mut Quiet).unwrap();
    assert!(complete);
    let g = report.gravity.as_ref().expect("a gravity report");
    assert_eq!(g.g, 0.1);
    assert!(g.snapshots >= 190, "{} snapshots", g.snapshots);
    let (e0, e1) = (g.total_energy_first.unwrap(), g.total_energy_last.unwrap());
    assert!((e1 - e0).abs() < 1e-9 * e0, "K + U from {e0} to {e1}");
    // U ≈ N (m g a + kT) for a tall dilute column, about 60 · (0.05 + 1.2); only
    // its order is checked here, the fit is the measurement.
    assert!(
        g.potential_energy > 30.0 && g.potential_energy < 150.0,
        "{}",
        g.potential_energy
    );
    let fit = &g.barometric[0];
    let se = fit.beta_std_error.unwrap();
    println!(
        "β_g = {} ± {se} against m g/kT = {}; U = {}",
        fit.beta, fit.beta_expected, g.potential_energy
    );
    // Nearly an ideal gas: within 4 SE (a short run; the validation case is longer).
    assert!(fit.deviation_se.unwrap().abs() < 4.0, "{fit:?}");
    let n_total: f64 = g.density[0].iter().sum::<f64>() * g.bin_width * 200.0;
    assert!(
        (n_total - 60.0).abs() < 1e-9,
        "the profile holds every disc: {n_total}"
    );
    let json = serde_json::to_value(&report).unwrap();
    assert!(json["gravity"]["barometric"][0]["beta"].is_number());
    for p in [&full, &cut, &out] {
        std::fs::remove_file(p).unwrap();
    }
}
