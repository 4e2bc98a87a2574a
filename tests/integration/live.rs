//! `carom run --live`: a client of Foxglove's own WebSocket library
//! (`tests/node/live.mjs`: `@foxglove/ws-protocol`, protobufjs for
//! `foxglove.SceneUpdate`) watches a running run, and what it gets is exact: each
//! `/scene` frame holds the state at its time bit for bit (the state an engine of
//! the same configuration has when stopped at that time, which also reproduces the
//! log's snapshots bit for bit), and each `/thermo` record is one the log holds. It
//! disconnects, reconnects and stays until the run ends; the run ends cleanly with a
//! complete log. A client that never reads neither holds up the run nor makes its
//! memory grow. Skips without node and tests/node's modules; fails instead when
//! `CI` is set. (The collision rates with and without `--live` are measured
//! outside the tests: docs/performance.md.)

use std::io::{BufRead, BufReader, Read};
use std::path::Path;
use std::process::{Child, Command, ExitStatus, Stdio};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use carom_config::Config;
use carom_engine::{Engine, State};
use carom_log::{scan, LogEnd, LogMessage, LogReader, Thermo};
use serde_json::Value;

use crate::cli_common::{node_with, scratch, BIN};

/// A run of `carom run CONFIG --live 0` (any free port) in `dir`, with its URL.
struct LiveRun {
    child: Child,
    url: String,
    /// Standard error, read to the end (so the pipe never fills).
    stderr: JoinHandle<String>,
}

