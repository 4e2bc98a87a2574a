//! Neighbour lists: for each disc, the discs whose list centres lie near its own.
//!
//! Each disc i has a list centre c_i, its position at its last list update, and
//! a skin s: until it has moved s from c_i it is not updated again. Disc j is in
//! i's list iff |c_j + image·L − c_i| < R = σ_max + 2s + δ (physics.md (2.8)),
//! decided from both current centres, so the lists are symmetric and a function
//! of the centres alone. Two discs not listed are more than σ_max + δ apart as
//! long as neither has left its skin, so they cannot touch before one of them
//! is updated. Each list is one 64-byte line (its centre and at most
//! [`CAPACITY`] members, each a disc index with its periodic image in the top
//! four bits), kept sorted by index so that a list rebuilt from the centres is
//! the same list. See docs/performance.md, "neighbour lists".

use crate::memory;
use carom_core::DVec2;

/// How the engine finds the discs a disc may meet next.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Neighbours {
    /// Neighbour lists where they pay (dense equal discs in a straight flight:
    /// see [`crate::Engine::neighbour_lists`]), cells elsewhere.
    #[default]
    Auto,
    /// The cell grid: a disc tests the discs of its 3 × 3 block of cells, and
    /// crossing a cell edge is an event.
    Cells,
    /// Neighbour lists with a skin; refused where the engine cannot use them
    /// (fields, growth, a mixture that needs a grid per size class, a periodic
    /// box fewer than three list cells wide).
    Lists,
}

impl Neighbours {
    /// The name a configuration uses: `"auto"`, `"cells"` or `"lists"`.
    pub fn name(self) -> &'static str {
        match self {
            Neighbours::Auto => "auto",
            Neighbours::Cells => "cells",
            Neighbours::Lists => "lists",
        }
    }

    /// The setting named `name` ([`Neighbours::name`]).
    pub fn from_name(name: &str) -> Option<Neighbours> {
        [Neighbours::Auto, Neighbours::Cells, Neighbours::Lists]
            .into_iter()
            .find(|n| n.name() == name)
    }
}

/// The packing fraction from which [`Neighbours::Auto`] chooses lists: where
/// the two paths' instructions per collision cross (η ≈ 0.665 at N = 10⁴;
/// docs/performance.md, "neighbour lists").
pub const LISTS_FROM_PACKING: f64 = 0.66;

/// The most members a list holds. A list that would hold more sends the engine
/// back to the cell path for the rest of the run (deterministically).
pub(crate) const CAPACITY: usize = 11;

/// The bits of a member that hold the disc index.
const INDEX: u32 = (1 << 28) - 1;

/// The most discs the lists can number (indices below 2²⁸).
pub(crate) const MAX_DISCS: usize = INDEX as usize;

/// One disc's list: its centre and its members, in one cache line.
#[derive(Debug, Clone, Copy, PartialEq)]
#[repr(C, align(64))]
pub(crate) struct Line {
    /// The list centre: the disc's position (in the box) at its last update.
    pub(crate) centre: DVec2,
    /// Number of members.
    len: u32,
    /// Members, sorted by disc index: index | image code << 28.
    members: [u32; CAPACITY],
}

const _: () = assert!(std::mem::size_of::<Line>() == 64);

impl Line {
    /// An empty list centred at `centre`.
    pub(crate) fn empty(centre: DVec2) -> Line {
        Line {
            centre,
            len: 0,
            members: [0; CAPACITY],
        }
    }

    /// The members as (disc index, image code); the image code is
    /// `(sx + 1) + 3 (sy + 1)`, j seen at r_j + (sx L_x, sy L_y).
    #[inline(always)]
    pub(crate) fn members(&self) -> impl Iterator<Item = (u32, u8)> + '_ {
        self.members[..self.len as usize]
            .iter()
            .map(|&m| (m & INDEX, (m >> 28) as u8))
    }

    /// Number of members.
    #[cfg(test)]
    pub(crate) fn len(&self) -> usize {
        self.len as usize
    }

    /// Add disc `j` seen through image `code`, keeping the order; `false` (and
    /// the list unchanged) when the list is full.
    #[inline]
    pub(crate) fn insert(&mut self, j: u32, code: u8) -> bool {
        let n = self.len as usize;
        if n == CAPACITY {
            return false;
        }
        let at = self.members[..n].partition_point(|&m| m & INDEX < j);
        self.members.copy_within(at..n, at + 1);
        self.members[at] = j | (code as u32) << 28;
        self.len += 1;
        true
    }

    /// Take disc `j` out (it must be a member).
    #[inline]
    pub(crate) fn remove(&mut self, j: u32) {
        let n = self.len as usize;
        let at = self.members[..n].partition_point(|&m| m & INDEX < j);
        debug_assert!(at < n && self.members[at] & INDEX == j, "{j} not listed");
        self.members.copy_within(at + 1..n, at);
        self.len -= 1;
    }

    /// Renumber the members by `new_index` (old index → new) and sort again.
    pub(crate) fn renumber(&mut self, new_index: &[u32]) {
        let n = self.len as usize;
        for m in &mut self.members[..n] {
            *m = new_index[(*m & INDEX) as usize] | (*m & !INDEX);
        }
        self.members[..n].sort_unstable_by_key(|&m| m & INDEX);
    }
}

