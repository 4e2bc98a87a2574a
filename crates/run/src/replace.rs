//! Writing a run's log over an older one (`carom run --force`, `carom resume
//! --out NAME`) without losing the older one to a run that fails at its start.
//!
//! The new log is written beside the old one, as `NAME.run-tmp`, and renamed over
//! it once its first checkpoint is on the disk, so that it can be resumed on its
//! own; a run that fails before then leaves the old log as it was. Both names are
//! locked ([`lock_log`]) for the whole run, so NAME is never unlocked across the
//! rename. A fresh log (no file, an empty one, a device) is written in place.

use std::path::{Path, PathBuf};

use super::lock::{lock_log, LogLock};
use super::RunError;

/// How the replacement goes: `carom run` renames once the checkpoint written at
/// the start of the run is on the disk (the writer syncs it); `carom resume --out
/// NAME` once the copied prefix, which ends in a checkpoint, is. From then on NAME
/// is the new log, as for a fresh run (a crash leaves it resumable in place). A
/// run that fails before then (an engine that refuses the configuration, a write
/// error, an abort for want of memory) has its temporary file removed, or, after a
/// kill or an abort, replaced by the next run over NAME.
///
/// The file a run writes its log to, locked, and the older log it replaces.
#[derive(Debug)]
pub(super) struct Output {
    /// The log's name, as given.
    name: PathBuf,
    /// Where the log goes: `name`, or where its symbolic link points.
    target: PathBuf,
    /// `NAME.run-tmp` while it has not replaced the older log at `target`.
    temp: Option<PathBuf>,
    /// Whether `target` was created here (it did not exist).
    created: bool,
    _locks: (LogLock, Option<LogLock>),
}

/// The rename of the new log over the older one, done once the run has started.
#[derive(Debug)]
pub(super) struct Replace {
    from: PathBuf,
    to: PathBuf,
}

impl Replace {
    /// Rename the new log (whose writer has synced it to its disk) over the
    /// older one, and sync the directory, so that after a crash the name holds
    /// one of the two logs whole; returns the log's path now.
    pub(super) fn apply(self) -> Result<PathBuf, RunError> {
        if let Err(source) = std::fs::rename(&self.from, &self.to) {
            return Err(RunError::Rename {
                from: self.from,
                to: self.to,
                source,
            });
        }
        // Best effort: not every file system can sync a directory.
        if let Some(dir) = self.to.parent().and_then(|d| std::fs::File::open(d).ok()) {
            let _ = dir.sync_all();
        }
        Ok(self.to)
    }
}

/// `NAME` → `NAME.run-tmp` beside it.
fn temp_name(target: &Path) -> PathBuf {
    let mut name = target.file_name().unwrap_or_default().to_os_string();
    name.push(".run-tmp");
    target.with_file_name(name)
}

impl Output {
    /// Lock `out` (creating it if it does not exist; a refused writer changes
    /// nothing), and, if it holds an older log, lock `NAME.run-tmp` beside it.
    pub(super) fn lock(out: &Path) -> Result<Output, RunError> {
        let created = !out.exists();
        let lock = lock_log(out, true)?;
        let older = !created && std::fs::metadata(out).is_ok_and(|m| m.is_file() && m.len() > 0);
        if !older {
            return Ok(Output {
                name: out.to_path_buf(),
                target: out.to_path_buf(),
                temp: None,
                created,
                _locks: (lock, None),
            });
        }
        let target = out.canonicalize().map_err(|source| RunError::Lock {
            file: out.to_path_buf(),
            source,
        })?;
        let temp = temp_name(&target);
        let temp_lock = lock_log(&temp, true)?;
        Ok(Output {
            name: out.to_path_buf(),
            target,
            temp: Some(temp),
            created,
            _locks: (lock, Some(temp_lock)),
        })
    }

    /// The file the writer is to create.
    pub(super) fn writing(&self) -> &Path {
        self.temp.as_deref().unwrap_or(&self.target)
    }

    /// The rename the driver does once the run has started, if there is an older
    /// log to replace.
    pub(super) fn replace_at_start(&self) -> Option<Replace> {
        self.temp.as_ref().map(|t| Replace {
            from: t.clone(),
            to: self.target.clone(),
        })
    }

