//! The sixfold bond factor e^{6iθ} of a bond (dx, dy) = r (cos θ, sin θ), from
//! which ψ6 and its estimators are built (physics.md §11): z⁶ for the unit
//! complex number z = (dx + i dy)/r, computed as ((dx + i dy)/r)⁶ by three
//! complex products, without trigonometry.

/// z⁶ for the unit complex number z = (dx + i dy)/r.
pub fn sixfold(dx: f64, dy: f64) -> [f64; 2] {
    let r2 = dx * dx + dy * dy;
    let (a, b) = (dx * dx - dy * dy, 2.0 * dx * dy); // z² r²
    let (c, d) = (a * a - b * b, 2.0 * a * b); // z⁴ r⁴
    let s = 1.0 / (r2 * r2 * r2);
    [(a * c - b * d) * s, (a * d + b * c) * s]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sixfold_is_the_sixth_power_of_the_bond_direction() {
        for th in [0.0, 0.3, 1.0, 2.5, -2.0, 3.1] {
            let z = sixfold(2.0 * f64::cos(th), 2.0 * f64::sin(th));
            assert!((z[0] - (6.0 * th).cos()).abs() < 1e-14);
            assert!((z[1] - (6.0 * th).sin()).abs() < 1e-14);
        }
    }

    /// z = (3 + 4i)/5 by hand: z² = (−7 + 24i)/25, z⁴ = (z²)² = (−527 − 336i)/625,
    /// z⁶ = z⁴ z² = (3689 + 8064 + (−12648 + 2352)i)/15625 = (11753 − 10296i)/15625
    /// (|z⁶|² = 15625²/15625² checks it). The bond's length, 5 or 0.35, drops out;
    /// the mirror image (3, −4) is the conjugate.
    #[test]
    fn sixfold_of_a_three_four_five_bond_is_worked_by_hand() {
        let exact = [11753.0 / 15625.0, -10296.0 / 15625.0];
        for (k, [dx, dy]) in [[3.0, 4.0], [0.21, 0.28], [3.0, -4.0]]
            .into_iter()
            .enumerate()
        {
            let z = sixfold(dx, dy);
            let im = if k == 2 { -exact[1] } else { exact[1] };
            assert!(
                (z[0] - exact[0]).abs() < 1e-15 && (z[1] - im).abs() < 1e-15,
                "{z:?}"
            );
        }
    }
}
