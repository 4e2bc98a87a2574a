//! Initial states: placement of the discs and their velocities, reproducible from a
//! seed (a `rand_pcg` generator).
//!
//! * Lattice placement picks the arrangement whose closest pair of occupied sites is
//!   farthest apart, and leaves spare sites empty (spread evenly). In a fully periodic
//!   box it searches every lattice that fits the torus (q rows of p sites with shear
//!   k/q — the Hermite normal form — with up to 2N sites for N ≤ 500), so it reaches
//!   packing fraction 0.72 at aspect ratios in [1/4, 4] for every N ≥ 34 tested
//!   (34–300, 1000, 4096, 10007, 20000: `tests/initial_states.rs`), and for smaller N
//!   wherever one of these lattices fits. Of N ≤ 33 at seven aspect ratios, 14 cases
//!   have none: some because no arrangement at all reaches 0.72 (N = 3 in a square
//!   box: about 0.631 at most, by a numerical search), others only because theirs is
//!   not a lattice (N = 7 in a square box, which relaxed placement reaches, as the
//!   refusal suggests). With walls it uses square and triangular rows spread to the
//!   walls.
//! * Random placement inserts discs one by one at uniformly random non-overlapping
//!   positions, largest first (so that size-asymmetric mixtures place too); meant
//!   for low density.
//! * Relaxed placement draws random positions at the requested density, one in
//!   each cell of a grid of about N cells (so the density is even on large scales),
//!   and removes the overlaps by minimizing a soft overlap energy
//!   ([`crate::relax`]): disordered states of any mixture up to just below jamming.
//! * Velocities are Maxwell–Boltzmann at temperature kT (each component Gaussian with
//!   variance kT/m, physics.md §6), shifted to zero total momentum and scaled so that
//!   the kinetic temperature 2K/f equals kT exactly; or all of one speed per species.

use crate::cells::{CellGrid, Link};
use crate::error::InitError;
use crate::relax::Why;
use crate::state::{degrees_of_freedom, packing_fraction, State};
use carom_core::{Boundary, DVec2, SimBox, Species};
use rand::{RngExt, SeedableRng};
use rand_distr::{Distribution, StandardNormal};
use rand_pcg::Pcg64;
use std::ops::ControlFlow;

/// How far relaxed placement has got, reported to the observer of
/// [`SystemSpec::build_observed`] before every minimization step.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PlacementProgress {
    /// Discs being placed.
    pub discs: usize,
    /// Minimization steps taken so far.
    pub steps: usize,
    /// The most steps relaxed placement takes before it gives up.
    pub max_steps: usize,
    /// Pairs and wall contacts still closer than [`crate::relax::MARGIN`] allows;
    /// placement is done when none is left.
    pub close: usize,
}

