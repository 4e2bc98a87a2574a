//! The resolved run as plain data ([`RunFacts`]), stored since log format 1.2 as
//! the JSON value `run_facts` of the `carom.run` metadata, so that a reader learns
//! the system without re-running the configuration front end or the placement.
//!
//! The JSON uses the configuration's words (docs/log-format.md): `species`, `box`
//! (size, boundaries, wall restitutions), `collision` (model, coefficient, t_c),
//! `n_discs`, `collision_every` (null when collisions are not logged) and
//! `accessible_area`, the area disc centres can reach (physics.md §5); then
//! `gravity` (only when not 0), `thermostat`, `growth` and `floor` (each only when
//! the run had it; format 2.4 on, [`RunFacts::hold_dynamics`]), and `neighbours`
//! (the setting's name, only when not auto; format 2.6 on). Every number is in
//! shortest round-trip form. Logs of format ≤ 1.1 have no facts.

use super::checkpoint::neighbours_named;
use super::facts_dynamics::{FloorJson, GrowthJson, ThermostatJson};
use crate::options::LogOptions;
use carom_core::observables::{accessible_area, disc_count};
use carom_core::vibrating_wall::Floor;
use carom_core::{Boundary, DVec2, Restitution, SimBox, Species};
use carom_engine::{EngineParams, Growth, Neighbours, Thermostat};
use serde::{Deserialize, Serialize};
use serde_json::Value;

/// What was run, resolved: the facts an analysis needs about the system.
#[derive(Debug, Clone, PartialEq)]
pub struct RunFacts {
    /// The species (count, radius, mass), in disc order.
    pub species: Vec<Species>,
    /// The box: edge lengths and per-axis boundary (with the wall restitution).
    pub sim_box: SimBox,
    /// The pair collision rule.
    pub restitution: Restitution,
    /// TC-model duration t_c (time; 0 = off).
    pub tc: f64,
    /// Number of discs N.
    pub n_discs: u64,
    /// Every k-th collision is logged; `None` when collisions are not logged.
    pub collision_every: Option<u64>,
    /// The area disc centres reach (length², physics.md §5): the box area when
    /// periodic, `carom_core::observables::accessible_area` with walls.
    pub accessible_area: f64,
    /// Uniform gravity g along −y (length/time², physics.md §15; 0: none). In the
    /// JSON only when not 0 (`"gravity"`), so facts without a field read as before.
    pub gravity: f64,
    /// The thermostat (physics.md §16), if the run had one.
    pub thermostat: Option<Thermostat>,
    /// The growth of the radii (compression, physics.md §17), if the discs grew
    /// (rate ≠ 0).
    pub growth: Option<Growth>,
    /// The vibrating floor (physics.md §18), if the run had one.
    pub floor: Option<Floor>,
    /// How the engine was told to find the discs a disc may meet (auto, cells or
    /// lists; docs/performance.md, "neighbour lists"). In the JSON only when not
    /// auto (`"neighbours"`, the setting's name), so facts without it, those of
    /// logs before format 2.6 too, read auto.
    pub neighbours: Neighbours,
}

/// The first log format whose facts hold the thermostat, growth and floor.
const DYNAMICS_SINCE: (u32, u32) = (2, 4);

impl RunFacts {
    /// The facts of a run of `species` in `sim_box` with the dynamics `params`,
    /// logged as `log` says.
    pub fn new(
        species: &[Species],
        sim_box: &SimBox,
        params: &EngineParams,
        log: &LogOptions,
    ) -> RunFacts {
        RunFacts {
            species: species.to_vec(),
            sim_box: *sim_box,
            restitution: params.restitution,
            tc: params.tc,
            n_discs: disc_count(species) as u64,
            collision_every: log.collisions.then_some(log.collision_every),
            accessible_area: accessible_area(species, sim_box),
            gravity: params.gravity,
            thermostat: None,
            growth: (params.growth.rate != 0.0).then_some(params.growth),
            floor: params.floor,
            neighbours: params.neighbours,
        }
    }

    /// These facts with the run's `thermostat` (the engine's parameters leave it
    /// out: it is set on the engine apart).
    pub fn with_thermostat(self, thermostat: Option<Thermostat>) -> RunFacts {
        RunFacts { thermostat, ..self }
    }

