//! Lattice placement: the arrangement of sites whose closest pair of occupied sites
//! is farthest apart, with spare sites left empty and spread evenly.
//!
//! In a fully periodic box every lattice that fits the torus is searched (q rows
//! of p sites with shear k/q, the Hermite normal form, with up to 2N sites for
//! N ≤ 500), which reaches packing fraction 0.72 at aspect ratios in [1/4, 4] for
//! every N ≥ 34 tested; with walls, square and triangular rows are spread to the
//! walls. A request the best lattice cannot meet (closest pair below 2 a (1 +
//! 10⁻⁹)) is refused with the densest packing fraction it can place, printed with
//! the digits that tell it from the one asked for. See docs/performance.md,
//! "initial states".

use super::random::shuffle;
use super::spec::{box_size_for, SystemSpec};
use crate::error::InitError;
use carom_core::observables::packing_fraction;
use carom_core::{DVec2, SimBox};
use rand_pcg::Pcg64;
use rows::Axes;

mod rows;

/// Sites along one axis: `count` coordinates and their spacing (∞ for one site on a
/// walled axis, which has no neighbour along it).
fn axis_sites(len: f64, periodic: bool, a: f64, count: usize) -> (Vec<f64>, f64) {
    if periodic {
        let s = len / count as f64;
        ((0..count).map(|k| (k as f64 + 0.5) * s).collect(), s)
    } else if count == 1 {
        (vec![len / 2.0], f64::INFINITY)
    } else {
        let s = (len - 2.0 * a) / (count - 1) as f64;
        // Clamped: a + (count − 1) s may round one ulp past len − a.
        (
            (0..count)
                .map(|k| (a + k as f64 * s).min(len - a))
                .collect(),
            s,
        )
    }
}

/// One candidate lattice: `rows` rows of `cols` sites, rows alternately shifted by
/// half a spacing when `shifted` (triangular), in a frame where rows run along `u`.
#[derive(Debug, Clone, Copy)]
struct Lattice {
    rows: usize,
    cols: usize,
    shifted: bool,
    /// When true, "rows" run along y (the frame is transposed).
    transposed: bool,
}

impl Lattice {
    /// (capacity, closest distance between two sites, including periodic images).
    fn quality(&self, axes: &Axes) -> (usize, f64) {
        let (pu, pv) = (axes.pu, axes.pv);
        let su = axes.su(self.cols);
        let sv = axes.sv(self.rows);
        if !self.shifted {
            return (self.rows * self.cols, su.min(sv));
        }
        // Shifted rows on a walled u axis hold one site fewer.
        let short = if pu { self.cols } else { self.cols - 1 };
        let cap = self.rows.div_ceil(2) * self.cols + (self.rows / 2) * short;
        let mut d = su.min((0.25 * su * su + sv * sv).sqrt());
        if self.rows > 1 {
            // Same-parity rows: two rows apart, or adjacent across a periodic edge
            // when the row count is odd.
            let same = if pv && self.rows % 2 == 1 {
                sv
            } else {
                2.0 * sv
            };
            d = d.min(same);
        }
        (cap, d)
    }

    fn sites(&self, sim_box: &SimBox, a: f64) -> Vec<DVec2> {
        let (ku, kv) = if self.transposed { (1, 0) } else { (0, 1) };
        let (lu, lv) = (sim_box.size[ku], sim_box.size[kv]);
        let (pu, pv) = (
            sim_box.boundary[ku].is_periodic(),
            sim_box.boundary[kv].is_periodic(),
        );
        let (us, su) = axis_sites(lu, pu, a, self.cols);
        let (vs, _) = axis_sites(lv, pv, a, self.rows);
        let mut out = Vec::with_capacity(self.rows * self.cols);
        for (r, &v) in vs.iter().enumerate() {
            let shift = self.shifted && r % 2 == 1;
            let cols = if shift && !pu {
                self.cols - 1
            } else {
                self.cols
            };
            for &u in us.iter().take(cols) {
                let u = if shift { u + 0.5 * su } else { u };
                let u = if pu { u.rem_euclid(lu) } else { u };
                let mut p = DVec2::ZERO;
                p[ku] = u;
                p[kv] = v;
                out.push(p);
            }
        }
        out
    }
}

