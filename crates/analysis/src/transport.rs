//! Transport coefficients from the collision log (physics.md §14). Every disc is
//! replayed from the first snapshot analysed, flight by flight; each pair
//! collision feeds the Helfand moments ([`Helfand`]) and the exact VACF
//! ([`ExactVacf`]), and later snapshots check the replay bit for bit.
//! [`Transport::report`] gives D (MSD and ∫VACF), η and λ (Einstein–Helfand and
//! Green–Kubo, e.g. η = lim Var[ΔG_xy(τ)]/(2 V kT τ), (14.4)) over one lag window with errors
//! from the spread over time segments, beside Enskog's values, the mode-coupling
//! tail and a verdict each (`transport_reliability.rs`). Only elastic, periodic
//! runs logging every collision qualify; lags scale with the collision time t_c
//! (Helfand every t_c/20, VACF 0.01–1000 t_c, window 10–100 t_c).

use carom_core::DVec2;

use super::helfand::Helfand;
use super::increment_correlator::RING;
use super::sonine::SONINE_FACTORS;
use super::transport_reliability::{estimate, judge, Halves, TRANSPORT_WINDOW};
use super::transport_report::{EnskogTransport, HelfandReport, SpeciesTransport, TransportReport};
use super::transport_theory::{chi_from_z, enskog, tail_amplitude};
use super::vacf_exact::{ExactVacf, Replayed, VacfSums};
use super::RunDescription;

/// Time segments for the standard errors.
pub const TRANSPORT_SEGMENTS: usize = 10;
/// Live VACF origins at most.
const ORIGINS: usize = 32;
/// Live VACF disc-origins aimed at (fewer origins for larger N, at least 2): each
/// reading costs N, and with N large one origin already averages over many discs.
const ORIGIN_DISCS: usize = 131_072;
/// Helfand samples per mean collision time.
const SAMPLES_PER_COLLISION_TIME: f64 = 20.0;
/// Bytes of VACF origins at most (each keeps v and X of every disc: 32 bytes).
const ORIGIN_BYTES: usize = 1 << 29;

/// The replayed run and its accumulators.
#[derive(Debug, Clone)]
pub(super) struct Transport {
    discs: Vec<Replayed>,
    species: Vec<u16>,
    v_cm: DVec2,
    kt: f64,
    t_start: f64,
    t_now: f64,
    /// The last time an origin may start (so that every origin runs to τ_max).
    origin_stop: f64,
    pairs: u64,
    area: f64,
    checked: u64,
    mismatched: u64,
    helfand: Helfand,
    vacf: ExactVacf,
}

impl Transport {
    /// Starts at a snapshot at time `t` (species index and velocity of every
    /// disc) of `run`, which ends at `run.t_end`; `t_c` is the expected time
    /// between a disc's collisions. `None` when the run does not qualify.
    pub(super) fn start(
        run: &RunDescription,
        t: f64,
        species_of: &[u16],
        (vx, vy): (&[f64], &[f64]),
        t_c: f64,
    ) -> Option<Self> {
        let periodic = run.sim_box.boundary.iter().all(|b| b.is_periodic());
        let n = species_of.len();
        if !periodic
            || !run.restitution.is_elastic()
            || run.collision_stride != 1
            || run.totals_from_thermo
            || n < 2
            || !(t_c.is_finite() && t_c > 0.0)
            || t >= run.t_end
        {
            return None;
        }
        let mass: Vec<f64> = species_of
            .iter()
            .map(|&s| run.species[s as usize].mass)
            .collect();
        let radius: Vec<f64> = species_of
            .iter()
            .map(|&s| run.species[s as usize].radius)
            .collect();
        let v: Vec<DVec2> = vx.iter().zip(vy).map(|(&x, &y)| DVec2::new(x, y)).collect();
        let total_mass: f64 = mass.iter().sum();
        let v_cm = mass.iter().zip(&v).map(|(&m, &v)| m * v).sum::<DVec2>() / total_mass;
        let kinetic: f64 = mass
            .iter()
            .zip(&v)
            .map(|(&m, &v)| 0.5 * m * (v - v_cm).length_squared())
            .sum();
        let segment = (run.t_end - t) / TRANSPORT_SEGMENTS as f64;
        let segments = (TRANSPORT_SEGMENTS, segment);
        let dt = t_c / SAMPLES_PER_COLLISION_TIME;
        let tau_max = (1000.0 * t_c).min(segment / 2.0);
        // Helfand lags reach (p − 1)·2^(levels−1)·Δ ≥ τ_max, as the VACF's do.
        let levels =
            ((tau_max / ((RING - 1) as f64 * dt)).log2().ceil().max(0.0) as usize + 1).min(48);
        let w = mass.iter().zip(&v).map(|(&m, &v)| (m, v - v_cm));
        let helfand = Helfand::new(t, w, dt, levels, segments);
        let origins = (ORIGIN_DISCS / n)
            .clamp(2, ORIGINS)
            .min(ORIGIN_BYTES / (32 * n))
            .max(1);
        let vacf = ExactVacf::new(
            t,
            (0.01 * t_c, tau_max),
            origins,
            run.species.len(),
            segments,
        );
        let discs = (0..n)
            .map(|i| Replayed {
                v: v[i],
                x: DVec2::ZERO,
                t,
                mass: mass[i],
                radius: radius[i],
            })
            .collect();
        Some(Transport {
            discs,
            species: species_of.to_vec(),
            v_cm,
            kt: kinetic / (n - 1) as f64,
            t_start: t,
            t_now: t,
            origin_stop: t.max(run.t_end - tau_max),
            pairs: 0,
            area: run.sim_box.area(),
            checked: 0,
            mismatched: 0,
            helfand,
            vacf,
        })
    }

