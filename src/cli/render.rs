//! `carom render`: a picture of a log's snapshot (PNG or SVG), or a movie of a
//! range of snapshots (animated GIF); see [`crate::render`].

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use crate::frames::{for_each_frame, nearest_snapshot, time_text, FrameRange};
use crate::render::{render_snapshot, ColourBy, ImageFormat, Movie};
use clap::{Args, ValueEnum};

use super::reading::ReadDisplay;
use super::{emit, CliError};

/// What the discs are coloured by.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum ColourArg {
    /// Each species its own colour.
    Species,
    /// Speed |v| on a colour map, with a colour bar.
    Speed,
    /// Local bond order |ψ6| (Delaunay neighbours), 0 to 1: crystalline and
    /// hexatic patches bright, defects and grain boundaries dark.
    Psi6,
    /// Phase of ψ6, arg ψ6 / 6 (the local lattice orientation modulo 60°) on a
    /// colour wheel: each orientational domain its own colour.
    Psi6Phase,
}

/// Arguments of `carom render`.
#[derive(Debug, Args)]
pub struct RenderArgs {
    /// The log to draw.
    pub file: PathBuf,
    /// Draw the snapshot nearest this simulated time; default: the last.
    #[arg(
        long,
        value_name = "T",
        allow_negative_numbers = true,
        conflicts_with = "movie"
    )]
    pub time: Option<f64>,
    /// The picture to write: .png or .svg (a movie: .gif); default: FILE's name
    /// with .png (.gif) beside FILE.
    #[arg(short, long, value_name = "FILE")]
    pub out: Option<PathBuf>,
    /// Colour discs by species or by speed.
    #[arg(long, visible_alias = "colour", value_enum, default_value_t = ColourArg::Species)]
    pub color: ColourArg,
    /// Width of the image in pixels (its height follows from the box); default
    /// 800, for a --movie 480.
    #[arg(long, value_name = "PIXELS",
          value_parser = clap::value_parser!(u32).range(64..=16384))]
    pub size: Option<u32>,
    /// Write an animated GIF of the snapshots from --from to --to, --every apart.
    #[arg(long)]
    pub movie: bool,
    /// First time of the movie; default: the first snapshot.
    #[arg(
        long,
        value_name = "T0",
        allow_negative_numbers = true,
        requires = "movie"
    )]
    pub from: Option<f64>,
    /// Last time of the movie; default: the last snapshot.
    #[arg(
        long,
        value_name = "T1",
        allow_negative_numbers = true,
        requires = "movie"
    )]
    pub to: Option<f64>,
    /// Least simulated time between movie frames; default: every snapshot.
    #[arg(
        long,
        value_name = "DT",
        allow_negative_numbers = true,
        requires = "movie"
    )]
    pub every: Option<f64>,
    /// Movie frames per second.
    #[arg(long, default_value_t = 10, value_parser = clap::value_parser!(u32).range(1..=100),
          requires = "movie")]
    pub fps: u32,
    /// Overwrite the output file if it exists.
    #[arg(short, long)]
    pub force: bool,
    /// No progress display.
    #[arg(short, long)]
    pub quiet: bool,
}

/// FILE.mcap → FILE.`ext` beside it.
pub(crate) fn default_out(file: &Path, ext: &str) -> PathBuf {
    match file.extension() {
        Some(e) if e == "mcap" => file.with_extension(ext),
        _ => {
            let mut name = file.file_name().unwrap_or_default().to_os_string();
            name.push(format!(".{ext}"));
            file.with_file_name(name)
        }
    }
}

/// Refuse to write over the log itself, or over an existing file without --force.
pub(crate) fn check_out(file: &Path, out: &Path, force: bool) -> Result<(), CliError> {
    if out == file || carom_run::same_file(out, file) {
        return Err(CliError::Usage(format!(
            "--out {}: that is the log being read (choose another --out)",
            out.display()
        )));
    }
    if !force && out.exists() {
        return Err(CliError::Usage(format!(
            "{} exists; use --force to overwrite it, or choose another --out",
            out.display()
        )));
    }
    Ok(())
}

/// The lock on a file a command writes ([`carom_run::lock_log`], the lock a run
/// holds on its log), taken after [`check_out`] and before anything is written:
/// a file another process writes (a run's log, another export) is refused and
/// left as it is. A file created here is removed again unless [`OutLock::keep`]
/// is called (the command failed).
pub(crate) struct OutLock {
    _lock: Option<carom_run::LogLock>,
    created: Option<PathBuf>,
}

