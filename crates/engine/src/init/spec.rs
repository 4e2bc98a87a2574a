//! What an initial state is asked to be: [`SystemSpec`], its placement and
//! velocity choices, and the one validation of a request.
//!
//! A request names the species (count, radius, mass), the box, the temperature
//! kT, the seed, the placement and the velocities. Every field is checked before
//! anything is drawn, each refusal naming the field, what is wrong and what is
//! allowed; so are the scales (speeds times box size must stay far from overflow).
//! [`SystemSpec::build`] (`init::build`) then places the discs and draws their
//! velocities.

use crate::error::InitError;
use carom_core::observables::packing_fraction;
use carom_core::{check_species, Boundary, DVec2, SimBox, Species};

/// How far relaxed or compressed placement has got, reported to the observer of
/// [`SystemSpec::build_observed`]: before every minimization step of relaxed
/// placement; after every rescale interval of compressed placement, and every
/// few thousand events within one (`compressing` then says how dense it is).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlacementProgress {
    /// Discs being placed.
    pub discs: usize,
    /// Minimization steps taken so far.
    pub steps: usize,
    /// The most steps relaxed placement takes before it gives up.
    pub max_steps: usize,
    /// Pairs and wall contacts still closer than the minimizer's margin
    /// (`init::relax::MARGIN`) allows; placement is done when none is left.
    /// Compressed placement: 1 while it grows the discs, 0 once done.
    pub close: usize,
    /// Compressed placement only: the packing fraction reached and the target.
    /// `steps` then counts rescale intervals and `max_steps` those the growth law
    /// needs to reach the target (physics.md §17), if it does not jam first.
    pub compressing: Option<Compressing>,
}

/// How dense compressed placement has got ([`PlacementProgress::compressing`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Compressing {
    /// Packing fraction now.
    pub packing_fraction: f64,
    /// Packing fraction asked for.
    pub target: f64,
    /// Reduced pressure Z = βPA/N over the last rescale interval (physics.md (17.7)).
    pub reduced_pressure: f64,
}

/// How the discs are placed.
#[derive(Debug, Clone, PartialEq)]
pub enum Placement {
    /// On the best-fitting lattice: any density up to 0.72 (N ≥ 34), and beyond it up
    /// to the densest lattice that fits the box.
    Lattice,
    /// Uniformly at random without overlap (low density only).
    Random,
    /// Random positions (one per cell of a grid of about N cells) made free of
    /// overlaps by minimizing a soft overlap energy (any mixture up to just below
    /// jamming, η ≈ 0.83 for the equimolar 1 : 1.4 mixture; see `init::relax`).
    Relaxed,
    /// At the given centre positions, one per disc (length).
    Explicit(Vec<DVec2>),
    /// Random at packing fraction `start`, then compressed to the requested radii by
    /// growing the discs at the relative rate `rate` (1/time) in the engine
    /// (physics.md §17; see `init::compressed`).
    Compressed {
        /// Relative growth rate γ (1/time).
        rate: f64,
        /// Packing fraction of the random start.
        start: f64,
    },
}

/// How initial velocities are drawn.
#[derive(Debug, Clone, PartialEq)]
pub enum Velocities {
    /// Maxwell–Boltzmann at the requested temperature, zero total momentum.
    MaxwellBoltzmann,
    /// Every disc of a species has the same speed, in a random direction, with the
    /// temperature 2K/f equal to kT (a deliberately non-equilibrium start).
    EqualSpeed,
    /// The given velocities, one per disc (length/time).
    Explicit(Vec<DVec2>),
}

/// Everything needed to build an initial [`State`](crate::State).
#[derive(Debug, Clone, PartialEq)]
pub struct SystemSpec {
    /// The species (count, radius, mass); discs are numbered species by species.
    pub species: Vec<Species>,
    /// The box.
    pub sim_box: SimBox,
    /// Temperature kT (energy) for drawn velocities.
    pub temperature: f64,
    /// Seed of the random generator (placement shuffles and velocities).
    pub seed: u64,
    /// Placement of the discs.
    pub placement: Placement,
    /// Initial velocities.
    pub velocities: Velocities,
}

/// Box edge lengths (L_x, L_y) giving packing fraction `eta` with aspect ratio
/// L_x/L_y = `aspect` for the given species (length).
pub fn box_size_for(species: &[Species], eta: f64, aspect: f64) -> DVec2 {
    let covered: f64 = species.iter().map(|s| s.count as f64 * s.disc_area()).sum();
    let area = covered / eta;
    let lx = (area * aspect).sqrt();
    DVec2::new(lx, area / lx)
}

