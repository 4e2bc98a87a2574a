//! The live `/scene` frame: the discs of a state as Foxglove's own
//! `foxglove.SceneUpdate` (protobuf, the SDK's type), drawn by the rules of the
//! log's `/scene` (carom-log: one entity `"discs"` in frame `"box"`, disc i a
//! cylinder at (xᵢ, yᵢ, 0) of size (dᵢ, dᵢ, dᵢ/10), the box a closed line loop,
//! the timestamp the simulated time as seconds, the exact time as metadata
//! `time`), so that one layout shows a live run and a log alike. Only the colours
//! may differ: by species as in the log, or by speed ([`Colouring`]).

use carom_engine::State;
use carom_log::{
    box_outline, disc_size, scene_stamp, BOX_COLOR, BOX_LINE_PIXELS, SCENE_ENTITY, SCENE_FRAME,
};
use foxglove::messages::{
    line_primitive, Color, CylinderPrimitive, KeyValuePair, LinePrimitive, Point3, Pose,
    Quaternion, SceneEntity, SceneUpdate, Timestamp, Vector3,
};

use crate::colour::{colours, Colouring};

/// An identity pose at (x, y, 0).
fn pose(x: f64, y: f64) -> Option<Pose> {
    Some(Pose {
        position: Some(Vector3 { x, y, z: 0.0 }),
        orientation: Some(Quaternion {
            x: 0.0,
            y: 0.0,
            z: 0.0,
            w: 1.0,
        }),
    })
}

/// An opaque colour.
fn opaque([r, g, b]: [f64; 3]) -> Option<Color> {
    Some(Color { r, g, b, a: 1.0 })
}

/// The `/scene` frame of `state`, its discs coloured by `colouring`.
pub(crate) fn scene_update(state: &State, colouring: Colouring) -> SceneUpdate {
    let (sec, nsec) = scene_stamp(state.time);
    let cylinders = state
        .positions
        .iter()
        .zip(&state.species_of)
        .zip(colours(state, colouring))
        .map(|((p, &s), c)| {
            let [x, y, z] = disc_size(state.species[s as usize].radius);
            CylinderPrimitive {
                pose: pose(p.x, p.y),
                size: Some(Vector3 { x, y, z }),
                bottom_scale: 1.0,
                top_scale: 1.0,
                color: opaque(c),
            }
        })
        .collect();
    let [r, g, b, a] = BOX_COLOR;
    let outline = LinePrimitive {
        r#type: line_primitive::Type::LineLoop as i32,
        pose: pose(0.0, 0.0),
        thickness: BOX_LINE_PIXELS,
        scale_invariant: true,
        points: box_outline(&state.sim_box)
            .iter()
            .map(|&(x, y)| Point3 { x, y, z: 0.0 })
            .collect(),
        color: Some(Color { r, g, b, a }),
        colors: Vec::new(),
        indices: Vec::new(),
    };
    SceneUpdate {
        deletions: Vec::new(),
        entities: vec![SceneEntity {
            // Simulated time is never negative; the log's stamp saturates at 2³¹ − 1 s.
            timestamp: Some(Timestamp::new(sec.max(0) as u32, nsec)),
            frame_id: SCENE_FRAME.into(),
            id: SCENE_ENTITY.into(),
            lifetime: None,
            frame_locked: false,
            metadata: vec![KeyValuePair {
                key: "time".into(),
                value: format!("{:?}", state.time),
            }],
            cylinders,
            lines: vec![outline],
            ..SceneEntity::default()
        }],
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use carom_core::{Boundary, DVec2, SimBox, Species};

    fn state() -> State {
        State {
            sim_box: SimBox {
                size: DVec2::new(7.5, 4.0),
                boundary: [Boundary::Periodic, Boundary::Periodic],
            },
            species: vec![Species::reference(2), Species::new(1, 0.7, 2.5)],
            species_of: vec![0, 1],
            positions: vec![DVec2::new(1.0, 1.0), DVec2::new(3.0, 2.0)],
            velocities: vec![DVec2::new(0.1, -0.2); 2],
            images: Vec::new(),
            time: 2.75,
        }
    }

    #[test]
    fn a_frame_draws_what_the_log_draws() {
        let s = state();
        let u = scene_update(&s, Colouring::Species);
        let e = &u.entities[0];
        assert_eq!((e.frame_id.as_str(), e.id.as_str()), ("box", "discs"));
        assert_eq!(e.timestamp, Some(Timestamp::new(2, 750_000_000)));
        assert_eq!(e.metadata[0].value, "2.75");
        let c = &e.cylinders[1];
        let p = c.pose.unwrap().position.unwrap();
        assert_eq!((p.x, p.y, p.z), (3.0, 2.0, 0.0));
        let size = c.size.unwrap();
        assert_eq!((size.x, size.y), (1.4, 1.4));
        assert!((size.z - 0.14).abs() < 1e-15);
        let col = c.color.unwrap();
        assert_eq!([col.r, col.g, col.b], carom_log::SPECIES_COLORS[1]);
        let corners: Vec<_> = e.lines[0].points.iter().map(|p| (p.x, p.y)).collect();
        assert_eq!(corners, [(0.0, 0.0), (7.5, 0.0), (7.5, 4.0), (0.0, 4.0)]);
    }

    #[test]
    fn by_speed_the_same_speed_has_the_same_colour() {
        let mut s = state();
        s.velocities = vec![DVec2::new(0.3, 0.4), DVec2::new(-0.5, 0.0)];
        let u = scene_update(&s, Colouring::Speed);
        let c: Vec<_> = u.entities[0].cylinders.iter().map(|c| c.color).collect();
        assert_eq!(c[0], c[1]);
        s.velocities[1] = DVec2::new(0.0, 0.0);
        let u = scene_update(&s, Colouring::Speed);
        let c: Vec<_> = u.entities[0].cylinders.iter().map(|c| c.color).collect();
        assert_ne!(c[0], c[1]);
    }
}
