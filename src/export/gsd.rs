//! HOOMD GSD frames through the `hoomd-gsd` crate (by the HOOMD authors), in
//! HOOMD's schema (version 1.4): per frame `configuration/step` (the frame's
//! number), `configuration/dimensions` = 2, `configuration/box` = [L_x, L_y, 1,
//! 0, 0, 0], and N, `particles/types` (species names), `typeid`, `mass`,
//! `diameter` (2a), `position` and `velocity` (float32, z = 0), `image` (the
//! periodic images of logs of format 2.1 on), plus the simulated time as
//! `log/carom/time` (float64).
//!
//! HOOMD's box spans [−L/2, L/2): positions are shifted, x_HOOMD = x − L/2. A
//! shifted coordinate that rounds to L/2 in float32 is wrapped to −L/2 on a
//! periodic axis (the same point, its image one higher) and moved one float32 step
//! inside by a wall. The unwrapped position is x_HOOMD + image · L, as in HOOMD.

use std::path::{Path, PathBuf};

use carom_log::Snapshot;
use hoomd_gsd::file_layer::GsdFile;

use super::type_name;
use crate::frames::FrameError;

/// Bytes of a type name in `particles/types` (NUL-padded).
const NAME_BYTES: usize = 16;

/// A GSD file being written.
pub struct GsdWriter {
    file: GsdFile,
    path: PathBuf,
    frame: u64,
}

/// The error `e` and its causes, in words.
fn reason(e: &(dyn std::error::Error + 'static)) -> String {
    let mut text = e.to_string();
    let mut source = e.source();
    while let Some(s) = source {
        text.push_str(": ");
        text.push_str(&s.to_string());
        source = s.source();
    }
    text
}

/// `x` (in [0, l)) in HOOMD's centred coordinates, as float32 inside [−l/2, l/2).
pub fn centred(x: f64, l: f64, periodic: bool) -> f32 {
    let half = (l / 2.0) as f32;
    let c = (x - l / 2.0) as f32;
    if c < half {
        c
    } else if periodic {
        -half
    } else {
        f32::from_bits(half.to_bits() - 1)
    }
}

impl GsdWriter {
    /// Create (or overwrite) `path`.
    pub fn create(path: &Path) -> Result<GsdWriter, FrameError> {
        let app = format!("carom {}", env!("CARGO_PKG_VERSION"));
        let file = GsdFile::create(path, &app, "hoomd", (1, 4)).map_err(|e| FrameError::Write {
            file: path.display().to_string(),
            reason: reason(&e),
        })?;
        Ok(GsdWriter {
            file,
            path: path.to_path_buf(),
            frame: 0,
        })
    }

    fn error(&self, e: &(dyn std::error::Error + 'static)) -> FrameError {
        FrameError::Write {
            file: self.path.display().to_string(),
            reason: reason(e),
        }
    }

    /// Append `s` as a frame.
    pub fn write(&mut self, s: &Snapshot) -> Result<(), FrameError> {
        self.write_chunks(s).map_err(|e| self.error(&*e))?;
        self.frame += 1;
        Ok(())
    }

    fn write_chunks(&mut self, s: &Snapshot) -> Result<(), Box<dyn std::error::Error>> {
        let f = &mut self.file;
        let (l, n) = (s.box_size, s.positions.len());
        let periodic = [s.boundary[0] == 0, s.boundary[1] == 0];
        let radius = |i: usize| {
            s.species_radius
                .get(usize::from(s.species[i]))
                .copied()
                .unwrap_or(0.0)
        };
        let mass = |i: usize| {
            s.species_mass
                .get(usize::from(s.species[i]))
                .copied()
                .unwrap_or(0.0)
        };
        f.write_scalars("configuration/step", [self.frame])?;
        f.write_scalars("configuration/dimensions", [2u8])?;
        f.write_scalars(
            "configuration/box",
            [l.x as f32, l.y as f32, 1.0, 0.0, 0.0, 0.0],
        )?;
        f.write_scalars("particles/N", [u32::try_from(n)?])?;
        f.write_arrays(
            "particles/types",
            (0..s.species_radius.len()).map(|k| {
                let name = type_name(k);
                std::array::from_fn::<u8, NAME_BYTES, _>(|b| {
                    name.as_bytes()
                        .get(b)
                        .copied()
                        .filter(|_| b < NAME_BYTES - 1)
                        .unwrap_or(0)
                })
            }),
        )?;
        f.write_scalars("particles/typeid", s.species.iter().map(|&k| u32::from(k)))?;
        f.write_scalars("particles/mass", (0..n).map(|i| mass(i) as f32))?;
        f.write_scalars(
            "particles/diameter",
            (0..n).map(|i| (2.0 * radius(i)) as f32),
        )?;
        f.write_arrays(
            "particles/position",
            s.positions.iter().map(|p| {
                [
                    centred(p.x, l.x, periodic[0]),
                    centred(p.y, l.y, periodic[1]),
                    0.0f32,
                ]
            }),
        )?;
        if s.images.len() == n {
            // One more image where `centred` wrapped L/2 to −L/2.
            let image = |x: f64, l: f64, periodic: bool, m: i32| {
                m + i32::from(periodic && centred(x, l, periodic) < ((x - l / 2.0) as f32))
            };
            f.write_arrays(
                "particles/image",
                s.positions.iter().zip(&s.images).map(|(p, m)| {
                    [
                        image(p.x, l.x, periodic[0], m[0]),
                        image(p.y, l.y, periodic[1], m[1]),
                        0i32,
                    ]
                }),
            )?;
        }
        f.write_arrays(
            "particles/velocity",
            s.velocities
                .iter()
                .map(|v| [v.x as f32, v.y as f32, 0.0f32]),
        )?;
        f.write_scalars("log/carom/time", [s.time])?;
        f.end_frame()?;
        Ok(())
    }

    /// Write everything to the file.
    pub fn finish(mut self) -> Result<(), FrameError> {
        self.file.sync_all().map_err(|e| self.error(&e))
    }
}

#[cfg(test)]
mod tests {
    use super::centred;

    #[test]
    fn centred_coordinates_stay_inside_hoomds_box() {
        assert_eq!(centred(0.0, 10.0, true), -5.0);
        assert_eq!(centred(7.5, 10.0, true), 2.5);
        // Just below L: rounds to L/2 in float32, which is −L/2 periodically.
        let x = 10.0 - 1e-12;
        assert_eq!(centred(x, 10.0, true), -5.0);
        let inside = centred(x, 10.0, false);
        assert!(inside < 5.0 && inside > 4.99999);
    }
}
