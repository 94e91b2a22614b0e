//! What interrupted runs left in an output folder: a staging folder (the
//! process died before its commit) is removed; a commit folder (it died during
//! its commit) is finished, as its manifest says. Each gets a one-line note on
//! stderr.
//!
//! A folder is left only while its owner lives. Its owner holds a lock on the
//! folder's manifest from the moment it makes it (the system releases it when
//! the process ends, however it ends), so a lock this process can take means the
//! owner is gone; a process id could be reused by another process, a lock
//! cannot. Where the file system has no locks, or the owner died before it made
//! its manifest, a folder last changed before this process first looked is
//! taken as left.
//!
//! Versions before evidence was staged as a set wrote each file through a
//! temporary `.sightline-XXXXXX` file (six letters or digits), which a killed run
//! left behind; such a file older than this run is removed too.

use std::collections::BTreeSet;
use std::fs::{self, File, OpenOptions, TryLockError};
use std::io::ErrorKind;
use std::path::{Path, PathBuf};
use std::sync::{Mutex, OnceLock};
use std::time::SystemTime;

use anyhow::Context;

use super::manifest::{MANIFEST, Manifest};
use crate::files::{TEXT_LIMIT, read_regular};
use crate::terminal::stderr;

/// The name of a staging folder begins so, followed by its id.
pub const STAGING: &str = ".sightline-staging-";

/// The name of a commit folder begins so, followed by its id.
pub const COMMIT: &str = ".sightline-commit-";

/// Removes the staging folders and finishes the commits that interrupted runs
/// left in `dir`, in the order of their names; `own` (this process's staging
/// folder) is never touched.
pub fn clean(dir: &Path, own: Option<&Path>) -> anyhow::Result<()> {
    // The first look (before the first simulation) is when this run started.
    static STARTED: OnceLock<SystemTime> = OnceLock::new();
    let started = *STARTED.get_or_init(SystemTime::now);
    let mut entries = Vec::new();
    for entry in fs::read_dir(dir).with_context(|| format!("failed to read {}", dir.display()))? {
        let entry = entry.with_context(|| format!("failed to read {}", dir.display()))?;
        let name = entry.file_name().to_string_lossy().into_owned();
        if is_legacy_temporary(&name)
            && entry.file_type().is_ok_and(|kind| kind.is_file())
            && matches!(by_age(&entry.path(), started), Ok(Owner::Gone(_)))
        {
            fs::remove_file(entry.path()).with_context(|| format!("failed to remove {}", entry.path().display()))?;
            stderr!(
                "note: {}: removed {name}, left by an interrupted run of an earlier version",
                dir.display()
            );
            continue;
        }
        if (name.starts_with(STAGING) || name.starts_with(COMMIT))
            && entry.file_type().is_ok_and(|kind| kind.is_dir())
            && own != Some(entry.path().as_path())
        {
            entries.push((name, entry.path()));
        }
    }
    entries.sort();
    for (name, folder) in entries {
        // The lock is held until the folder is dealt with, so no other run deals with it too.
        let Owner::Gone(_lock) =
            owner(&folder, started).with_context(|| format!("failed to read {}", folder.display()))?
        else {
            continue;
        };
        if name.starts_with(STAGING) {
            fs::remove_dir_all(&folder).with_context(|| format!("failed to remove {}", folder.display()))?;
            stderr!("note: {}: removed {name}, left by an interrupted run", dir.display());
        } else if let Some(manifest) = manifest_of(&folder) {
            manifest.apply(dir, &folder)?;
            stderr!(
                "note: {}: finished the evidence set an interrupted run had committed ({name})",
                dir.display()
            );
        }
    }
    Ok(())
}

/// Whether `name` is a temporary file of an earlier version: `.sightline-` and
/// six letters or digits.
fn is_legacy_temporary(name: &str) -> bool {
    name.strip_prefix(".sightline-")
        .is_some_and(|id| id.len() == 6 && id.bytes().all(|b| b.is_ascii_alphanumeric()))
}

/// Whether a staging or commit folder's owner lives.
enum Owner {
    /// It does: the folder is its work in progress.
    Alive,
    /// It is gone; the folder's manifest is locked by this process, when it has one.
    Gone(Option<File>),
}

