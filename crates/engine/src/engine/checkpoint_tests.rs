use crate::*;
use carom_core::{Boundary, DVec2, SimBox, Species};

/// Small discs (diameter 1, mass 1) and `large` discs of radius `radius` and
/// mass `mass` at packing fraction `eta` in a channel (periodic in x, walls in
/// y, aspect 1.5), placed by `placement`, with a grid per size class where
/// that is faster if `split`.
fn channel(
    (small, large): (usize, usize),
    (radius, mass): (f64, f64),
    eta: f64,
    (seed, placement): (u64, Placement),
    split: bool,
) -> Engine {
    let species = vec![
        Species::reference(small),
        Species {
            count: large,
            radius,
            mass,
        },
    ];
    let size = box_size_for(&species, eta, 1.5);
    let sim_box = SimBox {
        size,
        boundary: [Boundary::Periodic, Boundary::Walls { restitution: 1.0 }],
    };
    let spec = SystemSpec {
        species,
        sim_box,
        temperature: 1.0,
        seed,
        placement,
        velocities: Velocities::MaxwellBoltzmann,
    };
    Engine::with_grids(spec.build().unwrap(), EngineParams::default(), split).unwrap()
}

/// 150 + 50 discs of radii 0.5 and 0.7 in a channel (one grid).
fn channel_mixture() -> Engine {
    channel((150, 50), (0.7, 4.0), 0.45, (7, Placement::Lattice), true)
}

/// 400 small discs and 6 of 6 times their diameter in a channel: a grid per
/// size class (or one for all, when not `split`).
fn asymmetric_channel(split: bool) -> Engine {
    channel((400, 6), (3.0, 36.0), 0.35, (8, Placement::Relaxed), split)
}

fn trajectory(e: &mut Engine, n: usize) -> Vec<Event> {
    (0..n).map(|_| e.next_event().unwrap().unwrap()).collect()
}

#[test]
fn resumed_engine_continues_bit_identically() {
    let mut a = channel_mixture();
    // Stop 5 000 collisions short of a renumbering (every 65 536 pair collisions
    // here), so that the compared stretch crosses one.
    a.run_collisions(60_000).unwrap();
    let before = a.stats().pair_collisions;
    a.schedule(a.now() + 3.0, 1).unwrap();
    let mut b = Engine::from_checkpoint(a.checkpoint()).unwrap();
    let ta = trajectory(&mut a, 20_000);
    let tb = trajectory(&mut b, 20_000);
    assert!(ta
        .iter()
        .any(|e| matches!(e, Event::Scheduled { tag: 1, .. })));
    assert_eq!(ta, tb);
    assert!(before < 65_536 && a.stats().pair_collisions > 65_536);
    let (sa, sb) = (a.state(), b.state());
    let bits = |v: &[DVec2]| {
        v.iter()
            .flat_map(|p| [p.x.to_bits(), p.y.to_bits()])
            .collect::<Vec<_>>()
    };
    assert_eq!(bits(&sa.positions), bits(&sb.positions));
    assert_eq!(bits(&sa.velocities), bits(&sb.velocities));
}

/// Run the asymmetric channel (a grid per size class if `split`) for 10⁴
/// events, resume a copy from its checkpoint, and check that both have `grids`
/// grids, follow the same next 2·10⁴ events and end with equal checkpoints.
fn resumes_bit_identically(split: bool, grids: usize) -> Engine {
    let mut a = asymmetric_channel(split);
    assert_eq!(a.grid_count(), grids);
    a.run_collisions(10_000).unwrap();
    let mut b = Engine::from_checkpoint(a.checkpoint()).unwrap();
    assert_eq!(b.grid_count(), grids);
    assert_eq!(trajectory(&mut a, 20_000), trajectory(&mut b, 20_000));
    assert_eq!(a.checkpoint(), b.checkpoint());
    a
}

#[test]
fn a_grid_per_size_class_resumes_bit_identically() {
    resumes_bit_identically(true, 2);
}

#[test]
fn a_checkpoint_with_one_grid_for_all_sizes_resumes_with_one() {
    // As written before carom had size classes.
    let a = resumes_bit_identically(false, 1);
    // Lists that fit neither layout are refused, naming the cells needed.
    let mut cp = a.checkpoint();
    cp.cell_head.push(NO_DISC);
    let Err(EngineError::BadCheckpoint(m)) = Engine::from_checkpoint(cp) else {
        panic!("accepted a checkpoint with a cell too many");
    };
    assert!(m.contains("cells stored"), "{m}");
}

