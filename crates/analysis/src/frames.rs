//! The observables of snapshots on plain arrays, for data that is not a carom
//! log (a GSD file, another code's frames, the Python package): a [`Frame`] is
//! one snapshot's time, species index, x and y per disc (and optionally vx, vy);
//! a [`System`] the box and the species. [`structure`] gives g_ab(r) with its
//! contact values, ψ6, g6(r) and S(k) (physics.md §10–§11), [`dynamics`] the MSD,
//! D, the snapshot VACF and F_s(k*, τ) (§13), as the very sections of
//! [`Report`](super::Report), through the same accumulators the
//! [`Analyzer`](super::Analyzer) uses: the same frames and window give the same
//! numbers, bit for bit. Each frame starts a block (no snapshot schedule).
//! Positions for [`structure`] are in the box (wrapped); for [`dynamics`] they
//! must be unwrapped (continuous in time, physics.md §12: [`Unwrapper`](super::Unwrapper)
//! or x + image·L).

use carom_core::{SimBox, Species};

use super::dynamics::Dynamics;
use super::dynamics_report::DynamicsReport;
use super::stats::StatsError;
use super::structure::{smallest_diameter, Structure, StructureReport};

/// One snapshot: per disc its species index and centre, optionally its velocity.
#[derive(Debug, Clone, PartialEq)]
pub struct Frame {
    /// Time (time).
    pub time: f64,
    /// Species index of every disc (into [`System::species`]).
    pub species: Vec<u16>,
    /// x of every centre (length).
    pub x: Vec<f64>,
    /// y of every centre (length).
    pub y: Vec<f64>,
    /// (vx, vy) of every disc (length/time), when known.
    pub velocities: Option<[Vec<f64>; 2]>,
}

/// The box and the species (count, radius, mass) of the frames.
#[derive(Debug, Clone, PartialEq)]
pub struct System {
    /// The box, its axes periodic or walled.
    pub sim_box: SimBox,
    /// The species; counts must match the frames' species indices.
    pub species: Vec<Species>,
}

/// The window [start, end] (time) analysed: frames before `start` are skipped,
/// and the time blocks behind the errors split it (as `carom analyze` splits
/// [equilibrate, t_end]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Window {
    /// Start (time), `window.equilibrate` of the log's report.
    pub start: f64,
    /// End (time), `window.t_end` of the log's report.
    pub end: f64,
}

/// Every frame's slices agree in length with N and its species indices exist.
fn check(system: &System, f: &Frame) -> Result<(), StatsError> {
    let n: usize = system.species.iter().map(|s| s.count).sum();
    let lengths = [f.species.len(), f.x.len(), f.y.len()];
    let bad_velocities = f
        .velocities
        .as_ref()
        .is_some_and(|[vx, vy]| vx.len() != n || vy.len() != n);
    if lengths.iter().any(|&l| l != n) || bad_velocities {
        return Err(StatsError::InvalidArgument(format!(
            "frame at t = {}: {lengths:?} species, x, y for {n} discs",
            f.time
        )));
    }
    if let Some(&s) = f
        .species
        .iter()
        .find(|&&s| s as usize >= system.species.len())
    {
        return Err(StatsError::InvalidArgument(format!(
            "frame at t = {}: species index {s} of {} species",
            f.time,
            system.species.len()
        )));
    }
    Ok(())
}

/// g_ab(r) with contact values, ψ6, g6(r) and S(k) of the frames in `window`
/// (positions in the box), without the contact theorem (it needs a pressure).
pub fn structure(
    system: &System,
    window: Window,
    frames: &[Frame],
) -> Result<StructureReport, StatsError> {
    let mut s = Structure::new(&system.species, &system.sim_box, window.start, window.end);
    // As the Analyzer: a frame at the window's start counts despite rounding.
    let span = frames.first().map_or(0.0, |f| window.end - f.time);
    for f in frames {
        check(system, f)?;
        if f.time >= window.start - 1e-12 * window.start.abs().max(span) {
            s.add(f.time.max(window.start), &f.species, &f.x, &f.y);
        }
    }
    Ok(s.report(false, None))
}

