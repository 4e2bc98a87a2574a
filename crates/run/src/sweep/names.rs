//! Point names: the directory name of each point under the sweep's output, built
//! from its values (`packing_fraction=0.3,seed=2`). Each axis is labelled by the
//! last segment of its path (the whole path where two axes share it); a value is
//! written bare if a string, as compact JSON otherwise, with `/`, whitespace and
//! `"` replaced by `_`. A name must be a file name on every system carom runs on:
//! at most [`MAX_NAME_BYTES`] bytes and no control character (a NUL cannot be in
//! a path at all). A name that is not is refused when the plan is read — by
//! `--dry-run` too — rather than when its directory is made, half-way through
//! laying out the sweep.

use serde_json::Value;

use super::Axis;

/// The longest file name (bytes) Linux, macOS and the common file systems accept.
pub const MAX_NAME_BYTES: usize = 255;

/// Each axis's label in point names: the last segment of its path, or the whole
/// path where two axes share a last segment.
pub(super) fn labels(axes: &[Axis]) -> Vec<String> {
    let last = |p: &str| p.rsplit('.').next().unwrap_or(p).to_owned();
    axes.iter()
        .map(|a| {
            let l = last(&a.path);
            let shared = axes.iter().filter(|b| last(&b.path) == l).count() > 1;
            if shared {
                a.path.clone()
            } else {
                l
            }
        })
        .collect()
}

/// A value as it appears in a point's name: strings bare, `/` and whitespace
/// replaced, anything else as compact JSON.
pub(super) fn value_text(v: &Value) -> String {
    let s = match v {
        Value::String(s) => s.clone(),
        other => other.to_string(),
    };
    s.chars()
        .map(|c| {
            if c == '/' || c.is_whitespace() || c == '"' {
                '_'
            } else {
                c
            }
        })
        .collect()
}

/// Why `name` cannot be a directory name, if it cannot.
pub(super) fn unusable(name: &str) -> Option<String> {
    if let Some(c) = name.chars().find(|c| c.is_control()) {
        return Some(format!(
            "holds the control character U+{:04X}, which a file name cannot hold",
            c as u32
        ));
    }
    if name.len() > MAX_NAME_BYTES {
        return Some(format!(
            "is {} bytes long, more than the {MAX_NAME_BYTES} a file name may have \
             (shorten the varied values, e.g. a long description)",
            name.len()
        ));
    }
    None
}

/// `name` cut to about 60 characters for an error message.
pub(super) fn shown(name: &str) -> String {
    let printable: String = name
        .chars()
        .map(|c| if c.is_control() { '\u{fffd}' } else { c })
        .collect();
    if printable.chars().count() <= 60 {
        printable
    } else {
        printable.chars().take(57).collect::<String>() + "…"
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_that_cannot_be_file_names_are_told_why() {
        assert_eq!(unusable("packing_fraction=0.3,seed=2"), None);
        assert!(unusable("description=a\u{0}b").unwrap().contains("U+0000"));
        let long = format!("description={}", "a".repeat(300));
        assert!(unusable(&long).unwrap().contains("312 bytes"));
        // 255 bytes is allowed, 256 not; bytes, not characters, count.
        assert_eq!(unusable(&"a".repeat(255)), None);
        assert!(unusable(&"é".repeat(128)).is_some());
        assert_eq!(shown(&"a".repeat(100)).chars().count(), 58);
        assert_eq!(shown("a\u{0}b"), "a\u{fffd}b");
    }
}
