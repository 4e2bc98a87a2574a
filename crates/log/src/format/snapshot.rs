//! The `/snapshot` channel: the exact state of every disc at one time, encoded
//! as CDR with the `ros2msg` schema [`SNAPSHOT_MSG`].

use super::cdr::{CdrError, CdrReader, CdrWriter};
use carom_core::DVec2;
use carom_engine::State;

/// `ros2msg` text of the schema `carom_msgs/msg/Snapshot`.
pub const SNAPSHOT_MSG: &str = "\
# The exact state of every disc at one time (struct of arrays, one entry per disc).
float64 time              # simulated time of the state (time)
float64 box_x             # box edge lengths (length); the box is [0, box_x) x [0, box_y)
float64 box_y
uint8 boundary_x          # 0 = periodic, 1 = hard walls
uint8 boundary_y
float64[] species_radius  # per species: radius (length)
float64[] species_mass    # per species: mass (mass)
uint16[] species          # per disc: species index
float64[] x               # per disc: centre position (length), inside the box
float64[] y
float64[] vx              # per disc: velocity (length/time)
float64[] vy
int32[] image_x           # per disc: periodic image; the unwrapped position is x + image_x * box_x
int32[] image_y           #   (net edges crossed since the run began; 0 along walls; log format 2.1 on)
";

/// Boundary code in snapshots and checkpoints: 0 periodic, 1 walls.
pub(crate) fn boundary_code(b: &carom_core::Boundary) -> u8 {
    match b {
        carom_core::Boundary::Periodic => 0,
        carom_core::Boundary::Walls { .. } => 1,
    }
}

/// The state of every disc at one time ([`SNAPSHOT_MSG`]).
#[derive(Debug, Clone, PartialEq)]
pub struct Snapshot {
    /// Simulated time (time).
    pub time: f64,
    /// Box edge lengths (length).
    pub box_size: DVec2,
    /// Boundary codes of the x and y axes (0 periodic, 1 walls).
    pub boundary: [u8; 2],
    /// Radius of each species (length).
    pub species_radius: Vec<f64>,
    /// Mass of each species (mass).
    pub species_mass: Vec<f64>,
    /// Species index of each disc.
    pub species: Vec<u16>,
    /// Centre positions (length).
    pub positions: Vec<DVec2>,
    /// Velocities (length/time).
    pub velocities: Vec<DVec2>,
    /// Periodic image of each disc ([`State::images`]): the unwrapped position is
    /// `positions[k] + images[k] · box_size`. Empty in logs before format 2.1.
    pub images: Vec<[i32; 2]>,
}

/// The CDR form of a snapshot (`SNAPSHOT_MSG`): (time, box size, boundary codes),
/// each species' (radius, mass), then each disc's species, x, y, vx, vy and
/// images (all 0 when `images` is empty).
fn encode_snapshot<'a>(
    w: &mut CdrWriter,
    (time, box_size, boundary): (f64, DVec2, [u8; 2]),
    (radius, mass): (
        impl ExactSizeIterator<Item = &'a f64>,
        impl ExactSizeIterator<Item = &'a f64>,
    ),
    species: &[u16],
    positions: &[DVec2],
    velocities: &[DVec2],
    images: &[[i32; 2]],
) {
    w.reset();
    w.reserve(72 + positions.len() * 42 + radius.len() * 16);
    w.put(time);
    w.put(box_size.x);
    w.put(box_size.y);
    w.put(boundary[0]);
    w.put(boundary[1]);
    w.seq_iter(radius.copied());
    w.seq_iter(mass.copied());
    w.seq(species);
    w.seq_iter(positions.iter().map(|p| p.x));
    w.seq_iter(positions.iter().map(|p| p.y));
    w.seq_iter(velocities.iter().map(|p| p.x));
    w.seq_iter(velocities.iter().map(|p| p.y));
    for k in 0..2 {
        if images.is_empty() {
            w.seq_iter(std::iter::repeat_n(0i32, positions.len()));
        } else {
            w.seq_iter(images.iter().map(|m| m[k]));
        }
    }
}

impl Snapshot {
    /// The snapshot of an engine state.
    pub fn from_state(s: &State) -> Self {
        Snapshot {
            time: s.time,
            box_size: s.sim_box.size,
            boundary: [
                boundary_code(&s.sim_box.boundary[0]),
                boundary_code(&s.sim_box.boundary[1]),
            ],
            species_radius: s.species.iter().map(|sp| sp.radius).collect(),
            species_mass: s.species.iter().map(|sp| sp.mass).collect(),
            species: s.species_of.clone(),
            positions: s.positions.clone(),
            velocities: s.velocities.clone(),
            images: if s.images.is_empty() {
                vec![[0; 2]; s.len()]
            } else {
                s.images.clone()
            },
        }
    }

