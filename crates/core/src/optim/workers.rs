//! How many worker threads a `plan` or a `bench` starts.
//!
//! Why: the work is bound by the processor, so threads beyond the cores the process may use
//! only wait on each other. For a run they cost far more than that: the evaluator hands each
//! swarm batch of a few rows to the pool, and every extra idle worker wakes and searches for
//! work on every batch (`plan --threads 256` took 8.3 s on 2 cores against 0.40 s on 2
//! threads, the same plan). A run's results do not depend on the thread count (see the
//! evaluator), so holding a request to the cores changes only how long it takes.

use std::num::NonZeroUsize;

/// The cores this process may use (its affinity and quota), at least 1.
#[must_use]
pub fn cores() -> usize {
    std::thread::available_parallelism().map_or(1, NonZeroUsize::get)
}

/// The threads to start when `requested` were asked for on a machine with `cores`: the
/// request held to the cores; 0 (the pool's own default: one per core) stays 0.
#[must_use]
pub fn worker_threads(requested: usize, cores: usize) -> usize {
    requested.min(cores.max(1))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_request_is_held_to_the_cores_and_zero_stays_the_default() {
        assert_eq!(worker_threads(0, 2), 0);
        assert_eq!(worker_threads(1, 2), 1);
        assert_eq!(worker_threads(2, 2), 2);
        assert_eq!(worker_threads(256, 2), 2);
        assert_eq!(worker_threads(3, 0), 1);
        assert!(cores() >= 1);
    }
}
