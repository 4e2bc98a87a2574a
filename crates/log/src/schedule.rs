//! When `/snapshot` messages are taken: the one definition of the snapshot times,
//! shared by the run driver (which schedules them), the option check and the
//! analysis (which tells block starts from the snapshots inside a block).
//!
//! Snapshots come in blocks of length T = `log.snapshot_interval` starting at
//! t₀ + b·T. With `log.snapshot_schedule` = {n = `points`, δ = `first`} each block
//! holds n more, at the geometric offsets
//!
//!   δ_j = δ·(T/δ)^((j−1)/n),   j = 1..n   (δ_1 = δ, δ_n < T),
//!
//! so that mean-square displacements and correlation functions see lag times from
//! δ to many T without a snapshot every δ. Snapshot k = b·(n+1) + j (j = 0 the block
//! start) is at t₀ + b·T + δ_j, with b·T computed as `b as f64 * T`: without a
//! schedule (n = 0) snapshot k is at `t₀ + k as f64 * T`, as it always was.

use crate::options_error::{options_error, OptionsError};

/// The most snapshots a schedule may add per block.
pub const MAX_SCHEDULE_POINTS: u32 = 1000;

/// The smallest `first` offset as a fraction of the interval: δ ≥ 10⁻⁶·T.
pub const MIN_FIRST_FRACTION: f64 = 1e-6;

/// `log.snapshot_schedule`: the snapshots added inside every block of
/// `log.snapshot_interval` (see the module documentation).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SchedulePoints {
    /// n: snapshots added per block, 1 ≤ n ≤ [`MAX_SCHEDULE_POINTS`].
    pub points: u64,
    /// δ: offset of the first one from the block start (time), 10⁻⁶·T ≤ δ < T.
    pub first: f64,
}

impl SchedulePoints {
    /// Check n and δ against the snapshot interval T (`None`: no snapshots).
    /// Errors name `log.snapshot_schedule` (no interval), `.points` or `.first`.
    pub fn check(&self, interval: Option<f64>) -> Result<(), OptionsError> {
        let Some(t) = interval else {
            return Err(options_error(
                "log.snapshot_schedule",
                "given with log.snapshot_interval = null (no snapshots)".into(),
                "a schedule only together with a log.snapshot_interval, whose blocks it fills",
            ));
        };
        if !(1..=u64::from(MAX_SCHEDULE_POINTS)).contains(&self.points) {
            return Err(options_error(
                "log.snapshot_schedule.points",
                format!("value {}", self.points),
                format!("an integer 1 ≤ n ≤ {MAX_SCHEDULE_POINTS}"),
            ));
        }
        let d = self.first;
        if !(d.is_finite() && d >= MIN_FIRST_FRACTION * t && d < t) {
            return Err(options_error(
                "log.snapshot_schedule.first",
                format!("value {d} with log.snapshot_interval = {t}"),
                format!(
                    "finite simulated time with 10⁻⁶·T = {:e} ≤ first < T = {t}",
                    MIN_FIRST_FRACTION * t
                ),
            ));
        }
        let s = SnapshotSchedule::new(t, Some(*self));
        if let Some(j) = (1..s.points).find(|&j| s.offset(j + 1) <= s.offset(j)) {
            return Err(options_error(
                "log.snapshot_schedule.first",
                format!(
                    "value {d} so near T = {t} that with {} points offsets {j} and {} \
                     coincide",
                    self.points,
                    j + 1
                ),
                "a first offset further below T, or fewer points",
            ));
        }
        Ok(())
    }
}

/// The snapshot times of a run: blocks of `interval` T, each a block start and
/// `points` n more at the offsets δ_j (n = 0: no schedule, one snapshot per block).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SnapshotSchedule {
    /// T: the block length, `log.snapshot_interval` (time).
    pub interval: f64,
    /// n: snapshots inside each block after its start (0 without a schedule).
    pub points: u32,
    /// δ: the first offset (time); unused when n = 0.
    pub first: f64,
}