    /// Brings the accumulators up to time `t` (readings due at `t` first).
    fn advance(&mut self, t: f64) {
        self.helfand.advance(t);
        if self.vacf.next_event() <= t {
            self.vacf
                .advance(t, self.origin_stop, &self.discs, &self.species);
        }
        self.t_now = t;
    }

    /// A pair collision of discs `i` and `j` at time `t` with unit normal `n`
    /// from i to j and the velocities after.
    pub(super) fn pair(&mut self, t: f64, (i, j): (usize, usize), n: DVec2, after: [DVec2; 2]) {
        self.advance(t);
        let (a, b) = (self.discs[i], self.discs[j]);
        let r = -(a.radius + b.radius) * n;
        let c = self.v_cm;
        self.helfand.collide(
            (a.mass, b.mass),
            r,
            (a.v - c, after[0] - c),
            (b.v - c, after[1] - c),
        );
        for (k, v) in [(i, after[0]), (j, after[1])] {
            let d = &mut self.discs[k];
            d.x = d.x_at(t);
            d.t = t;
            d.v = v;
        }
        self.pairs += 1;
    }

    /// The mean time between a disc's pair collisions, t_c = N T/(2 N_pair).
    fn collision_time(&self) -> f64 {
        let elapsed = self.t_now - self.t_start;
        self.discs.len() as f64 * elapsed / (2.0 * self.pairs as f64)
    }

    /// Pair collisions replayed.
    pub(super) fn pairs(&self) -> u64 {
        self.pairs
    }

    /// A later snapshot at time `t`: its velocities must be the replayed ones bit
    /// for bit; the kinetic fluxes are summed afresh.
    pub(super) fn check(&mut self, t: f64, (vx, vy): (&[f64], &[f64])) {
        self.advance(t);
        self.checked += 1;
        let same = vx.len() == self.discs.len()
            && (self.discs.iter().zip(vx.iter().zip(vy)))
                .all(|(d, (&x, &y))| d.v.x == x && d.v.y == y);
        if !same {
            self.mismatched += 1;
        }
        let c = self.v_cm;
        self.helfand
            .reset_flux(self.discs.iter().map(|d| (d.mass, d.v - c)));
    }

