//! Output: evidence files written atomically (each to a temporary file in its
//! directory, renamed into place, so a reader never sees half a file), and lines
//! on stdout.

use std::fmt::Display;
use std::io::{ErrorKind, Write};
use std::path::Path;

use anyhow::Context;
use tempfile::NamedTempFile;

/// A temporary file in `dir` (created if needed), for evidence written as it is
/// produced; [`write_atomically`] renames it into place with the rest.
pub fn staging_file(dir: &Path) -> anyhow::Result<NamedTempFile> {
    std::fs::create_dir_all(dir).with_context(|| format!("failed to create {}", dir.display()))?;
    let mut builder = tempfile::Builder::new();
    builder.prefix(".sightline-");
    // Evidence is meant to be read by others (CI artefacts, assessors), not
    // kept private as temporary files are by default.
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        builder.permissions(std::fs::Permissions::from_mode(0o644));
    }
    builder
        .tempfile_in(dir)
        .with_context(|| format!("failed to create a temporary file in {}", dir.display()))
}

/// Writes every (name, contents) pair into `dir`, creating it if needed, and
/// moves every (staged file, name) pair there too. All files are complete on
/// disk before the first is renamed into place.
pub fn write_atomically(dir: &Path, files: &[(&str, &str)], staged: Vec<(NamedTempFile, &str)>) -> anyhow::Result<()> {
    let mut ready = Vec::new();
    for (name, contents) in files {
        let mut file = staging_file(dir)?;
        file.write_all(contents.as_bytes())
            .with_context(|| format!("failed to write {}", dir.join(name).display()))?;
        ready.push((file, *name));
    }
    ready.extend(staged);
    for (file, name) in &ready {
        file.as_file()
            .sync_all()
            .with_context(|| format!("failed to write {}", dir.join(name).display()))?;
    }
    for (file, name) in ready {
        let path = dir.join(name);
        file.persist(&path)
            .with_context(|| format!("failed to write {}", path.display()))?;
    }
    Ok(())
}

/// Prints a line on stdout. A closed stdout (`sightline run … | head`) is not an
/// error: the evidence files and the exit status are what matter, so the run goes
/// on and exits with the status it earns.
pub fn say(line: impl Display) {
    if let Err(error) = writeln!(std::io::stdout().lock(), "{line}")
        && error.kind() != ErrorKind::BrokenPipe
    {
        eprintln!("warning: failed to write to stdout: {error}");
    }
}
