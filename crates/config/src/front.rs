//! The front end: JSON text (a file, or `{}` for the built-in default), the
//! `--set key=value` overrides, and deserialisation into [`Config`] with serde's
//! messages turned into errors that name the field as a dotted path and say what
//! is allowed in words.

use super::{Config, ConfigError};
use carom_log::RunSpec;
use serde_json::Value;
use std::path::Path;

/// The largest configuration (or sweep plan, or sweep base) file read, in bytes:
/// 256 MiB, room for explicit positions and velocities of more than 10⁶ discs. A
/// larger file, or one without end (`/dev/zero`), is refused once this much is
/// read, rather than read until memory runs out.
pub const MAX_CONFIG_BYTES: u64 = 256 << 20;

/// The text of the configuration file `path`, refused (an error of kind
/// `InvalidData`) past [`MAX_CONFIG_BYTES`] bytes.
pub fn read_config_text(path: &Path) -> std::io::Result<String> {
    use std::io::Read;
    let mut text = String::new();
    std::fs::File::open(path)?
        .take(MAX_CONFIG_BYTES + 1)
        .read_to_string(&mut text)?;
    if text.len() as u64 > MAX_CONFIG_BYTES {
        return Err(std::io::Error::new(
            std::io::ErrorKind::InvalidData,
            format!(
                "larger than the {} MiB a configuration file may have",
                MAX_CONFIG_BYTES >> 20
            ),
        ));
    }
    Ok(text)
}

/// Read a configuration file (or the built-in default when `path` is `None`),
/// apply the `--set key=value` overrides in order, check everything and build the
/// [`RunSpec`]. This is what `carom run` calls.
pub fn load_config(path: Option<&Path>, sets: &[String]) -> Result<RunSpec, ConfigError> {
    let (text, origin) = match path {
        Some(p) => (
            read_config_text(p).map_err(|source| ConfigError::Io {
                path: p.display().to_string(),
                source,
            })?,
            p.display().to_string(),
        ),
        None => ("{}".to_owned(), "built-in default".to_owned()),
    };
    // A byte-order mark (some Windows editors write one) is not JSON; skip it.
    let text = text.strip_prefix('\u{feff}').unwrap_or(&text);
    let config = Config::from_json_with_sets(text, &origin, sets)?;
    config.to_run_spec()
}

/// Parse JSON text into a [`Value`], reporting syntax errors with line and column.
fn parse_json(text: &str, origin: &str) -> Result<Value, ConfigError> {
    let value = serde_json::from_str(text).map_err(|e| ConfigError::Syntax {
        origin: origin.to_owned(),
        line: e.line(),
        column: e.column(),
        message: strip_position(&e.to_string()).to_owned(),
    })?;
    // A JSON object read into a Value keeps the last of two equal keys without a
    // word; reading the text straight into the configuration's structs notices.
    // (Any other error of that reading is left to the checks that follow, which
    // see the `--set` overrides too.)
    let mut de = serde_json::Deserializer::from_str(text);
    if let Err(e) = serde_path_to_error::deserialize::<_, Config>(&mut de) {
        let message = e.inner().to_string();
        if let Some(rest) = message.strip_prefix("duplicate field `") {
            let key = rest.split('`').next().unwrap_or_default();
            let parent = dotted(e.path());
            let field = if parent == "(top level)" || parent.ends_with(key) {
                key.to_owned()
            } else {
                format!("{parent}.{key}")
            };
            return Err(ConfigError::invalid(
                field,
                format!("given twice ({})", strip_position(&message)),
                "each key once per object",
            ));
        }
    }
    Ok(value)
}

/// Render a serde_path_to_error path as a dotted path (`species.0.count`).
fn dotted(path: &serde_path_to_error::Path) -> String {
    use serde_path_to_error::Segment;
    let parts: Vec<String> = path
        .iter()
        .filter_map(|s| match s {
            Segment::Seq { index } => Some(index.to_string()),
            Segment::Map { key } => Some(key.clone()),
            Segment::Enum { variant } => Some(variant.clone()),
            Segment::Unknown => None,
        })
        .collect();
    if parts.is_empty() {
        "(top level)".to_owned()
    } else {
        parts.join(".")
    }
}

/// Drop serde_json's trailing " at line L column C" (reported separately).
fn strip_position(msg: &str) -> &str {
    match msg.rfind(" at line ") {
        Some(k) if msg[k..].contains(" column ") => &msg[..k],
        _ => msg,
    }
}

/// serde's name of an expected Rust type in words a user of the config reads
/// ("f64" is "a number"); anything else as it is.
fn plain_type(expected: &str) -> String {
    match expected {
        "f64" | "f32" => "a number".to_owned(),
        "u64" | "u32" | "usize" | "u16" => "a non-negative integer".to_owned(),
        "i64" | "i32" => "an integer".to_owned(),
        "a boolean" | "bool" => "true or false".to_owned(),
        _ => expected.to_owned(),
    }
}

/// Split serde's message "problem, expected X" into (problem, allowed).
fn split_serde_message(msg: &str) -> (String, String) {
    // serde_json appends " at line L column C" only when parsing text; from a Value
    // there is none, but strip it in case.
    let msg = strip_position(msg);
    if msg.starts_with("invalid length") {
        // Only the [x, y] pairs (box.size, explicit positions and velocities) have
        // a fixed length; serde's "expected fewer elements" says too little.
        let problem = msg.split(", expected").next().unwrap_or(msg);
        return (
            format!("{problem} numbers"),
            "an array of exactly 2 numbers [x, y]".to_owned(),
        );
    }
    match msg.find(", expected ") {
        Some(k) => (
            msg[..k].to_owned(),
            plain_type(&msg[k + ", expected ".len()..]),
        ),
        None => {
            if msg.starts_with("missing field") {
                (msg.to_owned(), "the field is required here".to_owned())
            } else {
                (msg.to_owned(), "see data/config.schema.json".to_owned())
            }
        }
    }
}

