//! The `vibrating_floor` field (physics.md §18): amplitude and frequency finite
//! and > 0, hard walls along y, no compression, and full collision records (a
//! moving wall gives velocities that compact records cannot replay). The engine
//! checks the rest, that the floor's travel plus a diameter fits in half the box.

use super::ConfigError;
use super::{AxisBoundary, CollisionDetailConfig, Config};

impl Config {
    /// The vibrating floor's values and the dynamics it needs.
    pub(super) fn check_floor(&self) -> Result<(), ConfigError> {
        let Some(fl) = self.vibrating_floor else {
            return Ok(());
        };
        for (field, x, unit) in [
            ("vibrating_floor.amplitude", fl.amplitude, "length"),
            ("vibrating_floor.frequency", fl.frequency, "1/time"),
        ] {
            if !(x.is_finite() && x > 0.0) {
                return Err(ConfigError::invalid(
                    field,
                    format!("value {x}"),
                    format!("finite, > 0 ({unit})"),
                ));
            }
        }
        if self.sim_box.boundary.axes()[1] == AxisBoundary::Periodic {
            return Err(ConfigError::invalid(
                "vibrating_floor",
                "a floor with a periodic y axis".to_string(),
                "hard walls along y: box.boundary \"walls\" or {\"x\": \"periodic\", \"y\": \"walls\"}",
            ));
        }
        if self.compression.is_some() {
            return Err(ConfigError::invalid(
                "vibrating_floor",
                "a floor with compression".to_string(),
                "a vibrating floor or compression, not both",
            ));
        }
        if self.log.collision_detail == Some(CollisionDetailConfig::Compact) {
            return Err(ConfigError::invalid(
                "log.collision_detail",
                "\"compact\" with a vibrating floor: compact records cannot replay the floor's bounces".to_string(),
                "\"full\" (or no log.collision_detail, which is full with a floor)",
            ));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::super::tests::err_of;
    use super::super::Config;

    const BED: &str = r#"{"gravity": 1, "box": {"boundary": {"x": "periodic", "y": "walls"}, "size": [20, 40]}, "species": [{"count": 50, "radius": 0.5}], "vibrating_floor": {"amplitude": 0.5, "frequency": 2}}"#;

    #[test]
    fn a_floor_reaches_the_engine_with_omega_two_pi_f_and_full_records() {
        let s = Config::from_json_str(BED).unwrap().to_run_spec().unwrap();
        let fl = s.params.floor.unwrap();
        assert_eq!(fl.amplitude, 0.5);
        assert_eq!(fl.omega, std::f64::consts::TAU * 2.0);
        assert_eq!(s.log.collision_detail, carom_log::CollisionDetail::Full);
        assert!(s.config_json.contains("vibrating_floor"));
        let plain = Config::from_json_str("{}").unwrap().to_run_spec().unwrap();
        assert!(plain.params.floor.is_none());
        assert!(!plain.config_json.contains("vibrating_floor"));
    }

    #[test]
    fn bad_floors_are_refused_naming_the_field() {
        for (sets, field, says) in [
            (
                vec!["vibrating_floor.amplitude=-1"],
                "vibrating_floor.amplitude",
                "value -1",
            ),
            (
                vec!["vibrating_floor.frequency=0"],
                "vibrating_floor.frequency",
                "value 0",
            ),
            (
                vec!["box.boundary=periodic", "gravity=0"],
                "vibrating_floor",
                "periodic y",
            ),
            (
                vec!["log.collision_detail=compact", "gravity=0"],
                "log.collision_detail",
                "floor",
            ),
        ] {
            let msg = err_of(BED, &sets).to_string();
            assert!(msg.contains(field) && msg.contains(says), "{sets:?}: {msg}");
        }
        let msg = err_of(r#"{"vibrating_floor": {"amplitude": 1}}"#, &[]).to_string();
        assert!(msg.contains("frequency"), "{msg}");
    }
}
