//! Neighbour search: a grid of cells at least one contact distance wide.
//!
//! Two discs can touch only if their centres lie in the same or adjacent cells
//! (|r_i − r_j| = a_i + a_j ≤ cell width), so a disc predicts collisions only with
//! the discs of its 3 × 3 block. Crossing a cell wall is itself an event of the
//! engine, which keeps every disc in the cell that contains its centre. Each cell
//! holds an intrusive singly linked list of its discs; a disc's cell and list link
//! share one 8-byte [`Link`] that lives in the caller's per-disc record (a
//! [`Member`]), so walking a list reads only records a scan needs anyway. On a
//! periodic axis the block wraps around, a neighbour across the edge seen through
//! its image shifted by ±L; boxes narrower than three cells visit a cell once per
//! image. The cells are as narrow as the contact distance allows (at most
//! [`CELLS_PER_DISC`] per disc), the heads stored row by row. See
//! docs/performance.md, "cells".

use crate::memory;
use crate::NO_DISC;
use carom_core::{DVec2, SimBox};

/// A disc's place in the grid: its cell and the next disc in that cell's list.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[repr(C, align(8))]
pub struct Link {
    /// Cell coordinates (column, row); at most 2¹⁵ cells per axis.
    pub cell: [u16; 2],
    /// Next disc in the same cell, or [`NO_DISC`].
    pub next: u32,
}

impl Link {
    /// Not in any list, cell (0, 0).
    pub const UNLINKED: Link = Link {
        cell: [0, 0],
        next: NO_DISC,
    };

    /// The cell coordinates (column, row).
    #[inline]
    pub fn coords(&self) -> [u32; 2] {
        self.cell.map(u32::from)
    }
}

/// A per-disc record that carries the disc's [`Link`]: the cell lists are threaded
/// through a slice of these, indexed by disc.
pub trait Member {
    /// The disc's cell and next disc.
    fn link(&self) -> &Link;
    /// The same, for changing.
    fn link_mut(&mut self) -> &mut Link;
}

impl Member for Link {
    #[inline]
    fn link(&self) -> &Link {
        self
    }
    #[inline]
    fn link_mut(&mut self) -> &mut Link {
        self
    }
}

/// The most cells per disc a grid gets (see [`CellGrid::new`]). Cells narrower than
/// this allows (packing fraction above π/16 ≈ 0.2 for cells one diameter wide) are
/// never widened. Below that the wider cells save crossings (see
/// docs/performance.md, "cells").
pub const CELLS_PER_DISC: u64 = 4;

/// Cells per axis: `n` (each axis as many as fit), reduced in the same proportion
/// on both axes until there are at most `max` in all; an axis squeezed to one cell
/// leaves its share to the other. Never more than `n` on either axis, so cells only
/// get wider.
fn cap_cells(n: [u32; 2], max: u64) -> [u32; 2] {
    let total = n[0] as u64 * n[1] as u64;
    if total <= max {
        return n;
    }
    // y in proportion (at least one); then each as many as the other leaves room
    // for (more than its proportional share only when the other was squeezed to one).
    let f = (max as f64 / total as f64).sqrt();
    let y = ((n[1] as f64 * f).floor() as u64).max(1);
    let x = (max / y).clamp(1, n[0] as u64);
    let y = (max / x).clamp(1, n[1] as u64);
    [x as u32, y as u32]
}

/// The geometry of the cell grid and the first disc of each cell's list (the rest
/// of each list is in the discs' [`Link`]s, see [`Member`]).
#[derive(Debug, Clone)]
pub struct CellGrid {
    /// Number of cells along x and y.
    pub n: [u32; 2],
    /// Cell edge lengths (length); each ≥ the largest contact distance.
    pub width: DVec2,
    /// Box edge lengths (length).
    pub size: DVec2,
    /// Whether each axis is periodic.
    pub periodic: [bool; 2],
    /// First disc of each cell, or [`NO_DISC`].
    pub head: Vec<u32>,
}

impl CellGrid {
    /// An empty grid in `sim_box`, with cells at least `min_width` wide (the largest
    /// contact distance, 2 a_max).
    ///
    /// At most [`CELLS_PER_DISC`] cells per disc for `discs` discs: in a dilute
    /// system cells as narrow as the contact distance would number far more than the
    /// discs (10 discs in a box of 10⁵ diameters would need 2³⁰ cells, 4 GB), while
    /// wider cells cost a scan little there (few discs per cell) and save crossings.
    pub fn new(sim_box: &SimBox, min_width: f64, discs: usize) -> Self {
        let size = sim_box.size;
        let n = Self::shape(sim_box, min_width, discs);
        let width = DVec2::new(size.x / n[0] as f64, size.y / n[1] as f64);
        CellGrid {
            n,
            width,
            size,
            periodic: [
                sim_box.boundary[0].is_periodic(),
                sim_box.boundary[1].is_periodic(),
            ],
            head: memory::filled(n[0] as usize * n[1] as usize, NO_DISC),
        }
    }

