//! What the end-to-end tests of the `carom` binary share: the binary, a scratch
//! directory per test, running it, and reading its output.

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};

use serde_json::Value;

pub use crate::readers_common::{node_with, python_with};

/// The `carom` binary under test.
pub const BIN: &str = env!("CARGO_BIN_EXE_carom");

/// A fresh directory for one test, named after the calling test's module (the
/// file it was, e.g. `cli_render` → `cli-render-NAME`) and `name`: all modules run
/// in one process, so the module keeps two files' equal `name`s apart.
#[track_caller]
pub fn scratch(name: &str) -> PathBuf {
    let module = crate::module_of(std::panic::Location::caller().file()).replace('_', "-");
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("{module}-{name}"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Run `carom ARGS` in `dir` with no standard input.
pub fn carom(dir: &Path, args: &[&str]) -> Output {
    Command::new(BIN)
        .args(args)
        .current_dir(dir)
        .stdin(Stdio::null())
        .output()
        .unwrap()
}

/// The standard output of a run that must have succeeded without a panic.
pub fn ok(out: &Output) -> String {
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "exit {:?}: {stderr}", out.status);
    assert!(!stderr.contains("panicked"), "{stderr}");
    String::from_utf8(out.stdout.clone()).unwrap()
}

/// The standard output of a successful run, as JSON.
pub fn json_of(out: &Output) -> Value {
    serde_json::from_str(&ok(out)).unwrap()
}

/// Run the shell script `script` in `dir` with no standard input (for `ulimit`
/// and `trap` in front of `exec carom …`).
pub fn sh(dir: &Path, script: &str) -> Output {
    Command::new("sh")
        .args(["-c", script])
        .current_dir(dir)
        .stdin(Stdio::null())
        .output()
        .unwrap()
}
