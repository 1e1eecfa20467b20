//! Stopping runs from outside, between iterations: what Ctrl-C does to a Python call.
//!
//! Why a flag in the budget: the command line is stopped by its signal (a bench keeps every
//! record it wrote, `--resume` goes on), but a Python call runs inside the interpreter, which
//! only sees Ctrl-C when the call returns, minutes or hours later. So the bindings watch for
//! it while the work runs on another thread, and raise this flag, which
//! [`super::solve_watching`] reads between iterations (the run then ends as
//! [`super::Termination::Cancelled`]) and the experiment runner reads between runs. A flag
//! is not part of what a budget *is*: budgets with and without one compare equal and
//! serialise the same (as nothing).

use std::sync::atomic::{AtomicBool, Ordering};

/// An optional flag that stops the runs whose budget carries it.
#[derive(Clone, Copy, Default)]
pub struct Cancel(Option<&'static AtomicBool>);

impl Cancel {
    /// No flag: never cancelled.
    pub const NONE: Self = Self(None);

    /// Runs carrying this are cancelled once `flag` is true.
    #[must_use]
    pub const fn on(flag: &'static AtomicBool) -> Self {
        Self(Some(flag))
    }

    /// Whether the flag is raised.
    #[must_use]
    pub fn requested(self) -> bool {
        self.0.is_some_and(|f| f.load(Ordering::Relaxed))
    }
}

impl PartialEq for Cancel {
    /// Always: a flag does not change what a budget allows.
    fn eq(&self, _: &Self) -> bool {
        true
    }
}

impl Eq for Cancel {}

impl std::fmt::Debug for Cancel {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(if self.0.is_some() {
            "Cancel(on)"
        } else {
            "Cancel(none)"
        })
    }
}
