//! Nearest neighbours of every disc in one snapshot from the Delaunay
//! triangulation of the centres (the `delaunator` crate): i and j are neighbours
//! when their Voronoi cells share an edge, whose length (the distance between
//! the circumcentres of the two triangles on the bond) is kept as the bond's
//! weight (physics.md §11). Along a periodic axis
//! the triangulation also holds ghost copies of the discs within
//! [`GHOST_SPACINGS`] mean spacings of each edge, so that a disc near the edge
//! finds its neighbours across it; the displacement to a neighbour is the
//! ghost's, i.e. the minimum image. Along a walled axis there are no ghosts: the
//! outermost discs have the neighbours the hull gives them.

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
    pub start: Vec<usize>,
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
            let m = margin.min(0.5 * l);
            if v < m {
                s.push(l);
            }
            if v > l - m {
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
    use super::*;
    use rand::{RngExt, SeedableRng};
    use rand_pcg::Pcg64;

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
}
