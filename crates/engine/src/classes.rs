//! Size classes: a cell grid for each class of similar disc sizes.
//!
//! One grid for all species needs cells as wide as the largest contact distance, so
//! a few much larger discs make every scan walk many small ones. The species are
//! sorted by radius and may be split into classes of consecutive sizes, each with
//! its own grid. A disc crosses only its own grid's cells and scans its 3 × 3 block
//! there, and in class b's grid every cell meeting its own widened by a_i + a_max(b)
//! (plus a hair for rounding): if i and j meet at t, at i's last prediction both
//! were in their cells at t, σ_ij = a_i + a_j apart, so i's scan read j's cell. A
//! deterministic estimate of the scans' work (`work`) decides the split, so a
//! configuration always gets the same grids; a class is split off only when every
//! periodic axis is longer than each widened cell. See docs/performance.md, "size
//! classes".

use crate::cells::{CellGrid, Member};
use crate::NO_DISC;
use carom_core::rates::henderson_contact_value;
use carom_core::{SimBox, Species};

/// Relative margin on a scan's reach into another grid, so that rounding of
/// positions at cell edges never hides a contact (as the grid's own cells are a
/// hair wider than the contact distance).
const REACH_MARGIN: f64 = 1e-9;

/// The cell grids of the size classes, and which class each species is in.
#[derive(Debug, Clone)]
pub struct Grids {
    /// Grid of class 0, the smallest discs (the only grid when there is one class).
    pub first: CellGrid,
    /// Grids of classes 1, 2, … (empty when there is one class).
    pub rest: Vec<CellGrid>,
    /// Class of each species (0 for a species with no discs).
    pub class_of: Vec<u8>,
    /// Largest radius of the discs of each class (length).
    pub radius: Vec<f64>,
}

impl Grids {
    /// The grids for `species` (discs' species `species_of`) in `sim_box`: one per
    /// size class when `split`, else a single grid for all (the layout of
    /// checkpoints written before carom had classes). Classes are only formed
    /// when the box is wide enough for them (see the module docs).
    pub fn new(sim_box: &SimBox, species: &[Species], species_of: &[u16], split: bool) -> Grids {
        let mut count = vec![0usize; species.len()];
        for &s in species_of {
            count[s as usize] += 1;
        }
        // Present species by radius (ties by index, so that the choice is
        // deterministic).
        let mut order: Vec<usize> = (0..species.len()).filter(|&s| count[s] > 0).collect();
        order.sort_by(|&a, &b| {
            species[a]
                .radius
                .total_cmp(&species[b].radius)
                .then(a.cmp(&b))
        });
        let single = vec![order.clone()];
        let mut best = single.clone();
        if split && order.len() > 1 {
            let mut least = work(sim_box, species, &count, &single).unwrap_or(f64::INFINITY);
            for layout in layouts(species, &order) {
                // Strictly less: of equal estimates the earlier (fewer grids) wins.
                if let Some(w) = work(sim_box, species, &count, &layout) {
                    if w < least {
                        least = w;
                        best = layout;
                    }
                }
            }
        }
        let mut class_of = vec![0u8; species.len()];
        let mut radius = Vec::new();
        let mut grids = Vec::new();
        for (c, members) in best.iter().enumerate() {
            let (r, discs) = extent(species, &count, members);
            for &s in members {
                class_of[s] = c as u8;
            }
            radius.push(r);
            grids.push(CellGrid::new(sim_box, 2.0 * r, discs));
        }
        if radius.is_empty() {
            // No discs at all: one grid, as for one species.
            radius.push(0.0);
            grids.push(CellGrid::new(sim_box, 0.0, 0));
        }
        let mut grids = grids.into_iter();
        Grids {
            first: grids.next().expect("at least one grid"),
            rest: grids.collect(),
            class_of,
            radius,
        }
    }

