//! The species check (`carom_core::check_species`) at the edges of what it
//! allows: exactly 65535 species, a total of 2³² − 2 discs, and radii and masses
//! that are positive but tiny, against the first values it refuses (65536
//! species, 2³² − 1 discs, a radius or mass of 0, ∞). A disc's area is π a².
//!
//! Found missing by mutation testing (docs/testing.md): the unit tests tried only
//! values well inside or well outside each limit.

use carom_core::{check_species, Species};

#[test]
fn the_species_check_accepts_up_to_each_limit_and_refuses_the_next_value() {
    let kinds = vec![Species::new(1, 0.5, 1.0); 65535];
    assert_eq!(check_species(&kinds), Ok(65535));
    let most = (u32::MAX - 1) as usize;
    assert_eq!(check_species(&[Species::new(most, 0.5, 1.0)]), Ok(most));
    let split = [Species::new(most - 5, 0.5, 1.0), Species::new(6, 0.5, 1.0)];
    let refused = check_species(&split).unwrap_err();
    assert_eq!(refused.setting, None);
    assert!(refused.problem.contains("4294967295 discs"), "{refused:?}");
    let tiny = f64::MIN_POSITIVE;
    assert_eq!(check_species(&[Species::new(2, tiny, tiny)]), Ok(2));
    for (radius, mass, setting) in [
        (0.0, 1.0, "radius"),
        (0.5, 0.0, "mass"),
        (f64::INFINITY, 1.0, "radius"),
        (0.5, f64::INFINITY, "mass"),
    ] {
        let got = check_species(&[Species::new(1, radius, mass)]).unwrap_err();
        assert_eq!(
            got.setting,
            Some((0, setting)),
            "radius {radius}, mass {mass}"
        );
    }
    // The count saturates rather than wraps: two enormous species are too many.
    let huge = [
        Species::new(usize::MAX, 0.5, 1.0),
        Species::new(2, 0.5, 1.0),
    ];
    assert_eq!(check_species(&huge).unwrap_err().setting, None);
}

#[test]
fn a_disc_covers_pi_a_squared() {
    let s = Species::new(1, 1.5, 2.0);
    assert!((s.disc_area() - std::f64::consts::PI * 2.25).abs() < 1e-15);
}
