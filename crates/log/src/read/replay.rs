//! Replaying compact collision records ([`CompactBatch`]) into full ones
//! ([`CollisionBatch`]): every disc's velocity is kept from the latest
//! `/snapshot` (or `/checkpoint`) and each collision applies its impulse exactly as
//! the engine did, v_i' = v_i + Δp_i/m_i, v_j' = v_j − Δp_i/m_j (a wall:
//! v_k' = v_k + Δp_k/m; `carom_core::collision::apply_impulse`), so velocities
//! before and after are the engine's bit for bit. The rest is derived: the unit
//! normal n̂ is the stored one or −Δp_i/|Δp_i| (rules whose impulse is along the
//! line of centres), the virial r_ij·Δp_i = −σ_ij n̂·Δp_i (physics.md §5), and the
//! energy lost 0 in an elastic run, else the kinetic energy before minus after;
//! those three agree with the full record to rounding (docs/log-format.md,
//! "Compact collisions").

use crate::format::{
    wall_of, CdrError, CollisionBatch, CompactBatch, LogCheckpoint, RunFacts, Snapshot, KIND_PAIR,
    KIND_WALL, NO_DISC,
};
use carom_core::collision::{apply_impulse, apply_wall_impulse};
use carom_core::{Boundary, DVec2, WallSide};

/// The replay state: each disc's current velocity and what it is made of.
#[derive(Debug, Default)]
pub(super) struct Replay {
    velocities: Vec<DVec2>,
    species_of: Vec<u16>,
    mass: Vec<f64>,
    radius: Vec<f64>,
    /// True once a snapshot or checkpoint has given the velocities.
    synced: bool,
    /// Every collision of the run is elastic (pair rule and walls): energy lost 0.
    elastic: bool,
    compact: CompactBatch,
}

impl Replay {
    /// A replay for a run with `facts` (`None`: energy lost is always the kinetic
    /// energy difference).
    pub(super) fn new(facts: Option<&RunFacts>) -> Self {
        let elastic = facts.is_some_and(|f| {
            f.restitution.is_elastic()
                && f.sim_box.boundary.iter().all(|b| match b {
                    Boundary::Periodic => true,
                    Boundary::Walls { restitution } => *restitution == 1.0,
                })
        });
        Replay {
            elastic,
            ..Replay::default()
        }
    }

    /// Take every disc's velocity, species, mass and radius from a snapshot.
    pub(super) fn sync_snapshot(&mut self, s: &Snapshot) {
        self.velocities.clone_from(&s.velocities);
        self.species_of.clone_from(&s.species);
        self.mass.clone_from(&s.species_mass);
        self.radius.clone_from(&s.species_radius);
        self.synced = true;
    }

    /// Take every disc's velocity, species, mass and radius from a checkpoint
    /// (whose per-disc arrays are in the engine's internal order).
    pub(super) fn sync_checkpoint(&mut self, c: &LogCheckpoint) {
        let e = &c.engine;
        let n = e.labels.len();
        self.velocities.resize(n, DVec2::ZERO);
        self.species_of.resize(n, 0);
        for (k, &l) in e.labels.iter().enumerate() {
            self.velocities[l as usize] = e.velocities[k];
            self.species_of[l as usize] = e.species_of[k];
        }
        self.mass = e.species.iter().map(|s| s.mass).collect();
        self.radius = e.species.iter().map(|s| s.radius).collect();
        self.synced = true;
    }

    /// Mass and radius of disc `d`, if it exists.
    fn disc(&self, d: u32) -> Option<(f64, f64)> {
        let s = *self.species_of.get(d as usize)? as usize;
        Some((*self.mass.get(s)?, *self.radius.get(s)?))
    }

    /// Decode the compact batch `data` and replay it into `out` (its previous
    /// content replaced), advancing the velocities.
    pub(super) fn expand(&mut self, data: &[u8], out: &mut CollisionBatch) -> Result<(), CdrError> {
        out.clear();
        self.compact.decode_into(data)?;
        if !self.synced && !self.compact.is_empty() {
            return Err(CdrError::Invalid {
                field: "time",
                problem: "no /snapshot or /checkpoint before this compact batch: the \
                          velocities cannot be replayed"
                    .into(),
            });
        }
        let r = self.replay_into(out);
        if r.is_err() {
            out.clear();
        }
        r
    }

