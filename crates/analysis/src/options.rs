//! The choices of `carom analyze` and their defaults: the window, the spacing of
//! the snapshots used for the velocity distribution (a few collisions apart, so
//! that a disc's velocities are independent, and no more of them than memory
//! holds), and the bins. The measurements behind the defaults: see
//! docs/performance.md, 'analyze defaults'.

#[cfg(doc)]
use super::RunDescription;

/// Pair collisions per disc between the snapshots that the Maxwell–Boltzmann
/// tests use by default: a disc's speed stays correlated with itself over about
/// one collision, and correlated samples make both tests reject too often. See
/// docs/performance.md, 'analyze defaults'.
pub const DECORRELATION_COLLISIONS: f64 = 5.0;

/// Velocities (one per disc and snapshot used) that the Maxwell–Boltzmann tests
/// keep in memory by default, 32 bytes each (about 640 MB); more are spaced further
/// apart (see [`AnalysisOptions::max_velocities`]). 2·10⁷ velocities resolve a
/// difference of 3·10⁻⁴ between distribution functions (KS at p = 0.05).
pub const MAX_VELOCITIES: usize = 20_000_000;

/// Snapshots closer than this many pair collisions per disc hold correlated
/// velocities (see [`DECORRELATION_COLLISIONS`]): `carom analyze` warns.
pub const CORRELATED_SPACING: f64 = 4.0;

/// Choices of `carom analyze`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AnalysisOptions {
    /// Ignore everything before this simulated time (time). `None`: the first 10 %
    /// of the log's time span.
    pub equilibrate: Option<f64>,
    /// Use snapshots at least this far apart for the velocity distribution (time).
    /// `None`: [`DECORRELATION_COLLISIONS`] collision times apart when
    /// [`RunDescription::pair_rate`] is known, otherwise every snapshot after
    /// `equilibrate`; for an inelastic run, whose collision rate changes as it
    /// cools, [`DECORRELATION_COLLISIONS`] pair collisions per disc counted
    /// between the snapshots (from the `/thermo` running counts or the logged
    /// collisions), from any snapshot of a `log.snapshot_schedule`; either way
    /// spaced further apart when that would keep more than `max_velocities`
    /// velocities.
    pub every: Option<f64>,
    /// The most velocities (discs × snapshots used) that the default spacing keeps
    /// in memory; an `every` asked for is used as it is. Default
    /// [`MAX_VELOCITIES`].
    pub max_velocities: usize,
    /// Bins of the speed histograms (before merging for χ²).
    pub speed_bins: usize,
    /// Time bins for the pressure and collision-rate series (a power of two suits
    /// the blocking analysis).
    pub time_bins: usize,
    /// Measure the structure (g(r), ψ6, g6, S(k)) from the snapshots' positions; `false` skips it, for a quick pass over the
    /// collisions and velocities (`carom analyze --no-structure`).
    pub structure: bool,
}

impl Default for AnalysisOptions {
    fn default() -> Self {
        AnalysisOptions {
            equilibrate: None,
            every: None,
            max_velocities: MAX_VELOCITIES,
            speed_bins: 40,
            time_bins: 1024,
            structure: true,
        }
    }
}

/// The spacing (time) of snapshots in a window of length `window` that keeps at
/// most `max_velocities` velocities of `n` discs, or `None` if snapshots
/// `spacing` apart (`None`: any distance apart) keep no more than that. With room
/// for fewer than two snapshots, the spacing is the whole window, which keeps one
/// (or two, at its very ends).
pub(super) fn budget_spacing(
    n: usize,
    max_velocities: usize,
    window: f64,
    spacing: Option<f64>,
) -> Option<f64> {
    // Snapshots at least `s` apart in a window of length `window` number at most
    // ⌊window/s⌋ + 1.
    let room = max_velocities / n.max(1);
    if let Some(s) = spacing.filter(|s| *s > 0.0) {
        let snapshots = (window / s).floor() + 1.0;
        if snapshots <= room as f64 {
            return None;
        }
    }
    Some(match room {
        0 | 1 => window,
        m => window / (m - 1) as f64,
    })
}

#[cfg(test)]
mod tests {
    use super::budget_spacing;

    #[test]
    fn the_memory_bound_spaces_snapshots_only_when_they_would_exceed_it() {
        // 100 discs, room for 10 snapshots, a window of 9.
        let b = |spacing| budget_spacing(100, 1000, 9.0, spacing);
        // Snapshots 1 apart: 10 of them fit; 0.5 apart: 19 would not.
        assert_eq!(b(Some(1.0)), None);
        assert_eq!(b(Some(0.5)), Some(1.0));
        // Spacing unknown: assume a window full of snapshots.
        assert_eq!(b(None), Some(1.0));
        assert_eq!(b(Some(0.0)), Some(1.0));
        // Room for one snapshot or none: the whole window apart.
        assert_eq!(budget_spacing(100, 150, 9.0, Some(0.5)), Some(9.0));
        assert_eq!(budget_spacing(100, 50, 9.0, None), Some(9.0));
        // Room for two: the window's two ends.
        assert_eq!(budget_spacing(100, 200, 9.0, Some(0.5)), Some(9.0));
        assert_eq!(budget_spacing(100, 300, 9.0, Some(0.5)), Some(4.5));
    }

    /// Snapshots 1 apart over a window of 10 are ⌊10/1⌋ + 1 = 11, one more than
    /// the room for 10 (1000 velocities of 100 discs): the 10 that fit are spaced
    /// 10/9, the first and last at the window's ends.
    #[test]
    fn a_window_holding_one_snapshot_too_many_is_spaced_to_the_room() {
        assert_eq!(budget_spacing(100, 1000, 10.0, Some(1.0)), Some(10.0 / 9.0));
        // Spaced 10/9 apart they fit: ⌊10/(10/9)⌋ + 1 ≤ 10 (9 or 10 with rounding).
        assert_eq!(budget_spacing(100, 1000, 10.0, Some(10.0 / 9.0)), None);
    }
}
