//! Export of a log's snapshots to the formats of other tools (`carom export`):
//! HOOMD's GSD (`gsd`: HOOMD-blue, freud, OVITO, the `gsd` Python package) and
//! extended XYZ (`xyz`: OVITO). One frame per kept `/snapshot` (see
//! [`crate::frames`]), written as it is read, so memory stays one snapshot.
//!
//! Species k is the particle type named by [`type_name`] ("A", "B", …): carom's
//! species have no names of their own. Positions keep all of f64 in XYZ; GSD
//! stores float32 (HOOMD's schema), about 7 significant digits.

mod gsd;
mod xyz;

pub use gsd::GsdWriter;
pub use xyz::XyzWriter;

use std::path::Path;

use carom_log::{ReadProgress, Snapshot};

use crate::frames::{for_each_frame, FrameCount, FrameError, FrameRange};

/// The name of species `k` as a particle type: "A" … "Z", then "T26", "T27", ….
pub fn type_name(k: usize) -> String {
    match u8::try_from(k) {
        Ok(b) if b < 26 => char::from(b'A' + b).to_string(),
        _ => format!("T{k}"),
    }
}

/// The export formats.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ExportFormat {
    /// HOOMD's GSD.
    Gsd,
    /// Extended XYZ.
    Xyz,
}

impl ExportFormat {
    /// The usual file extension.
    pub fn extension(self) -> &'static str {
        match self {
            ExportFormat::Gsd => "gsd",
            ExportFormat::Xyz => "xyz",
        }
    }
}

/// A file that takes frames one by one.
trait FrameSink {
    fn frame(&mut self, s: &Snapshot) -> Result<(), FrameError>;
    fn finish(self: Box<Self>) -> Result<(), FrameError>;
}

impl FrameSink for GsdWriter {
    fn frame(&mut self, s: &Snapshot) -> Result<(), FrameError> {
        self.write(s)
    }
    fn finish(self: Box<Self>) -> Result<(), FrameError> {
        GsdWriter::finish(*self)
    }
}

impl FrameSink for XyzWriter {
    fn frame(&mut self, s: &Snapshot) -> Result<(), FrameError> {
        self.write(s)
    }
    fn finish(self: Box<Self>) -> Result<(), FrameError> {
        XyzWriter::finish(*self)
    }
}

/// Export the snapshots of `log` that `range` keeps into `out` as `format`,
/// telling `progress` how far reading has got. The output is created when the
/// first frame is found and removed again if the export fails.
pub fn export(
    log: &Path,
    out: &Path,
    format: ExportFormat,
    range: FrameRange,
    progress: &mut dyn FnMut(ReadProgress),
) -> Result<FrameCount, FrameError> {
    let mut sink: Option<Box<dyn FrameSink>> = None;
    let result = for_each_frame(log, range, progress, &mut |s| {
        if sink.is_none() {
            sink = Some(match format {
                ExportFormat::Gsd => Box::new(GsdWriter::create(out)?),
                ExportFormat::Xyz => Box::new(XyzWriter::create(out)?),
            });
        }
        sink.as_mut().map_or(Ok(()), |k| k.frame(s))
    });
    let result = result.and_then(|count| match sink.take() {
        Some(k) => k.finish().map(|()| count),
        None => Ok(count),
    });
    if result.is_err() {
        drop(sink);
        crate::frames::remove_output(out);
    }
    result
}

#[cfg(test)]
mod tests {
    use super::type_name;

    #[test]
    fn species_are_named_by_letters() {
        assert_eq!(type_name(0), "A");
        assert_eq!(type_name(1), "B");
        assert_eq!(type_name(25), "Z");
        assert_eq!(type_name(26), "T26");
        assert_eq!(type_name(300), "T300");
    }
}
