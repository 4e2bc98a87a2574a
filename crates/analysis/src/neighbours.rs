//! Nearest neighbours of every disc in one snapshot from the Delaunay
//! triangulation of the centres (the `delaunator` crate): i and j are neighbours
//! when their Voronoi cells share an edge, whose length (the distance between
//! the circumcentres of the two triangles on the bond) is kept as the bond's
//! weight (physics.md §11). Along a periodic axis
//! the triangulation also holds ghost copies of the discs within
//! [`GHOST_SPACINGS`] mean spacings of each edge (every disc's on both sides when
//! that is a whole box: a few discs' bonds can be longer than half a box), so
//! that a disc near the edge finds its neighbours across it; the displacement to
//! a neighbour is the ghost's, i.e. the minimum image for a bond shorter than half
//! a box. Along a walled axis there are no ghosts: the outermost discs have the
//! neighbours the hull gives them.

use carom_core::SimBox;
use delaunator::{next_halfedge, triangulate, Point, EMPTY};

/// Width of the ghost layer beyond each periodic edge, in mean spacings √(A/N).
pub const GHOST_SPACINGS: f64 = 4.0;

/// Neighbour lists of one snapshot: disc i's neighbours are
/// `list[start[i]..start[i + 1]]`, each the neighbour's index, the displacement
/// r_j − r_i (minimum image, length) and the length of the Voronoi edge the two
/// cells share (NaN for an edge of the hull, whose cells are unbounded).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Neighbours {
    /// Where each disc's neighbours begin in `list` (N + 1 entries).
    pub start: Vec<usize>,
    /// (neighbour index, displacement r_j − r_i, Voronoi edge length), disc by disc.
    pub list: Vec<(u32, [f64; 2], f64)>,
}

impl Neighbours {
    /// The neighbours of disc `i`.
    pub fn of(&self, i: usize) -> &[(u32, [f64; 2], f64)] {
        &self.list[self.start[i]..self.start[i + 1]]
    }
}

/// The Delaunay neighbours of the discs at (`x`, `y`) in `sim_box`.
pub fn delaunay_neighbours(sim_box: &SimBox, x: &[f64], y: &[f64]) -> Neighbours {
    let n = x.len();
    let (lx, ly) = (sim_box.size.x, sim_box.size.y);
    let margin = GHOST_SPACINGS * (lx * ly / n.max(1) as f64).sqrt();
    let shifts = |l: f64, periodic: bool, v: f64| -> Vec<f64> {
        let mut s = vec![0.0];
        if periodic {
            if v < margin {
                s.push(l);
            }
            if v > l - margin {
                s.push(-l);
            }
        }
        s
    };
    let per = sim_box.boundary.map(|b| b.is_periodic());
    // Point k is disc owner[k], at its own position or a ghost's.
    let mut points: Vec<Point> = (0..n).map(|i| Point { x: x[i], y: y[i] }).collect();
    let mut owner: Vec<u32> = (0..n as u32).collect();
    let mut shift: Vec<[f64; 2]> = vec![[0.0; 2]; n];
    for i in 0..n {
        for &sx in &shifts(lx, per[0], x[i]) {
            for &sy in &shifts(ly, per[1], y[i]) {
                if sx != 0.0 || sy != 0.0 {
                    points.push(Point {
                        x: x[i] + sx,
                        y: y[i] + sy,
                    });
                    owner.push(i as u32);
                    shift.push([sx, sy]);
                }
            }
        }
    }
    let tri = triangulate(&points);
    // Circumcentre of each triangle: the Voronoi vertices.
    let centre: Vec<[f64; 2]> = tri
        .triangles
        .chunks_exact(3)
        .map(|t| circumcentre(&points[t[0]], &points[t[1]], &points[t[2]]))
        .collect();
    // Each half-edge p → q (q the next vertex of its triangle) once; its Voronoi
    // facet joins its triangle's circumcentre and its twin's. A hull edge has no
    // twin: it is also entered as q → p, with an unknown (NaN) facet.
    let mut edges: Vec<(u32, u32, f64)> = Vec::with_capacity(tri.triangles.len() + 8);
    for e in 0..tri.triangles.len() {
        let (p, q) = (tri.triangles[e], tri.triangles[next_halfedge(e)]);
        let twin = tri.halfedges[e];
        let facet = if twin == EMPTY {
            f64::NAN
        } else {
            let (c, d) = (centre[e / 3], centre[twin / 3]);
            (c[0] - d[0]).hypot(c[1] - d[1])
        };
        if p < n {
            edges.push((p as u32, q as u32, facet));
        }
        if twin == EMPTY && q < n {
            edges.push((q as u32, p as u32, facet));
        }
    }
    edges.sort_unstable_by_key(|e| (e.0, e.1));
    let mut start = vec![0usize; n + 1];
    for &(p, _, _) in &edges {
        start[p as usize + 1] += 1;
    }
    for i in 0..n {
        start[i + 1] += start[i];
    }
    let list = edges
        .iter()
        .map(|&(p, q, facet)| {
            // (x_j − x_i) + shift, so that j's view of i is exactly the negative.
            let (i, j, s) = (p as usize, owner[q as usize], shift[q as usize]);
            let d = [x[j as usize] - x[i] + s[0], y[j as usize] - y[i] + s[1]];
            (j, d, facet)
        })
        .collect();
    Neighbours { start, list }
}