    /// Number of discs.
    pub fn len(&self) -> usize {
        self.positions.len()
    }

    /// True when there are no discs.
    pub fn is_empty(&self) -> bool {
        self.positions.is_empty()
    }

    /// Mass of disc `k` (mass).
    pub fn mass(&self, k: usize) -> f64 {
        self.species_mass[self.species[k] as usize]
    }

    /// Encode as CDR into `w` (which is reset first).
    pub fn encode(&self, w: &mut CdrWriter) {
        encode_snapshot(
            w,
            (self.time, self.box_size, self.boundary),
            (self.species_radius.iter(), self.species_mass.iter()),
            &self.species,
            &self.positions,
            &self.velocities,
            &self.images,
        );
    }

    /// Encode the snapshot of `state` into `w` (reset first): the same bytes as
    /// [`Snapshot::from_state`] followed by [`Snapshot::encode`], without copying
    /// the state's arrays first.
    pub fn encode_state(state: &State, w: &mut CdrWriter) {
        let b = &state.sim_box.boundary;
        encode_snapshot(
            w,
            (
                state.time,
                state.sim_box.size,
                [boundary_code(&b[0]), boundary_code(&b[1])],
            ),
            (
                state.species.iter().map(|sp| &sp.radius),
                state.species.iter().map(|sp| &sp.mass),
            ),
            &state.species_of,
            &state.positions,
            &state.velocities,
            &state.images,
        );
    }

