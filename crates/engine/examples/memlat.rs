//! Memory probe: `cargo run --release -p carom-engine --example memlat`.
//!
//! Measures the latency of dependent random loads (a pointer chase over one random
//! cycle through every cache line of a buffer) for buffers from 1 MB to 256 MB. A
//! jump in latency marks the capacity of the cache this process really gets; it
//! tells at which N the engine's state (about 155 bytes per disc) stops fitting and
//! every event waits for main memory. Not part of the engine; a tool for reading
//! its speed on a given machine. (The buffer has ordinary pages, so beyond the TLB's
//! reach each load also walks the page table: a few tens of ns, against the
//! hundred or so that a jump from cache to main memory adds.)

use std::time::Instant;

/// Bytes in a cache line.
const LINE: usize = 64;

fn main() {
    let loads = 20_000_000;
    println!("buffer (MB)  ns per dependent random load");
    for mb in [1, 2, 3, 4, 5, 6, 7, 8, 16, 32, 64, 128, 256] {
        let lines = mb * 1_000_000 / LINE;
        let ns = chase(lines, loads);
        println!("{mb:>11}  {ns:>6.1}");
    }
}

/// Mean time (ns) of one load when following a random cycle through `lines` cache
/// lines, `loads` times.
fn chase(lines: usize, loads: usize) -> f64 {
    // One u64 per line is used: the index of the next line of the cycle.
    let words = LINE / 8;
    let mut buf = vec![0u64; lines * words];
    // A random cyclic order (Sattolo's shuffle) from a fixed xorshift seed.
    let mut order: Vec<usize> = (0..lines).collect();
    let mut x: u64 = 0x9e37_79b9_7f4a_7c15;
    for i in (1..lines).rev() {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        let j = (x % i as u64) as usize;
        order.swap(i, j);
    }
    for k in 0..lines {
        buf[order[k] * words] = (order[(k + 1) % lines] * words) as u64;
    }
    let mut at = order[0] * words;
    let start = Instant::now();
    for _ in 0..loads {
        at = buf[at] as usize;
    }
    let ns = start.elapsed().as_secs_f64() * 1e9 / loads as f64;
    std::hint::black_box(at);
    ns
}
