use super::super::bond_order::local_psi6_from;
use super::super::neighbours::delaunay_neighbours;
use super::super::test_lattice::triangular;
use super::*;
use std::f64::consts::PI;

fn close(a: [f64; 2], b: [f64; 2], tol: f64) -> bool {
    (a[0] - b[0]).abs() <= tol && (a[1] - b[1]).abs() <= tol
}

/// A perfect triangular lattice in a periodic box it fits: six Delaunay
/// neighbours and six nearest neighbours, all on the hexagon, so every estimator
/// gives ψ6 = 1 for every disc and the six-neighbour fraction is 1.
#[test]
fn every_estimator_gives_one_on_the_triangular_lattice() {
    for (cols, rows, a) in [(12, 14, 1.1), (4, 4, 0.7)] {
        let (sb, x, y) = triangular(cols, rows, a);
        let nb = delaunay_neighbours(&sb, &x, &y);
        assert_eq!(six_neighbour_fraction(&nb), 1.0);
        for psi in [
            local_psi6_equal(&nb),
            local_psi6_nearest(&sb, &x, &y, &nb, 6),
        ] {
            assert_eq!(psi.len(), x.len());
            for p in psi {
                assert!(close(p, [1.0, 0.0], 1e-12), "{cols} x {rows}: {p:?}");
            }
        }
    }
}

/// The lattice with basis a1 = (1, 0), a2 = (δ, 1) (rows sheared by δ = ±1/128,
/// 4 × 128 sites in a 4 × 128 periodic box: 128 rows shift by one column). For
/// δ > 0 the Delaunay bonds are ±a1, ±a2 and the short diagonal ±a3 = ±(a2 − a1);
/// every triangle has area 1/2, and a bond e shared by two congruent triangles
/// with opposite angle θ_e has the Voronoi edge ℓ_e = |e| cot θ_e (each triangle's
/// circumcentre lies (|e|/2) cot θ_e from the bond's midpoint), cot θ = u·v/|u × v|
/// with u, v the other two sides from the opposite vertex and |u × v| = 1:
/// ℓ1 = 1 − δ + δ² (opposite a2), ℓ2 = √(1 + δ²)(1 − δ) (opposite a1),
/// ℓ3 = √((1 − δ)² + 1) δ (opposite the origin) — the diagonal between four
/// nearly co-circular discs, whose edge vanishes as δ → 0. With z_e = e^{6iθ_e}
/// (bond and its opposite alike): weighted ψ6 = Σ ℓ_e z_e / Σ ℓ_e, equal-weight
/// ψ6 = (z1 + z2 + z3)/3, the same as the six nearest neighbours'. Mirroring
/// x → −x turns δ into −δ and ψ6 into its conjugate. As δ → 0 (the square
/// lattice) z1 = 1, z2 = −1, z3 = e^{6i·135°} = i: the equal-weight ψ6 tends to
/// ±i/3 depending on the side (a jump of 2/3 across δ = 0), the weighted one to 0
/// continuously (O(δ)).
#[test]
fn a_sheared_lattice_is_worked_by_hand_and_only_the_weighted_psi6_is_continuous() {
    let (cols, rows) = (4usize, 128usize);
    let d = 1.0 / rows as f64;
    let sixfold_of = |v: [f64; 2]| sixfold(v[0], v[1]);
    let (a1, a2, a3) = ([1.0, 0.0], [d, 1.0], [d - 1.0, 1.0]);
    let (l1, l2, l3) = (
        1.0 - d + d * d,
        (1.0 + d * d).sqrt() * (1.0 - d),
        ((1.0 - d) * (1.0 - d) + 1.0).sqrt() * d,
    );
    let (z1, z2, z3) = (sixfold_of(a1), sixfold_of(a2), sixfold_of(a3));
    let weighted = [
        (l1 * z1[0] + l2 * z2[0] + l3 * z3[0]) / (l1 + l2 + l3),
        (l1 * z1[1] + l2 * z2[1] + l3 * z3[1]) / (l1 + l2 + l3),
    ];
    let equal = [(z1[0] + z2[0] + z3[0]) / 3.0, (z1[1] + z2[1] + z3[1]) / 3.0];
    let sb = SimBox::periodic(cols as f64, rows as f64);
    let mut got = Vec::new();
    for sign in [1.0, -1.0] {
        let (mut x, mut y) = (Vec::new(), Vec::new());
        for r in 0..rows {
            for c in 0..cols {
                x.push((c as f64 + 0.25 + sign * d * r as f64).rem_euclid(cols as f64));
                y.push(r as f64 + 0.5);
            }
        }
        let nb = delaunay_neighbours(&sb, &x, &y);
        assert_eq!(six_neighbour_fraction(&nb), 1.0);
        let conj = |p: [f64; 2]| [p[0], sign * p[1]];
        for i in 0..x.len() {
            let mut edges: Vec<f64> = nb.of(i).iter().map(|b| b.2).collect();
            edges.sort_by(f64::total_cmp);
            let mut want = [l1, l1, l2, l2, l3, l3];
            want.sort_by(f64::total_cmp);
            for (e, w) in edges.iter().zip(want) {
                assert!((e - w).abs() < 1e-12, "disc {i}: {edges:?} vs {want:?}");
            }
        }
        let w = local_psi6_from(&nb);
        let e = local_psi6_equal(&nb);
        let k = local_psi6_nearest(&sb, &x, &y, &nb, 6);
        for i in 0..x.len() {
            assert!(close(w[i], conj(weighted), 1e-12), "{sign} {i}: {:?}", w[i]);
            assert!(close(e[i], conj(equal), 1e-12), "{sign} {i}: {:?}", e[i]);
            assert!(close(k[i], conj(equal), 1e-12), "{sign} {i}: {:?}", k[i]);
        }
        got.push((w[0], e[0]));
    }
    let dist = |a: [f64; 2], b: [f64; 2]| (a[0] - b[0]).hypot(a[1] - b[1]);
    // Shearing by 2δ = 1/64 moves the weighted ψ6 by 0.057 and the others by 0.70.
    assert!(dist(got[0].0, got[1].0) < 0.06, "{got:?}");
    assert!(dist(got[0].1, got[1].1) > 0.65, "{got:?}");
    assert!(weighted[1] > 0.0 && weighted[1] < 0.03 && (equal[1] - 1.0 / 3.0).abs() < 0.04);
}

