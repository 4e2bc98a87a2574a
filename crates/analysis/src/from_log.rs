//! From a log file to a [`Report`] in one streaming pass: the time span and
//! counts from the log's index (or a scan of a log cut short), the run from its
//! facts ([`describe`]; a log before format 2.4 derives them once through the
//! caller's [`OldLogFacts`]), a compression run's growth read first
//! (`compression.rs`: radii after growth, window after it), then every message
//! fed to the [`Analyzer`]. A log without collisions, or with every k-th, gives
//! the virial and wall impulse from differences of consecutive `/thermo`
//! running totals. A log described by its first snapshot keeps the messages
//! read up to it and feeds them after, so the pass stays one. The thermostat,
//! compression and floor go to [`Analyzer::finish_with`] as [`RunDynamics`].

use std::path::Path;

use carom_core::DVec2;
use carom_log::{
    scan_indexed, scan_observed, LogEnd, LogMessage, LogReader, ReadError, ReadProgress,
};
use carom_log::{Snapshot, KIND_PAIR};

use super::compression::Compression;
use super::description::describe;
use super::error::AnalysisError;
use super::log_facts::{log_facts, no_old_log_facts, OldLogFacts};
use super::run_dynamics::{FloorRun, RunDynamics};
use super::stats::StatsError;
use super::{AnalysisOptions, Analyzer, Report, Unwrapper};

