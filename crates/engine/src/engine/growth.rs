//! Growing discs: Lubachevsky–Stillinger compression (physics.md §17).
//!
//! Every radius grows linearly and all in proportion, a_i(t) = a_i⁰ s(t) with
//! s(t) = s₀ + γ t on the internal clock (17.1): the engine's species keep the
//! reference radii a_i⁰, and the scale is computed where it is needed. Pair and
//! wall times become those of `carom_core::growth`; at contact a pair leaves at
//! u' = −u + 2g and a wall returns v' = −v ± 2ȧ (16.4, 16.6), so collisions add
//! kinetic energy, and every `rescale_interval` the velocities are scaled back to
//! the target kT (an exact, scheduled instant; §17 "Temperature"). Growth stops when s reaches
//! the target scale, or at a rescale whose virial pressure Z over the interval past
//! exceeds the jamming bound (17.7); the discs then keep their size. All discs
//! share one cell grid sized for the target (cells wider than the largest final
//! diameter), so it stays valid throughout. Entered by one test of γ ≠ 0 per
//! event, like gravity: the engine without growth does exactly what it did before.

use super::body::{Face, Pending};
use super::Engine;
use crate::error::EngineError;
use crate::event::Event;
use carom_core::growth::{growing_wall_impulse, wall_time_growing};
use carom_core::observables::{degrees_of_freedom, temperature, virial_z};
use carom_core::{Boundary, DVec2, Restitution, SimBox, Species};
use std::ops::ControlFlow;

/// How the discs grow (physics.md §17); part of [`crate::EngineParams`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Growth {
    /// Relative growth rate γ (1/time): every radius a_i(t) = a_i⁰ (1 + γ t),
    /// a_i⁰ the radius at the start. 0 (the default) turns growth off.
    pub rate: f64,
    /// The scale a_i/a_i⁰ at which growth stops (≥ 1): √(η_target/η₀) for a
    /// target packing fraction η_target from η₀.
    pub target_scale: f64,
    /// The kT to which velocities are scaled back at each rescale (energy, > 0).
    pub kt: f64,
    /// Time between two rescales (time, > 0).
    pub rescale_interval: f64,
    /// Jamming bound: growth stops at a rescale when the virial Z = βPA/N over the
    /// interval just ended exceeds it (> 1).
    pub max_reduced_pressure: f64,
}

impl Default for Growth {
    fn default() -> Self {
        Growth {
            rate: 0.0,
            target_scale: 1.0,
            kt: 1.0,
            rescale_interval: 1.0,
            max_reduced_pressure: 1e3,
        }
    }
}

/// Why growth ended, if it has.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum GrowthEnd {
    /// Still growing (or never grew).
    #[default]
    Growing,
    /// The target scale was reached.
    Target,
    /// The jamming bound on Z was exceeded.
    Jammed,
}

/// The state of the growth, on the internal clock; part of the checkpoint.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GrowthState {
    /// Scale s₀ at internal time 0 (radius / reference radius).
    pub scale0: f64,
    /// Relative growth rate now (1/time; 0 once growth has ended).
    pub rate: f64,
    /// Internal time at which the scale reaches the target (+∞ once ended).
    pub end: f64,
    /// Internal time of the next rescale (+∞ once ended).
    pub next_rescale: f64,
    /// The virial sum at the last rescale (for the interval's Z).
    pub virial_mark: f64,
    /// Why growth ended.
    pub ended: GrowthEnd,
    /// Z over the last interval between rescales (0 before the first).
    pub last_z: f64,
}

impl GrowthState {
    /// No growth: scale 1, nothing scheduled.
    pub const NONE: GrowthState = GrowthState {
        scale0: 1.0,
        rate: 0.0,
        end: f64::INFINITY,
        next_rescale: f64::INFINITY,
        virial_mark: 0.0,
        ended: GrowthEnd::Growing,
        last_z: 0.0,
    };

    /// The growth `g` starting at internal time 0 with scale 1.
    pub(super) fn start(g: &Growth) -> GrowthState {
        if g.rate == 0.0 {
            return GrowthState::NONE;
        }
        GrowthState {
            rate: g.rate,
            end: ((g.target_scale - 1.0) / g.rate).max(0.0),
            next_rescale: g.rescale_interval,
            ..GrowthState::NONE
        }
    }

    /// (s, γ) at internal time `t`: the scale s₀ + γ t and the rate.
    #[inline(always)]
    pub(super) fn now(&self, t: f64) -> (f64, f64) {
        (self.scale0 + self.rate * t, self.rate)
    }

