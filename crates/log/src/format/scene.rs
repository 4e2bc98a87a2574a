//! The optional `/scene` channel: the discs as Foxglove draws them, in Foxglove's
//! own schema `foxglove_msgs/msg/SceneUpdate` (`ros2msg` text [`SCENE_UPDATE_MSG`],
//! CDR), so its 3D panel shows a run with no plug-in.
//!
//! Each frame is one entity `"discs"` in frame `"box"` (it replaces the previous
//! frame's), stamped with the simulated time as seconds and nanoseconds
//! ([`log_time_ns`]) and carrying the exact time as metadata `time`. Disc i is a
//! cylinder at (xᵢ, yᵢ, 0) of size (dᵢ, dᵢ, dᵢ/10), dᵢ = 2rᵢ, coloured by species
//! ([`SPECIES_COLORS`]); the box [0, Lx] × [0, Ly] is a closed line loop. A
//! cylinder takes 128 bytes (16 `float64`); see docs/log-format.md, "/scene".

use super::cdr::CdrWriter;
use super::log_time_ns;
use carom_core::SimBox;
use carom_engine::State;

/// `ros2msg` text of the schema `foxglove_msgs/msg/SceneUpdate`: Foxglove's
/// definitions (foxglove/schemas, `ros_foxglove_msgs/ros2`, comments dropped) with
/// every dependency after a `MSG:` header, as ROS 2 stores a message definition.
pub const SCENE_UPDATE_MSG: &str = "\
# foxglove_msgs/msg/SceneUpdate, written by carom: one entity \"discs\" per frame
foxglove_msgs/SceneEntityDeletion[] deletions
foxglove_msgs/SceneEntity[] entities
================================================================================
MSG: foxglove_msgs/SceneEntityDeletion
builtin_interfaces/Time timestamp
uint8 MATCHING_ID=0
uint8 ALL=1
uint8 type
string id
================================================================================
MSG: foxglove_msgs/SceneEntity
builtin_interfaces/Time timestamp
string frame_id
string id
builtin_interfaces/Duration lifetime
bool frame_locked
foxglove_msgs/KeyValuePair[] metadata
foxglove_msgs/ArrowPrimitive[] arrows
foxglove_msgs/CubePrimitive[] cubes
foxglove_msgs/SpherePrimitive[] spheres
foxglove_msgs/CylinderPrimitive[] cylinders
foxglove_msgs/LinePrimitive[] lines
foxglove_msgs/TriangleListPrimitive[] triangles
foxglove_msgs/TextPrimitive[] texts
foxglove_msgs/ModelPrimitive[] models
================================================================================
MSG: builtin_interfaces/Time
int32 sec
uint32 nanosec
================================================================================
MSG: builtin_interfaces/Duration
int32 sec
uint32 nanosec
================================================================================
MSG: foxglove_msgs/KeyValuePair
string key
string value
================================================================================
MSG: foxglove_msgs/ArrowPrimitive
geometry_msgs/Pose pose
float64 shaft_length
float64 shaft_diameter
float64 head_length
float64 head_diameter
foxglove_msgs/Color color
================================================================================
MSG: foxglove_msgs/CubePrimitive
geometry_msgs/Pose pose
geometry_msgs/Vector3 size
foxglove_msgs/Color color
================================================================================
MSG: foxglove_msgs/SpherePrimitive
geometry_msgs/Pose pose
geometry_msgs/Vector3 size
foxglove_msgs/Color color
================================================================================
MSG: foxglove_msgs/CylinderPrimitive
geometry_msgs/Pose pose
geometry_msgs/Vector3 size
float64 bottom_scale
float64 top_scale
foxglove_msgs/Color color
================================================================================
MSG: foxglove_msgs/LinePrimitive
uint8 LINE_STRIP=0
uint8 LINE_LOOP=1
uint8 LINE_LIST=2
uint8 type
geometry_msgs/Pose pose
float64 thickness
bool scale_invariant
geometry_msgs/Point[] points
foxglove_msgs/Color color
foxglove_msgs/Color[] colors
uint32[] indices
================================================================================
MSG: foxglove_msgs/TriangleListPrimitive
geometry_msgs/Pose pose
geometry_msgs/Point[] points
foxglove_msgs/Color color
foxglove_msgs/Color[] colors
uint32[] indices
================================================================================
MSG: foxglove_msgs/TextPrimitive
geometry_msgs/Pose pose
bool billboard
float64 font_size
bool scale_invariant
foxglove_msgs/Color color
string text
================================================================================
MSG: foxglove_msgs/ModelPrimitive
geometry_msgs/Pose pose
geometry_msgs/Vector3 scale
foxglove_msgs/Color color
bool override_color
string url
string media_type
uint8[] data
================================================================================
MSG: foxglove_msgs/Color
float64 r
float64 g
float64 b
float64 a
================================================================================
MSG: geometry_msgs/Pose
geometry_msgs/Point position
geometry_msgs/Quaternion orientation
================================================================================
MSG: geometry_msgs/Point
float64 x
float64 y
float64 z
================================================================================
MSG: geometry_msgs/Quaternion
float64 x 0
float64 y 0
float64 z 0
float64 w 1
================================================================================
MSG: geometry_msgs/Vector3
float64 x
float64 y
float64 z
";