impl SnapshotSchedule {
    /// The schedule of snapshots every `interval`, with the `points` of a
    /// `log.snapshot_schedule` when given (checked: [`SchedulePoints::check`]; more
    /// than [`MAX_SCHEDULE_POINTS`] are cut to it).
    pub fn new(interval: f64, points: Option<SchedulePoints>) -> Self {
        let (points, first) = points.map_or((0, 0.0), |p| {
            (p.points.min(u64::from(MAX_SCHEDULE_POINTS)) as u32, p.first)
        });
        SnapshotSchedule {
            interval,
            points,
            first,
        }
    }

    /// Snapshots per block, n + 1.
    pub fn per_block(&self) -> u64 {
        u64::from(self.points) + 1
    }

    /// δ_j, the offset of snapshot j of a block from its start (time): 0 for j = 0,
    /// δ·(T/δ)^((j−1)/n) for 1 ≤ j ≤ n.
    pub fn offset(&self, j: u32) -> f64 {
        if j == 0 {
            return 0.0;
        }
        let n = f64::from(self.points);
        self.first * (self.interval / self.first).powf(f64::from(j - 1) / n)
    }

    /// The offsets δ_1..δ_n (time).
    pub fn offsets(&self) -> Vec<f64> {
        (1..=self.points).map(|j| self.offset(j)).collect()
    }

    /// The time of snapshot `k` = b·(n+1) + j of a run started at `t0`:
    /// t₀ + b·T for a block start, t₀ + b·T + δ_j inside the block.
    pub fn time(&self, t0: f64, k: u64) -> f64 {
        let (b, j) = (k / self.per_block(), (k % self.per_block()) as u32);
        let start = t0 + b as f64 * self.interval;
        if j == 0 {
            start
        } else {
            start + self.offset(j)
        }
    }

    /// Which snapshot of a run started at `t0` is at time `t`: (block b, position j
    /// in it, 0 for its start), or `None` for a time that is no snapshot's. A time
    /// matches when it equals the computed time, or lies within a quarter of the
    /// gap to the neighbouring snapshots (a log's times rounded elsewhere).
    pub fn block_position(&self, t0: f64, t: f64) -> Option<(u64, u32)> {
        let x = (t - t0) / self.interval;
        if !(x.is_finite() && x > -0.5) {
            return None;
        }
        let b0 = x.floor().max(0.0) as u64;
        [b0, b0.saturating_sub(1), b0 + 1]
            .into_iter()
            .find_map(|b| Some((b, self.position_in_block(t0, b, t)?)))
    }

    /// The position j of time `t` in block `b`, if it is one of its snapshots.
    fn position_in_block(&self, t0: f64, b: u64, t: f64) -> Option<u32> {
        let k0 = b.checked_mul(self.per_block())?;
        let rem = t - (t0 + b as f64 * self.interval);
        // The smallest gap next to δ_j is δ_j·(1 − 1/r), r = (T/δ)^(1/n) the
        // ratio of neighbouring offsets; next to the start it is δ_1 = δ.
        if t == self.time(t0, k0) || (self.points > 0 && rem.abs() <= 0.25 * self.first) {
            return Some(0);
        }
        if self.points == 0 || rem <= 0.0 {
            return None;
        }
        let n = f64::from(self.points);
        let ln_ratio = (self.interval / self.first).ln();
        let r = (ln_ratio / n).exp();
        let guess = (n * (rem / self.first).ln() / ln_ratio).round() + 1.0;
        let guess = guess.clamp(1.0, n) as u32;
        [guess, guess.saturating_sub(1), guess + 1]
            .into_iter()
            .filter(|j| (1..=self.points).contains(j))
            .find(|&j| {
                let d = self.offset(j);
                t == self.time(t0, k0 + u64::from(j))
                    || (rem - d).abs() <= 0.25 * d * (1.0 - 1.0 / r)
            })
    }

