//! Periodic images: the unwrapped position `positions + images · L` the engine
//! reports is the position each disc reaches by flying straight between the
//! velocity changes the event stream reports (an independent integration of the
//! trajectory), across renumberings and clock restarts, and survives a checkpoint.

mod engine_common;
use carom_core::{Boundary, DVec2, SimBox};
use carom_engine::{Engine, EngineParams, Event, State, SystemSpec};
use engine_common::{lattice_spec, mixture};

/// The unwrapped position of every disc by its own flights: the position at the
/// last velocity change plus velocity × time since.
struct Flights {
    at: Vec<DVec2>,
    since: Vec<f64>,
    v: Vec<DVec2>,
}

impl Flights {
    fn new(s: &State) -> Self {
        Flights {
            at: s.positions.clone(),
            since: vec![s.time; s.len()],
            v: s.velocities.clone(),
        }
    }

    fn turn(&mut self, i: u32, t: f64, v: DVec2) {
        let i = i as usize;
        self.at[i] += self.v[i] * (t - self.since[i]);
        (self.since[i], self.v[i]) = (t, v);
    }

    fn event(&mut self, e: &Event) {
        match e {
            Event::Pair(c) => {
                self.turn(c.i, c.time, c.vi_after);
                self.turn(c.j, c.time, c.vj_after);
            }
            Event::Wall(w) => self.turn(w.i, w.time, w.v_after),
            Event::Scheduled { .. } | Event::Pause { .. } => {}
        }
    }

    fn now(&self, i: usize, t: f64) -> DVec2 {
        self.at[i] + self.v[i] * (t - self.since[i])
    }
}

/// The largest distance between the engine's unwrapped positions and the
/// flights', and the largest |image| component, at the engine's current time.
fn compare(e: &Engine, f: &Flights) -> (f64, i32) {
    let s = e.state();
    assert_eq!(s.images.len(), s.len());
    let mut worst = (0.0f64, 0);
    for i in 0..s.len() {
        let image = DVec2::new(s.images[i][0] as f64, s.images[i][1] as f64);
        let unwrapped = s.positions[i] + image * s.sim_box.size;
        worst.0 = worst.0.max((unwrapped - f.now(i, s.time)).length());
        worst.1 = worst.1.max(s.images[i][0].abs().max(s.images[i][1].abs()));
    }
    worst
}

/// Run `e` to `t_end`, comparing at `checks` evenly spaced times.
fn follow(e: &mut Engine, f: &mut Flights, t_end: f64, checks: u32) -> (f64, i32) {
    let t0 = e.now();
    for k in 1..=checks {
        e.schedule(t0 + (t_end - t0) * k as f64 / checks as f64, k as u64)
            .unwrap();
    }
    let mut worst = (0.0f64, 0);
    while let Some(ev) = e.next_event().unwrap() {
        f.event(&ev);
        if let Event::Scheduled { tag, .. } = ev {
            let (d, m) = compare(e, f);
            worst = (worst.0.max(d), worst.1.max(m));
            if tag == checks as u64 {
                break;
            }
        }
    }
    worst
}

/// A dilute periodic fluid: discs fly several box lengths, so images reach many
/// box lengths either way, through several renumberings (every 2¹⁶ collisions).
#[test]
fn unwrapped_positions_follow_the_flights_in_a_periodic_fluid() {
    let s = SystemSpec::periodic_fluid(400, 0.05, 11).build().unwrap();
    let l = s.sim_box.size.x;
    let mut f = Flights::new(&s);
    let mut e = Engine::new(s, EngineParams::default()).unwrap();
    assert!(e.state().images.iter().all(|m| *m == [0, 0]));
    let (err, most) = follow(&mut e, &mut f, 40.0 * l, 50);
    assert!(e.stats().pair_collisions > 1 << 17, "{:?}", e.stats());
    // Rounding: positions of size |image| L, after ~10⁵ flights of rounding each.
    assert!(err < 1e-9 * l * (1.0 + most as f64), "{err} (box {l})");
    assert!(most >= 3, "discs crossed at most {most} box lengths");
}

/// A mixture in a channel (periodic in x, walls in y, unequal sides): images along
/// the walled axis stay 0, along x they count the crossings.
#[test]
fn images_along_walls_stay_zero_in_a_channel() {
    let size = DVec2::new(37.0, 23.0);
    let walls = Boundary::Walls { restitution: 1.0 };
    let sim_box = SimBox {
        size,
        boundary: [Boundary::Periodic, walls],
    };
    let s = lattice_spec(mixture(90, 30), sim_box, 5).build().unwrap();
    let mut f = Flights::new(&s);
    let mut e = Engine::new(s, EngineParams::default()).unwrap();
    let (err, most) = follow(&mut e, &mut f, 300.0, 30);
    assert!(e.stats().wall_collisions > 1000);
    assert!(err < 1e-9 * size.x * (1.0 + most as f64), "{err}");
    assert!(most >= 2, "{most}");
    assert!(e.state().images.iter().all(|m| m[1] == 0));
}

/// A checkpoint keeps each disc's images: the resumed engine reports the same
/// images bit for bit; one from a checkpoint without them (as written before
/// carom counted them) restarts the count at 0 where the discs then are.
#[test]
fn a_checkpoint_keeps_the_images() {
    let s = SystemSpec::periodic_fluid(300, 0.1, 3).build().unwrap();
    let mut a = Engine::new(s, EngineParams::default()).unwrap();
    a.run_until(100.0).unwrap();
    let cp = a.checkpoint();
    assert!(cp.images.iter().any(|m| *m != [0, 0]));
    let mut b = Engine::from_checkpoint(cp.clone()).unwrap();
    assert_eq!(b.state(), a.state());
    a.run_until(150.0).unwrap();
    b.run_until(150.0).unwrap();
    assert_eq!(b.state(), a.state());

    let mut old = cp;
    old.images.clear();
    let mut c = Engine::from_checkpoint(old).unwrap();
    let start = c.state();
    assert!(start.images.iter().all(|m| *m == [0, 0]));
    let mut f = Flights::new(&start);
    let (err, most) = follow(&mut c, &mut f, 200.0, 5);
    assert!(err < 1e-9 * start.sim_box.size.x * (1.0 + most as f64));
    assert!(most >= 1);

    let mut short = a.checkpoint();
    short.images.pop();
    let refused = Engine::from_checkpoint(short).unwrap_err().to_string();
    assert!(
        refused.contains("images has 299 entries for 300 discs"),
        "{refused}"
    );
}

/// Images given with the initial state carry on: the engine starts from them.
#[test]
fn given_images_are_kept() {
    let mut s = SystemSpec::periodic_fluid(50, 0.2, 9).build().unwrap();
    s.images = (0..50).map(|i| [i - 25, 3 * i]).collect();
    let mut f = Flights::new(&s);
    let l = s.sim_box.size;
    for (p, m) in f.at.iter_mut().zip(&s.images) {
        *p += DVec2::new(m[0] as f64, m[1] as f64) * l;
    }
    let mut e = Engine::new(s.clone(), EngineParams::default()).unwrap();
    assert_eq!(e.state().images, s.images);
    let (err, _) = follow(&mut e, &mut f, 50.0, 5);
    assert!(err < 1e-9 * l.x * 200.0, "{err}");
}
