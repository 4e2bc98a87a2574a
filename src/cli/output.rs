//! What carom writes on its standard streams, written so that a stream that cannot
//! take it never stops a command. Progress, warnings and the closing lines go to
//! standard error through [`say!`]: a line that cannot be written (standard error
//! on a full disk, `2>/dev/full`, or a pipe whose reader has gone, `2>&1 | head`)
//! is dropped, and the run and its log go on to their end (Rust's `eprintln!`
//! would panic there, exit status 101). Results go to standard output through
//! [`emit`]: a closed pipe (`carom info x | head`) ends the output quietly, any
//! other failure is an error naming standard output.
//!
//! Error messages pass through [`compact_numbers`]: an f64 that a message prints
//! in full (`1e308` is 309 digits long) is shown in scientific notation instead.

use std::io::Write;

use super::CliError;

/// Write one line to standard error, or drop it if standard error cannot take it
/// (see the module's documentation).
pub(crate) fn say_line(line: &str) {
    let mut err = std::io::stderr().lock();
    let _ = writeln!(err, "{line}");
}

/// `eprintln!` that never panics: formats its arguments and hands the line to
/// [`say_line`].
macro_rules! say {
    ($($arg:tt)*) => {
        $crate::cli::output::say_line(&format!($($arg)*))
    };
}
pub(crate) use say;

/// Write `text` to standard output; a closed pipe (`carom info x | head`) is not
/// an error.
pub(crate) fn emit(text: &str) -> Result<(), CliError> {
    let mut out = std::io::stdout().lock();
    match out.write_all(text.as_bytes()).and_then(|()| out.flush()) {
        Err(e) if e.kind() != std::io::ErrorKind::BrokenPipe => Err(CliError::Io {
            context: "cannot write to standard output".into(),
            source: e,
        }),
        _ => Ok(()),
    }
}

/// Digits (and decimal point) beyond which a number in a message is an f64
/// printed in full: no integer carom counts with (u64, at most 20 digits) is as
/// long.
const LONGEST_PLAIN_NUMBER: usize = 21;

/// `text` with every decimal number longer than [`LONGEST_PLAIN_NUMBER`]
/// characters (`1000…0`, `0.000…01`, as Rust prints an f64 such as 1e308 or
/// 1e-300 with `{}`) written in scientific notation, `1e308`. The f64 is read back
/// from its digits and printed in its shortest exact form, so nothing is lost.
pub(crate) fn compact_numbers(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while let Some(start) = rest.find(|c: char| c.is_ascii_digit()) {
        out.push_str(&rest[..start]);
        let tail = &rest[start..];
        let mut len = tail
            .find(|c: char| !c.is_ascii_digit())
            .unwrap_or(tail.len());
        // A fractional part, when a point follows with a digit after it.
        if tail[len..].starts_with('.') && tail[len + 1..].starts_with(|c: char| c.is_ascii_digit())
        {
            let frac = &tail[len + 1..];
            len += 1 + frac
                .find(|c: char| !c.is_ascii_digit())
                .unwrap_or(frac.len());
        }
        let number = &tail[..len];
        match number.parse::<f64>() {
            Ok(x) if number.len() > LONGEST_PLAIN_NUMBER => out.push_str(&format!("{x:e}")),
            _ => out.push_str(number),
        }
        rest = &tail[len..];
    }
    out.push_str(rest);
    out
}

#[cfg(test)]
mod tests {
    use super::compact_numbers;

    #[test]
    fn numbers_printed_in_full_are_written_in_scientific_notation_and_others_kept() {
        let huge = format!("stop time {} (stop.duration)", 1e308);
        assert!(huge.len() > 300);
        assert_eq!(compact_numbers(&huge), "stop time 1e308 (stop.duration)");
        let tiny = format!("the latest stop time is {}", 1e-300);
        assert_eq!(compact_numbers(&tiny), "the latest stop time is 1e-300");
        let neg = format!("value {}, at most 1", -f64::MAX);
        assert_eq!(
            compact_numbers(&neg),
            "value -1.7976931348623157e308, at most 1"
        );
        // Exact: the compact form reads back to the same f64.
        let x = 123_456_789.0e300_f64;
        let back: f64 = compact_numbers(&x.to_string()).parse().unwrap();
        assert_eq!(back, x);
        // Counts, ordinary numbers, versions, names and exponents stay as they were.
        for kept in [
            "18446744073709551615 collisions at t = 12.700000000000001",
            "carom 0.1.0 (log format 2.2), run_0003.mcap, 1e-99 and 5.55e-142",
            "point eta=0.3_rep2: 2.44 ± 0.01",
            "",
        ] {
            assert_eq!(compact_numbers(kept), kept);
        }
    }
}
