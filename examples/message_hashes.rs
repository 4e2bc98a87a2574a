//! Hash every message of a carom log, channel by channel: a fingerprint of a
//! trajectory for checking that a change of the code leaves runs bit-identical
//! (`scripts/identity.sh` runs it on ten logs). Prints one line per channel:
//! topic, message count, and a 64-bit FNV-1a hash over each message's sequence
//! number, log time and bytes, in file order.
//!
//! ```sh
//! cargo run --release --example message_hashes -- run.mcap
//! ```

use carom_log::{LogReader, TOPICS};

fn main() {
    let path = std::env::args()
        .nth(1)
        .expect("usage: message_hashes LOG.mcap");
    let mut log = LogReader::open(path.as_ref()).unwrap_or_else(|e| panic!("{e}"));
    let mut hashes = vec![(0u64, 0xcbf2_9ce4_8422_2325u64); TOPICS.len()];
    let mix = |h: &mut u64, bytes: &[u8]| {
        for &b in bytes {
            *h = (*h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3);
        }
    };
    while let Some(m) = log.next_raw().unwrap_or_else(|e| panic!("{e}")) {
        let (count, h) = &mut hashes[m.channel];
        *count += 1;
        mix(h, &m.sequence.to_le_bytes());
        mix(h, &m.log_time.to_le_bytes());
        mix(h, m.data);
    }
    for (topic, (count, h)) in TOPICS.iter().zip(hashes) {
        println!("{topic} {count} {h:016x}");
    }
}
