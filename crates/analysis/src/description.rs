//! Which run a log holds: species, box, collision rule, logging stride and time
//! span, derived once per log by [`describe`].
//!
//! The species, box and rule come from the run's facts (`log_facts.rs`): stored
//! in the log's metadata (format 1.2 on), or for older logs derived once from the
//! configuration stored in the log (the box from η; no disc is placed); only when
//! there are none are they taken from the first snapshot (counts per species,
//! radii, masses, box, boundaries; collisions then assumed elastic).

use carom_core::{Boundary, Restitution, SimBox, Species};
use carom_log::{LogInfo, ReadError, RunFacts};
use carom_log::{Snapshot, SnapshotSchedule};

use super::error::AnalysisError;

/// Which run is analysed: what the log's metadata and first snapshot say.
#[derive(Debug, Clone, PartialEq)]
pub struct RunDescription {
    /// The species (count, radius, mass).
    pub species: Vec<Species>,
    /// The box.
    pub sim_box: SimBox,
    /// The pair collision rule.
    pub restitution: Restitution,
    /// Logged collisions are every `collision_stride`-th collision (1 = all); sums
    /// over logged collisions are multiplied by it.
    pub collision_stride: u64,
    /// The virial, wall impulse and collision counts come from running totals over
    /// every collision ([`Analyzer::increment`](crate::Analyzer::increment), from the `/thermo` records), and
    /// logged collisions are only counted: for logs without collisions, and for
    /// logs of every k-th collision (k > 1), whose sums would only estimate them.
    pub totals_from_thermo: bool,
    /// Simulated time of the start of the log (time).
    pub t_start: f64,
    /// Simulated time of the end of the log (time).
    pub t_end: f64,
    /// The pair collision rate ω (pair collisions per disc per unit time) known
    /// before the events are read, e.g. from the log's first and last `/thermo`
    /// records; it sets the default spacing of the snapshots used for the velocity
    /// distribution (see [`AnalysisOptions::every`](crate::AnalysisOptions::every)). `None`: unknown.
    pub pair_rate: Option<f64>,
    /// Time between the log's snapshots (time), from its configuration; `None`:
    /// unknown. With it the default spacing is widened only when the snapshots
    /// would otherwise hold more than [`AnalysisOptions::max_velocities`](crate::AnalysisOptions::max_velocities)
    /// velocities; without it, whenever a window full of snapshots could.
    pub snapshot_interval: Option<f64>,
    /// The log's `log.snapshot_schedule`, when it has one: snapshots inside each
    /// snapshot interval, which the structure and velocity tests skip
    /// (`Analyzer::block_start`); `None`: every snapshot starts a block.
    pub snapshot_schedule: Option<SnapshotSchedule>,
    /// Uniform gravity g along −y (length/time², physics.md §15; 0: none).
    pub gravity: f64,
}

impl RunDescription {
    /// Number of discs N.
    pub fn n(&self) -> usize {
        carom_core::observables::disc_count(&self.species)
    }
}

#[cfg(test)]
impl RunDescription {
    /// Two reference discs in a periodic 10 × 10 box, elastic, logged over [0, 10].
    pub(super) fn for_tests() -> Self {
        RunDescription {
            species: vec![Species::reference(2)],
            sim_box: SimBox::periodic(10.0, 10.0),
            restitution: Restitution::Elastic,
            collision_stride: 1,
            totals_from_thermo: false,
            t_start: 0.0,
            t_end: 10.0,
            pair_rate: None,
            snapshot_interval: None,
            snapshot_schedule: None,
            gravity: 0.0,
        }
    }
}

/// The run's species, box and collision rule.
struct Resolved {
    species: Vec<Species>,
    sim_box: SimBox,
    restitution: Restitution,
    gravity: f64,
}

/// From the run's facts.
fn from_facts(f: &RunFacts) -> Resolved {
    Resolved {
        species: f.species.clone(),
        sim_box: f.sim_box,
        restitution: f.restitution,
        gravity: f.gravity,
    }
}

