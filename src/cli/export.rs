//! `carom export`: a log's snapshots as HOOMD GSD or extended XYZ frames (see
//! [`carom::export`]).

use std::path::PathBuf;
use std::process::ExitCode;

use carom::export::{export as export_frames, ExportFormat};
use carom::frames::FrameRange;
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
    let bytes = std::fs::metadata(&out).map(|m| m.len()).unwrap_or(0);
    emit(&format!(
        "wrote {}: {} frames of {} discs, {:.1} MB\n",
        out.display(),
        count.frames,
        count.discs,
        bytes as f64 / 1e6
    ))?;
    Ok(ExitCode::SUCCESS)
}
