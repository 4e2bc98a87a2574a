//! The pair-correlation report: g_ab(r) with block error bars, the contact value
//! g_ab(σ_ab⁺) from a least-squares parabola in ln g through the bins lying
//! wholly in [σ_ab, σ_ab + 0.2 σ_ab], extrapolated to σ_ab (physics.md §10), and the contact
//! theorem (10.3) Z = 1 + (π/2) n Σ_ab x_a x_b σ_ab² g_ab(σ_ab⁺) next to the
//! collision-virial Z, the difference in standard errors (periodic elastic runs
//! only: with walls the wall term enters the pressure, and inelastic runs have no
//! equilibrium g). Each estimate is made per time block; its error is the
//! standard error of the block values.

use serde::Serialize;

use super::pair_correlation::{mean_se, pairs, PairCorrelation, BLOCKS};
use super::thermo_report::PressureReport;

/// Width of the contact fit in units of σ_ab.
pub const CONTACT_FIT_SIGMA: f64 = 0.2;

/// g(r) per species pair (physics.md §10).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PairCorrelationReport {
    /// Bin centres (length).
    pub r: Vec<f64>,
    /// Bin width (length): σ_min/50.
    pub bin_width: f64,
    /// Largest r (length): 10 σ_max, at most half a periodic edge.
    pub r_max: f64,
    /// Snapshots used (all after the equilibration time).
    pub snapshots: u64,
    /// Time blocks with snapshots (the error bars' spread).
    pub blocks: usize,
    /// One entry per species pair a ≤ b present in the run.
    pub pairs: Vec<PairReport>,
    /// The contact theorem against the virial Z; `null` unless periodic, elastic,
    /// with a pressure.
    pub contact_theorem: Option<ContactTheoremReport>,
}

/// g_ab(r) of one species pair.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PairReport {
    /// Species indices a ≤ b.
    pub a: usize,
    /// Second species index.
    pub b: usize,
    /// Contact distance σ_ab = r_a + r_b (length).
    pub sigma: f64,
    /// g at each bin centre, pooled over all snapshots.
    pub g: Vec<f64>,
    /// Standard error of g from the spread of the time blocks.
    pub std_error: Vec<f64>,
    /// Contact value g_ab(σ_ab⁺); `null` when it cannot be estimated, then
    /// `contact_missing` says why.
    pub contact: Option<ContactValue>,
    /// Why there is no contact value: no bin in the fit range, or too few pairs
    /// near contact to fit.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub contact_missing: Option<String>,
}

/// The contact value with its error.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ContactValue {
    /// g(σ⁺) extrapolated from the least-squares parabola in ln g over [σ, σ + 0.2 σ]
    /// ([`CONTACT_FIT_SIGMA`]).
    pub value: f64,
    /// Its standard error (spread of the per-block fits); `null` when a time
    /// block has too few pairs near contact to fit, then `no_error` says so.
    pub std_error: Option<f64>,
    /// Why there is no standard error.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub no_error: Option<String>,
    /// Number of bins in the fit.
    pub fit_bins: usize,
}

/// The contact theorem (physics.md (10.3)) against the collision virial.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ContactTheoremReport {
    /// Z from the structure, 1 + (π/2) n Σ_ab x_a x_b σ_ab² g_ab(σ_ab⁺).
    pub z_structure: f64,
    /// Its standard error.
    pub z_structure_std_error: f64,
    /// Z from the collision virial (the pressure report).
    pub z_virial: f64,
    /// Its standard error.
    pub z_virial_std_error: f64,
    /// z_structure − z_virial.
    pub difference: f64,
    /// The difference over √(SE_s² + SE_v²) (the two treated as independent).
    pub difference_std_errors: f64,
}

