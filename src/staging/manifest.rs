//! A commit's manifest: the files it puts into the output folder and the files
//! of the previous set it removes, and how both are carried out, the same way
//! by the commit itself and by a later run that finishes an interrupted one.
//!
//! The manifest is text, one entry a line after its format line:
//!
//! ```text
//! sightline-commit/1
//! put results.json
//! put junit.xml
//! put report.html
//! remove run.mcap
//! ```

use std::fs;
use std::io::ErrorKind;
use std::path::Path;

use anyhow::Context;

/// The manifest's name in a staging or commit folder.
pub const MANIFEST: &str = "manifest";

/// The first line of every manifest.
const FORMAT: &str = "sightline-commit/1";

/// What a commit does to its output folder.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Manifest {
    /// The files of the new set, in the commit folder until they are renamed into place.
    pub put: Vec<String>,
    /// The files of an earlier set the new one does not have.
    pub remove: Vec<String>,
}

impl Manifest {
    /// The set of the files `put`, replacing every name of `replaces`.
    pub fn new(put: &[String], replaces: &[&str]) -> Self {
        Manifest {
            put: put.to_vec(),
            remove: replaces
                .iter()
                .filter(|name| !put.iter().any(|p| p == *name))
                .map(|name| name.to_string())
                .collect(),
        }
    }

    /// The manifest as written.
    pub fn text(&self) -> String {
        let mut text = format!("{FORMAT}\n");
        for name in &self.put {
            text.push_str(&format!("put {name}\n"));
        }
        for name in &self.remove {
            text.push_str(&format!("remove {name}\n"));
        }
        text
    }

    /// Reads a manifest; `Err((line, problem))` when it is not one.
    pub fn parse(text: &str) -> Result<Self, (usize, String)> {
        let mut lines = text.lines().enumerate().map(|(i, line)| (i + 1, line));
        match lines.next() {
            Some((_, FORMAT)) => {}
            _ => return Err((1, format!("expected `{FORMAT}`"))),
        }
        let mut manifest = Manifest {
            put: Vec::new(),
            remove: Vec::new(),
        };
        for (number, line) in lines {
            let (list, name) = match line.split_once(' ') {
                Some(("put", name)) => (&mut manifest.put, name),
                Some(("remove", name)) => (&mut manifest.remove, name),
                _ => return Err((number, format!("expected `put NAME` or `remove NAME`, found `{line}`"))),
            };
            if !is_plain_name(name) {
                return Err((
                    number,
                    format!("`{name}` is not the name of a file in the output folder"),
                ));
            }
            list.push(name.to_string());
        }
        Ok(manifest)
    }

    /// Checks, before anything is moved, that each name the commit puts or
    /// removes in `dir` is free or a file: a directory there would stop the
    /// commit halfway.
    pub fn check_targets(&self, dir: &Path) -> anyhow::Result<()> {
        for name in self.put.iter().chain(&self.remove) {
            let target = dir.join(name);
            match fs::symlink_metadata(&target) {
                Ok(metadata) if metadata.is_dir() => {
                    anyhow::bail!(
                        "failed to write {}: a directory is in its place (nothing was changed)",
                        target.display()
                    )
                }
                Err(error) if error.kind() != ErrorKind::NotFound => {
                    return Err(error).with_context(|| format!("failed to write {}", target.display()));
                }
                _ => {}
            }
        }
        Ok(())
    }

    /// Renames each file of `commit` into `dir` and removes the files of the
    /// earlier set, then removes `commit`. A file already moved, or already
    /// removed, is skipped, so a commit cut short is finished by doing it again.
    pub fn apply(&self, dir: &Path, commit: &Path) -> anyhow::Result<()> {
        for name in &self.put {
            let (from, to) = (commit.join(name), dir.join(name));
            match fs::rename(&from, &to) {
                // Not found and gone from the commit folder: moved already.
                Err(error) if error.kind() != ErrorKind::NotFound || from.exists() => {
                    return Err(error).with_context(|| format!("failed to write {}", to.display()));
                }
                _ => {}
            }
        }
        for name in &self.remove {
            let path = dir.join(name);
            match fs::remove_file(&path) {
                Err(error) if error.kind() != ErrorKind::NotFound => {
                    return Err(error).with_context(|| format!("failed to remove {}", path.display()));
                }
                _ => {}
            }
        }
        sync_dir(dir)?;
        fs::remove_dir_all(commit).with_context(|| format!("failed to remove {}", commit.display()))?;
        sync_dir(dir)
    }
}

