//! `carom run` with `gravity` and `carom analyze` of its log: the gravity report in
//! the JSON and the text, and with `--plot` the `density_profile` figure; a
//! gravity with a periodic y is refused with exit code 2 and the field named.

use crate::cli_common::*;

#[test]
fn a_run_in_a_field_shows_its_atmosphere_in_json_text_and_figure() {
    let dir = scratch("gravity");
    let sets = [
        "species.0.count=60",
        "box.size=[200,60]",
        "box.boundary={\"x\":\"periodic\",\"y\":\"walls\"}",
        "gravity=0.1",
        "placement=\"random\"",
        "stop.duration=100",
    ];
    let mut args = vec!["run", "--quiet", "--out", "g.mcap"];
    for s in &sets {
        args.extend(["--set", s]);
    }
    ok(&carom(&dir, &args));
    let r = json_of(&carom(
        &dir,
        &["analyze", "g.mcap", "--quiet", "--json", "--plot", "figs"],
    ));
    let g = &r["gravity"];
    assert_eq!(g["g"], 0.1, "{g}");
    assert!(g["barometric"][0]["beta"].as_f64().unwrap() > 0.0, "{g}");
    assert!(g["potential_energy"].as_f64().unwrap() > 0.0, "{g}");
    for ext in ["png", "svg"] {
        let f = dir.join("figs").join(format!("density_profile.{ext}"));
        assert!(f.metadata().unwrap().len() > 1000, "{}", f.display());
    }
    let text = ok(&carom(&dir, &["analyze", "g.mcap", "--quiet"]));
    assert!(
        text.contains("density profile n(y), species 0") && text.contains("fitted m g/kT"),
        "{text}"
    );
    assert!(text.contains("U = Σ m g y"), "{text}");

    let refused = carom(&dir, &["run", "--quiet", "--dry-run", "--set", "gravity=1"]);
    assert_eq!(refused.status.code(), Some(2));
    let err = String::from_utf8_lossy(&refused.stderr);
    assert!(
        err.contains("gravity") && err.contains("periodic y"),
        "{err}"
    );
}
