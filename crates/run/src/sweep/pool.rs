//! The local pool: at most `jobs` points run at once as `carom` processes, the
//! next starting as one ends, until every point has had its attempt. A failing
//! point does not stop the others. A stop request (Ctrl-C) starts nothing more
//! and asks each running point to stop cleanly (SIGTERM: it finishes its log,
//! which the next sweep resumes). The pool asks for no more than `jobs` and the
//! caller caps `jobs` at the cores ([`super::jobs`]). The points are separate
//! processes writing to their own files (see [`super::point`]): the pool only
//! starts them, reads their progress from their `carom.log`, and waits for them.

use std::path::Path;
use std::process::ExitStatus;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc;
use std::time::{Duration, Instant};

use super::error::io;
use super::point::{start_point, Running};
use super::{PointOutcome, SweepDir, SweepError};

/// What the pool tells its display.
#[derive(Debug, Clone)]
pub enum PoolEvent {
    /// Point `i` started.
    Started(usize),
    /// Point `i`'s log was not its own and was moved aside (where, and why).
    SetAside(usize, String),
    /// Point `i` ended (or had nothing to do).
    Ended(usize, PointOutcome),
    /// About once a second: (point, fraction done) of those running.
    Tick(Vec<(usize, f64)>),
}

/// How each point's attempt ended, by point.
#[derive(Debug, Clone, Default)]
pub struct PoolReport {
    /// One per point, in order.
    pub outcomes: Vec<Option<PointOutcome>>,
    /// Wall time of the whole pool (seconds).
    pub wall_seconds: f64,
}

/// Run every point of `sweep` that needs it with `exe`, `jobs` at a time.
pub fn run_pool(
    exe: &Path,
    sweep: &SweepDir,
    jobs: usize,
    stop: &AtomicBool,
    mut on_event: impl FnMut(PoolEvent),
) -> Result<PoolReport, SweepError> {
    let start = Instant::now();
    let n = sweep.plan.points.len();
    let jobs = jobs.max(1);
    let mut fractions = vec![0.0f64; n];
    let mut outcomes: Vec<Option<PointOutcome>> = vec![None; n];
    // Running points: index, PID, and the rest of the child; a waiter thread per
    // child reports its exit on `ended`, so the next point starts at once.
    let mut running: Vec<(usize, u32, Running)> = Vec::new();
    let (ended_tx, ended) = mpsc::channel::<(usize, std::io::Result<ExitStatus>)>();
    let mut next = 0;
    let mut signalled = false;
    let mut last_tick = Instant::now();
    loop {
        let stopping = stop.load(Ordering::SeqCst);
        while !stopping && running.len() < jobs && next < n {
            let i = next;
            next += 1;
            match start_point(exe, sweep, i)? {
                Ok(mut r) => {
                    if let Some(note) = r.set_aside.take() {
                        on_event(PoolEvent::SetAside(i, note));
                    }
                    let mut child = r.child.take().expect("a started point has its child");
                    let pid = child.id();
                    let tx = ended_tx.clone();
                    std::thread::spawn(move || {
                        let _ = tx.send((i, child.wait()));
                    });
                    on_event(PoolEvent::Started(i));
                    running.push((i, pid, r));
                }
                Err(state) => {
                    let o = PointOutcome::Skipped(state);
                    on_event(PoolEvent::Ended(i, o.clone()));
                    outcomes[i] = Some(o);
                }
            }
        }
        if stopping && !signalled {
            for (_, pid, _) in &running {
                // The run finishes its log on SIGTERM as on Ctrl-C.
                let _ = std::process::Command::new("kill")
                    .args(["-TERM", &pid.to_string()])
                    .status();
            }
            signalled = true;
        }
        if running.is_empty() && (next >= n || stopping) {
            break;
        }
        match ended.recv_timeout(Duration::from_millis(200)) {
            Ok((i, status)) => {
                let k = running
                    .iter()
                    .position(|r| r.0 == i)
                    .expect("a running point ended");
                let (_, _, r) = running.swap_remove(k);
                let status = status.map_err(io(exe))?;
                let o = r.finish(sweep, i, status);
                fractions[i] = 1.0;
                on_event(PoolEvent::Ended(i, o.clone()));
                outcomes[i] = Some(o);
            }
            Err(mpsc::RecvTimeoutError::Timeout) => {}
            Err(mpsc::RecvTimeoutError::Disconnected) => unreachable!("the pool holds a sender"),
        }
        if last_tick.elapsed() >= Duration::from_secs(1) {
            for (i, _, r) in running.iter_mut() {
                if let Some(f) = r.progress() {
                    fractions[*i] = f;
                }
            }
            on_event(PoolEvent::Tick(
                running
                    .iter()
                    .map(|(i, _, _)| (*i, fractions[*i]))
                    .collect(),
            ));
            last_tick = Instant::now();
        }
    }
    Ok(PoolReport {
        outcomes,
        wall_seconds: start.elapsed().as_secs_f64(),
    })
}
