//! Time origins for the displacement statistics (physics.md §13): which earlier
//! snapshot is paired with which later one, in fixed memory whatever the log's
//! length. Origins are block-start snapshots (t₀ + b T) after the equilibration
//! time. Level 0 keeps the last p of them and pairs each with every later
//! snapshot, block start or in-block, at block separation m < p. Level ℓ ≥ 1
//! keeps the last p origins whose block index is a multiple of 2^ℓ and pairs
//! them only with later block starts at m = 2^ℓ q, q = p/2 … p − 1: the lags grow
//! geometrically up to the run's length with about p(1 + ℓ_max/2) origins stored.
//! A pairing is named by its [`LagKey`] (ℓ, m, j), j the later snapshot's index
//! in its block. The stored origins (N × 32 bytes each) are capped at
//! [`MAX_DISC_ORIGINS`] disc-origins by lowering p, then the number of levels.

use std::collections::{BTreeMap, VecDeque};

/// Origins kept per level when memory allows (p; even).
pub const ORIGINS_PER_LEVEL: usize = 16;
/// Most disc-origins stored (N × stored origins; 32 bytes each: 256 MiB).
pub const MAX_DISC_ORIGINS: usize = 8_000_000;
/// Most levels (lags up to 2^23 p blocks).
const MAX_LEVELS: usize = 24;

/// Which pairing: level ℓ, block separation m, index j of the later snapshot in
/// its block (0 at a block start).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct LagKey {
    /// Level ℓ.
    pub level: u32,
    /// Block separation m.
    pub m: u64,
    /// Index of the later snapshot within its block.
    pub j: u32,
}

/// One stored origin: its time, block, time segment and every disc's unwrapped
/// position and velocity.
#[derive(Debug, Clone, PartialEq)]
pub struct Origin {
    /// Time t₀ (time).
    pub time: f64,
    /// Block index b.
    pub block: u64,
    /// Time segment of the run the origin falls in.
    pub segment: usize,
    /// Unwrapped x of every disc (length).
    pub ux: Vec<f64>,
    /// Unwrapped y (length).
    pub uy: Vec<f64>,
    /// Velocity x (length/time).
    pub vx: Vec<f64>,
    /// Velocity y (length/time).
    pub vy: Vec<f64>,
}

/// How many origins per level and how many levels, for N discs and a run of
/// `blocks` blocks (None: unknown), within [`MAX_DISC_ORIGINS`]. Returns (p,
/// levels, whether the cap lowered them). Level ℓ ≥ 1 starts at lag 2^(ℓ−1) p, so
/// it is needed while that is below the run's blocks. At most p × levels origins
/// are stored (each level holds ≤ p). At p = 4 on one level the cap is not
/// lowered further (N above 2·10⁶ discs then exceeds it).
pub fn plan(n: usize, blocks: Option<u64>) -> (usize, usize, bool) {
    let levels_for = |p: usize| -> usize {
        match blocks {
            None => MAX_LEVELS,
            Some(nb) => {
                1 + (1..MAX_LEVELS)
                    .take_while(|&l| (1u64 << (l - 1)) * (p as u64) < nb)
                    .count()
            }
        }
    };
    let (mut p, mut levels) = (ORIGINS_PER_LEVEL, levels_for(ORIGINS_PER_LEVEL));
    let mut capped = false;
    while n.saturating_mul(p * levels) > MAX_DISC_ORIGINS {
        capped = true;
        if p > 4 {
            p /= 2;
            levels = levels_for(p);
        } else if levels > 1 {
            levels -= 1;
        } else {
            break;
        }
    }
    (p, levels, capped)
}

/// The stored origins and where the stream of snapshots is.
#[derive(Debug, Clone)]
pub struct OriginStore {
    p: usize,
    /// Block indices held by each level, oldest first.
    levels: Vec<VecDeque<u64>>,
    origins: BTreeMap<u64, Origin>,
    /// The current block and the index of the last snapshot in it.
    at: Option<(u64, u32)>,
    /// Block starts seen (the block index when the interval is unknown).
    starts: u64,
}

impl OriginStore {
    /// A store of `p` origins per level (even, ≥ 2) on `levels` levels (≥ 1).
    pub fn new(p: usize, levels: usize) -> Self {
        OriginStore {
            p: p.max(2) & !1,
            levels: vec![VecDeque::new(); levels.max(1)],
            origins: BTreeMap::new(),
            at: None,
            starts: 0,
        }
    }

