//! Handing control back during long stretches of unobservable work.
//!
//! Thermostat events and growth rescales are handled inside
//! [`Engine::next_event`] without being reported, so a thermostat of huge rate or
//! a rescale interval of 10⁻⁹ could keep one call busy for hours, and the caller
//! could neither stop nor show progress. The engine counts that work in disc
//! updates (one per Andersen redraw, N per driving kick or rescale) and, each
//! time the count passes a multiple of [`PAUSE_WORK`], returns an
//! [`Event::Pause`] at the current time.
//! A pause changes nothing: the next call goes on exactly where this one stopped.
//! The count is not part of a checkpoint, since nothing depends on it.

use super::Engine;
use crate::event::Event;

/// Disc updates of unobservable work between pauses: about 0.1 s of work.
pub(super) const PAUSE_WORK: u64 = 1 << 20;

impl Engine {
    /// Count `discs` disc updates of unobservable work; whether a pause is due.
    #[inline]
    pub(super) fn quiet_work(&mut self, discs: usize) -> bool {
        let before = self.quiet_work;
        self.quiet_work = before.wrapping_add(discs as u64);
        before / PAUSE_WORK != self.quiet_work / PAUSE_WORK
    }

    /// The pause event, at the current time.
    pub(super) fn pause(&self) -> Option<Event> {
        Some(Event::Pause {
            time: self.reported,
        })
    }
}