    /// Whether the new log has not yet replaced the older one.
    fn pending(&self) -> bool {
        self.temp.as_ref().is_some_and(|t| t.exists())
    }

    /// A failure before the writer started: remove what this run created, and say
    /// that no log was written.
    pub(super) fn abandon(self, e: RunError) -> RunError {
        if self.created {
            let _ = std::fs::remove_file(&self.target);
        }
        let kept = self.temp.is_some().then(|| self.name.clone());
        not_started(e, kept)
    }

    /// After the run: a run that ended (for whatever reason) before its first
    /// checkpoint replaces the older log now; a run that failed before it leaves
    /// the older log as it was, and says so.
    pub(super) fn finish<T>(self, result: Result<T, RunError>) -> Result<T, RunError> {
        if !self.pending() {
            return result;
        }
        match result {
            Ok(summary) => {
                if let Some(r) = self.replace_at_start() {
                    r.apply()?;
                }
                Ok(summary)
            }
            Err(e) => Err(not_started(e, Some(self.name.clone()))),
        }
    }
}

/// A failure of the engine or of the writer before the log started, said so:
/// no log was written, and the older log `kept` (if any) is as it was. Other
/// errors say that by themselves.
fn not_started(e: RunError, kept: Option<PathBuf>) -> RunError {
    let reason = match e {
        RunError::Engine { source, time, .. } => {
            format!("engine failed at simulated time {time}: {source}")
        }
        RunError::LogCut { source, .. } | RunError::Write(source) => source.to_string(),
        e => return e,
    };
    RunError::NotStarted { reason, kept }
}

impl Drop for Output {
    /// Remove a temporary file that did not replace the older log.
    fn drop(&mut self) {
        if let Some(t) = &self.temp {
            if t.exists() {
                let _ = std::fs::remove_file(t);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dir(name: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("carom-replace-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(&d).unwrap();
        d
    }

    #[test]
    fn an_older_log_is_kept_until_the_new_one_replaces_it() {
        let d = dir("older");
        let log = d.join("s.mcap");
        std::fs::write(&log, b"older").unwrap();
        let out = Output::lock(&log).unwrap();
        let temp = d.join("s.mcap.run-tmp");
        assert_eq!(out.writing(), temp.canonicalize().unwrap());
        // Both names are locked meanwhile.
        assert!(matches!(
            lock_log(&log, false),
            Err(RunError::Locked { .. })
        ));
        std::fs::write(&temp, b"newer").unwrap();
        // A failure before the start: the older log is as it was, no temporary file.
        let failed = RunError::Engine {
            source: carom_engine::EngineError::BadCheckpoint("test".into()),
            time: 0.0,
            log: log.clone(),
        };
        let e = out.finish::<()>(Err(failed));
        assert!(matches!(e, Err(RunError::NotStarted { kept: Some(_), .. })));
        assert_eq!(std::fs::read(&log).unwrap(), b"older");
        assert!(!temp.exists());
        // Replaced at the start: the name holds the new log, still locked.
        let out = Output::lock(&log).unwrap();
        std::fs::write(out.writing(), b"newer").unwrap();
        assert_eq!(
            out.replace_at_start().unwrap().apply().unwrap(),
            log.canonicalize().unwrap()
        );
        assert!(matches!(
            lock_log(&log, false),
            Err(RunError::Locked { .. })
        ));
        out.finish(Ok(())).unwrap();
        assert_eq!(std::fs::read(&log).unwrap(), b"newer");
        assert!(!temp.exists());
        std::fs::remove_dir_all(&d).unwrap();
    }

    #[test]
    fn a_fresh_log_is_written_in_place_and_abandoned_without_a_trace() {
        let d = dir("fresh");
        let log = d.join("s.mcap");
        let out = Output::lock(&log).unwrap();
        assert_eq!(out.writing(), log);
        assert!(out.replace_at_start().is_none());
        let e = out.abandon(RunError::InterruptedPlacing { steps: 0 });
        assert!(matches!(e, RunError::InterruptedPlacing { .. }));
        assert_eq!(std::fs::read_dir(&d).unwrap().count(), 0);
        std::fs::remove_dir_all(&d).unwrap();
    }
}
