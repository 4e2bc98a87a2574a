//! The figures of `carom analyze --plot` read back from their SVG text, on
//! real runs: log axes ticked at distinct, non-overlapping powers of ten, the
//! legends naming the errors, fits, windows and references, and the figures
//! that would be empty skipped with their reasons.

use crate::cli_common::*;

use std::path::Path;

/// A `<text>` of an SVG: x, y, its anchor, font size and content.
struct Text {
    x: f64,
    y: f64,
    anchor: String,
    size: f64,
    s: String,
}

fn attr(tag: &str, name: &str) -> String {
    let key = format!(" {name}=\"");
    tag.split(&key)
        .nth(1)
        .and_then(|r| r.split('"').next())
        .unwrap_or("")
        .to_owned()
}

fn texts(svg: &str) -> Vec<Text> {
    svg.split("<text")
        .skip(1)
        .filter_map(|t| {
            let (tag, rest) = t.split_once('>')?;
            let s = rest.split("</text>").next()?.trim().to_owned();
            Some(Text {
                x: attr(tag, "x").parse().ok()?,
                y: attr(tag, "y").parse().ok()?,
                anchor: attr(tag, "text-anchor"),
                size: attr(tag, "font-size").parse().unwrap_or(12.0),
                s,
            })
        })
        .collect()
}

/// Whether a text is a tick label (a number or a power of ten).
fn is_tick(s: &str) -> bool {
    !s.is_empty() && s.chars().all(|c| "0123456789.-−×⁰¹²³⁴⁵⁶⁷⁸⁹⁻".contains(c))
}

/// Whether a label is 10ᵏ or m×10ᵏ.
fn is_power_of_ten(s: &str) -> bool {
    let rest = match s.split_once('×') {
        Some((m, r)) => {
            if !(m.len() == 1 && m.chars().all(|c| c.is_ascii_digit())) {
                return false;
            }
            r
        }
        None => s,
    };
    rest.strip_prefix("10")
        .is_some_and(|e| !e.is_empty() && e.chars().all(|c| "⁰¹²³⁴⁵⁶⁷⁸⁹⁻".contains(c)))
}

/// Which coordinate of a label its axis shares.
type Coordinate = fn(&Text) -> f64;

/// The x-axis tick labels (the numbers sharing a baseline, centred) and the
/// y-axis tick labels (right-aligned, sharing an x), per axis.
fn axes(svg: &str) -> (Vec<Vec<Text>>, Vec<Vec<Text>>) {
    let (mut xs, mut ys): (Vec<Vec<Text>>, Vec<Vec<Text>>) = (vec![], vec![]);
    for t in texts(svg).into_iter().filter(|t| is_tick(&t.s)) {
        let (groups, key): (&mut Vec<Vec<Text>>, Coordinate) = if t.anchor == "end" {
            (&mut ys, |t| t.x)
        } else {
            (&mut xs, |t| t.y)
        };
        match groups.iter_mut().find(|g| key(&g[0]) == key(&t)) {
            Some(g) => g.push(t),
            None => groups.push(vec![t]),
        }
    }
    (xs, ys)
}

/// Every axis: distinct labels; the x labels not overlapping (a glyph is at
/// most 0.65 of the font size wide), the y labels a line apart; on the log
/// axes named, every label a power of ten.
fn check_ticks(name: &str, svg: &str, log_x: bool, log_y: bool) {
    let (xs, ys) = axes(svg);
    assert!(!xs.is_empty() && !ys.is_empty(), "{name}: no ticks");
    for (groups, log) in [(&xs, log_x), (&ys, log_y)] {
        for g in groups.iter() {
            let labels: Vec<&str> = g.iter().map(|t| t.s.as_str()).collect();
            let mut sorted = labels.clone();
            sorted.sort();
            sorted.dedup();
            assert_eq!(sorted.len(), labels.len(), "{name}: repeated {labels:?}");
            if log {
                assert!(
                    labels.iter().all(|l| is_power_of_ten(l)),
                    "{name}: {labels:?}"
                );
                assert!(labels.len() >= 2, "{name}: {labels:?}");
            }
        }
    }
    for g in &xs {
        let mut spans: Vec<(f64, f64)> = g
            .iter()
            .map(|t| {
                let w = 0.65 * t.size * t.s.chars().count() as f64;
                (t.x - w / 2.0, t.x + w / 2.0)
            })
            .collect();
        spans.sort_by(|a, b| a.0.total_cmp(&b.0));
        for w in spans.windows(2) {
            assert!(w[0].1 <= w[1].0, "{name}: x labels overlap {spans:?}");
        }
        assert!(spans.iter().all(|s| s.1 <= 900.0), "{name}: clipped");
    }
    for g in &ys {
        let mut y: Vec<f64> = g.iter().map(|t| t.y).collect();
        y.sort_by(f64::total_cmp);
        for w in y.windows(2) {
            assert!(w[1] - w[0] >= g[0].size, "{name}: y labels overlap {y:?}");
        }
    }
}