    /// The report; `z` is the measured compressibility factor (for Enskog's χ),
    /// `phi` the packing fraction, `t_end` the end of the log.
    pub(super) fn report(
        mut self,
        t_end: f64,
        z: Option<f64>,
        phi: f64,
    ) -> Option<TransportReport> {
        self.advance(t_end);
        let n = self.discs.len();
        let elapsed = self.t_now - self.t_start;
        if self.pairs == 0 || elapsed <= 0.0 {
            return None;
        }
        let t_c = self.collision_time();
        let tau_b_max = self.vacf.lags.last().copied().unwrap_or(0.0);
        let tau_b = (TRANSPORT_WINDOW[1] * t_c).min(tau_b_max);
        let tau_a = (TRANSPORT_WINDOW[0] * t_c).min(tau_b / 10.0);
        let window_tc = [tau_a / t_c, tau_b / t_c];
        let viscosity = self.helfand_report("shear viscosity", [0, 1], 1, (tau_a, tau_b))?;
        let counts = species_counts(&self.species);
        let one_species = counts.iter().filter(|&&c| c > 0).count() == 1;
        let thermal_conductivity = if one_species {
            self.helfand_report("thermal conductivity", [2, 3], 2, (tau_a, tau_b))
        } else {
            None
        };
        let density = n as f64 / self.area;
        let m = self.discs[0].mass;
        let species = (0..counts.len())
            .filter(|&s| counts[s] > 0)
            .map(|s| {
                let mut r = self.species_report(s, (tau_a, tau_b), t_c);
                if one_species {
                    let (d, eta) = (r.diffusion_vacf, viscosity.value_helfand);
                    let a = tail_amplitude(density, m, d.value, eta.value);
                    // A = 1/[8π n (D + η/(nm))]: δA = 8π n A² √(δD² + (δη/(nm))²).
                    let spread = d.std_error.hypot(eta.std_error / (density * m));
                    r.tail_amplitude_theory = Some(a);
                    r.tail_amplitude_theory_std_error =
                        Some(8.0 * std::f64::consts::PI * density * a * a * spread);
                }
                r
            })
            .collect();
        let enskog = match (one_species, z) {
            (true, Some(z)) if phi > 0.0 => {
                let chi = chi_from_z(z, phi);
                let sigma = 2.0 * self.discs[0].radius;
                let e = enskog(sigma, m, density, self.kt, [phi, chi], SONINE_FACTORS);
                Some(EnskogTransport {
                    chi,
                    sonine_factors: [SONINE_FACTORS.d, SONINE_FACTORS.eta, SONINE_FACTORS.lambda],
                    diffusion: e.d,
                    viscosity: e.eta,
                    thermal_conductivity: e.lambda,
                })
            }
            _ => None,
        };
        Some(TransportReport {
            n,
            collision_time: t_c,
            kt: self.kt,
            window: [tau_a, tau_b],
            window_collision_times: window_tc,
            documented_window_collision_times: TRANSPORT_WINDOW,
            segments: TRANSPORT_SEGMENTS,
            snapshots_checked: self.checked,
            snapshots_mismatched: self.mismatched,
            species,
            viscosity,
            thermal_conductivity,
            enskog,
        })
    }

    /// Einstein–Helfand and Green–Kubo for the moments `which` (averaged), with
    /// kT to the power `power` in the denominator, over the window.
    fn helfand_report(
        &self,
        quantity: &'static str,
        which: [usize; 2],
        power: i32,
        (tau_a, tau_b): (f64, f64),
    ) -> Option<HelfandReport> {
        let lags = self.helfand.lags();
        let scale = 1.0 / (self.area * self.kt.powi(power));
        let corr = &self.helfand.correlators;
        let segments = corr[0].segments();
        // Var[ΔG] and Cov[J, J] per lag, from the sums of `part` (None = all).
        let curves = |part: Option<usize>| -> (Vec<f64>, Vec<f64>) {
            let mut var = vec![0.0; lags.len()];
            let mut cov = vec![0.0; lags.len()];
            for (q, &lag) in lags.iter().enumerate() {
                for &k in &which {
                    let s = match part {
                        Some(p) => corr[k].sums(lag, p),
                        None => corr[k].total(lag),
                    };
                    var[q] += s.increment_mean_square().unwrap_or(f64::NAN) / 2.0;
                    cov[q] += s.flux_product().unwrap_or(f64::NAN) / 2.0;
                }
            }
            if !lags.is_empty() {
                var[0] = 0.0;
            }
            (var, cov)
        };
        let taus: Vec<f64> = lags.iter().map(|l| l.tau).collect();
        let a = nearest(&taus, tau_a);
        let b = nearest(&taus, tau_b);
        if b <= a {
            return None;
        }
        let m = nearest(&taus, (taus[a] * taus[b]).sqrt());
        // The two estimates over the window from one set of curves, and the
        // Green–Kubo running integral's means over the window's halves.
        let values = |(var, cov): &(Vec<f64>, Vec<f64>)| -> (f64, f64, [f64; 2]) {
            let helfand = (var[b] - var[a]) / (2.0 * (taus[b] - taus[a])) * scale;
            let gk = running_integral(&taus, cov);
            let mean_gk = window_mean(&taus, &gk, a, b) * scale;
            let halves = [
                window_mean(&taus, &gk, a, m) * scale,
                window_mean(&taus, &gk, m, b) * scale,
            ];
            (helfand, mean_gk, halves)
        };
        let all = curves(None);
        let (h, g, halves) = values(&all);
        let parts: Vec<_> = (0..segments).map(|p| values(&curves(Some(p)))).collect();
        let pick = |f: fn(&(f64, f64, [f64; 2])) -> f64| -> Vec<f64> {
            parts.iter().map(f).filter(|x| x.is_finite()).collect()
        };
        let halves = (m > a && b > m).then(|| Halves {
            first: halves[0],
            second: halves[1],
            difference_std_error: estimate(0.0, &pick(|p| p.2[1] - p.2[0])).std_error,
            mean: g,
        });
        let t_c = self.collision_time();
        let reliability = judge([taus[a] / t_c, taus[b] / t_c], halves);
        let gk_curve = running_integral(&taus, &all.1);
        Some(HelfandReport {
            quantity,
            helfand: taus
                .iter()
                .zip(&all.0)
                .map(|(&t, &v)| {
                    if t > 0.0 {
                        v / (2.0 * t) * scale
                    } else {
                        f64::NAN
                    }
                })
                .collect(),
            green_kubo: gk_curve.iter().map(|g| g * scale).collect(),
            lags: taus,
            helfand_moment: all.0,
            value_helfand: estimate(h, &pick(|p| p.0)),
            value_green_kubo: estimate(g, &pick(|p| p.1)),
            difference: estimate(h - g, &pick(|p| p.0 - p.1)),
            reliability,
        })
    }