/// From a snapshot, assuming elastic collisions.
fn from_snapshot(s: &Snapshot) -> Result<Resolved, String> {
    let mut counts = vec![0usize; s.species_radius.len()];
    for &k in &s.species {
        *counts.get_mut(k as usize).ok_or_else(|| {
            format!(
                "the first snapshot names species {k} but lists {} species",
                s.species_radius.len()
            )
        })? += 1;
    }
    let species = counts
        .iter()
        .zip(s.species_radius.iter().zip(&s.species_mass))
        .map(|(&count, (&radius, &mass))| Species::new(count, radius, mass))
        .collect();
    let b = |code: u8| match code {
        0 => Boundary::Periodic,
        _ => Boundary::Walls { restitution: 1.0 },
    };
    Ok(Resolved {
        species,
        sim_box: SimBox {
            size: s.box_size,
            boundary: [b(s.boundary[0]), b(s.boundary[1])],
        },
        restitution: Restitution::Elastic,
        gravity: 0.0,
    })
}

/// The pair collision rate ω over the log, from its first and last `/thermo`
/// records, or else from its summary (counts since `t_start`); `None` if neither
/// tells.
fn pair_rate(info: &LogInfo, n: usize, t_start: f64) -> Option<f64> {
    use carom_core::observables::collision_rate;
    let from_thermo = info.thermo_counts.and_then(|[(t0, p0, _), (t1, p1, _)]| {
        (t1 > t0 && p1 > p0).then(|| collision_rate((p1 - p0) as f64, n, t1 - t0))
    });
    let from_summary = info.summary.as_ref().and_then(|s| {
        (s.sim_time > t_start && s.pair_collisions > 0)
            .then(|| collision_rate(s.pair_collisions as f64, n, s.sim_time - t_start))
    });
    from_thermo
        .or(from_summary)
        .filter(|w| w.is_finite() && *w > 0.0)
}