    /// Whether time `t` is the start of a block (every snapshot is one without a
    /// schedule; a time that is no snapshot's is not).
    pub fn is_block_start(&self, t0: f64, t: f64) -> bool {
        self.points == 0 || matches!(self.block_position(t0, t), Some((_, 0)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sched(t: f64, n: u64, d: f64) -> SnapshotSchedule {
        SnapshotSchedule::new(
            t,
            Some(SchedulePoints {
                points: n,
                first: d,
            }),
        )
    }

    #[test]
    fn offsets_are_geometric_from_first_to_below_the_interval() {
        // T = 1, δ = 0.01, n = 2: δ_1 = 0.01, δ_2 = 0.01·(1/0.01)^(1/2) = 0.01·10 = 0.1.
        let s = sched(1.0, 2, 0.01);
        let o = s.offsets();
        assert_eq!(o.len(), 2);
        assert!(
            (o[0] - 0.01).abs() < 1e-15 && (o[1] - 0.1).abs() < 1e-15,
            "{o:?}"
        );
        // T = 8, δ = 1, n = 3: ratio 8^(1/3) = 2, offsets 1, 2, 4 (8 is the next block).
        let o = sched(8.0, 3, 1.0).offsets();
        for (a, b) in o.iter().zip([1.0, 2.0, 4.0]) {
            assert!((a - b).abs() < 1e-14, "{o:?}");
        }
    }

    #[test]
    fn snapshot_k_is_block_b_position_j() {
        // n = 2: k = 3b + j. k = 0, 1, 2 → 0, 0.01, 0.1; k = 3 → 1; k = 7 → 2 + 0.01.
        let s = sched(1.0, 2, 0.01);
        let t0 = 5.0;
        let want = [5.0, 5.01, 5.1, 6.0, 6.01, 6.1, 7.0, 7.01];
        for (k, w) in want.iter().enumerate() {
            let t = s.time(t0, k as u64);
            assert!((t - w).abs() < 1e-13, "k = {k}: {t} ≠ {w}");
            let pos = s.block_position(t0, t);
            assert_eq!(pos, Some((k as u64 / 3, (k % 3) as u32)), "k = {k}");
            assert_eq!(s.is_block_start(t0, t), k % 3 == 0, "k = {k}");
        }
        // Halfway between snapshots, or before the run, is no snapshot.
        assert_eq!(s.block_position(t0, 5.5), None);
        assert_eq!(s.block_position(t0, 5.05), None);
        assert_eq!(s.block_position(t0, 3.0), None);
        assert!(!s.is_block_start(t0, 5.5));
        // A time rounded in the last digits still matches.
        assert_eq!(s.block_position(t0, 6.1 + 1e-12), Some((1, 2)));
    }

    #[test]
    fn without_a_schedule_every_snapshot_is_at_t0_plus_k_interval() {
        // The driver's rule before schedules existed: t0 + k as f64 * T, to the bit.
        let s = SnapshotSchedule::new(0.3, None);
        let t0 = 1.7;
        for k in [0u64, 1, 2, 3, 10, 12_345, 1 << 40] {
            assert_eq!(s.time(t0, k).to_bits(), (t0 + k as f64 * 0.3).to_bits());
            assert_eq!(s.block_position(t0, s.time(t0, k)), Some((k, 0)));
        }
        assert!(s.is_block_start(t0, 123.456));
    }

    #[test]
    fn each_bad_setting_is_named() {
        let p = |n, d| SchedulePoints {
            points: n,
            first: d,
        };
        let field = |pts: SchedulePoints, t: Option<f64>| pts.check(t).err().map(|e| e.field);
        assert_eq!(field(p(2, 0.01), Some(1.0)), None);
        assert_eq!(field(p(1000, 1e-6), Some(1.0)), None);
        assert_eq!(field(p(2, 0.01), None), Some("log.snapshot_schedule"));
        assert_eq!(
            field(p(0, 0.01), Some(1.0)),
            Some("log.snapshot_schedule.points")
        );
        assert_eq!(
            field(p(1001, 0.01), Some(1.0)),
            Some("log.snapshot_schedule.points")
        );
        for d in [1.0, 2.0, 0.0, -0.1, 0.9e-6, f64::NAN, f64::INFINITY] {
            assert_eq!(
                field(p(2, d), Some(1.0)),
                Some("log.snapshot_schedule.first"),
                "first = {d}"
            );
        }
        // 1 − 10⁻¹⁵ below T with 1000 points: neighbouring offsets round together.
        assert_eq!(
            field(p(1000, 1.0 - 1e-15), Some(1.0)),
            Some("log.snapshot_schedule.first")
        );
        let text = p(0, 0.01).check(Some(1.0)).unwrap_err().to_string();
        assert!(text.contains("1 ≤ n ≤ 1000"), "{text}");
    }
}
