//! The disk policy: a run stops, with a finished log, while its disk still has the
//! room that finishing the log needs ([`disk_low`], [`finish_reserve`]), rather
//! than dying later with a write error and a log cut at its last flush. The room
//! is asked of the caller ([`Control::free_space`]) or of the file system
//! ([`free_space_for`]), every [`Control::progress_interval`] and, on a disk
//! nearly full, whenever the log has grown by a quarter of the room left over
//! the reserve ([`DiskWatch`]): a log of every collision grows by tens of MB per
//! second, more than a small disk holds between two timed looks.

use std::path::Path;

use super::memory::CHECKPOINT_MESSAGE;
#[cfg(doc)]
use super::Control;
#[cfg(doc)]
use carom_log::LogWriter;

/// Whether a log must stop now to be finished: its disk has `free` bytes, finishing
/// it would write up to `finish` bytes ([`LogWriter::finish_bound`]), and it grew by
/// `growth` bytes since the last look, a [`Control::progress_interval`] ago. Twice
/// that growth is kept in hand, as the next look comes one interval later and the
/// writer may have fallen behind by as much.
pub fn disk_low(free: u64, finish: u64, growth: u64) -> bool {
    free <= finish.saturating_add(growth.saturating_mul(2))
}

/// How many times the free room the rest of a log, projected from its growth so
/// far, must need before the run is refused ([`far_too_small`]).
pub const FAR_BEYOND_FREE: f64 = 10.0;

/// Whether a log of `bytes` heading for `projected` bytes at the stop
/// ([`Progress::projected_log_bytes`](super::Progress::projected_log_bytes))
/// needs more than [`FAR_BEYOND_FREE`] times the `free` bytes of its disk: the run
/// is then stopped as soon as the projection says so (seconds after the start),
/// rather than only when the disk is nearly full.
pub fn far_too_small(bytes: u64, projected: f64, free: u64) -> bool {
    projected - bytes as f64 > FAR_BEYOND_FREE * free as f64
}

/// What finishing a log may still write (bytes): the writer's bound `writer`
/// ([`LogWriter::finish_bound`], which takes the final checkpoint as twice the
/// largest message so far, `largest`), with that checkpoint taken as at least
/// twice [`CHECKPOINT_MESSAGE`] bytes per disc for `discs` discs: a resumed
/// writer has copied its checkpoints, not written one, and does not know their
/// size.
pub fn finish_reserve(writer: u64, largest: u64, discs: u64) -> u64 {
    let checkpoint = discs.saturating_mul(CHECKPOINT_MESSAGE);
    writer.saturating_add(checkpoint.saturating_sub(largest).saturating_mul(2))
}

/// When to look at the room on the log's disk next: what the log's size was at
/// the last look, and the size at which to look again whatever the time.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct DiskWatch {
    bytes_at_look: u64,
    look_at: u64,
}

impl DiskWatch {
    /// A watch over a log of `bytes` bytes now, which looks at its first chance.
    pub(super) fn new(bytes: u64) -> Self {
        DiskWatch {
            bytes_at_look: bytes,
            look_at: bytes,
        }
    }

    /// Whether the log, now of `bytes` bytes, has grown enough to look again.
    pub(super) fn due(&self, bytes: u64) -> bool {
        bytes >= self.look_at
    }

    /// Look: with the log at `bytes` bytes, `free` bytes free on its disk (an
    /// error when that cannot be told: never low) and `finish` bytes to finish
    /// it, whether it must stop now ([`disk_low`], with the growth since the last
    /// look). The next look comes after a quarter of the room left over `finish`.
    pub(super) fn look(&mut self, bytes: u64, free: std::io::Result<u64>, finish: u64) -> bool {
        let growth = bytes.saturating_sub(self.bytes_at_look);
        self.bytes_at_look = bytes;
        let Ok(free) = free else {
            self.look_at = u64::MAX;
            return false;
        };
        self.look_at = bytes.saturating_add(free.saturating_sub(finish) / 4);
        disk_low(free, finish, growth)
    }
}

/// The bytes free for this user on the disk that holds (or will hold) the file
/// `path` (`fs4::statvfs` of its directory). A file system that reports a total
/// size of zero (some FUSE mounts do not report sizes at all) gives an error of
/// kind `Unsupported` rather than "0 bytes free", which would stop every run.
pub fn free_space_for(path: &Path) -> std::io::Result<u64> {
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let stats = fs4::statvfs(dir)?;
    if stats.total_space() == 0 {
        return Err(std::io::Error::new(
            std::io::ErrorKind::Unsupported,
            "the file system reports no size",
        ));
    }
    Ok(stats.available_space())
}

