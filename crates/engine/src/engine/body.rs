//! A disc's record: everything the event loop touches for one disc in one cache
//! line, and the typed fields of its pending event.
//!
//! The record holds the disc's straight path r(t) = r0 + v t (physics.md §1, the
//! last-update time folded into the origin r0), its collision counter, its pair
//! candidate, its pending event ([`Pending`], with the wall or cell face, the
//! candidate's periodic image and whether the disc rests on the floor packed into
//! one byte, [`Aux`]) and that event's
//! time, its species and its place in the cell lists. At large N every event lands
//! at a random place in memory, so one 64-byte record per disc saves a cache miss
//! per lookup. See docs/performance.md, "disc record".

use crate::cells::{Link, Member};
use crate::memory;
use crate::queue::EventTimes;
use carom_core::DVec2;

/// Everything the event loop touches for one disc, in one 64-byte cache line: its
/// straight path (origin and velocity), collision counter, pair candidate, pending
/// event and its time, species, and its place in the cell lists. At large N every
/// event lands at a random place in memory, so keeping these together saves a cache
/// miss per lookup, and a scan walking a cell's list reads nothing but the records
/// it tests.
///
/// The path is stored as its origin `r0`, the position the disc would have had at
/// internal time 0 on its current velocity: its position at time t is `r0 + v t`
/// (physics.md §1). Its rounding is that of positions of the size of |r0| + |v t|,
/// the same order as the rounding of event times (≈ ulp(t)·|v|) that the clock's
/// restarts at each renumbering keep small.
#[derive(Debug, Clone, Copy, PartialEq)]
#[repr(C, align(64))]
pub(super) struct Body {
    /// Path origin: the position at internal time 0 on the current velocity
    /// (length; may lie outside the box).
    pub(super) r0: DVec2,
    /// Velocity (length/time).
    pub(super) v: DVec2,
    /// Time of the pending event, the queue's key (time; +∞ if none; changed only
    /// through [`crate::queue::EventQueue::set`]). For a pair event it is the pair
    /// candidate's time; when a crossing or wall comes first the candidate's time is
    /// not kept (see [`crate::engine::Engine::predict_after_crossing`]).
    pub(super) event_time: f64,
    /// Collision counter: bumped on every velocity change and periodic wrap.
    pub(super) count: u32,
    /// Partner of the pair candidate ([`crate::NO_DISC`] if none).
    pub(super) partner: u32,
    /// Partner's collision counter when the candidate was found.
    pub(super) partner_count: u32,
    /// Which event is pending (pair = the candidate).
    pub(super) pending: Pending,
    /// The face of the boundary event, the candidate's periodic image, and
    /// whether the disc rests on the floor (engine::resting).
    pub(super) aux: Aux,
    /// Species index.
    pub(super) species: u16,
    /// Cell and next disc of the cell's list (see [`crate::cells`]).
    pub(super) link: Link,
}

impl Body {
    /// Position at internal time `t` (length), not wrapped into the box.
    #[inline(always)]
    pub(super) fn at(&self, t: f64) -> DVec2 {
        self.r0 + self.v * t
    }

    /// Set the velocity to `v` at internal time `now`, keeping the position there:
    /// the path origin moves by (v_old − v) now.
    #[inline]
    pub(super) fn set_velocity(&mut self, v: DVec2, now: f64) {
        self.r0 = origin_after((self.r0, self.v), v, now);
        self.v = v;
    }
}

/// The origin (length) of a path (origin, velocity) = `path` once its velocity is
/// set to `v` at internal time `now` ([`Body::set_velocity`]).
#[inline(always)]
pub(super) fn origin_after((r0, v0): (DVec2, DVec2), v: DVec2, now: f64) -> DVec2 {
    r0 + (v0 - v) * now
}

/// The queue reads each disc's event time from its record, which the event reads
/// anyway: a separate array of times cost a cache miss per disc an event touches at
/// large N.
impl EventTimes for [Body] {
    #[inline(always)]
    fn time(&self, i: u32) -> f64 {
        self[i as usize].event_time
    }
    #[inline(always)]
    fn store(&mut self, i: u32, t: f64) {
        self[i as usize].event_time = t;
    }
    #[inline(always)]
    fn prefetch(&self, i: u32) {
        memory::prefetch_at(self, i as usize);
    }
}

impl Member for Body {
    #[inline(always)]
    fn link(&self) -> &Link {
        &self.link
    }
    #[inline(always)]
    fn link_mut(&mut self) -> &mut Link {
        &mut self.link
    }
}

const _: () = assert!(
    std::mem::size_of::<Body>() == 64,
    "Body must fill one cache line"
);