    /// Whether the facts of a log of format `log_format` ("major.minor") hold
    /// its dynamics — thermostat, growth, floor — so that a missing one means
    /// none (format 2.4 on). Older facts say nothing of them.
    pub fn hold_dynamics(log_format: &str) -> bool {
        let mut parts = log_format.split('.').map(str::parse::<u32>);
        match (parts.next(), parts.next()) {
            (Some(Ok(major)), Some(Ok(minor))) => (major, minor) >= DYNAMICS_SINCE,
            _ => false,
        }
    }

    /// The facts as JSON (see the module documentation).
    pub fn to_json(&self) -> Value {
        let boundary = self.sim_box.boundary;
        let wire = FactsJson {
            species: self
                .species
                .iter()
                .map(|s| SpeciesJson {
                    count: s.count as u64,
                    radius: s.radius,
                    mass: s.mass,
                })
                .collect(),
            sim_box: BoxJson {
                size: [self.sim_box.size.x, self.sim_box.size.y],
                boundary: boundary.map(|b| match b {
                    Boundary::Periodic => AxisJson::Periodic,
                    Boundary::Walls { .. } => AxisJson::Walls,
                }),
                wall_restitution: boundary.map(|b| match b {
                    Boundary::Periodic => None,
                    Boundary::Walls { restitution } => Some(restitution),
                }),
            },
            collision: CollisionJson {
                model: match self.restitution {
                    Restitution::Elastic => ModelJson::Elastic,
                    Restitution::Normal(_) => ModelJson::Normal,
                    Restitution::CentreOfMass(_) => ModelJson::CentreOfMass,
                },
                coefficient: self.restitution.coefficient(),
                tc: self.tc,
            },
            n_discs: self.n_discs,
            collision_every: self.collision_every,
            accessible_area: self.accessible_area,
            gravity: self.gravity,
            thermostat: self.thermostat.map(ThermostatJson::from),
            growth: self.growth.map(GrowthJson::from),
            floor: self.floor.map(FloorJson::from),
            neighbours: (self.neighbours != Neighbours::Auto)
                .then(|| self.neighbours.name().into()),
        };
        serde_json::to_value(wire).expect("the facts always serialise")
    }

    /// The facts from JSON; `Err` says what is wrong.
    pub fn from_json(v: &Value) -> Result<RunFacts, String> {
        let w = FactsJson::deserialize(v).map_err(|e| e.to_string())?;
        let mut boundary = [Boundary::Periodic; 2];
        for (k, b) in boundary.iter_mut().enumerate() {
            *b = match (w.sim_box.boundary[k], w.sim_box.wall_restitution[k]) {
                (AxisJson::Periodic, None) => Boundary::Periodic,
                (AxisJson::Walls, Some(restitution)) => Boundary::Walls { restitution },
                _ => {
                    return Err(format!(
                        "box axis {k}: wall_restitution is given exactly for walls"
                    ))
                }
            };
        }
        let e = w.collision.coefficient;
        Ok(RunFacts {
            species: w
                .species
                .iter()
                .map(|s| Species::new(s.count as usize, s.radius, s.mass))
                .collect(),
            sim_box: SimBox {
                size: DVec2::new(w.sim_box.size[0], w.sim_box.size[1]),
                boundary,
            },
            restitution: match w.collision.model {
                ModelJson::Elastic => Restitution::Elastic,
                ModelJson::Normal => Restitution::Normal(e),
                ModelJson::CentreOfMass => Restitution::CentreOfMass(e),
            },
            tc: w.collision.tc,
            n_discs: w.n_discs,
            collision_every: w.collision_every,
            accessible_area: w.accessible_area,
            gravity: w.gravity,
            thermostat: w.thermostat.map(Thermostat::from),
            growth: w.growth.map(Growth::from),
            floor: w.floor.map(Floor::from),
            neighbours: match &w.neighbours {
                None => Neighbours::Auto,
                Some(name) => neighbours_named(name).map_err(|e| format!("neighbours: {e}"))?,
            },
        })
    }
}

#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct FactsJson {
    species: Vec<SpeciesJson>,
    #[serde(rename = "box")]
    sim_box: BoxJson,
    collision: CollisionJson,
    n_discs: u64,
    collision_every: Option<u64>,
    #[serde(with = "super::number::float")]
    accessible_area: f64,
    #[serde(
        default,
        skip_serializing_if = "is_zero",
        with = "super::number::float"
    )]
    gravity: f64,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    thermostat: Option<ThermostatJson>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    growth: Option<GrowthJson>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    floor: Option<FloorJson>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    neighbours: Option<String>,
}

