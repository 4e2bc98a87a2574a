//! The `/thermo` record: the engine's running totals turned into kT, the pressure,
//! the compressibility factor Z and the pair collision rate over the run so far.
//!
//! kT = 2K/f; in a periodic box Z = 1 + W/(N kT) from the collision virial, with
//! walls Z from the wall impulse and the area each species' centres reach
//! (physics.md §5); ω = 2 N_pair/(N t) (physics.md §7). Every formula is
//! `carom_core::observables`', the same that `carom analyze` uses, so the two agree.
//! In a field the record adds U = Σ m g y and K + U (physics.md §15); with growing
//! discs the scale s, η of the radii now, the phase and the last interval's Z
//! (physics.md §17).

use carom_core::observables::packing_fraction;
use carom_core::observables::{
    accessible_area, collision_rate, degrees_of_freedom, has_walls, pressure, temperature,
    virial_pressure, virial_z, wall_z,
};
use carom_engine::{Engine, GrowthEnd};
use carom_log::{GrowthPhase, Thermo};

/// The `/thermo` record of `engine` now, with rates and pressures averaged since
/// `run_start_time` (none at that time, nor without thermal motion): the record a
/// log writes, and the one a live viewer of a run without a log gets.
pub fn thermo(engine: &Engine, run_start_time: f64) -> Thermo {
    let n = engine.len();
    let (sim_box, species) = (engine.sim_box(), engine.species());
    let k_energy = engine.kinetic_energy();
    let kt = temperature(k_energy, degrees_of_freedom(n, sim_box));
    let s = engine.stats();
    let t = engine.now() - run_start_time;
    let wall_impulse: f64 = s.wall_impulse.iter().flatten().sum();
    let (mut p, mut z, mut rate) = (None, None, None);
    if t > 0.0 {
        rate = Some(collision_rate(s.pair_collisions as f64, n, t));
        if kt > 0.0 {
            if has_walls(sim_box) {
                let zw = wall_z(species, sim_box, kt, wall_impulse, t);
                z = Some(zw);
                p = Some(pressure(zw, n, kt, accessible_area(species, sim_box)));
            } else {
                z = Some(virial_z(n, kt, s.virial_sum, t));
                p = Some(virial_pressure(n, kt, s.virial_sum, t, sim_box.area()));
            }
        }
    }
    let mut th = Thermo {
        time: engine.now(),
        kinetic_energy: k_energy,
        temperature: kt,
        collisions: s.pair_collisions + s.wall_collisions,
        pair_collisions: s.pair_collisions,
        wall_collisions: s.wall_collisions,
        energy_lost: s.energy_lost,
        virial_sum: s.virial_sum,
        wall_impulse,
        pressure: p.filter(|x| x.is_finite()),
        z: z.filter(|x| x.is_finite()),
        collision_rate: rate.filter(|x| x.is_finite()),
        ..Thermo::default()
    };
    if engine.gravity() != 0.0 {
        let u = engine.potential_energy();
        th.potential_energy = Some(u);
        th.total_energy = Some(k_energy + u);
    }
    if engine.params().growth.rate != 0.0 {
        let scale = engine.radius_scale();
        let grown: Vec<_> = species
            .iter()
            .map(|sp| carom_core::Species {
                radius: sp.radius * scale,
                ..*sp
            })
            .collect();
        let g = engine.growth();
        th.radius_scale = Some(scale);
        th.packing_fraction = Some(packing_fraction(&grown, sim_box));
        th.growth = Some(phase(g.ended));
        th.growth_z = Some(g.last_z);
    }
    th
}

/// The log's name for the engine's growth phase.
pub(super) fn phase(e: GrowthEnd) -> GrowthPhase {
    match e {
        GrowthEnd::Growing => GrowthPhase::Growing,
        GrowthEnd::Target => GrowthPhase::Target,
        GrowthEnd::Jammed => GrowthPhase::Jammed,
    }
}
