//! One flipped bit does not lose the whole log (issue 51, fault 9). A small log
//! is written by `carom run`; single bits are flipped at positions spread over
//! every region of the file (header, `carom.run`, chunks, message indexes,
//! `carom.summary`, data end, summary section, footer), and for each flip
//! `info`, `info --verify`, `analyze` and `repair` are run. Each outcome is
//! classified, counted per region, and checked against what the region allows:
//! a damaged chunk loses its messages only (repair keeps the rest and names the
//! loss), a damaged `carom.summary` is a warning naming it (analysis unchanged),
//! a damaged `carom.run` is an error naming it, damage in the index or footer is
//! a warning with every message read; `info --verify` never passes a damaged file.

use crate::cli_common::*;
use serde_json::Value;
use std::collections::BTreeMap;
use std::path::Path;
use std::process::Output;

/// The regions of a finished MCAP file, by its top-level records: name → byte ranges.
fn regions(bytes: &[u8]) -> BTreeMap<&'static str, Vec<(usize, usize)>> {
    let mut r: BTreeMap<&'static str, Vec<(usize, usize)>> = BTreeMap::new();
    let mut pos = 8;
    let mut metadata = 0;
    let mut in_summary = false;
    while pos + 9 <= bytes.len() - 8 {
        let op = bytes[pos];
        let len = u64::from_le_bytes(bytes[pos + 1..pos + 9].try_into().unwrap()) as usize;
        let end = pos + 9 + len;
        let name = match op {
            0x01 => "header",
            0x0c if !in_summary => {
                metadata += 1;
                if metadata == 1 {
                    "carom.run"
                } else {
                    "carom.summary"
                }
            }
            0x06 => "chunk",
            0x07 => "message index",
            0x0f => {
                in_summary = true;
                "data end"
            }
            0x02 => "footer",
            _ if in_summary => "summary section",
            other => panic!("record of opcode {other:#04x} in the data section"),
        };
        r.entry(name).or_default().push((pos, end));
        pos = end;
    }
    assert_eq!(pos, bytes.len() - 8, "the records end at the end magic");
    r.get_mut("header").unwrap().push((0, 8));
    r.get_mut("footer").unwrap().push((pos, bytes.len()));
    r
}