    /// Move the internal clock's zero to `shift` (engine::clock).
    pub(super) fn rebase(&mut self, shift: f64) {
        self.scale0 += self.rate * shift;
        self.end -= shift;
        self.next_rescale -= shift;
    }
}

impl Default for GrowthState {
    fn default() -> Self {
        GrowthState::NONE
    }
}

/// Whether growth `g` is allowed with these dynamics: finite values in range, and
/// when it is on, elastic pairs and walls, no TC model and no gravity (the
/// contact rule (17.4) is the elastic one; growth in a field is not built).
pub(crate) fn check_growth(
    g: &Growth,
    restitution: Restitution,
    tc: f64,
    gravity: f64,
    sim_box: &SimBox,
) -> Result<(), EngineError> {
    let bad = |m: String| Err(EngineError::BadGrowth(m));
    if !(g.rate.is_finite() && g.rate >= 0.0) {
        return bad(format!("rate = {} (allowed: finite, ≥ 0)", g.rate));
    }
    if g.rate == 0.0 {
        return Ok(());
    }
    if !(g.target_scale.is_finite() && g.target_scale >= 1.0) {
        return bad(format!(
            "target scale = {} (allowed: finite, ≥ 1: a target packing fraction at or \
             above the start's)",
            g.target_scale
        ));
    }
    for (name, v) in [("kT", g.kt), ("rescale interval", g.rescale_interval)] {
        if !(v.is_finite() && v > 0.0) {
            return bad(format!("{name} = {v} (allowed: finite, > 0)"));
        }
    }
    if g.max_reduced_pressure.is_nan() || g.max_reduced_pressure <= 1.0 {
        return bad(format!(
            "max reduced pressure = {} (allowed: > 1, or +∞ for no jamming stop)",
            g.max_reduced_pressure
        ));
    }
    let walls_elastic = sim_box.boundary.iter().all(|b| match b {
        Boundary::Walls { restitution } => *restitution == 1.0,
        Boundary::Periodic => true,
    });
    if !restitution.is_elastic() || tc != 0.0 || !walls_elastic {
        return bad("growing discs need elastic collisions (pairs and walls), no TC model".into());
    }
    if gravity != 0.0 {
        return bad("growing discs in a gravity field are not supported".into());
    }
    Ok(())
}

/// The species whose radii the cell grid of growing discs is built for: the
/// reference radii times the target scale (the largest the discs get).
pub(super) fn grid_species(species: &[Species], g: &Growth) -> Vec<Species> {
    let mut s = species.to_vec();
    if g.rate != 0.0 {
        for sp in &mut s {
            sp.radius *= g.target_scale;
        }
    }
    s
}

impl Engine {
    /// The growth state (physics.md §17; [`GrowthState::NONE`] without growth).
    pub fn growth(&self) -> &GrowthState {
        &self.growth
    }

    /// Time of the next velocity rescale on the caller's clock (time; +∞ without
    /// growth or once it has ended): the start of the growth plus k times the
    /// rescale interval, to rounding.
    pub fn next_rescale_time(&self) -> f64 {
        self.epoch + self.growth.next_rescale
    }

    /// Radii now relative to the species' reference radii: 1 without growth.
    pub fn radius_scale(&self) -> f64 {
        self.growth.now(self.clock).0
    }

    /// Disc `i`'s earliest cell crossing or wall hit from now while growing, as
    /// [`Engine::boundary_event`] gives it without growth: crossings are those of
    /// the straight path, walls meet the growing radius (physics.md (17.5)).
    #[cold]
    #[inline(never)]
    pub(super) fn boundary_event_growing(
        &self,
        i: usize,
        ri: DVec2,
        v: DVec2,
    ) -> (f64, Pending, Face) {
        let b = &self.bodies[i];
        let c = b.link.coords();
        let grid = self.grids.get(self.grids.class(b.species));
        let a0 = self.species[b.species as usize].radius;
        let (s, rate) = self.growth.now(self.clock);
        let mut best = f64::INFINITY;
        let (mut kind, mut face) = (Pending::None, Face::new(0, false));
        for k in 0..2 {
            let (dt, up) = grid.crossing_time(k, c[k], ri[k], v[k]);
            if dt < best {
                (best, kind, face) = (dt, Pending::Cell, Face::new(k, up));
            }
            if let Boundary::Walls { .. } = self.sim_box.boundary[k] {
                let (dt, high) =
                    wall_time_growing(ri[k], v[k], a0 * s, a0 * rate, self.sim_box.size[k]);
                if dt < best {
                    (best, kind, face) = (dt, Pending::Wall, Face::new(k, high));
                }
            }
        }
        (best, kind, face)
    }