/// How the discs are placed.
#[derive(Debug, Clone, PartialEq)]
pub enum Placement {
    /// On the best-fitting square or triangular lattice (any density up to ~0.72).
    Lattice,
    /// Uniformly at random without overlap (low density only).
    Random,
    /// Random positions (one per cell of a grid of about N cells) made free of
    /// overlaps by minimizing a soft overlap energy (any mixture up to just below
    /// jamming, η ≈ 0.83 for the equimolar 1 : 1.4 mixture; see [`crate::relax`]).
    Relaxed,
    /// At the given centre positions, one per disc (length).
    Explicit(Vec<DVec2>),
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

/// Everything needed to build an initial [`State`].
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

/// The largest allowed product of the fastest disc's speed and the longest box edge
/// (length²/time). The contact time (physics.md §2) squares products of a
/// separation and a relative velocity, and positions and kinetic energies square
/// or multiply these scales too: kept below 1e150, every such square stays far from
/// the overflow of f64 at 1.8e308 (an infinity there would stop every collision,
/// or put NaN into the event times).
pub const SPEED_TIMES_SIZE_LIMIT: f64 = 1e150;

/// Refuse velocities whose scale would overflow the engine's arithmetic (see
/// [`SPEED_TIMES_SIZE_LIMIT`]); `field` names where they came from. When even a
/// box one diameter across would pass (fastest speed × largest diameter within the
/// limit), the box is what is too large, and the error names `box.size`.
fn check_scales(
    spec: &SystemSpec,
    species_of: &[u16],
    velocities: &[DVec2],
    field: &str,
) -> Result<(), InitError> {
    let fastest = velocities.iter().map(|v| v.length()).fold(0.0, f64::max);
    let edge = spec.sim_box.size.max_element();
    let product = fastest * edge;
    if product.is_nan() || product > SPEED_TIMES_SIZE_LIMIT {
        let box_too_large = fastest * 2.0 * spec.largest_radius() <= SPEED_TIMES_SIZE_LIMIT;
        return Err(InitError::invalid(
            if box_too_large { "box.size" } else { field },
            format!(
                "the fastest disc's speed {fastest:.3e} times the longest box edge {edge:.3e} \
                 is {product:.3e}, beyond what f64 arithmetic on contact times can hold"
            ),
            format!("speed × box edge ≤ {SPEED_TIMES_SIZE_LIMIT:e}"),
        ));
    }
    let energy = crate::state::kinetic_energy(&spec.species, species_of, velocities);
    if !energy.is_finite() {
        return Err(InitError::invalid(
            field,
            "the total kinetic energy overflows f64",
            "masses and speeds whose Σ m v²/2 is finite",
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

    /// Check every field, place the discs and draw velocities.
    pub fn build(&self) -> Result<State, InitError> {
        let state = self.build_observed(&mut |_| ControlFlow::Continue(()))?;
        Ok(state.expect("an observer that never stops"))
    }

    /// [`SystemSpec::build`], reporting the progress of relaxed placement (the one
    /// placement that can take long: about a minute for 10⁶ discs, more near
    /// jamming) to `observe` before every minimization step. When `observe` breaks,
    /// building stops and returns `Ok(None)`. Other placements never call it.
    pub fn build_observed(
        &self,
        observe: &mut dyn FnMut(&PlacementProgress) -> ControlFlow<()>,
    ) -> Result<Option<State>, InitError> {
        self.validate()?;
        let n: usize = self.species.iter().map(|s| s.count).sum();
        let mut species_of = Vec::with_capacity(n);
        for (k, s) in self.species.iter().enumerate() {
            species_of.extend(std::iter::repeat_n(k as u16, s.count));
        }
        let mut rng = Pcg64::seed_from_u64(self.seed);
        let positions = match &self.placement {
            Placement::Lattice => lattice(self, &species_of, &mut rng)?,
            Placement::Random => random(self, &species_of, &mut rng)?,
            Placement::Relaxed => match relaxed(self, &species_of, &mut rng, observe)? {
                Some(p) => p,
                None => return Ok(None),
            },
            Placement::Explicit(p) => {
                check_explicit(self, &species_of, p)?;
                p.iter().map(|&r| self.sim_box.wrap(r)).collect()
            }
        };
        let velocities = match &self.velocities {
            Velocities::MaxwellBoltzmann => maxwell_boltzmann(self, &species_of, &mut rng),
            Velocities::EqualSpeed => equal_speed(self, &species_of, &mut rng),
            Velocities::Explicit(v) => {
                if v.len() != n {
                    return Err(InitError::invalid(
                        "velocities",
                        format!("{} velocities given for {n} discs", v.len()),
                        "exactly one velocity per disc",
                    ));
                }
                if let Some(k) = v.iter().position(|v| !v.is_finite()) {
                    return Err(InitError::invalid(
                        format!("velocities[{k}]"),
                        "velocity is not finite",
                        "finite numbers",
                    ));
                }
                v.clone()
            }
        };
        let field = match &self.velocities {
            Velocities::Explicit(_) => "velocities",
            _ => "temperature",
        };
        check_scales(self, &species_of, &velocities, field)?;
        Ok(Some(State {
            sim_box: self.sim_box,
            species: self.species.clone(),
            species_of,
            positions,
            velocities,
            time: 0.0,
        }))
    }

    /// The largest radius of the species that have discs (length; see
    /// [`largest_radius`]).
    fn largest_radius(&self) -> f64 {
        largest_radius(&self.species)
    }

    fn validate(&self) -> Result<(), InitError> {
        if self.species.is_empty() {
            return Err(InitError::invalid(
                "species",
                "no species given",
                "at least one species",
            ));
        }
        if self.species.len() > u16::MAX as usize {
            return Err(InitError::invalid(
                "species",
                "too many species",
                "at most 65535",
            ));
        }
        let mut n = 0usize;
        for (k, s) in self.species.iter().enumerate() {
            check_finite_positive(&format!("species[{k}].radius"), s.radius)?;
            check_finite_positive(&format!("species[{k}].mass"), s.mass)?;
            n += s.count;
        }
        if n == 0 {
            return Err(InitError::invalid(
                "species",
                "zero discs in total",
                "at least one disc",
            ));
        }
        if n >= u32::MAX as usize {
            return Err(InitError::invalid(
                "species",
                format!("{n} discs"),
                "fewer than 2^32 − 1 discs",
            ));
        }
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
                "η < 0.9069 (and ≤ 0.72 for lattice placement, at N ≥ 34 or where a lattice fits)",
            ));
        }
        Ok(())
    }
}

/// Sites along one axis: `count` coordinates and their spacing (∞ for one site on a
/// walled axis, which has no neighbour along it).
fn axis_sites(len: f64, periodic: bool, a: f64, count: usize) -> (Vec<f64>, f64) {
    if periodic {
        let s = len / count as f64;
        ((0..count).map(|k| (k as f64 + 0.5) * s).collect(), s)
    } else if count == 1 {
        (vec![len / 2.0], f64::INFINITY)
    } else {
        let s = (len - 2.0 * a) / (count - 1) as f64;
        // Clamped: a + (count − 1) s may round one ulp past len − a.
        (
            (0..count)
                .map(|k| (a + k as f64 * s).min(len - a))
                .collect(),
            s,
        )
    }
}

/// One candidate lattice: `rows` rows of `cols` sites, rows alternately shifted by
/// half a spacing when `shifted` (triangular), in a frame where rows run along `u`.
#[derive(Debug, Clone, Copy)]
struct Lattice {
    rows: usize,
    cols: usize,
    shifted: bool,
    /// When true, "rows" run along y (the frame is transposed).
    transposed: bool,
}

impl Lattice {
    /// (capacity, closest distance between two sites, including periodic images).
    fn quality(&self, lu: f64, lv: f64, pu: bool, pv: bool, a: f64) -> (usize, f64) {
        let su = if pu {
            lu / self.cols as f64
        } else if self.cols == 1 {
            f64::INFINITY
        } else {
            (lu - 2.0 * a) / (self.cols - 1) as f64
        };
        let sv = if pv {
            lv / self.rows as f64
        } else if self.rows == 1 {
            f64::INFINITY
        } else {
            (lv - 2.0 * a) / (self.rows - 1) as f64
        };
        if !self.shifted {
            return (self.rows * self.cols, su.min(sv));
        }
        // Shifted rows on a walled u axis hold one site fewer.
        let short = if pu { self.cols } else { self.cols - 1 };
        let cap = self.rows.div_ceil(2) * self.cols + (self.rows / 2) * short;
        let mut d = su.min((0.25 * su * su + sv * sv).sqrt());
        if self.rows > 1 {
            // Same-parity rows: two rows apart, or adjacent across a periodic edge
            // when the row count is odd.
            let same = if pv && self.rows % 2 == 1 {
                sv
            } else {
                2.0 * sv
            };
            d = d.min(same);
        }
        (cap, d)
    }