/// MSD and D per species, the snapshot VACF and F_s(k*, τ) with τ_α of the
/// frames (unwrapped positions and velocities, in time order) with time origins
/// in `window`; `snapshot_interval` the frames' spacing when regular (sets the
/// origins' memory), `collision_rate` ω per disc (1/time; the D window starts
/// [`D_WINDOW_COLLISIONS`](super::D_WINDOW_COLLISIONS)/ω after an origin).
/// `None` without two frames in the window.
pub fn dynamics(
    system: &System,
    window: Window,
    snapshot_interval: Option<f64>,
    collision_rate: f64,
    frames: &[Frame],
) -> Result<Option<DynamicsReport>, StatsError> {
    let t_start = frames.first().map_or(window.start, |f| f.time);
    let mut d = Dynamics::new(
        (&system.species, &system.sim_box),
        [t_start, window.start, window.end],
        snapshot_interval,
        smallest_diameter(&system.species),
    );
    for f in frames {
        check(system, f)?;
        let Some([vx, vy]) = &f.velocities else {
            return Err(StatsError::InvalidArgument(format!(
                "frame at t = {}: dynamics needs the velocities (the VACF)",
                f.time
            )));
        };
        d.add(f.time, true, &f.species, [&f.x, &f.y], [vx, vy]);
    }
    Ok(d.report(collision_rate))
}

#[cfg(test)]
mod tests {
    //! The same engine frames through the Analyzer and through the arrays give
    //! equal sections, bit for bit.
    use super::*;
    use crate::{AnalysisOptions, Analyzer, RunDescription, Unwrapper};
    use carom_core::Boundary;
    use carom_engine::{Engine, EngineParams, Event, SystemSpec};
    use carom_log::Snapshot;

    #[test]
    fn arrays_give_the_analyzers_sections() {
        let species = vec![Species::reference(60), Species::new(20, 0.7, 2.5)];
        let state = SystemSpec::square_box(species.clone(), 0.3, [Boundary::Periodic; 2], 7)
            .build()
            .unwrap();
        let sim_box = state.sim_box;
        let mut e = Engine::new(state, EngineParams::default()).unwrap();
        let mut unwrapper = Unwrapper::new();
        let (mut wrapped, mut unwrapped) = (Vec::new(), Vec::new());
        for k in 0..=40 {
            if k > 0 {
                e.schedule(0.25 * k as f64, k).unwrap();
                while !matches!(e.next_event().unwrap(), Some(Event::Scheduled { .. })) {}
            }
            let s = Snapshot::from_state(&e.state());
            let frame = |p: &[carom_core::DVec2]| Frame {
                time: s.time,
                species: s.species.clone(),
                x: p.iter().map(|p| p.x).collect(),
                y: p.iter().map(|p| p.y).collect(),
                velocities: Some([
                    s.velocities.iter().map(|v| v.x).collect(),
                    s.velocities.iter().map(|v| v.y).collect(),
                ]),
            };
            wrapped.push(frame(&s.positions));
            unwrapped.push(frame(unwrapper.push(&s)));
        }
        let run = RunDescription {
            species: species.clone(),
            sim_box,
            t_end: 10.0,
            ..RunDescription::for_tests()
        };
        let mut a = Analyzer::new(run, AnalysisOptions::default()).unwrap();
        for (w, u) in wrapped.iter().zip(&unwrapped) {
            let [vx, vy] = w.velocities.as_ref().unwrap();
            a.snapshot(w.time, &w.species, vx, vy).unwrap();
            a.motion(w.time, &u.species, [&u.x, &u.y], [vx, vy])
                .unwrap();
            a.positions(w.time, &w.species, &w.x, &w.y).unwrap();
        }
        let r = a.finish().unwrap();
        let system = System { sim_box, species };
        let window = Window {
            start: r.window.equilibrate,
            end: r.window.t_end,
        };
        let s = structure(&system, window, &wrapped).unwrap();
        assert!(s.pair_correlation.is_some() && s.structure_factor.is_some());
        let mut pc = r.pair_correlation.clone().unwrap();
        pc.contact_theorem = None;
        // Debug prints every f64 exactly (NaN bins, where == fails, included).
        let same = |a: &dyn std::fmt::Debug, b: &dyn std::fmt::Debug| {
            assert_eq!(format!("{a:?}"), format!("{b:?}"));
        };
        same(&s.pair_correlation, &Some(pc));
        same(&s.bond_order, &r.bond_order);
        same(&s.orientational_correlation, &r.orientational_correlation);
        same(&s.structure_factor, &r.structure_factor);
        let per_disc = r.collision_rate.per_disc;
        let d = dynamics(&system, window, None, per_disc, &unwrapped).unwrap();
        assert!(d.is_some());
        same(&d, &r.dynamics);
        // A frame of the wrong length is refused.
        let mut bad = wrapped[..1].to_vec();
        bad[0].x.pop();
        assert!(structure(&system, window, &bad).is_err());
    }
}
