//! The look-ahead tuner: whether fetching ahead pays is decided by timing it.
//!
//! The crossover depends on how much of the shared last-level cache the process
//! gets, which changes from day to day, so from [`TUNED_FROM`] discs on both
//! settings are timed in windows of equal event counts (on, off, off, on, each
//! setting judged by the shorter of its two windows), and the faster is kept for
//! a while — twice as long each time the same setting wins again. The setting
//! changes only speed, never the trajectory, so the choice may depend on the
//! clock. See docs/performance.md, "look-ahead".

/// Systems of at least this many discs have fetching ahead chosen by timing
/// ([`Tuner`]); smaller ones (under 3.2 MB of state, which any cache this engine
/// runs on holds) never fetch ahead.
const TUNED_FROM: usize = 20_000;

/// Events per timed window (about 0.05 s at N = 10⁶).
const WINDOW: u64 = 1 << 16;

/// Windows kept with the chosen setting after a first trial, before both are timed
/// again; doubled each time the same setting wins again, up to [`MAX_KEEP`].
const KEEP: u32 = 60;

/// The longest run of kept windows (about 25 s at N = 10⁶).
const MAX_KEEP: u32 = 512;

/// Chooses whether to fetch ahead by timing it: four windows of [`WINDOW`] events
/// (on, off, off, on), then the faster setting for a while, and again. Each setting
/// is judged by the shorter of its two windows, so a one-off pause in one window (the
/// caller writing a checkpoint, the process descheduled) does not decide the trial;
/// the engine's own renumbering is not charged to any window
/// ([`Tuner::exclude`]). The setting only changes speed, never the trajectory, so
/// the choice may depend on the clock. Wall-clock windows of equal event counts are
/// compared; all four see the same machine within a fifth of a second.
#[derive(Debug, Clone)]
pub(in crate::engine) struct Tuner {
    /// Events left in the current window; `u64::MAX` when not tuning.
    pub(in crate::engine) left: u64,
    phase: Phase,
    /// Start of the current window.
    started: Option<std::time::Instant>,
    /// The shorter window (s) so far of this trial, [with, without] fetching ahead.
    best: [f64; 2],
    /// Windows to keep the winner of the next trial for.
    keep: u32,
    /// The winner of the last trial.
    last_winner: Option<bool>,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Phase {
    /// The first window: not timed (caches and calendar settle).
    Warm,
    /// Trial window k (0–3) of the settings on, off, off, on.
    Trial(u8),
    /// Keeping the chosen setting for this many more windows.
    Keep(u32),
}

/// The setting of each trial window: on, off, off, on (a drift in speed during the
/// trial weighs on both settings alike).
const TRIAL: [bool; 4] = [true, false, false, true];

impl Tuner {
    /// A tuner for `n` discs: active from [`TUNED_FROM`] discs on.
    pub(in crate::engine) fn new(n: usize) -> Tuner {
        Tuner {
            left: if n >= TUNED_FROM { WINDOW } else { u64::MAX },
            phase: Phase::Warm,
            started: None,
            best: [f64::INFINITY; 2],
            keep: KEEP,
            last_winner: None,
        }
    }

    /// A tuner that never changes the setting (the caller chose it).
    pub(in crate::engine) fn off() -> Tuner {
        Tuner {
            left: u64::MAX,
            ..Tuner::new(0)
        }
    }

    /// Whether windows are being timed.
    pub(in crate::engine) fn active(&self) -> bool {
        self.left != u64::MAX
    }

    /// Leave `pause` (wall-clock time spent on something other than events, such as
    /// a renumbering of the discs) out of the current window.
    pub(in crate::engine) fn exclude(&mut self, pause: std::time::Duration) {
        if let Some(t) = self.started.as_mut() {
            *t += pause;
        }
    }

    /// The window just ended at `now` with setting `current`: the setting for the
    /// next one.
    pub(in crate::engine) fn next_window(
        &mut self,
        now: std::time::Instant,
        current: bool,
    ) -> bool {
        let seconds = self
            .started
            .map_or(0.0, |t| now.saturating_duration_since(t).as_secs_f64());
        self.started = Some(now);
        self.left = WINDOW;
        self.step(seconds, current)
    }

