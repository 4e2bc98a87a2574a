//! A sweep plan: a base configuration, the dotted configuration paths to vary with
//! their values (a list, or a range), and replicas by seed, expanded into the grid
//! of points it names (every combination of the varied values, times the
//! replicas). Each point's configuration is the base with `--set path=value`
//! applied for each varied path and the seed set, checked as `carom run` would
//! check it, so a bad value is reported before anything runs. Point names are
//! readable and unique: `packing_fraction=0.3,seed=2`.

use std::path::Path;

use carom_io::{apply_set, Config};
use serde::de::{MapAccess, Visitor};
use serde::{Deserialize, Deserializer};
use serde_json::Value;

use super::SweepError;

/// A plan as written (`data/sweeps/*.json`; its schema is `data/sweep.schema.json`).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
struct PlanFile {
    /// The schema, for editors (ignored).
    #[serde(default, rename = "$schema")]
    _schema: Option<String>,
    /// Words for people (ignored).
    #[serde(default)]
    description: Option<String>,
    /// The base configuration: a file (relative to the plan) or the object itself.
    base: Value,
    /// Dotted path → values, in the order written.
    #[serde(default)]
    vary: OrderedMap,
    /// Runs per grid point, seeds `seed`, `seed` + 1, … Default 1.
    #[serde(default = "one")]
    replicas: u32,
    /// Seed of the first replica; default: the base's `seed`, or 1.
    #[serde(default)]
    seed: Option<u64>,
}

fn one() -> u32 {
    1
}

/// A JSON object's entries in the order written.
#[derive(Debug, Clone, Default)]
struct OrderedMap(Vec<(String, Value)>);

impl<'de> Deserialize<'de> for OrderedMap {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V;
        impl<'de> Visitor<'de> for V {
            type Value = OrderedMap;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("an object of dotted paths to values")
            }
            fn visit_map<A: MapAccess<'de>>(self, mut m: A) -> Result<OrderedMap, A::Error> {
                let mut out = Vec::new();
                while let Some((k, v)) = m.next_entry::<String, Value>()? {
                    out.push((k, v));
                }
                Ok(OrderedMap(out))
            }
        }
        d.deserialize_map(V)
    }
}

/// One varied configuration path and its values.
#[derive(Debug, Clone, PartialEq)]
pub struct Axis {
    /// Dotted configuration path, e.g. `box.packing_fraction`.
    pub path: String,
    /// Its values, in order.
    pub values: Vec<Value>,
}

/// A checked, expanded plan.
#[derive(Debug, Clone)]
pub struct Plan {
    /// The plan's own description, if it has one.
    pub description: Option<String>,
    /// The base configuration (the file's contents if `base` named a file).
    pub base: Value,
    /// The varied paths, in the order written.
    pub axes: Vec<Axis>,
    /// Runs per grid point.
    pub replicas: u32,
    /// Seed of the first replica.
    pub first_seed: u64,
    /// Every point, grid order (the last axis fastest), replicas innermost.
    pub points: Vec<Point>,
}

/// One run of a sweep.
#[derive(Debug, Clone, PartialEq)]
pub struct Point {
    /// Its directory name under the sweep's output, e.g. `packing_fraction=0.3,seed=2`.
    pub name: String,
    /// The varied paths' values at this point (one per axis).
    pub values: Vec<Value>,
    /// Its seed.
    pub seed: u64,
    /// Its full configuration (the base with the values and the seed set).
    pub config: Value,
}

impl Plan {
    /// Read and expand the plan file at `path`.
    pub fn load(path: &Path) -> Result<Plan, SweepError> {
        let text = carom_io::read_config_text(path).map_err(|source| SweepError::Io {
            path: path.to_path_buf(),
            source,
        })?;
        let dir = path.parent().map(Path::to_path_buf).unwrap_or_default();
        Plan::from_json(&text, &path.display().to_string(), &dir)
    }