/// g(σ⁺) from the bins (x, g) of width `h`: exp of the least-squares parabola
/// through (x, ln g) at `x0` (a straight line with fewer than 4 bins). ln g
/// bends near contact in a dense fluid; a straight line through it reads g(σ⁺)
/// low (physics.md §10). A bin holds g averaged over its annulus, which for
/// ln g = f is g(x)(1 + (f'² + f'')h²/24 + f'h²/(12x)) to order h²; that factor
/// is taken off at x0. Empty bins (g = 0) are left out.
/// The standard error of a contact value from its per-block fits, or why there
/// is none: fewer than two blocks, or blocks with too few pairs to fit.
fn block_error(per_block: &[f64]) -> Result<f64, String> {
    let empty = per_block.iter().filter(|g| !g.is_finite()).count();
    if empty > 0 || per_block.len() < 2 {
        return Err(format!(
            "{empty} of {} time blocks have too few pairs near contact to fit ln g (too few \
             discs or snapshots)",
            per_block.len()
        ));
    }
    Ok(mean_se(per_block).1)
}

fn contact_at(x: &[f64], g: &[f64], x0: f64, h: f64) -> f64 {
    let (x, lg): (Vec<f64>, Vec<f64>) = x
        .iter()
        .zip(g)
        .filter(|(_, &g)| g > 0.0)
        .map(|(&x, &g)| (x - x0, g.ln()))
        .unzip();
    let [c0, c1, c2] = if x.len() >= 4 {
        parabola(&x, &lg)
    } else {
        let [c0, c1] = line(&x, &lg);
        [c0, c1, 0.0]
    };
    (c0 - h * h * ((c1 * c1 + 2.0 * c2) / 24.0 + c1 / (12.0 * x0))).exp()
}

/// Coefficients [c0, c1, c2] of the least-squares parabola y = c0 + c1 x + c2 x²
/// (the normal equations about the mean of x, solved by Cramer's rule).
fn parabola(x: &[f64], y: &[f64]) -> [f64; 3] {
    let n = x.len() as f64;
    let m = x.iter().sum::<f64>() / n;
    let (mut s, mut t) = ([0.0; 5], [0.0; 3]);
    for (&x, &y) in x.iter().zip(y) {
        let u = x - m;
        let mut p = 1.0;
        for (k, sk) in s.iter_mut().enumerate() {
            *sk += p;
            if k < 3 {
                t[k] += p * y;
            }
            p *= u;
        }
    }
    let det3 = |a: [[f64; 3]; 3]| {
        a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1])
            - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0])
            + a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0])
    };
    let a = [[s[0], s[1], s[2]], [s[1], s[2], s[3]], [s[2], s[3], s[4]]];
    let d = det3(a);
    let col = |k: usize| {
        let mut b = a;
        for (row, &tk) in b.iter_mut().zip(&t) {
            row[k] = tk;
        }
        det3(b) / d
    };
    // y = b0 + b1 u + b2 u² with u = x − m.
    let (b0, b1, b2) = (col(0), col(1), col(2));
    [b0 - b1 * m + b2 * m * m, b1 - 2.0 * b2 * m, b2]
}

/// Coefficients [c0, c1] of the least-squares line y = c0 + c1 x (a constant
/// through one point).
fn line(x: &[f64], y: &[f64]) -> [f64; 2] {
    let n = x.len() as f64;
    if x.len() == 1 {
        return [y[0], 0.0];
    }
    let (mx, my) = (x.iter().sum::<f64>() / n, y.iter().sum::<f64>() / n);
    let sxx: f64 = x.iter().map(|v| (v - mx).powi(2)).sum();
    let sxy: f64 = x.iter().zip(y).map(|(a, b)| (a - mx) * (b - my)).sum();
    let slope = sxy / sxx;
    [my - slope * mx, slope]
}