/// Eight discs in a walled box: c = (5, 5), p_k = c + (cos 60k°, sin 60k°) for
/// k = 0 … 5 and q = c + 1.1 (cos 30°, sin 30°). q lies inside the circle through
/// c, p0, p1 (centre c + (cos 30°, sin 30°)/√3, radius 1/√3 = 0.577; q is
/// 1.1 − 0.577 from it), so c–q is a Delaunay bond and c has 7 neighbours: the
/// hexagon (z = 1 each) and q at 30° (z = e^{i180°} = −1): equal-weight
/// ψ6(c) = (6 − 1)/7 = 5/7, while its six nearest are the hexagon: ψ6 = 1.
/// p0's six nearest: q (0.55), c, p1, p5 (1), p2, p4 (√3), not p3 (2); the
/// bonds to c, p1, p5 point at 180°, 120°, 240° (z = 1), to p2, p4 at 150°, 210°
/// (z = −1): ψ6(p0) = (1 + z_q)/6 with z_q the sixfold of q − p0. p2 and p4 are
/// reached through c (not Delaunay neighbours of p0).
#[test]
fn six_nearest_neighbours_are_found_through_the_delaunay_graph() {
    let (mut x, mut y) = (vec![5.0], vec![5.0]);
    for k in 0..6 {
        let t = k as f64 * PI / 3.0;
        x.push(5.0 + t.cos());
        y.push(5.0 + t.sin());
    }
    let t = PI / 6.0;
    x.push(5.0 + 1.1 * t.cos());
    y.push(5.0 + 1.1 * t.sin());
    let sb = SimBox::walled(10.0, 10.0, 1.0);
    let nb = delaunay_neighbours(&sb, &x, &y);
    assert_eq!(nb.of(0).len(), 7);
    assert!(
        nb.of(1).iter().all(|b| b.0 != 3 && b.0 != 5),
        "{:?}",
        nb.of(1)
    );
    let e = local_psi6_equal(&nb);
    assert!(close(e[0], [5.0 / 7.0, 0.0], 1e-12), "{:?}", e[0]);
    let k = local_psi6_nearest(&sb, &x, &y, &nb, 6);
    assert!(close(k[0], [1.0, 0.0], 1e-12), "{:?}", k[0]);
    let zq = sixfold(x[7] - x[1], y[7] - y[1]);
    assert!(
        close(k[1], [(1.0 + zq[0]) / 6.0, zq[1] / 6.0], 1e-12),
        "{:?}",
        k[1]
    );
    let six = (0..8).filter(|&i| nb.of(i).len() == 6).count();
    assert_eq!(six_neighbour_fraction(&nb), six as f64 / 8.0);
}

/// Two discs alone in a 3 × 3 periodic box at (0.5, 1.5) and (2, 1.5): the walk
/// counts each image once, nearest first, and stops at k.
#[test]
fn images_across_a_periodic_edge_are_distinct_neighbours() {
    let sb = SimBox::periodic(3.0, 3.0);
    let (x, y) = (vec![0.5, 2.0], vec![1.5, 1.5]);
    let nb = delaunay_neighbours(&sb, &x, &y);
    let k = local_psi6_nearest(&sb, &x, &y, &nb, 2);
    // Disc 0's two nearest: disc 1 at +1.5 and its image at −1.5 (a tie, both
    // along x: z = 1 each).
    assert!(close(k[0], [1.0, 0.0], 1e-12), "{:?}", k[0]);
    // Four nearest: those two and two of disc 0's own images at (±3, 0), (0, ±3)
    // (a four-way tie; z = 1 along x, −1 along y), before disc 1's images at
    // (±1.5, ±3): ψ6 = (2 + z + z')/4 is real whichever two.
    let k4 = local_psi6_nearest(&sb, &x, &y, &nb, 4);
    assert!(k4[0][1].abs() < 1e-12);
}
