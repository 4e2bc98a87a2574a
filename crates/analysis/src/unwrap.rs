//! Unwrapped positions over a run's snapshots (physics.md §12): each disc's
//! position continuous in time, u_i = r_i + n_i L along periodic axes. Snapshots
//! of log format 2.1 on carry the image n_i the engine counts at every crossing of
//! a periodic edge, and u_i follows exactly. Older snapshots carry none: the
//! image change between two snapshots is then taken as the minimum image of the
//! displacement, which is right when no disc can have moved half a box length in
//! between. A disc's speed is at most √(2K/m_i) (K the kinetic energy of the
//! earlier snapshot; collisions never raise it), so a gap Δt is unambiguous when
//! √(2K/m_min) Δt < L/2 on every periodic axis; longer gaps are unwrapped the same
//! way and counted, so that a report can warn.

use carom_core::DVec2;
use carom_log::Snapshot;

/// Unwraps the positions of successive snapshots of one run.
#[derive(Debug, Default)]
pub struct Unwrapper {
    /// The previous snapshot's time, wrapped positions, images (if it had them)
    /// and the bound on how far any disc moves per unit time.
    previous: Option<Previous>,
    unwrapped: Vec<DVec2>,
    inferred_gaps: u64,
    ambiguous_gaps: u64,
}

#[derive(Debug)]
struct Previous {
    time: f64,
    positions: Vec<DVec2>,
    images: Vec<[i32; 2]>,
    box_size: DVec2,
    max_speed: f64,
}

/// The largest speed any disc can reach from snapshot `s` on, √(2K/m_min).
fn max_speed(s: &Snapshot) -> f64 {
    let k: f64 = (0..s.len())
        .map(|i| 0.5 * s.mass(i) * s.velocities[i].length_squared())
        .sum();
    let m_min = (0..s.len())
        .map(|i| s.mass(i))
        .fold(f64::INFINITY, f64::min);
    (2.0 * k / m_min).sqrt()
}

impl Unwrapper {
    /// An unwrapper that has seen no snapshot.
    pub fn new() -> Self {
        Self::default()
    }

    /// The unwrapped positions at snapshot `s`, which follows the previous one in
    /// time. The first snapshot's unwrapped positions are its wrapped ones plus its
    /// images; so are those of a snapshot of other discs or another box than the
    /// previous one (a new start).
    pub fn push(&mut self, s: &Snapshot) -> &[DVec2] {
        let periodic = s.boundary.map(|b| b == 0);
        let shift = |m: [i32; 2]| DVec2::new(m[0] as f64, m[1] as f64) * s.box_size;
        let images = s.images.len() == s.len();
        match &self.previous {
            Some(p) if p.positions.len() == s.len() && p.box_size == s.box_size => {
                let both = images && p.images.len() == s.len();
                if !both {
                    self.inferred_gaps += 1;
                    let reach = p.max_speed * (s.time - p.time);
                    let half = (0..2)
                        .filter(|&k| periodic[k])
                        .map(|k| 0.5 * s.box_size[k])
                        .fold(f64::INFINITY, f64::min);
                    if reach.is_nan() || reach >= half {
                        self.ambiguous_gaps += 1;
                    }
                }
                for i in 0..s.len() {
                    let step = if both {
                        (s.positions[i] + shift(s.images[i]))
                            - (p.positions[i] + shift(p.images[i]))
                    } else {
                        let mut d = s.positions[i] - p.positions[i];
                        for k in (0..2).filter(|&k| periodic[k]) {
                            d[k] -= s.box_size[k] * (d[k] / s.box_size[k]).round();
                        }
                        d
                    };
                    self.unwrapped[i] += step;
                }
            }
            _ => {
                self.unwrapped = (0..s.len())
                    .map(|i| {
                        s.positions[i]
                            + if images {
                                shift(s.images[i])
                            } else {
                                DVec2::ZERO
                            }
                    })
                    .collect();
            }
        }
        self.previous = Some(Previous {
            time: s.time,
            positions: s.positions.clone(),
            images: s.images.clone(),
            box_size: s.box_size,
            max_speed: max_speed(s),
        });
        &self.unwrapped
    }

    /// Gaps between snapshots unwrapped by the minimum image (a snapshot without
    /// images on either side).
    pub fn inferred_gaps(&self) -> u64 {
        self.inferred_gaps
    }