/// The entity's `frame_id`: the box, with the origin at its corner (0, 0).
pub const SCENE_FRAME: &str = "box";
/// The entity's `id`: every frame replaces the previous one.
pub const SCENE_ENTITY: &str = "discs";
/// Cylinder height over diameter: flat discs seen from above, visible edge-on.
pub const DISC_HEIGHT_RATIO: f64 = 0.1;
/// Colour of species k is `SPECIES_COLORS[k % 10]` (RGB in [0, 1], opaque):
/// matplotlib's `tab10` palette (blue, orange, green, red, purple, brown, pink,
/// grey, olive, cyan).
pub const SPECIES_COLORS: [[f64; 3]; 10] = [
    [0.122, 0.467, 0.706],
    [1.0, 0.498, 0.055],
    [0.173, 0.627, 0.173],
    [0.839, 0.153, 0.157],
    [0.580, 0.404, 0.741],
    [0.549, 0.337, 0.294],
    [0.890, 0.467, 0.761],
    [0.498, 0.498, 0.498],
    [0.737, 0.741, 0.133],
    [0.090, 0.745, 0.812],
];
/// Colour of the box outline (RGBA): white.
pub const BOX_COLOR: [f64; 4] = [1.0, 1.0, 1.0, 1.0];
/// Width of the box outline in screen pixels (`scale_invariant`).
pub const BOX_LINE_PIXELS: f64 = 2.0;
/// `LinePrimitive.type` of the box: `LINE_LOOP`, a closed polygon.
const LINE_LOOP: u8 = 1;

/// Bytes of one cylinder in CDR (16 `float64`, always 8-aligned here).
pub const CYLINDER_BYTES: usize = 128;

/// The size (x, y, z) of the cylinder of a disc of radius `r`: (d, d, d/10),
/// d = 2r. The scene's geometry rules ([`disc_size`], [`species_color`],
/// [`box_outline`], [`scene_stamp`]) are public so that a live viewer's frames
/// (carom-live) draw exactly what the log's do.
pub fn disc_size(r: f64) -> [f64; 3] {
    let d = 2.0 * r;
    [d, d, d * DISC_HEIGHT_RATIO]
}

/// The colour (RGB in [0, 1]) of species `s`: [`SPECIES_COLORS`], cycled.
pub fn species_color(s: u16) -> [f64; 3] {
    SPECIES_COLORS[s as usize % SPECIES_COLORS.len()]
}

/// The corners (x, y) of the box outline [0, Lx] × [0, Ly], counter-clockwise
/// from the origin (a closed loop).
pub fn box_outline(b: &SimBox) -> [(f64, f64); 4] {
    let (lx, ly) = (b.size.x, b.size.y);
    [(0.0, 0.0), (lx, 0.0), (lx, ly), (0.0, ly)]
}

/// `builtin_interfaces/Time` of simulated time `t`: the log time split into
/// whole seconds and nanoseconds, saturating at the latest time it holds
/// (2³¹ − 1 s and 999 999 999 ns, about 68 years of simulated seconds).
pub fn scene_stamp(t: f64) -> (i32, u32) {
    let ns = log_time_ns(t);
    match i32::try_from(ns / 1_000_000_000) {
        Ok(sec) => (sec, (ns % 1_000_000_000) as u32),
        Err(_) => (i32::MAX, 999_999_999),
    }
}

/// An identity pose at (x, y, z).
fn pose(w: &mut CdrWriter, x: f64, y: f64, z: f64) {
    for v in [x, y, z, 0.0, 0.0, 0.0, 1.0] {
        w.put(v);
    }
}