/// A caller's answer to "how many bytes are free for the log at this path"
/// ([`Control::free_space`]).
pub type FreeSpace<'a> = dyn FnMut(&Path) -> std::io::Result<u64> + 'a;

/// The bytes free for the file `path` on its disk: the caller's answer `ask`
/// ([`Control::free_space`]) or, without one, the file system's
/// ([`free_space_for`]).
pub(super) fn free_bytes(
    ask: &mut Option<&mut FreeSpace<'_>>,
    path: &Path,
) -> std::io::Result<u64> {
    match ask {
        Some(ask) => ask(path),
        None => free_space_for(path),
    }
}

#[cfg(test)]
mod tests {
    use super::{disk_low, finish_reserve, free_space_for, DiskWatch};
    use std::path::Path;

    #[test]
    fn a_file_system_that_reports_no_size_is_not_taken_for_a_full_disk() {
        // A directory of this test's own, wherever the checkout and its target are.
        let dir = std::env::temp_dir();
        let here = free_space_for(&dir.join("some.mcap")).expect("a real disk");
        assert!(here > 0);
        // procfs reports a total size of 0 blocks, as some FUSE mounts do.
        #[cfg(target_os = "linux")]
        {
            let e = free_space_for(Path::new("/proc/some.mcap")).unwrap_err();
            assert_eq!(e.kind(), std::io::ErrorKind::Unsupported);
        }
    }

    #[test]
    fn a_disk_is_low_when_its_room_no_longer_covers_finishing_and_two_more_intervals() {
        // 100 MB to finish, growing 10 MB per interval: stop at 120 MB free.
        let mb = 1_000_000;
        assert!(!disk_low(121 * mb, 100 * mb, 10 * mb));
        assert!(disk_low(120 * mb, 100 * mb, 10 * mb));
        assert!(disk_low(0, 0, 0));
        // No growth: only the finish is kept.
        assert!(!disk_low(100 * mb + 1, 100 * mb, 0));
        // Huge numbers saturate instead of wrapping round to "plenty of room".
        assert!(disk_low(u64::MAX - 1, u64::MAX / 2, u64::MAX / 2));
    }

    #[test]
    fn a_nearly_full_disk_is_looked_at_before_the_log_can_outgrow_it() {
        let mb = 1_000_000;
        // 5 MB to finish, 9 MB free at the start: look again after 1 MB of growth,
        // whatever the time.
        let mut w = DiskWatch::new(2 * mb);
        assert!(w.due(2 * mb));
        assert!(!w.look(2 * mb, Ok(9 * mb), 5 * mb));
        assert!(!w.due(3 * mb - 1) && w.due(3 * mb));
        // A 16 MB disk and a log growing by 300 kB between two chances to look (a
        // log of every collision, 1024 events), with no look by the clock: the run
        // stops while the room left still holds the finish.
        let (disk, finish, step) = (16 * mb, 5 * mb, 300_000);
        let mut w = DiskWatch::new(0);
        let mut bytes = 0;
        loop {
            assert!(
                bytes + finish <= disk,
                "the log outgrew its disk at {bytes} bytes"
            );
            if w.due(bytes) && w.look(bytes, Ok(disk - bytes), finish) {
                break;
            }
            bytes += step;
        }
        // ... and not long before it must: within a few steps of the reserve.
        assert!(
            disk - bytes - finish <= 4 * step,
            "stopped at {bytes} bytes"
        );
        // A large disk is looked at by the clock only, and one whose room cannot
        // be told never stops the run.
        let mut big = DiskWatch::new(0);
        assert!(!big.look(0, Ok(1 << 50), 5 * mb));
        assert!(!big.due(1 << 40));
        let mut unknown = DiskWatch::new(0);
        assert!(!unknown.look(0, Err(std::io::ErrorKind::Unsupported.into()), 5 * mb));
        assert!(!unknown.due(u64::MAX - 1));
    }

    #[test]
    fn the_final_checkpoint_is_reserved_also_before_the_writer_has_written_one() {
        // A resumed writer has written no checkpoint: 2 × 106 B per disc are added.
        assert_eq!(finish_reserve(1000, 0, 2000), 1000 + 2 * 106 * 2000);
        // Once a message as large as a checkpoint is written, the writer's bound
        // holds it already.
        assert_eq!(finish_reserve(1000, 106 * 2000, 2000), 1000);
        assert_eq!(finish_reserve(1000, 10 * 106 * 2000, 2000), 1000);
        assert_eq!(finish_reserve(u64::MAX, 0, u64::MAX), u64::MAX);
    }
}
