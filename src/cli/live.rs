//! `--live [ADDR]` of `carom run` and `carom resume`: serve the run while it runs
//! over Foxglove's WebSocket protocol (carom-live), so that Foxglove or Lichtblick
//! shows its `/scene`, `/thermo` and `/progress` live (docs/look.md, "live").

use carom_live::{Colouring, Live, LiveOptions, DEFAULT_ADDR};
use clap::Args;

use super::output::say;
use super::CliError;

/// The live options of `carom run` and `carom resume`.
#[derive(Debug, Clone, Args)]
pub struct LiveArgs {
    /// Serve the run live to Foxglove or Lichtblick (Foxglove WebSocket protocol)
    /// at ADDR: HOST:PORT, or a port on 127.0.0.1 (0: any free port); without
    /// ADDR, 127.0.0.1:8765. The address is printed at the start.
    #[arg(long, value_name = "ADDR", num_args = 0..=1, default_missing_value = DEFAULT_ADDR)]
    pub live: Option<String>,
    /// The most live frames per second of wall time (default 10).
    #[arg(long, value_name = "FPS", requires = "live")]
    pub live_rate: Option<f64>,
    /// What colours the discs of the live /scene: species (as in the log) or
    /// speed.
    #[arg(long, value_name = "BY", requires = "live", value_parser = Colouring::from_name)]
    pub live_colour: Option<Colouring>,
}

impl LiveArgs {
    /// Start the live server asked for, if any, and say where it serves.
    pub fn start(&self) -> Result<Option<Live>, CliError> {
        let Some(addr) = &self.live else {
            return Ok(None);
        };
        let usage = |e: carom_live::LiveError| CliError::Usage(format!("--live: {e}"));
        let mut options = LiveOptions::at(addr).map_err(usage)?;
        if let Some(rate) = self.live_rate {
            options.frame_rate = rate;
        }
        if let Some(c) = self.live_colour {
            options.colouring = c;
        }
        let live = Live::start(&options).map_err(usage)?;
        say!(
            "live: serving {} (Foxglove or Lichtblick: Open connection → Foxglove WebSocket)",
            live.url()
        );
        Ok(Some(live))
    }
}
