//! Resolution: the configuration with every default made explicit (what the log
//! stores), and the engine's [`RunSpec`] built from it, with the box size derived
//! from the packing fraction when the configuration gives none.

use super::{
    AxisBoundary, BoxConfig, CollisionDetailConfig, CollisionModel, CompressionConfig, Config,
    ConfigError, LogConfig, PlacementConfig, StopConfig, VelocitiesConfig, DEFAULT_DURATION,
    DEFAULT_PACKING_FRACTION,
};
use carom_core::observables::packing_fraction;
use carom_core::vibrating_wall::Floor;
use carom_core::{Boundary, DVec2, Restitution, SimBox, Species};
use carom_engine::{
    box_size_for, largest_radius, EngineParams, Growth, Placement, SystemSpec, Velocities,
};
use carom_log::SchedulePoints;
use carom_log::{CollisionDetail, Compression, LogOptions, RunSpec, Stop};

impl Config {
    /// The configuration with every default made explicit: the box's packing
    /// fraction and aspect (when no size is given), the stop criterion, the wall
    /// restitution (when there are walls) and the elastic coefficient. Parsing its
    /// JSON gives the same run.
    pub fn resolved(&self) -> Config {
        let mut c = self.clone();
        if c.sim_box.size.is_none() {
            c.sim_box
                .packing_fraction
                .get_or_insert(DEFAULT_PACKING_FRACTION);
            c.sim_box.aspect.get_or_insert(1.0);
        }
        if c.sim_box.boundary.axes().contains(&AxisBoundary::Walls) {
            c.sim_box.wall_restitution.get_or_insert(1.0);
        }
        if c.stop.duration.is_none() && c.stop.collisions.is_none() {
            c.stop.duration = Some(DEFAULT_DURATION);
        }
        c.collision.coefficient.get_or_insert(1.0);
        c
    }

    /// The fully resolved configuration ([`Config::resolved`]) as pretty JSON: what
    /// is stored in the log.
    pub fn canonical_json(&self) -> String {
        serde_json::to_string_pretty(&self.resolved()).expect("a Config always serialises")
    }

    /// The engine's view of the configuration: the system to build, the dynamics,
    /// the stop criterion and the log options, with [`Config::canonical_json`] as
    /// `config_json`. Checks the configuration first.
    pub fn to_run_spec(&self) -> Result<RunSpec, ConfigError> {
        self.validate()?;
        let c = self.resolved();
        let species: Vec<Species> = c
            .species
            .iter()
            .map(|s| Species::new(s.count as usize, s.radius, s.mass))
            .collect();
        let size = match c.sim_box.size {
            Some([lx, ly]) => DVec2::new(lx, ly),
            None => derived_box_size(&species, &c.sim_box)?,
        };
        let restitution = c.sim_box.wall_restitution.unwrap_or(1.0);
        let axes = c.sim_box.boundary.axes();
        let boundary = axes.map(|a| match a {
            AxisBoundary::Periodic => Boundary::Periodic,
            AxisBoundary::Walls => Boundary::Walls { restitution },
        });
        let to_vecs = |l: &[[f64; 2]]| l.iter().map(|&[x, y]| DVec2::new(x, y)).collect();
        let eta = packing_fraction(&species, &SimBox { size, boundary });
        let system = SystemSpec {
            species,
            sim_box: SimBox { size, boundary },
            temperature: c.temperature,
            seed: c.seed,
            placement: match &c.placement {
                PlacementConfig::Lattice => Placement::Lattice,
                PlacementConfig::Random => Placement::Random,
                PlacementConfig::Relaxed => Placement::Relaxed,
                PlacementConfig::Explicit(p) => Placement::Explicit(to_vecs(p)),
                PlacementConfig::Compressed(p) => Placement::Compressed {
                    rate: p.rate,
                    start: p.start_packing_fraction.unwrap_or(eta.min(0.3)),
                },
            },
            velocities: match &c.velocities {
                VelocitiesConfig::MaxwellBoltzmann => Velocities::MaxwellBoltzmann,
                VelocitiesConfig::EqualSpeed => Velocities::EqualSpeed,
                VelocitiesConfig::Explicit(v) => Velocities::Explicit(to_vecs(v)),
            },
        };
        let e = c.collision.coefficient.unwrap_or(1.0);
        let params = EngineParams {
            restitution: match c.collision.model {
                CollisionModel::Elastic => Restitution::Elastic,
                CollisionModel::Normal => Restitution::Normal(e),
                CollisionModel::CentreOfMass => Restitution::CentreOfMass(e),
            },
            tc: c.collision.tc,
            max_events_without_time_advance: c.collision.max_events_without_time_advance,
            gravity: c.gravity,
            growth: match c.compression {
                None => Growth::default(),
                Some(g) => Growth {
                    rate: g.rate,
                    target_scale: (g.target_packing_fraction
                        / packing_fraction(&system.species, &system.sim_box))
                    .sqrt(),
                    kt: c.temperature,
                    rescale_interval: g.rescale_interval,
                    max_reduced_pressure: g.max_reduced_pressure,
                },
            },
            floor: c.vibrating_floor.map(|fl| Floor {
                amplitude: fl.amplitude,
                omega: std::f64::consts::TAU * fl.frequency,
            }),
            neighbours: c.neighbours.neighbours(),
        };
        let mut log = c.log.options();
        if ((c.gravity > 0.0 || c.compression.is_some() || c.vibrating_floor.is_some())
            && c.log.collision_detail.is_none())
            || c.thermostat.is_some()
        {
            // Compact records cannot replay velocities that change between
            // collisions (see Config::gravity) or that the thermostat changed.
            log.collision_detail = CollisionDetail::Full;
        }
        Ok(RunSpec {
            system,
            params,
            stop: c.stop.stop(),
            max_time_without_collision: c.stop.max_time_without_collision,
            log,
            config_json: self.canonical_json(),
            thermostat: c.thermostat.map(|t| t.thermostat()),
        })
    }
}

