//! Tests of the event queue.

use super::*;
use proptest::prelude::*;

fn t(x: f64) -> Time {
    NotNan::new(x).unwrap()
}

/// A queue with its times in a plain array, as the tests drive it.
struct Q {
    q: EventQueue,
    times: Vec<f64>,
}

impl Q {
    fn new(n: usize) -> Q {
        Q {
            q: EventQueue::new(n),
            times: vec![f64::INFINITY; n],
        }
    }
    fn set(&mut self, i: u32, x: Time) {
        self.q.set(self.times.as_mut_slice(), i, x);
    }
    fn retune(&mut self, now: f64) {
        self.q.retune(self.times.as_slice(), now);
    }
    fn peek(&mut self) -> (Time, u32) {
        self.q.peek(self.times.as_slice())
    }
    fn get(&self, i: u32) -> Time {
        t(self.times[i as usize])
    }
}

#[test]
fn ties_go_to_the_smaller_index() {
    let mut q = Q::new(5);
    q.set(3, t(1.0));
    q.set(1, t(1.0));
    q.set(4, t(1.0));
    assert_eq!(q.peek(), (t(1.0), 1));
    q.set(1, t(2.0));
    assert_eq!(q.peek(), (t(1.0), 3));
}

#[test]
fn far_future_events_come_back_from_overflow() {
    let mut q = Q::new(4);
    q.set(0, t(0.5));
    q.retune(0.0);
    q.set(1, t(1e6));
    q.set(2, t(3e3));
    q.set(0, t(f64::INFINITY));
    assert_eq!(q.peek(), (t(3e3), 2));
    q.set(2, t(f64::INFINITY));
    assert_eq!(q.peek(), (t(1e6), 1));
    q.set(1, t(f64::INFINITY));
    assert!(q.peek().0.is_infinite());
}

#[test]
fn a_time_set_back_is_found_and_stale_copies_are_dropped() {
    let mut q = Q::new(3);
    q.set(0, t(5.0));
    q.set(1, t(6.0));
    q.retune(0.0);
    // Disc 0 moves away and back: two entries with time 5 exist, both true.
    q.set(0, t(9.0));
    q.set(0, t(5.0));
    assert_eq!(q.peek(), (t(5.0), 0));
    q.set(0, t(7.0));
    // Both old entries are stale now; the next event is disc 1's.
    assert_eq!(q.peek(), (t(6.0), 1));
    q.set(1, t(f64::INFINITY));
    assert_eq!(q.peek(), (t(7.0), 0));
    q.set(0, t(f64::INFINITY));
    assert!(q.peek().0.is_infinite());
}

#[test]
fn piled_up_stale_entries_are_collected() {
    let n = 10;
    let mut q = Q::new(n);
    for i in 0..n {
        q.set(i as u32, t(100.0 + i as f64));
    }
    q.retune(0.0);
    // Many changes of far-future times leave stale entries behind; the pool
    // must stay bounded and the order exact.
    for k in 0..100_000u32 {
        let i = k % n as u32;
        q.set(i, t(50.0 + (k % 977) as f64 * 0.1 + i as f64 * 1e-3));
        assert!(q.q.chunks_used <= q.q.chunk_limit());
        assert!(q.q.overflow.len() <= q.q.overflow_limit());
    }
    let (t0, i0) = q.peek();
    let best = (0..n as u32).map(|i| (q.get(i), i)).min().unwrap();
    assert_eq!((t0, i0), best);
}

#[test]
fn a_crowded_bucket_spills_into_chunks_and_keeps_the_order() {
    // Every disc at one time: after the retune they all share one bucket, far
    // more than a slot holds. The rebuild must not loop, and the events must come
    // out in index order, each exactly once.
    let n = 1000;
    let mut q = Q::new(n);
    for i in 0..n as u32 {
        q.set(i, t(5.0));
    }
    q.retune(0.0);
    q.q.flush();
    assert!(
        q.q.chunks_used >= n / SLOT_DISCS - 1,
        "{} chunks",
        q.q.chunks_used
    );
    for i in 0..n as u32 {
        assert_eq!(q.peek(), (t(5.0), i));
        q.set(i, t(f64::INFINITY));
    }
    assert!(q.peek().0.is_infinite());
}

#[test]
fn entries_waiting_to_be_filed_are_found() {
    // Fewer sets than the pending buffer holds, then more: both must be seen.
    for k in [3usize, PENDING, 3 * PENDING + 1] {
        let n = 64;
        let mut q = Q::new(n);
        q.set(0, t(1.0));
        q.retune(0.0);
        for i in 1..=k as u32 {
            q.set(i % n as u32, t(0.5 + 0.01 * i as f64));
        }
        let best = (0..n as u32).map(|i| (q.get(i), i)).min().unwrap();
        assert_eq!(q.peek(), best, "k = {k}");
    }
}

/// Events that spread out after Δ was tuned (a cooling gas: each new interval 5 %
/// longer than the last) still come out in order, and Δ follows them: the
/// calendar is tuned anew once most events lie beyond it, so the mean time ahead
/// stays within a bounded number of bucket widths per disc (tuned: 1/2).
#[test]
fn the_bucket_width_follows_events_that_spread_out() {
    let n = 64;
    let mut q = Q::new(n);
    for i in 0..n {
        q.set(i as u32, t(1.0 + i as f64));
    }
    q.retune(0.0);
    let mut scale = 1.0;
    let mut worst: f64 = 0.0;
    for k in 0..3000 {
        let (head, i) = q.peek();
        let now = head.into_inner();
        let (min, arg) =
            q.times.iter().enumerate().fold(
                (f64::INFINITY, 0),
                |a, (j, &x)| if x < a.0 { (x, j) } else { a },
            );
        assert_eq!((now, i as usize), (min, arg), "pop {k}");
        let ahead = q.times.iter().map(|&x| x - now).sum::<f64>() / n as f64;
        worst = worst.max(ahead * q.q.inv_width / n as f64);
        scale *= 1.05;
        q.set(i, t(now + scale * (1 + (k * 7) % 13) as f64));
    }
    assert!(scale > 1e60, "the events spread out by {scale:e}");
    assert!(worst < 20.0, "mean time ahead / (N Δ) reached {worst}");
}

proptest! {
    /// Popping in a simulation-like pattern (the head moves to a later time, others
    /// change anywhere ahead of the head) always yields the (time, index) minimum.
    #[test]
    fn head_is_lexicographic_minimum(
        n in 1usize..40,
        width in 0.01f64..10.0,
        ops in proptest::collection::vec((0usize..40, 0u32..2000, any::<bool>()), 1..300),
    ) {
        let mut q = Q::new(n);
        let mut model = vec![f64::INFINITY; n];
        for (k, m) in model.iter_mut().enumerate() {
            *m = k as f64 * 0.37;
            q.set(k as u32, t(*m));
        }
        q.retune(0.0);
        let mut now = 0.0;
        for (i, dt, pop) in ops {
            let (qt, qi) = q.peek();
            let (bt, bi) = model.iter().enumerate()
                .fold((f64::INFINITY, 0usize), |acc, (k, &x)| if x < acc.0 { (x, k) } else { acc });
            prop_assert_eq!(qt.into_inner(), bt);
            if bt.is_finite() { prop_assert_eq!(qi as usize, bi); now = bt; }
            let target = if pop && bt.is_finite() { bi } else { i % n };
            let v = if dt == 1999 { f64::INFINITY } else { now + (dt / 7) as f64 * width };
            q.set(target as u32, t(v));
            model[target] = v;
        }
    }
}
