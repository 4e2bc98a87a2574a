//! Equation of state Z(η) and collision rate (cases 1 and 2 of the validation suite).
//! The suite's tolerances, references and the command that runs it: `super`.

use super::{engine, kt, li2022, mono, periodic_spec, psi6};
use crate::stats_common;
use crate::stats_common::{est, Est};
use crate::validation_common::{fmt_se, Check, Fragment, Row};
use carom_analysis::kolafa_rottner;
use carom_engine::{EngineParams, Velocities};
use std::f64::consts::PI;
use std::time::Instant;

// ===========================================================================
// Case 1 + 2: equation of state and collision rate
// ===========================================================================

struct EosResult {
    n: usize,
    kt: f64,
    z: Est,
    z_naive: f64,
    z_halves: [Est; 2],
    omega: Est,
    /// (Z − 1) − (√π/4) ω τ0 per bin, blocked.
    enskog_diff: Est,
    pairs: u64,
    time: f64,
    t_eq: f64,
    psi6: [f64; 3],
    seconds: f64,
}

/// Equilibrate `n` discs at `eta` for `eq_collisions` pair collisions, then measure
/// for `collisions` more in time bins of ≈ 2 collisions per disc.
fn eos_run(n: usize, eta: f64, seed: u64, eq_collisions: u64, collisions: u64) -> EosResult {
    let wall = Instant::now();
    let spec = periodic_spec(mono(n), eta, seed, Velocities::MaxwellBoltzmann);
    let mut e = engine(&spec, EngineParams::default());
    let psi_start = psi6(&e.state());
    e.run_collisions(eq_collisions).expect("equilibration");
    let t_eq = e.now();
    let psi_eq = psi6(&e.state());
    let kt0 = kt(&e);
    let nf = n as f64;
    // Bins of ≈ 2 collisions per disc, from the equilibration's rate.
    let rate = eq_collisions as f64 / t_eq; // pair collisions per unit time
    let bin = nf / rate;
    let bins = ((collisions as f64 / rate) / bin).round().max(64.0) as usize;
    let (mut w_prev, mut p_prev) = (e.stats().virial_sum, e.stats().pair_collisions);
    let (mut z, mut omega, mut diff) = (
        Vec::with_capacity(bins),
        Vec::with_capacity(bins),
        Vec::with_capacity(bins),
    );
    let c = PI.sqrt() / 4.0;
    let tau0 = 1.0 * (1.0 / kt0).sqrt(); // σ √(m/kT)
    for k in 1..=bins {
        e.run_until(t_eq + k as f64 * bin).expect("production");
        let s = e.stats();
        let dw = s.virial_sum - w_prev;
        let dp = (s.pair_collisions - p_prev) as f64;
        (w_prev, p_prev) = (s.virial_sum, s.pair_collisions);
        // βPA/N = 1 + W/(N kT), W = Σ r·Δp / (2 t)   (physics.md §5)
        let zk = 1.0 + dw / (2.0 * bin) / (nf * kt0);
        let wk = 2.0 * dp / (nf * bin);
        z.push(zk);
        omega.push(wk);
        diff.push((zk - 1.0) - c * wk * tau0);
    }
    let kt1 = kt(&e);
    assert!(
        ((kt1 - kt0) / kt0).abs() < 1e-10,
        "energy drift in an elastic run: kT {kt0} → {kt1}"
    );
    let half = z.len() / 2;
    let zest = est(&z);
    // The naive estimator PA = K + W with K = (N−1) kT: βPA/N = (N−1)/N + W/(N kT).
    let z_naive = zest.mean - 1.0 / nf;
    EosResult {
        n,
        kt: kt0,
        z: zest,
        z_naive,
        z_halves: [est(&z[..half]), est(&z[half..])],
        omega: est(&omega),
        enskog_diff: est(&diff),
        pairs: e.stats().pair_collisions,
        time: e.now(),
        t_eq,
        psi6: [psi_start, psi_eq, psi6(&e.state())],
        seconds: wall.elapsed().as_secs_f64(),
    }
}

