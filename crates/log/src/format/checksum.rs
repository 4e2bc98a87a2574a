//! The checksum of a carom metadata record (`carom.run`, `carom.summary`; log
//! format 2.3 on). The two records sit in the MCAP data section outside the
//! chunks, so no chunk CRC covers them; each carries its own in the key
//! [`CHECKSUM_KEY`]: the CRC-32 (IEEE, as MCAP's) of the canonical encoding of
//! every other key/value pair, as 8 lowercase hexadecimal digits.
//!
//! Canonical encoding (defined once, in [`canonical_bytes`]): the pairs in
//! ascending byte order of their keys, each as `len(key) key len(value) value`,
//! lengths as u32 little-endian, strings as their UTF-8 bytes. The lengths make
//! the encoding unambiguous (no separator can be forged by a value), so one
//! flipped bit anywhere in a key or a value changes the CRC. A record without
//! the key (older logs) reads as before ([`Checksum::Absent`]).

use std::collections::BTreeMap;

/// The metadata key holding a record's checksum.
pub const CHECKSUM_KEY: &str = "crc32";

/// What a record's checksum says.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Checksum {
    /// The record has no checksum (a log older than format 2.3).
    Absent,
    /// The stored checksum matches the record.
    Holds,
    /// The stored checksum (as stored) does not match the record's pairs.
    Fails {
        /// The value stored under [`CHECKSUM_KEY`].
        stored: String,
        /// The checksum of the pairs as read.
        computed: String,
    },
}

impl Checksum {
    /// A sentence for the user when the checksum fails.
    pub fn problem(&self) -> Option<String> {
        match self {
            Checksum::Fails { stored, computed } => Some(format!(
                "checksum fails (stored {stored}, computed {computed}): the record is damaged"
            )),
            _ => None,
        }
    }
}

/// The canonical encoding of every pair but [`CHECKSUM_KEY`] (see the module doc).
pub fn canonical_bytes(map: &BTreeMap<String, String>) -> Vec<u8> {
    let mut out = Vec::new();
    // A BTreeMap<String, _> iterates in ascending byte order of its keys.
    for (k, v) in map.iter().filter(|(k, _)| k.as_str() != CHECKSUM_KEY) {
        for s in [k, v] {
            out.extend_from_slice(&(s.len() as u32).to_le_bytes());
            out.extend_from_slice(s.as_bytes());
        }
    }
    out
}

/// The checksum of `map` as stored: CRC-32 of [`canonical_bytes`], 8 lowercase
/// hexadecimal digits.
pub fn checksum_text(map: &BTreeMap<String, String>) -> String {
    format!("{:08x}", crc32fast::hash(&canonical_bytes(map)))
}

/// Put the checksum of the other pairs into `map` (replacing any stored one):
/// every writer of a `carom.run` or `carom.summary` record calls this last.
pub fn seal(map: &mut BTreeMap<String, String>) {
    let crc = checksum_text(map);
    map.insert(CHECKSUM_KEY.into(), crc);
}

/// Check `map`'s stored checksum.
pub fn verify(map: &BTreeMap<String, String>) -> Checksum {
    let Some(stored) = map.get(CHECKSUM_KEY) else {
        return Checksum::Absent;
    };
    let computed = checksum_text(map);
    if *stored == computed {
        Checksum::Holds
    } else {
        Checksum::Fails {
            stored: stored.clone(),
            computed,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn record() -> BTreeMap<String, String> {
        [
            ("kinetic_energy", "498.9999999999997"),
            ("stop_reason", "time"),
            ("sim_time", "50"),
            ("end_time", "2024-05-01T12:34:56.789Z"),
        ]
        .into_iter()
        .map(|(k, v)| (k.to_string(), v.to_string()))
        .collect()
    }

    /// Lengths then bytes, keys in order; the checksum key itself left out.
    #[test]
    fn the_canonical_encoding_is_length_prefixed_pairs_in_key_order() {
        let mut m = BTreeMap::new();
        m.insert("b".to_string(), "xy".to_string());
        m.insert("a".to_string(), String::new());
        m.insert(CHECKSUM_KEY.to_string(), "whatever".to_string());
        let expected: Vec<u8> = [
            &1u32.to_le_bytes()[..],
            b"a",
            &0u32.to_le_bytes(),
            &1u32.to_le_bytes(),
            b"b",
            &2u32.to_le_bytes(),
            b"xy",
        ]
        .concat();
        assert_eq!(canonical_bytes(&m), expected);
    }

    /// The CRC is IEEE CRC-32 (MCAP's): checked against the standard check
    /// value of "123456789", 0xcbf43926, through a one-pair record.
    #[test]
    fn the_checksum_is_the_ieee_crc32_of_the_encoding() {
        let mut m = BTreeMap::new();
        m.insert("k".to_string(), "123456789".to_string());
        let bytes = canonical_bytes(&m);
        assert_eq!(crc32fast::hash(b"123456789"), 0xcbf4_3926);
        assert_eq!(
            checksum_text(&m),
            format!("{:08x}", crc32fast::hash(&bytes))
        );
    }

    #[test]
    fn a_sealed_record_verifies_and_sealing_again_changes_nothing() {
        let mut m = record();
        assert_eq!(verify(&m), Checksum::Absent);
        seal(&mut m);
        assert_eq!(verify(&m), Checksum::Holds);
        let once = m.clone();
        seal(&mut m);
        assert_eq!(m, once);
    }

    /// Every single-bit flip of every byte of every key and value (that stays
    /// UTF-8, as a metadata string must) is caught, as is a pair moved between
    /// key and value.
    #[test]
    fn every_single_bit_flip_of_a_key_or_a_value_fails_the_checksum() {
        let mut sealed = record();
        seal(&mut sealed);
        let mut flips = 0;
        for (key, value) in record() {
            for (which, text) in [(0, &key), (1, &value)] {
                for byte in 0..text.len() {
                    for bit in 0..8 {
                        let mut b = text.clone().into_bytes();
                        b[byte] ^= 1 << bit;
                        let Ok(flipped) = String::from_utf8(b) else {
                            continue;
                        };
                        let mut m = sealed.clone();
                        if which == 0 {
                            m.remove(&key);
                            m.insert(flipped, value.clone());
                        } else {
                            m.insert(key.clone(), flipped);
                        }
                        assert!(
                            matches!(verify(&m), Checksum::Fails { .. }),
                            "{key}={value}: byte {byte} bit {bit}"
                        );
                        flips += 1;
                    }
                }
            }
        }
        assert!(flips > 500, "{flips}");
        // The flip: 498.9999999999997 → 498.9999998999997.
        let mut m = sealed.clone();
        m.insert("kinetic_energy".into(), "498.9999998999997".into());
        assert!(verify(&m).problem().unwrap().contains("checksum fails"));
        // Splitting differently ("ab" = "c" against "a" = "bc") is another record.
        let mut a = BTreeMap::from([("ab".to_string(), "c".to_string())]);
        seal(&mut a);
        let stored = a[CHECKSUM_KEY].clone();
        let mut b = BTreeMap::from([("a".to_string(), "bc".to_string())]);
        b.insert(CHECKSUM_KEY.into(), stored);
        assert!(matches!(verify(&b), Checksum::Fails { .. }));
    }
}