    /// Origins per level.
    pub fn per_level(&self) -> usize {
        self.p
    }

    /// Number of levels.
    pub fn level_count(&self) -> usize {
        self.levels.len()
    }

    /// Origins stored now (each once, however many levels hold it).
    pub fn stored(&self) -> usize {
        self.origins.len()
    }

    /// Place the next snapshot, at `t`, a block start when `start`
    /// ([`super::Analyzer::block_start`]): its block and index in the block. With
    /// the interval T the block is ⌊(t − t_start)/T + 10⁻⁹⌋; without, every
    /// snapshot is the next block. `None` for an in-block snapshot before any
    /// block start.
    pub fn locate(
        &mut self,
        t: f64,
        start: bool,
        t_start: f64,
        interval: Option<f64>,
    ) -> Option<(u64, u32)> {
        let start = start || interval.is_none();
        let block = match interval.filter(|i| i.is_finite() && *i > 0.0) {
            Some(i) => ((t - t_start) / i + 1e-9).floor().max(0.0) as u64,
            None => self.starts,
        };
        if start {
            self.starts += 1;
            self.at = Some((block, 0));
        } else {
            match &mut self.at {
                Some((b, j)) if *b == block => *j += 1,
                _ => return None,
            }
        }
        self.at
    }

    /// Keep `o` (a block start) as an origin on every level whose spacing
    /// divides its block, dropping the oldest beyond p.
    pub fn store(&mut self, o: Origin) {
        let b = o.block;
        let p = self.p;
        let mut dropped = Vec::new();
        for (l, q) in self.levels.iter_mut().enumerate() {
            if b.is_multiple_of(1u64 << l) {
                q.push_back(b);
                if q.len() > p {
                    dropped.extend(q.pop_front());
                }
            }
        }
        self.origins.insert(b, o);
        for d in dropped {
            if !self.levels.iter().any(|q| q.contains(&d)) {
                self.origins.remove(&d);
            }
        }
    }