    /// Cells per axis of the grid [`CellGrid::new`] builds for these arguments
    /// (without building it).
    pub fn shape(sim_box: &SimBox, min_width: f64, discs: usize) -> [u32; 2] {
        let size = sim_box.size;
        // A hair of margin so that rounding at a cell edge never hides a contact.
        let w = min_width * (1.0 + 1e-9);
        let count = |l: f64| ((l / w).floor() as u64).clamp(1, 1 << 15) as u32;
        cap_cells(
            [count(size.x), count(size.y)],
            CELLS_PER_DISC * discs.max(1) as u64,
        )
    }

    /// The cell coordinates containing position `r` (clamped into the grid).
    pub fn coords_of(&self, r: DVec2) -> [u32; 2] {
        let c = |k: usize, x: f64| -> u32 {
            let f = (x / self.width[k]).floor();
            if f < 0.0 {
                0
            } else {
                (f as u64).min(self.n[k] as u64 - 1) as u32
            }
        };
        [c(0, r.x), c(1, r.y)]
    }

    /// Linear index of cell (column, row).
    #[inline]
    pub fn index(&self, c: [u32; 2]) -> usize {
        c[1] as usize * self.n[0] as usize + c[0] as usize
    }

    /// Put disc `i` (of the records `members`) into cell `c`, at the head of its
    /// list.
    #[inline]
    pub fn insert<M: Member>(&mut self, members: &mut [M], i: u32, c: [u32; 2]) {
        // At most 2¹⁵ cells per axis (see `new`), so the coordinates fit in u16.
        debug_assert!(c[0] < self.n[0] && c[1] < self.n[1]);
        let k = self.index(c);
        *members[i as usize].link_mut() = Link {
            cell: c.map(|x| x as u16),
            next: self.head[k],
        };
        self.head[k] = i;
    }

    /// Take disc `i` out of its cell (walking the cell's list to its predecessor).
    #[inline]
    pub fn remove<M: Member>(&mut self, members: &mut [M], i: u32) {
        let Link { cell, next } = *members[i as usize].link();
        let k = self.index(cell.map(u32::from));
        if self.head[k] == i {
            self.head[k] = next;
            return;
        }
        let mut j = self.head[k] as usize;
        while members[j].link().next != i {
            j = members[j].link().next as usize;
        }
        members[j].link_mut().next = next;
    }

