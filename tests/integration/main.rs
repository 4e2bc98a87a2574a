//! carom's integration tests, one test binary (`cargo test --test integration`).
//!
//! Each module is one former test file (`tests/<name>.rs` until issue 52) and keeps
//! its name, so `cargo test --release --test integration hardening_locks::` runs what
//! `--test hardening_locks` ran. One binary instead of ~50 links the `carom` library
//! (with plotters, clap, …) once, under the release profile's fat LTO, instead of
//! once per file. The helpers the modules share are declared here once and used as
//! `crate::cli_common::…`. Tests that must be alone in their process stay separate
//! binaries: `tests/mcap_memory.rs` (it reads this process's peak memory).
//!
//! Everything here runs in one process, on parallel threads: a test's scratch
//! files are named after its module ([`module_of`]), never after the binary.

mod analysis_common;
mod cli_common;
mod log_view_common;
mod mcap_common;
mod readers_common;
mod stats_common;
mod validation_common;

mod analysis_cooling;
mod analysis_dynamics;
mod analysis_engine;
mod analysis_structure;
mod analysis_transport;
mod arrays;
mod cli;
mod cli_compression;
mod cli_cooling;
mod cli_export;
mod cli_figures;
mod cli_floor;
mod cli_gravity;
mod cli_hardening;
mod cli_neighbours;
mod cli_one_writer;
mod cli_render;
mod cli_report_text;
mod cli_resume_in_place;
mod cli_thermo_schema;
mod cli_transport;
mod cli_watchdog;
mod compact_log;
mod compact_python;
mod examples;
mod gravity_log;
mod hardening_bitflips;
mod hardening_locks;
mod hardening_logs;
mod hardening_procs;
mod hardening_resting;
mod hardening_stops;
mod hardening_sweep;
mod live;
mod mcap_corruption;
mod mcap_crash;
mod mcap_python;
mod mcap_repair;
mod mcap_resume;
mod mcap_roundtrip;
mod mcap_scene;
mod python;
mod slurm;
mod snapshot_schedule;
mod sweep;
mod thermo_pressure;
mod thermostat;
mod thermostat_log;
mod validation;
mod validation_compression;
mod validation_gravity;
mod validation_structure;
mod validation_transport;
mod validation_transport_seeds;

/// The top-level module a source file of this binary belongs to, from its path
/// (`file!()` or [`std::panic::Location`]): `tests/integration/cli.rs` → `cli`,
/// `tests/integration/validation/eos.rs` → `validation`. This is the name the
/// module's own test binary had, so scratch directories and the validation
/// tables keep their names.
pub fn module_of(file: &str) -> &str {
    let parts: Vec<&str> = file.split(['/', '\\']).collect();
    let i = parts
        .iter()
        .rposition(|p| *p == "integration")
        .unwrap_or_else(|| panic!("{file} is not under tests/integration"));
    parts[i + 1].trim_end_matches(".rs")
}
