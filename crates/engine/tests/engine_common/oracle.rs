//! A brute-force O(N²) event-driven integrator with the seed's physics, written
//! independently of the engine (tests/engine_oracle.rs compares the two): free
//! flight, wrapping, the nearest image and the choice of the next event here; pair
//! contacts by the seed's angular contact time (`kinematics::contact_time_seed`,
//! seed 000 Eq. 14–17), collisions by the seed's component form
//! (`collision::elastic_seed`, Eq. 8–13); the wall time and a specular reflection at
//! elastic walls (physics.md (2.6), (4.7)) written here. The engine uses none of these.

use carom_core::collision::elastic_seed;
use carom_core::kinematics::contact_time_seed;
use carom_core::{Boundary, DVec2, WallSide};
use carom_engine::State;

/// An event named independently of who predicted it: pairs unordered (i < j), walls
/// by disc, axis and side.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Key {
    Pair(usize, usize),
    Wall(usize, usize, WallSide),
}

/// One of the oracle's predictions: the event and the time until it.
#[derive(Debug, Clone, Copy)]
pub struct Prediction {
    /// The event.
    pub key: Key,
    /// Time from the oracle's state until it (time).
    pub dt: f64,
}

/// The oracle: every disc's position and velocity at `time`, advanced together.
pub struct Oracle {
    pub size: DVec2,
    pub periodic: [bool; 2],
    pub pos: Vec<DVec2>,
    pub vel: Vec<DVec2>,
    pub radius: Vec<f64>,
    pub mass: Vec<f64>,
    pub time: f64,
    /// How many times the predictions searched all images.
    pub all_images: usize,
}

impl Oracle {
    pub fn new(s: &State) -> Self {
        let walls_elastic = s.sim_box.boundary.iter().all(|b| match b {
            Boundary::Periodic => true,
            Boundary::Walls { restitution } => *restitution == 1.0,
        });
        assert!(walls_elastic, "the oracle knows elastic walls only");
        Oracle {
            size: s.sim_box.size,
            periodic: s.sim_box.boundary.map(|b| b.is_periodic()),
            pos: s.positions.clone(),
            vel: s.velocities.clone(),
            radius: (0..s.len()).map(|i| s.radius(i)).collect(),
            mass: (0..s.len()).map(|i| s.mass(i)).collect(),
            time: s.time,
            all_images: 0,
        }
    }

    /// The separation `d` through the nearest periodic image: each periodic
    /// component shifted by a whole number of box lengths into [−L/2, L/2].
    fn nearest_image(&self, mut d: DVec2) -> DVec2 {
        for k in 0..2 {
            if self.periodic[k] {
                d[k] -= self.size[k] * (d[k] / self.size[k]).round();
            }
        }
        d
    }

    /// All periodic images of `d` with shifts −1, 0, +1 box lengths per periodic
    /// axis.
    fn images(&self, d: DVec2) -> Vec<DVec2> {
        let shifts = |k: usize| {
            if self.periodic[k] {
                vec![-1.0, 0.0, 1.0]
            } else {
                vec![0.0]
            }
        };
        let mut out = Vec::new();
        for sx in shifts(0) {
            for sy in shifts(1) {
                out.push(d + DVec2::new(sx * self.size.x, sy * self.size.y));
            }
        }
        out
    }

    /// Time until disc `i` touches a wall of the walled axis `k`: its centre reaches
    /// a (low wall) or L − a (high wall) at its constant velocity; never if still.
    fn wall(&self, i: usize, k: usize) -> Option<Prediction> {
        let (x, v, a, l) = (self.pos[i][k], self.vel[i][k], self.radius[i], self.size[k]);
        let (gap, side) = if v > 0.0 {
            (l - a - x, WallSide::High)
        } else if v < 0.0 {
            (a - x, WallSide::Low)
        } else {
            return None;
        };
        Some(Prediction {
            key: Key::Wall(i, k, side),
            dt: (gap / v).max(0.0),
        })
    }