/// The description of the run in the log `file` that `info` summarises (its index
/// or a scan), with the run's `facts` (`log_facts.rs`). `first_snapshot` is asked
/// for the log's first snapshot only when there are no facts (`Err`: why, when
/// the stored configuration cannot be read); `warn` hears why it was asked.
pub(super) fn describe(
    file: &str,
    info: &LogInfo,
    facts: &Result<RunFacts, String>,
    first_snapshot: &mut dyn FnMut() -> Result<Option<Snapshot>, ReadError>,
    warn: &mut dyn FnMut(&str),
) -> Result<RunDescription, AnalysisError> {
    let (mut t_start, mut t_end) = (f64::INFINITY, f64::NEG_INFINITY);
    for (a, b) in info.time_span.iter().flatten() {
        t_start = t_start.min(*a);
        t_end = t_end.max(*b);
    }
    if t_end.is_nan() || t_start.is_nan() || t_end <= t_start {
        return Err(AnalysisError::Unusable(format!(
            "{file} holds no data spanning any simulated time"
        )));
    }
    let resolved = match facts {
        Ok(f) => from_facts(f),
        Err(e) => {
            let s = first_snapshot()?.ok_or_else(|| {
                AnalysisError::Unusable(format!(
                    "the log's configuration cannot be read ({e}) and it has no snapshot"
                ))
            })?;
            warn(&format!("warning: the log's configuration cannot be read ({e}); using its first snapshot and assuming elastic collisions"));
            from_snapshot(&s).map_err(AnalysisError::Unusable)?
        }
    };
    let log = &info.run.log;
    let collisions_logged = log.collisions && info.channels[0];
    let n = carom_core::observables::disc_count(&resolved.species);
    Ok(RunDescription {
        pair_rate: pair_rate(info, n, t_start),
        snapshot_interval: log.snapshot_interval,
        snapshot_schedule: log.snapshots().filter(|s| s.points > 0),
        species: resolved.species,
        sim_box: resolved.sim_box,
        restitution: resolved.restitution,
        gravity: resolved.gravity,
        collision_stride: log.collision_every.max(1),
        // Every k-th collision (k > 1) gives only an estimate of the sums that the
        // /thermo records hold exactly.
        totals_from_thermo: !collisions_logged
            || (log.collision_every > 1 && log.thermo_interval.is_some()),
        t_start,
        t_end,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use carom_engine::EngineParams;
    use carom_log::{LogEnd, LogOptions, RunFacts, RunMetadata, Stop};

    /// A log's scan with the stored configuration `config` and the given facts.
    fn info(config: &str, facts: Option<RunFacts>) -> LogInfo {
        LogInfo {
            run: RunMetadata {
                log_format: "1.2".into(),
                carom_version: "0".into(),
                config: config.into(),
                seed: 0,
                start_time: String::new(),
                n_discs: 7,
                stop: Stop::Time(5.0),
                max_time_without_collision: None,
                log: LogOptions::default(),
                resumed_from: None,
                resumed_at: None,
                run_facts: facts,
            },
            summary: None,
            end: LogEnd::Complete,
            channels: [true; carom_log::N_CHANNELS],
            messages: [1; carom_log::N_CHANNELS],
            logged_collisions: 0,
            time_span: [Some((0.0, 5.0)); carom_log::N_CHANNELS],
            last_checkpoint_time: None,
            thermo_counts: None,
            file_bytes: 0,
        }
    }

    /// An old log's configuration that the test's derivation reads: 30 discs of
    /// radius 0.5, mass 2 between walls 20 × 10.
    const OLD_CONFIG: &str = "the 30 discs";

    /// The facts of `OLD_CONFIG`; any other text cannot be read.
    fn derive(config: &str) -> Result<RunFacts, String> {
        (config == OLD_CONFIG)
            .then(|| {
                RunFacts::new(
                    &[Species::new(30, 0.5, 2.0)],
                    &SimBox::walled(20.0, 10.0, 1.0),
                    &EngineParams::default(),
                    &LogOptions::default(),
                )
            })
            .ok_or_else(|| format!("cannot read {config:?}"))
    }

    fn describe_quietly(info: &LogInfo) -> (Result<RunDescription, AnalysisError>, bool) {
        let mut asked = false;
        let facts = super::super::log_facts::log_facts(&info.run, &derive).description;
        let d = describe(
            "log.mcap",
            info,
            &facts,
            &mut || {
                asked = true;
                Ok(None)
            },
            &mut |_| {},
        );
        (d, asked)
    }

    #[test]
    fn the_run_facts_describe_the_run_without_the_configuration() {
        let species = [Species::new(4, 0.5, 1.0), Species::new(3, 0.7, 2.0)];
        let sim_box = SimBox::walled(12.0, 9.0, 0.9);
        let params = EngineParams {
            restitution: Restitution::Normal(0.8),
            ..EngineParams::default()
        };
        let facts = RunFacts::new(&species, &sim_box, &params, &LogOptions::default());
        // The stored configuration is unreadable: only the facts can describe the run.
        let (d, asked) = describe_quietly(&info("not json", Some(facts)));
        let d = d.unwrap();
        assert!(
            !asked,
            "the first snapshot was read although the facts describe the run"
        );
        assert_eq!(d.species, species);
        assert_eq!(d.sim_box, sim_box);
        assert_eq!(d.restitution, Restitution::Normal(0.8));
        assert_eq!((d.t_start, d.t_end), (0.0, 5.0));
    }

    #[test]
    fn a_log_without_facts_is_described_by_its_configuration() {
        let (d, asked) = describe_quietly(&info(OLD_CONFIG, None));
        let d = d.unwrap();
        assert!(!asked);
        assert_eq!(d.species, vec![Species::new(30, 0.5, 2.0)]);
        assert_eq!(d.sim_box.size, carom_core::DVec2::new(20.0, 10.0));
        // Neither facts nor a readable configuration: the first snapshot is asked for.
        let (d, asked) = describe_quietly(&info("not json", None));
        assert!(asked && d.is_err());
    }

    /// The facts of 4 + 3 discs (N = 7), periodic, elastic.
    fn facts() -> RunFacts {
        let species = [Species::new(4, 0.5, 1.0), Species::new(3, 0.7, 2.0)];
        let sim_box = SimBox::periodic(12.0, 9.0);
        RunFacts::new(
            &species,
            &sim_box,
            &EngineParams::default(),
            &LogOptions::default(),
        )
    }

    fn summary(sim_time: f64, pair_collisions: u64) -> carom_log::SummaryMetadata {
        carom_log::SummaryMetadata {
            end_time: String::new(),
            stop_reason: carom_log::StopReason::Time,
            error: None,
            sim_time,
            pair_collisions,
            wall_collisions: 0,
            logged_collisions: 0,
            kinetic_energy: 1.0,
            energy_lost: 0.0,
            virial_sum: 0.0,
            wall_seconds: 1.0,
            collisions_per_second: 1.0,
            potential_energy: None,
        }
    }

    fn rate_of(info: &LogInfo) -> Option<f64> {
        describe_quietly(info).0.unwrap().pair_rate
    }

    /// ω = 2 N_pair/(N t) with N = 7. From the thermo records (1, 100) and
    /// (5, 900): 2·800/(7·4) = 400/7. From the summary, counted since the log's
    /// start 0.5 to 4.5: 2·140/(7·4) = 10, used only when the thermo records
    /// tell nothing (no time or no collision between them).
    #[test]
    fn the_pair_rate_comes_from_the_thermo_records_or_else_the_summary() {
        let mut i = info("not json", Some(facts()));
        i.time_span = [Some((0.5, 6.0)); carom_log::N_CHANNELS];
        assert_eq!(describe_quietly(&i).0.unwrap().n(), 7);
        assert_eq!(rate_of(&i), None);
        i.summary = Some(summary(4.5, 140));
        assert_eq!(rate_of(&i), Some(10.0));
        let thermo = |t1: f64, p1: u64| Some([(1.0, 100, 3), (t1, p1, 4)]);
        for (counts, rate) in [
            (thermo(5.0, 900), 400.0 / 7.0),
            // No time, no collision, or fewer collisions between the records.
            (thermo(1.0, 900), 10.0),
            (thermo(0.5, 900), 10.0),
            (thermo(5.0, 100), 10.0),
            (thermo(5.0, 40), 10.0),
        ] {
            i.thermo_counts = counts;
            assert!((rate_of(&i).unwrap() - rate).abs() < 1e-12, "{counts:?}");
        }
        // A rate that is not finite and positive is unknown: an infinite summary
        // time gives 0, records 5·10⁻³²⁴ apart give +∞.
        i.summary = Some(summary(f64::INFINITY, 140));
        i.thermo_counts = None;
        assert_eq!(rate_of(&i), None);
        i.summary = None;
        i.thermo_counts = Some([(0.0, 100, 3), (5e-324, 900, 4)]);
        assert_eq!(rate_of(&i), None);
        // No collision or no time since the start in the summary: unknown.
        for s in [summary(4.5, 0), summary(0.5, 140), summary(0.25, 140)] {
            i.summary = Some(s);
            assert_eq!(rate_of(&i), None);
        }
    }

    /// The time span is the union of the channels' spans; a log spanning no time
    /// (no span, or a single instant) cannot be analysed.
    #[test]
    fn the_run_spans_the_union_of_the_channels_times() {
        let mut i = info("not json", Some(facts()));
        i.time_span = [None; carom_log::N_CHANNELS];
        i.time_span[0] = Some((1.5, 4.0));
        i.time_span[2] = Some((0.5, 3.0));
        i.time_span[3] = Some((2.0, 6.5));
        let d = describe_quietly(&i).0.unwrap();
        assert_eq!((d.t_start, d.t_end), (0.5, 6.5));
        i.time_span = [None; carom_log::N_CHANNELS];
        assert!(matches!(
            describe_quietly(&i).0,
            Err(AnalysisError::Unusable(_))
        ));
        i.time_span[1] = Some((2.0, 2.0));
        assert!(matches!(
            describe_quietly(&i).0,
            Err(AnalysisError::Unusable(_))
        ));
    }

    /// Sums come from the logged collisions × stride only when every collision is
    /// logged, or every k-th without thermo records to take exact totals from.
    #[test]
    fn the_totals_come_from_the_thermo_records_unless_every_collision_is_logged() {
        // (collisions logged, channel present, every, thermo) → (from thermo, stride)
        let cases = [
            ((true, true, 1, true), (false, 1)),
            ((true, false, 1, true), (true, 1)),
            ((false, true, 1, true), (true, 1)),
            ((true, true, 3, true), (true, 3)),
            ((true, true, 3, false), (false, 3)),
            ((true, true, 1, false), (false, 1)),
            ((true, true, 0, true), (false, 1)),
        ];
        for ((collisions, channel, every, thermo), want) in cases {
            let mut i = info("not json", Some(facts()));
            i.run.log.collisions = collisions;
            i.run.log.collision_every = every;
            i.run.log.thermo_interval = thermo.then_some(0.25);
            i.run.log.snapshot_interval = Some(0.75);
            i.channels[0] = channel;
            let d = describe_quietly(&i).0.unwrap();
            let got = (d.totals_from_thermo, d.collision_stride);
            assert_eq!(got, want, "{collisions} {channel} {every} {thermo}");
            assert_eq!(d.snapshot_interval, Some(0.75));
        }
    }

    /// Neither facts nor a configuration: the first snapshot gives 2 discs of
    /// species 0 and 3 of species 1 (radii, masses as listed), x periodic and walls
    /// on y (restitution 1), and elastic collisions; a warning says so.
    #[test]
    fn without_facts_or_configuration_the_first_snapshot_describes_the_run() {
        let snapshot = |species: Vec<u16>| Snapshot {
            time: 0.0,
            box_size: carom_core::DVec2::new(12.0, 9.0),
            boundary: [0, 1],
            species_radius: vec![0.5, 0.7],
            species_mass: vec![1.0, 2.5],
            positions: vec![carom_core::DVec2::ZERO; species.len()],
            velocities: vec![carom_core::DVec2::ZERO; species.len()],
            images: Vec::new(),
            species,
        };
        let mut i = info("not json", None);
        i.run.log.collisions = true;
        let mut warned = Vec::new();
        let none = Err("not json".to_owned());
        let d = describe(
            "log.mcap",
            &i,
            &none,
            &mut || Ok(Some(snapshot(vec![0, 1, 1, 0, 1]))),
            &mut |w| warned.push(w.to_owned()),
        )
        .unwrap();
        assert_eq!(
            d.species,
            [Species::new(2, 0.5, 1.0), Species::new(3, 0.7, 2.5)]
        );
        assert_eq!(d.n(), 5);
        let walls = Boundary::Walls { restitution: 1.0 };
        assert_eq!(d.sim_box.boundary, [Boundary::Periodic, walls]);
        assert_eq!(d.sim_box.size, carom_core::DVec2::new(12.0, 9.0));
        assert_eq!(d.restitution, Restitution::Elastic);
        assert_eq!(warned.len(), 1);
        // A snapshot naming a species it does not list is refused.
        let bad = describe(
            "log.mcap",
            &i,
            &none,
            &mut || Ok(Some(snapshot(vec![0, 2]))),
            &mut |_| {},
        );
        assert!(matches!(bad, Err(AnalysisError::Unusable(_))));
    }
}
