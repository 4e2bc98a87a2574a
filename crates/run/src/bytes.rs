//! Sizes of files and disks in words: decimal prefixes (1 kB = 1000 B), two
//! decimals, as `42.41 MB` or `18.45 EB`; below 1000 bytes the count itself.

use std::fmt;

/// A byte count, shown with a decimal prefix (see the module documentation).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Bytes(pub u64);

impl fmt::Display for Bytes {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        const PREFIXES: [&str; 6] = ["k", "M", "G", "T", "P", "E"];
        if self.0 < 1000 {
            return write!(f, "{} B", self.0);
        }
        let mut value = self.0 as f64 / 1000.0;
        let mut k = 0;
        while value >= 1000.0 && k + 1 < PREFIXES.len() {
            value /= 1000.0;
            k += 1;
        }
        write!(f, "{value:.2} {}B", PREFIXES[k])
    }
}

#[cfg(test)]
mod tests {
    use super::Bytes;

    #[test]
    fn sizes_read_with_decimal_prefixes() {
        let shown: Vec<String> = [
            0,
            999,
            1000,
            266_640,
            42_410_000,
            3_610_000_000_000,
            u64::MAX,
        ]
        .map(|n| Bytes(n).to_string())
        .into();
        assert_eq!(
            shown,
            [
                "0 B",
                "999 B",
                "1.00 kB",
                "266.64 kB",
                "42.41 MB",
                "3.61 TB",
                "18.45 EB"
            ]
        );
    }
}
