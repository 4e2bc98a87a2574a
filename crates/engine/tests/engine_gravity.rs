//! Uniform gravity (physics.md §15): hand-worked single-disc flights (bounce times
//! and heights on the floor and under the ceiling, a parabola through the cells with
//! its apex a hair below and a hair above a cell edge), total energy K + U conserved
//! to rounding in a long run of many discs, the checkpoint continuing bit for bit,
//! and the configurations the engine refuses. The comparison with a brute-force
//! reference is in `engine_gravity_reference.rs`.

use carom_core::{Boundary, DVec2, Restitution, SimBox, Species, WallSide};
use carom_engine::{
    box_size_for, Engine, EngineError, EngineParams, Event, Placement, State, SystemSpec,
    Velocities,
};

fn walls(lx: f64, ly: f64) -> SimBox {
    SimBox {
        size: DVec2::new(lx, ly),
        boundary: [Boundary::Walls { restitution: 1.0 }; 2],
    }
}

fn with_gravity(g: f64) -> EngineParams {
    EngineParams {
        gravity: g,
        ..EngineParams::default()
    }
}

/// Discs of radius 0.5 and mass 1 at `positions` with velocities `velocities`.
fn discs(sim_box: SimBox, positions: Vec<DVec2>, velocities: Vec<DVec2>) -> State {
    let n = positions.len();
    State {
        sim_box,
        species: vec![Species::reference(n)],
        species_of: vec![0; n],
        positions,
        velocities,
        images: Vec::new(),
        time: 0.0,
    }
}

/// The wall hits of the first `n` collisions, with every scheduled observation
/// `(time, position, velocity)` of disc 0 on the way.
fn wall_hits(
    e: &mut Engine,
    n: usize,
) -> (Vec<carom_engine::WallCollision>, Vec<(f64, DVec2, DVec2)>) {
    let (mut hits, mut seen) = (Vec::new(), Vec::new());
    while hits.len() < n {
        match e
            .next_event()
            .unwrap()
            .expect("a falling disc always has an event")
        {
            Event::Wall(w) => hits.push(w),
            Event::Pause { .. } => {}
            Event::Scheduled { time, .. } => seen.push((time, e.position(0), e.velocity(0))),
            Event::Pair(p) => panic!("no partner to collide with: {p:?}"),
        }
    }
    (hits, seen)
}

/// Dropped from rest at height 5 with g = 1 in a 10 × 10 box: the centre reaches
/// the floor (0.5) after falling 4.5 = t²/2, at t = 3, at speed 3; it comes back to
/// rest at 5 at t = 6 and bounces every 6 from then on: floor hits at 3 + 6k, all at
/// speed 3, apexes 5 at 6k.
#[test]
fn a_dropped_disc_bounces_on_the_floor_every_6_and_comes_back_to_its_height() {
    let state = discs(
        walls(10.0, 10.0),
        vec![DVec2::new(5.0, 5.0)],
        vec![DVec2::ZERO],
    );
    let mut e = Engine::new(state, with_gravity(1.0)).unwrap();
    for k in 1..=20 {
        e.schedule(6.0 * k as f64, k).unwrap();
    }
    let (hits, seen) = wall_hits(&mut e, 20);
    for (k, w) in hits.iter().enumerate() {
        let t = 3.0 + 6.0 * k as f64;
        assert!(
            (w.time - t).abs() < 1e-13 * t,
            "hit {k} at {} not {t}",
            w.time
        );
        assert_eq!((w.side, w.axis), (WallSide::Low, carom_core::Axis::Y));
        assert!((w.v_before.y + 3.0).abs() < 1e-13, "{:?}", w.v_before);
        assert_eq!(w.v_after.y, -w.v_before.y);
        assert_eq!(w.v_before.x, 0.0);
    }
    assert_eq!(seen.len(), 19);
    for (k, &(t, r, v)) in seen.iter().enumerate() {
        assert_eq!(t, 6.0 * (k + 1) as f64);
        assert!((r - DVec2::new(5.0, 5.0)).length() < 1e-12, "apex {k}: {r}");
        assert!(v.y.abs() < 1e-12, "apex {k}: {v}");
    }
    let energy = e.kinetic_energy() + e.potential_energy();
    assert!(
        (energy - 5.0).abs() < 1e-12,
        "K + U = {energy}, dropped from m g y = 5"
    );
}

