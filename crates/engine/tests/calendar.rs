//! The calendar of scheduled events (engine::calendar): every u64 tag is the
//! caller's, the thermostat's events share the caller's sequence counter (so at
//! one time they come in the order they were made), and a resume from a
//! checkpoint keeps that order bit for bit.

use carom_engine::{Engine, EngineParams, Event, SystemSpec, Thermostat};

fn fluid(n: usize, eta: f64, seed: u64) -> Engine {
    Engine::new(
        SystemSpec::periodic_fluid(n, eta, seed).build().unwrap(),
        EngineParams::default(),
    )
    .unwrap()
}

/// Driving kicks every 1.0 from time 0 (the first kick's entry is made now).
fn driven(e: &mut Engine) {
    let t = Thermostat::Driven {
        xi2: 0.05,
        interval: 1.0,
    };
    e.set_thermostat(Some(t), 5).unwrap();
}

/// The caller's events up to `n` of them, each with the number of thermostat
/// kicks done when it was delivered; pauses left out.
fn delivered(e: &mut Engine, n: usize) -> Vec<(f64, u64, u64)> {
    let mut out = Vec::new();
    while out.len() < n {
        if let Event::Scheduled { time, tag } = e.next_event().unwrap().unwrap() {
            out.push((time, tag, e.thermostat_stats().events));
        }
    }
    out
}

/// The tags carom once kept for itself (the thermostat's u64::MAX − 1, the
/// pause's u64::MAX − 2) are the caller's like any other, with a thermostat
/// running too.
#[test]
fn every_tag_is_the_callers() {
    let mut e = fluid(100, 0.3, 3);
    driven(&mut e);
    for (k, tag) in [u64::MAX - 1, u64::MAX - 2, 0, u64::MAX]
        .into_iter()
        .enumerate()
    {
        e.schedule(0.5 + k as f64, tag).unwrap();
    }
    let got: Vec<(f64, u64)> = delivered(&mut e, 4).iter().map(|d| (d.0, d.1)).collect();
    assert_eq!(
        got,
        vec![
            (0.5, u64::MAX - 1),
            (1.5, u64::MAX - 2),
            (2.5, 0),
            (3.5, u64::MAX)
        ]
    );
    assert_eq!(e.thermostat_stats().events, 3);
}

/// At one time a kick and a caller's event come in the order they were made.
/// The kick at 1 is made when the thermostat is set, before the caller's event
/// at 1: the caller sees it done. The kick at 2 is made at the kick at 1, after
/// the caller's event at 2: the caller sees it not yet done. A copy resumed from
/// a checkpoint taken between keeps both orders and the trajectory, bit for bit.
#[test]
fn kicks_and_callers_events_at_one_time_keep_their_order_through_a_resume() {
    let mut a = fluid(200, 0.35, 4);
    driven(&mut a);
    for k in 1..=4 {
        a.schedule(k as f64, 10 + k).unwrap();
    }
    let first = delivered(&mut a, 1);
    assert_eq!(first, vec![(1.0, 11, 1)]);
    // Kick 3's entry is made at kick 2, after this event at 3: the event first.
    let mut b = Engine::from_checkpoint(a.checkpoint()).unwrap();
    assert_eq!(a.checkpoint(), b.checkpoint());
    let (ta, tb) = (delivered(&mut a, 3), delivered(&mut b, 3));
    assert_eq!(ta, vec![(2.0, 12, 1), (3.0, 13, 2), (4.0, 14, 3)]);
    assert_eq!(ta, tb);
    assert_eq!(a.checkpoint(), b.checkpoint());
    let bits = |e: &Engine| -> Vec<u64> {
        let s = e.state();
        s.positions
            .iter()
            .chain(&s.velocities)
            .flat_map(|p| [p.x.to_bits(), p.y.to_bits()])
            .collect()
    };
    assert_eq!(bits(&a), bits(&b));
}

/// Without a thermostat the checkpoint holds exactly the caller's events, and
/// the thermostat's next event is held apart from them when one is set.
#[test]
fn the_thermostats_next_event_is_not_among_the_callers() {
    let mut e = fluid(50, 0.3, 6);
    e.schedule(2.0, u64::MAX - 1).unwrap();
    let cp = e.checkpoint();
    assert_eq!(cp.scheduled, vec![(2.0, 0, u64::MAX - 1)]);
    assert!(cp.thermostat.is_none());
    driven(&mut e);
    let cp = e.checkpoint();
    assert_eq!(cp.scheduled, vec![(2.0, 0, u64::MAX - 1)]);
    assert_eq!(cp.thermostat.unwrap().next, Some((1.0, 1)));
    assert_eq!(cp.next_seq, 2);
}

/// `run_until`'s end is the engine's own entry: a caller's event with any tag
/// (u64::MAX, which it once borrowed) before it does not end the run early, and
/// nothing of the stop is left behind, neither in the calendar nor in a
/// checkpoint. The run still ends at exactly `t_end`.
#[test]
fn run_until_borrows_no_tag() {
    let mut e = fluid(100, 0.3, 4);
    e.schedule(0.5, u64::MAX).unwrap();
    e.schedule(3.0, u64::MAX).unwrap();
    let collisions = e.run_until(2.0).unwrap();
    assert_eq!(e.now(), 2.0);
    assert!(collisions > 0);
    let tags: Vec<u64> = e.checkpoint().scheduled.iter().map(|s| s.2).collect();
    assert_eq!(tags, [u64::MAX], "only the caller's event at 3.0 is left");
    // With a thermostat (pauses on the way) and growth-free: the same.
    let mut d = fluid(100, 0.3, 4);
    driven(&mut d);
    d.schedule(0.5, u64::MAX).unwrap();
    d.run_until(4.5).unwrap();
    assert_eq!(d.now(), 4.5);
    assert!(d.checkpoint().scheduled.is_empty());
    // The next caller's event comes to the caller, not to a stale stop.
    d.schedule(5.0, 11).unwrap();
    assert_eq!(
        delivered(&mut d, 1),
        [(5.0, 11, d.thermostat_stats().events)]
    );
}