/// The centre of the circle through `a`, `b`, `c`.
fn circumcentre(a: &Point, b: &Point, c: &Point) -> [f64; 2] {
    let (bx, by) = (b.x - a.x, b.y - a.y);
    let (cx, cy) = (c.x - a.x, c.y - a.y);
    let d = 2.0 * (bx * cy - by * cx);
    let (b2, c2) = (bx * bx + by * by, cx * cx + cy * cy);
    [a.x + (cy * b2 - by * c2) / d, a.y + (bx * c2 - cx * b2) / d]
}

#[cfg(test)]
mod tests {
    use super::super::test_lattice::triangular;
    use super::*;
    use rand::{RngExt, SeedableRng};
    use rand_pcg::Pcg64;
    use std::f64::consts::{PI, SQRT_2};

    /// Random points: neighbourhood is symmetric with opposite displacements and
    /// equal facets, the Voronoi cells' areas (Σ facet·|d|/4) add up to the
    /// box's, and on a torus the Delaunay triangulation has exactly 3N edges (Euler:
    /// V − E + F = 0 with 3F = 2E), so the mean number of neighbours is 6 — a
    /// missing or doubled ghost breaks it.
    #[test]
    fn neighbours_are_symmetric_and_six_on_average_on_a_torus() {
        let mut rng = Pcg64::seed_from_u64(11);
        for (n, lx, ly) in [(400, 20.0, 20.0), (150, 30.0, 7.0), (1000, 15.0, 40.0)] {
            let x: Vec<f64> = (0..n).map(|_| rng.random_range(0.0..lx)).collect();
            let y: Vec<f64> = (0..n).map(|_| rng.random_range(0.0..ly)).collect();
            for sb in [SimBox::periodic(lx, ly), SimBox::walled(lx, ly, 1.0)] {
                let nb = delaunay_neighbours(&sb, &x, &y);
                let mut area = 0.0;
                for i in 0..n {
                    for &(j, d, facet) in nb.of(i) {
                        let back = nb.of(j as usize).iter().find(|e| e.0 == i as u32);
                        let back = back.unwrap_or_else(|| panic!("{i} -> {j} not mutual"));
                        assert_eq!([back.1[0], back.1[1]], [-d[0], -d[1]]);
                        assert!(
                            (back.2 - facet).abs() <= 1e-9 * facet
                                || (back.2.is_nan() && facet.is_nan())
                        );
                        // The triangle of the cell's edge and the centre.
                        area += 0.25 * facet * d[0].hypot(d[1]);
                    }
                }
                if sb.boundary[0].is_periodic() {
                    assert_eq!(nb.list.len(), 6 * n, "{lx} x {ly}");
                    // The Voronoi cells tile the torus.
                    assert!((area / (lx * ly) - 1.0).abs() < 1e-9, "area {area}");
                } else {
                    // A planar triangulation of N points has fewer than 3N edges.
                    assert!(nb.list.len() < 6 * n && nb.list.len() > 5 * n);
                }
            }
        }
    }