    fn sites(&self, sim_box: &SimBox, a: f64) -> Vec<DVec2> {
        let (ku, kv) = if self.transposed { (1, 0) } else { (0, 1) };
        let (lu, lv) = (sim_box.size[ku], sim_box.size[kv]);
        let (pu, pv) = (
            sim_box.boundary[ku].is_periodic(),
            sim_box.boundary[kv].is_periodic(),
        );
        let (us, su) = axis_sites(lu, pu, a, self.cols);
        let (vs, _) = axis_sites(lv, pv, a, self.rows);
        let mut out = Vec::new();
        for (r, &v) in vs.iter().enumerate() {
            let shift = self.shifted && r % 2 == 1;
            let cols = if shift && !pu {
                self.cols - 1
            } else {
                self.cols
            };
            for &u in us.iter().take(cols) {
                let u = if shift { u + 0.5 * su } else { u };
                let u = if pu { u.rem_euclid(lu) } else { u };
                let mut p = DVec2::ZERO;
                p[ku] = u;
                p[kv] = v;
                out.push(p);
            }
        }
        out
    }
}

/// A lattice in a box periodic on both axes: `q` rows of `p` sites, row j shifted
/// along x by j k/q of the site spacing. Every lattice with p q sites that fits the
/// torus has such a basis (its Hermite normal form), so this family holds every
/// periodic lattice arrangement; `k = 0` is square-like and `k = q/2` the usual
/// alternate-row triangular lattice.
#[derive(Debug, Clone, Copy)]
struct Sheared {
    p: usize,
    q: usize,
    k: usize,
}

impl Sheared {
    /// Basis vectors b1 = (L_x/p, 0), b2 = (k L_x/(p q), L_y/q) (length).
    fn basis(&self, size: DVec2) -> (DVec2, DVec2) {
        (
            DVec2::new(size.x / self.p as f64, 0.0),
            DVec2::new(
                size.x * self.k as f64 / (self.p * self.q) as f64,
                size.y / self.q as f64,
            ),
        )
    }