impl Config {
    /// Parse and check a configuration from JSON text (no overrides).
    pub fn from_json_str(text: &str) -> Result<Config, ConfigError> {
        Config::from_json_with_sets(text, "configuration", &[])
    }

    /// Parse JSON text, apply `--set key=value` overrides in order, deserialise and
    /// check. `origin` names the text in syntax errors (a file name).
    pub fn from_json_with_sets(
        text: &str,
        origin: &str,
        sets: &[String],
    ) -> Result<Config, ConfigError> {
        let mut value = parse_json(text, origin)?;
        for s in sets {
            apply_set(&mut value, s)?;
        }
        Config::from_value(value)
    }

    /// Deserialise a JSON value and check it ([`Config::validate`]).
    pub fn from_value(value: Value) -> Result<Config, ConfigError> {
        if !value.is_object() {
            return Err(ConfigError::invalid(
                "(top level)",
                format!("the configuration is {}", kind_of(&value)),
                "a JSON object {...}",
            ));
        }
        let config: Config = serde_path_to_error::deserialize(value).map_err(|e| {
            let mut field = dotted(e.path());
            let message = e.inner().to_string();
            // For an unknown field the path ends at the enclosing object; name the
            // field itself.
            if let Some(rest) = message.strip_prefix("unknown field `") {
                if let Some(end) = rest.find('`') {
                    let key = &rest[..end];
                    if !field.ends_with(key) {
                        field = if field == "(top level)" {
                            key.to_owned()
                        } else {
                            format!("{field}.{key}")
                        };
                    }
                }
            }
            let (problem, allowed) = split_serde_message(&message);
            ConfigError::invalid(field, problem, allowed)
        })?;
        config.validate()?;
        Ok(config)
    }
}

fn kind_of(v: &Value) -> &'static str {
    match v {
        Value::Null => "null",
        Value::Bool(_) => "a boolean",
        Value::Number(_) => "a number",
        Value::String(_) => "a string",
        Value::Array(_) => "an array",
        Value::Object(_) => "an object",
    }
}

/// Apply one `--set key=value` override to a configuration's JSON value.
///
/// `key` is a dotted path: object keys, and array indices for arrays
/// (`species.1.radius`). `value` is parsed as JSON if it parses, otherwise taken
/// as a string (`placement=random`). Missing top-level sections start from their
/// default (`species.0.count=500` on an empty configuration edits the default
/// species), missing objects below are created, and an index equal to an array's
/// length appends an element. Whether the resulting key is known is checked when
/// the value is deserialised, which names the field.
pub fn apply_set(config: &mut Value, arg: &str) -> Result<(), ConfigError> {
    let bad = |problem: String| ConfigError::Set {
        arg: arg.to_owned(),
        problem,
    };
    let (key, raw) = arg
        .split_once('=')
        .ok_or_else(|| bad("expected key=value (e.g. species.0.count=500)".to_owned()))?;
    let key = key.trim();
    if key.is_empty() || key.split('.').any(str::is_empty) {
        return Err(bad(format!(
            "`{key}` is not a dotted path (e.g. log.snapshot_interval)"
        )));
    }
    let new: Value = serde_json::from_str(raw).unwrap_or_else(|_| Value::String(raw.to_owned()));
    if !config.is_object() {
        return Err(bad("the configuration is not a JSON object".to_owned()));
    }
    let defaults = serde_json::to_value(Config::default()).expect("a Config always serialises");
    let segments: Vec<&str> = key.split('.').collect();
    let mut here = config;
    for (depth, seg) in segments.iter().enumerate() {
        let last = depth + 1 == segments.len();
        let path_so_far = segments[..=depth].join(".");
        here = match here {
            Value::Object(map) => {
                if !map.contains_key(*seg) {
                    // A top-level section missing from the file starts from its
                    // default; anything else missing starts empty.
                    let fill = if depth == 0 {
                        defaults.get(*seg).cloned()
                    } else {
                        None
                    };
                    map.insert(
                        (*seg).to_owned(),
                        fill.unwrap_or_else(|| Value::Object(Default::default())),
                    );
                }
                map.get_mut(*seg).expect("inserted above")
            }
            Value::Array(items) => {
                let idx: usize = seg.parse().map_err(|_| {
                    bad(format!(
                        "`{path_so_far}`: `{seg}` is not an index into the list (use 0, 1, ...)"
                    ))
                })?;
                if idx > items.len() {
                    return Err(bad(format!(
                        "`{path_so_far}`: index {idx} is beyond the list of {} (indices 0..={} \
                         allowed; {} appends)",
                        items.len(),
                        items.len(),
                        items.len()
                    )));
                }
                if idx == items.len() {
                    items.push(Value::Object(Default::default()));
                }
                &mut items[idx]
            }
            other => {
                return Err(bad(format!(
                    "`{}` is {}, not an object or list, so it has no field `{seg}`",
                    segments[..depth].join("."),
                    kind_of(other)
                )))
            }
        };
        if last {
            *here = new;
            return Ok(());
        }
    }
    unreachable!("the loop returns at the last segment")
}
