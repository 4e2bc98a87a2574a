//! The run facts of a log written before they were complete (format < 2.4: no
//! thermostat, growth or floor in them; ≤ 1.1: no facts at all), derived from
//! the configuration stored in the log: it is resolved as the run resolved it
//! (the box from η; no disc is placed). The one place an old log's configuration
//! is read; the caller hands it to `carom_analysis::analyze_log_with`.

use carom_log::RunFacts;

use crate::Config;

/// The facts of the run whose stored configuration is `config`; `Err`: why it
/// cannot be read.
pub fn derive_facts_for_old_log(config: &str) -> Result<RunFacts, String> {
    let spec = Config::from_json_str(config)
        .and_then(|c| c.to_run_spec())
        .map_err(|e| e.to_string())?;
    let system = &spec.system;
    Ok(
        RunFacts::new(&system.species, &system.sim_box, &spec.params, &spec.log)
            .with_thermostat(spec.thermostat),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_old_logs_configuration_gives_its_facts_with_the_dynamics() {
        let config = r#"{"species": [{"count": 30, "radius": 0.5, "mass": 2}],
            "box": {"size": [20, 10], "boundary": "walls"},
            "thermostat": {"kind": "andersen", "kT": 1.5, "rate": 0.2}}"#;
        let f = derive_facts_for_old_log(config).unwrap();
        assert_eq!(f.species, [carom_core::Species::new(30, 0.5, 2.0)]);
        assert_eq!(f.sim_box.size, carom_core::DVec2::new(20.0, 10.0));
        assert_eq!(
            f.thermostat,
            Some(carom_engine::Thermostat::Andersen { kt: 1.5, rate: 0.2 })
        );
        assert_eq!((f.growth, f.floor), (None, None));
        assert!(derive_facts_for_old_log("not json").is_err());
    }
}