/// The box edges (length) for `species` at the packing fraction and aspect ratio
/// of `b` (no `size` given), refused when they come out infinite, zero, or with the
/// shorter edge not longer than the largest diameter: the error then names the
/// setting that made them so, rather than a `box.size` the user never wrote.
fn derived_box_size(species: &[Species], b: &BoxConfig) -> Result<DVec2, ConfigError> {
    let eta = b.packing_fraction.unwrap_or(DEFAULT_PACKING_FRACTION);
    let aspect = b.aspect.unwrap_or(1.0);
    let covered: f64 = species.iter().map(|s| s.count as f64 * s.disc_area()).sum();
    if !covered.is_finite() {
        return Err(ConfigError::invalid(
            "species",
            format!("the discs' total area Σ count π a² is {covered}"),
            "radii and counts whose total area is a finite number",
        ));
    }
    let size = box_size_for(species, eta, aspect);
    if !size.is_finite() || size.min_element() <= 0.0 {
        return Err(ConfigError::invalid(
            "box.packing_fraction",
            format!(
                "η = {eta:?} with these discs gives box edges {:?} × {:?}",
                size.x, size.y
            ),
            "a packing fraction and disc sizes whose box has finite edges",
        ));
    }
    let diameter = 2.0 * largest_radius(species);
    if size.min_element() <= diameter {
        return Err(ConfigError::invalid(
            "box.aspect",
            format!(
                "aspect {aspect} at η = {eta} gives box edges {:.4} × {:.4}, the shorter \
                 not longer than the largest disc diameter {diameter}",
                size.x, size.y
            ),
            "an aspect ratio nearer 1, or more discs, so that both edges exceed the \
             largest diameter",
        ));
    }
    Ok(size)
}

impl StopConfig {
    /// The stop criterion: the collision count when given, else the duration
    /// (default [`DEFAULT_DURATION`]) as a stop time for a run starting at 0.
    pub fn stop(&self) -> Stop {
        match (self.duration, self.collisions) {
            (_, Some(n)) => Stop::Collisions(n),
            (Some(t), None) => Stop::Time(t),
            (None, None) => Stop::Time(DEFAULT_DURATION),
        }
    }
}

impl LogConfig {
    /// The log options these settings give.
    pub fn options(&self) -> LogOptions {
        LogOptions {
            collisions: self.collisions,
            collision_every: self.collision_every,
            collision_detail: match self.collision_detail {
                Some(CollisionDetailConfig::Full) => CollisionDetail::Full,
                Some(CollisionDetailConfig::Compact) => CollisionDetail::Compact,
                None if self.collision_every > 1 => CollisionDetail::Full,
                None => CollisionDetail::Compact,
            },
            snapshot_interval: self.snapshot_interval,
            snapshot_schedule: self.snapshot_schedule.map(|s| SchedulePoints {
                points: s.points,
                first: s.first,
            }),
            thermo_interval: self.thermo_interval,
            checkpoint_interval: self.checkpoint_interval,
            scene_interval: self.scene_interval,
            compression: match self.compression {
                CompressionConfig::Zstd => Compression::Zstd,
                CompressionConfig::Lz4 => Compression::Lz4,
                CompressionConfig::None => Compression::None,
            },
            flush_seconds: self.flush_seconds,
        }
    }
}