/// The largest radius among the species with a count above 0 (length; 0 for
/// none): a species with count 0 sets neither the lattice spacing nor the cell
/// size, nor how narrow a box may be.
pub fn largest_radius(species: &[Species]) -> f64 {
    species
        .iter()
        .filter(|s| s.count > 0)
        .map(|s| s.radius)
        .fold(0.0, f64::max)
}

fn check_finite_positive(field: &str, x: f64) -> Result<(), InitError> {
    if !x.is_finite() || x <= 0.0 {
        return Err(InitError::invalid(
            field,
            format!("value {x} is not a positive finite number"),
            "finite numbers > 0",
        ));
    }
    Ok(())
}

impl SystemSpec {
    /// The reference system of physics.md: `n` discs of diameter σ = 1 and mass 1 at
    /// packing fraction `eta` in a square periodic box, on a lattice, with
    /// Maxwell–Boltzmann velocities at kT = 1 drawn from `seed`.
    pub fn periodic_fluid(n: usize, eta: f64, seed: u64) -> SystemSpec {
        let species = vec![Species::reference(n)];
        SystemSpec::square_box(species, eta, [Boundary::Periodic; 2], seed)
    }

    /// `species` on a lattice in a square box sized for packing fraction `eta`, with
    /// the boundaries `boundary` (x, y), and Maxwell–Boltzmann velocities at kT = 1
    /// drawn from `seed`.
    pub fn square_box(
        species: Vec<Species>,
        eta: f64,
        boundary: [Boundary; 2],
        seed: u64,
    ) -> SystemSpec {
        let size = box_size_for(&species, eta, 1.0);
        SystemSpec {
            species,
            sim_box: SimBox { size, boundary },
            temperature: 1.0,
            seed,
            placement: Placement::Lattice,
            velocities: Velocities::MaxwellBoltzmann,
        }
    }

    /// The largest radius of the species that have discs (length; see
    /// [`largest_radius`]).
    pub(super) fn largest_radius(&self) -> f64 {
        largest_radius(&self.species)
    }

    /// Check every field of the request (before anything is drawn).
    pub(super) fn validate(&self) -> Result<(), InitError> {
        check_species(&self.species).map_err(|p| {
            let field = match p.setting {
                Some((k, setting)) => format!("species[{k}].{setting}"),
                None => "species".to_owned(),
            };
            InitError::invalid(field, p.problem, p.allowed)
        })?;
        for (k, name) in ["x", "y"].iter().enumerate() {
            check_finite_positive(&format!("box.size.{name}"), self.sim_box.size[k])?;
            if let Boundary::Walls { restitution } = self.sim_box.boundary[k] {
                if !(0.0..=1.0).contains(&restitution) {
                    return Err(InitError::invalid(
                        format!("box.boundary.{name}.restitution"),
                        format!("value {restitution}"),
                        "0 ≤ restitution ≤ 1",
                    ));
                }
            }
            let a_max = self.largest_radius();
            if self.sim_box.size[k] <= 2.0 * a_max {
                return Err(InitError::invalid(
                    format!("box.size.{name}"),
                    format!(
                        "edge {} is not longer than the largest diameter {}",
                        self.sim_box.size[k],
                        2.0 * a_max
                    ),
                    "edges longer than the largest disc diameter",
                ));
            }
        }
        if !self.temperature.is_finite() || self.temperature < 0.0 {
            return Err(InitError::invalid(
                "temperature",
                format!("value {}", self.temperature),
                "finite kT ≥ 0",
            ));
        }
        // Drawn velocities have zero total momentum, which leaves a single disc at
        // rest: a temperature above 0 would be silently ignored.
        let discs: usize = self.species.iter().map(|s| s.count).sum();
        if discs == 1
            && self.temperature > 0.0
            && !matches!(self.velocities, Velocities::Explicit(_))
        {
            return Err(InitError::invalid(
                "temperature",
                format!(
                    "kT = {} for a single disc, which zero total momentum leaves at rest",
                    self.temperature
                ),
                "at least two discs, or explicit velocities",
            ));
        }
        let eta = packing_fraction(&self.species, &self.sim_box);
        if eta >= std::f64::consts::PI / (2.0 * 3f64.sqrt()) {
            return Err(InitError::invalid(
                "packing_fraction",
                format!("{eta:.4} is above hexagonal close packing"),
                "η < 0.9069 (lattice placement: always up to 0.72 at N ≥ 34, beyond that up to the \
                 densest lattice that fits the box)",
            ));
        }
        Ok(())
    }
}
