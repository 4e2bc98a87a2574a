//! The resolved run as plain data ([`RunFacts`]), stored since log format 1.2 as
//! the JSON value `run_facts` of the `carom.run` metadata: the species, the box
//! and its boundaries, the pair collision rule, N, the collision logging stride
//! and the area disc centres can reach (physics.md §5). A reader learns the
//! system from here instead of re-running the configuration through the front end
//! and the placement code. Logs of format ≤ 1.1 have no facts.
//!
//! The JSON uses the configuration's words: `{"species": [{"count", "radius",
//! "mass"}], "box": {"size": [Lx, Ly], "boundary": ["periodic" | "walls", …],
//! "wall_restitution": [e_w or null, …]}, "collision": {"model", "coefficient",
//! "tc"}, "n_discs", "collision_every" (null when collisions are not logged),
//! "accessible_area", "gravity" (only when not 0)}`; every number in shortest
//! round-trip form.

use crate::options::LogOptions;
use carom_core::observables::{accessible_area, disc_count};
use carom_core::{Boundary, DVec2, Restitution, SimBox, Species};
use carom_engine::EngineParams;
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
}

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
}
