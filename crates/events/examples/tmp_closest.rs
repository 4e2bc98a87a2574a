use carom_core::{Boundary, DVec2, SimBox, Species};
use carom_events::{Engine, EngineParams, Placement, SystemSpec, Velocities};
fn main() {
    let n: usize = std::env::args().nth(1).unwrap().parse().unwrap();
    let l: f64 = std::env::args().nth(2).unwrap().parse().unwrap();
    let spec = SystemSpec {
        species: vec![Species {
            count: n,
            radius: 0.5,
            mass: 1.0,
        }],
        sim_box: SimBox {
            size: DVec2::new(l, l),
            boundary: [Boundary::Periodic; 2],
        },
        temperature: 1.0,
        seed: 0,
        placement: Placement::Lattice,
        velocities: Velocities::MaxwellBoltzmann,
    };
    let s = spec.build().unwrap();
    let mut best = f64::INFINITY;
    let mut cnt = 0;
    for i in 0..n {
        for j in i + 1..n {
            let mut d = s.positions[j] - s.positions[i];
            d.x -= l * (d.x / l).round();
            d.y -= l * (d.y / l).round();
            let r = d.length();
            if r < best {
                best = r;
            }
            if r < 1.0 + 1e-12 {
                cnt += 1;
            }
        }
    }
    println!("closest {best:.17} pairs within 1e-12 of contact: {cnt}");
    let mut e = Engine::new(s, EngineParams::default()).unwrap();
    match e.run_collisions(1_000_000) {
        Ok(c) => println!("ran {c} to t={}", e.now()),
        Err(err) => println!("error: {err}"),
    }
}
