//! Cost of logging every collision to MCAP (issue 3): collisions per second of the
//! bare engine against the same engine with every collision logged, at N = 10⁴,
//! η = 0.5 (periodic, σ = 1, m = 1, kT = 1, equilibrated for 10 collisions per
//! disc), plus the full run driver.
//!
//! * `bare` — `Engine::run_collisions`, no logging;
//! * first, outside criterion, `interleaved`: bare and logged blocks of 200 000
//!   collisions of the same trajectory, alternated so that changing machine load
//!   hits both alike; prints both rates, their ratio, and bytes per collision, for
//!   the default (zstd −1, writer thread), inline writing, and zstd levels 1 and 3,
//!   and the default at N = 10⁶ (`CAROM_BENCH_INTERLEAVED_ONLY=1` stops there;
//!   `CAROM_BENCH_DETAIL=full` logs the full record instead of the compact one);
//! * `logged/zstd` (default level −1), `logged/zstd1`, `logged/lz4`, `logged/none` —
//!   the driver's hot loop: every event to a [`LogWriter`] with its default options
//!   (batches of 4096 collisions, writer thread), into a file that is finished and
//!   deleted after each sample;
//! * `run/bare-engine` vs `run/logged` — a whole `carom_run::run` of 10⁶
//!   collisions from the lattice start against building and running a bare engine
//!   for as many collisions: `run/logged` with the default log options (snapshots,
//!   thermo, checkpoints), `run/logged-collisions-only` with every collision and
//!   only the initial and final checkpoints.
//!
//! Each logged case prints the bytes per logged collision of the files it wrote.
//! Run: `cargo bench --bench logging -- --warm-up-time 1 --measurement-time 5`.

use carom_engine::{Engine, EngineParams, Event, SystemSpec};
use carom_log::{Compression, LogOptions, LogWriter, RunSpec, Stop, WriterOptions, WriterPosition};
use criterion::{criterion_group, Criterion, Throughput};
use std::collections::BTreeMap;
use std::path::PathBuf;
use std::time::{Duration, Instant};

const N: usize = 10_000;
const ETA: f64 = 0.5;
const BATCH: u64 = 100_000;

fn system() -> SystemSpec {
    SystemSpec::periodic_fluid(N, ETA, 42)
}

fn engine() -> Engine {
    engine_of(N)
}

/// An equilibrated fluid of `n` discs at η = [`ETA`] (10 collisions per disc).
fn engine_of(n: usize) -> Engine {
    let spec = SystemSpec::periodic_fluid(n, ETA, 42);
    let mut e =
        Engine::new(spec.build().expect("valid"), EngineParams::default()).expect("engine starts");
    e.run_collisions(10 * n as u64).expect("equilibrates");
    e
}

/// Process the engine's next event and log it; 1 if it was a collision.
fn log_next(e: &mut Engine, w: &mut LogWriter) -> u64 {
    match e.next_event().expect("elastic").expect("events") {
        Event::Pair(p) => {
            w.observe_pair(&p).expect("write");
            1
        }
        Event::Wall(wc) => {
            w.observe_wall(&wc).expect("write");
            1
        }
        Event::Scheduled { .. } | Event::Pause { .. } => 0,
    }
}

fn out_path(name: &str) -> PathBuf {
    std::env::temp_dir().join(format!("carom-bench-{}-{name}.mcap", std::process::id()))
}

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("N=10000,eta=0.50");
    group.throughput(Throughput::Elements(BATCH));
    group.sample_size(10);
    let mut slot: Option<Engine> = None;
    group.bench_function("bare", |b| {
        let e = slot.get_or_insert_with(engine);
        b.iter_custom(|iters| {
            let start = Instant::now();
            for _ in 0..iters {
                e.run_collisions(BATCH).expect("elastic");
            }
            start.elapsed()
        });
    });
    for (name, compression, level) in [
        ("logged/zstd", Compression::Zstd, None),
        ("logged/zstd1", Compression::Zstd, Some(1)),
        ("logged/lz4", Compression::Lz4, None),
        ("logged/none", Compression::None, None),
    ] {
        let mut slot: Option<Engine> = None;
        let (mut bytes, mut logged) = (0u64, 0u64);
        group.bench_function(name, |b| {
            let e = slot.get_or_insert_with(engine);
            b.iter_custom(|iters| {
                let path = out_path("hot");
                let mut opts = WriterOptions::from_log_options(&LogOptions {
                    compression,
                    ..LogOptions::default()
                });
                if let Some(level) = level {
                    opts.compression_level = level;
                }
                let start = Instant::now();
                let mut w =
                    LogWriter::create(&path, opts, &BTreeMap::new(), WriterPosition::default())
                        .expect("log opens");
                let mut tick = 0u32;
                for _ in 0..iters {
                    let mut done = 0;
                    while done < BATCH {
                        done += log_next(e, &mut w);
                        tick = tick.wrapping_add(1);
                        if tick.is_multiple_of(1024) {
                            w.maybe_flush().expect("flush");
                        }
                    }
                }
                let size = w.finish(&BTreeMap::new()).expect("finish");
                let elapsed = start.elapsed();
                bytes += size;
                logged += w.stats().logged_collisions;
                std::fs::remove_file(&path).ok();
                elapsed
            });
        });
        if logged > 0 {
            eprintln!(
                "\n[{name}] {:.1} bytes per logged collision ({:.1} MB per 10^6 collisions)",
                bytes as f64 / logged as f64,
                bytes as f64 / logged as f64
            );
        }
    }
    group.finish();

    // The full driver against an equally long bare run, both from the lattice start.
    let mut group = c.benchmark_group("run,N=10000,eta=0.50");
    const RUN: u64 = 1_000_000;
    group.throughput(Throughput::Elements(RUN));
    group.sample_size(10);
    group.measurement_time(Duration::from_secs(15));
    group.bench_function("bare-engine", |b| {
        b.iter(|| {
            let mut e = Engine::new(system().build().expect("valid"), EngineParams::default())
                .expect("engine starts");
            e.run_collisions(RUN).expect("elastic")
        })
    });
    let path = out_path("run");
    for (name, log) in [
        // The default log options: snapshots every 1, thermo every 0.1, checkpoints
        // every 10 time units (at N = 10⁴ a snapshot is ~340 kB, a checkpoint ~1.3 MB).
        ("logged", LogOptions::default()),
        // Every collision, nothing else but the initial and final checkpoint.
        (
            "logged-collisions-only",
            LogOptions {
                snapshot_interval: None,
                thermo_interval: None,
                checkpoint_interval: None,
                ..LogOptions::default()
            },
        ),
    ] {
        let spec = RunSpec {
            system: system(),
            params: EngineParams::default(),
            stop: Stop::Collisions(RUN),
            max_time_without_collision: None,
            log,
            config_json: "{}".into(),
            thermostat: None,
        };
        let mut size = 0;
        group.bench_function(name, |b| {
            b.iter(|| {
                let s = carom_run::run(&spec, &path, Default::default()).expect("runs");
                size = s.file_bytes;
                s.collisions_this_process
            })
        });
        if size > 0 {
            eprintln!(
                "\n[run/{name}] file of {size} bytes for {RUN} collisions ({:.1} bytes per collision)",
                size as f64 / RUN as f64
            );
        }
    }
    std::fs::remove_file(&path).ok();
    group.finish();
}

