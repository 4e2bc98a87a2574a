//! The long elastic run of issue 5, case 7 (not part of any test suite): the bare
//! engine, no log, N = 10⁴ monodisperse discs at η = 0.5 in a periodic square box
//! (lattice start, Maxwell–Boltzmann velocities at kT = 1, seed 1), run for a given
//! number of pair collisions (default 10⁹).
//!
//! Measured and printed (one line per report interval, then a summary):
//! * the contact distance of *every* pair collision: the largest relative overlap
//!   (σ − |r_i − r_j|)/σ seen at a collision, and the largest gap (a collision
//!   resolved while the discs were apart);
//! * every report interval: the relative kinetic-energy drift (K − K0)/K0 and the
//!   momentum change relative to Σ m|v| (`InvariantChecker::check_conservation`,
//!   tolerances disabled so that the run always finishes and reports), and the
//!   largest overlap between any two discs at that instant
//!   (`InvariantChecker::check_overlaps`);
//! * collisions per second of wall-clock time (including the per-collision
//!   distance check, which costs a few per cent); the first report interval is
//!   run through `Engine::run_collisions` without any per-event work and timed
//!   separately as the bare engine speed.
//!
//! ```sh
//! cargo build --release --example long_run
//! nice -n 10 target/release/examples/long_run [COLLISIONS] [REPORT_EVERY]
//! ```

use std::time::Instant;

use carom_engine::{Engine, EngineParams, Event, InvariantChecker, SystemSpec};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let parse = |k: usize, default: f64| -> u64 {
        args.get(k)
            .map(|s| s.parse::<f64>().expect("a number (1e9 accepted)"))
            .unwrap_or(default) as u64
    };
    let total = parse(1, 1e9);
    let every = parse(2, 1e7).max(1);
    let n = 10_000;
    let eta = 0.5;
    let state = SystemSpec::periodic_fluid(n, eta, 1)
        .build()
        .expect("a valid system");
    let mut engine = Engine::new(state, EngineParams::default()).expect("engine");
    let mut checker = InvariantChecker::new(&engine);
    checker.energy_tolerance = f64::INFINITY;
    checker.momentum_tolerance = f64::INFINITY;
    checker.overlap_tolerance = f64::INFINITY;
    let k0 = engine.kinetic_energy();
    println!("N = {n}, eta = {eta}, K0 = {k0:.17e}, {total} pair collisions, report every {every}");

    // Bare speed first (run_collisions, no per-event work), one interval.
    let t_bare = Instant::now();
    let bare = engine.run_collisions(every.min(total)).expect("engine");
    let bare_rate = bare as f64 / t_bare.elapsed().as_secs_f64();
    println!("bare engine: {bare} collisions at {bare_rate:.4e} collisions/s");
    let mut done = bare;

    let mut max_overlap_at_contact = 0.0f64;
    let mut max_gap_at_contact = 0.0f64;
    let mut max_drift = 0.0f64;
    let wall = Instant::now();
    let mut last_report = Instant::now();
    let mut since_report = 0u64;
    while done < total {
        let ev = engine
            .next_event()
            .unwrap_or_else(|e| panic!("engine error after {done} collisions: {e}"))
            .unwrap_or_else(|| panic!("no more events after {done} collisions"));
        if let Event::Pair(p) = ev {
            let (i, j) = (p.i as usize, p.j as usize);
            let d = engine
                .sim_box()
                .minimum_image(engine.position(j) - engine.position(i))
                .length();
            let rel = (1.0 - d) / 1.0; // σ = 1
            if rel > 0.0 {
                max_overlap_at_contact = max_overlap_at_contact.max(rel);
            } else {
                max_gap_at_contact = max_gap_at_contact.max(-rel);
            }
            done += 1;
            since_report += 1;
            if done.is_multiple_of(every) || done == total {
                let _ = checker.check(&engine);
                let drift = (engine.kinetic_energy() - k0) / k0;
                max_drift = max_drift.max(drift.abs());
                let dt = last_report.elapsed().as_secs_f64();
                println!(
                    "{done:>12} collisions  t = {:.4}  dK/K0 = {drift:+.3e}  \
                     max overlap at contact = {max_overlap_at_contact:.3e}  \
                     max gap at contact = {max_gap_at_contact:.3e}  \
                     max overlap (snapshot) = {:.3e}  {:.4e} coll/s",
                    engine.now(),
                    checker.max_overlap,
                    since_report as f64 / dt
                );
                last_report = Instant::now();
                since_report = 0;
            }
        }
    }
    let secs = wall.elapsed().as_secs_f64();
    let s = engine.stats();
    println!(
        "SUMMARY collisions={done} sim_time={:.6} final_dK/K0={:+.6e} max|dK/K0|={max_drift:.6e} \
         max_overlap_at_contact={max_overlap_at_contact:.6e} max_gap_at_contact={max_gap_at_contact:.6e} \
         max_overlap_snapshots={:.6e} |P|/sum(m|v|)={:.3e} checked_rate={:.6e}/s bare_rate={bare_rate:.6e}/s \
         stale={} cell_crossings={}",
        engine.now(),
        (engine.kinetic_energy() - k0) / k0,
        checker.max_overlap,
        momentum_change(&engine),
        (done - bare) as f64 / secs,
        s.stale_events,
        s.cell_crossings
    );
}

/// |Σ m v| / Σ m|v| now (the start has zero total momentum; unit masses).
fn momentum_change(engine: &Engine) -> f64 {
    let (mut p, mut scale) = (carom_core::DVec2::ZERO, 0.0);
    for i in 0..engine.len() {
        let v = engine.velocity(i);
        p += v;
        scale += v.length();
    }
    p.length() / scale
}
