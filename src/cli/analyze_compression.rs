//! The compression line of `carom analyze`'s text report (physics.md §17): η
//! from the configured radii to the end of growth (η_end = s_end² η₀), how growth
//! ended (the target, or jammed with the virial Z of its last interval above the
//! bound), when, and how many velocity rescales the log holds. Only formatting
//! here: every number comes from [`CompressionReport`].

use std::fmt::Write;

use carom::analysis::CompressionReport;

use super::Num;

/// The compression lines, just after the window line that they explain.
pub(super) fn compression_text(c: &CompressionReport, s: &mut String) {
    let how = match c.ended {
        "target" => format!(
            "reached the target η = {:.4}",
            Num(c.target_packing_fraction)
        ),
        "jammed" => format!(
            "jammed: Z over the last interval above the bound {} (target η = {:.4} not reached)",
            c.max_reduced_pressure,
            Num(c.target_packing_fraction)
        ),
        _ => "still growing at the end of the log".to_owned(),
    };
    let when = c
        .end_time
        .map_or(String::new(), |t| format!(" at t = {}", Num(t)));
    let _ = writeln!(
        s,
        "compression  η = {:.4} → {:.4} (radii × {:.6}); {how}{when}; last Z = {:.4}; {} velocity rescales logged (γ = {}, every {})",
        Num(c.start_packing_fraction),
        Num(c.final_packing_fraction),
        Num(c.final_radius_scale),
        Num(c.last_z),
        c.rescales,
        c.rate,
        c.rescale_interval
    );
    let _ = writeln!(
        s,
        "  the analysis below uses the radii after growth and only the time after it (physics.md §17)"
    );
}
