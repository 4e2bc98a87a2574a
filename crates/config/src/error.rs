//! What can go wrong with a configuration ([`ConfigError`]), and the mapping of
//! the initial-state builder's errors ([`InitError`]) to the configuration's own
//! field names, so that every error names a setting the user can change.

use carom_engine::InitError;
use carom_log::OptionsError;
use thiserror::Error;

/// A configuration that cannot be read or does not describe a valid run. Every
/// variant that concerns a field names it as a dotted path (`species.0.radius`).
#[derive(Debug, Error)]
pub enum ConfigError {
    /// The configuration file could not be read.
    #[error("cannot read configuration file {path}: {source}")]
    Io {
        /// The file.
        path: String,
        /// The operating-system error.
        #[source]
        source: std::io::Error,
    },
    /// The text is not JSON.
    #[error("{origin}: not valid JSON at line {line}, column {column}: {message}")]
    Syntax {
        /// File name (or `configuration`).
        origin: String,
        /// Line of the error (1-based).
        line: usize,
        /// Column of the error (1-based).
        column: usize,
        /// What the parser found.
        message: String,
    },
    /// A `--set` argument is malformed or its path does not exist.
    #[error("--set {arg}: {problem}")]
    Set {
        /// The argument as given (`key=value`).
        arg: String,
        /// What was wrong.
        problem: String,
    },
    /// A field has the wrong type, is unknown, missing, or out of range.
    #[error("{field}: {problem} (allowed: {allowed})")]
    Invalid {
        /// Dotted path of the field, e.g. `species.1.radius`; `(top level)` for the
        /// document itself.
        field: String,
        /// What was wrong.
        problem: String,
        /// What is allowed.
        allowed: String,
    },
}

impl ConfigError {
    pub(crate) fn invalid(
        field: impl Into<String>,
        problem: impl Into<String>,
        allowed: impl Into<String>,
    ) -> Self {
        ConfigError::Invalid {
            field: field.into(),
            problem: problem.into(),
            allowed: allowed.into(),
        }
    }

    /// The dotted path of the offending field, when the error concerns one.
    pub fn field(&self) -> Option<&str> {
        match self {
            ConfigError::Invalid { field, .. } => Some(field),
            _ => None,
        }
    }

    /// Translate an error of the initial-state builder ([`carom_engine::SystemSpec::build`]) into
    /// the configuration's field names: `species[1].radius` becomes
    /// `species.1.radius`, `positions[3].x` becomes `placement.explicit.3`,
    /// overlapping explicit discs are reported on `placement.explicit`.
    pub fn from_init(e: InitError) -> Self {
        match e {
            InitError::Invalid {
                field,
                problem,
                allowed,
            } => ConfigError::Invalid {
                field: init_field_to_config(&field),
                problem,
                allowed,
            },
            InitError::Overlap {
                i,
                j,
                distance,
                sigma,
            } => ConfigError::invalid(
                "placement.explicit",
                format!(
                    "discs {i} and {j} overlap (centre distance {distance} < sum of radii {sigma})"
                ),
                "centre distances ≥ the sum of the two radii (minimum image on periodic axes)",
            ),
        }
    }

    /// [`ConfigError::from_init`] for the configuration `config_json` (the text in
    /// [`RunSpec::config_json`](carom_log::RunSpec)): the builder's `packing_fraction`
    /// is named as the setting that fixed it, `box.size` when the configuration
    /// gives the box's size and `box.packing_fraction` otherwise.
    pub fn from_init_in(e: InitError, config_json: &str) -> Self {
        let mut e = ConfigError::from_init(e);
        if let ConfigError::Invalid { field, .. } = &mut e {
            if field == "box" {
                let sized = serde_json::from_str::<serde_json::Value>(config_json)
                    .ok()
                    .is_some_and(|v| v.pointer("/box/size").is_some());
                *field = if sized {
                    "box.size"
                } else {
                    "box.packing_fraction"
                }
                .to_owned();
            }
        }
        e
    }
}

impl From<OptionsError> for ConfigError {
    fn from(e: OptionsError) -> Self {
        ConfigError::invalid(e.field, e.problem, e.allowed)
    }
}

impl From<InitError> for ConfigError {
    fn from(e: InitError) -> Self {
        ConfigError::from_init(e)
    }
}

/// Map a field name of [`InitError`] to the configuration's dotted path.
pub(super) fn init_field_to_config(field: &str) -> String {
    // `name[3].rest` → segments name, 3, rest.
    let dotted = field.replace('[', ".").replace(']', "");
    let mut parts: Vec<&str> = dotted.split('.').filter(|s| !s.is_empty()).collect();
    match parts.first().copied() {
        Some("positions") => {
            // Explicit positions are `[x, y]` pairs: drop the component name.
            parts.truncate(2);
            parts[0] = "placement.explicit";
        }
        Some("velocities") => {
            parts.truncate(2);
            parts[0] = "velocities.explicit";
        }
        Some("box") if parts.get(1) == Some(&"size") => {
            return "box.size".to_owned();
        }
        Some("box") if parts.get(1) == Some(&"boundary") => {
            return "box.wall_restitution".to_owned();
        }
        Some("packing_fraction") => return "box".to_owned(),
        _ => {}
    }
    parts.join(".")
}
