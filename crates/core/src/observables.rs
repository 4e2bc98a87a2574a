//! Thermodynamic observables of a system of discs: the one definition of each.
//!
//! Degrees of freedom f = 2N − (periodic axes), kT = 2K/f, the packing fraction,
//! the area disc centres can reach in a walled box (each species its own), and the
//! two pressure estimators: the collision virial in a periodic box and the wall
//! impulse in a box with walls (physics.md §5, Eq. 5.1–5.8). The engine's running
//! totals, the `/thermo` writer and `carom analyze` all call these functions.

use crate::{SimBox, Species};

/// Number of discs N = Σ_s N_s.
pub fn disc_count(species: &[Species]) -> usize {
    species.iter().map(|s| s.count).sum()
}

/// Degrees of freedom f = 2N − (number of periodic axes) (physics.md §5): each
/// periodic axis conserves one momentum component.
pub fn degrees_of_freedom(n: usize, sim_box: &SimBox) -> usize {
    (2 * n).saturating_sub(sim_box.conserved_momentum_components())
}

/// Kinetic temperature kT = 2K/f (energy), with f at least 1.
pub fn temperature(kinetic_energy: f64, degrees_of_freedom: usize) -> f64 {
    2.0 * kinetic_energy / degrees_of_freedom.max(1) as f64
}

/// Packing fraction η = Σ_s N_s π a_s² / (L_x L_y).
pub fn packing_fraction(species: &[Species], sim_box: &SimBox) -> f64 {
    species
        .iter()
        .map(|s| s.count as f64 * s.disc_area())
        .sum::<f64>()
        / sim_box.area()
}

/// True when at least one axis has hard walls.
pub fn has_walls(sim_box: &SimBox) -> bool {
    sim_box.conserved_momentum_components() < 2
}

/// ℓ_k(a): the extent along axis `k` that the centre of a disc of radius `a`
/// reaches, L_k − 2a between walls and L_k on a periodic axis (length).
pub fn reachable_length(sim_box: &SimBox, k: usize, radius: f64) -> f64 {
    let l = sim_box.size[k];
    if sim_box.boundary[k].is_periodic() {
        l
    } else {
        l - 2.0 * radius
    }
}

/// The area the centres of a mixture can reach, A = N / Σ_s (N_s / A_s) with
/// A_s = ℓ_x(a_s) ℓ_y(a_s) (length², physics.md §5): the area at which an ideal
/// gas of the same species has the same mean density. The box area when periodic.
pub fn accessible_area(species: &[Species], sim_box: &SimBox) -> f64 {
    if !has_walls(sim_box) {
        return sim_box.area();
    }
    let per_area: f64 = species
        .iter()
        .filter(|s| s.count > 0)
        .map(|s| {
            let a_s =
                reachable_length(sim_box, 0, s.radius) * reachable_length(sim_box, 1, s.radius);
            s.count as f64 / a_s
        })
        .sum();
    disc_count(species) as f64 / per_area
}

/// Compressibility factor from the collision virial in a periodic box,
/// Z = βPA/N = 1 + W/(N kT) with W = Σ r_ij·Δp_i / (2t) (physics.md §5).
/// `virial_sum` is Σ r_ij·Δp_i over a window of length `t`.
pub fn virial_z(n: usize, kt: f64, virial_sum: f64, t: f64) -> f64 {
    let w = virial_sum / (2.0 * t);
    1.0 + w / (n.max(1) as f64 * kt)
}

/// Compressibility factor from the wall impulse in a box with walls, pooled over
/// the walled axes: Z = J / (2 t kT Σ_{k walled} Σ_s N_s / ℓ_k(a_s)) (physics.md §5),
/// where `wall_impulse` J is the total impulse on every wall over a window of
/// length `t`. An ideal gas of any mixture gives Z = 1 exactly.
pub fn wall_z(species: &[Species], sim_box: &SimBox, kt: f64, wall_impulse: f64, t: f64) -> f64 {
    let ideal_rate: f64 = (0..2)
        .filter(|&k| !sim_box.boundary[k].is_periodic())
        .flat_map(|k| {
            species
                .iter()
                .filter(|s| s.count > 0)
                .map(move |s| s.count as f64 / reachable_length(sim_box, k, s.radius))
        })
        .sum();
    wall_impulse / (2.0 * t * kt * ideal_rate)
}

