//! The neighbour search on the command line: `carom run` and `carom resume` say
//! which is in force as the events begin (not with `--quiet`), `--set
//! neighbours=cells` is obeyed, and `"lists"` where lists cannot work, or an
//! unknown name, is refused with exit code 2 naming the field and what is allowed.

use crate::cli_common::*;

/// The line of stderr that says how the run is set up.
fn setup_line(stderr: &str) -> Option<&str> {
    stderr.lines().find(|l| l.contains("neighbour search: "))
}

#[test]
fn run_and_resume_say_which_neighbour_search_is_in_force() {
    let dir = scratch("say");
    let small = ["--set", "species.0.count=400", "--set", "stop.duration=1"];
    let run = |args: &[&str]| {
        let out = carom(&dir, &[args, &small[..]].concat());
        ok(&out);
        String::from_utf8_lossy(&out.stderr).into_owned()
    };
    let stderr = run(&["run", "--out", "a.mcap"]);
    assert_eq!(
        setup_line(&stderr),
        Some("400 discs, neighbour search: cells, 25 × 25"),
        "{stderr}"
    );
    let out = carom(&dir, &["resume", "a.mcap", "--until", "2"]);
    ok(&out);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        setup_line(&stderr).is_some_and(|l| l.starts_with("400 discs, neighbour search: ")),
        "{stderr}"
    );
    let stderr = run(&["run", "--quiet", "--out", "q.mcap"]);
    assert_eq!(setup_line(&stderr), None, "{stderr}");
    // Lists where "auto" chooses them (η ≥ 0.66), and when asked for at η = 0.5.
    let dense = ["--set", "box.packing_fraction=0.7"];
    let stderr = run(&[&["run", "--out", "l.mcap"], &dense[..]].concat());
    assert_eq!(
        setup_line(&stderr),
        Some("400 discs, neighbour search: neighbour lists"),
        "{stderr}"
    );
    let out = carom(&dir, &["resume", "l.mcap", "--until", "2"]);
    ok(&out);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(
        setup_line(&stderr),
        Some("400 discs, neighbour search: neighbour lists"),
        "a resume continues on the lists it left: {stderr}"
    );
    let stderr = run(&["run", "--out", "m.mcap", "--set", "neighbours=lists"]);
    assert!(
        setup_line(&stderr).is_some_and(|l| l.ends_with("neighbour lists")),
        "{stderr}"
    );
    // Cells when asked for, also where "auto" may choose lists.
    let stderr = run(&[
        "run",
        "--out",
        "c.mcap",
        "--set",
        "box.packing_fraction=0.7",
        "--set",
        "neighbours=cells",
    ]);
    assert!(
        setup_line(&stderr).is_some_and(|l| l.contains("neighbour search: cells")),
        "{stderr}"
    );
}

#[test]
fn lists_without_straight_flights_and_unknown_names_are_refused() {
    let dir = scratch("refused");
    for (sets, says) in [
        (
            vec!["neighbours=lists", "gravity=1", "box.boundary=walls"],
            r#"neighbours: "lists" cannot be used with gravity"#,
        ),
        (
            vec!["neighbours=grid"],
            "neighbours: unknown variant `grid` (allowed: one of `auto`, `cells`, `lists`)",
        ),
    ] {
        let mut args = vec!["run", "--out", "x.mcap"];
        for s in &sets {
            args.extend(["--set", s]);
        }
        let out = carom(&dir, &args);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{sets:?}: {stderr}");
        assert!(stderr.contains(says), "{sets:?}: {stderr}");
        assert!(!dir.join("x.mcap").exists(), "{sets:?}");
    }
}