fn svg(dir: &Path, name: &str) -> String {
    std::fs::read_to_string(dir.join(format!("figs/{name}.svg")))
        .unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// A small default fluid: every figure's ticks, the legends' entries, the
/// error bands, and the flat temperature skipped with its reason.
#[test]
fn the_figures_of_a_fluid_have_decade_ticks_errors_and_references() {
    let dir = scratch("figures");
    ok(&carom(
        &dir,
        &[
            "run",
            "--quiet",
            "--set",
            "species.0.count=2000",
            "--set",
            "stop.duration=20",
        ],
    ));
    let out = carom(&dir, &["analyze", "carom.mcap", "--plot", "figs"]);
    ok(&out);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("skipped temperature: kT = ") && err.contains("elastic"),
        "{err}"
    );
    assert!(!dir.join("figs/temperature.png").exists());
    // (figure, log x, log y)
    let log = [
        ("msd", true, true),
        ("vacf", true, true),
        ("msd_exact", true, true),
        ("vacf_exact", true, true),
        ("g6", true, true),
        ("helfand_viscosity", true, false),
        ("helfand_conductivity", true, false),
        ("pair_correlation", false, false),
        ("structure_factor", false, false),
        ("bond_order", false, false),
        ("pressure", false, false),
        ("speed_species0", false, false),
    ];
    for (name, lx, ly) in log {
        check_ticks(name, &svg(&dir, name), lx, ly);
    }
    let se = "± one standard error";
    let legends: [(&str, &[&str]); 9] = [
        ("msd", &[se, "fit 4Dτ + c", "fit window", "slope 1"]),
        ("vacf", &[se, "τ⁻¹"]),
        (
            "pair_correlation",
            &[se, "ideal gas g = 1", "contact g(σ⁺)"],
        ),
        ("structure_factor", &[se, "ideal gas S = 1"]),
        ("g6", &[se]),
        (
            "bond_order",
            &["± one standard error of the mean", "mean |Ψ6|"],
        ),
        ("pressure", &["± one standard error of the mean", "mean Z"]),
        ("vacf_exact", &[se, "window τ", "mode coupling"]),
        (
            "helfand_viscosity",
            &[
                "Enskog η_E",
                "Einstein–Helfand read",
                "Green–Kubo read",
                "window τ",
            ],
        ),
    ];
    for (name, entries) in legends {
        let s = svg(&dir, name);
        for e in entries {
            assert!(s.contains(e), "{name}: no {e}");
        }
    }
    // Bands are drawn where their legend says so (a filled polygon).
    for name in [
        "msd",
        "vacf",
        "pair_correlation",
        "g6",
        "bond_order",
        "pressure",
    ] {
        assert!(svg(&dir, name).contains("<polygon"), "{name}: no band");
    }
    // Distances in σ, lags in τ₀.
    assert!(svg(&dir, "pair_correlation").contains("r/σ"));
    assert!(svg(&dir, "msd").contains("τ/τ₀"));
    // A coefficient is titled with ± only if the report judges it reliable
    // (one rule, physics.md §14.6), and its legend says the same verdict.
    let report = json_of(&carom(&dir, &["analyze", "carom.mcap", "--json", "-q"]));
    for (name, field) in [
        ("helfand_viscosity", "viscosity"),
        ("helfand_conductivity", "thermal_conductivity"),
    ] {
        let reliable = report["transport"][field]["reliability"]["reliable"]
            .as_bool()
            .unwrap();
        let s = svg(&dir, name);
        let caption = &texts(&s)[0].s;
        assert_eq!(caption.contains('±'), reliable, "{name}: {caption}");
        assert_eq!(
            caption.contains("unreliable here"),
            !reliable,
            "{name}: {caption}"
        );
        let verdict = if reliable {
            "(reliable)"
        } else {
            "(UNRELIABLE)"
        };
        for method in ["Einstein–Helfand", "Green–Kubo"] {
            assert!(
                texts(&s)
                    .iter()
                    .any(|t| t.s.starts_with(&format!("{method} read:")) && t.s.ends_with(verdict)),
                "{name}: no '{method} read: … {verdict}'"
            );
        }
    }
}

/// Two discs: the averages over discs are skipped, each with a reason.
#[test]
fn the_figures_of_two_discs_are_skipped_with_reasons() {
    let dir = scratch("figures-two");
    let cfg = Path::new(env!("CARGO_MANIFEST_DIR")).join("data/two-discs.json");
    ok(&carom(
        &dir,
        &["run", "--quiet", cfg.to_str().unwrap(), "--out", "two.mcap"],
    ));
    let out = carom(&dir, &["analyze", "two.mcap", "--plot", "figs"]);
    ok(&out);
    let err = String::from_utf8_lossy(&out.stderr);
    for name in ["pair_correlation", "bond_order", "g6", "msd", "temperature"] {
        let line = err
            .lines()
            .find(|l| l.starts_with(&format!("skipped {name}: ")))
            .unwrap_or_else(|| panic!("{name} not skipped: {err}"));
        assert!(
            line.len() > format!("skipped {name}: ").len() + 10,
            "{line}"
        );
        assert!(!dir.join(format!("figs/{name}.png")).exists(), "{name}");
    }
}
