//! Long calls that Ctrl-C stops.
//!
//! The interpreter only runs its signal handlers between bytecodes of the main thread, so a
//! `plan` or `bench` running in Rust would ignore Ctrl-C until it returned (a long bench:
//! hours; every run still made, then the records thrown away by the exception). So the work
//! runs on a worker thread while the calling thread waits for it and, every 50 ms, asks the
//! interpreter for signals; on one (its handler raised, e.g. `KeyboardInterrupt`) it raises the work's cancel
//! flag (`swarmplan_core::optim::cancel`), waits for the work to stop between iterations
//! or runs, and returns the handler's exception. A bench's records written so far stay in
//! its folder, so `resume=True` continues.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::RecvTimeoutError;
use std::sync::Mutex;
use std::time::Duration;

use pyo3::prelude::*;
use swarmplan_core::optim::cancel::Cancel;

/// How often the waiting thread asks for signals.
const POLL: Duration = Duration::from_millis(50);

/// Flags no call holds now. Each call takes its own (concurrent calls from several Python
/// threads must not stop each other), so at most as many are ever made as calls ran at once.
static FREE: Mutex<Vec<&'static AtomicBool>> = Mutex::new(Vec::new());

/// Runs `work`, given its cancel flag, so that a signal handler that raises (Ctrl-C) stops
/// it; the work's result, or the handler's exception.
pub fn interruptible<T: Send>(
    py: Python<'_>,
    work: impl FnOnce(Cancel) -> T + Send,
) -> PyResult<T> {
    let flag = FREE
        .lock()
        .ok()
        .and_then(|mut free| free.pop())
        .unwrap_or_else(|| Box::leak(Box::new(AtomicBool::new(false))));
    flag.store(false, Ordering::Relaxed);
    let (finished, done) = std::sync::mpsc::channel::<()>();
    let outcome = std::thread::scope(|scope| {
        let handle = scope.spawn(move || {
            let value = work(Cancel::on(flag));
            // Wakes the waiting thread at once (a panic wakes it too: the sender drops).
            let _ = finished.send(());
            value
        });
        let mut done = done;
        loop {
            // The receiver goes into the released section and comes back (it may move
            // between threads, not be shared).
            let waited;
            (done, waited) = py.detach(move || {
                let waited = done.recv_timeout(POLL);
                (done, waited)
            });
            if waited != Err(RecvTimeoutError::Timeout) {
                return Ok(handle.join());
            }
            if let Err(signal) = py.check_signals() {
                flag.store(true, Ordering::Relaxed);
                // The join only fails if the work panicked, which the signal outranks.
                let _ = py.detach(|| handle.join());
                return Err(signal);
            }
        }
    });
    if let Ok(mut free) = FREE.lock() {
        free.push(flag);
    }
    match outcome? {
        Ok(value) => Ok(value),
        // A panic in the work: carried on to the caller as it would have been unthreaded.
        Err(panic) => std::panic::resume_unwind(panic),
    }
}
