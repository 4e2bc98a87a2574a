//! Test configurations with known structure, shared by the structure tests.

use carom_core::SimBox;

/// A triangular lattice with spacing `a`, `cols` × `rows` sites (rows even),
/// filling a periodic box exactly, bonds along x.
pub fn triangular(cols: usize, rows: usize, a: f64) -> (SimBox, Vec<f64>, Vec<f64>) {
    let h = a * 3f64.sqrt() / 2.0;
    let sb = SimBox::periodic(cols as f64 * a, rows as f64 * h);
    let (mut x, mut y) = (Vec::new(), Vec::new());
    for r in 0..rows {
        for c in 0..cols {
            x.push((c as f64 + 0.5 * (r % 2) as f64 + 0.25) * a);
            y.push((r as f64 + 0.5) * h);
        }
    }
    (sb, x, y)
}