#[test]
fn any_point_of_a_path_restores_it() {
    // carom writes each path's origin with time 0; a checkpoint naming another
    // point of the same line (the position at time t, as older checkpoints
    // stored it) must restore the same paths, to rounding.
    let mut a = channel_mixture();
    a.run_collisions(5_000).unwrap();
    let cp = a.checkpoint();
    assert!(cp.times.iter().all(|&t| t == 0.0));
    let mut moved = cp.clone();
    for (k, (p, v)) in moved.positions.iter_mut().zip(&cp.velocities).enumerate() {
        let t = cp.clock - 0.25 * (k % 4) as f64;
        *p += *v * t;
        moved.times[k] = t;
    }
    let b = Engine::from_checkpoint(moved).unwrap();
    let (sa, sb) = (a.state(), b.state());
    for (i, (pa, pb)) in sa.positions.iter().zip(&sb.positions).enumerate() {
        let d = a.sim_box().minimum_image(*pb - *pa).length();
        assert!(d < 1e-12, "disc {i}: restored {d} away from its path");
    }
    assert_eq!(sa.velocities, sb.velocities);
    // The same position named at another time is another path: the disc is
    // then displaced by v Δt (which shows the times are not ignored).
    let mut off = cp.clone();
    off.times[0] = 0.5;
    let c = Engine::from_checkpoint(off).unwrap();
    let ext = cp.labels[0] as usize;
    let d = a
        .sim_box()
        .minimum_image(c.state().positions[ext] - sa.positions[ext])
        .length();
    let expected = 0.5 * cp.velocities[0].length();
    assert!((d - expected).abs() < 1e-9, "{d} vs {expected}");
}

#[test]
fn inconsistent_checkpoint_is_rejected() {
    let a = channel_mixture();
    let mut cp = a.checkpoint();
    cp.times.pop();
    assert!(matches!(
        Engine::from_checkpoint(cp),
        Err(EngineError::BadCheckpoint(_))
    ));
    let mut cp = a.checkpoint();
    cp.cell_next[3] = 1_000_000;
    assert!(matches!(
        Engine::from_checkpoint(cp),
        Err(EngineError::BadCheckpoint(_))
    ));
    // A list that loops back on itself (the event loop would never leave it).
    let mut cp = a.checkpoint();
    let first = cp.cell_head.iter().position(|&h| h != NO_DISC).unwrap();
    let d = cp.cell_head[first];
    cp.cell_next[d as usize] = d;
    let err = Engine::from_checkpoint(cp).unwrap_err().to_string();
    assert!(err.contains(&format!("disc {d} is listed twice")), "{err}");
    // Back links that do not match the forward links.
    let mut cp = a.checkpoint();
    cp.cell_prev[d as usize] = (d + 1) % cp.cell_prev.len() as u32;
    let err = Engine::from_checkpoint(cp).unwrap_err().to_string();
    assert!(err.contains("back links"), "{err}");
    // A path that is not finite: each of its three parts is named.
    let mut cp = a.checkpoint();
    cp.positions[2].x = f64::NAN;
    let err = Engine::from_checkpoint(cp).unwrap_err().to_string();
    assert!(err.contains("position of disc 2 is not finite"), "{err}");
    let mut cp = a.checkpoint();
    cp.velocities[4].y = f64::INFINITY;
    let err = Engine::from_checkpoint(cp).unwrap_err().to_string();
    assert!(err.contains("velocity of disc 4 is not finite"), "{err}");
    let mut cp = a.checkpoint();
    cp.times[1] = f64::NEG_INFINITY;
    let err = Engine::from_checkpoint(cp).unwrap_err().to_string();
    assert!(err.contains("time of disc 1 is not finite"), "{err}");
    // Finite parts whose path origin p − v t overflows.
    let mut cp = a.checkpoint();
    cp.velocities[3] = DVec2::new(1e300, 0.0);
    cp.times[3] = 1e300;
    let err = Engine::from_checkpoint(cp).unwrap_err().to_string();
    assert!(err.contains("path of disc 3 overflows"), "{err}");
}