    /// Expand plan text (`origin` names it in errors; a `base` file is read
    /// relative to `dir`).
    pub fn from_json(text: &str, origin: &str, dir: &Path) -> Result<Plan, SweepError> {
        let bad = |field: &str, problem: String, allowed: &str| SweepError::Plan {
            plan: origin.to_owned(),
            field: field.to_owned(),
            problem,
            allowed: allowed.to_owned(),
        };
        let file: PlanFile = serde_json::from_str(text).map_err(|e| {
            bad(
                "(plan)",
                e.to_string(),
                "an object with base, vary, replicas, seed (data/sweep.schema.json)",
            )
        })?;
        let base = match file.base {
            Value::String(p) => read_base(&dir.join(&p), origin)?,
            v @ Value::Object(_) => v,
            other => {
                return Err(bad(
                    "base",
                    format!("{other} is neither a file name nor an object"),
                    "a configuration file (relative to the plan) or a configuration object",
                ))
            }
        };
        if file.replicas == 0 {
            return Err(bad("replicas", "0".into(), "1 or more"));
        }
        let mut axes = Vec::new();
        for (path, spec) in file.vary.0 {
            let field = format!("vary.{path}");
            if path == "seed" {
                return Err(bad(
                    &field,
                    "the seed is set by replicas".into(),
                    "replicas and seed (the first replica's seed)",
                ));
            }
            let values = axis_values(&spec).map_err(|(p, a)| bad(&field, p, a))?;
            axes.push(Axis { path, values });
        }
        let first_seed = match file.seed {
            Some(s) => s,
            None => base.get("seed").and_then(Value::as_u64).unwrap_or(1),
        };
        let points = expand(&base, &axes, file.replicas, first_seed, origin)?;
        Ok(Plan {
            description: file.description,
            base,
            axes,
            replicas: file.replicas,
            first_seed,
            points,
        })
    }
}

fn read_base(path: &Path, origin: &str) -> Result<Value, SweepError> {
    let text = carom_io::read_config_text(path).map_err(|e| SweepError::Plan {
        plan: origin.to_owned(),
        field: "base".into(),
        problem: format!("cannot read {}: {e}", path.display()),
        allowed: "a configuration file (relative to the plan) or a configuration object".into(),
    })?;
    let text = text.strip_prefix('\u{feff}').unwrap_or(&text);
    serde_json::from_str(text).map_err(|e| SweepError::Plan {
        plan: origin.to_owned(),
        field: "base".into(),
        problem: format!("{}: {e}", path.display()),
        allowed: "a JSON configuration file".into(),
    })
}

/// The values of one axis: a non-empty list, or `{"from", "to", "count"}`
/// (inclusive, evenly spaced; `"scale": "log"` for a geometric progression).
fn axis_values(spec: &Value) -> Result<Vec<Value>, (String, &'static str)> {
    const ALLOWED: &str = "a non-empty list of values, or {\"from\": a, \"to\": b, \"count\": n} \
                           (n ≥ 2 evenly spaced, ends included; \"scale\": \"log\" for geometric)";
    match spec {
        Value::Array(list) if !list.is_empty() => Ok(list.clone()),
        Value::Object(o) => {
            let num = |k: &str| o.get(k).and_then(Value::as_f64);
            let (Some(from), Some(to), Some(count)) = (
                num("from"),
                num("to"),
                o.get("count").and_then(Value::as_u64),
            ) else {
                return Err((format!("{spec} lacks from, to or count"), ALLOWED));
            };
            if let Some(k) = o
                .keys()
                .find(|k| !["from", "to", "count", "scale"].contains(&k.as_str()))
            {
                return Err((format!("unknown key `{k}`"), ALLOWED));
            }
            let log = match o.get("scale").map(|s| s.as_str()) {
                None | Some(Some("linear")) => false,
                Some(Some("log")) => true,
                Some(_) => return Err(("scale is not \"linear\" or \"log\"".into(), ALLOWED)),
            };
            if !(2..=100_000).contains(&count) {
                return Err((format!("count {count}"), ALLOWED));
            }
            if log && !(from > 0.0 && to > 0.0) {
                return Err((format!("log scale from {from} to {to}"), ALLOWED));
            }
            Ok((0..count)
                .map(|k| {
                    let f = k as f64 / (count - 1) as f64;
                    let x = if log {
                        from * (to / from).powf(f)
                    } else {
                        from + (to - from) * f
                    };
                    Value::from(round12(x))
                })
                .collect())
        }
        _ => Err((format!("{spec}"), ALLOWED)),
    }
}

