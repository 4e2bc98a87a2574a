//! `carom repair`: a complete, indexed log from one cut short (see
//! [`carom_run::repair`]). Never writes over its input, nor over a file that
//! another process writes (a run's log).

use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use carom_log::LogEnd;

use super::{emit, CliError, RepairArgs};

/// FILE.mcap → FILE.repaired.mcap (any other name: FILE.repaired.mcap appended).
fn default_out(file: &Path) -> PathBuf {
    let stem = match file.extension() {
        Some(e) if e == "mcap" => file.with_extension(""),
        _ => file.to_path_buf(),
    };
    let mut name = stem.file_name().unwrap_or_default().to_os_string();
    name.push(".repaired.mcap");
    file.with_file_name(name)
}

/// Run `carom repair`.
pub fn repair(args: RepairArgs) -> Result<ExitCode, CliError> {
    let out = args.out.unwrap_or_else(|| default_out(&args.file));
    if out == args.file || carom_run::same_file(&out, &args.file) {
        return Err(CliError::Usage(format!(
            "--out {}: that is the input; repair writes a new file (choose another --out)",
            out.display()
        )));
    }
    if !args.force && out.exists() {
        return Err(CliError::Usage(format!(
            "{} exists; use --force to overwrite it, or choose another --out",
            out.display()
        )));
    }
    let lock = super::render::OutLock::take(&out)?;
    let r = carom_run::repair(&args.file, &out)?;
    lock.keep();
    let how = match &r.input_end {
        LogEnd::Complete => "the input was already complete; copied whole".to_string(),
        LogEnd::Truncated { detail } => format!("the input was cut ({detail})"),
        LogEnd::Damaged { detail } => {
            format!("every message was read; the input was damaged outside its chunks ({detail})")
        }
        _ if !r.lost.is_empty() => format!(
            "the input is damaged: {} part(s) lost, every chunk whose CRC holds copied",
            r.lost.len()
        ),
        _ => "the input was damaged outside its chunks (its start, or a record's framing); \
              every message was read around the damage"
            .to_string(),
    };
    for l in &r.lost {
        let _ = writeln!(
            std::io::stderr(),
            "lost: bytes {}..{} of {} ({})",
            l.offset,
            l.offset + l.length,
            args.file.display(),
            l.what
        );
    }
    if r.dropped_batches > 0 {
        let _ =
            writeln!(std::io::stderr(),
            "left out {} compact /collisions batches after a lost part, up to the next snapshot \
             (their velocities replay from the snapshot before the gap)",
            r.dropped_batches
        );
    }
    emit(&format!(
        "wrote {}: {} messages, {} bytes, complete and indexed; {how}\n",
        r.out.display(),
        r.messages,
        r.bytes
    ))?;
    Ok(ExitCode::SUCCESS)
}

#[cfg(test)]
mod tests {
    use super::default_out;
    use std::path::Path;

    #[test]
    fn the_default_output_is_beside_the_input() {
        assert_eq!(
            default_out(Path::new("d/run.mcap")),
            Path::new("d/run.repaired.mcap")
        );
        assert_eq!(
            default_out(Path::new("log")),
            Path::new("log.repaired.mcap")
        );
    }
}
