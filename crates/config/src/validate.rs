//! The single validator of a configuration: every value against its allowed
//! range, one function per section (species, box, initial state, collision rule,
//! stop), and the log options through [`check_log_options`], which a resume
//! calls too. Errors name the field. Placement feasibility and overlaps are
//! checked when the state is built ([`ConfigError::from_init`]).

use super::{
    AxisBoundary, CollisionDetailConfig, CollisionModel, Config, ConfigError, PlacementConfig,
    VelocitiesConfig,
};
use carom_core::{check_species, Species};
use carom_log::check_log_options;

use super::model::ETA_CLOSE_PACKED;

impl Config {
    /// Check every value against its allowed range. Errors name the field.
    /// (Placement feasibility and overlaps are checked when the state is built,
    /// see [`ConfigError::from_init`].)
    pub fn validate(&self) -> Result<(), ConfigError> {
        let n = self.check_species()?;
        self.check_box()?;
        self.check_initial_state(n)?;
        self.check_collision()?;
        self.check_stop()?;
        self.check_gravity()?;
        self.check_compression()?;
        self.check_floor()?;
        self.check_neighbours()?;
        if self.log.collision_detail == Some(CollisionDetailConfig::Compact)
            && self.log.collision_every > 1
        {
            return Err(ConfigError::invalid(
                "log.collision_detail",
                format!(
                    "\"compact\" with log.collision_every = {}: compact records replay \
                     velocities only from every collision",
                    self.log.collision_every
                ),
                "\"full\" (or no log.collision_detail) when log.collision_every > 1; \
                 \"compact\" with log.collision_every = 1",
            ));
        }
        if let Some(t) = &self.thermostat {
            t.thermostat().validate().map_err(|m| {
                // "thermostat.FIELD: value V (allowed: A)" from the engine's check.
                let (field, rest) = m.split_once(": ").unwrap_or(("thermostat", &m));
                let (problem, allowed) = rest
                    .trim_end_matches(')')
                    .split_once(" (allowed: ")
                    .unwrap_or((rest, "a finite number > 0"));
                ConfigError::invalid(field, problem, allowed)
            })?;
            if self.log.collision_detail == Some(CollisionDetailConfig::Compact) {
                return Err(ConfigError::invalid(
                    "log.collision_detail",
                    "\"compact\" with a thermostat: compact records replay velocities \
                     from collisions alone, and the thermostat changes them in between",
                    "\"full\" (or no log.collision_detail) with a thermostat",
                ));
            }
        }
        // A run of known length starts at time 0 and lasts stop.duration.
        check_log_options(&self.log.options(), &self.stop.stop(), 0.0, "stop.duration")?;
        Ok(())
    }

    /// The species, by the one check of `carom_core::check_species`; their
    /// number of discs.
    fn check_species(&self) -> Result<usize, ConfigError> {
        let species: Vec<Species> = self
            .species
            .iter()
            .map(|s| {
                Species::new(
                    usize::try_from(s.count).unwrap_or(usize::MAX),
                    s.radius,
                    s.mass,
                )
            })
            .collect();
        check_species(&species).map_err(|p| {
            let field = match p.setting {
                Some((k, setting)) => format!("species.{k}.{setting}"),
                None => "species".to_owned(),
            };
            ConfigError::invalid(field, p.problem, p.allowed)
        })
    }

    /// The box: either its size or its packing fraction and aspect, and a wall
    /// restitution only with walls.
    fn check_box(&self) -> Result<(), ConfigError> {
        let b = &self.sim_box;
        if let Some(size) = b.size {
            for (k, name) in ["box.packing_fraction", "box.aspect"].iter().enumerate() {
                let given = if k == 0 { b.packing_fraction } else { b.aspect };
                if given.is_some() {
                    return Err(ConfigError::invalid(
                        *name,
                        "given together with box.size",
                        "either box.size, or box.packing_fraction (with optional box.aspect)",
                    ));
                }
            }
            let d_max = 2.0 * self.species.iter().map(|s| s.radius).fold(0.0, f64::max);
            for (k, l) in size.iter().enumerate() {
                if !l.is_finite() || *l <= d_max {
                    return Err(ConfigError::invalid(
                        format!("box.size.{k}"),
                        format!("edge length {l}"),
                        format!("finite and longer than the largest disc diameter {d_max}"),
                    ));
                }
            }
        } else {
            if let Some(eta) = b.packing_fraction {
                if !(eta.is_finite() && eta > 0.0 && eta < ETA_CLOSE_PACKED) {
                    return Err(ConfigError::invalid(
                        "box.packing_fraction",
                        format!("value {eta}"),
                        "0 < η < 0.9069 (hexagonal close packing); lattice placement reaches at least \
                         0.72, and up to the densest lattice that fits the box",
                    ));
                }
            }
            if let Some(a) = b.aspect {
                if !(a.is_finite() && (0.01..=100.0).contains(&a)) {
                    return Err(ConfigError::invalid(
                        "box.aspect",
                        format!("value {a}"),
                        "0.01 ≤ L_x/L_y ≤ 100",
                    ));
                }
            }
        }
        if let Some(e) = b.wall_restitution {
            if !b.boundary.axes().contains(&AxisBoundary::Walls) {
                return Err(ConfigError::invalid(
                    "box.wall_restitution",
                    "given but no axis has walls",
                    "only with box.boundary \"walls\" or walls on one axis",
                ));
            }
            if !(0.0..=1.0).contains(&e) {
                return Err(ConfigError::invalid(
                    "box.wall_restitution",
                    format!("value {e}"),
                    "0 ≤ e_w ≤ 1",
                ));
            }
        }
        Ok(())
    }