/// Whether `x` is 0 (gravity left out of the JSON).
fn is_zero(x: &f64) -> bool {
    *x == 0.0
}

#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct SpeciesJson {
    count: u64,
    #[serde(with = "super::number::float")]
    radius: f64,
    #[serde(with = "super::number::float")]
    mass: f64,
}

#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct BoxJson {
    #[serde(with = "float_pair")]
    size: [f64; 2],
    boundary: [AxisJson; 2],
    #[serde(with = "opt_float_pair")]
    wall_restitution: [Option<f64>; 2],
}

#[derive(Clone, Copy, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
enum AxisJson {
    Periodic,
    Walls,
}

#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct CollisionJson {
    model: ModelJson,
    #[serde(with = "super::number::float")]
    coefficient: f64,
    #[serde(with = "super::number::float")]
    tc: f64,
}

#[derive(Clone, Copy, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
enum ModelJson {
    Elastic,
    Normal,
    CentreOfMass,
}

/// `[f64; 2]` under the log's rule for numbers (`super::number`).
mod float_pair {
    use serde::{Deserialize, Deserializer, Serialize, Serializer};

    #[derive(Serialize, Deserialize)]
    struct F(#[serde(with = "super::super::number::float")] f64);

    pub fn serialize<S: Serializer>(x: &[f64; 2], s: S) -> Result<S::Ok, S::Error> {
        [F(x[0]), F(x[1])].serialize(s)
    }

    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<[f64; 2], D::Error> {
        let [F(a), F(b)] = <[F; 2]>::deserialize(d)?;
        Ok([a, b])
    }
}

/// `[Option<f64>; 2]` under the log's rule for numbers (`null`: `None`).
mod opt_float_pair {
    use serde::{Deserialize, Deserializer, Serialize, Serializer};