    /// One species' exact VACF, MSD and D.
    fn species_report(&self, s: usize, (tau_a, tau_b): (f64, f64), t_c: f64) -> SpeciesTransport {
        let lags = &self.vacf.lags;
        let sums = &self.vacf.sums;
        let segments = sums[0][s].len();
        let total = |q: usize| -> VacfSums {
            let mut t = VacfSums::default();
            for p in &sums[q][s] {
                t.count += p.count;
                t.c += p.c;
                t.integral += p.integral;
                t.msd += p.msd;
            }
            t
        };
        let a = nearest(lags, tau_a);
        let b = nearest(lags, tau_b);
        let m = nearest(lags, (lags[a] * lags[b]).sqrt());
        // (C/C0 per lag, MSD, D(τ)) from per-lag sums.
        let curves = |get: &dyn Fn(usize) -> VacfSums| {
            let c0 = get(0).c / get(0).count;
            let mut vacf = Vec::new();
            let mut msd = Vec::new();
            let mut d = Vec::new();
            for q in 0..lags.len() {
                let t = get(q);
                vacf.push(t.c / t.count / c0);
                msd.push(t.msd / t.count);
                d.push(0.5 * t.integral / t.count);
            }
            (c0, vacf, msd, d)
        };
        let window = |(_, vacf, msd, d): &(f64, Vec<f64>, Vec<f64>, Vec<f64>)| {
            let d_msd = (msd[b] - msd[a]) / (4.0 * (lags[b] - lags[a]));
            let d_vacf = window_mean(lags, d, a, b);
            let tail: Vec<f64> = (a..lags.len()).map(|q| lags[q] * vacf[q]).collect();
            let tail = tail.iter().sum::<f64>() / tail.len() as f64;
            let halves = if m > a && b > m {
                window_mean(lags, d, m, b) - window_mean(lags, d, a, m)
            } else {
                f64::NAN
            };
            (d_msd, d_vacf, tail, halves)
        };
        let all = curves(&total);
        let parts: Vec<_> = (0..segments)
            .filter(|&p| sums[lags.len() - 1][s][p].count > 0.0)
            .map(|p| curves(&|q| sums[q][s][p]))
            .collect();
        let per: Vec<(f64, f64, f64, f64)> = parts.iter().map(window).collect();
        let (d_msd, d_vacf, tail, _) = window(&all);
        let vacf_std_error = (0..lags.len())
            .map(|q| {
                estimate(all.1[q], &parts.iter().map(|p| p.1[q]).collect::<Vec<_>>()).std_error
            })
            .collect();
        let col = |f: fn(&(f64, f64, f64, f64)) -> f64| per.iter().map(f).collect::<Vec<f64>>();
        let window_tc = [lags[a] / t_c, lags[b] / t_c];
        let halves = (m > a && b > m).then(|| Halves {
            first: window_mean(lags, &all.3, a, m),
            second: window_mean(lags, &all.3, m, b),
            difference_std_error: estimate(0.0, &col(|p| p.3)).std_error,
            mean: d_vacf,
        });
        SpeciesTransport {
            species: s,
            origins: self.vacf.started,
            lags: lags.clone(),
            vacf: all.1.clone(),
            vacf_std_error,
            vacf_zero: all.0,
            msd: all.2.clone(),
            running_diffusion: all.3.clone(),
            diffusion_msd: estimate(d_msd, &col(|p| p.0)),
            diffusion_vacf: estimate(d_vacf, &col(|p| p.1)),
            difference: estimate(d_msd - d_vacf, &col(|p| p.0 - p.1)),
            diffusion_reliability: judge(window_tc, halves),
            tail_amplitude: (b > a).then(|| estimate(tail, &col(|p| p.2))),
            tail_amplitude_reliability: judge(window_tc, None),
            tail_amplitude_theory: None,
            tail_amplitude_theory_std_error: None,
        }
    }
}