/// The NVE (zero-momentum microcanonical) collision rate exceeds the canonical one
/// by the factor ⟨|x|⟩/(√(2/π) ⟨x²⟩^½) for one coordinate x of a point uniform on a
/// sphere in D = f dimensions: √D Γ(D/2) / (√π Γ((D+1)/2)) / √(2/π) ≈ 1 + 1/(4D).
/// The virial is exact with kT = 2K/f (it depends on ⟨x²⟩ only), so in NVE
/// (Z − 1) − (√π/4) ω τ0 = −(Z − 1)(factor − 1) / factor.
fn nve_rate_factor(f: usize) -> f64 {
    use statrs::function::gamma::ln_gamma;
    let d = f as f64;
    (0.5 * d.ln() + ln_gamma(d / 2.0) - ln_gamma((d + 1.0) / 2.0)).exp()
        / PI.sqrt()
        / (2.0 / PI).sqrt()
}

fn eos_rows(frag: &mut Fragment, label: &str, r: &EosResult, reference: (f64, f64)) {
    frag.row(
        Row::new(format!("Z, {label}"), r.z.mean, r.z.se)
            .reference(reference.0, reference.1)
            .check(Check::Sigma(3.0)),
    );
    // Equilibration: the two halves of the production run agree.
    let [h0, h1] = &r.z_halves;
    let d = stats_common::deviation(h0.mean, h0.se, h1.mean, h1.se).unwrap_or(0.0);
    frag.row(
        Row::new(
            format!("Z drift, 1st − 2nd half of production (SE), {label}"),
            d,
            0.0,
        )
        .check(Check::AtMost(4.0)),
    );
    // Collision rate: Z − 1 = (√π/4) ω τ0 within 0.1 % (relative to Z − 1).
    let rel = r.enskog_diff.mean / (r.z.mean - 1.0);
    let rel_se = r.enskog_diff.se / (r.z.mean - 1.0);
    frag.row(
        Row::new(format!("[(Z−1) − (√π/4)ωτ0]/(Z−1), {label}"), rel, rel_se)
            .reference(0.0, 0.0)
            .check(Check::Abs(1e-3)),
    );
    let factor = nve_rate_factor(2 * r.n - 2);
    let nve = -(factor - 1.0) / factor;
    frag.note(format!(
        "{label}: N = {}, {} pair collisions in all, equilibration t = {:.1} τ0, \
         production t = {:.1} τ0, kT = {:.12}, {:.1} s. Z = {} (blocking {}), halves {} and {}; \
         the naive PA = K + W estimator would give {:.5}. ω τ0 = {}. \
         Enskog relative difference {:+.2e} ± {:.1e}; expected NVE offset {:+.2e} \
         (microcanonical ⟨|g_n|⟩, see nve_rate_factor). |Ψ6| start {:.3}, after equilibration {:.3}, end {:.3}.",
        r.n,
        r.pairs,
        r.t_eq,
        r.time - r.t_eq,
        r.kt,
        r.seconds,
        fmt_se(r.z.mean, r.z.se),
        if r.z.converged { "converged" } else { "NOT converged: SE is a lower bound" },
        fmt_se(r.z_halves[0].mean, r.z_halves[0].se),
        fmt_se(r.z_halves[1].mean, r.z_halves[1].se),
        r.z_naive,
        fmt_se(r.omega.mean * (1.0 / r.kt).sqrt(), r.omega.se * (1.0 / r.kt).sqrt()),
        rel,
        rel_se,
        nve,
        r.psi6[0],
        r.psi6[1],
        r.psi6[2],
    ));
}