/// `x` to 12 significant digits, so that ranges give 0.3, not 0.30000000000000004.
fn round12(x: f64) -> f64 {
    format!("{x:.11e}").parse().expect("a formatted f64 parses")
}

/// Every point of the grid: the last axis fastest, replicas innermost.
fn expand(
    base: &Value,
    axes: &[Axis],
    replicas: u32,
    first_seed: u64,
    origin: &str,
) -> Result<Vec<Point>, SweepError> {
    let labels = labels(axes);
    let mut grid: Vec<Vec<Value>> = vec![vec![]];
    for axis in axes {
        grid = grid
            .into_iter()
            .flat_map(|head| {
                axis.values.iter().map(move |v| {
                    let mut h = head.clone();
                    h.push(v.clone());
                    h
                })
            })
            .collect();
    }
    let mut points = Vec::new();
    for values in grid {
        for r in 0..replicas as u64 {
            let seed = first_seed + r;
            let mut config = base.clone();
            let mut parts = Vec::new();
            for ((axis, v), label) in axes.iter().zip(&values).zip(&labels) {
                apply_set(&mut config, &format!("{}={v}", axis.path)).map_err(|e| {
                    SweepError::Point {
                        plan: origin.to_owned(),
                        point: format!("{}={v}", axis.path),
                        problem: e.to_string(),
                    }
                })?;
                parts.push(format!("{label}={}", value_text(v)));
            }
            config["seed"] = Value::from(seed);
            if replicas > 1 || parts.is_empty() {
                parts.push(format!("seed={seed}"));
            }
            let name = parts.join(",");
            Config::from_value(config.clone())
                .and_then(|c| c.to_run_spec().map(|_| ()))
                .map_err(|e| SweepError::Point {
                    plan: origin.to_owned(),
                    point: name.clone(),
                    problem: e.to_string(),
                })?;
            points.push(Point {
                name,
                values: values.clone(),
                seed,
                config,
            });
        }
    }
    let mut names: Vec<&str> = points.iter().map(|p| p.name.as_str()).collect();
    names.sort_unstable();
    if let Some(w) = names.windows(2).find(|w| w[0] == w[1]) {
        return Err(SweepError::Plan {
            plan: origin.to_owned(),
            field: "vary".into(),
            problem: format!("two points are both named {}", w[0]),
            allowed: "distinct values along each path".into(),
        });
    }
    Ok(points)
}

/// Each axis's label in point names: the last segment of its path, or the whole
/// path where two axes share a last segment.
fn labels(axes: &[Axis]) -> Vec<String> {
    let last = |p: &str| p.rsplit('.').next().unwrap_or(p).to_owned();
    axes.iter()
        .map(|a| {
            let l = last(&a.path);
            let shared = axes.iter().filter(|b| last(&b.path) == l).count() > 1;
            if shared {
                a.path.clone()
            } else {
                l
            }
        })
        .collect()
}

