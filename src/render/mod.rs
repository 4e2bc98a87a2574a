//! Pictures of a run (`carom render`): one snapshot as PNG or SVG, or a range of
//! snapshots as an animated GIF, drawn with plotters (text in DejaVu Sans,
//! embedded, so no system fonts are needed).
//!
//! `layout` places the box in the image, `colours` holds the species palette and
//! the speed map, `draw` draws one snapshot. A movie keeps one frame's pixels in
//! memory and appends each frame to the GIF as it is drawn, so memory does not grow
//! with the number of frames; its speed scale is fixed by the first frame, so a
//! cooling gas darkens from frame to frame.

mod colours;
mod draw;
mod layout;
mod raster;

use colours::speed_scale;
use draw::{draw_snapshot, Colouring, DiscStyle};
pub use layout::Layout;

use std::path::Path;
use std::sync::Once;

use carom_log::Snapshot;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters_backend::DrawingErrorKind;

use crate::frames::FrameError;

/// What the discs are coloured by.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ColourBy {
    /// Species (a fixed palette).
    Species,
    /// Speed (the viridis map with a colour bar).
    Speed,
    /// The local bond order |ψ6| (viridis from 0 to 1, with a colour bar).
    Psi6,
    /// The phase of ψ6, arg ψ6 / 6 ∈ (−30°, 30°] (a colour wheel, with a bar).
    Psi6Phase,
}

impl ColourBy {
    /// Whether the picture has a colour bar.
    pub fn has_bar(self) -> bool {
        self != ColourBy::Species
    }
}

/// The colouring of `s` by `by`: a speed scale from `s`'s own speeds.
pub fn colouring_for(s: &Snapshot, by: ColourBy) -> Colouring {
    match by {
        ColourBy::Species => Colouring::Species,
        ColourBy::Speed => {
            let mut v: Vec<f64> = s.velocities.iter().map(|v| v.length()).collect();
            Colouring::Speed {
                max: speed_scale(&mut v),
            }
        }
        ColourBy::Psi6 => Colouring::Psi6,
        ColourBy::Psi6Phase => Colouring::Psi6Phase,
    }
}

/// Register the embedded font (DejaVu Sans as "sans-serif") with plotters, once:
/// every figure carom draws uses it.
pub fn register_font() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        // The bytes are a valid font shipped by the `dejavu` crate.
        let _ = plotters::style::register_font(
            "sans-serif",
            FontStyle::Normal,
            dejavu::sans::regular(),
        );
    });
}

/// A picture that could not be drawn or written, naming the file and the reason
/// (the operating system's reason for a write error).
fn write_error<E: std::error::Error + Send + Sync + 'static>(
    path: &Path,
    e: DrawingAreaErrorKind<E>,
) -> FrameError {
    let reason = drawing_error_reason(&e);
    FrameError::Write {
        file: path.display().to_string(),
        reason,
    }
}

/// Why plotters could not draw or write a picture, in words (the operating
/// system's reason for a write error); every figure carom writes reports this.
pub fn drawing_error_reason<E: std::error::Error + Send + Sync + 'static>(
    e: &DrawingAreaErrorKind<E>,
) -> String {
    match e {
        DrawingAreaErrorKind::BackendError(DrawingErrorKind::DrawingError(b)) => backend_reason(b),
        other => other.to_string(),
    }
}

/// The bitmap backend prints its errors as Rust debug text: its I/O and encoding
/// errors are unwrapped into words.
fn backend_reason(e: &(dyn std::error::Error + 'static)) -> String {
    type B = <BitMapBackend<'static> as DrawingBackend>::ErrorType;
    match e.downcast_ref::<B>() {
        Some(B::IOError(io)) => io.to_string(),
        Some(B::ImageError(image)) => image.to_string(),
        Some(B::InvalidBuffer) => "invalid pixel buffer".to_owned(),
        Some(B::GifEncodingError(g)) => g.to_string(),
        _ => e.to_string(),
    }
}

/// The image formats of a single picture.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ImageFormat {
    /// PNG (bitmap).
    Png,
    /// SVG (vector).
    Svg,
}