    /// Closest distance between two sites (including periodic images): the shortest
    /// nonzero lattice vector, by Lagrange–Gauss reduction of the basis.
    fn closest(&self, size: DVec2) -> f64 {
        let (mut u, mut v) = self.basis(size);
        if u.length_squared() > v.length_squared() {
            std::mem::swap(&mut u, &mut v);
        }
        loop {
            let mu = (u.dot(v) / u.length_squared()).round();
            v -= u * mu;
            if v.length_squared() >= u.length_squared() {
                return u.length();
            }
            std::mem::swap(&mut u, &mut v);
        }
    }

    fn sites(&self, size: DVec2) -> Vec<DVec2> {
        let (p, q) = (self.p as f64, self.q as f64);
        let mut out = Vec::with_capacity(self.p * self.q);
        for j in 0..self.q {
            let y = (j as f64 + 0.5) * size.y / q;
            let shift = j as f64 * self.k as f64 / q;
            for i in 0..self.p {
                let x = ((i as f64 + 0.5 + shift) * size.x / p).rem_euclid(size.x);
                out.push(DVec2::new(x.min(size.x * (1.0 - f64::EPSILON)), y));
            }
        }
        out
    }
}

/// A candidate arrangement of lattice sites.
#[derive(Debug, Clone, Copy)]
enum Arrangement {
    /// Rows, plain or alternately shifted (any boundaries), with the rule choosing
    /// which sites are occupied when there are more sites than discs.
    Rows(Lattice, Selection),
    /// A sheared lattice (periodic on both axes).
    Sheared(Sheared),
}

/// Which n of m ≥ n sites (in row order) are occupied.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Selection {
    /// Sites ⌊k m/n⌋: spread evenly.
    Spread,
    /// Sites ⌊k (m−1)/(n−1)⌋: spread evenly including the last site (corners).
    Ends,
}

impl Selection {
    fn pick<T: Copy>(self, sites: &[T], n: usize) -> Vec<T> {
        let m = sites.len();
        match self {
            Selection::Ends if n > 1 => (0..n).map(|k| sites[k * (m - 1) / (n - 1)]).collect(),
            _ => (0..n).map(|k| sites[k * m / n]).collect(),
        }
    }
}

impl Arrangement {
    /// The n occupied sites.
    fn occupied(&self, sim_box: &SimBox, a: f64, n: usize) -> Vec<DVec2> {
        match self {
            Arrangement::Rows(l, sel) => sel.pick(&l.sites(sim_box, a), n),
            Arrangement::Sheared(l) => Selection::Spread.pick(&l.sites(sim_box.size), n),
        }
    }
}

/// Closest distance between any two of `pts` (minimum image on periodic axes); ∞ for
/// fewer than two points. O(n²): for small n only.
fn closest_pair_distance(sim_box: &SimBox, pts: &[DVec2]) -> f64 {
    let mut d2 = f64::INFINITY;
    for (i, p) in pts.iter().enumerate() {
        for q in &pts[i + 1..] {
            d2 = d2.min(sim_box.minimum_image(*q - *p).length_squared());
        }
    }
    d2.sqrt()
}

