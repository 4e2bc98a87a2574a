//! `carom.Simulation.from_arrays`: a system given as arrays (positions,
//! velocities, radii and masses or species, box, boundaries, collision rule)
//! made into the configuration `carom run` would read for it, with
//! `placement.explicit` and `velocities.explicit`, so that the checks, the
//! messages and the trajectory are the command's. Only what JSON cannot say is
//! checked here: shapes, lengths, finite numbers, species indices.
//!
//! Discs of one (radius, mass) make a species, numbered in order of first
//! appearance. The configuration lists each species' discs together (that is
//! how explicit placement orders them); when the user's discs are not so
//! grouped, the simulation keeps the user's index of each engine disc
//! (`user_of`), so that disc i of `state` is the user's disc i. Errors name the
//! argument and the user's disc (`x[3]`, `radius[5]`), not the configuration.

use std::collections::HashMap;

use carom_config::ConfigError;
use carom_engine::InitError;
use numpy::{PyArray1, PyArrayMethods};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyDictMethods};
use serde_json::{json, Map, Value};

/// Configuration fields the arrays set themselves.
const SET_BY_ARRAYS: [&str; 2] = ["placement", "velocities"];

/// A number or one per disc.
pub enum PerDisc {
    /// The same for every disc.
    All(f64),
    /// One per disc.
    Each(Vec<f64>),
}

/// The discs' kinds: per-disc radius and mass, or species indices into tables.
pub enum Kinds {
    /// Radius and mass of each disc (or of all).
    Discs { radius: PerDisc, mass: PerDisc },
    /// Species of each disc, with each species' radius and mass.
    Species {
        species: Vec<f64>,
        radius: Vec<f64>,
        mass: Vec<f64>,
    },
}

/// What `from_arrays` hands to the simulation: the configuration's text, the
/// user's index of each engine disc (if not the same), and how to name errors.
pub struct Prepared {
    /// The configuration as JSON text.
    pub text: String,
    /// The user's index of engine disc k, when the discs were regrouped.
    pub user_of: Option<Vec<u32>>,
    names: Names,
}

/// How configuration fields are named as arguments.
struct Names {
    /// Which argument gave the radii (and masses): `radius`, `radius[k]`, or
    /// `species_radius[s]`, by the first user disc of each species.
    kinds: KindNames,
    first_of: Vec<usize>,
    user_of: Option<Vec<u32>>,
}

enum KindNames {
    Scalar { radius: bool, mass: bool },
    Species,
}

/// A column of floats from any array-like: one-dimensional, finite numbers.
pub fn floats(name: &str, obj: &Bound<'_, PyAny>) -> PyResult<Vec<f64>> {
    let py = obj.py();
    let kw = PyDict::new(py);
    kw.set_item("dtype", "float64")?;
    let a = py
        .import("numpy")?
        .call_method("asarray", (obj,), Some(&kw))
        .map_err(|e| PyValueError::new_err(format!("{name}: not an array of numbers ({e})")))?;
    let a = a.cast_into::<PyArray1<f64>>().map_err(|e| {
        let shape = e.into_inner().getattr("shape").map(|s| s.to_string());
        PyValueError::new_err(format!(
            "{name}: an array of one number per disc is needed, got shape {}",
            shape.unwrap_or_default()
        ))
    })?;
    let v = a.readonly().to_vec()?;
    if let Some(k) = v.iter().position(|x| !x.is_finite()) {
        return Err(PyValueError::new_err(format!(
            "{name}[{k}] = {}: not a finite number",
            v[k]
        )));
    }
    Ok(v)
}

/// A number for every disc, or one per disc: `None` is `default`.
pub fn per_disc(name: &str, obj: Option<&Bound<'_, PyAny>>, default: f64) -> PyResult<PerDisc> {
    match obj {
        None => Ok(PerDisc::All(default)),
        // A number (a Python float, or a numpy scalar of dimension 0).
        Some(o)
            if o.extract::<f64>().is_ok()
                && !o.getattr("ndim").is_ok_and(|d| d.to_string() != "0") =>
        {
            Ok(PerDisc::All(o.extract()?))
        }
        Some(o) => floats(name, o).map(PerDisc::Each),
    }
}

fn same_length(name: &str, v: &[f64], n: usize) -> PyResult<()> {
    if v.len() == n {
        return Ok(());
    }
    Err(PyValueError::new_err(format!(
        "{name}: {} values for {n} discs (one per disc, as x)",
        v.len()
    )))
}

