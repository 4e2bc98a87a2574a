//! What a log says about its run, for the analysis: the facts it stores
//! (`carom_log::RunFacts`), and for a log written before they were complete
//! those derived once, from its stored configuration, by the caller's
//! [`OldLogFacts`] (the analysis does not depend on the configuration front end;
//! `carom_config::derive_facts_for_old_log` is the one derivation).
//!
//! | log format | species, box, rule, g | thermostat, growth, floor |
//! |---|---|---|
//! | 2.4 on | stored facts | stored facts (absent: none) |
//! | 1.2 – 2.3 | stored facts | derived (configuration unreadable: none) |
//! | ≤ 1.1 | derived (unreadable: the first snapshot) | derived |

use carom_log::{RunFacts, RunMetadata};

/// How the facts of a log older than format 2.4 are derived from its stored
/// configuration text; `Err` says why they cannot be.
pub type OldLogFacts<'a> = &'a dyn Fn(&str) -> Result<RunFacts, String>;

/// For callers without the configuration front end: an old log's configuration
/// is not read (a log without facts is then described by its first snapshot,
/// and a log before 2.4 is analysed without thermostat, growth and floor).
pub fn no_old_log_facts(_config: &str) -> Result<RunFacts, String> {
    Err("no configuration front end to read it with".into())
}

/// The facts the analysis uses.
pub(super) struct LogFacts {
    /// What describes the run (species, box, rule, g), or why nothing does.
    pub(super) description: Result<RunFacts, String>,
    /// Whose thermostat, growth, floor (and rule and g with them) the run had;
    /// `None`: none known.
    pub(super) dynamics: Option<RunFacts>,
}

/// The facts of the run `run` (the `carom.run` record), the configuration read
/// by `old_log` at most once and only for a log before format 2.4.
pub(super) fn log_facts(run: &RunMetadata, old_log: OldLogFacts<'_>) -> LogFacts {
    let stored = run.run_facts.clone();
    if RunFacts::hold_dynamics(&run.log_format) {
        if let Some(f) = stored {
            return LogFacts {
                description: Ok(f.clone()),
                dynamics: Some(f),
            };
        }
    }
    let derived = old_log(&run.config);
    LogFacts {
        dynamics: derived.as_ref().ok().cloned(),
        description: stored.map_or(derived, Ok),
    }
}