    /// One grid for all discs, of cells at least `min_width` wide (length), for
    /// `discs` discs of largest radius `radius`: the grid of list centres
    /// (engine::listed).
    pub fn one(
        sim_box: &SimBox,
        species: usize,
        radius: f64,
        min_width: f64,
        discs: usize,
    ) -> Grids {
        Grids {
            first: CellGrid::new(sim_box, min_width, discs),
            rest: Vec::new(),
            class_of: vec![0; species],
            radius: vec![radius],
        }
    }

    /// The largest contact distance 2 a_max of all classes (length).
    pub fn largest_sigma(&self) -> f64 {
        2.0 * self.radius.iter().copied().fold(0.0, f64::max)
    }

    /// Whether there is a single grid (one class).
    #[inline(always)]
    pub fn single(&self) -> bool {
        self.rest.is_empty()
    }

    /// Number of classes (grids).
    pub fn len(&self) -> usize {
        1 + self.rest.len()
    }

    /// Class of species `s`.
    #[inline(always)]
    pub fn class(&self, s: u16) -> u8 {
        if self.single() {
            0
        } else {
            self.class_of[s as usize]
        }
    }

    /// The grid of class `c`.
    #[inline(always)]
    pub fn get(&self, c: u8) -> &CellGrid {
        if c == 0 {
            &self.first
        } else {
            &self.rest[c as usize - 1]
        }
    }

    /// The grid of class `c`, for changing.
    #[inline(always)]
    pub fn get_mut(&mut self, c: u8) -> &mut CellGrid {
        if c == 0 {
            &mut self.first
        } else {
            &mut self.rest[c as usize - 1]
        }
    }

    /// The grids in class order.
    pub fn iter(&self) -> impl Iterator<Item = &CellGrid> {
        std::iter::once(&self.first).chain(&self.rest)
    }

    /// The grids in class order, for changing.
    pub fn iter_mut(&mut self) -> impl Iterator<Item = &mut CellGrid> {
        std::iter::once(&mut self.first).chain(&mut self.rest)
    }

    /// How far beyond its own cell a disc of radius `a` must look for discs of
    /// class `c` (length): a + a_max(c), with the rounding margin.
    #[inline]
    pub fn reach(&self, a: f64, c: u8) -> f64 {
        (a + self.radius[c as usize]) * (1.0 + REACH_MARGIN)
    }

    /// The previous disc in its cell's list of each disc, or [`NO_DISC`] for the first
    /// ([`CellGrid::prev_links`] over all the grids).
    pub fn prev_links<M: Member>(&self, members: &[M]) -> Vec<u32> {
        let mut prev = vec![NO_DISC; members.len()];
        for grid in self.iter() {
            for (p, q) in prev.iter_mut().zip(grid.prev_links(members)) {
                if q != NO_DISC {
                    *p = q;
                }
            }
        }
        prev
    }

    /// The first disc of each cell, grid after grid in class order (as checkpoints
    /// store them).
    pub fn heads(&self) -> Vec<u32> {
        self.iter().flat_map(|g| g.head.iter().copied()).collect()
    }

    /// Bytes of heap memory used (for the memory report).
    pub fn heap_bytes(&self) -> usize {
        self.iter().map(CellGrid::heap_bytes).sum::<usize>() + self.class_of.capacity()
    }
}

/// The cells of `grid` along axis `k` meeting the interval [`lo`, `hi`] (length),
/// as (cell, image shift in box lengths) in increasing order: on a periodic axis
/// the interval may run up to one box length past either edge, on a walled axis it
/// is cut at the walls.
#[inline]
pub fn cells_along(
    grid: &CellGrid,
    k: usize,
    lo: f64,
    hi: f64,
) -> impl Iterator<Item = (u32, i32)> {
    let n = grid.n[k] as i64;
    let mut from = (lo / grid.width[k]).floor() as i64;
    let mut to = (hi / grid.width[k]).floor() as i64;
    let periodic = grid.periodic[k];
    if !periodic {
        from = from.max(0);
        to = to.min(n - 1);
    }
    (from..=to).map(move |v| {
        let shift = v.div_euclid(n);
        debug_assert!(periodic || shift == 0);
        ((v - shift * n) as u32, shift as i32)
    })
}

