//! The one slot between the run and the sender thread: the run puts the newest
//! state in it and goes on at once (a frame not yet taken is replaced, not
//! queued: a slow sender loses frames, never slows the run); the sender thread
//! takes it, builds and sends the frame, and hands the state's arrays back for the
//! next frame, so that a frame costs the run one pass over the discs and no
//! allocation. The lock is held only to swap states, never while one is filled
//! or sent.

use std::sync::{Arc, Condvar, Mutex, MutexGuard};
use std::thread::JoinHandle;

use carom_engine::State;

/// What the run and the sender thread share.
#[derive(Default)]
struct Slot {
    /// The newest state, not yet taken by the sender.
    ready: Option<State>,
    /// Arrays to fill the next state into.
    spare: Option<State>,
    /// No more states will come: send the one ready, then end.
    closed: bool,
}

/// The slot and the sender thread.
pub(crate) struct Handoff {
    shared: Arc<(Mutex<Slot>, Condvar)>,
    thread: Option<JoinHandle<()>>,
}

/// The slot, locked (a sender that panicked leaves it usable).
fn lock(m: &Mutex<Slot>) -> MutexGuard<'_, Slot> {
    m.lock().unwrap_or_else(|e| e.into_inner())
}

impl Handoff {
    /// Start the sender thread, which calls `send` with each state it takes.
    pub(crate) fn new(mut send: impl FnMut(&State) + Send + 'static) -> Self {
        let shared = Arc::new((Mutex::new(Slot::default()), Condvar::new()));
        let theirs = Arc::clone(&shared);
        let thread = std::thread::Builder::new()
            .name("carom-live".into())
            .spawn(move || {
                let (m, wake) = &*theirs;
                loop {
                    let state = {
                        let mut slot = lock(m);
                        while slot.ready.is_none() && !slot.closed {
                            slot = wake.wait(slot).unwrap_or_else(|e| e.into_inner());
                        }
                        match slot.ready.take() {
                            Some(s) => s,
                            None => return,
                        }
                    };
                    send(&state);
                    lock(m).spare.get_or_insert(state);
                }
            })
            .expect("a thread for the live frames");
        Handoff {
            shared,
            thread: Some(thread),
        }
    }

    /// Put a new state in the slot: `fill` writes it into the spare arrays it is
    /// given (`None` the first time). A state still in the slot is dropped.
    pub(crate) fn give(&self, fill: impl FnOnce(Option<State>) -> State) {
        let (m, wake) = &*self.shared;
        let spare = lock(m).spare.take();
        let state = fill(spare);
        let mut slot = lock(m);
        if let Some(old) = slot.ready.replace(state) {
            slot.spare.get_or_insert(old);
        }
        drop(slot);
        wake.notify_one();
    }

    /// Send the state in the slot, if any, and end the sender thread.
    pub(crate) fn close(&mut self) {
        let (m, wake) = &*self.shared;
        lock(m).closed = true;
        wake.notify_one();
        if let Some(t) = self.thread.take() {
            let _ = t.join();
        }
    }
}

impl Drop for Handoff {
    fn drop(&mut self) {
        self.close();
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::mpsc;

    fn at(t: f64) -> impl FnOnce(Option<State>) -> State {
        move |spare| {
            let mut s = spare.unwrap_or_else(|| State {
                sim_box: carom_core::SimBox::periodic(1.0, 1.0),
                species: Vec::new(),
                species_of: Vec::new(),
                positions: Vec::new(),
                velocities: Vec::new(),
                images: Vec::new(),
                time: 0.0,
            });
            s.time = t;
            s
        }
    }

    /// A sender held up takes only the newest state once it is free; the states
    /// given meanwhile never wait, and the last one is sent at the close.
    #[test]
    fn a_slow_sender_loses_states_and_never_holds_up_the_giver() {
        let (go_tx, go_rx) = mpsc::channel::<()>();
        let (sent_tx, sent_rx) = mpsc::channel::<f64>();
        let mut h = Handoff::new(move |s| {
            go_rx.recv().ok();
            sent_tx.send(s.time).unwrap();
        });
        h.give(at(1.0));
        // Wait until the sender holds state 1 (the slot is empty again).
        while lock(&h.shared.0).ready.is_some() {
            std::thread::yield_now();
        }
        for t in 2..=50 {
            h.give(at(t as f64));
        }
        go_tx.send(()).unwrap();
        go_tx.send(()).unwrap();
        h.close();
        let sent: Vec<f64> = sent_rx.try_iter().collect();
        assert_eq!(sent, [1.0, 50.0]);
    }
}
