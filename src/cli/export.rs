//! `carom export`: a log's snapshots as HOOMD GSD or extended XYZ frames (see
//! [`crate::export`]).

use std::path::PathBuf;
use std::process::ExitCode;

use crate::export::{export as export_frames, ExportFormat};
use crate::frames::FrameRange;
use clap::{Args, ValueEnum};

use super::reading::ReadDisplay;
use super::render::{check_out, default_out, OutLock};
use super::{emit, CliError};

/// The export formats.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum FormatArg {
    /// HOOMD's GSD (HOOMD-blue, freud, OVITO, the gsd Python package).
    Gsd,
    /// Extended XYZ (OVITO).
    Xyz,
}

/// Arguments of `carom export`.
#[derive(Debug, Args)]
pub struct ExportArgs {
    /// The log to export.
    pub file: PathBuf,
    /// The file format.
    #[arg(long, value_enum)]
    pub format: FormatArg,
    /// The file to write; default: FILE's name with .gsd or .xyz beside FILE.
    #[arg(short, long, value_name = "FILE")]
    pub out: Option<PathBuf>,
    /// Least simulated time between frames; default: every snapshot.
    #[arg(long, value_name = "DT", allow_negative_numbers = true)]
    pub every: Option<f64>,
    /// First time exported; default: the first snapshot.
    #[arg(long, value_name = "T0", allow_negative_numbers = true)]
    pub from: Option<f64>,
    /// Last time exported; default: the last snapshot.
    #[arg(long, value_name = "T1", allow_negative_numbers = true)]
    pub to: Option<f64>,
    /// Overwrite the output file if it exists.
    #[arg(short, long)]
    pub force: bool,
    /// No progress display.
    #[arg(short, long)]
    pub quiet: bool,
}

/// Run `carom export`.
pub fn export(args: ExportArgs) -> Result<ExitCode, CliError> {
    let format = match args.format {
        FormatArg::Gsd => ExportFormat::Gsd,
        FormatArg::Xyz => ExportFormat::Xyz,
    };
    let out = args
        .out
        .clone()
        .unwrap_or_else(|| default_out(&args.file, format.extension()));
    check_out(&args.file, &out, args.force)?;
    // GSD seeks back to write its index: it needs a regular file, not a device or
    // a pipe (/dev/null, /dev/stdout), which XYZ, written straight through, takes.
    if format == ExportFormat::Gsd && std::fs::metadata(&out).is_ok_and(|m| !m.is_file()) {
        return Err(CliError::Usage(format!(
            "--out {}: not a regular file, and GSD needs one (it goes back to write its \
             index); choose a file, or --format xyz, which can also go to a device or a pipe",
            out.display()
        )));
    }
    let lock = OutLock::take(&out)?;
    let range = FrameRange {
        from: args.from,
        to: args.to,
        every: args.every,
    };
    let mut display = ReadDisplay::new(args.quiet, &args.file.display().to_string());
    display.pass("exporting");
    let result = export_frames(&args.file, &out, format, range, &mut |p| display.update(p));
    display.finish();
    let count = result?;
    lock.keep();
    // The size of a regular file; a device or a pipe has none to tell.
    let size = std::fs::metadata(&out)
        .ok()
        .filter(|m| m.is_file())
        .map_or(String::new(), |m| {
            format!(", {:.1} MB", m.len() as f64 / 1e6)
        });
    emit(&format!(
        "wrote {}: {} frames of {} discs{size}\n",
        out.display(),
        count.frames,
        count.discs,
    ))?;
    Ok(ExitCode::SUCCESS)
}
