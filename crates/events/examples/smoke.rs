use carom_core::{SimBox, Species};
use carom_events::*;
fn main() {
    let args: Vec<String> = std::env::args().collect();
    let n: usize = args.get(1).map(|s| s.parse().unwrap()).unwrap_or(1000);
    let eta: f64 = args.get(2).map(|s| s.parse().unwrap()).unwrap_or(0.5);
    let ncoll: u64 = args.get(3).map(|s| s.parse().unwrap()).unwrap_or(1_000_000);
    let species = vec![Species {
        count: n,
        radius: 0.5,
        mass: 1.0,
    }];
    let size = box_size_for(&species, eta, 1.0);
    let spec = SystemSpec {
        species,
        sim_box: SimBox::periodic(size.x, size.y),
        temperature: 1.0,
        seed: 1,
        placement: Placement::Lattice,
        velocities: Velocities::MaxwellBoltzmann,
    };
    let st = spec.build().unwrap();
    let mut e = Engine::new(st, EngineParams::default()).unwrap();
    let mut chk = InvariantChecker::new(&e);
    chk.check(&e).unwrap();
    e.run_collisions(ncoll / 10).unwrap();
    let t0 = std::time::Instant::now();
    let c0 = e.stats().pair_collisions;
    e.run_collisions(ncoll).unwrap();
    let dt = t0.elapsed().as_secs_f64();
    let s = e.stats();
    println!("N={n} eta={eta} cells={:?} coll/s={:.3e} t={:.3} crossings/coll={:.3} stale/coll={:.3} bytes/disc={}", e.cells(), (s.pair_collisions - c0) as f64 / dt, e.now(), s.cell_crossings as f64 / s.pair_collisions as f64, s.stale_events as f64 / s.pair_collisions as f64, e.heap_bytes() / n);
    chk.check(&e).unwrap();
    println!(
        "max overlap {:e} energy drift {:e}",
        chk.max_overlap, chk.max_energy_drift
    );
    let z = 1.0 + s.virial_sum / (2.0 * e.now() * e.kinetic_energy() / (n as f64 - 1.0) * n as f64);
    println!("Z ~ {z:.4}");
}