/// A lattice in a box periodic on both axes: `q` rows of `p` sites, row j shifted
/// along x by j k/q of the site spacing. Every lattice with p q sites that fits the
/// torus has such a basis (its Hermite normal form), so this family holds every
/// periodic lattice arrangement; `k = 0` is square-like and `k = q/2` the usual
/// alternate-row triangular lattice.
#[derive(Debug, Clone, Copy)]
struct Sheared {
    p: usize,
    q: usize,
    k: usize,
}

impl Sheared {
    /// Basis vectors b1 = (L_x/p, 0), b2 = (k L_x/(p q), L_y/q) (length).
    fn basis(&self, size: DVec2) -> (DVec2, DVec2) {
        (
            DVec2::new(size.x / self.p as f64, 0.0),
            DVec2::new(
                size.x * self.k as f64 / (self.p * self.q) as f64,
                size.y / self.q as f64,
            ),
        )
    }

    /// Closest distance between two sites (including periodic images): the shortest
    /// nonzero lattice vector, by Lagrange–Gauss reduction of the basis.
    fn closest(&self, size: DVec2) -> f64 {
        let (mut u, mut v) = self.basis(size);
        if u.length_squared() > v.length_squared() {
            std::mem::swap(&mut u, &mut v);
        }
        loop {
            let mu = (u.dot(v) / u.length_squared()).round();
            v -= u * mu;
            if v.length_squared() >= u.length_squared() {
                return u.length();
            }
            std::mem::swap(&mut u, &mut v);
        }
    }

    fn sites(&self, size: DVec2) -> Vec<DVec2> {
        let (p, q) = (self.p as f64, self.q as f64);
        let mut out = Vec::with_capacity(self.p * self.q);
        for j in 0..self.q {
            let y = (j as f64 + 0.5) * size.y / q;
            let shift = j as f64 * self.k as f64 / q;
            for i in 0..self.p {
                let x = ((i as f64 + 0.5 + shift) * size.x / p).rem_euclid(size.x);
                out.push(DVec2::new(x.min(size.x * (1.0 - f64::EPSILON)), y));
            }
        }
        out
    }
}

/// A candidate arrangement of lattice sites.
#[derive(Debug, Clone, Copy)]
enum Arrangement {
    /// Rows, plain or alternately shifted (any boundaries), with the rule choosing
    /// which sites are occupied when there are more sites than discs.
    Rows(Lattice, Selection),
    /// A sheared lattice (periodic on both axes).
    Sheared(Sheared),
}

/// Which n of m ≥ n sites (in row order) are occupied.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Selection {
    /// Sites ⌊k m/n⌋: spread evenly.
    Spread,
    /// Sites ⌊k (m−1)/(n−1)⌋: spread evenly including the last site (corners).
    Ends,
}

impl Selection {
    fn pick<T: Copy>(self, sites: &[T], n: usize) -> Vec<T> {
        let m = sites.len();
        match self {
            Selection::Ends if n > 1 => (0..n).map(|k| sites[k * (m - 1) / (n - 1)]).collect(),
            _ => (0..n).map(|k| sites[k * m / n]).collect(),
        }
    }
}

impl Arrangement {
    /// The n occupied sites.
    fn occupied(&self, sim_box: &SimBox, a: f64, n: usize) -> Vec<DVec2> {
        match self {
            Arrangement::Rows(l, sel) => sel.pick(&l.sites(sim_box, a), n),
            Arrangement::Sheared(l) => Selection::Spread.pick(&l.sites(sim_box.size), n),
        }
    }
}

/// Closest distance between any two of `pts` (minimum image on periodic axes); ∞ for
/// fewer than two points. O(n²): for small n only.
fn closest_pair_distance(sim_box: &SimBox, pts: &[DVec2]) -> f64 {
    let mut d2 = f64::INFINITY;
    for (i, p) in pts.iter().enumerate() {
        for q in &pts[i + 1..] {
            d2 = d2.min(sim_box.minimum_image(*q - *p).length_squared());
        }
    }
    d2.sqrt()
}