/// Thrown up at 4 from height 5 (g = 1, 10 × 10 box, radius 0.5): it meets the
/// ceiling (centre 9.5) when 4.5 = 4t − t²/2, t = 4 − √7, at speed √7; falls from
/// there to the floor in 9 = √7 t + t²/2, t = 5 − √7, arriving at speed 5, which
/// takes it back up to the ceiling in 5 − √7 again. The k-th hit (k = 1, 2, …) is
/// at 5k − 1 − k√7, ceiling and floor in turn.
#[test]
fn a_disc_thrown_up_alternates_ceiling_and_floor_at_hand_worked_times() {
    let state = discs(
        walls(10.0, 10.0),
        vec![DVec2::new(5.0, 5.0)],
        vec![DVec2::new(0.0, 4.0)],
    );
    let mut e = Engine::new(state, with_gravity(1.0)).unwrap();
    let (hits, _) = wall_hits(&mut e, 40);
    let r7 = 7f64.sqrt();
    for (k, w) in hits.iter().enumerate() {
        let k1 = (k + 1) as f64;
        let t = 5.0 * k1 - 1.0 - k1 * r7;
        assert!(
            (w.time - t).abs() < 1e-12 * t,
            "hit {k1} at {} not {t}",
            w.time
        );
        let (side, speed) = if k % 2 == 0 {
            (WallSide::High, r7)
        } else {
            (WallSide::Low, 5.0)
        };
        assert_eq!(w.side, side, "hit {k1}");
        assert!(
            (w.v_before.y.abs() - speed).abs() < 1e-12,
            "hit {k1}: {:?}",
            w.v_before
        );
    }
}

/// Ten discs side by side with one velocity never meet (their relative velocities
/// are 0), so each flies the same parabola y = y0 + u t − g t²/2 through the cell
/// rows, and the engine counts one crossing per row edge passed. The apex is put
/// 10⁻⁹ below a row edge (never crossed: up and down the rows below it) and 10⁻⁹
/// above one (crossed up and at once back down): the crossings on the way are
/// counted exactly and the positions at 40 observation times follow the parabola.
#[test]
fn a_parabola_crosses_the_cell_rows_it_passes_and_turns_at_its_apex() {
    let (lx, ly, g, y0) = (24.0, 30.0, 0.7, 2.25);
    for margin in [-1e-9, 1e-9] {
        let xs: Vec<DVec2> = (0..10)
            .map(|k| DVec2::new(1.5 + 2.3 * k as f64, y0))
            .collect();
        let sim_box = walls(lx, ly);
        // The row edges of the engine's grid, from its row count.
        let rows = {
            let e = Engine::new(
                discs(sim_box, xs.clone(), vec![DVec2::ZERO; 10]),
                with_gravity(g),
            );
            e.unwrap().cells()[1]
        };
        let w = ly / rows as f64;
        // Apex a hair from the 4th edge above the start.
        let edge = ((y0 / w).floor() + 4.0) * w;
        let apex = edge + margin;
        let u = (2.0 * g * (apex - y0)).sqrt();
        let mut e = Engine::new(
            discs(sim_box, xs.clone(), vec![DVec2::new(0.0, u); 10]),
            with_gravity(g),
        )
        .unwrap();
        // Up to the apex and down to the floor (centre at 0.5).
        let t_floor = (u + (u * u + 2.0 * g * (y0 - 0.5)).sqrt()) / g;
        for k in 1..=40 {
            e.schedule(t_floor * k as f64 / 41.0, k).unwrap();
        }
        let (hits, seen) = wall_hits(&mut e, 10);
        for h in &hits {
            assert!(
                (h.time - t_floor).abs() < 1e-12 * t_floor,
                "{} not {t_floor}",
                h.time
            );
        }
        for (t, r, v) in seen {
            let y = y0 + u * t - 0.5 * g * t * t;
            assert!(
                (r.y - y).abs() < 1e-12 && r.x == xs[0].x,
                "at {t}: {r} not y = {y}"
            );
            assert!((v.y - (u - g * t)).abs() < 1e-12, "at {t}: {v}");
        }
        // Edges crossed: those strictly between y0 and the apex on the way up, and
        // between 0.5 and the apex on the way down.
        let edges = (1..rows).map(|k| k as f64 * w);
        let up = edges.clone().filter(|&y| y > y0 && y < apex).count();
        let down = edges.filter(|&y| y > 0.5 && y < apex).count();
        assert_eq!(
            e.stats().cell_crossings,
            10 * (up + down) as u64,
            "apex {margin:e} from an edge: {up} up, {down} down for each of 10 discs"
        );
    }
}

/// 400 discs at η = 0.3 and kT = 1 placed at random in a walled box, falling in
/// g = 0.5.
fn settling_fluid(seed: u64) -> Engine {
    let species = vec![Species::reference(400)];
    let spec = SystemSpec {
        sim_box: SimBox {
            size: box_size_for(&species, 0.3, 1.0),
            boundary: [Boundary::Walls { restitution: 1.0 }; 2],
        },
        species,
        temperature: 1.0,
        seed,
        placement: Placement::Random,
        velocities: Velocities::MaxwellBoltzmann,
    };
    Engine::new(spec.build().unwrap(), with_gravity(0.5)).unwrap()
}

/// 400 discs at η = 0.3 in a walled box, g = 0.5 (scale height kT/mg = 2 in a box
/// 32 high): over 2 · 10⁵ collisions K + U stays at its start to 10⁻¹¹ of K, and the
/// potential energy has fallen by more than a tenth (the discs are settling; K + U
/// conserved with U fixed would test little).
#[test]
fn total_energy_is_conserved_to_rounding_over_a_long_run() {
    let mut e = settling_fluid(3);
    let (k0, u0) = (e.kinetic_energy(), e.potential_energy());
    for _ in 0..20 {
        e.run_collisions(10_000).unwrap();
        let drift = (e.kinetic_energy() + e.potential_energy() - (k0 + u0)) / k0;
        assert!(
            drift.abs() < 1e-11,
            "relative drift {drift:e} at t = {}",
            e.now()
        );
    }
    assert!(
        e.potential_energy() < 0.9 * u0,
        "U fell from {u0} to only {}",
        e.potential_energy()
    );
}

