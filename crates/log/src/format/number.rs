//! Floating-point numbers in the log's text: one rule for every writer and reader.
//!
//! JSON has no number for NaN or ±∞ (serde_json writes them as `null`, which no
//! `f64` reads back), yet a run can end with them: a runaway error leaves K = NaN,
//! a thermostat at kT = 1e308 gives K = +∞. So every float the log stores as text
//! (the `carom.run` and `carom.summary` metadata values, `/thermo` records, the
//! JSON inside metadata such as `run_facts`, `stop`, `log_options`) is written as
//!
//! * a finite x: its shortest round-trip decimal (a JSON number);
//! * NaN, +∞, −∞: the text `NaN`, `Infinity`, `-Infinity` (inside JSON, a string).
//!
//! Readers accept exactly these, and also `null` (what carom wrote before this
//! rule) as NaN. `docs/log-format.md` ("Numbers") states the rule for other readers.

use serde::de::{self, Deserializer, Visitor};
use serde::ser::Serializer;
use serde_json::Value;

/// The text of a non-finite `x`, or `None` for a finite one.
fn non_finite_name(x: f64) -> Option<&'static str> {
    if x.is_nan() {
        Some("NaN")
    } else if x == f64::INFINITY {
        Some("Infinity")
    } else if x == f64::NEG_INFINITY {
        Some("-Infinity")
    } else {
        None
    }
}

/// The value named by one of the non-finite texts (`NaN`, `Infinity`, `-Infinity`).
fn non_finite_value(s: &str) -> Option<f64> {
    match s {
        "NaN" => Some(f64::NAN),
        "Infinity" => Some(f64::INFINITY),
        "-Infinity" => Some(f64::NEG_INFINITY),
        _ => None,
    }
}

/// `x` as a JSON value: a number, or the string `NaN`, `Infinity`, `-Infinity`.
pub fn f64_to_json(x: f64) -> Value {
    match non_finite_name(x) {
        Some(name) => Value::String(name.into()),
        None => Value::from(x),
    }
}

/// A float from a JSON value written by [`f64_to_json`] (or `null`, read as NaN).
pub fn f64_from_json(v: &Value) -> Option<f64> {
    match v {
        Value::Number(n) => n.as_f64(),
        Value::String(s) => non_finite_value(s),
        Value::Null => Some(f64::NAN),
        _ => None,
    }
}

/// `x` as a metadata value: shortest round-trip decimal, or `NaN`, `Infinity`,
/// `-Infinity`.
pub fn f64_to_text(x: f64) -> String {
    match non_finite_name(x) {
        Some(name) => name.into(),
        None => Value::from(x).to_string(),
    }
}

/// A float from a metadata value written by [`f64_to_text`] (or `null`, read as
/// NaN); `None` for anything else.
pub fn f64_from_text(s: &str) -> Option<f64> {
    if let Some(x) = non_finite_value(s) {
        return Some(x);
    }
    if s == "null" {
        return Some(f64::NAN);
    }
    // A decimal only: Rust's parser would also take "inf" or "nan", which carom
    // never writes.
    let decimal = |c: char| c.is_ascii_digit() || matches!(c, '-' | '+' | '.' | 'e' | 'E');
    if s.is_empty() || !s.chars().all(decimal) {
        return None;
    }
    s.parse().ok()
}

struct FloatVisitor;

impl<'de> Visitor<'de> for FloatVisitor {
    type Value = f64;
    fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        f.write_str("a number, or \"NaN\", \"Infinity\", \"-Infinity\"")
    }
    fn visit_f64<E: de::Error>(self, x: f64) -> Result<f64, E> {
        Ok(x)
    }
    fn visit_i64<E: de::Error>(self, x: i64) -> Result<f64, E> {
        Ok(x as f64)
    }
    fn visit_u64<E: de::Error>(self, x: u64) -> Result<f64, E> {
        Ok(x as f64)
    }
    fn visit_str<E: de::Error>(self, s: &str) -> Result<f64, E> {
        non_finite_value(s).ok_or_else(|| E::invalid_value(de::Unexpected::Str(s), &self))
    }
    fn visit_unit<E: de::Error>(self) -> Result<f64, E> {
        Ok(f64::NAN)
    }
}

