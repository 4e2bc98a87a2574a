//! The progress of `carom run` and `carom resume`: an indicatif bar on a
//! terminal, a plain line every `PLAIN_EVERY` otherwise, nothing with `--quiet`;
//! the placement spinner; the line saying how the run is set up (the neighbour
//! search in force) as its events begin; and the warning when the log will
//! outgrow its disk.

use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::time::Instant;

use carom_engine::{Engine, PlacementProgress};
use carom_log::Stop;
use carom_run::Bytes;
use carom_run::Progress;
use indicatif::{ProgressBar, ProgressStyle};

use super::output::say;
use super::{Num, PLAIN_EVERY};

/// Progress display: an indicatif bar on a terminal, a plain line every
/// `PLAIN_EVERY` otherwise, nothing with `--quiet`. Relaxed placement, before the
/// run, gets a spinner of its own (its length is not known in advance).
pub(super) struct Display {
    bar: Option<ProgressBar>,
    plain: bool,
    last_plain: Option<Instant>,
    /// The placement spinner (terminal only) and when placement started.
    placing: Option<(Option<ProgressBar>, Instant)>,
    /// The log file, whose disk is checked for room, and whether the warning that
    /// it will run out was given.
    log: PathBuf,
    warned_full: bool,
}

/// "N discs, neighbour search: neighbour lists" (or "cells, 64 × 64").
fn setup_text(engine: &Engine) -> String {
    let search = if engine.neighbour_lists() {
        "neighbour lists".to_owned()
    } else {
        let [nx, ny] = engine.cells();
        match engine.grid_count() {
            1 => format!("cells, {nx} × {ny}"),
            k => format!("cells, {k} grids, the first {nx} × {ny}"),
        }
    };
    format!("{} discs, neighbour search: {search}", engine.len())
}

fn stop_text(s: &Stop) -> String {
    match s {
        Stop::Time(t) => format!("t = {}", Num(*t)),
        Stop::Collisions(n) => format!("{n} collisions"),
    }
}

impl Display {
    pub(super) fn new(quiet: bool, log: &Path) -> Self {
        let (bar, plain) = if quiet {
            (None, false)
        } else if std::io::stderr().is_terminal() {
            let bar = ProgressBar::new(1000);
            bar.set_style(
                ProgressStyle::with_template(
                    "{spinner} [{elapsed_precise}] {bar:30} {percent:>3}% {msg} (ETA {eta})",
                )
                .expect("valid template"),
            );
            (Some(bar), false)
        } else {
            (None, true)
        };
        Display {
            bar,
            plain,
            last_plain: None,
            placing: None,
            log: log.to_path_buf(),
            warned_full: false,
        }
    }

    /// Print `line` (through the bar on a terminal, so that it is not overwritten).
    pub(super) fn say(&self, line: &str) {
        match &self.bar {
            Some(bar) => bar.suspend(|| say!("{line}")),
            None => say!("{line}"),
        }
    }

    pub(super) fn update(&mut self, p: &Progress) {
        let projected = p.projected_log_bytes();
        let mut msg = format!(
            "t = {:.4} / {}, {} collisions, {:.3e} coll/s, log {}",
            Num(p.sim_time),
            stop_text(&p.stop),
            p.collisions,
            p.collisions_per_second,
            Bytes(p.log_bytes)
        );
        if let Some(b) = projected.filter(|_| p.fraction < 1.0) {
            msg += &format!(" → ~{}", Bytes(b as u64));
        }
        self.warn_if_disk_too_small(p, projected);
        if let Some(bar) = &self.bar {
            bar.set_position((p.fraction.clamp(0.0, 1.0) * 1000.0) as u64);
            bar.set_message(msg);
        } else if self.plain {
            let due = self.last_plain.is_none_or(|t| t.elapsed() >= PLAIN_EVERY);
            if due || p.fraction >= 1.0 {
                say!(
                    "[{:7.1} s] {:5.1}% {msg}",
                    p.wall_seconds,
                    100.0 * p.fraction.clamp(0.0, 1.0)
                );
                self.last_plain = Some(Instant::now());
            }
        }
    }