/// Encode the `/scene` frame of `state` into `w` (which is reset first).
pub fn encode_scene(state: &State, w: &mut CdrWriter) {
    let n = state.positions.len();
    w.reset();
    w.reserve(1024 + n * CYLINDER_BYTES);
    w.put(0u32); // deletions
    w.put(1u32); // entities
    let (sec, nanosec) = scene_stamp(state.time);
    w.put(sec);
    w.put(nanosec);
    w.string(SCENE_FRAME);
    w.string(SCENE_ENTITY);
    w.put(0i32); // lifetime: until replaced
    w.put(0u32);
    w.put(0u8); // frame_locked
    w.put(1u32); // metadata: the exact time
    w.string("time");
    w.string(&format!("{:?}", state.time));
    for _ in 0..3 {
        w.put(0u32); // arrows, cubes, spheres
    }
    w.put(u32::try_from(n).expect("at most 2^32 - 1 discs"));
    for (p, &s) in state.positions.iter().zip(&state.species_of) {
        let [dx, dy, h] = disc_size(state.species[s as usize].radius);
        let [r, g, b] = species_color(s);
        pose(w, p.x, p.y, 0.0);
        for v in [dx, dy, h, 1.0, 1.0, r, g, b, 1.0] {
            w.put(v);
        }
    }
    w.put(1u32); // lines: the box
    w.put(LINE_LOOP);
    pose(w, 0.0, 0.0, 0.0);
    w.put(BOX_LINE_PIXELS);
    w.put(1u8); // scale_invariant
    w.put(4u32);
    for (x, y) in box_outline(&state.sim_box) {
        for v in [x, y, 0.0] {
            w.put(v);
        }
    }
    for v in BOX_COLOR {
        w.put(v);
    }
    w.put(0u32); // colors
    w.put(0u32); // indices
    for _ in 0..3 {
        w.put(0u32); // triangles, texts, models
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::format::cdr::{CdrError, CdrReader};

    /// What a `/scene` frame says, decoded (carom's own readers skip the channel).
    #[derive(Debug, Clone, PartialEq)]
    struct SceneFrame {
        /// `timestamp` as (sec, nanosec).
        stamp: (i32, u32),
        /// The exact simulated time from the metadata `time`.
        time: f64,
        /// Per cylinder: (x, y, diameter, height, RGB).
        discs: Vec<(f64, f64, f64, f64, [f64; 3])>,
        /// The box outline's corners.
        outline: Vec<(f64, f64)>,
    }

    impl SceneFrame {
        /// Decode a frame written by [`encode_scene`] (one entity, one line
        /// primitive, no other primitives).
        fn decode(data: &[u8]) -> Result<Self, CdrError> {
            let mut r = CdrReader::new(data)?;
            let count = |r: &mut CdrReader, field: &'static str, want: u32| {
                let n = r.get::<u32>(field)?;
                if n == want {
                    Ok(())
                } else {
                    Err(CdrError::Invalid {
                        field,
                        problem: format!("{n} entries, carom writes {want}"),
                    })
                }
            };
            count(&mut r, "deletions", 0)?;
            count(&mut r, "entities", 1)?;
            let stamp = (
                r.get::<i32>("timestamp.sec")?,
                r.get::<u32>("timestamp.nanosec")?,
            );
            for (field, want) in [("frame_id", SCENE_FRAME), ("id", SCENE_ENTITY)] {
                let s = r.string(field)?;
                if s != want {
                    return Err(CdrError::Invalid {
                        field,
                        problem: format!("{s:?}, carom writes {want:?}"),
                    });
                }
            }
            r.skip::<u32>("lifetime", 2)?;
            r.get::<u8>("frame_locked")?;
            count(&mut r, "metadata", 1)?;
            r.string("metadata.key")?;
            let time = r
                .string("metadata.value")?
                .parse()
                .map_err(|e| CdrError::Invalid {
                    field: "metadata.value",
                    problem: format!("not a time: {e}"),
                })?;
            for field in ["arrows", "cubes", "spheres"] {
                count(&mut r, field, 0)?;
            }
            let n = r.get::<u32>("cylinders")? as usize;
            let mut discs = Vec::with_capacity(n.min(r.remaining() / CYLINDER_BYTES));
            for _ in 0..n {
                let v: [f64; 16] = r.fixed("cylinders")?;
                if v[8] != v[7] {
                    return Err(CdrError::Invalid {
                        field: "cylinders.size",
                        problem: format!("an ellipse {} × {}", v[7], v[8]),
                    });
                }
                discs.push((v[0], v[1], v[7], v[9], [v[12], v[13], v[14]]));
            }
            count(&mut r, "lines", 1)?;
            r.get::<u8>("lines.type")?;
            r.skip::<f64>("lines.pose", 7)?;
            r.get::<f64>("lines.thickness")?;
            r.get::<u8>("lines.scale_invariant")?;
            let k = r.get::<u32>("lines.points")? as usize;
            let mut outline = Vec::new();
            for _ in 0..k {
                let p: [f64; 3] = r.fixed("lines.points")?;
                outline.push((p[0], p[1]));
            }
            r.skip::<f64>("lines.color", 4)?;
            for field in [
                "lines.colors",
                "lines.indices",
                "triangles",
                "texts",
                "models",
            ] {
                count(&mut r, field, 0)?;
            }
            Ok(SceneFrame {
                stamp,
                time,
                discs,
                outline,
            })
        }
    }

    fn state() -> State {
        use carom_core::{Boundary, DVec2, SimBox, Species};
        State {
            sim_box: SimBox {
                size: DVec2::new(7.5, 4.0),
                boundary: [Boundary::Periodic, Boundary::Walls { restitution: 0.9 }],
            },
            species: vec![Species::reference(2), Species::new(1, 0.7, 2.5)],
            species_of: vec![0, 1, 0],
            positions: vec![
                DVec2::new(1.0, 1.0),
                DVec2::new(3.0, 2.0),
                DVec2::new(5.5, 2.5),
            ],
            velocities: vec![DVec2::new(0.1, -0.2); 3],
            images: Vec::new(),
            time: 2.75,
        }
    }

    #[test]
    fn a_frame_holds_each_disc_at_its_place_and_size_and_the_box() {
        let s = state();
        let mut w = CdrWriter::new();
        w.reuse(vec![0xAB; 8192]);
        encode_scene(&s, &mut w);
        let f = SceneFrame::decode(w.bytes()).unwrap();
        assert_eq!(f.stamp, (2, 750_000_000));
        assert_eq!(f.time, 2.75);
        let d0 = 2.0 * s.species[0].radius;
        assert_eq!(
            f.discs,
            vec![
                // Cylinders as tall as a tenth of their diameter (docs/log-format.md).
                (1.0, 1.0, d0, 0.1 * d0, SPECIES_COLORS[0]),
                (3.0, 2.0, 1.4, 0.1 * 1.4, SPECIES_COLORS[1]),
                (5.5, 2.5, d0, 0.1 * d0, SPECIES_COLORS[0]),
            ]
        );
        assert_eq!(
            f.outline,
            vec![(0.0, 0.0), (7.5, 0.0), (7.5, 4.0), (0.0, 4.0)]
        );
        // Bytes: each cylinder is 128 (16 float64), the rest does not depend on N.
        let mut one = s.clone();
        one.positions.truncate(1);
        one.species_of.truncate(1);
        let mut w1 = CdrWriter::new();
        encode_scene(&one, &mut w1);
        assert_eq!(w.bytes().len() - w1.bytes().len(), 2 * CYLINDER_BYTES);
        // A cut frame is an error, not a panic.
        let cut = &w.bytes()[..w.bytes().len() - 5];
        assert!(SceneFrame::decode(cut).is_err());
    }

    #[test]
    fn stamps_split_the_log_time_and_saturate() {
        assert_eq!(scene_stamp(0.0), (0, 0));
        assert_eq!(scene_stamp(1.5), (1, 500_000_000));
        assert_eq!(scene_stamp(1e12), (i32::MAX, 999_999_999));
        assert_eq!(scene_stamp(2147483647.0), (i32::MAX, 0));
    }

    #[test]
    fn every_type_the_schema_names_is_defined_once() {
        let builtin = ["bool", "uint8", "int32", "uint32", "float64", "string"];
        let mut defined = vec![];
        let mut used = vec![];
        for line in SCENE_UPDATE_MSG.lines() {
            if let Some(name) = line.strip_prefix("MSG: ") {
                defined.push(name);
            } else if !(line.starts_with('#') || line.starts_with('=') || line.is_empty()) {
                let ty = line.split_whitespace().next().unwrap();
                let ty = ty.split('[').next().unwrap();
                if !builtin.contains(&ty) {
                    used.push(ty);
                }
            }
        }
        for ty in &used {
            assert_eq!(defined.iter().filter(|d| d == &ty).count(), 1, "{ty}");
        }
        for d in &defined {
            assert!(used.contains(d), "{d} is defined but not used");
        }
    }
}