/// Bare and logged runs of the same trajectory, alternated in blocks so that a
/// machine whose load changes over time (other processes) affects both alike.
/// Prints both rates and their ratio. Each logged block opens a log, logs every
/// collision of the block and finishes the file (waiting for the writer thread).
fn interleaved(label: &str, level: i32, background: bool, rounds: usize) {
    interleaved_at(N, label, level, background, rounds);
}

/// [`interleaved`] for `n` discs.
fn interleaved_at(n: usize, label: &str, level: i32, background: bool, rounds: usize) {
    const BLOCK: u64 = 200_000;
    let mut bare = engine_of(n);
    let mut logged = bare.clone();
    let (mut t_bare, mut t_logged) = (Duration::ZERO, Duration::ZERO);
    let (mut bytes, mut count) = (0u64, 0u64);
    let path = out_path("interleaved");
    for _ in 0..rounds {
        let start = Instant::now();
        bare.run_collisions(BLOCK).expect("elastic");
        t_bare += start.elapsed();

        let mut opts = WriterOptions::from_log_options(&LogOptions::default());
        opts.compression_level = level;
        opts.background = background;
        // CAROM_BENCH_DETAIL=full: the full record (log format 1's) instead.
        if std::env::var("CAROM_BENCH_DETAIL").is_ok_and(|d| d == "full") {
            opts.collision_detail = carom_log::CollisionDetail::Full;
        }
        let start = Instant::now();
        let mut w = LogWriter::create(&path, opts, &BTreeMap::new(), WriterPosition::default())
            .expect("log opens");
        let mut done = 0;
        while done < BLOCK {
            done += log_next(&mut logged, &mut w);
        }
        bytes += w.finish(&BTreeMap::new()).expect("finish");
        t_logged += start.elapsed();
        count += BLOCK;
    }
    std::fs::remove_file(&path).ok();
    let rb = count as f64 / t_bare.as_secs_f64();
    let rl = count as f64 / t_logged.as_secs_f64();
    eprintln!(
        "[interleaved N = {n}, {label}] bare {:.0} collisions/s, logged {:.0} collisions/s: {:.1} % of bare; {:.1} bytes per collision",
        rb,
        rl,
        100.0 * rl / rb,
        bytes as f64 / count as f64
    );
}

// Plots off: criterion draws them with plotters, whose PDF backend panics when the
// machine has no fonts (the 2-core test machine has none), ending the run after the
// first case. The numbers are printed either way.
criterion_group! {
    name = benches;
    config = Criterion::default().without_plots();
    targets = bench
}

fn main() {
    interleaved("zstd level -1 (default), writer thread", -1, true, 10);
    interleaved("zstd level -1 (default), inline", -1, false, 10);
    interleaved("zstd level 1, writer thread", 1, true, 10);
    interleaved("zstd level 3 (zstd's default), writer thread", 3, true, 10);
    interleaved_at(
        1_000_000,
        "zstd level -1 (default), writer thread",
        -1,
        true,
        10,
    );
    // CAROM_BENCH_INTERLEAVED_ONLY=1: the interleaved ratios only, no criterion cases.
    if std::env::var_os("CAROM_BENCH_INTERLEAVED_ONLY").is_some() {
        return;
    }
    benches();
    Criterion::default().configure_from_args().final_summary();
}