impl PerDisc {
    fn at(&self, i: usize) -> f64 {
        match self {
            PerDisc::All(a) => *a,
            PerDisc::Each(v) => v[i],
        }
    }
}

/// The configuration of discs at `x`, `y` moving at `vx`, `vy`, of `kinds`, in
/// the box `sim_box` (the configuration's `box`) with the other configuration
/// fields `rest`.
pub fn prepare(
    [x, y, vx, vy]: [Vec<f64>; 4],
    kinds: Kinds,
    sim_box: Map<String, Value>,
    rest: Map<String, Value>,
) -> PyResult<Prepared> {
    let n = x.len();
    if n == 0 {
        return Err(PyValueError::new_err(
            "x: no discs (at least one is needed)",
        ));
    }
    for (name, v) in [("y", &y), ("vx", &vx), ("vy", &vy)] {
        same_length(name, v, n)?;
    }
    for key in rest.keys() {
        if SET_BY_ARRAYS.contains(&key.as_str()) {
            return Err(PyValueError::new_err(format!(
                "{key}: set by the arrays (x, y, vx, vy); leave it out"
            )));
        }
    }
    // The species of each disc, and each species' radius and mass.
    let (species_of, table, kind_names) = match kinds {
        Kinds::Discs { radius, mass } => {
            for (name, v) in [("radius", &radius), ("mass", &mass)] {
                if let PerDisc::Each(v) = v {
                    same_length(name, v, n)?;
                }
            }
            let mut index: HashMap<(u64, u64), usize> = HashMap::new();
            let mut table = Vec::new();
            let species_of: Vec<usize> = (0..n)
                .map(|i| {
                    let (a, m) = (radius.at(i), mass.at(i));
                    *index.entry((a.to_bits(), m.to_bits())).or_insert_with(|| {
                        table.push((a, m));
                        table.len() - 1
                    })
                })
                .collect();
            let names = KindNames::Scalar {
                radius: matches!(radius, PerDisc::All(_)),
                mass: matches!(mass, PerDisc::All(_)),
            };
            (species_of, table, names)
        }
        Kinds::Species {
            species,
            radius,
            mass,
        } => {
            same_length("species", &species, n)?;
            if mass.len() != radius.len() {
                return Err(PyValueError::new_err(format!(
                    "species_mass: {} values for {} species (one per species_radius)",
                    mass.len(),
                    radius.len()
                )));
            }
            let s = radius.len();
            let species_of = species
                .iter()
                .enumerate()
                .map(|(i, &k)| {
                    if k.fract() == 0.0 && k >= 0.0 && (k as usize) < s {
                        Ok(k as usize)
                    } else {
                        Err(PyValueError::new_err(format!(
                            "species[{i}] = {k}: not a species (allowed: integers 0 to {}, \
                             indices into species_radius)",
                            s.saturating_sub(1)
                        )))
                    }
                })
                .collect::<PyResult<Vec<usize>>>()?;
            let table = radius.into_iter().zip(mass).collect();
            (species_of, table, KindNames::Species)
        }
    };
    if table.len() > usize::from(u16::MAX) + 1 {
        return Err(PyValueError::new_err(format!(
            "radius, mass: {} distinct (radius, mass) pairs (allowed: at most 65536 kinds of disc)",
            table.len()
        )));
    }
    // The configuration's order: species by species, each in the user's order
    // (a stable counting sort).
    let mut count = vec![0usize; table.len()];
    for &s in &species_of {
        count[s] += 1;
    }
    let mut start: Vec<usize> = count
        .iter()
        .scan(0, |acc, &c| {
            let s = *acc;
            *acc += c;
            Some(s)
        })
        .collect();
    let first_of: Vec<usize> = (0..table.len())
        .map(|s| species_of.iter().position(|&k| k == s).unwrap_or(0))
        .collect();
    let mut user_of = vec![0u32; n];
    for (i, &s) in species_of.iter().enumerate() {
        user_of[start[s]] = i as u32;
        start[s] += 1;
    }
    let sorted = user_of.iter().enumerate().all(|(k, &i)| k == i as usize);
    let species: Vec<Value> = table
        .iter()
        .zip(&count)
        .map(|(&(a, m), &c)| json!({"count": c, "radius": a, "mass": m}))
        .collect();
    let pairs = |a: &[f64], b: &[f64]| -> Vec<[f64; 2]> {
        user_of
            .iter()
            .map(|&i| [a[i as usize], b[i as usize]])
            .collect()
    };
    let mut config = rest;
    config.insert("species".into(), Value::Array(species));
    config.insert("box".into(), Value::Object(sim_box));
    config.insert("placement".into(), json!({"explicit": pairs(&x, &y)}));
    config.insert("velocities".into(), json!({"explicit": pairs(&vx, &vy)}));
    Ok(Prepared {
        text: Value::Object(config).to_string(),
        user_of: (!sorted).then(|| user_of.clone()),
        names: Names {
            kinds: kind_names,
            first_of,
            user_of: Some(user_of),
        },
    })
}