/// Z(η) in the fluid against Kolafa–Rottner; `scale` multiplies the run lengths.
fn eos_fluid(key: &'static str, title: &str, etas: &[f64], scale: f64) {
    let mut frag = Fragment::new(key, title);
    for (k, &eta) in etas.iter().enumerate() {
        let n = 1024;
        // ≈ 100 collisions per disc to melt the lattice and equilibrate.
        let r = eos_run(
            n,
            eta,
            11 + k as u64,
            (50.0 * n as f64) as u64,
            (scale * 1e7) as u64,
        );
        eos_rows(
            &mut frag,
            &format!("η = {eta}"),
            &r,
            kolafa_rottner(eta).expect("η in the physics.md §7 table"),
        );
    }
    frag.note(
        "Reference: Kolafa–Rottner fit (physics.md §7); ± is the spread of other fits, \
         finite-size effects < 0.05 % for N ≥ 10³. Estimator βPA/N = 1 + W/(N kT), \
         kT = 2K/(2N − 2) (physics.md §5); SE from the blocking analysis of per-bin Z \
         (bins of ≈ 2 collisions per disc).",
    );
    frag.finish();
}

/// 10⁷ collisions: the collision-rate check's band (± 0.1 %) must be several standard
/// errors wide. At 3·10⁶ collisions (SE 3.7·10⁻⁴) it was 2.7 SE, and a change of
/// rounding alone moved the value from −0.0002 to −0.0011 (the long case, with its
/// SE of 10⁻⁴, stayed at the expected NVE offset).
#[test]
fn case1_eos_fluid_short() {
    eos_fluid(
        "1a-eos-fluid-short",
        "1/2 EOS + Enskog, fluid (short)",
        &[0.4],
        1.0,
    );
}

/// The dense regime on every commit (issue 39 item 5): η = 0.6, N = 1024, 10⁷
/// collisions after 50 per disc of equilibration from the lattice, against
/// Kolafa–Rottner 6.4553 ± 0.0034 within 3 combined SE (measured SE ≈ 0.002), with
/// the drift between the production halves within 4 SE as the equilibration check.
#[test]
fn case1_eos_dense_short() {
    eos_fluid(
        "1a-eos-dense-short",
        "1/2 EOS + Enskog, dense fluid (short)",
        &[0.6],
        1.0,
    );
}

#[test]
#[ignore = "long: ≈ 2 min (4 × 4·10⁷ collisions)"]
fn case1_eos_fluid() {
    eos_fluid(
        "1b-eos-fluid",
        "1/2 EOS + Enskog, fluid",
        &[0.2, 0.4, 0.5, 0.6],
        4.0,
    );
}

#[test]
#[ignore = "long: ≈ 8 min (3 × 2.2·10⁸ collisions)"]
fn case1_eos_dense_n870() {
    let mut frag = Fragment::new("1c-eos-dense", "1/2 EOS + Enskog, N = 870 dense");
    for (k, &eta) in [0.670, 0.680, 0.690].iter().enumerate() {
        let n = 870;
        let (bp, err) = li2022(eta);
        // Z = βPd² π/(4η): the CSV's βPd² and its error as Z.
        let zf = PI / (4.0 * eta);
        // Equilibrate 2·10⁷ collisions (≈ 2300 τ0, ≈ 4.6·10⁴ collisions per disc).
        let r = eos_run(n, eta, 21 + k as u64, 20_000_000, 200_000_000);
        eos_rows(&mut frag, &format!("η = {eta}"), &r, (bp * zf, err * zf));
        frag.row(
            Row::new(
                format!("naive Z = (N−1)/N + W/(NkT), η = {eta}"),
                r.z_naive,
                r.z.se,
            )
            .reference(bp * zf, err * zf),
        );
        frag.row(Row::new(format!("|Ψ6| at end, η = {eta}"), r.psi6[2], 0.0));
    }
    frag.note(
        "Reference: Li et al., J. Chem. Phys. 157, 234111 (2022), event-chain Monte Carlo, \
         N = 870, square periodic box, Z = βPd² π/(4η). Start: the lattice of \
         `Placement::Lattice`; no compression exists in the engine, so the runs equilibrate \
         for 2·10⁷ collisions and the pressure drift (first vs second half of production, \
         in SE) and the hexatic order |Ψ6| show whether the start has melted. The row \
         'naive Z' uses PA = K + W with K = (N−1)kT — it is 1/N lower, the finite-N \
         effect physics.md §5 warns about; at this precision it is informative, not judged.",
    );
    frag.finish();
}
