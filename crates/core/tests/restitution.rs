//! The collision rules' coefficients (`carom_core::Restitution`, physics.md §3–4):
//! R of the centre-of-mass rule and e of the normal rule are what the rule was
//! given, the elastic rule's is 1, and a rule is elastic exactly when its
//! coefficient is 1 (an inelastic rule given 1 conserves energy too; one given
//! 0.999 does not).
//!
//! Found missing by mutation testing (docs/testing.md): the coefficient and the
//! elasticity test were used only by the engine and the CLI, never checked in core.

use carom_core::collision::resolve;
use carom_core::{DVec2, Restitution};

#[test]
fn each_rule_reports_its_coefficient_and_is_elastic_only_at_one() {
    let rules = [
        (Restitution::Elastic, 1.0, true),
        (Restitution::CentreOfMass(0.75), 0.75, false),
        (Restitution::Normal(0.5), 0.5, false),
        (Restitution::Normal(0.0), 0.0, false),
        (Restitution::CentreOfMass(1.0), 1.0, true),
        (Restitution::Normal(1.0), 1.0, true),
        (Restitution::Normal(0.999), 0.999, false),
    ];
    for (rule, coefficient, elastic) in rules {
        assert_eq!(rule.coefficient(), coefficient, "{rule:?}");
        assert_eq!(rule.is_elastic(), elastic, "{rule:?}");
        // What is_elastic promises: no energy lost in a head-on collision.
        let r = resolve(
            DVec2::new(1.0, 0.0),
            DVec2::new(-1.0, 0.0),
            1.0,
            2.0,
            DVec2::new(1.0, 0.0),
            rule,
        );
        assert_eq!(r.energy_lost == 0.0, elastic, "{rule:?}: {r:?}");
    }
}
