//! The Helfand moments of shear stress and heat (physics.md §14.2), exact along
//! the collision log. Between collisions each moment grows at its kinetic flux,
//! during a collision of i and j it jumps by the collisional transfer:
//!
//!   G_xy  = ∫ Σ m w_x w_y dt            + Σ r_ij,x Δp_i,y
//!   G_N   = ∫ ½ Σ m (w_x² − w_y²) dt    + Σ ½ (r_ij,x Δp_i,x − r_ij,y Δp_i,y)
//!   G_q,a = ∫ Σ e w_a dt                + Σ r_ij,a Δe_i      (a = x, y)
//!
//! with w = v − V_cm, e = ½ m |w|², and r_ij = r_i − r_j = −σ_ij n̂ the contact
//! vector by the minimum image (so the moments need no positions). G_N is the
//! shear stress of axes turned by 45°, a second estimate of η. The moments are
//! sampled every Δ into [`IncrementCorrelator`]s; η = Var[ΔG]/(2 V kT τ) and
//! λ = Var[ΔG_q]/(2 V kT² τ) at long τ, and Green–Kubo from the same samples.

use carom_core::DVec2;

use super::increment_correlator::{IncrementCorrelator, Lag};

/// Which moment: shear xy, shear (xx − yy)/2, heat x, heat y.
pub(super) const MOMENTS: usize = 4;

/// The kinetic fluxes of one disc of mass `m` with velocity `w` (centre-of-mass
/// frame), in the order of the moments.
fn kinetic(m: f64, w: DVec2) -> [f64; MOMENTS] {
    let e = 0.5 * m * w.length_squared();
    [
        m * w.x * w.y,
        0.5 * m * (w.x * w.x - w.y * w.y),
        e * w.x,
        e * w.y,
    ]
}

/// The Helfand moments along a run and their correlators.
#[derive(Debug, Clone)]
pub(super) struct Helfand {
    /// Σ of the kinetic fluxes over all discs.
    flux: [f64; MOMENTS],
    /// The moments at `t`.
    g: [f64; MOMENTS],
    t: f64,
    t0: f64,
    dt: f64,
    samples: u64,
    segment_length: f64,
    pub(super) correlators: Vec<IncrementCorrelator>,
}

impl Helfand {
    /// Moments from time `t0` (all zero there), for discs of masses and
    /// centre-of-mass-frame velocities `w`; samples `dt` apart, `levels` levels,
    /// `segments` segments of `segment_length`.
    pub(super) fn new(
        t0: f64,
        w: impl Iterator<Item = (f64, DVec2)>,
        dt: f64,
        levels: usize,
        (segments, segment_length): (usize, f64),
    ) -> Self {
        let mut h = Helfand {
            flux: [0.0; MOMENTS],
            g: [0.0; MOMENTS],
            t: t0,
            t0,
            dt,
            samples: 0,
            segment_length,
            correlators: vec![IncrementCorrelator::new(dt, levels, segments); MOMENTS],
        };
        h.reset_flux(w);
        for c in &mut h.correlators {
            c.push(0.0, 0);
        }
        h
    }

    /// Recomputes the kinetic fluxes from scratch (at a snapshot, so that rounding
    /// of the running sums does not accumulate).
    pub(super) fn reset_flux(&mut self, w: impl Iterator<Item = (f64, DVec2)>) {
        self.flux = [0.0; MOMENTS];
        for (m, w) in w {
            for (f, k) in self.flux.iter_mut().zip(kinetic(m, w)) {
                *f += k;
            }
        }
    }

    /// Lets the moments grow at their fluxes up to time `t`, sampling on the way
    /// (a sample at exactly `t` comes before a collision at `t`).
    pub(super) fn advance(&mut self, t: f64) {
        loop {
            let next = self.t0 + (self.samples + 1) as f64 * self.dt;
            if next > t {
                break;
            }
            let segment = ((next - self.t0) / self.segment_length) as usize;
            for k in 0..MOMENTS {
                let g = self.g[k] + self.flux[k] * (next - self.t);
                self.correlators[k].push(g, segment);
            }
            self.samples += 1;
        }
        for k in 0..MOMENTS {
            self.g[k] += self.flux[k] * (t - self.t);
        }
        self.t = t;
    }

