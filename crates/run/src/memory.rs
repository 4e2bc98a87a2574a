//! The memory check before a run: an estimate of the memory a run of N discs needs
//! ([`memory_needed`]) against the memory the machine has for it
//! ([`memory_available`]: `MemAvailable` of /proc/meminfo, and the room left under
//! a cgroup limit or an address-space limit (`ulimit -v`, RLIMIT_AS) when one is
//! set), so that a run far too large for the machine is
//! refused with the numbers before anything big is allocated, rather than placing
//! discs for minutes while the machine runs out of memory. The estimate is per
//! disc: the engine (about 140 B per disc, `Engine::heap_bytes`; docs/performance.md,
//! "memory"), the initial state and the lattice sites while the engine is built,
//! and the log writer's snapshot, checkpoint and (when logged) scene buffers.
//! `CAROM_IGNORE_MEMORY_CHECK=1` skips the check (README, "Two commands").

use carom_config::ConfigError;
use carom_log::RunSpec;

/// Bytes per disc of the engine's arrays (138.2 measured at N = 10⁶, with room).
const ENGINE: u64 = 140;
/// Bytes per disc while the discs are placed and the engine is built: the initial
/// state (position, velocity, species: 34 B), lattice sites (up to two per disc,
/// 16 B each) and the occupied ones (16 B).
const PLACEMENT: u64 = 34 + 32 + 16;
/// Bytes per disc of the writer at a snapshot (34 B per disc: the state copied out
/// of the engine, its encoded message and the chunk it goes into).
const SNAPSHOT: u64 = 3 * 34;
/// Bytes per disc of a `/checkpoint` message (the engine's arrays, encoded).
pub(super) const CHECKPOINT_MESSAGE: u64 = 106;
/// Bytes per disc of the writer at a checkpoint: the engine's arrays copied out,
/// their encoded message and the compressed chunk.
const CHECKPOINT: u64 = 3 * CHECKPOINT_MESSAGE;

/// Bytes per disc of the writer at a `/scene` frame, when scenes are logged (128 B
/// per disc: the encoded message, the buffer recycled for the next one, and the
/// chunk it goes into); the state it encodes is the snapshot's.
const SCENE: u64 = 3 * 128;

/// The environment variable that, set to 1, skips the check.
pub const IGNORE_MEMORY_CHECK: &str = "CAROM_IGNORE_MEMORY_CHECK";

/// What a run of `n` discs is estimated to need at its peak (bytes): the engine
/// with the larger of the placement (before the run) and the writer's buffers (a
/// checkpoint is always written; a snapshot's buffers are kept with it when
/// snapshots are logged).
pub fn memory_needed(n: u64, snapshots: bool) -> u64 {
    let writer = CHECKPOINT + if snapshots { SNAPSHOT } else { 0 };
    n.saturating_mul(ENGINE + PLACEMENT.max(writer))
}

/// The memory available to this process (bytes) and where the limit comes from:
/// `MemAvailable` from /proc/meminfo, or the room under the cgroup's limit
/// (v2 `memory.max` − `memory.current`, v1 `memory.limit_in_bytes` −
/// `memory.usage_in_bytes`) or under the process's address-space limit (the soft
/// "Max address space" of /proc/self/limits − `VmSize` of /proc/self/status),
/// whichever is least. `None` where none is known.
pub fn memory_available() -> Option<(u64, &'static str)> {
    let read = |p: &str| std::fs::read_to_string(p).ok();
    let meminfo = read("/proc/meminfo")
        .and_then(|t| mem_available(&t))
        .map(|b| (b, "MemAvailable in /proc/meminfo"));
    let cgroup = [
        (
            "/sys/fs/cgroup/memory.max",
            "/sys/fs/cgroup/memory.current",
            "the cgroup's memory.max",
        ),
        (
            "/sys/fs/cgroup/memory/memory.limit_in_bytes",
            "/sys/fs/cgroup/memory/memory.usage_in_bytes",
            "the cgroup's memory.limit_in_bytes",
        ),
    ]
    .iter()
    .find_map(|(limit, usage, what)| {
        let room = cgroup_room(&read(limit)?, read(usage).as_deref())?;
        Some((room, *what))
    });
    let address_space = read("/proc/self/limits")
        .and_then(|limits| {
            let status = read("/proc/self/status");
            address_space_room(&limits, status.as_deref())
        })
        .map(|b| (b / 3 * 2, ADDRESS_SPACE));
    [meminfo, cgroup, address_space]
        .into_iter()
        .flatten()
        .min_by_key(|&(bytes, _)| bytes)
}