/// The best lattice for `n` discs of largest radius `a` in `sim_box`: the candidate
/// whose closest pair of sites is farthest apart (fewer spare sites on ties).
/// Returns it with that distance.
fn best_lattice(sim_box: &SimBox, n: usize, a: f64) -> (Arrangement, f64) {
    let mut best: Option<(Arrangement, f64, usize)> = None;
    fn consider(
        best: &mut Option<(Arrangement, f64, usize)>,
        arr: Arrangement,
        d: f64,
        cap: usize,
    ) {
        let better = match *best {
            None => true,
            Some((_, bd, bcap)) => d > bd || (d == bd && cap < bcap),
        };
        if better {
            *best = Some((arr, d, cap));
        }
    }
    let fully_periodic = sim_box.boundary.iter().all(|b| b.is_periodic());
    if fully_periodic {
        // Row counts to try: all of them (with up to 2n sites) for small n, else a
        // wide band around the row count of an ideal triangular lattice.
        let ideal = (n as f64 * sim_box.size.y / sim_box.size.x * 3f64.sqrt() / 2.0).sqrt();
        let (q_lo, q_hi) = if n <= 500 {
            (1, 2 * n)
        } else {
            ((ideal / 2.0) as usize, (2.0 * ideal) as usize + 1)
        };
        for q in q_lo.max(1)..=q_hi.min(2 * n) {
            // Columns: from the fewest that hold n discs; for small n up to 2n sites
            // (a sparser-looking lattice can have a better shape).
            let p0 = n.div_ceil(q).max(1);
            let p_hi = if n <= 500 {
                (2 * n / q).max(p0)
            } else {
                p0 + 1
            };
            for p in p0..=p_hi {
                // b1 is a lattice vector, so L_x/p bounds the closest distance: no shear
                // of a lattice with this many columns can beat the best found so far.
                if best.is_some_and(|(_, bd, _)| sim_box.size.x / p as f64 <= bd) {
                    break;
                }
                for k in 0..q {
                    let l = Sheared { p, q, k };
                    consider(
                        &mut best,
                        Arrangement::Sheared(l),
                        l.closest(sim_box.size),
                        p * q,
                    );
                }
            }
        }
    }
    for transposed in [false, true] {
        let (ku, kv) = if transposed { (1, 0) } else { (0, 1) };
        let (lu, lv) = (sim_box.size[ku], sim_box.size[kv]);
        let (pu, pv) = (
            sim_box.boundary[ku].is_periodic(),
            sim_box.boundary[kv].is_periodic(),
        );
        for shifted in [false, true] {
            for rows in 1..=n {
                // Fewest columns whose capacity holds n discs.
                let mut lat = Lattice {
                    rows,
                    cols: n.div_ceil(rows),
                    shifted,
                    transposed,
                };
                while lat.quality(lu, lv, pu, pv, a).0 < n {
                    lat.cols += 1;
                }
                let (cap, d) = lat.quality(lu, lv, pu, pv, a);
                consider(&mut best, Arrangement::Rows(lat, Selection::Spread), d, cap);
                if cap > n && n <= 64 && !fully_periodic {
                    // In small walled boxes the occupied subset can be much better
                    // spaced than the full lattice (two discs on a diagonal).
                    let sites = lat.sites(sim_box, a);
                    for sel in [Selection::Spread, Selection::Ends] {
                        let d = closest_pair_distance(sim_box, &sel.pick(&sites, n));
                        consider(&mut best, Arrangement::Rows(lat, sel), d, cap);
                    }
                }
            }
        }
    }
    let (lat, d, _) = best.expect("at least one candidate lattice");
    (lat, d)
}

/// How many decimals (6 to 12) show `limit` and the refused density `eta` as
/// different numbers: a lattice that only just fails (its closest sites exactly at
/// contact) has a limit within about 10⁻⁹ of the density asked for.
fn decimals_apart(limit: f64, eta: f64) -> usize {
    (6..=12)
        .find(|&p| format!("{:.p$}", round_down(limit, p)) != format!("{eta:.p$}"))
        .unwrap_or(12)
}

/// `x` rounded down to `p` decimals, so that "η < x" printed with `p` decimals stays
/// true of the limit `x`.
fn round_down(x: f64, p: usize) -> f64 {
    let scale = 10f64.powi(p as i32);
    (x * scale).floor() / scale
}

