//! A sweep plan: a base configuration, the dotted configuration paths to vary with
//! their values (a list, or a range), and replicas by seed, expanded into the grid
//! of points it names (every combination of the varied values, times the
//! replicas). Each point's configuration is the base with `--set path=value`
//! applied for each varied path and the seed set, checked as `carom run` would
//! check it, so a bad value is reported before anything runs. Point names are
//! readable and unique: `packing_fraction=0.3,seed=2` (see [`super::names`]).
//! The number of points, Π (values per axis) × replicas, is counted before any
//! is made and refused above [`MAX_POINTS`]; each point's configuration is built
//! when it is needed ([`Plan::config`]), not held for all points at once.

use std::path::Path;

use carom_config::{apply_set, Config};
use carom_log::RunSpec;
use serde::de::{MapAccess, Visitor};
use serde::{Deserialize, Deserializer};
use serde_json::Value;

use super::names::{labels, shown, unusable, value_text};
use super::SweepError;

/// The most points a plan may expand to (documented in docs/sweeps.md): far more
/// than a cluster's job array takes (Slurm's default `MaxArraySize` is 1001),
/// and few enough that a plan is read, checked and laid out in seconds.
pub const MAX_POINTS: u64 = 100_000;

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
    /// Where the plan came from, for errors.
    origin: String,
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
}