/// Where the address-space limit comes from, in words for the refusal. Only two
/// thirds of the room under it are counted: address space is also taken by what
/// is reserved and never touched (the allocator's arenas, buffers grown by
/// doubling), which `MemAvailable` and a cgroup do not count. Under `ulimit -v
/// 2000000` (2.05 GB) 3.1·10⁶ discs ran and 3.2·10⁶ failed, under 4000000
/// 5.4·10⁶ ran and 5.8·10⁶ failed: 640 to 760 bytes of address space per disc
/// against the 560 of [`memory_needed`]; two thirds allow 2.4·10⁶ and 4.9·10⁶.
const ADDRESS_SPACE: &str = "two thirds of the room under the address-space limit `ulimit -v` \
     (RLIMIT_AS), for the address space reserved but never touched";

/// The room (bytes) under the soft address-space limit, from the text of
/// /proc/self/limits, less the `VmSize` (kB) of /proc/self/status where known.
/// No limit ("unlimited") gives `None`.
fn address_space_room(limits: &str, status: Option<&str>) -> Option<u64> {
    let line = limits
        .lines()
        .find(|l| l.starts_with("Max address space"))?;
    let soft: u64 = line
        .trim_start_matches("Max address space")
        .split_whitespace()
        .next()?
        .parse()
        .ok()?;
    let mapped = status
        .and_then(|s| s.lines().find(|l| l.starts_with("VmSize:")))
        .and_then(|l| l.split_whitespace().nth(1)?.parse::<u64>().ok())
        .map_or(0, |kb| kb.saturating_mul(1024));
    Some(soft.saturating_sub(mapped))
}

/// `MemAvailable` (bytes) from the text of /proc/meminfo.
fn mem_available(meminfo: &str) -> Option<u64> {
    let line = meminfo.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kb: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb.saturating_mul(1024))
}

/// The room (bytes) under a cgroup memory limit: `limit` less `usage` where known.
/// No limit ("max", or the huge number cgroup v1 reports for none) gives `None`.
fn cgroup_room(limit: &str, usage: Option<&str>) -> Option<u64> {
    let limit: u64 = limit.trim().parse().ok()?;
    if limit >= 1 << 60 {
        return None;
    }
    let used = usage
        .and_then(|u| u.trim().parse::<u64>().ok())
        .unwrap_or(0);
    Some(limit.saturating_sub(used))
}

/// Refuse `spec` when the run needs more memory than is available: an error on
/// `species.K.count` (the largest species) with both numbers in GB. Passes when
/// the memory available is not known or `CAROM_IGNORE_MEMORY_CHECK=1` is set.
pub fn check_memory(spec: &RunSpec) -> Result<(), ConfigError> {
    if std::env::var(IGNORE_MEMORY_CHECK).is_ok_and(|v| v == "1") {
        return Ok(());
    }
    match memory_available() {
        Some((available, source)) => check_against(spec, available, source),
        None => Ok(()),
    }
}

/// [`check_memory`] against `available` bytes, known from `source`.
fn check_against(spec: &RunSpec, available: u64, source: &str) -> Result<(), ConfigError> {
    let species = &spec.system.species;
    let n: u64 = species.iter().map(|s| s.count as u64).sum();
    let snapshots = spec.log.snapshot_interval.is_some();
    let scene = if spec.log.scene_interval.is_some() {
        SCENE
    } else {
        0
    };
    let needed = memory_needed(n, snapshots).saturating_add(n.saturating_mul(scene));
    if needed <= available {
        return Ok(());
    }
    let largest = (0..species.len())
        .max_by_key(|&k| species[k].count)
        .unwrap_or(0);
    let per_disc = memory_needed(1, snapshots) + scene;
    let gb = |b: u64| b as f64 / 1e9;
    Err(ConfigError::Invalid {
        field: format!("species.{largest}.count"),
        problem: format!(
            "{n} discs need about {:.1} GB of memory ({per_disc} bytes per disc: the engine, \
             placement and the log's snapshot, checkpoint and scene buffers), but {:.1} GB are \
             available ({source})",
            gb(needed),
            gb(available),
        ),
        allowed: format!(
            "at most about {} discs in all on this machine now; set \
             {IGNORE_MEMORY_CHECK}=1 to run anyway",
            available / per_disc
        ),
    })
}