/// The largest packing fraction the lattice placement reaches for these species in a
/// box of this aspect ratio and these boundaries (by bisection on η; for messages).
fn lattice_limit(spec: &SystemSpec) -> f64 {
    let n: usize = spec.species.iter().map(|s| s.count).sum();
    let a = spec.largest_radius();
    let aspect = spec.sim_box.size.x / spec.sim_box.size.y;
    let (mut lo, mut hi) = (0.0, 0.9069);
    for _ in 0..40 {
        let mid = 0.5 * (lo + hi);
        let mut b = spec.sim_box;
        b.size = box_size_for(&spec.species, mid, aspect);
        if apart(best_lattice(&b, n, a).1, a) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    lo
}

/// The relative gap (of the contact distance) that lattice placement leaves at
/// least between the closest discs. Discs placed exactly at contact are not
/// overlapping, but they are no state to start from: in a row of touching discs
/// round a periodic box or from wall to wall (a lattice exactly at its closest
/// packing, such as 1020 discs in a periodic 30 × 30 box, or 100 in a walled
/// 10 × 10 one) each collision at t = 0 sets off the next, and the momentum goes
/// round or to and fro forever without time advancing. The gap, far above the rounding
/// of the positions (about 10⁻¹⁶ of the box), lets time advance between them.
const LATTICE_GAP: f64 = 1e-9;

/// Whether lattice sites `d` apart hold discs of radius `a` with the gap
/// [`LATTICE_GAP`] between them.
fn apart(d: f64, a: f64) -> bool {
    d >= 2.0 * a * (1.0 + LATTICE_GAP)
}

fn lattice(
    spec: &SystemSpec,
    species_of: &[u16],
    rng: &mut Pcg64,
) -> Result<Vec<DVec2>, InitError> {
    let n = species_of.len();
    let a = spec.largest_radius();
    let (lat, d) = best_lattice(&spec.sim_box, n, a);
    if !apart(d, a) {
        let eta = packing_fraction(&spec.species, &spec.sim_box);
        let limit = lattice_limit(spec);
        let p = decimals_apart(limit, eta);
        let problem = if d >= 2.0 * a * (1.0 - LATTICE_GAP) {
            format!(
                "{eta:.p$} is the density at which lattice placement for N = {n} in this box \
                 has its closest sites exactly one diameter ({}) apart: the discs would \
                 start in contact, and a row of touching discs round the periodic box or \
                 from wall to wall passes its momentum on forever at one instant",
                2.0 * a
            )
        } else {
            format!(
                "{eta:.4} is beyond what lattice placement reaches for N = {n} in this box \
                 (closest sites {d:.6} apart, diameter {})",
                2.0 * a
            )
        };
        return Err(InitError::invalid(
            "packing_fraction",
            problem,
            format!(
                "η < {:.p$} for this N, box shape and boundaries; relaxed placement, not \
                 tied to a lattice, may reach more",
                round_down(limit, p)
            ),
        ));
    }
    let mut chosen = lat.occupied(&spec.sim_box, a, n);
    // Shuffle which disc sits where, so species mix.
    shuffle(&mut chosen, rng);
    Ok(chosen)
}

/// Shuffle `v` in place with the seeded generator (Fisher–Yates, from the end; the
/// order of draws is part of what a seed reproduces).
fn shuffle<T>(v: &mut [T], rng: &mut Pcg64) {
    for k in (1..v.len()).rev() {
        let j = rng.random_range(0..=k);
        v.swap(k, j);
    }
}

fn random(spec: &SystemSpec, species_of: &[u16], rng: &mut Pcg64) -> Result<Vec<DVec2>, InitError> {
    let n = species_of.len();
    let a_max = spec.largest_radius();
    let mut grid = CellGrid::new(&spec.sim_box, 2.0 * a_max, n);
    let mut links = vec![Link::UNLINKED; n];
    // Largest discs first: a large disc needs a hole its own size, which the small
    // ones would already have filled (a radius ratio of 4 at η = 0.25 failed
    // small-first). The discs keep their numbers; only the order of insertion (and
    // with it the use of the seeded generator) follows the radius. Equal radii keep
    // their order, so a monodisperse system is placed as before.
    let radius = |i: usize| spec.species[species_of[i] as usize].radius;
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&i, &j| radius(j).total_cmp(&radius(i)));
    let mut pos = vec![DVec2::ZERO; n];
    let mut placed_so_far = 0;
    const ATTEMPTS: usize = 100_000;
    for i in order {
        let s = species_of[i];
        let a = radius(i);
        let mut placed = false;
        for _ in 0..ATTEMPTS {
            let mut r = DVec2::ZERO;
            for k in 0..2 {
                let l = spec.sim_box.size[k];
                r[k] = if spec.sim_box.boundary[k].is_periodic() {
                    rng.random::<f64>() * l
                } else {
                    a + rng.random::<f64>() * (l - 2.0 * a)
                };
            }
            if !overlaps_any(&grid, &links, &spec.sim_box, &pos, radius, r, a) {
                let c = grid.coords_of(r);
                grid.insert(&mut links, i as u32, c);
                pos[i] = r;
                placed_so_far += 1;
                placed = true;
                break;
            }
        }
        if !placed {
            return Err(InitError::invalid(
                "placement",
                format!(
                    "random placement found no free spot for disc {i} (species {s}, radius {a}) \
                     after {ATTEMPTS} tries, with {placed_so_far} of {n} discs placed (largest \
                     first), at η = {:.4}",
                    packing_fraction(&spec.species, &spec.sim_box)
                ),
                "\"random\" at low density (η ≲ 0.4); use \"lattice\" for dense systems",
            ));
        }
    }
    Ok(pos)
}

/// Most minimization steps of relaxed placement (about 2 minutes at N = 10⁴; the
/// equimolar 1 : 1.4 mixture at η = 0.83 needs about a thousand, and is found
/// jammed at 0.85 after some 10⁴).
const RELAX_STEPS: usize = 100_000;

