//! How many points run, or how many logs are analysed, at once: `--jobs N`,
//! by default one per core, and never more than the cores. Each point is one
//! single-threaded `carom run`, each analysis one thread: more of them than cores
//! only share the cores, at the price of memory and of the machine's response
//! (`collect --jobs 1000` once started 1,007 threads). The number of cores is the
//! one the process may use (`std::thread::available_parallelism`: affinity and
//! cgroup quotas included).

/// The cores this process may use (1 if unknown).
pub fn cores() -> usize {
    std::thread::available_parallelism()
        .map(|n| n.get())
        .unwrap_or(1)
}

/// The number to run at once for `--jobs requested` on `cores` cores, and a note
/// to print when the request was cut down.
pub fn jobs_at_once(requested: Option<u32>, cores: usize) -> (usize, Option<String>) {
    let cores = cores.max(1);
    match requested {
        None => (cores, None),
        Some(n) if n as usize > cores => (
            cores,
            Some(format!(
                "--jobs {n}: capped at the {cores} core{} this process may use",
                if cores == 1 { "" } else { "s" }
            )),
        ),
        Some(n) => ((n as usize).max(1), None),
    }
}

#[cfg(test)]
mod tests {
    use super::jobs_at_once;

    #[test]
    fn jobs_are_capped_at_the_cores() {
        assert_eq!(jobs_at_once(None, 8), (8, None));
        assert_eq!(jobs_at_once(Some(3), 8), (3, None));
        let (n, note) = jobs_at_once(Some(1000), 2);
        assert_eq!(n, 2);
        assert!(note.unwrap().contains("--jobs 1000: capped at the 2 cores"));
        assert_eq!(jobs_at_once(Some(2), 2), (2, None));
    }
}