    /// A pair collision at the current time: discs of masses `mi`, `mj`, contact
    /// vector `r` = r_i − r_j, centre-of-mass-frame velocities before and after.
    pub(super) fn collide(
        &mut self,
        (mi, mj): (f64, f64),
        r: DVec2,
        (wi, wi_after): (DVec2, DVec2),
        (wj, wj_after): (DVec2, DVec2),
    ) {
        let dp = mi * (wi_after - wi);
        let de = 0.5 * mi * (wi_after.length_squared() - wi.length_squared());
        self.g[0] += r.x * dp.y;
        self.g[1] += 0.5 * (r.x * dp.x - r.y * dp.y);
        self.g[2] += r.x * de;
        self.g[3] += r.y * de;
        let [a, b, c, d] = [
            kinetic(mi, wi),
            kinetic(mi, wi_after),
            kinetic(mj, wj),
            kinetic(mj, wj_after),
        ];
        for k in 0..MOMENTS {
            self.flux[k] += (b[k] - a[k]) + (d[k] - c[k]);
        }
    }

    /// The lags of the correlators.
    pub(super) fn lags(&self) -> Vec<Lag> {
        self.correlators[0].lags()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two discs with constant velocities and no collision: each moment grows at
    /// its kinetic flux, so a sample at time t holds flux·t. Disc 1 (m = 2,
    /// w = (1, −3)): m w_x w_y = −6, ½m(w_x² − w_y²) = −8, e = 10, e w = (10, −30);
    /// disc 2 (m = 0.5, w = (2, 2)): 2, 0, e = 2, e w = (4, 4).
    #[test]
    fn free_flight_grows_at_the_kinetic_flux() {
        let masses = [2.0, 0.5];
        let w = [DVec2::new(1.0, -3.0), DVec2::new(2.0, 2.0)];
        let w = masses.into_iter().zip(w);
        let mut h = Helfand::new(1.0, w, 0.25, 2, (1, 10.0));
        h.advance(1.5);
        let flux = [-4.0, -8.0, 14.0, -26.0];
        for (k, f) in flux.into_iter().enumerate() {
            assert!((h.g[k] - 0.5 * f).abs() < 1e-12, "{k}");
            // Samples at 1.25 and 1.5: increments over one Δ are flux·0.25.
            let t = h.correlators[k].total(h.lags()[1]);
            assert_eq!(t.count, 2.0);
            assert!((t.inc - 2.0 * 0.25 * f).abs() < 1e-12, "{k}");
        }
    }

    /// A head-on elastic collision of equal masses along x swaps the velocities:
    /// Δp_i = m (w_j − w_i), Δe_i = e_j − e_i, and the moments jump by r·Δp and
    /// r·Δe with r = (−σ, 0); the kinetic fluxes after are those of the swapped
    /// velocities (here unchanged as a sum).
    #[test]
    fn a_collision_adds_the_collisional_transfer() {
        let m = 1.5;
        let (wi, wj) = (DVec2::new(2.0, 0.0), DVec2::new(-1.0, 0.0));
        let mut h = Helfand::new(0.0, [(m, wi), (m, wj)].into_iter(), 1.0, 1, (1, 1.0));
        let flux_before = h.flux;
        let r = DVec2::new(-1.2, 0.0);
        h.collide((m, m), r, (wi, wj), (wj, wi));
        let dp = m * (wj - wi);
        let de = 0.5 * m * (1.0 - 4.0);
        assert_eq!(h.g[0], r.x * dp.y);
        assert!((h.g[1] - 0.5 * r.x * dp.x).abs() < 1e-15);
        assert!((h.g[2] - r.x * de).abs() < 1e-15);
        assert_eq!(h.g[3], 0.0);
        for (after, before) in h.flux.iter().zip(flux_before) {
            assert!((after - before).abs() < 1e-12);
        }
    }
}
