//! Progress of reading a log (`carom analyze`, `carom info`): a logged run of 10⁶
//! discs writes about 100 bytes per collision, so its log can take minutes to read.
//!
//! On a terminal an indicatif bar shows the bytes read; otherwise a plain line goes
//! to standard error every [`PLAIN_EVERY`] once reading has taken that long (so a
//! short read prints nothing), and a last line when a read that printed one ends;
//! `--quiet` shows nothing. Reading writes nothing, so Ctrl-C simply ends it.

use std::io::IsTerminal;
use std::time::{Duration, Instant};

use carom_log::ReadProgress;
use indicatif::{ProgressBar, ProgressStyle};

use super::output::say;
use super::PLAIN_EVERY;

/// Shows how far a read of one file has got, through one or more passes.
pub(crate) struct ReadDisplay {
    bar: Option<ProgressBar>,
    plain: Option<PlainLines>,
}

impl ReadDisplay {
    /// A display for reading `file`; `quiet` shows nothing.
    pub(crate) fn new(quiet: bool, file: &str) -> Self {
        if quiet {
            return ReadDisplay {
                bar: None,
                plain: None,
            };
        }
        if std::io::stderr().is_terminal() {
            let bar = ProgressBar::new(0);
            bar.set_style(
                ProgressStyle::with_template(
                    "{spinner} [{elapsed_precise}] {bar:30} {bytes}/{total_bytes} {msg} (ETA {eta})",
                )
                .expect("valid template"),
            );
            ReadDisplay {
                bar: Some(bar),
                plain: None,
            }
        } else {
            ReadDisplay {
                bar: None,
                plain: Some(PlainLines::new(file, Instant::now(), PLAIN_EVERY)),
            }
        }
    }

    /// Start a pass over the file, named by what it does ("scanning", "reading").
    pub(crate) fn pass(&mut self, what: &'static str) {
        if let Some(bar) = &self.bar {
            bar.reset();
            bar.set_message(what);
        }
        if let Some(p) = &mut self.plain {
            p.pass = what;
        }
    }

    /// Show `p`, the reader's progress in the current pass.
    pub(crate) fn update(&mut self, p: ReadProgress) {
        if let Some(bar) = &self.bar {
            bar.set_length(p.file_bytes);
            bar.set_position(p.bytes_read.min(p.file_bytes));
        }
        if let Some(plain) = &mut self.plain {
            if let Some(line) = plain.line(p, Instant::now()) {
                say!("{line}");
            }
        }
    }

    /// Print `line` on standard error without breaking the bar.
    pub(crate) fn warn(&self, line: &str) {
        match &self.bar {
            Some(bar) => bar.suspend(|| say!("{line}")),
            None => say!("{line}"),
        }
    }

    /// Reading is over: clear the bar, or print a last line if any was printed.
    pub(crate) fn finish(&mut self) {
        if let Some(bar) = &self.bar {
            bar.finish_and_clear();
        }
        if let Some(line) = self.plain.as_mut().and_then(|p| p.last(Instant::now())) {
            say!("{line}");
        }
    }
}

/// The plain-text lines of a [`ReadDisplay`], as a function of the time they are
/// asked for (so that their timing can be tested).
#[derive(Debug)]
pub(crate) struct PlainLines {
    file: String,
    pass: &'static str,
    start: Instant,
    every: Duration,
    /// When the last line was printed; `None` before the first.
    last: Option<Instant>,
}

impl PlainLines {
    pub(crate) fn new(file: &str, start: Instant, every: Duration) -> Self {
        PlainLines {
            file: file.to_string(),
            pass: "reading",
            start,
            every,
            last: None,
        }
    }

    /// The line to print for progress `p` at time `now`, if one is due: the first
    /// once `every` has passed since the start, then one per `every`.
    pub(crate) fn line(&mut self, p: ReadProgress, now: Instant) -> Option<String> {
        let since = self.last.unwrap_or(self.start);
        if now.saturating_duration_since(since) < self.every {
            return None;
        }
        self.last = Some(now);
        Some(format!(
            "[{:7.1} s] {} {}: {:5.1}% ({:.1} of {:.1} MB)",
            now.saturating_duration_since(self.start).as_secs_f64(),
            self.pass,
            self.file,
            100.0 * p.fraction(),
            p.bytes_read.min(p.file_bytes) as f64 / 1e6,
            p.file_bytes as f64 / 1e6
        ))
    }

    /// The closing line at time `now`, if any progress line was printed.
    pub(crate) fn last(&mut self, now: Instant) -> Option<String> {
        self.last.take()?;
        Some(format!(
            "[{:7.1} s] read {}",
            now.saturating_duration_since(self.start).as_secs_f64(),
            self.file
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn at(bytes_read: u64) -> ReadProgress {
        ReadProgress {
            bytes_read,
            file_bytes: 4_000_000,
        }
    }

    #[test]
    fn a_short_read_prints_nothing_and_a_long_one_a_line_per_interval() {
        let t0 = Instant::now();
        let s = Duration::from_secs(1);
        let mut p = PlainLines::new("big.mcap", t0, 5 * s);
        // Within the first interval: silent, and nothing to close.
        assert_eq!(p.line(at(1_000_000), t0 + 4 * s), None);
        let mut quiet = PlainLines::new("small.mcap", t0, 5 * s);
        assert_eq!(quiet.line(at(4_000_000), t0 + s), None);
        assert_eq!(quiet.last(t0 + 2 * s), None);
        // Then one line per interval, whatever the number of updates.
        let first = p.line(at(2_000_000), t0 + 5 * s).expect("due after 5 s");
        assert_eq!(
            first,
            "[    5.0 s] reading big.mcap:  50.0% (2.0 of 4.0 MB)"
        );
        assert_eq!(p.line(at(2_500_000), t0 + 9 * s), None);
        p.pass = "scanning";
        let second = p.line(at(3_000_000), t0 + 10 * s).expect("due again");
        assert!(second.contains("scanning big.mcap:  75.0%"), "{second}");
        assert_eq!(
            p.last(t0 + 11 * s).as_deref(),
            Some("[   11.0 s] read big.mcap")
        );
    }

    #[test]
    fn progress_fraction_stays_in_range() {
        assert_eq!(at(0).fraction(), 0.0);
        assert_eq!(at(8_000_000).fraction(), 1.0);
        let empty = ReadProgress {
            bytes_read: 0,
            file_bytes: 0,
        };
        assert_eq!(empty.fraction(), 1.0);
    }
}
