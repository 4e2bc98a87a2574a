//! One sweep at a time in a directory: `carom sweep` holds an exclusive advisory
//! lock (`flock`) on `DIR/sweep.lock` from before it lays the plan out until its
//! last point has ended, and writes its process ID into the file. A second
//! `carom sweep` into the same directory is refused at once, naming that process,
//! instead of racing the first over `plan.json`. The lock goes with the process
//! (also when it is killed); the points' own processes do not hold it (the file
//! is closed on exec), and each point's log keeps its own writer's lock, so a
//! sweep started after a killed one skips the points still running. `carom sweep
//! status`, `collect` and the Slurm tasks (`carom sweep point`) do not take it.

use std::fs::{File, OpenOptions, TryLockError};
use std::io::Write;
use std::path::Path;

use super::error::io;
use super::SweepError;

/// The held lock of a sweep's directory; released when dropped.
#[derive(Debug)]
pub struct SweepLock {
    _file: File,
}

impl SweepLock {
    /// Create `dir` if missing and lock it for this sweep, or say which process
    /// holds it.
    pub fn take(dir: &Path) -> Result<SweepLock, SweepError> {
        std::fs::create_dir_all(dir).map_err(io(dir))?;
        let path = dir.join("sweep.lock");
        let mut file = OpenOptions::new()
            .read(true)
            .write(true)
            .create(true)
            .truncate(false)
            .open(&path)
            .map_err(io(&path))?;
        match file.try_lock() {
            Ok(()) => {}
            Err(TryLockError::WouldBlock) => {
                let pid = std::fs::read_to_string(&path).unwrap_or_default();
                let who = match pid.trim() {
                    "" => "another process".to_owned(),
                    p => format!("process {p}"),
                };
                return Err(SweepError::Directory {
                    dir: dir.to_path_buf(),
                    problem: format!(
                        "another sweep is running in this directory ({who} holds {}); \
                         wait for it to end, or stop it (its points resume on the next sweep)",
                        path.display()
                    ),
                });
            }
            Err(TryLockError::Error(e)) => return Err(io(&path)(e)),
        }
        file.set_len(0)
            .and_then(|()| writeln!(file, "{}", std::process::id()))
            .map_err(io(&path))?;
        Ok(SweepLock { _file: file })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_second_lock_on_a_directory_is_refused_naming_the_first() {
        let dir = std::env::temp_dir().join(format!("carom-sweep-lock-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        let first = SweepLock::take(&dir).unwrap();
        let e = SweepLock::take(&dir).unwrap_err().to_string();
        assert!(e.contains("another sweep is running"), "{e}");
        assert!(e.contains(&std::process::id().to_string()), "{e}");
        drop(first);
        SweepLock::take(&dir).unwrap();
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