    #[derive(Serialize, Deserialize)]
    struct F(#[serde(with = "super::super::number::float")] f64);

    pub fn serialize<S: Serializer>(x: &[Option<f64>; 2], s: S) -> Result<S::Ok, S::Error> {
        [x[0].map(F), x[1].map(F)].serialize(s)
    }

    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<[Option<f64>; 2], D::Error> {
        let [a, b] = <[Option<F>; 2]>::deserialize(d)?;
        Ok([a.map(|F(x)| x), b.map(|F(x)| x)])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn facts_round_trip_through_json() {
        let species = [Species::new(300, 0.5, 1.0), Species::new(200, 0.7, 2.0)];
        let mut sim_box = SimBox::walled(31.3, 20.1, 0.9);
        sim_box.boundary[0] = Boundary::Periodic;
        let params = EngineParams {
            restitution: Restitution::CentreOfMass(0.95),
            tc: 1e-4,
            ..EngineParams::default()
        };
        let f = RunFacts::new(&species, &sim_box, &params, &LogOptions::default());
        assert_eq!(f.n_discs, 500);
        assert_eq!(f.collision_every, Some(1));
        assert_eq!(f.accessible_area, accessible_area(&species, &sim_box));
        let v = f.to_json();
        assert_eq!(
            v["box"]["boundary"],
            serde_json::json!(["periodic", "walls"])
        );
        assert_eq!(v["collision"]["model"], "centre-of-mass");
        assert_eq!(RunFacts::from_json(&v).unwrap(), f);
        let text = v.to_string();
        let back: Value = serde_json::from_str(&text).unwrap();
        assert_eq!(RunFacts::from_json(&back).unwrap(), f);
        let mut bad = v.clone();
        bad["box"]["wall_restitution"][0] = serde_json::json!(1.0);
        assert!(RunFacts::from_json(&bad).is_err());
    }

    /// The dynamics round-trip (JSON → facts → JSON), each only when set; facts
    /// without them (as before format 2.4) read with none, and their JSON is
    /// unchanged.
    #[test]
    fn the_dynamics_round_trip_and_facts_without_them_read_as_before() {
        let species = [Species::new(40, 0.5, 1.0)];
        let sim_box = SimBox::walled(10.0, 30.0, 1.0);
        let plain = RunFacts::new(
            &species,
            &sim_box,
            &EngineParams::default(),
            &LogOptions::default(),
        );
        let v = plain.to_json();
        for key in ["gravity", "thermostat", "growth", "floor", "neighbours"] {
            assert!(v.get(key).is_none(), "{key} in {v}");
        }
        let back = RunFacts::from_json(&v).unwrap();
        assert_eq!(
            (back.thermostat, back.growth, back.floor, back.neighbours),
            (None, None, None, Neighbours::Auto)
        );
        assert_eq!(back.to_json().to_string(), v.to_string());
        let growth = Growth {
            rate: 0.1,
            target_scale: 1.1,
            kt: 0.7,
            rescale_interval: 0.3,
            max_reduced_pressure: 500.0,
        };
        let floor = Floor {
            amplitude: 0.05,
            omega: 2.0 * std::f64::consts::PI * 3.0,
        };
        let cases = [
            (
                Thermostat::Andersen { kt: 1.3, rate: 0.1 },
                EngineParams {
                    growth,
                    ..EngineParams::default()
                },
            ),
            (
                Thermostat::Driven {
                    xi2: 0.02,
                    interval: 1.0 / 3.0,
                },
                EngineParams {
                    gravity: 9.81,
                    floor: Some(floor),
                    ..EngineParams::default()
                },
            ),
        ];
        for (thermostat, params) in cases {
            let f = RunFacts::new(&species, &sim_box, &params, &LogOptions::default())
                .with_thermostat(Some(thermostat));
            let text = f.to_json().to_string();
            let back = RunFacts::from_json(&serde_json::from_str(&text).unwrap()).unwrap();
            assert_eq!(back, f);
            assert_eq!(back.to_json().to_string(), text);
            assert_eq!(back.thermostat, Some(thermostat));
            assert_eq!(back.growth.is_some(), params.growth.rate != 0.0);
            assert_eq!(back.floor, params.floor);
        }
        let v = RunFacts::new(&species, &sim_box, &cases[0].1, &LogOptions::default())
            .with_thermostat(Some(cases[0].0))
            .to_json();
        assert_eq!(v["thermostat"]["kind"], "andersen");
        assert_eq!(v["growth"]["target_scale"], 1.1);
        let mut bad = v.clone();
        bad["thermostat"]["xi2"] = serde_json::json!(1.0);
        assert!(RunFacts::from_json(&bad).is_err());
    }

    /// The neighbour setting round-trips by name (auto left out), and an unknown
    /// name is refused, saying what is allowed.
    #[test]
    fn the_neighbour_setting_round_trips_by_name() {
        let species = [Species::new(40, 0.5, 1.0)];
        let sim_box = SimBox::walled(10.0, 30.0, 1.0);
        for (neighbours, json) in [
            (Neighbours::Auto, None),
            (Neighbours::Cells, Some("cells")),
            (Neighbours::Lists, Some("lists")),
        ] {
            let params = EngineParams {
                neighbours,
                ..EngineParams::default()
            };
            let f = RunFacts::new(&species, &sim_box, &params, &LogOptions::default());
            let v = f.to_json();
            assert_eq!(v.get("neighbours").and_then(Value::as_str), json);
            let back = RunFacts::from_json(&v).unwrap();
            assert_eq!(back.neighbours, neighbours);
            assert_eq!(back, f);
        }
        let mut bad = RunFacts::new(
            &species,
            &sim_box,
            &EngineParams::default(),
            &LogOptions::default(),
        )
        .to_json();
        bad["neighbours"] = serde_json::json!("grid");
        assert_eq!(
            RunFacts::from_json(&bad).unwrap_err(),
            "neighbours: unknown setting \"grid\" (allowed: auto, cells, lists)"
        );
    }

    #[test]
    fn only_facts_of_format_2_4_on_hold_the_dynamics() {
        for (format, hold) in [
            ("1.2", false),
            ("2.3", false),
            ("2.4", true),
            ("2.10", true),
            ("3.0", true),
            ("", false),
            ("2", false),
            ("two.four", false),
        ] {
            assert_eq!(RunFacts::hold_dynamics(format), hold, "{format}");
        }
        assert!(RunFacts::hold_dynamics(crate::LOG_FORMAT_VERSION));
    }
}