/// Discs per species index.
fn species_counts(species: &[u16]) -> Vec<usize> {
    let mut c = vec![0; species.iter().map(|&s| s as usize + 1).max().unwrap_or(0)];
    for &s in species {
        c[s as usize] += 1;
    }
    c
}

/// Index of the value of sorted `xs` nearest `x`.
fn nearest(xs: &[f64], x: f64) -> usize {
    (0..xs.len())
        .min_by(|&p, &q| (xs[p] - x).abs().total_cmp(&(xs[q] - x).abs()))
        .unwrap_or(0)
}

/// ∫₀^τ f by the trapezoid rule over the points (τ_q, f_q), at every τ_q.
fn running_integral(taus: &[f64], f: &[f64]) -> Vec<f64> {
    let mut out = vec![0.0; taus.len()];
    for q in 1..taus.len() {
        out[q] = out[q - 1] + 0.5 * (f[q] + f[q - 1]) * (taus[q] - taus[q - 1]);
    }
    out
}

/// The mean of f over [τ_a, τ_b] (indices a < b) by the trapezoid rule.
fn window_mean(taus: &[f64], f: &[f64], a: usize, b: usize) -> f64 {
    let integral = running_integral(&taus[a..=b], &f[a..=b]);
    integral[integral.len() - 1] / (taus[b] - taus[a])
}

#[cfg(test)]
mod tests {
    use super::*;
    use carom_core::{Restitution, SimBox};

    fn run() -> RunDescription {
        RunDescription::for_tests()
    }

    /// Walls, inelastic collisions, a thinned collision log or running totals
    /// instead of collisions: no transport.
    #[test]
    fn only_elastic_periodic_complete_logs_qualify() {
        let v = ([1.0, -1.0].as_slice(), [0.5, -0.5].as_slice());
        assert!(Transport::start(&run(), 0.0, &[0, 0], v, 1.0).is_some());
        let mut r = run();
        r.sim_box = SimBox::walled(10.0, 10.0, 1.0);
        assert!(Transport::start(&r, 0.0, &[0, 0], v, 1.0).is_none());
        let mut r = run();
        r.restitution = Restitution::Normal(0.9);
        assert!(Transport::start(&r, 0.0, &[0, 0], v, 1.0).is_none());
        let mut r = run();
        r.collision_stride = 2;
        assert!(Transport::start(&r, 0.0, &[0, 0], v, 1.0).is_none());
        let mut r = run();
        r.totals_from_thermo = true;
        assert!(Transport::start(&r, 0.0, &[0, 0], v, 1.0).is_none());
        assert!(Transport::start(&run(), 10.0, &[0, 0], v, 1.0).is_none());
    }

    /// kT in the centre-of-mass frame: velocities (3, 1) and (1, −1) of unit
    /// mass move at V = (2, 0); relative velocities (±1, ±1) give K = 2 and
    /// kT = K/(N − 1) = 2. A collision replayed changes the velocities; a later
    /// snapshot with those velocities matches, one with others does not.
    #[test]
    fn replay_is_checked_against_snapshots() {
        let vx = [3.0, 1.0];
        let vy = [1.0, -1.0];
        let mut t = Transport::start(&run(), 0.0, &[0, 0], (&vx, &vy), 1.0).unwrap();
        assert_eq!(t.kt, 2.0);
        // Discs meet along x (normal from 0 to 1 = (1, 0)) and swap v_x.
        let after = [DVec2::new(1.0, 1.0), DVec2::new(3.0, -1.0)];
        t.pair(1.0, (0, 1), DVec2::X, after);
        t.check(2.0, (&[1.0, 3.0], &[1.0, -1.0]));
        assert_eq!((t.checked, t.mismatched), (1, 0));
        t.check(3.0, (&[1.0, 3.0], &[1.0, -1.5]));
        assert_eq!((t.checked, t.mismatched), (2, 1));
        // Disc 0 flew (3, 1) for 1, then (1, 1) for 2: displacement (5, 3) at 3.
        assert_eq!(t.discs[0].x_at(3.0), DVec2::new(5.0, 3.0));
    }
}