    /// Warn once when the log, growing as it has so far, will not fit in the room
    /// left on its disk before the stop: the run would stop early (a log of every
    /// collision of a dense crystal grew by 150 MB/s towards 220 GB). The run goes
    /// on; the warning says how to make the log smaller. Given with
    /// `--quiet` too, which only silences the progress display.
    pub(super) fn warn_if_disk_too_small(&mut self, p: &Progress, projected: Option<f64>) {
        if self.warned_full {
            return;
        }
        let Some(total) = projected else {
            return;
        };
        let Ok(free) = carom_run::free_space_for(&self.log) else {
            return;
        };
        if outgrows(p.log_bytes, total, free) {
            self.warned_full = true;
            self.say(&format!(
                "warning: at this rate the log will grow to about {} by the stop, but its \
                 disk has {} free, so the run will stop early, while there is still room to \
                 finish the log, which `carom resume {}` then continues (with --out on \
                 another disk); to avoid that, log fewer collisions (log.collision_every, \
                 log.collisions = false) or stop sooner",
                Bytes(total as u64),
                Bytes(free),
                self.log.display()
            ));
        }
    }

    /// Whether nothing is shown (`--quiet`).
    pub(super) fn quiet(&self) -> bool {
        self.bar.is_none() && !self.plain
    }

    /// Say how the run is set up as its events begin: the discs and the
    /// neighbour search in force (the configuration's `neighbours`, `"auto"`
    /// decided by the engine).
    pub(super) fn started(&self, engine: &Engine) {
        if !self.quiet() {
            self.say(&setup_text(engine));
        }
    }

    /// Show how far relaxed placement has got; `p.close == 0` means it is done.
    pub(super) fn placing(&mut self, p: &PlacementProgress) {
        if self.quiet() {
            return;
        }
        let terminal = self.bar.is_some();
        let (spinner, start) = self.placing.get_or_insert_with(|| {
            let spinner = terminal.then(|| {
                let s = ProgressBar::new_spinner();
                s.set_style(
                    ProgressStyle::with_template("{spinner} [{elapsed_precise}] {msg}")
                        .expect("valid template"),
                );
                s
            });
            (spinner, Instant::now())
        });
        if let Some(s) = spinner {
            if p.close == 0 {
                s.finish_and_clear();
            } else if let Some(c) = p.compressing {
                s.set_message(format!(
                    "placing {} discs (compressed): η = {:.4} of {:.4}, Z = {:.3}",
                    p.discs, c.packing_fraction, c.target, c.reduced_pressure
                ));
                s.tick();
            } else {
                // Short enough for one line of an 80-column terminal.
                s.set_message(format!(
                    "placing {} discs (relaxed): step {}, {} pairs too close",
                    p.discs, p.steps, p.close
                ));
                s.tick();
            }
            return;
        }
        let due = self.last_plain.is_none_or(|t| t.elapsed() >= PLAIN_EVERY);
        if due || p.close == 0 {
            let seconds = start.elapsed().as_secs_f64();
            if let Some(c) = p.compressing {
                if p.close == 0 {
                    say!(
                        "[{seconds:7.1} s] placed {} discs (compressed placement) in {} rescale \
                         intervals",
                        p.discs,
                        p.steps
                    );
                } else {
                    say!(
                        "[{seconds:7.1} s] placing {} discs (compressed placement): packing \
                         fraction {:.4} of {:.4}, Z = {:.3}, rescale interval {} of about {}",
                        p.discs,
                        c.packing_fraction,
                        c.target,
                        c.reduced_pressure,
                        p.steps,
                        p.max_steps
                    );
                }
            } else if p.close == 0 {
                say!(
                    "[{seconds:7.1} s] placed {} discs (relaxed placement) in {} minimization \
                     steps",
                    p.discs,
                    p.steps
                );
            } else {
                say!(
                    "[{seconds:7.1} s] placing {} discs (relaxed placement): step {} of at most \
                     {}, {} pairs or wall contacts still too close",
                    p.discs,
                    p.steps,
                    p.max_steps,
                    p.close
                );
            }
            self.last_plain = Some(Instant::now());
        }
    }

    pub(super) fn finish(&self) {
        if let Some((Some(s), _)) = &self.placing {
            s.finish_and_clear();
        }
        if let Some(bar) = &self.bar {
            bar.finish_and_clear();
        }
    }
}

/// Whether a log of `bytes` heading for `total` bytes at the stop needs more than
/// the `free` bytes left on its disk.
pub(super) fn outgrows(bytes: u64, total: f64, free: u64) -> bool {
    total - bytes as f64 > free as f64
}

#[cfg(test)]
mod tests {
    use super::outgrows;

    #[test]
    fn only_what_is_still_to_be_written_must_fit_on_the_disk() {
        // 30 GB written of 100 GB: 70 GB still to come.
        assert!(outgrows(30_000_000_000, 1e11, 69_000_000_000));
        assert!(!outgrows(30_000_000_000, 1e11, 71_000_000_000));
        assert!(!outgrows(0, 0.0, 0));
    }
}
