//! The thermodynamic observables (`carom_core::observables`, physics.md §5) on
//! cases whose answer is known in closed form, chosen so that no factor is 1:
//!
//! * kT = 2K/f;
//! * the virial estimators: Z − 1 is the virial rate W = Σ r·Δp / (2t) per N kT,
//!   so it halves when the window doubles, and P = Z N kT / A;
//! * a species with no discs counts for nothing, even one too wide for the box;
//! * which boxes have walls (any walled axis), and the reachable area of a channel
//!   or a walled box, L − 2a on each walled axis only;
//! * the wall estimator: an ideal gas hitting the walls at its kinetic rate gives
//!   Z = 1 in a channel and in a walled box, for a window of any length.
//!
//! Found missing by mutation testing (docs/testing.md): the earlier examples used
//! a window t = 1, where `2t` and `2/t` agree.

use carom_core::observables::{
    accessible_area, has_walls, pressure, reachable_length, temperature, virial_pressure, virial_z,
    wall_z,
};
use carom_core::{Boundary, SimBox, Species};

fn channel(lx: f64, ly: f64) -> SimBox {
    SimBox {
        size: carom_core::DVec2::new(lx, ly),
        boundary: [Boundary::Periodic, Boundary::Walls { restitution: 1.0 }],
    }
}

#[test]
fn the_virial_excess_is_the_virial_rate_per_n_kt() {
    let (n, kt, area) = (200, 1.5, 400.0);
    // W = Σ / (2t) = 1200 / 8 = 150, Z = 1 + 150 / 300.
    let (sum, t) = (1200.0, 4.0);
    assert_eq!(virial_z(n, kt, sum, t), 1.5);
    // The same sum over twice the window: half the excess.
    assert_eq!(virial_z(n, kt, sum, 2.0 * t), 1.25);
    // P = (N kT + W) / A = Z N kT / A.
    let p = virial_pressure(n, kt, sum, t, area);
    assert_eq!(p, (300.0 + 150.0) / 400.0);
    assert_eq!(p, pressure(virial_z(n, kt, sum, t), n, kt, area));
    assert_eq!(virial_pressure(n, kt, sum, 2.0 * t, area), 375.0 / 400.0);
}

#[test]
fn the_temperature_is_twice_the_kinetic_energy_per_degree_of_freedom() {
    assert_eq!(temperature(300.0, 200), 3.0);
    assert_eq!(temperature(0.75, 1), 1.5);
    // No degree of freedom: counted as one, never a division by zero.
    assert_eq!(temperature(0.75, 0), 1.5);
}

#[test]
fn a_box_has_walls_when_any_axis_has_them() {
    assert!(!has_walls(&SimBox::periodic(10.0, 6.0)));
    assert!(has_walls(&channel(10.0, 6.0)));
    assert!(has_walls(&SimBox::walled(10.0, 6.0, 0.9)));
}

#[test]
fn a_channel_shrinks_only_across_its_walls() {
    let b = channel(12.0, 7.0);
    assert_eq!(reachable_length(&b, 0, 0.75), 12.0);
    assert_eq!(reachable_length(&b, 1, 0.75), 5.5);
    let s = [Species::new(30, 0.75, 1.0)];
    assert_eq!(accessible_area(&s, &b), 12.0 * 5.5);
}

/// The total impulse an ideal gas at temperature kT gives the walls in a window
/// t: per walled axis, two walls each hit at the rate N_s ⟨|v_k|⟩/(2 ℓ_k) with
/// impulse 2 m |v_k|, i.e. 2 kT t Σ_s N_s / ℓ_k(a_s) in all.
fn ideal_wall_impulse(s: &[Species], b: &SimBox, kt: f64, t: f64) -> f64 {
    (0..2)
        .filter(|&k| !b.boundary[k].is_periodic())
        .map(|k| {
            let per_length: f64 = s
                .iter()
                .map(|sp| sp.count as f64 / reachable_length(b, k, sp.radius))
                .sum();
            2.0 * kt * t * per_length
        })
        .sum()
}

#[test]
fn a_species_without_discs_changes_nothing_even_as_wide_as_the_box() {
    // Diameter 6 = L_y: its centres could reach no area at all.
    let b = SimBox::walled(10.0, 6.0, 1.0);
    let one = [Species::new(10, 0.5, 1.0)];
    let with_absent = [one[0], Species::new(0, 3.0, 1.0)];
    assert_eq!(accessible_area(&with_absent, &b), 9.0 * 5.0);
    let j = ideal_wall_impulse(&one, &b, 1.0, 2.0);
    assert_eq!(
        wall_z(&with_absent, &b, 1.0, j, 2.0),
        wall_z(&one, &b, 1.0, j, 2.0)
    );
}

#[test]
fn an_ideal_gas_gives_z_one_on_the_walls_of_a_channel_and_a_box() {
    let s = [Species::new(120, 0.5, 1.0), Species::new(40, 0.75, 3.0)];
    for b in [channel(30.0, 16.0), SimBox::walled(30.0, 16.0, 1.0)] {
        for (kt, t) in [(0.75, 3.0), (2.5, 0.25)] {
            let j = ideal_wall_impulse(&s, &b, kt, t);
            let z = wall_z(&s, &b, kt, j, t);
            assert!((z - 1.0).abs() < 1e-14, "{b:?}, kT {kt}, t {t}: Z {z}");
            // Twice the impulse in the same window: twice the pressure.
            assert!((wall_z(&s, &b, kt, 2.0 * j, t) - 2.0).abs() < 1e-14);
        }
    }
}
