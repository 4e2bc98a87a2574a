//! The event loop and the public calls that drive it.
//!
//! Each turn of the loop is dispatch only: upkeep (look-ahead tuning, the
//! renumbering), then the earlier of the next internal instant and the discs' own
//! events in the queue, handled by one function each. The caller's scheduled events
//! and the thermostat's events (§16) share one calendar (engine/calendar.rs), which
//! also weighs the growth's rescales and end (§17). A disc's event is a pair
//! collision (§2–§4), a wall hit, a cell crossing (on neighbour lists a skin exit,
//! engine::listed), or a prediction found obsolete or a floor search resumed,
//! recomputed; crossings, skin exits and recomputations are not
//! reported, and the loop turns until something observable happens. Compiled once
//! per law of motion (engine::motion).

use super::body::Pending;
use super::calendar::{Due, Whose};
use super::clock::reorder_interval;
use super::motion::{Falling, Growing, Listed, Motion, Straight};
use super::Engine;
use crate::error::EngineError;
use crate::event::Event;
use crate::memory;

/// What one turn of the loop found.
enum Step {
    /// Return this to the caller.
    Report(Option<Event>),
    /// Nothing observable: turn again.
    Continue,
}

impl Engine {
    /// Ask for an [`Event::Scheduled`] with `tag` at time `time` (≥ now). Events at the
    /// same time are delivered in the order they were scheduled, before any collision
    /// at that time. Every tag is the caller's: the engine's own instants are
    /// not tagged (engine::calendar).
    pub fn schedule(&mut self, time: f64, tag: u64) -> Result<(), EngineError> {
        self.push_calendar(time, Whose::Caller(tag))
    }

    /// An entry of the calendar at `time`, which must be finite and not past.
    pub(super) fn push_calendar(&mut self, time: f64, whose: Whose) -> Result<(), EngineError> {
        if time.is_nan() || time < self.reported || time.is_infinite() {
            return Err(EngineError::ScheduleInPast {
                time,
                now: self.reported,
            });
        }
        self.calendar.push(time, whose);
        Ok(())
    }

    /// Whether the stop of a `run_until` is still to come (after a pause: a
    /// pause without it is the stop itself).
    pub(super) fn stop_pending(&self) -> bool {
        self.calendar.holds(Whose::Stop)
    }

    /// Forget a `run_until`'s stop (the call ends, early on an error).
    pub(super) fn drop_stop(&mut self) {
        self.calendar.drop(Whose::Stop);
    }

    /// Process events until the next observable one and return it; `None` when
    /// nothing will ever happen again (all discs at rest and nothing scheduled).
    /// After long unobservable work (thermostat events, growth rescales) it returns
    /// an [`Event::Pause`], so that the caller can stop or report progress
    /// (`engine::pause`), and once when an overflowing neighbour list sends the run
    /// back to cells (engine::listed); just call again.
    ///
    /// Cell crossings are not observable, so in a system whose discs move but never
    /// collide again (a lone disc in a periodic box) this call returns only at the
    /// next scheduled event: schedule a stop ([`Engine::schedule`], or use
    /// [`Engine::run_until`]) rather than waiting for collisions that never come.
    pub fn next_event(&mut self) -> Result<Option<Event>, EngineError> {
        if self.params.gravity != 0.0 || self.params.floor.is_some() {
            self.next_event_falling()
        } else if self.params.growth.rate != 0.0 || self.lists.is_some() {
            self.next_event_other()
        } else {
            self.next_event_in::<Straight>()
        }
    }

    /// [`Engine::next_event`] with growing discs or on neighbour lists
    /// (engine::listed), each a copy of the loop of its own like
    /// [`Engine::next_event_falling`].
    #[inline(never)]
    fn next_event_other(&mut self) -> Result<Option<Event>, EngineError> {
        if self.lists.is_some() {
            self.next_event_in::<Listed>()
        } else {
            self.next_event_growing()
        }
    }

    /// [`Engine::next_event`] in a field (engine::motion::Falling): a copy of the
    /// loop of its own, so that the loop without one is compiled as if fields did
    /// not exist.
    #[cold]
    #[inline(never)]
    fn next_event_falling(&mut self) -> Result<Option<Event>, EngineError> {
        self.next_event_in::<Falling>()
    }

    /// [`Engine::next_event`] with growing discs (engine::growth), a copy of the
    /// loop of its own like [`Engine::next_event_falling`].
    #[cold]
    #[inline(never)]
    pub(super) fn next_event_growing(&mut self) -> Result<Option<Event>, EngineError> {
        self.next_event_in::<Growing>()
    }

    /// [`Engine::next_event`] with the discs moving by the law `M`
    /// (engine::motion), compiled once per law: upkeep, then the earlier of the
    /// calendar's instants (engine::calendar) and the discs' own events, each
    /// handled by its own function.
    #[inline(always)]
    fn next_event_in<M: Motion>(&mut self) -> Result<Option<Event>, EngineError> {
        loop {
            self.upkeep();
            let (t, who) = self.queue.peek(self.bodies.as_slice());
            self.fetch_ahead();
            let t = t.into_inner();
            let step = match self.calendar_due::<M>(t) {
                Some(Due::Growth(due)) => self.growth_step(due),
                Some(Due::Entry {
                    ts,
                    internal,
                    whose,
                }) => self.entry_step(ts, internal, whose)?,
                None => self.disc_step::<M>(t, who)?,
            };
            if let Step::Report(ev) = step {
                return Ok(ev);
            }
        }
    }

