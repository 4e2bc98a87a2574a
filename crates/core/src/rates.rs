//! Collision rates expected of a fluid from its density and temperature: the one
//! place where carom estimates how often discs collide before it has watched them.
//!
//! Pair collisions follow Enskog's rate with Henderson's contact value g at the
//! total packing fraction (physics.md (7.6), (7.7), (7.9)): disc a meets discs of species b
//! at ν_ab = 2 σ_ab ρ_b g √(πkT/2 · (1/m_a + 1/m_b)), which is (7.2) for one
//! species. Each walled axis adds the ideal-gas wall rate of a disc crossing its
//! reachable length ℓ_k(a) at mean speed ⟨|v_k|⟩ = √(2kT/(πm)) (7.9). These are
//! estimates (exact for a dilute elastic gas, within tens of per cent for a dense
//! fluid), used for the neighbour-search layout and a run's watchdog, never in a
//! measurement.

use crate::observables::{packing_fraction, reachable_length};
use crate::{SimBox, Species};
use std::f64::consts::PI;

/// Henderson's contact value of the pair distribution of hard discs,
/// g(σ) ≈ (1 − 7η/16)/(1 − η)² (physics.md (7.6)), with η capped at 0.8 (beyond
/// the fluid, where the formula is not meant to hold).
pub fn henderson_contact_value(eta: f64) -> f64 {
    let eta = eta.min(0.8);
    (1.0 - 7.0 * eta / 16.0) / ((1.0 - eta) * (1.0 - eta))
}

/// Collisions per unit time expected in the whole system at temperature `kt`
/// (energy): pair collisions ½ Σ_a N_a Σ_b ν_ab (with N_b − 1 partners of a's own
/// species) plus wall collisions
/// Σ_k walled Σ_a N_a ⟨|v_k|⟩_a / ℓ_k(a_a) (physics.md (7.9)); 0 at kT = 0.
pub fn expected_collision_rate(species: &[Species], sim_box: &SimBox, kt: f64) -> f64 {
    if kt.is_nan() || kt <= 0.0 {
        return 0.0;
    }
    let area = sim_box.area();
    let g = henderson_contact_value(packing_fraction(species, sim_box));
    let present = || species.iter().filter(|s| s.count > 0);
    let pairs: f64 = present()
        .map(|a| {
            let nu_a: f64 = present()
                .map(|b| {
                    // The other discs of b: one fewer when b is a's own species.
                    let others = b.count as f64 - if std::ptr::eq(a, b) { 1.0 } else { 0.0 };
                    let sigma = a.radius + b.radius;
                    let speed = (PI * kt / 2.0 * (1.0 / a.mass + 1.0 / b.mass)).sqrt();
                    2.0 * sigma * (others / area) * g * speed
                })
                .sum();
            a.count as f64 * nu_a
        })
        .sum::<f64>()
        / 2.0;
    let walls: f64 = (0..2)
        .filter(|&k| !sim_box.boundary[k].is_periodic())
        .flat_map(|k| {
            present().map(move |a| {
                let speed = (2.0 * kt / (PI * a.mass)).sqrt();
                a.count as f64 * speed / reachable_length(sim_box, k, a.radius)
            })
        })
        .sum();
    pairs + walls
}

/// The mean free time per disc expected at temperature `kt`, t_free = N / (2 R_pair)
/// with R_pair the pair part of [`expected_collision_rate`] (physics.md (7.5), (7.9));
/// with walls, the time between any two collisions of a disc, N / (2 R_pair + R_wall).
/// Infinite when nothing is expected to collide.
pub fn expected_mean_free_time(species: &[Species], sim_box: &SimBox, kt: f64) -> f64 {
    let n: usize = species.iter().map(|s| s.count).sum();
    let all = expected_collision_rate(species, sim_box, kt);
    let pairs = expected_collision_rate(species, &periodic_only(sim_box), kt);
    // Per disc, a pair collision counts for two discs, a wall hit for one.
    let per_disc = (2.0 * pairs + (all - pairs)) / n.max(1) as f64;
    if per_disc > 0.0 {
        1.0 / per_disc
    } else {
        f64::INFINITY
    }
}

/// The same box with every axis periodic (its pair rate alone).
fn periodic_only(sim_box: &SimBox) -> SimBox {
    SimBox::periodic(sim_box.size.x, sim_box.size.y)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_species_gives_enskog_rate_per_disc() {
        // (7.2): ω = 2 σ n g √(πkT/m) per disc, N ω / 2 in all.
        let s = [Species::new(400, 0.5, 2.0)];
        let b = SimBox::periodic(40.0, 40.0);
        let (n, kt) = (400.0, 1.5);
        let eta = packing_fraction(&s, &b);
        let omega = 2.0
            * 1.0
            * ((n - 1.0) / 1600.0)
            * henderson_contact_value(eta)
            * (PI * kt / 2.0).sqrt();
        let r = expected_collision_rate(&s, &b, kt);
        assert!(
            (r - n * omega / 2.0).abs() < 1e-12 * r,
            "{r} vs {}",
            n * omega / 2.0
        );
        let t = expected_mean_free_time(&s, &b, kt);
        assert!((t * omega - 1.0).abs() < 1e-12);
    }

    #[test]
    fn a_mixture_of_identical_species_is_one_species() {
        let b = SimBox::periodic(30.0, 20.0);
        let one = expected_collision_rate(&[Species::new(300, 0.5, 1.0)], &b, 1.0);
        let two = expected_collision_rate(
            &[Species::new(100, 0.5, 1.0), Species::new(200, 0.5, 1.0)],
            &b,
            1.0,
        );
        assert!((one - two).abs() < 1e-12 * one);
    }

    #[test]
    fn a_lone_disc_between_walls_hits_them_at_the_ideal_gas_rate() {
        let s = [Species::new(1, 0.5, 1.0)];
        let mut b = SimBox::walled(11.0, 11.0, 1.0);
        b.boundary[1] = SimBox::periodic(1.0, 1.0).boundary[1];
        // ⟨|v_x|⟩ / (L − 2a) = √(2/π) / 10 at kT = 1; no pair collisions.
        let r = expected_collision_rate(&s, &b, 1.0);
        assert!((r - (2.0 / PI).sqrt() / 10.0).abs() < 1e-15);
        assert!((expected_mean_free_time(&s, &b, 1.0) - 1.0 / r).abs() < 1e-9);
    }

    #[test]
    fn nothing_collides_at_zero_temperature() {
        let s = [Species::new(10, 0.5, 1.0)];
        let b = SimBox::periodic(10.0, 10.0);
        assert_eq!(expected_collision_rate(&s, &b, 0.0), 0.0);
        assert_eq!(expected_mean_free_time(&s, &b, 0.0), f64::INFINITY);
        assert_eq!(expected_collision_rate(&s, &b, f64::NAN), 0.0);
    }
}