    /// The field: finite g ≥ 0, walls along y when g > 0, and full collision
    /// records (compact ones replay velocities that only collisions change).
    fn check_gravity(&self) -> Result<(), ConfigError> {
        let g = self.gravity;
        if !(g.is_finite() && g >= 0.0) {
            return Err(ConfigError::invalid(
                "gravity",
                format!("value {g}"),
                "finite g ≥ 0 (length/time², along −y); 0 for none",
            ));
        }
        if g > 0.0 && self.sim_box.boundary.axes()[1] == AxisBoundary::Periodic {
            return Err(ConfigError::invalid(
                "gravity",
                format!("g = {g} with a periodic y axis: discs would fall for ever"),
                "hard walls along y with a field: box.boundary \"walls\" or                  {\"x\": \"periodic\", \"y\": \"walls\"}; or gravity 0",
            ));
        }
        if g > 0.0 && self.log.collision_detail == Some(CollisionDetailConfig::Compact) {
            return Err(ConfigError::invalid(
                "log.collision_detail",
                format!("\"compact\" with gravity {g}: compact records replay velocities that only collisions change, and a field changes them in between"),
                "\"full\" (or no log.collision_detail, which is full with a field)",
            ));
        }
        Ok(())
    }

    /// Compression, as a run mode or a placement (physics.md §17): rates finite
    /// and > 0, a target between the start and close packing, and elastic dynamics
    /// without gravity, the TC model or (as a run mode) a thermostat.
    fn check_compression(&self) -> Result<(), ConfigError> {
        let positive = |field: &str, x: f64| {
            if x.is_finite() && x > 0.0 {
                Ok(())
            } else {
                Err(ConfigError::invalid(
                    field,
                    format!("value {x}"),
                    "finite, > 0",
                ))
            }
        };
        let run = self.compression.is_some();
        let placed = matches!(self.placement, PlacementConfig::Compressed(_));
        if let PlacementConfig::Compressed(p) = &self.placement {
            positive("placement.compressed.rate", p.rate)?;
            if let Some(start) = p.start_packing_fraction {
                positive("placement.compressed.start_packing_fraction", start)?;
            }
        }
        if let Some(g) = &self.compression {
            positive("compression.rate", g.rate)?;
            positive("compression.rescale_interval", g.rescale_interval)?;
            let t = g.target_packing_fraction;
            if !(t.is_finite() && t > 0.0 && t < ETA_CLOSE_PACKED) {
                return Err(ConfigError::invalid(
                    "compression.target_packing_fraction",
                    format!("value {t}"),
                    "0 < η < 0.9069 (hexagonal close packing), above the start's",
                ));
            }
            if let Some(eta) = self.sim_box.packing_fraction {
                if t < eta {
                    return Err(ConfigError::invalid(
                        "compression.target_packing_fraction",
                        format!("{t} is below the start's box.packing_fraction {eta}"),
                        "a target at or above the packing fraction of the start",
                    ));
                }
            }
            if g.max_reduced_pressure.is_nan() || g.max_reduced_pressure <= 1.0 {
                return Err(ConfigError::invalid(
                    "compression.max_reduced_pressure",
                    format!("value {}", g.max_reduced_pressure),
                    "> 1 (the jamming bound on Z = βPA/N), or a very large number for none",
                ));
            }
        }
        if !(run || placed) {
            return Ok(());
        }
        let field = if run {
            "compression"
        } else {
            "placement.compressed"
        };
        let inelastic = self.collision.model != CollisionModel::Elastic
            || self.collision.tc != 0.0
            || self.sim_box.wall_restitution.is_some_and(|e| e != 1.0);
        if run && inelastic {
            return Err(ConfigError::invalid(
                field,
                "given with inelastic collisions, inelastic walls or the TC model",
                "growing discs with elastic collisions and walls (collision.model \"elastic\", \
                 no collision.tc, box.wall_restitution 1)",
            ));
        }
        if run && self.gravity != 0.0 {
            return Err(ConfigError::invalid(
                field,
                format!("given with gravity {}", self.gravity),
                "compression without gravity (gravity 0); compressed placement then a field",
            ));
        }
        if run && self.thermostat.is_some() {
            return Err(ConfigError::invalid(
                field,
                "given with a thermostat",
                "compression without a thermostat (it rescales the velocities to `temperature` \
                 itself); compressed placement then a thermostat",
            ));
        }
        Ok(())
    }