/// Pressure from the collision virial in a periodic box, P = (N kT + W)/A with
/// W = Σ r_ij·Δp_i / (2t) (physics.md §5): [`pressure`] of [`virial_z`], written in
/// this order (as the `/thermo` records always have been) so its bits stay the same.
pub fn virial_pressure(n: usize, kt: f64, virial_sum: f64, t: f64, area: f64) -> f64 {
    let w = virial_sum / (2.0 * t);
    (n.max(1) as f64 * kt + w) / area
}

/// Pair collisions per disc per unit time, ω = 2 N_pair / (N t) (physics.md §7):
/// each pair collision involves two discs.
pub fn collision_rate(pair_collisions: f64, n: usize, t: f64) -> f64 {
    2.0 * pair_collisions / (n.max(1) as f64 * t)
}

/// Pressure P = Z N kT / A (energy/length²), with A the box area when periodic
/// and [`accessible_area`] with walls.
pub fn pressure(z: f64, n: usize, kt: f64, area: f64) -> f64 {
    z * n.max(1) as f64 * kt / area
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Boundary;

    fn walls(lx: f64, ly: f64) -> SimBox {
        SimBox::walled(lx, ly, 1.0)
    }

    #[test]
    fn degrees_of_freedom_lose_one_per_periodic_axis() {
        let mut b = SimBox::periodic(10.0, 10.0);
        assert_eq!(degrees_of_freedom(100, &b), 198);
        b.boundary[1] = walls(1.0, 1.0).boundary[1];
        assert_eq!(degrees_of_freedom(100, &b), 199);
        assert_eq!(degrees_of_freedom(100, &walls(10.0, 10.0)), 200);
        assert_eq!(temperature(99.0, 198), 1.0);
        assert_eq!(temperature(0.5, 0), 1.0);
    }

    #[test]
    fn one_species_reaches_the_box_shrunk_by_a_radius_at_each_wall() {
        let s = [Species::new(10, 0.5, 1.0)];
        let b = walls(10.0, 6.0);
        assert_eq!(accessible_area(&s, &b), 9.0 * 5.0);
        let mut channel = b;
        channel.boundary[0] = Boundary::Periodic;
        assert_eq!(accessible_area(&s, &channel), 10.0 * 5.0);
        assert_eq!(accessible_area(&s, &SimBox::periodic(10.0, 6.0)), 60.0);
    }

    #[test]
    fn an_ideal_mixture_on_walls_gives_z_one() {
        // Ideal-gas impulse on the two walls normal to k: 2 kT Σ_s N_s / ℓ_k(a_s).
        let s = [Species::new(300, 0.5, 1.0), Species::new(200, 0.7, 2.0)];
        let b = walls(30.0, 20.0);
        let (kt, t) = (1.3, 7.0);
        let j: f64 = (0..2)
            .map(|k| {
                2.0 * kt
                    * t
                    * s.iter()
                        .map(|sp| sp.count as f64 / reachable_length(&b, k, sp.radius))
                        .sum::<f64>()
            })
            .sum();
        assert!((wall_z(&s, &b, kt, j, t) - 1.0).abs() < 1e-14);
        // The mixture's area lies between the species' own areas.
        let a = accessible_area(&s, &b);
        assert!(a > 28.6 * 18.6 && a < 29.0 * 19.0, "{a}");
    }

    #[test]
    fn the_virial_estimator_is_one_plus_w_over_n_kt() {
        assert_eq!(virial_z(100, 2.0, 800.0, 1.0), 3.0);
        assert_eq!(pressure(3.0, 100, 2.0, 50.0), 12.0);
        assert_eq!(virial_pressure(100, 2.0, 800.0, 1.0, 50.0), 12.0);
        assert_eq!(collision_rate(50.0, 100, 0.5), 2.0);
        let s = [Species::new(4, 0.5, 1.0)];
        let eta = packing_fraction(&s, &SimBox::periodic(2.0, 2.0));
        assert!((eta - std::f64::consts::PI / 4.0).abs() < 1e-15);
    }
}