/// The report from the accumulator; `elastic_periodic` and `pressure` decide the
/// contact theorem.
pub(super) fn report(
    pc: &PairCorrelation,
    elastic_periodic: bool,
    pressure: Option<&PressureReport>,
) -> Option<PairCorrelationReport> {
    if pc.snapshot_count() == 0 {
        return None;
    }
    let ns = pc.species.len();
    let r = pc.r();
    let used: Vec<usize> = (0..BLOCKS).filter(|&k| pc.snapshots[k] > 0).collect();
    let mut out = Vec::new();
    // Per block: Σ over ordered pairs of x_a x_b σ² g(σ⁺).
    let mut block_sum = vec![0.0; used.len()];
    let mut all_contacts = true;
    let n_total: usize = pc.species.iter().map(|s| s.count).sum();
    for (a, b) in pairs(ns) {
        let (sa, sb) = (&pc.species[a], &pc.species[b]);
        if sa.count == 0 || sb.count == 0 || (a == b && sa.count < 2) {
            continue;
        }
        let sigma = sa.radius + sb.radius;
        let (blocks, pooled) = pc.g(a, b);
        let blocks: Vec<Vec<f64>> = blocks.into_iter().flatten().collect();
        let std_error = (0..pc.nbins)
            .map(|k| mean_se(&blocks.iter().map(|g| g[k]).collect::<Vec<_>>()).1)
            .collect();
        // Bins wholly in [σ, σ(1 + 0.2)] (edges with a relative tolerance).
        let tol = 1e-9 * sigma;
        let fit: Vec<usize> = (0..pc.nbins)
            .filter(|&k| {
                let (lo, hi) = (k as f64 * pc.dr, (k + 1) as f64 * pc.dr);
                lo >= sigma - tol && hi <= sigma * (1.0 + CONTACT_FIT_SIGMA) + tol
            })
            .collect();
        let contact = if fit.is_empty() {
            Err(format!(
                "no bin of width {} lies within [σ, {} σ]",
                pc.dr,
                1.0 + CONTACT_FIT_SIGMA
            ))
        } else {
            let xs: Vec<f64> = fit.iter().map(|&k| r[k]).collect();
            let per_block: Vec<f64> = blocks
                .iter()
                .map(|g| {
                    let g: Vec<f64> = fit.iter().map(|&k| g[k]).collect();
                    contact_at(&xs, &g, sigma, pc.dr)
                })
                .collect();
            let g: Vec<f64> = fit.iter().map(|&k| pooled[k]).collect();
            let value = contact_at(&xs, &g, sigma, pc.dr);
            if value.is_finite() {
                Ok((per_block, value))
            } else {
                Err(format!(
                    "too few pairs within [σ, {} σ] to fit ln g",
                    1.0 + CONTACT_FIT_SIGMA
                ))
            }
        };
        let weight = {
            let (xa, xb) = (
                sa.count as f64 / n_total as f64,
                sb.count as f64 / n_total as f64,
            );
            let ordered = if a == b { 1.0 } else { 2.0 };
            ordered * xa * xb * sigma * sigma
        };
        let error = contact
            .as_ref()
            .ok()
            .map(|(per_block, _)| block_error(per_block));
        match (&contact, &error) {
            (Ok((per_block, _)), Some(Ok(_))) => {
                for (s, g) in block_sum.iter_mut().zip(per_block) {
                    *s += weight * g;
                }
            }
            _ => all_contacts = false,
        }
        out.push(PairReport {
            a,
            b,
            sigma,
            g: pooled,
            std_error,
            contact_missing: contact.as_ref().err().cloned(),
            contact: contact.ok().map(|(_, value)| {
                let error = error.expect("a value has an error or a reason");
                ContactValue {
                    value,
                    std_error: error.as_ref().ok().copied(),
                    no_error: error.err(),
                    fit_bins: fit.len(),
                }
            }),
        });
    }
    let contact_theorem = match pressure {
        Some(p) if elastic_periodic && all_contacts && !out.is_empty() => {
            let n = n_total as f64 / pc.sim_box.area();
            let c = std::f64::consts::FRAC_PI_2 * n;
            let z: Vec<f64> = block_sum.iter().map(|s| 1.0 + c * s).collect();
            // The pooled value: the same sum over the pooled contact values.
            let pooled_sum: f64 = out
                .iter()
                .map(|pr| {
                    let (sa, sb) = (&pc.species[pr.a], &pc.species[pr.b]);
                    let (xa, xb) = (
                        sa.count as f64 / n_total as f64,
                        sb.count as f64 / n_total as f64,
                    );
                    let ordered = if pr.a == pr.b { 1.0 } else { 2.0 };
                    ordered
                        * xa
                        * xb
                        * pr.sigma
                        * pr.sigma
                        * pr.contact.as_ref().map_or(0.0, |c| c.value)
                })
                .sum();
            let z_s = 1.0 + c * pooled_sum;
            let se_s = mean_se(&z).1;
            let se = se_s.hypot(p.z_std_error);
            Some(ContactTheoremReport {
                z_structure: z_s,
                z_structure_std_error: se_s,
                z_virial: p.z,
                z_virial_std_error: p.z_std_error,
                difference: z_s - p.z,
                difference_std_errors: (z_s - p.z) / se,
            })
        }
        _ => None,
    };
    Some(PairCorrelationReport {
        r,
        bin_width: pc.dr,
        r_max: pc.r_max,
        snapshots: pc.snapshot_count(),
        blocks: used.len(),
        pairs: out,
        contact_theorem,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use carom_core::{SimBox, Species};

    /// Bins of width `h` from `r0` holding g averaged over their annuli (the
    /// r-weighted mean, by Simpson's rule on 200 intervals).
    fn binned(g: impl Fn(f64) -> f64, r0: f64, h: f64, n: usize) -> (Vec<f64>, Vec<f64>) {
        let avg = |a: f64| {
            let m = 200;
            let (mut num, mut den) = (0.0, 0.0);
            for i in 0..=m {
                let r = a + h * i as f64 / m as f64;
                let w = if i == 0 || i == m {
                    1.0
                } else if i % 2 == 1 {
                    4.0
                } else {
                    2.0
                };
                num += w * g(r) * r;
                den += w * r;
            }
            num / den
        };
        (0..n)
            .map(|k| {
                let a = r0 + h * k as f64;
                (a + 0.5 * h, avg(a))
            })
            .unzip()
    }

    #[test]
    fn a_straight_line_in_ln_g_is_recovered_through_two_or_three_bins() {
        let (x, g) = binned(|r| 3.0 * (-2.0 * (r - 1.0)).exp(), 1.0, 0.02, 3);
        assert!((contact_at(&x, &g, 1.0, 0.02) / 3.0 - 1.0).abs() < 1e-7);
        assert!((contact_at(&x[..2], &g[..2], 1.0, 0.02) / 3.0 - 1.0).abs() < 1e-7);
        let [c0, c1] = line(&[1.0, 2.0, 3.0], &[5.0, 3.0, 1.0]);
        assert!((c0 - 7.0).abs() < 1e-12 && (c1 + 2.0).abs() < 1e-12);
    }

    /// ln g with the slope and curvature of a dense fluid at contact (η ≈ 0.65):
    /// the parabola with the bin correction recovers g(σ) to 10⁻⁶; without the
    /// correction it reads high (by more than 0.04 %), a straight line low.
    #[test]
    fn contact_fit_follows_the_curvature_of_ln_g_and_the_bins_averages() {
        let f = |r: f64| 6.0 * (-7.0 * (r - 1.0) + 12.0 * (r - 1.0).powi(2)).exp();
        let (x, g) = binned(f, 1.0, 0.02, 10);
        let fitted = contact_at(&x, &g, 1.0, 0.02);
        assert!((fitted / 6.0 - 1.0).abs() < 1e-6, "{fitted}");
        let uncorrected = contact_at(&x, &g, 1.0, 0.0);
        assert!(uncorrected / 6.0 - 1.0 > 4e-4, "{uncorrected}");
        let lg: Vec<f64> = g.iter().map(|v| v.ln()).collect();
        let straight = line(
            &x[..5].iter().map(|v| v - 1.0).collect::<Vec<_>>(),
            &lg[..5],
        )[0]
        .exp();
        assert!(straight < 5.99, "{straight}");
        // An empty bin is left out, not read as ln 0.
        let mut holed = g.clone();
        holed[9] = 0.0;
        assert!((contact_at(&x, &holed, 1.0, 0.02) / 6.0 - 1.0).abs() < 1e-5);
        let [c0, c1, c2] = parabola(&[0.0, 1.0, 2.0, 3.0], &[1.0, 2.0, 5.0, 10.0]);
        assert!((c0 - 1.0).abs() < 1e-12 && c1.abs() < 1e-12 && (c2 - 1.0).abs() < 1e-12);
    }

    /// The least-squares fits satisfy their normal equations: the residuals are
    /// orthogonal to 1, x (and x² for the parabola) — on uneven, off-centre x and
    /// data no low polynomial fits exactly; an exact quadratic is recovered.
    #[test]
    fn the_fits_satisfy_their_normal_equations() {
        let x = [0.1, 0.4, 0.5, 1.3, 2.2, 2.9];
        let y = [3.0, -1.0, 0.5, 2.0, 7.5, 4.0];
        let [c0, c1, c2] = parabola(&x, &y);
        let res: Vec<f64> = x
            .iter()
            .zip(&y)
            .map(|(x, y)| y - c0 - c1 * x - c2 * x * x)
            .collect();
        for p in 0..3 {
            let dot: f64 = x.iter().zip(&res).map(|(x, r)| r * x.powi(p)).sum();
            assert!(dot.abs() < 1e-10, "parabola, x^{p}: {dot}");
        }
        assert!(
            res.iter().map(|r| r * r).sum::<f64>() > 1.0,
            "the data are not a parabola"
        );
        let [d0, d1] = line(&x, &y);
        let res: Vec<f64> = x.iter().zip(&y).map(|(x, y)| y - d0 - d1 * x).collect();
        for p in 0..2 {
            let dot: f64 = x.iter().zip(&res).map(|(x, r)| r * x.powi(p)).sum();
            assert!(dot.abs() < 1e-10, "line, x^{p}: {dot}");
        }
        // y = 2 − 3x + 0.5x² on the same x.
        let q: Vec<f64> = x.iter().map(|x| 2.0 - 3.0 * x + 0.5 * x * x).collect();
        let [c0, c1, c2] = parabola(&x[1..], &q[1..]);
        assert!((c0 - 2.0).abs() < 1e-10 && (c1 + 3.0).abs() < 1e-10 && (c2 - 0.5).abs() < 1e-10);
        // Through one point: the constant.
        assert_eq!(line(&[0.7], &[-2.5]), [-2.5, 0.0]);
    }

    /// With ln g exactly c0 + c1 u + c2 u² (u = r − σ) at the bin centres, the fit
    /// is exact and the contact value is exp(c0 − h²((c1² + 2c2)/24 + c1/(12σ)))
    /// ((10.4) taken off at σ), here with σ = 0.9, h = 0.05: a parabola from 4
    /// bins on, a straight line (c2 = 0) below; through 3 bins of curved data the
    /// line is the least-squares one, slope (y₂ − y₀)/2h through the means.
    #[test]
    fn the_contact_value_is_the_fit_at_sigma_less_the_bin_average() {
        let (s, h) = (0.9, 0.05);
        let want = |c0: f64, c1: f64, c2: f64| {
            (c0 - h * h * ((c1 * c1 + 2.0 * c2) / 24.0 + c1 / (12.0 * s))).exp()
        };
        let bins = |n: usize, c: [f64; 3]| -> (Vec<f64>, Vec<f64>) {
            (0..n)
                .map(|k| {
                    let r = s + (k as f64 + 0.5) * h;
                    let u = r - s;
                    (r, (c[0] + c[1] * u + c[2] * u * u).exp())
                })
                .unzip()
        };
        let close = |u: f64, v: f64| (u / v - 1.0).abs() < 1e-10;
        let c = [1.3, -4.0, 9.0];
        for n in [4, 6] {
            let (x, g) = bins(n, c);
            let v = contact_at(&x, &g, s, h);
            assert!(close(v, want(c[0], c[1], c[2])), "{n} bins: {v}");
        }
        let (x, g) = bins(3, [1.3, -4.0, 0.0]);
        assert!(close(contact_at(&x, &g, s, h), want(1.3, -4.0, 0.0)));
        let (x, g) = bins(3, c);
        let y: Vec<f64> = g.iter().map(|g| g.ln()).collect();
        let slope = (y[2] - y[0]) / (2.0 * h);
        let c0 = (y[0] + y[1] + y[2]) / 3.0 - slope * (x[1] - s);
        assert!(close(contact_at(&x, &g, s, h), want(c0, slope, 0.0)));
        // An empty bin among 5 is left out: the other 4 still fit exactly.
        let (x, mut g) = bins(5, c);
        g[2] = 0.0;
        assert!(close(contact_at(&x, &g, s, h), want(c[0], c[1], c[2])));
    }

    /// Three A discs (radius 0.3, mass 2), two B discs (radius 0.45), no C disc,
    /// periodic 9 × 7, window [0, 16] (blocks of 1): bins 0.012 wide, fit ranges
    /// [σ, 1.2σ] = bins 50–59 (A–A, σ = 0.6), 63–74 (A–B, 0.75), 75–89 (B–B,
    /// 0.9). Two snapshots, in blocks 0 and 3, place pairs in the middle of bins
    /// 52 (A–A), 66 (A–B) and 80 (B–B); every other pair lies outside its fit range.
    fn two_snapshots() -> PairCorrelation {
        scaled_snapshots(1.0)
    }

    /// [`two_snapshots`] with every length (radii, box, positions) times `l`.
    fn scaled_snapshots(l: f64) -> PairCorrelation {
        let sp = [
            Species::new(3, 0.3 * l, 2.0),
            Species::new(2, 0.45 * l, 0.5),
            Species::new(0, 0.2 * l, 1.0),
        ];
        let mut pc = PairCorrelation::new(&sp, &SimBox::periodic(9.0 * l, 7.0 * l), 0.0, 16.0);
        let mid = |k: usize| (k as f64 + 0.5) * 0.012;
        let (aa, ab, bb) = (mid(52), mid(66), mid(80));
        let species = [0, 0, 0, 1, 1];
        let at = |v: [f64; 5]| v.map(|v| v * l);
        // A0–A1 side by side; B0–B1 side by side above, A2 above B1.
        let x = at([1.0, 1.0 + aa, 1.0 + bb, 1.0, 1.0 + bb]);
        pc.add(0.5, &species, &x, &at([1.0, 1.0, 3.2 + ab, 3.2, 3.2]));
        // A0–A1–A2 at a right angle (A0–A2 = 0.89), B0 from A2 at 30° from the
        // x axis, B1 from B0 at 120°: every other pair further apart than its
        // fit range (and than σ_ab), none within 0.15 bins of a bin edge.
        let (c, s) = (3f64.sqrt() / 2.0, 0.5);
        let b0 = [1.0 + aa + ab * c, 1.0 + aa + ab * s];
        let x = at([1.0, 1.0 + aa, 1.0 + aa, b0[0], b0[0] - bb * s]);
        pc.add(
            3.5,
            &species,
            &x,
            &at([1.0, 1.0, 1.0 + aa, b0[1], b0[1] + bb * c]),
        );
        pc
    }

    fn pressure(z: f64, z_std_error: f64) -> PressureReport {
        PressureReport {
            estimator: "collision virial",
            z,
            z_std_error,
            beta_p: 0.0,
            beta_p_std_error: 0.0,
            p: 0.0,
            area: 63.0,
            blocks: 16,
            block_time: 1.0,
            converged: true,
            series: Vec::new(),
            drift: None,
        }
    }

    /// g (10.1) with P_k = π dr²(2k + 1)/A, M_AA = 3, M_AB = 6, M_BB = 1; a
    /// contact value from one occupied fit bin is g there (the line through one
    /// point is flat: no bin correction); the contact theorem (10.3) sums over
    /// ordered pairs x_a x_b σ_ab² g_ab, per block for its error (two blocks: SE
    /// = half their difference).
    #[test]
    fn the_report_gives_each_pair_its_g_contact_value_and_the_contact_theorem() {
        let pc = two_snapshots();
        let rep = report(&pc, true, Some(&pressure(1.05, 0.02))).unwrap();
        let dr = rep.bin_width;
        assert!((dr - 0.012).abs() < 1e-15);
        assert!((rep.r_max - 291.0 * dr).abs() < 1e-12 && rep.r.len() == 291);
        assert!((rep.r[66] - 66.5 * dr).abs() < 1e-14);
        assert_eq!((rep.snapshots, rep.blocks), (2, 2));
        let who: Vec<(usize, usize)> = rep.pairs.iter().map(|p| (p.a, p.b)).collect();
        assert_eq!(who, [(0, 0), (0, 1), (1, 1)]);
        let close = |u: f64, v: f64| (u / v - 1.0).abs() < 1e-12;
        let p = |k: usize| std::f64::consts::PI * dr * dr * (2 * k + 1) as f64 / 63.0;
        // A–A in bin 52: 1 then 2 pairs of 3 → g 1/(3P), 2/(3P), pooled 1/(2P).
        let (g0, g1) = (1.0 / (3.0 * p(52)), 2.0 / (3.0 * p(52)));
        // (sigma, fit bins, bin, per-block contact values)
        let expected = [
            (0.6, 10, 52, [g0, g1]),
            (0.75, 12, 66, [1.0 / (6.0 * p(66)); 2]),
            (0.9, 15, 80, [1.0 / p(80); 2]),
        ];
        for (pr, (sigma, fit_bins, k, g)) in rep.pairs.iter().zip(expected) {
            let mean = 0.5 * (g[0] + g[1]);
            let se = 0.5 * (g[1] - g[0]);
            assert!((pr.sigma - sigma).abs() < 1e-15, "{pr:?}");
            assert_eq!(pr.g.len(), 291);
            assert!(close(pr.g[k], mean) && pr.g[k + 1] == 0.0 && pr.g[k - 1] == 0.0);
            assert!((pr.std_error[k] - se).abs() <= 1e-12 * mean && pr.std_error[k + 1] == 0.0);
            let c = pr.contact.as_ref().unwrap();
            assert_eq!(c.fit_bins, fit_bins, "{pr:?}");
            assert!(close(c.value, mean), "{c:?} vs {mean}");
            assert!(
                (c.std_error.unwrap() - se).abs() <= 1e-12 * mean,
                "{c:?} vs {se}"
            );
        }
        // Z = 1 + (π/2)(5/63) Σ x_a x_b σ² g over ordered pairs, x = 3/5, 2/5.
        let z = |gaa: f64| {
            let (xa, xb) = (0.6, 0.4);
            let s = xa * xa * 0.36 * gaa
                + 2.0 * xa * xb * 0.5625 * expected[1].3[0]
                + xb * xb * 0.81 * expected[2].3[0];
            1.0 + std::f64::consts::FRAC_PI_2 * 5.0 / 63.0 * s
        };
        let ct = rep.contact_theorem.unwrap();
        let (zs, se) = (z(0.5 * (g0 + g1)), 0.5 * (z(g1) - z(g0)));
        assert!(
            close(ct.z_structure, zs) && close(ct.z_structure_std_error, se),
            "{ct:?}"
        );
        assert_eq!((ct.z_virial, ct.z_virial_std_error), (1.05, 0.02));
        assert!(close(ct.difference, zs - 1.05));
        assert!(close(
            ct.difference_std_errors,
            (zs - 1.05) / (se * se + 0.0004).sqrt()
        ));
    }

    /// No contact theorem for a run with walls or inelastic (the caller's flag),
    /// without a pressure, or when a pair has no contact value (its fit range
    /// beyond r_max); no report at all without snapshots; a species of one disc
    /// has no pair with itself.
    #[test]
    fn the_contact_theorem_needs_every_contact_value_and_a_periodic_elastic_pressure() {
        let pc = two_snapshots();
        let p = pressure(1.05, 0.02);
        assert!(report(&pc, false, Some(&p))
            .unwrap()
            .contact_theorem
            .is_none());
        assert!(report(&pc, true, None).unwrap().contact_theorem.is_none());
        // B of radius 2: σ_BB = 4, fit range [4, 4.8] beyond r_max = 3.5.
        let sp = [Species::new(3, 0.3, 2.0), Species::new(2, 2.0, 1.0)];
        let mut big = PairCorrelation::new(&sp, &SimBox::periodic(9.0, 7.0), 0.0, 16.0);
        assert!(report(&big, true, Some(&p)).is_none());
        let x = [1.0, 1.63, 1.0, 1.0, 5.0];
        big.add(0.5, &[0, 0, 0, 1, 1], &x, &[1.0, 1.0, 1.6, 5.0, 5.0]);
        let rep = report(&big, true, Some(&p)).unwrap();
        // A–A has pairs near contact; A–B (σ = 2.3) none within [2.3, 2.76]: no
        // value rather than a NaN; B–B's fit range lies beyond r_max.
        let contacts: Vec<bool> = rep.pairs.iter().map(|p| p.contact.is_some()).collect();
        assert_eq!(contacts, [true, false, false]);
        assert!(rep.pairs[1]
            .contact_missing
            .as_ref()
            .unwrap()
            .contains("too few pairs"));
        assert!(rep.pairs[2]
            .contact_missing
            .as_ref()
            .unwrap()
            .contains("no bin"));
        assert!(rep.contact_theorem.is_none());
        // One disc of each species: only the A–B pair, which has its contact.
        let sp = [Species::new(1, 0.3, 2.0), Species::new(1, 0.45, 0.5)];
        let mut two = PairCorrelation::new(&sp, &SimBox::periodic(9.0, 7.0), 0.0, 16.0);
        two.add(0.5, &[0, 1], &[1.0, 1.798], &[1.0, 1.0]);
        // One time block: a contact value, but no error, so no theorem.
        let rep = report(&two, true, Some(&p)).unwrap();
        let c = rep.pairs[0].contact.as_ref().unwrap();
        assert!(c.std_error.is_none() && c.no_error.as_ref().unwrap().contains("1 time blocks"));
        assert!(rep.contact_theorem.is_none());
        two.add(8.5, &[0, 1], &[1.0, 1.0], &[1.0, 1.799]);
        let rep = report(&two, true, Some(&p)).unwrap();
        assert_eq!(
            rep.pairs.iter().map(|p| (p.a, p.b)).collect::<Vec<_>>(),
            [(0, 1)]
        );
        assert!(rep.contact_theorem.is_some());
        let sp = [Species::new(1, 0.3, 2.0)];
        let mut one = PairCorrelation::new(&sp, &SimBox::periodic(9.0, 7.0), 0.0, 16.0);
        one.add(0.5, &[0], &[1.0], &[1.0]);
        let rep = report(&one, true, Some(&p)).unwrap();
        assert!(rep.pairs.is_empty() && rep.contact_theorem.is_none());
    }

    /// g, the contact values and Z are numbers without units: the same run with
    /// every length 10⁻⁵ or 10⁵ times as large reports them unchanged, with the
    /// same fit bins (the fit range's edges have a tolerance relative to σ).
    #[test]
    fn the_report_does_not_depend_on_the_unit_of_length() {
        let p = pressure(1.05, 0.02);
        let one = report(&two_snapshots(), true, Some(&p)).unwrap();
        for l in [1e-5, 1e5] {
            let rep = report(&scaled_snapshots(l), true, Some(&p)).unwrap();
            assert!((rep.bin_width / (0.012 * l) - 1.0).abs() < 1e-14, "{l}");
            for (a, b) in rep.pairs.iter().zip(&one.pairs) {
                assert!((a.sigma / (b.sigma * l) - 1.0).abs() < 1e-14);
                for (u, v) in a.g.iter().zip(&b.g) {
                    assert!((u - v).abs() <= 1e-9 * v, "{l}: {u} vs {v}");
                }
                let (ca, cb) = (a.contact.as_ref().unwrap(), b.contact.as_ref().unwrap());
                assert_eq!(ca.fit_bins, cb.fit_bins, "{l}: {a:?}");
                assert!(
                    (ca.value / cb.value - 1.0).abs() < 1e-9,
                    "{l}: {ca:?} vs {cb:?}"
                );
            }
            let (za, zb) = (
                rep.contact_theorem.unwrap(),
                one.contact_theorem.as_ref().unwrap(),
            );
            assert!((za.z_structure / zb.z_structure - 1.0).abs() < 1e-9, "{l}");
        }
    }
}