impl Plan {
    /// Read and expand the plan file at `path`.
    pub fn load(path: &Path) -> Result<Plan, SweepError> {
        let text = carom_config::read_config_text(path).map_err(|source| SweepError::Io {
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
        if first_seed
            .checked_add(u64::from(file.replicas) - 1)
            .is_none()
        {
            return Err(bad(
                "seed",
                format!(
                    "{first_seed} with {} replicas: their seeds {first_seed} + r would pass \
                     2^64 - 1 = {} (seeds do not wrap round to 0)",
                    file.replicas,
                    u64::MAX
                ),
                &format!(
                    "a first seed of at most {}",
                    u64::MAX - (u64::from(file.replicas) - 1)
                ),
            ));
        }
        let count = axes.iter().fold(u128::from(file.replicas), |n, a| {
            n.saturating_mul(a.values.len() as u128)
        });
        if count > u128::from(MAX_POINTS) {
            let sizes: Vec<String> = axes.iter().map(|a| a.values.len().to_string()).collect();
            return Err(bad(
                if axes.is_empty() { "replicas" } else { "vary" },
                format!(
                    "the plan has {} points (values per axis: {}; replicas: {}), more than the \
                     {MAX_POINTS} a sweep may have",
                    if count == u128::MAX {
                        "more than 10^38".to_owned()
                    } else {
                        count.to_string()
                    },
                    if sizes.is_empty() {
                        "no axis".into()
                    } else {
                        sizes.join(" × ")
                    },
                    file.replicas
                ),
                &format!("at most {MAX_POINTS} points: split the plan into several sweeps"),
            ));
        }
        let mut plan = Plan {
            description: file.description,
            base,
            axes,
            replicas: file.replicas,
            first_seed,
            points: Vec::new(),
            origin: origin.to_owned(),
        };
        plan.points = plan.expand(count as usize)?;
        Ok(plan)
    }

    /// Point `i`'s full configuration: the base with its values and its seed set.
    pub fn config(&self, i: usize) -> Value {
        self.build(&self.points[i])
            .expect("every point's configuration was built when the plan was read")
    }

    /// Point `i`'s run as `carom run` would make it from [`Plan::config`].
    pub fn run_spec(&self, i: usize) -> RunSpec {
        Config::from_value(self.config(i))
            .and_then(|c| c.to_run_spec())
            .expect("every point's configuration was checked when the plan was read")
    }

    /// `point`'s configuration: the base with its values and its seed set.
    fn build(&self, point: &Point) -> Result<Value, SweepError> {
        let mut config = self.base.clone();
        for (axis, v) in self.axes.iter().zip(&point.values) {
            apply_set(&mut config, &format!("{}={v}", axis.path)).map_err(|e| {
                SweepError::Point {
                    plan: self.origin.clone(),
                    point: format!("{}={v}", axis.path),
                    problem: e.to_string(),
                }
            })?;
        }
        config["seed"] = Value::from(point.seed);
        Ok(config)
    }

    /// The `count` points of the grid, each checked (its name usable, its
    /// configuration one `carom run` accepts): the last axis fastest, replicas
    /// innermost.
    fn expand(&self, count: usize) -> Result<Vec<Point>, SweepError> {
        let labels = labels(&self.axes);
        let replicas = self.replicas as usize;
        let mut points = Vec::with_capacity(count);
        for k in 0..count {
            // Grid point g = k / replicas, its value index along each axis by
            // mixed radix, the last axis fastest.
            let (mut g, r) = (k / replicas, (k % replicas) as u64);
            let mut values = vec![Value::Null; self.axes.len()];
            for (a, axis) in self.axes.iter().enumerate().rev() {
                values[a] = axis.values[g % axis.values.len()].clone();
                g /= axis.values.len();
            }
            let seed = self.first_seed + r;
            let mut parts: Vec<String> = labels
                .iter()
                .zip(&values)
                .map(|(label, v)| format!("{label}={}", value_text(v)))
                .collect();
            if self.replicas > 1 || parts.is_empty() {
                parts.push(format!("seed={seed}"));
            }
            let point = Point {
                name: parts.join(","),
                values,
                seed,
            };
            let refuse = |problem: String| SweepError::Point {
                plan: self.origin.clone(),
                point: shown(&point.name),
                problem,
            };
            if let Some(why) = unusable(&point.name) {
                return Err(refuse(format!("its name, the directory it runs in, {why}")));
            }
            Config::from_value(self.build(&point)?)
                .and_then(|c| c.to_run_spec().map(|_| ()))
                .map_err(|e| refuse(e.to_string()))?;
            points.push(point);
        }
        let mut names: Vec<&str> = points.iter().map(|p| p.name.as_str()).collect();
        names.sort_unstable();
        if let Some(w) = names.windows(2).find(|w| w[0] == w[1]) {
            return Err(SweepError::Plan {
                plan: self.origin.clone(),
                field: "vary".into(),
                problem: format!("two points are both named {}", w[0]),
                allowed: "distinct values along each path".into(),
            });
        }
        Ok(points)
    }
}

fn read_base(path: &Path, origin: &str) -> Result<Value, SweepError> {
    let text = carom_config::read_config_text(path).map_err(|e| SweepError::Plan {
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
        let last = &p.config(7);
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

    /// Points are counted before any is made: a billion replicas, or a grid of
    /// 10¹⁰, is refused at once naming the count, and the limit itself passes.
    #[test]
    fn plans_past_the_point_limit_are_refused_naming_their_count() {
        let base = r#"{"species": [{"count": 20}], "stop": {"duration": 1}}"#;
        let e = plan(&format!(r#"{{"base": {base}, "replicas": 1000000000}}"#))
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("1000000000 points") && e.contains("100000"),
            "{e}"
        );
        let e = plan(&format!(
            r#"{{"base": {base}, "vary": {{
                "temperature": {{"from": 1, "to": 2, "count": 100000}},
                "box.packing_fraction": {{"from": 0.1, "to": 0.2, "count": 100000}}}}}}"#
        ))
        .unwrap_err()
        .to_string();
        assert!(e.contains("10000000000 points"), "{e}");
        let at_limit = plan(&format!(
            r#"{{"base": {base}, "vary": {{"temperature": {{"from": 1, "to": 2, "count": 1000}}}},
                "replicas": 100}}"#
        ))
        .unwrap();
        assert_eq!(at_limit.points.len() as u64, MAX_POINTS);
        assert_eq!(at_limit.points[99_999].name, "temperature=2.0,seed=100");
        assert_eq!(at_limit.config(99_999)["seed"], 100);
    }

    /// Replica r has seed `seed` + r: a first seed whose replicas would pass
    /// 2⁶⁴ − 1 is refused naming it; the largest that fits is accepted.
    #[test]
    fn replica_seeds_never_wrap_round() {
        let e = plan(r#"{"base": {}, "replicas": 2, "seed": 18446744073709551615}"#)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("seed")
                && e.contains("18446744073709551615")
                && e.contains("18446744073709551614"),
            "{e}"
        );
        let p = plan(r#"{"base": {}, "replicas": 2, "seed": 18446744073709551614}"#).unwrap();
        let seeds: Vec<u64> = p.points.iter().map(|p| p.seed).collect();
        assert_eq!(seeds, [u64::MAX - 1, u64::MAX]);
    }

    /// A point whose name cannot be a directory is refused when the plan is read.
    #[test]
    fn points_whose_names_cannot_be_directories_are_refused() {
        let long = "a".repeat(300);
        let e = plan(&format!(
            r#"{{"base": {{}}, "vary": {{"description": ["{long}"]}}}}"#
        ))
        .unwrap_err()
        .to_string();
        assert!(e.contains("312 bytes"), "{e}");
        let e = plan(r#"{"base": {}, "vary": {"description": ["a\u0000b"]}}"#)
            .unwrap_err()
            .to_string();
        assert!(e.contains("U+0000"), "{e}");
    }

    /// The schema names exactly the fields the plan reader accepts, and the
    /// shipped example expands into its eight packing fractions × two replicas.
    #[test]
    fn the_schema_and_the_example_match_the_reader() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
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
            .enumerate()
            .step_by(2)
            .map(|(i, _)| eos.config(i)["box"]["packing_fraction"].as_f64().unwrap())
            .collect();
        assert_eq!(etas, [0.1, 0.2, 0.3, 0.4, 0.5, 0.55, 0.6, 0.68]);
        assert_eq!(eos.points[1].name, "packing_fraction=0.1,seed=2");
    }
}