impl OutLock {
    /// Lock `out`, creating it if it does not exist. A file that cannot be opened
    /// (no such directory) is left to the writer, which says why.
    pub(crate) fn take(out: &Path) -> Result<OutLock, CliError> {
        let created = (!out.exists()).then(|| out.to_path_buf());
        let lock = match carom_run::lock_log(out, true) {
            Err(carom_run::RunError::Lock { .. }) => None,
            lock => Some(lock?),
        };
        Ok(OutLock {
            created: created.filter(|_| lock.is_some()),
            _lock: lock,
        })
    }

    /// The command wrote the file: keep it.
    pub(crate) fn keep(mut self) {
        self.created = None;
    }
}

impl Drop for OutLock {
    fn drop(&mut self) {
        if let Some(out) = &self.created {
            crate::frames::remove_output(out);
        }
    }
}

fn extension(out: &Path) -> String {
    out.extension()
        .map(|e| e.to_string_lossy().to_lowercase())
        .unwrap_or_default()
}

/// Run `carom render`.
pub fn render(args: RenderArgs) -> Result<ExitCode, CliError> {
    let by = match args.color {
        ColourArg::Species => ColourBy::Species,
        ColourArg::Speed => ColourBy::Speed,
        ColourArg::Psi6 => ColourBy::Psi6,
        ColourArg::Psi6Phase => ColourBy::Psi6Phase,
    };
    let out = args
        .out
        .clone()
        .unwrap_or_else(|| default_out(&args.file, if args.movie { "gif" } else { "png" }));
    check_out(&args.file, &out, args.force)?;
    let ext = extension(&out);
    let format = match (args.movie, ext.as_str()) {
        (false, "png") => Some(ImageFormat::Png),
        (false, "svg") => Some(ImageFormat::Svg),
        (true, "gif") => None,
        (false, _) => {
            return Err(CliError::Usage(format!(
                "--out {}: unknown picture type .{ext} (allowed: .png, .svg; a --movie is .gif)",
                out.display()
            )))
        }
        (true, _) => {
            return Err(CliError::Usage(format!(
                "--out {}: a --movie is written as an animated GIF (allowed: .gif)",
                out.display()
            )))
        }
    };
    let lock = OutLock::take(&out)?;
    let mut display = ReadDisplay::new(args.quiet, &args.file.display().to_string());
    display.pass("reading");
    let Some(format) = format else {
        let done = movie(&args, &out, by, &mut display)?;
        lock.keep();
        return Ok(done);
    };
    let snapshot = nearest_snapshot(&args.file, args.time, &mut |p| display.update(p));
    display.finish();
    let s = snapshot?;
    let layout = render_snapshot(&s, &out, format, args.size.unwrap_or(800), by)?;
    lock.keep();
    emit(&format!(
        "wrote {} ({}×{} px): t = {}, N = {}\n",
        out.display(),
        layout.size.0,
        layout.size.1,
        time_text(s.time),
        s.positions.len()
    ))?;
    Ok(ExitCode::SUCCESS)
}

fn movie(
    args: &RenderArgs,
    out: &Path,
    by: ColourBy,
    display: &mut ReadDisplay,
) -> Result<ExitCode, CliError> {
    let range = FrameRange {
        from: args.from,
        to: args.to,
        every: args.every,
    };
    let delay_ms = 1000 / args.fps;
    let mut movie: Option<Movie> = None;
    let mut span: Option<(f64, f64)> = None;
    let result = for_each_frame(&args.file, range, &mut |p| display.update(p), &mut |s| {
        if movie.is_none() {
            movie = Some(Movie::create(
                out,
                s,
                args.size.unwrap_or(480),
                by,
                delay_ms,
            )?);
        }
        span = Some(span.map_or((s.time, s.time), |(a, _)| (a, s.time)));
        movie.as_mut().map_or(Ok(()), |m| m.push(s))
    });
    display.finish();
    let size = movie.as_ref().map(|m| m.layout().size);
    // Dropping the movie writes the GIF's trailer.
    drop(movie);
    let count = match result {
        Ok(c) => c,
        Err(e) => {
            crate::frames::remove_output(out);
            return Err(e.into());
        }
    };
    let (w, h) = size.unwrap_or_default();
    let (a, b) = span.unwrap_or_default();
    emit(&format!(
        "wrote {} ({w}×{h} px): {} frames, t = {} … {}\n",
        out.display(),
        count.frames,
        time_text(a),
        time_text(b)
    ))?;
    Ok(ExitCode::SUCCESS)
}

#[cfg(test)]
mod tests {
    use super::default_out;
    use std::path::Path;

    #[test]
    fn the_default_picture_is_beside_the_log() {
        assert_eq!(
            default_out(Path::new("d/run.mcap"), "png"),
            Path::new("d/run.png")
        );
        assert_eq!(default_out(Path::new("log"), "gif"), Path::new("log.gif"));
    }
}
