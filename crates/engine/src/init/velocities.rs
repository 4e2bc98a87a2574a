//! Initial velocities: Maxwell–Boltzmann at temperature kT (each component
//! Gaussian with variance kT/m, physics.md §6), or one speed per species in random
//! directions; either is shifted to zero total momentum where momentum is
//! conserved and scaled so that the kinetic temperature 2K/f (physics.md §5) equals
//! kT exactly.

use super::spec::SystemSpec;
use carom_core::observables::degrees_of_freedom;
use carom_core::DVec2;
use rand::RngExt;
use rand_distr::{Distribution, StandardNormal};
use rand_pcg::Pcg64;

pub(super) fn maxwell_boltzmann(
    spec: &SystemSpec,
    species_of: &[u16],
    rng: &mut Pcg64,
) -> Vec<DVec2> {
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

pub(super) fn equal_speed(spec: &SystemSpec, species_of: &[u16], rng: &mut Pcg64) -> Vec<DVec2> {
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
