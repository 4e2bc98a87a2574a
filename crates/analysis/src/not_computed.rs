//! What the report could not compute, and why. A section of the [`Report`] that
//! is `null` is not a silent gap: each absent quantity that a reader of this kind
//! of run would look for is listed with the reason, in the JSON
//! (`not_computed`) and in the text. The reasons are read off the report itself
//! (box, elasticity, N, window, what the log holds), so they stay true to it.

use super::bond_order::MIN_BOND_ORDER_DISCS;
use super::report::{NotComputed, Report};

/// The quantities absent from `r` with the reason for each.
pub fn explain(r: &Report) -> Vec<NotComputed> {
    let mut out = Vec::new();
    let mut say = |quantity: &'static str, why: String| out.push(NotComputed { quantity, why });
    let periodic = r.periodic.iter().all(|&p| p);
    let snapshots = r.window.snapshot_times.len();
    let no_snapshots = || "no snapshot after the equilibration time".to_string();
    let few_discs = r.n < MIN_BOND_ORDER_DISCS;
    if r.pressure.is_none() {
        say("pressure", "no temperature in the log".into());
    }
    if r.enskog.is_none() {
        let species = r.species.iter().filter(|s| s.count > 0).count();
        let why = if !periodic {
            "needs a periodic box (walls change the collision rate near them)"
        } else if !r.elastic {
            "needs elastic collisions"
        } else if species != 1 {
            "needs a single species"
        } else {
            "needs a pressure"
        };
        say("enskog", why.into());
    }
    match &r.pair_correlation {
        None => say("pair_correlation", no_snapshots()),
        Some(pc) => {
            if pc.contact_theorem.is_none() && periodic && r.elastic {
                say(
                    "contact_theorem",
                    "needs every contact value (pair_correlation.pairs[].contact_missing says \
                     why one is absent) and a pressure"
                        .into(),
                );
            }
        }
    }
    let bond_why = || {
        if few_discs {
            format!("needs at least {MIN_BOND_ORDER_DISCS} discs (a disc and six neighbours); the run has {}", r.n)
        } else {
            "needs at least two snapshots after the equilibration time".into()
        }
    };
    if r.bond_order.is_none() {
        say("bond_order", bond_why());
    }
    if r.orientational_correlation.is_none() {
        say("orientational_correlation", bond_why());
    }
    if r.structure_factor.is_none() {
        say(
            "structure_factor",
            if periodic {
                no_snapshots()
            } else {
                "needs a periodic box (the box's wave vectors)".into()
            },
        );
    }
    if r.dynamics.is_none() {
        say(
            "dynamics",
            format!("needs two snapshots after the equilibration time; {snapshots} used"),
        );
    }
    inelastic(r, &mut say);
    if r.transport.is_none() {
        let c = &r.collision_rate;
        let why = if r.thermostat.is_some() {
            "a thermostat changes the velocities between collisions, which the replay of \
             the logged collisions does not see"
        } else if !r.elastic {
            "needs elastic collisions"
        } else if !periodic {
            "needs a periodic box"
        } else if c.counted_from == "thermo" && c.logged_pair_collisions == 0 {
            "needs the collisions in the log (the run did not log them)"
        } else if c.collision_stride > 1 {
            "needs every collision in the log (log.collision_every > 1)"
        } else {
            "needs a snapshot after the equilibration time to start the collision replay \
             from, and time after it"
        };
        say("transport", why.into());
    }
    out
}

/// The parts of an inelastic run's report that are absent: its Sonine
/// coefficient, Haff's law and its Enskog prediction, the energy budget.
fn inelastic(r: &Report, say: &mut dyn FnMut(&'static str, String)) {
    let Some(i) = &r.inelastic else {
        return;
    };
    let used = r.window.snapshot_times.len();
    if i.sonine.is_none() {
        say(
            "inelastic.sonine",
            format!(
                "needs two snapshots in the window t ∈ [{}, {}] with a finite a2; {used} used                  of {} in the log",
                r.window.equilibrate, r.window.t_end, r.window.snapshots_seen
            ),
        );
    }
    if r.thermostat.is_some() {
        let why = "the thermostat feeds energy in; the energy budget and Haff's law assume none";
        say("inelastic.energy", why.into());
        say("inelastic.haff", why.into());
        return;
    }
    if i.energy.is_none() && r.gravity.is_none() {
        say(
            "inelastic.energy",
            "needs two kinetic-energy records (/thermo or snapshots)".into(),
        );
    }
    // In a field (a vibrated bed, say) the cooling laws are not compared at all.
    if r.gravity.is_some() {
        return;
    }
    match &i.haff {
        None => say(
            "inelastic.haff",
            "needs normal restitution e < 1, three kT records and counted pair collisions".into(),
        ),
        Some(h) if h.enskog.is_none() => {
            let species = r.species.iter().filter(|s| s.count > 0).count();
            let why = if species != 1 {
                "needs a single species"
            } else if !r.periodic.iter().all(|&p| p) {
                "needs a periodic box"
            } else if i.sonine.is_none() {
                "needs the measured a2 (inelastic.sonine)"
            } else {
                "needs three kT records in the window"
            };
            say("inelastic.haff.enskog", why.into());
        }
        _ => {}
    }
}
