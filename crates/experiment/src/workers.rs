//! How many worker threads a `plan` or a `bench` starts (the CLI's and Python's).
//!
//! Why: the work is bound by the processor, so threads beyond the cores the process may use
//! only wait on each other. For a run they cost far more than that: the evaluator hands each
//! swarm batch of a few rows to the pool, and every extra idle worker wakes and searches for
//! work on every batch (`plan --threads 256` took 8.3 s on 2 cores against 0.40 s on 2
//! threads, the same plan). A run's results do not depend on the thread count (see the
//! evaluator in swarmplan-core), so holding a request to the cores changes only how long it
//! takes. A request comes from `--threads` or, when that is 0, from rayon's own
//! `RAYON_NUM_THREADS`, which is held the same way. Here, not in swarmplan-core, because it
//! reads the process's environment and affinity.

use std::num::NonZeroUsize;

/// The environment variable rayon reads for its default thread count.
pub const RAYON_ENV: &str = "RAYON_NUM_THREADS";

/// The cores this process may use (its affinity and quota), at least 1.
#[must_use]
pub fn cores() -> usize {
    std::thread::available_parallelism().map_or(1, NonZeroUsize::get)
}

/// Where a thread count was asked for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Asked {
    /// Nothing asked: one thread per core.
    Default,
    /// `--threads N` (or a library call's count), N >= 1.
    Count(usize),
    /// `RAYON_NUM_THREADS=N`, N >= 1, under a count of 0.
    Env(usize),
}

impl Asked {
    /// What `count` (0: none) asks for, and under 0 this process's `RAYON_NUM_THREADS`.
    #[must_use]
    pub fn from_count_or_env(count: usize) -> Self {
        Self::from_parts(count, std::env::var(RAYON_ENV).ok().as_deref())
    }

    /// What `count` and the variable's value `env` ask for: the count when it is not 0,
    /// else the variable when it holds a positive whole number (read as rayon reads it,
    /// untrimmed), else the default.
    #[must_use]
    pub fn from_parts(count: usize, env: Option<&str>) -> Self {
        if count > 0 {
            return Self::Count(count);
        }
        match env.and_then(|v| v.parse::<usize>().ok()) {
            Some(n) if n > 0 => Self::Env(n),
            _ => Self::Default,
        }
    }

    /// The threads to start on a machine with `cores`: the request held to the cores, one
    /// per core by default.
    #[must_use]
    pub fn threads(self, cores: usize) -> usize {
        let cores = cores.max(1);
        match self {
            Self::Default => cores,
            Self::Count(n) | Self::Env(n) => n.min(cores),
        }
    }

    /// When the request was more than `cores` and is held to them: what asked for it
    /// (`--threads N` or `RAYON_NUM_THREADS=N`), for a note.
    #[must_use]
    pub fn held(self, cores: usize) -> Option<String> {
        match self {
            Self::Count(n) if n > cores.max(1) => Some(format!("--threads {n}")),
            Self::Env(n) if n > cores.max(1) => Some(format!("{RAYON_ENV}={n}")),
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_request_is_held_to_the_cores_and_none_means_one_per_core() {
        let asked = |count, env| Asked::from_parts(count, env);
        assert_eq!(asked(0, None), Asked::Default);
        assert_eq!(asked(0, Some("")), Asked::Default);
        assert_eq!(asked(0, Some("0")), Asked::Default);
        assert_eq!(asked(0, Some("many")), Asked::Default);
        assert_eq!(asked(0, Some(" 256")), Asked::Default);
        assert_eq!(asked(0, Some("256")), Asked::Env(256));
        assert_eq!(asked(3, Some("256")), Asked::Count(3));
        assert_eq!(Asked::Default.threads(2), 2);
        assert_eq!(Asked::Count(1).threads(2), 1);
        assert_eq!(Asked::Count(256).threads(2), 2);
        assert_eq!(Asked::Env(256).threads(2), 2);
        assert_eq!(Asked::Count(3).threads(0), 1);
        assert_eq!(Asked::Count(3).held(2).as_deref(), Some("--threads 3"));
        assert_eq!(
            Asked::Env(3).held(2).as_deref(),
            Some("RAYON_NUM_THREADS=3")
        );
        assert_eq!(Asked::Count(2).held(2), None);
        assert_eq!(Asked::Default.held(1), None);
        assert!(cores() >= 1);
    }
}