    /// Of those, the gaps long enough that a disc may have moved half a box length:
    /// their unwrapping may be wrong.
    pub fn ambiguous_gaps(&self) -> u64 {
        self.ambiguous_gaps
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use carom_core::Boundary;
    use carom_engine::{Engine, EngineParams, Event, SystemSpec};

    /// One disc of mass 2 at x = 9.5 moving at +0.3 in a 10 × 4 box periodic in x,
    /// walled in y, seen at t = 0 and t = 2: it crossed x = 10 once and is at
    /// 0.1, so its unwrapped x is 10.1, with or without the image (without: the
    /// step 0.1 − 9.5 = −9.4 is taken as its minimum image, +0.6). y moves by
    /// 2 × 0.25 = 0.5 along the wall axis and is never shifted. The speed bound
    /// √(2K/m) = |v| = √(0.3² + 0.25²) ≈ 0.39 reaches 0.78 < L_x/2 = 5 in Δt = 2.
    #[test]
    fn one_disc_across_the_edge() {
        let snap = |t: f64, x: f64, y: f64, image: i32| Snapshot {
            time: t,
            box_size: DVec2::new(10.0, 4.0),
            boundary: [0, 1],
            species_radius: vec![0.5],
            species_mass: vec![2.0],
            species: vec![0],
            positions: vec![DVec2::new(x, y)],
            velocities: vec![DVec2::new(0.3, 0.25)],
            images: if image < 0 { vec![] } else { vec![[image, 0]] },
        };
        for with_images in [true, false] {
            let m = |k: i32| if with_images { k } else { -1 };
            let mut u = Unwrapper::new();
            assert_eq!(u.push(&snap(0.0, 9.5, 1.0, m(0))), [DVec2::new(9.5, 1.0)]);
            let got = u.push(&snap(2.0, 0.1, 1.5, m(1)))[0];
            assert!((got - DVec2::new(10.1, 1.5)).length() < 1e-12, "{got}");
            assert_eq!(u.inferred_gaps(), u64::from(!with_images));
            assert_eq!(u.ambiguous_gaps(), 0);
            // 20 time units later (x = 6.1 + 1·10, two crossings in all): the bound
            // reaches 7.8 ≥ 5, so the gap is ambiguous without images, and the
            // minimum image (−4.0 + 10·0 = −4.0 → 6.1) is then one box short.
            let far = u.push(&snap(22.0, 6.1, 1.5, m(2)))[0];
            if with_images {
                assert!((far.x - 26.1).abs() < 1e-12, "{far}");
            } else {
                assert!((far.x - 6.1).abs() < 1e-12, "{far}");
                assert_eq!(u.ambiguous_gaps(), 1);
            }
        }
    }

    /// The speed bound √(2K/m_min) by hand: masses 2 and 0.5 at (3, 0) and
    /// (0, −2) give K = 9 + 1 = 10, so √(2·10/0.5) = √40.
    #[test]
    fn the_speed_bound_is_that_of_all_the_energy_in_the_lightest_disc() {
        let s = Snapshot {
            time: 0.0,
            box_size: DVec2::new(10.0, 10.0),
            boundary: [0, 0],
            species_radius: vec![0.5, 0.25],
            species_mass: vec![2.0, 0.5],
            species: vec![0, 1],
            positions: vec![DVec2::new(1.0, 1.0), DVec2::new(5.0, 5.0)],
            velocities: vec![DVec2::new(3.0, 0.0), DVec2::new(0.0, -2.0)],
            images: vec![],
        };
        assert_eq!(max_speed(&s), 40f64.sqrt());
        // Gaps with reach just under and at L/2 = 5: Δt = 5/√40 ± a little.
        let mut u = Unwrapper::new();
        u.push(&s);
        let dt = 5.0 / 40f64.sqrt();
        u.push(&Snapshot {
            time: dt * (1.0 - 1e-9),
            ..s.clone()
        });
        assert_eq!((u.inferred_gaps(), u.ambiguous_gaps()), (1, 0));
        u.push(&Snapshot {
            time: dt * (1.0 - 1e-9) + dt * (1.0 + 1e-9),
            ..s.clone()
        });
        assert_eq!((u.inferred_gaps(), u.ambiguous_gaps()), (2, 1));
    }

    /// A snapshot of other discs or another box starts afresh: its unwrapped
    /// positions are its own plus its images (here (2, −1) box lengths of 10 × 8).
    #[test]
    fn other_discs_or_another_box_start_afresh() {
        let s = |n: usize, size: DVec2, image: [i32; 2]| Snapshot {
            time: 0.0,
            box_size: size,
            boundary: [0, 0],
            species_radius: vec![0.5],
            species_mass: vec![1.0],
            species: vec![0; n],
            positions: vec![DVec2::new(1.0, 2.0); n],
            velocities: vec![DVec2::new(0.5, 0.5); n],
            images: vec![image; n],
        };
        let a = DVec2::new(10.0, 8.0);
        let mut u = Unwrapper::new();
        assert_eq!(u.push(&s(1, a, [2, -1])), [DVec2::new(21.0, -6.0)]);
        // Two discs now: a new start, not a step from the one disc before.
        assert_eq!(u.push(&s(2, a, [2, -1])), [DVec2::new(21.0, -6.0); 2]);
        // The same two discs in a box 12 × 8: a new start again.
        let b = DVec2::new(12.0, 8.0);
        assert_eq!(u.push(&s(2, b, [1, 0])), [DVec2::new(13.0, 2.0); 2]);
        assert_eq!(u.inferred_gaps(), 0);
    }

    /// Snapshots of an engine run a short time apart: unwrapping by the images and
    /// by the minimum image agree, and both are continuous across a switch from
    /// snapshots without images to snapshots whose images restart at 0 (a log
    /// resumed from a checkpoint written before images were counted).
    #[test]
    fn images_and_inference_agree_on_close_snapshots() {
        let state = SystemSpec::square_box(
            vec![
                carom_core::Species::reference(60),
                carom_core::Species::new(20, 0.7, 2.5),
            ],
            0.15,
            [Boundary::Periodic; 2],
            4,
        )
        .build()
        .unwrap();
        let size = state.sim_box.size;
        let mut e = Engine::new(state, EngineParams::default()).unwrap();
        let (mut exact, mut guessed, mut restarted) =
            (Unwrapper::new(), Unwrapper::new(), Unwrapper::new());
        let mut offset: Vec<[i32; 2]> = Vec::new();
        let mut first: [Vec<DVec2>; 3] = Default::default();
        let mut most = 0;
        for k in 1..=200 {
            e.schedule(0.5 * k as f64, k).unwrap();
            while !matches!(e.next_event().unwrap(), Some(Event::Scheduled { .. })) {}
            let s = Snapshot::from_state(&e.state());
            let a = exact.push(&s).to_vec();
            let b = guessed
                .push(&Snapshot {
                    images: vec![],
                    ..s.clone()
                })
                .to_vec();
            // Images restarting at 0 at snapshot 100: what a resumed run writes.
            if k == 100 {
                offset = s.images.clone();
            }
            let restart = Snapshot {
                images: if k < 100 {
                    vec![]
                } else {
                    s.images
                        .iter()
                        .zip(&offset)
                        .map(|(m, o)| [m[0] - o[0], m[1] - o[1]])
                        .collect()
                },
                ..s.clone()
            };
            let c = restarted.push(&restart).to_vec();
            // Displacements since the first snapshot (the first one's images are
            // known only where the snapshot has them).
            if k == 1 {
                first = [a.clone(), b.clone(), c.clone()];
            }
            for i in 0..s.len() {
                let [da, db, dc] = [&a, &b, &c].map(|u| u[i]);
                let [fa, fb, fc] = [0, 1, 2].map(|w| first[w][i]);
                assert!(
                    ((da - fa) - (db - fb)).length() < 1e-9,
                    "snapshot {k} disc {i}"
                );
                assert!(
                    ((da - fa) - (dc - fc)).length() < 1e-9,
                    "snapshot {k} disc {i}"
                );
                most = most.max(s.images[i][0].abs().max(s.images[i][1].abs()));
            }
        }
        assert!(most >= 1, "no disc crossed an edge in {size}");
        assert_eq!(exact.inferred_gaps(), 0);
        assert_eq!(guessed.inferred_gaps(), 199);
        assert_eq!(restarted.inferred_gaps(), 99);
        assert_eq!(guessed.ambiguous_gaps(), 0, "Δt = 0.5 in a box of {size}");
    }
}