    /// Decode from CDR, checking that the arrays are consistent.
    pub fn decode(data: &[u8]) -> Result<Self, CdrError> {
        let mut r = CdrReader::new(data)?;
        let time = r.get("time")?;
        let bx = r.get("box_x")?;
        let by = r.get("box_y")?;
        let boundary = [r.get("boundary_x")?, r.get("boundary_y")?];
        let species_radius: Vec<f64> = r.seq("species_radius")?;
        let species_mass: Vec<f64> = r.seq("species_mass")?;
        let species: Vec<u16> = r.seq("species")?;
        let x: Vec<f64> = r.seq("x")?;
        let y: Vec<f64> = r.seq("y")?;
        let vx: Vec<f64> = r.seq("vx")?;
        let vy: Vec<f64> = r.seq("vy")?;
        // Snapshots before log format 2.1 end here.
        let (image_x, image_y): (Vec<i32>, Vec<i32>) = if r.remaining() == 0 {
            (Vec::new(), Vec::new())
        } else {
            (r.seq("image_x")?, r.seq("image_y")?)
        };
        let n = species.len();
        let m = if image_x.is_empty() { 0 } else { n };
        for (field, len, want) in [
            ("x", x.len(), n),
            ("y", y.len(), n),
            ("vx", vx.len(), n),
            ("vy", vy.len(), n),
            ("image_x", image_x.len(), m),
            ("image_y", image_y.len(), m),
        ] {
            if len != want {
                return Err(CdrError::Invalid {
                    field,
                    problem: format!("{len} entries, but `species` has {n}"),
                });
            }
        }
        if species_mass.len() != species_radius.len() {
            return Err(CdrError::Invalid {
                field: "species_mass",
                problem: format!(
                    "{} entries, but `species_radius` has {}",
                    species_mass.len(),
                    species_radius.len()
                ),
            });
        }
        if let Some(&s) = species
            .iter()
            .find(|&&s| s as usize >= species_radius.len())
        {
            return Err(CdrError::Invalid {
                field: "species",
                problem: format!(
                    "species index {s} but only {} species",
                    species_radius.len()
                ),
            });
        }
        Ok(Snapshot {
            time,
            box_size: DVec2::new(bx, by),
            boundary,
            species_radius,
            species_mass,
            species,
            positions: x.iter().zip(&y).map(|(&a, &b)| DVec2::new(a, b)).collect(),
            velocities: vx
                .iter()
                .zip(&vy)
                .map(|(&a, &b)| DVec2::new(a, b))
                .collect(),
            images: image_x
                .iter()
                .zip(&image_y)
                .map(|(&a, &b)| [a, b])
                .collect(),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use carom_core::{Boundary, SimBox, Species};

    /// Three discs of two species (masses 0.5 and 2.5, neither 1) in a box
    /// periodic in x and walled in y.
    fn state() -> State {
        State {
            sim_box: SimBox {
                size: DVec2::new(7.5, 4.0),
                boundary: [Boundary::Periodic, Boundary::Walls { restitution: 0.9 }],
            },
            species: vec![Species::new(2, 0.5, 0.5), Species::new(1, 0.7, 2.5)],
            species_of: vec![0, 0, 1],
            positions: vec![
                DVec2::new(1.0, 1.0),
                DVec2::new(3.0, 2.0),
                DVec2::new(5.5, 2.5),
            ],
            velocities: vec![
                DVec2::new(0.1, -0.2),
                DVec2::new(-1.5, 0.25),
                DVec2::new(0.0, 3.0),
            ],
            images: vec![[2, 0], [-1, 0], [40_000, 0]],
            time: 2.75,
        }
    }

    #[test]
    fn a_state_encodes_as_its_snapshot() {
        let state = state();
        let (mut a, mut b) = (CdrWriter::new(), CdrWriter::new());
        Snapshot::from_state(&state).encode(&mut a);
        // Into a writer that held an earlier, longer message.
        b.reuse(vec![0xAB; 4096]);
        Snapshot::encode_state(&state, &mut b);
        assert_eq!(a.bytes(), b.bytes());
        assert_eq!(
            Snapshot::decode(b.bytes()).unwrap(),
            Snapshot::from_state(&state)
        );
    }

    /// A snapshot of log format 2.0 ends after `vy`: it reads with no images; one
    /// of a state without images is written with images 0.
    #[test]
    fn images_are_optional_on_reading_and_zero_when_untracked() {
        let state = state();
        let mut w = CdrWriter::new();
        Snapshot::encode_state(&state, &mut w);
        let old = &w.bytes()[..w.bytes().len() - 2 * (4 + 3 * 4)];
        let read = Snapshot::decode(old).unwrap();
        assert!(read.images.is_empty());
        assert_eq!(read.positions, state.positions);
        let untracked = State {
            images: Vec::new(),
            ..state
        };
        Snapshot::encode_state(&untracked, &mut w);
        let read = Snapshot::decode(w.bytes()).unwrap();
        assert_eq!(read.images, vec![[0, 0]; 3]);
        assert_eq!(read, Snapshot::from_state(&untracked));
    }

    /// Found missing by mutation testing (docs/testing.md): each disc's mass is its
    /// species' mass, the boundary codes are 0 periodic and 1 walls, and the
    /// number of discs is the length of the arrays.
    #[test]
    fn a_snapshot_knows_its_discs_masses_and_boundaries() {
        let s = Snapshot::from_state(&state());
        assert_eq!(s.boundary, [0, 1]);
        assert_eq!((s.len(), s.is_empty()), (3, false));
        let masses: Vec<f64> = (0..s.len()).map(|k| s.mass(k)).collect();
        assert_eq!(masses, [0.5, 0.5, 2.5]);
        let none = Snapshot {
            species: vec![],
            positions: vec![],
            velocities: vec![],
            ..s
        };
        assert_eq!((none.len(), none.is_empty()), (0, true));
    }

    /// A snapshot whose arrays disagree is refused, naming the field; the last
    /// species index is accepted, one past it is not.
    #[test]
    fn an_inconsistent_snapshot_is_refused() {
        let good = Snapshot::from_state(&state());
        let refused = |s: &Snapshot| {
            let mut w = CdrWriter::new();
            s.encode(&mut w);
            match Snapshot::decode(w.bytes()) {
                Err(CdrError::Invalid { field, .. }) => field,
                other => panic!("accepted or wrong error: {other:?}"),
            }
        };
        let mut short = good.clone();
        short.velocities.pop();
        assert_eq!(refused(&short), "vx");
        let mut images = good.clone();
        images.images.pop();
        assert_eq!(refused(&images), "image_x");
        let mut masses = good.clone();
        masses.species_mass.push(1.5);
        assert_eq!(refused(&masses), "species_mass");
        let mut past = good.clone();
        past.species[2] = 2;
        assert_eq!(refused(&past), "species");
        let mut last = good.clone();
        last.species[0] = 1;
        let mut w = CdrWriter::new();
        last.encode(&mut w);
        assert_eq!(Snapshot::decode(w.bytes()).unwrap(), last);
    }
}