    /// Between events: time the look-ahead from time to time, and renumber the
    /// discs (restarting the clock) when due.
    #[inline(always)]
    fn upkeep(&mut self) {
        self.tuner.left -= 1;
        if self.tuner.left == 0 {
            self.tune_look_ahead();
        }
        if self.stats.pair_collisions >= self.next_reorder {
            // The renumbering is not the look-ahead's doing: leave its time out
            // of the tuner's window.
            let started = self.tuner.active().then(std::time::Instant::now);
            self.reorder();
            if let Some(t) = started {
                self.tuner.exclude(t.elapsed());
            }
            self.next_reorder += reorder_interval(self.len());
        }
    }

    /// Start fetching the records (and cell coordinates) of the likely next
    /// events while this one is processed: at large N each is a cache miss. A
    /// prefetch hint only; nothing depends on it.
    #[inline(always)]
    fn fetch_ahead(&mut self) {
        for d in self.queue.upcoming() {
            if let Some(b) = self.bodies.get(d as usize) {
                memory::prefetch(b);
            }
        }
        if self.look_ahead && self.queue.moved_on() {
            self.look_ahead();
        }
    }

    /// The growth's instant at internal time `due` (engine::growth).
    #[inline(always)]
    fn growth_step(&mut self, due: f64) -> Step {
        self.move_clock(due);
        if self.growth_event() {
            Step::Report(self.pause())
        } else {
            Step::Continue
        }
    }

    /// The calendar's entry at time `ts` (internal time `internal`): the
    /// thermostat's is handled here, the caller's reported.
    #[inline(always)]
    fn entry_step(&mut self, ts: f64, internal: f64, whose: Whose) -> Result<Step, EngineError> {
        self.calendar.pop();
        self.move_clock(internal);
        self.reported = self.reported.max(ts);
        match whose {
            Whose::Thermostat => Ok(if self.thermostat_event()? {
                Step::Report(self.pause())
            } else {
                Step::Continue
            }),
            Whose::Caller(tag) => Ok(Step::Report(Some(Event::Scheduled {
                time: self.reported,
                tag,
            }))),
            Whose::Stop => Ok(Step::Report(Some(Event::Pause {
                time: self.reported,
            }))),
        }
    }

    /// Disc `who`'s pending event at internal time `t`: a pair collision (or a
    /// prediction made obsolete by the partner, recomputed), a wall hit, a cell
    /// crossing or a floor search resumed; nothing ever again at t = +∞.
    #[inline(always)]
    fn disc_step<M: Motion>(&mut self, t: f64, who: u32) -> Result<Step, EngineError> {
        if t == f64::INFINITY {
            return Ok(Step::Report(None));
        }
        debug_assert!(t >= self.clock, "event in the past: {t} < {}", self.clock);
        let i = who as usize;
        let b = &self.bodies[i];
        let (pending, aux) = (b.pending, b.aux);
        match pending {
            Pending::Pair => {
                let j = b.partner as usize;
                if self.bodies[j].count != b.partner_count {
                    self.move_clock(t);
                    self.stats.stale_events += 1;
                    self.predict::<M>(i);
                    return Ok(Step::Continue);
                }
                self.advance_clock(t)?;
                let ev = self.collide::<M>(i, j, aux.image());
                Ok(Step::Report(Some(Event::Pair(ev))))
            }
            Pending::Wall => {
                self.advance_clock(t)?;
                let ev = self.hit_wall::<M>(i, aux.face());
                Ok(Step::Report(Some(Event::Wall(ev))))
            }
            Pending::Cell => {
                self.move_clock(t);
                self.cross::<M>(i, aux.face());
                Ok(Step::Continue)
            }
            Pending::Recheck => {
                // The floor search stopped short (engine::floor): search on.
                self.move_clock(t);
                self.predict::<M>(i);
                Ok(Step::Continue)
            }
            Pending::Skin => {
                // Only on lists (and compiled only into their loop).
                assert!(M::LISTS, "a skin exit on the cell path");
                self.move_clock(t);
                self.renew_list(i);
                // A list that overflowed put the run on cells (engine::listed):
                // hand back a pause, so that the next call runs the cells' loop.
                Ok(if self.lists.is_none() {
                    Step::Report(self.pause())
                } else {
                    Step::Continue
                })
            }
            Pending::None => unreachable!("a disc with no event has time +∞"),
        }
    }

    /// Run until time `t_end` (≥ now): the engine stops with every disc's state known
    /// at exactly `t_end`. Returns the number of collisions (pair + wall) processed.
    pub fn run_until(&mut self, t_end: f64) -> Result<u64, EngineError> {
        self.push_calendar(t_end, Whose::Stop)?;
        let mut collisions = 0;
        let ended = loop {
            match self.next_event() {
                Ok(Some(Event::Pause { .. })) if !self.stop_pending() => break Ok(collisions),
                Ok(Some(Event::Scheduled { .. } | Event::Pause { .. })) => {}
                Ok(Some(_)) => collisions += 1,
                Ok(None) => break Ok(collisions),
                Err(e) => break Err(e),
            }
        };
        self.drop_stop();
        ended
    }

    /// Run `n` collisions (pair + wall), skipping scheduled events. Stops early if
    /// nothing will ever happen again; returns the number processed. (Like
    /// [`Engine::next_event`], it does not return while discs that never collide
    /// again keep crossing cells.)
    pub fn run_collisions(&mut self, n: u64) -> Result<u64, EngineError> {
        let mut done = 0;
        while done < n {
            match self.next_event()? {
                Some(Event::Scheduled { .. } | Event::Pause { .. }) => {}
                Some(_) => done += 1,
                None => break,
            }
        }
        Ok(done)
    }
}