    /// The reference: triangulate the whole 3 × 3 tiling of the box (every disc and
    /// its eight images, the discs first) and keep the bonds of the central copies,
    /// each sorted by (neighbour, displacement).
    fn tiled(lx: f64, ly: f64, x: &[f64], y: &[f64]) -> Vec<Vec<(u32, [f64; 2], f64)>> {
        let n = x.len();
        let mut pts: Vec<Point> = (0..n).map(|i| Point { x: x[i], y: y[i] }).collect();
        let mut img: Vec<(usize, [f64; 2])> = (0..n).map(|i| (i, [0.0; 2])).collect();
        for sx in [-lx, 0.0, lx] {
            for sy in [-ly, 0.0, ly] {
                if sx != 0.0 || sy != 0.0 {
                    for i in 0..n {
                        pts.push(Point {
                            x: x[i] + sx,
                            y: y[i] + sy,
                        });
                        img.push((i, [sx, sy]));
                    }
                }
            }
        }
        let t = triangulate(&pts);
        let cc = |k: usize| {
            let v = &t.triangles[3 * (k / 3)..3 * (k / 3) + 3];
            circumcentre(&pts[v[0]], &pts[v[1]], &pts[v[2]])
        };
        let mut out = vec![Vec::new(); n];
        for e in 0..t.triangles.len() {
            let (p, q) = (t.triangles[e], t.triangles[next_halfedge(e)]);
            if p < n {
                let (c, d) = (cc(e), cc(t.halfedges[e]));
                let (j, s) = img[q];
                let disp = [x[j] - x[p] + s[0], y[j] - y[p] + s[1]];
                out[p].push((j as u32, disp, (c[0] - d[0]).hypot(c[1] - d[1])));
            }
        }
        for l in &mut out {
            l.sort_by(|a, b| {
                (a.0, a.1[0], a.1[1])
                    .partial_cmp(&(b.0, b.1[0], b.1[1]))
                    .unwrap()
            });
        }
        out
    }

    /// Random discs on tori of 12 to 400 discs (the ghost layer four spacings wide:
    /// more than half the box for the 12 and 40, which half a box missed): exactly
    /// the neighbours, displacements and Voronoi edges of the full 3 × 3 tiling; and
    /// again with every length scaled by 10, 1000 and 1/16 (a triangulation has no
    /// length scale, nor must the layer in spacings).
    #[test]
    fn the_ghost_layer_gives_the_neighbours_of_the_whole_tiling() {
        let mut rng = Pcg64::seed_from_u64(5);
        for (n, lx, ly) in [
            (12, 5.0, 3.0),
            (40, 6.0, 9.0),
            (90, 4.0, 20.0),
            (400, 21.0, 19.0),
        ] {
            let x0: Vec<f64> = (0..n).map(|_| rng.random_range(0.0..lx)).collect();
            let y0: Vec<f64> = (0..n).map(|_| rng.random_range(0.0..ly)).collect();
            for k in [1.0, 10.0, 1000.0, 0.0625] {
                let x: Vec<f64> = x0.iter().map(|v| v * k).collect();
                let y: Vec<f64> = y0.iter().map(|v| v * k).collect();
                let nb = delaunay_neighbours(&SimBox::periodic(lx * k, ly * k), &x, &y);
                let reference = tiled(lx * k, ly * k, &x, &y);
                for (i, r) in reference.iter().enumerate() {
                    let mut got = nb.of(i).to_vec();
                    got.sort_by(|a, b| {
                        (a.0, a.1[0], a.1[1])
                            .partial_cmp(&(b.0, b.1[0], b.1[1]))
                            .unwrap()
                    });
                    assert_eq!(got.len(), r.len(), "n {n} x{k}, disc {i}: {got:?} vs {r:?}");
                    for (g, w) in got.iter().zip(r) {
                        assert_eq!((g.0, g.1), (w.0, w.1), "n {n} x{k}, disc {i}");
                        assert!((g.2 - w.2).abs() <= 1e-9 * w.2, "n {n} x{k}, disc {i}");
                    }
                }
            }
        }
    }

    /// The circle through (5, 3), (−3, −1), (6, −4) is centred at (2, −1): each is
    /// 5 from it (3² + 4², 5² + 0², 4² + 3²). Any order of the corners; the same
    /// triangle scaled by 0.3 and moved by (7.1, −2.6) has its centre moved with it.
    #[test]
    fn the_circumcentre_is_equidistant_from_the_corners() {
        let p = |x: f64, y: f64| Point { x, y };
        let (a, b, c) = (p(5.0, 3.0), p(-3.0, -1.0), p(6.0, -4.0));
        for (u, v, w) in [(&a, &b, &c), (&b, &c, &a), (&c, &b, &a)] {
            assert_eq!(circumcentre(u, v, w), [2.0, -1.0]);
        }
        let m = |q: &Point| p(7.1 + 0.3 * q.x, -2.6 + 0.3 * q.y);
        let o = circumcentre(&m(&a), &m(&b), &m(&c));
        assert!(
            (o[0] - 7.7).abs() < 1e-14 && (o[1] + 2.9).abs() < 1e-14,
            "{o:?}"
        );
    }

