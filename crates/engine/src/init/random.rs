//! Random placement: discs inserted one by one at uniformly random positions that
//! overlap no disc placed before, largest first (so that size-asymmetric mixtures
//! place too); meant for low density, and refused with the density reached when a
//! disc finds no room. Also the overlap test shared with explicit positions, which
//! are checked here (|r_i − r_j| ≥ a_i + a_j under the minimum image), and the
//! seeded shuffle every placement uses (the order of draws is part of what a seed
//! reproduces).

use super::spec::SystemSpec;
use crate::cells::{CellGrid, Link};
use crate::error::InitError;
use carom_core::observables::packing_fraction;
use carom_core::{DVec2, SimBox};
use rand::RngExt;
use rand_pcg::Pcg64;

/// Shuffle `v` in place with the seeded generator (Fisher–Yates, from the end; the
/// order of draws is part of what a seed reproduces).
pub(super) fn shuffle<T>(v: &mut [T], rng: &mut Pcg64) {
    for k in (1..v.len()).rev() {
        let j = rng.random_range(0..=k);
        v.swap(k, j);
    }
}

pub(super) fn random(
    spec: &SystemSpec,
    species_of: &[u16],
    rng: &mut Pcg64,
) -> Result<Vec<DVec2>, InitError> {
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

pub(super) fn check_explicit(
    spec: &SystemSpec,
    species_of: &[u16],
    p: &[DVec2],
) -> Result<(), InitError> {
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
