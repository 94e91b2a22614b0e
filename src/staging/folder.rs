//! [`Staging`]: one set of output files, written into a staging folder inside
//! the output folder and committed whole, or removed.

use std::fs::{self, File, TryLockError};
use std::io::{ErrorKind, Write};
use std::path::{Path, PathBuf};

use anyhow::Context;

use super::leftovers::{COMMIT, STAGING, clean};
use super::manifest::{MANIFEST, Manifest, sync_dir};
use crate::signals::{Ticket, with_pending};

/// A set of output files being written: in `DIR/.sightline-staging-<pid>-<random>/`
/// until [`commit`](Self::commit) puts them into `DIR` together; dropped
/// uncommitted (an error, a refusal), or at SIGINT/SIGTERM/SIGHUP, the folder is
/// removed with the directories opening it created.
pub struct Staging {
    /// The output folder.
    dir: PathBuf,
    /// `<pid>-<random>`, shared by the staging and the commit folder.
    id: String,
    /// The staging folder.
    folder: PathBuf,
    /// The manifest, locked while this process lives (see the `leftovers` module).
    manifest: File,
    /// The names of the files staged, in order.
    names: Vec<String>,
    /// The names the set replaces: those it does not have are removed.
    replaces: &'static [&'static str],
    /// The clean-up registered against interruption, until the commit's point
    /// of no return.
    ticket: Option<Ticket>,
}