/// The largest radius (length) and the number of discs of the class made of the
/// species `members` (`count`: discs of each species).
fn extent(species: &[Species], count: &[usize], members: &[usize]) -> (f64, usize) {
    let radius = members
        .iter()
        .map(|&s| species[s].radius)
        .fold(0.0, f64::max);
    (radius, members.iter().map(|&s| count[s]).sum())
}

/// The layouts tried besides one grid for all: the species `order` (present
/// species by increasing radius) cut into runs. Every way of cutting up to
/// [`ALL_LAYOUTS_UP_TO`] species; beyond that, the cuts where the radius grows by
/// more than 1.25, 1.5, 2, 3, 5 or 10 times over the smallest radius of the run.
fn layouts(species: &[Species], order: &[usize]) -> Vec<Vec<Vec<usize>>> {
    let k = order.len();
    let cut = |cuts: &dyn Fn(usize, f64) -> bool| {
        let mut layout: Vec<Vec<usize>> = vec![vec![order[0]]];
        let mut smallest = species[order[0]].radius;
        for (p, &s) in order.iter().enumerate().skip(1) {
            if cuts(p, smallest) {
                layout.push(Vec::new());
                smallest = species[s].radius;
            }
            layout.last_mut().expect("a run").push(s);
        }
        layout
    };
    if k <= ALL_LAYOUTS_UP_TO {
        // Bit p − 1 of `mask` cuts before the p-th species.
        (1..1u32 << (k - 1))
            .map(|mask| cut(&|p, _| mask >> (p - 1) & 1 == 1))
            .collect()
    } else {
        [1.25, 1.5, 2.0, 3.0, 5.0, 10.0]
            .iter()
            .map(|&f| cut(&|p, smallest| species[order[p]].radius > f * smallest))
            .filter(|l| l.len() > 1 && l.len() <= u8::MAX as usize)
            .collect()
    }
}

/// Up to this many species with discs, every way of grouping them into classes of
/// consecutive sizes is weighed.
const ALL_LAYOUTS_UP_TO: usize = 10;

/// Weights of [`work`], in units of one pair test: visiting a cell of the own
/// grid, visiting a cell of another class's grid (a general loop with image
/// shifts), and the rest of an event (queue, collision rule).
const VISIT: f64 = 1.0;
const OTHER_VISIT: f64 = 3.0;
const EVENT: f64 = 15.0;

