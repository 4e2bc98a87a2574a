//! The `carom` command: `run`, `resume`, `analyze`, `info`, `render`, `export`,
//! `sweep` and `collect` (see `carom --help`).
//!
//! This package is the binary only: the physics and the log live in the workspace's
//! library crates (`carom-core`, `carom-engine`, `carom-log`, `carom-config`,
//! `carom-analysis`, `carom-run`), and this is the only home of the terminal and
//! picture dependencies (clap, indicatif, ctrlc, plotters, image, hoomd-gsd).
//! Its own modules: `cli` (the commands), `frames` (choosing snapshots), `render`
//! (pictures) and `export` (GSD, XYZ).

mod cli;
mod export;
mod frames;
mod render;

fn main() -> std::process::ExitCode {
    cli::main()
}
