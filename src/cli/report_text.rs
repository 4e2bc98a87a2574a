//! The layout of `carom analyze`'s text report, for a terminal: a section is a
//! heading line, then one quantity per line, indented, as
//! `name  value ± SE  (reference …)  verdict`, with the name in a column of its
//! own; notes that explain a section go on their own indented lines. No line is
//! wider than [`WIDTH`] columns: longer ones are wrapped at a space, continued
//! under their value. Values with an error are rounded to the error's second
//! significant digit ([`pm`]). The JSON keeps every detail; the text keeps what a
//! reader scans for.

use std::fmt::Write;

/// The widest line of the report, in columns (characters).
pub const WIDTH: usize = 100;

/// The column where values start (after two spaces of indent and the name).
const NAME: usize = 24;

/// A report being written: sections, quantities and notes.
#[derive(Default)]
pub struct Text {
    out: String,
}

impl Text {
    /// A heading line; a blank line before every section but the first.
    pub fn section(&mut self, title: &str) {
        if !self.out.is_empty() {
            self.out.push('\n');
        }
        self.wrapped(title, 4);
    }

    /// One quantity: `name` in its column, then `value` (wrapped under itself).
    pub fn item(&mut self, name: &str, value: &str) {
        let pad = NAME.saturating_sub(name.chars().count() + 2).max(2);
        let line = format!("  {name}{}{value}", " ".repeat(pad));
        let hang = (name.chars().count() + 2 + pad).min(NAME);
        self.wrapped(&line, hang);
    }

    /// A line of explanation under a section, indented by two.
    pub fn note(&mut self, text: &str) {
        self.wrapped(&format!("  {text}"), 4);
    }

    /// The report written so far.
    pub fn finish(self) -> String {
        self.out
    }

    fn wrapped(&mut self, line: &str, hang: usize) {
        for l in wrap(line, hang) {
            let _ = writeln!(self.out, "{l}");
        }
    }
}

/// `line` cut at spaces into pieces of at most [`WIDTH`] columns, every piece
/// after the first indented by `hang` spaces; the spacing inside a piece is kept
/// (the column between a name and its value). A word longer than a line stays
/// whole.
pub fn wrap(line: &str, hang: usize) -> Vec<String> {
    let mut out = Vec::new();
    let (mut current, mut width) = (String::new(), 0);
    let mut rest = line.trim_end();
    while !rest.is_empty() {
        let after = rest.trim_start_matches(' ');
        let gap = &rest[..rest.len() - after.len()];
        let word = &after[..after.find(' ').unwrap_or(after.len())];
        rest = &after[word.len()..];
        let (g, w) = (gap.chars().count(), word.chars().count());
        if width > hang && width + g + w > WIDTH {
            out.push(std::mem::take(&mut current));
            current = format!("{}{word}", " ".repeat(hang));
            width = hang + w;
        } else {
            current.push_str(gap);
            current.push_str(word);
            width += g + w;
        }
    }
    out.push(current);
    out
}

/// Every line of `text` wrapped to [`WIDTH`] columns, continuation lines
/// indented two more than the line's own indent.
pub fn fit(text: &str) -> String {
    let mut out = String::new();
    for line in text.lines() {
        let indent = line.chars().take_while(|c| *c == ' ').count();
        for l in wrap(line, indent + 4) {
            out.push_str(&l);
            out.push('\n');
        }
    }
    out
}

/// `x ± se`, both rounded to the second significant digit of `se` (4.10492 ±
/// 0.00284 → "4.1049 ± 0.0028"); in scientific notation for very large or small
/// values; `x` alone, to six significant digits, with "(no error estimate)"
/// when `se` is not a positive finite number.
pub fn pm(x: f64, se: f64) -> String {
    if !x.is_finite() {
        return format!("{x}");
    }
    if !(se.is_finite() && se > 0.0) {
        return format!("{} (no error estimate)", sig(x, 6));
    }
    let decimals = 1 - se.log10().floor() as i32;
    let big = x.abs().max(se);
    if (0..=8).contains(&decimals) && big < 1e7 {
        let d = decimals as usize;
        format!("{x:.d$} ± {se:.d$}")
    } else if decimals < 0 && big < 1e9 {
        format!("{:.0} ± {:.0}", x, se)
    } else {
        // Both in units of the larger one's decade.
        let e = big.log10().floor() as i32;
        let unit = 10f64.powi(e);
        let d = (1 - (se / unit).log10().floor() as i32).clamp(0, 12) as usize;
        format!("({:.d$} ± {:.d$})e{e}", x / unit, se / unit)
    }
}

/// `x` to `n` significant digits, plain where readable, else scientific.
pub fn sig(x: f64, n: usize) -> String {
    if x == 0.0 || !x.is_finite() {
        return format!("{x}");
    }
    let mag = x.abs().log10().floor() as i32;
    if (-4..7).contains(&mag) {
        let d = (n as i32 - 1 - mag).max(0) as usize;
        format!("{x:.d$}")
    } else {
        format!("{x:.*e}", n - 1)
    }
}

/// A difference in standard errors, "+1.5σ"; "–" without an error.
pub fn sigmas(diff: f64, se: f64) -> String {
    if se.is_finite() && se > 0.0 {
        format!("{:+.1}σ", diff / se)
    } else {
        "–".into()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn values_are_rounded_to_their_error() {
        assert_eq!(pm(4.10492, 0.00284), "4.1049 ± 0.0028");
        assert_eq!(pm(0.21152, 0.00321), "0.2115 ± 0.0032");
        assert_eq!(pm(9851.4, 12.3), "9851 ± 12");
        assert_eq!(pm(3.80, 0.31), "3.80 ± 0.31");
        assert_eq!(pm(1.0, f64::NAN), "1.00000 (no error estimate)");
        assert_eq!(pm(2.5e-9, 3.1e-11), "(2.500 ± 0.031)e-9");
    }

    #[test]
    fn no_line_is_wider_than_the_terminal_and_no_word_is_lost() {
        let long = format!("  name{}{}", " ".repeat(16), "word ".repeat(60));
        let lines = wrap(&long, 22);
        assert!(lines.len() > 2);
        for l in &lines {
            assert!(l.chars().count() <= WIDTH, "{l}");
        }
        let words: usize = lines.iter().map(|l| l.split_whitespace().count()).sum();
        assert_eq!(words, 61);
        assert!(lines[1].starts_with(&" ".repeat(22)), "{}", lines[1]);
        // The padding between name and value is kept on the first line.
        assert!(
            lines[0].starts_with("  name                word"),
            "{}",
            lines[0]
        );
    }

    #[test]
    fn items_line_up_their_values() {
        let mut t = Text::default();
        t.section("pressure");
        t.item("Z = βPA/N", "4.1049 ± 0.0028");
        t.item("βP", "2.6133 ± 0.0018");
        let s = t.finish();
        let cols: Vec<usize> = s
            .lines()
            .skip(1)
            .map(|l| {
                l.char_indices()
                    .position(|(_, c)| c.is_ascii_digit())
                    .unwrap()
            })
            .collect();
        assert_eq!(cols, vec![NAME, NAME], "{s}");
    }
}