    /// Four discs on a parallelogram A(0.5, 0.5), B(4.5, 0.5), C(5.5, 3.5),
    /// D(1.5, 3.5) in a walled box: the short diagonal BD (|BD|² = 18 < |AC|² = 34)
    /// is the Delaunay edge, the four sides are the hull (NaN facets). BD's Voronoi
    /// edge joins the circumcentres of ABD, (2.5, 1.5) (on x = 2.5, and
    /// 4 + (y − 0.5)² = 1 + (y − 3.5)² gives y = 1.5), and of BCD, its image
    /// (3.5, 2.5) under the half-turn about the centre (3, 2): length √2.
    #[test]
    fn four_discs_on_a_parallelogram_have_the_short_diagonal_as_a_bond() {
        let (x, y) = ([0.5, 4.5, 5.5, 1.5], [0.5, 0.5, 3.5, 3.5]);
        let nb = delaunay_neighbours(&SimBox::walled(6.0, 4.0, 1.0), &x, &y);
        let nan = f64::NAN;
        let expected: [&[(u32, [f64; 2], f64)]; 4] = [
            &[(1, [4.0, 0.0], nan), (3, [1.0, 3.0], nan)],
            &[
                (0, [-4.0, 0.0], nan),
                (2, [1.0, 3.0], nan),
                (3, [-3.0, 3.0], SQRT_2),
            ],
            &[(1, [-1.0, -3.0], nan), (3, [-4.0, 0.0], nan)],
            &[
                (0, [-1.0, -3.0], nan),
                (1, [3.0, -3.0], SQRT_2),
                (2, [4.0, 0.0], nan),
            ],
        ];
        assert_eq!(nb.start, vec![0, 2, 5, 7, 10]);
        for (i, e) in expected.iter().enumerate() {
            let got = nb.of(i);
            assert_eq!(got.len(), e.len(), "disc {i}: {got:?}");
            for (g, w) in got.iter().zip(e.iter()) {
                assert_eq!((g.0, g.1), (w.0, w.1), "disc {i}");
                assert!(
                    (g.2 - w.2).abs() < 1e-14 || (g.2.is_nan() && w.2.is_nan()),
                    "disc {i}: {g:?}"
                );
            }
        }
    }

    /// A triangular lattice filling a periodic box (test_lattice): every disc has the
    /// same six neighbours, at the six lattice vectors a(cos k60°, sin k60°), each the
    /// disc found there modulo the box, and every Voronoi cell is the regular hexagon
    /// of side a/√3 (its edges a/√3 long). The discs are numbered from the fourth row
    /// (y = 3.5h) so that disc 0's first ghost, one box up, is on the hull (the
    /// highest of all: 4 × 4 sites, the margin 4√(ah) = 4.84 more than the box's
    /// 4h = 4.5, so every row is copied up; 12 × 14, margin 4√(ah) ≈ 4.3h copies up
    /// the rows below it, the fourth the highest).
    #[test]
    fn a_periodic_lattice_gives_every_disc_its_six_lattice_neighbours() {
        for (cols, rows, a) in [(4, 4, 1.3), (12, 14, 0.8)] {
            let (sb, mut x, mut y) = triangular(cols, rows, a);
            x.rotate_left(3 * cols);
            y.rotate_left(3 * cols);
            let (lx, ly) = (sb.size.x, sb.size.y);
            let nb = delaunay_neighbours(&sb, &x, &y);
            assert_eq!(nb.start.len(), x.len() + 1);
            for i in 0..x.len() {
                let bonds = nb.of(i);
                assert_eq!(bonds.len(), 6, "{cols} x {rows}, disc {i}: {bonds:?}");
                let mut angles: Vec<f64> = Vec::new();
                for &(j, d, facet) in bonds {
                    assert!((d[0].hypot(d[1]) - a).abs() < 1e-12, "{d:?}");
                    assert!((facet - a / 3f64.sqrt()).abs() < 1e-12, "facet {facet}");
                    // r_i + d is disc j's position up to whole boxes.
                    let (wx, wy) = (
                        (x[i] + d[0] - x[j as usize]) / lx,
                        (y[i] + d[1] - y[j as usize]) / ly,
                    );
                    assert!((wx - wx.round()).abs() < 1e-9 && (wy - wy.round()).abs() < 1e-9);
                    angles.push(d[1].atan2(d[0]).rem_euclid(2.0 * PI));
                }
                angles.sort_by(f64::total_cmp);
                for (k, t) in angles.iter().enumerate() {
                    assert!(
                        (t - k as f64 * PI / 3.0).abs() < 1e-9,
                        "disc {i}: {angles:?}"
                    );
                }
            }
        }
    }
}