    /// The origins paired with a snapshot at (`block`, `j`), with their keys:
    /// level 0 every origin at m = block − b < p; when j = 0 also level ℓ ≥ 1 at
    /// m = 2^ℓ q, q = p/2 … p − 1. An origin at the same block start pairs with
    /// it at lag 0 (key (0, 0, 0)).
    pub fn pairings(&self, block: u64, j: u32) -> Vec<(LagKey, &Origin)> {
        let p = self.p as u64;
        let mut out = Vec::new();
        for (l, q) in self.levels.iter().enumerate() {
            if l > 0 && j != 0 {
                break;
            }
            for &b in q {
                let Some(m) = block.checked_sub(b) else {
                    continue;
                };
                let ok = if l == 0 {
                    m < p
                } else {
                    let step = 1u64 << l;
                    m.is_multiple_of(step) && (p / 2..p).contains(&(m / step))
                };
                if ok {
                    let key = LagKey {
                        level: l as u32,
                        m,
                        j,
                    };
                    out.push((key, &self.origins[&b]));
                }
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn origin(t: f64, block: u64) -> Origin {
        Origin {
            time: t,
            block,
            segment: 0,
            ux: vec![],
            uy: vec![],
            vx: vec![],
            vy: vec![],
        }
    }

    /// p = 4, 3 levels, T = 1 from 0; snapshots at every block start 0 … 12 and
    /// in-block ones at b + 0.25 and b + 0.5. Expected by hand:
    /// - at 5.5 (block 5, j = 2): level 0 only, origins 2, 3, 4, 5 (m = 3 … 0);
    /// - at 8 (block 8, j = 0): level 0 m = 0 … 3 (origins 8, 7, 6, 5); level 1
    ///   (even blocks, q ∈ {2, 3}, m ∈ {4, 6}): origins 4 and 2; level 2 (multiples
    ///   of 4, q ∈ {2, 3}, m ∈ {8, 12}): origin 0 (m = 8);
    /// - at 12: level 2 m = 12 needs origin 0, which level 2 still holds (0, 4, 8,
    ///   12), and m = 8: origin 4; level 1 holds 6, 8, 10, 12: m = 6 (origin 6)
    ///   and m = 4 (origin 8).
    #[test]
    fn pairings_by_hand() {
        let mut s = OriginStore::new(4, 3);
        let at = |s: &mut OriginStore, t: f64| {
            let start = t.fract() == 0.0;
            let (b, j) = s.locate(t, start, 0.0, Some(1.0)).unwrap();
            if j == 0 {
                s.store(origin(t, b));
            }
            let mut got: Vec<(u32, u64, u32, u64)> = s
                .pairings(b, j)
                .iter()
                .map(|(k, o)| (k.level, k.m, k.j, o.block))
                .collect();
            got.sort();
            got
        };
        let mut seen = BTreeMap::new();
        for b in 0..=12u64 {
            for (dt, j) in [(0.0, 0u32), (0.25, 1), (0.5, 2)] {
                seen.insert((b, j), at(&mut s, b as f64 + dt));
            }
        }
        assert_eq!(
            seen[&(5, 2)],
            vec![(0, 0, 2, 5), (0, 1, 2, 4), (0, 2, 2, 3), (0, 3, 2, 2)]
        );
        assert_eq!(
            seen[&(8, 0)],
            vec![
                (0, 0, 0, 8),
                (0, 1, 0, 7),
                (0, 2, 0, 6),
                (0, 3, 0, 5),
                (1, 4, 0, 4),
                (1, 6, 0, 2),
                (2, 8, 0, 0)
            ]
        );
        assert_eq!(
            seen[&(12, 0)],
            vec![
                (0, 0, 0, 12),
                (0, 1, 0, 11),
                (0, 2, 0, 10),
                (0, 3, 0, 9),
                (1, 4, 0, 8),
                (1, 6, 0, 6),
                (2, 8, 0, 4),
                (2, 12, 0, 0)
            ]
        );
        // Block 1 is too early for level 1 (m = 4 from block 5 needs q ≥ 2):
        // at block 5 level 1 pairs nothing (5 is odd), level 2 nothing.
        assert!(seen[&(5, 0)].iter().all(|k| k.0 == 0));
        // Stored: level 0 holds 9–12, level 1 6, 8, 10, 12, level 2 0, 4, 8, 12:
        // distinct 0, 4, 6, 8, 9, 10, 11, 12.
        assert_eq!(s.stored(), 8);
    }

    /// An in-block snapshot before any block start pairs with nothing; blocks are
    /// whole intervals from the start; without an interval every snapshot is a
    /// block of its own.
    #[test]
    fn snapshots_are_located_in_their_blocks() {
        let mut s = OriginStore::new(4, 1);
        let t = Some(1.0);
        assert_eq!(s.locate(0.3, false, 0.0, t), None);
        assert_eq!(s.locate(1.0, true, 0.0, t), Some((1, 0)));
        assert_eq!(s.locate(1.3, false, 0.0, t), Some((1, 1)));
        assert_eq!(s.locate(1.6, false, 0.0, t), Some((1, 2)));
        assert_eq!(s.locate(3.0, true, 0.0, t), Some((3, 0)));
        // A block start a rounding below its time is still its block.
        assert_eq!(s.locate(4.0 - 1e-12, true, 0.0, t), Some((4, 0)));
        let mut s = OriginStore::new(4, 1);
        assert_eq!(s.locate(0.3, false, 0.0, None), Some((0, 0)));
        assert_eq!(s.locate(0.7, false, 0.0, None), Some((1, 0)));
    }

    /// 16 per level: 2000 blocks need levels with 2^(ℓ−1)·16 < 2000, ℓ = 1 … 7,
    /// so 8 levels; N = 10⁴ stores ≤ 16·8·10⁴ = 1.28·10⁶ (no cap). N = 10⁵:
    /// 1.28·10⁷ > 8·10⁶, p = 8 needs ℓ with 2^(ℓ−1)·8 < 2000, ℓ ≤ 8: 9 levels,
    /// 8·9·10⁵ = 7.2·10⁶ fits.
    #[test]
    fn the_plan_fits_the_memory_cap() {
        assert_eq!(plan(10_000, Some(2000)), (16, 8, false));
        assert_eq!(plan(100_000, Some(2000)), (8, 9, true));
        assert_eq!(plan(10, Some(10)), (16, 1, false));
        let (p, l, capped) = plan(10_000_000, None);
        assert!(capped && p * l * 10_000_000 >= MAX_DISC_ORIGINS && (p, l) == (4, 1));
    }
}