/// Estimated work of the neighbour search per unit time (pair tests per time, in
/// units of √(kT/m₀)) with the species grouped into the classes `layout`; `None`
/// when the box is too narrow for the layout (see the module docs). `count` is the
/// number of discs of each species.
///
/// A disc of species a in class k predicts at each collision (rate
/// ν_a = Σ_b 2 σ_ab g ρ_b ⟨|v_ab|⟩, ⟨|v_ab|⟩ = √(π/2 · (1/m_a + 1/m_b)) and g
/// Henderson's contact value (1 − 7η/16)/(1 − η)² at the total packing
/// fraction) and at each crossing (rate Σ_axes ⟨|v_x|⟩/w = √(2/(π m_a)) Σ 1/w). A
/// prediction visits the 3 × 3 cells of its own grid (three after a crossing) and
/// tests the ρ_k w_x w_y discs per cell there, and in the grid of each other class
/// b the (w + 2 reach)/W + 1 cells per axis around its cell and the discs in them.
/// Calibrated against `examples/mixture` (20 000 + 200 discs at η = 0.4 with
/// diameter ratios 1.4, 2, 2.5, 5 and 10; 10 000 + 10 000 with ratios 1.4 and 3;
/// 10 000 + 1000 with ratio 5; 2000 + 2000 with ratio 10): it picks the faster
/// layout in each, measured both ways.
fn work(
    sim_box: &SimBox,
    species: &[Species],
    count: &[usize],
    layout: &[Vec<usize>],
) -> Option<f64> {
    let size = sim_box.size;
    let area = size.x * size.y;
    let rho: Vec<f64> = count.iter().map(|&n| n as f64 / area).collect();
    let eta: f64 = (0..species.len())
        .map(|s| rho[s] * species[s].disc_area())
        .sum::<f64>();
    let g = henderson_contact_value(eta);
    struct Class {
        radius: f64,
        width: [f64; 2],
        rho: f64,
    }
    let classes: Vec<Class> = layout
        .iter()
        .map(|members| {
            let (radius, discs) = extent(species, count, members);
            let n = CellGrid::shape(sim_box, 2.0 * radius, discs);
            Class {
                radius,
                width: [size.x / n[0] as f64, size.y / n[1] as f64],
                rho: members.iter().map(|&s| rho[s]).sum(),
            }
        })
        .collect();
    let periodic = [
        sim_box.boundary[0].is_periodic(),
        sim_box.boundary[1].is_periodic(),
    ];
    let mut total = 0.0;
    for (k, members) in layout.iter().enumerate() {
        let own = &classes[k];
        for &a in members {
            let (ra, ma) = (species[a].radius, species[a].mass);
            let cell = own.width[0] * own.width[1];
            let full = VISIT * 9.0 + 9.0 * cell * own.rho;
            let strip = VISIT * 3.0 + 3.0 * cell * own.rho;
            let mut other = 0.0;
            for (_, theirs) in classes.iter().enumerate().filter(|&(b, _)| b != k) {
                let reach = (ra + theirs.radius) * (1.0 + REACH_MARGIN);
                let (mut cells, mut tested) = (1.0, theirs.rho);
                for x in 0..2 {
                    let span =
                        own.width[x] + 2.0 * (own.radius + theirs.radius) * (1.0 + REACH_MARGIN);
                    if periodic[x] && span >= size[x] {
                        return None;
                    }
                    let region = own.width[x] + 2.0 * reach;
                    cells *= region / theirs.width[x] + 1.0;
                    tested *= region + theirs.width[x];
                }
                other += OTHER_VISIT * cells + tested;
            }
            let collisions: f64 = (0..species.len())
                .map(|b| {
                    let speed =
                        (std::f64::consts::FRAC_PI_2 * (1.0 / ma + 1.0 / species[b].mass)).sqrt();
                    2.0 * (ra + species[b].radius) * g * rho[b] * speed
                })
                .sum();
            let crossings = (2.0 / (std::f64::consts::PI * ma)).sqrt()
                * (1.0 / own.width[0] + 1.0 / own.width[1]);
            total += count[a] as f64
                * (collisions * (EVENT + full + other) + crossings * (EVENT + strip + other));
        }
    }
    Some(total)
}

#[cfg(test)]
mod tests {
    use super::*;
    use carom_core::Boundary;

    fn two(n_small: usize, n_large: usize, ratio: f64) -> Vec<Species> {
        vec![Species::reference(n_small), Species::scaled(n_large, ratio)]
    }

    fn periodic(size: DVec2) -> SimBox {
        SimBox {
            size,
            boundary: [Boundary::Periodic; 2],
        }
    }

    fn species_of(species: &[Species]) -> Vec<u16> {
        species
            .iter()
            .enumerate()
            .flat_map(|(s, sp)| std::iter::repeat_n(s as u16, sp.count))
            .collect()
    }

    fn grids_for(species: &[Species], sim_box: &SimBox) -> Grids {
        Grids::new(sim_box, species, &species_of(species), true)
    }

    use carom_core::DVec2;