/// `k` positions spread evenly over `ranges` (byte offsets).
fn spread(ranges: &[(usize, usize)], k: usize) -> Vec<usize> {
    let total: usize = ranges.iter().map(|(a, b)| b - a).sum();
    (0..k)
        .map(|i| {
            let mut at = (2 * i + 1) * total / (2 * k);
            for &(a, b) in ranges {
                if at < b - a {
                    return a + at;
                }
                at -= b - a;
            }
            unreachable!()
        })
        .collect()
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// No panic, no abort: an exit code of 0 or 1.
fn no_panic(what: &str, o: &Output) {
    let e = stderr(o);
    assert!(!e.contains("panicked"), "{what}: {e}");
    assert!(
        matches!(o.status.code(), Some(0 | 1)),
        "{what}: {:?}: {e}",
        o.status
    );
}

/// Messages per channel summed, from `info --json`.
fn messages(info: &Value) -> u64 {
    info["channels"]
        .as_object()
        .unwrap()
        .values()
        .map(|c| c["messages"].as_u64().unwrap())
        .sum()
}

/// `analyze --json` without what names the file or says whether it is complete.
fn analysis(o: &Output) -> Value {
    let mut v: Value = serde_json::from_slice(&o.stdout).unwrap();
    let m = v.as_object_mut().unwrap();
    m.remove("file");
    m.remove("log_complete");
    v
}

/// What the tools did with one flipped file.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
enum Outcome {
    /// Every message read, with a warning; analysis as of the intact file.
    AllReadWithWarning,
    /// Every message read, the warning naming the damaged `carom.summary`.
    SummaryDamaged,
    /// Readers stop at the damage; repair keeps every message and names the
    /// unreadable record (a length outside the chunks).
    FramingSalvaged,
    /// Readers stop at the damage; repair keeps the other chunks and names the
    /// lost one.
    ChunkLost,
    /// Every tool refuses the file, naming `carom.run`.
    RunRefused,
    /// Every tool refuses the file as not a readable MCAP/carom file.
    Refused,
}

struct Intact {
    messages: u64,
    analysis: Value,
}

/// Run the four tools on `file` (a flipped copy) and classify what they did.
fn outcome(dir: &Path, file: &str, intact: &Intact, label: &str) -> Outcome {
    let info = carom(dir, &["info", "--json", file]);
    let verify = carom(dir, &["info", "--verify", "--json", file]);
    let analyze = carom(dir, &["analyze", "--json", file]);
    let repair = carom(dir, &["repair", file, "--out", "rep.mcap", "--force"]);
    for (what, o) in [
        ("info", &info),
        ("info --verify", &verify),
        ("analyze", &analyze),
        ("repair", &repair),
    ] {
        no_panic(&format!("{label}: {what}"), o);
    }
    // The check of every CRC and the footer never passes a damaged file.
    assert!(!verify.status.success(), "{label}: --verify passed");
    let refused = [&info, &verify, &analyze, &repair]
        .iter()
        .all(|o| !o.status.success());
    if refused {
        let all_name = |s: &str| {
            [&info, &verify, &analyze, &repair]
                .iter()
                .all(|o| stderr(o).contains(s))
        };
        if all_name("carom.run") {
            return Outcome::RunRefused;
        }
        assert!(all_name("not a carom log"), "{label}: {}", stderr(&repair));
        return Outcome::Refused;
    }
    // Repair ran: its copy is intact.
    assert!(repair.status.success(), "{label}: {}", stderr(&repair));
    let rep = carom(dir, &["info", "--verify", "--json", "rep.mcap"]);
    let kept = messages(&json_of(&rep));
    let lost_named = stderr(&repair).contains("lost: bytes");
    if verify.stdout.is_empty() {
        // Reading stopped at the damage: repair read around it.
        assert!(
            !analyze.status.success(),
            "{label}: analyze read a file --verify could not"
        );
        // It names what it could not read, or, when that was only the file's
        // start or a record's framing, says so.
        assert!(
            lost_named
                || String::from_utf8_lossy(&repair.stdout)
                    .contains("every message was read around the damage"),
            "{label}: repair names no loss: {}",
            stderr(&repair)
        );
        return if kept == intact.messages {
            Outcome::FramingSalvaged
        } else {
            assert!(0 < kept && kept < intact.messages, "{label}: kept {kept}");
            Outcome::ChunkLost
        };
    }
    // Every message read, with a warning, by every reader.
    let v: Value = serde_json::from_slice(&verify.stdout).unwrap();
    assert_eq!(v["complete"], false, "{label}");
    assert_eq!(messages(&v), intact.messages, "{label}");
    assert!(stderr(&verify).contains("warning"), "{label}");
    ok(&info);
    assert!(analyze.status.success(), "{label}: {}", stderr(&analyze));
    assert!(stderr(&analyze).contains("warning"), "{label}");
    assert_eq!(analysis(&analyze), intact.analysis, "{label}");
    assert_eq!(kept, intact.messages, "{label}");
    assert!(!lost_named, "{label}");
    let end = v["end"].as_str().unwrap();
    if end.contains("carom.summary") {
        // Not shown: no summary values in the report, and the text says so.
        assert_eq!(v["summary"], Value::Null, "{label}");
        assert_eq!(v["summary_damaged"], true, "{label}");
        let text = carom(dir, &["info", file]);
        assert!(ok(&text).contains("summary: DAMAGED"), "{label}");
        return Outcome::SummaryDamaged;
    }
    Outcome::AllReadWithWarning
}

/// The flips per region (few where the region is a handful of bytes).
const FLIPS: [(&str, usize); 8] = [
    ("header", 4),
    ("carom.run", 6),
    ("chunk", 10),
    ("message index", 4),
    ("carom.summary", 6),
    ("data end", 3),
    ("summary section", 6),
    ("footer", 4),
];

#[test]
fn single_bit_flips_anywhere_lose_at_most_the_chunk_they_hit() {
    let dir = scratch("flips");
    let run = carom(
        &dir,
        &[
            "run",
            "--force",
            "-q",
            "--out",
            "log.mcap",
            "--set",
            "species.0.count=1000",
            "--set",
            "stop.duration=6",
            "--set",
            "log.collision_detail=full",
            "--set",
            "log.snapshot_interval=1",
            "--set",
            "log.checkpoint_interval=2",
        ],
    );
    ok(&run);
    let bytes = std::fs::read(dir.join("log.mcap")).unwrap();
    let regions = regions(&bytes);
    assert!(regions["chunk"].len() >= 3, "{:?}", regions["chunk"]);
    let intact = Intact {
        messages: messages(&json_of(&carom(
            &dir,
            &["info", "--verify", "--json", "log.mcap"],
        ))),
        analysis: analysis(&carom(&dir, &["analyze", "--json", "log.mcap"])),
    };
    let mut counts: BTreeMap<&str, BTreeMap<Outcome, usize>> = BTreeMap::new();
    for (region, k) in FLIPS {
        for (n, at) in spread(&regions[region], k).into_iter().enumerate() {
            let mut flipped = bytes.clone();
            flipped[at] ^= 1 << (n * 3 % 8);
            std::fs::write(dir.join("flip.mcap"), &flipped).unwrap();
            let label = format!("{region}: byte {at} bit {}", n * 3 % 8);
            let o = outcome(&dir, "flip.mcap", &intact, &label);
            *counts.entry(region).or_default().entry(o).or_default() += 1;
        }
    }
    eprintln!("outcomes per region: {counts:#?}");
    use Outcome::*;
    let only = |region: &str, allowed: &[Outcome]| {
        let c = &counts[region];
        assert!(c.keys().all(|o| allowed.contains(o)), "{region}: {c:?}");
    };
    // The configuration cannot be trusted: refused, naming the record.
    only("carom.run", &[RunRefused]);
    // A chunk's messages are lost with it (its header's times, outside its
    // CRC, are damage read without harm); never more.
    only("chunk", &[ChunkLost, AllReadWithWarning]);
    assert!(counts["chunk"].get(&ChunkLost).copied().unwrap_or(0) * 2 >= FLIPS[2].1);
    // Outside the chunks, no message is lost.
    only("message index", &[AllReadWithWarning, FramingSalvaged]);
    only("carom.summary", &[SummaryDamaged, FramingSalvaged]);
    assert!(
        counts["carom.summary"]
            .get(&SummaryDamaged)
            .copied()
            .unwrap_or(0)
            >= 3
    );
    for region in ["data end", "summary section", "footer"] {
        only(region, &[AllReadWithWarning]);
    }
    // The file's start (magic, header record): read around by the readers, or
    // by `repair`, which finds `carom.run` after it and keeps every message.
    only("header", &[AllReadWithWarning, FramingSalvaged]);
}

/// A log without `carom.summary` (a cut log finished by `repair`) whose index or
/// footer is damaged: every reader falls back to reading the chunks, and reads
/// every message with a warning (the data-end record was reached, its CRC held).
#[test]
fn a_log_without_a_summary_reads_every_message_past_a_damaged_index() {
    let dir = scratch("no-summary");
    let run = carom(
        &dir,
        &[
            "run",
            "--force",
            "-q",
            "--out",
            "log.mcap",
            "--set",
            "species.0.count=1000",
            "--set",
            "stop.duration=6",
            "--set",
            "log.collision_detail=full",
        ],
    );
    ok(&run);
    let bytes = std::fs::read(dir.join("log.mcap")).unwrap();
    std::fs::write(dir.join("cut.mcap"), &bytes[..bytes.len() * 2 / 3]).unwrap();
    ok(&carom(
        &dir,
        &["repair", "cut.mcap", "--out", "repaired.mcap"],
    ));
    let repaired = std::fs::read(dir.join("repaired.mcap")).unwrap();
    let regions = regions(&repaired);
    assert!(!regions.contains_key("carom.summary"));
    let all = messages(&json_of(&carom(
        &dir,
        &["info", "--verify", "--json", "repaired.mcap"],
    )));
    let analysis_intact = analysis(&carom(&dir, &["analyze", "--json", "repaired.mcap"]));
    for region in ["summary section", "footer", "message index"] {
        for (n, at) in spread(&regions[region], 4).into_iter().enumerate() {
            let mut flipped = repaired.clone();
            flipped[at] ^= 1 << (n * 3 % 8);
            std::fs::write(dir.join("flip.mcap"), &flipped).unwrap();
            let label = format!("{region}: byte {at}");
            let verify = carom(&dir, &["info", "--verify", "--json", "flip.mcap"]);
            no_panic(&label, &verify);
            assert!(!verify.status.success(), "{label}");
            let v: Value = serde_json::from_slice(&verify.stdout).unwrap_or_else(|_| {
                panic!("{label}: {}", stderr(&verify));
            });
            assert_eq!(messages(&v), all, "{label}");
            let info = carom(&dir, &["info", "--json", "flip.mcap"]);
            assert_eq!(messages(&json_of(&info)), all, "{label}");
            let analyze = carom(&dir, &["analyze", "--json", "flip.mcap"]);
            assert!(analyze.status.success(), "{label}: {}", stderr(&analyze));
            assert!(stderr(&analyze).contains("warning"), "{label}");
            assert_eq!(analysis(&analyze), analysis_intact, "{label}");
        }
    }
}

/// A log whose records carry no checksum (older than format 2.3; here the key
/// renamed in place) keeps failing on a data-section CRC: nothing vouches for
/// the records outside the chunks.
#[test]
fn a_log_without_checksums_keeps_failing_on_a_data_section_crc() {
    let dir = scratch("old");
    ok(&carom(
        &dir,
        &[
            "run",
            "--force",
            "-q",
            "--out",
            "log.mcap",
            "--set",
            "species.0.count=400",
            "--set",
            "stop.duration=2",
        ],
    ));
    let bytes = std::fs::read(dir.join("log.mcap")).unwrap();
    let regions = regions(&bytes);
    let mut old = bytes.clone();
    for region in ["carom.run", "carom.summary"] {
        let (a, b) = regions[region][0];
        let at = a + old[a..b].windows(5).position(|w| w == b"crc32").unwrap();
        old[at + 4] = b'0'; // `crc30`: a key nobody reads
    }
    std::fs::write(dir.join("old.mcap"), &old).unwrap();
    let verify = carom(&dir, &["info", "--verify", "old.mcap"]);
    no_panic("old", &verify);
    assert!(!verify.status.success());
    assert!(
        stderr(&verify).contains("Data section CRC failed"),
        "{}",
        stderr(&verify)
    );
    assert!(stderr(&verify).contains("corrupted"), "{}", stderr(&verify));
    // The same change with the checksums in place is a summary damaged.
    let mut sealed = bytes.clone();
    let (a, b) = regions["carom.summary"][0];
    let at = a + sealed[a..b].windows(5).position(|w| w == b"crc32").unwrap();
    sealed[at + 4] = b'0';
    std::fs::write(dir.join("summary.mcap"), &sealed).unwrap();
    let verify = carom(&dir, &["info", "--verify", "summary.mcap"]);
    no_panic("summary", &verify);
    assert!(stderr(&verify).contains("warning"), "{}", stderr(&verify));
}
