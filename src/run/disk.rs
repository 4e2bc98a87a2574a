//! The disk policy: a run stops, with a finished log, while its disk still has the
//! room that finishing the log needs ([`disk_low`]), rather than dying later with a
//! write error and a log cut at its last flush. The room is asked of the caller
//! ([`Control::free_space`]) or of the file system ([`free_space_for`]).

use std::path::Path;

#[cfg(doc)]
use super::Control;
#[cfg(doc)]
use carom_io::LogWriter;

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
    use super::{disk_low, free_space_for};
    use std::path::Path;

    #[test]
    fn a_file_system_that_reports_no_size_is_not_taken_for_a_full_disk() {
        let here = free_space_for(Path::new("target/some.mcap")).expect("a real disk");
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
}
