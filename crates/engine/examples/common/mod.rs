//! What the profiling examples share: their numeric arguments, CPU time and a
//! fingerprint of the final state.
use carom_engine::State;

/// CPU time of this thread so far (s), from /proc/self/schedstat (Linux).
pub fn cpu_seconds() -> f64 {
    std::fs::read_to_string("/proc/thread-self/schedstat")
        .ok()
        .and_then(|s| s.split_whitespace().next()?.parse::<f64>().ok())
        .map_or(f64::NAN, |ns| ns * 1e-9)
}

/// FNV-1a over the bits of every position and velocity: equal hashes mean
/// bit-identical trajectories (for checking that a speed change left the dynamics
/// alone).
pub fn state_hash(state: &State) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for (r, v) in state.positions.iter().zip(&state.velocities) {
        for x in [r.x, r.y, v.x, v.y] {
            h = (h ^ x.to_bits()).wrapping_mul(0x0000_0100_0000_01b3);
        }
    }
    h
}

/// Command-line argument `k` read as a number, or `default` when it is missing or
/// not a number.
pub fn arg(k: usize, default: f64) -> f64 {
    std::env::args()
        .nth(k)
        .and_then(|s| s.parse().ok())
        .unwrap_or(default)
}
