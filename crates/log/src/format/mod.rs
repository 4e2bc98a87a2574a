//! The format of a carom log, shared by the writer and the reader: the
//! channels ([`CHANNELS`]: topic, schema, encodings), the version constants, the
//! metadata records, and each message's Rust form with its encoder and decoder.
//!
//! | topic | schema | encoding | content |
//! |---|---|---|---|
//! | `/collisions` | `carom_msgs/msg/CompactCollisionBatch` or (`collision_detail = "full"`, format 1) `carom_msgs/msg/CollisionBatch` (`ros2msg`) | `cdr` | [`CompactBatch`], [`CollisionBatch`] |
//! | `/snapshot` | `carom_msgs/msg/Snapshot` (`ros2msg`) | `cdr` | [`Snapshot`] |
//! | `/thermo` | `carom.Thermo` (`jsonschema`) | `json` | [`Thermo`] |
//! | `/checkpoint` | `carom_msgs/msg/Checkpoint` (`ros2msg`) | `cdr` | [`LogCheckpoint`] |
//! | `/scene` (optional) | `foxglove_msgs/msg/SceneUpdate` (`ros2msg`) | `cdr` | [`encode_scene`] |
//!
//! Message log times are simulated times in nanoseconds, taking one simulated time
//! unit as one second ([`log_time_ns`]). `docs/log-format.md` documents every field.

mod cdr;
mod checkpoint;
mod checksum;
mod collisions;
mod compact;
mod facts;
mod facts_dynamics;
mod metadata;
mod number;
mod scene;
#[cfg(test)]
mod schema_layout;
mod snapshot;
mod thermo;

pub use cdr::CdrError;
pub(crate) use cdr::{CdrReader, CdrWriter};
pub use checkpoint::{DriverState, LogCheckpoint, CHECKPOINT_FORMAT_VERSION, CHECKPOINT_MSG};
pub use checksum::{seal, verify, Checksum, CHECKSUM_KEY};
pub use collisions::{
    CollisionBatch, CollisionRecord, COLLISION_BATCH_MSG, KIND_PAIR, KIND_WALL, NO_DISC,
};
pub use compact::{
    wall_code, wall_of, CompactBatch, COMPACT_COLLISIONS_CHANNEL, COMPACT_COLLISION_BATCH_MSG,
    WALL_CODE_BASE,
};
pub use facts::RunFacts;
pub use metadata::{now_rfc3339, MetadataError, RunMetadata, StopReason, SummaryMetadata};
pub use scene::{
    box_outline, disc_size, encode_scene, scene_stamp, species_color, BOX_COLOR, BOX_LINE_PIXELS,
    SCENE_ENTITY, SCENE_FRAME, SCENE_UPDATE_MSG, SPECIES_COLORS,
};
pub use snapshot::{Snapshot, SNAPSHOT_MSG};
pub use thermo::{GrowthEvent, GrowthPhase, Thermo, THERMO_JSON_SCHEMA};

/// Topic of the collision batches.
pub const TOPIC_COLLISIONS: &str = "/collisions";
/// Topic of the snapshots.
pub const TOPIC_SNAPSHOT: &str = "/snapshot";
/// Topic of the thermodynamic records.
pub const TOPIC_THERMO: &str = "/thermo";
/// Topic of the checkpoints.
pub const TOPIC_CHECKPOINT: &str = "/checkpoint";
/// Topic of the optional Foxglove scene frames.
pub const TOPIC_SCENE: &str = "/scene";

/// Name of the metadata record written at the start of a run.
pub const METADATA_RUN: &str = "carom.run";
/// Name of the metadata record written at the end of a run.
pub const METADATA_SUMMARY: &str = "carom.summary";

/// Version of the log layout described here; stored in the `carom.run` metadata as
/// `log_format`. Readers reject files with a different major version.
///
/// 1.1: `/checkpoint` format 2 (each disc's pair candidate time; the engine's
/// internal clock and its epoch); a log 1.0 checkpoint cannot be resumed (its
/// reader reports the format). 1.2: `carom.run` gains `run_facts` ([`RunFacts`]);
/// the messages are unchanged, and 1.1 logs read with no facts. 2.0: `/collisions`
/// is by default the compact record ([`COMPACT_COLLISIONS_CHANNEL`]: time, discs,
/// impulse), replayed from a snapshot; the log options gain `collision_detail`
/// and `scene_interval` (the optional `/scene` channel); `carom.run` may hold
/// `max_time_without_collision`, and `carom.summary` the stop reason
/// `no_collision`. 2.1: `/snapshot` and `/checkpoint` (format 3) end with each
/// disc's periodic image; 2.0 files read with none. 2.2: `/thermo` records of
/// runs in a field carry U and K + U, those of runs with growing discs the scale,
/// η, the growth phase and Z, and such runs write an extra record after each
/// rescale and at the end of growth ([`GrowthEvent`]); `carom.summary` may hold
/// `potential_energy`; older files read with none. 2.3: `carom.run` and
/// `carom.summary` each carry a checksum (`crc32`, see `checksum`), so that a
/// damaged summary is left out with a warning, a damaged `carom.run` is an error,
/// and a failed data-section CRC in a log whose chunks and both records hold is a
/// warning; older files read as before. 2.4: `run_facts` holds the resolved
/// dynamics too — thermostat, growth, floor ([`RunFacts`]) — each only when the
/// run had it; older facts read without them. 2.5: every scheduled-event tag is
/// the caller's; a `/checkpoint` with a thermostat stores its next event as the
/// last scheduled entry of tag u64::MAX − 1 (layout unchanged; older checkpoints
/// read by the same rule, see `checkpoint::calendar`). 2.6: `/checkpoint`
/// (`format_version` 6) stores the neighbour setting and, on neighbour lists,
/// their skin and centres, and `run_facts` the setting when not auto; older
/// checkpoints and facts read auto, without lists. Readers accept 1.x (full
/// records) and 2.x.
pub const LOG_FORMAT_VERSION: &str = "2.6";

