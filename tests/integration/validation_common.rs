//! The validation suites' results table (tests/integration/validation/mod.rs,
//! tests/integration/validation_structure.rs): each case adds rows (value, standard error,
//! reference, deviation in standard errors, tolerance, pass/fail) and notes,
//! writes them to `target/tmp/<suite>/<case>.md` before asserting, and the table
//! of every case last run (in this or an earlier run: a long case can be rerun
//! alone) is assembled into `target/tmp/<suite>.md`; with
//! `CAROM_VALIDATION_DOCS=path` it is spliced into that file between the suite's
//! own generated-section markers (one section per test file).
#![allow(dead_code)]

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

use crate::stats_common;

/// How a row passes.
#[derive(Debug, Clone, Copy)]
pub enum Check {
    /// |value − reference| ≤ k combined standard errors.
    Sigma(f64),
    /// |value − reference| ≤ tol.
    Abs(f64),
    /// |value| ≤ bound (reference unused).
    AtMost(f64),
    /// value ≥ bound.
    AtLeast(f64),
    /// Reported, not judged.
    Info,
}

#[derive(Debug, Clone)]
pub struct Row {
    quantity: String,
    value: f64,
    se: f64,
    reference: Option<(f64, f64)>,
    check: Check,
}

impl Row {
    pub fn new(quantity: impl Into<String>, value: f64, se: f64) -> Self {
        Row {
            quantity: quantity.into(),
            value,
            se,
            reference: None,
            check: Check::Info,
        }
    }
    pub fn reference(mut self, r: f64, err: f64) -> Self {
        self.reference = Some((r, err));
        self
    }
    pub fn check(mut self, c: Check) -> Self {
        self.check = c;
        self
    }
    /// (value − reference) / √(se² + err²).
    pub fn deviation(&self) -> Option<f64> {
        let (r, e) = self.reference?;
        stats_common::deviation(self.value, self.se, r, e)
    }
    pub fn pass(&self) -> Option<bool> {
        let r = self.reference.map(|r| r.0);
        Some(match self.check {
            Check::Sigma(k) => self.deviation().is_some_and(|d| d.abs() <= k),
            Check::Abs(tol) => r.is_some_and(|r| (self.value - r).abs() <= tol),
            Check::AtMost(b) => self.value.abs() <= b,
            Check::AtLeast(b) => self.value >= b,
            Check::Info => return None,
        })
    }
    pub fn tolerance(&self) -> String {
        match self.check {
            Check::Sigma(k) => format!("{k} SE"),
            Check::Abs(t) => format!("± {}", fmt_g(t)),
            Check::AtMost(b) => format!("\\|x\\| ≤ {}", fmt_g(b)),
            Check::AtLeast(b) => format!("≥ {}", fmt_g(b)),
            Check::Info => "—".into(),
        }
    }
}

/// A number in a short general format.
pub fn fmt_g(x: f64) -> String {
    if x == 0.0 {
        return "0".into();
    }
    let a = x.abs();
    if !(1e-3..1e6).contains(&a) {
        format!("{x:.2e}")
    } else {
        let s = format!("{x:.4}");
        let s = s.trim_end_matches('0').trim_end_matches('.');
        s.to_string()
    }
}

/// A value with its standard error, rounded to two significant digits of the error.
pub fn fmt_se(v: f64, se: f64) -> String {
    if se.is_nan() || se <= 0.0 || !se.is_finite() {
        return fmt_g(v);
    }
    let digits = (1 - se.log10().floor() as i32).clamp(0, 12) as usize;
    if v.abs() >= 1e6 || (v != 0.0 && v.abs() < 1e-4) {
        return format!("{v:.3e} ± {se:.1e}");
    }
    format!("{v:.digits$} ± {se:.digits$}")
}

/// One case's contribution to the table.
pub struct Fragment {
    /// File name and sort key, e.g. "1a-eos-fluid".
    key: &'static str,
    title: String,
    rows: Vec<Row>,
    notes: Vec<String>,
    start: Instant,
    /// The suite it belongs to: the test module that made it, e.g. "validation".
    suite: &'static str,
}