/// The best lattice for `n` discs of largest radius `a` in `sim_box`: the candidate
/// whose closest pair of sites is farthest apart (fewer spare sites on ties).
/// Returns it with that distance.
fn best_lattice(sim_box: &SimBox, n: usize, a: f64) -> (Arrangement, f64) {
    best_lattice_searching(sim_box, n, a, Axes::rows_to_search)
}

/// The row counts a rows lattice search tries for `n` discs (in increasing order),
/// given the frame, the row shape and the best closest distance seen so far.
type RowSearch = fn(&Axes, usize, bool, bool, Option<f64>) -> std::ops::RangeInclusive<usize>;

/// [`best_lattice`] trying the row counts `search` gives.
fn best_lattice_searching(
    sim_box: &SimBox,
    n: usize,
    a: f64,
    search: RowSearch,
) -> (Arrangement, f64) {
    let mut best: Option<(Arrangement, f64, usize)> = None;
    fn consider(
        best: &mut Option<(Arrangement, f64, usize)>,
        arr: Arrangement,
        d: f64,
        cap: usize,
    ) {
        let better = match *best {
            None => true,
            Some((_, bd, bcap)) => d > bd || (d == bd && cap < bcap),
        };
        if better {
            *best = Some((arr, d, cap));
        }
    }
    let fully_periodic = sim_box.boundary.iter().all(|b| b.is_periodic());
    if fully_periodic {
        // Row counts to try: all of them (with up to 2n sites) for small n, else a
        // wide band around the row count of an ideal triangular lattice.
        let ideal = (n as f64 * sim_box.size.y / sim_box.size.x * 3f64.sqrt() / 2.0).sqrt();
        let (q_lo, q_hi) = if n <= 500 {
            (1, 2 * n)
        } else {
            ((ideal / 2.0) as usize, (2.0 * ideal) as usize + 1)
        };
        for q in q_lo.max(1)..=q_hi.min(2 * n) {
            // Columns: from the fewest that hold n discs; for small n up to 2n sites
            // (a sparser-looking lattice can have a better shape).
            let p0 = n.div_ceil(q).max(1);
            let p_hi = if n <= 500 {
                (2 * n / q).max(p0)
            } else {
                p0 + 1
            };
            for p in p0..=p_hi {
                // b1 is a lattice vector, so L_x/p bounds the closest distance: no shear
                // of a lattice with this many columns can beat the best found so far.
                if best.is_some_and(|(_, bd, _)| sim_box.size.x / p as f64 <= bd) {
                    break;
                }
                for k in 0..q {
                    let l = Sheared { p, q, k };
                    consider(
                        &mut best,
                        Arrangement::Sheared(l),
                        l.closest(sim_box.size),
                        p * q,
                    );
                }
            }
        }
    }
    for transposed in [false, true] {
        let (ku, kv) = if transposed { (1, 0) } else { (0, 1) };
        let (lu, lv) = (sim_box.size[ku], sim_box.size[kv]);
        let (pu, pv) = (
            sim_box.boundary[ku].is_periodic(),
            sim_box.boundary[kv].is_periodic(),
        );
        let axes = Axes { lu, lv, pu, pv, a };
        for shifted in [false, true] {
            let known = best.map(|(_, bd, _)| bd);
            for rows in search(&axes, n, shifted, transposed, known) {
                let (lat, cap, d) = axes.fewest_columns(n, rows, shifted, transposed);
                consider(&mut best, Arrangement::Rows(lat, Selection::Spread), d, cap);
                if cap > n && n <= 64 && !fully_periodic {
                    // In small walled boxes the occupied subset can be much better
                    // spaced than the full lattice (two discs on a diagonal).
                    let sites = lat.sites(sim_box, a);
                    for sel in [Selection::Spread, Selection::Ends] {
                        let d = closest_pair_distance(sim_box, &sel.pick(&sites, n));
                        consider(&mut best, Arrangement::Rows(lat, sel), d, cap);
                    }
                }
            }
        }
    }
    let (lat, d, _) = best.expect("at least one candidate lattice");
    (lat, d)
}

