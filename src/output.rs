//! Output: evidence files written atomically (each to a temporary file in its
//! directory, renamed into place, so a reader never sees half a file), and lines
//! on stdout.

use std::ffi::OsString;
use std::fmt::Display;
use std::io::{ErrorKind, Write};
use std::path::{Component, Path, PathBuf};

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

/// The default output directory of a scenario file: `out/STEM/` (STEM: the file
/// name without its extension).
pub fn default_dir(file: &Path) -> PathBuf {
    Path::new("out").join(stem(file))
}

/// A scenario file's name without its extension.
pub fn stem(file: &Path) -> OsString {
    file.file_stem().map_or_else(|| "scenario".into(), |s| s.to_os_string())
}

/// The path of `to` seen from the directory `from_dir` (both absolute, or both
/// relative to the same directory): `../sumo/x.xml`.
pub fn relative(from_dir: &Path, to: &Path) -> PathBuf {
    let from: Vec<_> = from_dir.components().collect();
    let target: Vec<_> = to.components().collect();
    let common = from.iter().zip(&target).take_while(|(a, b)| a == b).count();
    let mut path: PathBuf = from[common..].iter().map(|_| Component::ParentDir).collect();
    path.extend(&target[common..]);
    path
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

/// A progress bar over `len` sweep points of `name` on stderr, shown only on a
/// terminal outside CI (`CI` unset): logs and pipes stay quiet.
pub fn progress(len: usize, name: &str) -> indicatif::ProgressBar {
    use std::io::IsTerminal;
    if std::env::var_os("CI").is_some() || !std::io::stderr().is_terminal() {
        return indicatif::ProgressBar::hidden();
    }
    let bar = indicatif::ProgressBar::new(len as u64).with_message(name.to_string());
    if let Ok(style) = indicatif::ProgressStyle::with_template("{msg} [{bar:30}] {pos}/{len} points, {elapsed}") {
        bar.set_style(style.progress_chars("=> "));
    }
    bar
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn relative_paths_climb_to_the_common_directory() {
        let path = relative(Path::new("/work/out/grid"), Path::new("/work/scenarios/sumo/x.xml"));
        assert_eq!(path, Path::new("../../scenarios/sumo/x.xml"));
        assert_eq!(relative(Path::new("/a"), Path::new("/a/b.xml")), Path::new("b.xml"));
    }
}