    /// The initial state of `n` discs: the temperature, and one explicit position
    /// or velocity per disc.
    fn check_initial_state(&self, n: usize) -> Result<(), ConfigError> {
        if !(self.temperature.is_finite() && self.temperature > 0.0) {
            return Err(ConfigError::invalid(
                "temperature",
                format!("value {}", self.temperature),
                "finite kT > 0",
            ));
        }
        let check_list = |field: &str, list: &[[f64; 2]], what: &str| {
            if list.len() != n {
                return Err(ConfigError::invalid(
                    field,
                    format!("{} {what} given for {n} discs", list.len()),
                    format!("exactly one [x, y] pair per disc ({n})"),
                ));
            }
            Ok(())
        };
        if let PlacementConfig::Explicit(p) = &self.placement {
            check_list("placement.explicit", p, "positions")?;
        }
        if let VelocitiesConfig::Explicit(v) = &self.velocities {
            check_list("velocities.explicit", v, "velocities")?;
        }
        Ok(())
    }

    /// The pair collision rule and the inelastic-collapse safeguards.
    fn check_collision(&self) -> Result<(), ConfigError> {
        let c = &self.collision;
        match (c.model, c.coefficient) {
            (CollisionModel::Elastic, Some(e)) if e != 1.0 => {
                return Err(ConfigError::invalid(
                    "collision.coefficient",
                    format!("{e} with model \"elastic\""),
                    "1 (or absent) for \"elastic\"; set collision.model to \"normal\" or \
                     \"centre-of-mass\" for inelastic collisions",
                ))
            }
            (CollisionModel::Normal | CollisionModel::CentreOfMass, None) => {
                return Err(ConfigError::invalid(
                    "collision.coefficient",
                    "missing for an inelastic model",
                    "a restitution coefficient 0 ≤ e ≤ 1",
                ))
            }
            (_, Some(e)) if !(0.0..=1.0).contains(&e) => {
                return Err(ConfigError::invalid(
                    "collision.coefficient",
                    format!("value {e}"),
                    "0 ≤ coefficient ≤ 1",
                ))
            }
            _ => {}
        }
        if !(c.tc.is_finite() && c.tc >= 0.0) {
            return Err(ConfigError::invalid(
                "collision.tc",
                format!("value {}", c.tc),
                "finite t_c ≥ 0 (0 switches the TC model off)",
            ));
        }
        if c.max_events_without_time_advance == 0 {
            return Err(ConfigError::invalid(
                "collision.max_events_without_time_advance",
                "value 0",
                "an integer ≥ 1",
            ));
        }
        Ok(())
    }

    /// The stop: exactly one of a positive duration and a collision count that
    /// can be reached.
    fn check_stop(&self) -> Result<(), ConfigError> {
        match (self.stop.duration, self.stop.collisions) {
            (Some(_), Some(_)) => {
                return Err(ConfigError::invalid(
                    "stop",
                    "both duration and collisions given",
                    "exactly one of stop.duration and stop.collisions",
                ))
            }
            (Some(t), None) if !(t.is_finite() && t > 0.0) => {
                return Err(ConfigError::invalid(
                    "stop.duration",
                    format!("value {t}"),
                    "finite simulated time > 0",
                ))
            }
            (None, Some(0)) => {
                return Err(ConfigError::invalid(
                    "stop.collisions",
                    "value 0",
                    "an integer ≥ 1",
                ))
            }
            (None, Some(_))
                if self
                    .species
                    .iter()
                    .map(|s| s.count)
                    .filter(|&c| c > 0)
                    .eq([1])
                    && !self.sim_box.boundary.axes().contains(&AxisBoundary::Walls) =>
            {
                // It would run forever, filling the disk with snapshots.
                return Err(ConfigError::invalid(
                    "stop.collisions",
                    "a single disc in a periodic box never collides",
                    "stop.duration, or walls, or more than one disc",
                ));
            }
            (None, Some(_))
                if matches!(&self.velocities, VelocitiesConfig::Explicit(v)
                    if v.iter().all(|&[x, y]| x == 0.0 && y == 0.0)) =>
            {
                // No kinetic energy: nothing ever moves, so nothing collides.
                return Err(ConfigError::invalid(
                    "stop.collisions",
                    "every explicit velocity is [0, 0], so no disc ever moves or collides",
                    "stop.duration, or a non-zero velocity in velocities.explicit",
                ));
            }
            _ => {}
        }
        match self.stop.max_time_without_collision {
            Some(t) if !(t.is_finite() && t > 0.0) => Err(ConfigError::invalid(
                "stop.max_time_without_collision",
                format!("value {t}"),
                "finite simulated time > 0 (absent: 100 expected mean free times with a \
                 collision stop, no bound with a time stop)",
            )),
            _ => Ok(()),
        }
    }
}