impl Staging {
    /// Opens a staging folder in `dir` (created, with its parents, if need be)
    /// for a set that replaces the files named in `replaces`, after cleaning
    /// what interrupted runs left there.
    pub fn open(dir: &Path, replaces: &'static [&'static str]) -> anyhow::Result<Self> {
        // Deepest first, so they can be removed in order.
        let created: Vec<PathBuf> = dir
            .ancestors()
            .take_while(|d| !d.as_os_str().is_empty() && !d.exists())
            .map(Path::to_path_buf)
            .collect();
        fs::create_dir_all(dir).with_context(|| format!("failed to create {}", dir.display()))?;
        {
            let _dir = lock_dir(dir);
            clean(dir, None)?;
        }
        let failed = || format!("failed to create a staging folder in {}", dir.display());
        with_pending(|pending| {
            let folder = tempfile::Builder::new()
                .prefix(&format!("{STAGING}{}-", std::process::id()))
                .rand_bytes(8)
                .tempdir_in(dir)
                .with_context(failed)?
                .keep();
            let undo = {
                let folder = folder.clone();
                move || {
                    let _ = fs::remove_dir_all(&folder);
                    for dir in &created {
                        // Only when empty: another run may have written there since.
                        let _ = fs::remove_dir(dir);
                    }
                }
            };
            let ticket = pending.add(undo);
            let manifest = File::create_new(folder.join(MANIFEST)).and_then(|manifest| match manifest.try_lock() {
                Err(TryLockError::Error(error)) if error.kind() != ErrorKind::Unsupported => Err(error),
                _ => Ok(manifest),
            });
            let manifest = match manifest {
                Ok(manifest) => manifest,
                Err(error) => {
                    if let Some(undo) = pending.take(ticket) {
                        undo();
                    }
                    return Err(error).with_context(failed);
                }
            };
            let id = folder
                .file_name()
                .and_then(|name| name.to_str()?.strip_prefix(STAGING))
                .unwrap_or_default()
                .to_string();
            Ok(Staging {
                dir: dir.to_path_buf(),
                id,
                folder,
                manifest,
                names: Vec::new(),
                replaces,
                ticket: Some(ticket),
            })
        })
    }

    /// The output folder.
    pub fn dir(&self) -> &Path {
        &self.dir
    }

    /// Where the staged file `name` is until the commit.
    pub fn path(&self, name: &str) -> PathBuf {
        self.folder.join(name)
    }

    /// Creates the file `name` of the set, to be written as it is produced.
    pub fn create(&mut self, name: &str) -> anyhow::Result<File> {
        let file = File::create_new(self.path(name))
            .with_context(|| format!("failed to write {}", self.dir.join(name).display()))?;
        self.names.push(name.to_string());
        Ok(file)
    }

    /// Writes the file `name` of the set.
    pub fn write(&mut self, name: &str, bytes: &[u8]) -> anyhow::Result<()> {
        self.create(name)?
            .write_all(bytes)
            .with_context(|| format!("failed to write {}", self.dir.join(name).display()))
    }

    /// Renames the staged file `from` of the set to `to`, a name not staged.
    ///
    /// # Panics
    ///
    /// If `from` is not a staged file of the set.
    pub fn rename(&mut self, from: &str, to: &str) -> anyhow::Result<()> {
        let at = self.staged(from);
        fs::rename(self.path(from), self.path(to))
            .with_context(|| format!("failed to write {}", self.dir.join(to).display()))?;
        self.names[at] = to.to_string();
        Ok(())
    }

    /// Removes the staged file `name` from the set.
    ///
    /// # Panics
    ///
    /// If `name` is not a staged file of the set.
    pub fn remove(&mut self, name: &str) -> anyhow::Result<()> {
        let at = self.staged(name);
        fs::remove_file(self.path(name)).with_context(|| format!("failed to remove {}", self.path(name).display()))?;
        self.names.remove(at);
        Ok(())
    }

    /// Where `name` is among the staged files.
    fn staged(&self, name: &str) -> usize {
        self.names
            .iter()
            .position(|n| n == name)
            .unwrap_or_else(|| panic!("{name} is not a staged file"))
    }

    /// Puts the set into the output folder, replacing the previous one whole:
    /// every file and the manifest made durable, the staging folder renamed to
    /// `.sightline-commit-<id>` (the point of no return), each file renamed into
    /// place, the previous set's other files removed, the commit folder removed.
    /// Before the point of no return a failure changes nothing in the output
    /// folder; after it, the next run into the folder finishes the commit.
    pub fn commit(mut self) -> anyhow::Result<()> {
        let manifest = Manifest::new(&self.names, self.replaces);
        for name in &self.names {
            File::open(self.path(name))
                .and_then(|file| file.sync_all())
                .with_context(|| format!("failed to write {}", self.dir.join(name).display()))?;
        }
        let at = self.path(MANIFEST);
        let failed = || format!("failed to write {}", at.display());
        self.manifest
            .write_all(manifest.text().as_bytes())
            .with_context(failed)?;
        self.manifest.sync_all().with_context(failed)?;
        sync_dir(&self.folder)?;
        // One commit at a time in a folder, and none while leftovers are cleaned.
        let _dir = lock_dir(&self.dir);
        clean(&self.dir, Some(&self.folder))?;
        manifest.check_targets(&self.dir)?;
        let commit = self.dir.join(format!("{COMMIT}{}", self.id));
        // A signal waits until the commit is done.
        with_pending(|pending| {
            fs::rename(&self.folder, &commit)
                .with_context(|| format!("failed to write the evidence into {}", self.dir.display()))?;
            // The point of no return: the staging folder is the commit folder now.
            if let Some(ticket) = self.ticket.take() {
                drop(pending.take(ticket));
            }
            sync_dir(&self.dir)
                .and_then(|()| manifest.apply(&self.dir, &commit))
                .with_context(|| {
                    format!(
                        "failed to finish the commit of the evidence into {} (the next run into it finishes it)",
                        self.dir.display()
                    )
                })
        })
    }
}

impl Drop for Staging {
    /// Removes the staging folder of a set that was not committed.
    fn drop(&mut self) {
        if let Some(ticket) = self.ticket.take() {
            with_pending(|pending| pending.take(ticket).map(|undo| undo()));
        }
    }
}

/// An exclusive lock on the directory `dir`, held while the value lives; `None`
/// where the file system or the system cannot lock a directory (the commit
/// then relies on the folders' own locks).
fn lock_dir(dir: &Path) -> Option<File> {
    let file = File::open(dir).ok()?;
    file.lock().ok()?;
    Some(file)
}