/// A run with gravity resumed from its checkpoint follows the same events bit for
/// bit and ends in the same checkpoint: the field is part of it, and the clock's
/// restarts (forced in the field every √(L_y/g)) happen on both alike.
#[test]
fn a_run_with_gravity_resumes_bit_identically_from_its_checkpoint() {
    for (boundary_x, rule) in [
        (
            Boundary::Walls { restitution: 0.9 },
            Restitution::Normal(0.95),
        ),
        (Boundary::Periodic, Restitution::Elastic),
    ] {
        let species = vec![Species::reference(120), Species::new(30, 0.7, 2.5)];
        let spec = SystemSpec {
            sim_box: SimBox {
                size: box_size_for(&species, 0.35, 1.0),
                boundary: [boundary_x, Boundary::Walls { restitution: 1.0 }],
            },
            species,
            temperature: 1.0,
            seed: 11,
            placement: Placement::Random,
            velocities: Velocities::MaxwellBoltzmann,
        };
        let params = EngineParams {
            restitution: rule,
            tc: if rule.is_elastic() { 0.0 } else { 1e-3 },
            gravity: 0.8,
            ..EngineParams::default()
        };
        let mut a = Engine::new(spec.build().unwrap(), params).unwrap();
        a.run_collisions(20_000).unwrap();
        let mut b = Engine::from_checkpoint(a.checkpoint()).unwrap();
        assert_eq!(b.gravity(), 0.8);
        for _ in 0..60_000 {
            assert_eq!(a.next_event().unwrap(), b.next_event().unwrap());
        }
        assert_eq!(a.checkpoint(), b.checkpoint());
        assert_eq!(a.state(), b.state());
    }
}

/// A field with a periodic y axis, a negative or a non-finite g are refused, by
/// the engine and when a checkpoint is restored.
#[test]
fn gravity_needs_walls_along_y_and_a_finite_g_at_least_0() {
    let one = |sim_box: SimBox| discs(sim_box, vec![DVec2::new(2.0, 2.0)], vec![DVec2::ZERO]);
    let channel_x = SimBox {
        size: DVec2::new(5.0, 5.0),
        boundary: [Boundary::Walls { restitution: 1.0 }, Boundary::Periodic],
    };
    for (sim_box, g) in [
        (channel_x, 1.0),
        (walls(5.0, 5.0), -1.0),
        (walls(5.0, 5.0), f64::NAN),
        (walls(5.0, 5.0), f64::INFINITY),
    ] {
        let Err(err) = Engine::new(one(sim_box), with_gravity(g)) else {
            panic!("accepted g = {g} in {sim_box:?}");
        };
        assert!(matches!(err, EngineError::BadGravity(_)), "{err}");
        assert!(err.to_string().contains("walls"), "{err}");
    }
    // Without a field a periodic y is fine, and so is g = 0 anywhere.
    assert!(Engine::new(one(channel_x), with_gravity(0.0)).is_ok());
    let mut cp = Engine::new(one(walls(5.0, 5.0)), with_gravity(1.0))
        .unwrap()
        .checkpoint();
    cp.sim_box.boundary[1] = Boundary::Periodic;
    let Err(EngineError::BadCheckpoint(m)) = Engine::from_checkpoint(cp) else {
        panic!("restored a checkpoint with gravity and a periodic y");
    };
    assert!(m.contains("periodic"), "{m}");
}

/// A thermostat in a field acts on the discs' true velocities: over a run of 400
/// discs (g = 0.5) with Andersen (kT = 2) and then with driving, K + U changes by
/// exactly the energy the thermostat counts, to rounding. Were the redraws applied
/// to the stored path velocities (which run ahead by ŷ g t), the count and the
/// change would part by far more.
#[test]
fn a_thermostat_in_a_field_counts_the_energy_it_adds() {
    use carom_engine::Thermostat;
    for (k, thermostat) in [
        Thermostat::Andersen { kt: 2.0, rate: 0.2 },
        Thermostat::Driven {
            xi2: 0.5,
            interval: 0.05,
        },
    ]
    .into_iter()
    .enumerate()
    {
        let mut e = settling_fluid(21 + k as u64);
        e.set_thermostat(Some(thermostat), 5).unwrap();
        let e0 = e.kinetic_energy() + e.potential_energy();
        e.run_until(20.0).unwrap();
        let stats = e.thermostat_stats();
        assert!(
            stats.events > 100,
            "{thermostat:?}: {} events",
            stats.events
        );
        let change = e.kinetic_energy() + e.potential_energy() - e0;
        assert!(
            (change - stats.energy_added).abs() < 1e-10 * e0,
            "{thermostat:?}: K + U changed by {change}, the thermostat counts {}",
            stats.energy_added
        );
    }
}