    fn replay_into(&mut self, out: &mut CollisionBatch) -> Result<(), CdrError> {
        let b = std::mem::take(&mut self.compact);
        out.first_ordinal = b.first_ordinal;
        out.stride = 1;
        let normals = b.has_normals();
        let discs = self.velocities.len();
        let bad = |field, d: u32| CdrError::Invalid {
            field,
            problem: format!("disc {d}, but the snapshot has {discs} discs"),
        };
        for k in 0..b.len() {
            let (i, j) = (b.i[k], b.j[k]);
            let dp = DVec2::new(b.dpx[k], b.dpy[k]);
            let (mi, ri) = self.disc(i).ok_or_else(|| bad("i", i))?;
            let vib = self.velocities[i as usize];
            if let Some((axis, side)) = wall_of(j) {
                let a = axis.index();
                let mut via = vib;
                via[a] = apply_wall_impulse(vib[a], mi, dp[a]);
                self.velocities[i as usize] = via;
                let mut normal = DVec2::ZERO;
                normal[a] = if side == WallSide::High { 1.0 } else { -1.0 };
                let lost = if self.elastic {
                    0.0
                } else {
                    0.5 * mi * (vib.length_squared() - via.length_squared())
                };
                push(
                    out,
                    b.time[k],
                    KIND_WALL,
                    (i, NO_DISC),
                    normal,
                    [vib, DVec2::ZERO, via, DVec2::ZERO],
                    lost,
                    dp[a].abs(),
                );
                continue;
            }
            let (mj, rj) = self.disc(j).ok_or_else(|| bad("j", j))?;
            let vjb = self.velocities[j as usize];
            let (via, vja) = apply_impulse(vib, vjb, mi, mj, dp);
            self.velocities[i as usize] = via;
            self.velocities[j as usize] = vja;
            let normal = if normals {
                DVec2::new(b.nx[k], b.ny[k])
            } else {
                -dp.normalize_or_zero()
            };
            let virial = -(ri + rj) * normal.dot(dp);
            let lost = if self.elastic {
                0.0
            } else {
                0.5 * (mi * (vib.length_squared() - via.length_squared())
                    + mj * (vjb.length_squared() - vja.length_squared()))
            };
            push(
                out,
                b.time[k],
                KIND_PAIR,
                (i, j),
                normal,
                [vib, vjb, via, vja],
                lost,
                virial,
            );
        }
        out_impulses(out, &b);
        self.compact = b;
        Ok(())
    }
}

/// Append one collision to a full batch: velocities [i before, j before, i after,
/// j after].
#[allow(clippy::too_many_arguments)]
#[inline]
fn push(
    out: &mut CollisionBatch,
    time: f64,
    kind: u8,
    (i, j): (u32, u32),
    n: DVec2,
    v: [DVec2; 4],
    energy_lost: f64,
    virial: f64,
) {
    out.push_raw(
        time,
        kind,
        i,
        j,
        n,
        v[0],
        v[1],
        v[2],
        v[3],
        energy_lost,
        virial,
    );
}

