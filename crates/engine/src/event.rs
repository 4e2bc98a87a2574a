//! What the engine reports: the events a caller can observe.

use carom_core::{Axis, DVec2, WallSide};

/// A collision of two discs, resolved at time `time`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PairCollision {
    /// Time of contact (time).
    pub time: f64,
    /// First disc (the one whose prediction fired).
    pub i: u32,
    /// Second disc.
    pub j: u32,
    /// Unit contact normal from i to j (minimum image / periodic image used).
    pub normal: DVec2,
    /// Velocity of i before the collision (length/time).
    pub vi_before: DVec2,
    /// Velocity of j before the collision (length/time).
    pub vj_before: DVec2,
    /// Velocity of i after the collision (length/time).
    pub vi_after: DVec2,
    /// Velocity of j after the collision (length/time).
    pub vj_after: DVec2,
    /// Kinetic energy dissipated (energy; 0 for elastic collisions).
    pub energy_lost: f64,
    /// Collision virial r_ij·Δp_i with r_ij = r_i − r_j at contact (energy·time,
    /// i.e. length·momentum); physics.md §5.
    pub virial: f64,
    /// Momentum given to disc i, Δp_i (mass·length/time); disc j received −Δp_i
    /// and the velocities after are exactly v_i + Δp_i/m_i and v_j − Δp_i/m_j
    /// (`carom_core::collision::apply_impulse`).
    pub impulse: DVec2,
}

/// A collision of a disc with a hard wall.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WallCollision {
    /// Time of contact (time).
    pub time: f64,
    /// The disc.
    pub i: u32,
    /// The axis normal to the wall.
    pub axis: Axis,
    /// Which of the two walls of that axis.
    pub side: WallSide,
    /// Velocity before (length/time).
    pub v_before: DVec2,
    /// Velocity after (length/time).
    pub v_after: DVec2,
    /// Magnitude of the momentum given to the wall (mass·length/time). The disc
    /// received Δp = −(1 + e) m v_k along the wall's axis k, of this magnitude and
    /// pointing away from the wall ([`WallCollision::impulse_vector`]), and its
    /// velocity after is exactly v_k + Δp/m.
    pub impulse: f64,
    /// Kinetic energy dissipated (energy).
    pub energy_lost: f64,
}

impl WallCollision {
    /// The momentum Δp the disc received (mass·length/time): [`WallCollision::impulse`]
    /// along the wall's axis, away from the wall.
    pub fn impulse_vector(&self) -> DVec2 {
        let dp = match self.side {
            WallSide::Low => self.impulse,
            WallSide::High => -self.impulse,
        };
        match self.axis {
            Axis::X => DVec2::new(dp, 0.0),
            Axis::Y => DVec2::new(0.0, dp),
        }
    }
}

/// An event the caller sees. Cell crossings and invalidated predictions are internal
/// and never reported.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Event {
    /// Two discs collided.
    Pair(PairCollision),
    /// A disc hit a wall.
    Wall(WallCollision),
    /// A time the caller scheduled has been reached; [`crate::Engine::state`] now
    /// gives the exact state at that time.
    Scheduled {
        /// The scheduled time (time).
        time: f64,
        /// The caller's tag.
        tag: u64,
    },
    /// The engine hands back control after long unobservable work (thermostat
    /// events, growth rescales) so that the caller can stop or show progress;
    /// nothing happened at `time`, and the next call goes on (`engine::pause`).
    Pause {
        /// The current time (time).
        time: f64,
    },
}

impl Event {
    /// The time of the event (time).
    pub fn time(&self) -> f64 {
        match self {
            Event::Pair(p) => p.time,
            Event::Wall(w) => w.time,
            Event::Scheduled { time, .. } | Event::Pause { time } => *time,
        }
    }
}