/// Whose `folder` is, seen by a run that started at `started`. A manifest that
/// is not a regular file (a FIFO, a device: sightline writes none) is not
/// opened, as if there were none.
fn owner(folder: &Path, started: SystemTime) -> std::io::Result<Owner> {
    let manifest = folder.join(MANIFEST);
    if fs::metadata(&manifest).is_ok_and(|m| !m.is_file()) {
        return by_age(folder, started);
    }
    match OpenOptions::new().read(true).write(true).open(manifest) {
        Ok(manifest) => match manifest.try_lock() {
            Ok(()) => Ok(Owner::Gone(Some(manifest))),
            Err(TryLockError::WouldBlock) => Ok(Owner::Alive),
            Err(TryLockError::Error(error)) if error.kind() == ErrorKind::Unsupported => by_age(folder, started),
            Err(TryLockError::Error(error)) => Err(error),
        },
        Err(error) if error.kind() == ErrorKind::NotFound => by_age(folder, started),
        Err(error) => Err(error),
    }
}

/// Gone when `path` was last changed before `started`.
fn by_age(path: &Path, started: SystemTime) -> std::io::Result<Owner> {
    let changed = fs::metadata(path)?.modified()?;
    Ok(if changed < started {
        Owner::Gone(None)
    } else {
        Owner::Alive
    })
}

/// The manifest of a commit folder; `None`, after a warning (once a process),
/// when it cannot be read: the folder is then left as it is (a later commit
/// replaces the whole set all the same).
fn manifest_of(folder: &Path) -> Option<Manifest> {
    static WARNED: Mutex<BTreeSet<PathBuf>> = Mutex::new(BTreeSet::new());
    let path = folder.join(MANIFEST);
    let text = read_regular(&path, TEXT_LIMIT).and_then(|bytes| {
        String::from_utf8(bytes).map_err(|_| std::io::Error::new(ErrorKind::InvalidData, "not UTF-8 text"))
    });
    let problem = match text {
        Ok(text) => match Manifest::parse(&text) {
            Ok(manifest) => return Some(manifest),
            Err((line, problem)) => format!(
                "{}:{line}:1: warning: not a manifest sightline wrote ({problem}); the interrupted commit is left as it is",
                path.display()
            ),
        },
        Err(error) => format!(
            "{}: warning: failed to read the manifest of an interrupted commit ({error}); left as it is",
            path.display()
        ),
    };
    if WARNED.lock().unwrap_or_else(|p| p.into_inner()).insert(path) {
        stderr!("{problem}");
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_locked_folder_is_owned_and_an_unlocked_one_left() {
        let dir = tempfile::tempdir().unwrap();
        let folder = dir.path().join(format!("{STAGING}1-x"));
        fs::create_dir(&folder).unwrap();
        let live = File::create(folder.join(MANIFEST)).unwrap();
        live.lock().unwrap();
        assert!(
            matches!(owner(&folder, SystemTime::now()).unwrap(), Owner::Alive),
            "a live owner's folder"
        );
        clean(dir.path(), None).unwrap();
        assert!(folder.exists());
        drop(live);
        assert!(
            matches!(owner(&folder, SystemTime::now()).unwrap(), Owner::Gone(Some(_))),
            "the owner is gone"
        );
        clean(dir.path(), None).unwrap();
        assert!(!folder.exists());
    }

    #[test]
    fn a_folder_without_a_manifest_is_left_only_when_older_than_the_run() {
        let dir = tempfile::tempdir().unwrap();
        let folder = dir.path().join(format!("{STAGING}1-x"));
        fs::create_dir(&folder).unwrap();
        let later = SystemTime::now() + std::time::Duration::from_secs(60);
        assert!(matches!(owner(&folder, later).unwrap(), Owner::Gone(None)));
        assert!(matches!(owner(&folder, SystemTime::UNIX_EPOCH).unwrap(), Owner::Alive));
    }

    #[test]
    fn a_commit_is_finished_an_earlier_temporary_removed_and_other_names_kept() {
        let dir = tempfile::tempdir().unwrap();
        let commit = dir.path().join(format!("{COMMIT}1-x"));
        fs::create_dir(&commit).unwrap();
        fs::write(commit.join("results.json"), "new").unwrap();
        let manifest = Manifest::new(&["results.json".into()], &["results.json", "run.mcap"]);
        fs::write(commit.join(MANIFEST), manifest.text()).unwrap();
        fs::write(dir.path().join("run.mcap"), "old").unwrap();
        fs::write(dir.path().join(".sightline-other"), "not ours").unwrap();
        for name in [".sightline-a1B2c3", ".sightline-a1B2c"] {
            let old = File::create(dir.path().join(name)).unwrap();
            old.set_modified(SystemTime::UNIX_EPOCH).unwrap();
        }
        clean(dir.path(), None).unwrap();
        assert!(!dir.path().join(".sightline-a1B2c3").exists());
        assert!(dir.path().join(".sightline-a1B2c").exists());
        assert_eq!(fs::read_to_string(dir.path().join("results.json")).unwrap(), "new");
        assert!(!dir.path().join("run.mcap").exists());
        assert!(!commit.exists());
        assert!(dir.path().join(".sightline-other").exists());
    }
}