impl Prepared {
    /// The user's index of engine disc `k`.
    fn user(&self, k: usize) -> usize {
        self.names.user_of.as_ref().map_or(k, |u| u[k] as usize)
    }

    /// A builder's error in the user's terms: discs by the user's index, fields
    /// by argument (`x[3]`), the problem in the command's words.
    pub fn init_error(&self, e: InitError, config_json: &str) -> ConfigError {
        let e = match e {
            InitError::Overlap {
                i,
                j,
                distance,
                sigma,
            } => InitError::Overlap {
                i: self.user(i),
                j: self.user(j),
                distance,
                sigma,
            },
            InitError::Invalid {
                field,
                problem,
                allowed,
            } => {
                if let Some((k, axis)) = disc_field(&field, "positions") {
                    let field = format!("{axis}[{}]", self.user(k));
                    return ConfigError::Invalid {
                        field,
                        problem,
                        allowed,
                    };
                }
                if let Some((k, _)) = disc_field(&field, "velocities") {
                    let k = self.user(k);
                    let field = format!("vx[{k}], vy[{k}]");
                    return ConfigError::Invalid {
                        field,
                        problem,
                        allowed,
                    };
                }
                InitError::Invalid {
                    field,
                    problem,
                    allowed,
                }
            }
        };
        self.config_error(ConfigError::from_init_in(e, config_json))
    }

    /// A configuration error with its field named as the argument it came from.
    pub fn config_error(&self, e: ConfigError) -> ConfigError {
        let ConfigError::Invalid {
            field,
            problem,
            allowed,
        } = e
        else {
            return e;
        };
        let parts: Vec<&str> = field.split('.').collect();
        let field = match parts.as_slice() {
            ["placement", "explicit", k] => index_of(k, |k| format!("x[{k}], y[{k}]"), self),
            ["placement", ..] => "x, y".into(),
            ["velocities", "explicit", k] => index_of(k, |k| format!("vx[{k}], vy[{k}]"), self),
            ["velocities", ..] => "vx, vy".into(),
            ["species", s, what @ ("radius" | "mass")] => self.kind_name(s, what),
            ["box", "boundary", ..] => "boundaries".into(),
            ["box", "wall_restitution"] => "wall_restitution".into(),
            ["box", ..] => "box".into(),
            _ => field.clone(),
        };
        ConfigError::Invalid {
            field,
            problem,
            allowed,
        }
    }

    /// `radius`, `radius[i]` (the first disc of species `s`) or `species_radius[s]`.
    fn kind_name(&self, s: &str, what: &str) -> String {
        let Ok(s) = s.parse::<usize>() else {
            return what.into();
        };
        match self.names.kinds {
            KindNames::Species => format!("species_{what}[{s}]"),
            KindNames::Scalar { radius, mass } => {
                let scalar = if what == "radius" { radius } else { mass };
                match (scalar, self.names.first_of.get(s)) {
                    (false, Some(i)) => format!("{what}[{i}]"),
                    _ => what.into(),
                }
            }
        }
    }
}

/// The user's index in a field `k` (an engine disc's index), named by `name`.
fn index_of(k: &str, name: impl Fn(usize) -> String, p: &Prepared) -> String {
    k.parse::<usize>()
        .map_or_else(|_| k.to_owned(), |k| name(p.user(k)))
}

/// The disc and component of a builder's field `list[k].axis` (`positions[3].x`).
fn disc_field<'a>(field: &'a str, list: &str) -> Option<(usize, &'a str)> {
    let rest = field.strip_prefix(list)?.strip_prefix('[')?;
    let (k, axis) = rest.split_once(']')?;
    Some((k.parse().ok()?, axis.trim_start_matches('.')))
}