    /// Linear indices of the cells of the 3 × 3 block around cell `c`: cells beyond
    /// a wall are dropped, and on a periodic axis narrower than three cells a cell
    /// may come more than once.
    pub fn cells_near(&self, c: [u32; 2]) -> impl Iterator<Item = usize> + '_ {
        let cell = move |o: [i64; 2]| -> Option<usize> {
            let mut cc = [0u32; 2];
            for k in 0..2 {
                let v = c[k] as i64 + o[k];
                let nk = self.n[k] as i64;
                cc[k] = if self.periodic[k] {
                    v.rem_euclid(nk) as u32
                } else if (0..nk).contains(&v) {
                    v as u32
                } else {
                    return None;
                };
            }
            Some(self.index(cc))
        };
        (-1..=1)
            .flat_map(|oy| (-1..=1).map(move |ox| [ox, oy]))
            .filter_map(cell)
    }

    /// Every disc in the 3 × 3 block of cells around cell `c` ([`Self::cells_near`]:
    /// on a periodic axis narrower than three cells a disc may come more than once).
    /// For setup and checks that use minimum images; the event loop walks the block
    /// itself because it tracks each cell's image shift.
    pub fn discs_near<'a, M: Member>(
        &'a self,
        members: &'a [M],
        c: [u32; 2],
    ) -> impl Iterator<Item = u32> + 'a {
        self.cells_near(c).flat_map(move |k| {
            let mut j = self.head[k];
            std::iter::from_fn(move || {
                let cur = j;
                (cur != NO_DISC).then(|| {
                    j = members[cur as usize].link().next;
                    cur
                })
            })
        })
    }

    /// Time from now until a disc at coordinate `x` (its position now), moving with
    /// velocity `v`, leaves cell column/row `c` along axis `k` (time), and whether it
    /// leaves through the upper edge (v > 0). +∞ when it never does (at rest, or
    /// heading into a wall, which it hits first).
    ///
    /// Computed without a branch on the direction of motion, which is a coin toss for
    /// the branch predictor.
    #[inline]
    pub fn crossing_time(&self, k: usize, c: u32, x: f64, v: f64) -> (f64, bool) {
        let up = v > 0.0;
        let last = c + 1 == self.n[k];
        // The upper edge of the last cell is the box edge itself, exactly.
        let upper = if last {
            self.size[k]
        } else {
            (c + 1) as f64 * self.width[k]
        };
        let lower = c as f64 * self.width[k];
        let edge = std::hint::select_unpredictable(up, upper, lower);
        // Beyond the first and last cells of a walled axis there is only the wall.
        let walled = !self.periodic[k];
        let blocked = std::hint::select_unpredictable(up, last & walled, (c == 0) & walled);
        let dt = ((edge - x) / v).max(0.0);
        // At rest (or NaN) never crosses; the quotient above is then discarded.
        let moving = (v > 0.0) | (v < 0.0);
        let never = blocked | !moving;
        (
            std::hint::select_unpredictable(never, f64::INFINITY, dt),
            up,
        )
    }

    /// The previous disc in its cell's list of each disc, or [`NO_DISC`] for the first
    /// (the back links checkpoints store). The lists must pass
    /// [`CellGrid::check_lists`].
    pub fn prev_links<M: Member>(&self, members: &[M]) -> Vec<u32> {
        let mut prev = vec![NO_DISC; members.len()];
        for &h in &self.head {
            let mut j = h;
            while j != NO_DISC {
                let next = members[j as usize].link().next;
                if next != NO_DISC {
                    prev[next as usize] = j;
                }
                j = next;
            }
        }
        prev
    }

    /// Check that the lists describe a partition of the discs: every disc is listed
    /// exactly once, in the list of the cell its record names. Returns what is wrong
    /// otherwise (for checkpoints read from disk, and the tests).
    #[cfg(test)]
    pub fn check_lists<M: Member>(&self, members: &[M]) -> Result<(), String> {
        self.check_lists_of(members, |_| true)
    }

    /// [`CellGrid::check_lists`] for a grid that holds only the discs `i` for
    /// which `belongs(i)` (one size class of several, see the `classes` module):
    /// those discs are listed exactly once each, and no other disc is.
    pub fn check_lists_of<M: Member>(
        &self,
        members: &[M],
        belongs: impl Fn(usize) -> bool,
    ) -> Result<(), String> {
        let n = members.len();
        // Discs of other grids count as seen already.
        let mut seen: Vec<bool> = (0..n).map(|i| !belongs(i)).collect();
        for cy in 0..self.n[1] {
            for cx in 0..self.n[0] {
                let mut j = self.head[self.index([cx, cy])];
                while j != NO_DISC {
                    let Some(link) = members.get(j as usize).map(Member::link) else {
                        return Err(format!(
                            "cell ({cx}, {cy}) lists disc {j}, beyond {n} discs"
                        ));
                    };
                    if !belongs(j as usize) {
                        return Err(format!(
                            "cell ({cx}, {cy}) lists disc {j}, which belongs to another grid"
                        ));
                    }
                    if std::mem::replace(&mut seen[j as usize], true) {
                        return Err(format!("disc {j} is listed twice"));
                    }
                    if link.cell != [cx as u16, cy as u16] {
                        return Err(format!(
                            "disc {j} is listed in cell ({cx}, {cy}) but its record says {:?}",
                            link.cell
                        ));
                    }
                    j = link.next;
                }
            }
        }
        match seen.iter().position(|&s| !s) {
            Some(i) => Err(format!("disc {i} is in no cell's list")),
            None => Ok(()),
        }
    }

    /// Bytes of heap memory used (for the memory report).
    pub fn heap_bytes(&self) -> usize {
        self.head.capacity() * 4
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use carom_core::Boundary;
    use proptest::prelude::*;

    /// A 4 × 3 grid and the links of `n_discs` discs, in no list yet.
    fn grid(n_discs: usize) -> (CellGrid, Vec<Link>) {
        let sim_box = SimBox {
            size: DVec2::new(4.5, 3.5),
            boundary: [Boundary::Periodic, Boundary::Walls { restitution: 1.0 }],
        };
        let g = CellGrid::new(&sim_box, 1.0, 10);
        assert_eq!(g.n, [4, 3]);
        (g, vec![Link::UNLINKED; n_discs])
    }

    /// A sparse system gets at most [`CELLS_PER_DISC`] cells per disc, none narrower
    /// than the contact distance; a dense one keeps cells one contact distance wide.
    #[test]
    fn dilute_systems_get_wider_cells_not_more_of_them() {
        let square = |l: f64| SimBox {
            size: DVec2::new(l, l),
            boundary: [Boundary::Periodic; 2],
        };
        // 10 discs in a box of 10⁵ diameters: 2³⁰ cells uncapped.
        let g = CellGrid::new(&square(1e5), 1.0, 10);
        assert!(g.head.len() <= 40, "{:?}", g.n);
        assert!(g.width.min_element() >= 1.0);
        // A dense fluid (η = 0.5, 10⁴ discs of diameter 1): 125 cells of width ~1 per axis.
        let l = (1e4 * std::f64::consts::PI / 4.0 / 0.5).sqrt();
        let g = CellGrid::new(&square(l), 1.0, 10_000);
        assert_eq!(g.n, [125, 125]);
        // A long channel squeezed to one row gives the row all the cells allowed.
        let channel = SimBox {
            size: DVec2::new(1e6, 1.5),
            boundary: [Boundary::Periodic, Boundary::Walls { restitution: 1.0 }],
        };
        let g = CellGrid::new(&channel, 1.0, 100);
        assert_eq!(g.n, [400, 1]);
    }

    proptest! {
        /// Whatever the box and the number of discs: cells are at least the
        /// contact distance wide (or one spans the axis), there are at most
        /// CELLS_PER_DISC per disc, and no axis has more cells than fit.
        #[test]
        fn cell_counts_are_capped_and_wide_enough(
            ex in -0.3f64..7.0, ey in -0.3f64..7.0, discs in 1usize..100_000,
        ) {
            // Edges from half a diameter to 10⁷, uniform in the exponent (so that
            // long channels one cell wide come up as often as squares).
            let (lx, ly) = (10f64.powf(ex), 10f64.powf(ey));
            let sim_box = SimBox { size: DVec2::new(lx, ly), boundary: [Boundary::Periodic; 2] };
            let g = CellGrid::new(&sim_box, 1.0, discs);
            prop_assert!(g.width.x >= 1.0 || g.n[0] == 1);
            prop_assert!(g.width.y >= 1.0 || g.n[1] == 1);
            prop_assert!(g.head.len() as u64 <= CELLS_PER_DISC * discs as u64);
            // Each axis has at most as many cells as fit.
            prop_assert!(g.n[0] as f64 <= (lx / 1.0).floor().max(1.0));
            prop_assert!(g.n[1] as f64 <= (ly / 1.0).floor().max(1.0));
        }
    }

    /// The discs of cell `c` in list order.
    fn list(g: &CellGrid, links: &[Link], c: [u32; 2]) -> Vec<u32> {
        let mut out = vec![];
        let mut j = g.head[g.index(c)];
        while j != NO_DISC {
            out.push(j);
            j = links[j as usize].next;
        }
        out
    }

    proptest! {
        /// Random moves between cells keep every list equal to a model (a vector per
        /// cell, new discs in front, removals keeping the order of the rest), and the
        /// back links are those of the model.
        #[test]
        fn moves_keep_lists_in_model_order(moves in prop::collection::vec((0u32..10, 0u32..4, 0u32..3), 0..200)) {
            let n = 10;
            let (mut g, mut links) = grid(n);
            let mut model: Vec<Vec<u32>> = vec![vec![]; 12];
            let cell = |k: usize| [(k % 4) as u32, (k / 4) as u32];
            for i in 0..n as u32 {
                g.insert(&mut links, i, [0, 0]);
                model[0].insert(0, i);
            }
            for (i, cx, cy) in moves {
                let from = model.iter().position(|l| l.contains(&i)).unwrap();
                model[from].retain(|&d| d != i);
                g.remove(&mut links, i);
                g.insert(&mut links, i, [cx, cy]);
                model[(cy * 4 + cx) as usize].insert(0, i);
                prop_assert_eq!(g.check_lists(&links), Ok(()));
            }
            let prev = g.prev_links(&links);
            for (k, l) in model.iter().enumerate() {
                prop_assert_eq!(&list(&g, &links, cell(k)), l);
                for w in l.windows(2) {
                    prop_assert_eq!(prev[w[1] as usize], w[0]);
                }
                if let Some(&first) = l.first() {
                    prop_assert_eq!(prev[first as usize], NO_DISC);
                }
            }
        }
    }

    #[test]
    fn broken_lists_are_named() {
        let (mut g, mut links) = grid(3);
        for i in 0..3 {
            g.insert(&mut links, i, [1, 1]);
        }
        assert_eq!(g.check_lists(&links), Ok(()));
        // A cycle: the last disc points back to the first.
        let mut cyc = links.clone();
        cyc[0].next = 2;
        assert_eq!(g.check_lists(&cyc), Err("disc 2 is listed twice".into()));
        // A disc left out of every list.
        let mut lost = links.clone();
        lost[1].next = NO_DISC;
        assert_eq!(
            g.check_lists(&lost),
            Err("disc 0 is in no cell's list".into())
        );
        // A record naming another cell than the list it is in.
        let mut moved = links.clone();
        moved[1].cell = [2, 1];
        assert!(g
            .check_lists(&moved)
            .unwrap_err()
            .contains("disc 1 is listed in cell (1, 1)"));
    }
}
