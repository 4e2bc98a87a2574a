//! Which row counts the search for the best rows lattice tries. Every row count
//! from 1 to N was tried once, which took minutes at N = 10⁹; the closest distance
//! of a rows lattice is bounded above by its spacing along the rows (which grows
//! with the row count, as fewer columns are needed) and by twice its spacing
//! across them (which shrinks), so only the row counts whose bounds reach the
//! best distance already known — a band of about √N row counts near the square
//! and triangular shapes — can hold the best lattice. The bounds are computed with
//! the very expressions the lattice's quality uses (correctly rounded division is
//! monotone), so the search returns exactly the lattice the exhaustive one did:
//! the test below compares the two.

use super::Lattice;
use std::ops::RangeInclusive;

/// The frame of a rows lattice: the lengths and periodicity of the axis the rows
/// run along (u) and the one across them (v), and the largest radius.
#[derive(Debug, Clone, Copy)]
pub(super) struct Axes {
    pub lu: f64,
    pub lv: f64,
    pub pu: bool,
    pub pv: bool,
    pub a: f64,
}

impl Axes {
    /// Spacing of `cols` sites along u (∞ for one site on a walled axis).
    pub(super) fn su(&self, cols: usize) -> f64 {
        spacing(self.lu, self.pu, self.a, cols)
    }

    /// Spacing of `rows` rows along v (∞ for one row on a walled axis).
    pub(super) fn sv(&self, rows: usize) -> f64 {
        spacing(self.lv, self.pv, self.a, rows)
    }

    /// The rows lattice with `rows` rows and the fewest columns whose capacity
    /// holds `n` discs, with its capacity and closest distance.
    pub(super) fn fewest_columns(
        &self,
        n: usize,
        rows: usize,
        shifted: bool,
        transposed: bool,
    ) -> (Lattice, usize, f64) {
        let mut lat = Lattice {
            rows,
            cols: n.div_ceil(rows),
            shifted,
            transposed,
        };
        while lat.quality(self).0 < n {
            lat.cols += 1;
        }
        let (cap, d) = lat.quality(self);
        (lat, cap, d)
    }

    /// The row counts, in increasing order, that can hold the best rows lattice for
    /// `n` discs when a candidate with closest distance `known` has been seen: the
    /// others cannot reach it (see the module doc). All of 1..=n for n ≤ 64 (where
    /// the occupied subset of a lattice is also tried, which these bounds do not
    /// cover) and for frames where the bounds might not be monotone.
    pub(super) fn rows_to_search(
        &self,
        n: usize,
        shifted: bool,
        transposed: bool,
        known: Option<f64>,
    ) -> RangeInclusive<usize> {
        let monotone = [self.lu, self.lv, self.a].iter().all(|x| x.is_finite())
            && self.lu > 0.0
            && self.lv > 0.0
            && (self.pu || self.lu - 2.0 * self.a >= 0.0)
            && (self.pv || self.lv - 2.0 * self.a >= 0.0);
        if n <= 64 || !monotone {
            return 1..=n;
        }
        // A distance some candidate reaches: the one known and those of the
        // square-like and triangular-like row counts.
        let mut reached = known.unwrap_or(f64::NEG_INFINITY);
        let square = (n as f64 * self.lv / self.lu).sqrt();
        for r in [square, square * (2.0 / 3f64.sqrt()).sqrt()] {
            for rows in [r.floor() as usize, r.ceil() as usize] {
                if (1..=n).contains(&rows) {
                    reached = reached.max(self.fewest_columns(n, rows, shifted, transposed).2);
                }
            }
        }
        if !(reached > 0.0 && reached.is_finite()) {
            return 1..=n;
        }
        // The closest distance is at most the spacing along u, and the columns are
        // at least ⌈n/rows⌉: a bound that grows with the row count.
        let along = |rows: usize| self.su(n.div_ceil(rows)) >= reached;
        // ... and, for more than one row, at most twice the spacing across (the same
        // row parity two rows apart; once for plain rows): a bound that shrinks.
        let factor = if shifted { 2.0 } else { 1.0 };
        let across = |rows: usize| rows == 1 || factor * self.sv(rows) >= reached;
        let first = first_true(n, along);
        let last = first_true(n, |r| !across(r)) - 1;
        first..=last
    }
}

/// Spacing of `count` sites on an axis of length `len` (as the sites are placed:
/// `len / count` when periodic, wall to wall a radius in otherwise).
fn spacing(len: f64, periodic: bool, a: f64, count: usize) -> f64 {
    if periodic {
        len / count as f64
    } else if count == 1 {
        f64::INFINITY
    } else {
        (len - 2.0 * a) / (count - 1) as f64
    }
}

/// The least r in 1..=n with `p(r)` (n + 1 if none), for `p` false then true.
fn first_true(n: usize, p: impl Fn(usize) -> bool) -> usize {
    let (mut lo, mut hi) = (1, n + 1);
    while lo < hi {
        let mid = lo + (hi - lo) / 2;
        if p(mid) {
            hi = mid;
        } else {
            lo = mid + 1;
        }
    }
    lo
}