/// How many decimals (6 to 12) show `limit` and the refused density `eta` as
/// different numbers: a lattice that only just fails (its closest sites exactly at
/// contact) has a limit within about 10⁻⁹ of the density asked for.
fn decimals_apart(limit: f64, eta: f64) -> usize {
    (6..=12)
        .find(|&p| format!("{:.p$}", round_down(limit, p)) != format!("{eta:.p$}"))
        .unwrap_or(12)
}

/// `x` rounded down to `p` decimals, so that "η < x" printed with `p` decimals stays
/// true of the limit `x`.
fn round_down(x: f64, p: usize) -> f64 {
    let scale = 10f64.powi(p as i32);
    (x * scale).floor() / scale
}

/// The largest packing fraction the lattice placement reaches for these species in a
/// box of this aspect ratio and these boundaries (by bisection on η; for messages).
fn lattice_limit(spec: &SystemSpec) -> f64 {
    let n: usize = spec.species.iter().map(|s| s.count).sum();
    let a = spec.largest_radius();
    let aspect = spec.sim_box.size.x / spec.sim_box.size.y;
    let (mut lo, mut hi) = (0.0, 0.9069);
    for _ in 0..40 {
        let mid = 0.5 * (lo + hi);
        let mut b = spec.sim_box;
        b.size = box_size_for(&spec.species, mid, aspect);
        if apart(best_lattice(&b, n, a).1, a) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    lo
}

/// The relative gap (of the contact distance) that lattice placement leaves at
/// least between the closest discs. Discs placed exactly at contact are not
/// overlapping, but they are no state to start from: in a row of touching discs
/// round a periodic box or from wall to wall (a lattice exactly at its closest
/// packing, such as 1020 discs in a periodic 30 × 30 box, or 100 in a walled
/// 10 × 10 one) each collision at t = 0 sets off the next, and the momentum goes
/// round or to and fro forever without time advancing. The gap, far above the rounding
/// of the positions (about 10⁻¹⁶ of the box), lets time advance between them.
const LATTICE_GAP: f64 = 1e-9;

/// Whether lattice sites `d` apart hold discs of radius `a` with the gap
/// [`LATTICE_GAP`] between them.
fn apart(d: f64, a: f64) -> bool {
    d >= 2.0 * a * (1.0 + LATTICE_GAP)
}

pub(super) fn lattice(
    spec: &SystemSpec,
    species_of: &[u16],
    rng: &mut Pcg64,
) -> Result<Vec<DVec2>, InitError> {
    let n = species_of.len();
    let a = spec.largest_radius();
    let (lat, d) = best_lattice(&spec.sim_box, n, a);
    if !apart(d, a) {
        let eta = packing_fraction(&spec.species, &spec.sim_box);
        let limit = lattice_limit(spec);
        let p = decimals_apart(limit, eta);
        let problem = if d >= 2.0 * a * (1.0 - LATTICE_GAP) {
            format!(
                "{eta:.p$} is the density at which lattice placement for N = {n} in this box \
                 has its closest sites exactly one diameter ({}) apart: the discs would \
                 start in contact, and a row of touching discs round the periodic box or \
                 from wall to wall passes its momentum on forever at one instant",
                2.0 * a
            )
        } else {
            format!(
                "{eta:.4} is beyond what lattice placement reaches for N = {n} in this box \
                 (closest sites {d:.6} apart, diameter {})",
                2.0 * a
            )
        };
        return Err(InitError::invalid(
            "packing_fraction",
            problem,
            format!(
                "η < {:.p$} for this N, box shape and boundaries; relaxed placement, not \
                 tied to a lattice, may reach more",
                round_down(limit, p)
            ),
        ));
    }
    let mut chosen = lat.occupied(&spec.sim_box, a, n);
    // Shuffle which disc sits where, so species mix.
    shuffle(&mut chosen, rng);
    Ok(chosen)
}
