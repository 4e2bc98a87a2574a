//! The box's boundary conditions as the configuration writes them: one word for
//! both axes (`"periodic"`, `"walls"`) or one per axis (`{"x": "periodic", "y":
//! "walls"}`, a channel). The JSON is a string or an object, so serde and the
//! schema (`anyOf` of the two) are written here by hand; the engine's
//! boundaries are built from [`BoundaryConfig::axes`] in `resolve`.

use schemars::JsonSchema;
use serde::{Deserialize, Deserializer, Serialize};

/// The boundary condition of one axis.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum AxisBoundary {
    /// `"periodic"`: minimum-image distances, discs re-enter on the other side.
    Periodic,
    /// `"walls"`: hard walls at 0 and L, disc centres stay in [a, L − a].
    Walls,
}

/// Boundaries of both axes: the same on both or one per axis.
#[derive(Debug, Clone, Copy, PartialEq, Eq, JsonSchema)]
#[schemars(untagged, deny_unknown_fields)]
pub enum BoundaryConfig {
    /// The same boundary on x and y (`"periodic"` or `"walls"`).
    Both(AxisBoundary),
    /// One per axis (`{"x": "periodic", "y": "walls"}`: a channel).
    PerAxis {
        /// Boundary of the x axis.
        x: AxisBoundary,
        /// Boundary of the y axis.
        y: AxisBoundary,
    },
}

impl Default for BoundaryConfig {
    fn default() -> Self {
        BoundaryConfig::Both(AxisBoundary::Periodic)
    }
}

impl BoundaryConfig {
    /// The boundaries of the x and y axes.
    pub fn axes(&self) -> [AxisBoundary; 2] {
        match *self {
            BoundaryConfig::Both(b) => [b, b],
            BoundaryConfig::PerAxis { x, y } => [x, y],
        }
    }
}

#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct PerAxis {
    x: AxisBoundary,
    y: AxisBoundary,
}

impl Serialize for BoundaryConfig {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match *self {
            BoundaryConfig::Both(b) => b.serialize(s),
            BoundaryConfig::PerAxis { x, y } => PerAxis { x, y }.serialize(s),
        }
    }
}

impl<'de> Deserialize<'de> for BoundaryConfig {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V;
        impl<'de> serde::de::Visitor<'de> for V {
            type Value = BoundaryConfig;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str(
                    "\"periodic\", \"walls\" or an object {\"x\": ..., \"y\": ...} \
                     with \"periodic\" or \"walls\" per axis",
                )
            }
            fn visit_str<E: serde::de::Error>(self, s: &str) -> Result<Self::Value, E> {
                match s {
                    "periodic" => Ok(BoundaryConfig::Both(AxisBoundary::Periodic)),
                    "walls" => Ok(BoundaryConfig::Both(AxisBoundary::Walls)),
                    _ => Err(E::invalid_value(serde::de::Unexpected::Str(s), &self)),
                }
            }
            fn visit_map<A: serde::de::MapAccess<'de>>(
                self,
                map: A,
            ) -> Result<Self::Value, A::Error> {
                let p = PerAxis::deserialize(serde::de::value::MapAccessDeserializer::new(map))?;
                Ok(BoundaryConfig::PerAxis { x: p.x, y: p.y })
            }
        }
        d.deserialize_any(V)
    }
}
