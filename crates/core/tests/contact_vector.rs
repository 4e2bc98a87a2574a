//! The engine resolves a pair collision with the contact vector r_j − r_i, of
//! length σ = a_i + a_j, not with a unit normal (collision.rs, module docs). The
//! outcome must not depend on that length: for each rule, the velocities, the
//! impulse and the energy lost with n = σ n̂ equal those with n̂, and the energy
//! lost is the kinetic energy the discs actually lose.
//! (Found missing by mutation testing, docs/testing.md: the examples and the
//! property tests used unit normals, where u² = (g·n)²/|n|² and (g·n)²|n|² agree.)

use carom_core::collision::resolve;
use carom_core::{DVec2, Restitution};

fn kinetic(m: f64, v: DVec2) -> f64 {
    0.5 * m * v.length_squared()
}

#[test]
fn the_outcome_does_not_depend_on_the_length_of_the_contact_vector() {
    let (vi, vj) = (DVec2::new(1.25, -0.5), DVec2::new(-0.75, 0.375));
    let (mi, mj) = (1.0, 2.5);
    let unit = DVec2::new(0.6, 0.8);
    for rule in [
        Restitution::Elastic,
        Restitution::Normal(0.8),
        Restitution::Normal(0.0),
        Restitution::CentreOfMass(0.7),
    ] {
        let reference = resolve(vi, vj, mi, mj, unit, rule);
        for sigma in [0.5, 1.4, 3.0] {
            let r = resolve(vi, vj, mi, mj, unit * sigma, rule);
            let close = |a: DVec2, b: DVec2| (a - b).length() < 1e-14;
            assert!(
                close(r.vi, reference.vi) && close(r.vj, reference.vj),
                "{rule:?} σ {sigma}"
            );
            assert!(
                close(r.impulse_i, reference.impulse_i),
                "{rule:?} σ {sigma}"
            );
            assert!(
                (r.energy_lost - reference.energy_lost).abs() < 1e-14,
                "{rule:?} σ {sigma}: {} against {}",
                r.energy_lost,
                reference.energy_lost
            );
            let lost = kinetic(mi, vi) + kinetic(mj, vj) - kinetic(mi, r.vi) - kinetic(mj, r.vj);
            assert!((lost - r.energy_lost).abs() < 1e-14, "{rule:?} σ {sigma}");
        }
    }
}