/// The image code of i seen from j, for j seen from i through `code`.
#[inline(always)]
pub(crate) fn mirror(code: u8) -> u8 {
    8 - code
}

/// Every disc's list, with the skin and the list radius.
#[derive(Debug, Clone)]
pub(crate) struct Lists {
    /// One line per disc, in the engine's internal order.
    pub(crate) lines: Vec<Line>,
    /// The skin s (length): a disc is updated when it has moved s from its centre.
    pub(crate) skin: f64,
    /// The list radius R = σ_max + 2 s + δ (length).
    pub(crate) radius: f64,
    /// The periodic shift of each image code (length), (sx L_x, sy L_y).
    pub(crate) shifts: [DVec2; 9],
}

impl Lists {
    /// Empty lists for `n` discs of largest contact distance `sigma` with skin
    /// `skin` in a box of edges `size`, every centre at `centres[i]`.
    pub(crate) fn new(centres: &[DVec2], sigma: f64, skin: f64, size: DVec2) -> Lists {
        let shifts = std::array::from_fn(|code| {
            let (sx, sy) = ((code % 3) as f64 - 1.0, (code / 3) as f64 - 1.0);
            DVec2::new(sx * size.x, sy * size.y)
        });
        Lists {
            lines: memory::collect(centres.len(), centres.iter().map(|&c| Line::empty(c))),
            skin,
            radius: list_radius(sigma, skin),
            shifts,
        }
    }

    /// Heap bytes held.
    pub(crate) fn heap_bytes(&self) -> usize {
        self.lines.capacity() * std::mem::size_of::<Line>()
    }
}

/// The skin of discs of largest contact distance `sigma` (length): 0.35 σ, a
/// list radius of 1.7 σ. Larger skins need fewer updates but hold more members:
/// 0.35 σ gave the fewest instructions per collision at η = 0.7–0.72 of the skins
/// whose lists never overflowed up to η = 0.85 (docs/performance.md, "neighbour
/// lists").
pub(crate) fn skin_for(sigma: f64) -> f64 {
    0.35 * sigma
}

/// The list radius R = σ + 2 s + δ for contact distance `sigma` and skin `skin`;
/// δ = 2⁻²⁰ σ covers the rounding of positions and exit times many times over.
pub(crate) fn list_radius(sigma: f64, skin: f64) -> f64 {
    sigma + 2.0 * skin + sigma * (1.0 / (1u64 << 20) as f64)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_line_keeps_its_members_sorted_and_refuses_a_twelfth() {
        let mut l = Line::empty(DVec2::ZERO);
        for (j, code) in [(7u32, 4u8), (3, 0), (11, 8), (5, 4)] {
            assert!(l.insert(j, code));
        }
        assert_eq!(
            l.members().collect::<Vec<_>>(),
            vec![(3, 0), (5, 4), (7, 4), (11, 8)]
        );
        l.remove(5);
        assert_eq!(l.members().map(|m| m.0).collect::<Vec<_>>(), vec![3, 7, 11]);
        for j in 20..28 {
            assert!(l.insert(j, 4));
        }
        assert_eq!(l.len(), CAPACITY);
        assert!(!l.insert(1, 4));
        assert_eq!(l.len(), CAPACITY);
        l.renumber(&(0..30).rev().collect::<Vec<u32>>());
        let idx: Vec<u32> = l.members().map(|m| m.0).collect();
        assert!(idx.windows(2).all(|w| w[0] < w[1]), "{idx:?}");
        let code = |j| l.members().find(|m| m.0 == j).unwrap().1;
        assert_eq!(
            (code(26), code(18)),
            (0, 8),
            "3 → 26 and 11 → 18 keep their codes"
        );
    }

    #[test]
    fn mirrored_images_shift_the_other_way() {
        let lists = Lists::new(&[], 1.0, 0.3, DVec2::new(10.0, 20.0));
        for code in 0..9u8 {
            assert_eq!(
                lists.shifts[code as usize],
                -lists.shifts[mirror(code) as usize]
            );
        }
        assert_eq!(lists.shifts[4], DVec2::ZERO);
    }
}
