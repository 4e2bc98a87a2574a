//! Extended XYZ frames (the format OVITO reads; ASE parses the header but wants
//! chemical symbols as species): per frame a line with N, a comment line of
//! key=value pairs, then one line per disc:
//!
//! ```text
//! 3
//! Lattice="Lx 0 0 0 Ly 0 0 0 1" Properties=species:S:1:pos:R:3:velo:R:3:radius:R:1:mass:R:1 Time=t pbc="T T F"
//! A x y 0 vx vy 0 a m
//! ```
//!
//! Positions are carom's box coordinates in [0, L) (the lattice's origin is 0),
//! every number printed as the shortest text that reads back as the same f64.
//! `pbc` is T for a periodic axis, F for walls (and for z, which has thickness 1).

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

use carom_log::Snapshot;

use super::type_name;
use crate::frames::FrameError;

/// An extended XYZ file being written.
pub struct XyzWriter {
    out: BufWriter<File>,
    path: PathBuf,
    names: Vec<String>,
    line: String,
}

fn io_error(path: &Path, e: std::io::Error) -> FrameError {
    FrameError::Write {
        file: path.display().to_string(),
        reason: e.to_string(),
    }
}

impl XyzWriter {
    /// Create (or overwrite) `path`.
    pub fn create(path: &Path) -> Result<XyzWriter, FrameError> {
        let file = File::create(path).map_err(|e| io_error(path, e))?;
        Ok(XyzWriter {
            out: BufWriter::with_capacity(1 << 20, file),
            path: path.to_path_buf(),
            names: Vec::new(),
            line: String::new(),
        })
    }

    /// The comment line of `s`.
    pub fn comment(s: &Snapshot) -> String {
        let pbc = |b: u8| if b == 0 { "T" } else { "F" };
        format!(
            "Lattice=\"{} 0 0 0 {} 0 0 0 1\" \
             Properties=species:S:1:pos:R:3:velo:R:3:radius:R:1:mass:R:1 \
             Time={} pbc=\"{} {} F\"",
            s.box_size.x,
            s.box_size.y,
            s.time,
            pbc(s.boundary[0]),
            pbc(s.boundary[1])
        )
    }

    /// Append `s` as a frame.
    pub fn write(&mut self, s: &Snapshot) -> Result<(), FrameError> {
        use std::fmt::Write as _;
        while self.names.len() < s.species_radius.len() {
            self.names.push(type_name(self.names.len()));
        }
        let n = s.positions.len();
        let head = format!("{n}\n{}\n", Self::comment(s));
        self.out
            .write_all(head.as_bytes())
            .map_err(|e| io_error(&self.path, e))?;
        for i in 0..n {
            let k = usize::from(s.species[i]);
            let (p, v) = (s.positions[i], s.velocities[i]);
            let (a, m) = (
                s.species_radius.get(k).copied().unwrap_or(f64::NAN),
                s.species_mass.get(k).copied().unwrap_or(f64::NAN),
            );
            let name = self.names.get(k).map_or("?", String::as_str);
            self.line.clear();
            let _ = writeln!(
                self.line,
                "{name} {} {} 0 {} {} 0 {a} {m}",
                p.x, p.y, v.x, v.y
            );
            self.out
                .write_all(self.line.as_bytes())
                .map_err(|e| io_error(&self.path, e))?;
        }
        Ok(())
    }

    /// Flush everything to the file, and a regular file to its disk (a device or
    /// a pipe, such as /dev/null, has no disk to sync: Linux refuses with EINVAL).
    pub fn finish(mut self) -> Result<(), FrameError> {
        self.out.flush().map_err(|e| io_error(&self.path, e))?;
        let file = self.out.get_ref();
        if file.metadata().is_ok_and(|m| m.is_file()) {
            file.sync_all().map_err(|e| io_error(&self.path, e))?;
        }
        Ok(())
    }
}