/// Who hears how reading a log goes (a progress display).
pub trait ReadObserver {
    /// A pass over the file begins, named by what it does ("scanning", "reading").
    fn pass(&mut self, what: &'static str);
    /// How far the current pass has got.
    fn progress(&mut self, p: ReadProgress);
    /// A warning about the log, for people.
    fn warn(&mut self, line: &str);
}

/// Analyse the log `path` with `opts`, telling `observer` how reading goes, from
/// the facts the log stores alone: [`analyze_log_with`] and [`no_old_log_facts`]
/// (a log before format 2.4 is analysed without its thermostat, growth and floor).
pub fn analyze_log(
    path: &Path,
    opts: AnalysisOptions,
    observer: &mut dyn ReadObserver,
) -> Result<(Report, bool), AnalysisError> {
    analyze_log_with(path, opts, &no_old_log_facts, observer)
}

/// Analyse the log `path` with `opts`, telling `observer` how reading goes; a
/// log written before its facts were complete (format < 2.4) has them derived
/// once from its configuration by `old_log`. Returns the report and whether
/// every message was read (the log is not cut short; it may be damaged outside
/// its chunks, which the observer is told).
pub fn analyze_log_with(
    path: &Path,
    opts: AnalysisOptions,
    old_log: OldLogFacts<'_>,
    observer: &mut dyn ReadObserver,
) -> Result<(Report, bool), AnalysisError> {
    let info = match scan_indexed(path)? {
        Some(info) => info,
        None => {
            observer.pass("scanning");
            scan_observed(path, &mut |p| observer.progress(p))?
        }
    };
    if let Some(w) = info.end.warning() {
        observer.warn(&format!("warning: {w}"));
    }
    let complete = matches!(info.end, LogEnd::Complete | LogEnd::Damaged { .. });
    let warned = matches!(info.end, LogEnd::Damaged { .. });
    // Decompression on a second core, ahead of the analysis on this one.
    let mut reader = LogReader::open(path)?;
    observer.pass("reading");
    let shown = 0;
    // Messages read before the analysis could start (only when the run is learnt
    // from the first snapshot).
    let mut early: Vec<LogMessage> = Vec::new();
    let mut first_snapshot = || -> Result<Option<Snapshot>, ReadError> {
        while let Some(m) = reader.next_message()? {
            let s = match &m {
                LogMessage::Snapshot(s) => Some(s.clone()),
                _ => None,
            };
            early.push(m);
            if s.is_some() {
                return Ok(s);
            }
        }
        Ok(None)
    };
    let mut warnings = Vec::new();
    let facts = log_facts(&info.run, old_log);
    let mut run = describe(
        &path.display().to_string(),
        &info,
        &facts.description,
        &mut first_snapshot,
        &mut |w: &str| warnings.push(w.to_owned()),
    )?;
    for w in &warnings {
        observer.warn(w);
    }
    let t_end = run.t_end;
    // The run's thermostat, growth and floor (none known: none).
    let dynamics = facts.dynamics.as_ref();
    let mut opts = opts;
    let compression = match dynamics.and_then(|d| d.growth.as_ref()) {
        Some(g) => {
            let c = Compression::read(path, g, &run.species, &run.sim_box)?;
            if let Some(t) = opts.equilibrate {
                if !(t.is_finite() && t >= 0.0) {
                    return Err(AnalysisError::Unusable(format!(
                        "--equilibrate {t}: must be a finite time ≥ 0"
                    )));
                }
            }
            opts.equilibrate = Some(c.window_start(opts.equilibrate, run.t_start, t_end)?);
            if let Some(species) = c.final_species(&run.species) {
                run.species = species;
            }
            Some(c)
        }
        None => None,
    };
    if let Some(t) = opts.equilibrate {
        if !(t.is_finite() && t >= 0.0) {
            return Err(AnalysisError::Unusable(format!(
                "--equilibrate {t}: must be a finite time ≥ 0"
            )));
        }
        if t >= t_end {
            return Err(AnalysisError::Unusable(format!(
                "--equilibrate {t}: must be before the end of the log at t = {t_end}"
            )));
        }
    }
    if let Some(dt) = opts.every {
        if !(dt.is_finite() && dt >= 0.0) {
            return Err(AnalysisError::Unusable(format!(
                "--every {dt}: must be a finite time ≥ 0"
            )));
        }
    }
    let mut feed = Feed {
        totals_from_thermo: run.totals_from_thermo,
        analyzer: Analyzer::new(run, opts)?,
        previous_thermo: None,
        vx: Vec::new(),
        vy: Vec::new(),
        ux: Vec::new(),
        uy: Vec::new(),
        unwrapper: Unwrapper::new(),
        totals: Vec::new(),
    };
    for m in early {
        feed.message(m)?;
    }
    // Reading, decompressing and decoding on other threads, the analysis here.
    // A truncated tail ends the stream (the scan already warned).
    for item in decode_ahead(reader, shown, warned) {
        let (m, progress) = item?;
        if let Some(p) = progress {
            observer.progress(p);
        }
        feed.message(m)?;
    }
    let totals = std::mem::take(&mut feed.totals);
    let gaps = feed.unwrapper.ambiguous_gaps();
    feed.analyzer.ambiguous_gaps(gaps);
    let run_dynamics = RunDynamics {
        thermostat: dynamics.and_then(|d| d.thermostat.map(|t| (t, d.restitution))),
        compression: compression.map(|c| c.report),
        floor: dynamics.and_then(|d| {
            d.floor.map(|floor| FloorRun {
                floor,
                gravity: d.gravity,
                totals,
            })
        }),
    };
    let report = feed.analyzer.finish_with(run_dynamics)?;
    Ok((report, complete))
}

/// Messages read and decoded on a thread of their own (the records themselves
/// read ahead on another), handed over in order with the reading progress when
/// it changed; the first error ends the stream. At most [`AHEAD`] messages wait.
/// Damage after the last chunk is told once, unless `warned` already.
fn decode_ahead(
    mut reader: LogReader,
    mut shown: u64,
    warned: bool,
) -> impl Iterator<Item = Result<(LogMessage, Option<ReadProgress>), ReadError>> {
    let (tx, rx) = std::sync::mpsc::sync_channel(AHEAD);
    std::thread::spawn(move || loop {
        let progress = reader.progress_since(&mut shown);
        let item = match reader.next_message() {
            Ok(Some(m)) => Ok((m, progress)),
            Ok(None) => {
                // Damage after the last chunk shows only to this full read.
                if let (LogEnd::Damaged { .. }, Some(w), false) =
                    (reader.end(), reader.end().warning(), warned)
                {
                    use std::io::Write as _;
                    let _ = writeln!(std::io::stderr(), "warning: {w}");
                }
                return;
            }
            Err(e) => Err(e),
        };
        let failed = item.is_err();
        // A closed channel: the analysis stopped; so does the reading.
        if tx.send(item).is_err() || failed {
            return;
        }
    });
    rx.into_iter()
}

/// Decoded messages waiting for the analysis at most.
const AHEAD: usize = 8;

/// An [`Analyzer`] fed message by message.
struct Feed {
    analyzer: Analyzer,
    totals_from_thermo: bool,
    /// (time, virial sum, wall impulse, pair collisions) of the last `/thermo`.
    previous_thermo: Option<(f64, f64, f64, u64)>,
    vx: Vec<f64>,
    vy: Vec<f64>,
    /// Unwrapped positions of the last snapshot (physics.md §12).
    ux: Vec<f64>,
    uy: Vec<f64>,
    unwrapper: Unwrapper,
    /// (time, floor work, energy lost) of each `/checkpoint`: the engine's totals.
    totals: Vec<(f64, f64, f64)>,
}

/// The components of `v` into `x` and `y`.
fn components(v: &[DVec2], x: &mut Vec<f64>, y: &mut Vec<f64>) {
    x.clear();
    y.clear();
    x.extend(v.iter().map(|p| p.x));
    y.extend(v.iter().map(|p| p.y));
}

impl Feed {
    fn message(&mut self, m: LogMessage) -> Result<(), StatsError> {
        let a = &mut self.analyzer;
        match m {
            LogMessage::Collisions(b) => {
                for k in 0..b.time.len() {
                    if b.kind[k] == KIND_PAIR {
                        a.pair(b.time[k], b.virial[k], b.energy_lost[k]);
                        a.pair_detail(
                            b.time[k],
                            (b.i[k], b.j[k]),
                            [b.nx[k], b.ny[k]],
                            [
                                [b.vix_after[k], b.viy_after[k]],
                                [b.vjx_after[k], b.vjy_after[k]],
                            ],
                        );
                    } else {
                        a.wall(b.time[k], b.virial[k], b.energy_lost[k]);
                    }
                }
            }
            LogMessage::Snapshot(s) => {
                components(&s.velocities, &mut self.vx, &mut self.vy);
                a.snapshot(s.time, &s.species, &self.vx, &self.vy)?;
                components(self.unwrapper.push(&s), &mut self.ux, &mut self.uy);
                let (u, v) = ([&self.ux[..], &self.uy], [&self.vx[..], &self.vy]);
                a.motion(s.time, &s.species, u, v)?;
                components(&s.positions, &mut self.vx, &mut self.vy);
                a.positions(s.time, &s.species, &self.vx, &self.vy)?;
            }
            LogMessage::Thermo(t) => {
                a.thermo(t.time, t.kinetic_energy, Some(t.energy_lost));
                a.pair_count(t.pair_collisions);
                if self.totals_from_thermo {
                    if let Some((t0, v0, w0, p0)) = self.previous_thermo {
                        if t.pair_collisions >= p0 {
                            a.increment(
                                t0,
                                t.time,
                                t.virial_sum - v0,
                                t.wall_impulse - w0,
                                t.pair_collisions - p0,
                            );
                        }
                    }
                    self.previous_thermo =
                        Some((t.time, t.virial_sum, t.wall_impulse, t.pair_collisions));
                }
            }
            LogMessage::Checkpoint(c) => {
                let s = &c.engine.stats;
                self.totals
                    .push((c.engine.now, s.floor_work, s.energy_lost));
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    //! Small logs written by hand with carom-log's `LogWriter` (the events chosen
    //! by the test, not run by an engine), analysed from the file; expected
    //! values worked from the events written.
    use super::*;
    use carom_core::{Axis, SimBox, Species, WallSide};
    use carom_engine::{EngineParams, PairCollision, State, WallCollision};
    use carom_log::{
        CollisionDetail, LogOptions, LogWriter, RunFacts, RunMetadata, Stop, StopReason,
        SummaryMetadata, Thermo, WriterOptions, WriterPosition,
    };
    use std::path::PathBuf;

    /// Hears nothing but the warnings.
    #[derive(Default)]
    struct Quiet(Vec<String>);

    impl ReadObserver for Quiet {
        fn pass(&mut self, _: &'static str) {}
        fn progress(&mut self, _: ReadProgress) {}
        fn warn(&mut self, line: &str) {
            self.0.push(line.to_owned());
        }
    }

    /// A log file removed when dropped.
    struct TmpLog(PathBuf);

    impl Drop for TmpLog {
        fn drop(&mut self) {
            let _ = std::fs::remove_file(&self.0);
        }
    }

    /// Four discs of radius 0.5 and mass 2.
    const SPECIES: Species = Species::new(4, 0.5, 2.0);

    /// What a test log holds.
    struct Plan {
        sim_box: SimBox,
        /// Log the collisions (else only the thermo records' running totals).
        collisions: bool,
        /// Store the run's facts (else an unreadable configuration, so that the
        /// first snapshot describes the run).
        facts: bool,
        /// Kinetic energy of every thermo record and of the snapshot.
        kinetic: f64,
        /// Running totals per unit time: virial sum, wall impulse, pair collisions.
        rates: (f64, f64, u64),
    }

    /// A log over [0, 10]: thermo records every 0.5 with running totals growing
    /// at `plan.rates`; if `plan.collisions`, a pair collision (virial 0.3) at
    /// 0.25 + 0.5k and a wall collision (impulse 0.45) at 0.3 + 0.5k, k = 0..19;
    /// one snapshot at 0.5 (after the thermo record at 0) with K = `plan.kinetic`.
    fn write_log(name: &str, plan: &Plan) -> TmpLog {
        static N: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);
        let k = N.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        let path = std::env::temp_dir().join(format!(
            "carom-from-log-{}-{k}-{name}.mcap",
            std::process::id()
        ));
        let log = LogOptions {
            collisions: plan.collisions,
            collision_every: 1,
            collision_detail: CollisionDetail::Full,
            snapshot_interval: Some(10.0),
            thermo_interval: Some(0.5),
            checkpoint_interval: None,
            scene_interval: None,
            ..LogOptions::default()
        };
        let params = EngineParams::default();
        let meta = RunMetadata {
            log_format: carom_log::LOG_FORMAT_VERSION.into(),
            carom_version: "0.0.0-test".into(),
            config: "not json".into(),
            seed: 1,
            start_time: String::new(),
            n_discs: 4,
            stop: Stop::Time(10.0),
            max_time_without_collision: None,
            log: log.clone(),
            resumed_from: None,
            resumed_at: None,
            run_facts: plan
                .facts
                .then(|| RunFacts::new(&[SPECIES], &plan.sim_box, &params, &log)),
        };
        let options = WriterOptions::from_log_options(&log);
        let mut w =
            LogWriter::create(&path, options, &meta.to_map(), WriterPosition::default()).unwrap();
        let (virial_rate, impulse_rate, pair_rate) = plan.rates;
        let thermo = |t: f64| Thermo {
            time: t,
            kinetic_energy: plan.kinetic,
            temperature: 0.0,
            collisions: 0,
            pair_collisions: (t * pair_rate as f64) as u64,
            wall_collisions: 0,
            energy_lost: 0.0,
            virial_sum: virial_rate * t,
            wall_impulse: impulse_rate * t,
            pressure: None,
            z: None,
            collision_rate: None,
            ..Default::default()
        };
        let v = carom_core::DVec2::new(plan.kinetic.sqrt() / 2.0, 0.0);
        for k in 0..=20 {
            let t = 0.5 * k as f64;
            w.write_thermo(&thermo(t)).unwrap();
            if k == 1 {
                // ½·2·(K/4)·4 = K.
                w.write_snapshot(&State {
                    sim_box: plan.sim_box,
                    species: vec![SPECIES],
                    species_of: vec![0; 4],
                    positions: (0..4)
                        .map(|i| carom_core::DVec2::new(1.0 + 2.0 * i as f64, 3.0))
                        .collect(),
                    velocities: vec![v, -v, v, -v],
                    images: Vec::new(),
                    time: t,
                })
                .unwrap();
            }
            if plan.collisions && k < 20 {
                w.observe_pair(&PairCollision {
                    time: t + 0.25,
                    i: 0,
                    j: 1,
                    normal: carom_core::DVec2::new(1.0, 0.0),
                    vi_before: v,
                    vj_before: -v,
                    vi_after: -v,
                    vj_after: v,
                    energy_lost: 0.0,
                    virial: 0.3,
                    impulse: -4.0 * v,
                })
                .unwrap();
                w.observe_wall(&WallCollision {
                    time: t + 0.3,
                    i: 2,
                    axis: Axis::X,
                    side: WallSide::High,
                    v_before: v,
                    v_after: -v,
                    impulse: 0.45,
                    energy_lost: 0.0,
                })
                .unwrap();
            }
        }
        let summary = SummaryMetadata {
            end_time: String::new(),
            stop_reason: StopReason::Time,
            error: None,
            sim_time: 10.0,
            pair_collisions: 20,
            wall_collisions: 20,
            logged_collisions: if plan.collisions { 40 } else { 0 },
            kinetic_energy: plan.kinetic,
            energy_lost: 0.0,
            virial_sum: 0.0,
            wall_seconds: 1.0,
            collisions_per_second: 1.0,
            potential_energy: None,
        };
        w.finish(&summary.to_map()).unwrap();
        TmpLog(path)
    }

    fn opts(equilibrate: Option<f64>, every: Option<f64>) -> AnalysisOptions {
        AnalysisOptions {
            equilibrate,
            every,
            time_bins: 16,
            ..Default::default()
        }
    }

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() < 1e-9 * b.abs().max(1.0)
    }

    /// Walls 10 × 8 (f = 2N = 8), K = 6: kT = 2·6/8 = 1.5. Window [1, 10] (the
    /// default skips 10 %): 18 logged pairs (1.25 … 9.75) and 18 wall collisions
    /// of impulse 0.45 (1.3 … 9.8): ω = 2·18/(4·9) = 1; J/t = 8.1/9 = 0.9 and
    /// Z = (J/t)/(2 kT Σ_axes N/ℓ) with ℓ = 10 − 1, 8 − 1: 0.9/(3·(4/9 + 4/7)).
    #[test]
    fn logged_collisions_are_read_as_pairs_and_walls() {
        let plan = Plan {
            sim_box: SimBox::walled(10.0, 8.0, 1.0),
            collisions: true,
            facts: true,
            kinetic: 6.0,
            rates: (0.0, 0.0, 0),
        };
        let log = write_log("walls", &plan);
        let (r, complete) = analyze_log(&log.0, opts(None, None), &mut Quiet::default()).unwrap();
        assert!(complete);
        let c = &r.collision_rate;
        assert_eq!(
            (c.logged_pair_collisions, c.logged_wall_collisions),
            (20, 20)
        );
        assert!(close(c.per_disc, 1.0), "{c:?}");
        assert_eq!(r.window.equilibrate, 1.0);
        let z = r.pressure.unwrap().z;
        assert!(close(z, 0.9 / (3.0 * (4.0 / 9.0 + 4.0 / 7.0))), "{z}");
        assert!(close(r.temperature.kt, 1.5));
    }

    /// Without collisions the running totals of consecutive thermo records are
    /// spread over the bins. Periodic (f = 2N − 2 = 6), K = 4.5: kT = 1.5; the
    /// virial sum grows by 12 per unit time: Z = 1 + 12/(2 N kT) = 2; 8 pairs
    /// per unit time: ω = 2·8/4 = 4. With walls 10 × 8 (f = 8, K = 6, kT = 1.5),
    /// the impulse growing by 9: Z = 9/(2·1.5·(4/9 + 4/7)).
    #[test]
    fn without_collisions_the_thermo_records_give_the_totals() {
        let plan = Plan {
            sim_box: SimBox::periodic(10.0, 10.0),
            collisions: false,
            facts: true,
            kinetic: 4.5,
            rates: (12.0, 5.0, 8),
        };
        let log = write_log("periodic", &plan);
        let (r, _) = analyze_log(&log.0, opts(None, None), &mut Quiet::default()).unwrap();
        assert!(close(r.pressure.unwrap().z, 2.0));
        assert!(close(r.collision_rate.per_disc, 4.0));
        assert_eq!(r.collision_rate.logged_pair_collisions, 0);
        let plan = Plan {
            sim_box: SimBox::walled(10.0, 8.0, 1.0),
            kinetic: 6.0,
            rates: (12.0, 9.0, 8),
            ..plan
        };
        let log = write_log("walled", &plan);
        let (r, _) = analyze_log(&log.0, opts(None, None), &mut Quiet::default()).unwrap();
        let z = r.pressure.unwrap().z;
        assert!(close(z, 9.0 / (3.0 * (4.0 / 9.0 + 4.0 / 7.0))), "{z}");
        assert!(close(r.collision_rate.per_disc, 4.0));
    }

    /// A log whose configuration cannot be read and without facts: the first
    /// snapshot (at 0.5) describes the run, and the thermo record read before it
    /// (at 0) is still analysed: kT at the first record is 2·4.5/6 = 1.5 although
    /// the first snapshot is at 0.5.
    #[test]
    fn messages_before_the_first_snapshot_are_kept_when_it_describes_the_run() {
        let plan = Plan {
            sim_box: SimBox::periodic(10.0, 10.0),
            collisions: false,
            facts: false,
            kinetic: 4.5,
            rates: (12.0, 0.0, 8),
        };
        let log = write_log("no-facts", &plan);
        let mut quiet = Quiet::default();
        let (r, complete) = analyze_log(&log.0, opts(None, None), &mut quiet).unwrap();
        assert!(complete);
        assert_eq!(quiet.0.len(), 1, "{:?}", quiet.0);
        assert_eq!((r.n, r.elastic, r.periodic), (4, true, [true, true]));
        assert_eq!(r.temperature.series[0], [0.0, 1.5]);
        assert_eq!(r.temperature.kt_initial, Some(1.5));
        assert!(close(r.pressure.unwrap().z, 2.0));
        assert_eq!(r.window.snapshots_seen, 1);
    }

    /// `--equilibrate` must be a finite time ≥ 0 before the log's end (10), and
    /// `--every` a finite time ≥ 0; both refused as unusable, not as a statistic.
    #[test]
    fn the_options_must_fit_the_log() {
        let plan = Plan {
            sim_box: SimBox::periodic(10.0, 10.0),
            collisions: false,
            facts: true,
            kinetic: 4.5,
            rates: (12.0, 0.0, 8),
        };
        let log = write_log("options", &plan);
        let analyse = |o| analyze_log(&log.0, o, &mut Quiet::default());
        for (eq, every) in [
            (Some(-1.0), None),
            (Some(f64::NAN), None),
            (Some(10.0), None),
            (Some(12.0), None),
            (None, Some(-0.5)),
            (None, Some(f64::NAN)),
            (None, Some(f64::INFINITY)),
        ] {
            let r = analyse(opts(eq, every));
            assert!(
                matches!(r, Err(AnalysisError::Unusable(_))),
                "{eq:?} {every:?}: {r:?}"
            );
        }
        for (eq, every) in [(Some(0.0), Some(0.0)), (Some(2.0), Some(1.5))] {
            let (r, _) = analyse(opts(eq, every)).unwrap();
            assert_eq!((r.window.equilibrate, r.window.every), (eq.unwrap(), every));
        }
    }
}