/// Major versions of the log format this carom reads.
pub const READABLE_MAJOR_VERSIONS: [&str; 2] = ["1", "2"];

/// Encoding of the JSON Schema `carom.Thermo`.
pub const SCHEMA_ENCODING_JSONSCHEMA: &str = "jsonschema";
/// Encoding of the `ros2msg` schemas.
pub const SCHEMA_ENCODING_ROS2MSG: &str = "ros2msg";
/// Message encoding of CDR channels.
pub const MESSAGE_ENCODING_CDR: &str = "cdr";
/// Message encoding of JSON channels.
pub const MESSAGE_ENCODING_JSON: &str = "json";
/// One channel of a carom log: its topic, its schema and the encodings.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Channel {
    /// The MCAP topic.
    pub topic: &'static str,
    /// The schema's name.
    pub schema_name: &'static str,
    /// The schema's encoding (`ros2msg` or `jsonschema`).
    pub schema_encoding: &'static str,
    /// The schema's text, stored in the file.
    pub schema_text: &'static str,
    /// The messages' encoding (`cdr` or `json`).
    pub message_encoding: &'static str,
}

/// Index of `/collisions` in [`CHANNELS`] and in per-channel arrays.
pub const CH_COLLISIONS: usize = 0;
/// Index of `/snapshot` in [`CHANNELS`] and in per-channel arrays.
pub const CH_SNAPSHOT: usize = 1;
/// Index of `/thermo` in [`CHANNELS`] and in per-channel arrays.
pub const CH_THERMO: usize = 2;
/// Index of `/checkpoint` in [`CHANNELS`] and in per-channel arrays.
pub const CH_CHECKPOINT: usize = 3;
/// Index of `/scene` in [`CHANNELS`] and in per-channel arrays. The writer
/// defines it only when a run writes scene frames; carom's readers skip it.
pub const CH_SCENE: usize = 4;
/// Number of channels: the length of [`CHANNELS`] and of per-channel arrays.
pub const N_CHANNELS: usize = 5;

/// The channels, in per-channel-array order ([`CH_COLLISIONS`] …).
pub const CHANNELS: [Channel; N_CHANNELS] = [
    Channel {
        topic: TOPIC_COLLISIONS,
        schema_name: "carom_msgs/msg/CollisionBatch",
        schema_encoding: SCHEMA_ENCODING_ROS2MSG,
        schema_text: COLLISION_BATCH_MSG,
        message_encoding: MESSAGE_ENCODING_CDR,
    },
    Channel {
        topic: TOPIC_SNAPSHOT,
        schema_name: "carom_msgs/msg/Snapshot",
        schema_encoding: SCHEMA_ENCODING_ROS2MSG,
        schema_text: SNAPSHOT_MSG,
        message_encoding: MESSAGE_ENCODING_CDR,
    },
    Channel {
        topic: TOPIC_THERMO,
        schema_name: "carom.Thermo",
        schema_encoding: SCHEMA_ENCODING_JSONSCHEMA,
        schema_text: THERMO_JSON_SCHEMA,
        message_encoding: MESSAGE_ENCODING_JSON,
    },
    Channel {
        topic: TOPIC_CHECKPOINT,
        schema_name: "carom_msgs/msg/Checkpoint",
        schema_encoding: SCHEMA_ENCODING_ROS2MSG,
        schema_text: CHECKPOINT_MSG,
        message_encoding: MESSAGE_ENCODING_CDR,
    },
    Channel {
        topic: TOPIC_SCENE,
        schema_name: "foxglove_msgs/msg/SceneUpdate",
        schema_encoding: SCHEMA_ENCODING_ROS2MSG,
        schema_text: SCENE_UPDATE_MSG,
        message_encoding: MESSAGE_ENCODING_CDR,
    },
];

/// Topics in per-channel-array order.
pub const TOPICS: [&str; N_CHANNELS] = [
    CHANNELS[0].topic,
    CHANNELS[1].topic,
    CHANNELS[2].topic,
    CHANNELS[3].topic,
    CHANNELS[4].topic,
];

/// MCAP log time of simulated time `t`: nanoseconds, one simulated time unit taken
/// as one second; negative times map to 0 and times beyond ~584 years saturate.
pub fn log_time_ns(t: f64) -> u64 {
    let ns = t * 1e9;
    if ns.is_nan() || ns <= 0.0 {
        0
    } else if ns >= u64::MAX as f64 {
        u64::MAX
    } else {
        ns.round() as u64
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn log_time_saturates() {
        assert_eq!(log_time_ns(-1.0), 0);
        assert_eq!(log_time_ns(f64::NAN), 0);
        assert_eq!(log_time_ns(1.5), 1_500_000_000);
        assert_eq!(log_time_ns(1e30), u64::MAX);
    }
}