/// Give the full batch the compact one's impulses (records then carry Δp_i).
fn out_impulses(out: &mut CollisionBatch, b: &CompactBatch) {
    out.impulse_x.clone_from(&b.dpx);
    out.impulse_y.clone_from(&b.dpy);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::format::{wall_code, CdrWriter};
    use carom_core::{Axis, SimBox, Species};

    fn snapshot() -> Snapshot {
        Snapshot {
            time: 0.0,
            box_size: DVec2::new(10.0, 10.0),
            boundary: [0, 1],
            species_radius: vec![0.5, 0.7],
            species_mass: vec![1.0, 3.0],
            species: vec![0, 1],
            positions: vec![DVec2::new(1.0, 1.0), DVec2::new(2.0, 1.0)],
            velocities: vec![DVec2::new(1.0, 0.25), DVec2::new(-0.5, 0.1)],
            images: Vec::new(),
        }
    }

    fn encoded(b: &CompactBatch) -> Vec<u8> {
        let mut w = CdrWriter::new();
        b.encode(&mut w);
        w.bytes().to_vec()
    }

    #[test]
    fn a_compact_batch_before_any_snapshot_is_an_error() {
        let b = CompactBatch {
            time: vec![0.5],
            i: vec![0],
            j: vec![1],
            dpx: vec![-1.0],
            dpy: vec![0.0],
            ..CompactBatch::default()
        };
        let mut out = CollisionBatch::default();
        let e = Replay::new(None)
            .expand(&encoded(&b), &mut out)
            .unwrap_err();
        assert!(e.to_string().contains("snapshot"), "{e}");
        let mut r = Replay::new(None);
        r.sync_snapshot(&snapshot());
        let bad = CompactBatch { j: vec![7], ..b };
        let e = r.expand(&encoded(&bad), &mut out).unwrap_err();
        assert!(matches!(e, CdrError::Invalid { field: "j", .. }), "{e}");
    }

    #[test]
    fn replay_applies_impulses_and_derives_the_rest() {
        let facts = RunFacts::new(
            &[Species::new(1, 0.5, 1.0), Species::new(1, 0.7, 3.0)],
            &SimBox::walled(10.0, 10.0, 1.0),
            &carom_engine::EngineParams::default(),
            &crate::LogOptions::default(),
        );
        let mut r = Replay::new(Some(&facts));
        r.sync_snapshot(&snapshot());
        let dp = DVec2::new(-0.9, 0.0);
        let b = CompactBatch {
            time: vec![0.5, 0.75],
            i: vec![0, 1],
            j: vec![1, wall_code(Axis::Y, WallSide::High)],
            dpx: vec![dp.x, 0.0],
            dpy: vec![dp.y, -0.2],
            ..CompactBatch::default()
        };
        let mut out = CollisionBatch::default();
        r.expand(&encoded(&b), &mut out).unwrap();
        let (p, w) = (out.get(0), out.get(1));
        let (vi, vj) = (DVec2::new(1.0, 0.25), DVec2::new(-0.5, 0.1));
        assert_eq!((p.vi_before, p.vj_before), (vi, vj));
        assert_eq!((p.vi_after, p.vj_after), (vi + dp / 1.0, vj - dp / 3.0));
        assert_eq!(p.normal, DVec2::X);
        assert_eq!(p.virial, 1.2 * 0.9);
        assert_eq!((p.energy_lost, p.impulse), (0.0, dp));
        // The wall: disc 1 after the pair collision, its y velocity changed.
        assert_eq!(w.vi_before, vj - dp / 3.0);
        assert_eq!(w.vi_after.y, w.vi_before.y + -0.2 / 3.0);
        assert_eq!(w.vi_after.x, w.vi_before.x);
        assert_eq!((w.normal, w.virial, w.kind), (DVec2::Y, 0.2, KIND_WALL));
        assert_eq!(w.ordinal, 1);
    }

    /// Two discs of masses 2 and 3 (radii 0.5 and 0.7) in a box walled in y.
    fn heavy_snapshot() -> Snapshot {
        Snapshot {
            species_mass: vec![2.0, 3.0],
            ..snapshot()
        }
    }

    fn inelastic_facts() -> RunFacts {
        RunFacts::new(
            &[Species::new(1, 0.5, 2.0), Species::new(1, 0.7, 3.0)],
            &SimBox::walled(10.0, 10.0, 0.9),
            &carom_engine::EngineParams {
                restitution: carom_core::Restitution::Normal(0.8),
                ..Default::default()
            },
            &crate::LogOptions::default(),
        )
    }

    #[test]
    fn an_inelastic_replay_reports_the_kinetic_energy_each_collision_takes() {
        let mut r = Replay::new(Some(&inelastic_facts()));
        r.sync_snapshot(&heavy_snapshot());
        let dp = DVec2::new(-0.9, 0.6);
        let dpy = 0.4;
        let b = CompactBatch {
            time: vec![0.5, 0.75],
            i: vec![0, 1],
            j: vec![1, wall_code(Axis::Y, WallSide::Low)],
            dpx: vec![dp.x, 0.0],
            dpy: vec![dp.y, dpy],
            ..CompactBatch::default()
        };
        let mut out = CollisionBatch::default();
        r.expand(&encoded(&b), &mut out).unwrap();
        let (p, w) = (out.get(0), out.get(1));
        // K' − K for v_i + Δp/m_i, v_j − Δp/m_j, expanded:
        // Δp·(v_i − v_j) + |Δp|²(1/m_i + 1/m_j)/2; the energy lost is its negative.
        let (vi, vj) = (DVec2::new(1.0, 0.25), DVec2::new(-0.5, 0.1));
        let lost = -dp.dot(vi - vj) - 0.5 * dp.length_squared() * (1.0 / 2.0 + 1.0 / 3.0);
        assert!(
            (p.energy_lost - lost).abs() < 1e-14,
            "{} {lost}",
            p.energy_lost
        );
        assert!(lost > 0.0);
        // The wall on the low side: normal −y; disc 1 (mass 3) arrives with
        // v_y = 0.1 − 0.6/3 = −0.1 and loses −Δp v_y − Δp²/(2m) > 0.
        assert_eq!(w.normal, DVec2::new(0.0, -1.0));
        let vy = 0.1 - 0.6 / 3.0;
        let wall_lost = -dpy * vy - dpy * dpy / (2.0 * 3.0);
        assert!(wall_lost > 0.0);
        assert!(
            (w.energy_lost - wall_lost).abs() < 1e-14,
            "{} {wall_lost}",
            w.energy_lost
        );
        assert_eq!(w.vi_after.y, w.vi_before.y + dpy / 3.0);
    }

    #[test]
    fn an_empty_compact_batch_needs_no_velocities() {
        let mut out = CollisionBatch::default();
        Replay::new(None)
            .expand(&encoded(&CompactBatch::default()), &mut out)
            .unwrap();
        assert!(out.is_empty());
    }

    /// A checkpoint stores discs in the engine's order with their labels; replay
    /// must give each label its own velocity, mass and radius.
    #[test]
    fn a_checkpoint_gives_each_labelled_disc_its_velocity_and_species() {
        use carom_engine::{box_size_for, Engine, Placement, SystemSpec, Velocities};
        let species = vec![Species::new(6, 0.5, 2.0), Species::new(6, 0.7, 3.0)];
        let size = box_size_for(&species, 0.3, 1.0);
        let spec = SystemSpec {
            sim_box: SimBox::periodic(size.x, size.y),
            species,
            temperature: 1.5,
            seed: 9,
            placement: Placement::Lattice,
            velocities: Velocities::MaxwellBoltzmann,
        };
        let mut e = Engine::new(spec.build().unwrap(), Default::default()).unwrap();
        e.run_collisions(40).unwrap();
        let mut cp = LogCheckpoint {
            driver: Default::default(),
            engine: e.checkpoint(),
        };
        // Reverse the engine's order consistently: a different, valid storage order.
        let c = &mut cp.engine;
        c.labels.reverse();
        c.velocities.reverse();
        c.species_of.reverse();
        let mut r = Replay::new(None);
        r.sync_checkpoint(&cp);
        let (i, j) = (1u32, 9u32); // one disc of each species
        let dp = DVec2::new(0.25, -0.5);
        let b = CompactBatch {
            time: vec![e.now()],
            i: vec![i],
            j: vec![j],
            dpx: vec![dp.x],
            dpy: vec![dp.y],
            ..CompactBatch::default()
        };
        let mut out = CollisionBatch::default();
        r.expand(&encoded(&b), &mut out).unwrap();
        let p = out.get(0);
        let (vi, vj) = (e.velocity(i as usize), e.velocity(j as usize));
        assert_eq!((p.vi_before, p.vj_before), (vi, vj));
        assert_eq!((p.vi_after, p.vj_after), (vi + dp / 2.0, vj - dp / 3.0));
        // virial −σ_ij n̂·Δp with n̂ = −Δp/|Δp|: σ_ij |Δp| = 1.2 |Δp|.
        assert!((p.virial - 1.2 * dp.length()).abs() < 1e-15);
    }
}