#[cfg(test)]
mod tests {
    use super::super::{best_lattice, best_lattice_searching, Arrangement};
    use super::{first_true, Axes};
    use carom_core::{Boundary, DVec2, SimBox};
    use std::ops::RangeInclusive;

    /// The search as it was: every row count from 1 to n.
    fn every_row_count(
        _: &Axes,
        n: usize,
        _: bool,
        _: bool,
        _: Option<f64>,
    ) -> RangeInclusive<usize> {
        1..=n
    }

    /// Boxes holding `n` discs of radius 1 at packing fraction `eta`, aspect ratio
    /// `aspect`: periodic, walled, and periodic along x only.
    fn boxes(n: usize, eta: f64, aspect: f64) -> [SimBox; 3] {
        let area = n as f64 * std::f64::consts::PI / eta;
        let lx = (area * aspect).sqrt();
        let size = DVec2::new(lx, area / lx);
        let walls = Boundary::Walls { restitution: 1.0 };
        [
            [Boundary::Periodic; 2],
            [walls; 2],
            [Boundary::Periodic, walls],
        ]
        .map(|boundary| SimBox { size, boundary })
    }

    /// Whether the bounded search picks exactly the lattice the exhaustive one did
    /// for `n` discs in the boxes of `boxes` with these indices.
    fn same_choice(n: usize, eta: f64, aspect: f64, kinds: &[usize]) {
        let all = boxes(n, eta, aspect);
        for b in kinds.iter().map(|&k| all[k]) {
            let (new, dn) = best_lattice(&b, n, 1.0);
            let (old, d_old) = best_lattice_searching(&b, n, 1.0, every_row_count);
            let show = |x: &Arrangement| format!("{x:?}");
            assert!(
                show(&new) == show(&old) && dn.to_bits() == d_old.to_bits(),
                "N = {n}, η = {eta}, aspect {aspect}, box {b:?}: {new:?} ({dn}) against the \
                 exhaustive search's {old:?} ({d_old})"
            );
        }
    }

    const SHAPES: [(f64, f64); 3] = [(0.7, 1.0), (0.5, 0.37), (0.85, 2.6)];

    /// The bounded search picks exactly the lattice the exhaustive one did (same
    /// arrangement, same closest distance to the bit), so every trajectory that
    /// starts from lattice placement is unchanged: all N ≤ 5000 in walled boxes.
    #[test]
    fn the_bounded_row_search_chooses_what_the_exhaustive_one_did_with_walls() {
        for n in 1..=5000 {
            for (eta, aspect) in SHAPES {
                same_choice(n, eta, aspect, &[1]);
            }
        }
    }

    /// As above, all N ≤ 5000 in boxes periodic along x and walled along y.
    #[test]
    fn the_bounded_row_search_chooses_what_the_exhaustive_one_did_half_periodic() {
        for n in 1..=5000 {
            for (eta, aspect) in SHAPES {
                same_choice(n, eta, aspect, &[2]);
            }
        }
    }

    /// As above in periodic boxes, for a sample of N ≤ 5000 (their sheared search,
    /// the same in both, is slow for small N).
    #[test]
    fn the_bounded_row_search_chooses_what_the_exhaustive_one_did_periodic() {
        for n in (1..=5000).filter(|n| n % 37 == 0 || n % 5 == 0 && *n > 500 || *n < 40) {
            for (eta, aspect) in SHAPES {
                same_choice(n, eta, aspect, &[0]);
            }
        }
    }

    /// As above for a sample of N from 5000 to 10⁶, in all three kinds of box.
    #[test]
    fn the_bounded_row_search_chooses_what_the_exhaustive_one_did_up_to_a_million() {
        let mut n = 5000.0f64;
        while n < 1e6 {
            n *= 1.3;
            for (eta, aspect) in [(0.6, 1.0), (0.8, 0.5), (0.3, 3.1)] {
                same_choice(n as usize, eta, aspect, &[0, 1, 2]);
            }
        }
    }

    /// A million discs: the bounded search tries a few thousand row counts, not
    /// four million.
    #[test]
    fn the_row_search_of_a_large_n_is_a_narrow_band() {
        for b in boxes(1_000_000, 0.7, 1.0) {
            let axes = Axes {
                lu: b.size.x,
                lv: b.size.y,
                pu: b.boundary[0].is_periodic(),
                pv: b.boundary[1].is_periodic(),
                a: 1.0,
            };
            for shifted in [false, true] {
                let r = axes.rows_to_search(1_000_000, shifted, false, None);
                assert!(r.clone().count() < 3000 && *r.start() > 500, "{r:?}");
            }
        }
    }

    #[test]
    fn first_true_finds_the_boundary() {
        assert_eq!(first_true(10, |r| r >= 4), 4);
        assert_eq!(first_true(10, |_| true), 1);
        assert_eq!(first_true(10, |_| false), 11);
    }
}
