//! The three live channels, in a context of their own (so that two servers in
//! one process, or a Python session's runs, never mix): `/scene`
//! (`foxglove.SceneUpdate`, protobuf, the SDK's schema), `/thermo` (JSON, the
//! log's `carom.Thermo` schema) and `/progress` (JSON, `carom.Progress`). Every
//! message is stamped with its simulated time as log time (one time unit as one
//! second, carom-log's `log_time_ns`), as the log's messages are, so that plots
//! against time look the same live and from a file.

use std::sync::Arc;

use carom_log::{log_time_ns, Thermo, CH_SCENE, CH_THERMO, THERMO_JSON_SCHEMA, TOPICS};
use foxglove::messages::SceneUpdate;
use foxglove::{Channel, ChannelBuilder, Context, PartialMetadata, RawChannel, Schema};

use crate::progress::{ProgressRecord, PROGRESS_JSON_SCHEMA};
use crate::LiveError;

/// Topic of the live progress records.
pub(crate) const TOPIC_PROGRESS: &str = "/progress";

/// The live channels.
pub(crate) struct Channels {
    pub(crate) scene: Channel<SceneUpdate>,
    thermo: Arc<RawChannel>,
    progress: Arc<RawChannel>,
}

/// A JSON channel on `topic` with the JSON Schema `schema` titled `name`.
fn json_channel(
    ctx: &Arc<Context>,
    topic: &str,
    name: &str,
    schema: &str,
) -> Result<Arc<RawChannel>, LiveError> {
    ChannelBuilder::new(topic)
        .context(ctx)
        .message_encoding("json")
        .schema(Schema::new(name, "jsonschema", schema.as_bytes().to_vec()))
        .build_raw()
        .map_err(|e| LiveError::Channel {
            topic: topic.into(),
            problem: e.to_string(),
        })
}

/// The log time of simulated time `t`.
fn at(t: f64) -> PartialMetadata {
    PartialMetadata::with_log_time(log_time_ns(t))
}

impl Channels {
    /// The channels, in `ctx`.
    pub(crate) fn new(ctx: &Arc<Context>) -> Result<Self, LiveError> {
        Ok(Channels {
            scene: ChannelBuilder::new(TOPICS[CH_SCENE]).context(ctx).build(),
            thermo: json_channel(ctx, TOPICS[CH_THERMO], "carom.Thermo", THERMO_JSON_SCHEMA)?,
            progress: json_channel(ctx, TOPIC_PROGRESS, "carom.Progress", PROGRESS_JSON_SCHEMA)?,
        })
    }

    /// Whether a client is subscribed to a channel that frames feed.
    pub(crate) fn frames_wanted(&self) -> bool {
        self.scene.has_sinks() || self.progress.has_sinks()
    }

    /// Send a `/scene` frame of the state at time `t`.
    pub(crate) fn scene(&self, update: &SceneUpdate, t: f64) {
        self.scene.log_with_meta(update, at(t));
    }

    /// Send a `/thermo` record, as the log writes it (when anyone listens).
    pub(crate) fn thermo(&self, th: &Thermo) {
        if self.thermo.has_sinks() {
            if let Ok(json) = serde_json::to_vec(th) {
                self.thermo.log_with_meta(&json, at(th.time));
            }
        }
    }

    /// Send a `/progress` record (when anyone listens).
    pub(crate) fn progress(&self, p: &carom_run::Progress) {
        if self.progress.has_sinks() {
            let json = ProgressRecord::of(p).to_json();
            self.progress.log_with_meta(&json, at(p.sim_time));
        }
    }

    /// Whether a client is subscribed to `/scene`.
    pub(crate) fn scene_wanted(&self) -> bool {
        self.scene.has_sinks()
    }
}
