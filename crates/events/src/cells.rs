//! Neighbour search: a grid of cells at least one contact distance wide.
//!
//! Two discs can touch only if their centres lie in the same or adjacent cells, so a
//! disc predicts collisions only with the discs of its 3 × 3 block. Crossing a cell
//! wall is itself an event of the engine, which keeps every disc in the cell that
//! contains its centre. Each cell holds an intrusive doubly linked list of its discs;
//! a disc's cell and its two list links share one 16-byte record ([`Link`]), so that
//! the event loop finds them in one cache line.
//!
//! On a periodic axis the block wraps around; a neighbour reached across the box edge
//! is seen through its periodic image, shifted by ±L. Boxes narrower than three cells
//! work too: the same cell is then visited more than once, each time with a different
//! image shift, which is exactly the set of images a disc can reach.

use crate::memory;
use carom_core::{DVec2, SimBox};

/// Marker for "no disc" in the linked lists.
pub const NONE: u32 = u32::MAX;

/// A disc's place in the grid: its cell and its neighbours in that cell's list.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[repr(C, align(16))]
pub struct Link {
    /// Cell coordinates (column, row).
    pub cell: [u32; 2],
    /// Next disc in the same cell, or [`NONE`].
    pub next: u32,
    /// Previous disc in the same cell, or [`NONE`].
    pub prev: u32,
}

impl Link {
    /// Not in any list, cell (0, 0).
    pub const UNLINKED: Link = Link {
        cell: [0, 0],
        next: NONE,
        prev: NONE,
    };
}

/// The geometry and membership of the cell grid.
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
    /// First disc of each cell, or [`NONE`].
    pub head: Vec<u32>,
    /// Each disc's cell and list links.
    pub link: Vec<Link>,
}

impl CellGrid {
    /// An empty grid for `n_discs` discs in `sim_box`, with cells at least
    /// `min_width` wide (the largest contact distance, 2 a_max).
    pub fn new(sim_box: &SimBox, min_width: f64, n_discs: usize) -> Self {
        let size = sim_box.size;
        // A hair of margin so that rounding at a cell edge never hides a contact.
        let w = min_width * (1.0 + 1e-9);
        let count = |l: f64| ((l / w).floor() as u64).clamp(1, 1 << 15) as u32;
        let n = [count(size.x), count(size.y)];
        let width = DVec2::new(size.x / n[0] as f64, size.y / n[1] as f64);
        CellGrid {
            n,
            width,
            size,
            periodic: [
                sim_box.boundary[0].is_periodic(),
                sim_box.boundary[1].is_periodic(),
            ],
            head: memory::filled(n[0] as usize * n[1] as usize, NONE),
            link: memory::filled(n_discs, Link::UNLINKED),
        }
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

    /// Cell coordinates (column, row) of disc `i`.
    #[inline]
    pub fn cell_of(&self, i: usize) -> [u32; 2] {
        self.link[i].cell
    }

    /// Put disc `i` into cell `c` (at the head of its list).
    #[inline]
    pub fn insert(&mut self, i: u32, c: [u32; 2]) {
        let k = self.index(c);
        let h = self.head[k];
        self.link[i as usize] = Link {
            cell: c,
            next: h,
            prev: NONE,
        };
        if h != NONE {
            self.link[h as usize].prev = i;
        }
        self.head[k] = i;
    }

    /// Take disc `i` out of its cell.
    #[inline]
    pub fn remove(&mut self, i: u32) {
        let Link { cell, next, prev } = self.link[i as usize];
        if prev != NONE {
            self.link[prev as usize].next = next;
        } else {
            let k = self.index(cell);
            self.head[k] = next;
        }
        if next != NONE {
            self.link[next as usize].prev = prev;
        }
    }

    /// Every disc in the 3 × 3 block of cells around cell `c`: cells beyond a wall
    /// are dropped, and on a periodic axis narrower than three cells a disc may come
    /// more than once. For setup and checks that use minimum images; the event loop
    /// walks the block itself because it tracks each cell's image shift.
    pub fn discs_near(&self, c: [u32; 2]) -> impl Iterator<Item = u32> + '_ {
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
            .flat_map(move |k| {
                let mut j = self.head[k];
                std::iter::from_fn(move || {
                    let cur = j;
                    (cur != NONE).then(|| {
                        j = self.link[cur as usize].next;
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

    /// Bytes of heap memory used (for the memory report).
    pub fn heap_bytes(&self) -> usize {
        self.head.capacity() * 4 + self.link.capacity() * std::mem::size_of::<Link>()
    }
}