    #[test]
    fn a_few_large_discs_get_their_own_grid() {
        let species = two(20_000, 200, 10.0);
        let b = periodic(crate::box_size_for(&species, 0.4, 1.0));
        let g = grids_for(&species, &b);
        assert_eq!(g.len(), 2);
        assert_eq!(g.class_of, vec![0, 1]);
        assert_eq!(g.radius, vec![0.5, 5.0]);
        // Each grid's cells are as narrow as its own discs allow.
        assert!(g.first.width.min_element() >= 1.0 && g.first.width.max_element() < 1.1);
        assert!(g.rest[0].width.min_element() >= 10.0);
        // Asked for the old layout: one grid, sized for the largest discs.
        let one = Grids::new(&b, &species, &species_of(&species), false);
        assert_eq!(one.len(), 1);
        assert!(one.first.width.min_element() >= 10.0);
    }

    #[test]
    fn many_large_discs_share_one_grid() {
        // Measured faster with one grid (module docs).
        for (small, large, ratio, eta) in [
            (2000, 2000, 10.0, 0.5),
            (10_000, 10_000, 3.0, 0.5),
            (10_000, 10_000, 1.4, 0.6),
            (20_000, 200, 2.0, 0.4),
        ] {
            let species = two(small, large, ratio);
            let b = periodic(crate::box_size_for(&species, eta, 1.0));
            assert_eq!(
                grids_for(&species, &b).len(),
                1,
                "{small} + {large}, ratio {ratio}"
            );
        }
    }

    #[test]
    fn similar_sizes_share_a_class() {
        // Two small species 10 % apart and one large: the small ones share a grid.
        let mut species = two(10_000, 100, 10.0);
        species.insert(1, Species::new(10_000, 0.55, 1.2));
        let b = periodic(crate::box_size_for(&species, 0.4, 1.0));
        let g = grids_for(&species, &b);
        assert_eq!(g.class_of, vec![0, 0, 1]);
        assert_eq!(g.radius, vec![0.55, 5.0]);
    }

    #[test]
    fn a_box_too_narrow_for_two_grids_keeps_one() {
        // The same discs in a periodic strip 15 wide: a large disc's cell (10) widened by
        // its reach into the small grid (2 × 5.5) is wider than the box.
        let species = two(20_000, 200, 10.0);
        let area = crate::box_size_for(&species, 0.4, 1.0).element_product();
        let wide = periodic(DVec2::new(150.0, area / 150.0));
        assert_eq!(grids_for(&species, &wide).len(), 2);
        let narrow = periodic(DVec2::new(15.0, area / 15.0));
        assert_eq!(grids_for(&species, &narrow).len(), 1);
        // Walls on the narrow axis put no such limit.
        let walled = SimBox {
            boundary: [Boundary::Walls { restitution: 1.0 }, Boundary::Periodic],
            ..narrow
        };
        assert_eq!(grids_for(&species, &walled).len(), 2);
    }

    #[test]
    fn cells_along_wrap_with_their_image_and_stop_at_walls() {
        let b = periodic(DVec2::new(10.0, 10.0));
        let g = CellGrid::new(&b, 0.99, 1000);
        assert_eq!(g.n, [10, 10]);
        let got: Vec<_> = cells_along(&g, 0, -1.5, 0.5).collect();
        assert_eq!(got, vec![(8, -1), (9, -1), (0, 0)]);
        let got: Vec<_> = cells_along(&g, 1, 8.5, 11.2).collect();
        assert_eq!(got, vec![(8, 0), (9, 0), (0, 1), (1, 1)]);
        let walled = SimBox {
            boundary: [Boundary::Walls { restitution: 1.0 }; 2],
            ..b
        };
        let g = CellGrid::new(&walled, 0.99, 1000);
        let got: Vec<_> = cells_along(&g, 0, -1.5, 1.5).collect();
        assert_eq!(got, vec![(0, 0), (1, 0)]);
        let got: Vec<_> = cells_along(&g, 0, 8.5, 11.5).collect();
        assert_eq!(got, vec![(8, 0), (9, 0)]);
    }
}
