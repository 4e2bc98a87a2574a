//! Neighbour search: a grid of cells at least one contact distance wide.
//!
//! Two discs can touch only if their centres lie in the same or adjacent cells, so a
//! disc predicts collisions only with the discs of its 3 × 3 block. Crossing a cell
//! wall is itself an event of the engine, which keeps every disc in the cell that
//! contains its centre. Each cell holds an intrusive doubly linked list of its discs.
//!
//! On a periodic axis the block wraps around; a neighbour reached across the box edge
//! is seen through its periodic image, shifted by ±L. Boxes narrower than three cells
//! work too: the same cell is then visited more than once, each time with a different
//! image shift, which is exactly the set of images a disc can reach.

use crate::memory;
use carom_core::{DVec2, SimBox};

/// Marker for "no disc" in the linked lists.
pub const NONE: u32 = u32::MAX;

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
    /// Next disc in the same cell, or [`NONE`].
    pub next: Vec<u32>,
    /// Previous disc in the same cell, or [`NONE`].
    pub prev: Vec<u32>,
    /// Cell coordinates (column, row) of each disc.
    pub cell: Vec<[u32; 2]>,
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
            next: memory::filled(n_discs, NONE),
            prev: memory::filled(n_discs, NONE),
            cell: memory::filled(n_discs, [0, 0]),
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

    /// Put disc `i` into cell `c` (at the head of its list).
    #[inline]
    pub fn insert(&mut self, i: u32, c: [u32; 2]) {
        let k = self.index(c);
        let h = self.head[k];
        self.next[i as usize] = h;
        self.prev[i as usize] = NONE;
        if h != NONE {
            self.prev[h as usize] = i;
        }
        self.head[k] = i;
        self.cell[i as usize] = c;
    }

    /// Take disc `i` out of its cell.
    #[inline]
    pub fn remove(&mut self, i: u32) {
        let (p, n) = (self.prev[i as usize], self.next[i as usize]);
        if p != NONE {
            self.next[p as usize] = n;
        } else {
            let k = self.index(self.cell[i as usize]);
            self.head[k] = n;
        }
        if n != NONE {
            self.prev[n as usize] = p;
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
                        j = self.next[cur as usize];
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
        (self.head.capacity() + self.next.capacity() + self.prev.capacity()) * 4
            + self.cell.capacity() * 8
    }
}
