//! The end of a run, whatever stopped it: a last `/thermo` record and
//! `/checkpoint` at the final state (unless one was just written, or the engine
//! failed), the final frame for the caller's observer, the `carom.summary`
//! metadata, and the [`RunSummary`] the caller gets.

use std::path::Path;

use carom_engine::EngineError;
use carom_log::{now_rfc3339, StopReason, SummaryMetadata};

use super::Driver;
use crate::{RunError, RunSummary};

impl Driver<'_> {
    /// Finish the log of a run stopped for `reason` (with the engine's `failure`,
    /// if any) and sum the run up.
    pub(super) fn finish(
        &mut self,
        reason: StopReason,
        failure: Option<EngineError>,
        log_path: &Path,
    ) -> Result<RunSummary, RunError> {
        if failure.is_none() {
            let now = self.engine.now();
            if self.log.thermo_interval.is_some()
                && self.last_thermo_at != Some((now, self.collisions))
            {
                self.write_thermo()?;
            }
            if self.last_checkpoint_at != Some((now, self.collisions)) {
                self.write_checkpoint()?;
            }
        }
        self.progress();
        if failure.is_none() {
            self.live_frame();
        }
        let wall = self.started.elapsed().as_secs_f64();
        let s = *self.engine.stats();
        let this = self.collisions - self.start_collisions;
        let cps = match self.earlier_speed {
            Some(v) if this == 0 => v,
            _ if wall > 0.0 => this as f64 / wall,
            _ => 0.0,
        };
        let kinetic_energy = self.engine.kinetic_energy();
        let potential_energy =
            (self.engine.gravity() != 0.0).then(|| self.engine.potential_energy());
        let logged = self.writer.stats().logged_collisions;
        let sm = SummaryMetadata {
            end_time: now_rfc3339(),
            stop_reason: reason,
            error: failure
                .as_ref()
                .map(|e| e.to_string())
                .or(self.quiet_detail.clone()),
            sim_time: self.engine.now(),
            pair_collisions: s.pair_collisions,
            wall_collisions: s.wall_collisions,
            logged_collisions: logged,
            kinetic_energy,
            energy_lost: s.energy_lost,
            virial_sum: s.virial_sum,
            wall_seconds: wall,
            collisions_per_second: cps,
            potential_energy,
        };
        let file_bytes = self.writer.finish(&sm.to_map())?;
        if let Some(source) = failure {
            return Err(RunError::Engine {
                source,
                time: self.engine.now(),
                log: log_path.to_path_buf(),
            });
        }
        Ok(RunSummary {
            log: log_path.to_path_buf(),
            stop_reason: reason,
            sim_time: self.engine.now(),
            pair_collisions: s.pair_collisions,
            wall_collisions: s.wall_collisions,
            logged_collisions: logged,
            collisions_this_process: this,
            wall_seconds: wall,
            collisions_per_second: cps,
            kinetic_energy,
            potential_energy,
            energy_lost: s.energy_lost,
            file_bytes,
            detail: self.quiet_detail.take(),
        })
    }
}