    /// The impulse a wall `high` (or low) of axis `k` gives disc `i` of mass `m`
    /// with normal velocity `vk` while it grows (physics.md (17.6)).
    pub(super) fn growing_wall_impulse(&self, i: usize, vk: f64, m: f64, high: bool) -> f64 {
        let a0 = self.species[self.bodies[i].species as usize].radius;
        growing_wall_impulse(vk, m, a0 * self.growth.rate, high)
    }

    /// The growth's next instant (internal time): a rescale or the end.
    #[inline(always)]
    pub(super) fn growth_due(&self) -> f64 {
        self.growth.next_rescale.min(self.growth.end)
    }

    /// Handle the growth's instant now (the clock is at [`Engine::growth_due`]):
    /// rescale the velocities to the target kT, and end the growth at the target
    /// scale or when Z over the interval past exceeds the jamming bound (17.7);
    /// then predict every disc again (all paths changed, or the radii stopped).
    /// Returns whether a pause is due (`engine::pause`).
    #[cold]
    #[inline(never)]
    pub(super) fn growth_event(&mut self) -> bool {
        let g = self.params.growth;
        let now = self.clock;
        let n = self.len();
        let k = self.kinetic_energy();
        let dof = degrees_of_freedom(n, &self.sim_box);
        let at_end = self.growth.end <= self.growth.next_rescale;
        if !at_end {
            let z = virial_z(
                n,
                g.kt,
                self.stats.virial_sum - self.growth.virial_mark,
                g.rescale_interval,
            );
            self.growth.last_z = z;
            self.growth.virial_mark = self.stats.virial_sum;
            self.growth.next_rescale += g.rescale_interval;
            if z > g.max_reduced_pressure {
                self.stop_growth(GrowthEnd::Jammed);
            }
        } else {
            self.stop_growth(GrowthEnd::Target);
        }
        let kt = temperature(k, dof);
        if kt > 0.0 {
            let lambda = (g.kt / kt).sqrt();
            for b in self.bodies.iter_mut() {
                let v = b.v * lambda;
                b.set_velocity(v, now);
                b.count = b.count.wrapping_add(1);
            }
        }
        for i in 0..n {
            self.predict::<super::motion::Growing>(i);
        }
        self.quiet_work(n.max(1))
    }

    /// [`Engine::run_until`] `t_end` for an engine with growth configured, through
    /// the growing copy of the event loop only (for compressed placement): a call
    /// of [`Engine::next_event`] from the placement changed how the whole-program
    /// optimiser inlines the plain loop, +3 % instructions for the plain engine
    /// (docs/performance.md, "growth off"). `observe` is called every 4096 events
    /// and at every pause (`engine::pause`); when it breaks, the run stops there.
    pub(crate) fn run_growing_until(
        &mut self,
        t_end: f64,
        observe: &mut dyn FnMut(&Engine) -> ControlFlow<()>,
    ) -> Result<ControlFlow<()>, EngineError> {
        debug_assert!(self.params.growth.rate != 0.0);
        self.push_calendar(t_end, super::calendar::Whose::Stop)?;
        let mut events: u32 = 0;
        let ended = loop {
            let ev = match self.next_event_growing() {
                Ok(Some(ev)) => ev,
                Ok(None) => break Ok(ControlFlow::Continue(())),
                Err(e) => break Err(e),
            };
            let paused = matches!(ev, Event::Pause { .. });
            if paused && !self.stop_pending() {
                break Ok(ControlFlow::Continue(()));
            }
            events = events.wrapping_add(1);
            if (events.is_multiple_of(4096) || paused) && observe(self).is_break() {
                break Ok(ControlFlow::Break(()));
            }
        };
        self.drop_stop();
        ended
    }

    /// Stop growing now, keeping the size (and say why).
    fn stop_growth(&mut self, why: GrowthEnd) {
        let st = &mut self.growth;
        st.scale0 = if why == GrowthEnd::Target {
            self.params.growth.target_scale
        } else {
            st.scale0 + st.rate * self.clock
        };
        // On the internal clock from now on s = s₀ (rate 0): s₀ is the scale now.
        st.rate = 0.0;
        st.end = f64::INFINITY;
        st.next_rescale = f64::INFINITY;
        st.ended = why;
    }
}
