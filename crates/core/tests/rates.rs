//! The expected collision rates (`carom_core::rates`, physics.md (7.6)–(7.9)) on
//! cases worked by hand, chosen so that no factor is 1:
//!
//! * Henderson's contact value at η = 1/2 is (1 − 7/32)/(1/4) = 25/8, and the
//!   formula stops at η = 0.8;
//! * a binary mixture of unequal radii and masses: the pair rate sums
//!   ν_ab = 2 σ_ab ρ_b g √(πkT/2 · (1/m_a + 1/m_b)) over both orders of unlike
//!   pairs, with N_b − 1 partners of a's own species;
//! * a heavy gas between walls on both axes of unequal length: each disc hits the
//!   walls of axis k at ⟨|v_k|⟩ / (L_k − 2a) with ⟨|v_k|⟩ = √(2kT/(πm));
//! * the mean free time counts a pair collision for two discs, a wall hit for one;
//! * a species with no discs changes nothing, even one as wide as the box.
//!
//! Found missing by mutation testing (docs/testing.md): the unit tests used equal
//! masses (where 1/m_a + 1/m_b and 1/m_a ÷ 1/m_b agree up to a constant) and m = 1
//! at the walls (where πm and π/m agree).

use carom_core::observables::packing_fraction;
use carom_core::rates::{
    expected_collision_rate, expected_mean_free_time, henderson_contact_value,
};
use carom_core::{SimBox, Species};
use std::f64::consts::PI;

fn close(got: f64, want: f64, what: &str) {
    assert!(
        (got - want).abs() <= 1e-13 * want.abs(),
        "{what}: {got} against {want}"
    );
}

#[test]
fn henderson_contact_value_at_half_packing_and_its_cap() {
    close(henderson_contact_value(0.5), 25.0 / 8.0, "g(σ) at η = 1/2");
    close(henderson_contact_value(0.0), 1.0, "g(σ) of the ideal gas");
    // Beyond η = 0.8 the value stays that of η = 0.8: (1 − 0.35)/0.04 = 16.25.
    close(henderson_contact_value(0.8), 16.25, "g(σ) at η = 0.8");
    close(henderson_contact_value(0.95), 16.25, "g(σ) capped");
}

#[test]
fn a_binary_mixture_collides_at_the_enskog_rate_of_each_pair_kind() {
    // 30 discs of radius 0.5 and mass 1, 20 of radius 1 and mass 4, in 40 × 25.
    let (small, large) = (Species::new(30, 0.5, 1.0), Species::new(20, 1.0, 4.0));
    let s = [small, large];
    let b = SimBox::periodic(40.0, 25.0);
    let kt = 1.5;
    let area = 1000.0;
    let g = henderson_contact_value(packing_fraction(&s, &b));
    let nu = |sigma: f64, partners: f64, inv_m: f64| {
        2.0 * sigma * (partners / area) * g * (PI * kt / 2.0 * inv_m).sqrt()
    };
    let small_small = 30.0 * nu(1.0, 29.0, 2.0);
    let large_large = 20.0 * nu(2.0, 19.0, 0.5);
    let small_large = 30.0 * nu(1.5, 20.0, 1.25);
    let large_small = 20.0 * nu(1.5, 30.0, 1.25);
    close(
        small_large,
        large_small,
        "each unlike pair counted from both sides",
    );
    let want = (small_small + large_large + small_large + large_small) / 2.0;
    close(
        expected_collision_rate(&s, &b, kt),
        want,
        "mixture pair rate",
    );
    // No walls: each collision involves two discs, t_free = N / (2 R).
    close(
        expected_mean_free_time(&s, &b, kt),
        50.0 / (2.0 * want),
        "mixture mean free time",
    );
}

#[test]
fn a_heavy_gas_between_walls_hits_each_axis_at_its_own_ideal_gas_rate() {
    // One disc of radius 0.75 and mass 4 at kT = 2 in a 12 × 7 box walled on both
    // axes: ⟨|v_k|⟩ = √(2·2/(4π)) = 1/√π; reachable lengths 10.5 and 5.5.
    let s = [Species::new(1, 0.75, 4.0)];
    let b = SimBox::walled(12.0, 7.0, 0.9);
    let speed = 1.0 / PI.sqrt();
    let walls = speed / 10.5 + speed / 5.5;
    close(expected_collision_rate(&s, &b, 2.0), walls, "wall rate");
    close(
        expected_mean_free_time(&s, &b, 2.0),
        1.0 / walls,
        "time between wall hits",
    );
}

#[test]
fn the_mean_free_time_counts_pair_collisions_twice_and_wall_hits_once() {
    let s = [Species::new(50, 0.5, 2.0)];
    let b = SimBox::walled(20.0, 16.0, 1.0);
    let kt = 3.0;
    let all = expected_collision_rate(&s, &b, kt);
    let pairs = expected_collision_rate(&s, &SimBox::periodic(20.0, 16.0), kt);
    let walls = all - pairs;
    let speed = (2.0 * kt / (PI * 2.0)).sqrt();
    close(walls, 50.0 * (speed / 19.0 + speed / 15.0), "wall part");
    close(
        expected_mean_free_time(&s, &b, kt),
        50.0 / (2.0 * pairs + walls),
        "mean free time",
    );
}

#[test]
fn a_species_without_discs_changes_no_rate_even_as_wide_as_the_box() {
    // A species of no discs with diameter 12 in a 12 × 7 walled box: its reachable
    // length is 0 or less, and 0 discs × speed / 0 would be NaN.
    let b = SimBox::walled(12.0, 7.0, 1.0);
    let gas = Species::new(20, 0.5, 2.0);
    let with = [gas, Species::new(0, 6.0, 3.0)];
    for kt in [0.5, 2.0] {
        let want = expected_collision_rate(&[gas], &b, kt);
        assert_eq!(expected_collision_rate(&with, &b, kt), want, "kT = {kt}");
        assert_eq!(
            expected_mean_free_time(&with, &b, kt),
            expected_mean_free_time(&[gas], &b, kt)
        );
    }
}