/// Which event a disc has pending. The discriminants are the kinds a
/// [`crate::Checkpoint`] stores.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[repr(u8)]
pub(super) enum Pending {
    /// No event (time +∞: the disc is at rest in a closed box, or alone).
    None = 0,
    /// A collision with the pair candidate.
    Pair = 1,
    /// A wall collision.
    Wall = 2,
    /// A cell crossing.
    Cell = 3,
    /// Search again for a floor contact (engine::floor): the search stopped at its
    /// step limit without finding one.
    Recheck = 4,
    /// Leaving the neighbour-list skin (engine::listed): renew the disc's list.
    Skin = 5,
}

impl Pending {
    /// The kind with checkpoint code `code`, if it is one carom writes.
    pub(super) fn from_code(code: u32) -> Option<Pending> {
        [
            Pending::None,
            Pending::Pair,
            Pending::Wall,
            Pending::Cell,
            Pending::Recheck,
            Pending::Skin,
        ]
        .into_iter()
        .find(|&p| p as u32 == code)
    }
}

/// A face of a disc's cell or box, crossed or hit along axis k, on the high side
/// (or upwards) or the low one; stored as 2 k + high.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct Face(u8);

impl Face {
    /// The face along axis `k`, on the high side if `high`.
    #[inline(always)]
    pub(super) fn new(k: usize, high: bool) -> Face {
        Face((2 * k) as u8 + high as u8)
    }

    /// The axis normal to the face (0 = x, 1 = y).
    #[inline(always)]
    pub(super) fn axis(self) -> usize {
        (self.0 / 2) as usize
    }

    /// Whether it is the high-side face (crossed upwards).
    #[inline(always)]
    pub(super) fn high(self) -> bool {
        self.0 % 2 == 1
    }
}

/// The periodic image through which a partner is seen, shifted by (s_x L_x, s_y
/// L_y) with s ∈ {−1, 0, 1}; stored as (s_x + 1) + 3 (s_y + 1).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct Image(u8);

impl Image {
    /// The partner itself, unshifted.
    pub(super) const SAME: Image = Image(4);
    /// What a disc without a pair candidate stores (read as no image).
    pub(super) const UNSET: Image = Image(0);

    /// The image shifted by (`sx` L_x, `sy` L_y).
    #[inline(always)]
    pub(super) fn new(sx: i32, sy: i32) -> Image {
        Image(((sx + 1) + 3 * (sy + 1)) as u8)
    }

    /// The image with code `code` = (s_x + 1) + 3 (s_y + 1) (as a neighbour list
    /// stores it).
    #[inline(always)]
    pub(super) fn from_code(code: u8) -> Image {
        Image(code)
    }

    /// Its code (s_x + 1) + 3 (s_y + 1).
    #[inline(always)]
    pub(super) fn code(self) -> u8 {
        self.0
    }

    /// The shift (length) in a box of edges `size`.
    #[inline]
    pub(super) fn shift(self, size: DVec2) -> DVec2 {
        let sx = (self.0 % 3) as f64 - 1.0;
        let sy = (self.0 / 3) as f64 - 1.0;
        DVec2::new(sx * size.x, sy * size.y)
    }
}

/// The pending event's face (bits 0–1; a wall or cell event), the pair
/// candidate's image (bits 2–5) and, in a field, whether the disc rests on the
/// floor (bit 6; engine::resting), in the one byte the record has for them.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct Aux(u8);

/// The bit of [`Aux`] set while the disc rests on the floor.
const RESTING: u8 = 1 << 6;

impl Aux {
    /// Face 0, no image, not resting: what a record starts with.
    pub(super) const EMPTY: Aux = Aux(0);

    /// The byte for `face` and `image` (not resting).
    #[inline(always)]
    pub(super) fn new(face: Face, image: Image) -> Aux {
        Aux(face.0 | image.0 << 2)
    }

    /// The face of the boundary event.
    #[inline(always)]
    pub(super) fn face(self) -> Face {
        Face(self.0 & 3)
    }

    /// The pair candidate's image.
    #[inline(always)]
    pub(super) fn image(self) -> Image {
        Image((self.0 >> 2) & 0xf)
    }

    /// Whether the disc rests on the floor (engine::resting).
    #[inline(always)]
    pub(super) fn resting(self) -> bool {
        self.0 & RESTING != 0
    }

    /// The same byte, resting on the floor or not as `resting` says.
    #[inline(always)]
    pub(super) fn with_resting(self, resting: bool) -> Aux {
        Aux((self.0 & !RESTING) | (resting as u8) << 6)
    }

    /// The face and image bits (0–5) as a checkpoint stores them; the resting bit
    /// is stored apart (engine::checkpoint).
    pub(super) fn event_bits(self) -> u8 {
        self.0 & !RESTING
    }

    /// The value of a checkpoint's face and image bits (0–5), not resting.
    pub(super) fn from_event_bits(bits: u8) -> Aux {
        Aux(bits & !RESTING)
    }
}
