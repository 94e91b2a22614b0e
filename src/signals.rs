//! Interruptions: on SIGINT, SIGTERM or SIGHUP the process undoes what it has
//! begun to write (each staging folder registers how to remove itself) and exits
//! with the conventional status 128 + N (130, 143, 129).
//!
//! A thread of [`signal_hook`] receives the signals (it is told which came, so
//! the status can say it); it takes the lock of the pending clean-ups, runs them
//! and exits while still holding it. Code that must not be cut short (the commit
//! of an evidence set) runs inside [`with_pending`], holding the same lock: a
//! signal then waits until it is done. On other systems nothing is installed and
//! a signal ends the process as it would anyway; what it leaves is cleaned at the
//! next run.

use std::collections::BTreeMap;
use std::sync::{Mutex, MutexGuard};

/// A clean-up to run if the process is interrupted.
type Cleanup = Box<dyn FnOnce() + Send>;

/// The clean-ups of the work under way, by ticket.
#[derive(Default)]
pub struct Pending {
    next: u64,
    cleanups: BTreeMap<u64, Cleanup>,
}

/// Names one pending clean-up.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Ticket(u64);

impl Pending {
    /// Adds a clean-up, run if the process is interrupted before [`take`](Self::take).
    pub fn add(&mut self, cleanup: impl FnOnce() + Send + 'static) -> Ticket {
        self.next += 1;
        self.cleanups.insert(self.next, Box::new(cleanup));
        Ticket(self.next)
    }

    /// Removes a clean-up and gives it back (to run it now, or drop it when the
    /// work is done).
    pub fn take(&mut self, ticket: Ticket) -> Option<impl FnOnce() + Send + use<>> {
        self.cleanups.remove(&ticket.0)
    }
}

static PENDING: Mutex<Pending> = Mutex::new(Pending {
    next: 0,
    cleanups: BTreeMap::new(),
});

/// The pending clean-ups, locked. A clean-up that panicked cannot have left
/// the map half changed, so a poisoned lock is taken as it is.
fn lock() -> MutexGuard<'static, Pending> {
    PENDING.lock().unwrap_or_else(|poisoned| poisoned.into_inner())
}

/// Runs `work` with the pending clean-ups; a signal that comes meanwhile waits
/// until `work` returns.
pub fn with_pending<T>(work: impl FnOnce(&mut Pending) -> T) -> T {
    work(&mut lock())
}

/// Starts the thread that handles SIGINT, SIGTERM and SIGHUP.
#[cfg(unix)]
pub fn install() -> std::io::Result<()> {
    use signal_hook::consts::{SIGHUP, SIGINT, SIGTERM};
    let mut signals = signal_hook::iterator::Signals::new([SIGINT, SIGTERM, SIGHUP])?;
    std::thread::Builder::new().name("signals".into()).spawn(move || {
        if let Some(signal) = signals.forever().next() {
            let mut pending = lock();
            for (_, cleanup) in std::mem::take(&mut pending.cleanups) {
                cleanup();
            }
            // Still holding the lock: nothing can start a new write now.
            std::process::exit(128 + signal);
        }
    })?;
    Ok(())
}

/// Nothing to install: a signal ends the process, the next run cleans up.
#[cfg(not(unix))]
pub fn install() -> std::io::Result<()> {
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_taken_cleanup_is_given_back_once() {
        let mut pending = Pending::default();
        let (first, second) = (pending.add(|| {}), pending.add(|| {}));
        assert_ne!(first, second);
        assert!(pending.take(first).is_some());
        assert!(pending.take(first).is_none());
        assert!(pending.take(second).is_some());
        assert!(pending.cleanups.is_empty());
    }
}