#[cfg(test)]
mod tests {
    use super::{
        address_space_room, cgroup_room, check_against, mem_available, memory_needed, ADDRESS_SPACE,
    };

    #[test]
    fn the_estimate_is_the_engine_and_the_writers_buffers_per_disc() {
        // Engine 140 B + checkpoint 318 B + snapshot 102 B per disc.
        assert_eq!(memory_needed(1, true), 560);
        assert_eq!(memory_needed(1_000_000, true), 560_000_000);
        // Without snapshots the checkpoint's buffers are still needed.
        assert_eq!(memory_needed(10, false), 4580);
        // At least the engine's measured 138.2 B per disc, and no overflow.
        assert!(memory_needed(1, false) > 139);
        assert_eq!(memory_needed(u64::MAX / 2, true), u64::MAX);
    }

    #[test]
    fn available_memory_is_read_from_meminfo_and_the_cgroup() {
        let meminfo = "MemTotal:       24684096 kB\nMemFree: 1 kB\nMemAvailable:   23183564 kB\n";
        assert_eq!(mem_available(meminfo), Some(23_183_564 * 1024));
        assert_eq!(mem_available("MemTotal: 5 kB\n"), None);
        assert_eq!(cgroup_room("max\n", Some("5")), None);
        assert_eq!(cgroup_room("9223372036854771712\n", Some("5")), None);
        assert_eq!(
            cgroup_room("8000000000\n", Some("3000000000\n")),
            Some(5_000_000_000)
        );
        assert_eq!(cgroup_room("8000000000\n", None), Some(8_000_000_000));
    }

    #[test]
    fn the_address_space_limit_less_what_is_mapped_is_available() {
        let limits = "Limit                     Soft Limit           Hard Limit           Units     \n\
                      Max data size             unlimited            unlimited            bytes     \n\
                      Max address space         8192000000           unlimited            bytes     \n";
        let status = "Name:\tcarom\nVmPeak:\t  9000 kB\nVmSize:\t    3892 kB\n";
        assert_eq!(
            address_space_room(limits, Some(status)),
            Some(8_192_000_000 - 3892 * 1024)
        );
        assert_eq!(address_space_room(limits, None), Some(8_192_000_000));
        let unlimited = limits.replace("8192000000", "unlimited ");
        assert_eq!(address_space_room(&unlimited, Some(status)), None);
        // Refused naming the limit: 3·10⁷ discs need 16.8 GB.
        let mut spec = carom_config::load_config(None, &[]).unwrap();
        spec.system.species[0].count = 30_000_000;
        let e = check_against(&spec, 8_192_000_000, ADDRESS_SPACE)
            .unwrap_err()
            .to_string();
        assert!(e.contains("ulimit -v") && e.contains("16.8 GB"), "{e}");
    }

    #[test]
    fn a_run_larger_than_the_memory_is_refused_with_the_numbers() {
        let mut spec = carom_config::load_config(None, &[]).unwrap();
        spec.system.species[0].count = 10_000_000_000;
        let e = check_against(&spec, 8_000_000_000, "test")
            .unwrap_err()
            .to_string();
        assert!(e.contains("species.0.count"), "{e}");
        assert!(e.contains("5600.0 GB") && e.contains("8.0 GB"), "{e}");
        spec.system.species[0].count = 1000;
        assert!(check_against(&spec, 8_000_000_000, "test").is_ok());
        // /scene frames add 384 B per disc: 10⁷ discs need 5.6 GB, 9.44 GB with them.
        spec.system.species[0].count = 10_000_000;
        assert!(check_against(&spec, 8_000_000_000, "test").is_ok());
        spec.log.scene_interval = Some(1.0);
        let e = check_against(&spec, 8_000_000_000, "test")
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("9.4 GB") && e.contains("944 bytes per disc"),
            "{e}"
        );
    }
}