    /// The window just ended took `seconds` with setting `current`: the next
    /// setting.
    fn step(&mut self, seconds: f64, current: bool) -> bool {
        let (phase, on) = match self.phase {
            Phase::Warm | Phase::Keep(0) => {
                self.best = [f64::INFINITY; 2];
                (Phase::Trial(0), TRIAL[0])
            }
            Phase::Trial(k) => {
                let slot = &mut self.best[usize::from(!TRIAL[k as usize])];
                *slot = slot.min(seconds);
                if (k as usize) + 1 < TRIAL.len() {
                    (Phase::Trial(k + 1), TRIAL[k as usize + 1])
                } else {
                    let winner = self.best[0] < self.best[1];
                    self.keep = if self.last_winner == Some(winner) {
                        (2 * self.keep).min(MAX_KEEP)
                    } else {
                        KEEP
                    };
                    self.last_winner = Some(winner);
                    (Phase::Keep(self.keep), winner)
                }
            }
            Phase::Keep(k) => (Phase::Keep(k - 1), current),
        };
        self.phase = phase;
        on
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Feed `tuner` windows lasting `on(k)` s with fetching ahead and `off` s
    /// without (k counts the windows); the settings it chose for each of `windows`
    /// windows.
    fn run_with(
        tuner: &mut Tuner,
        on: impl Fn(usize) -> f64,
        off: f64,
        windows: usize,
    ) -> Vec<bool> {
        let mut setting = false;
        let mut chosen = Vec::new();
        for k in 0..windows {
            let seconds = if setting { on(k) } else { off };
            setting = tuner.step(seconds, setting);
            chosen.push(setting);
        }
        chosen
    }

    fn run(tuner: &mut Tuner, on: f64, off: f64, windows: usize) -> Vec<bool> {
        run_with(tuner, |_| on, off, windows)
    }

    #[test]
    fn keeps_the_faster_setting_and_tries_both_again() {
        // Warm, then the four trial windows and KEEP + 1 windows of the winner, and
        // again.
        let period = KEEP as usize + 5;
        let faster_on = run(&mut Tuner::new(TUNED_FROM), 0.1, 0.2, 3 * period);
        assert_eq!(&faster_on[..4], &TRIAL);
        assert!(faster_on[4..period].iter().all(|&s| s));
        assert_eq!(&faster_on[period..period + 4], &TRIAL);
        // The same winner again: kept twice as long before the next trial.
        assert!(faster_on[period + 4..period + 5 + 2 * KEEP as usize]
            .iter()
            .all(|&s| s));
        let faster_off = run(&mut Tuner::new(TUNED_FROM), 0.3, 0.2, 2 * period);
        assert_eq!(&faster_off[..4], &TRIAL);
        assert!(faster_off[4..period].iter().all(|&s| !s));
        assert_eq!(&faster_off[period..period + 4], &TRIAL);
        assert!(faster_off[period + 4..].iter().all(|&s| !s));
    }

    #[test]
    fn one_slow_window_does_not_decide_a_trial() {
        // Fetching ahead is twice as fast, but the first window with it on takes
        // ten times as long (a pause that had nothing to do with the setting).
        let mut tuner = Tuner::new(TUNED_FROM);
        let chosen = run_with(&mut tuner, |k| if k == 1 { 2.0 } else { 0.1 }, 0.2, 10);
        assert_eq!(tuner.last_winner, Some(true));
        assert!(chosen[4..].iter().all(|&s| s));
    }

    #[test]
    fn an_excluded_pause_is_not_charged_to_the_window() {
        let mut tuner = Tuner::new(TUNED_FROM);
        let t0 = std::time::Instant::now();
        tuner.next_window(t0, false);
        tuner.exclude(std::time::Duration::from_secs(5));
        // The window ends 5.01 s after it began, 5 s of which were excluded.
        tuner.next_window(t0 + std::time::Duration::from_millis(5010), true);
        assert!((tuner.best[0] - 0.01).abs() < 1e-9, "{:?}", tuner.best);
    }

    #[test]
    fn a_change_of_winner_shortens_the_keep_again() {
        let mut tuner = Tuner::new(TUNED_FROM);
        run(&mut tuner, 0.1, 0.2, 3 * KEEP as usize);
        assert!(tuner.keep > KEEP);
        // Off is now faster: at the first trial it wins, the keep starts over.
        let mut windows = 0;
        while tuner.last_winner != Some(false) {
            run(&mut tuner, 0.3, 0.2, 1);
            windows += 1;
            assert!(windows <= MAX_KEEP as usize + 5, "no trial within a keep");
        }
        assert_eq!(tuner.keep, KEEP);
    }

    #[test]
    fn small_systems_and_chosen_settings_are_not_tuned() {
        assert!(!Tuner::new(TUNED_FROM - 1).active());
        assert!(!Tuner::off().active());
        assert_eq!(Tuner::new(TUNED_FROM).left, WINDOW);
        assert!(Tuner::new(TUNED_FROM).active());
    }
}