    /// Time until discs i and j touch through the image separation `d` = r_j − r_i,
    /// by the seed's angular formula.
    fn contact(&self, i: usize, j: usize, d: DVec2) -> Option<f64> {
        let (ri, rj) = (self.pos[i], self.pos[i] + d);
        contact_time_seed(
            ri,
            self.vel[i],
            self.radius[i],
            rj,
            self.vel[j],
            self.radius[j],
        )
    }

    /// Every event the state will reach: each pair's first contact, each disc's next
    /// wall. Pairs are predicted through the nearest image, or through all images
    /// when `all_images` is set.
    fn predictions(&self, all_images: bool) -> Vec<Prediction> {
        let n = self.pos.len();
        let mut out = Vec::new();
        for i in 0..n {
            for j in i + 1..n {
                let d = self.nearest_image(self.pos[j] - self.pos[i]);
                let candidates = if all_images { self.images(d) } else { vec![d] };
                let dt = candidates
                    .into_iter()
                    .filter_map(|d| self.contact(i, j, d))
                    .reduce(f64::min);
                if let Some(dt) = dt {
                    out.push(Prediction {
                        key: Key::Pair(i, j),
                        dt,
                    });
                }
            }
            out.extend(
                (0..2)
                    .filter(|&k| !self.periodic[k])
                    .filter_map(|k| self.wall(i, k)),
            );
        }
        out
    }

    /// The predictions, made safe against a contact through another image: one that
    /// is not the nearest now is at least L/2 away along a periodic axis, so no pair
    /// can reach it before the earliest event if the fastest relative speed (at most
    /// twice the fastest disc's) covers less than L/2 − σ_max by then. Otherwise all
    /// images are searched.
    pub fn safe_predictions(&mut self) -> Vec<Prediction> {
        let p = self.predictions(false);
        let first = p.iter().map(|p| p.dt).fold(f64::INFINITY, f64::min);
        let fastest = self.vel.iter().map(|v| v.length()).fold(0.0, f64::max);
        let sigma_max = 2.0 * self.radius.iter().cloned().fold(0.0, f64::max);
        let room = (0..2)
            .filter(|&k| self.periodic[k])
            .map(|k| self.size[k] / 2.0 - sigma_max)
            .fold(f64::INFINITY, f64::min);
        if 2.0 * fastest * first < room {
            p
        } else {
            self.all_images += 1;
            self.predictions(true)
        }
    }

    /// Move every disc on for `dt` and wrap it back into the box.
    fn advance(&mut self, dt: f64) {
        for (r, v) in self.pos.iter_mut().zip(&self.vel) {
            *r += *v * dt;
            for k in 0..2 {
                if self.periodic[k] {
                    r[k] -= self.size[k] * (r[k] / self.size[k]).floor();
                }
            }
        }
        self.time += dt;
    }

    /// Carry out `p` (advance to it and resolve it).
    pub fn perform(&mut self, p: Prediction) {
        self.advance(p.dt);
        match p.key {
            Key::Pair(i, j) => {
                // In contact the nearest image is the touching one (σ < L/2).
                let rj = self.pos[i] + self.nearest_image(self.pos[j] - self.pos[i]);
                let (vi, vj) = elastic_seed(
                    self.pos[i],
                    self.vel[i],
                    self.mass[i],
                    self.radius[i],
                    rj,
                    self.vel[j],
                    self.mass[j],
                    self.radius[j],
                );
                (self.vel[i], self.vel[j]) = (vi, vj);
            }
            // Specular reflection: the normal component reverses.
            Key::Wall(i, k, _) => self.vel[i][k] = -self.vel[i][k],
        }
    }

    /// Kinetic energy Σ m v²/2 and momentum Σ m v.
    pub fn energy_momentum(&self) -> (f64, DVec2) {
        let e = self
            .vel
            .iter()
            .zip(&self.mass)
            .map(|(v, m)| 0.5 * m * v.length_squared());
        let p = self.vel.iter().zip(&self.mass).map(|(v, m)| *v * *m);
        (e.sum(), p.sum())
    }
}

/// The earliest of the predictions.
pub fn earliest(p: &[Prediction]) -> Prediction {
    *p.iter()
        .min_by(|a, b| a.dt.total_cmp(&b.dt))
        .expect("moving discs always have a next event")
}