/// Relaxed placement (see [`crate::relax`]); `None` when `observe` stopped it.
fn relaxed(
    spec: &SystemSpec,
    species_of: &[u16],
    rng: &mut Pcg64,
    observe: &mut dyn FnMut(&PlacementProgress) -> ControlFlow<()>,
) -> Result<Option<Vec<DVec2>>, InitError> {
    let radius = |i: usize| spec.species[species_of[i] as usize].radius;
    let reach = 4.0 * spec.largest_radius() * crate::relax::INFLATE;
    for (k, name) in ["x", "y"].iter().enumerate() {
        let l = spec.sim_box.size[k];
        if spec.sim_box.boundary[k].is_periodic() && l <= reach {
            return Err(InitError::invalid(
                format!("box.size.{name}"),
                format!("periodic edge {l} is too short for relaxed placement"),
                format!("periodic edges longer than {reach:.6} (twice the largest contact distance, with a margin), or \"lattice\" placement"),
            ));
        }
    }
    let radii: Vec<f64> = (0..species_of.len()).map(radius).collect();
    // One disc per cell of a grid of about N cells, at a uniformly random place in
    // it (a jittered grid; the cells left over are chosen at random), so that the
    // discs are spread evenly on scales beyond a few diameters. From uniformly
    // random positions, with only the overlaps removed, the state was uneven on
    // large scales and started a collective flow: for 4000 discs of the 1 : 1.4
    // mixture at η = 0.78 the flow averaged over 4 × 4 blocks held 1.5 % of the
    // kinetic energy at t = 1, four times its equilibrium share, and still 1.5
    // times at t = 8, and the speeds failed Maxwell–Boltzmann over t ∈ [1, 10]
    // (p ≈ 1e-5 to 1e-10). From the jittered grid the flow is at its
    // equilibrium share from the start.
    let n = radii.len();
    let size = spec.sim_box.size;
    let nx = ((n as f64 * size.x / size.y).sqrt().round() as usize).clamp(1, n);
    let ny = n.div_ceil(nx);
    let mut cells: Vec<usize> = (0..nx * ny).collect();
    shuffle(&mut cells, rng);
    cells.truncate(n);
    cells.sort_unstable();
    // Shuffle which disc takes which cell, so the species mix.
    shuffle(&mut cells, rng);
    let cell = DVec2::new(size.x / nx as f64, size.y / ny as f64);
    let start: Vec<DVec2> = cells
        .iter()
        .map(|&c| {
            let corner = DVec2::new((c % nx) as f64, (c / nx) as f64) * cell;
            let r = corner + DVec2::new(rng.random::<f64>(), rng.random::<f64>()) * cell;
            // Inside the box although rounding may put a coordinate at L.
            DVec2::new(
                r.x.min(size.x * (1.0 - f64::EPSILON)),
                r.y.min(size.y * (1.0 - f64::EPSILON)),
            )
        })
        .collect();
    let mut report = |steps, close| {
        observe(&PlacementProgress {
            discs: n,
            steps,
            max_steps: RELAX_STEPS,
            close,
        })
    };
    let relaxed = crate::relax::relax(&spec.sim_box, &radii, start, RELAX_STEPS, &mut report);
    let e = match relaxed {
        Ok(p) => return Ok(Some(p)),
        Err(e) => e,
    };
    let eta = packing_fraction(&spec.species, &spec.sim_box);
    let why = match e.why {
        Why::Stopped => return Ok(None),
        Why::Jammed => format!(
            "the discs jammed with {} pairs or wall contacts still overlapping",
            e.close
        ),
        Why::OutOfSteps => format!(
            "{} pairs or wall contacts still too close after {} minimization steps",
            e.close, e.steps
        ),
    };
    Err(InitError::invalid(
        "packing_fraction",
        format!("{eta:.4} is too dense for relaxed placement in this box: {why}"),
        "η below the jamming density of the mixture (about 0.84 for discs; \
             0.83 works for an equimolar 1 : 1.4 mixture), or \"lattice\" placement",
    ))
}

/// Whether a disc of radius `a` at `r` would overlap one of the discs already in
/// the grid's lists (`links`), at positions `pos` with radii `radius(j)`.
fn overlaps_any(
    grid: &CellGrid,
    links: &[Link],
    sim_box: &SimBox,
    pos: &[DVec2],
    radius: impl Fn(usize) -> f64,
    r: DVec2,
    a: f64,
) -> bool {
    grid.discs_near(links, grid.coords_of(r)).any(|j| {
        let sigma = a + radius(j as usize);
        sim_box.minimum_image(pos[j as usize] - r).length_squared() < sigma * sigma
    })
}