/// Draw `s` into the file `out` as `format`, `width` pixels wide. Returns the
/// layout used. A file that could not be written is removed.
pub fn render_snapshot(
    s: &Snapshot,
    out: &Path,
    format: ImageFormat,
    width: u32,
    by: ColourBy,
) -> Result<Layout, FrameError> {
    register_font();
    let colouring = colouring_for(s, by);
    let layout = Layout::new(width, s.box_size, by.has_bar());
    let result = match format {
        ImageFormat::Png => {
            let (w, h) = layout.size;
            let mut rgb = vec![0u8; 3 * w as usize * h as usize];
            {
                let area = BitMapBackend::with_buffer(&mut rgb, layout.size).into_drawing_area();
                draw_snapshot(&area, s, &layout, colouring, DiscStyle::Raster)
                    .and_then(|()| area.present())
                    .map_err(|e| write_error(out, e))?;
            }
            write_png(out, &rgb, layout.size)
        }
        ImageFormat::Svg => {
            let area = SVGBackend::new(out, layout.size).into_drawing_area();
            draw_snapshot(&area, s, &layout, colouring, DiscStyle::Vector)
                .and_then(|()| area.present())
                .map_err(|e| write_error(out, e))
        }
    };
    if result.is_err() {
        crate::frames::remove_output(out);
    }
    result.map(|()| layout)
}

/// Write `rgb` as a PNG at the best compression (an anti-aliased picture of
/// 10⁴ discs, 800 pixels wide: 1.2 MB against 1.6 MB by default).
fn write_png(out: &Path, rgb: &[u8], (w, h): (u32, u32)) -> Result<(), FrameError> {
    use image::codecs::png::{CompressionType, FilterType, PngEncoder};
    use image::ImageEncoder;
    let error = |reason: String| FrameError::Write {
        file: out.display().to_string(),
        reason,
    };
    let file = std::fs::File::create(out).map_err(|e| error(e.to_string()))?;
    let mut writer = std::io::BufWriter::new(file);
    PngEncoder::new_with_quality(&mut writer, CompressionType::Best, FilterType::Adaptive)
        .write_image(rgb, w, h, image::ColorType::Rgb8)
        .map_err(|e| error(e.to_string()))?;
    use std::io::Write;
    writer.flush().map_err(|e| error(e.to_string()))
}

/// An animated GIF being written frame by frame.
pub struct Movie {
    area: DrawingArea<BitMapBackend<'static>, Shift>,
    layout: Layout,
    colouring: Colouring,
    path: std::path::PathBuf,
}

impl Movie {
    /// Start a movie in `out`, `width` pixels wide, showing each frame for
    /// `delay_ms`; its layout and speed scale come from `first` (which is not yet
    /// drawn: push it too).
    pub fn create(
        out: &Path,
        first: &Snapshot,
        width: u32,
        by: ColourBy,
        delay_ms: u32,
    ) -> Result<Movie, FrameError> {
        register_font();
        let layout = Layout::new(width, first.box_size, by.has_bar());
        let backend = BitMapBackend::gif(out, layout.size, delay_ms).map_err(|e| {
            crate::frames::remove_output(out);
            FrameError::Write {
                file: out.display().to_string(),
                reason: backend_reason(&e),
            }
        })?;
        Ok(Movie {
            area: backend.into_drawing_area(),
            layout,
            colouring: colouring_for(first, by),
            path: out.to_path_buf(),
        })
    }

    /// Draw `s` as the next frame.
    pub fn push(&mut self, s: &Snapshot) -> Result<(), FrameError> {
        draw_snapshot(
            &self.area,
            s,
            &self.layout,
            self.colouring,
            DiscStyle::Raster,
        )
        .and_then(|()| self.area.present())
        .map_err(|e| write_error(&self.path, e))
    }

    /// The layout of every frame.
    pub fn layout(&self) -> &Layout {
        &self.layout
    }
}

#[cfg(test)]
mod tests;