impl LiveRun {
    fn start(dir: &Path, config: &str, extra: &[&str]) -> LiveRun {
        std::fs::write(dir.join("run.json"), config).unwrap();
        let mut child = Command::new(BIN)
            .args(["run", "run.json", "-o", "run.mcap", "-q", "--live", "0"])
            .args(extra)
            .current_dir(dir)
            .stdin(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        let mut lines = BufReader::new(child.stderr.take().unwrap()).lines();
        let mut said = String::new();
        let url = loop {
            let Some(Ok(line)) = lines.next() else {
                panic!("carom ended before serving:\n{said}");
            };
            said += &line;
            said.push('\n');
            if let Some(at) = line.find("ws://") {
                break line[at..].split_whitespace().next().unwrap().to_string();
            }
        };
        let stderr = std::thread::spawn(move || {
            lines.map_while(Result::ok).fold(said, |s, l| s + &l + "\n")
        });
        LiveRun { child, url, stderr }
    }

    /// Wait for the run to end (at most `limit`: a hang is a failure).
    fn wait(mut self, limit: Duration) -> (ExitStatus, String) {
        let status = wait_for(&mut self.child, limit, "carom run --live");
        (status, self.stderr.join().unwrap())
    }
}

/// Wait for `child` at most `limit`; kill it and fail beyond.
fn wait_for(child: &mut Child, limit: Duration, what: &str) -> ExitStatus {
    let t0 = Instant::now();
    loop {
        if let Some(s) = child.try_wait().unwrap() {
            return s;
        }
        if t0.elapsed() > limit {
            let _ = child.kill();
            panic!("{what} still running after {limit:?}");
        }
        std::thread::sleep(Duration::from_millis(20));
    }
}

/// A periodic fluid of `n` discs at η = 0.5 for `duration`, logging `/thermo`
/// every `thermo` and snapshots every `snapshot`, no collisions.
fn config(n: usize, duration: f64, thermo: f64, snapshot: f64) -> String {
    serde_json::json!({
        "species": [{"count": n, "radius": 0.5, "mass": 1.0}],
        "box": {"packing_fraction": 0.5, "aspect": 1.0, "boundary": "periodic"},
        "temperature": 1.0,
        "seed": 54,
        "stop": {"duration": duration},
        "log": {"collisions": false, "snapshot_interval": snapshot,
                "thermo_interval": thermo, "checkpoint_interval": duration / 4.0}
    })
    .to_string()
}

/// The engine of `config` as `carom run` builds it.
fn engine_of(config: &str) -> Engine {
    let spec = Config::from_json_with_sets(config, "configuration", &[])
        .and_then(|c| c.to_run_spec())
        .unwrap();
    let mut e = Engine::new(spec.system.build().unwrap(), spec.params).unwrap();
    e.set_thermostat(spec.thermostat, spec.system.seed).unwrap();
    e
}

/// The positions of `s` as two arrays of bits.
/// The bits of every x and of every y of a frame, compared exactly.
type Positions = (Vec<u64>, Vec<u64>);

fn bits(x: impl Iterator<Item = f64>) -> Vec<u64> {
    x.map(f64::to_bits).collect()
}

fn xs(s: &State) -> (Vec<u64>, Vec<u64>) {
    (
        bits(s.positions.iter().map(|p| p.x)),
        bits(s.positions.iter().map(|p| p.y)),
    )
}

fn floats(v: &Value) -> Vec<u64> {
    bits(v.as_array().unwrap().iter().map(|x| x.as_f64().unwrap()))
}

#[test]
fn a_client_sees_the_runs_exact_states_and_records_and_can_come_back() {
    let Some(node) = node_with("@foxglove/ws-protocol") else {
        return;
    };
    let dir = scratch("watch");
    let text = config(400, 6_000.0, 100.0, 600.0);
    let run = LiveRun::start(&dir, &text, &["--live-rate", "40"]);
    let mut client = Command::new("node")
        .arg(node.join("live.mjs"))
        .args([&run.url, "watch", "25"])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let read = |pipe: Option<Box<dyn Read + Send>>| {
        std::thread::spawn(move || {
            let mut s = String::new();
            pipe.unwrap().read_to_string(&mut s).unwrap();
            s
        })
    };
    let stdout = read(client.stdout.take().map(|p| Box::new(p) as _));
    let stderr = read(client.stderr.take().map(|p| Box::new(p) as _));
    let (status, said) = run.wait(Duration::from_secs(300));
    assert!(status.success(), "carom run --live: {status}\n{said}");
    // The server closes the connection at the end: the client ends by itself.
    let cs = wait_for(&mut client, Duration::from_secs(30), "the node client");
    let (stdout, stderr) = (stdout.join().unwrap(), stderr.join().unwrap());
    assert!(cs.success(), "live.mjs: {cs}\n{stderr}");
    let got: Value = serde_json::from_str(&stdout).expect("live.mjs prints JSON");

    // The channels, in Foxglove's schemas.
    let channels = &got["channels"];
    for (topic, encoding, schema) in [
        ("/scene", "protobuf", "foxglove.SceneUpdate"),
        ("/thermo", "json", "carom.Thermo"),
        ("/progress", "json", "carom.Progress"),
    ] {
        assert_eq!(channels[topic]["encoding"], encoding, "{topic}");
        assert_eq!(channels[topic]["schemaName"], schema, "{topic}");
    }

    // A complete log.
    let log = dir.join("run.mcap");
    let info = scan(&log).unwrap();
    assert!(matches!(info.end, LogEnd::Complete), "{:?}", info.end);
    assert!(info.summary.is_some());

    // The frames: 25 at increasing times, each stamped with its time; a reference
    // engine stopped at each time has exactly their positions, and it also has
    // exactly the log's snapshots.
    let frames = got["frames"].as_array().unwrap();
    let again = got["again"]["frames"].as_array().unwrap();
    assert_eq!(frames.len(), 25);
    assert!(!again.is_empty(), "the reconnected client got no frame");
    assert_eq!(got["stamps_ok"], true, "a frame's log time is not its time");
    let mut exact: Vec<(f64, Positions, &str)> = Vec::new();
    let mut last = -1.0;
    for f in frames.iter().chain(again) {
        let t = f["time"].as_f64().unwrap();
        assert!(t >= last, "frames out of order: {t} after {last}");
        last = t;
        exact.push((t, (floats(&f["x"]), floats(&f["y"])), "live frame"));
    }
    let mut r = LogReader::open(&log).unwrap();
    let snapshots: Vec<_> = r
        .snapshots()
        .map(|m| match m.unwrap() {
            LogMessage::Snapshot(s) => s,
            other => panic!("{other:?}"),
        })
        .collect();
    assert_eq!(snapshots.len(), 11);
    for s in &snapshots {
        let p = (
            bits(s.positions.iter().map(|p| p.x)),
            bits(s.positions.iter().map(|p| p.y)),
        );
        exact.push((s.time, p, "log snapshot"));
    }
    exact.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut e = engine_of(&text);
    for (t, positions, what) in &exact {
        e.run_until(*t).unwrap();
        assert!(xs(&e.state()) == *positions, "{what} at t = {t:?} differs");
    }
    let d = frames[0]["d"].as_array().unwrap();
    assert!(d.iter().all(|d| d.as_f64() == Some(1.0)), "diameter 2r = 1");

    // The /thermo records the first client got are the log's, field for field.
    let logged: Vec<Thermo> = LogReader::open(&log)
        .unwrap()
        .thermo()
        .map(|m| match m.unwrap() {
            LogMessage::Thermo(t) => t,
            other => panic!("{other:?}"),
        })
        .collect();
    let live = got["thermo"].as_array().unwrap();
    assert!(!live.is_empty(), "no /thermo record came");
    for v in live {
        let th: Thermo = serde_json::from_value(v.clone()).unwrap();
        assert!(
            logged.contains(&th),
            "a live /thermo record the log lacks: {v}"
        );
    }
    // The layout in data/ plots fields of /thermo that the live records carry.
    let layout = Path::new(env!("CARGO_MANIFEST_DIR")).join("data/foxglove/layout.json");
    let layout = std::fs::read_to_string(layout).unwrap();
    let running = live.last().unwrap();
    for field in ["temperature", "pressure", "z", "collision_rate"] {
        assert!(layout.contains(&format!("/thermo.{field}")), "{field}");
        assert!(
            running[field].is_number(),
            "a live /thermo record lacks {field}"
        );
    }
    // /progress: collisions never go back, the fraction stays in [0, 1].
    let progress = got["progress"].as_array().unwrap();
    assert!(!progress.is_empty());
    let counts: Vec<u64> = progress
        .iter()
        .map(|p| p["collisions"].as_u64().unwrap())
        .collect();
    assert!(counts.windows(2).all(|w| w[0] <= w[1]), "{counts:?}");
    assert!(progress
        .iter()
        .all(|p| (0.0..=1.0).contains(&p["fraction"].as_f64().unwrap())));
}

/// The resident memory of process `pid` (bytes), from /proc.
fn rss(pid: u32) -> Option<u64> {
    let status = std::fs::read_to_string(format!("/proc/{pid}/status")).ok()?;
    let line = status.lines().find(|l| l.starts_with("VmRSS:"))?;
    let kb: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb * 1024)
}

