//! One writer per file: an exclusive advisory lock (`flock`) on the log a run
//! writes, on the log a resume reads, on a resume's `--out`, and on every file a
//! command writes (`repair --out`, `export --out`, `render --out`, figures), held until
//! the command ends. A second writer is refused at once, before it truncates or
//! replaces anything, and is told which process holds the lock (on Linux, from
//! `/proc/locks`; elsewhere only that one does). The lock is advisory: it keeps
//! out other carom processes, not other programs.

use std::fs::{File, OpenOptions, TryLockError};
use std::path::Path;

use super::RunError;

/// Tries, 5 ms apart, before a held lock is reported (0.1 s in all).
const FORK_WAITS: u32 = 20;

/// A held lock on a log file; released when dropped (or when the process ends).
#[derive(Debug)]
pub struct LogLock {
    _file: File,
}

/// Lock the log at `path` for writing: create it if `create` (a fresh log; it is
/// not truncated here, so a refused writer leaves another's log intact), else
/// open the existing file. Refused with [`RunError::Locked`] when another process
/// holds the lock. A file replaced by a rename while the lock was taken (a
/// resume in place finishing) is locked anew. Every command that writes a file
/// takes this lock on it first.
pub fn lock_log(path: &Path, create: bool) -> Result<LogLock, RunError> {
    let io_err = |source| RunError::Lock {
        file: path.to_path_buf(),
        source,
    };
    // A lock can be held for a moment by a child being forked from another
    // thread of this process (the file's descriptor is shared until the child
    // execs and closes it): a refusal is only final after a short wait.
    let mut waits = 0;
    loop {
        let file = OpenOptions::new()
            .read(true)
            .write(create)
            .create(create)
            .truncate(false)
            .open(path)
            .map_err(io_err)?;
        match file.try_lock() {
            Ok(()) => {}
            Err(TryLockError::WouldBlock) if waits < FORK_WAITS => {
                waits += 1;
                std::thread::sleep(std::time::Duration::from_millis(5));
                continue;
            }
            Err(TryLockError::WouldBlock) => {
                return Err(RunError::Locked {
                    file: path.to_path_buf(),
                    holder: holder(&file),
                })
            }
            Err(TryLockError::Error(e)) => return Err(io_err(e)),
        }
        if still_at(&file, path) {
            return Ok(LogLock { _file: file });
        }
    }
}

/// Whether `path` still names the file `file` is open on.
#[cfg(unix)]
fn still_at(file: &File, path: &Path) -> bool {
    use std::os::unix::fs::MetadataExt;
    match (file.metadata(), std::fs::metadata(path)) {
        (Ok(a), Ok(b)) => a.dev() == b.dev() && a.ino() == b.ino(),
        _ => false,
    }
}

#[cfg(not(unix))]
fn still_at(_: &File, _: &Path) -> bool {
    true
}

/// The process holding a lock on `file`, as "process PID (COMMAND LINE)", read
/// from `/proc/locks` (Linux only; `None` elsewhere or when it cannot be told).
#[cfg(target_os = "linux")]
fn holder(file: &File) -> Option<String> {
    use std::os::unix::fs::MetadataExt;
    let m = file.metadata().ok()?;
    let dev = m.dev();
    let major = ((dev >> 8) & 0xfff) | ((dev >> 32) & !0xfff);
    let minor = (dev & 0xff) | ((dev >> 12) & !0xff);
    let key = format!("{major:02x}:{minor:02x}:{}", m.ino());
    let locks = std::fs::read_to_string("/proc/locks").ok()?;
    // "1: FLOCK  ADVISORY  WRITE 1234 08:01:5678 0 EOF"
    let pid: u32 = locks.lines().find_map(|l| {
        let f: Vec<&str> = l.split_whitespace().collect();
        (f.len() > 5 && f[1] == "FLOCK" && f[5] == key)
            .then(|| f[4].parse().ok())
            .flatten()
    })?;
    let cmd = std::fs::read(format!("/proc/{pid}/cmdline")).unwrap_or_default();
    let cmd = String::from_utf8_lossy(&cmd).replace('\0', " ");
    Some(match cmd.trim() {
        "" => format!("process {pid}"),
        c => format!("process {pid} ({c})"),
    })
}

#[cfg(not(target_os = "linux"))]
fn holder(_: &File) -> Option<String> {
    None
}

/// The text naming the holder in [`RunError::Locked`].
pub(super) fn holder_text(holder: &Option<String>) -> String {
    holder
        .clone()
        .unwrap_or_else(|| "another process".to_owned())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_second_lock_is_refused_and_names_this_process() {
        let dir = std::env::temp_dir().join(format!("carom-lock-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("a.mcap");
        std::fs::write(&path, b"first").unwrap();
        let held = lock_log(&path, true).unwrap();
        let e = lock_log(&path, true).unwrap_err();
        assert!(
            matches!(&e, RunError::Locked { file, .. } if *file == path),
            "{e}"
        );
        #[cfg(target_os = "linux")]
        assert!(
            e.to_string()
                .contains(&format!("process {}", std::process::id())),
            "{e}"
        );
        // Neither truncated nor replaced.
        assert_eq!(std::fs::read(&path).unwrap(), b"first");
        drop(held);
        lock_log(&path, false).unwrap();
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