/// A value as it appears in a point's name: strings bare, `/` and whitespace
/// replaced, anything else as compact JSON.
fn value_text(v: &Value) -> String {
    let s = match v {
        Value::String(s) => s.clone(),
        other => other.to_string(),
    };
    s.chars()
        .map(|c| {
            if c == '/' || c.is_whitespace() || c == '"' {
                '_'
            } else {
                c
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn plan(text: &str) -> Result<Plan, SweepError> {
        Plan::from_json(text, "test plan", Path::new("."))
    }

    #[test]
    fn a_grid_times_replicas_in_written_order() {
        let p = plan(
            r#"{"base": {"species": [{"count": 50}], "stop": {"duration": 1}},
                "vary": {"box.packing_fraction": [0.2, 0.3], "temperature": [1, 2]},
                "replicas": 2, "seed": 7}"#,
        )
        .unwrap();
        let names: Vec<&str> = p.points.iter().map(|p| p.name.as_str()).collect();
        assert_eq!(names.len(), 8);
        assert_eq!(names[0], "packing_fraction=0.2,temperature=1,seed=7");
        assert_eq!(names[1], "packing_fraction=0.2,temperature=1,seed=8");
        assert_eq!(names[2], "packing_fraction=0.2,temperature=2,seed=7");
        assert_eq!(names[7], "packing_fraction=0.3,temperature=2,seed=8");
        let last = &p.points[7].config;
        assert_eq!(last["box"]["packing_fraction"], 0.3);
        assert_eq!(last["temperature"], 2);
        assert_eq!(last["seed"], 8);
        assert_eq!(last["species"][0]["count"], 50);
    }

    #[test]
    fn ranges_are_inclusive_and_rounded() {
        let lin = axis_values(&serde_json::json!({"from": 0.1, "to": 0.5, "count": 5})).unwrap();
        assert_eq!(
            lin,
            serde_json::json!([0.1, 0.2, 0.3, 0.4, 0.5])
                .as_array()
                .unwrap()
                .clone()
        );
        let log =
            axis_values(&serde_json::json!({"from": 1, "to": 100, "count": 3, "scale": "log"}))
                .unwrap();
        assert_eq!(
            log,
            vec![Value::from(1.0), Value::from(10.0), Value::from(100.0)]
        );
    }

    #[test]
    fn without_axes_or_replicas_the_one_point_is_named_by_its_seed() {
        let p = plan(r#"{"base": {}}"#).unwrap();
        assert_eq!(p.points.len(), 1);
        assert_eq!(p.points[0].name, "seed=1");
    }

    #[test]
    fn shared_last_segments_use_the_whole_path() {
        let p = plan(
            r#"{"base": {"species": [{"count": 20}, {"count": 20, "radius": 0.7}]},
                "vary": {"species.0.count": [10], "species.1.count": [30]}}"#,
        )
        .unwrap();
        assert_eq!(p.points[0].name, "species.0.count=10,species.1.count=30");
    }

    #[test]
    fn bad_plans_name_the_field_and_what_is_allowed() {
        let e = plan(r#"{"base": {}, "vary": {"box.packing_fraction": []}}"#)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("vary.box.packing_fraction") && e.contains("non-empty list"),
            "{e}"
        );
        let e = plan(r#"{"base": {}, "vary": {"box.packing_fraction": [0.2, 0.95]}}"#)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("packing_fraction=0.95") && e.contains("box.packing_fraction"),
            "{e}"
        );
        let e = plan(r#"{"base": {}, "replicas": 0}"#)
            .unwrap_err()
            .to_string();
        assert!(e.contains("replicas"), "{e}");
        let e = plan(r#"{"base": {}, "vary": {"seed": [1, 2]}}"#)
            .unwrap_err()
            .to_string();
        assert!(e.contains("vary.seed"), "{e}");
        let e = plan(r#"{"base": {}, "extra": 1}"#).unwrap_err().to_string();
        assert!(e.contains("extra"), "{e}");
        let e = plan(r#"{"base": {}, "vary": {"temperature": [1, 1]}}"#)
            .unwrap_err()
            .to_string();
        assert!(e.contains("temperature=1"), "{e}");
    }

    /// The schema names exactly the fields the plan reader accepts, and the
    /// shipped example expands into its eight packing fractions × two replicas.
    #[test]
    fn the_schema_and_the_example_match_the_reader() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR"));
        let schema: Value = serde_json::from_str(
            &std::fs::read_to_string(root.join("data/sweep.schema.json")).unwrap(),
        )
        .unwrap();
        let mut keys: Vec<&str> = schema["properties"]
            .as_object()
            .unwrap()
            .keys()
            .map(String::as_str)
            .collect();
        keys.sort_unstable();
        assert_eq!(
            keys,
            ["$schema", "base", "description", "replicas", "seed", "vary"]
        );
        let eos = Plan::load(&root.join("data/sweeps/eos.json")).unwrap();
        assert_eq!(eos.points.len(), 16);
        let etas: Vec<f64> = eos
            .points
            .iter()
            .step_by(2)
            .map(|p| p.config["box"]["packing_fraction"].as_f64().unwrap())
            .collect();
        assert_eq!(etas, [0.1, 0.2, 0.3, 0.4, 0.5, 0.55, 0.6, 0.68]);
        assert_eq!(eos.points[1].name, "packing_fraction=0.1,seed=2");
    }
}