/// `#[serde(with = "number::float")]`: an `f64` field under the rule above.
pub mod float {
    use super::*;

    /// Write `x` as a JSON number or a non-finite name.
    pub fn serialize<S: Serializer>(x: &f64, s: S) -> Result<S::Ok, S::Error> {
        match non_finite_name(*x) {
            Some(name) => s.serialize_str(name),
            None => s.serialize_f64(*x),
        }
    }

    /// Read a number, a non-finite name or `null` (NaN).
    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
        d.deserialize_any(FloatVisitor)
    }
}

/// `#[serde(with = "number::opt_float")]`: an optional `f64` field (absent or
/// `null`: `None`) under the rule above.
pub mod opt_float {
    use super::*;
    use serde::Deserialize;

    /// Write `Some(x)` as [`float::serialize`] does (`None` is skipped by the field).
    pub fn serialize<S: Serializer>(x: &Option<f64>, s: S) -> Result<S::Ok, S::Error> {
        match x {
            Some(x) => float::serialize(x, s),
            None => s.serialize_none(),
        }
    }

    /// Read a number, a non-finite name, or `null` (`None`).
    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<Option<f64>, D::Error> {
        #[derive(Deserialize)]
        struct Wrap(#[serde(with = "float")] f64);
        Option::<Wrap>::deserialize(d).map(|w| w.map(|Wrap(x)| x))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const SAMPLES: [f64; 8] = [
        0.0,
        -0.0,
        1.5,
        0.1 + 0.2,
        -3.0e-300,
        f64::MAX,
        f64::INFINITY,
        f64::NEG_INFINITY,
    ];

    fn same(a: f64, b: f64) -> bool {
        a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan())
    }

    #[test]
    fn every_float_round_trips_through_text_and_json() {
        for x in SAMPLES.into_iter().chain([f64::NAN]) {
            let text = f64_to_text(x);
            assert!(same(f64_from_text(&text).unwrap(), x), "{x}: {text}");
            let json = f64_to_json(x);
            let back: Value = serde_json::from_str(&json.to_string()).unwrap();
            assert!(same(f64_from_json(&back).unwrap(), x), "{x}: {json}");
        }
        assert_eq!(f64_to_text(f64::NAN), "NaN");
        assert_eq!(f64_to_text(f64::NEG_INFINITY), "-Infinity");
        assert_eq!(f64_to_json(f64::INFINITY), Value::String("Infinity".into()));
    }

    #[test]
    fn null_reads_as_nan_and_other_words_are_refused() {
        assert!(f64_from_text("null").unwrap().is_nan());
        assert!(f64_from_json(&Value::Null).unwrap().is_nan());
        for bad in ["", "inf", "nan", "infinity", "1.0x", "true"] {
            assert_eq!(f64_from_text(bad), None, "{bad}");
        }
        assert_eq!(f64_from_json(&Value::String("inf".into())), None);
    }

    #[test]
    fn serde_fields_follow_the_rule() {
        #[derive(serde::Serialize, serde::Deserialize, Debug)]
        struct R {
            #[serde(with = "float")]
            a: f64,
            #[serde(default, with = "opt_float", skip_serializing_if = "Option::is_none")]
            b: Option<f64>,
        }
        for x in SAMPLES.into_iter().chain([f64::NAN]) {
            let text = serde_json::to_string(&R { a: x, b: Some(x) }).unwrap();
            let r: R = serde_json::from_str(&text).unwrap();
            assert!(same(r.a, x) && same(r.b.unwrap(), x), "{text}");
        }
        let r: R = serde_json::from_str(r#"{"a": null, "b": null}"#).unwrap();
        assert!(r.a.is_nan() && r.b.is_none());
        let r: R = serde_json::from_str(r#"{"a": 3}"#).unwrap();
        assert_eq!((r.a, r.b), (3.0, None));
        assert!(serde_json::from_str::<R>(r#"{"a": "inf"}"#).is_err());
    }
}
