//! carom's Python package (crates/python): its pytest suite, run by the Python
//! that has it installed. `.ci/run` installs the package into `.venv` with pytest
//! and numpy (tests/python-requirements.txt) and sets `CAROM_PYTHON`; then a
//! failed build, install or test fails here. Without an interpreter that imports
//! `carom` and `pytest` the test skips, loudly, or fails when `CI` is set
//! (tests/readers_common).
//!
//! The suite compares the package with this very `carom` binary (`CAROM_BIN`):
//! configuration messages, final states bit for bit, logs and `analyze --json`.

use crate::readers_common::python_with;
use std::path::Path;
use std::process::Command;

#[test]
fn the_python_package_passes_its_pytest_suite() {
    let Some(py) = python_with(&["carom", "pytest", "numpy"]) else {
        return;
    };
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let out = Command::new(&py)
        .args([
            "-m",
            "pytest",
            "crates/python/tests",
            "-q",
            "-p",
            "no:cacheprovider",
        ])
        .current_dir(root)
        .env("CAROM_BIN", env!("CARGO_BIN_EXE_carom"))
        .output()
        .expect("python runs");
    assert!(
        out.status.success(),
        "pytest crates/python/tests failed:\n{}\n{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
}