/// A file name of the output folder, nothing more: no separator, not `.` or
/// `..`, not one of sightline's own folders.
fn is_plain_name(name: &str) -> bool {
    !name.is_empty()
        && name != "."
        && name != ".."
        && !name.contains(['/', '\\', '\0'])
        && !name.starts_with(".sightline-")
}

/// Makes the entries of `dir` (files created, renamed or removed in it)
/// durable. Only Unix can open a directory to sync it.
pub fn sync_dir(dir: &Path) -> anyhow::Result<()> {
    #[cfg(unix)]
    fs::File::open(dir)
        .and_then(|d| d.sync_all())
        .with_context(|| format!("failed to write {}", dir.display()))?;
    #[cfg(not(unix))]
    let _ = dir;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn names(list: &[&str]) -> Vec<String> {
        list.iter().map(|n| n.to_string()).collect()
    }

    #[test]
    fn a_set_removes_what_it_replaces_and_does_not_put() {
        let manifest = Manifest::new(&names(&["results.json", "report.html"]), &["report.html", "run.mcap"]);
        assert_eq!(manifest.remove, names(&["run.mcap"]));
        assert_eq!(
            manifest.text(),
            "sightline-commit/1\nput results.json\nput report.html\nremove run.mcap\n"
        );
        assert_eq!(Manifest::parse(&manifest.text()), Ok(manifest));
    }

    #[test]
    fn a_damaged_manifest_is_refused_at_its_line() {
        assert_eq!(Manifest::parse("").unwrap_err().0, 1);
        assert_eq!(Manifest::parse("sightline-commit/2\n").unwrap_err().0, 1);
        let moved = Manifest::parse("sightline-commit/1\nput a.json\nmove b.json\n").unwrap_err();
        assert_eq!(
            moved,
            (3, "expected `put NAME` or `remove NAME`, found `move b.json`".into())
        );
        for name in ["../x", "a/b", "..", ".sightline-commit-1", ""] {
            let text = format!("sightline-commit/1\nremove {name}\n");
            assert_eq!(Manifest::parse(&text).unwrap_err().0, 2, "{name}");
        }
    }

    #[test]
    fn applying_twice_finishes_a_commit_cut_short() {
        let dir = tempfile::tempdir().unwrap();
        let commit = dir.path().join(".sightline-commit-1-x");
        fs::create_dir(&commit).unwrap();
        for (name, text) in [("a.json", "new a"), ("b.json", "new b")] {
            fs::write(commit.join(name), text).unwrap();
        }
        fs::write(dir.path().join("b.json"), "old b").unwrap();
        fs::write(dir.path().join("c.mcap"), "old c").unwrap();
        let manifest = Manifest::new(&names(&["a.json", "b.json"]), &["a.json", "b.json", "c.mcap"]);
        // Cut short after the first rename.
        fs::rename(commit.join("a.json"), dir.path().join("a.json")).unwrap();
        manifest.apply(dir.path(), &commit).unwrap();
        assert!(!commit.exists());
        assert_eq!(fs::read_to_string(dir.path().join("a.json")).unwrap(), "new a");
        assert_eq!(fs::read_to_string(dir.path().join("b.json")).unwrap(), "new b");
        assert!(!dir.path().join("c.mcap").exists());
    }

    #[test]
    fn a_directory_in_a_files_place_stops_the_commit_before_it_starts() {
        let dir = tempfile::tempdir().unwrap();
        fs::create_dir(dir.path().join("report.html")).unwrap();
        let manifest = Manifest::new(&names(&["report.html"]), &[]);
        let error = manifest.check_targets(dir.path()).unwrap_err();
        assert!(error.to_string().contains("a directory is in its place"), "{error}");
        assert!(
            Manifest::new(&names(&["results.json"]), &[])
                .check_targets(dir.path())
                .is_ok()
        );
    }
}
