//! Output written as a set: every file a command writes for one scenario
//! (results.json, junit.xml, report.html, run.mcap; falsify's files; a shard
//! file) is staged in one folder inside the output folder and put into place
//! only when all are complete, so the folder holds one run's whole set or the
//! previous one, never a mix, and an interrupted run leaves nothing after the
//! next.
//!
//! The protocol, in the output folder `DIR`:
//!
//! 1. **Stage.** The files are written into `DIR/.sightline-staging-<pid>-<random>/`,
//!    beside a `manifest` its owner holds locked while it lives. A failure, a
//!    refusal (a custom template failing on the data) or SIGINT/SIGTERM/SIGHUP
//!    removes the folder, and the directories it had to create.
//! 2. **Seal.** Each file and the manifest (the names to put, the names of the
//!    previous set to remove) are synced to disk; a name the set would replace
//!    that is a directory stops the commit here, with nothing changed.
//! 3. **Commit.** The staging folder is renamed to `DIR/.sightline-commit-<id>/`
//!    and `DIR` synced: the point of no return.
//! 4. **Apply.** Each file is renamed into `DIR`, the previous set's other files
//!    are removed (a `run.mcap` when the new run records nothing), and the
//!    commit folder is removed. Commits in one folder take a lock on it, one at
//!    a time; a signal waits until the commit is done.
//!
//! A run that opens a staging folder in `DIR`, and again before it commits,
//! first deals with what dead runs left (`leftovers`): it removes their
//! staging folders and finishes their commits (step 4 again, from the
//! manifest), each with a note on stderr. Only a process killed (SIGKILL, power
//! loss) during step 4, a few renames long, leaves `DIR` holding a mix, marked
//! by its commit folder, until the next run into `DIR` finishes it.

mod folder;
mod leftovers;
mod manifest;

pub use folder::Staging;