impl Fragment {
    #[track_caller]
    pub fn new(key: &'static str, title: impl Into<String>) -> Self {
        Fragment {
            suite: crate::module_of(std::panic::Location::caller().file()),
            key,
            title: title.into(),
            rows: Vec::new(),
            notes: Vec::new(),
            start: Instant::now(),
        }
    }
    pub fn row(&mut self, r: Row) {
        println!(
            "[{}] {}: {} ref {:?} dev {:?} pass {:?}",
            self.key,
            r.quantity,
            fmt_se(r.value, r.se),
            r.reference,
            r.deviation(),
            r.pass()
        );
        self.rows.push(r);
    }
    pub fn note(&mut self, s: impl Into<String>) {
        let s = s.into();
        println!("[{}] note: {s}", self.key);
        self.notes.push(s);
    }

    fn markdown(&self) -> String {
        let mut s = String::new();
        for r in &self.rows {
            let (reference, dev) = match (r.reference, r.deviation()) {
                (Some((v, e)), d) => (
                    if e > 0.0 { fmt_se(v, e) } else { fmt_g(v) },
                    d.map_or("—".into(), |d| format!("{d:+.2}")),
                ),
                (None, _) => ("—".into(), "—".into()),
            };
            let pass = match r.pass() {
                Some(true) => "pass",
                Some(false) => "**FAIL**",
                None => "info",
            };
            let _ = writeln!(
                s,
                "| {} | {} | {} | {} | {} | {} | {} |",
                self.title.replace('|', "\\|"),
                r.quantity.replace('|', "\\|"),
                fmt_se(r.value, r.se),
                reference,
                dev,
                r.tolerance(),
                pass
            );
        }
        s.push('\u{0}');
        let _ = writeln!(
            s,
            "**{}** ({:.0} s wall clock)\n",
            self.title,
            self.start.elapsed().as_secs_f64()
        );
        for n in &self.notes {
            let _ = writeln!(s, "- {n}");
        }
        s
    }

    /// Write the fragment, reassemble the table, then fail if any row failed.
    pub fn finish(self) {
        let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(self.suite);
        std::fs::create_dir_all(&dir).expect("create the fragment directory");
        write_atomic(&dir.join(format!("{}.md", self.key)), &self.markdown());
        assemble(self.suite, &dir);
        let failed: Vec<String> = self
            .rows
            .iter()
            .filter(|r| r.pass() == Some(false))
            .map(|r| {
                format!(
                    "{}: {} (reference {:?}, deviation {:?}, tolerance {})",
                    r.quantity,
                    fmt_se(r.value, r.se),
                    r.reference,
                    r.deviation(),
                    r.tolerance()
                )
            })
            .collect();
        assert!(
            failed.is_empty(),
            "{}: failed rows:\n{}",
            self.title,
            failed.join("\n")
        );
    }
}

fn write_atomic(path: &Path, text: &str) {
    let tmp = path.with_extension(format!("tmp{}", std::process::id()));
    std::fs::write(&tmp, text).expect("write");
    std::fs::rename(&tmp, path).expect("rename");
}

const END: &str = "<!-- END GENERATED -->";

/// Build `suite`'s table from every case's latest fragment and write it.
fn assemble(suite: &str, dir: &Path) {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .expect("read the fragment directory")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "md"))
        .collect();
    files.sort();
    let mut table = String::from(
        "| case | quantity | value ± SE | reference | deviation (SE) | tolerance | result |\n\
         |---|---|---|---|---|---|---|\n",
    );
    let mut notes = String::new();
    for f in &files {
        let text = std::fs::read_to_string(f).unwrap_or_default();
        let (rows, rest) = text.split_once('\u{0}').unwrap_or(("", &text));
        table.push_str(rows);
        notes.push_str(rest);
        notes.push('\n');
    }
    let begin = format!("<!-- BEGIN GENERATED by tests/{suite}.rs -->");
    let body = format!("{begin}\n\n{table}\n### Notes per case\n\n{notes}{END}");
    let out = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("{suite}.md"));
    write_atomic(&out, &format!("{body}\n"));
    if let Ok(docs) = std::env::var("CAROM_VALIDATION_DOCS") {
        let path = PathBuf::from(docs);
        let old = std::fs::read_to_string(&path).unwrap_or_default();
        // This suite's section: its own BEGIN and the first END after it.
        let section = old
            .find(&begin)
            .and_then(|a| old[a..].find(END).map(|b| (a, a + b)));
        let new = match section {
            Some((a, b)) => format!("{}{}{}", &old[..a], body, &old[b + END.len()..]),
            _ => format!("{old}\n{body}\n"),
        };
        write_atomic(&path, &new);
    }
}