fn check_explicit(spec: &SystemSpec, species_of: &[u16], p: &[DVec2]) -> Result<(), InitError> {
    let n = species_of.len();
    if p.len() != n {
        return Err(InitError::invalid(
            "positions",
            format!("{} positions given for {n} discs", p.len()),
            "exactly one position per disc",
        ));
    }
    for (i, r) in p.iter().enumerate() {
        let a = spec.species[species_of[i] as usize].radius;
        for (k, name) in ["x", "y"].iter().enumerate() {
            let l = spec.sim_box.size[k];
            let ok = r[k].is_finite()
                && if spec.sim_box.boundary[k].is_periodic() {
                    (0.0..l).contains(&r[k])
                } else {
                    r[k] >= a && r[k] <= l - a
                };
            if !ok {
                return Err(InitError::invalid(
                    format!("positions[{i}].{name}"),
                    format!("value {} lies outside the box", r[k]),
                    if spec.sim_box.boundary[k].is_periodic() {
                        format!("0 ≤ {name} < {l}")
                    } else {
                        format!(
                            "{a} ≤ {name} ≤ {} (centre at least one radius from the walls)",
                            l - a
                        )
                    },
                ));
            }
        }
    }
    // Overlap check through a cell grid.
    let a_max = spec.largest_radius();
    let mut grid = CellGrid::new(&spec.sim_box, 2.0 * a_max, n);
    let mut links = vec![Link::UNLINKED; n];
    let radius = |j: usize| spec.species[species_of[j] as usize].radius;
    for (i, &r) in p.iter().enumerate() {
        let a = radius(i);
        if overlaps_any(&grid, &links, &spec.sim_box, &p[..i], radius, r, a) {
            // Find the partner for the message.
            for (j, &q) in p[..i].iter().enumerate() {
                let sigma = a + radius(j);
                let d = spec.sim_box.minimum_image(q - r).length();
                if d < sigma {
                    return Err(InitError::Overlap {
                        i: j,
                        j: i,
                        distance: d,
                        sigma,
                    });
                }
            }
        }
        grid.insert(&mut links, i as u32, grid.coords_of(r));
    }
    Ok(())
}

fn maxwell_boltzmann(spec: &SystemSpec, species_of: &[u16], rng: &mut Pcg64) -> Vec<DVec2> {
    let mut v: Vec<DVec2> = species_of
        .iter()
        .map(|&s| {
            let sd = (spec.temperature / spec.species[s as usize].mass).sqrt();
            let x: f64 = StandardNormal.sample(rng);
            let y: f64 = StandardNormal.sample(rng);
            DVec2::new(x, y) * sd
        })
        .collect();
    zero_momentum(spec, species_of, &mut v);
    scale_to_temperature(spec, species_of, &mut v);
    v
}

fn equal_speed(spec: &SystemSpec, species_of: &[u16], rng: &mut Pcg64) -> Vec<DVec2> {
    // Discs of a species come in ± pairs, and an odd number of them ends with three
    // at 120° to each other, so that momentum is zero and speeds equal. (A species
    // of one disc cannot balance itself: its momentum is left as it is.)
    let n = species_of.len();
    let f = degrees_of_freedom(n, &spec.sim_box) as f64;
    let mut v = vec![DVec2::ZERO; n];
    let mut k = 0;
    while k < n {
        let s = species_of[k] as usize;
        // Discs of this species left, counted up to 4 (enough to tell a final three
        // from a pair; counting them all made this O(N²)).
        let left = species_of[k..]
            .iter()
            .take(4)
            .take_while(|&&x| x as usize == s)
            .count();
        let speed = (2.0 * spec.temperature * f / (2.0 * n as f64) / spec.species[s].mass).sqrt();
        let phi = rng.random::<f64>() * std::f64::consts::TAU;
        let u = DVec2::from_angle(phi) * speed;
        let group = if left == 3 { 3 } else { left.min(2) };
        let third = std::f64::consts::TAU / 3.0;
        for (m, vk) in v[k..k + group].iter_mut().enumerate() {
            *vk = match (group, m) {
                (2, 1) => -u,
                (3, m) => DVec2::from_angle(phi + m as f64 * third) * speed,
                _ => u,
            };
        }
        k += group;
    }
    v
}

fn zero_momentum(spec: &SystemSpec, species_of: &[u16], v: &mut [DVec2]) {
    let mut p = DVec2::ZERO;
    let mut m = 0.0;
    for (vi, &s) in v.iter().zip(species_of) {
        let ms = spec.species[s as usize].mass;
        p += *vi * ms;
        m += ms;
    }
    let vcm = p / m;
    for vi in v.iter_mut() {
        *vi -= vcm;
    }
}

fn scale_to_temperature(spec: &SystemSpec, species_of: &[u16], v: &mut [DVec2]) {
    let k = crate::state::kinetic_energy(&spec.species, species_of, v);
    let f = degrees_of_freedom(v.len(), &spec.sim_box) as f64;
    if k > 0.0 && f > 0.0 {
        let scale = (spec.temperature * f / (2.0 * k)).sqrt();
        for vi in v.iter_mut() {
            *vi *= scale;
        }
    }
}
