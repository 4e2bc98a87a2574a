//! The one rule for a test whose independent reader is missing (the Python
//! packages of tests/python-requirements.txt, or node with tests/node's modules):
//! with the environment variable `CI` set (non-empty; `.ci/run` sets it) the test
//! FAILS, naming what is missing and how to install it; locally it skips, loudly
//! (straight to stderr, past the harness's output capture). Re-exported by
//! `mcap_common` and `cli_common`.
#![allow(dead_code)] // tests/mcap_memory.rs uses only some of these

use std::io::Write;
use std::process::Command;

/// Whether `CI` is set to something non-empty: then every independent reader is
/// required.
pub fn readers_required() -> bool {
    std::env::var_os("CI").is_some_and(|v| !v.is_empty())
}

/// `None` (skip) after saying on stderr that `what` is missing and `how` to get it;
/// a test failure instead when [`readers_required`].
pub fn skip_or_fail<T>(what: &str, how: &str) -> Option<T> {
    assert!(
        !readers_required(),
        "CI is set, so the independent readers are required: {what}; {how}"
    );
    let _ = writeln!(
        std::io::stderr(),
        "SKIPPED: {what}; {how} (with CI set this is a failure)"
    );
    None
}

/// The Python interpreter that can import `modules`: `$CAROM_PYTHON` if set (then
/// it must have them), else `python3`; or [`skip_or_fail`].
pub fn python_with(modules: &[&str]) -> Option<String> {
    let (py, explicit) = match std::env::var("CAROM_PYTHON") {
        Ok(p) if !p.is_empty() => (p, true),
        _ => ("python3".to_string(), false),
    };
    let ok = Command::new(&py)
        .args(["-c", &format!("import {}", modules.join(", "))])
        .output()
        .map(|o| o.status.success())
        .unwrap_or(false);
    if ok {
        return Some(py);
    }
    let how = "pip install -r tests/python-requirements.txt into a venv and set \
               CAROM_PYTHON to its python (.ci/run does)";
    assert!(
        !explicit,
        "CAROM_PYTHON={py} is set but cannot import {modules:?}; {how}"
    );
    skip_or_fail(
        &format!("the Python packages {modules:?} are not available to {py}"),
        how,
    )
}

/// The directory `tests/node` when `node` runs and `tests/node/node_modules` holds
/// `package`; or [`skip_or_fail`].
pub fn node_with(package: &str) -> Option<std::path::PathBuf> {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/node");
    let how = "install node and npm, then `npm ci --prefix tests/node` (.ci/run does)";
    if Command::new("node").arg("--version").output().is_err() {
        return skip_or_fail("node is not installed", how);
    }
    if !dir.join("node_modules").join(package).exists() {
        return skip_or_fail(&format!("tests/node/node_modules has no {package}"), how);
    }
    Some(dir)
}