/// The collision rate a finished run reports (collisions/s), from its log.
fn rate_of(log: &Path) -> f64 {
    scan(log).unwrap().summary.unwrap().collisions_per_second
}

#[test]
fn a_client_that_never_reads_neither_holds_up_the_run_nor_fills_memory() {
    let Some(node) = node_with("@foxglove/ws-protocol") else {
        return;
    };
    // 10⁴ discs: a frame is about 1 MB; at 50 frames a second a server that
    // queued every frame for the stuck client would grow by 50 MB a second.
    let text = config(10_000, 30.0, 0.5, 30.0);
    let plain = scratch("plain");
    std::fs::write(plain.join("run.json"), &text).unwrap();
    let out = Command::new(BIN)
        .args(["run", "run.json", "-o", "run.mcap", "-q"])
        .current_dir(&plain)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );

    let dir = scratch("stall");
    let mut run = LiveRun::start(&dir, &text, &["--live-rate", "50"]);
    let mut client = Command::new("node")
        .arg(node.join("live.mjs"))
        .args([&run.url, "stall"])
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut subscribed = BufReader::new(client.stderr.take().unwrap()).lines();
    assert!(subscribed
        .next()
        .is_some_and(|l| l.unwrap().contains("not reading")));
    let pid = run.child.id();
    let (first, mut peak) = (rss(pid).unwrap(), 0);
    while run.child.try_wait().unwrap().is_none() {
        peak = peak.max(rss(pid).unwrap_or(0));
        std::thread::sleep(Duration::from_millis(50));
    }
    let (status, said) = run.wait(Duration::from_secs(5));
    let _ = client.kill();
    let _ = client.wait();
    assert!(status.success(), "{status}\n{said}");
    assert!(matches!(
        scan(&dir.join("run.mcap")).unwrap().end,
        LogEnd::Complete
    ));
    let grown = peak.saturating_sub(first);
    assert!(
        grown < 64 << 20,
        "RSS grew by {grown} bytes with a client that never reads"
    );
    // A guard against a run that waits for its client, not a measurement (that
    // is in docs/performance.md): the two runs take turns on a shared machine.
    let (with, without) = (
        rate_of(&dir.join("run.mcap")),
        rate_of(&plain.join("run.mcap")),
    );
    assert!(
        with > 0.5 * without,
        "{with:.3e} collisions/s with a client that never reads, {without:.3e} without --live"
    );
}
